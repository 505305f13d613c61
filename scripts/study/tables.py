"""The study tables: the paper's values (Tables 4-6), our values from the runs of one mesh level (Markdown and CSV
in <work>/tables/), and the discretization error bars over the levels."""
import os

from convergence import ASSUMED_ORDER, LEVELS, richardson
from curves import interpolate, pad_slip, pull_off_summary, read_curve
from study.runs import complete, outcome, started
from study.snap_split import snap_split_lines


# Fig. 9's pull-offs at 60 deg: (scene, label, end face free in X), for its table and its plot.
STICTION_RUNS = (('pull-off-60', 'frictionless', False),
                 ('pull-off-60-stiction', 'stiction, end face free in X', True),
                 ('pull-off-60-stiction-x-held', 'stiction, end face held in X', False))


def paper_values():
    """The paper's values this project may use, from scripts/study/paper-values.csv (its Tables 4, 5 and 6 and Pi_c0 of
    Sec. 3; the rest are held out): (Table 4, Table 6, Table 5's Pi_ext,0, Pi_c0), the tables keyed by theta_y (an
    int, or a label such as '31-')."""
    tables = {'table4': {}, 'table5': {}, 'table6': {}}
    pi_c0 = None
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), 'paper-values.csv')) as values:
        for line in values:
            if line.startswith('#') or not line.strip():
                continue
            table, key, *numbers = line.strip().split(',')
            numbers = tuple(int(n) if n.isdigit() else float(n) for n in numbers)
            if table == 'pi_c0':
                pi_c0 = numbers[0]
            else:
                tables[table][int(key) if key.isdigit() else key] = numbers if len(numbers) > 1 else numbers[0]
    return tables['table4'], tables['table6'], tables['table5'], pi_c0


PAPER_TABLE4, PAPER_TABLE6, PAPER_TABLE5_START, PAPER_PI_C0 = paper_values()


def rotation_curve(work):
    """(rows, source) of a level's peel by rotation: the peel-rotation run ('peel-rotation'); where that run restarted
    from a checkpoint of the rotation that precedes the pull-off at 60 deg (the fine level's, run in segments), that
    rotation's states before the restart and then the run's ('pull-off-60 + peel-rotation'); where a level has no
    peel-rotation (the fine level ran only the pull-off at 60 deg) the rotation stage of its pull-off at 60 deg
    ('pull-off-60'); (None, None) without either."""
    earlier = None
    if started(work, 'pull-off-60'):
        earlier = [r for r in read_curve(work, 'pull-off-60') if r['stage'] == 'rotation']
        earlier = earlier if len(earlier) > 1 else None
    run = rotation_run(work)
    if run:
        rows = read_curve(work, run)
        if earlier and rows and rows[0]['step'] > 0 and rows[0]['theta_y_deg'] > earlier[0]['theta_y_deg']:
            start = rows[0]['theta_y_deg']
            return [r for r in earlier if r['theta_y_deg'] < start - 1e-9] + rows, 'pull-off-60 + peel-rotation'
        return rows, 'peel-rotation'
    if earlier:
        return earlier, 'pull-off-60'
    return None, None


# A peel by rotation kept under another name: the fine level's rotation from 60 deg, restarted from
# the 60 deg state of the pull-off at 60 deg, whose checkpoints were lost with its machine. A study's own peel-rotation
# run (from the undeformed state) takes its place once complete.
EARLIER_ROTATION = 'peel-rotation-from-60'


def rotation_run(work):
    """The peel-rotation run a level's Table 4 reads: the study's own when complete, else the earlier one kept under
    EARLIER_ROTATION, else the study's own stopped run (its curve up to where it stopped); None without any."""
    if complete(work, 'peel-rotation'):
        return 'peel-rotation'
    if complete(work, EARLIER_ROTATION):
        return EARLIER_ROTATION
    return 'peel-rotation' if started(work, 'peel-rotation') else None


