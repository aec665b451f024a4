#!/usr/bin/env python3
"""Topology and accuracy on CGAL shapes beyond the bunny and the fandisk (issue 19).

Five closed meshes of CGAL's data set (libcgal-demo's data.tar.gz), each centred and scaled to a
bounding-box diagonal of 1 and sampled in the six variants of ../shared/data: clean (20k points,
area-uniform, exact normals), sparse (2k), noise05 / noise10 (Gaussian offsets along the normal of
0.5 % / 1 % of the diagonal, normals jittered by 0.1 / 0.2 per component), holes (three balls of
radius 8 % of the diagonal emptied) and vardens (one half of the shape ten times sparser). Then
pdd with default options, PoissonRecon and SSDRecon at depth 8 (../shared/anchors/bin) on each:
topology right (closed, manifold, the truth's components and genus), Chamfer-L1 and Hausdorff to
the truth, mean min angle, share of triangles under 20°, wall time.

  bench/cgal_shapes.py [--pdd PATH] [--only REGEX] [--no-peers] [--keep DIR] [--out FILE]
                       [-- extra pdd reconstruct options]

Inputs are generated once (seeded) into build/cgal_shapes/. Writes bench/results/cgal_shapes.md.
"""
import argparse, json, os, re, subprocess, sys, tarfile, tempfile, time
import numpy as np
import open3d as o3d

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARBALL = "/usr/share/doc/libcgal-dev/data.tar.gz"
# name -> why it is here
SHAPES = {
    "armadillo": "thin parts: ears, fingers, claws (genus 0)",
    "camel": "thin legs and neck (genus 0)",
    "elephant": "thin trunk and tusks, genus 3",
    "knot1": "a knotted tube, genus 1",
    "couplingdown": "a mechanical part of genus 9",
}
VARIANTS = ["clean", "sparse", "noise05", "noise10", "holes", "vardens"]


def extract_mesh(name, dest):
    path = os.path.join(dest, name + ".off")
    if not os.path.exists(path):
        with tarfile.open(TARBALL) as tar:
            member = tar.getmember(f"data/meshes/{name}.off")
            with tar.extractfile(member) as f, open(path, "wb") as out:
                out.write(f.read())
    return path


def normalized_truth(name, dest):
    """The mesh centred and scaled to a bounding-box diagonal of 1, written as PLY."""
    out = os.path.join(dest, f"{name}_gt.ply")
    mesh = o3d.io.read_triangle_mesh(extract_mesh(name, dest))
    v = np.asarray(mesh.vertices)
    lo, hi = v.min(0), v.max(0)
    mesh.vertices = o3d.utility.Vector3dVector((v - (lo + hi) / 2) / np.linalg.norm(hi - lo))
    if not os.path.exists(out):
        o3d.io.write_triangle_mesh(out, mesh, write_ascii=False)
    return out, mesh


def area_samples(mesh, n, rng):
    """n area-uniform points on the mesh with their faces' normals."""
    v = np.asarray(mesh.vertices)
    f = np.asarray(mesh.triangles)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    cross = np.cross(b - a, c - a)
    area = np.linalg.norm(cross, axis=1)
    face = rng.choice(len(f), size=n, p=area / area.sum())
    r1, r2 = rng.random(n), rng.random(n)
    s = np.sqrt(r1)
    p = (1 - s)[:, None] * a[face] + (s * (1 - r2))[:, None] * b[face] + (s * r2)[:, None] * c[face]
    return p, cross[face] / area[face][:, None]


def write_points(path, p, n):
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(p) +
              "".join(f"property float {k}\n" for k in ["x", "y", "z", "nx", "ny", "nz"]) +
              "end_header\n")
    with open(path, "wb") as out:
        out.write(header.encode())
        out.write(np.hstack([p, n]).astype("<f4").tobytes())


def make_variants(name, mesh, dest, seed=1):
    paths = {}
    for k, variant in enumerate(VARIANTS):
        path = os.path.join(dest, f"{name}_{variant}.ply")
        paths[variant] = path
        if os.path.exists(path):
            continue
        rng = np.random.default_rng(seed * 100 + k)
        if variant == "sparse":
            p, n = area_samples(mesh, 2000, rng)
        elif variant == "vardens":
            p, n = area_samples(mesh, 20000, rng)
            keep = (p[:, 0] < 0) | (rng.random(len(p)) < 0.1)
            p, n = p[keep], n[keep]
        elif variant == "holes":
            p, n = area_samples(mesh, 20000, rng)
            centres = p[rng.choice(len(p), 3, replace=False)]
            keep = np.ones(len(p), bool)
            for c in centres:
                keep &= np.linalg.norm(p - c, axis=1) > 0.08
            p, n = p[keep], n[keep]
        else:
            p, n = area_samples(mesh, 20000, rng)
            if variant.startswith("noise"):
                sigma = 0.005 if variant == "noise05" else 0.01
                p = p + n * rng.normal(0, sigma, len(p))[:, None]
                n = n + rng.normal(0, 20 * sigma, n.shape)
                n /= np.linalg.norm(n, axis=1)[:, None]
        write_points(path, p, n)
    return paths


