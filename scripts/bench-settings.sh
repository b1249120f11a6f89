#!/usr/bin/env bash
# The speed/accuracy trade, timed: softraster bench on 1 thread for each quality setting of the
# spider, the bunny and the built-in scene, interleaved (every setting once per round), printing
# the median, min and max of the rounds' median ms per frame.
# Usage: scripts/bench-settings.sh SOFTRASTER [extra bench flags, e.g. --isa sse2]
#   env: ROUNDS (5), FRAMES (40), W x H (800 x 600). Needs assimp-testmodels and glmark2-data.
set -uo pipefail
BIN=${1:?usage: scripts/bench-settings.sh SOFTRASTER [flags]}; shift
EXTRA=("$@")
S=/usr/share/assimp/models/OBJ/spider.obj
B=/usr/share/glmark2/models/bunny.obj
for f in "$S" "$B"; do [[ -f $f ]] || { echo "missing $f (apt-get install assimp-testmodels glmark2-data)" >&2; exit 1; }; done
configs=(
  "spider|phong|--obj $S --shading phong"     "spider|gouraud|--obj $S --shading gouraud"
  "spider|flat|--obj $S --shading flat"       "spider|unlit|--obj $S --shading unlit"
  "spider|nearest|--obj $S --filter nearest"  "spider|trilinear|--obj $S --filter trilinear"
  "spider|affine|--obj $S --persp affine"
  "spider|scalar|--obj $S --isa scalar"
  "bunny|phong|--obj $B --cull cw"            "bunny|gouraud|--obj $B --cull cw --shading gouraud"
  "bunny|flat|--obj $B --cull cw --shading flat" "bunny|unlit|--obj $B --cull cw --shading unlit"
  "builtin|phong|"                            "builtin|gouraud|--shading gouraud"
  "builtin|flat|--shading flat"               "builtin|unlit|--shading unlit"
  "builtin|nearest|--filter nearest"          "builtin|trilinear|--filter trilinear"
  "builtin|affine|--persp affine"
)
declare -A res
for _ in $(seq "${ROUNDS:-5}"); do
  for c in "${configs[@]}"; do
    IFS='|' read -r scene name args <<<"$c"
    # shellcheck disable=SC2086  # args is a flag list
    ms=$("$BIN" bench $args --width "${W:-800}" --height "${H:-600}" --frames "${FRAMES:-40}" --warmup 5 --threads 1 \
           "${EXTRA[@]}" 2>/dev/null | grep -oE '"ms_per_frame_median":[0-9.]+' | cut -d: -f2)
    res["$scene|$name"]+="${ms:-nan} "
  done
done
for c in "${configs[@]}"; do
  IFS='|' read -r scene name _ <<<"$c"
  # shellcheck disable=SC2086
  python3 -c 'import sys, statistics as st
v = sorted(float(x) for x in sys.argv[3:])
print("%-8s %-10s median %7.3f  min %7.3f  max %7.3f" % (sys.argv[1], sys.argv[2], st.median(v), v[0], v[-1]))' \
    "$scene" "$name" ${res[$scene|$name]}
done
