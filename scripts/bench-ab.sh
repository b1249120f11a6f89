#!/usr/bin/env bash
# Interleaved A/B timing of softraster builds or settings: each round runs every configuration
# once (softraster bench, 1 thread), so drift on a shared machine hits them all alike; prints
# the median, min and max of the rounds' per-run median ms per frame.
# Usage: scripts/bench-ab.sh ROUNDS "label|SOFTRASTER|bench flags" ...
#   e.g. scripts/bench-ab.sh 7 "old|old/softraster|--filter trilinear" "new|build/native/bin/softraster|--filter trilinear"
#   env: FRAMES (40) timed frames per run, after 5 warm-up frames.
set -uo pipefail
[[ $# -ge 2 ]] || { sed -n 2,7p "$0" >&2; exit 2; }
rounds=$1; shift
declare -A res
for _ in $(seq "$rounds"); do
  for c in "$@"; do
    IFS='|' read -r name bin args <<<"$c"
    # shellcheck disable=SC2086  # args is a flag list
    ms=$("$bin" bench $args --frames "${FRAMES:-40}" --warmup 5 --threads 1 2>/dev/null |
           grep -oE '"ms_per_frame_median":[0-9.]+' | cut -d: -f2)
    res[$name]+="${ms:-nan} "
  done
done
for c in "$@"; do
  IFS='|' read -r name _ _ <<<"$c"
  # shellcheck disable=SC2086
  python3 -c 'import sys, statistics as st
v = sorted(float(x) for x in sys.argv[2:])
print("%-28s median %8.3f  min %8.3f  max %8.3f" % (sys.argv[1], st.median(v), v[0], v[-1]))' "$name" ${res[$name]}
done
