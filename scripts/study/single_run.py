"""One run of a study scene, as a workflow job runs it (scripts/workflow/Snakefile): restored from results/ where
it is kept there, else the scene file written, the rotation's checkpoint copied for a pull-off, a stopped run
resumed (`spatula --resume`), the app run with its ranks, and the complete run kept in results/.

    python3 scripts/study/single_run.py --work DIR --level LEVEL --scene SCENE [--ranks N] [--launcher mpiexec|srun]
        [--set [SCENE:]LIST/NAME=VALUE ...] [--stop-after THETA]

With --stop-after, the rotation only up to its checkpoint at THETA deg (`spatula --stop-after-checkpoint`), the
job that a pull-off from there waits for: its checkpoints file is copied to
<work>/<level>/<scene>.checkpoint-<THETA>.h5, and the rotation is left stopped there for the next part to resume.

Exit status: the app's (0: the run is complete in <work>/<level>/<scene>/, or with --stop-after its checkpoint is
copied)."""
import argparse
import os
import shutil
import subprocess
import sys

import h5py

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from study.archive import archive, archiving, restore  # noqa: E402
from study.runner import APP, RUN_ENVIRONMENT, copy_restart, resumable  # noqa: E402
from study.runs import complete  # noqa: E402
from study.scenes import DEPENDS, OVERRIDES, parse_override, scene_file, scene_parameter  # noqa: E402


def launch(ranks, launcher):
    """The command prefix that starts `ranks` ranks: none for one rank with mpiexec (the app alone)."""
    if launcher == 'srun':
        return ['srun', '--ntasks', str(ranks)]
    if ranks == 1:
        return []
    return ['mpiexec', '-n', str(ranks)] + (['--allow-run-as-root'] if os.geteuid() == 0 else [])


def memory_estimate_mb(xml, directory):
    """The app's preflight estimate of the run's memory [MB] (`--validate-only`), or None."""
    result = subprocess.run([APP, xml, '--validate-only'], cwd=directory, capture_output=True, text=True)
    for line in result.stdout.splitlines():
        if line.strip().startswith('memory estimate'):
            return int(float(line.split()[2]) * 1024) + 1
    return None


def checkpoint_copy(work, level, scene, theta):
    """Where the part of rotation `scene` up to its checkpoint at theta [deg] leaves that checkpoint."""
    return os.path.join(work, level, f'{scene}.checkpoint-{theta:g}.h5')


def holds_checkpoint(path, theta):
    """Whether the checkpoints file holds the one taken at theta [deg] (the app's label, theta_y=<theta>)."""
    try:
        with h5py.File(path, 'r') as checkpoints:
            return f'checkpoints/theta_y={round(theta * 1000) / 1000:g}/displacements' in checkpoints
    except OSError:
        return False


def written_checkpoints(directory, scene, theta):
    """The rotation's checkpoints file once it holds the checkpoint at theta: the complete run's, or the stopped
    run's (<scene>.incomplete or .partial), else None."""
    for suffix in ('', '.incomplete', '.partial'):
        path = os.path.join(directory, scene + suffix, 'checkpoints.h5')
        if holds_checkpoint(path, theta):
            return path
    return None


def run(work, level, scene, ranks=1, launcher='mpiexec', stop_after=None):
    directory = os.path.join(work, level)
    os.makedirs(directory, exist_ok=True)
    if archiving() and restore(work, [(level, scene)]):
        print(f'[{level} {scene}] restored from results/ (complete)', flush=True)
    if stop_after is not None:
        return run_part(work, level, scene, stop_after, ranks, launcher)
    if complete(directory, scene):
        return 0
    dependency = DEPENDS.get(scene)
    if dependency:   # the rotation's checkpoint the pull-off starts from (a file dependency of the workflow)
        theta = float(scene_parameter(scene, 'restart theta_y'))
        copy_restart(directory, scene, checkpoint_copy(work, level, dependency, theta))
    status = run_app(directory, level, scene, ranks, launcher)
    if status == 0 and archiving() and complete(directory, scene):
        archive(work, level, scene)
    print(f'[{level} {scene}] ' + ('done' if status == 0 else f'failed (exit {status})'), flush=True)
    return status


def run_app(directory, level, scene, ranks, launcher, options=()):
    """Runs the app on the scene (resuming a stopped run of it); returns its exit status."""
    xml = scene_file(directory, level, scene)
    resume = resumable(directory, xml)
    with open(os.path.join(directory, scene + '.log'), 'a' if resume else 'w') as log:
        print(f'[{level} {scene}] ' + ('resumed from its last checkpoint' if resume else 'started') +
              (f' ({" ".join(options)})' if options else ''), flush=True)
        command = launch(ranks, launcher) + [APP, xml] + (['--resume'] if resume else []) + list(options)
        return subprocess.run(command, cwd=directory, stdout=log, stderr=subprocess.STDOUT,
                              env=RUN_ENVIRONMENT).returncode


def run_part(work, level, scene, theta, ranks, launcher):
    """The rotation up to its checkpoint at theta (unless it has passed it), that checkpoint's file copied out."""
    directory = os.path.join(work, level)
    copy = checkpoint_copy(work, level, scene, theta)
    source = written_checkpoints(directory, scene, theta)
    if not source:
        status = run_app(directory, level, scene, ranks, launcher, ['--stop-after-checkpoint', f'{theta:g}'])
        if status != 0:
            print(f'[{level} {scene}] failed (exit {status}) on its way to theta_y = {theta:g} deg', flush=True)
            return status
        if archiving() and complete(directory, scene):
            archive(work, level, scene)
        source = written_checkpoints(directory, scene, theta)
        if not source:
            print(f'[{level} {scene}] ended without a checkpoint at theta_y = {theta:g} deg (see {scene}.log)',
                  flush=True)
            return 1
    shutil.copyfile(source, copy + '.copying')
    os.replace(copy + '.copying', copy)
    print(f'[{level} {scene}] checkpoint theta_y = {theta:g} deg in {os.path.relpath(copy, work)}', flush=True)
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--work', required=True)
    parser.add_argument('--level', required=True)
    parser.add_argument('--scene', required=True)
    parser.add_argument('--ranks', type=int, default=1)
    parser.add_argument('--launcher', choices=('mpiexec', 'srun'), default='mpiexec')
    parser.add_argument('--set', action='append', type=parse_override, default=[])
    parser.add_argument('--memory', action='store_true', help="print the preflight's memory estimate [MB] and exit")
    parser.add_argument('--stop-after', type=float, metavar='THETA',
                        help="the rotation only up to its checkpoint at THETA deg, that checkpoint's file copied out")
    arguments = parser.parse_args()
    OVERRIDES.extend(arguments.set)
    if arguments.memory:   # a pull-off needs what its rotation does (the same mesh and solver)
        directory = os.path.join(arguments.work, arguments.level)
        os.makedirs(directory, exist_ok=True)
        scene = DEPENDS.get(arguments.scene, arguments.scene)
        print(memory_estimate_mb(scene_file(directory, arguments.level, scene), directory) or 0)
        return 0
    return run(arguments.work, arguments.level, arguments.scene, arguments.ranks, arguments.launcher,
               arguments.stop_after)


if __name__ == '__main__':
    sys.exit(main())
