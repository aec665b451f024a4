#!/usr/bin/env python3
"""Reconstructs the bundled kitten scan from Python and, when Open3D is installed,
hands the mesh to it.

    bash scripts/build.sh
    PYTHONPATH=build/python python3 examples/reconstruct_kitten.py
"""

import pathlib

import pdd

root = pathlib.Path(__file__).resolve().parent.parent
cloud = pdd.read_points(root / "data" / "kitten_scan.ply")
print(f"read {cloud}")


def show(progress):
    print(f"\r  {progress.stage:10s} iteration {progress.iteration:2d} "
          f"{progress.vertices:9d} vertices {progress.elapsed_seconds:6.1f} s", end="")


mesh = pdd.reconstruct(cloud, seed=0, progress=show)
print(f"\n{mesh}: {mesh.stats['seconds']:.1f} s, "
      f"{len(mesh.stats['iterations'])} iterations, final domain {mesh.stats['vertices']} vertices")

report = pdd.quality(mesh)
surface = report["surface"]
print(f"closed {surface['closed']}, manifold {surface['manifold']}, genus {surface['genus']}, "
      f"mean min angle {report['triangles']['mean_min_angle']:.1f} degrees")

out = root / "out"
out.mkdir(exist_ok=True)
pdd.write_mesh(out / "kitten_python.ply", mesh)
print(f"wrote {out / 'kitten_python.ply'}")

try:
    import open3d as o3d
except ImportError:
    print("open3d is not installed (Debian: python3-open3d): skipping the hand-over")
else:
    o3d_mesh = mesh.to_open3d()
    o3d_mesh.compute_vertex_normals()
    print(f"Open3D: edge-manifold {o3d_mesh.is_edge_manifold()}, area {o3d_mesh.get_surface_area():.4g}, "
          f"volume {o3d_mesh.get_volume():.4g}")
    o3d.io.write_triangle_mesh(str(out / "kitten_open3d.ply"), o3d_mesh)
    print(f"wrote {out / 'kitten_open3d.ply'} (with Open3D's vertex normals)")