def table4(work):
    rows, source = rotation_curve(work)
    columns = ['Pi_ext_per_Pi_c0', 'Pi_int_per_Pi_c0', 'Pi_sa_per_Pi_c0', 'balance_error_per_Pi_c0', 'M_y_nNnm']
    out = []
    for theta in (30, 60, 90, 120):
        values = interpolate(rows, 'theta_y_deg', theta, columns)
        if values:
            out.append((str(theta), theta, values, PAPER_TABLE4[theta]))
    if source == 'pull-off-60':   # a rotation to 60 deg only: no detachment
        return out, rows
    # The first instability: the first jump after which the moment dropped by more than 10 %; only where the curve
    # starts at the undeformed state (a curve that starts from a restart may begin after it).
    for i, row in enumerate(rows if rows[0]['step'] == 0 else []):
        if row['after_jump'] == 1 and row['M_y_nNnm'] < 0.9 * rows[i - 1]['M_y_nNnm']:
            out.insert(1, ('31- (before the first drop)', rows[i - 1]['theta_y_deg'], rows[i - 1], PAPER_TABLE4['31-']))
            out.insert(2, ('31+ (after it)', row['theta_y_deg'], row, PAPER_TABLE4['31+']))
            break
    # The last state before detachment: the final row is the detached state when the run ended by a collapse.
    peak = max(abs(r['M_y_nNnm']) for r in rows)
    detached = len(rows) > 1 and abs(rows[-1]['M_y_nNnm']) < 0.01 * peak
    last = rows[-2] if detached else rows[-1]
    label = '128 (last state before detachment)' if detached else '128 (paper) / our last state: not detached'
    out.append((label, last['theta_y_deg'], last, PAPER_TABLE4[128]))
    return out, rows


def percent(ours, paper):
    return f'{100.0 * (ours / paper - 1.0):+.1f} %' if paper else ''


def table4_lines(work, level, tables):
    """Table 4 (peeling by rotation, energies at the paper's angles), in our Pi_c0 and in the paper's."""
    rotation_rows, rotation_source = rotation_curve(work)
    if not rotation_rows:
        return []
    entries, rows = table4(work)
    markdown = [f'### Table 4: peeling by rotation (values / Pi_c0) ({level} mesh)\n']
    if rotation_source == 'pull-off-60':
        markdown.append(f'From the rotation that precedes the pull-off at 60 deg (this level has no peel to '
                        f'detachment; its curve starts at theta_y = {rows[0]["theta_y_deg"]:.2f} deg).\n')
    elif rotation_source != 'peel-rotation':
        markdown.append(f'From the rotation that precedes the pull-off at 60 deg up to the checkpoint the '
                        f'peel-rotation run restarted from, then that run; the curve starts at theta_y = '
                        f'{rows[0]["theta_y_deg"]:.2f} deg, so the first instability is not in it.\n')
    markdown.append('| theta_y | ours: theta_y [deg] | Pi_ext ours / paper | Pi_int ours / paper | Pi_sa ours / paper '
                    '| balance error |')
    markdown.append('|---|---|---|---|---|---|')
    with open(os.path.join(tables, 'table4.csv'), 'w') as out:
        out.write('label,theta_y_deg,Pi_ext,Pi_int,Pi_sa,paper_Pi_ext,paper_Pi_int,paper_Pi_sa\n')
        for label, theta, v, p in entries:
            out.write(f'{label},{theta:.3f},{v["Pi_ext_per_Pi_c0"]:.4f},{v["Pi_int_per_Pi_c0"]:.4f},'
                      f'{v["Pi_sa_per_Pi_c0"]:.4f},{p[0]},{p[1]},{p[2]}\n')
            markdown.append(
                f'| {label} | {theta:.2f} | {v["Pi_ext_per_Pi_c0"]:.3f} / {p[0]} ({percent(v["Pi_ext_per_Pi_c0"], p[0])}) '
                f'| {v["Pi_int_per_Pi_c0"]:.3f} / {p[1]} ({percent(v["Pi_int_per_Pi_c0"], p[1])}) '
                f'| {v["Pi_sa_per_Pi_c0"]:.3f} / {p[2]} ({percent(v["Pi_sa_per_Pi_c0"], p[2])}) '
                f'| {v["balance_error_per_Pi_c0"]:.1e} |')
    markdown.append('')
    # The same energies in units of the paper's Pi_c0 (its contact area is 1.4 % smaller than ours): the
    # deformation energies are absolute, so this is the like-for-like comparison of Pi_ext and Pi_int.
    row = next(r for r in rows if r['Pi_ext_per_Pi_c0'] > 0.01 and abs(r['M_y_per_ER0^3']) > 0.01)
    young_r0_cubed = row['M_y_nNnm'] / row['M_y_per_ER0^3']   # E R0^3 in nN nm = 1e-18 J
    ours = row['Pi_ext_1e-18J'] / row['Pi_ext_per_Pi_c0'] / young_r0_cubed
    scale = ours / PAPER_PI_C0
    markdown.append(f'The same in units of the paper\'s Pi_c0 = {PAPER_PI_C0} E R0^3 (ours is {ours:.1f} E R0^3: '
                    f'values x {scale:.4f}):\n')
    markdown.append('| theta_y | Pi_ext ours / paper | Pi_int ours / paper | Pi_sa ours / paper |')
    markdown.append('|---|---|---|---|')
    for label, theta, v, p in entries:
        cells = [f'{scale * v[k]:.3f} / {q} ({percent(scale * v[k], q)})'
                 for k, q in zip(('Pi_ext_per_Pi_c0', 'Pi_int_per_Pi_c0', 'Pi_sa_per_Pi_c0'), p)]
        markdown.append(f'| {label} | ' + ' | '.join(cells) + ' |')
    markdown.append('')
    return markdown


