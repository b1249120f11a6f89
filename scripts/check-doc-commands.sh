#!/usr/bin/env bash
# Runs every `softraster` command quoted in the fenced ```sh blocks of README.md and docs/*.md, at a
# small size, so that the docs cannot drift from the flags. The check fails when a command exits
# with 2 (a usage error: a flag or value the command no longer takes), crashes or hangs, or when a
# softraster line cannot be run as a plain command.
# Usage: scripts/check-doc-commands.sh SOFTRASTER [DOC.md ...]   (default: README.md docs/*.md)
#        scripts/check-doc-commands.sh --selftest SOFTRASTER     (the check must catch a bad flag)
#
# What is run: each line of a ```sh (or bash / shell) block whose command, after any VAR=value
# prefixes, is `softraster` or a path ending in /softraster. Variables set by earlier lines of the
# same block (`S=/path`, `CLOSE="--eye ..."`) are substituted; comments and anything after an
# unquoted | ; & < > are dropped. The arguments are then made small and local:
#   --width / --height                  -> --width 64 --height 48 (appended to every subcommand)
#   --frames / --warmup (bench, report) -> --frames 2 --warmup 1;  --rounds (report) -> --rounds 1
#   --out / --depth-out / --out-dir     -> files in a temporary folder (the commands run there)
#   --obj / --model PATH that does not exist -> the Debian file of the same name (bunny.obj:
#       glmark2-data; spider.obj, BoxTextured.glb: assimp-testmodels), else one of the same kind
#   --texture / --skybox, and compare's images, that do not exist -> images made by softraster itself
#   --shadow-size above 512             -> 512
# A flag kept on a subcommand that does not take it still exits 2: that is what is checked. Exit 1
# (the command ran but failed, e.g. a substituted model without the camera asked for) is listed,
# not failed.
# shellcheck disable=SC2016  # single-quoted $ and backquotes are Markdown / doc text, not for this shell
set -uo pipefail

if [[ ${1:-} == --selftest ]]; then
  sr=${2:?usage: check-doc-commands.sh --selftest SOFTRASTER}
  dir=$(mktemp -d)
  trap 'rm -rf "$dir"' EXIT
  self=$(cd "$(dirname "$0")" && pwd)/$(basename "$0")
  printf '# good\n\n```sh\nM=spider.obj\nsoftraster render --obj $M --out a.png   # fine\n```\n' >"$dir/good.md"
  printf '# bad\n\n```sh\nsoftraster render --out a.png\nsoftraster render --no-such-flag 3 --out b.png\n```\n' >"$dir/bad.md"
  printf '# bad\n\n```sh\nsoftraster render --frames 3\n```\n' >"$dir/wrongsub.md"
  fail=0
  bash "$self" "$sr" "$dir/good.md" >"$dir/good.log" 2>&1 || { echo "selftest: a good doc failed:"; cat "$dir/good.log"; fail=1; }
  for bad in bad wrongsub; do
    if bash "$self" "$sr" "$dir/$bad.md" >"$dir/$bad.log" 2>&1; then
      echo "selftest: $bad.md passed but has a usage error:"; cat "$dir/$bad.log"; fail=1
    elif ! grep -q "FAIL.*$bad.md:[0-9]*: exit 2" "$dir/$bad.log"; then
      echo "selftest: $bad.md failed without naming its line:"; cat "$dir/$bad.log"; fail=1
    fi
  done
  ((fail)) || echo "check-doc-commands selftest: passed (a good doc passes, an unknown flag and a flag on the wrong subcommand fail)"
  exit "$fail"
fi

