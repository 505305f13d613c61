#!/usr/bin/env python3
"""Run time against error: the pull-off at 60 deg (rotation to 60 deg with zero net force, then lift to detachment)
over mesh level x Q1C1/Q1C2 x contact quadrature x linear solver x MPI ranks x step-size control.

    benchmarks/error_vs_time.py [--set grid refinement solvers ...] [--work DIR] [--docs]

Measured per run: P_max, Delta u_z and Delta Pi_ext of the pull-off, M_y at theta_y = 15, 20, 25 deg (the smooth part
of the moment curve; since 2026-12-02 each run's rotation lands a step on these angles, so that M_y there is not a
chord across a step of up to 2 deg: the check row moved by at most 0.03 %), the wall time (rotation, lift, total;
one run at a time) and the CPU time of the run's processes (all ranks). Time is plotted as CPU seconds: that stays meaningful when the machine is shared with other
runs, which wall time does not. Reference: Richardson extrapolation over the in-plane refinement k = 1, 2, 4 (coarse,
coarse with refinement factor 2, medium; Q1C2, 6x6 points), with the observed order; the errors of every run are
relative to it. `--medium-from DIR` takes the k = 4 point from a study's medium runs (DIR/peel-rotation and
DIR/pull-off-60 of scripts/run-study.py, which differ from the benchmark's scene only in reusing factorizations,
lag 4) instead of running it again (about 25 minutes); its time is then that study's wall time. Results:
<work>/results.csv, and with --docs docs/error-vs-time.md and docs/error-vs-time.png (error against time with the
Pareto front), and docs/error-vs-time.csv (every configuration's values and errors). Runs already in
<work>/results.csv are not repeated.

`--check NAME` (CI) runs one configuration in a fresh work directory and compares it with its row in
docs/error-vs-time.csv: the quantities must agree to 0.2 % and the error against the stored reference must be the
recorded one within 0.2 percentage points; and every jump of the run must have released more than 1e-4 Pi_c0. SPATULA_APP overrides the app's path.
"""
import argparse
import csv
import math
import os
import resource
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from curves import RECORDED_BENCHMARK_START, interpolate, pull_off_summary, read_curve  # noqa: E402
from scenes import app_diagnosis, benchmark_scene  # noqa: E402

# The base every option is compared with. It keeps lag 0 (the app's default when the sets were measured; the app's
# default became 4 after the lag pair, then 'refactor' = cost) so that the stored rows stay comparable; the scenes
# always set the lag and 'refactor' = lag, under which the lag applies.
DEFAULT = dict(level='coarse', refinement=1, enrichment='Q1C2', quadrature=6, solver='mumps', lag=0, ranks=1,
               rotation_maximum=2.0, lift_maximum=5.0, skip=True, substrate='flat', fields=-1)
SETS = {
    # mesh level x enrichment x contact quadrature on the coarse mesh
    'grid': [dict(enrichment=e, quadrature=q) for e in ('Q1C1', 'Q1C2') for q in (2, 3, 4, 6)],
    # in-plane refinement k = 1, 2, 4 (the reference) and the enrichment / quadrature on the finer meshes
    'refinement': [dict(refinement=2), dict(level='medium')],
    'refinement-extra': [dict(refinement=2, enrichment='Q1C1'), dict(refinement=2, quadrature=3),
                         dict(level='medium', quadrature=3)],
    # linear solvers, ranks and step control on the coarse mesh (each against the coarse default: what it saves and
    # what it changes), and on the coarse x2 mesh
    'solvers': [dict(lag=4), dict(solver='gmres-ilu'), dict(ranks=2), dict(rotation_maximum=4.0, lift_maximum=10.0),
                dict(rotation_maximum=1.0, lift_maximum=2.5)],
    'solvers-x2': [dict(refinement=2, lag=4), dict(refinement=2, solver='gmres-ilu'), dict(refinement=2, ranks=2),
                   dict(refinement=2, rotation_maximum=4.0, lift_maximum=10.0),
                   dict(refinement=2, rotation_maximum=1.0, lift_maximum=2.5)],
    'medium-solvers': [dict(level='medium', lag=4), dict(level='medium', ranks=2, lag=4)],
    # what each skip saves, on the coarse mesh: the cut-off skip off, the flat substrate through the rough-substrate
    # code (z0 = 0: projection and curvature terms evaluated), fields written at every step / first and last only
    # (fields=-1, the default here, writes none)
    # reusing a factorization for up to 4 Newton iterations
    'lag': [dict(lag=4), dict(refinement=2, lag=4)],
    'skips': [dict(skip=False), dict(substrate='rough0'), dict(fields=1), dict(fields=0)],
}
REFERENCE = [dict(), dict(refinement=2), dict(level='medium')]
MOMENT_ANGLES = (15.0, 20.0, 25.0)
QUANTITIES = ('P_max_nN', 'delta_u_z_nm', 'delta_Pi_ext_1e-18J')
# This benchmark measures Delta u_z and Delta Pi_ext to the final detachment (as its recorded table was made), not to
# the main snap the study tables use (scripts/curves.py, pull_off_summary).
SUMMARY_KEY = {'delta_u_z_nm': 'final_delta_u_z_nm', 'delta_Pi_ext_1e-18J': 'final_delta_Pi_ext_1e-18J'}


