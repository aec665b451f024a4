#!/usr/bin/env python3
"""How soon a run stops when asked to (issue 20).

For each input (default: the virtual scans of bench/scale.sh, build/scale_inputs/
fandisk_large_{100000,1000000}.ply, and ../shared/data/points/bunny_clean.ply):

1. the library: pdd.reconstruct with a progress callback that only records when it
   is called; the longest time between two calls bounds how long a callback's False
   (or Ctrl-C in Python) waits to be heard. Reported overall and per stage.
2. the command line: `pdd reconstruct` sent SIGTERM at a few points of the run;
   the time from the signal to the exit, the exit code (143) and whether any
   output file was left (signals later than 200 s into the run are skipped).

    bash scripts/build.sh && /usr/bin/python3 bench/cancellation.py [INPUT.ply ...]

Prints a Markdown table and writes it to bench/results/cancellation.md.
"""

import os
import pathlib
import signal
import subprocess
import sys
import tempfile
import time

root = pathlib.Path(__file__).resolve().parent.parent
build = root / "build"
sys.path.insert(0, str(build / "python"))
import pdd  # noqa: E402

inputs = [pathlib.Path(a) for a in sys.argv[1:]] or [
    root.parent / "shared" / "data" / "points" / "bunny_clean.ply",
    build / "scale_inputs" / "fandisk_large_100000.ply",
    build / "scale_inputs" / "fandisk_large_1000000.ply",
]


def library_gaps(path):
    cloud = pdd.read_points(str(path))
    calls = []

    def record(p):
        calls.append((time.monotonic(), p.stage))

    start = time.monotonic()
    pdd.reconstruct(cloud, progress=record)
    total = time.monotonic() - start
    gaps = {}
    previous = (start, "start")
    for now, stage in calls:
        gaps.setdefault(previous[1], []).append(now - previous[0])
        previous = (now, stage)
    longest = max((max(v), k) for k, v in gaps.items())
    return total, len(calls), longest, {k: max(v) for k, v in gaps.items()}


def cli_signal(path, after, scratch):
    out = pathlib.Path(scratch) / "out.ply"
    stats = pathlib.Path(scratch) / "stats.json"
    child = subprocess.Popen([str(build / "pdd"), "reconstruct", str(path), "-o", str(out),
                              "--stats", str(stats), "--quiet"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(after)
    if child.poll() is not None:
        return None
    sent = time.monotonic()
    child.send_signal(signal.SIGTERM)
    code = child.wait()
    latency = time.monotonic() - sent
    left = sorted(os.listdir(scratch))
    for name in left:
        os.remove(pathlib.Path(scratch) / name)
    return latency, code, left


rows = []
for path in inputs:
    if not path.exists():
        print(f"skipped {path}: not there (bench/scale.sh makes the virtual scans)")
        continue
    total, calls, (longest, stage), per_stage = library_gaps(path)
    stages = ", ".join(f"{k} {v:.2f}" for k, v in sorted(per_stage.items(), key=lambda kv: -kv[1])[:4])
    signals = []
    with tempfile.TemporaryDirectory() as scratch:
        for fraction in (0.1, 0.4, 0.7, 0.9):
            if fraction * total > 200:
                continue  # a 1M-point run: the first two points only
            r = cli_signal(path, fraction * total, scratch)
            if r:
                signals.append(f"{fraction:.0%}: {r[0]:.2f} s, exit {r[1]}, "
                               f"{'no file left' if not r[2] else 'left ' + ' '.join(r[2])}")
    rows.append((path.stem, f"{total:.1f}", str(calls), f"{longest:.2f} ({stage})", stages,
                 "; ".join(signals)))
    print(rows[-1], flush=True)

header = ("| input | run (s) | callback calls | longest gap, s (after stage) | longest per stage, s "
          "| SIGTERM at a fraction of the run: seconds to exit |\n| --- | --- | --- | --- | --- | --- |\n")
table = header + "".join("| " + " | ".join(r) + " |\n" for r in rows)
commit = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"],
                        capture_output=True, text=True).stdout.strip()
text = (f"# Cancellation latency (bench/cancellation.py, commit {commit}, "
        f"{os.cpu_count()} cores)\n\n{table}")
print(text)
(root / "bench" / "results" / "cancellation.md").write_text(text)
