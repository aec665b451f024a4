#!/usr/bin/env python3
"""Point sets without normals, or with normals of unknown orientation (issue 17).

For every input of ../shared/data/points (the bunny and the fandisk, six variants each):
pdd with the true normals (the reference), then with the normals removed and with half of
them flipped (seed 0), for each orientation design (--orientation); side by side, Open3D's
estimate_normals + orient_normals_consistent_tangent_plane + Poisson (depth 8) on the same
bare points. Per run: topology (closed, manifold, components, genus against the truth's),
Chamfer-L1 against the ground truth (pdd compare, 100k samples), mean min angle, wall time
and peak memory; and the ratios against the true-normals run.

    bash scripts/build.sh && /usr/bin/python3 bench/unoriented.py [--only REGEX]
        [--designs spectral,visibility,mst,spectral-solver]
        [--pdd BIN] [--output FILE]

Writes bench/results/unoriented.md (also printed).
"""

import argparse
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

root = pathlib.Path(__file__).resolve().parent.parent
pdd = root / "build" / "pdd"
data = root.parent / "shared" / "data"
TRUTH = {"bunny": (1, 0), "fandisk": (1, 0)}  # components, genus


def timed(command):
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(process.pid, 0)
    err = process.stderr.read().decode()
    process.stderr.close()
    return status == 0, time.monotonic() - start, usage.ru_maxrss / 1024, err


def measure(mesh, shape):
    q = json.loads(subprocess.run([pdd, "quality", mesh, "--json"], check=True,
                                  capture_output=True, text=True).stdout)
    c = json.loads(subprocess.run([pdd, "compare", mesh, data / "gt" / f"{shape}.ply", "--json",
                                   "--samples", "100000"], check=True, capture_output=True,
                                  text=True).stdout)
    s = q["surface"]
    right = s["closed"] and s["manifold"] and (s["components"], s["genus"]) == TRUTH[shape]
    return {"chamfer": c["chamfer_l1_relative"], "genus": s["genus"],
            "components": s["components"], "right": right,
            "angle": q["triangles"]["mean_min_angle"], "faces": q["faces"]}


def open3d_poisson(xyz, out):
    """Open3D's own pipeline on bare points, in a child process (timed like the others)."""
    script = (
        "import sys, numpy as np, open3d as o3d\n"
        "p = np.loadtxt(sys.argv[1])[:, :3]\n"
        "pc = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(p))\n"
        "pc.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(18))\n"
        "pc.orient_normals_consistent_tangent_plane(18)\n"
        "m, _ = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pc, depth=8)\n"
        "o3d.io.write_triangle_mesh(sys.argv[2], m)\n")
    return timed(["/usr/bin/python3", "-c", script, xyz, out])


def design_args(design, given):
    """pdd's options for a design: an orientation, or "spectral-solver" (the spectral solver,
    which ignores the normals' signs: bare points get estimated normals, given ones are kept)."""
    if design == "spectral-solver":
        return ["--solver", "spectral"]
    return (["--normals", "orient"] if given else []) + ["--orientation", design]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--only", default="")
    parser.add_argument("--designs", default="spectral,mst")
    parser.add_argument("--pdd", default=str(pdd), help="the binary (default build/pdd)")
    parser.add_argument("--output", default=str(root / "bench" / "results" / "unoriented.md"))
    args = parser.parse_args()
    globals()["pdd"] = pathlib.Path(args.pdd)
    designs = args.designs.split(",")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for ply in sorted((data / "points").glob("*.ply")):
            name, shape = ply.stem, ply.stem.split("_")[0]
            if shape not in TRUTH or not re.search(args.only, name):
                continue
            table = np.loadtxt(data / "points" / f"{name}.xyz")
            bare, flipped = tmp / f"{name}_bare.xyz", tmp / f"{name}_flipped.xyz"
            np.savetxt(bare, table[:, :3], fmt="%.17g")
            signs = np.where(np.random.default_rng(0).random(len(table)) < 0.5, -1.0, 1.0)
            np.savetxt(flipped, np.column_stack([table[:, :3], table[:, 3:] * signs[:, None]]),
                       fmt="%.17g")
            runs = [("true normals", [ply], [])]
            for d in designs:
                runs.append((f"no normals, {d}", [bare], design_args(d, False)))
            for d in designs:
                runs.append((f"half flipped, {d}", [flipped], design_args(d, True)))
            reference = None
            for label, (source,), extra in runs:
                out = tmp / "out.ply"
                ok, seconds, mb, err = timed([pdd, "reconstruct", source, "-o", out, "--quiet",
                                              *extra])
                row = {"input": name, "run": label, "seconds": seconds, "mb": mb, "ok": ok}
                if ok:
                    row.update(measure(out, shape))
                    reference = reference or row
                else:
                    row["error"] = err.strip().splitlines()[-1] if err.strip() else "failed"
                rows.append((row, reference))
                print(f"{name} {label}: {format_row(row, reference)}", flush=True)
            out = tmp / "o3d.ply"
            ok, seconds, mb, err = open3d_poisson(bare, out)
            row = {"input": name, "run": "Open3D: PCA + tangent-plane MST + Poisson d8",
                   "seconds": seconds, "mb": mb, "ok": ok}
            if ok:
                row.update(measure(out, shape))
            rows.append((row, reference))
            print(f"{name} {row['run']}: {format_row(row, reference)}", flush=True)

    lines = ["| input | run | topology right | genus | components | Chamfer-L1 (1e-3) | "
             "x true | mean min angle | time s | x true | peak MB |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for row, reference in rows:
        lines.append("| " + format_row(row, reference, markdown=True) + " |")
    summary = {}
    for row, reference in rows:
        run = row["run"].split(" (")[0]
        s = summary.setdefault(run, {"right": 0, "n": 0, "chamfer": [], "time": []})
        s["n"] += 1
        if row["ok"]:
            s["right"] += row["right"]
            s["chamfer"].append(row["chamfer"] / reference["chamfer"])
            s["time"].append(row["seconds"] / reference["seconds"])
    lines += ["", "| run | topology right | Chamfer x true (mean, max) | time x true (mean, max) |",
              "| --- | --- | --- | --- |"]
    for run, s in summary.items():
        c, t = s["chamfer"] or [float("nan")], s["time"] or [float("nan")]
        lines.append(f"| {run} | {s['right']} of {s['n']} | {np.mean(c):.2f}, {max(c):.2f} | "
                     f"{np.mean(t):.2f}, {max(t):.2f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    pathlib.Path(args.output).write_text(text)


def format_row(row, reference, markdown=False):
    if not row["ok"]:
        cells = [row["input"], row["run"], f"failed: {row.get('error', '')}"] + [""] * 8
    else:
        cells = [row["input"], row["run"], "yes" if row["right"] else "no", str(row["genus"]),
                 str(row["components"]), f"{row['chamfer'] * 1e3:.3f}",
                 f"{row['chamfer'] / reference['chamfer']:.2f}", f"{row['angle']:.1f}",
                 f"{row['seconds']:.1f}", f"{row['seconds'] / reference['seconds']:.2f}",
                 f"{row['mb']:.0f}"]
    return (" | " if markdown else "  ").join(cells)


if __name__ == "__main__":
    sys.exit(main())
