#!/usr/bin/env python3
"""The cost of the Python module over the command line (issue 18).

For every input of ../shared/data/points (*.ply), the same reconstruction (default
options, seed 0) through `pdd reconstruct` and through `pdd.reconstruct` in a fresh
Debian python3, in alternation, ROUNDS times each: wall time and peak memory of each
process (os.wait4), their ratios, and whether both wrote the same mesh. Then the time
to convert a 1M-point array into the library and back.

    bash scripts/build.sh && /usr/bin/python3 bench/python_overhead.py [ROUNDS] [--only REGEX]
        [--input PATH ...]

--input takes other inputs instead (e.g. bench/scale.sh's virtual scans in
build/scale_inputs/), and writes bench/results/python_overhead_inputs.md instead.
Prints a Markdown table and writes it to bench/results/python_overhead.md.
"""

import os
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile
import time

root = pathlib.Path(__file__).resolve().parent.parent
build = root / "build"
data = root.parent / "shared" / "data" / "points"
args = sys.argv[1:]
only = None
if "--only" in args:
    i = args.index("--only")
    only = re.compile(args[i + 1])
    del args[i:i + 2]
given = []
while "--input" in args:
    i = args.index("--input")
    given.append(pathlib.Path(args[i + 1]))
    del args[i:i + 2]
rounds = int(args[0]) if args else 3

PYTHON_RUN = """
import sys, pdd
cloud = pdd.read_points(sys.argv[1])
pdd.write_mesh(sys.argv[2], pdd.reconstruct(cloud, seed=0))
"""


def run(command, env=None):
    """Wall seconds and peak resident memory (MB) of one process.

    The peak comes from /usr/bin/time, not from this process's wait4: Linux carries a
    process's maximum RSS across exec, so a direct child forked from this Python would
    report at least this Python's own RSS (19 MB for `pdd --version`, which holds 9 MB)."""
    with tempfile.NamedTemporaryFile("r") as peak:
        start = time.monotonic()
        done = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", peak.name, *map(str, command)],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        seconds = time.monotonic() - start
        if done.returncode != 0:
            sys.exit(f"failed: {' '.join(map(str, command))}: {done.stderr.decode()}")
        return seconds, int(peak.read().split()[-1]) / 1024


def main():
    env = dict(os.environ, PYTHONPATH=str(build / "python"))
    inputs = given or sorted(p for p in data.glob("*.ply") if not only or only.search(p.stem))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for path in inputs:
            cli_out, py_out = pathlib.Path(tmp, "cli.ply"), pathlib.Path(tmp, "py.ply")
            cli, py = [], []
            for _ in range(rounds):
                cli.append(run([build / "pdd", "reconstruct", path, "-o", cli_out, "--quiet",
                                "--seed", "0"]))
                py.append(run(["/usr/bin/python3", "-c", PYTHON_RUN, path, py_out], env))
            same = cli_out.read_bytes() == py_out.read_bytes()
            if not same:
                print(f"{path.stem}: the two meshes differ", file=sys.stderr)
            t_cli = statistics.median(s for s, _ in cli)
            t_py = statistics.median(s for s, _ in py)
            m_cli = max(m for _, m in cli)
            m_py = max(m for _, m in py)
            rows.append((path.stem, t_cli, t_py, m_cli, m_py, same))
            print(f"{path.stem}: {t_cli:.2f} s / {t_py:.2f} s, {m_cli:.0f} / {m_py:.0f} MB, "
                  f"same mesh {same}", flush=True)

    # The fixed cost of a Python process: the interpreter, numpy and the module, against the
    # command line's own start-up (both do nothing else): seconds and MB.
    start_py = [run(["/usr/bin/python3", "-c", "import pdd"], env) for _ in range(5)]
    start_cli = [run([build / "pdd", "--version"]) for _ in range(5)]
    fixed_py = statistics.median(m for _, m in start_py)
    fixed_cli = statistics.median(m for _, m in start_cli)
    fixed = fixed_py - fixed_cli
    fixed_s = statistics.median(s for s, _ in start_py) - statistics.median(s for s, _ in start_cli)

    sys.path.insert(0, str(build / "python"))
    import numpy as np
    import pdd

    points = np.random.default_rng(0).random((1_000_000, 3))
    conversions = []
    for array in (points, points.astype(np.float32), np.asfortranarray(points)):
        best = min(timed(lambda: pdd._pdd.convert_points(array)) for _ in range(5))
        conversions.append((str(array.dtype) + (" F-order" if array.flags.f_contiguous else ""),
                            best))

    lines = [
        f"Python module overhead ({rounds} alternating rounds per input, medians; peak = "
        "max RSS of the process)",
        "",
        f"A Python process costs {fixed:.0f} MB and {fixed_s:.2f} s more than the command line "
        f"before any work (`python3 -c 'import pdd'`: {fixed_py:.0f} MB, `pdd --version`: "
        f"{fixed_cli:.0f} MB); the columns \"without the fixed cost\" take them out.",
        "",
        "| input | CLI s | Python s | time ratio | without the fixed cost | CLI MB | Python MB | "
        "memory ratio | without the fixed cost | same mesh |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for name, t_cli, t_py, m_cli, m_py, same in rows:
        lines.append(f"| {name} | {t_cli:.2f} | {t_py:.2f} | {t_py / t_cli:.3f} | "
                     f"{(t_py - fixed_s) / t_cli:.3f} | {m_cli:.0f} | {m_py:.0f} | "
                     f"{m_py / m_cli:.3f} | {(m_py - fixed) / m_cli:.3f} | "
                     f"{'yes' if same else 'NO'} |")
    if rows:
        t_cli, t_py = sum(r[1] for r in rows), sum(r[2] for r in rows)
        lines.append(f"| **total** | {t_cli:.1f} | {t_py:.1f} | {t_py / t_cli:.3f} | "
                     f"{(t_py - len(rows) * fixed_s) / t_cli:.3f} | | | "
                     f"{statistics.mean(r[4] / r[3] for r in rows):.3f} (mean) | "
                     f"{statistics.mean((r[4] - fixed) / r[3] for r in rows):.3f} (mean) | |")
    lines += ["", "1M points into the library and back (best of 5):", ""]
    lines += [f"- {name}: {seconds * 1000:.1f} ms" for name, seconds in conversions]
    table = "\n".join(lines) + "\n"
    print(table)
    name = "python_overhead_inputs.md" if given else "python_overhead.md"
    (root / "bench" / "results" / name).write_text(table)


def timed(function):
    start = time.perf_counter()
    function()
    return time.perf_counter() - start


if __name__ == "__main__":
    main()
