#!/usr/bin/env python3
"""Numerical stress tests: scenes at the edges of the parameter space, each of which must either reach detachment
(or its final load) or stop with a clear diagnosis (which step, which quantity, why). Never a NaN in the output,
never a hang, never a silently wrong curve (the energy balance error is checked at every state).

    benchmarks/stress_tests.py [--jobs 2] [--work stress-output] [--only NAME ...] [--again] [--docs] [--time-limit 1200]

Cases (coarse mesh, Q1C2, pull-off at 60 deg unless said): gamma_W / gamma_W0 = 1.5^-2 .. 1.5^3, gamma_L / gamma_L0 =
1.5^-3 .. 1.5^2, rough substrate z0 = 8 and 10 nm (rotation to 45 deg), step-size maxima x4, Q1C1 (rotation to
140 deg and pull-off). With --docs the outcome matrix goes to docs/stability.md (the page's text is the template
docs/stability-notes.md). The same script with --only runs single cases. Outcomes are kept in <work>/outcomes.json;
a case already there is not run again unless --again is given. `--check NAME` (CI) runs one case afresh and compares
it with its row in docs/stability.md: the same outcome, P_max and the last state's u_z within 1 %, and the energy
balance within the paper's 2e-3 Pi_c0 at every state; exit 1 with the differences otherwise.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
GAMMA_W0, GAMMA_L0 = 25.266, 2.5
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from scenes import app_diagnosis, benchmark_scene  # noqa: E402
BALANCE_LIMIT = 2e-3   # the paper's bound on |Pi_ext - Pi_int - Pi_sa - D| / Pi_c0


def normalized(gamma_w, gamma_l):
    return {'specification': 'normalized', 'gamma_W': float(f'{gamma_w:.6g}'), 'gamma_L': float(f'{gamma_l:.6g}')}


def cases():
    out = []
    for k in (-2, -1, 0, 1, 2, 3):
        out.append((f'gamma-W-1.5^{k}', f'gamma_W = 1.5^{k} gamma_W0, pull-off at 60 deg',
                    benchmark_scene(f'gamma-W-1.5^{k}', adhesion=normalized(GAMMA_W0 * 1.5 ** k, GAMMA_L0))))
    for k in (-3, -2, -1, 1, 2):
        out.append((f'gamma-L-1.5^{k}', f'gamma_L = 1.5^{k} gamma_L0, pull-off at 60 deg',
                    benchmark_scene(f'gamma-L-1.5^{k}', adhesion=normalized(GAMMA_W0, GAMMA_L0 * 1.5 ** k))))
    for z0 in (8, 10):
        rough = {'substrate': 'rough', 'Rough Substrate': {'z0': float(z0)}}
        out.append((f'rough-z0-{z0}', f'rough substrate z0 = {z0} nm, rotation to 45 deg',
                    benchmark_scene(f'rough-z0-{z0}', adhesion=rough, loading='rotation', theta_y=45)))
    out.append(('steps-x4', 'step maxima x4 (8 deg, 20 nm), pull-off at 60 deg',
                benchmark_scene('steps-x4', rotation_maximum=8, lift_maximum=20)))
    q1c1 = {'enrichment': 'Q1C1'}
    out.append(('Q1C1-rotation', 'Q1C1, peel by rotation to 140 deg', benchmark_scene('Q1C1-rotation', adhesion=q1c1, loading='rotation', theta_y=140)))
    out.append(('Q1C1-pull-off', 'Q1C1, pull-off at 60 deg', benchmark_scene('Q1C1-pull-off', adhesion=q1c1)))
    return out


def classify(work, name, status, log_text, seconds, time_limit):
    """One row of the outcome matrix."""
    directory = os.path.join(work, name)
    curve = os.path.join(directory, 'curve.csv')
    if not os.path.exists(curve):
        curve = os.path.join(work, name + '.incomplete', 'curve.csv')
    rows = list(csv.DictReader(open(curve))) if os.path.exists(curve) else []
    finite = all(math.isfinite(float(v)) for r in rows for k, v in r.items() if k != 'stage')
    worst = max((float(r['balance_error_per_Pi_c0']) for r in rows), default=float('nan'))
    jumps = sum(int(float(r['after_jump'])) for r in rows)
    last = rows[-1] if rows else {}
    where = (f"theta_y {float(last['theta_y_deg']):.1f} deg, u_z {float(last['u_z_nm']):.0f} nm" if last else '-')
    lines = log_text.splitlines()
    detached = [l for l in lines if l.startswith('detachment')]
    error = app_diagnosis(log_text)
    if status is None:
        outcome = f'HANG: killed after {time_limit} s'
    elif not finite:
        outcome = 'NON-FINITE VALUE IN curve.csv'
    elif status == 0 and detached:
        outcome = 'detached: ' + detached[0].split(':', 1)[1].strip()
    elif status == 0:
        outcome = 'reached the final load'
    elif error:
        outcome = 'stopped: ' + error
    else:
        outcome = f'FAILED WITHOUT A DIAGNOSIS (exit {status})'
    warned = [l for l in lines if l.startswith('warning:') and 'energy balance' in l]
    balance_ok = not rows or worst <= BALANCE_LIMIT or bool(warned)   # a wrong curve, but not a silent one
    if worst > BALANCE_LIMIT:
        outcome += f'; BALANCE ERROR {worst:.1e} > {BALANCE_LIMIT:g}' + (
            f' (the app warned: {warned[0].split(":", 1)[1].split(" Pi_c0")[0].strip()})' if warned
            else ' WITHOUT A WARNING')
    acceptable = status is not None and finite and balance_ok and (status == 0 or bool(error))
    peak = max((float(r['P_z_nN']) for r in rows if r['stage'] == 'lift'), default=float('nan'))
    return {'case': name, 'status': status, 'outcome': outcome, 'acceptable': acceptable, 'states': len(rows), 'jumps': jumps,
            'last': where, 'P_max': peak, 'balance': worst, 'seconds': seconds}


def run(work, selected, jobs, time_limit, on_result=lambda row: None):
    os.makedirs(work, exist_ok=True)
    environment = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
    pending, running, results = list(selected), {}, {}
    while pending or running:
        while pending and len(running) < jobs:
            name, description, text = pending.pop(0)
            xml = os.path.join(work, name + '.xml')
            open(xml, 'w').write(text)
            log = open(os.path.join(work, name + '.log'), 'w')
            process = subprocess.Popen([APP, xml], cwd=work, stdout=log, stderr=subprocess.STDOUT, env=environment)
            running[name] = (process, log, time.time(), description)
            print(f'[{name}] started: {description}', flush=True)
        time.sleep(2)
        for name, (process, log, started, description) in list(running.items()):
            elapsed = time.time() - started
            status = process.poll()
            if status is None and elapsed < time_limit:
                continue
            if status is None:
                process.kill()
                process.wait()
            log.close()
            text = open(os.path.join(work, name + '.log')).read()
            row = classify(work, name, status, text, elapsed, time_limit)
            row['description'] = description
            results[name] = row
            on_result(row)
            print(f'[{name}] {row["outcome"]} ({elapsed:.0f} s, {row["states"]} states, worst balance '
                  f'{row["balance"]:.1e})', flush=True)
            del running[name]
    return [results[name] for name, _, _ in selected]


def markdown(rows):
    lines = ['| case | outcome | converged states | jumps | last state | P_max [nN] | worst balance error / Pi_c0 | wall [s] | acceptable |',
             '|---|---|---|---|---|---|---|---|---|']
    for r in rows:
        peak = f'{r["P_max"]:.2f}' if math.isfinite(r['P_max']) else '-'
        lines.append(f'| {r["description"]} | {r["outcome"]} | {r["states"]} | {r["jumps"]} | {r["last"]} | {peak} '
                     f'| {r["balance"]:.1e} | {r["seconds"]:.0f} '
                     f'| {"-" if r["acceptable"] is None else "yes" if r["acceptable"] else "**no**"} |')
    return '\n'.join(lines)


def recorded_row(description):
    """The row of docs/stability.md for the case with this description: outcome, P_max, the last state's u_z."""
    for line in open(os.path.join(ROOT, 'docs', 'stability.md')):
        cells = [c.strip() for c in line.strip().strip('|').split('|')]
        if len(cells) == 9 and cells[0] == description:
            return {'outcome': cells[1], 'P_max': float(cells[5]), 'u_z': float(cells[4].split('u_z')[1].split()[0])}
    sys.exit(f'no row for "{description}" in docs/stability.md')


