#!/usr/bin/env python3
"""The model's fall causes summed over the seeds: the defaults against ankle_gain 1 (C runs).
python3 falls.py > falls.txt (from this directory)."""
import collections
import json

print("The model's fall causes summed over the seeds (C, 400 pushes): defaults against ankle_gain 1")
for seeds, dfmt in [(range(5), "../learner-levers/C-default-%s-s%d"),
                    (range(5, 10), "../judge-sets-landing/C-step-x,step-time-%s-s%d")]:
    for d in ["forward", "backward"]:
        for name, fmt in [("default", dfmt), ("ankle 1", "C-a1-%s-s%d")]:
            c = collections.Counter()
            for s in seeds:
                with open((fmt % (d, s)) + "/summary.json") as f:
                    c.update(json.load(f)["fall_causes"]["model"])
            print(f"seeds {seeds[0]}-{seeds[-1]} {d} {name}:", {k: v for k, v in c.items() if v})