def pull_off_summaries(work, scenes):
    """The summary of every pull-off (and sweep) run that reached its lift, and a line for each that stopped
    before it."""
    summaries, unfinished = {}, []
    for scene in scenes:
        if (scene.startswith('pull-off') or scene.startswith('gamma')) and started(work, scene):
            summary = dict(pull_off_summary(work, scene), outcome=outcome(work, scene))
            if summary['rows']:
                summaries[scene] = summary
            else:   # stopped before the lift began
                last = read_curve(work, scene)[-1]
                unfinished.append(f'- `{scene}`, during the rotation at theta_y = {last["theta_y_deg"]:.1f} deg: '
                                  f'{summary["outcome"]}')
    return summaries, unfinished


def table6_lines(summaries, pulls, level, tables):
    """Table 6: P_max, Delta u_z and Delta Pi_ext of the pull-offs at 45-90 deg."""
    markdown = [f'### Table 6: pull-off at fixed inclination ({level} mesh)\n',
                '| theta_y | P_max [nN] ours / paper | Delta u_z [nm] ours / paper | Delta Pi_ext [1e-18 J] ours / paper |',
                '|---|---|---|---|']
    with open(os.path.join(tables, 'table6.csv'), 'w') as out:
        out.write('theta_y_deg,P_max_nN,delta_u_z_nm,delta_Pi_ext_1e-18J,paper_P_max,paper_delta_u_z,'
                  'paper_delta_Pi_ext,detached\n')
        for t in pulls:
            s, p = summaries[f'pull-off-{t}'], PAPER_TABLE6[t]
            out.write(f'{t},{s["P_max_nN"]:.4f},{s["delta_u_z_nm"]:.2f},{s["delta_Pi_ext_1e-18J"]:.1f},'
                      f'{p[0]},{p[1]},{p[2]},{s["detached"]}\n')
            markdown.append(f'| {t} | {s["P_max_nN"]:.2f} / {p[0]} ({percent(s["P_max_nN"], p[0])}) '
                            f'| {s["delta_u_z_nm"]:.0f} / {p[1]} ({percent(s["delta_u_z_nm"], p[1])}) '
                            f'| {s["delta_Pi_ext_1e-18J"]:.0f} / {p[2]} ({percent(s["delta_Pi_ext_1e-18J"], p[2])}) |'
                            + ('' if s['outcome'] == 'detached' else f' {s["outcome"]}'))
    markdown.append('')
    return markdown


def detachment_lines(summaries, pulls, level, tables):
    """The main snap (the tables' values) against the final detachment, and the tail between them."""
    markdown = [f'### Detachment: the main snap (the tables\' values) and the final detachment ({level} mesh)\n',
                'The paper takes the state before the main snap (the jump that drops the pull the most); a '
                'small patch of the pad can stay attached after it (the tail) until the pull falls below 1 % '
                'of its peak (the final detachment).\n',
                '| theta_y | Delta u_z to the main snap [nm] | P_z after it [nN] | energy it released / Pi_c0 '
                '| Delta u_z to the final detachment [nm] | tail: length [nm], work [1e-18 J] |',
                '|---|---|---|---|---|---|']
    with open(os.path.join(tables, 'detachment.csv'), 'w') as out:
        out.write('theta_y_deg,delta_u_z_main_nm,P_after_main_nN,released_main_per_Pi_c0,delta_u_z_final_nm,'
                  'tail_u_z_nm,tail_Pi_ext_1e-18J\n')
        for t in pulls:
            s = summaries[f'pull-off-{t}']
            out.write(f'{t},{s["delta_u_z_nm"]:.2f},{s["main_snap_P_after_nN"]:.4f},'
                      f'{s["main_snap_released_per_Pi_c0"]:.4f},{s["final_delta_u_z_nm"]:.2f},'
                      f'{s["tail_u_z_nm"]:.2f},{s["tail_Pi_ext_1e-18J"]:.1f}\n')
            markdown.append(f'| {t} | {s["delta_u_z_nm"]:.1f} | {s["main_snap_P_after_nN"]:.2f} '
                            f'| {s["main_snap_released_per_Pi_c0"]:.3f} | {s["final_delta_u_z_nm"]:.1f} '
                            f'| {s["tail_u_z_nm"]:.1f}, {s["tail_Pi_ext_1e-18J"]:.0f} |')
    markdown.append('')
    return markdown


