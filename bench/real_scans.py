#!/usr/bin/python3
"""Real scans: open surfaces (--trim), outliers (--outliers) and colours (issue 16).

Inputs, prepared once into a cache folder outside the repository (--work, default
/tmp/pdd_real_scans):

- CGAL's real scans (data/points_3 of /usr/share/doc/libcgal-dev/data.tar.gz): building and
  ball (x y z nx ny nz segment_index), hippo1 and hippo2 (x y z nx ny nz): open, one-sided;
- virtual scans of ../shared/data/gt/{bunny,fandisk}.ply by ../shared/tools/virtual_scan.py
  (50k points, seed 0): an unseen base, occlusion holes, normals toward the scanner;
- outlier variants of ../shared/data/points/{bunny,fandisk}_clean.ply: 1 % and 5 % extra
  points spread uniformly in the bounding box enlarged by 10 % (each side by 5 %), with random
  unit normals, shuffled in (seeded numpy generator); the mask of the true outliers is saved
  beside each file as NAME.outliers.npy;
- coloured inputs: CGAL's b9_training.ply (aerial LIDAR, x y z red green blue label, no
  normals) and bunny_ramp, bunny_clean coloured by an analytic field of the position
  (ramp_colour() below: red rises with height, green and blue are smooth waves along x and z),
  written with uchar red green blue.

Runs, for each input in turn, pdd first and the peers after it:
- `pdd reconstruct IN -o OUT --stats S.json`, closed (the default), and open (`--trim 2`) when
  `pdd reconstruct --help` lists --trim; with --outliers-off also `--outliers 0` on the outlier
  variants (when the option exists; minutes each). pdd's defaults apply otherwise (its outlier
  removal, its colour output). An input pdd refuses for zero normals (hippo2 has two) is run
  again without those points, and the report says so;
- PoissonRecon --density + SurfaceTrimmer --trim 7 --aRatio 0.001 (../shared/anchors), at the
  octree depth whose untrimmed output's face count is nearest pdd's closed output (from 8, one
  step at a time, stopping where one more level adds under 20 %: sparse scans saturate), with
  --colors for coloured inputs. Where trim 7 cuts into the scanned surface (its points-to-surface
  distance over 1.25x the untrimmed mesh's, or nothing left), one more row with the highest of
  6.5, 6, ..., 4 that does not ("lowered");
- Open3D's create_from_point_cloud_poisson at the same depth, trimmed by removing the vertices
  whose density is under its 5 % quantile (the usual recipe; one child process writes both).
Inputs without normals (b9_training) get Open3D's estimate_normals (18 neighbours) +
orient_normals_consistent_tangent_plane (18) for both peers; PoissonRecon's time includes that
step (a timed child process). Every command runs under a small launcher that times it and reads
its peak RSS with os.wait4 (a direct child of this process, which holds open3d, would inherit
its ~150 MB high-water mark), and stops it past --time-limit (900 s).

Metrics per output (numpy + open3d, `pdd quality --json` for manifoldness and genus, `pdd
compare --json` against the ground truth where there is one):
- area near samples: the share of the output's area (200k area-uniform samples) within 2
  average spacings s of an input point (average spacing: the mean distance of each input point
  to its nearest other one; outliers excluded) - an open surface should reach 99 %; also within
  3 s, since randomly spread samples cap the 2 s share at 1 - exp(-pi) = 95.7 % even on the
  true surface;
- points to surface: mean distance of the input points (outliers excluded) to the output,
  relative to their bounding-box diagonal (open3d RaycastingScene);
- components, boundary loops (connected sets of boundary edges), closed, manifold, faces, mean
  min angle and the share of triangles under 20 degrees, overall and over the triangles with a
  boundary edge (the cut);
- outlier variants: components of the output, points removed (the stats JSON's key containing
  "outlier"), and how many of them were not outliers: exact when the Python module (build/python)
  has a function returning the outlier mask, otherwise removed - true outliers, a lower bound;
  Chamfer-L1 and Hausdorff against the ground truth;
- colours: mean absolute error per channel (0-255) at the output's vertices, against the
  analytic field (bunny_ramp) or the nearest input point's colour (b9_training).

    /usr/bin/python3 bench/real_scans.py [--only REGEX] [--work DIR] [--skip-peers]
                                         [--outliers-off] [--time-limit S] [--output FILE]
    bash bench/real_scans.sh ...        # the same

It uses build/pdd as it is (build it first: bash scripts/build.sh), and build/python for the
outlier mask when the module there has a function with "outlier" in its name.

Writes bench/results/real_scans.md (also printed) and WORK/results.json. About 20-30 minutes
on 2 cores with all inputs.
"""

import argparse
import datetime
import json
import os
import pathlib
import re
import subprocess
import sys
import tarfile
import time

import numpy as np
import open3d as o3d

root = pathlib.Path(__file__).resolve().parent.parent
PDD = root / "build" / "pdd"
shared = root.parent / "shared"
ANCHORS = shared / "anchors" / "bin"
CGAL_DATA = pathlib.Path("/usr/share/doc/libcgal-dev/data.tar.gz")
PY = "/usr/bin/python3"
SAMPLES = 200000
TRIM_TOLERANCE = 1.25  # a SurfaceTrimmer value "cuts into the scan" past this x untrimmed p2s

# name -> (topics, kind); topics: open, outliers, colours
INPUTS = {
    "hippo1": ({"open"}, "cgal"),
    "hippo2": ({"open"}, "cgal"),
    "ball": ({"open"}, "cgal"),
    "building": ({"open"}, "cgal"),
    "vscan_bunny": ({"open"}, "vscan"),
    "vscan_fandisk": ({"open"}, "vscan"),
    "bunny_out1": ({"outliers"}, "outliers"),
    "bunny_out5": ({"outliers"}, "outliers"),
    "fandisk_out1": ({"outliers"}, "outliers"),
    "fandisk_out5": ({"outliers"}, "outliers"),
    "bunny_ramp": ({"colours"}, "ramp"),
    "b9_training": ({"colours", "open"}, "cgal"),
}


# ---------------------------------------------------------------------------------------------
# PLY vertex element I/O (the vertex element only; binary little endian or ascii)

PLY_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2",
             "int16": "i2", "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4",
             "uint": "u4", "uint32": "u4", "float": "f4", "float32": "f4", "double": "f8",
             "float64": "f8"}


def ply_header(path):
    with open(path, "rb") as f:
        lines = []
        while True:
            line = f.readline()
            if not line:
                raise ValueError(f"{path}: no end_header")
            line = line.decode("ascii", "replace").strip()
            lines.append(line)
            if line == "end_header":
                return lines, f.tell()


