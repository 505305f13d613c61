"""The shear study's results (docs/shear.md): for every pull of the grid, the pull-off force along the pull, the force
(P_x, P_z) it is carried by, how far the end face travelled along the pull to detachment and the work it took; a
table per law, the adhesion-shear envelope and the pull-off force against the pull angle as figures."""
import math
import os
import re

from curves import read_curve
from scenes import app_diagnosis
from study.runs import complete, started
from study.shear_scenes import ANGLES, CONSTRAINTS, LAWS, grid, scene_name

LAW_NAMES = {'frictionless': 'frictionless', 'amontons': 'extended Amontons (mu = 0.3)',
             'strength': 'constant strength (tau_0 = 0.037 nN/nm^2)', 'stiction': 'stiction (no sliding)'}


def pull_summary(rows, beta):
    """The pull's quantities from its curve rows (the rotation's rows first): with the pull direction
    e = (cos beta, 0, sin beta), the force along it P = P_x cos beta + P_z sin beta, its peak (the pull-off force), the
    force across the pull at the peak, the travel along e from the pull's start to the peak and to the last state,
    the work of the pull to there and the energy dissipated on the way (jumps and sliding). None before the pull has
    begun."""
    pulled = [r for r in rows if r['stage'] == 'lift']
    if not pulled:
        return None
    first = rows.index(pulled[0])
    start = rows[first - 1] if first > 0 else pulled[0]
    c, s = math.cos(math.radians(beta)), math.sin(math.radians(beta))

    def along(r):
        return r['P_x_nN'] * c + r['P_z_nN'] * s

    def travel(r):
        return (r['u_x_nm'] - start['u_x_nm']) * c + (r['u_z_nm'] - start['u_z_nm']) * s

    peak, last = max(pulled, key=along), pulled[-1]
    return {
        'pull_off_nN': along(peak), 'P_x_nN': peak['P_x_nN'], 'P_z_nN': peak['P_z_nN'],
        'across_nN': peak['P_x_nN'] * s - peak['P_z_nN'] * c,
        'travel_at_peak_nm': travel(peak), 'travel_nm': travel(last),
        'work_1e-18J': last['Pi_ext_1e-18J'] - start['Pi_ext_1e-18J'],
        'dissipated_per_Pi_c0': last['dissipated_per_Pi_c0'] - start['dissipated_per_Pi_c0'],
        'jumps': sum(1 for r in pulled[1:] if r['after_jump']),
        'worst_balance_error': max(r['balance_error_per_Pi_c0'] for r in pulled),
    }


def summaries(work):
    """{(law, constraint, beta): summary with its run's outcome} of every grid point that has begun to pull."""
    found = {}
    for law, constraint, beta in grid():
        scene = scene_name(law, constraint, beta)
        if not started(work, scene):
            continue
        summary = pull_summary(read_curve(work, scene), beta)
        if summary:
            detached, words = outcome(work, scene)
            found[(law, constraint, beta)] = dict(summary, complete=complete(work, scene), detached=detached,
                                                  outcome=words)
    return found


# A pull whose jump found no stable state while the part of the pad still adhering slid farther than this along the
# substrate (the Lennard-Jones cut-off, beyond the reach of the adhesion it started in) has slid off: a way to let go
# of its own, not a solver stop.
SLID_OFF_NM = 10.0
NOT_FINISHED = 'not finished: values up to its last checkpoint'


RESUMED = 'spatula: resuming the stopped run'


def outcome(work, scene):
    """How a pull ended, as its run says: (detached?, words): detached (the app's detachment line), held on to its
    final travel, slid off (SLID_OFF_NM), stopped (with the app's diagnosis) or not finished (a run still going or
    interrupted, such as one carried in results/<level>/<scene>.stopped/). Only the log since the run's last resume
    counts: a failure before it is what the resume went on from."""
    log = os.path.join(work, scene + '.log')
    text = open(log).read() if os.path.exists(log) else ''
    text = text[text.rfind(RESUMED):] if RESUMED in text else text
    if complete(work, scene):
        detachment = [line for line in text.splitlines() if line.startswith('detachment:')]
        return (True, 'detached') if detachment else (False, 'held on to the final travel')
    diagnosis = app_diagnosis(text)
    if not diagnosis:
        return False, NOT_FINISHED
    kept = re.search(r'jump past the instability failed.*kept (\d+ %) of the adhesion energy'
                     r'(?:, its adhering part slid ([0-9.]+) nm)?', diagnosis)
    if kept and kept.group(2) and float(kept.group(2)) > SLID_OFF_NM:   # the pad neither settled nor came off
        return False, (f'slid off: no stable state after a jump, its adhering part slid {kept.group(2)} nm along the '
                       f'substrate keeping {kept.group(1)} of the adhesion')
    if kept:
        return False, f'stopped: no stable state after a jump (its descent kept {kept.group(1)} of the adhesion)'
    return False, f'stopped: {diagnosis} (values up to the last converged state)'


