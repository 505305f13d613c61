"""How a study's run stands in its work directory: complete, started (complete or stopped with a curve), and how a
pull-off ended; a stopped run the app refuses to resume kept aside."""
import os
import shutil

from curves import pull_off_summary
from run_lock import directory_lock
from scenes import app_diagnosis


def complete(work, scene):
    return os.path.exists(os.path.join(work, scene, 'curve.csv'))


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


STOPPED_DIRECTORIES = ('.partial', '.incomplete')   # a killed run's staging directory, a stopped run's


def stopped(work, scene):
    """A stopped run of it is there to resume: <scene>.partial/ (killed) or <scene>.incomplete/ (stopped)."""
    return any(os.path.isdir(os.path.join(work, scene + suffix)) for suffix in STOPPED_DIRECTORIES)


REFUSED_SUFFIX = '.refused'


def keep_aside(work, scene):
    """Moves the stopped run of <scene> (its directory and log) to <work>/<scene>.refused/ (replacing one kept there
    before), under the run's lock so a live run is never moved; returns that directory. For a stopped run the app
    refuses to resume, which a new run would otherwise replace."""
    aside = os.path.join(work, scene + REFUSED_SUFFIX)
    with directory_lock(os.path.join(work, scene)):
        shutil.rmtree(aside, ignore_errors=True)
        for suffix in STOPPED_DIRECTORIES:
            if os.path.isdir(os.path.join(work, scene + suffix)):
                os.replace(os.path.join(work, scene + suffix), aside)
                break
        log = os.path.join(work, scene + '.log')
        if os.path.exists(log):
            shutil.copyfile(log, os.path.join(aside, 'run.log'))
    return aside


def checkpoint_copy(work, level, rotation, theta):
    """The file the rotation's part up to its checkpoint at theta [deg] leaves (a workflow job's output): its
    checkpoints, the one at theta among them."""
    return os.path.join(work, level, f'{rotation}.checkpoint-{theta:g}.h5')