def read_ply_vertices(path):
    """The vertex element of a PLY as {property: array}, with the property types."""
    lines, offset = ply_header(path)
    fmt = next(l.split()[1] for l in lines if l.startswith("format"))
    elements, current = [], None
    for l in lines:
        w = l.split()
        if w[0] == "element":
            current = (w[1], int(w[2]), [])
            elements.append(current)
        elif w[0] == "property" and current is not None:
            current[2].append((w[-1], w[1:-1]))
    name, count, props = elements[0]
    if name != "vertex" or any(p[1][0] == "list" for p in props):
        raise ValueError(f"{path}: the vertex element is not first or has lists")
    types = {p[0]: PLY_TYPES[p[1][0]] for p in props}
    if fmt == "ascii":
        with open(path, "rb") as f:
            f.seek(offset)
            rows = [f.readline().split() for _ in range(count)]
        table = np.array(rows, dtype=np.float64).reshape(count, len(props))
        return {p[0]: table[:, i] for i, p in enumerate(props)}, types
    if fmt != "binary_little_endian":
        raise ValueError(f"{path}: {fmt} is not read here")
    dtype = np.dtype([(p[0], "<" + PLY_TYPES[p[1][0]]) for p in props])
    with open(path, "rb") as f:
        f.seek(offset)
        data = np.frombuffer(f.read(dtype.itemsize * count), dtype=dtype, count=count)
    return {p[0]: data[p[0]].astype(np.float64) for p in props}, types


def write_points_ply(path, points, normals=None, colours=None, real="f4"):
    fields = [("x", real), ("y", real), ("z", real)]
    columns = [points[:, 0], points[:, 1], points[:, 2]]
    if normals is not None:
        fields += [("nx", real), ("ny", real), ("nz", real)]
        columns += [normals[:, 0], normals[:, 1], normals[:, 2]]
    if colours is not None:
        fields += [("red", "u1"), ("green", "u1"), ("blue", "u1")]
        columns += [colours[:, 0], colours[:, 1], colours[:, 2]]
    data = np.empty(len(points), dtype=np.dtype([(n, "<" + t) for n, t in fields]))
    for (n, _), c in zip(fields, columns):
        data[n] = c
    names = {"f4": "float", "f8": "double", "u1": "uchar"}
    header = ["ply", "format binary_little_endian 1.0", "comment bench/real_scans.py",
              f"element vertex {len(points)}"]
    header += [f"property {names[t]} {n}" for n, t in fields] + ["end_header"]
    tmp = pathlib.Path(str(path) + ".tmp")
    with open(tmp, "wb") as f:
        f.write(("\n".join(header) + "\n").encode())
        f.write(data.tobytes())
    tmp.rename(path)


def cloud_arrays(vertices):
    p = np.column_stack([vertices["x"], vertices["y"], vertices["z"]])
    n = (np.column_stack([vertices["nx"], vertices["ny"], vertices["nz"]])
         if "nx" in vertices else None)
    c = (np.column_stack([vertices["red"], vertices["green"], vertices["blue"]])
         if "red" in vertices else None)
    return p, n, c


# ---------------------------------------------------------------------------------------------
# inputs

def ramp_colour(p, lo, hi):
    """The analytic colour field of bunny_ramp (0-255, float): red rises with the height y,
    green and blue are smooth waves along x and z. lo, hi: the clean points' bounding box."""
    u = np.clip((p - lo) / (hi - lo), 0.0, 1.0)
    return np.column_stack([255.0 * u[:, 1],
                            255.0 * (0.5 + 0.5 * np.sin(2.0 * np.pi * u[:, 0])),
                            255.0 * (0.5 + 0.5 * np.cos(np.pi * u[:, 2]))])


def prepare(name, kind, work):
    """Writes WORK/inputs/NAME.ply (pdd's input), NAME.meta.json and, for the peers,
    NAME.peer.ply (x y z nx ny nz [red green blue], double). Cached."""
    folder = work / "inputs"
    folder.mkdir(parents=True, exist_ok=True)
    meta_path = folder / f"{name}.meta.json"
    if meta_path.exists():
        return json.loads(meta_path.read_text())
    src = folder / f"{name}.ply"
    meta = {"name": name, "kind": kind, "input": str(src), "peer_input": str(folder / f"{name}.peer.ply")}
    if kind == "cgal":
        member = f"data/points_3/{name}.ply"
        with tarfile.open(CGAL_DATA) as tar:
            data = tar.extractfile(member).read()
        src.write_bytes(data)
        meta["source"] = f"{CGAL_DATA}:{member}"
    elif kind == "vscan":
        shape = name.split("_")[1]
        subprocess.run([PY, str(shared / "tools" / "virtual_scan.py"),
                        str(shared / "data" / "gt" / f"{shape}.ply"), str(src),
                        "--points", "50000", "--seed", "0"], check=True,
                       stdout=subprocess.DEVNULL)
        meta["gt"] = str(shared / "data" / "gt" / f"{shape}.ply")
        meta["source"] = f"virtual_scan.py gt/{shape}.ply --points 50000 --seed 0"
    elif kind == "outliers":
        shape, rate = name.split("_out")
        rate = int(rate) / 100.0
        v, _ = read_ply_vertices(shared / "data" / "points" / f"{shape}_clean.ply")
        p, n, _ = cloud_arrays(v)
        rng = np.random.default_rng(int(rate * 100))
        lo, hi = p.min(0), p.max(0)
        centre, half = (lo + hi) / 2, (hi - lo) / 2 * 1.1
        k = int(round(rate * len(p)))
        po = rng.uniform(centre - half, centre + half, (k, 3))
        no = rng.normal(size=(k, 3))
        no /= np.linalg.norm(no, axis=1, keepdims=True)
        order = rng.permutation(len(p) + k)
        allp, alln = np.vstack([p, po])[order], np.vstack([n, no])[order]
        mask = (np.arange(len(p) + k) >= len(p))[order]
        write_points_ply(src, allp, alln)
        np.save(folder / f"{name}.outliers.npy", mask)
        meta["gt"] = str(shared / "data" / "gt" / f"{shape}.ply")
        meta["source"] = f"{shape}_clean.ply + {k} uniform outliers (seed {int(rate * 100)})"
        meta["outliers"] = str(folder / f"{name}.outliers.npy")
    elif kind == "ramp":
        v, _ = read_ply_vertices(shared / "data" / "points" / "bunny_clean.ply")
        p, n, _ = cloud_arrays(v)
        lo, hi = p.min(0), p.max(0)
        colours = np.clip(np.rint(ramp_colour(p, lo, hi)), 0, 255).astype(np.uint8)
        write_points_ply(src, p, n, colours)
        meta["ramp_box"] = [lo.tolist(), hi.tolist()]
        meta["gt"] = str(shared / "data" / "gt" / "bunny.ply")
        meta["source"] = "bunny_clean.ply + ramp_colour()"
    v, _ = read_ply_vertices(src)
    p, n, c = cloud_arrays(v)
    meta["points"] = len(p)
    meta["has_normals"] = n is not None
    meta["has_colours"] = c is not None
    peer = pathlib.Path(meta["peer_input"])
    if n is not None:
        write_points_ply(peer, p, n, c, real="f8")
    else:
        # the peers' normals: Open3D's estimate + tangent-plane orientation, timed
        script = (
            "import sys, numpy as np, open3d as o3d\n"
            "sys.dont_write_bytecode = True\n"
            f"sys.path.insert(0, {str(pathlib.Path(__file__).resolve().parent)!r})\n"
            "import real_scans as rs\n"
            "v, _ = rs.read_ply_vertices(sys.argv[1]); p, n, c = rs.cloud_arrays(v)\n"
            "pc = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(p - p.mean(0)))\n"
            "pc.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(18))\n"
            "pc.orient_normals_consistent_tangent_plane(18)\n"
            "rs.write_points_ply(sys.argv[2], p, np.asarray(pc.normals), c, real='f8')\n")
        ok, seconds, mb, err = timed([PY, "-c", script, str(src), str(peer)])
        if not ok:
            raise RuntimeError(f"normal estimation for the peers failed: {err[-500:]}")
        meta["peer_normals"] = {"seconds": seconds, "mb": mb}
    meta_path.write_text(json.dumps(meta, indent=1))
    return meta


