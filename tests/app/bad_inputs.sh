#!/usr/bin/env bash
# Every bad input gives exit code 2, a message naming the key, value and allowed range, and writes nothing.
# usage: bad_inputs.sh <spatula executable> <folder of bad scenes>
# Each scene's first line is "<!-- expect: MESSAGE -->"; MESSAGE must appear in the app's error output.
set -u
app=$1
folder=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
check() {   # name, expected message, command...
  local name=$1 expected=$2
  shift 2
  local status=0
  "$@" > stdout.txt 2> stderr.txt || status=$?
  if [ "$status" -ne 2 ]; then
    echo "FAIL $name: exit code $status, expected 2"; failures=$((failures + 1))
  elif ! grep -qF -- "$expected" stderr.txt; then
    echo "FAIL $name: message lacks '$expected':"; cat stderr.txt; failures=$((failures + 1))
  elif [ -n "$(ls -A | grep -v -e '^stdout.txt$' -e '^stderr.txt$')" ]; then
    echo "FAIL $name: wrote files:"; ls -A; failures=$((failures + 1))
  else
    echo "ok   $name: $(head -c 200 stderr.txt | tr '\n' ' ')"
  fi
  rm -f stdout.txt stderr.txt
}
for scene in "$folder"/*.xml; do
  expected=$(head -n 1 "$scene" | sed -e 's/^<!-- expect: //' -e 's/ -->$//')
  check "$(basename "$scene")" "$expected" "$app" "$scene"
done
check missing_file "cannot open input file '$work/none.xml'" "$app" "$work/none.xml"
check unknown_option "unknown option '--frobnicate'" "$app" --frobnicate
[ "$failures" -eq 0 ] && echo "all bad inputs rejected cleanly"
exit "$failures"