def configuration(overrides):
    c = dict(DEFAULT)
    c.update(overrides)
    return c


def name(c):
    parts = [c['level'] + (f'x{c["refinement"]}' if c['refinement'] > 1 else ''), c['enrichment'], f'q{c["quadrature"]}',
             c['solver'] + (f'-lag{c["lag"]}' if c['lag'] else ''), f'np{c["ranks"]}',
             f'steps{c["rotation_maximum"]:g}-{c["lift_maximum"]:g}']
    if not c['skip']:
        parts.append('noskip')
    if c['substrate'] != 'flat':
        parts.append(c['substrate'])
    if c['fields'] >= 0:
        parts.append(f'fields{c["fields"]}')
    return '_'.join(parts)


def scene(c, directory):
    adhesion = {'enrichment': c['enrichment'], 'quadrature': c['quadrature'], 'skip distant faces': c['skip']}
    if c['substrate'] == 'rough0':
        adhesion.update({'substrate': 'rough', 'Rough Substrate': {'z0': 0.0}})
    return benchmark_scene(directory, mesh=c['level'], refinement=c['refinement'], adhesion=adhesion,
                           rotation_maximum=c['rotation_maximum'], lift_maximum=c['lift_maximum'],
                           linear_solver={'type': c['solver'], 'lag': c['lag'], 'refactor': 'lag'}, fields=c['fields'],
                           land_at=MOMENT_ANGLES)


def measure(work, c):
    directory = name(c)
    xml = os.path.join(work, directory + '.xml')
    open(xml, 'w').write(scene(c, directory))
    command = [APP, xml]
    if c['ranks'] > 1:
        command = ['mpirun', '--allow-run-as-root', '-np', str(c['ranks'])] + command
    environment = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
    started = time.time()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(os.path.join(work, directory + '.log'), 'w') as log:
        status = subprocess.call(command, cwd=work, stdout=log, stderr=subprocess.STDOUT, env=environment)
    wall = time.time() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    row = dict(c, name=directory, status=status, wall_s=round(wall, 1), cpu_s=round(cpu, 1))
    if status != 0:
        return row
    rows = read_curve(work, directory)
    rotation = [r for r in rows if r['stage'] == 'rotation']
    row['rotation_s'] = round(rotation[-1]['wall_s'], 1)
    row['lift_s'] = round(rows[-1]['wall_s'] - rotation[-1]['wall_s'], 1)
    row['newton_iterations'] = int(sum(r['newton_iterations'] for r in rows))
    summary = pull_off_summary(work, directory, count_from=RECORDED_BENCHMARK_START)
    for q in QUANTITIES:
        row[q] = summary[SUMMARY_KEY.get(q, q)]
    for angle in MOMENT_ANGLES:
        row[f'M_y_{angle:g}'] = interpolate(rotation, 'theta_y_deg', angle, ['M_y_nNnm'])['M_y_nNnm']
    row['worst_balance'] = summary['worst_balance_error']
    return row


