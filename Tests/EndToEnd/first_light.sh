#!/usr/bin/env bash
# First-light smoke test: SoftRaster.exe under Wine on a private Xvfb shows a non-uniform
# picture in a window titled "SoftRaster...", and Escape makes it exit with code 0.
# Usage: first_light.sh <path/to/SoftRaster.exe> [artifacts dir (default build/artifacts)]
set -euo pipefail

exe=${1:?usage: first_light.sh <SoftRaster.exe> [artifacts dir]}
artifacts=${2:-build/artifacts}
window_timeout=60   # Wine's first start in a fresh prefix can take 20-40 s
exit_timeout=10
min_stddev=0.05     # ImageMagick standard deviation (0..1) of the screenshot; flat colour = 0

[[ -f "$exe" ]] || { echo "first_light: $exe not found" >&2; exit 1; }
exe=$(readlink -f "$exe")
mkdir -p "$artifacts"
shot="$artifacts/first_light.png"
rm -f "$shot"

e2e_name=first_light
source "$(dirname "$0")/xsession.sh"

# --- A private X display (:91-:140), no window manager -------------------------------------
start_xvfb 91 140
log "Xvfb on $DISPLAY"

# --- Start the demo and wait for its window -------------------------------------------------
start_app "$exe"
log "window $win: '$(xdotool getwindowname "$win")' $(xdotool getwindowgeometry "$win" | tr '\n' ' ')"

# --- Screenshot: the window must show a picture, not a flat fill -----------------------------
sleep 1 # let a few frames reach the screen
import -window "$win" "$shot"
stddev=$(convert "$shot" -format '%[fx:standard_deviation]' info:)
colours=$(convert "$shot" -format '%k' info:)
size=$(convert "$shot" -format '%w %h' info:)
width=${size% *}
height=${size#* }
log "screenshot $shot: ${width}x${height}, standard deviation $stddev, $colours colours"
(( width >= 100 && height >= 100 )) || fail "screenshot is only ${width}x${height}"
awk -v s="$stddev" -v m="$min_stddev" 'BEGIN { exit !(s > m) }' ||
  fail "the window looks blank (standard deviation $stddev <= $min_stddev)"
(( colours >= 256 )) || fail "only $colours distinct colours: no gradient on screen"

# --- Escape quits with exit code 0 ------------------------------------------------------------
# Xvfb has no window manager: focus the window explicitly, then send the key to it.
xdotool windowfocus --sync "$win" 2>/dev/null || xdotool windowfocus "$win" || true
xdotool key --window "$win" Escape
wait_exit Escape
log "Escape -> exit code 0. PASS"
