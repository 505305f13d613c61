"""Discretization error estimates from results on several mesh levels (Richardson extrapolation): used by the
studies' error bars (scripts/run-study.py) and checked on manufactured values by tests/app/richardson.py."""

# In-plane element size of each level relative to the coarse mesh (in-plane factors 1, 4, 8: the paper's Table 3).
ELEMENT_SIZE = {'coarse': 1.0, 'medium': 1.0 / 4.0, 'fine': 1.0 / 8.0}
LEVELS = tuple(ELEMENT_SIZE)   # coarse to fine
# Element layers through the pad of each level (packages/mesh, mesh_levels()). The fine level's 10 against 4 also
# changes the discretized geometry (a fuller shaft section: +8 % volume, docs/validation.md), so levels with different layer counts
# are not one refinement sequence in the element size alone.
LAYERS = {'coarse': 4, 'medium': 4, 'fine': 10}
# The equal-area sequence (`Mesh/section` = equal area, 4 layers throughout, one refinement sequence in the element
# size alone): the coarse mesh refined 2 x 2 and 3 x 3 in-plane (`Mesh/refinement factor`) and the medium mesh
# (the coarse one's in-plane factor 4), each kept in results/<name>/.
EQUAL_AREA_SIZE = {'coarse-x2-equal-area': 1.0 / 2.0, 'coarse-x3-equal-area': 1.0 / 3.0, 'medium-equal-area': 1.0 / 4.0}
LAYERS.update({name: 4 for name in EQUAL_AREA_SIZE})
# Where only two levels ran: the order of convergence assumed (the error benchmark observed 2.2 for P_max from k = 1,
# 2, 4, docs/error-vs-time.md).
ASSUMED_ORDER = 2.0
# Levels whose values differ by more than this factor did not follow the same kind of path (an instability moved
# between them, the coarser run detached early): no extrapolation through them is meaningful.
PATH_CHANGE = 2.0


def observed_order(values, sizes):
    """The order p of f = f* + C h^p through three levels (bisection), or None if the changes do not decrease
    monotonically (not in the asymptotic range)."""
    (f1, f2, f3), (h1, h2, h3) = values, sizes
    d12, d23 = f1 - f2, f2 - f3
    if d12 == 0.0 or d23 == 0.0 or (d12 > 0) != (d23 > 0):
        return None
    ratio = d12 / d23
    g = lambda q: (h1 ** q - h2 ** q) / (h2 ** q - h3 ** q) - ratio
    low, high = 0.05, 10.0
    if g(low) * g(high) > 0:
        return None
    for _ in range(80):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if g(low) * g(middle) > 0 else (low, middle)
    return 0.5 * (low + high)


def layers_remark(levels):
    """'; the levels differ in element layers ...' where they do, else ''."""
    layers = [LAYERS[level] for level in levels]
    if len(set(layers)) == 1:
        return ''
    return ('; the levels differ in element layers through the pad (' + ', '.join(map(str, layers)) +
            '): the estimate mixes the in-plane error with a change of the discretized geometry')


def richardson(by_level, element_size=ELEMENT_SIZE):
    """The finest value, an estimate of its discretization error, the extrapolated value and a remark (the order
    observed from three levels, or assumed with two; why the estimate is not reliable where it is not). The levels
    are those of `element_size` (the paper's by default, or EQUAL_AREA_SIZE), coarse to fine."""
    levels = [level for level in element_size if level in by_level]
    values = [by_level[level] for level in levels]
    sizes = [element_size[level] for level in levels]
    finest, next_finest = values[-1], values[-2]
    magnitudes = [abs(v) for v in values]
    path_change = (f'; **not reliable**: the levels differ by more than a factor {PATH_CHANGE:g} (a run followed '
                   'another path)') if min(magnitudes) > 0.0 and max(magnitudes) > PATH_CHANGE * min(magnitudes) else ''
    order, remark = ASSUMED_ORDER, f'order {ASSUMED_ORDER:g} assumed (two levels)'
    if len(levels) >= 3:
        order = observed_order(values[-3:], sizes[-3:])
        if order is None:
            return finest, abs(finest - next_finest), None, ('not in the asymptotic range (the changes between levels '
                                                             'do not shrink monotonically): estimate = last change'
                                                             + layers_remark(levels) + path_change)
        remark = f'order {order:.2f} observed'
    ratio = sizes[-2] / sizes[-1]
    correction = (finest - next_finest) / (ratio ** order - 1.0)
    if abs(correction) > 0.5 * abs(finest):
        remark += '; not reliable (the estimate exceeds half the value)'
    return finest, abs(correction), finest + correction, remark + layers_remark(levels) + path_change
