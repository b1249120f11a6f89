#!/usr/bin/env bash
# Exact-mode image identity check for speed work: renders 34 reference scenes (colour PPM + depth PFM) and compares them byte for byte:
# the bunny, the spider and the built-in scene in every shading mode, then glTF scenes with punctual lights, transparency
# (sorted BLEND), texel alpha (MASK, BLEND), shadows, the sky, the stencil outline and SSAA (skipped when the extra flags choose
# an anti-aliasing of their own: pass --msaa 2|4|8 to check multisampling over all the others).
# Usage: scripts/perf-identity.sh SOFTRASTER OUTDIR [REFDIR] [extra flags, e.g. --threads 2]
#   Without REFDIR (or with REFDIR = -) it only renders (make the reference with the code BEFORE a change);
#   with REFDIR it renders into OUTDIR and `cmp`s every file against REFDIR. Exit 1 on any difference.
set -uo pipefail
BIN=$1; OUT=$2; REF=${3:--}; shift $(( $# >= 3 ? 3 : $# ))
EXTRA=("$@")
mkdir -p "$OUT"
B=/usr/share/glmark2/models/bunny.obj
S=/usr/share/assimp/models/OBJ/spider.obj
SC=(--eye "60,60,60" --target "0,0,-10" --near 1 --far 500)
HERE=$(cd "$(dirname "$0")" && pwd)
SCENES=$(mktemp -d)
trap 'rm -rf "$SCENES"' EXIT
python3 "$HERE/make-lights-scene.py" "$SCENES/lights.gltf" --lights 4 --kind mixed --transparent >/dev/null || exit 2
python3 "$HERE/make-lights-scene.py" "$SCENES/mask.gltf" --texel-alpha mask >/dev/null || exit 2
python3 "$HERE/make-lights-scene.py" "$SCENES/blend.gltf" --texel-alpha blend >/dev/null || exit 2
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
r lights_transparent --model "$SCENES/lights.gltf" --camera 0
r lights_shadows_sky --model "$SCENES/lights.gltf" --camera 0 --shadows --sky gradient
r texel_mask --model "$SCENES/mask.gltf" --camera 0
r texel_blend --model "$SCENES/blend.gltf" --camera 0
r bunny_outline --obj $B --outline
r builtin_sky_wire --sky gradient --wireframe
r spider_close_shadows --obj $S "${SC[@]}" --shadows
[[ " ${EXTRA[*]} " =~ \ --(msaa|ssaa|fxaa|quality)\  ]] || r builtin_ssaa4 --ssaa 4
[[ "$REF" == - ]] && exit 0
bad=0
for f in "$REF"/*; do b=$(basename "$f"); cmp -s "$f" "$OUT/$b" || { echo "DIFF $b"; bad=1; }; done
echo "identical: $([[ $bad == 0 ]] && echo yes || echo NO)"
exit $bad
