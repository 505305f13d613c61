#!/usr/bin/env python3
"""Why Newton needs many iterations at the moving peel front: counts, not timings (a busy machine changes nothing).

Runs, with 'Output/tangent spectrum' (the tangent's eigenvalue nearest zero at every converged state, by inverse
iteration on its LDL^T factors, and the participation ratio of its mode), 'Output/convergence tables' and
'Nonlinear Solver/front diagnosis' on:
  medium-rotation-45-54   the medium study rotation (results/medium/peel-rotation) restarted from its 45 deg
                          checkpoint to 54 deg with rotation steps of at most 0.9 deg (the smooth peel);
  coarse-rotation-to-40   the default scene (coarse) to 40 deg, through its first snaps (and with every element
                          split in plane, Mesh/refinement factor = 2: does the front's barrier follow the mesh?).
each with the solver variants of VARIANTS: the current defaults ('Nonlinear Solver' and 'Linear Solver' as declared; the
recorded medium scene's own lists are dropped), the recorded scene's solver (the study run's settings: line search
backtrack, absolute tolerance 1e-9), 'converging extension' = 0 (an attempt fails at its iteration limit whatever
its progress), and the two uses of 'Nonlinear Solver/Front Elimination'. For each: converged states, tangents
(converged and failed attempts, the front elimination's local ones included), the histogram of Newton iterations per
state, the nearest eigenvalue's range (nN/nm and over the tangent's mean diagonal) and its mode's participation, and
the Newton iterations whose line search cut the step below 1 (with the slope ratio at the end of such steps: near 1
means the energy still fell steeply there), and from the diagnosis under each row of the convergence table the
contact points each full Newton step carries across the law's inflection (median, largest, their spread in X), the
full steps along which the energy rises over a barrier, and those of them whose energy would rise even without the
crossing points' adhesion energy. Writes docs/peel-front-diagnosis.csv and prints the table for
docs/performance.md.

usage: benchmarks/peel_front_diagnosis.py [--work DIR] [--only CASE] [--variant NAME]   (about 15 minutes; needs a build)
--only and --variant run a part and replace its rows of the csv.
"""
import argparse
import collections
import csv
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
ROTATION = os.path.join(ROOT, 'results', 'medium', 'peel-rotation')


def set_parameter(root, key, value, kind):
    *lists, name = key.split('/')
    node = root
    for part in lists:
        found = [c for c in node if c.tag == 'ParameterList' and c.get('name') == part]
        node = found[0] if found else ElementTree.SubElement(node, 'ParameterList', name=part)
    found = [c for c in node if c.tag == 'Parameter' and c.get('name') == name]
    parameter = found[0] if found else ElementTree.SubElement(node, 'Parameter', name=name, type=kind)
    parameter.set('value', str(value))


DIAGNOSIS = [('Output/tangent spectrum', 10, 'int'), ('Output/convergence tables', 'true', 'bool'),
             ('Nonlinear Solver/front diagnosis', 'true', 'bool'),
             ('Output/write mesh', 'false', 'bool'), ('Output/field interval', 0, 'int')]
CASES = {
    'medium-rotation-45-54': (os.path.join(ROTATION, 'scene.xml'), [
        ('Loading/theta_y', 54.0, 'double'), ('Loading/restart file', os.path.join(ROTATION, 'checkpoints.h5'), 'string'),
        ('Loading/restart theta_y', 45.0, 'double'), ('Loading/Rotation Steps/initial', 0.9, 'double'),
        ('Loading/Rotation Steps/maximum', 0.9, 'double')]),
    'coarse-rotation-to-40': (os.path.join(ROOT, 'xml', 'default.xml'), [('Loading/theta_y', 40.0, 'double')]),
}
ROW = re.compile(r'^ +(\d+) +([0-9.e+-]+) +([0-9.e+-]+) +([0-9.e+-]+) +(-?\d+) +([0-9.e+-]+) +([0-9.e+-]+)$')
# The diagnosis of each iteration's full step, on the line under its row (solvers/front_diagnosis.hpp).
FULL_STEP = re.compile(r'full step: (\d+) contact points cross the law.s inflection(?: \(at X = ([0-9.-]+) \+- '
                       r'([0-9.]+), Y = [0-9.-]+ \+- [0-9.]+ nm\))?; Pi - Pi_0 at t = 0.25: (\S+), 0.5: (\S+), '
                       r'0.75: (\S+), 1: (\S+) nN nm, of which their Pi_c (\S+), (\S+), (\S+), (\S+);')


