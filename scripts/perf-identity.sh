#!/usr/bin/env bash
# Exact-mode image identity check for speed work: renders 26 reference scenes (colour PPM + depth PFM) and compares them byte for byte.
# Usage: scripts/perf-identity.sh SOFTRASTER OUTDIR [REFDIR] [extra flags, e.g. --threads 2]
#   Without REFDIR (or with REFDIR = -) it only renders (make the reference with the code BEFORE a change);
#   with REFDIR it renders into OUTDIR and `cmp`s every file against REFDIR. Exit 1 on any difference.
set -uo pipefail
BIN=$1; OUT=$2; REF=${3:--}; shift $(( $# >= 3 ? 3 : $# ))
EXTRA=("$@")
mkdir -p "$OUT"
B=/usr/share/glmark2/models/bunny.obj
S=/usr/share/assimp/models/OBJ/spider.obj
SC=(--eye 60,60,60 --target 0,0,-10 --near 1 --far 500)
r() { local name=$1; shift; "$BIN" render "$@" "${EXTRA[@]}" --quiet --out "$OUT/$name.ppm" --depth-out "$OUT/$name.pfm" >/dev/null || echo "FAIL $name"; }
for sh in phong flat gouraud unlit; do r bunny_$sh --obj $B --shading $sh; done
r bunny_phong_cw --obj $B --cull cw
r bunny_phong_ccw --obj $B --cull ccw
r bunny_phong_1080 --obj $B --width 1920 --height 1080
r bunny_phong_1080_cw --obj $B --width 1920 --height 1080 --cull cw
r bunny_phong_wire --obj $B --wireframe
r bunny_close --obj $B --eye 0.3,0.2,0.4 --target 0,0.1,0 --near 0.01 --far 10
r spider_close --obj $S "${SC[@]}"
r spider_close_unlit --obj $S "${SC[@]}" --shading unlit
r spider_close_gouraud --obj $S "${SC[@]}" --shading gouraud
r spider_close_tri --obj $S "${SC[@]}" --filter trilinear
r spider_auto --obj $S
r spider_inside --obj $S --eye 0,0,0 --target 0,0,-10 --near 0.5 --far 500
r builtin
r builtin_gouraud --shading gouraud
r builtin_flat --shading flat
r builtin_unlit --shading unlit
r builtin_affine --persp affine
r builtin_tri --filter trilinear
r builtin_wire --wireframe
r builtin_cw --cull cw
r builtin_odd --width 333 --height 77
r builtin_tall --width 17 --height 1000
[[ "$REF" == - ]] && exit 0
bad=0
for f in "$REF"/*; do b=$(basename "$f"); cmp -s "$f" "$OUT/$b" || { echo "DIFF $b"; bad=1; }; done
echo "identical: $([[ $bad == 0 ]] && echo yes || echo NO)"
exit $bad
