#!/usr/bin/env bash
# Stress test of SoftRaster.exe under Xvfb + Wine + openbox: identical rounds (3) of rapid
# resizes (1 x 1, very wide, very tall, larger than the screen, a 0 height the WM may refuse),
# minimise / restore (windowminimize, windowactivate, windowmap, resizes while iconic) and mode
# keys in between. Passes when the demo survives, renders again after each round (the title's
# frame counter advances and a screenshot at the asked size is not blank), its memory, threads
# and file descriptors do not grow from one round to the next, and Esc exits with code 0.
# Usage: demo_stress.sh <path/to/SoftRaster.exe> [artifacts dir (default build/artifacts)]
# Knobs (environment): SR_STRESS_ROUNDS (default 3, at least 2), SR_STRESS_THREADS (default 2).
set -euo pipefail

exe=${1:?usage: demo_stress.sh <SoftRaster.exe> [artifacts dir]}
artifacts=${2:-build/artifacts}/demo_stress
rounds=${SR_STRESS_ROUNDS:-3}
threads=${SR_STRESS_THREADS:-2}
window_timeout=90  # Wine's first start in a fresh prefix can take 20-40 s on a loaded machine
poll_timeout=40    # every other wait: poll until the condition holds, at most this long
exit_timeout=15
settle_seconds=3   # after a round: let queued messages drain and freed memory go back
# Memory bounds (VmRSS of the Wine process, KiB). See "Memory" below for the reasoning.
round_growth_kib=$((16 * 1024))
slack_kib=$((32 * 1024))

[[ -f "$exe" ]] || { echo "demo_stress: $exe not found" >&2; exit 1; }
(( rounds >= 2 )) || { echo "demo_stress: SR_STRESS_ROUNDS must be at least 2" >&2; exit 1; }
exe=$(readlink -f "$exe")
rm -rf "$artifacts"
mkdir -p "$artifacts"

e2e_name=demo_stress
source "$(dirname "$0")/xsession.sh"
# On failure: what X knows about our window and every SoftRaster window, and the app's state.
diagnose() {
  [[ -n "${win:-}" && -n "${DISPLAY:-}" ]] || return 0
  echo "--- window $win: $(xdotool getwindowname "$win" 2>&1), $(xwininfo -id "$win" 2>&1 | grep -E 'Map State|geometry|error' | tr -s ' \n' ' ')"
  xprop -id "$win" WM_STATE _NET_WM_STATE 2>&1 | tr -s '\t\n' '  '; echo
  echo "--- SoftRaster windows: $(xdotool search --name SoftRaster 2>/dev/null | tr '\n' ' ') (visible: $(xdotool search --onlyvisible --name SoftRaster 2>/dev/null | tr '\n' ' '))"
  echo "--- focus: $(xdotool getwindowfocus 2>&1); app alive: $(alive && echo yes || echo no)"
  [[ -n "${unix_pid:-}" && -r /proc/$unix_pid/status ]] && grep -E 'State|VmRSS|Threads' "/proc/$unix_pid/status" | tr -s '\t\n' '  '; echo
}
gt() { awk -v a="$1" -v b="$2" 'BEGIN{exit !(a > b)}'; }

# --- A private X display (:191-:240, apart from the other end-to-end tests' ranges) -----------
start_xvfb 191 240
# The window manager honours iconify requests and sends the app its size; without one the
# minimise operations are skipped.
start_wm
log "Xvfb on $DISPLAY ($(xdotool getdisplaygeometry | tr ' ' x)), window manager: $([[ -n "$wm_pid" ]] && echo openbox || echo "none: minimise steps skipped")"

# --- Helpers -----------------------------------------------------------------------------------
x() { timeout 10 xdotool "$@" >/dev/null 2>&1 || true; } # storm operations: never hang, never fail
alive() { kill -0 "$app_pid" 2>/dev/null; }
shot() { local f="$artifacts/$1.png"; import -window "$win" "$f" 2>/dev/null || return 1; echo "$f"; }
size_of() { convert "$1" -format '%w %h\n' info:; }
stddev() { convert "$1" -format '%[fx:standard_deviation]' info:; }
# The title's frame counter ("... — frame 12,345 — ..."); empty when not found.
title_frames() {
  local t; t=$(xdotool getwindowname "$win" 2>/dev/null || true)
  [[ "$t" =~ frame\ ([0-9,]+) ]] && echo "${BASH_REMATCH[1]//,/}"
}
poll() { # poll DESCRIPTION COMMAND...: every 0.5 s until it succeeds or poll_timeout passes
  local what=$1; shift
  local deadline=$(( $(date +%s) + poll_timeout ))
  while (( $(date +%s) < deadline )); do
    "$@" && return 0
    alive || fail "SoftRaster.exe exited while waiting for: $what"
    sleep 0.5
  done
  fail "timed out (${poll_timeout} s) waiting for: $what (last: ${last:-})"
}
wm_state() { xprop -id "$win" WM_STATE 2>/dev/null | grep -o 'state: [A-Za-z]*' || true; }
focus() {
  if [[ -n "$wm_pid" ]]; then timeout 10 xdotool windowactivate --sync "$win" 2>/dev/null || true; fi
  timeout 10 xdotool windowfocus --sync "$win" 2>/dev/null || true
}
# Memory and resources of the Wine process that runs SoftRaster.exe: "rss_kib anon_kib threads fds".
sample() {
  local rss anon thr fds
  rss=$(awk '/^VmRSS:/{print $2}' "/proc/$unix_pid/status")
  anon=$(awk '/^RssAnon:/{print $2}' "/proc/$unix_pid/status")
  thr=$(awk '/^Threads:/{print $2}' "/proc/$unix_pid/status")
  fds=$(ls "/proc/$unix_pid/fd" 2>/dev/null | wc -l)
  echo "$rss $anon $thr $fds"
}
mib() { awk -v k="$1" 'BEGIN{printf "%.1f MiB", k / 1024}'; }

