"""Scene files for the benchmarks: one builder for the pull-off and rotation scenes that benchmarks/error_vs_time.py
and benchmarks/stress_tests.py run, and one reader of the app's diagnosis line."""


def parameter_list(name, entries, indent=0):
    """A Teuchos XML parameter list from a dict: str -> string, bool -> bool, int -> int, float -> double, a dict ->
    a sublist. Doubles must be given as floats (60.0, not 60): the app's validator rejects an int for a double."""
    pad = '  ' * indent
    lines = [f'{pad}<ParameterList name="{name}">']
    for key, value in entries.items():
        if isinstance(value, dict):
            lines.append(parameter_list(key, value, indent + 1))
            continue
        kind = {bool: 'bool', int: 'int', float: 'double', str: 'string'}[type(value)]
        text = str(value).lower() if kind == 'bool' else f'{value:.10g}' if kind == 'double' else str(value)
        lines.append(f'{pad}  <Parameter name="{key}" type="{kind}" value="{text}"/>')
    lines.append(f'{pad}</ParameterList>')
    return '\n'.join(lines)


def benchmark_scene(name, *, mesh='coarse', refinement=1, layers=0, section='inscribed', adhesion=None, loading='lift', theta_y=60.0,
                    final_lift=600.0, rotation_maximum=2.0, lift_maximum=5.0, linear_solver=None, newton=None,
                    steps=None, jump=None, fields=-1, land_at=(), checkpoint_minutes=None):
    """A frictionless scene on a flat substrate unless `adhesion` (the Adhesion list's entries) says otherwise:
    rotation to theta_y with zero net force, then (loading 'lift') a lift of final_lift nm beyond the rotated state.
    Step maxima in deg and nm, minima 0.01; `steps`: further entries of both step lists. fields: -1 writes no
    fields, 0 the first and last states only, n every n-th state. `land_at`: rotation angles [deg] a step ends at
    exactly (written as checkpoints), so that values there are not interpolated. layers: element layers through the
    pad (0: the level's). section: Mesh/section (the shaft's section polygon; always written, so that a recorded
    benchmark keeps its meaning whatever the program's default). jump: entries of Loading/Jump. checkpoint_minutes: minutes between the `last state` checkpoints of a long run (the app's
    default when None). The output directory is `name`."""
    step_lists = {'Rotation Steps': {'maximum': float(rotation_maximum), 'minimum': 0.01, **(steps or {})}}
    load = {'type': loading, 'theta_y': float(theta_y)}
    if land_at:
        load['checkpoints at theta_y'] = ','.join(f'{a:g}' for a in land_at)
    if loading == 'lift':
        load.update({'final lift': float(final_lift), 'final lift relative': True})
        step_lists['Lift Steps'] = {'maximum': float(lift_maximum), 'minimum': 0.01, **(steps or {})}
    entries = {
        'Mesh': {'level': mesh, **({'refinement factor': refinement} if refinement != 1 else {}),
                 **({'layers': layers} if layers else {}), 'section': section},
        'Adhesion': {'law': 'frictionless', **(adhesion or {})},
        'Loading': {**load, **step_lists, **({'Jump': jump} if jump else {})},
        **({'Linear Solver': linear_solver} if linear_solver else {}),
        **({'Nonlinear Solver': newton} if newton else {}),
        'Output': {'directory': name, 'write mesh': fields >= 0, 'field interval': max(fields, 0),
                   **({'checkpoint interval': float(checkpoint_minutes)} if checkpoint_minutes else {})},
    }
    return parameter_list(name, entries) + '\n'


# The lines apps/spatula/main.cpp writes when a run fails (a solver failure, a bad input, any other error).
DIAGNOSIS_PREFIXES = ('spatula: solver failure', 'spatula: input error', 'spatula: error')


def app_diagnosis(log_text):
    """The app's last failure line (which step, which load, why) without the 'spatula:' prefix; None if there is none."""
    lines = [l for l in log_text.splitlines() if l.startswith(DIAGNOSIS_PREFIXES)]
    return lines[-1].split(':', 1)[1].strip() if lines else None
