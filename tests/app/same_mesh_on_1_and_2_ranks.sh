#!/usr/bin/env bash
# The mesh written by a 1-rank and a 2-rank run is the same (coordinates, connectivity, sets); the 2-rank run
# records a two-way partition. usage: same_mesh_on_1_and_2_ranks.sh <spatula> <mpiexec> [mpiexec flags...]
set -eu
app=$1
mpiexec=$2
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
cat > scene.xml <<'XML'
<ParameterList>
  <ParameterList name="Mesh"><Parameter name="level" type="string" value="medium"/></ParameterList>
  <ParameterList name="Output"><Parameter name="directory" type="string" value="OUT"/></ParameterList>
</ParameterList>
XML
sed 's/OUT/one/' scene.xml > one.xml
sed 's/OUT/two/' scene.xml > two.xml
"$mpiexec" -np 1 "$@" "$app" one.xml > one.log
"$mpiexec" -np 2 "$@" "$app" two.xml > two.log
/usr/bin/python3 - <<'PY'
import sys
import h5py
import numpy as np
one, two = h5py.File('one/mesh.h5', 'r'), h5py.File('two/mesh.h5', 'r')
for name in ('coordinates', 'hexahedra', 'part', 'node_sets/symmetry', 'node_sets/end_face', 'node_sets/contact',
             'side_sets/contact', 'side_sets/symmetry', 'side_sets/end_face'):
    a, b = one['mesh/' + name][...], two['mesh/' + name][...]
    if a.shape != b.shape or not np.array_equal(a, b):
        sys.exit(f'mesh/{name} differs between 1 and 2 ranks')
ranks_one, ranks_two = np.unique(one['mesh/rank'][...]), np.unique(two['mesh/rank'][...])
if list(ranks_one) != [0] or list(ranks_two) != [0, 1]:
    sys.exit(f'partition not recorded: {ranks_one} {ranks_two}')
print('same mesh on 1 and 2 ranks:', one['mesh/coordinates'].shape[0], 'nodes,', one['mesh/hexahedra'].shape[0],
      'elements; 2-rank split', np.bincount(two['mesh/rank'][...]))
PY
