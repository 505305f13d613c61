#!/usr/bin/env python3
"""scripts/study/costs.py on a manufactured kept run: the wall time is the curve's last wall_s, the states its rows,
the ranks and memory the last partition and memory-estimate lines of run.log (a resumed run logs them again); a run
without its curve has no cost.

    study_costs.py"""
import os
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from expectations import check, finish  # noqa: E402
from study.costs import run_cost  # noqa: E402

with tempfile.TemporaryDirectory() as run:
    check(run_cost(run) is None, 'no curve: no cost')
    open(os.path.join(run, 'curve.csv'), 'w').write('step,stage,wall_s\n1,rotation,12.5\n2,rotation,30.25\n'
                                                    '3,lift,3600.5\n')
    open(os.path.join(run, 'run.log'), 'w').write(
        '  partition                           1 rank(s), elements per rank: 9424\n'
        '  memory estimate                     0.198514 GB of 24.6 GB available\n'
        'resumed\n  partition                           2 rank(s), elements per rank: 4712 4712\n'
        '  memory estimate                     0.25 GB of 24.6 GB available\n')
    check(run_cost(run) == (3600.5, 3, 2, 0.25), f'the run as logged last: {run_cost(run)}')
finish('costs: a kept run read')
