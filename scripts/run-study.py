#!/usr/bin/env python3
"""Runs the paper's studies (the scenes in xml/studies/) and writes their tables and figures.

    scripts/run-study.py <study> [--jobs 2] [--work DIR] [--mesh LEVEL] [--docs] [--set [SCENE:]LIST/NAME=VALUE ...]

studies: table4 (peel by rotation), table6 (pull-off at 45/60/75/90 deg, also Table 5), stiction, gamma-W (Table 7),
gamma-L (Table 8), rough (Fig. 14), all (these: the paper's); shear (beyond the paper: pulls at angles with friction,
on the coarse mesh unless --mesh says otherwise; with --docs it writes docs/shear.md). The runs are the Snakemake
workflow's jobs (scripts/workflow/Snakefile), `--jobs` of them at once (both cores by default), one MPI rank each: a
rotation that pull-offs start from runs in parts, up to each checkpoint they need, and each pull-off starts as soon
as its checkpoint is written (a copy of it, <scene>.restart.h5, is what it reads). Progress: Snakemake's count of
jobs done, and one line per converged step of every run (stage, theta_y or u_z, elapsed, an estimate of what
remains; the app's own output in <work>/<level>/<scene>.log).

Stopping and resuming: a study can be stopped at any moment (Ctrl-C, kill). Every run
checkpoints its last converged state every few minutes (Output/checkpoint interval); the next `run-study.py` of the
study goes on with each stopped run from there (`spatula --resume`) and repeats only the steps after the checkpoint
(Snakemake's --rerun-incomplete). A stopped run the app refuses to resume (its scene changed in a way --resume
does not accept) starts again, and the stopped one is kept in <work>/<level>/<scene>.refused/ with its log.

Mesh level: the scenes in xml/studies/ are written for the medium mesh and tables 4 and 6, the stiction pull-off (it
restarts from the medium rotation) and the rough study run on it. The sweeps (gamma-W, gamma-L: six rotations and
pull-offs) run on the coarse mesh unless `--mesh` says otherwise: on the medium mesh each takes about 25 minutes here,
on the coarse one about 3. `--mesh LEVEL` runs every
scene of the study on LEVEL. A run's scene file is the study XML with the level replaced, written beside its output.

Other settings: `--set 'Linear Solver/refactor=lag'` sets a parameter in every scene of the study (sublists and
parameters are added where missing; a new parameter's type is read from its value: true/false, an integer, a
number, else a string), `--set peel-rotation:Loading/theta_y=90` in one scene only. Such runs are not the study's
own: they are not restored from or kept in results/, and --docs is refused (benchmarks/speedup.py runs Table 6
this way with older solver settings).

Carrying a long run to another machine: with `--carry` the last checkpointed state of every run still going (its
checkpoints, curve, scene and log) is copied to results/<level>/<scene>.stopped/ each time the run writes it;
commit that, and the same command on a new machine resumes the run from there (the shear study's tables show such a
run with its values so far, "not finished"). `--scene NAME` (repeatable) runs only
those scenes of the study, e.g. the fine runs still to come:
`run-study.py all --mesh fine --carry --scene peel-rotation --scene pull-off-75 --scene rough-z0-4`.

Results: <work>/<level>/<scene>/ per run, <work>/<level>/tables/*.csv and *.md, and with --docs docs/validation.md
and its PNGs. Needs a build (build/apps/spatula/spatula). Runs already complete in <work> are not repeated. Each
complete run's curve, scene, log (and a rotation's checkpoints) are kept in results/<level>/<scene>/ (commit
them): a study on another machine or with an empty <work> restores them instead of running them again.

This file is the command line; the work is in the package scripts/study/: scenes.py (the studies' scenes and the
--set overrides), archive.py (results/: archive, restore, carry), single_run.py (one run, a workflow job), app.py and
progress.py (the app as a job starts it and its progress lines), runs.py (how a run stands), tables.py (the tables,
with the paper's values in paper-values.csv) and figures.py.
"""
import argparse
import json
import os
import shlex
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from convergence import LEVELS  # noqa: E402
from run_lock import DirectoryInUse  # noqa: E402
from study.archive import (ARCHIVE, ENDED_SUFFIX, STOPPED_SUFFIX, archive, archiving, linked_equal_area,  # noqa: E402
                           restore, restore_ended, restore_stopped)
