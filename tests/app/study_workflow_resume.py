#!/usr/bin/env python3
"""A study stopped in the middle under Slurm goes on where it stopped: the coarse rough study (inclined to 20 deg,
a checkpoint at every converged state) in Slurm jobs on a one-node cluster of this machine
(scripts/workflow/local-slurm.sh), its jobs cancelled (scancel) once a run has converged a few states; the same
command again resumes the stopped runs from their last checkpoints (`spatula --resume`) and completes the study, with
the last states of the workflow run uninterrupted on this machine (to 1e-5). Skipped (exit 77) where snakemake, slurm-wlm
or munge is missing or not root.

    study_workflow_resume.py <spatula>"""
import csv
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
sys.path.insert(0, os.path.join(ROOT, 'tests', 'app'))
from expectations import check, finish  # noqa: E402
from workflow_checks import prepare_slurm_test, shown  # noqa: E402

prepare_slurm_test(sys.argv[1], 6837)   # each Slurm test its own ports: they may run at once
CLUSTER = os.path.join(ROOT, 'scripts', 'workflow', 'local-slurm.sh')
SCENES = ('rough-z0-0', 'rough-z0-4', 'rough-z0-8')


def command(directory, work, slurm):
    mode = (['--profile', os.path.join(ROOT, 'scripts', 'workflow', 'profiles', 'slurm'),
             '--max-status-checks-per-second', '0.5'] if slurm else ['--cores', '2'])
    return (['snakemake', '-s', os.path.join(ROOT, 'scripts', 'workflow', 'Snakefile'), '-d', directory] + mode +
            ['rough', '--config', 'mesh=coarse', f'work={work}',
             'set=["Loading/theta_y=20", "Output/checkpoint interval=1e-6"]'])


def converged_states(work, scene):
    log = os.path.join(work, 'coarse', scene + '.log')
    return sum(line.startswith('step ') for line in open(log)) if os.path.exists(log) else 0


with tempfile.TemporaryDirectory() as root:
    cluster, work = os.path.join(root, 'slurm'), os.path.join(root, 'batch')
    check(shown(subprocess.run(command(root, f'{root}/local', False), capture_output=True, text=True)).returncode
          == 0, 'the study run uninterrupted')
    started = subprocess.run([CLUSTER, 'start', cluster, '2'], capture_output=True, text=True)
    check(started.returncode == 0, f'the local Slurm cluster started: {started.stdout} {started.stderr}')
    os.environ['SLURM_CONF'] = os.path.join(cluster, 'slurm.conf')
    try:
        first = subprocess.Popen(command(root, work, True), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.time() + 600
        while time.time() < deadline and not any(converged_states(work, s) >= 3 for s in SCENES):
            time.sleep(0.5)
        subprocess.run(['scancel', '--user', os.environ['USER']])
        first.terminate()
        first.wait()
        stopped = [s for s in SCENES if not os.path.exists(os.path.join(work, 'coarse', s, 'curve.csv'))
                   and converged_states(work, s) >= 3]
        check(stopped, 'a run was stopped after converging three states')
        again = shown(subprocess.run(command(root, work, True), capture_output=True, text=True))
        check(again.returncode == 0, 'the same command again completes the study')
        for scene in stopped:
            log = open(os.path.join(work, 'coarse', scene + '.workflow.log')).read()
            check('resumed from its last checkpoint' in log, f'{scene}: resumed, not started again')
        for scene in SCENES:   # a resumed run's Newton starts without the predictor: its states agree to 1e-5
            ends = [list(csv.DictReader(open(os.path.join(root, w, 'coarse', scene, 'curve.csv'))))[-1]
                    for w in ('batch', 'local')]
            check(all(abs(float(ends[0][k]) - float(ends[1][k])) <= 1e-5 * max(1.0, abs(float(ends[1][k])))
                      for k in ('theta_y_deg', 'M_y_nNnm', 'Pi_int_1e-18J', 'Pi_ext_1e-18J')),
                  f"{scene}: the uninterrupted run's last state (theta_y, M_y: {ends[0]['theta_y_deg']}, "
                  f"{ends[0]['M_y_nNnm']} against {ends[1]['theta_y_deg']}, {ends[1]['M_y_nNnm']})")
    finally:
        subprocess.run([CLUSTER, 'stop', cluster])
        # A job step that scancel left behind (snakemake's, waiting for files in this directory) goes with it.
        subprocess.run(['pkill', '-KILL', '-f', root])

finish('workflow under Slurm: a cancelled study resumed to the uninterrupted curves')
