#!/usr/bin/env python3
"""Runs the paper's studies (the scenes in xml/studies/) and writes their tables and figures.

    scripts/run-study.py <study> [--jobs 2] [--work DIR] [--mesh LEVEL] [--docs] [--set [SCENE:]LIST/NAME=VALUE ...]

studies: table4 (peel by rotation), table6 (pull-off at 45/60/75/90 deg, also Table 5), stiction, gamma-W (Table 7),
gamma-L (Table 8), rough (Fig. 14), all. Runs use one MPI rank each, `--jobs` of them at once (both cores by default); pull-offs
start as soon as the rotation run they start from has written their checkpoint (a copy of it, <scene>.restart.h5, is
what they read). Progress: one line per converged step of every run (stage, theta_y or u_z, elapsed, an estimate of
what remains).

Stopping and resuming: a study can be stopped at any moment (Ctrl-C, kill, the end of a session). Every run
checkpoints its last converged state every few minutes (Output/checkpoint interval); the next `run-study.py` of the
study goes on with each stopped run from there (`spatula --resume`) and repeats only the steps after the checkpoint.

Mesh level: the scenes in xml/studies/ are written for the medium mesh and tables 4 and 6, the stiction pull-off (it
restarts from the medium rotation) and the rough study run on it. The sweeps (gamma-W, gamma-L: six rotations and
pull-offs) run on the coarse mesh unless `--mesh` says otherwise: on the medium mesh each takes about 25 minutes here,
on the coarse one about 3. `--mesh LEVEL` runs every
scene of the study on LEVEL. A run's scene file is the study XML with the level replaced, written beside its output.

Other settings: `--set 'Linear Solver/refactor=lag'` sets a parameter in every scene of the study (sublists and
parameters are added where missing; a new parameter's type is read from its value: true/false, an integer, a
number, else a string), `--set peel-rotation:Loading/theta_y=90` in one scene only. Such runs are not the study's
own: they are not restored from or kept in results, and --docs is refused (benchmarks/speedup.py runs Table 6
this way with the settings from before issue 15).

Carrying a long run to another machine: with `--carry` the last checkpointed state of every run still going (its
checkpoints, curve, scene and log) is copied to results/<level>/<scene>.stopped/ each time the run writes it;
commit that, and the same command on a new machine resumes the run from there. `--scene NAME` (repeatable) runs only
those scenes of the study, e.g. the fine runs still to come:
`run-study.py all --mesh fine --carry --scene peel-rotation --scene pull-off-75 --scene rough-z0-4`.

Results: <work>/<level>/<scene>/ per run, <work>/<level>/tables/*.csv and *.md, and with --docs docs/validation.md
and its PNGs. Needs a build (build/apps/spatula/spatula). Runs already complete in <work> are not repeated. Each
complete run's curve, scene, log (and a rotation's checkpoints) are kept in results/<level>/<scene>/ (commit
them): a study on another machine or with an empty <work> restores them instead of running them again.
"""
import argparse
import functools
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from xml.etree import ElementTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from convergence import ASSUMED_ORDER, LEVELS, richardson  # noqa: E402
from curves import interpolate, pad_slip, pull_off_summary, read_curve  # noqa: E402
from run_lock import DirectoryInUse, directory_lock  # noqa: E402
from scenes import app_diagnosis  # noqa: E402
from study_figures import field_pictures, plots  # noqa: E402
from study_runs import complete, outcome, started  # noqa: E402
from study_tables import STICTION_RUNS, error_bars, write_tables  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
SCENES = os.path.join(ROOT, 'xml', 'studies')

STUDIES = {
    'table4': ['peel-rotation'],
    'table6': ['peel-rotation', 'pull-off-45', 'pull-off-60', 'pull-off-75', 'pull-off-90'],
    'stiction': ['peel-rotation', 'pull-off-60', 'pull-off-60-stiction', 'pull-off-60-stiction-x-held'],
    'gamma-W': ['peel-rotation', 'pull-off-60', 'gamma-W-0.667', 'gamma-W-1.5', 'gamma-W-2.25'],
    'gamma-L': ['peel-rotation', 'pull-off-60', 'gamma-L-0.444', 'gamma-L-0.667', 'gamma-L-1.5'],
    'rough': ['rough-z0-0', 'rough-z0-4', 'rough-z0-8'],
}
STUDIES['all'] = sorted({scene for scenes in STUDIES.values() for scene in scenes},
                        key=lambda s: (not s.startswith('peel'), s))
