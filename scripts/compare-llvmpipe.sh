#!/usr/bin/env bash
# Side-by-side timing and image comparison of SoftRaster against Mesa llvmpipe (the reference
# renderer in ../shared/tools/llvmpipe-ref, built into a temporary folder; it is a development
# aid, not a dependency). Prints Markdown tables for docs/PERFORMANCE.md.
# Usage: scripts/compare-llvmpipe.sh [frames=100] [reps=5] [threads="1 2"] [culls="none cw"] [sizes="800x600 1920x1080"]
# Both run with their default material rule, --materials mtl (the MTL's Kd, Ks, Ns), so both do
# the same work and draw the same image (MATERIALS=fixed runs both with the old fixed values).
# Needs: a native build (build/native/bin/softraster, or $SOFTRASTER), g++ libosmesa6-dev libegl-dev.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
MATERIALS=${MATERIALS:-mtl}
FRAMES=${1:-100}; REPS=${2:-5}; THREADS=${3:-"1 2"}; CULLS=${4:-"none cw"}; SIZES=${5:-"800x600 1920x1080"}
ref_src="$root/../shared/tools/llvmpipe-ref"
[[ -d "$ref_src" ]] || { echo "compare-llvmpipe: $ref_src not found" >&2; exit 1; }
sr="${SOFTRASTER:-$root/build/native/bin/softraster}"
[[ -x "$sr" ]] || { echo "compare-llvmpipe: build the native preset first ($sr missing)" >&2; exit 1; }
missing=()
for p in libosmesa6-dev libegl-dev glmark2-data assimp-testmodels; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  sudo=(); [[ $(id -u) -eq 0 ]] || sudo=(sudo)
  "${sudo[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$ref_src"/. "$work/"
chmod -R u+w "$work"
(cd "$work" && ./build.sh >/dev/null)
glref="$work/glref"; imgcmp="$work/imgcmp"

BUNNY=/usr/share/glmark2/models/bunny.obj
SPIDER=/usr/share/assimp/models/OBJ/spider.obj
field() { sed -E "s/.*\"$1\":([0-9.]+).*/\1/" <<<"$2"; }
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(date -u +%Y-%m-%d)."
echo "Each row: $REPS interleaved runs (llvmpipe, then SoftRaster); each run gives a median ms/frame ($FRAMES frames after 10 warm-up)."
echo "ms columns: the median over the runs; speed = llvmpipe ms / SoftRaster ms of the same run (> 1: SoftRaster faster), median [min, max] over the runs."
echo "llvmpipe threads N = LP_NUM_THREADS=N (0 = its single-threaded case is used for N=1)."
echo
echo "| scene | size | cull | threads | llvmpipe ms | SoftRaster ms | speed vs llvmpipe, median [min, max] |"
echo "|---|---|---|---|---|---|---|"
for cfg in "bunny|$BUNNY|" "spider close-up|$SPIDER|--eye 60,60,60 --target 0,0,-10 --near 1 --far 500"; do
  IFS='|' read -r name obj cam <<<"$cfg"
  for size in $SIZES; do
    w=${size%x*}; h=${size#*x}
    for cull in $CULLS; do
      for t in $THREADS; do
        lp_threads=$t; [[ $t == 1 ]] && lp_threads=0
        g=(); s=(); r=()
        for _ in $(seq "$REPS"); do
          # shellcheck disable=SC2086
          gl=$("$glref" --quiet --materials "$MATERIALS" --obj "$obj" $cam --width "$w" --height "$h" --cull "$cull" --threads "$lp_threads" --frames "$FRAMES" --warmup 10)
          # shellcheck disable=SC2086
          so=$("$sr" bench --quiet --materials "$MATERIALS" --obj "$obj" $cam --width "$w" --height "$h" --cull "$cull" --threads "$t" --frames "$FRAMES" --warmup 10)
          g+=("$(field ms_per_frame_median "$gl")"); s+=("$(field ms_per_frame_median "$so")")
          r+=("$(awk -v a="${g[-1]}" -v b="${s[-1]}" 'BEGIN{printf "%.3f", a/b}')")
        done
        gm=$(echo "${g[*]}" | median); sm=$(echo "${s[*]}" | median)
        rs=$(echo "${r[*]}" | tr ' ' '\n' | sort -g | tr '\n' ' ')
        echo "| $name | $size | $cull | $t | $gm | $sm | $(echo "$rs" | median | xargs printf '%.2f') [$(awk '{printf "%.2f, %.2f", $1, $NF}' <<<"$rs")] |"
      done
    done
  done
done
echo
echo "Image differences (imgcmp: SoftRaster vs llvmpipe, same explicit camera, Phong, 800x600):"
echo
echo "| scene | differing pixels | max abs | PSNR dB | coverage mismatches |"
echo "|---|---|---|---|---|"
for cfg in "bunny|$BUNNY|--eye 0,0,2.69185406 --target 0,0,0 --near 1.33246776 --far 4.05124037" \
           "spider close-up|$SPIDER|--eye 60,60,60 --target 0,0,-10 --near 1 --far 500"; do
  IFS='|' read -r name obj cam <<<"$cfg"
  # shellcheck disable=SC2086
  "$glref" --quiet --materials "$MATERIALS" --obj "$obj" $cam --frames 1 --warmup 0 --out "$work/ref.ppm" >/dev/null
  # shellcheck disable=SC2086
  "$sr" render --quiet --materials "$MATERIALS" --obj "$obj" $cam --out "$work/new.ppm" >/dev/null
  c=$("$imgcmp" "$work/ref.ppm" "$work/new.ppm")
  echo "| $name | $(field differing "$c") | $(field max_abs "$c") | $(sed -E 's/.*"psnr_db":"?([0-9.inf]+)"?.*/\1/' <<<"$c") | $(field coverage_mismatch "$c") |"
done