from study.figures import field_pictures, plots  # noqa: E402
from study.app import APP  # noqa: E402
from study.runs import complete, started as run_started  # noqa: E402
from study.scenes import DEPENDS, OVERRIDES, STUDIES, format_override, parse_override, planned_runs  # noqa: E402
from study.glance import glance  # noqa: E402
from study import shear_tables  # noqa: E402
from study.tables import error_bars, write_tables  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


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
    if not arguments.no_run and not shutil.which('snakemake'):
        sys.exit('run-study.py: snakemake not found: the studies run as its workflow (Debian package snakemake; '
                 'scripts/install-dependencies.sh installs it); --no-run tabulates without it')
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
    if arguments.no_run:
        failed = []
    else:
        failed = run_workflow(runs, arguments.work, arguments.jobs, arguments.mesh, arguments.set, arguments.carry)
    if archiving():   # the tables cover every kept run, at every level (also those no study runs, as the fine
        # level's rotation from 60 deg, and the pull-off at 60 deg its Table 4 is joined to)
        kept = [(level, name) for level in LEVELS if os.path.isdir(os.path.join(ARCHIVE, level))
                for name in sorted(os.listdir(os.path.join(ARCHIVE, level)))]
        restore(arguments.work, [(level, name) for level, name in kept if not name.endswith(
            (STOPPED_SUFFIX, STOPPED_SUFFIX + '.copying', STOPPED_SUFFIX + '.old', ENDED_SUFFIX, ENDED_SUFFIX + '.copying'))])
        restore_ended(arguments.work, [(level, name[:-len(ENDED_SUFFIX)]) for level, name in kept
                                       if name.endswith(ENDED_SUFFIX)])   # the runs the app ended, as they ended
        restore_stopped(arguments.work, [(level, name[:-len(STOPPED_SUFFIX)]) for level, name in kept
                                         if name.endswith(STOPPED_SUFFIX)])   # carried runs still going, so far
    if arguments.no_run:   # nothing ran: say how many of the study's runs the tables can use
        missing = [scene for level, scene in runs if not run_started(os.path.join(arguments.work, level), scene)]
        print(f'study {arguments.study}: {len(runs) - len(missing)} of {len(runs)} runs there to tabulate '
              f'(complete, or ended by the app)' + (f'; not run: {", ".join(missing)}' if missing else ''), flush=True)
    else:
        print(f'study {arguments.study}: {len(runs) - len(failed)} of {len(runs)} runs complete in '
              f'{time.time() - started:.0f} s' + (f'; failed: {", ".join(" ".join(f) for f in failed)}' if failed
                                                  else ''), flush=True)
    if arguments.study == 'shear':
        shear_report(arguments.work, arguments.docs)
        return 1 if failed else 0
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
        accurate = {name: (directory, write_tables(directory, STUDIES['all'], name)[1])
                    for name, directory in linked_equal_area(arguments.work).items()}
        template = open(os.path.join(ROOT, 'docs', 'validation-notes.md')).read()
        with open(os.path.join(docs, 'validation.md'), 'w') as out:
            out.write(template.replace('{{GLANCE}}', glance(results, accurate)).replace('{{TABLES}}', text).replace(
                '{{FIGURES}}', figure_markdown(pictures)))
        print('wrote docs/validation.md')
    return 1 if failed else 0


def run_workflow(runs, work, jobs, mesh, overrides, carrying=False):
    """Runs the (level, scene) pairs through the Snakemake workflow, `jobs` at once, a stopped one resumed (the
    workflow's job runs scripts/study/single_run.py); returns the failed ones (no marker of completion)."""
    work = os.path.abspath(work)
    markers = {run: os.path.join(work, run[0], run[1] + '.complete') for run in runs}
    settings = [format_override(override) for override in overrides]
    command = (['snakemake', '-s', os.path.join(ROOT, 'scripts', 'workflow', 'Snakefile'), '-d', work, '--cores',
                str(jobs), '--rerun-incomplete', '--keep-going'] + list(markers.values()) +
               ['--config', f'work={work}', f'mesh={mesh or ""}', 'set=' + json.dumps(settings),
                f'carry={str(carrying).lower()}'])
    print('run-study: ' + ' '.join(shlex.quote(c) for c in command) + f'\n  (each run\'s progress: '
          f'{work}/<level>/<scene>.log)', flush=True)
    subprocess.call(command)
    return [run for run, marker in markers.items() if not os.path.exists(marker)]


def figure_markdown(pictures):
    """The (file, caption) pairs of a page's figures as Markdown, each under its caption."""
    return '\n\n'.join(f'{caption}:\n\n![{caption}]({name})' for name, caption in pictures)


def shear_report(work, docs):
    """The shear study's tables (and with docs, docs/shear.md and its figures) at every level it has run on."""
    texts, pictures, found_by_level = [], [], {}
    for level in LEVELS:
        directory = os.path.join(work, level)
        if os.path.isdir(directory):
            text, found = shear_tables.lines(directory, level)
            if not found:   # a level the study has not run (its directory holds other studies' runs)
                continue
            texts.append(text)
            found_by_level[level] = found
            if docs:
                pictures += shear_tables.figure(found, level, os.path.join(ROOT, 'docs'))
    texts.append(shear_tables.mesh_dependence(found_by_level))
    text = '\n'.join(t for t in texts if t)
    print(text)
    if docs:
        works = [os.path.join(work, level) for level in reversed(LEVELS) if level in found_by_level]
        pictures += field_pictures(works, os.path.join(ROOT, 'docs'), shear_tables.SLIDING_PICTURES)
        template = open(os.path.join(ROOT, 'docs', 'shear-notes.md')).read()
        with open(os.path.join(ROOT, 'docs', 'shear.md'), 'w') as out:
            out.write(template.replace('{{TABLES}}', text).replace(
                '{{FIGURES}}', figure_markdown(pictures)))
        print('wrote docs/shear.md')


if __name__ == '__main__':
    try:
        sys.exit(main())
    except DirectoryInUse as error:   # a run of the study's is being written by another process
        print(f'run-study: {error}', file=sys.stderr)
        sys.exit(2)
