#!/usr/bin/env python3
"""The solver work's outcome, old against new in one run of this script: writes docs/speedup.csv
(case,before_s,after_s,ratio,max_result_change_pct, plus what each case counted) and prints the table for
docs/performance.md.

Cases (each 'before' is the code as it was at commit 0f7a416, reached through the parameters that keep its
behaviour: 'Linear Solver/refactor' = lag with 'lag' 4, full-rank MUMPS, 'Nonlinear Solver/non-contracting
iterations' = 0; 'after' is the current defaults):
  fine-newton-iteration   benchmarks' solid_benchmark on the fine mesh (318,087 unknowns), 2 ranks: seconds per
                          Newton iteration of a 2.5 deg rotation step of the spatula without adhesion; also the
                          factorization memory MUMPS reports (INFOG(22), all ranks). A third run with a fresh
                          factorization every iteration (lag 0, the solid benchmark's setting when docs/performance.md
                          recorded 39.3 s) is recorded as fine-newton-iteration-fresh-factors.
  medium-pull-off-45      the medium frictionless Q1C2 pull-off at 45 deg (rotation to 45 deg with zero net force,
                          then 600 nm of lift, to detachment): CPU seconds, tangents, and the change of P_max,
                          Delta u_z and Delta Pi_ext. Its after scene takes the studies' step settings (AFTER_SCENE
                          below: lift steps up to 10 nm, 16 iterations per attempt).
  peer-medium-iteration   per Newton iteration on the peer's comparison scene (medium, Q1C1, 20 nm lift from
                          theta_s): before = the FEniCSx peer of ../shared/peers (MUMPS Cholesky every iteration),
                          after = ours with the current defaults; also the whole scene's Newton time of each. Needs
                          python3-dolfinx; skipped with a note without it.

  medium-table6-study     Table 6 as scripts/run-study.py runs it on the medium mesh, both cores (two runs at once, one
                          rank each): the rotation to 90 deg with checkpoints at 45, 60, 75 and 90 deg, and the four
                          pull-offs from them, each started as soon as its checkpoint exists: wall seconds of the
                          whole study, tangents, and the largest change of P_max, Delta u_z and Delta Pi_ext over the
                          four pull-offs. before = the study's scenes as they were at 0f7a416 (lift steps up to 5 nm,
                          grown after 7 iterations, 12 iterations per attempt) with the old solver settings; after =
                          the study's scenes as they are. Each half goes on from its checkpoints when a call of the
                          case is stopped (its wall time is then summed over the calls, a stopped call counted to its
                          runs' last log write; work directories table6-<level>-<before|after>); the row is written once both halves are complete. --level coarse runs
                          it on the coarse mesh, a quick check of the script (no row is written then).
  fine-pull-off-60        the fine-mesh (the paper's) frictionless Q1C2 pull-off at 60 deg on 2 ranks with the
                          after scene's settings, jumps by Loading/Jump/method = shifted newton with refactor = cost
                          (a fine factorization is dear; the default, auto, takes the trust region on this mesh):
                          rotation to 60 deg with zero net force (checkpoints at 30, 45 and
                          60 deg for later pull-offs), then 600 nm of lift, to detachment. No before: the code before
                          the code before it never finished it. Hours long: it checkpoints every 5 minutes, and a later call of
                          the case goes on from the last checkpoint (--resume). Its wall time is the sum over the
                          segments (a segment a session killed counts to its last logged step); its row is written
                          once the run has finished, with P_max, Delta u_z and Delta Pi_ext.
  fine-pull-off-60-trust-region   the same run with Loading/Jump/method = trust region (the snaps' descents by
                          truncated conjugate gradients in a trust region, preconditioned by kept factors); work
                          directory fine-60-trust-region, resumed like fine-pull-off-60.

  accurate-table6-study   the same study on the medium mesh with the equal-area section (within 1 % of the fine
                          level), both cores: the study scenes with double-precision factors against the faster path
                          following of benchmarks/speedup_front.py (AFTER_LIFT on the pull-offs, single-precision
                          factors on all); about an hour; --level coarse checks the script.
  medium-pull-off-90, newton-per-state   the peel front's cases on the accurate medium mesh, the study scenes'
                          settings against the faster path following: benchmarks/speedup_front.py says what each runs
                          and which rows it writes (medium-pull-off-90 also writes medium-snap and two-ranks-90).

    benchmarks/speedup.py [--cases fine-newton-iteration medium-pull-off-45 peer-medium-iteration
                                   medium-table6-study fine-pull-off-60 fine-pull-off-60-trust-region
                                   medium-pull-off-90 newton-per-state]
                          [--work DIR] [--docs] [--level LEVEL]

Run it on a quiet machine (nothing else on the two cores): the default cases take about an hour, most of it the
medium pull-off before the change; medium-table6-study (about 2 hours) and fine-pull-off-60 are asked for by name. With --docs the rows of the cases run replace theirs in docs/speedup.csv (each row carries the
date it was measured); the before/after pair of each row always comes from one run.
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
sys.path.insert(0, os.path.join(ROOT, 'benchmarks'))
from curves import RECORDED_BENCHMARK_START, pull_off_summary  # noqa: E402
from scenes import benchmark_scene  # noqa: E402
import peer_iteration  # noqa: E402
from speedup_front import AFTER_LIFT, BEFORE, FRONT_CASES, FRONT_ROWS, SINGLE, front_case  # noqa: E402

APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
SOLID = os.path.join(ROOT, 'build', 'benchmarks', 'solid_benchmark')
ENVIRONMENT = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
MPI = ['mpiexec', '--allow-run-as-root', '-np', '2']
OLD_SOLID = ['refactor=lag', 'lag=4', 'low-rank=0', 'precision=double']
OLD_SCENE = {'Linear Solver': {'refactor': 'lag', 'lag': 4,
                               'MUMPS': {'low rank tolerance': 0.0, 'factor precision': 'double'}},
             'Nonlinear Solver': {'non-contracting iterations': 0, 'short steps': 0, 'absolute tolerance': 1e-9,
                                  'line search': 'backtrack'},
             'Steps': {'predictor': 'secant'}}
# The after scene's step settings (those of the pull-off studies since 2026-12-02, sixth session): lift steps up to
# 10 nm, grown after steps of at most 10 Newton iterations, 16 iterations per attempt. The energy line search and the
# looser tolerance are what make such steps pay (at the medium peel front 10 nm steps take 11 iterations).
AFTER_SCENE = {'Nonlinear Solver': {'maximum iterations': 16}, 'Steps': {'easy iterations': 10}, 'lift maximum': 10.0}
QUANTITIES = ('P_max_nN', 'delta_u_z_nm', 'delta_Pi_ext_1e-18J')


def solid(options):
    result = subprocess.run(MPI + [SOLID, 'fine', 'mumps', '1'] + options, env=ENVIRONMENT, capture_output=True,
                            text=True)
    if result.returncode != 0:
        sys.exit(f'solid_benchmark {options}: exit {result.returncode}\n{result.stderr[-2000:]}')
    header, values = result.stdout.strip().splitlines()[-2:]
    row = dict(zip(header.split(','), values.split(',')))
    print(f"solid_benchmark fine {' '.join(options) or 'defaults'}: {float(row['newton_s_per_iteration']):.2f} s per "
          f"iteration, {row['factorizations']} factorizations, {row['factorization_MB_all_ranks']} MB", flush=True)
    return row


def fine_newton_iteration():
    fresh = solid(['refactor=lag', 'lag=0', 'low-rank=0', 'precision=double'])
    before = solid(OLD_SOLID)
    after = solid([])
    def row(case, old):
        b, a = float(old['newton_s_per_iteration']), float(after['newton_s_per_iteration'])
        return dict(case=case, before_s=round(b, 3), after_s=round(a, 3), ratio=round(b / a, 2),
                    max_result_change_pct='', before_counts=f"{old['newton_iterations']} iterations, "
                    f"{old['factorizations']} factorizations, {old['factorization_MB_all_ranks']} MB",
                    after_counts=f"{after['newton_iterations']} iterations, {after['factorizations']} "
                    f"factorizations, {after['factorization_MB_all_ranks']} MB")
    return [row('fine-newton-iteration', before), row('fine-newton-iteration-fresh-factors', fresh)]


def pull_off(work, label, options):
    directory = f'medium-45-{label}'
    xml = os.path.join(work, directory + '.xml')
    options = {k: dict(v) if isinstance(v, dict) else v for k, v in options.items()}
    open(xml, 'w').write(benchmark_scene(directory, mesh='medium', theta_y=45.0,
                                         linear_solver=options.get('Linear Solver'),
                                         newton=options.get('Nonlinear Solver'), steps=options.get('Steps'),
                                         lift_maximum=options.get('lift maximum', 5.0)))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.time()
    with open(os.path.join(work, directory + '.log'), 'w') as log:
        status = subprocess.call([APP, xml], cwd=work, stdout=log, stderr=subprocess.STDOUT, env=ENVIRONMENT)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if status != 0:
        sys.exit(f'{directory}: exit {status} (see {directory}.log)')
    text = open(os.path.join(work, directory + '.log')).read()
    solver = re.search(r'^solver: (\d+) tangents', text, re.M)
    summary = pull_off_summary(work, directory, count_from=RECORDED_BENCHMARK_START)
    result = dict(cpu_s=after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime,
                  wall_s=time.time() - started, tangents=int(solver.group(1)),
                  failed=len(re.findall(r'failed \(|converged on another branch', text)),
                  jumps=len(re.findall(r'^  jumped in', text, re.M)), **{q: summary[q] for q in QUANTITIES})
    print(f"medium pull-off 45 deg, {label}: {result['cpu_s']:.0f} CPU s, {result['tangents']} tangents, "
          f"P_max {result['P_max_nN']:.4f} nN", flush=True)
    return result


def medium_pull_off_45(work):
    before = pull_off(work, 'before', OLD_SCENE)
    after = pull_off(work, 'after', AFTER_SCENE)
    change = max(abs(after[q] / before[q] - 1) * 100 for q in QUANTITIES)
    counts = '{tangents} tangents, {failed} failed attempts, {jumps} jumps, P_max {P_max_nN:.4f} nN, Delta u_z ' \
             '{delta_u_z_nm:.2f} nm, wall {wall_s:.0f} s'
    return [dict(case='medium-pull-off-45', before_s=round(before['cpu_s'], 1), after_s=round(after['cpu_s'], 1),
                 ratio=round(before['cpu_s'] / after['cpu_s'], 2), max_result_change_pct=round(change, 4),
                 before_counts=counts.format(**before), after_counts=counts.format(**after))]


def flattened(options, prefix=''):
    """A scene's option dict as run-study.py --set entries ('List/Sublist/name=value')."""
    out = []
    for key, value in options.items():
        if isinstance(value, dict):
            out += flattened(value, prefix + key + '/')
        else:
            out.append(prefix + key + '=' + (f'{value!r}' if isinstance(value, float) else str(value)))
    return out


