#!/usr/bin/env bash
# The command line follows the conventions: --help prints the program's usage (not Kokkos'), each option once;
# --version prints the version, the commit, Trilinos' and Kokkos' versions, backend and threads; --kokkos-help prints
# Kokkos' options; none of them runs a scene or writes a file; a bad option exits 2 with the usage.
# usage: command_line.sh <spatula> <project version>
set -eu
app=$1
version=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }

"$app" --help > help.txt
head -n 1 help.txt | grep -q '^usage: spatula \[options\] \[scene.xml\]$' || fail "--help does not start with the usage"
! grep -qi kokkos.command.line help.txt || fail "--help prints Kokkos' options"
for option in --resume --validate-only --print-parameters --version --help --kokkos-help; do
  count=$(grep -o -- "$option\b" help.txt | wc -l)
  [ "$count" -eq 1 ] || fail "--help lists $option $count times"
done
"$app" -h | cmp -s - help.txt || fail "-h differs from --help"

"$app" --version > version.txt
grep -Eq "^spatula ${version//./\\.} \(commit ([0-9a-f]{7,}(-dirty)?|unknown)\)$" version.txt ||
  fail "--version's first line: $(head -n 1 version.txt)"
grep -Eq '^Trilinos [0-9]+\.[0-9]+.*, Kokkos [0-9]+\.[0-9]+\.[0-9]+: [A-Za-z]+ backend, [0-9]+ thread\(s\)$' version.txt ||
  fail "--version's libraries: $(tail -n 1 version.txt)"
[ "$(wc -l < version.txt)" -eq 2 ] || fail "--version prints more than its two lines"

"$app" --kokkos-help > kokkos.txt
grep -q -- '--kokkos-threads' kokkos.txt || fail "--kokkos-help lacks Kokkos' options"
! grep -q '^usage: spatula' kokkos.txt || fail "--kokkos-help prints the program's usage"

status=0
"$app" --frobnicate > out.txt 2> err.txt || status=$?
[ "$status" -eq 2 ] || fail "a bad option exits $status, not 2"
grep -q "unknown option '--frobnicate'" err.txt && grep -q '^usage: spatula' err.txt || fail "a bad option's message"
rm -f help.txt version.txt kokkos.txt out.txt err.txt
[ -z "$(ls -A)" ] || fail "wrote files: $(ls -A)"
echo "the usage, --version and --kokkos-help as they should be"
