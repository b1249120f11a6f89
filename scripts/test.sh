#!/usr/bin/env bash
# SoftRaster's test command: installs what it needs, builds every preset that can be built on
# Linux (native, native-asan, mingw) and runs every test (the mingw binaries under Wine).
# Usage: scripts/test.sh [preset...]     (default: native native-asan mingw)
# Exit code 0 only if every build and every test passed.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,5p' "$0" | sed 's/^# \{0,1\}//'; exit 0
fi
presets=("$@")
[[ ${#presets[@]} -gt 0 ]] || presets=(native native-asan mingw)

scripts/install-deps.sh test || exit 1

# Wine: a prefix of our own inside build/, quiet, and no Mono/Gecko installer dialogs.
export WINEPREFIX="$root/build/wineprefix"
export WINEDEBUG=-all
export WINEDLLOVERRIDES="mscoree,mshtml="
jobs=$(nproc 2>/dev/null || echo 2)

declare -A result
start_all=$SECONDS
for preset in "${presets[@]}"; do
  echo "=== [$preset] configure + build"
  t0=$SECONDS
  if [[ "$preset" == mingw && ! -d "$WINEPREFIX" ]]; then
    echo "=== [$preset] creating the Wine prefix $WINEPREFIX"
    wineboot -i >/dev/null 2>&1 || true
    wineserver -w 2>/dev/null || true
  fi
  cfglog=$(mktemp)
  if ! cmake --preset "$preset" >"$cfglog" 2>&1; then
    cat "$cfglog"; rm -f "$cfglog"; result[$preset]="configure FAILED"; continue
  fi
  mv -f "$cfglog" "build/$preset/configure.log"
  if ! cmake --build --preset "$preset" -j "$jobs" >"build/$preset/build.log" 2>&1; then
    grep -E 'error|Error|FAILED' "build/$preset/build.log" | head -40
    result[$preset]="build FAILED"; continue
  fi
  if grep -q 'warning:' "build/$preset/build.log"; then
    echo "=== [$preset] compiler warnings (the build must be warning-free):"
    grep 'warning:' "build/$preset/build.log" | sort -u | head -20
    result[$preset]="warnings"; continue
  fi
  echo "=== [$preset] test"
  ctest --preset "$preset" 2>&1 | tee "build/$preset/ctest.log"
  rc=${PIPESTATUS[0]}
  # Catch2 prints its own count per binary; show them so the log proves which suites ran.
  if [[ -f "build/$preset/Testing/Temporary/LastTest.log" ]]; then
    awk '/^[0-9]+\/[0-9]+ Test: /{name=$3} /test cases/ && /passed|failed/ {print "    catch2 [" name "] " $0}' \
      "build/$preset/Testing/Temporary/LastTest.log"
  fi
  passed=$(grep -oE '[0-9]+ tests failed out of [0-9]+' "build/$preset/ctest.log" | tail -1 | awk '{print $6 - $1}')
  failed=$(grep -oE '[0-9]+ tests failed out of [0-9]+' "build/$preset/ctest.log" | tail -1 | awk '{print $1}')
  result[$preset]="${passed:-0} passed, ${failed:-?} failed ($((SECONDS - t0)) s)"
  [[ $rc -eq 0 ]] || result[$preset]+=" FAILED"
done

echo
echo "=== summary ($((SECONDS - start_all)) s)"
total_pass=0; total_fail=0; ok=1
for preset in "${presets[@]}"; do
  r=${result[$preset]:-"not run"}
  echo "  $preset: $r"
  if [[ "$r" =~ ^([0-9]+)\ passed,\ ([0-9]+)\ failed && "$r" != *FAILED* ]]; then
    total_pass=$((total_pass + BASH_REMATCH[1])); total_fail=$((total_fail + BASH_REMATCH[2]))
  else
    ok=0; total_fail=$((total_fail + 1))
  fi
done
echo "total: $total_pass passed, $total_fail failed"
[[ $ok -eq 1 && $total_fail -eq 0 ]]
