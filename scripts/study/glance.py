"""The results page's first section: one table per paper table, our best value (the finest mesh level that ran the
scene) with its discretization error bar beside the paper's value, and a flag where the two differ by more than the
error bar, with the reason where it is known (scripts/study/glance-reasons.csv)."""
import csv
import os

from convergence import ELEMENT_SIZE, EQUAL_AREA_SIZE, richardson
from study.tables import PAPER_TABLE4, PAPER_TABLE5_START, PAPER_TABLE6, rotation_curve, table4

PULL_OFF_ANGLES = (45, 60, 75, 90)
TABLE6_QUANTITIES = (('P_max_nN', 'P_max [nN]', 0), ('delta_u_z_nm', 'Δu_z [nm]', 1),
                     ('delta_Pi_ext_1e-18J', 'ΔΠ_ext [1e-18 J]', 2))
SWEEPS = (('Table 7: adhesion strength γ_W / γ_W0 at 60°', 'gamma-W'),
          ('Table 8: length scale γ_L / γ_L0 at 60°', 'gamma-L'))
TABLE4_ROWS = (('30', 30), ('31-', '31-'), ('31+', '31+'), ('60', 60), ('90', 90), ('120', 120), ('128', 128))
TABLE4_CASES = {'31-': '31°, before the first drop', '31+': '31°, after it', '128': '128°, before detachment'}
TABLE4_QUANTITIES = (('Pi_ext_per_Pi_c0', 'Π_ext'), ('Pi_int_per_Pi_c0', 'Π_int'), ('Pi_sa_per_Pi_c0', 'Π_sa'))


