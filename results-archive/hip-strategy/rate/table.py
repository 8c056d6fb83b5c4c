#!/usr/bin/env python3
"""Prints the model I50 table (Markdown) from the run outputs in this folder."""
import glob, os, re, statistics, sys
# "model" (default) or "learned step-x"
WHICH = re.escape(sys.argv[1] if len(sys.argv) > 1 else "model")
here = os.path.dirname(os.path.abspath(__file__))
runs = {}
for f in glob.glob(os.path.join(here, "*_s*_*.txt")):
    m = re.match(r"(.+)_s(\d+)_(forward|backward)\.txt$", os.path.basename(f))
    i50 = re.search(r"^" + WHICH + r": I50 ([\d.]+) Ns", open(f).read(), re.M)
    if m and i50:
        runs[(m[1], int(m[2]), m[3])] = float(i50[1])
settings = sorted({k[0] for k in runs}, key=lambda s: (s != "base", s))
cols = sorted({(k[1], k[2]) for k in runs}, key=lambda c: (c[0], c[1] != "forward"))
print("| setting | " + " | ".join(f"s{s} {d[:3]}" for s, d in cols) + " | mean | vs base (same runs) |")
print("|---" * (len(cols) + 3) + "|")
for s in settings:
    vals = [runs.get((s, *c)) for c in cols]
    have = [c for c in cols if (s, *c) in runs and ("base", *c) in runs]
    mean = statistics.mean(runs[(s, *c)] for c in have) if have else float("nan")
    base = statistics.mean(runs[("base", *c)] for c in have) if have else float("nan")
    cells = " | ".join("" if v is None else f"{v:.2f}" for v in vals)
    print(f"| {s} | {cells} | {mean:.2f} | {mean / base:.3f} ({len(have)} runs) |")
