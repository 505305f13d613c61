#!/usr/bin/env python3
"""Time per Newton iteration on the medium mesh: ours with MUMPS' freed workspace returned to the kernel at every
factorization (`Linear Solver/MUMPS/keep workspace` = false, the code before the solver work) against ours keeping it
(the default), and against the FEniCSx peer of ../shared/peers (when Debian's python3-dolfinx is installed).

The scene is the peer's comparison scene (../shared/peers/README.md): xml/pull-off-medium.xml with no pre-rotation
(theta_y = theta_s), a 20 nm lift, Q1C1 faces, a fresh LDL^T factorization every iteration (lag 0), convergence
tables on. The runs alternate (old, new, peer, old, new, peer, ...) so that the machine's drift falls on all alike;
medians over the repetitions. Ours' time per iteration is the `spatula: newton` timer over the Newton iterations of
the run; the peer's is its assembly + solve summed over its iterations, over their number. Run on a quiet machine:

    benchmarks/peer_iteration.py [--repetitions 5] [--work peer-iteration] [--docs]

--docs writes docs/peer-iteration.csv (one row per run) and prints the table for docs/performance.md.
"""
import argparse
import csv
import os
import re
import shutil
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from scenes import parameter_list  # noqa: E402

APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
PEER = os.path.join(ROOT, '..', 'shared', 'peers', 'fenicsx_spatula.py')
THETA_S = 4.908063349054151
ENVIRONMENT = dict(os.environ, OPENBLAS_NUM_THREADS='1', OMP_NUM_THREADS='1')
VARIANTS = {'ours-old': False, 'ours-new': True}   # keep workspace


def scene(directory, keep_workspace):
    entries = {
        'Mesh': {'level': 'medium'},
        'Adhesion': {'law': 'frictionless', 'enrichment': 'Q1C1', 'quadrature': 6},
        'Loading': {'type': 'lift', 'theta_y': THETA_S, 'final lift': 20.0,
                    'Lift Steps': {'initial': 2.0, 'maximum': 5.0}},
        'Linear Solver': {'refactor': 'lag', 'lag': 0, 'MUMPS': {'symmetric': True, 'keep workspace': keep_workspace}},
        'Output': {'directory': directory, 'convergence tables': True},
    }
    if keep_workspace is None:   # the current defaults (benchmarks/speedup.py)
        del entries['Linear Solver']
    return parameter_list('peer comparison', entries) + '\n'


def timer(log, name):
    match = re.search(rf'^spatula: {re.escape(name)}\s+([0-9.eE+-]+) \((\d+)\)', log, re.M)
    return (float(match.group(1)), int(match.group(2))) if match else (float('nan'), 0)


def run_ours(work, variant, repetition):
    directory = f'{variant}-{repetition}'
    xml = os.path.join(work, directory + '.xml')
    open(xml, 'w').write(scene(directory, VARIANTS[variant]))
    shutil.rmtree(os.path.join(work, directory), ignore_errors=True)
    result = subprocess.run(['/usr/bin/time', '-f', '%S %R', APP, xml], cwd=work, env=ENVIRONMENT,
                            capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f'{variant}: exit {result.returncode}\n{result.stderr[-2000:]}')
    log = result.stdout
    rows = [r for r in csv.DictReader(open(os.path.join(work, directory, 'curve.csv'))) if r['stage'] == 'lift']
    iterations = sum(int(float(r['newton_iterations'])) for r in rows)
    newton, _ = timer(log, 'newton')
    factorization, factorizations = timer(log, 'linear solve (MUMPS factorization)')
    system_seconds, faults = result.stderr.strip().splitlines()[-1].split()
    return dict(run=variant, repetition=repetition, iterations=iterations, per_iteration_s=newton / iterations,
                factorization_s=factorization / max(factorizations, 1), system_s=float(system_seconds),
                page_faults=int(faults), P_z_final=float(rows[-1]['P_z_nN']), directory=directory)


def run_peer(work, ours, repetition):
    out = os.path.join(work, f'peer-{repetition}.csv')
    mesh, curve = (os.path.join(work, ours['directory'], f) for f in ('mesh.h5', 'curve.csv'))
    result = subprocess.run(['/usr/bin/python3', PEER, mesh, curve, '--solver', 'cholesky', '--out', out],
                            env=ENVIRONMENT, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f'peer: exit {result.returncode}\n{result.stderr[-2000:]}')
    rows = list(csv.DictReader(open(out)))
    total = sum(float(r['residual_s']) + float(r['tangent_s']) + float(r['solve_s']) for r in rows)
    final = [r for r in rows if r['step'] == rows[-1]['step']][-1]
    return dict(run='peer', repetition=repetition, iterations=len(rows), per_iteration_s=total / len(rows),
                factorization_s=float('nan'), system_s=float('nan'), page_faults=0,
                P_z_final=float(final['P_z']), directory='')


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--repetitions', type=int, default=5)
    parser.add_argument('--work', default='peer-iteration')
    parser.add_argument('--docs', action='store_true')
    arguments = parser.parse_args()
    os.makedirs(arguments.work, exist_ok=True)
    work = os.path.abspath(arguments.work)
    have_peer = subprocess.run(['/usr/bin/python3', '-c', 'import dolfinx'], capture_output=True).returncode == 0
    if not have_peer:
        print('python3-dolfinx is not installed: the peer is not run (apt-get install python3-dolfinx)')
    rows = []
    for repetition in range(arguments.repetitions):
        for variant in VARIANTS:
            rows.append(run_ours(work, variant, repetition))
            print(f"{variant} #{repetition}: {rows[-1]['per_iteration_s']:.3f} s per iteration "
                  f"({rows[-1]['iterations']} iterations, factorization {rows[-1]['factorization_s']:.3f} s, "
                  f"{rows[-1]['page_faults']} page faults), P_z {rows[-1]['P_z_final']:.9f} nN", flush=True)
        if have_peer:
            rows.append(run_peer(work, rows[-1], repetition))
            print(f"peer #{repetition}: {rows[-1]['per_iteration_s']:.3f} s per iteration "
                  f"({rows[-1]['iterations']} iterations), P_z {rows[-1]['P_z_final']:.9f} nN", flush=True)
    median = {name: statistics.median(r['per_iteration_s'] for r in rows if r['run'] == name)
              for name in dict.fromkeys(r['run'] for r in rows)}
    factor = {name: statistics.median(r['factorization_s'] for r in rows if r['run'] == name) for name in VARIANTS}
    print('\n| run | median per Newton iteration [s] | median factorization [s] | ratio to ours-old |')
    print('|---|---|---|---|')
    for name, seconds in median.items():
        print(f"| {name} | {seconds:.3f} | {factor.get(name, float('nan')):.3f} | {median['ours-old'] / seconds:.2f} |")
    if 'peer' in median:
        print(f"\npeer / ours-new per iteration: {median['peer'] / median['ours-new']:.2f} "
              f"(ours is {median['peer'] / median['ours-new']:.2f} x the peer's speed)")
    if arguments.docs:
        with open(os.path.join(ROOT, 'docs', 'peer-iteration.csv'), 'w', newline='') as out:
            writer = csv.DictWriter(out, fieldnames=[k for k in rows[0] if k != 'directory'], extrasaction='ignore')
            writer.writeheader()
            writer.writerows(rows)


if __name__ == '__main__':
    main()