def from_study(directory):
    """The k = 4 reference point from a study's medium peel-rotation (to 60 deg) and pull-off-60 runs."""
    c = configuration(dict(level='medium'))
    rotation = [r for r in read_curve(directory, 'peel-rotation') if r['theta_y_deg'] <= 60.0 + 1e-9]
    lift = read_curve(directory, 'pull-off-60')
    row = dict(c, name=name(c), status=0, rotation_s=round(rotation[-1]['wall_s'], 1),
               lift_s=round(lift[-1]['wall_s'], 1))
    row['wall_s'] = row['cpu_s'] = round(row['rotation_s'] + row['lift_s'], 1)
    row['newton_iterations'] = int(sum(r['newton_iterations'] for r in rotation + lift))
    summary = pull_off_summary(directory, 'pull-off-60', count_from=RECORDED_BENCHMARK_START)
    for q in QUANTITIES:
        row[q] = summary[SUMMARY_KEY.get(q, q)]
    for angle in MOMENT_ANGLES:
        row[f'M_y_{angle:g}'] = interpolate(rotation, 'theta_y_deg', angle, ['M_y_nNnm'])['M_y_nNnm']
    row['worst_balance'] = summary['worst_balance_error']
    row['source'] = f'study {directory}'
    return row


def number(text):
    """A CSV cell: a float where it is one, None where empty, the text otherwise (names, True/False)."""
    if not text:
        return None
    try:
        return float(text)
    except ValueError:
        return text


def load(path):
    if not os.path.exists(path):
        return {}
    out = {}
    for r in csv.DictReader(open(path)):
        out[r['name']] = {k: number(v) for k, v in r.items()}
    return out


def save(path, results):
    keys = []
    for r in results.values():
        keys += [k for k in r if k not in keys]
    with open(path, 'w') as out:
        writer = csv.DictWriter(out, keys)
        writer.writeheader()
        for r in results.values():
            writer.writerow(r)


def richardson(values):
    """The extrapolated limit of values at refinement 1, 2, 4 (halving h), the observed order, and an uncertainty."""
    a, b, c = values
    if (a - b) * (b - c) > 0 and abs(b - c) > 0:
        order = min(max(math.log(abs(a - b) / abs(b - c), 2.0), 0.5), 4.0)
        limit = c + (c - b) / (2.0 ** order - 1.0)
        return limit, order, abs(limit - c)
    return c, float('nan'), abs(c - b)   # not monotone: the finest value, with the last change as its uncertainty


def reference_names(results):
    """The runs the reference is made of: k = 1, 2, 4 where all three ran, else k = 1 and 4 (then the reference is
    the k = 4 value, with the k = 1 -> 4 change divided by 4^2 - 1 as its uncertainty, assuming second order)."""
    names = [name(configuration(o)) for o in REFERENCE]
    present = [n for n in names if n in results and results[n].get('status') == 0]
    if present == names:
        return names
    if names[0] in present and names[2] in present:
        return [names[0], names[2]]
    return None


def reference(results):
    names = reference_names(results)
    if names is None:
        return None
    out = {}
    for key in list(QUANTITIES) + [f'M_y_{a:g}' for a in MOMENT_ANGLES]:
        values = [results[n][key] for n in names]
        out[key] = richardson(values) if len(values) == 3 else (values[1], float('nan'), abs(values[1] - values[0]) / 15.0)
    return out


def errors(row, ref):
    pull = max(abs(row[q] / ref[q][0] - 1.0) for q in QUANTITIES)
    moment = max(abs(row[f'M_y_{a:g}'] / ref[f'M_y_{a:g}'][0] - 1.0) for a in MOMENT_ANGLES)
    return pull, moment


def diagnosis(work, run_name):
    """The app's failure line of a run (which step, which load, why)."""
    path = os.path.join(work, run_name + '.log')
    return (app_diagnosis(open(path).read()) if os.path.exists(path) else None) or 'no diagnosis in the log'


