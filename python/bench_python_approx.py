"""The cost of a Python approximator inside the Rust walker.

Runs one bench selection three times into fresh directories, on one thread: the built-in
``lwpr``; a factory returning ``steplearn.Lwpr`` with the same settings (taken over as the
Rust model: no Python call per tick); and the same model behind a Python object (every
``predict`` and ``update`` goes through Python, and the learner's trial copies through
``copy.deepcopy``). The three give the same leaderboard rows; the difference in time over the
number of Python calls is the cost per call.

    python python/bench_python_approx.py [--experiment stability] [--scale 0.1] [--seeds 2]
"""

import argparse
import copy
import tempfile
import time

import numpy as np

import steplearn

CALLS = {"predict": 0, "update": 0, "deepcopy": 0}


def lwpr(b):
    half = list((np.asarray(b.hi) - np.asarray(b.lo)) / 2)
    return steplearn.Lwpr(3, 1, norm_in=half, init_d=10.0)


class Wrapped:
    n_out = 1

    def __init__(self, model):
        self.model = model

    def predict(self, x):
        CALLS["predict"] += 1
        return self.model.predict(x)

    def update(self, x, y):
        CALLS["update"] += 1
        self.model.update(x, y)

    def __deepcopy__(self, memo):
        CALLS["deepcopy"] += 1
        return Wrapped(copy.copy(self.model))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--experiment", default="stability")
    p.add_argument("--scale", type=float, default=0.1)
    p.add_argument("--seeds", type=int, default=2)
    p.add_argument("--reps", type=int, default=3)
    a = p.parse_args()
    reg = (
        steplearn.Registry.builtin()
        .approximator("native-lwpr", lwpr)
        .approximator("python-lwpr", lambda b: Wrapped(lwpr(b)))
    )
    times = {k: [] for k in ["lwpr", "native-lwpr", "python-lwpr"]}
    rows = {}
    calls = None
    for _ in range(a.reps):
        for name in times:
            for k in CALLS:
                CALLS[k] = 0
            with tempfile.TemporaryDirectory() as out:
                bench = (
                    steplearn.Bench(reg).approximators([name]).rules(["pendulum-cart"])
                    .experiments([a.experiment]).seeds(a.seeds).scale(a.scale).threads(1).out(out)
                )
                t = time.perf_counter()
                r = bench.run()
                times[name].append(time.perf_counter() - t)
            rows[name] = [(x["headline"], x["vs_model"]) for x in r]
            if name == "python-lwpr":
                calls = dict(CALLS)
    same = rows["lwpr"] == rows["native-lwpr"] == rows["python-lwpr"]
    print(f"{a.experiment}, scale {a.scale}, {a.seeds} seeds, 1 thread, median of {a.reps}:")
    med = {k: float(np.median(v)) for k, v in times.items()}
    for k, v in med.items():
        print(f"  {k:12s} {v:8.3f} s")
    n = calls["predict"] + calls["update"] + calls["deepcopy"]
    print(f"  Python calls of python-lwpr: {calls} ({n} in all)")
    print(f"  cost per Python call: {(med['python-lwpr'] - med['lwpr']) / n * 1e6:.2f} us")
    print(f"  rows identical across the three: {same}")


if __name__ == "__main__":
    main()
