#!/usr/bin/env bash
# SoftRaster's demo command: installs what it needs, builds the Windows exe (MinGW) and starts it
# under Wine in a window when a display is available. Without a display it runs the exe on a
# private virtual display (Xvfb), saves a screenshot and prints the image's path.
# Usage: scripts/demo.sh [SoftRaster.exe arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,5p' "$0" | sed 's/^# \{0,1\}//'; exit 0
fi

scripts/install-deps.sh demo
export WINEPREFIX="${WINEPREFIX:-$root/build/wineprefix}"
export WINEDEBUG="${WINEDEBUG:--all}"
export WINEDLLOVERRIDES="${WINEDLLOVERRIDES:-mscoree,mshtml=}"

echo "demo: building SoftRaster.exe (preset mingw)"
cmake --preset mingw >/dev/null
cmake --build --preset mingw --target SoftRaster -j "$(nproc 2>/dev/null || echo 2)" >/dev/null
exe="$root/build/mingw/bin/SoftRaster.exe"

if [[ -n "${DISPLAY:-}" ]] && xdpyinfo >/dev/null 2>&1; then
  echo "demo: starting $exe on display $DISPLAY (Esc quits)"
  exec wine "$exe" "$@"
fi

# No display: run on a private Xvfb, screenshot the window, print the image path.
out_dir="$root/build/artifacts"
mkdir -p "$out_dir"
shot="$out_dir/demo.png"
disp=""
for n in $(seq 90 120); do
  if [[ ! -e /tmp/.X11-unix/X$n && ! -e /tmp/.X$n-lock ]]; then disp=":$n"; break; fi
done
[[ -n "$disp" ]] || { echo "demo: no free X display number" >&2; exit 1; }
Xvfb "$disp" -screen 0 1024x768x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
app_pid=""
cleanup() {
  [[ -n "$app_pid" ]] && kill "$app_pid" 2>/dev/null
  kill "$xvfb_pid" 2>/dev/null
  wineserver -k 2>/dev/null || true
}
trap cleanup EXIT
export DISPLAY="$disp"
for _ in $(seq 50); do xdpyinfo >/dev/null 2>&1 && break; sleep 0.2; done
echo "demo: no display found; running SoftRaster.exe on a virtual display ($disp)"
wine "$exe" "$@" &
app_pid=$!
win=""
for _ in $(seq 120); do
  win=$(xdotool search --name '^SoftRaster' 2>/dev/null | head -1 || true)
  [[ -n "$win" ]] && break
  kill -0 "$app_pid" 2>/dev/null || { echo "demo: SoftRaster.exe exited early" >&2; exit 1; }
  sleep 0.5
done
[[ -n "$win" ]] || { echo "demo: no SoftRaster window appeared within 60 s" >&2; exit 1; }
sleep 2
import -window "$win" "$shot"
echo "demo: screenshot of the running demo: $shot"
