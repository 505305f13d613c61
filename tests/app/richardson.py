#!/usr/bin/env python3
"""The study tables' error bars (scripts/convergence.py) on manufactured values f = f* + C h^p over the levels' in-plane
element sizes (coarse 1, medium 1/4, fine 1/8): three levels recover p and f* exactly, two levels with the assumed
order 2 recover f* when p = 2, alternating changes are reported as outside the asymptotic range, and levels more than
a factor 2 apart as another path; levels with different element layers through the pad (4, 4, 10) are flagged."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scripts'))
from convergence import ELEMENT_SIZE, EQUAL_AREA_SIZE, observed_order, richardson  # noqa: E402
from expectations import check, finish  # noqa: E402


for p in (1.0, 1.5, 2.0, 3.0):
    values = {level: 42.0 - 3.0 * size ** p for level, size in ELEMENT_SIZE.items()}
    finest, estimate, extrapolated, remark = richardson(values)
    order = observed_order([values[l] for l in ELEMENT_SIZE], list(ELEMENT_SIZE.values()))
    check(abs(order - p) < 1e-6, f'observed order {order} for p = {p}')
    check(abs(extrapolated - 42.0) < 1e-9, f'extrapolated {extrapolated} for p = {p}')
    check(abs(estimate - abs(values['fine'] - 42.0)) < 1e-9, f'estimate {estimate} for p = {p}')
    check('observed' in remark, remark)
two = {level: 42.0 + 3.0 * ELEMENT_SIZE[level] ** 2 for level in ('coarse', 'medium')}
finest, estimate, extrapolated, remark = richardson(two)
check(abs(extrapolated - 42.0) < 1e-9 and 'assumed' in remark, f'two levels: {extrapolated}, {remark}')
finest, estimate, extrapolated, remark = richardson({'coarse': 11.0, 'medium': 9.0, 'fine': 10.0})
check(extrapolated is None and 'not in the asymptotic range' in remark and estimate == 1.0, f'alternating: {remark}')
finest, estimate, extrapolated, remark = richardson({'coarse': 100.0, 'medium': 10.0})
check('not reliable' in remark, f'a change larger than the value: {remark}')
finest, estimate, extrapolated, remark = richardson({'coarse': 9.0, 'medium': 94.0})
check('another path' in remark, f'levels a factor 10 apart: {remark}')
finest, estimate, extrapolated, remark = richardson({'coarse': 11.0, 'medium': 6.7})
check('not reliable' not in remark, f'levels a factor 1.6 apart: {remark}')
finest, estimate, extrapolated, remark = richardson({'coarse': 11.0, 'medium': 6.7, 'fine': 6.6})
check('layers through the pad (4, 4, 10)' in remark, f'levels with 4, 4 and 10 layers: {remark}')
check('layers' not in richardson({'coarse': 11.0, 'medium': 6.7})[3], 'coarse and medium have the same layers')
remark = richardson({'coarse': 10.98, 'medium': 190.8 / 19.08, 'fine': 9.0})[3]
check('asymptotic' in remark and 'layers through the pad' in remark, f'non-monotone with mixed layers: {remark}')
# The equal-area sequence (h = 1/2, 1/3, 1/4, one layer count): the same recovery over its own sizes.
values = {level: 42.0 - 3.0 * size ** 1.7 for level, size in EQUAL_AREA_SIZE.items()}
finest, estimate, extrapolated, remark = richardson(values, EQUAL_AREA_SIZE)
check(abs(extrapolated - 42.0) < 1e-9 and 'order 1.70 observed' in remark and 'layers' not in remark,
      f'equal-area sequence: {extrapolated}, {remark}')
check(finest == values['medium-equal-area'], 'the equal-area sequence ends at the medium mesh')
finish('richardson: manufactured values recovered')
