#!/usr/bin/env python3
"""Summaries of the offset oracle's CSVs (offset_oracle's per-run rows).

python3 oracle.py union FILE...          oracle over the pairs of several files (same cases)
python3 oracle.py reflex TRAIN JUDGE     a reflex choosing its pair by the push's gait phase and
                                         impulse (bins: none, one or both, 2 or 3 each), chosen
                                         on TRAIN's cases, judged on JUDGE's

I50: maximum-likelihood logistic fit of fell ~ impulse, -a/b (as the library's, without its
fallbacks: every file here has falls and survivals over its range).
"""
import csv
import math
import sys
from collections import defaultdict


def rows(path):
    with open(path) as f:
        lines = []
        for line in f:
            if not line.strip():
                break
            lines.append(line)
    return list(csv.DictReader(lines))


def i50(samples):
    """samples: [(impulse, fell)] -> -a/b of the logistic fit P(fall) = 1/(1+exp(-(a+b j)))."""
    a, b = 0.0, 0.0
    mean_j = sum(j for j, _ in samples) / len(samples)
    for _ in range(100):
        ga = gb = haa = hab = hbb = 0.0
        for j, y in samples:
            x = j - mean_j
            p = 1.0 / (1.0 + math.exp(-(a + b * x)))
            ga += y - p
            gb += (y - p) * x
            w = p * (1 - p)
            haa += w
            hab += w * x
            hbb += w * x * x
        det = haa * hbb - hab * hab
        da = (hbb * ga - hab * gb) / det
        db = (haa * gb - hab * ga) / det
        a += da
        b += db
        if abs(da) + abs(db) < 1e-12:
            break
    return mean_j - a / b


def table(path):
    """case -> (impulse, phase, {(walker, dx, dt): fell})"""
    cases = {}
    for r in rows(path):
        c = int(r["case"])
        entry = cases.setdefault(c, [float(r["impulse_ns"]), float(r.get("phase_s") or "nan"), {}])
        entry[2][(r["walker"], float(r["dx"]), float(r["dt"]))] = r["fell"] == "1"
    return cases


def union(paths):
    tables = [table(p) for p in paths]
    cases = sorted(tables[0])
    model = [(tables[0][c][0], tables[0][c][2][("model", 0.0, 0.0)]) for c in cases]
    m = i50(model)
    print(f"model I50 {m:.3f} Ns (python fit), {sum(f for _, f in model)} falls of {len(cases)}")
    env = []
    for c in cases:
        fell = all(
            f for t in tables for (w, _, _), f in t[c][2].items() if w in ("model", "pair")
        )
        env.append((tables[0][c][0], fell))
    o = i50(env)
    print(f"oracle over {len(paths)} files: I50 {o:.3f} Ns, {o / m:.4f} x model, "
          f"{sum(f for _, f in env)} falls")


def bins(impulse, phase, i50_model, phase_edges, impulse_edges):
    r = impulse / i50_model
    pb = sum(phase >= e for e in phase_edges)
    ib = sum(r >= e for e in impulse_edges)
    return pb, ib


def reflex(train_path, judge_path, phase_edges=(0.15, 0.3), impulse_edges=(0.9, 1.1)):
    train, judge = table(train_path), table(judge_path)
    m_train = i50([(v[0], v[2][("model", 0.0, 0.0)]) for v in train.values()])
    pairs = sorted(k for k in next(iter(train.values()))[2] if k[0] in ("model", "pair"))
    # Per bin, survivals of each pair on the training cases; the model wins ties.
    score = defaultdict(lambda: defaultdict(int))
    for v in train.values():
        b = bins(v[0], v[1], m_train, phase_edges, impulse_edges)
        for p in pairs:
            score[b][p] += not v[2][p]
    choice = {}
    for b, s in score.items():
        best = max(s.values())
        model = ("model", 0.0, 0.0)
        choice[b] = model if s[model] == best else max(s, key=lambda p: s[p])
    model_j, reflex_j = [], []
    for v in judge.values():
        b = bins(v[0], v[1], m_train, phase_edges, impulse_edges)
        p = choice.get(b, ("model", 0.0, 0.0))
        model_j.append((v[0], v[2][("model", 0.0, 0.0)]))
        reflex_j.append((v[0], v[2][p]))
    m, r = i50(model_j), i50(reflex_j)
    print(f"bins phase {phase_edges} s, impulse {impulse_edges} x model I50 {m_train:.2f} Ns")
    for b in sorted(choice):
        print(f"  bin {b}: {choice[b][1]:+} m, {choice[b][2]:+} s "
              f"({score[b][choice[b]]} of {sum(1 for v in train.values() if bins(v[0], v[1], m_train, phase_edges, impulse_edges) == b)} survived)")
    print(f"judged: model I50 {m:.3f} Ns, reflex {r:.3f} Ns, {r / m:.4f} x model "
          f"({sum(f for _, f in model_j)} and {sum(f for _, f in reflex_j)} falls)")


if __name__ == "__main__":
    if sys.argv[1] == "union":
        union(sys.argv[2:])
    elif sys.argv[1] == "reflex":
        for phase_edges, impulse_edges in [((), ()), ((), (1.0,)), ((0.2,), ()), ((0.2,), (1.0,)),
                                           ((0.15, 0.3), (0.9, 1.1))]:
            reflex(sys.argv[2], sys.argv[3], phase_edges, impulse_edges)
    else:
        sys.exit(__doc__)
