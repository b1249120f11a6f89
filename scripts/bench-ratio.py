#!/usr/bin/env python3
"""Interleaved cost ratios of quality settings against a baseline, per scene, 1 render thread (a
setting may name its own: "--threads 2" gives the 2-thread time over the 1-thread one).

Each round runs `softraster bench` once per scene and setting (the baseline first), so drift on a
shared machine hits them alike; each setting's time is divided by the same round's baseline time
and the ratios are summarised as median [min, max] over the rounds.

Usage: scripts/bench-ratio.py ROUNDS "label|scene flags" ... -- "setting flags" ...
  e.g. scripts/bench-ratio.py 5 "bunny|--obj /usr/share/glmark2/models/bunny.obj --width 1920 --height 1080 --cull cw" \\
           -- "--msaa 4" "--msaa 8" "--ssaa 4"
  env: SOFTRASTER (build/native/bin/softraster), FRAMES (10) timed frames after 3 warm-up frames.
"""
import json
import os
import shlex
import statistics
import subprocess
import sys


def main():
    args = sys.argv[1:]
    if len(args) < 4 or "--" not in args or not args[0].isdigit():
        print(__doc__, file=sys.stderr)
        return 2
    rounds = int(args[0])
    split = args.index("--")
    scenes = [a.split("|", 1) for a in args[1:split]]
    settings = [""] + args[split + 1:]
    binary = os.environ.get("SOFTRASTER", "build/native/bin/softraster")
    frames = os.environ.get("FRAMES", "10")
    times = {}
    for _ in range(rounds):
        for label, flags in scenes:
            for setting in settings:
                cmd = [binary, "bench", *shlex.split(flags), "--frames", frames, "--warmup", "3", "--threads", "1",
                       *shlex.split(setting), "--quiet"]
                out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
                ms = json.loads(out.strip().splitlines()[-1])["ms_per_frame_median"]
                times.setdefault((label, setting), []).append(ms)
    for label, _ in scenes:
        base = times[(label, "")]
        print(f"{label}: baseline {statistics.median(base):.2f} ms [{min(base):.2f}, {max(base):.2f}]")
        for setting in settings[1:]:
            v = times[(label, setting)]
            r = [a / b for a, b in zip(v, base)]
            print(f"  {setting:14s} {statistics.median(v):8.2f} ms [{min(v):.2f}, {max(v):.2f}]"
                  f"  ratio {statistics.median(r):.2f}x [{min(r):.2f}, {max(r):.2f}]")
    return 0


if __name__ == "__main__":
    sys.exit(main())