sr=${1:?usage: check-doc-commands.sh SOFTRASTER [DOC.md ...]}
shift
root=$(cd "$(dirname "$0")/.." && pwd)
[[ $sr == /* ]] || sr=$(pwd)/$sr
[[ -x $sr ]] || { echo "check-doc-commands: $sr is not an executable" >&2; exit 1; }
docs=("$@")
if [[ ${#docs[@]} -eq 0 ]]; then
  docs=("$root/README.md")
  for f in "$root"/docs/*.md; do [[ -f $f ]] && docs+=("$f"); done
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The models the docs name, where Debian puts them; a missing one falls back to a file of its kind.
spider=/usr/share/assimp/models/OBJ/spider.obj
box=/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb
declare -A known=(
  [bunny.obj]=/usr/share/glmark2/models/bunny.obj
  [spider.obj]=$spider
  [BoxTextured.glb]=$box
  [BoxTextured.gltf]=/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf
)
model_for() { # a model path as the docs give it -> a file that exists (or the path unchanged)
  local p=$1 base=${1##*/} ext=${1##*.}
  if [[ -f $p ]]; then echo "$p"; return; fi
  if [[ $p != /* && -f $root/$p ]]; then echo "$root/$p"; return; fi
  if [[ -n ${known[$base]:-} && -f ${known[$base]} ]]; then echo "${known[$base]}"; return; fi
  case ${ext,,} in
    obj) [[ -f $spider ]] && { echo "     (no $p here: $spider instead)" >&2; echo "$spider"; return; } ;;
    gltf|glb) [[ -f $box ]] && { echo "     (no $p here: $box instead)" >&2; echo "$box"; return; } ;;
  esac
  echo "$p"
}
texture_file() {
  [[ -f $work/texture.png ]] || "$sr" render --quiet --width 16 --height 16 --out "$work/texture.png" >/dev/null 2>&1
  echo "$work/texture.png"
}
skybox_dir() {
  if [[ ! -d $work/skybox ]]; then
    mkdir -p "$work/skybox"
    for face in px nx py ny pz nz; do
      "$sr" render --quiet --width 16 --height 16 --out "$work/skybox/$face.png" >/dev/null 2>&1
    done
  fi
  echo "$work/skybox"
}

# split LINE: the shell words of one command line into WORDS (quotes removed); stops at an
# unquoted # (comment) or | ; & < > (the rest is not this command). SUBST=1 when the line uses
# command substitution, which this check does not run.
split() {
  local s=$1 i c q="" tok="" have=0 bs=$'\\'
  WORDS=(); SUBST=0
  for ((i = 0; i < ${#s}; i++)); do
    c=${s:i:1}
    if [[ -n $q ]]; then
      if [[ $c == "$q" ]]; then q=""
      elif [[ $q == '"' && ( $c == '`' || ( $c == '$' && ${s:i+1:1} == '(' ) ) ]]; then SUBST=1; tok+=$c
      elif [[ $q == '"' && $c == "$bs" ]]; then ((i++)); tok+=${s:i:1}
      else tok+=$c; fi
      continue
    fi
    case $c in
      "'" | '"') q=$c; have=1 ;;
      ' ' | $'\t') if ((have)); then WORDS+=("$tok"); tok=""; have=0; fi ;;
      "$bs") ((i++)); tok+=${s:i:1}; have=1 ;;
      '#') if ((have)); then tok+=$c; else break; fi ;;
      '|' | ';' | '&' | '<' | '>') break ;;
      '`') SUBST=1; tok+=$c; have=1 ;;
      '$') [[ ${s:i+1:1} == '(' ]] && SUBST=1; tok+=$c; have=1 ;;
      *) tok+=$c; have=1 ;;
    esac
  done
  ((have)) && WORDS+=("$tok")
}

# expand LINE: $NAME and ${NAME} replaced by the block's variables (VARS); UNKNOWN lists the others.
expand() {
  local s=$1 out="" name
  UNKNOWN=""
  while [[ $s =~ ^([^\$]*)\$(\{([A-Za-z_][A-Za-z0-9_]*)\}|([A-Za-z_][A-Za-z0-9_]*))(.*)$ ]]; do
    out+=${BASH_REMATCH[1]}
    name=${BASH_REMATCH[3]}${BASH_REMATCH[4]}
    s=${BASH_REMATCH[5]}
    if [[ -v VARS[$name] ]]; then out+=${VARS[$name]}; else UNKNOWN+=" \$$name"; fi
  done
  EXPANDED=$out$s
}

# Every line of every sh block: FILE<TAB>LINE<TAB>BLOCK<TAB>TEXT (continuation lines joined).
extract() {
  awk -v OFS='\t' '
    function flush() { if (text != "") print FILENAME, first, block, text; text = "" }
    FNR == 1 { inblock = 0; text = "" }
    /^[ \t]*```/ {
      if (!inblock) { inblock = 1; lang = $0; sub(/^[ \t]*```[ \t]*/, "", lang); sub(/[ \t].*$/, "", lang)
                      sh = (lang == "sh" || lang == "bash" || lang == "shell"); block++ }
      else { flush(); inblock = 0 }
      next
    }
    inblock && sh {
      line = $0; sub(/^[ \t]+/, "", line)
      if (text == "") first = FNR
      if (line ~ /\\$/) { sub(/\\$/, "", line); text = text line " "; next }
      text = text line; flush()
    }
' "$@"
}

