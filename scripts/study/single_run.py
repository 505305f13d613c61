"""One run of a study scene, as a workflow job runs it (scripts/workflow/Snakefile): restored from results/ where
it is kept there, else the scene file written, the rotation's checkpoint copied for a pull-off, a stopped run
resumed (`spatula --resume`), the app run with its ranks (a line per converged step on the standard output: stage,
theta_y or u_z, elapsed, what remains at the pace so far; the app's own output in <work>/<level>/<scene>.log), and
the complete run kept in results/.

    python3 scripts/study/single_run.py --work DIR --level LEVEL --scene SCENE [--ranks N] [--launcher mpiexec|srun]
        [--set [SCENE:]LIST/NAME=VALUE ...] [--stop-after THETA] [--carry]

With --carry, the run's last checkpointed state (checkpoints, curve, scene, log; not its fields) is copied to
results/<level>/<scene>.stopped/ each time the app writes it: commit that, and the same job on another machine
resumes the run from there.

With --stop-after, the rotation only up to its checkpoint at THETA deg (`spatula --stop-after-checkpoint`), the
job that a pull-off from there waits for: its checkpoints file is copied to
<work>/<level>/<scene>.checkpoint-<THETA>.h5, and the rotation is left stopped there for the next part to resume.

Exit status: the app's (0: the run is complete in <work>/<level>/<scene>/, or with --stop-after its checkpoint is
copied)."""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import h5py

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from study.app import APP, RUN_ENVIRONMENT, copy_restart, launch, memory_estimate_mb, resumable  # noqa: E402
from study.archive import (archive, archive_ended, archiving, carry, restore, restore_ended,  # noqa: E402
                           restore_stopped)
from study.progress import progress, step_lines  # noqa: E402
from study.runs import checkpoint_copy, complete, keep_aside, stopped  # noqa: E402
from study.scenes import DEPENDS, OVERRIDES, parse_override, restart_angle, scene_file  # noqa: E402


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


def run(work, level, scene, ranks=1, launcher='mpiexec', stop_after=None, carrying=False):
    directory = os.path.join(work, level)
    os.makedirs(directory, exist_ok=True)
    if archiving() and restore(work, [(level, scene)]):
        print(f'[{level} {scene}] restored from results/ (complete)', flush=True)
    if carrying and restore_stopped(work, [(level, scene)]):
        print(f'[{level} {scene}] stopped run restored from results/{level}/{scene}.stopped/', flush=True)
    if archiving() and restore_ended(work, [(level, scene)]):   # it would end the same way again
        print(f'[{level} {scene}] restored from results/{level}/{scene}.incomplete/ as it ended (a solver failure, '
              f'see its FAILURE.txt; remove that directory to run it again)', flush=True)
        return 1
    if stop_after is not None:
        return run_part(work, level, scene, stop_after, ranks, launcher, carrying)
    if complete(directory, scene):
        return 0
    dependency = DEPENDS.get(scene)
    if dependency:   # the rotation's checkpoint the pull-off starts from (a file dependency of the workflow)
        copy_restart(directory, scene, checkpoint_copy(work, level, dependency, restart_angle(scene)))
    status = run_app(directory, level, scene, ranks, launcher, carrying=carrying)
    if status == 0 and archiving() and complete(directory, scene):
        archive(work, level, scene)
    if status == 1 and archiving() and archive_ended(work, level, scene):
        print(f'[{level} {scene}] ended with a solver failure: kept in results/{level}/{scene}.incomplete/', flush=True)
    print(f'[{level} {scene}] ' + ('done' if status == 0 else f'failed (exit {status})'), flush=True)
    return status


def run_app(directory, level, scene, ranks, launcher, options=(), carrying=False):
    """Runs the app on the scene (resuming a stopped run of it), a progress line per converged step, and with
    `carrying` its last checkpointed state kept in results/<level>/<scene>.stopped/ as it goes; returns the app's
    exit status. Interrupted (Ctrl-C), the app stops at its next converged state and checkpoints it: waited for."""
    xml = scene_file(directory, level, scene)
    resume, refusal = resumable(directory, xml)
    if not resume and stopped(directory, scene):
        aside = keep_aside(directory, scene)
        print(f'[{level} {scene}] its stopped run cannot be resumed ({refusal}), so it starts again; the stopped run '
              f'is kept in {aside}/', flush=True)
    log_path = os.path.join(directory, scene + '.log')
    seen = len(step_lines(log_path)) if resume else 0   # the lines a stopped run showed are not shown again
    work = os.path.dirname(directory)
    origin, carried = {}, {}
    with open(log_path, 'a' if resume else 'w') as log:
        print(f'[{level} {scene}] ' + ('resumed from its last checkpoint' if resume else 'started') +
              (f' ({" ".join(options)})' if options else ''), flush=True)
        command = launch(ranks, launcher) + [APP, xml] + (['--resume'] if resume else []) + list(options)
        process = subprocess.Popen(command, cwd=directory, stdout=log, stderr=subprocess.STDOUT, env=RUN_ENVIRONMENT)
        started = time.time()
        while True:
            try:
                ended = process.wait(timeout=2) is not None
            except subprocess.TimeoutExpired:
                ended = False
            except KeyboardInterrupt:
                process.send_signal(signal.SIGINT)
                process.wait()
                ended = True
            steps = step_lines(log_path)
            for line in steps[seen:]:
                wall = re.search(r'([\d.]+) s$', line.strip())
                print(progress(work, (level, scene), line, float(wall.group(1)) if wall else time.time() - started,
                               origin), flush=True)
            seen = len(steps)
            if carrying:
                carry(work, level, scene, carried)
            if ended:
                return process.returncode


def run_part(work, level, scene, theta, ranks, launcher, carrying):
    """The rotation up to its checkpoint at theta (unless it has passed it), that checkpoint's file copied out."""
    directory = os.path.join(work, level)
    copy = checkpoint_copy(work, level, scene, theta)
    source = written_checkpoints(directory, scene, theta)
    if not source:
        status = run_app(directory, level, scene, ranks, launcher, ['--stop-after-checkpoint', f'{theta:g}'],
                         carrying)
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
    parser.add_argument('--carry', action='store_true',
                        help='keep the last checkpointed state of the run in results/<level>/<scene>.stopped/ as it '
                             'goes (commit it), and resume a run kept there')
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
    if arguments.carry and not archiving():
        parser.error('--carry keeps runs in results, which runs made with --set are not')
    return run(arguments.work, arguments.level, arguments.scene, arguments.ranks, arguments.launcher,
               arguments.stop_after, arguments.carry)


if __name__ == '__main__':
    sys.exit(main())
