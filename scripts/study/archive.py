"""The kept runs (results/<level>/<scene>/): a complete run archived and restored, a run still going carried as
<scene>.stopped/ and restored as a stopped run for `spatula --resume`, a run the app ended with a solver failure kept
as <scene>.incomplete/ and restored as it ended."""
import os
import re
import shutil

from convergence import EQUAL_AREA_SIZE
from curves import pad_slip, pull_off_summary
from run_lock import directory_lock
from study.runs import STOPPED_DIRECTORIES, complete, stopped
from study.scenes import DEPENDS, OVERRIDES, ROOT
from study.tables import STICTION_RUNS

# A complete run's results are kept in the repository (results/<level>/<scene>/), so that they outlive the
# work directory (a new machine, a cleaned disk): its curve, scene, mesh summary and log, and the checkpoints of a
# rotation that pull-offs start from. A later study restores them into the work directory instead of running again.
ARCHIVE = os.path.join(ROOT, 'results')
KEPT_FILES = ('curve.csv', 'scene.xml', 'mesh_summary.csv', 'mesh_summary.txt', '.spatula-output', 'pad_slip.csv')


def archiving():
    """Whether runs are restored from and kept in ARCHIVE: not when --set changed the scenes (not the study's own)."""
    return not OVERRIDES


def archive(work, level, scene, kept_as=None):
    """Copies the complete run's kept files into ARCHIVE/<level>/<scene>/ (ARCHIVE/<kept_as>/<scene>/ where named)."""
    source, kept = os.path.join(work, level, scene), os.path.join(ARCHIVE, kept_as or level, scene)
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
    shutil.rmtree(kept + ENDED_SUFFIX, ignore_errors=True)     # nor how an earlier run of it ended


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
# study on another machine resumes the run from there instead of starting it again. Its fields are
# not kept (the resumed run writes its fields from the state it resumes at).
STOPPED_SUFFIX = '.stopped'
CARRIED_FILES = ('checkpoints.h5', 'curve.csv', 'scene.xml', 'mesh_summary.csv', 'mesh_summary.txt', '.spatula-output')


def carry(work, level, scene, carried):
    """Copies the stopped-run files of the running or stopped <scene> into ARCHIVE/<level>/<scene>.stopped/ when its
    checkpoints file has changed since the last copy (`carried`: file -> modification time copied)."""
    for suffix in STOPPED_DIRECTORIES:
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
        shutil.rmtree(os.path.join(ARCHIVE, level, scene + ENDED_SUFFIX), ignore_errors=True)   # it goes on: not ended
        carried[checkpoints] = stamp
        return


def restore_stopped(work, runs):
    """Puts the carried stopped runs among `runs` that <work> has neither complete nor stopped back into <work> as
    stopped runs (<scene>.incomplete/, which `spatula --resume` goes on from); returns them."""
    return put_back_as_stopped(work, runs, STOPPED_SUFFIX, 'checkpoints.h5')


def put_back_as_stopped(work, runs, suffix, needed):
    """Puts ARCHIVE/<level>/<scene><suffix>/ (where it holds `needed`) back as <work>/<level>/<scene>.incomplete/ with
    its log, for the runs among `runs` that <work> has in no form; returns them."""
    restored = []
    for level, scene in runs:
        kept, directory = os.path.join(ARCHIVE, level, scene + suffix), os.path.join(work, level)
        if not os.path.exists(os.path.join(kept, needed)) or complete(directory, scene) or stopped(directory, scene):
            continue
        put_back(kept, os.path.join(directory, scene + '.incomplete'), os.path.join(directory, scene + '.log'))
        restored.append((level, scene))
    return restored


# A run the app ended with a solver failure (exit 1, its diagnosis in FAILURE.txt and the log: no stable state after
# a jump, say) is kept in ARCHIVE/<level>/<scene>.incomplete/ with its curve up to the last converged state, so that a
# study's tables (the shear study's stopped pulls) can be made from ARCHIVE alone. It is restored as it ended, not
# run again (it would end the same way): remove the kept directory to run it again.
ENDED_SUFFIX = '.incomplete'
ENDED_FILES = KEPT_FILES + ('FAILURE.txt',)


def ended_by_the_path(log_text):
    """Whether the app's log ends its run with a solver failure of the load path itself (not one of the machine's:
    memory, the file system, a signal), which a run of the same scene would meet again."""
    failures = [l for l in log_text.splitlines() if l.startswith(('spatula: solver failure', 'spatula: error',
                                                                  'spatula: interrupted'))]
    return bool(failures) and failures[-1].startswith('spatula: solver failure') and 'memory' not in failures[-1]


def archive_ended(work, level, scene):
    """Keeps the ended run <work>/<level>/<scene>.incomplete/ (its curve, scene, summaries, FAILURE.txt and log, not
    its checkpoints or fields) in ARCHIVE/<level>/<scene>.incomplete/ if the load path ended it; returns whether it
    did."""
    source, kept = os.path.join(work, level, scene + ENDED_SUFFIX), os.path.join(ARCHIVE, level, scene + ENDED_SUFFIX)
    log = os.path.join(work, level, scene + '.log')
    if not os.path.exists(os.path.join(source, 'curve.csv')) or not os.path.exists(os.path.join(source, 'FAILURE.txt')) \
            or not os.path.exists(log) or not ended_by_the_path(open(log).read()):
        return False
    shutil.rmtree(kept + '.copying', ignore_errors=True)
    os.makedirs(kept + '.copying')
    for name in ENDED_FILES:
        if os.path.exists(os.path.join(source, name)):
            shutil.copyfile(os.path.join(source, name), os.path.join(kept + '.copying', name))
    shutil.copyfile(log, os.path.join(kept + '.copying', 'run.log'))
    shutil.rmtree(kept, ignore_errors=True)
    os.replace(kept + '.copying', kept)
    shutil.rmtree(os.path.join(ARCHIVE, level, scene + STOPPED_SUFFIX), ignore_errors=True)   # it has ended since
    return True


def restore_ended(work, runs):
    """Puts the kept ended runs among `runs` that <work> has in no form back as <work>/<level>/<scene>.incomplete/
    with their log; returns them."""
    return put_back_as_stopped(work, runs, ENDED_SUFFIX, 'curve.csv')


# The paper's studies on the equal-area sequence (convergence.EQUAL_AREA_SIZE: coarse refined 2 x 2 and 3 x 3, and
# medium, each with `Mesh/section` = equal area; results/<name>/README.md): the results page sets the medium mesh's
# values, with an error bar over the sequence, beside the named levels'.
def linked_equal_area(work):
    """{name: <work>/<name>/} for each kept level of the equal-area sequence, each holding a link to each of its runs
    (their tables are written there, not in results/)."""
    linked = {}
    for name in EQUAL_AREA_SIZE:
        kept = os.path.join(ARCHIVE, name)
        if not os.path.isdir(kept):
            continue
        directory = linked[name] = os.path.join(work, name)
        os.makedirs(directory, exist_ok=True)
        for scene in sorted(os.listdir(kept)):
            source, link = os.path.join(kept, scene), os.path.join(directory, scene)
            if scene != 'tables' and os.path.isdir(source) and not os.path.lexists(link):
                os.symlink(source, link)
    return linked
