#!/usr/bin/env python3
"""scripts/study/keep_runs.py on a manufactured work directory: each complete run (a curve) is kept in
<results>/<name>/<scene>/ with its scene, mesh summary and log (as run.log), a rotation with its checkpoints; a run
still going (no curve, only its .partial) is left out and named.

    study_keep_runs.py"""
import contextlib
import io
import os
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
sys.path.insert(0, os.path.join(ROOT, 'scripts', 'study'))
from expectations import check, finish  # noqa: E402
import keep_runs  # noqa: E402
import study.archive  # noqa: E402

with tempfile.TemporaryDirectory() as work:
    level = os.path.join(work, 'coarse')
    for scene, files in (('peel-rotation', ('curve.csv', 'scene.xml', 'mesh_summary.txt', 'checkpoints.h5')),
                         ('rough-z0-0', ('curve.csv', 'scene.xml', 'mesh_summary.csv', 'fields.h5'))):
        os.makedirs(os.path.join(level, scene))
        for name in files:
            open(os.path.join(level, scene, name), 'w').write(f'{scene} {name}\n')
        open(os.path.join(level, scene + '.xml'), 'w').write('<ParameterList/>\n')
        open(os.path.join(level, scene + '.log'), 'w').write(f'{scene} log\n')
    os.makedirs(os.path.join(level, 'rough-z0-4.partial'))   # still going
    open(os.path.join(level, 'rough-z0-4.xml'), 'w').write('<ParameterList/>\n')
    results = os.path.join(work, 'results')
    study.archive.ARCHIVE = results   # archive() keeps the runs under ARCHIVE/<name>
    sys.argv = ['keep_runs.py', level, 'coarse-x2-equal-area']
    output = io.StringIO()
    with contextlib.redirect_stdout(output):
        keep_runs.main()
    kept = os.path.join(results, 'coarse-x2-equal-area')
    check(sorted(os.listdir(kept)) == ['peel-rotation', 'rough-z0-0'], f'kept runs {sorted(os.listdir(kept))}')
    check(sorted(os.listdir(os.path.join(kept, 'peel-rotation'))) ==
          ['checkpoints.h5', 'curve.csv', 'mesh_summary.txt', 'run.log', 'scene.xml'], 'the rotation with checkpoints')
    check(sorted(os.listdir(os.path.join(kept, 'rough-z0-0'))) ==
          ['curve.csv', 'mesh_summary.csv', 'run.log', 'scene.xml'], 'no fields kept')
    check(open(os.path.join(kept, 'rough-z0-0', 'run.log')).read() == 'rough-z0-0 log\n', 'the log as run.log')
    check('kept 2 complete runs' in output.getvalue() and 'not complete: rough-z0-4' in output.getvalue(),
          f'the summary line: {output.getvalue()}')
finish('keep_runs: complete runs kept, a run still going named')