# ---------------------------------------------------------------------------------------------
# runs

# A child of this process would report at least this process's peak RSS (Linux keeps the
# high-water mark across fork and exec, and open3d makes it ~150 MB): a small Python launcher
# starts the command, times it and reads its rusage with os.wait4.
# The launcher stops the command (SIGTERM, then SIGKILL) past the time limit.
LAUNCHER = """
import os, signal, subprocess, sys, time
limit = float(sys.argv[2])
start = time.monotonic()
process = subprocess.Popen(sys.argv[3:], stdout=subprocess.DEVNULL)
stopped = None
while True:
    pid, status, usage = os.wait4(process.pid, os.WNOHANG)
    if pid:
        break
    elapsed = time.monotonic() - start
    if stopped is None and elapsed > limit:
        process.send_signal(signal.SIGTERM); stopped = elapsed
    elif stopped is not None and elapsed > stopped + 10:
        process.kill()
    time.sleep(0.05)
with open(sys.argv[1], "w") as f:
    f.write(f"{status if stopped is None else -1} {time.monotonic() - start} {usage.ru_maxrss}")
"""
TIME_LIMIT = [900.0]  # seconds per command (--time-limit)
LOADS = []  # the 1-minute load average before each timed command
BINARIES = {}  # build/pdd's modification time when each pdd run starts -> the inputs run