# --- Start the demo and wait for its window ---------------------------------------------------
start_app "$exe" --width 640 --height 480 --threads "$threads"
# Wine sets _NET_WM_PID to the Unix process that runs the .exe (not the `wine` launcher).
unix_pid=$(xdotool getwindowpid "$win" 2>/dev/null || true)
[[ -n "$unix_pid" && -r /proc/$unix_pid/status ]] || fail "no /proc entry for the window's process (pid '${unix_pid}')"
tr '\0' ' ' <"/proc/$unix_pid/cmdline" | grep -qi 'SoftRaster.exe' || fail "pid $unix_pid is not SoftRaster.exe: $(tr '\0' ' ' <"/proc/$unix_pid/cmdline")"
log "window $win of pid $unix_pid (--threads $threads): '$(xdotool getwindowname "$win")'"

# rendering SIZE NAME: the picture is back at SIZE ("W H"), not blank, the title's frame counter
# has moved on by at least 10 frames since $frames_ref, and when $reference is set the picture
# matches it (under 1% of the pixels differ by more than 3%: same view, same modes).
reference=""
rendering() {
  local want=$1 name=$2 f w h s n ae=0
  n=$(title_frames); f=$(shot "$name") || return 1
  read -r w h < <(size_of "$f"); s=$(stddev "$f")
  if [[ -n "$reference" ]]; then ae=$(compare -metric AE -fuzz 3% "$reference" "$f" null: 2>&1 || true); fi
  last="$w x $h, stddev $s, frame ${n:-?} (was $frames_ref)${reference:+, $ae pixels differ from the warm-up}"
  [[ -n "$n" && "$w $h" == "$want" ]] && (( n >= frames_ref + 10 )) && gt "$s" 0.05 &&
    [[ "$ae" =~ ^[0-9]+$ ]] && (( ae < w * h / 100 ))
}
# The modes (the title after "tris — "): back to the start ones, one key at a time (keys sent
# while the window is minimised or unfocused are lost, so the storm's count is no guide); then R.
default_modes="cull none | phong | trilinear | exact | ssaa 4 | shadows" # --quality balanced and the built-in scene's shadows, the demo default
modes_now() { local t; t=$(xdotool getwindowname "$win" 2>/dev/null || true); echo "${t#* tris — }"; }
reset_modes() {
  local m k i
  focus
  for i in $(seq 40); do
    m=$(modes_now)
    if [[ "$m" == "$default_modes" ]]; then x key r; return 0; fi
    case $m in
      *"| help"*) k=F1 ;; *"depth view"*) k=z ;; *wireframe*) k=l ;;
      "cull none | phong | trilinear |"*) k=p ;; "cull none | phong |"*) k=t ;;
      "cull none |"*) k=m ;; *) k=c ;;
    esac
    x key "$k"; sleep 0.3
    (( i % 10 == 0 )) && focus
  done
  shot modes-stuck >/dev/null || true
  fail "could not bring the modes back to '$default_modes' (title: '$(xdotool getwindowname "$win" 2>/dev/null)', $(wm_state), focus $(xdotool getwindowfocus 2>/dev/null), window $win)"
}
restore_and_check() { # NAME: back to a normal 640 x 480 window that renders
  local name=$1
  if [[ -n "$wm_pid" ]]; then
    x windowactivate "$win"; x windowmap "$win"
    # Normal, or viewable without WM_STATE: an external windowmap racing openbox's iconify can
    # leave the window mapped on the root but no longer managed (the WM's bookkeeping, not the
    # demo's; later minimise operations then do nothing, the resizes and keys still apply).
    normal() {
      last="$(wm_state) / $(xwininfo -id "$win" 2>/dev/null | grep -o 'Map State: [A-Za-z]*')"
      [[ "$last" == "state: Normal / "* || "$last" == " / Map State: IsViewable" ]] || { x windowactivate "$win"; return 1; }
    }
    poll "the window to be restored (WM_STATE Normal)" normal
    [[ "$last" == "state: Normal / "* ]] || { unmanaged=$((unmanaged + 1)); log "$name: openbox no longer manages the window ($last)"; }
  fi
  x windowsize "$win" 640 480
  reset_modes
  frames_ref=$(title_frames); frames_ref=${frames_ref:-0}
  poll "rendering at 640 x 480 after $name" rendering "640 480" "$name"
}

