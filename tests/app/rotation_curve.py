#!/usr/bin/env python3
"""The study tables' peel by rotation for Table 4 (scripts/study/tables.py), on manufactured curves: a peel-rotation run that restarted from a
checkpoint of the rotation before the pull-off at 60 deg (the fine level) is joined to that rotation's earlier states,
its Table 4 has the later rows and the detachment but no first instability (the joined curve starts after it), and a
peel-rotation from the undeformed state is taken as it is, with its first instability found.

    rotation_curve.py"""
import csv
import os
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
from expectations import check, finish  # noqa: E402
from study import tables as study  # noqa: E402

COLUMNS = ('step', 'stage', 'theta_y_deg', 'M_y_nNnm', 'M_y_per_ER0^3', 'Pi_ext_1e-18J', 'Pi_ext_per_Pi_c0',
           'Pi_int_per_Pi_c0', 'Pi_sa_per_Pi_c0', 'balance_error_per_Pi_c0', 'after_jump')


def state(step, stage, theta, moment, jump=0):
    """A curve row whose energies grow with theta (Pi_ext = theta / 100), moment `moment`."""
    return dict(step=step, stage=stage, theta_y_deg=theta, M_y_nNnm=moment, **{'M_y_per_ER0^3': moment / 2.0},
                **{'Pi_ext_1e-18J': 15.391 * theta}, Pi_ext_per_Pi_c0=theta / 100.0, Pi_int_per_Pi_c0=theta / 200.0,
                Pi_sa_per_Pi_c0=theta / 400.0, balance_error_per_Pi_c0=1e-4, after_jump=jump)


def write(work, scene, rows):
    os.makedirs(os.path.join(work, scene), exist_ok=True)
    with open(os.path.join(work, scene, 'curve.csv'), 'w', newline='') as out:
        writer = csv.DictWriter(out, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)


with tempfile.TemporaryDirectory() as work:
    # The pull-off at 60 deg: its rotation curve starts at 29.69 deg (a restart after the first instability).
    rotation = [state(66 + i, 'rotation', theta, 1200.0 - 10 * i)
                for i, theta in enumerate((29.69, 35.0, 45.0, 55.0, 60.0))]
    write(work, 'pull-off-60', rotation + [state(71, 'lift', 60.0, 900.0)])
    # The peel-rotation run restarted from its 60 deg checkpoint (its first row is that state, as the app writes a
    # restarted run's curve), on to detachment (a jump at 100 deg; the last state has no moment).
    peel = [state(70 + i, 'rotation', theta, 1000.0 - 5 * i)
            for i, theta in enumerate((60.0, 62.0, 75.0, 90.0, 100.0, 120.0, 127.0))]
    peel[4]['after_jump'] = 1
    peel.append(state(77, 'rotation', 128.0, 0.0, 1))
    write(work, 'peel-rotation', peel)
    peel_from_60 = peel
    rows, source = study.rotation_curve(work)
    check(source == 'pull-off-60 + peel-rotation', f'source {source}')
    thetas = [r['theta_y_deg'] for r in rows]
    check(thetas == [29.69, 35.0, 45.0, 55.0, 60.0, 62.0, 75.0, 90.0, 100.0, 120.0, 127.0, 128.0],
          f'joined curve: {thetas} (the earlier states up to the restart, then the run)')
    entries, _ = study.table4(work)
    labels = [label for label, _, _, _ in entries]
    check(labels == ['30', '60', '90', '120', '128 (last state before detachment)'], f'Table 4 rows: {labels}')
    at_30 = entries[0][2]['Pi_ext_per_Pi_c0']
    check(abs(at_30 - 0.30) < 1e-12, f'Pi_ext at 30 deg: {at_30}')
    check(abs(entries[1][2]['Pi_ext_per_Pi_c0'] - 0.60) < 1e-12, 'Pi_ext at 60 deg (interpolated across the join)')
    check(entries[-1][1] == 127.0, f'last state before detachment at {entries[-1][1]}')

with tempfile.TemporaryDirectory() as work:
    # A peel-rotation from the undeformed state (step 0): taken as it is, and its first instability is found (the
    # first jump after which the moment fell by more than 10 %).
    peel = [state(i, 'rotation', theta, m) for i, (theta, m) in
            enumerate(((4.9, 0.0), (20.0, 800.0), (31.0, 1300.0), (31.5, 900.0), (60.0, 1000.0), (90.0, 900.0)))]
    peel[3]['after_jump'] = 1
    write(work, 'peel-rotation', peel)
    write(work, 'pull-off-60', rotation + [state(71, 'lift', 60.0, 900.0)])
    rows, source = study.rotation_curve(work)
    check(source == 'peel-rotation' and len(rows) == len(peel), f'source {source}, {len(rows)} rows')
    labels = [label for label, _, _, _ in study.table4(work)[0]]
    check(labels[1:3] == ['31- (before the first drop)', '31+ (after it)'], f'first instability rows: {labels}')

with tempfile.TemporaryDirectory() as work:
    # The fine level: the earlier rotation from 60 deg kept as EARLIER_ROTATION is joined as before while the study's
    # own peel-rotation from the undeformed state has only stopped (its curve in peel-rotation.incomplete/) ...
    write(work, 'pull-off-60', rotation + [state(71, 'lift', 60.0, 900.0)])
    write(work, study.EARLIER_ROTATION, peel_from_60)
    own = [state(i, 'rotation', theta, m) for i, (theta, m) in
           enumerate(((4.9, 0.0), (20.0, 800.0), (31.0, 1300.0), (31.5, 900.0), (50.0, 1000.0)))]
    own[3]['after_jump'] = 1
    write(work, 'peel-rotation.incomplete', own)
    rows, source = study.rotation_curve(work)
    check(study.rotation_run(work) == study.EARLIER_ROTATION and source == 'pull-off-60 + peel-rotation'
          and rows[-1]['theta_y_deg'] == 128.0, f'with the own run stopped: {study.rotation_run(work)}, {source}')
    # ... and the own run is taken once complete.
    write(work, 'peel-rotation', own + [state(5, 'rotation', 140.0, 0.0, 1)])
    rows, source = study.rotation_curve(work)
    check(study.rotation_run(work) == 'peel-rotation' and source == 'peel-rotation' and rows[0]['theta_y_deg'] == 4.9,
          f'with the own run complete: {study.rotation_run(work)}, {source}')

finish('rotation_curve: joined at a restart, first instability only in a curve from the undeformed state, the '
       "study's own rotation preferred once complete")