def table5_lines(summaries, pulls, level):
    """Table 5: the work and the stored energies before the main snap."""
    markdown = [f'### Table 5: work and stored energies prior to detachment (values / Pi_c0) ({level} mesh)\n',
                '| theta_y | Pi_ext,0 ours / paper | Delta Pi_ext | Pi_ext | Pi_int | Pi_sa | worst balance error |',
                '|---|---|---|---|---|---|---|']
    for t in pulls:
        s = summaries[f'pull-off-{t}']
        markdown.append(f'| {t} | {s["Pi_ext0_per_Pi_c0"]:.3f} / {PAPER_TABLE5_START[t]} '
                        f'| {s["delta_Pi_ext_per_Pi_c0"]:.3f} | {s["Pi_ext_per_Pi_c0"]:.3f} '
                        f'| {s["Pi_int_per_Pi_c0"]:.3f} | {s["Pi_sa_per_Pi_c0"]:.3f} | {s["worst_balance_error"]:.1e} |')
    markdown.append('')
    return markdown


def sweep_lines(work, summaries, level, title, prefix, rotation_rows, rotation_source):
    """Table 7 or 8: the sweep's pull-offs at 60 deg, with the factor-1 cell from the pull-off at 60 deg."""
    base = 1.0
    runs = sorted((float(s.split('-')[-1]), s) for s in summaries if s.startswith(prefix))
    if 'pull-off-60' in summaries:
        runs = sorted(runs + [(base, 'pull-off-60')])
    if not (len(runs) > 1 or (runs == [(base, 'pull-off-60')] and level == LEVELS[-1])):
        return []
    markdown = [f'### {title} ({level} mesh)\n']
    if len(runs) == 1:
        markdown.append('Only the factor-1 cell (the pull-off at 60 deg): the sweep was not run at this level.\n')
    own = [r for r in read_curve(work, 'pull-off-60') if r['stage'] == 'rotation'] \
        if 'pull-off-60' in summaries else []   # one state where it starts from the peel run's checkpoint
    first = own[0]['theta_y_deg'] if len(own) > 1 else 0.0
    if first > 0.0 and own[0]['Pi_ext_1e-18J'] > 0.0:   # its own rotation resumed from a checkpoint (a fresh
        # one starts unloaded): the curve holds only what came after
        markdown.append(f'The pull-off at 60 deg\'s curve starts at theta_y = {first:.2f} deg (a run resumed '
                        'from a checkpoint): jumps of its rotation before that are not counted.\n')
    markdown.append('The path of each point (the sweep compares like with like only if they follow the same '
                    'kind): Pi_sa / Pi_c0 when the lift begins (how much adhesion the rotation to 60 deg '
                    'already gave up) and the jumps in the rotation and in the lift.\n')
    markdown.append('| factor | P_max [nN] | Delta u_z [nm] | Delta Pi_ext [1e-18 J] | Pi_sa / Pi_c0 at the lift\'s '
                    'start | jumps: rotation, lift | end of the run |')
    markdown.append('|---|---|---|---|---|---|---|')
    for factor, scene in runs:
        s = summaries[scene]
        rotation_jumps = s['jumps_in_rotation']
        if scene == 'pull-off-60' and rotation_source == 'peel-rotation':   # its rotation is the peel run's
            rotation_jumps = sum(1 for r in rotation_rows if r['after_jump'] and r['theta_y_deg'] <= 60.0 + 1e-9)
        markdown.append(f'| {factor:g} | {s["P_max_nN"]:.2f} | {s["delta_u_z_nm"]:.0f} | {s["delta_Pi_ext_1e-18J"]:.0f} '
                        f'| {s["Pi_sa_at_lift_start"]:.3f} | {rotation_jumps}, {s["jumps_in_lift"]} '
                        f'| {s["outcome"]} |')
    markdown.append('')
    return markdown


