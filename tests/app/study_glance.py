#!/usr/bin/env python3
"""The results page's "At a glance" tables (scripts/study/glance.py) on manufactured pull-off summaries: the value is
the finest level's, the error bar Richardson's over the levels, the flag is up exactly where ours and the paper's
differ by more than the bar (with the reason from glance-reasons.csv), a scene run on one level has no bar, the
sweeps' paper values are held out, and the equal-area medium mesh's value stands beside each cell where it ran, with
Richardson's bar over the equal-area sequence (coarse x 2, x 3, medium) where more than the medium mesh ran it.

    study_glance.py"""
import os
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from convergence import EQUAL_AREA_SIZE, richardson  # noqa: E402
from expectations import check, finish  # noqa: E402
from study import glance as study  # noqa: E402
from study.tables import PAPER_TABLE6  # noqa: E402


def summary(p_max, delta_u_z, delta_pi_ext, pi_ext0=0.5):
    return {'P_max_nN': p_max, 'delta_u_z_nm': delta_u_z, 'delta_Pi_ext_1e-18J': delta_pi_ext,
            'Pi_ext0_per_Pi_c0': pi_ext0}


def row(text, case, quantity):
    """The cells of the glance row of `case` and `quantity` (under the heading `table`)."""
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip('|').split('|')]
        if len(cells) == 9 and cells[0] == case and cells[1] == quantity:
            return cells
    return None


paper_p, paper_u, paper_pi = PAPER_TABLE6[45]
with tempfile.TemporaryDirectory() as work:   # no rotation runs: no Table 4
    levels = {'coarse': summary(paper_p * 1.20, paper_u * 0.80, paper_pi),
              'medium': summary(paper_p * 1.03, paper_u * 0.99, paper_pi),
              'fine': summary(paper_p * 1.02, paper_u * 1.001, paper_pi)}
    results = {level: (os.path.join(work, level), {'pull-off-45': s, 'gamma-W-1.5': s} if level == 'medium'
                                                  else {'pull-off-45': s})
               for level, s in levels.items()}
    sequence = {'coarse-x2-equal-area': 1.08, 'coarse-x3-equal-area': 1.035, 'medium-equal-area': 1.01}
    accurate = {level: (os.path.join(work, level), {'pull-off-45': summary(paper_p * factor, paper_u, paper_pi)})
                for level, factor in sequence.items()}
    accurate['medium-equal-area'][1]['gamma-W-1.5'] = summary(paper_p, paper_u, paper_pi)   # the medium mesh alone
    text = study.glance(results, accurate)
    check('Table 4' not in text, 'a Table 4 without rotation runs')
    p = row(text, '45°', 'P_max [nN]')
    finest, estimate, _, _ = richardson({level: s['P_max_nN'] for level, s in levels.items()})
    check(p is not None and p[2].startswith(f'{finest:.3g} ± {estimate:.2g}') and p[3] == 'fine', f'P_max cells {p}')
    _, bar, _, _ = richardson({level: paper_p * factor for level, factor in sequence.items()}, EQUAL_AREA_SIZE)
    check(p[4].startswith(f'{paper_p * 1.01:.3g} ± {bar:.2g}'), f'the equal-area medium value and its bar {p[4]}')
    check(p[5] == str(paper_p) and p[6] == '+2.0 %', f'paper and difference {p[5:7]}')
    check(abs(finest - paper_p) > estimate and p[7] == '**more than the error bar**',
          f'flag {p[7]} where |ours - paper| = {abs(finest - paper_p):.3g} and the bar {estimate:.3g}')
    u = row(text, '45°', 'Δu_z [nm]')
    check(u is not None and u[6] == '+0.1 %' and u[7] == 'within the error bar' and u[8] == '', f'Δu_z cells {u}')
    check(row(text, '60°', 'P_max [nN]')[2] == 'not run', 'a scene not run')
    sweep = row(text, '× 1.5', 'P_max [nN]')
    check(sweep is not None and sweep[3] == 'medium' and sweep[5] == 'held out' and sweep[4] == f'{paper_p:.3g}'
          and '(one level)' in sweep[2],
          f'a sweep point run on one level: {sweep}')
    # A flagged cell takes its reason from glance-reasons.csv.
    check(study.reason('table4', '30', 'Π_int').startswith('the fine mesh passes the first instability'),
          'the reason of a whole case (quantity *)')
    check(study.reason('table6', '45', 'P_max [nN]') == '', 'no reason where none is known')

finish('study_glance: finest value, Richardson bar, flag exactly beyond the bar, held-out sweeps')
