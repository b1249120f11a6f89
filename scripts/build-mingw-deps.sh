#!/usr/bin/env bash
# Builds the glTF decoders (meshoptimizer, libwebp, Draco) for MinGW-w64 from Debian's source packages, cached outside the repository.
# Usage: scripts/build-mingw-deps.sh [--help]   (prints the prefix on stdout: cmake --preset mingw -DSR_MINGW_DEPS_PREFIX=<prefix>)
#
# The versions are those of Debian's libmeshoptimizer-dev, libwebp-dev and libdraco-dev (the
# installed ones, else apt's candidates), so the MinGW build decodes with the code the native build
# links. The sources come from `apt-get source` (a deb-src twin of Debian's entries is added when
# apt has no deb-src entry), Debian's patches applied; the static libraries (Release, -O2), their
# headers and the build logs go to one prefix (include/, lib/, logs/):
#   ${SR_MINGW_DEPS:-${XDG_CACHE_HOME:-$HOME/.cache}/softraster/mingw-deps}/<source>-<version>_..._
# Its stamp makes a later run print the prefix and do nothing else (0.2 s). Progress and errors
# go to stderr; installing packages and adding the deb-src entry use sudo when not root.
set -euo pipefail

if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,3p' "$0" | sed 's/^# //'; exit 0
fi
[[ $# -eq 0 ]] || { echo "build-mingw-deps: error: unexpected argument '$1' (see --help)" >&2; exit 2; }

repo=$(cd "$(dirname "$0")/.." && pwd)
toolchain=$repo/cmake/mingw-w64-x86_64.cmake
cache=$(realpath -m "${SR_MINGW_DEPS:-${XDG_CACHE_HOME:-$HOME/.cache}/softraster/mingw-deps}")
tools=(dpkg-dev cmake ninja-build g++-mingw-w64-x86-64-posix)
devs=(libmeshoptimizer-dev libwebp-dev libdraco-dev)   # built in this order, from their source packages

say() { echo "build-mingw-deps: $*" >&2; }
die() { echo "build-mingw-deps: error: $*" >&2; step=""; exit 1; }
# Any other failure (set -e ends the script there): the log's error lines, if a step has a log,
# then one line saying what was being done.
step="starting" log=""
on_exit() {
  local rc=$?
  [[ $rc -ne 0 && -n "$step" ]] || return 0
  if [[ -n "$log" && -f "$log" ]]; then
    { grep -E 'error|Error|FAILED' "$log" | head -15; echo "--- last lines of $log:"; tail -5 "$log"; } | sed 's/^/  /' >&2
  fi
  echo "build-mingw-deps: error: failed while ${step}${log:+ (log $log)} (exit ${rc})" >&2
}
trap on_exit EXIT
now_ms() { local t=${EPOCHREALTIME/[.,]/}; echo $((t / 1000)); }
# CPU time (user + system) of this script's finished child processes, in milliseconds.
cpu_ms() { local st; read -ra st </proc/$$/stat; echo $(((st[15] + st[16]) * 1000 / $(getconf CLK_TCK))); }
secs() { printf '%d.%d' $(($1 / 1000)) $(($1 % 1000 / 100)); }   # milliseconds as seconds, 1 decimal

case "$cache/" in "$repo"/*) die "the cache ($cache) must be outside the repository: set SR_MINGW_DEPS elsewhere" ;; esac

sudo=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then sudo=(sudo); else sudo=(false); fi
fi
as_root() {
  [[ "${sudo[*]}" != false ]] || die "need root or sudo to run: ${*#env DEBIAN_FRONTEND=noninteractive }"
  "${sudo[@]}" "$@"
}
apt_update() {
  step="running apt-get update"; say "apt-get update"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 update -qq >&2
}

# "source-package source-version" of a -dev package: the installed one, else apt's candidate.
source_of() {
  local pkg=$1 st ver field
  st=$(dpkg-query -W -f='${db:Status-Abbrev}|${source:Package}|${source:Version}' "$pkg" 2>/dev/null || true)
  if [[ "$st" == ii* ]]; then
    IFS='|' read -r _ src sver <<<"$st"; echo "$src $sver"; return 0
  fi
  ver=$(apt-cache policy "$pkg" 2>/dev/null | awk '/Candidate:/ {print $2}')
  [[ -n "$ver" && "$ver" != "(none)" ]] || return 1
  field=$(apt-cache show "$pkg=$ver" 2>/dev/null | awk '/^Source:/ && !n++ {sub(/^Source: */, ""); print}')
  if [[ -z "$field" ]]; then echo "$pkg $ver"
  elif [[ "$field" =~ ^([^ ]+)\ \((.+)\)$ ]]; then echo "${BASH_REMATCH[1]} ${BASH_REMATCH[2]}"
  else echo "$field $ver"; fi
}
resolve_versions() {
  srcs=() vers=()
  local d sv
  for d in "${devs[@]}"; do
    sv=$(source_of "$d") || return 1
    srcs+=("${sv% *}"); vers+=("${sv#* }")
  done
}

