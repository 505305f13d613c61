#!/usr/bin/env bash
# ParaView opens the default scene's mesh and states (the output app_default_scene leaves in <work>) and they carry
# their arrays; skipped (exit 77) where pvbatch or xvfb-run is not installed.
# usage: default_scene_in_paraview.sh <source dir> <work>
set -eu
source_dir=$1
work=$2
if ! command -v pvbatch > /dev/null || ! command -v xvfb-run > /dev/null; then
  echo "pvbatch/xvfb-run not installed: ParaView's reading of the output not checked" >&2
  exit 77
fi
[ -s "$work/spatula-output/mesh_states.xmf" ] || { echo "no default scene output in $work"; exit 1; }
bash "$source_dir/scripts/render.sh" "$source_dir/tests/app/check_xdmf_opens.py" "$work/spatula-output"
