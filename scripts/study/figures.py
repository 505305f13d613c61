"""The study figures: the paper's Figs. 6, 8, 9 and 10 from the runs (matplotlib), and the field pictures
(ParaView, headless)."""
import os
import shutil
import subprocess

from convergence import LEVELS
from curves import read_curve
from study.runs import complete, started
from study.tables import PAPER_TABLE4, STICTION_RUNS, rotation_curve

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def plots(results, directory):
    """Figures 6, 8, 9 and 10 from results = {level: (work directory, summaries)}; returns (file, caption) pairs."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    pictures = []
    finest_first = [level for level in reversed(LEVELS) if level in results]
    peels = [(level, rotation_curve(results[level][0])) for level in finest_first]
    peels = [(level, rows) for level, (rows, source) in peels if rows and source != 'pull-off-60']
    if peels:
        fig, (axis, energy) = plt.subplots(1, 2, figsize=(12, 4.2))
        for index, (level, rows) in enumerate(peels):
            style = '-' if index == 0 else '--'
            theta = [r['theta_y_deg'] for r in rows]
            axis.plot(theta, [r['M_y_per_ER0^3'] for r in rows], style, linewidth=1, label=f'{level} mesh')
            for key, label, colour, column in (('Pi_ext_per_Pi_c0', 'Pi_ext', 'tab:blue', 0),
                                               ('Pi_int_per_Pi_c0', 'Pi_int', 'tab:orange', 1),
                                               ('Pi_sa_per_Pi_c0', 'Pi_sa', 'tab:green', 2)):
                energy.plot(theta, [r[key] for r in rows], style, color=colour, linewidth=1,
                            label=f'{label} (ours, {level})')
                if index == 0:
                    paper = [(31.0 if k in ('31-', '31+') else k, v[column]) for k, v in PAPER_TABLE4.items()]
                    energy.plot([a for a, _ in paper], [v for _, v in paper], 'o', color=colour, markerfacecolor='none',
                                label=label + ' (paper, Table 4)')
        axis.set_xlabel('theta_y [deg]')
        axis.set_ylabel('M_y / (E R0^3)')
        axis.set_title('Moment (cf. paper Fig. 6)')
        axis.legend()
        axis.grid(alpha=0.3)
        energy.set_xlabel('theta_y [deg]')
        energy.set_ylabel('energy / Pi_c0')
        energy.set_title('Energies (cf. paper Table 4)')
        energy.legend(fontsize=7)
        energy.grid(alpha=0.3)
        fig.tight_layout()
        name = 'validation-fig6-moment.png'
        fig.savefig(os.path.join(directory, name), dpi=110)
        pictures.append((name, 'Peeling by rotation: moment and energies against inclination (cf. paper Fig. 6, Table 4)'))
    for level in finest_first:
        rough = [(z0, read_curve(results[level][0], f'rough-z0-{z0}'), complete(results[level][0], f'rough-z0-{z0}'))
                 for z0 in (0, 4, 8) if started(results[level][0], f'rough-z0-{z0}')]
        if not rough:
            continue
        fig, axis = plt.subplots(figsize=(7, 4))
        for z0, rows, done in rough:
            axis.plot([r['theta_y_deg'] for r in rows], [r['M_y_nNnm'] for r in rows], '.-', markersize=2,
                      label=f'z0 = {z0} nm' + ('' if done else ' (not finished)'))
        axis.set_xlabel('theta_y [deg]')
        axis.set_ylabel('M_y [nN nm]')
        title = f'Rough substrates, h = 20 nm, lambda = 100 nm (cf. paper Fig. 14), {level} mesh'
        axis.set_title(title, fontsize=10)
        axis.legend()
        axis.grid(alpha=0.3)
        fig.tight_layout()
        name = 'validation-fig14-rough-moment.png'
        fig.savefig(os.path.join(directory, name), dpi=110)
        pictures.append((name, 'Moment against inclination on rough substrates: ' + title))
        break
    groups = (('validation-fig8-pull-off.png', 'Pull-off at fixed inclination (cf. paper Fig. 8)',
               [(f'pull-off-{t}', f'{t} deg') for t in (45, 60, 75, 90)]),
              ('validation-fig9-stiction.png', 'Stiction vs frictionless at 60 deg (cf. paper Fig. 9)',
               [(scene, label) for scene, label, _ in STICTION_RUNS]),
              ('validation-fig10-gamma-W.png', 'gamma_W / gamma_W0 at 60 deg (cf. paper Fig. 10, left)',
               [('gamma-W-0.667', '1.5^-1'), ('pull-off-60', '1'), ('gamma-W-1.5', '1.5'), ('gamma-W-2.25', '1.5^2')]),
              ('validation-fig10-gamma-L.png', 'gamma_L / gamma_L0 at 60 deg (cf. paper Fig. 10, right)',
               [('gamma-L-0.444', '1.5^-2'), ('gamma-L-0.667', '1.5^-1'), ('pull-off-60', '1'), ('gamma-L-1.5', '1.5')]))
    for name, title, curves in groups:
        # The finest level that has the most of the group's curves.
        counts = [(sum(s in results[level][1] for s, _ in curves), level) for level in finest_first]
        count, level = max(counts, key=lambda c: c[0]) if counts else (0, None)
        if count < 1 or (count < 2 and len(curves) > 1 and name != 'validation-fig8-pull-off.png'):
            continue
        # The finer levels' runs of the same scenes, dashed in their curve's colour (there are fewer of them).
        finer = [other for other in finest_first[:finest_first.index(level)]
                 if any(s in results[other][1] for s, _ in curves)]
        fig, axis = plt.subplots(figsize=(7, 4))
        for scene, label in curves:
            colour = None
            for drawn, style in [(level, '.-')] + [(other, '--') for other in finer]:
                if scene in results[drawn][1]:
                    rows = results[drawn][1][scene]['rows']
                    line, = axis.plot([r['u_z_nm'] for r in rows], [r['P_z_nN'] for r in rows], style, markersize=2,
                                      linewidth=1, color=colour, label=label if drawn == level else f'{label}, {drawn}')
                    colour = line.get_color()
        axis.set_xlabel('u_z of the end face centre from the undeformed state [nm]')
        axis.set_ylabel('P_z [nN]')
        level_names = f'{level} mesh' + ''.join(f', {other} mesh dashed' for other in finer)
        axis.set_title(f'{title}, {level_names}', fontsize=10)
        axis.legend()
        axis.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(directory, name), dpi=110)
        pictures.append((name, f'{title}, {level_names}'))
    return pictures


# Field pictures (ParaView, headless): scene, states' load parameters, file name, caption.
FIELD_PICTURES = (
    ('peel-rotation', (30, 33, 60, 90, 120), 'validation-fig5-peel-states.png',
     'Peeling by rotation (cf. paper Figs. 5 and 7): deformed states near the given theta_y, side view and the pad from '
     'below, coloured by I1 = tr(sigma)/E (fields are written every 10 steps: the states nearest to the angles)'),
    ('pull-off-60', (), 'validation-fig7-pull-off-60-states.png',
     'Pull-off at 60 deg (cf. paper Fig. 7): states over the lift (load parameter u_z [nm])'),
    ('rough-z0-0', (45,), 'validation-fig14-rough-z0-0.png', 'Flat substrate through the rough-substrate code (z0 = 0), 45 deg'),
    ('rough-z0-4', (45,), 'validation-fig14-rough-z0-4.png', 'Rough substrate z0 = 4 nm, 45 deg (cf. paper Fig. 14)'),
    ('rough-z0-8', (45,), 'validation-fig14-rough-z0-8.png', 'Rough substrate z0 = 8 nm, 45 deg (cf. paper Fig. 14)'),
)


def field_pictures(works, directory, pictures=FIELD_PICTURES):
    """Renders `pictures` (scene, times, file, caption[, field]) from the finest level among `works` (finest first)
    whose run wrote fields; returns (file, caption) pairs. `times` may be a function of the run's directory (the states
    to draw, from its curve); `field` colours by that cell field instead of I1. A picture no run can render now (runs
    restored from results keep no fields) keeps its earlier rendering in `directory`, if there is one, so that
    documenting from the archive loses no figure."""
    renderer = shutil.which('pvbatch') and shutil.which('xvfb-run')
    if not renderer:
        print('pvbatch/xvfb-run not installed: field pictures not rendered (earlier renderings are kept)')
    out = []
    for scene, times, name, caption, *field in pictures:
        candidates = ((os.path.join(work, scene + suffix, 'mesh_states.xmf'), caption + note) for work in works
                      for suffix, note in (('', ''), ('.incomplete', ' (the run did not finish: its last written state)')))
        found = next(((states, text) for states, text in candidates if os.path.exists(states)), None)
        if found and renderer:
            wanted = times(os.path.dirname(found[0])) if callable(times) else times
            command = ['bash', os.path.join(ROOT, 'scripts', 'render.sh'),
                       os.path.join(ROOT, 'scripts', 'render_states.py'), found[0], os.path.join(directory, name),
                       '--bottom'] + (['--field', field[0]] if field else []) + [str(t) for t in wanted]
            if subprocess.call(command) == 0:
                out.append((name, found[1]))
                continue
        if os.path.exists(os.path.join(directory, name)):
            out.append((name, caption + ' (rendered from an earlier run of this scene)'))
    return out
