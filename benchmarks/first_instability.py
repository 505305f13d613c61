#!/usr/bin/env python3
"""What moves the first instability of the peel by rotation.

Ours comes at theta_y = 32.2 deg on the medium mesh, the paper's at 31 deg, and our Pi_sa at 30 deg is twice the
paper's. Each variant below is the frictionless Q1C2 rotation from theta_s to 36 deg with one thing changed from the
base (coarse mesh with 'refinement factor' 2: 2 x 2 more contact faces than the coarse pad, cheap enough to vary
everything); the mesh series refines the coarse mesh in plane ('refinement factor' 1, 2, 4, 8: pad elements of
about 33, 16, 8 and 4 nm; 4 is the medium mesh, 8 has the fine mesh's contact faces with the coarse shaft
cross-section and 4 layers through the pad) and adds the medium study's rotation (results/medium/
peel-rotation) when present:

  mesh          refinement factor 1, 2, 4, 8 (and the medium study run); 10 element layers through the pad
  quadrature    Gauss points per direction on each contact face: 3, 4, 8 (base 6)
  enrichment    Q1C1 (bilinear contact surface; base Q1C2)
  regularization  r_reg / r_eq = 0.6, 0.9 (base 0.8: below r_reg the traction continues linearly)
  cut-off       5 and 20 nm (base 10)
  steps         rotation steps of at most 0.5 deg (base 2), smallest 0.001 deg (base 0.01)

Recorded per run: the angle of the last state before the first jump that releases energy (more than 1e-4 Pi_c0; a
descent that stays on its branch is an ordinary step) and before the first instability proper (the first jump that
drops M_y by more than 10 %, as the paper's 23 % at 31 deg), M_y there and just after, Pi_sa / Pi_c0 and Pi_int / Pi_c0 at
30 deg (a step lands there), Newton iterations and wall time. Runs one after another in --work (default
first-instability/); a run already complete there is read, not run again.

    benchmarks/first_instability.py [--only base quadrature-3 ...] [--work DIR] [--docs]

--docs writes docs/first-instability.csv (the table is printed; docs/validation-notes.md quotes it).
"""
import argparse
import csv
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from curves import interpolate, read_curve  # noqa: E402
from scenes import benchmark_scene  # noqa: E402

APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
MEDIUM_STUDY = os.path.join(ROOT, 'results', 'medium')
FINAL_THETA = 36.0
JUMP_RELEASE = 1e-4   # Pi_c0: the app's step balance tolerance; less is an ordinary step
MAJOR_DROP = 0.1      # the first instability proper: a jump that drops M_y by more than 10 %
BASE = dict(refinement=2, layers=0, section='inscribed', adhesion={}, rotation_maximum=2.0, steps={})
VARIANTS = {   # name: (what changed, scene arguments)
    'refinement-1': ('refinement factor 1 (the coarse mesh)', dict(refinement=1)),
    'base': ('refinement factor 2 (the base)', {}),
    'refinement-4': ('refinement factor 4 (the medium mesh)', dict(refinement=4)),
    'refinement-8': ('refinement factor 8 (the fine mesh\'s contact faces)', dict(refinement=8)),
    'layers-6': ('6 element layers through the pad (base 4)', dict(layers=6)),
    'layers-8': ('8 element layers through the pad', dict(layers=8)),
    'layers-10': ('10 element layers through the pad (the fine level\'s)', dict(layers=10)),
    'refinement-4-layers-10': ('refinement factor 4 (medium) with 10 layers through the pad',
                               dict(refinement=4, layers=10)),
    'section-equal-area': ('4 layers, the shaft and rim section with its area (Mesh/section = equal area)',
                           dict(section='equal area')),
    'layers-10-section-equal-area': ('10 layers, the section with its area', dict(layers=10, section='equal area')),
    'refinement-4-section-equal-area': ('refinement factor 4 (medium), 4 layers, the section with its area',
                                        dict(refinement=4, section='equal area')),
    'quadrature-3': ('3 x 3 points per contact face', dict(adhesion={'quadrature': 3})),
    'quadrature-4': ('4 x 4 points per contact face', dict(adhesion={'quadrature': 4})),
    'quadrature-8': ('8 x 8 points per contact face', dict(adhesion={'quadrature': 8})),
    'Q1C1': ('bilinear contact surface (Q1C1)', dict(adhesion={'enrichment': 'Q1C1'})),
    'regularization-0.6': ('r_reg / r_eq = 0.6', dict(adhesion={'regularization': 0.6})),
    'regularization-0.9': ('r_reg / r_eq = 0.9', dict(adhesion={'regularization': 0.9})),
    'cut-off-5': ('cut-off 5 nm', dict(adhesion={'cut-off': 5.0})),
    'cut-off-20': ('cut-off 20 nm', dict(adhesion={'cut-off': 20.0})),
    'steps-0.5': ('rotation steps of at most 0.5 deg', dict(rotation_maximum=0.5, steps={'initial': 0.5})),
    'minimum-0.001': ('smallest rotation step 0.001 deg', dict(steps={'minimum': 0.001})),
}


def scene(name, arguments):
    a = {**BASE, **arguments}
    return benchmark_scene(name, mesh='coarse', refinement=a['refinement'], layers=a['layers'], section=a['section'],
                           adhesion={'enrichment': 'Q1C2', **a['adhesion']}, loading='rotation', theta_y=FINAL_THETA,
                           rotation_maximum=a['rotation_maximum'], steps=a['steps'] or None, land_at=(30.0,))


def jumps(rows):
    """(state before, state after) of every jump that released energy (more than JUMP_RELEASE)."""
    return [(before, after) for before, after in zip(rows, rows[1:])
            if after['after_jump'] and after['dissipated_per_Pi_c0'] - before['dissipated_per_Pi_c0'] > JUMP_RELEASE]