def option_table(done):
    """Each option against its base (the default configuration at the same mesh level): CPU time ratio and the change
    of every quantity, so that a skip or a solver choice shows what it saves and what it costs in accuracy."""
    by_name = {r['name']: r for r in done}
    configurations = {name(configuration(o)): configuration(o) for group in [REFERENCE] + list(SETS.values())
                      for o in group}
    rows = []
    for r in done:
        c = configurations.get(r['name'])
        if c is None:
            continue
        base = configuration(dict(level=c['level'], refinement=c['refinement']))
        if name(base) == r['name'] or name(base) not in by_name:
            continue
        b = by_name[name(base)]
        option = ', '.join(f'{k} = {v}' for k, v in c.items() if v != base[k])
        change = ' | '.join(f'{100 * (r[q] / b[q] - 1.0):+.2f} %' for q in list(QUANTITIES) + ['M_y_20'])
        rows.append(f'| {option} | {name(base)} | {r["cpu_s"]:.0f} / {b["cpu_s"]:.0f} = {r["cpu_s"] / b["cpu_s"]:.2f} '
                    f'| {change} |')
    if not rows:
        return []
    return ['', '## What each option saves and changes (against the default at the same mesh level)', '',
            'CPU time of the run with the option over that of its base; the change of each quantity relative to the '
            'base (not to the reference: the discretization error of the base is common to both).', '',
            '| option | base | CPU [s] option / base | P_max | Δu_z | ΔΠ_ext | M_y(20°) |', '|---|---|---|---|---|---|---|'] + sorted(rows)


def document(results, ref, work):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    done = [r for r in results.values() if r.get('status') == 0]
    lines = ['# Run time against error: pull-off at 60°', '',
             'Written by `benchmarks/error_vs_time.py --docs` (see its header for what is measured); numbers from one '
             'run of each configuration on this 2-core machine, one run at a time. Time is the CPU time of the run '
             '(all its processes): the machine ran other jobs at the same time, so wall times are longer and vary. '
             'A row whose source is a study took its time from that study\'s wall clock. The rows were made before '
             'the step control bisected towards a twice-failed load (commit 9d02272, 21 % less CPU on the coarse '
             'pull-off, [performance.md](performance.md)); a run is redone by deleting its row from '
             '`<work>/results.csv`. Against the fine level (the paper\'s resolution) and with the equal-area shaft '
             'section, and the mesh `Mesh/level` = auto picks for a target error: [mesh-choice.md](mesh-choice.md).', '',
             '## Reference (Q1C2, 6 × 6 points)', '']
    names = reference_names(results)
    if len(names) == 3:
        lines += ['Richardson extrapolation over the in-plane refinement k = 1, 2, 4 with the observed order.', '',
                  '| quantity | k = 1 | k = 2 | k = 4 | extrapolated | observed order | uncertainty |',
                  '|---|---|---|---|---|---|---|']
    else:
        lines += ['The k = 2 run was not made, so no extrapolation: the reference is the finest run (k = 4, the medium '
                  'mesh), with (k = 4 − k = 1)/15 as its uncertainty (second order assumed). Errors of the coarse '
                  'runs against it are therefore lower bounds only where they are small; the large ones stand.', '',
                  '| quantity | k = 1 | k = 4 | reference | observed order | uncertainty |', '|---|---|---|---|---|---|']
    for key, (limit, order, uncertainty) in ref.items():
        values = ' | '.join(f'{results[n][key]:.4g}' for n in names)
        order_text = f'{order:.2f}' if math.isfinite(order) else '-'
        lines.append(f'| {key} | {values} | {limit:.4g} | {order_text} | {uncertainty:.2g} |')
    lines += ['', '## Every configuration', '',
              '| configuration | CPU [s] | wall [s] | Newton its | P_max [nN] | Δu_z [nm] | ΔΠ_ext | '
              'pull-off error | M_y error | worst balance |', '|---|---|---|---|---|---|---|---|---|---|']
    points = []
    for r in sorted(done, key=lambda r: r['cpu_s']):
        pull, moment = errors(r, ref)
        points.append((r['cpu_s'], max(pull, moment), r['name']))
        label = r['name'] + (f' ({r["source"]})' if r.get('source') else '')
        lines.append(f'| {label} | {r["cpu_s"]:.0f} | {r["wall_s"]:.0f} | '
                     f'{r["newton_iterations"]:.0f} | {r["P_max_nN"]:.3f} | {r["delta_u_z_nm"]:.1f} | '
                     f'{r["delta_Pi_ext_1e-18J"]:.0f} | {100 * pull:.2f} % | {100 * moment:.2f} % | '
                     f'{r["worst_balance"]:.1e} |')
    lines += option_table(done)
    failed = [r for r in results.values() if r.get('status') != 0]
    for r in failed:
        lines.append(f'| {r["name"]} | {r["cpu_s"]:.0f} | {r["wall_s"]:.0f} | failed: {diagnosis(work, r["name"])} |'
                     ' | | | | | |')
    front, best = [], float('inf')
    for wall, error, label in sorted(points):
        if error < best:
            front.append((wall, error, label))
            best = error
    lines += ['', '## Pareto front (no configuration is both faster and more accurate)', '',
              '| configuration | CPU [s] | largest error |', '|---|---|---|']
    lines += [f'| {label} | {cpu:.0f} | {100 * error:.2f} % |' for cpu, error, label in front]
    within = [p for p in points if p[1] <= 0.01]
    if within:
        fastest = min(within)
        lines += ['', f'Fastest configuration within 1 %: **{fastest[2]}** ({fastest[0]:.0f} s, '
                      f'{100 * fastest[1]:.2f} %).']
    else:
        lines += ['', 'No configuration measured here is within 1 % of the reference in every quantity.']
    figure, axis = plt.subplots(figsize=(8, 5))
    for wall, error, label in points:
        axis.loglog(wall, 100 * error, 'o', color='tab:blue')
        axis.annotate(label.replace('_', ' '), (wall, 100 * error), fontsize=6, xytext=(3, 3), textcoords='offset points')
    axis.loglog([p[0] for p in front], [100 * p[1] for p in front], '-', color='tab:red', label='Pareto front')
    axis.axhline(1.0, color='grey', linestyle='--', label='1 %')
    axis.set_xlabel('CPU time, rotation to 60° + pull-off [s]')
    axis.set_ylabel('largest relative error (P_max, Δu_z, ΔΠ_ext, M_y) [%]')
    axis.legend()
    axis.grid(alpha=0.3, which='both')
    figure.tight_layout()
    figure.savefig(os.path.join(ROOT, 'docs', 'error-vs-time.png'), dpi=110)
    lines += ['', '![error against CPU time](error-vs-time.png)', '']
    open(os.path.join(ROOT, 'docs', 'error-vs-time.md'), 'w').write('\n'.join(lines))
    print('wrote docs/error-vs-time.md and docs/error-vs-time.png')