def full_steps(lines):
    """Per iteration: (line-search step, crossing points, X spread, energy along the full step rises, ... without
    the crossing points' adhesion)."""
    steps = []
    for row, below in zip(lines, lines[1:]):
        m, d = ROW.match(row), FULL_STEP.search(below)
        if not (m and d):
            continue
        total = [float(d.group(k)) for k in range(4, 8)]
        rest = [t - float(d.group(k + 4)) for k, t in zip(range(4, 8), total)]
        rises = lambda values: any(b > a for a, b in zip(values, values[1:]))
        steps.append((float(m.group(4)), int(d.group(1)), float(d.group(3) or 0.0), rises(total), rises(rest)))
    return steps


# Solver variants: (name, keep the recorded scene's solver lists, settings).
VARIANTS = {
    'medium-rotation-45-54': [
        ('default', False, []),
        ('extension-0', False, [('Nonlinear Solver/converging extension', 0, 'int')]),
        ('recorded-solver', True, []),
        ('recorded-solver-extension-0', True, [('Nonlinear Solver/converging extension', 0, 'int')]),
        ('elimination-before-direction', False,
         [('Nonlinear Solver/Front Elimination/use', 'before the direction', 'string')]),
        ('elimination-after-full-step', False,
         [('Nonlinear Solver/Front Elimination/use', 'after the full step', 'string')]),
        ('soft-mode-line-search', False, [('Nonlinear Solver/Front Elimination/use', 'soft mode', 'string')]),
        ('front-limited-step', False, [('Nonlinear Solver/Front Elimination/use', 'front-limited step', 'string')]),
        ('front-limited-step-0.1', False, [('Nonlinear Solver/Front Elimination/use', 'front-limited step', 'string'),
                                           ('Nonlinear Solver/Front Elimination/beyond inflection', 0.1, 'double')]),
        ('front-limited-step-0.4', False, [('Nonlinear Solver/Front Elimination/use', 'front-limited step', 'string'),
                                           ('Nonlinear Solver/Front Elimination/beyond inflection', 0.4, 'double')]),
        ('contact-quadrature-8', False, [('Adhesion/quadrature', 8, 'int')]),
        # the front's cost against the step: half and twice the 0.9 deg steps over the same 9 deg
        ('rotation-steps-0.45', False, [('Loading/Rotation Steps/initial', 0.45, 'double'),
                                        ('Loading/Rotation Steps/maximum', 0.45, 'double')]),
        ('rotation-steps-1.8', False, [('Loading/Rotation Steps/initial', 1.8, 'double'),
                                       ('Loading/Rotation Steps/maximum', 1.8, 'double')]),
    ],
    'coarse-rotation-to-40': [
        ('default', False, []),
        ('extension-0', False, [('Nonlinear Solver/converging extension', 0, 'int')]),
        ('refinement-2', False, [('Mesh/refinement factor', 2, 'int')]),   # every pad element split 2 x 2
    ],
}


def run(case, work, variant):
    source, settings = CASES[case]
    label, keep_solver, variant_settings = variant
    root = ElementTree.parse(source).getroot()
    if not keep_solver:   # the current solver defaults
        for child in [c for c in root if c.tag == 'ParameterList' and c.get('name') in ('Nonlinear Solver',
                                                                                         'Linear Solver')]:
            root.remove(child)
    name = f'{case}-{label}'
    extra = [('Output/directory', name, 'string')] + variant_settings
    for key, value, kind in settings + DIAGNOSIS + extra:
        set_parameter(root, key, value, kind)
    os.makedirs(work, exist_ok=True)
    scene = os.path.join(work, name + '.xml')
    ElementTree.ElementTree(root).write(scene)
    log = os.path.join(work, name + '.log')
    with open(log, 'w') as out:
        status = subprocess.run([APP, scene], cwd=work, stdout=out, stderr=subprocess.STDOUT).returncode
    if status != 0:
        sys.exit(f'{case}: spatula exited {status}; see {log}')
    return name, log, os.path.join(work, name, 'spectrum.csv')