TABLE6_ANGLES = (45, 60, 75, 90)
# The rotation stops at the last pre-rotated state Table 6 needs (the study's own goes on to detachment for Table 4).
TABLE6_ROTATION = ['peel-rotation:Loading/theta_y=90.0', 'peel-rotation:Loading/checkpoints at theta_y=45,60,75,90']
# The study's pull-off scenes at 0f7a416: lift steps up to 5 nm, grown after at most 7 iterations, 12 per attempt.
OLD_TABLE6_LIFT = ['Loading/Lift Steps/maximum=5.0', 'Loading/Lift Steps/easy iterations=7',
                   'Nonlinear Solver/maximum iterations=12']


def table6_half(work, label, settings, level):
    """One half of medium-table6-study: run-study.py table6 with `settings` (--set entries) in <work>/table6-<label>,
    resumed from its checkpoints if an earlier call was stopped; returns its totals and the pull-offs' results."""
    directory = os.path.join(work, f'table6-{level}-{label}')
    segments = directory + '.segments'
    runs = os.path.join(directory, level)
    scenes = ['peel-rotation'] + [f'pull-off-{angle}' for angle in TABLE6_ANGLES]
    def run_logs():
        return [os.path.join(runs, name) for name in os.listdir(runs) if name.endswith('.log')]
    lines = [line.split() for line in open(segments)] if os.path.exists(segments) else []
    if lines and lines[-1][0] == 'start':   # the last call was stopped: it ends at its runs' last log write
        stopped = float(lines[-1][1])
        with open(segments, 'a') as out:
            out.write(f'end {max([os.path.getmtime(l) for l in run_logs()] + [stopped]):.1f}\n')
    if not all(os.path.exists(os.path.join(runs, scene, 'curve.csv')) for scene in scenes):
        command = [sys.executable, os.path.join(ROOT, 'scripts', 'run-study.py'), 'table6', '--mesh', level,
                   '--work', directory, '--jobs', '2'] + [f'--set={entry}' for entry in settings]
        with open(segments, 'a') as out:
            out.write(f'start {time.time():.1f}\n')
        with open(directory + '.log', 'a') as log:
            status = subprocess.call(command, stdout=log, stderr=subprocess.STDOUT,
                                     env=dict(ENVIRONMENT, SPATULA_APP=APP))
        with open(segments, 'a') as out:
            out.write(f'end {time.time():.1f}\n')
        if status != 0:
            sys.exit(f'medium-table6-study, {label}: run-study.py exit {status} (see {directory}.log)')
    logs = run_logs()
    wall, start = 0.0, None
    for kind, stamp in (line.split() for line in open(segments)):
        if kind == 'start':
            start = float(stamp)
        else:
            wall, start = wall + float(stamp) - start, None
    tangents = {os.path.basename(l)[:-4]: sum(int(t) for t in re.findall(r'^solver: (\d+) tangents', open(l).read(),
                                                                         re.M)) for l in logs}
    results = {angle: pull_off_summary(runs, f'pull-off-{angle}', count_from=RECORDED_BENCHMARK_START)
               for angle in TABLE6_ANGLES}
    print(f"table6 study on the {level} mesh, {label}: {wall:.0f} s wall, {sum(tangents.values())} tangents, P_max "
          + ' / '.join(f"{results[a]['P_max_nN']:.3f}" for a in TABLE6_ANGLES) + ' nN', flush=True)
    return dict(wall_s=wall, tangents=sum(tangents.values()), rotation_tangents=tangents['peel-rotation'],
                results=results)