def summarize(name, label, rows, wall_s):
    rotation = [r for r in rows if r['stage'] == 'rotation' and r['theta_y_deg'] <= FINAL_THETA + 1e-9]
    found = jumps(rotation)
    first = found[0] if found else (None, None)
    # The paper's first instability: the moment drops by about a quarter. Smaller jumps before it are the peel
    # front moving from contact face to contact face.
    major = next(((b, a) for b, a in found if a['M_y_nNnm'] < (1 - MAJOR_DROP) * b['M_y_nNnm']), (None, None))
    at30 = interpolate(rotation, 'theta_y_deg', 30.0, ['Pi_sa_per_Pi_c0', 'Pi_int_per_Pi_c0', 'M_y_nNnm'])
    value = lambda state, key: state[key] if state else ''
    return dict(variant=name, change=label,
                theta_first_jump_deg=value(first[0], 'theta_y_deg'), jumps_before_major=found.index(major) if major[0]
                else len(found),
                theta_major_deg=value(major[0], 'theta_y_deg'), M_y_before_nNnm=value(major[0], 'M_y_nNnm'),
                M_y_after_nNnm=value(major[1], 'M_y_nNnm'),
                released_per_Pi_c0=(major[1]['dissipated_per_Pi_c0'] - major[0]['dissipated_per_Pi_c0']) if major[0]
                else '',
                Pi_sa_30_per_Pi_c0=at30['Pi_sa_per_Pi_c0'], Pi_int_30_per_Pi_c0=at30['Pi_int_per_Pi_c0'],
                M_y_30_nNnm=at30['M_y_nNnm'], contact_faces=int(rows[0]['contact_faces_active'] +
                                                               rows[0]['contact_faces_skipped']),
                newton_iterations=int(sum(r['newton_iterations'] for r in rotation)), wall_s=round(wall_s, 1))


def run(work, name):
    label, arguments = VARIANTS[name]
    directory = os.path.join(work, name)
    if not os.path.exists(os.path.join(directory, 'curve.csv')):
        open(os.path.join(work, name + '.xml'), 'w').write(scene(name, arguments))
        environment = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
        with open(os.path.join(work, name + '.log'), 'w') as log:
            status = subprocess.call([APP, name + '.xml'], cwd=work, stdout=log, stderr=subprocess.STDOUT,
                                     env=environment)
        if status != 0:
            print(f'{name}: the run failed (exit {status}); log in {work}/{name}.log', flush=True)
            return None
    rows = read_curve(work, name)
    return summarize(name, label, rows, rows[-1]['wall_s'])


def medium_study_row():
    if not os.path.exists(os.path.join(MEDIUM_STUDY, 'peel-rotation', 'curve.csv')):
        return None
    rows = read_curve(MEDIUM_STUDY, 'peel-rotation')
    rotation = [r for r in rows if r['theta_y_deg'] <= FINAL_THETA + 1e-9]
    return summarize('medium-study', 'the medium study run (app of ad6bb70: the step control before 592a79b)', rotation,
                     rotation[-1]['wall_s'])


def table(rows):
    number = lambda v, f: format(v, f) if v != '' else '—'
    lines = ['| variant | contact faces | first jump θ_y [deg] | first instability (M_y drop > 10 %) θ_y [deg] | '
             'smaller jumps before it | M_y before → after [nN nm] | released / Π_c0 | Π_sa / Π_c0 at 30° | '
             'Π_int / Π_c0 at 30° | Newton iterations | wall [s] |',
             '|---|---|---|---|---|---|---|---|---|---|---|']
    for r in rows:
        lines.append(f"| {r['change']} | {r['contact_faces']} | {number(r['theta_first_jump_deg'], '.3f')} | "
                     f"{number(r['theta_major_deg'], '.3f')} | {r['jumps_before_major']} | "
                     f"{number(r['M_y_before_nNnm'], '.0f')} → {number(r['M_y_after_nNnm'], '.0f')} | "
                     f"{number(r['released_per_Pi_c0'], '.4f')} | {r['Pi_sa_30_per_Pi_c0']:.4f} | "
                     f"{r['Pi_int_30_per_Pi_c0']:.4f} | {r['newton_iterations']} | {r['wall_s']:.0f} |")
    return '\n'.join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--only', nargs='*', default=list(VARIANTS), choices=list(VARIANTS))
    parser.add_argument('--work', default='first-instability')
    parser.add_argument('--docs', action='store_true')
    arguments = parser.parse_args()
    work = os.path.abspath(arguments.work)
    os.makedirs(work, exist_ok=True)
    started = time.time()
    rows = []
    for name in arguments.only:
        row = run(work, name)
        if row:
            rows.append(row)
            print(f"{name}: first instability at {row['theta_major_deg']} deg, Pi_sa/Pi_c0 at 30 deg "
                  f"{row['Pi_sa_30_per_Pi_c0']:.4f} ({time.time() - started:.0f} s so far)", flush=True)
    medium = medium_study_row()
    if medium:
        rows.append(medium)
    text = table(rows)
    print(text)
    if arguments.docs:   # the variants run replace their rows; the others are kept
        path = os.path.join(ROOT, 'docs', 'first-instability.csv')
        kept = [r for r in (csv.DictReader(open(path)) if os.path.exists(path) else [])
                if r['variant'] not in {n['variant'] for n in rows}]
        order = {name: k for k, name in enumerate(list(VARIANTS) + ['medium-study'])}
        with open(path, 'w', newline='') as out:
            writer = csv.DictWriter(out, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(sorted(kept + rows, key=lambda r: order.get(r['variant'], len(order))))
        print('wrote docs/first-instability.csv')
    return 0


if __name__ == '__main__':
    sys.exit(main())
