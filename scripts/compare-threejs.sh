#!/usr/bin/env bash
# Renders glTF models with softraster and with the three.js reference (../shared/tools/threejs-ref,
# built by its build.sh) under the same camera, and prints the PSNR over the pixels lit in both,
# for the default (pbr, linear) and the former model (phong on display values).
# With IBL=1 both light the models from the same cube-map sky too (scripts/make-sky.py, with
# three.js's mirrored lookup undone), and the PSNR is over all pixels, the sky included; the
# second column is then pbr with --no-ibl.
# Usage: scripts/compare-threejs.sh [OUT_DIR] [MODEL...]   (a development aid: not in the test command)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/threejs-compare}; shift || true
ref=${THREEJS_REF:-../shared/tools/threejs-ref}
sr=${SOFTRASTER:-build/native/bin/softraster}
M=/usr/share/assimp/models/glTF2
models=("$@")
[[ ${#models[@]} -gt 0 ]] || models=("$M/ClearCoat-glTF/ClearCoatTest.gltf" "$M/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"
  "$M/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" "$M/BoxTextured-glTF/BoxTextured.gltf")
mkdir -p "$out"
# A vertex-coloured model (COLOR_0): assimp's glTF export of assimp-testmodels' coloured cube.
cube=/usr/share/assimp/models/OBJ/cube_with_vertexcolors.obj
if [[ $# -eq 0 && -f $cube ]] && command -v assimp >/dev/null; then
  assimp export "$cube" "$out/cube_with_vertexcolors.gltf" -f gltf2 >/dev/null && models+=("$out/cube_with_vertexcolors.gltf")
fi
# Sphere sweeps: KHR_materials_ior with _specular, KHR_materials_clearcoat, _sheen, maps at their own addresses.
if [[ $# -eq 0 ]]; then
  for set in specular clearcoat sheen addressing; do
    python3 scripts/make-material-spheres.py "$set" "$out/${set}_spheres.gltf" && models+=("$out/${set}_spheres.gltf")
  done
fi
W=${WIDTH:-400} H=${HEIGHT:-300}
ours=() three=() second=(--shading phong --color gamma) key=psnr_both_nonblack
heading=("pbr+linear dB" "phong+gamma dB")
if [[ ${IBL:-0} == 1 ]]; then
  python3 scripts/make-sky.py "$out/sky" && python3 scripts/make-sky.py "$out/sky-three" --three
  ours=(--skybox "$out/sky" --ibl) three=(--skybox "$out/sky-three" --ibl) second=(--skybox "$out/sky" --no-ibl) key=psnr_all
  heading=("pbr+ibl dB" "pbr, no ibl dB")
fi
printf '%-22s %14s %14s\n' model "${heading[@]}"
for m in "${models[@]}"; do
  n=$(basename "${m%.*}")
  cam=$("$sr" render --model "$m" --width "$W" --height "$H" --out "$out/$n.png" --ssaa 16 "${ours[@]}" 2>&1 | sed -n 's/^softraster: camera: //p')
  "$sr" render --model "$m" --width "$W" --height "$H" --ssaa 16 "${second[@]}" --out "$out/${n}_phong.png" >/dev/null 2>&1
  # shellcheck disable=SC2086
  "$ref/render.sh" "$m" --out "$out/${n}_three.png" --width "$W" --height "$H" $cam "${three[@]}" --quiet >/dev/null
  p1=$(/usr/bin/python3 "$ref/compare.py" "$out/${n}_three.png" "$out/$n.png" --json | python3 -c 'import json,sys; print("%.1f" % json.load(sys.stdin)[sys.argv[1]])' "$key")
  p0=$(/usr/bin/python3 "$ref/compare.py" "$out/${n}_three.png" "$out/${n}_phong.png" --json | python3 -c 'import json,sys; print("%.1f" % json.load(sys.stdin)[sys.argv[1]])' "$key")
  printf '%-22s %14s %14s\n' "$n" "$p1" "$p0"
done
