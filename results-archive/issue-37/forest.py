#!/usr/bin/env python3
"""Every walker judged in experiment C on seeds 5-9 (which chose nothing) for issue 37: its I50
over the model's in the same run, mean over the seeds and 95% Student-t interval, pushed forward
and backward, against the issue's 1.15 mark. Reads the stored runs (summary.json) of the archive
directories named below; writes levers.csv and forest.svg (plain SVG, no fonts needed).
Run: python3 forest.py (from anywhere)."""
import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ARCHIVE = os.path.dirname(HERE)
sys.path.insert(0, ARCHIVE)
from paired import mean_h, ratio, summary  # noqa: E402

SEEDS = range(5, 10)
MARK = 1.15


def simple(pattern):
    """Runs named by `pattern` with {dir} and {s} (a directory under results-archive)."""
    return lambda d: [pattern.format(dir=d, s=s) for s in SEEDS]


def bench(approx, learn, dirs):
    """A bench's runs, in `dirs[direction]` (a directory under results-archive)."""
    return lambda d: [f"{dirs[d]}/stability__{approx}__pendulum-cart__s{s}__{learn}" for s in SEEDS]


HEEL = {"backward": "leaderboard-heel", "forward": "leaderboard-heel/forward"}
ALONE = {"backward": "leaderboard-heel/without", "forward": "leaderboard-heel/forward/without"}
GATED = {"backward": "leaderboard-heel/gated/backward", "forward": "leaderboard-heel/gated/forward"}
XT, XTA = "step-x+step-time", "step-x+step-time+ankle-pitch"

# (group, label, runs by direction)
WALKERS = [
    ("step-x,step-time", "LWPR (the default learner)", simple("judge-sets-landing/C-step-x,step-time-{dir}-s{s}")),
    ("step-x,step-time", "RBF", bench("rbf", XT, ALONE)),
    ("step-x,step-time", "grid", bench("grid", XT, ALONE)),
    ("step-x,step-time", "kernel ridge", bench("kernel-ridge", XT, ALONE)),
    ("step-x,step-time", "LWPR, dF clamped to 5 cm", simple("learner-levers/C-maxoff0.05-{dir}-s{s}")),
    ("step-x,step-time", "LWPR, ankle strategy (gain 1) for both walkers", simple("ankle-strategy/C-a1-{dir}-s{s}")),
    ("step-x,step-y,step-time", "LWPR", simple("judge-sets-landing/C-step-x,step-y,step-time-{dir}-s{s}")),
    ("step-x,step-time,ankle-pitch", "LWPR, toe and heel", simple("ankle-pitch/C-v1-{dir}-s{s}")),
    ("step-x,step-time,ankle-pitch", "LWPR, heel alone (configs/heel_pitch.toml)", simple("ankle-pitch/C-h2-{dir}-s{s}")),
    ("step-x,step-time,ankle-pitch", "RBF, heel alone", bench("rbf", XTA, HEEL)),
    ("step-x,step-time,ankle-pitch", "grid, heel alone", bench("grid", XTA, HEEL)),
    ("step-x,step-time,ankle-pitch", "kernel ridge, heel alone", bench("kernel-ridge", XTA, HEEL)),
    ("step-x,step-time,ankle-pitch", "LWPR, heel gated by the fall", simple("ankle-pitch/C-hg-{dir}-s{s}")),
    ("step-x,step-time,ankle-pitch", "RBF, heel gated by the fall", bench("rbf", XTA, GATED)),
    ("step-x,step-time,ankle-pitch", "grid, heel gated by the fall", bench("grid", XTA, GATED)),
]


def ratios(runs):
    return [ratio(summary(os.path.join(ARCHIVE, d))) for d in runs]


rows = []
for group, label, runs in WALKERS:
    row = {"set": group, "walker": label}
    for d in ["forward", "backward"]:
        m, h = mean_h(ratios(runs(d)))
        row[f"{d}_mean"], row[f"{d}_low"], row[f"{d}_high"] = round(m, 3), round(m - h, 3), round(m + h, 3)
    rows.append(row)

with open(os.path.join(HERE, "levers.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)

# The forest plot: one row per walker, forward and backward panels side by side.
LABEL_W, PANEL_W, ROW_H, TOP, GAP = 430, 300, 22, 60, 30
LO, HI = 0.7, 1.45
height = TOP + ROW_H * len(rows) + 45
width = LABEL_W + 2 * PANEL_W + GAP + 20


def x_of(panel, v):
    x0 = LABEL_W + panel * (PANEL_W + GAP)
    return x0 + (min(max(v, LO), HI) - LO) / (HI - LO) * PANEL_W


svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
       f'font-family="sans-serif" font-size="12">',
       f'<rect width="{width}" height="{height}" fill="white"/>',
       f'<text x="10" y="20" font-size="14">Experiment C, seeds 5-9: learned / model I50 '
       f'(mean, 95% interval), the issue\'s mark {MARK}</text>']
for panel, d in enumerate(["forward", "backward"]):
    x0 = LABEL_W + panel * (PANEL_W + GAP)
    svg.append(f'<text x="{x0 + PANEL_W / 2}" y="45" text-anchor="middle" font-size="13">pushed {d}</text>')
    for t in [0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4]:
        x = x_of(panel, t)
        colour = "#444" if t == 1.0 else "#ddd"
        svg.append(f'<line x1="{x:.1f}" y1="{TOP - 5}" x2="{x:.1f}" y2="{TOP + ROW_H * len(rows)}" stroke="{colour}"/>')
        svg.append(f'<text x="{x:.1f}" y="{TOP + ROW_H * len(rows) + 16}" text-anchor="middle">{t:.1f}</text>')
    xm = x_of(panel, MARK)
    svg.append(f'<line x1="{xm:.1f}" y1="{TOP - 5}" x2="{xm:.1f}" y2="{TOP + ROW_H * len(rows)}" '
               f'stroke="#c00" stroke-dasharray="4,3"/>')
    for i, r in enumerate(rows):
        y = TOP + ROW_H * i + ROW_H / 2
        lo, m, hi = r[f"{d}_low"], r[f"{d}_mean"], r[f"{d}_high"]
        colour = "#0a6" if lo > 1.0 else "#c60" if hi < 1.0 else "#246"
        svg.append(f'<line x1="{x_of(panel, lo):.1f}" y1="{y:.1f}" x2="{x_of(panel, hi):.1f}" y2="{y:.1f}" '
                   f'stroke="{colour}" stroke-width="2"/>')
        svg.append(f'<circle cx="{x_of(panel, m):.1f}" cy="{y:.1f}" r="4" fill="{colour}"/>')
for i, r in enumerate(rows):
    y = TOP + ROW_H * i + ROW_H / 2 + 4
    svg.append(f'<text x="10" y="{y:.1f}">{r["set"]}: {r["walker"]}</text>')
svg.append(f'<text x="10" y="{height - 12}" font-size="11">green: better than the model on its interval; '
           f'orange: worse; blue: level. Red dashes: the mark. Axis clipped to [{LO}, {HI}].</text>')
svg.append("</svg>")
with open(os.path.join(HERE, "forest.svg"), "w") as f:
    f.write("\n".join(svg) + "\n")
for r in rows:
    print(f"{r['set']}: {r['walker']}: forward {r['forward_mean']} [{r['forward_low']}, {r['forward_high']}], "
          f"backward {r['backward_mean']} [{r['backward_low']}, {r['backward_high']}]")