DEPENDS = {f'pull-off-{t}': 'peel-rotation' for t in (45, 60, 75, 90, '60-stiction', '60-stiction-x-held')}
# The mesh level each study runs on by default (None: the level written in the scene file).
STUDY_LEVEL = {'gamma-W': 'coarse', 'gamma-L': 'coarse'}


# Parameters set on the command line (--set), applied to every scene file a run reads: (scene or None for every
# scene, sublist path, parameter name, value as text).
OVERRIDES = []


def parse_override(text):
    """'[SCENE:]List/Sublist/name=value' -> (scene or None, ['List', 'Sublist'], 'name', 'value')."""
    match = re.fullmatch(r'(?:([\w.-]+):)?([^=:]+)=(.*)', text)
    if not match or '/' not in match.group(2):
        raise argparse.ArgumentTypeError(f"--set '{text}': expected [SCENE:]List/.../name=value, e.g. "
                                         "'Linear Solver/lag=4' or 'peel-rotation:Loading/theta_y=90'")
    *path, name = match.group(2).split('/')
    return match.group(1), tuple(path), name, match.group(3)


def parameter_type(value):
    """The Teuchos type a new parameter's text asks for: bool, int, double, else string."""
    if value in ('true', 'false'):
        return 'bool'
    if re.fullmatch(r'[-+]?\d+', value):
        return 'int'
    try:
        float(value)
        return 'double'
    except ValueError:
        return 'string'


def apply_overrides(text, scene, overrides):
    """The scene XML with the overrides that concern it set (an existing parameter keeps its type; a missing one,
    and the sublists on its path, are added)."""
    mine = [o for o in overrides if o[0] in (None, scene)]
    if not mine:
        return text
    root = ElementTree.fromstring(text, parser=ElementTree.XMLParser(target=ElementTree.TreeBuilder(
        insert_comments=True)))
    for _, path, name, value in mine:
        node = root
        for sublist in path:
            child = next((c for c in node.findall('ParameterList') if c.get('name') == sublist), None)
            node = child if child is not None else ElementTree.SubElement(node, 'ParameterList', name=sublist)
        parameter = next((c for c in node.findall('Parameter') if c.get('name') == name), None)
        if parameter is None:
            parameter = ElementTree.SubElement(node, 'Parameter', name=name, type=parameter_type(value))
        parameter.set('value', value)
    ElementTree.indent(root)
    return ElementTree.tostring(root, encoding='unicode') + '\n'


def scene_text(scene):
    """xml/studies/<scene>.xml with the command line's --set entries applied (as they are now: the cache is keyed
    by them, so a look-up before they were all read cannot hide them later)."""
    return overridden_scene_text(scene, tuple(OVERRIDES))


@functools.lru_cache(maxsize=None)
def overridden_scene_text(scene, overrides):
    return apply_overrides(open(os.path.join(SCENES, scene + '.xml')).read(), scene, overrides)


def scene_parameter(scene, name):
    """The value (as text) of parameter `name` in the scene (after --set), or None."""
    match = re.search(rf'name="{name}" type="\w+" value="([^"]*)"', scene_text(scene))
    return match.group(1) if match else None


def scene_level(scene):
    return scene_parameter(scene, 'level')


def planned_runs(study, forced_level):
    """(level, scene) pairs of a study, each at its study's level (or at forced_level)."""
    names = [n for n in STUDIES if n != 'all'] if study == 'all' else [study]
    runs = []
    for name in names:
        for scene in STUDIES[name]:
            level = forced_level or STUDY_LEVEL.get(name) or scene_level(scene)
            if level not in LEVELS:   # e.g. 'auto': a study tabulates and extrapolates by named levels
                sys.exit(f"run-study.py: scene {scene} has Mesh/level '{level}'; a study runs at one of "
                         f"{', '.join(LEVELS)} (use --mesh)")
            if (level, scene) not in runs:
                runs.append((level, scene))
    return sorted(runs, key=lambda r: (r[0] != 'coarse', not r[1].startswith('peel'), r[1]))