def medium_table6_study(work, level, accurate=False):
    """The Table 6 study before and after: the code of 0f7a416 against the study scenes as they are or, `accurate`,
    on the medium mesh with the equal-area section the study scenes with double-precision factors against the
    faster path following (speedup_front.AFTER on the pull-offs, single-precision factors on all)."""
    if accurate:
        section = ['Mesh/section=equal area']
        after_settings = section + TABLE6_ROTATION + SINGLE + [f'pull-off-{a}:{e}' for a in TABLE6_ANGLES
                                                                 for e in AFTER_LIFT]
        before_settings = section + TABLE6_ROTATION + BEFORE
        labels = ('accurate-after', 'accurate-before')
    else:
        solvers = {k: v for k, v in OLD_SCENE.items() if k != 'Steps'}   # 'Steps' holds entries of both step lists
        old_steps = flattened(OLD_SCENE['Steps'])
        steps = [f'peel-rotation:Loading/Rotation Steps/{entry}' for entry in old_steps]
        steps += [f'pull-off-{a}:{entry}' for a in TABLE6_ANGLES for entry in
                  OLD_TABLE6_LIFT + [f'Loading/Lift Steps/{e}' for e in old_steps]]
        after_settings, before_settings = TABLE6_ROTATION, flattened(solvers) + TABLE6_ROTATION + steps
        labels = ('after', 'before')
    # The after half first: it answers the 600 s target by itself, and the before half (the longer) can be stopped and
    # resumed in a later session.
    after = table6_half(work, labels[0], after_settings, level)
    before = table6_half(work, labels[1], before_settings, level)
    change = max(abs(after['results'][a][q] / before['results'][a][q] - 1) * 100
                 for a in TABLE6_ANGLES for q in QUANTITIES)
    def counts(half):
        return (f"wall {half['wall_s']:.0f} s, {half['tangents']} tangents (rotation to 90 deg {half['rotation_tangents']}), "
                'P_max ' + ' / '.join(f"{half['results'][a]['P_max_nN']:.3f}" for a in TABLE6_ANGLES) +
                ' nN at ' + '/'.join(str(a) for a in TABLE6_ANGLES) + ' deg')
    case = 'accurate-table6-study' if accurate else 'medium-table6-study'
    return [dict(case=case + ('' if level == 'medium' else f'-{level}'),
                 before_s=round(before['wall_s'], 1), after_s=round(after['wall_s'], 1),
                 ratio=round(before['wall_s'] / after['wall_s'], 2), max_result_change_pct=round(change, 4),
                 before_counts=counts(before), after_counts=counts(after))]


