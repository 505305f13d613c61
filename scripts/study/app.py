"""The app as a study's job starts it: where it is, its environment (one BLAS and one Kokkos thread per rank), the
launcher for its ranks, whether a stopped run of a scene can be resumed, and the copy of a rotation's checkpoints a
pull-off reads."""
import os
import shutil
import subprocess

from study.scenes import ROOT

APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))

# One BLAS and one Kokkos thread per rank: ranks are what pay here (docs/performance.md).
RUN_ENVIRONMENT = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')


def launch(ranks, launcher):
    """The command prefix that starts `ranks` ranks: none for one rank with mpiexec (the app alone)."""
    if launcher == 'srun':
        return ['srun', '--ntasks', str(ranks)]
    if ranks == 1:
        return []
    return ['mpiexec', '-n', str(ranks)] + (['--allow-run-as-root'] if os.geteuid() == 0 else [])


def copy_restart(directory, scene, source):
    """Copies the rotation's checkpoints file `source` to <directory>/<scene>.restart.h5 (what the pull-off reads),
    whole or not at all, unless it is there."""
    copy = os.path.join(directory, scene + '.restart.h5')
    if not os.path.exists(copy):
        shutil.copyfile(source, copy + '.copying')
        os.replace(copy + '.copying', copy)


def resumable(directory, scene_xml):
    """Whether the app finds a stopped run of this scene to go on from (`--resume --validate-only`), and if not, the
    app's reason (its last line of error output)."""
    result = subprocess.run([APP, scene_xml, '--resume', '--validate-only'], cwd=directory, capture_output=True,
                            text=True)
    reason = (result.stderr.strip().splitlines() or [''])[-1]
    return result.returncode == 0, reason


def memory_estimate_mb(xml, directory):
    """The app's preflight estimate of the run's memory [MB] (`--validate-only`), or None."""
    result = subprocess.run([APP, xml, '--validate-only'], cwd=directory, capture_output=True, text=True)
    for line in result.stdout.splitlines():
        if line.strip().startswith('memory estimate'):
            return int(float(line.split()[2]) * 1024) + 1
    return None
