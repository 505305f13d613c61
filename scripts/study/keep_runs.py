#!/usr/bin/env python3
"""Keeps the complete runs of a study made with --set overrides (which run-study.py does not keep: they are not the
study's own scenes) in results/<name>/, as the equal-area sequence's levels are kept (convergence.EQUAL_AREA_SIZE):

    /usr/bin/python3 scripts/study/keep_runs.py <work>/<level> <name>

e.g. scripts/study/keep_runs.py /work/runs/coarse-x2-ea/coarse coarse-x2-equal-area. Each complete run's curve, scene,
mesh summary and log (a rotation's checkpoints too; a stiction run's pad slip, which needs its fields) is copied;
runs still going or failed are left out and named."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from study.archive import ARCHIVE, archive  # noqa: E402
from study.runs import complete  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    directory, name = os.path.abspath(sys.argv[1]), sys.argv[2]
    work, level = os.path.dirname(directory), os.path.basename(directory)
    scenes = sorted(entry[:-4] for entry in os.listdir(directory) if entry.endswith('.xml'))
    kept = [scene for scene in scenes if complete(directory, scene)]
    for scene in kept:
        archive(work, level, scene, kept_as=name)
    left = sorted(set(scenes) - set(kept))
    print(f'kept {len(kept)} complete runs in {os.path.join(ARCHIVE, name)}'
          + (f'; not complete: {", ".join(left)}' if left else ''))


if __name__ == '__main__':
    main()