# --- How each library is configured and built: static, Release at -O2, what decoding needs ----
# The toolchain file requires Wine (ctest's emulator); these builds run nothing (no try_run), so
# Wine is named, not searched for: no Wine is needed and the result is the same with or without.
# -muse-unaligned-vector-move: as the project's own MinGW code (CMakeLists.txt, GCC bug 54412).
common_opts=(-G Ninja -DCMAKE_TOOLCHAIN_FILE="$toolchain" -DSR_WINE=/bin/false -DCMAKE_BUILD_TYPE=Release
             -DCMAKE_C_FLAGS_RELEASE="-O2 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG"
             -DCMAKE_C_FLAGS="-Wa,-muse-unaligned-vector-move" -DCMAKE_CXX_FLAGS="-Wa,-muse-unaligned-vector-move"
             -DBUILD_SHARED_LIBS=OFF -DCMAKE_INSTALL_LIBDIR=lib)
# shellcheck disable=SC2034  # read as ${!o}
opts_meshoptimizer=(-DMESHOPT_BUILD_SHARED_LIBS=OFF -DMESHOPT_BUILD_DEMO=OFF -DMESHOPT_BUILD_GLTFPACK=OFF)
# shellcheck disable=SC2034  # read as ${!o}
opts_libwebp=(-DWEBP_BUILD_ANIM_UTILS=OFF -DWEBP_BUILD_CWEBP=OFF -DWEBP_BUILD_DWEBP=OFF -DWEBP_BUILD_GIF2WEBP=OFF
              -DWEBP_BUILD_IMG2WEBP=OFF -DWEBP_BUILD_VWEBP=OFF -DWEBP_BUILD_WEBPINFO=OFF -DWEBP_BUILD_WEBPMUX=OFF
              -DWEBP_BUILD_EXTRAS=OFF -DWEBP_BUILD_WEBP_JS=OFF -DWEBP_BUILD_LIBWEBPMUX=OFF)
# shellcheck disable=SC2034  # read as ${!o}
opts_draco=(-DDRACO_TRANSCODER_SUPPORTED=OFF -DDRACO_TESTS=OFF -DDRACO_GLTF_BITSTREAM=OFF -DDRACO_JS_GLUE=OFF
            -DDRACO_MAYA_PLUGIN=OFF -DDRACO_UNITY_PLUGIN=OFF -DDRACO_ANIMATION_ENCODING=OFF)

# build_<source> BUILD SOURCE PREFIX: builds the configured tree and installs into PREFIX.
build_meshoptimizer() {   # the library alone: libmeshoptimizer.a, meshoptimizer.h
  cmake --build "$1" -j "$jobs" --target meshoptimizer
  mkdir -p "$3/include" "$3/lib"
  cp "$2/src/meshoptimizer.h" "$3/include/"
  cp "$1/libmeshoptimizer.a" "$3/lib/"
}
build_libwebp() {         # the decoder library alone: libwebpdecoder.a, webp/decode.h and types.h
  cmake --build "$1" -j "$jobs" --target webpdecoder
  mkdir -p "$3/include/webp" "$3/lib"
  cp "$2/src/webp/decode.h" "$2/src/webp/types.h" "$3/include/webp/"
  cp "$1/libwebpdecoder.a" "$3/lib/"
}
# Draco's library holds its encoders and file I/O too: its decoding object libraries alone (61
# of its 100 objects, about half the compile time) are archived as libdraco.a once every draco
# symbol they need is found among them; else (another Draco, other targets) the whole library is
# built. All of Draco's headers are installed, the encoders' too (their code is not in the library).
draco_decoder_objlibs=(draco_attributes draco_compression_attributes_dec draco_compression_bit_coders
  draco_compression_decode draco_compression_entropy draco_compression_mesh_dec draco_compression_options
  draco_compression_point_cloud_dec draco_core draco_dec_config draco_mesh draco_metadata
  draco_metadata_dec draco_point_cloud draco_points_dec)