def stiction_lines(work, summaries, level):
    """The stiction pull-offs at 60 deg beside the frictionless one."""
    if not ('pull-off-60' in summaries and any(scene in summaries for scene, _, _ in STICTION_RUNS[1:])):
        return []
    markdown = [f'### Stiction vs frictionless at 60 deg ({level} mesh)\n',
                '| law | P_max [nN] | Delta u_z [nm] | Delta Pi_ext [1e-18 J] | slip of the adhering pad by P_max '
                '| end face X travel by P_max | end of the run |',
                '|---|---|---|---|---|---|---|']
    for scene, name, free_in_x in STICTION_RUNS:
        if scene not in summaries:
            continue
        s = summaries[scene]
        slip = pad_slip(work, scene, s['u_z_at_P_max'])
        slip_text = (f'{slip[1]:.1f} nm ({slip[2]} nodes, state at u_z = {slip[0]:.0f} nm)' if slip else '')
        peak = max(s['rows'], key=lambda r: r['P_z_nN'])
        travel = (f'{peak["u_x_nm"] - s["start"]["u_x_nm"]:.1f} nm' if 'u_x_nm' in peak
                  else 'not recorded' if free_in_x else '0 (held)')
        markdown.append(f'| {name} | {s["P_max_nN"]:.2f} | {s["delta_u_z_nm"]:.0f} | {s["delta_Pi_ext_1e-18J"]:.0f} '
                        f'| {slip_text} | {travel} | {s["outcome"]} |')
    markdown.append('')
    return markdown


def rough_lines(work, level):
    """The rough substrates' rotations to 45 deg (Fig. 14)."""
    rough = [(z0, read_curve(work, f'rough-z0-{z0}'), complete(work, f'rough-z0-{z0}')) for z0 in (0, 4, 8)
             if started(work, f'rough-z0-{z0}')]
    if not rough:
        return []
    markdown = [f'### Rough substrates, rotation to 45 deg with zero net force (cf. paper Fig. 14) ({level} mesh)\n',
                '| z0 [nm] | reached theta_y [deg] | M_y at 30 deg [nN nm] | largest M_y [nN nm] | Pi_sa / Pi_c0 at the last state '
                '| worst balance error |',
                '|---|---|---|---|---|---|']
    for z0, rows, done in rough:
        at30 = interpolate(rows, 'theta_y_deg', 30.0, ['M_y_nNnm'])
        markdown.append(f'| {z0} | {rows[-1]["theta_y_deg"]:.1f}{"" if done else " (run not finished)"} '
                        f'| {at30["M_y_nNnm"]:.0f} | {max(r["M_y_nNnm"] for r in rows):.0f} '
                        f'| {rows[-1]["Pi_sa_per_Pi_c0"]:.3f} '
                        f'| {max(r["balance_error_per_Pi_c0"] for r in rows):.1e} |' if at30 else
                        f'| {z0} | {rows[-1]["theta_y_deg"]:.1f} (not finished) | | | | |')
    markdown.append('')
    return markdown


def write_tables(work, scenes, level):
    """The tables of the runs in work (one mesh level), as Markdown (also written to <work>/tables/)."""
    tables = os.path.join(work, 'tables')
    os.makedirs(tables, exist_ok=True)
    markdown = table4_lines(work, level, tables)
    rotation_rows, rotation_source = rotation_curve(work)
    summaries, unfinished = pull_off_summaries(work, scenes)
    pulls = [t for t in (45, 60, 75, 90) if f'pull-off-{t}' in summaries]
    if pulls:
        markdown += table6_lines(summaries, pulls, level, tables)
        markdown += detachment_lines(summaries, pulls, level, tables)
        markdown += table5_lines(summaries, pulls, level)
        markdown += snap_split_lines(summaries, pulls, level, PAPER_TABLE5_START, PAPER_TABLE6, PAPER_PI_C0)
    for title, prefix in (('Table 7: adhesion strength gamma_W / gamma_W0 (theta_y = 60 deg)', 'gamma-W'),
                          ('Table 8: length scale gamma_L / gamma_L0 (theta_y = 60 deg)', 'gamma-L')):
        markdown += sweep_lines(work, summaries, level, title, prefix, rotation_rows, rotation_source)
    markdown += stiction_lines(work, summaries, level)
    if unfinished:
        markdown += [f'### Runs that stopped before their pull-off ({level} mesh)\n'] + unfinished + ['']
    markdown += rough_lines(work, level)
    text = '\n'.join(markdown)
    open(os.path.join(tables, 'tables.md'), 'w').write(text)
    return text, summaries