def check(case, work, time_limit):
    """Runs one case afresh and returns the list of its differences from docs/stability.md (empty: it agrees)."""
    name, description, _ = case
    recorded = recorded_row(description)
    row = run(work, [case], 1, time_limit)[0]
    u_z = float(row['last'].split('u_z')[1].split()[0]) if row['last'] != '-' else float('nan')
    print(f'{name}: {row["outcome"]}; P_max {row["P_max"]:.3f} nN (recorded {recorded["P_max"]}), last u_z '
          f'{u_z:.1f} nm (recorded {recorded["u_z"]:g}), worst balance {row["balance"]:.1e}')
    differences = []
    if row['outcome'].split(':')[0] != recorded['outcome'].split(':')[0]:
        differences.append(f'outcome "{row["outcome"]}", recorded "{recorded["outcome"]}"')
    for key, value in (('P_max', row['P_max']), ('u_z', u_z)):
        if not abs(value - recorded[key]) <= 0.01 * abs(recorded[key]):
            differences.append(f'{key} {value:.4g}, recorded {recorded[key]:g} (more than 1 % apart)')
    if not row['balance'] <= BALANCE_LIMIT:
        differences.append(f'energy balance error {row["balance"]:.1e} > {BALANCE_LIMIT:g}')
    return differences


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--jobs', type=int, default=2)
    parser.add_argument('--work', default=os.path.join(ROOT, 'stress-output'))
    parser.add_argument('--only', nargs='*', help='case names (default: all)')
    parser.add_argument('--time-limit', type=float, default=1200.0, help='seconds before a run counts as a hang')
    parser.add_argument('--again', action='store_true', help='run the selected cases even if they have an outcome')
    parser.add_argument('--docs', action='store_true', help='write docs/stability.md')
    parser.add_argument('--no-run', action='store_true', help='only tabulate the outcomes already stored')
    parser.add_argument('--check', metavar='NAME', help='run one case afresh and compare it with docs/stability.md')
    arguments = parser.parse_args()
    if not os.path.exists(APP):
        sys.exit(f'{APP} not found: build first (bash scripts/build.sh)')
    everything = cases()
    names = [c[0] for c in everything]
    for name in (arguments.only or []) + ([arguments.check] if arguments.check else []):
        if name not in names:
            sys.exit(f'unknown case "{name}"; cases: {", ".join(names)}')
    if arguments.check:
        differences = check(next(c for c in everything if c[0] == arguments.check), arguments.work, arguments.time_limit)
        for difference in differences:
            print('DIFFERS: ' + difference)
        return 1 if differences else 0
    selected = [c for c in everything if not arguments.only or c[0] in arguments.only]
    started = time.time()
    stored = os.path.join(arguments.work, 'outcomes.json')
    known = json.load(open(stored)) if os.path.exists(stored) else {}
    pending = [c for c in selected if arguments.again or c[0] not in known]

    def keep(row):
        known[row['case']] = row
        json.dump(known, open(stored, 'w'), indent=1)

    if not arguments.no_run:
        run(arguments.work, pending, arguments.jobs, arguments.time_limit, keep)
    rows = []
    for name, description, _ in selected:   # classified again from the logs, so a better classifier applies to old runs
        if name not in known:
            rows.append({'case': name, 'description': description, 'outcome': 'not run', 'acceptable': None,
                         'states': 0, 'jumps': 0, 'last': '-', 'P_max': float('nan'), 'balance': float('nan'),
                         'seconds': 0.0})
            continue
        row = known[name]
        status = row.get('status', 0 if row['outcome'].startswith(('detached', 'reached')) else
                         None if row['outcome'].startswith('HANG') else 1)
        text = open(os.path.join(arguments.work, name + '.log')).read()
        rows.append(dict(classify(arguments.work, name, status, text, row['seconds'], arguments.time_limit),
                         description=description))
    table = markdown(rows)
    print(table)
    print(f'{len(rows)} cases in {time.time() - started:.0f} s')
    if arguments.docs:
        template = open(os.path.join(ROOT, 'docs', 'stability-notes.md')).read()
        open(os.path.join(ROOT, 'docs', 'stability.md'), 'w').write(template.replace('{{TABLE}}', table))
        print('wrote docs/stability.md')
    return 0 if all(r['acceptable'] is not False for r in rows) else 1


if __name__ == '__main__':
    sys.exit(main())
