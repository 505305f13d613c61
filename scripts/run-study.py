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
own: they are not restored from or kept in docs/study-runs, and --docs is refused (benchmarks/speedup.py runs Table 6
this way with the settings from before issue 15).

Carrying a long run to another machine: with `--carry` the last checkpointed state of every run still going (its
checkpoints, curve, scene and log) is copied to docs/study-runs/<level>/<scene>.stopped/ each time the run writes it;
commit that, and the same command on a new machine resumes the run from there. `--scene NAME` (repeatable) runs only
those scenes of the study, e.g. the fine runs still to come:
`run-study.py all --mesh fine --carry --scene peel-rotation --scene pull-off-75 --scene rough-z0-4`.

Results: <work>/<level>/<scene>/ per run, <work>/<level>/tables/*.csv and *.md, and with --docs docs/validation.md
and its PNGs. Needs a build (build/apps/spatula/spatula). Runs already complete in <work> are not repeated. Each
complete run's curve, scene, log (and a rotation's checkpoints) are kept in docs/study-runs/<level>/<scene>/ (commit
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
# Fig. 9's pull-offs at 60 deg: (scene, label, end face free in X), for its table and its plot.
STICTION_RUNS = (('pull-off-60', 'frictionless', False),
                 ('pull-off-60-stiction', 'stiction, end face free in X', True),
                 ('pull-off-60-stiction-x-held', 'stiction, end face held in X', False))
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

# The paper's values this project may use (its Tables 4, 5 and 6 and Pi_c0 of Sec. 3; docs/validation.md); the rest
# are held out.
PAPER_TABLE4 = {30: (0.237, 0.222, 0.013), '31-': (0.255, 0.232, 0.021), '31+': (0.255, 0.182, 0.071),
                60: (0.689, 0.395, 0.291), 90: (1.088, 0.545, 0.540), 120: (1.455, 0.728, 0.724),
                128: (1.551, 0.738, 0.811)}
PAPER_TABLE6 = {45: (7.63, 248, 1097), 60: (6.67, 185, 701), 75: (5.59, 125, 422), 90: (4.40, 80, 235)}
PAPER_TABLE5_START = {45: 0.463, 60: 0.689, 75: 0.897, 90: 1.088}
PAPER_PI_C0 = 759.3   # E R0^3, the paper's exact-law contact energy of the undeformed spatula (its area)


def complete(work, scene):
    return os.path.exists(os.path.join(work, scene, 'curve.csv'))


# A complete run's results are kept in the repository (docs/study-runs/<level>/<scene>/), so that they outlive the
# work directory (a new machine, a cleaned disk): its curve, scene, mesh summary and log, and the checkpoints of a
# rotation that pull-offs start from. A later study restores them into the work directory instead of running again.
ARCHIVE = os.path.join(ROOT, 'docs', 'study-runs')
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


def outcome(work, scene):
    """How a pull-off ended: detached, or stopped with the app's diagnosis (Delta u_z and Delta Pi_ext are then
    taken to the last converged state, just before the snap the jump could not follow)."""
    log = os.path.join(work, scene + '.log')
    if complete(work, scene):
        summary = pull_off_summary(work, scene)
        if 'detached' not in summary:   # the run ended during its rotation: the app detected detachment there
            lines = [l for l in open(log).read().splitlines() if l.startswith('detachment:')] if os.path.exists(log) else []
            return 'detached during the rotation, before the lift' + (f' ({lines[-1]})' if lines else '')
        return 'detached' if summary['detached'] else 'final lift reached'

    diagnosis = app_diagnosis(open(log).read()) if os.path.exists(log) else None
    if diagnosis:
        return 'stopped: ' + diagnosis + ' (values up to the last converged state)'
    return 'did not finish (values up to the last converged state)'


def started(work, scene):
    """Complete, or stopped with the curve up to its last converged state in <scene>.incomplete/."""
    return complete(work, scene) or os.path.exists(os.path.join(work, scene + '.incomplete', 'curve.csv'))


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


def rotation_curve(work):
    """(rows, source) of a level's peel by rotation: the peel-rotation run ('peel-rotation'); where that run restarted
    from a checkpoint of the rotation that precedes the pull-off at 60 deg (the fine level's, run in segments), that
    rotation's states before the restart and then the run's ('pull-off-60 + peel-rotation'); where a level has no
    peel-rotation (the fine level ran only the pull-off at 60 deg) the rotation stage of its pull-off at 60 deg
    ('pull-off-60'); (None, None) without either."""
    earlier = None
    if started(work, 'pull-off-60'):
        earlier = [r for r in read_curve(work, 'pull-off-60') if r['stage'] == 'rotation']
        earlier = earlier if len(earlier) > 1 else None
    run = rotation_run(work)
    if run:
        rows = read_curve(work, run)
        if earlier and rows and rows[0]['step'] > 0 and rows[0]['theta_y_deg'] > earlier[0]['theta_y_deg']:
            start = rows[0]['theta_y_deg']
            return [r for r in earlier if r['theta_y_deg'] < start - 1e-9] + rows, 'pull-off-60 + peel-rotation'
        return rows, 'peel-rotation'
    if earlier:
        return earlier, 'pull-off-60'
    return None, None


# A peel by rotation kept under another name: the fine level's rotation from 60 deg (twelfth session), restarted from
# the 60 deg state of the pull-off at 60 deg, whose checkpoints were lost with its machine. A study's own peel-rotation
# run (from the undeformed state) takes its place once complete.
EARLIER_ROTATION = 'peel-rotation-from-60'


def rotation_run(work):
    """The peel-rotation run a level's Table 4 reads: the study's own when complete, else the earlier one kept under
    EARLIER_ROTATION, else the study's own stopped run (its curve up to where it stopped); None without any."""
    if complete(work, 'peel-rotation'):
        return 'peel-rotation'
    if complete(work, EARLIER_ROTATION):
        return EARLIER_ROTATION
    return 'peel-rotation' if started(work, 'peel-rotation') else None


def table4(work):
    rows, source = rotation_curve(work)
    columns = ['Pi_ext_per_Pi_c0', 'Pi_int_per_Pi_c0', 'Pi_sa_per_Pi_c0', 'balance_error_per_Pi_c0', 'M_y_nNnm']
    out = []
    for theta in (30, 60, 90, 120):
        values = interpolate(rows, 'theta_y_deg', theta, columns)
        if values:
            out.append((str(theta), theta, values, PAPER_TABLE4[theta]))
    if source == 'pull-off-60':   # a rotation to 60 deg only: no detachment
        return out, rows
    # The first instability: the first jump after which the moment dropped by more than 10 %; only where the curve
    # starts at the undeformed state (a curve that starts from a restart may begin after it).
    for i, row in enumerate(rows if rows[0]['step'] == 0 else []):
        if row['after_jump'] == 1 and row['M_y_nNnm'] < 0.9 * rows[i - 1]['M_y_nNnm']:
            out.insert(1, ('31- (before the first drop)', rows[i - 1]['theta_y_deg'], rows[i - 1], PAPER_TABLE4['31-']))
            out.insert(2, ('31+ (after it)', row['theta_y_deg'], row, PAPER_TABLE4['31+']))
            break
    # The last state before detachment: the final row is the detached state when the run ended by a collapse.
    peak = max(abs(r['M_y_nNnm']) for r in rows)
    detached = len(rows) > 1 and abs(rows[-1]['M_y_nNnm']) < 0.01 * peak
    last = rows[-2] if detached else rows[-1]
    label = '128 (last state before detachment)' if detached else '128 (paper) / our last state: not detached'
    out.append((label, last['theta_y_deg'], last, PAPER_TABLE4[128]))
    return out, rows


def percent(ours, paper):
    return f'{100.0 * (ours / paper - 1.0):+.1f} %' if paper else ''


def write_tables(work, scenes, level):
    """The tables of the runs in work (one mesh level), as Markdown (also written to <work>/tables/)."""
    tables = os.path.join(work, 'tables')
    os.makedirs(tables, exist_ok=True)
    markdown = []
    rotation_rows, rotation_source = rotation_curve(work)
    if rotation_rows:
        entries, rows = table4(work)
        markdown.append(f'### Table 4: peeling by rotation (values / Pi_c0) ({level} mesh)\n')
        if rotation_source == 'pull-off-60':
            markdown.append(f'From the rotation that precedes the pull-off at 60 deg (this level has no peel to '
                            f'detachment; its curve starts at theta_y = {rows[0]["theta_y_deg"]:.2f} deg).\n')
        elif rotation_source != 'peel-rotation':
            markdown.append(f'From the rotation that precedes the pull-off at 60 deg up to the checkpoint the '
                            f'peel-rotation run restarted from, then that run; the curve starts at theta_y = '
                            f'{rows[0]["theta_y_deg"]:.2f} deg, so the first instability is not in it.\n')
        markdown.append('| theta_y | ours: theta_y [deg] | Pi_ext ours / paper | Pi_int ours / paper | Pi_sa ours / paper '
                        '| balance error |')
        markdown.append('|---|---|---|---|---|---|')
        with open(os.path.join(tables, 'table4.csv'), 'w') as out:
            out.write('label,theta_y_deg,Pi_ext,Pi_int,Pi_sa,paper_Pi_ext,paper_Pi_int,paper_Pi_sa\n')
            for label, theta, v, p in entries:
                out.write(f'{label},{theta:.3f},{v["Pi_ext_per_Pi_c0"]:.4f},{v["Pi_int_per_Pi_c0"]:.4f},'
                          f'{v["Pi_sa_per_Pi_c0"]:.4f},{p[0]},{p[1]},{p[2]}\n')
                markdown.append(
                    f'| {label} | {theta:.2f} | {v["Pi_ext_per_Pi_c0"]:.3f} / {p[0]} ({percent(v["Pi_ext_per_Pi_c0"], p[0])}) '
                    f'| {v["Pi_int_per_Pi_c0"]:.3f} / {p[1]} ({percent(v["Pi_int_per_Pi_c0"], p[1])}) '
                    f'| {v["Pi_sa_per_Pi_c0"]:.3f} / {p[2]} ({percent(v["Pi_sa_per_Pi_c0"], p[2])}) '
                    f'| {v["balance_error_per_Pi_c0"]:.1e} |')
        markdown.append('')
        # The same energies in units of the paper's Pi_c0 (its contact area is 1.4 % smaller than ours): the
        # deformation energies are absolute, so this is the like-for-like comparison of Pi_ext and Pi_int.
        row = next(r for r in rows if r['Pi_ext_per_Pi_c0'] > 0.01 and abs(r['M_y_per_ER0^3']) > 0.01)
        young_r0_cubed = row['M_y_nNnm'] / row['M_y_per_ER0^3']   # E R0^3 in nN nm = 1e-18 J
        ours = row['Pi_ext_1e-18J'] / row['Pi_ext_per_Pi_c0'] / young_r0_cubed
        scale = ours / PAPER_PI_C0
        markdown.append(f'The same in units of the paper\'s Pi_c0 = {PAPER_PI_C0} E R0^3 (ours is {ours:.1f} E R0^3: '
                        f'values x {scale:.4f}):\n')
        markdown.append('| theta_y | Pi_ext ours / paper | Pi_int ours / paper | Pi_sa ours / paper |')
        markdown.append('|---|---|---|---|')
        for label, theta, v, p in entries:
            cells = [f'{scale * v[k]:.3f} / {q} ({percent(scale * v[k], q)})'
                     for k, q in zip(('Pi_ext_per_Pi_c0', 'Pi_int_per_Pi_c0', 'Pi_sa_per_Pi_c0'), p)]
            markdown.append(f'| {label} | ' + ' | '.join(cells) + ' |')
        markdown.append('')
    summaries, unfinished = {}, []
    for scene in scenes:
        if (scene.startswith('pull-off') or scene.startswith('gamma')) and started(work, scene):
            summary = dict(pull_off_summary(work, scene), outcome=outcome(work, scene))
            if summary['rows']:
                summaries[scene] = summary
            else:   # stopped before the lift began
                last = read_curve(work, scene)[-1]
                unfinished.append(f'- `{scene}`, during the rotation at theta_y = {last["theta_y_deg"]:.1f} deg: '
                                  f'{summary["outcome"]}')
    pulls = [t for t in (45, 60, 75, 90) if f'pull-off-{t}' in summaries]
    if pulls:
        markdown.append(f'### Table 6: pull-off at fixed inclination ({level} mesh)\n')
        markdown.append('| theta_y | P_max [nN] ours / paper | Delta u_z [nm] ours / paper | Delta Pi_ext [1e-18 J] ours / paper |')
        markdown.append('|---|---|---|---|')
        with open(os.path.join(tables, 'table6.csv'), 'w') as out:
            out.write('theta_y_deg,P_max_nN,delta_u_z_nm,delta_Pi_ext_1e-18J,paper_P_max,paper_delta_u_z,'
                      'paper_delta_Pi_ext,detached\n')
            for t in pulls:
                s, p = summaries[f'pull-off-{t}'], PAPER_TABLE6[t]
                out.write(f'{t},{s["P_max_nN"]:.4f},{s["delta_u_z_nm"]:.2f},{s["delta_Pi_ext_1e-18J"]:.1f},'
                          f'{p[0]},{p[1]},{p[2]},{s["detached"]}\n')
                markdown.append(f'| {t} | {s["P_max_nN"]:.2f} / {p[0]} ({percent(s["P_max_nN"], p[0])}) '
                                f'| {s["delta_u_z_nm"]:.0f} / {p[1]} ({percent(s["delta_u_z_nm"], p[1])}) '
                                f'| {s["delta_Pi_ext_1e-18J"]:.0f} / {p[2]} ({percent(s["delta_Pi_ext_1e-18J"], p[2])}) |'
                                + ('' if s['outcome'] == 'detached' else f' {s["outcome"]}'))
        markdown.append('')
        markdown.append(f'### Detachment: the main snap (the tables\' values) and the final detachment ({level} mesh)\n')
        markdown.append('The paper takes the state before the main snap (the jump that drops the pull the most); a '
                        'small patch of the pad can stay attached after it (the tail) until the pull falls below 1 % '
                        'of its peak (the final detachment).\n')
        markdown.append('| theta_y | Delta u_z to the main snap [nm] | P_z after it [nN] | energy it released / Pi_c0 '
                        '| Delta u_z to the final detachment [nm] | tail: length [nm], work [1e-18 J] |')
        markdown.append('|---|---|---|---|---|---|')
        with open(os.path.join(tables, 'detachment.csv'), 'w') as out:
            out.write('theta_y_deg,delta_u_z_main_nm,P_after_main_nN,released_main_per_Pi_c0,delta_u_z_final_nm,'
                      'tail_u_z_nm,tail_Pi_ext_1e-18J\n')
            for t in pulls:
                s = summaries[f'pull-off-{t}']
                out.write(f'{t},{s["delta_u_z_nm"]:.2f},{s["main_snap_P_after_nN"]:.4f},'
                          f'{s["main_snap_released_per_Pi_c0"]:.4f},{s["final_delta_u_z_nm"]:.2f},'
                          f'{s["tail_u_z_nm"]:.2f},{s["tail_Pi_ext_1e-18J"]:.1f}\n')
                markdown.append(f'| {t} | {s["delta_u_z_nm"]:.1f} | {s["main_snap_P_after_nN"]:.2f} '
                                f'| {s["main_snap_released_per_Pi_c0"]:.3f} | {s["final_delta_u_z_nm"]:.1f} '
                                f'| {s["tail_u_z_nm"]:.1f}, {s["tail_Pi_ext_1e-18J"]:.0f} |')
        markdown.append('')
        markdown.append(f'### Table 5: work and stored energies prior to detachment (values / Pi_c0) ({level} mesh)\n')
        markdown.append('| theta_y | Pi_ext,0 ours / paper | Delta Pi_ext | Pi_ext | Pi_int | Pi_sa | worst balance error |')
        markdown.append('|---|---|---|---|---|---|---|')
        for t in pulls:
            s = summaries[f'pull-off-{t}']
            markdown.append(f'| {t} | {s["Pi_ext0_per_Pi_c0"]:.3f} / {PAPER_TABLE5_START[t]} '
                            f'| {s["delta_Pi_ext_per_Pi_c0"]:.3f} | {s["Pi_ext_per_Pi_c0"]:.3f} '
                            f'| {s["Pi_int_per_Pi_c0"]:.3f} | {s["Pi_sa_per_Pi_c0"]:.3f} | {s["worst_balance_error"]:.1e} |')
        markdown.append('')
    for title, prefix, base in (('Table 7: adhesion strength gamma_W / gamma_W0 (theta_y = 60 deg)', 'gamma-W', 1.0),
                                ('Table 8: length scale gamma_L / gamma_L0 (theta_y = 60 deg)', 'gamma-L', 1.0)):
        runs = sorted((float(s.split('-')[-1]), s) for s in summaries if s.startswith(prefix))
        if 'pull-off-60' in summaries:
            runs = sorted(runs + [(base, 'pull-off-60')])
        if len(runs) > 1 or (runs == [(base, 'pull-off-60')] and level == LEVELS[-1]):
            markdown.append(f'### {title} ({level} mesh)\n')
            if len(runs) == 1:
                markdown.append('Only the factor-1 cell (the pull-off at 60 deg): the sweep was not run at this level.\n')
            own = [r for r in read_curve(work, 'pull-off-60') if r['stage'] == 'rotation'] \
                if 'pull-off-60' in summaries else []   # one state where it starts from the peel run's checkpoint
            first = own[0]['theta_y_deg'] if len(own) > 1 else 0.0
            if first > 0.0 and own[0]['Pi_ext_1e-18J'] > 0.0:   # its own rotation resumed from a checkpoint (a fresh
                # one starts unloaded): the curve holds only what came after
                markdown.append(f'The pull-off at 60 deg\'s curve starts at theta_y = {first:.2f} deg (a run resumed '
                                'from a checkpoint): jumps of its rotation before that are not counted.\n')
            markdown.append('The path of each point (the sweep compares like with like only if they follow the same '
                            'kind): Pi_sa / Pi_c0 when the lift begins (how much adhesion the rotation to 60 deg '
                            'already gave up) and the jumps in the rotation and in the lift.\n')
            markdown.append('| factor | P_max [nN] | Delta u_z [nm] | Delta Pi_ext [1e-18 J] | Pi_sa / Pi_c0 at the lift\'s '
                            'start | jumps: rotation, lift | end of the run |')
            markdown.append('|---|---|---|---|---|---|---|')
            for factor, scene in runs:
                s = summaries[scene]
                rotation_jumps = s['jumps_in_rotation']
                if scene == 'pull-off-60' and rotation_source == 'peel-rotation':   # its rotation is the peel run's
                    rotation_jumps = sum(1 for r in rotation_rows if r['after_jump'] and r['theta_y_deg'] <= 60.0 + 1e-9)
                markdown.append(f'| {factor:g} | {s["P_max_nN"]:.2f} | {s["delta_u_z_nm"]:.0f} | {s["delta_Pi_ext_1e-18J"]:.0f} '
                                f'| {s["Pi_sa_at_lift_start"]:.3f} | {rotation_jumps}, {s["jumps_in_lift"]} '
                                f'| {s["outcome"]} |')
            markdown.append('')
    if 'pull-off-60' in summaries and any(scene in summaries for scene, _, _ in STICTION_RUNS[1:]):
        markdown.append(f'### Stiction vs frictionless at 60 deg ({level} mesh)\n')
        markdown.append('| law | P_max [nN] | Delta u_z [nm] | Delta Pi_ext [1e-18 J] | slip of the adhering pad by P_max '
                        '| end face X travel by P_max | end of the run |')
        markdown.append('|---|---|---|---|---|---|---|')
        for scene, name, free_in_x in STICTION_RUNS:
            if scene not in summaries:
                continue
            s = summaries[scene]
            slip = pad_slip(work, scene, s['u_z_at_P_max'])
            slip_text = (f'{slip[1]:.1f} nm ({slip[2]} nodes, state at u_z = {slip[0]:.0f} nm)' if slip else '')
            peak = max(s['rows'], key=lambda r: r['P_z_nN'])
            travel = (f'{peak["u_x_nm"] - s["start"]["u_x_nm"]:.1f} nm' if 'u_x_nm' in peak
                      else 'not recorded' if free_in_x else '0 (held)')
            markdown.append(f'| {name} | {s["P_max_nN"]:.2f} | {s["delta_u_z_nm"]:.0f} | {s["delta_Pi_ext_1e-18J"]:.0f} '
                            f'| {slip_text} | {travel} | {s["outcome"]} |')
        markdown.append('')
    if unfinished:
        markdown.append(f'### Runs that stopped before their pull-off ({level} mesh)\n')
        markdown += unfinished + ['']
    rough = [(z0, read_curve(work, f'rough-z0-{z0}'), complete(work, f'rough-z0-{z0}')) for z0 in (0, 4, 8)
             if started(work, f'rough-z0-{z0}')]
    if rough:
        markdown.append(f'### Rough substrates, rotation to 45 deg with zero net force (cf. paper Fig. 14) ({level} mesh)\n')
        markdown.append('| z0 [nm] | reached theta_y [deg] | M_y at 30 deg [nN nm] | largest M_y [nN nm] | Pi_sa / Pi_c0 at the last state '
                        '| worst balance error |')
        markdown.append('|---|---|---|---|---|---|')
        for z0, rows, done in rough:
            at30 = interpolate(rows, 'theta_y_deg', 30.0, ['M_y_nNnm'])
            markdown.append(f'| {z0} | {rows[-1]["theta_y_deg"]:.1f}{"" if done else " (run not finished)"} '
                            f'| {at30["M_y_nNnm"]:.0f} | {max(r["M_y_nNnm"] for r in rows):.0f} '
                            f'| {rows[-1]["Pi_sa_per_Pi_c0"]:.3f} '
                            f'| {max(r["balance_error_per_Pi_c0"] for r in rows):.1e} |' if at30 else
                            f'| {z0} | {rows[-1]["theta_y_deg"]:.1f} (not finished) | | | | |')
        markdown.append('')
    text = '\n'.join(markdown)
    open(os.path.join(tables, 'tables.md'), 'w').write(text)
    return text, summaries


def error_bars(results):
    """Markdown: each Table 6-8 quantity (and Table 4's energies at 30, 60, 90 deg) on every level run, as
    `value ± estimate` on the finest with the extrapolated value (Richardson), for the scenes run on two levels or
    more. A cell whose runs ended differently on the levels (detached on one, not on another), or whose levels differ
    by more than a factor PATH_CHANGE (scripts/convergence.py: another path on the coarser mesh), says so."""
    lines = ['### Discretization error: every quantity run on two mesh levels or more\n',
             f'Richardson extrapolation in the in-plane element size (coarse 1, medium 1/4, fine 1/8): with three levels '
             f'the observed order, with two the assumed order {ASSUMED_ORDER:g}. Values are those of the tables above '
             '(Delta u_z and Delta Pi_ext to the main snap).\n',
             '| scene | quantity | ' + ' | '.join(LEVELS) + ' | finest ± estimate | extrapolated | remark |',
             '|---|---|' + '---|' * len(LEVELS) + '---|---|---|']
    quantities = (('P_max_nN', 'P_max [nN]'), ('delta_u_z_nm', 'Delta u_z [nm]'),
                  ('delta_Pi_ext_1e-18J', 'Delta Pi_ext [1e-18 J]'))
    scenes = sorted({scene for _, summaries in results.values() for scene in summaries})
    rows = 0

    def row(what, label, by_level, remark_suffix=''):
        finest, estimate, extrapolated, remark = richardson(by_level)
        cells = [f'{by_level[level]:.4g}' if level in by_level else '' for level in LEVELS]
        lines.append(f'| {what} | {label} | ' + ' | '.join(cells) + f' | {finest:.4g} ± {estimate:.2g} '
                     f'| {"" if extrapolated is None else f"{extrapolated:.4g}"} | {remark}{remark_suffix} |')

    for scene in scenes:
        have = {level: summaries[scene] for level, (_, summaries) in results.items() if scene in summaries}
        if len(have) < 2:
            continue
        outcomes = {s['outcome'] for s in have.values()}
        differ = ('; the runs ended differently on the levels (' + ' / '.join(sorted(outcomes)) + ')'
                  if len(outcomes) > 1 else '')
        for key, label in quantities:
            row(scene, label, {level: s[key] for level, s in have.items()}, differ)
            rows += 1
    sources = {level: rotation_curve(directory) for level, (directory, _) in results.items()}
    rotation = {level: rows for level, (rows, _) in sources.items() if rows}
    borrowed = [level for level, (rows, source) in sources.items() if rows and source != 'peel-rotation']
    note = '; ' + '; '.join(f'{level}: the rotation before the pull-off at 60 deg'
                            + (', then the peel-rotation run restarted from its checkpoint' if sources[level][1] !=
                               'pull-off-60' else '') +
                            f', whose curve starts at theta_y = {rotation[level][0]["theta_y_deg"]:.2f} deg'
                            for level in borrowed) if borrowed else ''
    if len(rotation) >= 2:
        for theta in (30.0, 60.0, 90.0):
            for key, label in (('Pi_ext_per_Pi_c0', 'Pi_ext / Pi_c0'), ('Pi_int_per_Pi_c0', 'Pi_int / Pi_c0'),
                               ('Pi_sa_per_Pi_c0', 'Pi_sa / Pi_c0')):
                by_level = {}
                for level, curve in rotation.items():
                    point = interpolate(curve, 'theta_y_deg', theta, [key])
                    if point:
                        by_level[level] = point[key]
                if len(by_level) < 2:
                    continue
                row(f'peel-rotation at {theta:g} deg', label, by_level,
                    note if any(level in by_level for level in borrowed) else '')
                rows += 1
    return '\n'.join(lines) + '\n' if rows else ''


def plots(results, directory):
    """Figures 6, 8, 9 and 10 from results = {level: (work directory, summaries)}; returns (file, caption) pairs."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    pictures = []
    finest_first = [level for level in reversed(LEVELS) if level in results]
    peels = [(level, rotation_curve(results[level][0])) for level in finest_first]
    peels = [(level, rows) for level, (rows, source) in peels if rows and source != 'pull-off-60']
    if peels:
        fig, (axis, energy) = plt.subplots(1, 2, figsize=(12, 4.2))
        for index, (level, rows) in enumerate(peels):
            style = '-' if index == 0 else '--'
            theta = [r['theta_y_deg'] for r in rows]
            axis.plot(theta, [r['M_y_per_ER0^3'] for r in rows], style, linewidth=1, label=f'{level} mesh')
            for key, label, colour, column in (('Pi_ext_per_Pi_c0', 'Pi_ext', 'tab:blue', 0),
                                               ('Pi_int_per_Pi_c0', 'Pi_int', 'tab:orange', 1),
                                               ('Pi_sa_per_Pi_c0', 'Pi_sa', 'tab:green', 2)):
                energy.plot(theta, [r[key] for r in rows], style, color=colour, linewidth=1,
                            label=f'{label} (ours, {level})')
                if index == 0:
                    paper = [(31.0 if k in ('31-', '31+') else k, v[column]) for k, v in PAPER_TABLE4.items()]
                    energy.plot([a for a, _ in paper], [v for _, v in paper], 'o', color=colour, markerfacecolor='none',
                                label=label + ' (paper, Table 4)')
        axis.set_xlabel('theta_y [deg]')
        axis.set_ylabel('M_y / (E R0^3)')
        axis.set_title('Moment (cf. paper Fig. 6)')
        axis.legend()
        axis.grid(alpha=0.3)
        energy.set_xlabel('theta_y [deg]')
        energy.set_ylabel('energy / Pi_c0')
        energy.set_title('Energies (cf. paper Table 4)')
        energy.legend(fontsize=7)
        energy.grid(alpha=0.3)
        fig.tight_layout()
        name = 'validation-fig6-moment.png'
        fig.savefig(os.path.join(directory, name), dpi=110)
        pictures.append((name, 'Peeling by rotation: moment and energies against inclination (cf. paper Fig. 6, Table 4)'))
    for level in finest_first:
        rough = [(z0, read_curve(results[level][0], f'rough-z0-{z0}'), complete(results[level][0], f'rough-z0-{z0}'))
                 for z0 in (0, 4, 8) if started(results[level][0], f'rough-z0-{z0}')]
        if not rough:
            continue
        fig, axis = plt.subplots(figsize=(7, 4))
        for z0, rows, done in rough:
            axis.plot([r['theta_y_deg'] for r in rows], [r['M_y_nNnm'] for r in rows], '.-', markersize=2,
                      label=f'z0 = {z0} nm' + ('' if done else ' (not finished)'))
        axis.set_xlabel('theta_y [deg]')
        axis.set_ylabel('M_y [nN nm]')
        title = f'Rough substrates, h = 20 nm, lambda = 100 nm (cf. paper Fig. 14), {level} mesh'
        axis.set_title(title, fontsize=10)
        axis.legend()
        axis.grid(alpha=0.3)
        fig.tight_layout()
        name = 'validation-fig14-rough-moment.png'
        fig.savefig(os.path.join(directory, name), dpi=110)
        pictures.append((name, 'Moment against inclination on rough substrates: ' + title))
        break
    groups = (('validation-fig8-pull-off.png', 'Pull-off at fixed inclination (cf. paper Fig. 8)',
               [(f'pull-off-{t}', f'{t} deg') for t in (45, 60, 75, 90)]),
              ('validation-fig9-stiction.png', 'Stiction vs frictionless at 60 deg (cf. paper Fig. 9)',
               [(scene, label) for scene, label, _ in STICTION_RUNS]),
              ('validation-fig10-gamma-W.png', 'gamma_W / gamma_W0 at 60 deg (cf. paper Fig. 10, left)',
               [('gamma-W-0.667', '1.5^-1'), ('pull-off-60', '1'), ('gamma-W-1.5', '1.5'), ('gamma-W-2.25', '1.5^2')]),
              ('validation-fig10-gamma-L.png', 'gamma_L / gamma_L0 at 60 deg (cf. paper Fig. 10, right)',
               [('gamma-L-0.444', '1.5^-2'), ('gamma-L-0.667', '1.5^-1'), ('pull-off-60', '1'), ('gamma-L-1.5', '1.5')]))
    for name, title, curves in groups:
        # The finest level that has the most of the group's curves.
        counts = [(sum(s in results[level][1] for s, _ in curves), level) for level in finest_first]
        count, level = max(counts, key=lambda c: c[0]) if counts else (0, None)
        if count < 1 or (count < 2 and len(curves) > 1 and name != 'validation-fig8-pull-off.png'):
            continue
        # The finer levels' runs of the same scenes, dashed in their curve's colour (there are fewer of them).
        finer = [other for other in finest_first[:finest_first.index(level)]
                 if any(s in results[other][1] for s, _ in curves)]
        fig, axis = plt.subplots(figsize=(7, 4))
        for scene, label in curves:
            colour = None
            for drawn, style in [(level, '.-')] + [(other, '--') for other in finer]:
                if scene in results[drawn][1]:
                    rows = results[drawn][1][scene]['rows']
                    line, = axis.plot([r['u_z_nm'] for r in rows], [r['P_z_nN'] for r in rows], style, markersize=2,
                                      linewidth=1, color=colour, label=label if drawn == level else f'{label}, {drawn}')
                    colour = line.get_color()
        axis.set_xlabel('u_z of the end face centre from the undeformed state [nm]')
        axis.set_ylabel('P_z [nN]')
        level_names = f'{level} mesh' + ''.join(f', {other} mesh dashed' for other in finer)
        axis.set_title(f'{title}, {level_names}', fontsize=10)
        axis.legend()
        axis.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(directory, name), dpi=110)
        pictures.append((name, f'{title}, {level_names}'))
    return pictures


# Field pictures (ParaView, headless): scene, states' load parameters, file name, caption.
FIELD_PICTURES = (
    ('peel-rotation', (30, 33, 60, 90, 120), 'validation-fig5-peel-states.png',
     'Peeling by rotation (cf. paper Figs. 5 and 7): deformed states near the given theta_y, side view and the pad from '
     'below, coloured by I1 = tr(sigma)/E (fields are written every 10 steps: the states nearest to the angles)'),
    ('pull-off-60', (), 'validation-fig7-pull-off-60-states.png',
     'Pull-off at 60 deg (cf. paper Fig. 7): states over the lift (load parameter u_z [nm])'),
    ('rough-z0-0', (45,), 'validation-fig14-rough-z0-0.png', 'Flat substrate through the rough-substrate code (z0 = 0), 45 deg'),
    ('rough-z0-4', (45,), 'validation-fig14-rough-z0-4.png', 'Rough substrate z0 = 4 nm, 45 deg (cf. paper Fig. 14)'),
    ('rough-z0-8', (45,), 'validation-fig14-rough-z0-8.png', 'Rough substrate z0 = 8 nm, 45 deg (cf. paper Fig. 14)'),
)


def field_pictures(works, directory):
    """Renders FIELD_PICTURES from the finest level among `works` (finest first) whose run wrote fields; returns
    (file, caption) pairs. A picture no run can render now (runs restored from docs/study-runs keep no fields) keeps
    its earlier rendering in `directory`, if there is one, so that documenting from the archive loses no figure."""
    renderer = shutil.which('pvbatch') and shutil.which('xvfb-run')
    if not renderer:
        print('pvbatch/xvfb-run not installed: field pictures not rendered (earlier renderings are kept)')
    out = []
    for scene, times, name, caption in FIELD_PICTURES:
        candidates = ((os.path.join(work, scene + suffix, 'mesh_states.xmf'), caption + note) for work in works
                      for suffix, note in (('', ''), ('.incomplete', ' (the run did not finish: its last written state)')))
        found = next(((states, text) for states, text in candidates if os.path.exists(states)), None)
        if found and renderer:
            command = ['bash', os.path.join(ROOT, 'scripts', 'render.sh'),
                       os.path.join(ROOT, 'scripts', 'render_states.py'), found[0], os.path.join(directory, name),
                       '--bottom'] + [str(t) for t in times]
            if subprocess.call(command) == 0:
                out.append((name, found[1]))
                continue
        if os.path.exists(os.path.join(directory, name)):
            out.append((name, caption + ' (rendered from an earlier run of this scene)'))
    return out


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
                        help=f'keep the last checkpointed state of each run in docs/study-runs/<level>/<scene>'
                             f'{STOPPED_SUFFIX}/ as it goes (commit it), and resume the runs kept there')
    parser.add_argument('--set', action='append', type=parse_override, default=[], metavar='[SCENE:]LIST/NAME=VALUE',
                        help="set a parameter in every scene (or in SCENE's only), e.g. --set 'Linear Solver/lag=4'; "
                             'such runs are neither restored from nor kept in docs/study-runs, and --docs is refused')
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
        parser.error('--carry keeps runs in docs/study-runs, which runs made with --set are not')
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