# --- 1. Warm-up: every mode once, so lazily built state exists before the first sample --------
# Each mode key goes round its whole cycle (C 3, M 4, T 3, P 4, L 2, Z 2, F1 2 states); the
# picture after reset_modes is the reference for the rounds.
frames_ref=0
poll "the first frames (640 x 480, not blank)" rendering "640 480" warmup
focus
for k in c c c m m m m t t t p p p p l l z z F1 F1; do x key "$k"; sleep 0.1; done
reset_modes
frames_ref=$(title_frames); frames_ref=${frames_ref:-0}
poll "rendering after the warm-up keys" rendering "640 480" warmup-keys
reference="$artifacts/warmup-keys.png"
sleep "$settle_seconds"
read -r rss0 anon0 thr0 fd0 < <(sample)
log "warm-up: frame $(title_frames), VmRSS $(mib "$rss0"), RssAnon $(mib "$anon0"), $thr0 threads, $fd0 fds"

# --- 2. The storm: the same operation list every round ------------------------------------------
# size W H | min | act (windowactivate) | map (windowmap) | key K | pause S. No operation waits
# for the previous one to take effect; the pauses (0-0.3 s) vary the interleaving with rendering.
# Sizes: 1 x 1, a 0 height / width (X refuses 0, xdotool then fails: the WM's or Wine's minimum
# applies instead), 1-pixel strips, very wide / tall, larger than the 1280 x 800 screen, ordinary.
# Mode keys: whole cycles per round, W then R; keys that reach a minimised window are lost, so
# reset_modes brings back the warm-up's modes and view after each round.
ops=(
  "size 1 1" "size 640 480" "key c" "size 3000 40" "pause 0.1" "size 40 2000" "min" "act"
  "size 2500 1600" "key z" "size 1 300" "pause 0.05" "size 300 1" "size 1000 0" "key F1" "min"
  "size 200 150" "map" "size 0 200" "key m" "size 1279 799" "pause 0.2" "size 7 5" "min" "min"
  "act" "key t" "size 1600 1000" "size 2 2" "size 900 500" "key F1" "min" "size 320 240" "act"
  "pause 0.3" "size 1 1" "key w" "min" "map" "size 4000 100" "size 100 4000" "key p" "pause 0.1"
  "size 1920 1080" "size 640 480" "min" "act" "key l" "size 50 50" "size 3 1000" "key c"
  "min" "pause 0.1" "map" "act" "size 1000 3" "key z" "size 2048 2048" "pause 0.2" "size 123 457"
  "key r" "min" "size 800 600" "act" "size 1 1" "size 1280 800" "key m" "min" "act" "key t"
  "size 5000 5000" "pause 0.1" "size 16 9" "key p" "key p" "key p" "min" "map" "key c" "key m"
  "size 1 2" "key m" "min" "key t" "act" "size 33 4000" "key l" "size 640 480"
)
max_area=0
for op in "${ops[@]}"; do
  read -r verb a b <<<"$op"
  if [[ $verb == size ]]; then
    w=$(( a > 8192 ? 8192 : a )) h=$(( b > 8192 ? 8192 : b )) # FrameBuffer::kMaxDimension
    (( w * h > max_area )) && max_area=$((w * h))
  fi
done

run_op() {
  local verb=$1 a=${2:-} b=${3:-}
  case $verb in
    size) x windowsize "$win" "$a" "$b" ;;
    min) [[ -n "$wm_pid" ]] && x windowminimize "$win" ;;
    act) x windowactivate "$win" ;;
    map) x windowmap "$win" ;;
    key) x key "$a" ;;
    pause) sleep "$a" ;;
  esac
  return 0
}