# The fine pull-off's variants: case -> (work name, Loading/Jump entries). Shifted Newton's descents refactor by
# cost (a fine factorization is dear); the trust region keeps its factors as a preconditioner instead.
FINE_60 = {'fine-pull-off-60': ('fine-60', {'method': 'shifted newton', 'refactor': 'cost'}),
           'fine-pull-off-60-trust-region': ('fine-60-trust-region', {'method': 'trust region'})}


def segment_seconds(log_path):
    """Wall seconds of one segment of a resumed run: its 'wall' line when it ended by itself, else (a segment a
    session killed) the elapsed time of its last logged step."""
    text = open(log_path).read()
    ended = re.search(r'^segment wall: ([0-9.]+) s', text, re.M)
    if ended:
        return float(ended.group(1))
    steps = re.findall(r'^step .* ([0-9.]+) s$', text, re.M)
    return float(steps[-1]) if steps else 0.0


def fine_pull_off_60(work, case='fine-pull-off-60'):
    name, jump = FINE_60[case]
    xml = os.path.join(work, name + '.xml')
    if not os.path.exists(xml):
        open(xml, 'w').write(benchmark_scene(name, mesh='fine', theta_y=60.0, land_at=(30.0, 45.0, 60.0),
                                             newton=AFTER_SCENE['Nonlinear Solver'], steps=AFTER_SCENE['Steps'],
                                             lift_maximum=AFTER_SCENE['lift maximum'], fields=0,
                                             jump=jump, checkpoint_minutes=5))
    done = os.path.isdir(os.path.join(work, name))
    logs = sorted((f for f in os.listdir(work) if re.fullmatch(re.escape(name) + r'\.segment-\d+\.log', f)),
                  key=lambda f: int(re.search(r'(\d+)\.log$', f).group(1)))
    interrupted = bool(logs) and 'interrupted by SIG' in open(os.path.join(work, logs[-1])).read()
    if os.path.isdir(os.path.join(work, name + '.incomplete')) and not interrupted:   # (a signal's stop resumes)
        sys.exit(f'{name}: the run failed (see {work}/{name}.incomplete/FAILURE.txt)')
    if not done:
        resume = any(os.path.isdir(os.path.join(work, name + suffix)) for suffix in ('.partial', '.incomplete'))
        log_path = os.path.join(work, f'{name}.segment-{len(logs) + 1}.log')
        print(f'{name}: segment {len(logs) + 1} ({"resumed" if resume else "from the start"}), log {log_path}',
              flush=True)
        started = time.time()
        with open(log_path, 'w') as log:
            status = subprocess.call(MPI + [APP, xml] + (['--resume'] if resume else []), cwd=work, env=ENVIRONMENT,
                                     stdout=log, stderr=subprocess.STDOUT)
        with open(log_path, 'a') as log:
            log.write(f'segment wall: {time.time() - started:.1f} s\n')
        if status != 0:
            sys.exit(f'{name}: exit {status} (see {log_path})')
        logs.append(os.path.basename(log_path))
    seconds = [segment_seconds(os.path.join(work, f)) for f in logs]
    summary = pull_off_summary(work, name, count_from=RECORDED_BENCHMARK_START)
    solver = re.search(r'^solver: (\d+) tangents', open(os.path.join(work, logs[-1])).read(), re.M)
    print(f'{name}: {sum(seconds):.0f} s in {len(seconds)} segment(s), P_max {summary["P_max_nN"]:.4f} nN',
          flush=True)
    return [dict(case=case, before_s='', after_s=round(sum(seconds), 1), ratio='',
                 max_result_change_pct='',
                 before_counts='never finished before the solver work' if case == 'fine-pull-off-60' else
                 'shifted Newton descents: the fine-pull-off-60 row',
                 after_counts=f'2 ranks, Jump {jump}, wall in {len(seconds)} segment(s) '
                              f'({" + ".join(f"{s:.0f}" for s in seconds)} s), last segment '
                              f'{solver.group(1) if solver else "?"} tangents, P_max {summary["P_max_nN"]:.4f} nN, '
                              f'Delta u_z {summary["delta_u_z_nm"]:.2f} nm, '
                              f'Delta Pi_ext {summary["delta_Pi_ext_1e-18J"]:.2f} 1e-18 J')]


