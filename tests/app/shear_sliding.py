#!/usr/bin/env python3
"""The shear study's pull along the substrate with the constant-strength friction law, free across the pull
(shear-strength-free-180 on the coarse mesh, from the kept rotation at 60 deg): once the whole pad slides, the force
that drags it is the sliding limit over the contact area, P_x = -tau_0 A_c (to 1e-5: A_c as the mesh summary prints
it), with zero net normal force, and the pull reaches its final travel still attached.

    shear_sliding.py <spatula app>"""
import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from expectations import check, finish, xml_parameter  # noqa: E402
from study import scenes as study  # noqa: E402

SCENE = 'shear-strength-free-180'
ROTATION = os.path.join(ROOT, 'results', 'coarse', 'peel-rotation', 'checkpoints.h5')

with tempfile.TemporaryDirectory() as work:
    path = study.scene_file(work, 'coarse', SCENE)
    os.symlink(ROTATION, os.path.join(work, SCENE + '.restart.h5'))
    environment = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
    result = subprocess.run([os.path.abspath(sys.argv[1]), path], cwd=work, capture_output=True, text=True,
                            env=environment)
    check(result.returncode == 0, f'the pull failed: {result.stdout[-500:]} {result.stderr[-300:]}')
    if result.returncode == 0:
        rows = [r for r in csv.DictReader(open(os.path.join(work, SCENE, 'curve.csv'))) if r['stage'] == 'lift']
        summary = dict(csv.reader(open(os.path.join(work, SCENE, 'mesh_summary.csv'))))
        strength = 0.037   # the constant-strength limit's default, which the scene keeps
        check(xml_parameter(open(path).read(), 'strength') is None, 'the scene sets its own strength')
        limit = strength * float(summary['contact_area_nm2'])
        last = rows[-1]
        check(abs(float(last['u_x_nm']) + 600) < 1e-6, f"the pull ended at u_x = {last['u_x_nm']} nm, not -600")
        check(abs(-float(last['P_x_nN']) / limit - 1) < 1e-5, f"P_x = {last['P_x_nN']} nN against -tau_0 A_c = "
                                                              f"{-limit:.4f}")
        check(abs(float(last['P_z_nN'])) < 1e-6, f"net normal force {last['P_z_nN']} nN")
        check('detachment' not in result.stdout, 'the sliding pad was taken for detached')
        print(f"sliding at P_x = {float(last['P_x_nN']):.5f} nN, -tau_0 A_c = {-limit:.5f} nN")
finish('shear sliding: all expectations met')
