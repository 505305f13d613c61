#!/usr/bin/env python3
"""run-study.py --set: an override replaces an existing parameter's value and keeps its type, adds a missing
parameter (type from its value) and the sublists on its path, applies to one scene when scoped, leaves the other
scenes alone, and a malformed entry is refused; the scenes it writes pass the app's validation.

    study_overrides.py <spatula app>"""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from expectations import check, finish, xml_parameter as parameter  # noqa: E402
from study import scenes as study  # noqa: E402


# A scene read before the overrides were known (as when the command line checks the --set scene names) must not keep
# its old text: a cached text would hide every override from the runs.
check(study.scene_level('peel-rotation') == 'medium', 'peel-rotation is not a medium-level scene')
before = study.scene_text('peel-rotation')
for entry in ('Linear Solver/lag=4', 'Linear Solver/MUMPS/low rank tolerance=0.0', 'Nonlinear Solver/line search=backtrack',
              'peel-rotation:Loading/theta_y=90.0', 'pull-off-45:Loading/Lift Steps/maximum=5.0',
              'Output/write mesh=false'):
    study.OVERRIDES.append(study.parse_override(entry))
    check(study.format_override(study.OVERRIDES[-1]) == entry, f"'{entry}' does not read back as itself")
rotation, pull_off, other = (study.scene_text(s) for s in ('peel-rotation', 'pull-off-45', 'pull-off-60'))
check(parameter(rotation, 'theta_y') == ('double', '90.0'), f"scoped theta_y: {parameter(rotation, 'theta_y')}")
check(parameter(before, 'theta_y') != ('double', '90.0'), 'the scene text before the overrides already had them')
check(study.scene_parameter('peel-rotation', 'theta_y') == '90.0', 'scene_parameter kept the text from before --set')
check(parameter(other, 'theta_y') == ('double', '60'), 'an override scoped to peel-rotation changed pull-off-60')
check(parameter(pull_off, 'maximum') == ('double', '5.0'), f"existing Lift Steps/maximum: {parameter(pull_off, 'maximum')}")
check(parameter(other, 'maximum') == ('double', '10'), 'an override scoped to pull-off-45 changed pull-off-60')
check(parameter(rotation, 'lag') == ('int', '4'), f"new int: {parameter(rotation, 'lag')}")
check(parameter(rotation, 'low rank tolerance') == ('double', '0.0'), 'new double in a new sublist')
check(parameter(rotation, 'line search') == ('string', 'backtrack'), 'new string')
check(parameter(rotation, 'write mesh') == ('bool', 'false'), 'new bool')
check('<!--' in rotation, 'the scene lost its comments')
check(rotation.count('<ParameterList name="Linear Solver">') == 1, 'a sublist added twice')
for bad in ('lag=4', 'Linear Solver/lag', 'a:b:Linear Solver/lag=4'):
    try:
        study.parse_override(bad)
        check(False, f"malformed --set '{bad}' accepted")
    except argparse.ArgumentTypeError as error:
        check('expected [SCENE:]List/.../name=value' in str(error), f'message for {bad}: {error}')

with tempfile.TemporaryDirectory() as work:
    path = study.scene_file(work, 'coarse', 'peel-rotation')
    check(parameter(open(path).read(), 'level') == ('string', 'coarse'), 'the level was not set')
    result = subprocess.run([os.path.abspath(sys.argv[1]), path, '--validate-only'], cwd=work, capture_output=True, text=True)
    check(result.returncode == 0, f'the overridden scene is not valid: {result.stdout[-300:]} {result.stderr[-300:]}')
finish('study overrides: all expectations met')
