#!/usr/bin/env bash
# Regenerates the plot and the table of README "Speed or accuracy: which setting": `softraster
# report` on the spider close-up (a textured OBJ from Debian's assimp-testmodels) at a small size on
# 1 render thread, the plot copied to docs/images/trade-spider.svg, the six-line Markdown table
# (time per frame and error of the presets and two settings between them) printed on stdout.
# Usage: scripts/make-readme-trade.sh [REPORT_DIR]   (run from anywhere; default REPORT_DIR: a
#        temporary folder, deleted at the end)
#   env: SOFTRASTER (build/native/bin/softraster), W x H (320 x 240), FRAMES (10), WARMUP (2),
#        ROUNDS (3)
# shellcheck disable=SC2016  # single-quoted $ and backquotes are Markdown / doc text, not for this shell
set -euo pipefail
cd "$(dirname "$0")/.."
sr=${SOFTRASTER:-build/native/bin/softraster}
[[ -x "$sr" ]] || { echo "make-readme-trade: $sr missing: build the native preset first" >&2; exit 1; }
model=/usr/share/assimp/models/OBJ/spider.obj
[[ -f "$model" ]] || { echo "make-readme-trade: $model missing (apt-get install assimp-testmodels)" >&2; exit 1; }
W=${W:-320}; H=${H:-240}
if [[ $# -ge 1 ]]; then
  out=$1
else
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out" docs/images

# The close-up camera of docs/reports/spider_* (the texture fills most of the image).
# shellcheck disable=SC2054  # the commas are inside the flags' values
close=(--eye 60,60,60 --target 0,0,-10 --near 1 --far 500)
"$sr" report --quiet --obj "$model" "${close[@]}" --width "$W" --height "$H" --threads 1 \
  --frames "${FRAMES:-10}" --warmup "${WARMUP:-2}" --rounds "${ROUNDS:-3}" --out-dir "$out" >/dev/null
cp "$out/report.svg" docs/images/trade-spider.svg

isa=$(grep -oE 'span kernels [a-z0-9]+' "$out/report.md" | head -1 | cut -d' ' -f3)
cpu=$(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1)
echo "Spider close-up (\`--obj spider.obj ${close[*]}\`), ${W}x${H}, 1 render thread;" \
     "$(nproc) CPUs (\`nproc\`), ${cpu:-unknown CPU}, span kernels ${isa:-?};" \
     "${ROUNDS:-3} rounds of ${FRAMES:-10} frames; error: mean absolute error per channel against" \
     "the 16-sample ground truth, in levels of 255."
echo
echo "| setting | flags | ms per frame, median [min, max] | mean abs error | PSNR dB |"
echo "|---|---|---|---|---|"
# report.csv: ssaa,msaa,fxaa,filter,shading,persp,ms_median,ms_min,ms_max,mean_abs,psnr_db,...
row() { # label, flags, ssaa/msaa/fxaa/filter/shading/persp
  awk -F, -v key="$3" -v label="$1" -v flags="$2" 'NR > 1 && $1"/"$2"/"$3"/"$4"/"$5"/"$6 == key {
      printf "| %s | %s | %s [%s, %s] | %s | %s |\n", label, flags, $7, $8, $9, $10, $11; found = 1 }
    END { if (!found) { print "make-readme-trade: no row " key " in report.csv" > "/dev/stderr"; exit 1 } }' \
    "$out/report.csv"
}
row "fast" '`--quality fast`' "1/1/0/bilinear/gouraud/exact"
row "the defaults (1 sample, bilinear, Phong)" "(none)" "1/1/0/bilinear/phong/exact"
row "FXAA" '`--fxaa`' "1/1/1/bilinear/phong/exact"
row "MSAA 4, trilinear" '`--msaa 4 --filter trilinear`' "1/4/0/trilinear/phong/exact"
row "balanced (the demo's start)" '`--quality balanced`' "4/1/0/trilinear/phong/exact"
row "accurate (the ground truth)" '`--quality accurate`' "16/1/0/trilinear+aniso16/phong/exact"
echo
echo "make-readme-trade: plot written to docs/images/trade-spider.svg" >&2
