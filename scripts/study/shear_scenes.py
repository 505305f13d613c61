"""The shear study's scenes (docs/shear.md): the pull of xml/studies/shear-pull.xml at a grid of pull angles, for each
contact law, with the end face's motion across the pull held or free. Each grid point is a scene named
shear-<law>-<held|free>-<beta>, derived from the base scene by a few parameters. The grid's beta = 90 points repeat
the paper's pull-offs at 60 deg (frictionless and stiction: Table 6, Fig. 9) as runs of their own, since those
scenes' curves do not record the force across the pull."""
import re

BASE = 'shear-pull'

# The pull angles beta [deg] of the lift direction (cos beta, 0, sin beta): 90 straight up, 180 along the substrate
# away from the pad (the angle to the substrate on the shaft's side is 180 - beta).
ANGLES = (90, 105, 120, 135, 150, 165, 180)

# Each law's settings of the base scene's Adhesion list, and the constraints across the pull it runs with (a
# frictionless pad cannot hold a free end face: nothing resists its sliding).
LAWS = {
    'frictionless': ((('Adhesion',), 'law', 'frictionless'),),
    'amontons': ((('Adhesion',), 'law', 'adhesive friction'),
                 (('Adhesion', 'Friction'), 'sliding limit', 'extended Amontons')),
    'strength': ((('Adhesion',), 'law', 'adhesive friction'),
                 (('Adhesion', 'Friction'), 'sliding limit', 'constant strength')),
    'stiction': ((('Adhesion',), 'law', 'stiction'),),
}
CONSTRAINTS = {'frictionless': ('held',), 'amontons': ('held', 'free'), 'strength': ('held', 'free'),
               'stiction': ('held', 'free')}

NAME = r'shear-(\w+)-(held|free)-(\d+)'


def scene_name(law, constraint, beta):
    return f'shear-{law}-{constraint}-{beta}'


def grid():
    """(law, constraint, beta) of every point of the study."""
    return [(law, constraint, beta) for law in LAWS for constraint in CONSTRAINTS[law] for beta in ANGLES]


def scenes():
    """The study's scenes, the rotation first."""
    return ['peel-rotation'] + [scene_name(*point) for point in grid()]


def derived(scene):
    """(base scene, settings as (scene, sublist path, name, value)) of a shear grid scene, or None."""
    match = re.fullmatch(NAME, scene)
    if not match or match.group(1) not in LAWS or match.group(2) not in CONSTRAINTS[match.group(1)]:
        return None
    law, constraint, beta = match.group(1), match.group(2), int(match.group(3))
    settings = [(scene, path, name, value) for path, name, value in LAWS[law]]
    settings += [(scene, ('Loading',), 'pull angle', str(beta)),
                 (scene, ('Loading',), 'free slide during lift', 'true' if constraint == 'free' else 'false'),
                 (scene, ('Output',), 'directory', scene)]
    return BASE, settings


def point(scene):
    """(law, constraint, beta) of a shear scene, or None."""
    match = re.fullmatch(NAME, scene)
    return (match.group(1), match.group(2), int(match.group(3))) if match and derived(scene) else None