def check(configuration_name, work):
    """Runs one recorded configuration again and compares it with docs/error-vs-time.csv; returns the exit code."""
    recorded = load(os.path.join(ROOT, 'docs', 'error-vs-time.csv'))
    if configuration_name not in recorded or 'reference' not in recorded:
        sys.exit(f'docs/error-vs-time.csv has no row "{configuration_name}" (or no reference row); '
                 f'rows: {", ".join(recorded)}')
    c = next(configuration(o) for group in [REFERENCE] + list(SETS.values()) for o in group
             if name(configuration(o)) == configuration_name)
    os.makedirs(work, exist_ok=True)
    row = measure(work, c)
    if row['status'] != 0:
        print(f'{configuration_name}: the run failed (exit {row["status"]}); log in {work}')
        return 1
    ref = {k: (v, 0, 0) for k, v in recorded['reference'].items() if k in list(QUANTITIES) + [f'M_y_{a:g}' for a in MOMENT_ANGLES]}
    ok = True
    for key in ref:
        was, now = recorded[configuration_name][key], row[key]
        good = abs(now / was - 1.0) <= 2e-3
        ok &= good
        print(f'{key:22s} recorded {was:12.5g}  now {now:12.5g}  reference {ref[key][0]:12.5g}  '
              f'{"ok" if good else "DIFFERS"}')
    pull, moment = errors(row, ref)
    for label, now, was in (('pull-off error', pull, recorded[configuration_name]['pull_off_error']),
                            ('M_y error', moment, recorded[configuration_name]['moment_error'])):
        good = abs(now - was) <= 2e-3
        ok &= good
        print(f'{label:22s} recorded {100 * was:6.2f} %  now {100 * now:6.2f} %  {"ok" if good else "DIFFERS"}')
    # Every recorded jump is a snap: it released more than the step balance tolerance (1e-4 Pi_c0, the app's
    # default); a descent that stayed on its branch is an ordinary step.
    rows = read_curve(work, name(c))
    released = [b['dissipated_per_Pi_c0'] - a['dissipated_per_Pi_c0'] for a, b in zip(rows, rows[1:]) if b['after_jump']]
    good = all(r > 1e-4 for r in released)
    ok &= good
    print(f'{"jumps":22s} {len(released)}, the smallest released {min(released, default=0):.2e} Pi_c0  '
          f'{"ok" if good else "A JUMP RELEASED NO ENERGY"}')
    print(f'{configuration_name}: {row["cpu_s"]:.0f} s CPU; {"agrees with" if ok else "DIFFERS FROM"} docs/error-vs-time.csv')
    return 0 if ok else 1


