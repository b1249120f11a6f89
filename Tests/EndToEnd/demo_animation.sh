#!/usr/bin/env bash
# The demo plays a glTF file's animation under Xvfb + Wine: the time in the title advances and the
# picture changes; Space pauses (the time and the picture stand still); '.' steps 1/30 s forward;
# Esc exits with code 0. The model: simple_skin of Debian's assimp-testmodels (a skinned strip
# whose joint turns +-90 degrees over a 5.5 s clip).
# Usage: demo_animation.sh <path/to/SoftRaster.exe> [artifacts dir (default build/artifacts)]
set -euo pipefail

exe=${1:?usage: demo_animation.sh <SoftRaster.exe> [artifacts dir]}
artifacts=${2:-build/artifacts}/demo_animation
model=/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf
window_timeout=90
poll_timeout=40
exit_timeout=15

[[ -f "$exe" ]] || { echo "demo_animation: $exe not found" >&2; exit 1; }
[[ -f "$model" ]] || { echo "demo_animation: $model not found (install assimp-testmodels)" >&2; exit 1; }
exe=$(readlink -f "$exe")
rm -rf "$artifacts"
mkdir -p "$artifacts"

e2e_name=demo_animation
source "$(dirname "$0")/xsession.sh"
start_xvfb 141 190
log "Xvfb on $DISPLAY"

winpath() { command winepath -w "$1" 2>/dev/null || echo "$1"; }
shot() { local f="$artifacts/$1.png"; import -window "$win" "$f" 2>/dev/null || return 1; echo "$f"; }
differing() { compare -metric AE "$1" "$2" null: 2>&1 || true; }
# The animation time the title shows (" | t 1.23 s"), or nothing.
title_time() { xdotool getwindowname "$win" 2>/dev/null | sed -n 's/.* | t \([0-9.]*\) s.*/\1/p'; }
press() { xdotool windowfocus --sync "$win" 2>/dev/null || xdotool windowfocus "$win" || true; xdotool key "$1"; }

start_app "$exe" --model "$(winpath "$model")" --width 320 --height 240 --eye 0,1,4 --target 0,1,0 --threads 1
log "window $win: '$(xdotool getwindowname "$win")'"

# --- 1. Playing: the title's time moves on, and two screenshots a moment apart differ ----------
has_time() { t0=$(title_time); last="title '$(xdotool getwindowname "$win" 2>/dev/null)'"; [[ -n "$t0" ]]; }
poll "the animation time in the title" has_time
time_moves() { local t; t=$(title_time); last="t $t (first $t0)"; [[ -n "$t" && "$t" != "$t0" ]]; }
poll "the title's time to advance" time_moves
log "playing: $last"
n=0
picture_moves() {
  n=$((n + 1)); local a b; a=$(shot "play-$n-a") || return 1; sleep 0.3; b=$(shot "play-$n-b") || return 1
  last="$(differing "$a" "$b") pixels differ"; [[ "$last" =~ ^[1-9][0-9]*\ pixels ]]
}
poll "the picture to change while playing" picture_moves
log "playing: the picture moves ($last)"

# --- 2. Space pauses: the title says so; time and picture stand still ---------------------------
press space
paused() { last=$(xdotool getwindowname "$win" 2>/dev/null); [[ "$last" == *" paused"* ]]; }
poll "'paused' in the title after Space" paused
tp=$(title_time)
sleep 0.3 # a frame in flight
a=$(shot paused-a); sleep 1; b=$(shot paused-b)
ae=$(differing "$a" "$b")
[[ "$ae" == 0 ]] || fail "paused, yet $ae pixels changed in a second"
[[ "$(title_time)" == "$tp" ]] || fail "paused, yet the time moved from $tp to $(title_time)"
log "paused at t $tp: the picture stands still"

# --- 3. '.' steps 1/30 s forward (still paused) -------------------------------------------------
press period
stepped() {
  local t; t=$(title_time); last="t $t (paused at $tp)"
  awk -v a="$t" -v b="$tp" 'BEGIN { d = a - b; exit !(d > 0.02 && d < 0.05) }'
}
poll "'.' to step the time by 1/30 s" stepped
paused || fail "'.' should leave the animation paused (title '$last')"
log "'.': $last"

# --- 4. Escape quits with exit code 0 ------------------------------------------------------------
press Escape
wait_exit Escape
log "PASS (screenshots in $artifacts)"
