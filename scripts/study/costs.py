#!/usr/bin/env python3
"""What each study costs at each mesh level, from the kept runs (results/<level>/<scene>/): a run's wall time by its
own clock (curve.csv's last wall_s; a resumed run's clock goes on across its segments), its converged states, its
MPI ranks and the preflight's memory estimate (run.log); per study and level, the sum of its runs' times and the
largest memory. Prints the tables, or with --docs writes docs/study-costs.md.

    /usr/bin/python3 scripts/study/costs.py [--docs]"""
import argparse
import csv
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from study.scenes import ROOT, STUDIES  # noqa: E402

KEPT = (('coarse', 'coarse'), ('medium', 'medium'), ('medium-equal-area', 'medium, equal area'), ('fine', 'fine'))


def run_cost(directory):
    """(wall [s], states, ranks, memory [GB]) of a kept run, or None where it is not complete."""
    curve, log = os.path.join(directory, 'curve.csv'), os.path.join(directory, 'run.log')
    if not os.path.exists(curve) or not os.path.exists(log):
        return None
    rows = list(csv.DictReader(open(curve)))
    text = open(log).read()
    ranks = re.findall(r'partition\s+(\d+) rank', text)
    memory = re.findall(r'memory estimate\s+([\d.e+-]+) GB', text)
    return (float(rows[-1]['wall_s']), len(rows), int(ranks[-1]) if ranks else 1,
            float(memory[-1]) if memory else float('nan'))


def tables():
    costs = {(folder, scene): run_cost(os.path.join(ROOT, 'results', folder, scene))
             for folder, _ in KEPT for scene in STUDIES['all']}
    lines = ['| mesh | scene | wall [min] | states | ranks | memory [GB] |', '|---|---|---|---|---|---|']
    for folder, label in KEPT:
        for scene in STUDIES['all']:
            cost = costs[(folder, scene)]
            if cost:
                lines.append(f'| {label} | {scene} | {cost[0] / 60:,.1f} | {cost[1]} | {cost[2]} | {cost[3]:.3g} |')
    totals = ['| study | mesh | runs | sum of the runs [h] | largest memory [GB] |', '|---|---|---|---|---|']
    for study, scenes in STUDIES.items():
        if study == 'all':
            continue
        for folder, label in KEPT:
            found = [costs[(folder, s)] for s in scenes if costs[(folder, s)]]
            if len(found) == len(scenes):
                totals.append(f'| {study} | {label} | {len(found)} | {sum(c[0] for c in found) / 3600:,.2f} | '
                              f'{max(c[3] for c in found):.3g} |')
    return '\n'.join(totals), '\n'.join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--docs', action='store_true', help='write docs/study-costs.md')
    totals, runs = tables()
    if not parser.parse_args().docs:
        print(totals + '\n\n' + runs)
        return 0
    text = f"""# What each study costs

Written by `/usr/bin/python3 scripts/study/costs.py --docs` from the kept runs in `results/` (each run's own clock,
on the 2-core machine of [performance.md](performance.md), most of them with another run beside them: upper bounds
for a quiet core; a pull-off's time starts at its rotation's checkpoint; a fine run carried across machines counts
its segments). Each run was made by the app of its time: the equal-area medium runs (app of commit 83d36d7) are
more recent than the inscribed medium ones, and the solver has become faster between them. Memory: the app's
preflight estimate for the run (its `--validate-only` line "memory estimate"; the workflow asks a batch system for
it plus 512 MB). A study's runs are independent but for each pull-off waiting for its rotation, so with enough
cores its time is about its rotation's plus its longest pull-off's; the sums below are what one core would take.
How to run a study: [reproducing.md](reproducing.md).

## Per study

{totals}

## Per run

{runs}
"""
    open(os.path.join(ROOT, 'docs', 'study-costs.md'), 'w').write(text)
    print('wrote docs/study-costs.md')
    return 0


if __name__ == '__main__':
    sys.exit(main())