def scene_file(work, level, scene):
    """The study XML at the given mesh level, written to <work>/<scene>.xml (a pull-off reads its copy of the
    rotation's checkpoints, <scene>.restart.h5)."""
    placement = [(scene, ['Mesh'], 'level', level)]
    if scene in DEPENDS:
        placement.append((scene, ['Loading'], 'restart file', scene + '.restart.h5'))
    text = apply_overrides(scene_text(scene), scene, placement)
    path = os.path.join(work, scene + '.xml')
    open(path, 'w').write(text)
    return path


# A complete run's results are kept in the repository (results/<level>/<scene>/), so that they outlive the
# work directory (a new machine, a cleaned disk): its curve, scene, mesh summary and log, and the checkpoints of a
# rotation that pull-offs start from. A later study restores them into the work directory instead of running again.
ARCHIVE = os.path.join(ROOT, 'results')
KEPT_FILES = ('curve.csv', 'scene.xml', 'mesh_summary.csv', 'mesh_summary.txt', '.spatula-output', 'pad_slip.csv')


def archiving():
    """Whether runs are restored from and kept in ARCHIVE: not when --set changed the scenes (not the study's own)."""
    return not OVERRIDES


def archive(work, level, scene):
    """Copies the complete run's kept files into ARCHIVE/<level>/<scene>/."""
    source, kept = os.path.join(work, level, scene), os.path.join(ARCHIVE, level, scene)
    os.makedirs(kept, exist_ok=True)
    if scene in {name for name, _, _ in STICTION_RUNS}:   # the slip needs the fields, which are not kept
        try:
            pad_slip(os.path.join(work, level), scene, pull_off_summary(os.path.join(work, level), scene)['u_z_at_P_max'])
        except ImportError as error:
            print(f'{scene}: pad slip not measured ({error}); the archive keeps no fields to measure it later')
    names = KEPT_FILES + (('checkpoints.h5',) if scene in DEPENDS.values() else ())
    for name in names:
        if os.path.exists(os.path.join(source, name)):
            shutil.copyfile(os.path.join(source, name), os.path.join(kept, name))
    log = os.path.join(work, level, scene + '.log')
    if os.path.exists(log):
        shutil.copyfile(log, os.path.join(kept, 'run.log'))
    shutil.rmtree(kept + STOPPED_SUFFIX, ignore_errors=True)   # a carried stopped state of it is no longer needed


def put_back(kept, target_directory, log):
    """Copies a kept run (complete or stopped) into target_directory, replacing it whole, and its run.log to `log`.
    Under the run's directory lock: a directory a live run is writing is never replaced (run_lock.DirectoryInUse)."""
    run_directory = re.sub(r'\.(partial|incomplete)$', '', target_directory)
    with directory_lock(run_directory):
        os.makedirs(target_directory + '.restoring', exist_ok=True)
        for name in os.listdir(kept):
            if name != 'run.log':
                shutil.copyfile(os.path.join(kept, name), os.path.join(target_directory + '.restoring', name))
        if os.path.exists(os.path.join(kept, 'run.log')):
            shutil.copyfile(os.path.join(kept, 'run.log'), log)
        shutil.rmtree(target_directory, ignore_errors=True)
        os.replace(target_directory + '.restoring', target_directory)


def restore(work, runs):
    """Puts the archived complete runs among `runs` that <work> lacks back into <work>; returns them."""
    restored = []
    for level, scene in runs:
        kept, target_directory = os.path.join(ARCHIVE, level, scene), os.path.join(work, level, scene)
        if complete(os.path.join(work, level), scene) or not os.path.exists(os.path.join(kept, 'curve.csv')):
            continue
        put_back(kept, target_directory, os.path.join(work, level, scene + '.log'))
        restored.append((level, scene))
    return restored


# With --carry, the last checkpointed state of every run still going is kept in ARCHIVE/<level>/<scene>.stopped/ as
# the run writes it (every 'Output/checkpoint interval' minutes), with its curve, scene and log: commit it, and a
# study on another machine (a new session) resumes the run from there instead of starting it again. Its fields are
# not kept (the resumed run writes its fields from the state it resumes at).
STOPPED_SUFFIX = '.stopped'
CARRIED_FILES = ('checkpoints.h5', 'curve.csv', 'scene.xml', 'mesh_summary.csv', 'mesh_summary.txt', '.spatula-output')


