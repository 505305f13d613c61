#!/usr/bin/env python3
"""Table 5 near the main snap (scripts/study/snap_split.py), on a manufactured lift whose energies are linear in u_z:
the paper's total work from its Pi_ext,0 and Delta Pi_ext, Pi_int a lift before the last state, the lift over which
Pi_int changes by 5 %, and the changes of Pi_sa and of the adhesion still held that balance it.

    snap_split.py"""
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from expectations import check, finish  # noqa: E402
from study import snap_split  # noqa: E402


def row(u_z):
    """A lift state at u_z [nm] (10 at the last state before the snap): Pi_int = 0.3 + 0.02 (10 - u_z),
    Pi_sa = 0.9 - 0.01 (10 - u_z), Pi_ext their sum."""
    pi_int, pi_sa = 0.3 + 0.02 * (10.0 - u_z), 0.9 - 0.01 * (10.0 - u_z)
    return {'u_z_nm': u_z, 'Pi_int_per_Pi_c0': pi_int, 'Pi_sa_per_Pi_c0': pi_sa, 'Pi_ext_per_Pi_c0': pi_int + pi_sa}


lift = [row(u) for u in (0.0, 4.0, 8.0, 9.5, 10.0)]
after = {'u_z_nm': 10.01, 'Pi_int_per_Pi_c0': 0.01, 'Pi_sa_per_Pi_c0': 0.99, 'Pi_ext_per_Pi_c0': 1.2}
summary = {'rows': lift + [after], 'before': lift[-1]}

# Pi_int changes by 5 % of 0.3 (0.015) over 0.015 / 0.02 = 0.75 nm of lift; read between the rows at 9.5 and 10.
check(abs(snap_split.lift_for_change(lift, 0.05) - 0.75) < 1e-12, 'the lift for a 5 % change is 0.75 nm')
check(snap_split.lift_for_change(lift, 10.0) is None, 'a change the lift never reaches gives None')

# Paper: Pi_ext,0 = 0.5, Delta Pi_ext = 300e-18 J with Pi_c0 = 750 E R0^3 = 1500e-18 J: Pi_ext = 0.7.
values = snap_split.split_row(summary, 0.5, 300.0, 1500.0)
check(abs(values['paper_Pi_ext'] - 0.7) < 1e-12, f'the paper\'s total work 0.7 (got {values["paper_Pi_ext"]})')
check(abs(values['Pi_ext'] - 1.2) < 1e-12 and abs(values['Pi_int'] - 0.3) < 1e-12,
      'our energies are those of the state before the snap, not after it')
check(all(abs(a - b) < 1e-12 for a, b in zip(values['Pi_int_before'], (0.32, 0.34))),
      f'Pi_int 1 and 2 nm before: 0.32 and 0.34 (got {values["Pi_int_before"]})')
check(abs(values['Pi_sa_change'] - 0.015 / 0.9) < 1e-12, '5 % of Pi_int is 0.015 / 0.9 of Pi_sa')
check(abs(values['adhering_change'] - 0.15) < 1e-12, '5 % of Pi_int is 0.015 / 0.1 of the adhesion still held')

lines = snap_split.snap_split_lines({'pull-off-60': summary}, [60], 'test', {60: 0.5}, {60: (6.0, 100.0, 300.0)}, 750.0)
check(any(line.startswith('| 60 | 1.200 / 0.700 (+71.4 %) | 0.300 | 0.900 | 0.320 (+6.7 %) | 0.340 (+13.3 %) | 0.75 '
                          '| 1.7 %, 15 % |') for line in lines), 'the Markdown row:\n' + '\n'.join(lines))
finish('Table 5 near the main snap: the paper\'s total work, the lift for a 5 % change and the balancing share')
