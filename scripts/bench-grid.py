#!/usr/bin/env python3
# Material-switch cost: load, first frame, frame time and peak RSS of the alternating vs one-material quad grid.
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
--svg FILE also draws the cost per triangle (load, frame time, peak RSS) against the triangle
count, one line per build and grid: flat lines are linear cost. Python 3 standard library only.
"""
import argparse
import json
import math
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


def write_svg(path, series):
    """series: {(label, materials): [(triangles, load s, frame ms, rss MiB), ...]} -> three panels."""
    panels = [("load, microseconds per triangle", lambda t, r: r[1] * 1e6 / t),
              ("frame, nanoseconds per triangle", lambda t, r: r[2] * 1e6 / t),
              ("peak RSS, bytes per triangle", lambda t, r: r[3] * 1048576.0 / t)]
    colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"]
    pw, ph, m = 300, 220, 50
    width, height = len(panels) * (pw + m) + m, ph + 2 * m + 20 * (len(series) + 1)
    xs = sorted({row[0] for rows in series.values() for row in rows})
    if not xs:
        return
    lx0, lx1 = math.log10(xs[0]), math.log10(xs[-1])
    lx1 = lx1 if lx1 > lx0 else lx0 + 1.0
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="11">'
           % (width, height), '<rect width="100%" height="100%" fill="white"/>']
    for i, (title, f) in enumerate(panels):
        x0, y0 = m + i * (pw + m), m
        values = [f(row[0], row) for rows in series.values() for row in rows]
        top = max(values) * 1.15 if values and max(values) > 0 else 1.0
        out.append('<rect x="%d" y="%d" width="%d" height="%d" fill="none" stroke="#888"/>' % (x0, y0, pw, ph))
        out.append('<text x="%d" y="%d">%s</text>' % (x0, y0 - 8, title))
        for k in range(5):
            v = top * k / 4
            y = y0 + ph - ph * k / 4
            out.append('<text x="%d" y="%.1f" text-anchor="end">%.3g</text>' % (x0 - 4, y + 4, v))
        for x in xs:
            px = x0 + pw * (math.log10(x) - lx0) / (lx1 - lx0)
            out.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>' % (px, y0 + ph + 14, "{:,}".format(x)))
        for c, (key, rows) in enumerate(sorted(series.items())):
            pts = ["%.1f,%.1f" % (x0 + pw * (math.log10(row[0]) - lx0) / (lx1 - lx0),
                                  y0 + ph - ph * f(row[0], row) / top) for row in sorted(rows)]
            out.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>'
                       % (colours[c % len(colours)], " ".join(pts)))
    for c, key in enumerate(sorted(series)):
        y = m + ph + 40 + 20 * c
        out.append('<rect x="%d" y="%d" width="14" height="4" fill="%s"/>' % (m, y - 4, colours[c % len(colours)]))
        out.append('<text x="%d" y="%d">%s, %s</text>' % (m + 20, y, key[0], "alternating materials"
                                                           if key[1] == "alternate" else "one material"))
    out.append('<text x="%d" y="%d">x: triangles (log axis); 800x600, 1 thread, medians</text>'
               % (m, m + ph + 40 + 20 * len(series)))
    out.append("</svg>")
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")


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
    ap.add_argument("--svg", help="also write the per-triangle cost plot to this SVG file")
    ap.add_argument("--skip", action="append", default=[],
                    help="LABEL:alternate|one:SIZE combinations not to run (repeatable)")
    a = ap.parse_args(argv)
    binaries = [b.split("=", 1) for b in a.binaries]
    if any(len(b) != 2 for b in binaries):
        ap.error("binaries are given as LABEL=PATH")
    os.makedirs(a.grid_dir, exist_ok=True)

    rows = []
    series = {}
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
                        series.setdefault((label, materials), []).append(
                            (triangles, med["load"], med["frame"], med["rss"]))
                        cells = ["%.2f" % med["load"], "%.2f" % med["total"], "%.1f" % med["frame"],
                                 "%.0f" % med["rss"]]
                    rows.append([label, "{:,}".format(triangles), materials] + cells)

    head = ["build", "triangles", "materials", "load s", "load+render s", "frame ms", "peak RSS MiB"]
    print("| " + " | ".join(head) + " |")
    print("|" + "|".join("---" if i < 3 else "---:" for i in range(len(head))) + "|")
    for r in rows:
        print("| " + " | ".join(r) + " |")
    if a.svg:
        write_svg(a.svg, series)
    print("\nmedian of %d runs; `softraster render` / `bench --frames %d --warmup 1`%s" %
          (a.runs, a.frames, (" " + " ".join(extra)) if extra else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
