"""Table 5's stored energies near the main snap: how the total work splits into the elastic energy (Pi_int) and the
adhesion given up (Pi_sa), and how fast that split changes as the lift approaches the snap.

The paper's total work before detachment follows from its public values (Table 5's Pi_ext,0 plus Table 6's
Delta Pi_ext), and Pi_int + Pi_sa = Pi_ext for the frictionless pull-offs. So where our total work agrees with the
paper's, a departure in Pi_int is an equal and opposite departure in Pi_sa: a difference in how much of the pad still
adheres at the state taken as "prior to detachment". This table shows how much that state matters: Pi_int a fixed
lift before the last converged state, and the lift over which Pi_int changes by 5 %."""
from curves import interpolate

# The lifts before the last state before the main snap at which Pi_int is shown [nm].
LIFTS_BEFORE_NM = (1.0, 2.0)
# The relative change of Pi_int whose lift is shown.
CHANGE = 0.05


def lift_for_change(rows, change):
    """The lift [nm] before the last row of `rows` (a lift ending at the state before the main snap) over which
    Pi_int first differs from its last value by `change` (relative), read from the curve between its rows; None if it
    never does."""
    last = rows[-1]
    target = abs(change * last['Pi_int_per_Pi_c0'])
    for later, earlier in zip(reversed(rows), list(reversed(rows))[1:]):
        a = abs(earlier['Pi_int_per_Pi_c0'] - last['Pi_int_per_Pi_c0'])
        b = abs(later['Pi_int_per_Pi_c0'] - last['Pi_int_per_Pi_c0'])
        if a >= target > b:
            t = (target - b) / (a - b)
            return last['u_z_nm'] - (later['u_z_nm'] + t * (earlier['u_z_nm'] - later['u_z_nm']))
    return None


def approach(summary):
    """The lift rows up to the state before the main snap, and that state."""
    rows, before = summary['rows'], summary['before']
    return rows[:rows.index(before) + 1], before


def split_row(summary, paper_start, paper_delta_work, pi_c0_1e18):
    """The numbers of one angle: our total work and the paper's (both / Pi_c0), Pi_int and Pi_sa at the last state,
    Pi_int at each of LIFTS_BEFORE_NM before it, the lift over which Pi_int changes by CHANGE, and the change of Pi_sa
    (relative) that an equal and opposite change of Pi_int by CHANGE would be."""
    rows, last = approach(summary)
    paper_total = paper_start + paper_delta_work / pi_c0_1e18
    before = []
    for lift in LIFTS_BEFORE_NM:
        at = interpolate(rows, 'u_z_nm', last['u_z_nm'] - lift, ['Pi_int_per_Pi_c0'])
        before.append(at['Pi_int_per_Pi_c0'] if at else None)
    return {'Pi_ext': last['Pi_ext_per_Pi_c0'], 'paper_Pi_ext': paper_total,
            'Pi_int': last['Pi_int_per_Pi_c0'], 'Pi_sa': last['Pi_sa_per_Pi_c0'],
            'Pi_int_before': before, 'lift_for_change_nm': lift_for_change(rows, CHANGE),
            'Pi_sa_change': CHANGE * last['Pi_int_per_Pi_c0'] / last['Pi_sa_per_Pi_c0'],
            'adhering_change': CHANGE * last['Pi_int_per_Pi_c0'] / (1.0 - last['Pi_sa_per_Pi_c0'])}


def snap_split_lines(summaries, pulls, level, paper_start, paper_table6, paper_pi_c0):
    """The Markdown table of every pull-off in `pulls` (theta_y) of one level."""
    from study.tables import percent   # (here, not at the top: study.tables imports this module)
    pi_c0_1e18 = 2.0 * paper_pi_c0   # Pi_c0 [1e-18 J] for E = 2 GPa, R0 = 1 nm (the paper's units)
    heads = ' | '.join(f'Pi_int {lift:g} nm before' for lift in LIFTS_BEFORE_NM)
    markdown = [f'### Table 5 near the main snap: how the total work splits ({level} mesh)\n',
                'Pi_ext against the paper\'s Pi_ext,0 + Delta Pi_ext (Tables 5 and 6); Pi_int and Pi_sa at the '
                'last state before the main snap and Pi_int a lift before it; the lift over which Pi_int changes '
                f'by {100 * CHANGE:g} %, and the changes of Pi_sa and of the adhesion still held (1 - Pi_sa) that '
                'balance it at the same total work (values / Pi_c0).\n',
                f'| theta_y | Pi_ext ours / paper | Pi_int | Pi_sa | {heads} '
                f'| lift for {100 * CHANGE:g} % of Pi_int [nm] | the same change of Pi_sa, of 1 - Pi_sa |',
                '|---|---|---|---|' + '---|' * len(LIFTS_BEFORE_NM) + '---|---|']
    for t in pulls:
        s = split_row(summaries[f'pull-off-{t}'], paper_start[t], paper_table6[t][2], pi_c0_1e18)
        before = ' | '.join('' if value is None else f'{value:.3f} ({percent(value, s["Pi_int"])})'
                            for value in s['Pi_int_before'])
        lift = '' if s['lift_for_change_nm'] is None else f'{s["lift_for_change_nm"]:.2f}'
        markdown.append(f'| {t} | {s["Pi_ext"]:.3f} / {s["paper_Pi_ext"]:.3f} '
                        f'({percent(s["Pi_ext"], s["paper_Pi_ext"])}) | {s["Pi_int"]:.3f} | {s["Pi_sa"]:.3f} '
                        f'| {before} | {lift} | {100 * s["Pi_sa_change"]:.1f} %, {100 * s["adhering_change"]:.0f} % |')
    markdown.append('')
    return markdown
