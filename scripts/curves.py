"""Reading the app's curve.csv files: used by the study runner and the benchmarks."""
import csv
import os


def read_curve(work, scene):
    """The rows of <work>/<scene>/curve.csv (or of the .incomplete directory a failed run left), numbers as floats."""
    path = os.path.join(work, scene, 'curve.csv')
    if not os.path.exists(path):
        path = os.path.join(work, scene + '.incomplete', 'curve.csv')
    return [{k: (v if k == 'stage' else float(v)) for k, v in row.items()} for row in csv.DictReader(open(path))]


def interpolate(rows, key, at, columns):
    for a, b in zip(rows, rows[1:]):
        if a[key] <= at <= b[key] and b[key] > a[key]:
            t = (at - a[key]) / (b[key] - a[key])
            return {c: a[c] + t * (b[c] - a[c]) for c in columns}
    return None


def pull_off_summary(work, scene):
    """Table 6's quantities of a pull-off: the peak pull, the lift and the work from its start to detachment, and
    the energies of the last state before detachment (Table 5)."""
    rows = read_curve(work, scene)
    lift = [r for r in rows if r['stage'] == 'lift']
    if not lift:   # the run stopped before its lift began
        return {'rows': [], 'worst_balance_error': max(r['balance_error_per_Pi_c0'] for r in rows)}
    start = lift[0] if lift else rows[-1]
    peak = max(lift, key=lambda r: r['P_z_nN']) if lift else start
    detach = next((r for r in lift if r['u_z_nm'] > peak['u_z_nm'] and r['P_z_nN'] < 0.01 * peak['P_z_nN']), lift[-1])
    before = lift[lift.index(detach) - 1] if detach in lift and lift.index(detach) > 0 else detach
    return {
        'P_max_nN': peak['P_z_nN'], 'u_z_at_P_max': peak['u_z_nm'],
        'delta_u_z_nm': detach['u_z_nm'] - start['u_z_nm'],
        'delta_Pi_ext_1e-18J': detach['Pi_ext_1e-18J'] - start['Pi_ext_1e-18J'],
        'Pi_ext0_per_Pi_c0': start['Pi_ext_per_Pi_c0'],
        'delta_Pi_ext_per_Pi_c0': detach['Pi_ext_per_Pi_c0'] - start['Pi_ext_per_Pi_c0'],
        'Pi_ext_per_Pi_c0': before['Pi_ext_per_Pi_c0'], 'Pi_int_per_Pi_c0': before['Pi_int_per_Pi_c0'],
        'Pi_sa_per_Pi_c0': before['Pi_sa_per_Pi_c0'],
        'worst_balance_error': max(r['balance_error_per_Pi_c0'] for r in rows),
        'detached': detach['P_z_nN'] < 0.01 * peak['P_z_nN'], 'rows': lift,
    }
