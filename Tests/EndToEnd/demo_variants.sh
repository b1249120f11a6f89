#!/usr/bin/env bash
# The demo cycles a glTF file's material variants (KHR_materials_variants) with K under Xvfb +
# Wine: the title names the variant shown and the picture changes colour; a second K goes back to
# the file's own materials; I turns the light from the demo's sky off (the title says so, the
# picture darkens) and on again; Esc exits with code 0. The model, written here: a red quad whose
# variant "gold" makes it blue.
# Usage: demo_variants.sh <path/to/SoftRaster.exe> [artifacts dir (default build/artifacts)]
set -euo pipefail

exe=${1:?usage: demo_variants.sh <SoftRaster.exe> [artifacts dir]}
artifacts=${2:-build/artifacts}/demo_variants
window_timeout=90
poll_timeout=40
exit_timeout=15

[[ -f "$exe" ]] || { echo "demo_variants: $exe not found" >&2; exit 1; }
exe=$(readlink -f "$exe")
rm -rf "$artifacts"
mkdir -p "$artifacts"

# The quad (-1,-1,0) (1,-1,0) (1,1,0) (-1,1,0) as float32, then u16 indices 0 1 2 0 2 3.
m1='\x00\x00\x80\xbf' p1='\x00\x00\x80\x3f' z='\x00\x00\x00\x00'
data=$(printf "$m1$m1$z$p1$m1$z$p1$p1$z$m1$p1$z"'\x00\x00\x01\x00\x02\x00\x00\x00\x02\x00\x03\x00' | base64 -w0)
model="$artifacts/variants.gltf"
cat >"$model" <<JSON
{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0,
   "extensions":{"KHR_materials_variants":{"mappings":[{"material":1,"variants":[0]}]}}}]}],
 "materials":[{"doubleSided":true,"pbrMetallicRoughness":{"baseColorFactor":[1,0,0,1],"metallicFactor":0}},
              {"doubleSided":true,"pbrMetallicRoughness":{"baseColorFactor":[0,0,1,1],"metallicFactor":0}}],
 "extensionsUsed":["KHR_materials_variants"],"extensions":{"KHR_materials_variants":{"variants":[{"name":"gold"}]}},
 "buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,$data"}],
 "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},
              {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}]}
JSON

e2e_name=demo_variants
source "$(dirname "$0")/xsession.sh"
start_xvfb 141 190
log "Xvfb on $DISPLAY"

winpath() { command winepath -w "$1" 2>/dev/null || echo "$1"; }
shot() { local f="$artifacts/$1.png"; import -window "$win" "$f" 2>/dev/null || return 1; echo "$f"; }
differing() { compare -metric AE "$1" "$2" null: 2>&1 || true; }
press() { xdotool windowfocus --sync "$win" 2>/dev/null || xdotool windowfocus "$win" || true; xdotool key "$1"; }
title() { xdotool getwindowname "$win" 2>/dev/null; }

start_app "$exe" --model "$(winpath "$model")" --width 160 --height 120 --threads 1 --quality fast
log "window $win: '$(title)'"
[[ "$(title)" != *variant* ]] || fail "the title names a variant before K: '$(title)'"
sleep 1
own=$(shot own)

press k
named() { last=$(title); [[ "$last" == *"variant gold"* ]]; }
poll "'variant gold' in the title after K" named
log "title: '$last'"
n=0
recoloured() { n=$((n + 1)); local f; f=$(shot "gold-$n") || return 1; last="$(differing "$own" "$f") pixels differ"; [[ "$last" =~ ^[0-9]{4,}\  ]]; }
poll "the quad to change colour" recoloured
log "gold: $last"

press k
unnamed() { last=$(title); [[ "$last" != *"| variant "* ]]; }
poll "the variant gone from the title after a second K" unnamed
back() { local f; f=$(shot back) || return 1; last="$(differing "$own" "$f") pixels differ"; [[ "$last" == "0 pixels differ" ]]; }
poll "the file's own materials again" back

[[ "$(title)" == *"| sky light"* ]] || fail "the glTF scene is not lit by the sky at the start: '$(title)'"
press i
skyOff() { last=$(title); [[ "$last" == *"sky light off"* ]]; }
poll "'sky light off' in the title after I" skyOff
m=0
darker() { m=$((m + 1)); local f; f=$(shot "no-sky-$m") || return 1; last="$(differing "$own" "$f") pixels differ"; [[ "$last" =~ ^[0-9]{4,}\  ]]; }
poll "the quad to change without the sky's light" darker
log "sky light off: $last"
press i
skyOn() { last=$(title); [[ "$last" == *"| sky light"* && "$last" != *"sky light off"* ]]; }
poll "'sky light' in the title after a second I" skyOn
lit() { local f; f=$(shot sky-again) || return 1; last="$(differing "$own" "$f") pixels differ"; [[ "$last" == "0 pixels differ" ]]; }
poll "the sky's light again" lit

press Escape
wait_exit Escape
log "PASS (screenshots in $artifacts)"