def summarize(case, log, spectrum):
    lines = open(log).read().splitlines()
    rows = [m.groups() for m in (ROW.match(line) for line in lines) if m]
    tangents = next(int(m.group(1)) for m in (re.match(r'^solver: (\d+) tangents', line) for line in lines) if m)
    cut = [r for r in rows if float(r[3]) < 1.0]
    diagnosed = full_steps(lines)
    crossing = sorted(d[1] for d in diagnosed)
    failed = sum(1 for line in lines if 'failed (no convergence' in line)
    states = list(csv.DictReader(open(spectrum)))
    iterations = [int(s['newton_iterations']) for s in states]
    histogram = collections.Counter(min(i, 12) for i in iterations)
    relative = [abs(float(s['nearest_over_mean_diagonal'])) for s in states]
    value = [float(s['nearest_eigenvalue_nN_per_nm']) for s in states]
    participation = [float(s['participation']) for s in states]
    return {
        'case': case, 'end_theta_y_deg': states[-1]['load'][:8], 'states': len(states), 'tangents': tangents, 'tangents_per_state': round(tangents / len(states), 2),
        'iterations_in_converged_states': sum(iterations), 'failed_attempts': failed,
        'line_search_cuts': len(cut),
        'cut_slope_ratio_median': round(sorted(float(r[6]) for r in cut)[len(cut) // 2], 3) if cut else '',
        # the limiting points: crossing the law's inflection under the full step, and whether they alone raise the
        # energy along it (it rises with them, falls monotonically without their adhesion energy)
        'crossing_points_median': crossing[len(crossing) // 2] if crossing else '',
        'crossing_points_max': crossing[-1] if crossing else '',
        'crossing_x_spread_median_nm': sorted(d[2] for d in diagnosed)[len(diagnosed) // 2] if diagnosed else '',
        'full_steps_over_a_barrier': sum(1 for d in diagnosed if d[3]),
        'barriers_without_the_crossing_points': sum(1 for d in diagnosed if d[3] and d[4]),
        'nearest_eigenvalue_min': f'{min(value):.3e}', 'nearest_eigenvalue_max': f'{max(value):.3e}',
        'nearest_over_diagonal_min': f'{min(relative):.2e}', 'nearest_over_diagonal_max': f'{max(relative):.2e}',
        'participation_min': round(min(participation), 3), 'participation_max': round(max(participation), 3),
        'negative_pivots_max': max(int(s['negative_pivots']) for s in states),
        'iterations_histogram': ' '.join(f'{k}{"+" if k == 12 else ""}:{histogram[k]}' for k in sorted(histogram)),
    }


def write_rows(path, results):
    """Writes the results' rows into the csv, replacing the rows of the same case and keeping the others, in the
    order of CASES and VARIANTS."""
    rows = {r['case']: r for r in (csv.DictReader(open(path)) if os.path.exists(path) else [])}
    rows.update({r['case']: r for r in results})
    order = [f'{case}-{variant[0]}' for case in CASES for variant in VARIANTS[case]]
    fields = list(results[0]) + [k for r in rows.values() for k in r if k not in results[0]]
    fields = list(dict.fromkeys(fields))
    with open(path, 'w', newline='') as out:
        writer = csv.DictWriter(out, fieldnames=fields, restval='')
        writer.writeheader()
        writer.writerows(rows[name] for name in order if name in rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--work', default=os.path.join(ROOT, 'build', 'peel-front-diagnosis'))
    parser.add_argument('--only', choices=sorted(CASES))
    parser.add_argument('--variant', help='run only the variants of this name (their rows of the csv are replaced)')
    arguments = parser.parse_args()
    results = [summarize(*run(case, arguments.work, variant)) for case in CASES if arguments.only in (None, case)
               for variant in VARIANTS[case] if arguments.variant in (None, variant[0])]
    if not results:
        sys.exit(f'peel_front_diagnosis: no variant {arguments.variant!r} in {arguments.only or "any case"}')
    write_rows(os.path.join(ROOT, 'docs', 'peel-front-diagnosis.csv'), results)
    keys = list(results[0])
    print('| ' + ' | '.join(keys) + ' |\n|' + '---|' * len(keys))
    for result in results:
        print('| ' + ' | '.join(str(result[k]) for k in keys) + ' |')


if __name__ == '__main__':
    main()