def carry(work, level, scene, carried):
    """Copies the stopped-run files of the running or stopped <scene> into ARCHIVE/<level>/<scene>.stopped/ when its
    checkpoints file has changed since the last copy (`carried`: file -> modification time copied)."""
    for suffix in ('.partial', '.incomplete'):
        source = os.path.join(work, level, scene + suffix)
        checkpoints = os.path.join(source, 'checkpoints.h5')
        kept = os.path.join(ARCHIVE, level, scene + STOPPED_SUFFIX)
        try:
            stamp = os.path.getmtime(checkpoints)
            if carried.get(checkpoints) == stamp:
                return
            shutil.rmtree(kept + '.copying', ignore_errors=True)
            os.makedirs(kept + '.copying')
            # The log first: a checkpoint the log names is then in the copied file (the app writes the file before
            # it logs), so a pull-off on the next machine never waits on a label the carried file lacks.
            log = os.path.join(work, level, scene + '.log')
            if os.path.exists(log):
                shutil.copyfile(log, os.path.join(kept + '.copying', 'run.log'))
            for name in CARRIED_FILES:
                if os.path.exists(os.path.join(source, name)):
                    shutil.copyfile(os.path.join(source, name), os.path.join(kept + '.copying', name))
        except FileNotFoundError:   # the app renamed its directory meanwhile (finished, stopped, resumed): next poll
            shutil.rmtree(kept + '.copying', ignore_errors=True)
            continue
        # Swapped in without a moment with no kept copy: the old one is moved aside first.
        if os.path.exists(kept):
            shutil.rmtree(kept + '.old', ignore_errors=True)
            os.replace(kept, kept + '.old')
        os.replace(kept + '.copying', kept)
        shutil.rmtree(kept + '.old', ignore_errors=True)
        carried[checkpoints] = stamp
        return