declare -a rss anon thr fds
unmanaged=0
total_ops=0
storm_start=$(date +%s%N)
for round in $(seq 1 "$rounds"); do
  f_start=$(title_frames)
  r0=$(date +%s%N)
  # Paced (0.15 s after each operation: the demo reaches and renders every size), then fast (the
  # window manager and Wine coalesce and reorder what they can).
  for pace in 0.15 0; do
    for i in "${!ops[@]}"; do
      # shellcheck disable=SC2086 # the operation's words are its arguments
      run_op ${ops[$i]}
      [[ $pace == 0 ]] || sleep "$pace"
      total_ops=$((total_ops + 1))
      alive || { wait "$app_pid" && rc=0 || rc=$?; fail "SoftRaster.exe died (code $rc) at round $round, operation $i: ${ops[$i]}"; }
    done
  done
  storm_ms=$(( ($(date +%s%N) - r0) / 1000000 ))
  f_end=$(title_frames)
  restore_and_check "round-$round"
  sleep "$settle_seconds"
  read -r rss[$round] anon[$round] thr[$round] fds[$round] < <(sample)
  log "round $round: $((2 * ${#ops[@]})) operations in $((storm_ms / 1000)).$((storm_ms % 1000 / 100)) s, title frames ${f_start:-?} -> ${f_end:-?} during the storm, rendering again ($last); VmRSS $(mib "${rss[$round]}"), RssAnon $(mib "${anon[$round]}"), ${thr[$round]} threads, ${fds[$round]} fds"
done
storm_s=$(( ($(date +%s%N) - storm_start) / 1000000000 ))

# --- 3. Memory and resources -------------------------------------------------------------------
# Round 1 reaches every size the list asks for (its paced pass), so it sets the high-water mark of
# everything that legitimately keeps its largest size: the FrameBuffer reuses its allocation when
# the new size fits (colour + depth, 8 bytes per pixel), the render context's scratch vectors keep
# their capacity, Wine's window surface follows the window. (Wine clamps a Win32 window to its
# maximum tracking size, about the screen, so the 5000 x 5000 X window gives a ~1280 x 800
# client area.) Later rounds repeat the same list, so a working program ends them where round 1
# ended; what is left is heap fragmentation and X / Wine caches, a few MiB. Bound: 16 MiB
# (round_growth_kib) per round after round 1. A round resizes 68 times (34 sizes, twice): a leak
# of one 640 x 480 back buffer (2.4 MiB with depth) per resize would add ~160 MiB, one leaked
# 64 KiB block per resize (a 128 x 128 frame, a bitmap, a DC's state) ~4 MiB per round, which the
# 16 MiB bound does not see in one round but would in the sum over rounds, so that is checked too
# (at most 16 MiB over all rounds after the first). Threads and file descriptors must not grow
# (a render pool or a DC recreated per resize would show). Against the warm-up, the growth must
# stay within the largest frame the list asks for (12 bytes per pixel: colour, depth and Wine's
# window surface) plus 32 MiB (slack_kib). GDI objects are not counted: Wine's GetGuiResources is
# a stub that returns 0; the demo creates one font and uses a CS_OWNDC DC and StretchDIBits from
# the FrameBuffer's memory, with no bitmap or DC per frame or per resize.
hw_kib=$(( max_area * 12 / 1024 + slack_kib ))
growth_total=$(( rss[rounds] - rss0 ))
log "VmRSS: warm-up $(mib "$rss0"), after rounds 1-$rounds: $(for r in $(seq 1 "$rounds"); do printf '%s, ' "$(mib "${rss[$r]}")"; done)high-water bound $(mib "$hw_kib") (largest asked frame $max_area px)"
for r in $(seq 2 "$rounds"); do
  g=$(( rss[r] - rss[r - 1] ))
  (( g <= round_growth_kib )) || fail "VmRSS grew by $(mib "$g") in round $r (bound $(mib "$round_growth_kib")): memory leaks per operation"
  (( thr[r] <= thr[1] )) || fail "threads grew from ${thr[1]} (round 1) to ${thr[$r]} (round $r)"
  (( fds[r] <= fds[1] + 2 )) || fail "file descriptors grew from ${fds[1]} (round 1) to ${fds[$r]} (round $r)"
done
g=$(( rss[rounds] - rss[1] ))
(( g <= round_growth_kib )) || fail "VmRSS grew by $(mib "$g") from round 1 to round $rounds (bound $(mib "$round_growth_kib"))"
(( growth_total <= hw_kib )) || fail "VmRSS grew by $(mib "$growth_total") from the warm-up (bound $(mib "$hw_kib"))"
(( thr[rounds] <= thr0 )) || fail "threads grew from $thr0 (warm-up) to ${thr[$rounds]}"

# --- 4. Still rendering: the counter keeps moving over 2 s ------------------------------------
n0=$(title_frames); sleep 2; n1=$(title_frames)
(( n1 > n0 )) || fail "the frame counter stopped at $n0 after the storm"
log "rendering after $total_ops operations in $storm_s s: frame $n0 -> $n1 in 2 s"

# --- 5. Escape quits with exit code 0 ----------------------------------------------------------
focus
x key Escape
wait_exit Escape
log "Escape -> exit code 0. PASS ($total_ops operations, screenshots in $artifacts)"
