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

export WINEDEBUG=-all
export WINEDLLOVERRIDES="mscoree,mshtml="   # no Mono / Gecko install dialogs

t0=$(date +%s%N)
elapsed() { local ms=$(( ($(date +%s%N) - t0) / 1000000 )); printf '%d.%d' $((ms / 1000)) $((ms % 1000 / 100)); }
log() { echo "first_light [$(elapsed) s]: $*"; }

# --- A private X display: the first free number from :91 ----------------------------------
display=""
for n in $(seq 91 140); do
  if [[ ! -e /tmp/.X11-unix/X$n && ! -e /tmp/.X$n-lock ]]; then display=":$n"; break; fi
done
[[ -n "$display" ]] || { echo "first_light: no free X display number in :91-:140" >&2; exit 1; }

xvfb_pid=""
app_pid=""
cleanup() {
  # Only the processes this script started: the app (if still running) and its Xvfb.
  if [[ -n "$app_pid" ]] && kill -0 "$app_pid" 2>/dev/null; then kill "$app_pid" 2>/dev/null || true; fi
  if [[ -n "$xvfb_pid" ]]; then kill "$xvfb_pid" 2>/dev/null || true; wait "$xvfb_pid" 2>/dev/null || true; fi
}
trap cleanup EXIT

Xvfb "$display" -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
export DISPLAY=$display
for _ in $(seq 100); do
  xdotool getdisplaygeometry >/dev/null 2>&1 && break
  kill -0 "$xvfb_pid" 2>/dev/null || { echo "first_light: Xvfb $display died" >&2; exit 1; }
  sleep 0.1
done
log "Xvfb on $display"

# --- Start the demo and wait for its window -------------------------------------------------
wine "$exe" &
app_pid=$!
win=""
deadline=$(( $(date +%s) + window_timeout ))
while (( $(date +%s) < deadline )); do
  win=$(xdotool search --onlyvisible --name '^SoftRaster' 2>/dev/null | head -n1 || true)
  [[ -n "$win" ]] && break
  if ! kill -0 "$app_pid" 2>/dev/null; then
    wait "$app_pid" && rc=0 || rc=$?
    echo "first_light: SoftRaster.exe exited (code $rc) before showing a window" >&2; exit 1
  fi
  sleep 0.25
done
[[ -n "$win" ]] || { echo "first_light: no window named 'SoftRaster...' within ${window_timeout} s" >&2; exit 1; }
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
if (( width < 100 || height < 100 )); then
  echo "first_light: screenshot is only ${width}x${height}" >&2; exit 1
fi
if ! awk -v s="$stddev" -v m="$min_stddev" 'BEGIN { exit !(s > m) }'; then
  echo "first_light: the window looks blank (standard deviation $stddev <= $min_stddev)" >&2; exit 1
fi
if (( colours < 256 )); then
  echo "first_light: only $colours distinct colours: no gradient on screen" >&2; exit 1
fi

# --- Escape quits with exit code 0 ------------------------------------------------------------
# Xvfb has no window manager: focus the window explicitly, then send the key to it.
xdotool windowfocus --sync "$win" 2>/dev/null || xdotool windowfocus "$win" || true
xdotool key --window "$win" Escape
deadline=$(( $(date +%s) + exit_timeout ))
while kill -0 "$app_pid" 2>/dev/null && (( $(date +%s) < deadline )); do sleep 0.1; done
if kill -0 "$app_pid" 2>/dev/null; then
  echo "first_light: SoftRaster.exe still running ${exit_timeout} s after Escape" >&2; exit 1
fi
wait "$app_pid" && rc=0 || rc=$?
app_pid=""
if (( rc != 0 )); then
  echo "first_light: SoftRaster.exe exited with code $rc after Escape (expected 0)" >&2; exit 1
fi
log "Escape -> exit code 0. PASS"
