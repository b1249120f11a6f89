#!/usr/bin/env python3
# Material-switch cost (issue 14, item 6): load, first frame, frame time and peak RSS of the alternating vs one-material quad grid.
"""Usage: scripts/bench-grid.py [options] LABEL=SOFTRASTER [LABEL=SOFTRASTER ...]

For each size (--sizes, triangles) and each grid (alternating two textured materials, one
material; written by scripts/make-grid.py into --grid-dir if missing) runs every binary
--runs times, interleaved (binary A, binary B, A, B, ...), and prints the medians as a
Markdown table:
  load s        `softraster render`: from the start to its "<model>: N triangles" line on stderr
                (printed right after the model is loaded and split into draws)
  load+render s `softraster render`: the whole run (load, clear + first frame, 800x600 PPM write)
  frame ms      `softraster bench --frames F --warmup 1`: ms_per_frame_median
  peak RSS MiB  `/usr/bin/time -v softraster render`: Maximum resident set size
Defaults: 800x600, 1 thread, Phong, bilinear (the commands' defaults). Extra flags after `--`
go to both commands. A run over --timeout seconds is killed and reported as "> T s".
Python 3 standard library only.
"""
import argparse
import json
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def grid_quads(triangles):
    n = 1
    while 2 * n * n < triangles:
        n += 1
    return n


def ensure_grid(grid_dir, triangles, materials):
    n = grid_quads(triangles)
    path = os.path.join(grid_dir, "grid_%s_%d.obj" % (materials, n))
    if not os.path.exists(path):
        subprocess.run([sys.executable, os.path.join(HERE, "make-grid.py"), grid_dir, "--quads", str(n),
                        "--materials", materials], check=True, stdout=subprocess.DEVNULL)
    return path, 2 * n * n


def run_render(binary, obj, extra, timeout, out_dir):
    """(load s, total s, peak RSS MiB) of one `render`, or None on timeout."""
    cmd = ["/usr/bin/time", "-v", binary, "render", "--obj", obj, "--out", os.path.join(out_dir, "grid.ppm")] + extra
    t0 = time.monotonic()
    # Its own process group, so that a timeout ends softraster too, not only /usr/bin/time.
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True)
    watchdog = threading.Timer(timeout, lambda: os.killpg(proc.pid, signal.SIGKILL))
    watchdog.start()
    loaded, rss, lines = None, None, []
    for line in proc.stderr:
        lines.append(line)
        if loaded is None and re.search(r": \d+ triangles", line):
            loaded = time.monotonic() - t0
        m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", line)
        if m:
            rss = int(m.group(1)) / 1024.0
    proc.wait()
    watchdog.cancel()
    if time.monotonic() - t0 >= timeout:
        return None
    total = time.monotonic() - t0
    if proc.returncode != 0 or loaded is None or rss is None:
        sys.exit("bench-grid: %s failed:\n%s" % (" ".join(cmd), "".join(lines[-10:])))
    return loaded, total, rss


def run_bench(binary, obj, extra, frames, timeout):
    cmd = [binary, "bench", "--obj", obj, "--quiet", "--frames", str(frames), "--warmup", "1"] + extra
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None
    if p.returncode != 0:
        sys.exit("bench-grid: %s failed:\n%s" % (" ".join(cmd), p.stderr[-2000:]))
    return json.loads(p.stdout.strip().splitlines()[-1])["ms_per_frame_median"]


def main(argv):
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binaries", nargs="+", metavar="LABEL=SOFTRASTER")
    ap.add_argument("--sizes", default="100000,1000000,4000000", help="triangle counts (comma separated)")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--frames", type=int, default=10, help="bench frames per run")
    ap.add_argument("--grid-dir", default=os.path.join(tempfile.gettempdir(), "softraster-grids"))
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per command")
    ap.add_argument("--skip", action="append", default=[],
                    help="LABEL:alternate|one:SIZE combinations not to run (repeatable)")
    a = ap.parse_args(argv)
    binaries = [b.split("=", 1) for b in a.binaries]
    if any(len(b) != 2 for b in binaries):
        ap.error("binaries are given as LABEL=PATH")
    os.makedirs(a.grid_dir, exist_ok=True)

    rows = []
    with tempfile.TemporaryDirectory() as out_dir:
        for size in [int(s) for s in a.sizes.split(",")]:
            for materials in ("alternate", "one"):
                obj, triangles = ensure_grid(a.grid_dir, size, materials)
                results = {label: {"load": [], "total": [], "rss": [], "frame": []} for label, _ in binaries}
                timed_out = set()
                for run in range(a.runs):
                    for label, binary in binaries:
                        if "%s:%s:%d" % (label, materials, size) in a.skip or label in timed_out:
                            continue
                        r = run_render(binary, obj, extra, a.timeout, out_dir)
                        f = run_bench(binary, obj, extra, a.frames, a.timeout) if r else None
                        if r is None or f is None:
                            timed_out.add(label)
                            continue
                        res = results[label]
                        res["load"].append(r[0])
                        res["total"].append(r[1])
                        res["rss"].append(r[2])
                        res["frame"].append(f)
                        print("# %s %s %d run %d: load %.2f s, load+render %.2f s, frame %.1f ms, RSS %.0f MiB"
                              % (label, materials, triangles, run + 1, r[0], r[1], f, r[2]), file=sys.stderr)
                for label, _ in binaries:
                    res = results[label]
                    if label in timed_out:
                        cells = ["> %.0f s" % a.timeout] * 4
                    elif not res["load"]:
                        cells = ["not run"] * 4
                    else:
                        med = {k: statistics.median(v) for k, v in res.items()}
                        cells = ["%.2f" % med["load"], "%.2f" % med["total"], "%.1f" % med["frame"],
                                 "%.0f" % med["rss"]]
                    rows.append([label, "{:,}".format(triangles), materials] + cells)

    head = ["build", "triangles", "materials", "load s", "load+render s", "frame ms", "peak RSS MiB"]
    print("| " + " | ".join(head) + " |")
    print("|" + "|".join("---" if i < 3 else "---:" for i in range(len(head))) + "|")
    for r in rows:
        print("| " + " | ".join(r) + " |")
    print("\nmedian of %d runs; `softraster render` / `bench --frames %d --warmup 1`%s" %
          (a.runs, a.frames, (" " + " ".join(extra)) if extra else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
