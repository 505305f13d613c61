"""The study scenes: which scenes each study runs and at which mesh level, the command line's --set overrides applied
to them, and the scene file a run reads."""
import argparse
import functools
import os
import re
import sys
from xml.etree import ElementTree

from convergence import LEVELS
from study import shear_scenes

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, 'xml', 'studies')

STUDIES = {
    'table4': ['peel-rotation'],
    'table6': ['peel-rotation', 'pull-off-45', 'pull-off-60', 'pull-off-75', 'pull-off-90'],
    'stiction': ['peel-rotation', 'pull-off-60', 'pull-off-60-stiction', 'pull-off-60-stiction-x-held'],
    'gamma-W': ['peel-rotation', 'pull-off-60', 'gamma-W-0.667', 'gamma-W-1.5', 'gamma-W-2.25'],
    'gamma-L': ['peel-rotation', 'pull-off-60', 'gamma-L-0.444', 'gamma-L-0.667', 'gamma-L-1.5'],
    'rough': ['rough-z0-0', 'rough-z0-4', 'rough-z0-8'],
}
# 'all': the paper's studies.
STUDIES['all'] = sorted({scene for scenes in STUDIES.values() for scene in scenes},
                        key=lambda s: (not s.startswith('peel'), s))
# Beyond the paper: the spatula pulled at angles with friction (docs/shear.md).
STUDIES['shear'] = shear_scenes.scenes()
DEPENDS = {f'pull-off-{t}': 'peel-rotation' for t in (45, 60, 75, 90, '60-stiction', '60-stiction-x-held')}
DEPENDS.update({scene: 'peel-rotation' for scene in STUDIES['shear'] if scene.startswith('shear-')})
# The mesh level each study runs on by default (None: the level written in the scene file).
STUDY_LEVEL = {'gamma-W': 'coarse', 'gamma-L': 'coarse', 'shear': 'coarse'}


# Parameters set on the command line (--set), applied to every scene file a run reads: (scene or None for every
# scene, sublist path, parameter name, value as text).
OVERRIDES = []


def parse_override(text):
    """'[SCENE:]List/Sublist/name=value' -> (scene or None, ['List', 'Sublist'], 'name', 'value')."""
    match = re.fullmatch(r'(?:([\w.-]+):)?([^=:]+)=(.*)', text)
    if not match or '/' not in match.group(2):
        raise argparse.ArgumentTypeError(f"--set '{text}': expected [SCENE:]List/.../name=value, e.g. "
                                         "'Linear Solver/lag=4' or 'peel-rotation:Loading/theta_y=90'")
    *path, name = match.group(2).split('/')
    return match.group(1), tuple(path), name, match.group(3)


def format_override(override):
    """The text parse_override reads back as `override` (a study run by the workflow gets its --set so)."""
    scene, path, name, value = override
    return (f'{scene}:' if scene else '') + '/'.join(path + (name,)) + f'={value}'


def parameter_type(value):
    """The Teuchos type a new parameter's text asks for: bool, int, double, else string."""
    if value in ('true', 'false'):
        return 'bool'
    if re.fullmatch(r'[-+]?\d+', value):
        return 'int'
    try:
        float(value)
        return 'double'
    except ValueError:
        return 'string'


def apply_overrides(text, scene, overrides):
    """The scene XML with the overrides that concern it set (an existing parameter keeps its type; a missing one,
    and the sublists on its path, are added)."""
    mine = [o for o in overrides if o[0] in (None, scene)]
    if not mine:
        return text
    root = ElementTree.fromstring(text, parser=ElementTree.XMLParser(target=ElementTree.TreeBuilder(
        insert_comments=True)))
    for _, path, name, value in mine:
        node = root
        for sublist in path:
            child = next((c for c in node.findall('ParameterList') if c.get('name') == sublist), None)
            node = child if child is not None else ElementTree.SubElement(node, 'ParameterList', name=sublist)
        parameter = next((c for c in node.findall('Parameter') if c.get('name') == name), None)
        if parameter is None:
            parameter = ElementTree.SubElement(node, 'Parameter', name=name, type=parameter_type(value))
        parameter.set('value', value)
    ElementTree.indent(root)
    return ElementTree.tostring(root, encoding='unicode') + '\n'


def scene_text(scene):
    """xml/studies/<scene>.xml with the command line's --set entries applied (as they are now: the cache is keyed
    by them, so a look-up before they were all read cannot hide them later)."""
    return overridden_scene_text(scene, tuple(OVERRIDES))


@functools.lru_cache(maxsize=None)
def overridden_scene_text(scene, overrides):
    """xml/studies/<scene>.xml, or for a scene derived from another (the shear study's grid) its base scene with the
    derived settings, then the overrides."""
    base, settings = shear_scenes.derived(scene) or (scene, [])
    text = apply_overrides(open(os.path.join(SCENES, base + '.xml')).read(), scene, settings)
    return apply_overrides(text, scene, overrides)


def scene_parameter(scene, name):
    """The value (as text) of parameter `name` in the scene (after --set), or None."""
    match = re.search(rf'name="{name}" type="\w+" value="([^"]*)"', scene_text(scene))
    return match.group(1) if match else None


def restart_angle(scene):
    """The inclination [deg] of the rotation's checkpoint a pull-off starts from."""
    return float(scene_parameter(scene, 'restart theta_y'))


def scene_level(scene):
    return scene_parameter(scene, 'level')


def planned_runs(study, forced_level):
    """(level, scene) pairs of a study, each at its study's level (or at forced_level)."""
    names = [n for n in STUDIES if n != 'all'] if study == 'all' else [study]
    runs = []
    for name in names:
        for scene in STUDIES[name]:
            level = forced_level or STUDY_LEVEL.get(name) or scene_level(scene)
            if level not in LEVELS:   # e.g. 'auto': a study tabulates and extrapolates by named levels
                sys.exit(f"run-study.py: scene {scene} has Mesh/level '{level}'; a study runs at one of "
                         f"{', '.join(LEVELS)} (use --mesh)")
            if (level, scene) not in runs:
                runs.append((level, scene))
    return sorted(runs, key=lambda r: (r[0] != 'coarse', not r[1].startswith('peel'), r[1]))


def scene_file(work, level, scene):
    """The study XML at the given mesh level, written to <work>/<scene>.xml (a pull-off reads its copy of the
    rotation's checkpoints, <scene>.restart.h5)."""
    placement = [(scene, ['Mesh'], 'level', level)]
    if scene in DEPENDS:
        placement.append((scene, ['Loading'], 'restart file', scene + '.restart.h5'))
    text = apply_overrides(scene_text(scene), scene, placement)
    path = os.path.join(work, scene + '.xml')
    open(path, 'w').write(text)
    return path