def reasons():
    """{(table, case, quantity): reason} from glance-reasons.csv (quantity '*': every quantity of the case)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'glance-reasons.csv')
    rows = csv.reader(line for line in open(path, encoding='utf-8') if not line.startswith('#'))
    return {(table, case, quantity): ','.join(reason) for table, case, quantity, *reason in rows}


REASONS = reasons()


def reason(table, case, quantity):
    return REASONS.get((table, case, quantity), REASONS.get((table, case, '*'), ''))


def best(by_level, element_size=ELEMENT_SIZE):
    """(value, error bar or None, the mesh it came from, whether the estimate is reliable) from {level: value} over
    the levels of element_size (the paper's, or the equal-area sequence)."""
    levels = [level for level in element_size if level in by_level]
    if not levels:
        return None
    if len(levels) == 1:
        return by_level[levels[0]], None, levels[0], False
    finest, estimate, _, remark = richardson(by_level, element_size)
    return finest, estimate, levels[-1], 'not reliable' not in remark and 'asymptotic' not in remark


def equal_area(by_level):
    """(the medium mesh's value, its error bar over the equal-area sequence or None, whether it is reliable) from
    {equal-area level: value}, or None where the medium mesh did not run the scene."""
    if 'medium-equal-area' not in by_level:
        return None
    value, estimate, _, reliable = best(by_level, EQUAL_AREA_SIZE)
    return value, estimate, reliable


def with_bar(value, estimate, reliable):
    return digits(value) + (f' ± {estimate:.2g}' + ('' if reliable else ' (rough)') if estimate is not None else '')


def digits(value):
    return f'{value:.3g}' if abs(value) < 10 else f'{value:.4g}' if abs(value) < 1000 else f'{value:.0f}'


def cells(result, paper, why='', accurate=None):
    """ours ± error bar, its mesh, the equal-area medium mesh's value ± its bar (equal_area() of the sequence), the
    paper's value, the difference, the flag and why (where the flag is up)."""
    accurate_text = with_bar(*accurate) if accurate is not None else ''
    if result is None:
        return ['not run', '', accurate_text, str(paper) if paper is not None else 'held out', '', '', '']
    value, estimate, level, reliable = result
    ours = with_bar(value, estimate, reliable) + ('' if estimate is not None else ' (one level)')
    if paper is None:
        return [ours, level, accurate_text, 'held out', '', '', '']
    difference = 100.0 * (value / paper - 1.0)
    differs = estimate is None or abs(value - paper) > estimate
    flag = ('**more than the error bar**' if estimate is not None and differs else
            'no error bar' if estimate is None else 'within the error bar')
    return [ours, level, accurate_text, str(paper), f'{difference:+.1f} %', flag, why if differs else '']


def header(title):
    return [f'### {title}\n', '| case | quantity | ours ± error bar | mesh | medium, equal area ± error bar | paper | ours − paper '
            '| difference | why (where known) |', '|---|---|---|---|---|---|---|---|---|']


def table4_rows(directory):
    """{label: curve row} of a level's Table 4 ('30', '31-', ...), empty without a peel by rotation."""
    if not rotation_curve(directory)[0]:
        return {}
    entries, _ = table4(directory)
    return {label.split()[0]: values for label, _, values, _ in entries}


def glance(results, accurate=None):
    """Markdown: the tables at a glance from results = {level: (work directory, pull-off summaries)}, with the value
    of each cell on the medium mesh with the equal-area section, ± its error bar over the equal-area sequence, beside
    it where accurate = {equal-area level: (its work directory, its summaries)} is given."""
    accurate = accurate or {}
    accurate_table4 = {level: table4_rows(directory) for level, (directory, _) in accurate.items()}

    def accurate_value(scene, key):
        return equal_area({level: s[scene][key] for level, (_, s) in accurate.items() if scene in s})

    def accurate_table4_value(label, column):
        return equal_area({level: rows[label][column] for level, rows in accurate_table4.items() if label in rows})

    lines = []
    table4_by_level = {}
    for level, (directory, _) in results.items():
        rows = table4_rows(directory)
        if rows:
            table4_by_level[level] = rows
    if table4_by_level:
        lines += header('Table 4: peeling by rotation (energies / Π_c0)')
        for label, key in TABLE4_ROWS:
            for index, (column, name) in enumerate(TABLE4_QUANTITIES):
                by_level = {level: rows[label][column] for level, rows in table4_by_level.items() if label in rows}
                lines.append(f'| θ_y = {TABLE4_CASES.get(label, label + "°")} | {name} | ' + ' | '.join(
                    cells(best(by_level), PAPER_TABLE4[key][index], reason('table4', label, name),
                          accurate_table4_value(label, column))) + ' |')
        lines.append('')
    summaries = {level: summary for level, (_, summary) in results.items()}
    lines += header('Table 5: the work before the lift, Π_ext,0 / Π_c0')
    for t in PULL_OFF_ANGLES:
        by_level = {level: s[f'pull-off-{t}']['Pi_ext0_per_Pi_c0'] for level, s in summaries.items()
                    if f'pull-off-{t}' in s}
        lines.append(f'| {t}° | Π_ext,0 | ' + ' | '.join(
            cells(best(by_level), PAPER_TABLE5_START[t], reason('table5', str(t), 'Π_ext,0'),
                  accurate_value(f'pull-off-{t}', 'Pi_ext0_per_Pi_c0'))) + ' |')
    lines.append('')
    lines += header('Table 6: pull-off at fixed inclination')
    for t in PULL_OFF_ANGLES:
        for key, name, index in TABLE6_QUANTITIES:
            by_level = {level: s[f'pull-off-{t}'][key] for level, s in summaries.items() if f'pull-off-{t}' in s}
            lines.append(f'| {t}° | {name} | ' + ' | '.join(
                cells(best(by_level), PAPER_TABLE6[t][index], reason('table6', str(t), name),
                      accurate_value(f'pull-off-{t}', key))) + ' |')
    lines.append('')
    for title, prefix in SWEEPS:
        factors = sorted({float(scene.split('-')[-1]) for s in summaries.values() for scene in s
                          if scene.startswith(prefix)} | {1.0})
        lines += header(title + ' (the paper\'s values are held out)')
        for factor in factors:
            scene = 'pull-off-60' if factor == 1.0 else f'{prefix}-{factor:g}'
            for key, name, _ in TABLE6_QUANTITIES:
                by_level = {level: s[scene][key] for level, s in summaries.items() if scene in s}
                lines.append(f'| × {factor:g} | {name} | ' + ' | '.join(
                    cells(best(by_level), None, '', accurate_value(scene, key))) + ' |')
        lines.append('')
    return '\n'.join(lines)
