#!/usr/bin/env python3
"""Newton's give-up rule and convergence norms on whole pull-offs, old against new in one run.

Each configuration is the coarse frictionless Q1C2 pull-off (rotation to theta_y with zero net force, then a lift of
600 nm beyond it) with one Nonlinear Solver setting changed from the base (the rule as it was: a load step fails only
after 'maximum iterations' = 12; NOX's scaled norms):
  non-contracting 2 / 3   give up after 2 or 3 iterations in a row that did not shrink |f|
  slow 3-0.9 / 2-0.5      ... that shrank |f| by less than 10 % (3 in a row) or 50 % (2 in a row)
  unscaled                |f|_2 <= 1e-9 nN and |dx|_inf <= 1e-6 nm as written (docs/solvers.md)
  constant / Eisenstat-Walker  with the give-up rule 2 x 0.5: every linear solve to 'Linear Solver/tolerance', or
                          NOX's type-2 forcing terms (each solve only as accurate as the Newton step needs)
  default                 the defaults before the fold-aware rule: Eisenstat-Walker, the give-up rule off
  after-failure           the give-up rule 2 x 0.5 only in attempts that retry a load after a failed step
  cost-refactor           after-failure with 'Linear Solver/refactor' = cost (measured time decides refactoring)
  secant-1e-9               the defaults before the three rules below (secant predictor, 'short steps' 0,
                          'absolute tolerance' 1e-9)
  quadratic               secant-1e-9 with the quadratic predictor (Rotation/Lift Steps 'predictor')
  quadratic-short-steps   and 'short steps' 2 x 0.125 (a line search cut short twice ends any attempt)
  retry-load-only               the defaults before 'predict after a failure' (a retry after a failed attempt started
                          from the last converged state with only the load moved)
  backtrack-1e-6               the defaults before the energy line search ('line search' = backtrack, 'absolute
                          tolerance' 1e-6); every configuration above also runs with these two
  energy-line-search      backtrack-1e-6 with 'line search' = energy
  new                     the current defaults (as the parameter list declares them: the energy line search and the
                          'absolute tolerance' 1e-5)
  give-up-always(-3)      new with the give-up rule (2, or 3, iterations that do not halve |f|) in every attempt,
                          the first at a load too
  give-up-floor-0         new with 'give up above tolerance' = 0 (the give-up rules count at any |f|)
  descent-cost            new with 'Loading/Jump/refactor' = cost (the jumps' energy descents keep their factors
                          while the measured rate of decrease of Pi pays for it)
  descend-after-1 / -2    new with 'Loading/Jump/descend after failures' = 1 or 2 (the energy descent at the load
                          of the first or second failed attempt in a row, an ordinary step if it releases no more
                          than the step balance tolerance); -2-cost with the cost rule as well
(Rules tried and removed, with their counts: CHANGELOG.md, "Measured and not kept".)
It records CPU seconds, tangents, Newton iterations, failed step attempts, and the change of P_max, Delta u_z and
Delta Pi_ext against the base. Runs one after another (a quiet machine: CPU times are compared):

    benchmarks/step_control.py [--theta 45] [--mesh coarse] [--work step-control] [--docs]

--docs writes docs/step-control.csv and prints the table for docs/performance.md.
"""
import argparse
import csv
import os
import re
import resource
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from curves import RECORDED_BENCHMARK_START, pull_off_summary  # noqa: E402
from scenes import benchmark_scene  # noqa: E402

APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
# The rules added later (quadratic predictor, short steps, absolute tolerance 1e-6) switched off: the configurations
# recorded before them run as they were.
SECANT_1E_9 = {'short steps': 0, 'absolute tolerance': 1e-9, 'Steps': {'predictor': 'secant'}}
LAG = {'Linear Solver': {'refactor': 'lag'}}   # a factorization serves 4 tangents (before 'refactor' = cost)
BEFORE = {**SECANT_1E_9, 'non-contracting iterations': 0, 'forcing term': 'constant', **LAG}   # before the step-control rules
ALWAYS = {'give up': 'always'}   # the rule in every attempt, as it was before 'give up' existed
GIVE_UP = {**SECANT_1E_9, 'non-contracting iterations': 2, 'contraction': 0.5, **ALWAYS, **LAG}
AFTER_FAILURE = {**SECANT_1E_9, 'non-contracting iterations': 2, 'contraction': 0.5, 'give up': 'after a failed step'}
# The defaults before the energy line search and the absolute tolerance 1e-5.
BACKTRACK_1E_6 = {'line search': 'backtrack', 'absolute tolerance': 1e-6}
EARLIER = {   # each as the rows of docs/step-control.csv were run ('Linear Solver': that list's entries,
              # 'Steps': entries of both step lists, 'Jump': Loading/Jump's), with BACKTRACK_1E_6 below them
    'base': BEFORE,
    'non-contracting-3': {**BEFORE, 'non-contracting iterations': 3, 'contraction': 1.0, **ALWAYS},
    'non-contracting-2': {**BEFORE, 'non-contracting iterations': 2, 'contraction': 1.0, **ALWAYS},
    'slow-3-0.9': {**BEFORE, 'non-contracting iterations': 3, 'contraction': 0.9, **ALWAYS},
    'slow-2-0.5': {**BEFORE, **GIVE_UP},
    'unscaled': {**BEFORE, 'norms': 'unscaled'},
    'constant': {**GIVE_UP, 'forcing term': 'constant'},   # runs 6, 7
    'Eisenstat-Walker': GIVE_UP,                            # runs 6, 7
    'default': {**SECANT_1E_9, 'non-contracting iterations': 0, **LAG},   # Eisenstat-Walker, no give-up rule
    'after-failure': {**AFTER_FAILURE, **LAG},
    'cost-refactor': {**AFTER_FAILURE, 'Linear Solver': {'refactor': 'cost'}},
    'secant-1e-9': SECANT_1E_9,
    'quadratic': {'short steps': 0, 'absolute tolerance': 1e-9},
    'quadratic-short-steps': {'absolute tolerance': 1e-9},
    'retry-load-only': {'Steps': {'predict after a failure': False}},
    'backtrack-1e-6': {},
}
CONFIGURATIONS = {**{name: {**BACKTRACK_1E_6, **entries} for name, entries in EARLIER.items()},
                  'energy-line-search': {'absolute tolerance': 1e-6},
                  'new': {},
                  'give-up-always': ALWAYS,
                  'give-up-always-3': {**ALWAYS, 'non-contracting iterations': 3},
                  'give-up-floor-0': {'give up above tolerance': 0.0},
                  'descent-cost': {'Jump': {'refactor': 'cost'}},
                  'descend-after-1': {'Jump': {'descend after failures': 1}},
                  'descend-after-2': {'Jump': {'descend after failures': 2}},
                  'descend-after-2-cost': {'Jump': {'descend after failures': 2, 'refactor': 'cost'}}}
