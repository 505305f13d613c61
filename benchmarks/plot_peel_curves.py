"""Plots peel_curves' CSV: F/b against the pull for Q1C1 and Q1C2, with the energy-balance value.
usage: plot_peel_curves.py <curves.csv> <energy balance F/b> <title> <picture.png>"""
import csv
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
balance, title, picture = float(sys.argv[2]), sys.argv[3], sys.argv[4]
fig, axis = plt.subplots(figsize=(8, 4.5))
for name, style in (('Q1C1', 'tab:red'), ('Q1C2', 'tab:blue')):
    x = [float(r['pull_nm']) for r in rows if r['enrichment'] == name]
    y = [float(r['force_per_width_nN_per_nm']) for r in rows if r['enrichment'] == name]
    axis.plot(x, y, '.-', color=style, markersize=3, linewidth=0.8, label=name)
axis.axhline(balance, color='black', linestyle='--', label='energy balance (Kendall)')
axis.set_ylim(0, 3 * balance)
axis.set_xlabel('pull along the peel direction [nm]')
axis.set_ylabel('peel force per width F/b [nN/nm]')
axis.set_title(title)
axis.legend()
fig.tight_layout()
fig.savefig(picture, dpi=110)