# take: the value of the flag at args[i] (from --flag=value, or the next word, which it consumes).
take() { if ((hasValue)); then :; elif ((i + 1 < ${#args[@]})); then i=$((i + 1)); value=${args[i]}; else value=""; fi; }

declare -A VARS=()
current_block=""
ran=0; failed=0; notes=0; n=0
start=$SECONDS
while IFS=$'\t' read -r file line block text; do
  where="${file#"$root"/}:$line"
  if [[ "$file#$block" != "$current_block" ]]; then VARS=(); current_block="$file#$block"; fi
  expand "$text"
  split "$EXPANDED"
  [[ ${#WORDS[@]} -gt 0 ]] || continue
  # Leading VAR=value words: the whole line when nothing follows (kept for the block), else the
  # command's environment.
  envs=()
  while [[ ${#WORDS[@]} -gt 0 && ${WORDS[0]} =~ ^[A-Za-z_][A-Za-z0-9_]*= ]]; do
    envs+=("${WORDS[0]}"); WORDS=("${WORDS[@]:1}")
  done
  if [[ ${#WORDS[@]} -eq 0 ]]; then
    if ((SUBST == 0)); then for e in "${envs[@]}"; do VARS[${e%%=*}]=${e#*=}; done; fi
    continue
  fi
  cmd=${WORDS[0]}
  [[ $cmd == softraster || $cmd == */softraster ]] || continue
  if ((SUBST)) || [[ -n $UNKNOWN ]]; then
    why=""
    [[ -n $UNKNOWN ]] && why="variables not set in its block:$UNKNOWN"
    ((SUBST)) && why="${why:+$why; }command substitution"
    echo "FAIL $where: cannot run as a plain command ($why): $text"
    failed=$((failed + 1)); continue
  fi
  args=("${WORDS[@]:1}")
  sub=""
  [[ ${#args[@]} -gt 0 && ${args[0]} =~ ^(render|bench|report)$ ]] && sub=${args[0]}
  compare=0
  [[ ${#args[@]} -gt 0 && ${args[0]} == compare ]] && compare=1
  n=$((n + 1))
  out=()
  i=0
  while ((i < ${#args[@]})); do
    a=${args[i]}; flag=$a; value=""; hasValue=0
    if [[ $a == --*=* ]]; then flag=${a%%=*}; value=${a#*=}; hasValue=1; fi
    case $flag in
      --width | --height) [[ -n $sub ]] && { take; i=$((i + 1)); continue; } ;;
      --frames | --warmup) [[ $sub == bench || $sub == report ]] && { take; i=$((i + 1)); continue; } ;;
      --rounds) [[ $sub == report ]] && { take; i=$((i + 1)); continue; } ;;
      --out | --depth-out) take; out+=("$flag" "$work/$n-${value##*/}"); i=$((i + 1)); continue ;;
      --out-dir) take; out+=("$flag" "$work/$n-out"); i=$((i + 1)); continue ;;
      --obj | --model) take; out+=("$flag" "$(model_for "$value")"); i=$((i + 1)); continue ;;
      --texture) take; [[ -f $value || -f $root/$value ]] || value=$(texture_file); out+=("$flag" "$value"); i=$((i + 1)); continue ;;
      --skybox) take; [[ -d $value || -d $root/$value ]] || value=$(skybox_dir); out+=("$flag" "$value"); i=$((i + 1)); continue ;;
      --shadow-size) take; [[ $value =~ ^[0-9]+$ ]] && ((value > 512)) && value=512; out+=("$flag" "$value"); i=$((i + 1)); continue ;;
      --map) take; out+=("$flag" "$work/$n-${value##*/}"); i=$((i + 1)); continue ;;
    esac
    # compare's images: one softraster made, when the doc's do not exist here.
    if ((compare && i > 0)) && [[ $a != -* && ! -f $a && ! -f $root/$a ]]; then out+=("$(texture_file)"); i=$((i + 1)); continue; fi
    out+=("$a")
    i=$((i + 1))
  done
  if [[ -n $sub ]]; then
    out+=(--width 64 --height 48)
    [[ $sub == bench || $sub == report ]] && out+=(--frames 2 --warmup 1)
    [[ $sub == report ]] && out+=(--rounds 1)
  fi
  log=$work/$n.log
  (cd "$work" && env "${envs[@]}" timeout 60 "$sr" "${out[@]}") </dev/null >"$log" 2>&1
  rc=$?
  ran=$((ran + 1))
  if [[ $rc -eq 2 || $rc -ge 124 ]]; then
    why="exit $rc"
    [[ $rc -eq 2 ]] && why="exit 2 (usage error)"
    [[ $rc -eq 124 ]] && why="exit 124 (timed out after 60 s)"
    echo "FAIL $where: $why: $text"
    echo "     ran: softraster ${out[*]}"
    sed 's/^/     | /' "$log" | tail -n 5
    failed=$((failed + 1))
  elif [[ $rc -ne 0 ]]; then
    echo "note $where: exit $rc (ran, but failed; not a usage error): $text"
    sed 's/^/     | /' "$log" | tail -n 2
    notes=$((notes + 1))
  else
    echo "ok   $where: $text"
  fi
done < <(extract "${docs[@]}")

echo "check-doc-commands: $ran softraster commands from ${#docs[@]} files run in $((SECONDS - start)) s:" \
     "$failed failed, $notes ran with exit 1"
if ((ran == 0 && failed == 0)); then
  echo "check-doc-commands: no softraster command found in a sh block (the extraction is broken?)"
  exit 1
fi
((failed == 0))