def error_bars(results):
    """Markdown: each Table 6-8 quantity (and Table 4's energies at 30, 60, 90 deg) on every level run, as
    `value ± estimate` on the finest with the extrapolated value (Richardson), for the scenes run on two levels or
    more. A cell whose runs ended differently on the levels (detached on one, not on another), or whose levels differ
    by more than a factor PATH_CHANGE (scripts/convergence.py: another path on the coarser mesh), says so."""
    lines = ['### Discretization error: every quantity run on two mesh levels or more\n',
             f'Richardson extrapolation in the in-plane element size (coarse 1, medium 1/4, fine 1/8): with three levels '
             f'the observed order, with two the assumed order {ASSUMED_ORDER:g}. Values are those of the tables above '
             '(Delta u_z and Delta Pi_ext to the main snap).\n',
             '| scene | quantity | ' + ' | '.join(LEVELS) + ' | finest ± estimate | extrapolated | remark |',
             '|---|---|' + '---|' * len(LEVELS) + '---|---|---|']
    quantities = (('P_max_nN', 'P_max [nN]'), ('delta_u_z_nm', 'Delta u_z [nm]'),
                  ('delta_Pi_ext_1e-18J', 'Delta Pi_ext [1e-18 J]'))
    scenes = sorted({scene for _, summaries in results.values() for scene in summaries})
    rows = 0

    def row(what, label, by_level, remark_suffix=''):
        finest, estimate, extrapolated, remark = richardson(by_level)
        cells = [f'{by_level[level]:.4g}' if level in by_level else '' for level in LEVELS]
        lines.append(f'| {what} | {label} | ' + ' | '.join(cells) + f' | {finest:.4g} ± {estimate:.2g} '
                     f'| {"" if extrapolated is None else f"{extrapolated:.4g}"} | {remark}{remark_suffix} |')

    for scene in scenes:
        have = {level: summaries[scene] for level, (_, summaries) in results.items() if scene in summaries}
        if len(have) < 2:
            continue
        outcomes = {s['outcome'] for s in have.values()}
        differ = ('; the runs ended differently on the levels (' + ' / '.join(sorted(outcomes)) + ')'
                  if len(outcomes) > 1 else '')
        for key, label in quantities:
            row(scene, label, {level: s[key] for level, s in have.items()}, differ)
            rows += 1
    sources = {level: rotation_curve(directory) for level, (directory, _) in results.items()}
    rotation = {level: rows for level, (rows, _) in sources.items() if rows}
    borrowed = [level for level, (rows, source) in sources.items() if rows and source != 'peel-rotation']
    note = '; ' + '; '.join(f'{level}: the rotation before the pull-off at 60 deg'
                            + (', then the peel-rotation run restarted from its checkpoint' if sources[level][1] !=
                               'pull-off-60' else '') +
                            f', whose curve starts at theta_y = {rotation[level][0]["theta_y_deg"]:.2f} deg'
                            for level in borrowed) if borrowed else ''
    if len(rotation) >= 2:
        for theta in (30.0, 60.0, 90.0):
            for key, label in (('Pi_ext_per_Pi_c0', 'Pi_ext / Pi_c0'), ('Pi_int_per_Pi_c0', 'Pi_int / Pi_c0'),
                               ('Pi_sa_per_Pi_c0', 'Pi_sa / Pi_c0')):
                by_level = {}
                for level, curve in rotation.items():
                    point = interpolate(curve, 'theta_y_deg', theta, [key])
                    if point:
                        by_level[level] = point[key]
                if len(by_level) < 2:
                    continue
                row(f'peel-rotation at {theta:g} deg', label, by_level,
                    note if any(level in by_level for level in borrowed) else '')
                rows += 1
    return '\n'.join(lines) + '\n' if rows else ''