QUANTITIES = ('P_max_nN', 'delta_u_z_nm', 'delta_Pi_ext_1e-18J')


def measure(work, label, newton, mesh, theta):
    directory = f'{mesh}-{theta:g}-{label}'
    xml = os.path.join(work, directory + '.xml')
    newton = dict(newton)
    linear = newton.pop('Linear Solver', None)
    steps = newton.pop('Steps', None)
    jump = newton.pop('Jump', None)
    open(xml, 'w').write(benchmark_scene(directory, mesh=mesh, theta_y=float(theta), newton=newton or None,
                                         linear_solver=linear, steps=steps, jump=jump))
    environment = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.time()
    with open(os.path.join(work, directory + '.log'), 'w') as log:
        status = subprocess.call([APP, xml], cwd=work, stdout=log, stderr=subprocess.STDOUT, env=environment)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    text = open(os.path.join(work, directory + '.log')).read()
    row = dict(configuration=label, status=status, wall_s=round(time.time() - started, 1),
               cpu_s=round(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, 1))
    solver = re.search(r'^solver: (\d+) tangents, (\d+) residual-only evaluations.*?(\d+) factorizations', text, re.M)
    row['tangents'] = int(solver.group(1)) if solver else -1
    row['residuals'] = int(solver.group(2)) if solver else -1
    row['factorizations'] = int(solver.group(3)) if solver else -1
    solves = re.search(r'^solver: .*?(\d+) solves', text, re.M)
    row['solves'] = int(solves.group(1)) if solves else -1
    row['failed_attempts'] = len(re.findall(r'failed \(|converged on another branch', text))
    row['jumps'] = len(re.findall(r'^  jumped in', text, re.M))
    if status == 0:
        summary = pull_off_summary(work, directory, count_from=RECORDED_BENCHMARK_START)
        for q in QUANTITIES:
            row[q] = summary[q]
        row['worst_balance'] = summary['worst_balance_error']
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--theta', type=float, default=45.0)
    parser.add_argument('--mesh', default='coarse')
    parser.add_argument('--only', nargs='*', default=list(CONFIGURATIONS))
    parser.add_argument('--work', default='step-control')
    parser.add_argument('--docs', action='store_true')
    arguments = parser.parse_args()
    work = os.path.abspath(arguments.work)
    os.makedirs(work, exist_ok=True)
    rows = []
    for label in arguments.only:
        rows.append(measure(work, label, CONFIGURATIONS[label], arguments.mesh, arguments.theta))
        print(rows[-1], flush=True)
    base = rows[0]
    print('\n| configuration | CPU [s] | tangents | residual-only | factorizations | MUMPS solves | failed step attempts | jumps | '
          'P_max [nN] | change of P_max / Δu_z / ΔΠ_ext [%] |')
    print('|---|---|---|---|---|---|---|---|---|---|')
    for r in rows:
        if r['status'] != 0:
            print(f"| {r['configuration']} | exit {r['status']} | | | | | | | | |")
            continue
        change = ' / '.join(f"{100 * (r[q] / base[q] - 1):+.3f}" for q in QUANTITIES)
        print(f"| {r['configuration']} | {r['cpu_s']:.0f} ({r['cpu_s'] / base['cpu_s']:.2f}) | {r['tangents']} | "
              f"{r['residuals']} | {r['factorizations']} | {r['solves']} | {r['failed_attempts']} | {r['jumps']} | {r['P_max_nN']:.4f} | {change} |")
    if arguments.docs:
        with open(os.path.join(ROOT, 'docs', 'step-control.csv'), 'w', newline='') as out:
            writer = csv.DictWriter(out, fieldnames=list(dict.fromkeys(k for r in rows for k in r)))
            writer.writeheader()
            writer.writerows(rows)


if __name__ == '__main__':
    main()
