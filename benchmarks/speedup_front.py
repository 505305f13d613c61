"""The peel front's cases of benchmarks/speedup.py: the medium pull-offs of the Table 6 study on the accurate medium
mesh (`Mesh/section` = equal area), each from the study rotation's checkpoint kept in results/medium-equal-area, with
the study scenes' settings and double-precision factors (before) against the faster path following (after, AFTER
below), one run each in one sitting, one rank unless named.

  medium-pull-off-90   pull-off at 90 deg, before and after on 1 rank, after on 2 ranks, and before with
                       single-precision factors alone; writes four rows: medium-pull-off-90 (wall seconds, tangents,
                       states, the largest change of P_max, Delta u_z and Delta Pi_ext), single-precision-90 (before
                       against before with single-precision factors), medium-snap (the main snap's energy descent:
                       iterations, and seconds from the run's own timer) and two-ranks-90 (the after scene on 1 rank
                       against 2).
  newton-per-state     pull-off at 60 deg, before and after on 1 rank: tangents per converged state and in all.
"""
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from curves import pull_off_summary, read_curve  # noqa: E402
from study.scenes import apply_overrides, parse_override  # noqa: E402

APP = os.environ.get('SPATULA_APP', os.path.join(ROOT, 'build', 'apps', 'spatula', 'spatula'))
ENVIRONMENT = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
ROTATION = os.path.join(ROOT, 'results', 'medium-equal-area', 'peel-rotation', 'checkpoints.h5')
MESH = ['Mesh/level=medium', 'Mesh/section=equal area', 'Output/field interval=0']
# The faster path following: lift steps up to 40 nm, held to the reaction curve's resolution (docs/performance.md,
# "Longer lift steps where the path is smooth"), and single-precision factors (docs/solvers.md).
SINGLE = ['Linear Solver/MUMPS/factor precision=single']
AFTER_LIFT = ['Loading/Lift Steps/maximum=40', 'Loading/Lift Steps/curve tolerance=1e-3']
AFTER = AFTER_LIFT + SINGLE
# The study scenes' settings before: double-precision factors (the default before single precision was measured).
BEFORE = ['Linear Solver/MUMPS/factor precision=double']
QUANTITIES = ('P_max_nN', 'delta_u_z_nm', 'delta_Pi_ext_1e-18J')
FRONT_CASES = ('medium-pull-off-90', 'newton-per-state')
FRONT_ROWS = ('medium-pull-off-90', 'single-precision-90', 'medium-snap', 'two-ranks-90', 'newton-per-state')


def run(work, angle, label, settings, ranks=1):
    """One pull-off from the study rotation's checkpoint: its wall seconds, counts and Table 6 quantities."""
    name = f'front-{angle}-{label}'
    if not os.path.exists(ROTATION):
        sys.exit(f'{ROTATION} is missing: the kept equal-area medium rotation (results/medium-equal-area/README.md)')
    scene = f'pull-off-{angle}'
    entries = MESH + settings + [f'Output/directory={name}', f'Loading/restart file={name}.restart.h5']
    text = apply_overrides(open(os.path.join(ROOT, 'xml', 'studies', scene + '.xml')).read(), None,
                           [parse_override(entry) for entry in entries])
    open(os.path.join(work, name + '.xml'), 'w').write(text)
    shutil.copyfile(ROTATION, os.path.join(work, name + '.restart.h5'))
    shutil.rmtree(os.path.join(work, name), ignore_errors=True)
    launcher = ['mpiexec', '--allow-run-as-root', '-np', str(ranks)] if ranks > 1 else []
    started = time.time()
    with open(os.path.join(work, name + '.log'), 'w') as log:
        status = subprocess.call(launcher + [APP, name + '.xml'], cwd=work, stdout=log, stderr=subprocess.STDOUT,
                                 env=ENVIRONMENT)
    wall = time.time() - started
    if status != 0:
        sys.exit(f'{name}: exit {status} (see {work}/{name}.log)')
    text = open(os.path.join(work, name + '.log')).read()
    jumps = [int(n) for n in re.findall(r'^  jumped in (\d+) iterations', text, re.M)]
    jump_seconds = re.search(r'^spatula: jump past instability\s+([0-9.]+)', text, re.M)
    states = sum(1 for row in read_curve(work, name) if row['stage'] == 'lift')
    summary = pull_off_summary(work, name)
    result = dict(wall_s=wall, tangents=int(re.search(r'^solver: (\d+) tangents', text, re.M).group(1)),
                  states=states, snap_iterations=max(jumps, default=0),
                  snap_s=float(jump_seconds.group(1)) if jump_seconds and ranks == 1 else None,
                  **{q: summary[q] for q in QUANTITIES})
    print(f"{name}: {wall:.0f} s, {result['tangents']} tangents, {states} states, snap {result['snap_iterations']} "
          f"iterations, P_max {result['P_max_nN']:.4f} nN", flush=True)
    return result


def change_pct(before, after):
    return round(max(abs(after[q] / before[q] - 1) * 100 for q in QUANTITIES), 4)


def counts(r):
    return (f"{r['tangents']} tangents, {r['states']} states ({r['tangents'] / r['states']:.2f} per state), "
            f"P_max {r['P_max_nN']:.4f} nN, Delta u_z {r['delta_u_z_nm']:.2f} nm, "
            f"Delta Pi_ext {r['delta_Pi_ext_1e-18J']:.2f} 1e-18 J")


def comparison(case, before, after, labels=('', '')):
    """A row of docs/speedup.csv: the two runs' wall seconds, their ratio, the largest result change and counts."""
    return dict(case=case, before_s=round(before['wall_s'], 1), after_s=round(after['wall_s'], 1),
                ratio=round(before['wall_s'] / after['wall_s'], 2), max_result_change_pct=change_pct(before, after),
                before_counts=labels[0] + counts(before), after_counts=labels[1] + counts(after))


def pull_off_90(work):
    before = run(work, 90, 'before', BEFORE)
    single = run(work, 90, 'single-precision', SINGLE)
    after = run(work, 90, 'after', AFTER)
    two = run(work, 90, 'after-2-ranks', AFTER, ranks=2)
    snap = dict(case='medium-snap', before_s=round(before['snap_s'], 1), after_s=round(after['snap_s'], 1),
                ratio=round(before['snap_s'] / after['snap_s'], 2), max_result_change_pct='',
                before_counts=f"{before['snap_iterations']} iterations",
                after_counts=f"{after['snap_iterations']} iterations")
    return [comparison('medium-pull-off-90', before, after), comparison('single-precision-90', before, single), snap,
            comparison('two-ranks-90', after, two, ('1 rank: ', '2 ranks: '))]


def newton_per_state(work):
    return [comparison('newton-per-state', run(work, 60, 'before', BEFORE), run(work, 60, 'after', AFTER))]


def front_case(case, work):
    return pull_off_90(work) if case == 'medium-pull-off-90' else newton_per_state(work)
