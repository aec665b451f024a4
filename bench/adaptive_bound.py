#!/usr/bin/env python3
"""How many triangles curvature-adaptive sizing can save at a matched Chamfer-L1 (issue 19).

For each clean input: the uniform default, the uniform sizing and `--sizing adaptive` at
`--target-faces` fractions of the default's count, Chamfer-L1 to the truth as a ratio to the
default's; the adaptive count that matches the default's Chamfer-L1 (linear between the two
fractions that straddle it); and the bound a curvature field can reach: if the distance a
triangle of edge h adds goes as c h^2 (c the largest absolute principal curvature), the mean
distance at a fixed count is smallest with the target area ~ c^-1/2, and at the uniform run's
mean distance that field needs G = (mean sqrt c)^2 / mean c of its triangles (the paper's
area ~ 1/c equalises c h^2 and needs as many as uniform). c is measured on the input by a
quadric fitted over each point's 24 nearest neighbours in the frame of its given normal.

  bench/adaptive_bound.py [--pdd PATH] [--out FILE]

Inputs: the clean variants of bench/cgal_shapes.py's shapes (generated into build/cgal_shapes/)
and ../shared/data's bunny_clean and fandisk_clean. Writes bench/results/adaptive_bound.md.
"""
import argparse, json, os, subprocess, sys, tempfile
import numpy as np
import open3d as o3d

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cgal_shapes  # noqa: E402  (the shapes' inputs and truths)

ROOT = cgal_shapes.ROOT
UNIFORM = [0.7, 1.3]
ADAPTIVE = [0.55, 0.7, 0.85]


def inputs():
    dest = os.path.join(ROOT, "build", "cgal_shapes")
    os.makedirs(dest, exist_ok=True)
    out = []
    for name in cgal_shapes.SHAPES:
        gt, mesh = cgal_shapes.normalized_truth(name, dest)
        out.append((f"{name}_clean", cgal_shapes.make_variants(name, mesh, dest)["clean"], gt))
    shared = os.path.join(ROOT, "..", "shared", "data")
    for name in ["bunny", "fandisk"]:
        out.append((f"{name}_clean", os.path.join(shared, "points", f"{name}_clean.ply"),
                    os.path.join(shared, "gt", f"{name}.ply")))
    return out


def curvature_spread(path, k=24):
    pc = o3d.io.read_point_cloud(path)
    p, n = np.asarray(pc.points), np.asarray(pc.normals)
    tree = o3d.geometry.KDTreeFlann(pc)
    c = np.zeros(len(p))
    for i in range(len(p)):
        _, idx, _ = tree.search_knn_vector_3d(p[i], k)
        q = p[np.asarray(idx)] - p[i]
        z_axis = n[i] / np.linalg.norm(n[i])
        x_axis = np.cross(z_axis, [1.0, 0, 0] if abs(z_axis[0]) < 0.9 else [0, 1.0, 0])
        x_axis /= np.linalg.norm(x_axis)
        y_axis = np.cross(z_axis, x_axis)
        x, y, z = q @ x_axis, q @ y_axis, q @ z_axis
        fit = np.linalg.lstsq(np.stack([x * x, x * y, y * y, x, y, np.ones_like(x)], 1), z, rcond=None)[0]
        c[i] = np.abs(np.linalg.eigvalsh([[2 * fit[0], fit[1]], [fit[1], 2 * fit[2]]])).max()
    return np.mean(np.sqrt(c)) ** 2 / np.mean(c)


def reconstruct(pdd, src, gt, out, args):
    subprocess.run([pdd, "reconstruct", src, "-o", out, "--quiet"] + args, check=True,
                   capture_output=True)
    q = json.loads(subprocess.run([pdd, "quality", out, "--json"], check=True, capture_output=True,
                                  text=True).stdout)
    c = json.loads(subprocess.run([pdd, "compare", out, gt, "--json"], check=True, capture_output=True,
                                  text=True).stdout)
    return q["faces"], c["chamfer_l1_relative"] * 1e3


def matched(points):
    """The count ratio where the Chamfer ratio crosses 1, linear between neighbours."""
    points = sorted(points)
    for (n0, c0), (n1, c1) in zip(points, points[1:]):
        if c0 >= 1 >= c1:
            return n0 + (c0 - 1) / (c0 - c1) * (n1 - n0)
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pdd", default=os.path.join(ROOT, "build", "pdd"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "adaptive_bound.md"))
    a = ap.parse_args()
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    lines = [f"# Adaptive sizing against its bound (bench/adaptive_bound.py, commit {commit}, {os.cpu_count()} cores)",
             "",
             "Count ratio: Chamfer-L1 ratio, both to the uniform default's.",
             "",
             "| input | default: triangles / Chamfer-L1 (1e-3) | uniform | adaptive (area ~ 1/c) | "
             "adaptive count at the default's Chamfer-L1 | bound G |",
             "| --- | --- | --- | --- | --- | --- |"]
    with tempfile.TemporaryDirectory() as tmp:
        mesh = os.path.join(tmp, "out.ply")
        for name, src, gt in inputs():
            print(f"adaptive_bound.py: {name} ...", file=sys.stderr)
            faces, chamfer = reconstruct(a.pdd, src, gt, mesh, [])
            rows = {}
            for sizing, fractions in [("uniform", UNIFORM), ("adaptive", ADAPTIVE)]:
                rows[sizing] = []
                for f in fractions:
                    n, c = reconstruct(a.pdd, src, gt, mesh, ["--sizing", sizing, "--target-faces",
                                                              str(int(f * faces))])
                    rows[sizing].append((n / faces, c / chamfer))
            m = matched(rows["adaptive"])
            cells = [", ".join(f"{n:.2f}: {c:.3f}" for n, c in sorted(rows[s])) for s in ["uniform", "adaptive"]]
            lines.append(f"| {name} | {faces} / {chamfer:.3f} | {cells[0]} | {cells[1]} | "
                         f"{'over %.2f' % max(n for n, _ in rows['adaptive']) if m is None else '%.2f' % m} | "
                         f"{curvature_spread(src):.2f} |")
            print(lines[-1])
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
