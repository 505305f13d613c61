#!/usr/bin/env python3
"""Plots one run's curve.csv into <output-dir>/curve.png: the load against the load parameter (M_y against theta_y
while rotating, P_z against u_z while lifting) and the energies / Pi_c0 with the balance error.

    scripts/plot_curve.py <output-dir>
"""
import csv
import os
import sys

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    path = os.path.join(directory, 'curve.csv')
    if not os.path.exists(path):
        sys.exit(f'{path}: not found (did the run finish? a failed run leaves {directory}.incomplete/)')
    rows = list(csv.DictReader(open(path)))
    if len(rows) < 2:
        sys.exit(f'{path}: fewer than two states, nothing to plot')
    value = {key: [float(r[key]) for r in rows] for key in rows[0] if key != 'stage'}
    stages = [r['stage'] for r in rows]
    lifting = stages[-1] == 'lift'
    figure, (load, energy) = plt.subplots(1, 2, figsize=(11, 4))
    if lifting:
        picked = [i for i, s in enumerate(stages) if s == 'lift']
        x, y = [value['u_z_nm'][i] for i in picked], [value['P_z_nN'][i] for i in picked]
        load.set_xlabel('u_z of the end face centre [nm]')
        load.set_ylabel('P_z [nN]')
        parameter = 'u_z_nm'
    else:
        picked = range(len(rows))
        x, y = value['theta_y_deg'], value['M_y_nNnm']
        load.set_xlabel('theta_y [deg]')
        load.set_ylabel('M_y [nN nm]')
        parameter = 'theta_y_deg'
    load.plot(x, y, '.-', markersize=3)
    jumps = [i for i in picked if value['after_jump'][i] == 1]
    if jumps:
        load.plot([value[parameter][i] for i in jumps], [value['P_z_nN' if lifting else 'M_y_nNnm'][i] for i in jumps],
                  'rv', label='state after a jump (instability)')
        load.legend()
    load.set_title('load (full spatula)')
    load.grid(alpha=0.3)
    for key, label in (('Pi_ext_per_Pi_c0', 'Pi_ext'), ('Pi_int_per_Pi_c0', 'Pi_int'), ('Pi_sa_per_Pi_c0', 'Pi_sa'),
                       ('dissipated_per_Pi_c0', 'dissipated by jumps')):
        energy.plot([value[parameter][i] for i in picked], [value[key][i] for i in picked], '.-', markersize=2,
                    label=label)
    worst = max(value['balance_error_per_Pi_c0'])
    energy.set_title(f'energies / Pi_c0 (largest balance error {worst:.1e})')
    energy.set_xlabel(load.get_xlabel())
    energy.legend()
    energy.grid(alpha=0.3)
    figure.tight_layout()
    picture = os.path.join(directory, 'curve.png')
    figure.savefig(picture, dpi=110)
    print('wrote', picture)


if __name__ == '__main__':
    main()
