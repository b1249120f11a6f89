#!/usr/bin/env bash
# The demo opens a Draco-compressed glTF file under Xvfb + Wine (KHR_draco_mesh_compression,
# decoded by the Windows build's Draco): the title counts the decoded triangles, the picture shows
# the model, Esc exits with code 0. The model: draco/2CylinderEngine of Debian's assimp-testmodels
# (110,336 triangles once decoded).
# Usage: demo_draco.sh <path/to/SoftRaster.exe> [artifacts dir (default build/artifacts)]
set -euo pipefail

exe=${1:?usage: demo_draco.sh <SoftRaster.exe> [artifacts dir]}
artifacts=${2:-build/artifacts}/demo_draco
model=/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf
window_timeout=90
poll_timeout=60
exit_timeout=15

[[ -f "$exe" ]] || { echo "demo_draco: $exe not found" >&2; exit 1; }
[[ -f "$model" ]] || { echo "demo_draco: $model not found (install assimp-testmodels)" >&2; exit 1; }
exe=$(readlink -f "$exe")
rm -rf "$artifacts"
mkdir -p "$artifacts"

e2e_name=demo_draco
source "$(dirname "$0")/xsession.sh"
start_xvfb 141 190
log "Xvfb on $DISPLAY"

winpath() { command winepath -w "$1" 2>/dev/null || echo "$1"; }
shot() { local f="$artifacts/$1.png"; import -window "$win" "$f" 2>/dev/null || return 1; echo "$f"; }
press() { xdotool windowfocus --sync "$win" 2>/dev/null || xdotool windowfocus "$win" || true; xdotool key "$1"; }

start_app "$exe" --model "$(winpath "$model")" --width 320 --height 240 --threads 1 --quality fast
log "window $win: '$(xdotool getwindowname "$win")'"

# The decoded triangle count in the title (written with or without thousands separators).
counted() { last=$(xdotool getwindowname "$win" 2>/dev/null); [[ "$last" =~ 110[,.\ ]?336 ]]; }
poll "the decoded triangle count (110,336) in the title" counted
log "title: '$last'"
# The model is drawn: many colours in the picture, not the background alone.
n=0
drawn() {
  n=$((n + 1)); local f colours; f=$(shot "frame-$n") || return 1
  colours=$(convert "$f" -format %k info: 2>/dev/null || echo 0); last="$colours colours"; (( colours > 50 ))
}
poll "the model in the picture" drawn
log "drawn: $last"

press Escape
wait_exit Escape
log "PASS (screenshots in $artifacts)"
