#!/usr/bin/env bash
# The program never deletes or replaces what it did not write, and refuses a restart that cannot be used, before any
# computation: every refusal exits 2 with a message naming the key, and leaves the directory exactly as it was.
# usage: safe_outputs.sh <spatula>
set -u
app=$1
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
cd "$work"
export OMPI_MCA_btl=self OMPI_MCA_pml=ob1   # a single-process MPI start without network transports (faster)
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
snapshot() {   # every path, and each file's size and modification time
  find . -path ./stdout.txt -prune -o -path ./stderr.txt -prune -o -type f -printf '%p %s %T@\n' -o -printf '%p\n' |
    sort | md5sum
}
scene() {   # output directory, extra Loading parameters, extra sublists, file (scene.xml), type, extra Output keys
  cat > "${4:-scene.xml}" <<XML
<ParameterList>
  <ParameterList name="Loading"><Parameter name="type" type="string" value="${5:-none}"/>${2:-}</ParameterList>
  <ParameterList name="Output"><Parameter name="directory" type="string" value="$1"/>
    <Parameter name="write mesh" type="bool" value="false"/>${6:-}</ParameterList>
  ${3:-}
</ParameterList>
XML
}
refused() {   # name, expected message; runs scene.xml (or $3) and checks nothing changed
  local before status=0
  before=$(snapshot)
  "$app" "${3:-scene.xml}" > stdout.txt 2> stderr.txt || status=$?
  if [ "$status" -ne 2 ]; then fail "$1: exit $status, expected 2"; cat stderr.txt
  elif ! grep -qF -- "$2" stderr.txt; then fail "$1: message lacks '$2':"; cat stderr.txt
  elif [ "$(snapshot)" != "$before" ]; then fail "$1: the directory changed"
  else echo "ok   $1: $(head -c 220 stderr.txt)"; fi
  rm -f stdout.txt stderr.txt
}

# Things of the user's, each refused as an output directory and left untouched.
mkdir user-folder && echo "a user's data" > user-folder/data.txt
echo "a user's file" > user-file
mkdir -p result.partial && echo "not ours" > result.partial/notes.txt
ln -s . link-to-here
scene user-folder ""; refused "existing foreign folder" "exists and was not written by spatula"
scene user-file ""; refused "existing regular file" "exists and is not a directory"
scene result ""; refused "foreign folder at the staging name" "result.partial' exists and was not written by spatula"
scene link-to-here ""; refused "symbolic link to the working directory" "it is the working directory"
scene "$work" ""; refused "working directory by its absolute path" "it is the working directory"
scene "$(dirname "$work")" ""; refused "parent of the working directory" "it contains the working directory"
mkdir home && scene "$work/home" ""; HOME="$work/home" refused "home directory" "it is the home directory"
scene "/proc/spatula-output" ""; refused "a place where nothing can be made" "nothing can be created in '/proc'"
scene "$(printf 'x%.0s' $(seq 300))" ""; refused "a name too long" "a name in it is too long (300 characters"
[ "$(cat user-folder/data.txt)" = "a user's data" ] && [ "$(cat user-file)" = "a user's file" ] || fail "user data changed"

# A result of ours is replaced by the next run (and only with Output/overwrite, the default); the scene file and the
# restart file must not lie inside what the run replaces.
scene "ours/" ""
"$app" scene.xml > /dev/null 2>&1 || fail "first run into ours/"
[ -f ours/.spatula-output ] && [ -f ours/scene.xml ] && [ ! -e ours.partial ] && [ ! -e ours/.partial ] || fail "ours/ not written as a marked directory"
"$app" scene.xml > /dev/null 2>&1 || fail "second run replacing ours/"
cp scene.xml ours/my-scene.xml
refused "scene file inside the output directory" "would replace the scene file" ours/my-scene.xml
scene ours "" "" no-overwrite.xml none '<Parameter name="overwrite" type="bool" value="false"/>'
refused "overwrite = false and an earlier result" "holds an earlier result and 'Output/overwrite' is false" no-overwrite.xml

# Restart files: a checkpoint of a short coarse rotation, then restarts it cannot serve.
scene rotation '<Parameter name="theta_y" type="double" value="6"/><Parameter name="checkpoints at theta_y" type="string" value="5.5"/>' "" rotation.xml rotation
"$app" rotation.xml > rotation.log 2>&1 || { fail "the short rotation"; cat rotation.log; }
restart() { scene "$1" "<Parameter name=\"restart file\" type=\"string\" value=\"$2\"/><Parameter name=\"restart theta_y\" type=\"double\" value=\"${3:-5.5}\"/>" "${4:-}"; }
restart out rotation/checkpoints.h5; "$app" scene.xml --validate-only > /dev/null 2>&1 || fail "a good restart does not validate"
restart out no-such-file.h5; refused "missing restart file" "parameter 'Loading/restart file' = 'no-such-file.h5': no such file"
restart out user-file; refused "restart file not HDF5" "parameter 'Loading/restart file' = 'user-file': not an HDF5 file"
restart out rotation/checkpoints.h5 45; refused "no such checkpoint" "has no checkpoint 'theta_y=45'"
restart out rotation/checkpoints.h5 5.5 '<ParameterList name="Mesh"><Parameter name="layers" type="int" value="5"/></ParameterList>'
refused "checkpoint of another mesh" "was made for another scene (nodes (mesh and enrichment"
restart out rotation/checkpoints.h5 5.5 '<ParameterList name="Geometry"><Parameter name="w_p" type="double" value="240"/></ParameterList>'
refused "checkpoint of another geometry" "Geometry/w_p: 250 in the checkpoint, 240 in this scene"
restart out rotation/checkpoints.h5 5.5 '<ParameterList name="Material"><Parameter name="E" type="double" value="3"/></ParameterList>'
refused "checkpoint of another material" "Material/E: 2 in the checkpoint, 3 in this scene"
restart rotation rotation/checkpoints.h5; refused "restart file inside the output directory" "would replace 'Loading/restart file'"

[ "$failures" -eq 0 ] && echo "every unsafe output and unusable restart refused, nothing touched"
exit "$failures"