def restore_stopped(work, runs):
    """Puts the carried stopped runs among `runs` that <work> has neither complete nor stopped back into <work> as
    stopped runs (<scene>.incomplete/, which `spatula --resume` goes on from); returns them."""
    restored = []
    for level, scene in runs:
        kept, directory = os.path.join(ARCHIVE, level, scene + STOPPED_SUFFIX), os.path.join(work, level)
        if not os.path.exists(os.path.join(kept, 'checkpoints.h5')) or complete(directory, scene) or any(
                os.path.exists(os.path.join(directory, scene + suffix)) for suffix in ('.partial', '.incomplete')):
            continue
        target_directory = os.path.join(directory, scene + '.incomplete')
        put_back(kept, target_directory, os.path.join(directory, scene + '.log'))
        restored.append((level, scene))
    return restored


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
    environment = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
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
                if not os.path.exists(copy):
                    shutil.copyfile(source, copy + '.copying')
                    os.replace(copy + '.copying', copy)
            pending.remove(run)
            xml = scene_file(directory, level, scene)
            resume = resumable(directory, xml)
            if resume:   # the lines already shown by the stopped run are not shown again
                seen[run] = len(step_lines(os.path.join(directory, scene + '.log')))
            log = open(os.path.join(directory, scene + '.log'), 'a' if resume else 'w')
            running[run] = (subprocess.Popen([APP, xml] + (['--resume'] if resume else []), cwd=directory, stdout=log,
                                             stderr=subprocess.STDOUT, env=environment, start_new_session=True),
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


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('study', choices=sorted(STUDIES))
    parser.add_argument('--jobs', type=int, default=2)
    parser.add_argument('--work', default=os.path.join(ROOT, 'study-output'))
    parser.add_argument('--mesh', choices=LEVELS, help='run every scene of the study on this mesh level')
    parser.add_argument('--docs', action='store_true', help='write docs/validation.md and its figures')
    parser.add_argument('--no-run', action='store_true', help='only tabulate (and with --docs, document) the runs present')
    parser.add_argument('--scene', action='append', default=[], metavar='SCENE',
                        help="run only this scene of the study (repeat for more); the tables cover every run present")
    parser.add_argument('--carry', action='store_true',
                        help=f'keep the last checkpointed state of each run in results/<level>/<scene>'
                             f'{STOPPED_SUFFIX}/ as it goes (commit it), and resume the runs kept there')
    parser.add_argument('--set', action='append', type=parse_override, default=[], metavar='[SCENE:]LIST/NAME=VALUE',
                        help="set a parameter in every scene (or in SCENE's only), e.g. --set 'Linear Solver/lag=4'; "
                             'such runs are neither restored from nor kept in results, and --docs is refused')
    arguments = parser.parse_args()
    if arguments.set and arguments.docs:
        parser.error('--docs documents the study scenes as written: it cannot be combined with --set')
    if arguments.set and os.path.abspath(arguments.work) == os.path.abspath(parser.get_default('work')):
        parser.error('--set needs its own --work directory: runs made with other settings must not mix with the '
                     "study's own in " + parser.get_default('work'))
    OVERRIDES.extend(arguments.set)
    unknown = {o[0] for o in arguments.set if o[0]} - {scene for _, scene in planned_runs(arguments.study,
                                                                                             arguments.mesh)}
    if unknown:
        parser.error(f"--set names scene(s) not in study {arguments.study}: {', '.join(sorted(unknown))}")
    if arguments.carry and not archiving():
        parser.error('--carry keeps runs in results, which runs made with --set are not')
    if not os.path.exists(APP):
        sys.exit(f'{APP} not found: build first (bash scripts/build.sh)')
    runs = planned_runs(arguments.study, arguments.mesh)
    if arguments.scene:
        unknown = set(arguments.scene) - {scene for _, scene in runs}
        if unknown:
            parser.error(f"--scene names scene(s) not in study {arguments.study}: {', '.join(sorted(unknown))} "
                         f"(its scenes: {', '.join(scene for _, scene in runs)})")
        chosen = set(arguments.scene)
        for scene in arguments.scene:   # a pull-off needs the rotation it starts from (restored if complete)
            if scene in DEPENDS and DEPENDS[scene] not in chosen:
                print(f'--scene {scene}: with {DEPENDS[scene]}, which it starts from', flush=True)
                chosen.add(DEPENDS[scene])
        runs = [run for run in runs if run[1] in chosen]
    started = time.time()
    for level, scene in runs if archiving() else []:   # complete runs of an earlier study not yet kept
        if complete(os.path.join(arguments.work, level), scene) and not complete(os.path.join(ARCHIVE, level), scene):
            archive(arguments.work, level, scene)
    failed = [] if arguments.no_run else run_all(runs, arguments.work, arguments.jobs, arguments.carry)
    if archiving():   # the tables cover every kept run, at every level (also those no study runs, as the fine
        # level's rotation from 60 deg, and the pull-off at 60 deg its Table 4 is joined to)
        restore(arguments.work, [(level, scene) for level in LEVELS if os.path.isdir(os.path.join(ARCHIVE, level))
                                 for scene in sorted(os.listdir(os.path.join(ARCHIVE, level)))
                                 if not scene.endswith((STOPPED_SUFFIX, STOPPED_SUFFIX + '.copying',
                                                        STOPPED_SUFFIX + '.old'))])
    print(f'study {arguments.study}: {len(runs) - len(failed)} of {len(runs)} runs complete in '
          f'{time.time() - started:.0f} s' + (f'; failed: {", ".join(" ".join(f) for f in failed)}' if failed else ''),
          flush=True)
    results, texts = {}, []
    for level in LEVELS:
        directory = os.path.join(arguments.work, level)
        if os.path.isdir(directory):
            text, summaries = write_tables(directory, STUDIES['all'], level)
            results[level] = (directory, summaries)
            texts.append(text)
    text = '\n'.join(t for t in texts if t)
    if len(results) >= 2:
        text += '\n' + error_bars(results)
    print(text)
    if arguments.docs:
        docs = os.path.join(ROOT, 'docs')
        pictures = plots(results, docs)
        pictures += field_pictures([results[level][0] for level in reversed(LEVELS) if level in results], docs)
        template = open(os.path.join(ROOT, 'docs', 'validation-notes.md')).read()
        with open(os.path.join(docs, 'validation.md'), 'w') as out:
            out.write(template.replace('{{TABLES}}', text).replace(
                '{{FIGURES}}', '\n\n'.join(f'{caption}:\n\n![{caption}]({name})' for name, caption in pictures)))
        print('wrote docs/validation.md')
    return 1 if failed else 0


if __name__ == '__main__':
    try:
        sys.exit(main())
    except DirectoryInUse as error:   # a run of the study's is being written by another process
        print(f'run-study: {error}', file=sys.stderr)
        sys.exit(2)
