#!/usr/bin/env python3
"""The studies' Snakemake workflow (scripts/workflow/Snakefile) against run-study.py: the coarse Table 6 study's jobs
(a run per scene, the rotation in parts up to each pull-off's checkpoint, each pull-off after its part, the tables
last); that study restored from results/ gives run-study.py --no-run's tables byte for byte; the coarse rough study
run afresh (inclined to 8 deg only) by run-study.py, which hands its runs to the workflow, shows a progress line per
converged step and gives the same curves (all but the wall clock) as the app run directly on each job's scene file;
and a rotation run afresh in two parts meets the app's run in one go. Skipped (exit 77) where snakemake is missing.

    study_workflow.py <spatula>"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
sys.path.insert(0, os.path.join(ROOT, 'tests', 'app'))
from expectations import check, finish  # noqa: E402
from workflow_checks import curve_differences, shown, tables  # noqa: E402

SNAKEMAKE = shutil.which('snakemake')
if not SNAKEMAKE:
    print('snakemake not installed (Debian package snakemake): skipped')
    sys.exit(77)
os.environ['SPATULA_APP'] = os.path.abspath(sys.argv[1])
PYTHON = '/usr/bin/python3'


def workflow(directory, target, *config, dry=False):
    command = [SNAKEMAKE, '-s', os.path.join(ROOT, 'scripts', 'workflow', 'Snakefile'), '-d', directory,
               '--cores', '2', target] + (['-n'] if dry else []) + ['--config'] + list(config)
    return shown(subprocess.run(command, capture_output=True, text=True))


def direct_run(scene_xml, directory):
    """The app run on a job's scene file in `directory` (one rank, as the jobs): its output directory."""
    os.makedirs(directory, exist_ok=True)
    shutil.copyfile(scene_xml, os.path.join(directory, os.path.basename(scene_xml)))
    environment = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
    subprocess.run([os.environ['SPATULA_APP'], os.path.basename(scene_xml)], cwd=directory, env=environment,
                   capture_output=True)
    return os.path.join(directory, os.path.basename(scene_xml)[:-len('.xml')])


def run_study(study, work, *options):
    return shown(subprocess.run([PYTHON, os.path.join(ROOT, 'scripts', 'run-study.py'), study, '--mesh', 'coarse',
                                 '--work', work] + list(options), capture_output=True, text=True))


with tempfile.TemporaryDirectory() as root:
    # The plan: five runs, the rotation in parts up to each pull-off's checkpoint, the tables; each pull-off waits
    # for its checkpoint, each part for the one before.
    plan = workflow(root, 'table6', 'mesh=coarse', f'work={root}/plan', dry=True)
    text = plan.stdout + plan.stderr
    jobs = [(b.split(':')[0], b) for b in re.split(r'\nrule ', text)[1:]]
    runs = {re.search(r'scene=([\w.-]+)', b).group(1): b for rule, b in jobs if rule == 'run'}
    check(sorted(runs) == ['peel-rotation', 'pull-off-45', 'pull-off-60', 'pull-off-75', 'pull-off-90'],
          f'the plan runs the Table 6 scenes: {sorted(runs)}')
    parts = {re.search(r'theta=([\d.]+)', b).group(1): b for rule, b in jobs if rule == 'rotation_part'}
    check(sorted(parts, key=float) == ['45', '60', '75', '90'], f'the rotation in parts to 45, 60, 75, 90 deg: {parts}')
    checkpoint = f'{root}/plan/coarse/peel-rotation.checkpoint-' + '{}.h5'
    check(all(f'input: {checkpoint.format(t)}' in runs[f'pull-off-{t}'] for t in (45, 60, 75, 90)),
          "each pull-off starts once the rotation's part up to its inclination is done")
    check(all(f'input: {checkpoint.format(a)}' in parts[b] for a, b in (('45', '60'), ('60', '75'), ('75', '90'))) and
          'input:' not in parts['45'] and f'input: {checkpoint.format(90)}' in runs['peel-rotation'],
          'each part goes on from the one before, the rest of the rotation from the last')
    check(re.search(r'table6\s+1', text) is not None, 'the tables are the last job')

    # Restored from results/: the same tables as run-study.py's.
    check(workflow(root, 'table6', 'mesh=coarse', f'work={root}/restored').returncode == 0, 'the restored study')
    check(run_study('table6', f'{root}/tabulated', '--no-run').returncode == 0, 'run-study.py --no-run')
    check(tables(f'{root}/restored') == tables(f'{root}/tabulated'), "the restored study's tables are run-study.py's")

    # Run afresh by run-study.py (the workflow): the same curves as the app run directly on each job's scene file,
    # and a progress line per converged step of every run.
    override = 'Loading/theta_y=8'
    fresh = run_study('rough', f'{root}/fresh', '--set', override)
    output = fresh.stdout + fresh.stderr
    check(fresh.returncode == 0 and '3 of 3 steps (100%) done' in output, 'the rough study run by run-study.py')
    check(all(re.search(rf'\[coarse {s}\] step 3 rotation theta_y = ', output) for s in ('rough-z0-0', 'rough-z0-8')),
          'a progress line per converged step of each run')
    for scene in ('rough-z0-0', 'rough-z0-4', 'rough-z0-8'):
        rows, others, differences = curve_differences(os.path.join(root, 'fresh', 'coarse', scene),
                                                      direct_run(os.path.join(root, 'fresh', 'coarse', scene + '.xml'),
                                                                 f'{root}/direct'))
        check(rows == others >= 3 and not differences, f"{scene}: the same curve as the app's own run ({rows}, "
              f'{others} states; {differences[:3]})')

    # A rotation run afresh in parts (to 47 deg: one part to its checkpoint at 45, then the rest) meets the app's run
    # in one go to the Newton tolerance (the parts factor the tangent anew where the one-go run may reuse one).
    override = 'peel-rotation:Loading/theta_y=47'
    fresh = run_study('table4', f'{root}/parts', '--set', override)
    part = os.path.join(root, 'parts', 'coarse', 'peel-rotation.checkpoint-45.h5')
    check(fresh.returncode == 0 and os.path.exists(part), 'the rotation run in parts by the workflow')
    rows, others, differences = curve_differences(
        os.path.join(root, 'parts', 'coarse', 'peel-rotation'),
        direct_run(os.path.join(root, 'parts', 'coarse', 'peel-rotation.xml'), f'{root}/one-go'), relative=1e-5)
    check(rows == others >= 40 and not differences, f'the parts meet the one-go curve to 1e-5 ({rows}, {others} '
          f'states; {differences[:3]})')

finish('workflow: the plan, restored and fresh studies as the app\'s own runs')
