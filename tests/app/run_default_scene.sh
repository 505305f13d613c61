#!/usr/bin/env bash
# The app runs its embedded default scene with no arguments and writes the expected files, which ParaView opens.
# usage: run_default_scene.sh <spatula> <source dir>
set -eu
app=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$app" > log.txt
for file in scene.xml mesh.h5 mesh.xmf mesh_contact.xmf mesh_summary.txt mesh_summary.csv; do
  [ -s "spatula-output/$file" ] || { echo "missing spatula-output/$file"; exit 1; }
done
[ ! -e spatula-output.partial ] || { echo "staging directory left behind"; exit 1; }
grep -q "contact area A_c" log.txt
# The echoed scene is itself a valid scene.
"$app" spatula-output/scene.xml --validate-only
if command -v pvbatch > /dev/null && command -v xvfb-run > /dev/null; then
  xvfb-run -a pvbatch "$source_dir/tests/app/check_xdmf_opens.py" spatula-output 2>&1 | grep -v -e '^$' -e 'WARN'
else
  echo "pvbatch/xvfb-run not installed: skipped the ParaView check" >&2
  exit 77
fi
