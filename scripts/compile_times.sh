#!/usr/bin/env bash
# Where a build's compile time goes: compiles every C++ translation unit of a configured build
# folder again, with that object's own flags (its flags.make), into a scratch file, two at a
# time, and prints the seconds each took, slowest first, then the sum per top-level folder.
#   scripts/compile_times.sh build-sanitize        every translation unit (about 15 min there)
#   scripts/compile_times.sh build tests/flowtex   only the sources under tests/flowtex
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${1:?usage: scripts/compile_times.sh BUILD_DIR [SOURCE_PREFIX]}
prefix=${2:-}
[ -d "$build" ] || { echo "compile_times.sh: no build folder '$build'" >&2; exit 2; }
list=$(mktemp)
times=$(mktemp)
trap 'rm -f "$list" "$times"' EXIT
# Each object: its target's folder (with flags.make) and its source, from the object's path.
(cd "$build" && find . -name '*.cpp.o' -path '*CMakeFiles*' | sed 's|^\./||') |
  while read -r object; do
    dir=${object%%.dir/*}.dir
    source=${object#*.dir/}
    source=${source%.o}
    source=${dir%%/CMakeFiles/*}/${source//__/..}
    if [ -f "$root/$source" ] && [[ $source == $prefix* ]]; then echo "$dir $source"; fi
  done >"$list"
time_one() {  # DIR SOURCE BUILD ROOT
  local flags start end out
  flags=$(sed -n 's/^CXX_DEFINES = //p; s/^CXX_INCLUDES = //p; s/^CXX_FLAGS = //p' \
    "$3/$1/flags.make" | tr '\n' ' ')
  out=$(mktemp)
  start=$(date +%s.%N)
  (cd "$3" && eval g++ "$flags" -c "$4/$2" -o "$out") >/dev/null 2>&1 || true
  end=$(date +%s.%N)
  rm -f "$out"
  printf '%7.1f %s\n' "$(awk -v a="$start" -v b="$end" 'BEGIN {print b - a}')" "$2"
}
export -f time_one
xargs -P 2 -L 1 bash -c 'time_one "$0" "$1" "'"$build"'" "'"$root"'"' <"$list" | sort -rn >"$times"
cat "$times"
echo "--- per folder (seconds, files)"
awk '{split($2, p, "/"); s[p[1]] += $1; n[p[1]]++; t += $1}
     END {for (k in s) printf "%8.0f %4d %s\n", s[k], n[k], k; printf "%8.0f %4d total\n", t, NR}' \
  "$times" | sort -rn
