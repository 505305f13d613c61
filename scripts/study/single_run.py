"""One run of a study scene, as a workflow job runs it (scripts/workflow/Snakefile): restored from results/ where
it is kept there, else the scene file written, the rotation's checkpoint copied for a pull-off, a stopped run
resumed (`spatula --resume`), the app run with its ranks, and the complete run kept in results/.

    python3 scripts/study/single_run.py --work DIR --level LEVEL --scene SCENE [--ranks N] [--launcher mpiexec|srun]
        [--set [SCENE:]LIST/NAME=VALUE ...]

Exit status: the app's (0: the run is complete in <work>/<level>/<scene>/)."""
import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from study.archive import archive, archiving, restore  # noqa: E402
from study.runner import APP, RUN_ENVIRONMENT, copy_restart, resumable  # noqa: E402
from study.runs import complete  # noqa: E402
from study.scenes import DEPENDS, OVERRIDES, parse_override, scene_file  # noqa: E402


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


def run(work, level, scene, ranks=1, launcher='mpiexec'):
    directory = os.path.join(work, level)
    os.makedirs(directory, exist_ok=True)
    if archiving() and restore(work, [(level, scene)]):
        print(f'[{level} {scene}] restored from results/ (complete)', flush=True)
        return 0
    if complete(directory, scene):
        return 0
    dependency = DEPENDS.get(scene)
    if dependency:   # the complete rotation's checkpoints (a file dependency of the workflow)
        copy_restart(directory, scene, os.path.join(directory, dependency, 'checkpoints.h5'))
    xml = scene_file(directory, level, scene)
    resume = resumable(directory, xml)
    with open(os.path.join(directory, scene + '.log'), 'a' if resume else 'w') as log:
        print(f'[{level} {scene}] ' + ('resumed from its last checkpoint' if resume else 'started'), flush=True)
        status = subprocess.run(launch(ranks, launcher) + [APP, xml] + (['--resume'] if resume else []),
                                cwd=directory, stdout=log, stderr=subprocess.STDOUT, env=RUN_ENVIRONMENT).returncode
    if status == 0 and archiving() and complete(directory, scene):
        archive(work, level, scene)
    print(f'[{level} {scene}] ' + ('done' if status == 0 else f'failed (exit {status})'), flush=True)
    return status


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--work', required=True)
    parser.add_argument('--level', required=True)
    parser.add_argument('--scene', required=True)
    parser.add_argument('--ranks', type=int, default=1)
    parser.add_argument('--launcher', choices=('mpiexec', 'srun'), default='mpiexec')
    parser.add_argument('--set', action='append', type=parse_override, default=[])
    parser.add_argument('--memory', action='store_true', help="print the preflight's memory estimate [MB] and exit")
    arguments = parser.parse_args()
    OVERRIDES.extend(arguments.set)
    if arguments.memory:   # a pull-off needs what its rotation does (the same mesh and solver)
        directory = os.path.join(arguments.work, arguments.level)
        os.makedirs(directory, exist_ok=True)
        scene = DEPENDS.get(arguments.scene, arguments.scene)
        print(memory_estimate_mb(scene_file(directory, arguments.level, scene), directory) or 0)
        return 0
    return run(arguments.work, arguments.level, arguments.scene, arguments.ranks, arguments.launcher)


if __name__ == '__main__':
    sys.exit(main())
