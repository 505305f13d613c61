#!/usr/bin/env python3
"""A study job's progress line (scripts/study/progress.py) from the app's step lines: a rotation's stage, theta_y,
elapsed minutes and the minutes left at its pace to the scene's theta_y; a pull at an angle without an estimate (the
log shows u_z, its final travel is along the pull); other lines passed on shortened.

    study_progress.py"""
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from expectations import check, finish  # noqa: E402
from study.progress import progress, step_lines  # noqa: E402


def line(step, stage, theta, lift, seconds):
    return (f'step {step:<5} {stage:<9} theta_y {theta:<8.3f} deg  u_z {lift:<9.3f} nm  M_y 1.0 nN nm  P_z 0.0 nN  '
            f'newton 2  neg.piv 0  {seconds:.1f} s')


origin = {}
run = ('coarse', 'peel-rotation')   # xml/studies/peel-rotation.xml: to theta_y = 140
first = progress('/nowhere', run, line(1, 'rotation', 10.0, 1.0, 60.0), 60.0, origin)
check(first == '[coarse peel-rotation] step 1 rotation theta_y = 10.000 deg, 1.0 min', f'first line: {first}')
later = progress('/nowhere', run, line(2, 'rotation', 20.0, 2.0, 120.0), 120.0, origin)
# 10 deg a minute from 20 to 140 deg: 12 minutes left.
check(later == '[coarse peel-rotation] step 2 rotation theta_y = 20.000 deg, 2.0 min, about 12 min left at this pace',
      f'estimate: {later}')
pull = ('coarse', 'shear-amontons-free-135')
progress('/nowhere', pull, line(5, 'lift', 60.0, 560.0, 30.0), 30.0, origin)
angled = progress('/nowhere', pull, line(6, 'lift', 60.0, 570.0, 60.0), 60.0, origin)
check(angled == '[coarse shear-amontons-free-135] step 6 lift u_z = 570.000 nm, 1.0 min', f'pull at 135 deg: {angled}')
other = progress('/nowhere', run, 'jump   at lift = 520.8:   released 15.3 nN nm', 1.0, origin)
check(other == '[coarse peel-rotation] jump at lift = 520.8: released 15.3 nN nm', f'another line: {other}')
log = os.path.join(os.environ.get('TMPDIR', '/tmp'), f'study_progress_{os.getpid()}.log')
open(log, 'w').write('spatula 1.0\n' + line(1, 'rotation', 10.0, 1.0, 60.0) + '\njump ...\nsolver: 3 tangents\n')
check(len(step_lines(log)) == 2, f'the lines shown: {step_lines(log)}')
os.remove(log)

finish('study_progress: progress lines with and without an estimate')
