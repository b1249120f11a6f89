#!/usr/bin/env bash
# Installs the Debian packages SoftRaster needs, only those missing (apt-get, via sudo if not root).
# Usage: scripts/install-deps.sh [build|test|demo]...   (default: test, which includes build)
set -euo pipefail

build_pkgs=(cmake ninja-build g++ catch2 libstb-dev libtinyobjloader-dev nlohmann-json3-dev
            libmeshoptimizer-dev libdraco-dev libwebp-dev libavif-dev   # glTF decoders (cmake/Codecs.cmake)
            g++-mingw-w64-x86-64-posix
            dpkg-dev)   # apt-get source / dpkg-source: scripts/build-mingw-deps.sh builds the decoders for MinGW
wine_pkgs=(wine wine64)
x11_pkgs=(xvfb xdotool imagemagick x11-utils openbox)
test_pkgs=(clang libclang-rt-14-dev   # libFuzzer for the fuzz targets
           assimp-utils assimp-testmodels   # glTF test files and an independent loader to check ours
           gltfpack                         # glTF as pipelines make it: quantized, meshopt, instanced
           glmark2-data)                    # the bunny (bunny.obj), a real model the loader tests read

want=()
for what in "${@:-test}"; do
  case "$what" in
    build) want+=("${build_pkgs[@]}") ;;
    demo)  want+=("${build_pkgs[@]}" "${wine_pkgs[@]}" "${x11_pkgs[@]}") ;;
    test)  want+=("${build_pkgs[@]}" "${wine_pkgs[@]}" "${x11_pkgs[@]}" "${test_pkgs[@]}") ;;
    -h|--help) sed -n '2,3p' "$0" | sed 's/^# //'; exit 0 ;;
    *) echo "install-deps.sh: unknown set '$what' (expected build, test or demo)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${want[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
# De-duplicate while keeping the order.
mapfile -t missing < <(printf '%s\n' "${missing[@]}" | awk 'NF && !seen[$0]++')

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all packages present"
  exit 0
fi

if ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: missing packages (${missing[*]}) and no apt-get: install them by hand" >&2
  exit 1
fi
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then sudo=(sudo); else
    echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1
  fi
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
echo "install-deps: done"