def cell(summary):
    """A table cell: the pull-off force, marked where the run did not detach."""
    if summary is None:
        return 'not run'
    mark = '' if summary['detached'] else (' (held on)' if summary['complete'] else
                                           ' (slid off)' if summary['outcome'].startswith('slid off') else
                                           ' (not finished)' if summary['outcome'] == NOT_FINISHED else ' (stopped)')
    return f"{summary['pull_off_nN']:.2f}{mark}"


def lines(work, level):
    """The study's tables in Markdown."""
    found = summaries(work)
    markdown = [f'### Pull-off force along the pull [nN] ({level} mesh)\n',
                'Rows: the pull angle beta (90: straight up, 180: along the substrate away from the pad). Columns: '
                'the law, with the end face held across the pull or free. "held on": the pull reached its final '
                'travel (600 nm) still attached; "slid off": after a snap no stable state followed while the part of the '
                f'pad still adhering slid more than {SLID_OFF_NM:g} nm along the substrate; "stopped": the run ended '
                'before detachment; "not finished": a run still going, its values up to its last checkpoint.\n']
    columns = [(law, constraint) for law in LAWS for constraint in CONSTRAINTS[law]]
    markdown.append('| beta [deg] | ' + ' | '.join(f'{law} {constraint}' for law, constraint in columns) + ' |')
    markdown.append('|---|' + '---|' * len(columns))
    for beta in ANGLES:
        markdown.append(f'| {beta} | ' + ' | '.join(cell(found.get((law, constraint, beta)))
                                                     for law, constraint in columns) + ' |')
    markdown.append('')
    markdown.append(f'### The force at the pull-off peak, travel and work ({level} mesh)\n')
    markdown.append('| law | across | beta | pull-off [nN] | P_x [nN] | P_z [nN] | travel to peak [nm] | '
                    'travel to the end [nm] | work [1e-18 J] | dissipated / Pi_c0 | jumps | outcome |')
    markdown.append('|---|---|---|---|---|---|---|---|---|---|---|---|')
    for (law, constraint, beta), v in found.items():
        markdown.append(f"| {law} | {constraint} | {beta} | {v['pull_off_nN']:.3f} | {v['P_x_nN']:.3f} | "
                        f"{v['P_z_nN']:.3f} | {v['travel_at_peak_nm']:.1f} | {v['travel_nm']:.1f} | "
                        f"{v['work_1e-18J']:.1f} | {v['dissipated_per_Pi_c0']:.3f} | {v['jumps']} | {v['outcome']} |")
    markdown.append('')
    return '\n'.join(markdown), found


def mesh_dependence(found_by_level):
    """The pull-off forces of the grid points run on more than one level, and their change between the two finest:
    the error bar of the coarser value (a bound while only two levels are run), in Markdown; '' without such points."""
    levels = list(found_by_level)
    shared = [key for key in grid() if sum(key in found for found in found_by_level.values()) >= 2]
    if not shared:
        return ''
    markdown = ['### Mesh dependence of the pull-off force [nN]\n',
                'Points run on more than one mesh level; the change between the two finest levels bounds the error of '
                'the coarser one. A run that did not detach is marked as in the tables; a run not finished has no '
                'change yet.\n',
                '| law | across | beta | ' + ' | '.join(levels) + ' | change between the two finest |',
                '|---|---|---|' + '---|' * (len(levels) + 1)]
    for key in shared:
        values = [found_by_level[level].get(key) for level in levels]
        present = [v for v in values if v]
        change = ('not yet' if any(v['outcome'] == NOT_FINISHED for v in present[-2:]) else
                  f"{100 * (present[-1]['pull_off_nN'] / present[-2]['pull_off_nN'] - 1):+.1f} %")
        markdown.append(f'| {key[0]} | {key[1]} | {key[2]} | ' + ' | '.join(cell(v) for v in values) +
                        f' | {change} |')
    markdown.append('')
    return '\n'.join(markdown)