def peer_medium_iteration(work):
    if subprocess.run(['/usr/bin/python3', '-c', 'import dolfinx'], capture_output=True).returncode != 0:
        print('python3-dolfinx is not installed: peer-medium-iteration skipped (apt-get install python3-dolfinx)')
        return []
    peer_iteration.VARIANTS['ours-default'] = None   # the current defaults (no Linear Solver entries)
    ours = peer_iteration.run_ours(work, 'ours-default', 0)
    peer = peer_iteration.run_peer(work, ours, 0)
    change = abs(ours['P_z_final'] / peer['P_z_final'] - 1) * 100
    return [dict(case='peer-medium-iteration', before_s=round(peer['per_iteration_s'], 3),
                 after_s=round(ours['per_iteration_s'], 3),
                 ratio=round(peer['per_iteration_s'] / ours['per_iteration_s'], 2),
                 max_result_change_pct=round(change, 6),
                 before_counts=f"peer: {peer['iterations']} iterations, "
                               f"{peer['per_iteration_s'] * peer['iterations']:.1f} s in all",
                 after_counts=f"ours: {ours['iterations']} iterations, "
                              f"{ours['per_iteration_s'] * ours['iterations']:.1f} s in all")]


CASE_ROWS = ['medium-pull-off-45', 'fine-newton-iteration', 'fine-newton-iteration-fresh-factors',
             'peer-medium-iteration', 'medium-table6-study', 'fine-pull-off-60', 'fine-pull-off-60-trust-region', *FRONT_ROWS, 'accurate-table6-study']