build_draco() {           # libdraco.a, every header under src/draco and the generated draco_features.h
  mkdir -p "$3/include" "$3/lib"
  local nm=x86_64-w64-mingw32-nm objs=() missing="" t
  if cmake --build "$1" -j "$jobs" --target "${draco_decoder_objlibs[@]}"; then
    for t in "${draco_decoder_objlibs[@]}"; do
      [[ ! -d "$1/CMakeFiles/$t.dir" ]] || mapfile -t -O ${#objs[@]} objs < <(find "$1/CMakeFiles/$t.dir" -name '*.obj' | sort)
    done
    rm -f "$1/libdraco-decoder.a"
    x86_64-w64-mingw32-ar rcs "$1/libdraco-decoder.a" "${objs[@]}"
    missing=$(LC_ALL=C comm -23 <($nm -j -u "$1/libdraco-decoder.a" | grep 5draco | LC_ALL=C sort -u) \
                       <($nm -j --defined-only "$1/libdraco-decoder.a" | grep 5draco | LC_ALL=C sort -u) | head -3)
  else
    missing="a decoding target failed to build"
  fi
  if [[ ${#objs[@]} -gt 0 && -z "$missing" ]]; then
    echo "draco: decoder subset, ${#objs[@]} objects"
    cp "$1/libdraco-decoder.a" "$3/lib/libdraco.a"
  else
    echo "draco: no decoder subset (${missing}): building the whole library"
    cmake --build "$1" -j "$jobs" --target draco_static
    cp "$1/libdraco.a" "$3/lib/"
  fi
  (cd "$2/src" && find draco -name '*.h' -exec cp --parents {} "$3/include/" \;)
  cp "$1/draco/draco_features.h" "$3/include/draco/"
}

# --- Fast path: the prefix for these versions and this recipe is there ----------------------
step="finding the Debian versions of ${devs[*]}"
if ! resolve_versions; then
  apt_update
  resolve_versions || die "apt knows no ${devs[*]}: is Debian's main repository in apt's sources?"
fi
name=""; for i in "${!srcs[@]}"; do name+="${name:+_}${srcs[$i]}-${vers[$i]#*:}"; done
prefix=$cache/$name
# What the stamp records: versions, toolchain, and the recipe (options and build functions).
stamp_text() {
  local i o
  echo "toolchain file $(sha256sum "$toolchain" | cut -c1-16)"
  echo "compiler $(dpkg-query -W -f='${Package} ${Version} ' g++-mingw-w64-x86-64-posix mingw-w64-x86-64-dev 2>/dev/null || true)"
  for i in "${!srcs[@]}"; do
    o="opts_${srcs[$i]}[*]"
    echo "${srcs[$i]} ${vers[$i]}: ${common_opts[*]//$repo/<repo>} ${!o}" \
         "build $(declare -f "build_${srcs[$i]}" | sha256sum | cut -c1-16)"
  done
  echo "draco objects ${draco_decoder_objlibs[*]}"
}
if [[ -f "$prefix/.stamp" && "$(cat "$prefix/.stamp")" == "$(stamp_text)" ]]; then
  say "up to date: $prefix"
  echo "$prefix"; exit 0
fi

# --- Tools, and Debian's source packages reachable through apt ------------------------------
mkdir -p "$cache"
exec 9>"$cache/.lock"
step="waiting for another build-mingw-deps run (lock $cache/.lock)"
flock 9
missing=()
for p in "${tools[@]}"; do
  [[ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)" == "install ok installed" ]] || missing+=("$p")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  apt_update
  step="installing ${missing[*]}"; say "installing ${missing[*]}"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 install -y -qq "${missing[@]}" >&2
fi

has_source() { apt-cache showsrc --only-source "$1" 2>/dev/null | grep -x "Version: $2" >/dev/null; }
all_sources() { local i; for i in "${!srcs[@]}"; do has_source "${srcs[$i]}" "${vers[$i]}" || return 1; done; }
# deb-src twins of the Debian entries in apt's sources (one-line .list and deb822 .sources files),
# in files of our own; nothing is added when apt has a deb-src entry already.
add_deb_src() {
  local lists=() sources=() f text
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do [[ -f "$f" ]] && lists+=("$f"); done
  for f in /etc/apt/sources.list.d/*.sources; do [[ -f "$f" ]] && sources+=("$f"); done
  if { [[ ${#lists[@]} -gt 0 ]] && grep -qE '^[[:space:]]*deb-src[[:space:]]' "${lists[@]}"; } ||
     { [[ ${#sources[@]} -gt 0 ]] && grep -qiE '^Types:.*[[:space:]]deb-src([[:space:]]|$)' "${sources[@]}"; }; then
    return 0
  fi
  if [[ ${#lists[@]} -gt 0 ]] && grep -qE '^[[:space:]]*deb[[:space:]].*debian' "${lists[@]}"; then
    say "adding /etc/apt/sources.list.d/softraster-deb-src.list"
    grep -hE '^[[:space:]]*deb[[:space:]].*debian' "${lists[@]}" | sed -E 's/^[[:space:]]*deb[[:space:]]/deb-src /' |
      as_root tee /etc/apt/sources.list.d/softraster-deb-src.list >/dev/null
  fi
  if [[ ${#sources[@]} -gt 0 ]]; then
    # Each enabled stanza with "Types: deb" and a Debian URI, again with "Types: deb-src".
    text=$(awk 'function flush() { if (deb && debian && !off) printf "%s%s", (n++ ? "\n" : ""), para; para = ""; deb = debian = off = 0 }
                /^[[:space:]]*$/ { flush(); next }
                /^#/ { next }
                tolower($1) == "types:" { for (i = 2; i <= NF; i++) if ($i == "deb") deb = 1; para = para "Types: deb-src\n"; next }
                tolower($1) == "uris:" && /debian/ { debian = 1 }
                tolower($1) == "enabled:" && tolower($2) == "no" { off = 1 }
                { para = para $0 "\n" }
                END { flush() }' "${sources[@]}")
    if [[ -n "$text" ]]; then
      say "adding /etc/apt/sources.list.d/softraster-deb-src.sources"
      printf '%s\n' "$text" | as_root tee /etc/apt/sources.list.d/softraster-deb-src.sources >/dev/null
    fi
  fi
}
if ! all_sources; then
  step="adding a deb-src entry for Debian"
  add_deb_src
  apt_update
  for i in "${!srcs[@]}"; do
    has_source "${srcs[$i]}" "${vers[$i]}" ||
      die "apt offers no source package ${srcs[$i]} ${vers[$i]} (no deb-src entry for Debian's repository? or upgrade ${devs[$i]})"
  done
fi

# --- Build each library into a fresh prefix, moved into place when all are done --------------
work=$cache/work
rm -rf "$work" "$prefix.tmp"
mkdir -p "$work" "$prefix.tmp"
jobs=$(nproc 2>/dev/null || echo 2)
total0=$(now_ms) cpu0=$(cpu_ms)
for i in "${!srcs[@]}"; do
  src=${srcs[$i]} ver=${vers[$i]}
  log=$work/$src.log
  t0=$(now_ms) c0=$(cpu_ms)
  mkdir -p "$work/$src"
  step="downloading the source package $src $ver"
  (cd "$work/$src" && apt-get source --download-only -q "$src=$ver") >"$log" 2>&1
  step="unpacking $src $ver with Debian's patches"
  dpkg-source -x "$(ls "$work/$src"/*.dsc)" "$work/$src/source" >>"$log" 2>&1
  t1=$(now_ms)
  step="configuring $src $ver"
  o="opts_${src}[@]"
  cmake -S "$work/$src/source" -B "$work/$src/build" "${common_opts[@]}" "${!o}" >>"$log" 2>&1
  step="building $src $ver"
  "build_$src" "$work/$src/build" "$work/$src/source" "$prefix.tmp" >>"$log" 2>&1
  say "$src $ver: $(secs $(($(now_ms) - t0))) s (download + unpack $(secs $((t1 - t0))) s, configure + build $(secs $(($(now_ms) - t1))) s; CPU $(secs $(($(cpu_ms) - c0))) s)"
done
step="moving the new prefix into place" log=""
stamp_text >"$prefix.tmp/.stamp"
mkdir -p "$prefix.tmp/logs" && cp "$work"/*.log "$prefix.tmp/logs/"
rm -rf "$prefix"
mv "$prefix.tmp" "$prefix"
rm -rf "$work"
say "built in $(secs $(($(now_ms) - total0))) s (CPU $(secs $(($(cpu_ms) - cpu0))) s on $jobs jobs): $prefix"
echo "$prefix"
