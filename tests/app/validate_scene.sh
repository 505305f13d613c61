#!/usr/bin/env bash
# A scene of xml/ passes --validate-only in an empty directory, writing nothing. A scene that restarts from an
# earlier run's checkpoints (a pull-off study) must fail there for that reason alone: exit 2, naming the missing
# 'Loading/restart file' (every other check passed before it).
# usage: validate_scene.sh <spatula> <scene.xml>
set -u
app=$1
scene=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
status=0
OMPI_MCA_btl=self OMPI_MCA_pml=ob1 "$app" "$scene" --validate-only > stdout.txt 2> stderr.txt || status=$?
restart=$(sed -n 's/.*name="restart file" type="string" value="\([^"]\+\)".*/\1/p' "$scene")
if [ -n "$restart" ]; then
  expected="parameter 'Loading/restart file' = '$restart': no such file"
  [ "$status" -eq 2 ] && grep -qF "$expected" stderr.txt || { echo "expected exit 2 and '$expected', got $status:"; cat stderr.txt; exit 1; }
else
  [ "$status" -eq 0 ] || { echo "exit $status:"; cat stderr.txt; exit 1; }
  grep -q "is valid" stdout.txt || { echo "no 'is valid' line"; exit 1; }
fi
rm stdout.txt stderr.txt
[ -z "$(ls -A)" ] || { echo "validation wrote files:"; ls -A; exit 1; }
echo "ok: $(basename "$scene") (exit $status)"