def run(cmd, **kw):
    start = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    return r, time.monotonic() - start


def truth_topology(pdd, gt):
    q = json.loads(subprocess.run([pdd, "quality", gt, "--json"], capture_output=True, text=True,
                                  check=True).stdout)
    return q["surface"]["components"], q["surface"]["genus"]


def measure(pdd, out, gt, truth):
    q = json.loads(subprocess.run([pdd, "quality", out, "--json"], capture_output=True, text=True,
                                  check=True).stdout)
    c = json.loads(subprocess.run([pdd, "compare", out, gt, "--json"], capture_output=True, text=True,
                                  check=True).stdout)
    t = q["surface"]
    right = bool(t["closed"] and t["manifold"] and (t["components"], t["genus"]) == truth)
    return {"right": right, "genus": t["genus"], "components": t["components"],
            "closed": t["closed"], "chamfer": c["chamfer_l1_relative"] * 1e3, "hausdorff": c["hausdorff_relative"] * 100,
            "angle": q["triangles"]["mean_min_angle"],
            "below20": q["triangles"]["fraction_min_angle_below_20"] * 100, "faces": q["triangles"]["count"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pdd", default=os.path.join(ROOT, "build", "pdd"))
    ap.add_argument("--only", default="")
    ap.add_argument("--no-peers", action="store_true")
    ap.add_argument("--keep", default="")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "cgal_shapes.md"))
    ap.add_argument("extra", nargs="*")
    args = ap.parse_args()
    data = os.path.join(ROOT, "build", "cgal_shapes")
    os.makedirs(data, exist_ok=True)
    work = args.keep or tempfile.mkdtemp(prefix="pdd_cgal_shapes.")
    os.makedirs(work, exist_ok=True)
    anchors = os.path.join(ROOT, "..", "shared", "anchors", "bin")
    peers = [] if args.no_peers or not os.path.isdir(anchors) else [
        ("PoissonRecon d8", [os.path.join(anchors, "PoissonRecon"), "--depth", "8"]),
        ("SSDRecon d8", [os.path.join(anchors, "SSDRecon"), "--depth", "8"])]
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    rows = []
    lines = [f"# CGAL shapes (bench/cgal_shapes.py {' '.join(args.extra)}, commit {commit}, "
             f"{os.cpu_count()} cores, {time.strftime('%Y-%m-%d')})", "",
             "| input | tool | topology right | components | genus | Chamfer-L1 (1e-3) | Hausdorff (%) "
             "| mean min angle | under 20° (%) | faces | seconds |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    print("\n".join(lines), flush=True)
    for shape in SHAPES:
        gt, mesh = normalized_truth(shape, data)
        truth = truth_topology(args.pdd, gt)
        for variant, path in make_variants(shape, mesh, data).items():
            name = f"{shape}_{variant}"
            if args.only and not re.search(args.only, name):
                continue
            tools = [("pdd", [args.pdd, "reconstruct", path, "-o", None, "--quiet", *args.extra])]
            tools += [(label, cmd + ["--in", path, "--out", None]) for label, cmd in peers]
            for label, cmd in tools:
                out = os.path.join(work, f"{name}.{label.split()[0]}.ply")
                cmd = [out if c is None else c for c in cmd]
                r, seconds = run(cmd)
                if r.returncode != 0:
                    row = {"right": False, "failed": r.stderr.strip().splitlines()[-1:]}
                else:
                    row = measure(args.pdd, out, gt, truth)
                row.update(input=name, tool=label, seconds=seconds, truth=truth)
                rows.append(row)
                if "failed" in row:
                    line = f"| {name} | {label} | failed: {row['failed']} | | | | | | | | {seconds:.1f} |"
                else:
                    line = (f"| {name} | {label} | {'yes' if row['right'] else 'no'} | {row['components']} "
                            f"| {row['genus']} | {row['chamfer']:.3f} | {row['hausdorff']:.2f} "
                            f"| {row['angle']:.1f} | {row['below20']:.2f} | {row['faces']} | {seconds:.1f} |")
                lines.append(line)
                print(line, flush=True)
    lines += ["", "Topology right, of the inputs run:"]
    for label in ["pdd"] + [p[0] for p in peers]:
        mine = [r for r in rows if r["tool"] == label]
        lines.append(f"- {label}: {sum(r['right'] for r in mine)} of {len(mine)}")
    lines += ["", "Truth: " + ", ".join(f"{s} components {c} genus {g}" for s, (c, g) in
                                         ((s, truth_topology(args.pdd, os.path.join(data, f'{s}_gt.ply')))
                                          for s in SHAPES)) + "."]
    print("\n".join(lines[-(len(peers) + 4):]))
    with open(args.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    json.dump(rows, open(os.path.splitext(args.out)[0] + ".json", "w"), indent=1)


if __name__ == "__main__":
    sys.exit(main())
