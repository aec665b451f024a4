#!/usr/bin/python3
"""The spectral solver against SSD on dense virtual scans (issue 17).

Inputs: virtual scans (../shared/tools/virtual_scan.py, seed 1: occlusion holes, an unseen base,
noise along the rays) of CGAL's fandisk_large and bunny00, cached under build/scale_inputs/ as
bench/scale.sh caches them. For each, in turn: pdd --solver spectral, then pdd (SSD), with
/usr/bin/time. Per output: wall time, peak memory, final domain vertices, triangles, iterations;
the mean distance, relative to the points' diagonal, from the truth's surface where the scan saw
it (within 0.3 % of the diagonal of a point) to the output and back from the output there; and the
mean dihedral angle between adjacent triangles there (a surface that follows the noise is rough).

    /usr/bin/python3 bench/spectral_scans.py [--points N] [--pdd build/pdd] [--out FILE]

Needs python3-open3d (scripts/setup.sh). About 5 minutes at 100k points on 2 cores.
"""

import argparse
import datetime
import json
import pathlib
import re
import subprocess
import tempfile

import numpy as np
import open3d as o3d

root = pathlib.Path(__file__).resolve().parent.parent


def scan(shape, points):
    data = root / "build/scale_inputs/cgal"
    if not (data / "data/meshes").is_dir():
        data.mkdir(parents=True, exist_ok=True)
        subprocess.run(["tar", "-xzf", "/usr/share/doc/libcgal-dev/data.tar.gz", "-C", str(data),
                        "data/meshes"], check=True)
    truth = data / f"data/meshes/{shape}.off"
    path = root / f"build/scale_inputs/{shape}_{points}.ply"
    if not path.exists():
        subprocess.run(["/usr/bin/python3", str(root / "../shared/tools/virtual_scan.py"), str(truth),
                        str(path), "--points", str(points), "--seed", "1"], check=True,
                       stdout=subprocess.DEVNULL)
    return path, truth


def distance_to(mesh, points):
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.t.geometry.TriangleMesh.from_legacy(mesh))
    return scene.compute_distance(o3d.core.Tensor(points.astype(np.float32))).numpy()


def measure(output, cloud, truth):
    """Seen-part distances both ways and roughness, relative to the points' diagonal."""
    P = np.asarray(cloud.points)
    diag = np.linalg.norm(P.max(0) - P.min(0))
    near = lambda X: np.asarray(  # noqa: E731
        o3d.geometry.PointCloud(o3d.utility.Vector3dVector(X)).compute_point_cloud_distance(cloud)
    ) < 0.003 * diag
    mesh = o3d.io.read_triangle_mesh(str(output))
    seen_truth = np.asarray(truth.sample_points_uniformly(300000).points)
    seen_truth = seen_truth[near(seen_truth)]
    seen_out = np.asarray(mesh.sample_points_uniformly(300000).points)
    seen_out = seen_out[near(seen_out)]
    to_out = distance_to(mesh, seen_truth).mean() / diag
    to_truth = distance_to(truth, seen_out).mean() / diag
    V, T = np.asarray(mesh.vertices), np.asarray(mesh.triangles)
    n = np.cross(V[T[:, 1]] - V[T[:, 0]], V[T[:, 2]] - V[T[:, 0]])
    n /= np.maximum(np.linalg.norm(n, axis=1)[:, None], 1e-300)
    edges = np.concatenate([np.sort(T[:, [a, b]], 1) for a, b in ((0, 1), (1, 2), (2, 0))])
    face = np.tile(np.arange(len(T)), 3)
    key = edges[:, 0].astype(np.int64) * (len(V) + 1) + edges[:, 1]
    order = np.argsort(key, kind="stable")
    key, face = key[order], face[order]
    pair = key[1:] == key[:-1]
    f1, f2 = face[:-1][pair], face[1:][pair]
    angle = np.degrees(np.arccos(np.clip((n[f1] * n[f2]).sum(1), -1, 1)))
    angle = angle[near(V[T[f1]].mean(1))]
    return to_out, to_truth, angle.mean(), (angle > 20).mean()


def run(pdd, path, solver, work):
    out, stats, log = (work / f"{path.stem}_{solver}{s}" for s in (".ply", ".json", ".log"))
    with open(log, "w") as f:
        subprocess.run(["/usr/bin/time", "-v", pdd, "reconstruct", str(path), "-o", str(out),
                        "--solver", solver, "--stats", str(stats)], stdout=f, stderr=f, check=True)
    text = log.read_text()
    clock = re.search(r"Elapsed.*: (\S+)", text).group(1).split(":")
    seconds = sum(float(x) * 60 ** i for i, x in enumerate(reversed(clock)))
    peak = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", text).group(1)) / 1024
    alpha = re.search(r"value weight alpha (\S+)", text).group(1)
    s = json.loads(stats.read_text())
    return out, seconds, peak, s["vertices"], s["triangles"], len(s["iterations"]), alpha


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=100000)
    ap.add_argument("--pdd", default=str(root / "build/pdd"))
    ap.add_argument("--out", default=str(root / "bench/results/spectral_scans.md"))
    a = ap.parse_args()
    commit = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    lines = [f"# Spectral and SSD on {a.points}-point virtual scans ({datetime.date.today()}, "
             f"{commit}, `bench/spectral_scans.py`)", "",
             "| input | solver | s | MiB | vertices | triangles | iterations | alpha | "
             "seen truth -> output | output -> truth | dihedral mean | over 20° |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        for shape in ("fandisk_large", "bunny00"):
            path, truth_path = scan(shape, a.points)
            cloud = o3d.io.read_point_cloud(str(path))
            truth = o3d.io.read_triangle_mesh(str(truth_path))
            for solver in ("spectral", "ssd"):
                out, seconds, peak, v, t, it, alpha = run(a.pdd, path, solver, pathlib.Path(tmp))
                to_out, to_truth, dihedral, rough = measure(out, cloud, truth)
                lines.append(f"| {path.stem} | {solver} | {seconds:.1f} | {peak:.0f} | {v} | {t} | "
                             f"{it} | {alpha} | {to_out:.3e} | {to_truth:.3e} | {dihedral:.2f}° | "
                             f"{100 * rough:.2f} % |")
                print(lines[-1], flush=True)
    pathlib.Path(a.out).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
