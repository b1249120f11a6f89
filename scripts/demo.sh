#!/usr/bin/env bash
# SoftRaster's demo command: installs what it needs, builds the Windows exe (MinGW) and starts it
# under Wine in a window when a display is available. Without a display it renders the scene with
# the headless command (softraster.exe render) and prints the image's path.
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
cmake --build --preset mingw --target SoftRaster softraster -j "$(nproc 2>/dev/null || echo 2)" >/dev/null
exe="$root/build/mingw/bin/SoftRaster.exe"

if [[ -n "${DISPLAY:-}" ]] && xdpyinfo >/dev/null 2>&1; then
  echo "demo: starting $exe on display $DISPLAY (Esc quits)"
  exec wine "$exe" "$@"
fi

# No display: render the same scene with the headless command (the Windows build, under Wine)
# and print the image's path.
out_dir="$root/build/artifacts"
mkdir -p "$out_dir"
shot="$out_dir/demo.png"
echo "demo: no display found; rendering the scene headless with softraster.exe render"
headless_args=()
for a in "$@"; do
  case "$a" in *.obj|*.OBJ) headless_args+=(--obj "$a") ;; *) headless_args+=("$a") ;; esac
done
wine "$root/build/mingw/bin/softraster.exe" render "${headless_args[@]}" --out "$(winepath -w "$shot" 2>/dev/null || echo "$shot")" >/dev/null
[[ -s "$shot" ]] || { echo "demo: the headless render wrote no image" >&2; exit 1; }
echo "demo: image of the scene: $shot"
