#!/usr/bin/env python3
"""The studies' Snakemake workflow (scripts/workflow/Snakefile) against run-study.py: the coarse Table 6 study's jobs
(a run per scene, each pull-off after the rotation, the tables last); that study restored from results/ gives
run-study.py's tables byte for byte; and the coarse rough study run afresh (inclined to 8 deg only) by the workflow,
as `run-study.py --engine snakemake` starts it, gives the same curves (all but the wall clock) and tables as
run-study.py's own runner. Skipped (exit 77) where snakemake is missing.

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


def run_study(study, work, *options):
    return shown(subprocess.run([PYTHON, os.path.join(ROOT, 'scripts', 'run-study.py'), study, '--mesh', 'coarse',
                                 '--work', work] + list(options), capture_output=True, text=True))


with tempfile.TemporaryDirectory() as root:
    # The plan: five runs and the tables; each pull-off waits for the rotation's marker.
    plan = workflow(root, 'table6', 'mesh=coarse', f'work={root}/plan', dry=True)
    text = plan.stdout + plan.stderr
    runs = re.findall(r'wildcards: level=coarse, scene=([\w.-]+)', text)
    check(sorted(runs) == ['peel-rotation', 'pull-off-45', 'pull-off-60', 'pull-off-75', 'pull-off-90'],
          f'the plan runs the Table 6 scenes: {runs}')
    blocks = [b for b in text.split('rule run:') if 'scene=pull-off' in b.split('rule ')[0]]
    check(len(blocks) == 4 and all('input: ' + f'{root}/plan/coarse/peel-rotation.complete' in b for b in blocks),
          'each pull-off starts after the rotation')
    check(re.search(r'table6\s+1', text) is not None, 'the tables are the last job')

    # Restored from results/: the same tables as run-study.py's.
    check(workflow(root, 'table6', 'mesh=coarse', f'work={root}/restored').returncode == 0, 'the restored study')
    check(run_study('table6', f'{root}/tabulated', '--no-run').returncode == 0, 'run-study.py --no-run')
    check(tables(f'{root}/restored') == tables(f'{root}/tabulated'), "the restored study's tables are run-study.py's")

    # Run afresh: the same curves and tables as run-study.py's runs.
    override = 'Loading/theta_y=8'
    fresh = run_study('rough', f'{root}/fresh', '--engine', 'snakemake', '--set', override)
    check(fresh.returncode == 0 and '3 of 3 steps (100%) done' in fresh.stdout + fresh.stderr,
          'the rough study run by the workflow (run-study.py --engine snakemake)')
    check(run_study('rough', f'{root}/runner', '--set', override).returncode == 0, 'the rough study run by run-study.py')
    for scene in ('rough-z0-0', 'rough-z0-4', 'rough-z0-8'):
        rows, others, differences = curve_differences(*(os.path.join(root, work, 'coarse', scene)
                                                        for work in ('fresh', 'runner')))
        check(rows == others >= 3 and not differences, f"{scene}: the same curve as run-study.py's ({rows}, {others} "
              f'states; {differences[:3]})')
    check(tables(f'{root}/fresh') == tables(f'{root}/runner'), "the fresh study's tables are run-study.py's")

finish('workflow: the plan, restored and fresh studies as run-study.py\'s')
