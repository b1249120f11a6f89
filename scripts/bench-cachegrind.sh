#!/usr/bin/env bash
# Deterministic A/B of softraster builds or settings for a noisy machine: each configuration's
# `softraster bench` runs once under valgrind's cachegrind (1 thread), which counts the
# instructions executed and simulates the caches; the counts do not move with a neighbour's load.
# Prints per configuration the instructions, the first-level data misses and the last-level
# misses, and each one's ratio to the first configuration's.
# Usage: scripts/bench-cachegrind.sh "label|SOFTRASTER|bench flags" ...
#   e.g. scripts/bench-cachegrind.sh "old|old/softraster|--msaa 4" "new|build/native/bin/softraster|--msaa 4"
#   env: FRAMES (5) timed frames per run, after 1 warm-up frame; LL (1048576,16,64: size, ways,
#   line of the simulated last level, here one core's L2).
# Caveats: valgrind has no AVX-512, so the kernels run `avx2`; the counts include the bench's own
# partial frames that time its stages, so compare them between configurations, not to frame times.
set -uo pipefail
[[ $# -ge 1 ]] || { sed -n 2,12p "$0" >&2; exit 2; }
if ! command -v valgrind >/dev/null; then
  if [[ $(id -u) == 0 ]]; then apt-get install -y valgrind >/dev/null; else sudo apt-get install -y valgrind >/dev/null; fi
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
i=0
for c in "$@"; do
  IFS='|' read -r name bin args <<<"$c"
  # shellcheck disable=SC2086  # args is a flag list
  valgrind --tool=cachegrind --cache-sim=yes --LL="${LL:-1048576,16,64}" --D1=32768,8,64 \
    --cachegrind-out-file=/dev/null "$bin" bench $args --frames "${FRAMES:-5}" --warmup 1 --threads 1 --quiet \
    >/dev/null 2>"$out/$i.log" &
  i=$((i + 1))
  # no more runs at once than CPUs
  while (( $(jobs -rp | wc -l) >= $(nproc) )); do wait -n; done
done
wait
i=0
for c in "$@"; do
  IFS='|' read -r name _ _ <<<"$c"
  grep -qE 'I +refs' "$out/$i.log" || { echo "$name: cachegrind failed:" >&2; tail -5 "$out/$i.log" >&2; exit 1; }
  echo "$name $(grep -E 'I +refs' "$out/$i.log" | awk '{print $NF}') $(grep -E 'D1 +misses' "$out/$i.log" | awk '{print $4}') $(grep -E 'LL misses' "$out/$i.log" | awk '{print $4}')"
  i=$((i + 1))
done | python3 -c '
import sys
rows = [l.split() for l in sys.stdin if l.strip()]
num = lambda s: int(s.replace(",", ""))
base = [num(v) for v in rows[0][1:]]
for r in rows:
    v = [num(x) for x in r[1:]]
    print("%-20s instructions %14s (%.3f)  D1 misses %12s (%.3f)  LL misses %12s (%.3f)" %
          (r[0], f"{v[0]:,}", v[0] / base[0], f"{v[1]:,}", v[1] / max(base[1], 1), f"{v[2]:,}", v[2] / max(base[2], 1)))
'