def timed(command):
    """(ok, wall seconds, peak RSS in MB, stderr) of a command; stderr ends with a line
    saying so when the time limit stopped it."""
    report = pathlib.Path(f"/tmp/pdd_real_scans_rusage_{os.getpid()}")
    report.unlink(missing_ok=True)
    try:
        LOADS.append(float(pathlib.Path("/proc/loadavg").read_text().split()[0]))
    except (OSError, ValueError):
        pass
    process = subprocess.Popen([PY, "-c", LAUNCHER, str(report), str(TIME_LIMIT[0])]
                               + [str(c) for c in command],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    err = process.stderr.read().decode(errors="replace")
    process.stderr.close()
    process.wait()
    try:
        status, seconds, kb = report.read_text().split()
        report.unlink()
    except (OSError, ValueError):
        return False, 0.0, 0.0, err or "the launcher failed"
    if int(status) == -1:
        err += f"\nstopped at the time limit ({TIME_LIMIT[0]:.0f} s)"
    return int(status) == 0, float(seconds), int(kb) / 1024, err


def last_line(err):
    lines = [l for l in err.strip().splitlines() if l.strip()]
    return lines[-1][:200] if lines else "failed"


def pdd_features():
    try:
        text = subprocess.run([PDD, "reconstruct", "--help"], capture_output=True, text=True,
                              timeout=60).stdout
    except (OSError, subprocess.SubprocessError):
        text = ""
    return {"trim": "--trim" in text, "outliers": "--outliers" in text}


def run_pdd(meta, out, extra):
    stats = out.with_suffix(".json")
    command = [PDD, "reconstruct", meta["input"], "-o", out, "--quiet", "--stats", stats, *extra]
    for attempt in range(2):
        try:  # the binary this run executes (a rebuild replaces the file, not the running one)
            BINARIES.setdefault(PDD.stat().st_mtime, []).append(meta["name"])
        except OSError:
            pass
        for f in (out, stats):
            f.unlink(missing_ok=True)
        ok, seconds, mb, err = timed(command)
        if ok and out.exists():
            break
        if attempt == 0 and "time limit" not in err and "pdd: error:" not in err:
            print(f"  pdd failed ({last_line(err)}), retrying in 30 s", flush=True)
            time.sleep(30)
        else:
            break
    result = {"ok": ok and out.exists(), "seconds": seconds, "mb": mb,
              "command": " ".join(str(c) for c in command[1:] if c not in (out, stats))}

    if not result["ok"]:
        result["error"] = last_line(err)
        return result
    try:
        result["stats"] = json.loads(stats.read_text())
    except (OSError, ValueError):
        result["stats"] = {}
    return result


def run_trimmer(dense, value):
    """SurfaceTrimmer on PoissonRecon's run `dense` at a trim value: a result like dense's."""
    trimmed = pathlib.Path(str(dense["mesh"]).replace(".ply", f"_trim{value:g}.ply"))
    ok, seconds, mb, err = timed([ANCHORS / "SurfaceTrimmer", "--in", dense["mesh"], "--out",
                                  trimmed, "--trim", value, "--aRatio", "0.001"])
    trim = {"ok": ok and trimmed.exists(), "seconds": dense["seconds"] + seconds,
            "mb": max(dense["mb"], mb), "depth": dense["depth"], "mesh": trimmed, "trim": value}
    if not trim["ok"]:
        trim["error"] = last_line(err)
    return trim


def run_poissonrecon(meta, folder, depth, colours):
    dense = folder / f"poissonrecon_d{depth}.ply"
    command = [ANCHORS / "PoissonRecon", "--in", meta["peer_input"], "--out", dense,
               "--depth", depth, "--density"] + (["--colors"] if colours else [])
    ok, seconds, mb, err = timed(command)
    result = {"ok": ok and dense.exists(), "seconds": seconds, "mb": mb, "depth": depth,
              "mesh": dense}
    if not result["ok"]:
        result["error"] = last_line(err)
        return result, None
    extra = meta.get("peer_normals")
    if extra:
        result["seconds"] += extra["seconds"]
        result["mb"] = max(mb, extra["mb"])
    return result, run_trimmer(result, 7)


OPEN3D_SCRIPT = """
import sys, numpy as np, open3d as o3d
inp, depth, closed, trimmed, estimate = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5] == '1'
pc = o3d.io.read_point_cloud(inp)
if estimate:
    pc.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(18))
    pc.orient_normals_consistent_tangent_plane(18)
mesh, density = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pc, depth=depth)
if not pc.has_colors():
    mesh.vertex_colors = o3d.utility.Vector3dVector()
o3d.io.write_triangle_mesh(closed, mesh)
density = np.asarray(density)
mesh.remove_vertices_by_mask(density < np.quantile(density, 0.05))
o3d.io.write_triangle_mesh(trimmed, mesh)
"""


def run_open3d(meta, folder, depth):
    closed, trimmed = folder / f"open3d_d{depth}.ply", folder / f"open3d_d{depth}_trim.ply"
    estimate = not meta["has_normals"]
    ok, seconds, mb, err = timed([PY, "-c", OPEN3D_SCRIPT, meta["input"], depth, closed, trimmed,
                                  "1" if estimate else "0"])
    base = {"seconds": seconds, "mb": mb, "depth": depth}
    a = dict(base, ok=ok and closed.exists(), mesh=closed)
    b = dict(base, ok=ok and trimmed.exists(), mesh=trimmed)
    if not ok:
        a["error"] = b["error"] = last_line(err)
    return a, b


# ---------------------------------------------------------------------------------------------
# metrics

def union_find(n, edges):
    """Root label of each of n nodes, joined along the edges (m x 2), vectorized."""
    parent = np.arange(n)
    if len(edges) == 0:
        return parent
    a, b = edges[:, 0], edges[:, 1]
    while True:
        pa, pb = parent[a], parent[b]
        differ = pa != pb
        if not differ.any():
            return parent
        lo, hi = np.minimum(pa, pb)[differ], np.maximum(pa, pb)[differ]
        np.minimum.at(parent, hi, lo)
        while True:
            pp = parent[parent]
            if np.array_equal(pp, parent):
                break
            parent = pp


def min_angles(v, f):
    p0, p1, p2 = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    def angle(a, b, c):
        u, w = b - a, c - a
        nu, nw = np.linalg.norm(u, axis=1), np.linalg.norm(w, axis=1)
        cos = np.einsum("ij,ij->i", u, w) / np.maximum(nu * nw, 1e-300)
        return np.degrees(np.arccos(np.clip(cos, -1, 1)))
    return np.minimum(np.minimum(angle(p0, p1, p2), angle(p1, p2, p0)), angle(p2, p0, p1))


def read_mesh(path):
    mesh = o3d.io.read_triangle_mesh(str(path))
    v = np.asarray(mesh.vertices, dtype=np.float64)
    f = np.asarray(mesh.triangles, dtype=np.int64)
    colours = None
    try:
        _, types = read_ply_vertices(path) if str(path).endswith(".ply") else (None, {})
        if types and "red" in types:
            vert, _ = read_ply_vertices(path)
            colours = np.column_stack([vert["red"], vert["green"], vert["blue"]])
            if types["red"].startswith("f") and colours.max() <= 1.0:
                colours = colours * 255.0
            elif types["red"] == "u2":
                colours = colours / 257.0
            if len(colours) != len(v):
                colours = None
    except (ValueError, OSError, KeyError):
        colours = None
    return v, f, colours


def pdd_json(args):
    try:
        out = subprocess.run([PDD, *args, "--json"], capture_output=True, text=True, timeout=600)
        return json.loads(out.stdout) if out.returncode == 0 else None
    except (OSError, ValueError, subprocess.SubprocessError):
        return None


def points_to_surface(v_local, f, ref):
    """Mean distance of the reference points to the mesh, over the diagonal."""
    if len(f) == 0:
        return None
    # without the triangles of (nearly) zero area in float32: Debian's Open3D aborts on them
    # (an Eigen assertion in compute_distance)
    v32 = v_local.astype(np.float32)
    area = np.linalg.norm(np.cross(v32[f[:, 1]] - v32[f[:, 0]], v32[f[:, 2]] - v32[f[:, 0]]), axis=1)
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(v32),
                        o3d.core.Tensor(f[area > 1e-12 * ref["diagonal"] ** 2].astype(np.uint32)))
    d = scene.compute_distance(o3d.core.Tensor(ref["points"].astype(np.float32))).numpy()
    return float(np.mean(d) / ref["diagonal"])