def figure(found, level, directory):
    """The pull-off force against the pull angle, and the envelope (P_x, P_z) at the peak, per law; returns (file,
    caption) pairs."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    if not found:
        return []
    fig, (force, envelope) = plt.subplots(1, 2, figsize=(12, 4.5))
    for (law, constraint), colour in zip([(l, c) for l in LAWS for c in CONSTRAINTS[l]], plt.cm.tab10.colors):
        points = [(beta, found[(law, constraint, beta)]) for beta in ANGLES if (law, constraint, beta) in found]
        if not points:
            continue
        style = '-o' if constraint == 'free' else '--s'
        label = f'{law}, {constraint} across the pull'
        force.plot([b for b, _ in points], [v['pull_off_nN'] for _, v in points], style, color=colour, label=label,
                   markerfacecolor=colour if constraint == 'free' else 'none')
        envelope.plot([-v['P_x_nN'] for _, v in points], [v['P_z_nN'] for _, v in points], style, color=colour,
                      label=label, markerfacecolor=colour if constraint == 'free' else 'none')
        undetached = [(b, v) for b, v in points if not v['detached']]   # the peak so far: a lower bound
        force.plot([b for b, _ in undetached], [v['pull_off_nN'] for _, v in undetached], 'x', color='black',
                   markersize=9)
        envelope.plot([-v['P_x_nN'] for _, v in undetached], [v['P_z_nN'] for _, v in undetached], 'x',
                      color='black', markersize=9)
    force.set_xlabel('pull angle beta [deg] (90: normal, 180: along the substrate)')
    force.set_ylabel('pull-off force along the pull [nN]')
    force.set_yscale('log')   # from a few nN (frictionless at 165 deg) to the sliding limit over the pad
    force.set_ylim(bottom=1.0)   # (the frictionless pad pulled along the substrate carries nothing)
    force.set_title(f'Pull-off force against pull angle ({level} mesh)')
    force.grid(alpha=0.3)
    force.legend(fontsize=7)
    shear = [0.0] + sorted(-v['P_x_nN'] for v in found.values() if -v['P_x_nN'] > 0)
    envelope.plot(shear, [x * math.tan(math.radians(30)) for x in shear], ':', color='grey',
                  label='P_z = -P_x tan 30 deg (frictional adhesion, alpha* about 25-30 deg)')
    envelope.legend(fontsize=7)
    envelope.set_ylim(-5, 1.2 * max(v['P_z_nN'] for v in found.values()))
    envelope.set_xscale('symlog', linthresh=10)
    envelope.set_xlim(left=-1.0)
    envelope.set_xlabel('-P_x at the peak [nN] (shear, away from the pad; linear up to 10)')
    envelope.set_ylabel('P_z at the peak [nN] (normal)')
    envelope.set_title('Adhesion-shear envelope')
    envelope.axhline(0, color='grey', linewidth=0.5)
    envelope.axvline(0, color='grey', linewidth=0.5)
    envelope.grid(alpha=0.3)
    fig.tight_layout()
    name = f'shear-{level}.png'
    fig.savefig(os.path.join(directory, name), dpi=110)
    plt.close(fig)
    return [(name, f'Pull-off force against pull angle and the (P_x, P_z) envelope at the peak ({level} mesh; a '
                   f'cross marks a run that ended attached, its peak so far a lower bound)')]


def pulled_states(beta):
    """The states a picture of a pull at beta draws: the end face's lift along the pull (the field output's time) at
    the pull-off force and at the run's last state, from the curve in the run's directory."""
    c, s = math.cos(math.radians(beta)), math.sin(math.radians(beta))

    def times(run_directory):
        rows = read_curve(os.path.dirname(run_directory), os.path.basename(run_directory))
        pulled = [r for r in rows if r['stage'] == 'lift']
        peak = max(pulled, key=lambda r: r['P_x_nN'] * c + r['P_z_nN'] * s)
        return [r['u_x_nm'] * c + r['u_z_nm'] * s for r in (peak, pulled[-1])]
    return times


# Where the pad slid (docs/shear.md): the free and the held pull at 150 deg with the extended Amontons law.
SLIDING_PICTURES = tuple(
    (scene_name('amontons', constraint, 150), pulled_states(150), f'shear-sliding-amontons-{constraint}-150.png',
     f'Where the pad slid, extended Amontons law, pulled at 150 deg with the end face {constraint} across the pull: '
     'side view and the pad from below at the pull-off force and at the last state, coloured by the energy dissipated '
     'by sliding per unit area, dissipated_by_friction [J/m^2]', 'dissipated_by_friction')
    for constraint in ('free', 'held'))