def main():
    cases = ['fine-newton-iteration', 'medium-pull-off-45', 'peer-medium-iteration']   # the hour-long default
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--cases', nargs='*', default=cases, choices=cases + ['medium-table6-study', *FINE_60, *FRONT_CASES,
                                                            'accurate-table6-study'])
    parser.add_argument('--work', default='speedup')
    parser.add_argument('--docs', action='store_true')
    parser.add_argument('--level', default='medium', choices=['coarse', 'medium'],
                        help='the mesh of medium-table6-study (coarse: a quick check of the script, no docs row)')
    arguments = parser.parse_args()
    if arguments.docs and arguments.level != 'medium':
        parser.error('--docs takes the medium mesh only')
    work = os.path.abspath(arguments.work)
    os.makedirs(work, exist_ok=True)
    rows = []
    for case in arguments.cases:
        if case == 'fine-newton-iteration':
            rows += fine_newton_iteration()
        elif case == 'medium-pull-off-45':
            rows += medium_pull_off_45(work)
        elif case in FINE_60:
            rows += fine_pull_off_60(work, case)
        elif case in FRONT_CASES:
            rows += front_case(case, work)
        elif case in ('medium-table6-study', 'accurate-table6-study'):
            rows += medium_table6_study(work, arguments.level, accurate=case == 'accurate-table6-study')
        else:
            rows += peer_medium_iteration(work)
    print('\n| case | before [s] | after [s] | ratio | largest result change [%] | before | after |')
    print('|---|---|---|---|---|---|---|')
    for r in rows:
        print(f"| {r['case']} | {r['before_s']} | {r['after_s']} | {r['ratio']} | {r['max_result_change_pct']} | "
              f"{r['before_counts']} | {r['after_counts']} |")
    if arguments.docs:   # the cases run replace their rows; rows of cases not run this time are kept
        path = os.path.join(ROOT, 'docs', 'speedup.csv')
        today = time.strftime('%Y-%m-%d')
        for r in rows:
            r['measured'] = today
        kept = [r for r in (csv.DictReader(open(path)) if os.path.exists(path) else [])
                if r['case'] not in {n['case'] for n in rows}]
        order = {case: k for k, case in enumerate(CASE_ROWS)}
        merged = sorted(kept + rows, key=lambda r: order.get(r['case'], len(order)))
        with open(path, 'w', newline='') as out:
            writer = csv.DictWriter(out, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(merged)


if __name__ == '__main__':
    main()