def measure(path, ref, meta):
    """ref: the input's points without outliers, their tree, spacing, centre and diagonal."""
    v, f, colours = read_mesh(path)
    m = {"faces": int(len(f))}
    if len(f) == 0:
        return m
    v_local = v - ref["centre"]
    # area near the samples
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v_local),
                                     o3d.utility.Vector3iVector(f.astype(np.int32)))
    o3d.utility.random.seed(0)
    samples = np.asarray(mesh.sample_points_uniformly(SAMPLES).points)
    _, d2 = ref["nns"].knn_search(o3d.core.Tensor(samples), 1)
    distance = np.sqrt(d2.numpy()[:, 0])
    m["area_near"] = float(np.mean(distance <= 2 * ref["spacing"]))
    m["area_near3"] = float(np.mean(distance <= 3 * ref["spacing"]))
    m["points_to_surface"] = points_to_surface(v_local, f, ref)
    # topology
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    keys = edges[:, 0] * (len(v) + 1) + edges[:, 1]
    unique, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    boundary_key = counts[inverse] == 1
    bedges = edges[boundary_key]
    m["boundary_edges"] = int(len(bedges))
    m["non_manifold_edges"] = int(np.sum(counts > 2))
    if len(bedges):
        nodes, local = np.unique(bedges, return_inverse=True)
        labels = union_find(len(nodes), local.reshape(-1, 2))
        m["loops"] = int(len(np.unique(labels)))
    else:
        m["loops"] = 0
    used = np.unique(f)
    labels = union_find(len(v), edges)
    m["components"] = int(len(np.unique(labels[used])))
    m["closed"] = m["boundary_edges"] == 0 and m["non_manifold_edges"] == 0
    # angles, overall and at the cut
    angles = min_angles(v_local, f)
    m["mean_min_angle"] = float(np.mean(angles))
    m["below_20"] = float(np.mean(angles < 20))
    cut = np.zeros(len(f), dtype=bool)
    cut[np.arange(len(edges))[boundary_key] % len(f)] = True
    if cut.any():
        m["cut_faces"] = int(cut.sum())
        m["cut_mean_min_angle"] = float(np.mean(angles[cut]))
        m["cut_below_20"] = float(np.mean(angles[cut] < 20))
    # pdd quality: manifoldness, genus (its components agree with ours on vertex connectivity)
    q = pdd_json(["quality", str(path)])
    if q:
        m["manifold"] = bool(q["surface"]["manifold"])
        m["genus"] = q["surface"].get("genus")
        m["pdd_components"] = q["surface"].get("components")
    if meta.get("gt"):
        c = pdd_json(["compare", str(path), meta["gt"], "--samples", "100000"])
        if c:
            m["chamfer"] = c["chamfer_l1_relative"]
            m["hausdorff"] = c["hausdorff_relative"]
            m["out_to_gt"] = c["mean_a_to_b_relative"]
    # colours at the used vertices
    if colours is not None:
        m["colours"] = True
        at = used
        if meta["kind"] != "ramp" and "colours" not in ref:
            return m
        if meta["kind"] == "ramp":
            lo, hi = (np.array(b) for b in meta["ramp_box"])
            expected = ramp_colour(v[at], lo, hi)
        else:
            idx, _ = ref["nns_all"].knn_search(o3d.core.Tensor(v_local[at]), 1)
            expected = ref["colours"][idx.numpy()[:, 0]]
        err = np.abs(colours[at] - expected)
        m["colour_error"] = [float(e) for e in err.mean(0)]
        m["colour_error_mean"] = float(err.mean())
    else:
        m["colours"] = False
    return m


def reference(meta):
    v, _ = read_ply_vertices(meta["input"])
    p, _, c = cloud_arrays(v)
    keep = np.ones(len(p), dtype=bool)
    if meta.get("outliers"):
        keep = ~np.load(meta["outliers"])
    centre = (p[keep].min(0) + p[keep].max(0)) / 2
    local = p - centre
    pts = local[keep]
    nns = o3d.core.nns.NearestNeighborSearch(o3d.core.Tensor(pts))
    nns.knn_index()
    _, d2 = nns.knn_search(o3d.core.Tensor(pts), 2)
    spacing = float(np.mean(np.sqrt(d2.numpy()[:, 1])))
    ref = {"points": pts, "nns": nns, "spacing": spacing, "centre": centre,
           "diagonal": float(np.linalg.norm(pts.max(0) - pts.min(0))), "keep": keep}
    if c is not None:
        nns_all = o3d.core.nns.NearestNeighborSearch(o3d.core.Tensor(local))
        nns_all.knn_index()
        ref["nns_all"], ref["colours"] = nns_all, c
    return ref


def outlier_count(stats):
    """The number of points pdd removed as outliers, from its stats JSON: (count, key)."""
    found = []
    def walk(node, path):
        if isinstance(node, dict):
            for k, val in node.items():
                walk(val, path + [str(k)])
        elif isinstance(node, (int, float)) and not isinstance(node, bool):
            if any("outlier" in k.lower() for k in path):
                found.append((".".join(path), node))
    walk({k: v for k, v in stats.items() if k != "iterations"}, [])
    def rank(item):
        key = item[0].lower()
        return (0 if "removed" in key else 1 if "count" in key else 2,
                0 if float(item[1]).is_integer() else 1)
    found.sort(key=rank)
    if found and float(found[0][1]).is_integer():
        return int(found[0][1]), found[0][0]
    return None, None


MASK_SCRIPT = """
import sys, numpy as np
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[1])
import pdd
names = [n for n in dir(pdd) if 'outlier' in n.lower() and callable(getattr(pdd, n))]
cloud = pdd.read_points(sys.argv[2])
for name in names:
    fn = getattr(pdd, name)
    for args in ((cloud.points, cloud.normals), (cloud.points,), (cloud,)):
        try:
            r = fn(*args)
        except Exception:
            continue
        for cand in (r, getattr(r, 'mask', None), getattr(r, 'outliers', None),
                     r[0] if isinstance(r, tuple) else None):
            if cand is None:
                continue
            a = np.asarray(cand)
            n = len(cloud.points)
            if a.dtype == bool and a.shape == (n,):
                np.save(sys.argv[3], a); print(name); sys.exit(0)
            if a.ndim == 1 and np.issubdtype(a.dtype, np.integer) and (a.size == 0 or a.max() < n):
                m = np.zeros(n, bool); m[a] = True; np.save(sys.argv[3], m); print(name); sys.exit(0)
sys.exit(3)
"""


def drop_zero_normals(meta):
    """A copy of the input without its points whose normal is zero: (path, how many)."""
    v, _ = read_ply_vertices(meta["input"])
    p, n, c = cloud_arrays(v)
    keep = np.linalg.norm(n, axis=1) > 0
    path = pathlib.Path(meta["input"]).with_suffix(".nonzero.ply")
    if not path.exists():
        write_points_ply(path, p[keep], n[keep], None if c is None else c[keep], real="f8")
    return path, int((~keep).sum())


def pdd_outlier_mask(meta, folder):
    module = root / "build" / "python"
    if not any(module.glob("pdd*")):
        return None, None
    out = folder / "pdd_outlier_mask.npy"
    r = subprocess.run([PY, "-c", MASK_SCRIPT, str(module), meta["input"], str(out)],
                       capture_output=True, text=True, timeout=1800)
    if r.returncode != 0 or not out.exists():
        return None, None
    return np.load(out), r.stdout.strip()


# ---------------------------------------------------------------------------------------------
# report

def f1(x, scale=1.0, digits=1):
    return "-" if x is None else f"{x * scale:.{digits}f}"


def yes(x):
    return "-" if x is None else ("yes" if x else "no")


