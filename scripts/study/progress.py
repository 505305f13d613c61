"""A run's progress as a study's job shows it: one line per converged step of the app's log (stage, theta_y or u_z,
elapsed, and what remains at the pace so far)."""
import os
import re

from convergence import LEVELS
from curves import read_curve
from study.runs import complete
from study.scenes import scene_parameter


def target(scene):
    """(stage, final value) the scene's loading ends at: the rotation's theta_y, or the lift's final u_z (relative);
    (None, None) for a path of stages or a pull at an angle (no estimate of what remains)."""
    kind = scene_parameter(scene, 'type')
    if kind == 'rotation':
        return 'rotation', float(scene_parameter(scene, 'theta_y'))
    if kind == 'lift' and float(scene_parameter(scene, 'pull angle') or 90) == 90:
        return 'lift', float(scene_parameter(scene, 'final lift'))
    return None, None   # (a pull at an angle: its final travel is along the pull, the log shows u_z)


def progress(work, run, line, elapsed, origin):
    """The run's progress line: stage, theta_y or u_z, elapsed, and what remains at the pace so far (to the scene's
    final load; a pull-off ends earlier, at detachment: its estimate uses the coarser level's detachment when
    there is one)."""
    level, scene = run
    match = re.search(r'step\s+(\d+)\s+(\w+)\s+theta_y\s+([-\d.]+)\s+deg\s+u_z\s+([-\d.]+)\s+nm', line)
    if not match:
        return f'[{level} {scene}] {" ".join(line.split())[:170]}'
    step, stage, theta, lift = match.group(1), match.group(2), float(match.group(3)), float(match.group(4))
    value = theta if stage == 'rotation' else lift
    kind, end = target(scene)
    if stage == 'lift' and kind == 'lift':
        for coarser in LEVELS[:LEVELS.index(level)][::-1]:
            rows = read_curve(os.path.join(work, coarser), scene) if complete(os.path.join(work, coarser), scene) else None
            if rows:
                start = next(float(r['u_z_nm']) for r in rows if r['stage'] == 'lift')
                end = float(rows[-1]['u_z_nm']) - start
                break
    origin.setdefault((run, stage), (value, elapsed))   # where this stage's pace is measured from
    first_value, first_time = origin[(run, stage)]
    done = value - first_value
    remaining = ''
    if stage == kind and done > 0 and elapsed > first_time:
        goal = end if kind == 'rotation' else first_value + end
        minutes = max(0.0, goal - value) * (elapsed - first_time) / done / 60
        remaining = f', about {minutes:.{1 if minutes < 10 else 0}f} min left at this pace'
    unit = 'deg' if stage == 'rotation' else 'nm'
    name = 'theta_y' if stage == 'rotation' else 'u_z'
    return f'[{level} {scene}] step {step} {stage} {name} = {value:.3f} {unit}, {elapsed / 60:.1f} min{remaining}'


def step_lines(log):
    """The lines of the app's log that progress shows: converged steps, jumps, detachment."""
    lines = open(log).read().splitlines() if os.path.exists(log) else []
    return [l for l in lines if l.startswith('step ') or 'jump' in l or 'detachment' in l]
