# Shared by the end-to-end tests (sourced, not run): log lines with elapsed time, a private Xvfb,
# an optional window manager, SoftRaster.exe started under Wine with its window found, the wait
# for its exit, and cleanup of exactly the processes the test started.
# Before sourcing, set e2e_name (the prefix of every log line). A script may define diagnose()
# to print more context when it fails. Timeouts (seconds) may be set before the calls:
# window_timeout (default 90: Wine's first start in a fresh prefix takes 20-40 s on a loaded
# machine), exit_timeout (default 15), poll_timeout (default 40) and poll_interval (default 0.3).

export WINEDEBUG=${WINEDEBUG:--all}
export WINEDLLOVERRIDES="mscoree,mshtml=" # no Mono / Gecko install dialogs (WINEPREFIX: as set)

e2e_t0=$(date +%s%N)
elapsed() { local ms=$(( ($(date +%s%N) - e2e_t0) / 1000000 )); printf '%d.%d' $((ms / 1000)) $((ms % 1000 / 100)); }
log() { echo "$e2e_name [$(elapsed) s]: $*"; }
fail() {
  echo "$e2e_name [$(elapsed) s]: FAIL: $*" >&2
  if declare -F diagnose >/dev/null; then diagnose >&2 || true; fi
  exit 1
}

# poll DESCRIPTION COMMAND...: runs COMMAND every poll_interval seconds until it succeeds; fails
# when the app exits first or poll_timeout seconds pass (naming ${last}, what COMMAND last saw).
poll() {
  local what=$1; shift
  local deadline=$(( $(date +%s) + ${poll_timeout:-40} ))
  while (( $(date +%s) < deadline )); do
    "$@" && return 0
    kill -0 "$app_pid" 2>/dev/null || fail "SoftRaster.exe exited while waiting for: $what"
    sleep "${poll_interval:-0.3}"
  done
  fail "timed out (${poll_timeout:-40} s) waiting for: $what (last: ${last:-})"
}

xvfb_pid="" wm_pid="" app_pid="" win="" private_prefix=""
e2e_cleanup() {
  # Only the processes this script started: the app (if still running), the WM and Xvfb, and
  # the wineserver of our private prefix.
  if [[ -n "$app_pid" ]] && kill -0 "$app_pid" 2>/dev/null; then kill "$app_pid" 2>/dev/null || true; fi
  if [[ -n "$private_prefix" ]]; then WINEPREFIX=$private_prefix wineserver -k 2>/dev/null || true; fi
  if [[ -n "$wm_pid" ]]; then kill "$wm_pid" 2>/dev/null || true; wait "$wm_pid" 2>/dev/null || true; fi
  if [[ -n "$xvfb_pid" ]]; then kill "$xvfb_pid" 2>/dev/null || true; wait "$xvfb_pid" 2>/dev/null || true; fi
  if [[ -n "$private_prefix" ]]; then rm -rf "$private_prefix"; fi
}
trap e2e_cleanup EXIT

# A Wine prefix of this test's own, so that its wineserver and desktop are started here, with
# this test's DISPLAY. In a shared prefix a console test (ctest -j) or an earlier run may have
# started the wineserver without a display, and a window then cannot be created (error 1400).
# The wineserver is per prefix directory, so a hard-linked copy of $WINEPREFIX (fast, no disk)
# gets its own; Wine replaces the registry files it saves (rename), never writes through the links.
if [[ -n "${WINEPREFIX:-}" && -f "$WINEPREFIX/system.reg" ]]; then
  private_prefix="${WINEPREFIX%/}-$e2e_name-$$"
  rm -rf "$private_prefix"
  cp -al "$WINEPREFIX" "$private_prefix" 2>/dev/null || cp -a "$WINEPREFIX" "$private_prefix"
  export WINEPREFIX=$private_prefix
fi

# start_xvfb FIRST LAST: a 1280x800 Xvfb on the first free display number in FIRST..LAST, exported
# as DISPLAY. Each test has its own range; another run on the same machine may still take the
# same free number at the same moment, so when our Xvfb dies at start the next number is tried.
start_xvfb() {
  local n display=""
  for n in $(seq "$1" "$2"); do
    [[ -e /tmp/.X11-unix/X$n || -e /tmp/.X$n-lock ]] && continue
    Xvfb ":$n" -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
    xvfb_pid=$!
    for _ in $(seq 100); do
      kill -0 "$xvfb_pid" 2>/dev/null || break
      DISPLAY=":$n" xdotool getdisplaygeometry >/dev/null 2>&1 && { display=":$n"; break; }
      sleep 0.1
    done
    [[ -n "$display" ]] && break
    kill "$xvfb_pid" 2>/dev/null || true; wait "$xvfb_pid" 2>/dev/null || true; xvfb_pid=""
  done
  [[ -n "$display" ]] || fail "could not start Xvfb on any display in :$1-:$2"
  export DISPLAY=$display
}

# start_wm: openbox, when installed (scripts/install-deps.sh installs it). Without a window manager
# nobody honours an iconify request (xdotool windowminimize does nothing); wm_pid stays empty.
start_wm() {
  command -v openbox >/dev/null || return 0
  openbox --sm-disable >/dev/null 2>&1 &
  wm_pid=$!
  for _ in $(seq 100); do xprop -root _NET_SUPPORTING_WM_CHECK 2>/dev/null | grep -q 'window id' && break; sleep 0.1; done
}

# start_app EXE ARGS...: runs EXE under Wine in the background (app_pid) and waits up to
# window_timeout for its visible window titled "SoftRaster..." (win).
start_app() {
  local exe=$1 rc deadline; shift
  wine "$exe" "$@" &
  app_pid=$!
  win=""
  deadline=$(( $(date +%s) + ${window_timeout:-90} ))
  while (( $(date +%s) < deadline )); do
    win=$(xdotool search --onlyvisible --name '^SoftRaster' 2>/dev/null | head -n1 || true)
    [[ -n "$win" ]] && return 0
    if ! kill -0 "$app_pid" 2>/dev/null; then
      wait "$app_pid" && rc=0 || rc=$?
      fail "SoftRaster.exe exited (code $rc) before showing a window"
    fi
    sleep 0.25
  done
  fail "no window named 'SoftRaster...' within ${window_timeout:-90} s"
}

# wait_exit WHAT: after WHAT (e.g. "Escape") the app must exit within exit_timeout with code 0.
wait_exit() {
  local rc deadline=$(( $(date +%s) + ${exit_timeout:-15} ))
  while kill -0 "$app_pid" 2>/dev/null && (( $(date +%s) < deadline )); do sleep 0.1; done
  kill -0 "$app_pid" 2>/dev/null && fail "SoftRaster.exe still running ${exit_timeout:-15} s after $1"
  wait "$app_pid" && rc=0 || rc=$?
  app_pid=""
  (( rc == 0 )) || fail "SoftRaster.exe exited with code $rc after $1 (expected 0)"
}