def row_cells(r, columns, pdd_seconds):
    m = r.get("metrics", {})
    out = []
    for c in columns:
        if c == "input":
            out.append(r["input"])
        elif c == "points":
            out.append(str(r["points"]))
        elif c == "run":
            out.append(r["run"])
        elif not r["ok"]:
            out.append("failed: " + r.get("error", "") if c == columns[3] else "")
        elif c == "faces":
            out.append(str(m.get("faces", "-")))
        elif c == "area":
            out.append(f1(m.get("area_near"), 100))
        elif c == "area3":
            out.append(f1(m.get("area_near3"), 100))
        elif c == "p2s":
            out.append(f1(m.get("points_to_surface"), 1e3, 3))
        elif c == "comp":
            out.append(str(m.get("components", "-")))
        elif c == "loops":
            out.append(str(m.get("loops", "-")))
        elif c == "closed":
            out.append(yes(m.get("closed")))
        elif c == "manifold":
            out.append(yes(m.get("manifold")))
        elif c == "angle":
            out.append(f1(m.get("mean_min_angle")))
        elif c == "b20":
            out.append(f1(m.get("below_20"), 100))
        elif c == "cut":
            out.append("-" if "cut_mean_min_angle" not in m else
                       f"{m['cut_mean_min_angle']:.1f} / {m['cut_below_20'] * 100:.1f}")
        elif c == "chamfer":
            out.append(f1(m.get("chamfer"), 1e3, 3))
        elif c == "hausdorff":
            out.append(f1(m.get("hausdorff"), 100, 2))
        elif c == "removed":
            out.append(r.get("removed_text", "-"))
        elif c == "false":
            out.append(r.get("false_text", "-"))
        elif c == "colours":
            out.append(yes(m.get("colours")))
        elif c == "cerr":
            e = m.get("colour_error")
            out.append("-" if e is None else
                       f"{m['colour_error_mean']:.2f} ({e[0]:.1f}, {e[1]:.1f}, {e[2]:.1f})")
        elif c == "time":
            out.append(f"{r['seconds']:.1f}")
        elif c == "xpdd":
            out.append("-" if not pdd_seconds else f"{r['seconds'] / pdd_seconds:.2f}")
        elif c == "mb":
            out.append(f"{r['mb']:.0f}")
    return out


TABLES = {
    "open": ("Open surfaces",
             "How to read: an open surface (`--trim`, SurfaceTrimmer, Open3D's density "
             "quantile) should keep >= 99 % of its area within 2 average spacings s of an input "
             "point (\"area near\") while its points-to-surface distance stays that of the closed "
             "run; a closed run's share shows how much surface it invents (unseen bases, "
             "holes). Samples spread at random (the virtual scans, the outlier and ramp "
             "variants) cap \"area near\" at 1 - exp(-pi) = 95.7 % even on a perfect surface "
             "(the mean nearest-neighbour distance of a Poisson process is half the "
             "density's inverse square root), hence the 3 s column (cap 99.9 %). Loops: boundary loops; \"cut\": mean min angle (deg) / % under 20 deg of "
             "the triangles with a boundary edge. Chamfer: against the ground truth (virtual "
             "scans only; a trimmed output loses the unseen base there). x pdd: time over pdd's "
             "closed run on the same input.",
             [("input", "input"), ("points", "points"), ("run", "run"), ("faces", "faces"),
              ("area", "area near (%)"), ("area3", "within 3 s (%)"),
              ("p2s", "points to surface (1e-3 diag)"), ("comp", "components"), ("loops", "loops"), ("closed", "closed"),
              ("manifold", "manifold"), ("angle", "mean min angle"), ("b20", "< 20 deg (%)"),
              ("cut", "cut: angle / < 20 (%)"), ("chamfer", "Chamfer vs GT (1e-3)"),
              ("time", "time s"), ("xpdd", "x pdd"), ("mb", "peak MB")]),
    "outliers": ("Outliers",
                 "How to read: the bunny and the fandisk are one closed component each, so a "
                 "closed output should have components = 1 and a small Hausdorff distance to the "
                 "ground truth (blobs around outliers show up in both); removed: points pdd "
                 "dropped as outliers (true outliers in brackets); not outliers: removed points "
                 "that were true samples (exact from the Python module's mask, or >= removed - "
                 "true, a lower bound). Points to surface uses the true samples only.",
                 [("input", "input"), ("points", "points"), ("run", "run"), ("comp", "components"),
                  ("closed", "closed"), ("removed", "removed (true)"), ("false", "not outliers"),
                  ("p2s", "points to surface (1e-3 diag)"), ("chamfer", "Chamfer vs GT (1e-3)"),
                  ("hausdorff", "Hausdorff vs GT (%)"), ("area", "area near (%)"),
                  ("faces", "faces"), ("time", "time s"), ("xpdd", "x pdd"), ("mb", "peak MB")]),
    "colours": ("Colours",
                "How to read: mean absolute colour error (0-255, mean of the three channels, then "
                "red, green, blue) at the output's vertices, against the analytic field for "
                "bunny_ramp (the input's own rounding is <= 0.5) and against the nearest input "
                "point's colour for b9_training; \"-\" where the output has no colours.",
                [("input", "input"), ("points", "points"), ("run", "run"),
                 ("colours", "colours"), ("cerr", "colour error: mean (R, G, B)"),
                 ("faces", "faces"), ("area", "area near (%)"),
                 ("p2s", "points to surface (1e-3 diag)"), ("time", "time s"),
                 ("xpdd", "x pdd"), ("mb", "peak MB")]),
}


def commit_now():
    return subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"],
                          capture_output=True, text=True).stdout.strip()


