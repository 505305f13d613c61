#!/usr/bin/env python3
"""run-study.py --carry, on manufactured run directories: a running run's checkpoints, curve, scene and log are kept in
the archive's <scene>.stopped/ (not its fields), again only when its checkpoints file changed; a new work directory
gets the kept run back as a stopped run (<scene>.incomplete/ and its log) for `spatula --resume`, but not over a run
it already has; a workflow job with --carry keeps the state its app checkpoints while it runs; a stopped run the app
refuses to resume is kept aside; a run its load path ended (a solver failure) is kept and restored as it ended.

    study_carry.py"""
import os
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from expectations import check, finish  # noqa: E402
from study import archive as study  # noqa: E402


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    open(path, 'w').write(text)


with tempfile.TemporaryDirectory() as root:
    study.ARCHIVE = os.path.join(root, 'archive')
    work, fresh = os.path.join(root, 'work'), os.path.join(root, 'fresh')
    running = os.path.join(work, 'fine', 'peel-rotation.partial')
    for name, text in (('checkpoints.h5', 'state 1'), ('curve.csv', 'rows 1'), ('scene.xml', '<scene/>'),
                       ('fields.h5', 'big'), ('.spatula-output', 'ours')):
        write(os.path.join(running, name), text)
    write(os.path.join(work, 'fine', 'peel-rotation.log'), 'log 1')
    carried = {}
    study.carry(work, 'fine', 'peel-rotation', carried)
    kept = os.path.join(study.ARCHIVE, 'fine', 'peel-rotation' + study.STOPPED_SUFFIX)
    check(sorted(os.listdir(kept)) == ['.spatula-output', 'checkpoints.h5', 'curve.csv', 'run.log', 'scene.xml'],
          f'kept files: {sorted(os.listdir(kept))} (no fields)')
    check(open(os.path.join(kept, 'checkpoints.h5')).read() == 'state 1', 'kept checkpoint')
    # The curve grows between checkpoints: not copied again until the checkpoints file changes.
    write(os.path.join(running, 'curve.csv'), 'rows 2')
    study.carry(work, 'fine', 'peel-rotation', carried)
    check(open(os.path.join(kept, 'curve.csv')).read() == 'rows 1', 'copied again without a new checkpoint')
    write(os.path.join(running, 'checkpoints.h5'), 'state 2')
    os.utime(os.path.join(running, 'checkpoints.h5'), (1e9, 1e9))
    study.carry(work, 'fine', 'peel-rotation', carried)
    check(open(os.path.join(kept, 'checkpoints.h5')).read() == 'state 2'
          and open(os.path.join(kept, 'curve.csv')).read() == 'rows 2', 'not copied after a new checkpoint')

    # A new machine: the kept run comes back as a stopped run with its log ...
    restored = study.restore_stopped(fresh, [('fine', 'peel-rotation'), ('fine', 'rough-z0-4')])
    check(restored == [('fine', 'peel-rotation')], f'restored {restored}')
    stopped = os.path.join(fresh, 'fine', 'peel-rotation.incomplete')
    check(os.path.exists(os.path.join(stopped, 'checkpoints.h5'))
          and open(os.path.join(fresh, 'fine', 'peel-rotation.log')).read() == 'log 1'
          and not os.path.exists(os.path.join(stopped, 'run.log')), 'restored stopped run and its log')
    # ... but not over a stopped or complete run the work directory has.
    write(os.path.join(stopped, 'checkpoints.h5'), 'newer')
    check(study.restore_stopped(fresh, [('fine', 'peel-rotation')]) == []
          and open(os.path.join(stopped, 'checkpoints.h5')).read() == 'newer', 'restored over a stopped run')
    complete_only = os.path.join(root, 'complete-only')
    write(os.path.join(complete_only, 'fine', 'peel-rotation', 'curve.csv'), 'complete')
    check(study.restore_stopped(complete_only, [('fine', 'peel-rotation')]) == []
          and not os.path.exists(os.path.join(complete_only, 'fine', 'peel-rotation.incomplete')),
          'restored over a complete run')
    # Archiving the complete run drops its carried stopped state.
    write(os.path.join(work, 'fine', 'peel-rotation', 'curve.csv'), 'complete')
    study.archive(work, 'fine', 'peel-rotation')
    check(not os.path.exists(kept) and os.path.exists(os.path.join(study.ARCHIVE, 'fine', 'peel-rotation', 'curve.csv')),
          'the carried state kept after the run was archived')
    # A run directory renamed away by the app while it is carried: no error, nothing half-copied left.
    carried = {}
    study.carry(os.path.join(root, 'nowhere'), 'fine', 'rough-z0-4', carried)
    check(not os.path.exists(os.path.join(study.ARCHIVE, 'fine', 'rough-z0-4' + study.STOPPED_SUFFIX + '.copying')),
          'a half-copied carried state left')

    # A workflow job with --carry (single_run.run_app): the state its app checkpoints while it runs is kept, and the
    # job shows the app's step lines. The app here is a stand-in that checkpoints between two steps.
    from study import single_run
    fake = os.path.join(root, 'fake-spatula')
    write(fake, '#!/bin/sh\ncase "$*" in *--validate-only*) exit 1;; esac\n'
                'echo "step 1     rotation  theta_y 6.000    deg  u_z 1.0       nm  newton 2  neg.piv 0  1.0 s"\n'
                'mkdir -p rough-z0-0.partial && echo "state 3" > rough-z0-0.partial/checkpoints.h5\nsleep 3\n'
                'echo "step 2     rotation  theta_y 8.000    deg  u_z 2.0       nm  newton 2  neg.piv 0  4.0 s"\n')
    os.chmod(fake, 0o755)
    single_run.APP = fake
    directory = os.path.join(root, 'job', 'coarse')
    os.makedirs(directory)
    status = single_run.run_app(directory, 'coarse', 'rough-z0-0', 1, 'mpiexec', carrying=True)
    kept = os.path.join(study.ARCHIVE, 'coarse', 'rough-z0-0' + study.STOPPED_SUFFIX, 'checkpoints.h5')
    check(status == 0 and os.path.exists(kept) and open(kept).read() == 'state 3\n',
          f'a job with --carry: exit {status}, kept {os.path.exists(kept)}')
    check('step 2' in open(os.path.join(directory, 'rough-z0-0.log')).read(), "the app's output in the run's log")
    # A stopped run the app refuses to resume is kept aside with its log (the new run would replace it), and the job
    # says why, in the app's words.
    write(fake, '#!/bin/sh\ncase "$*" in *--validate-only*) echo "input error: other Loading parameters" >&2; exit 2;; '
                'esac\necho "step 1     rotation  theta_y 6.000    deg  u_z 1.0       nm  newton 2  neg.piv 0  1.0 s"\n')
    from study import app as study_app
    study_app.APP = fake   # (its --validate-only is what refuses)
    write(os.path.join(directory, 'rough-z0-4.incomplete', 'checkpoints.h5'), 'hours of work')
    write(os.path.join(directory, 'rough-z0-4.log'), 'the stopped run')
    from contextlib import redirect_stdout
    from io import StringIO
    said = StringIO()
    with redirect_stdout(said):
        status = single_run.run_app(directory, 'coarse', 'rough-z0-4', 1, 'mpiexec')
    from study.runs import REFUSED_SUFFIX
    aside = os.path.join(directory, 'rough-z0-4' + REFUSED_SUFFIX)
    check(status == 0 and not os.path.exists(os.path.join(directory, 'rough-z0-4.incomplete'))
          and open(os.path.join(aside, 'checkpoints.h5')).read() == 'hours of work'
          and open(os.path.join(aside, 'run.log')).read() == 'the stopped run', 'the refused stopped run kept aside')
    check('other Loading parameters' in said.getvalue() and aside in said.getvalue(), f'the job said {said.getvalue()!r}')

    # A run the app ended with a solver failure of its load path: kept with its curve, FAILURE.txt and log (not its
    # checkpoints), restored as it ended instead of being run again; not one a signal or the memory ended.
    ended = os.path.join(work, 'coarse', 'shear-x.incomplete')
    for name, text in (('curve.csv', 'rows to the failure'), ('FAILURE.txt', 'why'), ('checkpoints.h5', 'big'),
                       ('.spatula-output', 'ours')):
        write(os.path.join(ended, name), text)
    diagnosis = 'spatula: solver failure at step 9, lift = 3: the jump past the instability failed (kept 26 %)\n'
    for case, log, keep in (('a signal', 'spatula: interrupted at step 9, lift = 3: interrupted by SIGTERM\n', False),
                            ('the memory', 'spatula: solver failure at step 9: out of memory; the job allows less '
                                           'memory than this mesh and solver need\n', False),
                            ('the load path', diagnosis, True)):
        write(os.path.join(work, 'coarse', 'shear-x.log'), 'step 9 ...\n' + log)
        check(study.archive_ended(work, 'coarse', 'shear-x') == keep, f'a run ended by {case} kept: {not keep}')
    kept = os.path.join(study.ARCHIVE, 'coarse', 'shear-x' + study.ENDED_SUFFIX)
    check(sorted(os.listdir(kept)) == ['.spatula-output', 'FAILURE.txt', 'curve.csv', 'run.log'],
          f'an ended run kept: {sorted(os.listdir(kept))}')
    # Carried again (resumed, with another jump limit, say), it is a run going on: its end is dropped; ended again,
    # its carried state is.
    carried = {}
    study.carry(work, 'coarse', 'shear-x', carried)
    check(os.path.isdir(os.path.join(study.ARCHIVE, 'coarse', 'shear-x' + study.STOPPED_SUFFIX))
          and not os.path.exists(kept), 'a carried run still kept as ended')
    study.archive_ended(work, 'coarse', 'shear-x')
    check(os.path.isdir(kept) and not os.path.exists(os.path.join(study.ARCHIVE, 'coarse',
                                                                  'shear-x' + study.STOPPED_SUFFIX)),
          'an ended run still kept as carried')
    again = os.path.join(root, 'again')
    check(single_run.run(again, 'coarse', 'shear-x') == 1 and open(os.path.join(again, 'coarse', 'shear-x.incomplete',
                                                                                'curve.csv')).read()
          == 'rows to the failure' and 'jump past the instability failed' in open(os.path.join(
              again, 'coarse', 'shear-x.log')).read(), 'the ended run restored as it ended, its job failed, not run')
    check(study.restore_ended(again, [('coarse', 'shear-x')]) == [], 'restored over the run the work directory has')
    write(os.path.join(work, 'coarse', 'shear-x', 'curve.csv'), 'complete')
    study.archive(work, 'coarse', 'shear-x')
    check(not os.path.exists(kept), 'the ended run kept after the scene was archived complete')

finish('study_carry: stopped runs kept without fields when checkpointed, restored for --resume on a new machine')
