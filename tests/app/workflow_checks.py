"""What the workflow tests (study_workflow.py, study_workflow_slurm.py) compare: a command's result (its output's
tail shown when it failed), a study's coarse tables, and two runs' curves."""
import csv
import os


def shown(result):
    """The subprocess result, its output's tail printed if it failed."""
    if result.returncode != 0:
        print(result.stdout[-3000:], result.stderr[-3000:])
    return result


def tables(work):
    """The coarse level's tables of a study's work directory: file name -> text."""
    directory = os.path.join(work, 'coarse', 'tables')
    return {name: open(os.path.join(directory, name)).read() for name in sorted(os.listdir(directory))}


def curve_differences(first, second, relative=0.0):
    """The row counts of two runs' curve.csv and their differences (column, value, value) beyond `relative` x
    max(1, |value|), the wall clock and the stage's name aside."""
    curves = [list(csv.DictReader(open(os.path.join(run, 'curve.csv')))) for run in (first, second)]
    differences = [(key, a[key], b[key]) for a, b in zip(*curves) for key in a if key not in ('wall_s', 'stage')
                   and abs(float(a[key]) - float(b[key])) > relative * max(1.0, abs(float(a[key])))]
    return len(curves[0]), len(curves[1]), differences


def prepare_slurm_test(app, port):
    """Exits with 77 (skipped) where snakemake, slurm-wlm or munge is missing or this is not root; else sets what the
    runs and Snakemake's SLURM executor read: the app, $USER, and the local cluster's ports (local-slurm.sh)."""
    import pwd
    import shutil
    import sys
    missing = [p for p in ('snakemake', 'munged', 'slurmctld', 'slurmd', 'sbatch') if not shutil.which(p)]
    if missing or os.geteuid() != 0:
        print(f"skipped: {'missing ' + ', '.join(missing) if missing else 'needs root'} "
              '(Debian packages snakemake, slurm-wlm, munge)')
        sys.exit(77)
    os.environ['SPATULA_APP'] = os.path.abspath(app)
    os.environ.setdefault('USER', pwd.getpwuid(os.geteuid()).pw_name)
    os.environ['SLURM_LOCAL_PORT'] = str(port)
