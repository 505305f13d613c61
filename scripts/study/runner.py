"""Running a study's scenes: one MPI rank per run, `jobs` at once, a pull-off started once the rotation has written
its checkpoint, stopped runs resumed, one progress line per converged step."""
import os
import re
import shutil
import signal
import subprocess
import time

from convergence import LEVELS
from curves import read_curve
from study.archive import ARCHIVE, STOPPED_SUFFIX, archive, archiving, carry, restore, restore_stopped
from study.runs import complete
from study.scenes import DEPENDS, ROOT, scene_file, scene_parameter

APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))

def checkpoint_ready(directory, dependency, scene):
    """The rotation's checkpoints file once it holds the pull-off's checkpoint (complete run, or one that has logged
    writing it), else None."""
    if complete(directory, dependency):
        return os.path.join(directory, dependency, 'checkpoints.h5')
    log = os.path.join(directory, dependency + '.log')
    label = f"checkpoint theta_y={float(scene_parameter(scene, 'restart theta_y')):g} written"
    if os.path.exists(log) and label in open(log).read():
        for suffix in ('.partial', '.incomplete'):
            path = os.path.join(directory, dependency + suffix, 'checkpoints.h5')
            if os.path.exists(path):
                return path
    return None


# One BLAS and one Kokkos thread per rank: ranks are what pay here (docs/performance.md).
RUN_ENVIRONMENT = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')


def copy_restart(directory, scene, source):
    """Copies the rotation's checkpoints file `source` to <directory>/<scene>.restart.h5 (what the pull-off reads),
    whole or not at all, unless it is there."""
    copy = os.path.join(directory, scene + '.restart.h5')
    if not os.path.exists(copy):
        shutil.copyfile(source, copy + '.copying')
        os.replace(copy + '.copying', copy)


def resumable(directory, scene_xml):
    """Whether the app finds a stopped run of this scene to go on from (`--resume --validate-only`)."""
    result = subprocess.run([APP, scene_xml, '--resume', '--validate-only'], cwd=directory, capture_output=True)
    return result.returncode == 0


def target(scene):
    """(stage, final value) the scene's loading ends at: the rotation's theta_y, or the lift's final u_z (relative)."""
    if scene_parameter(scene, 'type') == 'rotation':
        return 'rotation', float(scene_parameter(scene, 'theta_y'))
    return 'lift', float(scene_parameter(scene, 'final lift'))


def progress(work, run, line, elapsed, origin):
    """The run's progress line: stage, theta_y or u_z, elapsed, and what remains at the pace so far (to the scene's
    final load; a pull-off ends earlier, at detachment: its estimate uses the coarser level's detachment when
    there is one)."""
    level, scene = run
    match = re.search(r'step\s+(\d+)\s+(\w+)\s+theta_y\s+([-\d.]+)\s+deg\s+u_z\s+([-\d.]+)\s+nm', line)
    if not match:
        return f'[{level} {scene}] {" ".join(line.split())[:170]}'
    step, stage, theta, lift = match.group(1), match.group(2), float(match.group(3)), float(match.group(4))
    value = theta if stage == 'rotation' else lift
    kind, end = target(scene)
    if stage == 'lift' and kind == 'lift':
        for coarser in LEVELS[:LEVELS.index(level)][::-1]:
            rows = read_curve(os.path.join(work, coarser), scene) if complete(os.path.join(work, coarser), scene) else None
            if rows:
                start = next(float(r['u_z_nm']) for r in rows if r['stage'] == 'lift')
                end = float(rows[-1]['u_z_nm']) - start
                break
    origin.setdefault((run, stage), (value, elapsed))   # where this stage's pace is measured from
    first_value, first_time = origin[(run, stage)]
    done = value - first_value
    remaining = ''
    if stage == kind and done > 0 and elapsed > first_time:
        goal = end if kind == 'rotation' else first_value + end
        minutes = max(0.0, goal - value) * (elapsed - first_time) / done / 60
        remaining = f', about {minutes:.{1 if minutes < 10 else 0}f} min left at this pace'
    unit = 'deg' if stage == 'rotation' else 'nm'
    name = 'theta_y' if stage == 'rotation' else 'u_z'
    return f'[{level} {scene}] step {step} {stage} {name} = {value:.3f} {unit}, {elapsed / 60:.1f} min{remaining}'