def record(results, ref):
    """docs/error-vs-time.csv: the reference and every configuration's values and errors."""
    keys = list(QUANTITIES) + [f'M_y_{a:g}' for a in MOMENT_ANGLES]
    rows = {'reference': dict(name='reference', **{k: ref[k][0] for k in keys})}
    for r in results.values():
        if r.get('status') == 0:
            pull, moment = errors(r, ref)
            rows[r['name']] = dict(name=r['name'], cpu_s=r['cpu_s'], wall_s=r['wall_s'],
                                   **{k: r[k] for k in keys}, pull_off_error=pull, moment_error=moment)
    save(os.path.join(ROOT, 'docs', 'error-vs-time.csv'), rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--set', nargs='*', default=['grid', 'refinement', 'solvers'], choices=sorted(SETS))
    parser.add_argument('--work', default=os.path.join(ROOT, 'benchmark-output', 'error-vs-time'))
    parser.add_argument('--medium-from', help='a study directory with peel-rotation and pull-off-60 on the medium mesh')
    parser.add_argument('--docs', action='store_true')
    parser.add_argument('--no-run', action='store_true', help='only tabulate the runs already in results.csv')
    parser.add_argument('--check', metavar='NAME', help='run one configuration and compare it with docs/error-vs-time.csv')
    arguments = parser.parse_args()
    if not os.path.exists(APP):
        sys.exit(f'{APP} not found: build first (bash scripts/build.sh)')
    if arguments.check:
        return check(arguments.check, arguments.work)
    os.makedirs(arguments.work, exist_ok=True)
    path = os.path.join(arguments.work, 'results.csv')
    results = load(path)
    wanted = [configuration(o) for o in REFERENCE]
    if arguments.medium_from:
        row = from_study(arguments.medium_from)
        results[row['name']] = row
        save(path, results)
    for s in arguments.set:
        wanted += [configuration(o) for o in SETS[s]]
    # the reference runs first (every error needs them), then the cheapest first
    references = {name(configuration(o)) for o in REFERENCE}
    wanted.sort(key=lambda c: (name(c) not in references, c['level'] == 'medium', c['refinement']))
    for c in wanted:
        n = name(c)
        if n in results or arguments.no_run:
            continue
        print(f'[{n}] running', flush=True)
        results[n] = measure(arguments.work, c)
        r = results[n]
        print(f'[{n}] exit {r["status"]}, {r["wall_s"]:.0f} s' +
              (f', P_max {r["P_max_nN"]:.3f} nN' if r['status'] == 0 else ''), flush=True)
        save(path, results)
    ref = reference(results)
    if ref is None:
        print('reference runs incomplete: no errors computed')
        return 1
    for r in results.values():
        if r.get('status') == 0:
            pull, moment = errors(r, ref)
            print(f'{r["name"]:60s} {r["wall_s"]:7.0f} s  pull-off error {100 * pull:6.2f} %  M_y error {100 * moment:6.2f} %')
    if arguments.docs:
        document(results, ref, arguments.work)
        record(results, ref)
    return 0


if __name__ == '__main__':
    sys.exit(main())
