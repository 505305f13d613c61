#!/usr/bin/env python3
"""The shear study (run-study.py shear): every grid scene is derived from xml/studies/shear-pull.xml with its law,
pull angle and constraint across the pull, and passes the app's validation with the coarse rotation's checkpoint
(results/coarse/peel-rotation); the tables' pull quantities decompose a manufactured pull at 135 deg exactly (force
along and across the pull, travel, work, dissipation), the mesh-dependence table compares the points run on two
levels, and a run's outcome is the app's own verdict.

    shear_study.py <spatula app>"""
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from expectations import check, finish, xml_parameter as parameter  # noqa: E402
from study import scenes as study  # noqa: E402
from study import shear_scenes, shear_tables  # noqa: E402

ROTATION = os.path.join(ROOT, 'results', 'coarse', 'peel-rotation', 'checkpoints.h5')
LAWS = {'frictionless': ('frictionless', None), 'amontons': ('adhesive friction', 'extended Amontons'),
        'strength': ('adhesive friction', 'constant strength'), 'stiction': ('stiction', None)}

# The grid: every law at every angle, a frictionless pad only held across the pull; the rotation first.
shear = study.STUDIES['shear']
check(shear[0] == 'peel-rotation' and len(shear) == 1 + 7 * 7, f'the study has {len(shear)} scenes')
check('shear-frictionless-free-120' not in shear and shear_scenes.derived('shear-frictionless-free-120') is None,
      'a frictionless pull free across the pull is in the grid')
check(not any(s.startswith('shear-') for s in study.STUDIES['all']), "the shear scenes are in 'all' (the paper's)")
check(all(study.DEPENDS[s] == 'peel-rotation' for s in shear[1:]), 'a shear pull does not start from the rotation')
with tempfile.TemporaryDirectory() as work:
    for scene in shear[1:]:
        law, constraint, beta = shear_scenes.point(scene)
        path = study.scene_file(work, 'coarse', scene)
        text = open(path).read()
        check(parameter(text, 'law') == ('string', LAWS[law][0]), f'{scene}: law {parameter(text, "law")}')
        if LAWS[law][1]:
            check(parameter(text, 'sliding limit') == ('string', LAWS[law][1]), f'{scene}: sliding limit')
            check(parameter(text, 'update') == ('string', 'return mapping'), f'{scene}: update {parameter(text, "update")}')
        check(parameter(text, 'pull angle') == ('double', str(beta)), f'{scene}: pull angle')
        check(parameter(text, 'free slide during lift') == ('bool', 'true' if constraint == 'free' else 'false'),
              f'{scene}: free slide')
        check(parameter(text, 'directory') == ('string', scene), f'{scene}: output directory')
        check(parameter(text, 'restart file') == ('string', scene + '.restart.h5'), f'{scene}: restart file')
        os.symlink(ROTATION, os.path.join(work, scene + '.restart.h5'))
        result = subprocess.run([os.path.abspath(sys.argv[1]), path, '--validate-only'], cwd=work,
                                capture_output=True, text=True)
        check(result.returncode == 0, f'{scene} is not valid: {result.stderr[-300:]}')

# A manufactured pull at beta = 135 deg: the force along the pull rises to 5 nN and falls, 2 nN across it; the end
# face travels 10 nm per state along the pull from u = (-3, 4) nm; the work grows by 7 and the dissipation by 0.1 per
# state after the first.
beta, c, s = 135, math.cos(math.radians(135)), math.sin(math.radians(135))
rows = [dict(stage='rotation', u_x_nm=-3.0, u_z_nm=4.0, P_x_nN=0.0, P_z_nN=0.0, **{'Pi_ext_1e-18J': 100.0},
             dissipated_per_Pi_c0=0.5, after_jump=0.0, balance_error_per_Pi_c0=1e-6)]
for k, along in enumerate((1.0, 3.0, 5.0, 4.0, 0.5), start=1):
    rows.append(dict(stage='lift', u_x_nm=-3.0 + 10 * k * c, u_z_nm=4.0 + 10 * k * s, P_x_nN=along * c + 2 * s,
                     P_z_nN=along * s - 2 * c, **{'Pi_ext_1e-18J': 100.0 + 7 * k}, dissipated_per_Pi_c0=0.5 + 0.1 * k,
                     after_jump=1.0 if k == 5 else 0.0, balance_error_per_Pi_c0=1e-6 * k))
summary = shear_tables.pull_summary(rows, beta)
for key, expected in (('pull_off_nN', 5.0), ('across_nN', 2.0), ('travel_at_peak_nm', 30.0), ('travel_nm', 50.0),
                      ('work_1e-18J', 35.0), ('dissipated_per_Pi_c0', 0.5), ('jumps', 1),
                      ('worst_balance_error', 5e-6), ('P_x_nN', 5 * c + 2 * s), ('P_z_nN', 5 * s - 2 * c)):
    check(abs(summary[key] - expected) < 1e-9, f'{key}: {summary[key]} against {expected}')
