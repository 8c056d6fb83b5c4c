"""Shared by the archive's table scripts: the mean of per-seed values with its Student-t 95%
interval, and a run's summary. `sys.path.insert(0, "..")` from a directory here, then
`from paired import interval, summary, i50, ratio` (or `mean_h`, `t975` for other formats)."""
import json
import math
import os

# Two-sided 97.5% quantiles of Student's t by degrees of freedom.
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306,
        9: 2.262, 10: 2.228, 11: 2.201, 12: 2.179, 13: 2.160, 14: 2.145, 15: 2.131,
        16: 2.120, 17: 2.110, 18: 2.101, 19: 2.093}


def t975(df):
    """The 97.5% quantile of Student's t with `df` degrees of freedom (1 to 19)."""
    return T975[df]


def mean_h(xs):
    """The mean over `xs` and the half-width of its 95% interval (nan for one value)."""
    n = len(xs)
    m = sum(xs) / n
    if n < 2:
        return m, math.nan
    sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1))
    return m, t975(n - 1) * sd / math.sqrt(n)


def interval(xs):
    """`mean [low, high]`, the 95% interval of the mean over `xs` (just the mean for one)."""
    m, h = mean_h(xs)
    if len(xs) < 2:
        return f"{m:.3f}"
    return f"{m:.3f} [{m - h:.3f}, {m + h:.3f}]"


def summary(path):
    """The run's summary.json."""
    with open(os.path.join(path, "summary.json")) as f:
        return json.load(f)


def i50(s, walker):
    """`walker`'s I50 (Ns) in the summary `s`."""
    return s["controllers"][walker]["impulse_at_50pct_fall_ns"]


def ratio(s):
    """The learned walker's I50 over the model's in the summary `s` (the same run's pushes)."""
    return i50(s, "learned") / i50(s, "model")