def report(rows, metas, features, notes, args, elapsed):
    commit = commit_now()
    dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--", "src",
                            "include", "apps", "python"], capture_output=True, text=True).stdout
    uname = subprocess.run(["uname", "-a"], capture_output=True, text=True).stdout.strip()
    lines = ["# Real scans: open surfaces, outliers, colours (issue 16)", "",
             f"`bench/real_scans.py` ({' '.join(sys.argv[1:]) or 'all inputs'}), "
             f"{datetime.datetime.now().strftime('%Y-%m-%d %H:%M')}, pdd {commit}"
             f"{' with uncommitted changes to the sources' if dirty.strip() else ''}, "
             f"{os.cpu_count()} cores (`uname -a`: {uname}), whole run {elapsed / 60:.1f} min.", "",
             f"pdd features found in `reconstruct --help`: --trim "
             f"{'yes' if features['trim'] else 'no'}, --outliers "
             f"{'yes' if features['outliers'] else 'no'}; colours in the output: "
             f"{'yes' if any(r['run'].startswith('pdd') and r.get('metrics', {}).get('colours') for r in rows) else 'no'}.",
             "", f"1-minute load average before the timed runs: min {min(LOADS, default=0):.1f}, "
             f"median {float(np.median(LOADS)) if LOADS else 0:.1f}, max {max(LOADS, default=0):.1f} "
             "(on 2 cores, anything above ~0.5 is other work, which slows every run and "
             "PoissonRecon's spinning OpenMP threads most).",
             "", "Inputs (spacing: mean distance to the nearest other input point; diagonal of "
             "the bounding box of the points without outliers):", "",
             "| input | points | normals | colours | spacing (1e-3 diag) | source |",
             "| --- | --- | --- | --- | --- | --- |"]
    for m in metas.values():
        lines.append(f"| {m['name']} | {m['points']} | {yes(m['has_normals'])} | "
                     f"{yes(m['has_colours'])} | {m['spacing'] / m['diagonal'] * 1e3:.2f} | "
                     f"{m['source']} |")
    pdd_time = {}
    for r in rows:  # pdd's closed run (the first row of each input, when it worked)
        if r["run"].startswith("pdd") and "--" not in r["run"] and r["ok"]:
            pdd_time.setdefault(r["input"], r["seconds"])
    for topic, (title, how, columns) in TABLES.items():
        selected = [r for r in rows if topic in INPUTS[r["input"]][0]]
        if not selected:
            continue
        keys = [c for c, _ in columns]
        lines += ["", f"## {title}", "", how, "",
                  "| " + " | ".join(h for _, h in columns) + " |",
                  "|" + " --- |" * len(columns)]
        for r in selected:
            lines.append("| " + " | ".join(row_cells(r, keys, pdd_time.get(r["input"]))) + " |")
    if notes:
        lines += ["", "Notes:", ""] + [f"- {n}" for n in notes]
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="", help="regex on the input names")
    parser.add_argument("--work", default="/tmp/pdd_real_scans", help="cache and output folder")
    parser.add_argument("--skip-peers", action="store_true")
    parser.add_argument("--outliers-off", action="store_true",
                        help="also run pdd --outliers 0 on the outlier variants (slow: "
                             "minutes each)")
    parser.add_argument("--time-limit", type=float, default=900,
                        help="seconds after which a run is stopped and reported as failed")
    parser.add_argument("--output", default=str(root / "bench" / "results" / "real_scans.md"))
    args = parser.parse_args()
    TIME_LIMIT[0] = args.time_limit
    work = pathlib.Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    features = pdd_features()
    notes = []
    if not features["trim"]:
        notes.append("`pdd reconstruct --help` has no `--trim`: the open pdd runs were skipped.")
    if not features["outliers"]:
        notes.append("`pdd reconstruct --help` has no `--outliers`: pdd ran with whatever it "
                     "does by default.")
    rows, metas = [], {}
    notes_zero, outlier_notes, trimmer_notes = [], set(), []
    for name, (topics, kind) in INPUTS.items():
        if not re.search(args.only, name):
            continue
        print(f"== {name}", flush=True)
        meta = prepare(name, kind, work)
        ref = reference(meta)
        meta["spacing"], meta["diagonal"] = ref["spacing"], ref["diagonal"]
        metas[name] = meta
        folder = work / "out" / name
        folder.mkdir(parents=True, exist_ok=True)
        true_outliers = int((~ref["keep"]).sum())

        def add(run, result, mesh):
            row = {"input": name, "points": meta["points"], "run": run, "ok": result["ok"],
                   "seconds": result["seconds"], "mb": result["mb"]}
            if not result["ok"]:
                row["error"] = result.get("error", "failed")
            else:
                try:
                    row["metrics"] = measure(mesh, ref, meta)
                except Exception as e:  # a mesh the metrics cannot read
                    row["metrics"] = {}
                    row["error"] = f"metrics: {e}"
            for key in ("removed_text", "false_text"):
                if key in result:
                    row[key] = result[key]
            rows.append(row)
            m = row.get("metrics", {})
            print(f"  {run}: {'ok' if row['ok'] else 'FAILED ' + row.get('error', '')} "
                  f"{row['seconds']:.1f} s {row['mb']:.0f} MB faces {m.get('faces')} "
                  f"area {f1(m.get('area_near'), 100)} % p2s {f1(m.get('points_to_surface'), 1e3, 3)} "
                  f"comp {m.get('components')} loops {m.get('loops')}"
                  + (f" colour {m['colour_error_mean']:.2f}" if "colour_error_mean" in m else ""),
                  flush=True)
            return row

        # pdd
        pdd_runs = [("pdd", [])]
        if features["trim"]:
            pdd_runs.append(("pdd --trim 2", ["--trim", "2"]))
        if "outliers" in topics and features["outliers"] and args.outliers_off:
            pdd_runs.append(("pdd --outliers 0", ["--outliers", "0"]))
        pdd_faces = None
        mask = None
        for run, extra in pdd_runs:
            out = folder / (re.sub(r"[^a-z0-9]+", "_", run).strip("_") + ".ply")
            result = run_pdd(meta, out, extra)
            if not result["ok"] and re.search(r"normal .* zero length", result.get("error", "")):
                # a real scan with a few zero normals (hippo2): once more without those points
                cleaned, dropped = drop_zero_normals(meta)
                result = run_pdd(dict(meta, input=str(cleaned)), out, extra)
                run += f" (without its {dropped} zero normals)"
                if not any(n.startswith(name + ":") for n in notes_zero):
                    notes_zero.append(f"{name}: pdd refuses the input as CGAL ships it "
                                      f"(\"{meta['input']}: point ...: the normal (0, 0, 0) has "
                                      f"zero length\"); its rows are on a copy without those "
                                      f"{dropped} points (the peers read the original).")
            if result["ok"] and "outliers" in topics:
                removed, key = outlier_count(result["stats"])
                if removed is None:
                    result["removed_text"] = f"? ({true_outliers})"
                    result["false_text"] = "?"
                    outlier_notes.add("no count of removed outliers in pdd's stats JSON")
                else:
                    result["removed_text"] = f"{removed} ({true_outliers})"
                    outlier_notes.add(f"pdd's removed outliers: stats key `{key}`")
                    if mask is None and "--outliers" not in extra:
                        mask, fn = pdd_outlier_mask(meta, folder)
                    if ("--outliers" not in extra and mask is not None
                            and len(mask) == len(ref["keep"]) and int(mask.sum()) == removed):
                        result["false_text"] = str(int(np.sum(mask & ref["keep"])))
                        outlier_notes.add(f"which points: the Python module's `pdd.{fn}` "
                                          "(its count matches the stats')")
                    else:
                        result["false_text"] = f">= {max(0, removed - true_outliers)}"
                        outlier_notes.add("\">=\": no mask from the Python module (or it "
                                          "disagreed with the count), removed - true outliers")
            row = add(run, result, out)
            if run == "pdd" and row["ok"]:
                pdd_faces = row.get("metrics", {}).get("faces")
        if args.skip_peers:
            continue
        # PoissonRecon at the depth nearest pdd's size, then Open3D at that depth
        colours = meta["has_colours"]
        tried = {}
        depth = 8
        while depth not in tried and 6 <= depth <= 10:
            tried[depth] = run_poissonrecon(meta, folder, depth, colours)
            dense = tried[depth][0]
            if not dense["ok"] or not pdd_faces:
                break
            faces = len(np.asarray(o3d.io.read_triangle_mesh(str(dense["mesh"])).triangles))
            dense["faces"] = faces
            below = tried.get(depth - 1, (None,))[0]
            if below and below.get("faces") and faces < 1.2 * below["faces"]:
                del tried[depth]  # saturated: the samples, not the depth, limit the octree
                depth -= 1
                break
            gap = np.log(pdd_faces / max(faces, 1))
            step = 1 if gap > np.log(2) else -1 if gap < -np.log(2) else 0
            if step == 0:
                break
            if depth + step in tried or not 6 <= depth + step <= 10:
                break
            depth += step
        ok_depths = [d for d, (dense, _) in tried.items() if dense["ok"] and "faces" in dense]
        if ok_depths and pdd_faces:
            depth = min(ok_depths, key=lambda d: abs(np.log(pdd_faces / max(tried[d][0]["faces"], 1))))
        saturated = depth + 1 not in tried and pdd_faces and tried[depth][0].get("faces") and \
            pdd_faces > 2 * tried[depth][0]["faces"] and depth < 10
        dense, trim = tried[depth]
        prefix = "PoissonRecon" + (" (Open3D normals)" if not meta["has_normals"] else "")
        dense_row = add(f"{prefix} d{depth}", dense, dense.get("mesh"))
        if trim is not None:
            trim_row = add(f"{prefix} d{depth} + SurfaceTrimmer 7", trim, trim.get("mesh"))
            limit = dense_row.get("metrics", {}).get("points_to_surface")
            p2s = trim_row.get("metrics", {}).get("points_to_surface")
            if dense_row["ok"] and limit and (p2s is None or p2s > TRIM_TOLERANCE * limit):
                # 7 cut into the scan: the highest value that does not
                tried_values = []
                for value in (6.5, 6, 5.5, 5, 4.5, 4):
                    trim = run_trimmer(dense, value)
                    if not trim["ok"]:
                        continue
                    v, f, _ = read_mesh(trim["mesh"])
                    p2s = points_to_surface(v - ref["centre"], f, ref)
                    tried_values.append(f"{value:g}: {f1(p2s, 1e3, 3)}")
                    if p2s is not None and p2s <= TRIM_TOLERANCE * limit:
                        break
                if trim["ok"]:
                    add(f"{prefix} d{depth} + SurfaceTrimmer {trim['trim']:g} (lowered)", trim,
                        trim["mesh"])
                p2s_7 = trim_row.get("metrics", {}).get("points_to_surface")
                trimmer_notes.append(f"{name} ({f1(limit, 1e3, 3)} untrimmed; 7: "
                                     f"{'nothing left' if p2s_7 is None else f1(p2s_7, 1e3, 3)}, "
                                     + ", ".join(tried_values) + ")")
        if len(tried) > 1:
            notes.append(f"{name}: PoissonRecon depths tried "
                         + ", ".join(f"{d} ({t[0].get('faces', 'failed')} faces)"
                                     for d, t in sorted(tried.items()))
                         + f" against pdd's {pdd_faces}; the peers ran at {depth}"
                         + (" (one more level adds under 20 %: the octree is limited by the "
                            "samples)" if saturated else "") + ".")
        closed, trimmed = run_open3d(meta, folder, depth)
        prefix = "Open3D Poisson" + (" (estimated normals)" if not meta["has_normals"] else "")
        add(f"{prefix} d{depth}", closed, closed.get("mesh"))
        add(f"{prefix} d{depth}, density >= 5 % quantile", trimmed, trimmed.get("mesh"))

    if len(BINARIES) > 1:
        notes.append("build/pdd was rebuilt during this run: "
                     + "; ".join(f"binary of {datetime.datetime.fromtimestamp(t):%H:%M:%S} for "
                                 + ", ".join(dict.fromkeys(names))
                                 for t, names in sorted(BINARIES.items()))
                     + f" (the commit above is the one at the end, {commit_now()}).")
    notes += notes_zero
    if outlier_notes:
        notes.append("Outliers: " + "; ".join(sorted(outlier_notes)) + ".")
    if trimmer_notes:
        notes.append("SurfaceTrimmer --trim 7 (the anchors' recipe) cut into the scanned "
                     "surface or left nothing on these inputs, so a row with the highest value "
                     f"of 6.5, 6, ..., 4 whose points-to-surface distance is within "
                     f"{TRIM_TOLERANCE}x the untrimmed mesh's follows (\"lowered\"); points to "
                     "surface (1e-3 diag) by value: " + "; ".join(trimmer_notes) + ".")
    if not args.skip_peers and any(not m["has_normals"] for m in metas.values()):
        notes.append("Inputs without normals: both peers use Open3D's estimate_normals (18 "
                     "neighbours) + orient_normals_consistent_tangent_plane (18); PoissonRecon's "
                     "time includes that step, Open3D's run does it itself; pdd estimates its own.")
    if not args.skip_peers:
        notes.append("Open3D's times include starting Python and importing open3d (about 1 s); "
                     "its two rows are one run. PoissonRecon + SurfaceTrimmer: the sum of both.")
    elapsed = time.monotonic() - started
    for r in rows:
        r.pop("mesh", None)
    (work / "results.json").write_text(json.dumps(
        {"rows": rows, "inputs": metas, "features": features, "notes": notes}, indent=1,
        default=str))
    text = report(rows, metas, features, notes, args, elapsed)
    print(text)
    pathlib.Path(args.output).write_text(text)


if __name__ == "__main__":
    sys.exit(main())