check(shear_tables.pull_summary(rows[:1], beta) is None, 'a run still rotating has a pull summary')

# The mesh dependence: a point run on two levels, its change between them; a point on one level only is left out.
point = dict(summary, detached=True, complete=True, outcome='detached')
table = shear_tables.mesh_dependence({'coarse': {('amontons', 'free', 120): dict(point, pull_off_nN=28.0),
                                                 ('amontons', 'free', 135): dict(point, pull_off_nN=56.0)},
                                      'medium': {('amontons', 'free', 120): dict(point, pull_off_nN=29.4)}})
check('| amontons | free | 120 | 28.00 | 29.40 | +5.0 % |' in table, f'mesh dependence: {table}')
check('| 135 |' not in table, 'a point on one level has a mesh dependence row')
check(shear_tables.mesh_dependence({'coarse': {('amontons', 'free', 120): point}}) == '', 'one level: a table')
going = dict(point, detached=False, complete=False, pull_off_nN=11.0, outcome=shear_tables.NOT_FINISHED)
table = shear_tables.mesh_dependence({'coarse': {('amontons', 'free', 120): dict(point, pull_off_nN=28.0)},
                                      'medium': {('amontons', 'free', 120): going}})
check('| 28.00 | 11.00 (not finished) | not yet |' in table, f'a point not finished has a change: {table}')

# The outcome is the app's: its detachment line, else the final travel reached (complete), else stopped (its
# diagnosis) or not finished.
with tempfile.TemporaryDirectory() as work:
    os.makedirs(os.path.join(work, 'a'))
    open(os.path.join(work, 'a', 'curve.csv'), 'w').write('step\n')
    open(os.path.join(work, 'a.log'), 'w').write('step 1 ...\ndetachment: the pull has collapsed\n')
    check(shear_tables.outcome(work, 'a') == (True, 'detached'), f"outcome a: {shear_tables.outcome(work, 'a')}")
    open(os.path.join(work, 'a.log'), 'w').write('step 1 ...\n')
    check(shear_tables.outcome(work, 'a') == (False, 'held on to the final travel'), 'outcome without detachment')
    check(shear_tables.outcome(work, 'b') == (False, shear_tables.NOT_FINISHED),
          f"outcome of a run without a log: {shear_tables.outcome(work, 'b')}")
    open(os.path.join(work, 'b.log'), 'w').write(
        'step 1 ...\nspatula: solver failure at step 302, lift = 287.783: jump past the instability failed: no stable '
        "state within 500 iterations (311 descent steps); the descent's last state kept 26 % of the adhesion energy; "
        'the descent state is checkpointed\n')
    check(shear_tables.outcome(work, 'b') == (False, 'stopped: no stable state after a jump (its descent kept 26 % of '
                                                     'the adhesion)'), f"a failed jump: {shear_tables.outcome(work, 'b')}")
    # The app's slip of the adhering part: beyond SLID_OFF_NM the pad slid off, within it the run stopped.
    for slip, expected in (('35.2', 'slid off: no stable state after a jump, its adhering part slid 35.2 nm along the '
                                    'substrate keeping 88 % of the adhesion'),
                           ('0.4', 'stopped: no stable state after a jump (its descent kept 88 % of the adhesion)')):
        open(os.path.join(work, 'b.log'), 'w').write(
            'step 1 ...\nspatula: solver failure at step 302, lift = 287.783: jump past the instability failed: no '
            "stable state within 500 iterations (311 descent steps); the descent's last state kept 88 % of the adhesion "
            f'energy, its adhering part slid {slip} nm along the substrate (mean); the descent state is checkpointed\n')
        check(shear_tables.outcome(work, 'b') == (False, expected), f"slip {slip}: {shear_tables.outcome(work, 'b')}")
    # A run resumed after its failure (another jump limit, say) and still going: not finished, whatever the log
    # said before its last resume.
    open(os.path.join(work, 'b.log'), 'a').write('spatula: resuming the stopped run /w/b.incomplete\nstep 303 ...\n')
    check(shear_tables.outcome(work, 'b') == (False, shear_tables.NOT_FINISHED),
          f"a resumed run still going: {shear_tables.outcome(work, 'b')}")
    check(shear_tables.cell(dict(point, detached=False, complete=False, outcome=shear_tables.NOT_FINISHED))
          .endswith('(not finished)'), 'a pull still going is marked so')
    stopped = 'stopped: no stable state after a jump (its descent kept 88 % of the adhesion)'
    check(shear_tables.cell(dict(point, detached=False, complete=False, outcome=stopped)).endswith('(stopped)'),
          'a stopped pull is marked so')
    check(shear_tables.cell(dict(point, detached=False, complete=False, outcome='slid off: ...')).endswith('(slid off)'),
          'a pull that slid off is marked so')
finish('shear study: all expectations met')