def step_lines(log):
    lines = open(log).read().splitlines() if os.path.exists(log) else []
    return [l for l in lines if l.startswith('step ') or 'jump' in l or 'detachment' in l]


def run_all(runs, work, jobs, carrying=False):
    """Runs the (level, scene) pairs not yet complete in <work>/<level>, `jobs` at a time (a stopped one resumed from
    its last checkpoint; with `carrying`, also one carried in ARCHIVE); returns the failed ones."""
    for level, scene in restore(work, runs) if archiving() else []:
        print(f'[{level} {scene}] restored from {os.path.relpath(ARCHIVE, ROOT)}/ (complete)', flush=True)
    for level, scene in restore_stopped(work, runs) if carrying else []:
        print(f'[{level} {scene}] stopped run restored from {os.path.relpath(ARCHIVE, ROOT)}/{level}/{scene}'
              f'{STOPPED_SUFFIX}/', flush=True)
    carried = {}
    pending = [r for r in runs if not complete(os.path.join(work, r[0]), r[1])]
    running = {}
    failed = []
    seen = {}
    origin = {}
    while pending or running:
        for run in list(pending):
            if len(running) >= jobs:
                break
            level, scene = run
            directory = os.path.join(work, level)
            os.makedirs(directory, exist_ok=True)
            dependency = DEPENDS.get(scene)
            if dependency:
                source = checkpoint_ready(directory, dependency, scene)
                copy = os.path.join(directory, scene + '.restart.h5')
                if not source and not os.path.exists(copy):
                    if (level, dependency) not in running and (level, dependency) not in pending:
                        print(f'[{level} {scene}] waits for {dependency}, which failed', flush=True)
                        pending.remove(run)
                        failed.append(run)
                    continue
                if source:
                    copy_restart(directory, scene, source)
            pending.remove(run)
            xml = scene_file(directory, level, scene)
            resume = resumable(directory, xml)
            if resume:   # the lines already shown by the stopped run are not shown again
                seen[run] = len(step_lines(os.path.join(directory, scene + '.log')))
            log = open(os.path.join(directory, scene + '.log'), 'a' if resume else 'w')
            running[run] = (subprocess.Popen([APP, xml] + (['--resume'] if resume else []), cwd=directory, stdout=log,
                                             stderr=subprocess.STDOUT, env=RUN_ENVIRONMENT, start_new_session=True),
                            log, time.time())
            print(f'[{level} {scene}] ' + ('resumed from its last checkpoint' if resume else 'started'), flush=True)
        try:
            time.sleep(5)
        except KeyboardInterrupt:   # each run stops at its next converged state and checkpoints it: wait for that
            print('interrupted: the runs stop at their next converged state (Ctrl-C again ends them at once); '
                  'the same command resumes them', flush=True)
            for process, _, _ in running.values():
                process.send_signal(signal.SIGINT)
            for process, _, _ in running.values():
                process.wait()
            for level, scene in running if carrying else []:
                carry(work, level, scene, carried)
            raise
        for run, (process, log, started) in list(running.items()):
            level, scene = run
            if carrying:
                carry(work, level, scene, carried)
            steps = step_lines(os.path.join(work, level, scene + '.log'))
            for line in steps[seen.get(run, 0):]:
                wall = re.search(r'([\d.]+) s$', line.strip())
                print(progress(work, run, line, float(wall.group(1)) if wall else time.time() - started, origin),
                      flush=True)
            seen[run] = len(steps)
            if process.poll() is not None:
                log.close()
                status = 'done' if process.returncode == 0 else f'failed (exit {process.returncode})'
                print(f'[{level} {scene}] {status} after {time.time() - started:.0f} s', flush=True)
                if process.returncode != 0:
                    failed.append(run)
                    if carrying:
                        carry(work, level, scene, carried)
                elif archiving() and complete(os.path.join(work, level), scene):
                    archive(work, level, scene)
                del running[run]
    return failed
