#!/usr/bin/env bash
# SoftRaster's demo command: installs what it needs, builds the Windows exe (MinGW) and starts it
# under Wine in a window when a display is available. Without a display it runs the same exe in
# its real window on a private Xvfb display for 60 frames, saves a screenshot and prints its path.
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
deps=$(scripts/build-mingw-deps.sh)   # the glTF decoders for Windows, cached outside the tree
cmake --preset mingw -DSR_MINGW_DEPS_PREFIX="$deps" >/dev/null
cmake --build --preset mingw --target SoftRaster softraster -j "$(nproc 2>/dev/null || echo 2)" >/dev/null
exe="$root/build/mingw/bin/SoftRaster.exe"

if [[ -n "${DISPLAY:-}" ]] && xdpyinfo >/dev/null 2>&1; then
  echo "demo: starting $exe on display $DISPLAY (Esc quits)"
  exec wine "$exe" "$@"
fi

# No display: the real window on a private Xvfb (Tests/EndToEnd/xsession.sh starts it and stops
# it on exit), 60 frames, then the demo's own --screenshot of its last frame.
out_dir="$root/build/artifacts"
mkdir -p "$out_dir"
shot="$out_dir/demo.png"
rm -f "$shot"
e2e_name=demo
# shellcheck source=../Tests/EndToEnd/xsession.sh
source "$root/Tests/EndToEnd/xsession.sh"
start_xvfb 80 89
echo "demo: no display found; running $exe on a private Xvfb display ($DISPLAY) for 60 frames"
wine "$exe" --frames 60 --screenshot "$(winepath -w "$shot" 2>/dev/null || echo "$shot")" "$@" || {
  rc=$?; echo "demo: SoftRaster.exe exited with code $rc" >&2; exit "$rc"; }
[[ -s "$shot" ]] || { echo "demo: SoftRaster.exe saved no screenshot" >&2; exit 1; }
echo "demo: screenshot of the demo window: $shot"
