#!/usr/bin/env python3
"""The studies' workflow through a real batch system: a one-node Slurm cluster on this machine
(scripts/workflow/local-slurm.sh: munged, slurmctld, slurmd with a generated configuration), the workflow's Slurm
profile (scripts/workflow/profiles/slurm). The coarse Table 6 study restored from results/ in Slurm jobs gives
run-study.py's tables; the coarse rough study run afresh with two MPI ranks per job (inclined to 8 deg only) gives
the same curves (all but the wall clock, to 1e-6: two-rank runs agree to rounding) and tables as the same workflow
run locally; each job asked for its ranks and the preflight's memory. The daemons are stopped at the end. Skipped
(exit 77) where snakemake, slurm-wlm or munge is missing or not root.

    study_workflow_slurm.py <spatula>"""
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
sys.path.insert(0, os.path.join(ROOT, 'tests', 'app'))
from expectations import check, finish  # noqa: E402
from workflow_checks import curve_differences, prepare_slurm_test, shown, tables  # noqa: E402

prepare_slurm_test(sys.argv[1], 6817)   # each Slurm test its own ports: they may run at once
SNAKEFILE = os.path.join(ROOT, 'scripts', 'workflow', 'Snakefile')
CLUSTER = os.path.join(ROOT, 'scripts', 'workflow', 'local-slurm.sh')


def workflow(directory, target, *config, slurm=False):
    # A job's state is polled every 2 s here (the profile keeps Snakemake's 33 s, kinder to a shared controller).
    mode = (['--profile', os.path.join(ROOT, 'scripts', 'workflow', 'profiles', 'slurm'),
             '--max-status-checks-per-second', '0.5'] if slurm else ['--cores', '2'])
    return shown(subprocess.run(['snakemake', '-s', SNAKEFILE, '-d', directory] + mode + [target, '--config'] +
                                list(config), capture_output=True, text=True))


with tempfile.TemporaryDirectory() as root:
    cluster = os.path.join(root, 'slurm')
    started = subprocess.run([CLUSTER, 'start', cluster, '2'], capture_output=True, text=True)
    check(started.returncode == 0, f'the local Slurm cluster started: {started.stdout} {started.stderr}')
    os.environ['SLURM_CONF'] = os.path.join(cluster, 'slurm.conf')
    try:
        check(workflow(root, 'table6', 'mesh=coarse', f'work={root}/restored', slurm=True).returncode == 0,
              'the restored Table 6 study in Slurm jobs')
        tabulated = subprocess.run(['/usr/bin/python3', os.path.join(ROOT, 'scripts', 'run-study.py'), 'table6',
                                    '--mesh', 'coarse', '--no-run', '--work', f'{root}/tabulated'], capture_output=True)
        check(tabulated.returncode == 0 and tables(f'{root}/restored') == tables(f'{root}/tabulated'),
              "the Slurm jobs' Table 6 is run-study.py's")
        jobs = subprocess.run(['scontrol', 'show', 'job'], capture_output=True, text=True).stdout
        check(len(re.findall(r'JobState=COMPLETED', jobs)) >= 6, 'six jobs completed (five runs and the tables)')

        override = 'set=["Loading/theta_y=8"]'
        check(workflow(root, 'rough', 'mesh=coarse', f'work={root}/batch', 'ranks=2', override,
                       slurm=True).returncode == 0, 'the rough study in two-rank Slurm jobs')
        check(workflow(root, 'rough', 'mesh=coarse', f'work={root}/local', 'ranks=2', override).returncode == 0,
              'the same study run locally')
        jobs = subprocess.run(['scontrol', 'show', 'job'], capture_output=True, text=True).stdout
        two_rank = [j for j in jobs.split('\n\n') if 'NumTasks=2' in j and 'JobState=COMPLETED' in j]
        check(len(two_rank) == 3, f'three two-rank jobs ({len(two_rank)})')
        check(all(re.search(r'mem=\d+', j) for j in two_rank), 'each with its memory request')
        for scene in ('rough-z0-0', 'rough-z0-4', 'rough-z0-8'):
            log = open(os.path.join(root, 'batch', 'coarse', scene + '.log')).read()
            check('2 rank(s)' in log, f'{scene}: ran on two ranks')
            rows, others, differences = curve_differences(*(os.path.join(root, work, 'coarse', scene)
                                                            for work in ('batch', 'local')), relative=1e-6)
            check(rows == others >= 3 and not differences,
                  f'{scene}: the Slurm run is the local one ({rows}, {others} states; {differences[:3]})')
        check(tables(f'{root}/batch') == tables(f'{root}/local'), "the Slurm study's tables are the local one's")
    finally:
        subprocess.run([CLUSTER, 'stop', cluster])
    check(not any(os.path.exists(os.path.join(cluster, f'{d}.pid')) for d in ('munged', 'slurmctld', 'slurmd')),
          'the daemons stopped')

finish('workflow under Slurm: the restored and fresh studies as run-study.py\'s and the local workflow\'s')
