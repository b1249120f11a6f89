#!/usr/bin/env bash
# One camera path: the same camera and quality flags give the same image in the demo window
# (SoftRaster.exe --frames N --screenshot, on a private Xvfb) and in the headless command
# (softraster.exe render), byte for byte. Both views come from makeFrameView (Platform/App).
# Usage: camera_path.sh <SoftRaster.exe> <softraster.exe> [artifacts dir (default build/artifacts)]
set -euo pipefail

exe=${1:?usage: camera_path.sh <SoftRaster.exe> <softraster.exe> [artifacts dir]}
cli=${2:?usage: camera_path.sh <SoftRaster.exe> <softraster.exe> [artifacts dir]}
artifacts=${3:-build/artifacts}/camera_path
for f in "$exe" "$cli"; do [[ -f "$f" ]] || { echo "camera_path: $f not found" >&2; exit 1; }; done
exe=$(readlink -f "$exe"); cli=$(readlink -f "$cli")
mkdir -p "$artifacts"

e2e_name=camera_path
source "$(dirname "$0")/xsession.sh"
start_xvfb 141 190
log "Xvfb on $DISPLAY"

winpath() { command winepath -w "$1" 2>/dev/null || echo "$1"; }
# Cases: an arbitrary look direction (not a whole yaw/pitch), the built-in scene's own camera,
# and the plain (1-sample) and supersampled paths. The demo renders on 2 threads, the command on 1;
# the demo starts at --quality balanced, the gradient sky and (built-in scene) shadows, and the
# command at the plain defaults (no sky, no shadows), so every case names its quality, sky and
# shadow flags.
cases=(
  "odd-view|--eye 0.4,2.3,6.2 --target 0,0.75,0.1 --near 0.5 --far 50 --quality balanced --sky gradient --shadows"
  "default-view|--ssaa 1 --filter bilinear --sky none --shadows --shadow-size 1024"
  "accurate|--eye -3,1.5,4 --target 0.5,0.5,0 --fov 50 --quality accurate --sky gradient --no-shadows"
)
for c in "${cases[@]}"; do
  name=${c%%|*}; read -r -a flags <<<"${c#*|}"
  demo_png="$artifacts/$name-demo.png" cli_png="$artifacts/$name-render.png"
  rm -f "$demo_png" "$cli_png"
  timeout 120 wine "$exe" --width 320 --height 240 --threads 2 "${flags[@]}" --frames 3 \
    --screenshot "$(winepath "$demo_png")" || fail "$name: SoftRaster.exe exited with code $?"
  timeout 120 wine "$cli" render --width 320 --height 240 "${flags[@]}" --quiet \
    --out "$(winepath "$cli_png")" >/dev/null || fail "$name: softraster.exe render exited with code $?"
  [[ -s "$demo_png" && -s "$cli_png" ]] || fail "$name: an image is missing ($demo_png, $cli_png)"
  # Pixels, not file bytes (PNG metadata may differ): ImageMagick's count of differing pixels.
  ae=$(compare -metric AE "$demo_png" "$cli_png" null: 2>&1 || true)
  [[ "$ae" == 0 ]] || fail "$name: $ae pixels differ between the demo's screenshot and softraster render (${c#*|})"
  log "$name: demo screenshot == softraster render (${c#*|})"
done
log PASS
