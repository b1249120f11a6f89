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
# The rounds, medians, min and max: scripts/bench-ab.sh, one "scene setting" label per configuration.
runs=()
for c in "${configs[@]}"; do
  IFS='|' read -r scene name args <<<"$c"
  runs+=("$scene $name|$BIN|$args --width ${W:-800} --height ${H:-600} ${EXTRA[*]}")
done
exec "$(dirname "$0")/bench-ab.sh" "${ROUNDS:-5}" "${runs[@]}"
