"""Every refused input raises ValueError or TypeError with the Rust message and leaves the
model exactly as it was."""

import numpy as np
import pytest

import steplearn
from conftest import stream

PROBE = np.array([[0.1, -0.2], [0.5, 0.5], [-0.7, 0.3]])


def trained(make):
    m = make()
    X, Y = stream(200, seed=11)
    m.update_many(X, Y)
    return m


def snapshot(m):
    return m.to_json(), m.predict_many(PROBE).tobytes()


BAD_UPDATES = [
    # (x, y, exception, message fragment)
    ([np.nan, 0.0], [1.0], ValueError, "input x[0] is not finite (NaN)"),
    ([0.0, np.inf], [1.0], ValueError, "input x[1] is not finite (inf)"),
    ([0.0, 0.0], [-np.inf], ValueError, "target y[0] is not finite (-inf)"),
    ([0.0], [1.0], ValueError, "input x: expected length 2, got 1"),
    ([0.0, 0.0, 0.0], [1.0], ValueError, "input x: expected length 2, got 3"),
    ([0.0, 0.0], [1.0, 2.0], ValueError, "target y: expected length 1, got 2"),
    ([0.0, 0.0], [], ValueError, "target y: expected length 1, got 0"),
    ("ab", [1.0], TypeError, "x must be a 1-D sequence of numbers, got str"),
    ([0.0, "a"], [1.0], TypeError, "x must be a 1-D array or sequence"),
    (None, [1.0], TypeError, "x must be a 1-D array or sequence"),
    (np.zeros((2, 1)), [1.0], TypeError, "x must be a 1-D array, got a 2-D array"),
    ([0.0, 0.0], 1.0, TypeError, "y must be a 1-D array or sequence"),
]


@pytest.mark.parametrize("x, y, exc, msg", BAD_UPDATES)
def test_bad_update_is_refused_and_changes_nothing(make, x, y, exc, msg):
    m = trained(make)
    before = snapshot(m)
    with pytest.raises(exc, match=None) as info:
        m.update(x, y)
    assert msg in str(info.value)
    assert snapshot(m) == before


@pytest.mark.parametrize("x, exc, msg", [
    ([np.nan, 0.0], ValueError, "input x[0] is not finite (NaN)"),
    ([0.0], ValueError, "input x: expected length 2, got 1"),
    ("ab", TypeError, "got str"),
    (np.zeros((1, 2)), TypeError, "got a 2-D array"),
])
def test_bad_predict_is_refused(make, x, exc, msg):
    m = trained(make)
    with pytest.raises(exc) as info:
        m.predict(x)
    assert msg in str(info.value)


def test_lwpr_out_of_range_sample():
    m = trained(lambda: steplearn.Lwpr(2, 1))
    before = snapshot(m)
    with pytest.raises(ValueError, match=r"input x\[1\] = 10000000000000000 is beyond the model's range"):
        m.update([0.0, 1e16], [0.0])
    with pytest.raises(ValueError, match=r"target y\[0\] = 1000000000000000000000 is beyond"):
        m.update([0.0, 0.0], [1e21])
    assert snapshot(m) == before
    with pytest.raises(ValueError, match="confidence|input x"):
        m.predict_conf([0.0])


BAD_BATCHES = [
    (lambda X, Y: (X[:, :1], Y), ValueError, "X: expected 2 columns, got 1"),
    (lambda X, Y: (X, np.hstack([Y, Y])), ValueError, "Y: expected 1 columns, got 2"),
    (lambda X, Y: (X, Y[:-1]), ValueError, "Y: expected 20 rows (one per row of X), got 19"),
    (lambda X, Y: (X[0], Y), TypeError, "X must be a 2-D array (rows are samples), got a 1-D"),
    (lambda X, Y: ([[0.0, 0.0], [0.0]], Y), TypeError, "X is ragged: row 1 has 1 entries"),
    (lambda X, Y: ("abc", Y), TypeError, "X must be a 2-D sequence of numbers, got str"),
]


@pytest.mark.parametrize("change, exc, msg", BAD_BATCHES)
def test_bad_batch_shape_is_refused_and_changes_nothing(make, change, exc, msg):
    m = trained(make)
    before = snapshot(m)
    X, Y = stream(20, seed=12)
    with pytest.raises(exc) as info:
        m.update_many(*change(X, Y))
    assert msg in str(info.value)
    assert snapshot(m) == before


@pytest.mark.parametrize("where", ["X", "Y"])
def test_bad_row_is_named_and_batch_is_all_or_nothing(make, where):
    m = trained(make)
    before = snapshot(m)
    X, Y = stream(20, seed=13)
    (X if where == "X" else Y)[17, 0] = np.nan
    with pytest.raises(ValueError, match=rf"row 17: {where}\[0\] is not finite \(NaN\)"):
        m.update_many(X, Y)
    assert snapshot(m) == before
    if where == "X":
        with pytest.raises(ValueError, match=r"row 17: X\[0\] is not finite"):
            m.predict_many(X)


def test_lwpr_batch_refused_late_by_the_model_keeps_earlier_rows_out():
    # finite but out of range: only the Rust model's own check catches it, at row 15
    m = trained(lambda: steplearn.Lwpr(2, 1))
    before = snapshot(m)
    X, Y = stream(20, seed=14)
    X[15, 1] = 1e16
    with pytest.raises(ValueError, match=r"row 15: input x\[1\] = 10000000000000000 is beyond .*unchanged"):
        m.update_many(X, Y)
    assert snapshot(m) == before


UNKNOWN = [
    (lambda: steplearn.Lwpr(2, 1, w_gne=0.2), "'w_gne'"),
    (lambda: steplearn.Rbf([0], [1], [3], learning_rate=0.1), "'learning_rate'"),
    (lambda: steplearn.Grid([0], [1], [3], widths=[1.0]), "'widths'"),
    (lambda: steplearn.KernelRidge([1.0], n_in=3), "'n_in'"),
    (lambda: steplearn.Rbf([0], [1], [3], update={"Nlms": {"learning_rate": 0.1, "x": 1}}),
     "'update.x'"),
]


@pytest.mark.parametrize("build, name", UNKNOWN)
def test_unknown_setting_is_a_type_error_naming_it(build, name):
    with pytest.raises(TypeError, match="unknown setting") as info:
        build()
    assert name in str(info.value)


OUT_OF_RANGE = [
    (lambda: steplearn.Lwpr(2, 1, w_gen=1.5), "invalid configuration: w_gen must be in (0, 1), got 1.5"),
    (lambda: steplearn.Lwpr(2, 1, init_d=-1.0), "init_d diagonal must be positive, got -1"),
    (lambda: steplearn.Lwpr(2, 1, init_d=[1.0, 2.0, 3.0]), "init_d needs 2 x 2 = 4 elements, got 3"),
    (lambda: steplearn.Lwpr(2, 1, init_d=[[1.0, 0.5], [0.5, 1.0]]), "must be diagonal when diag_only is on"),
    (lambda: steplearn.Lwpr(2, 1, init_alpha=float("nan")), "init_alpha must be finite, got NaN"),
    (lambda: steplearn.Lwpr(2, 1, norm_in=[1.0]), "norm_in needs 2 elements, got 1"),
    (lambda: steplearn.Lwpr(2, 1, max_rfs=0), "max_rfs must be at least 1"),
    (lambda: steplearn.Lwpr(2, 1, cutoff=1.0), "cutoff must be in [0, 1), got 1"),
    (lambda: steplearn.Lwpr(0, 1), "n_in must be at least 1"),
    (lambda: steplearn.Lwpr(-1, 1), "n_in must be in [1, 4096], got -1"),
    (lambda: steplearn.Lwpr(10**6, 1), "n_in must be in [1, 4096], got 1000000"),
    (lambda: steplearn.Lwpr(2, 1, budget=-1), None),  # unknown: TypeError, checked below
    (lambda: steplearn.Rbf([0], [1], [3], cutoff=0.5), "cutoff must be finite and >= 1, got 0.5"),
    (lambda: steplearn.Rbf([1], [0], [3]), "bounds dimension 0: need finite lo < hi, got [1, 0]"),
    (lambda: steplearn.Rbf([0], [1], [3], output_dim=0), "output_dim must be >= 1"),
    (lambda: steplearn.Grid([0], [1], [3], learning_rate=2.0), "learning_rate"),
    (lambda: steplearn.Grid([0], [1], [3], max_nodes=2), "resolution"),
    (lambda: steplearn.KernelRidge([0.0]), "length_scales input 0: must be finite and > 0, got 0"),
    (lambda: steplearn.KernelRidge([1.0], budget=0), "budget"),
    (lambda: steplearn.KernelRidge([1.0], forgetting=1.5), "forgetting"),
    (lambda: steplearn.KernelRidge([1.0], budget=-3), "setting budget: invalid value: integer `-3`"),
]


@pytest.mark.parametrize("build, msg", OUT_OF_RANGE)
def test_out_of_range_setting_is_a_value_error_with_the_rust_message(build, msg):
    if msg is None:
        with pytest.raises(TypeError):
            build()
        return
    with pytest.raises(ValueError) as info:
        build()
    assert msg in str(info.value), str(info.value)


@pytest.mark.parametrize("build, msg", [
    (lambda: steplearn.Lwpr(2, 1, w_gen="high"), "setting w_gen: invalid type: string"),
    (lambda: steplearn.Lwpr(2, 1, meta=1.0), "setting meta: invalid type"),
    (lambda: steplearn.Lwpr(2, 1, kernel="Square"), "unknown variant `Square`"),
    (lambda: steplearn.Lwpr(2, 1, init_d=object()), "setting init_d: unsupported type object"),
    (lambda: steplearn.KernelRidge([1.0], budget=2.5), "setting budget: invalid type: floating point"),
    (lambda: steplearn.Lwpr("2", 1), "'str' object cannot be interpreted as an integer"),
])
def test_wrong_setting_type_is_refused(build, msg):
    with pytest.raises((TypeError, ValueError)) as info:
        build()
    assert msg in str(info.value), str(info.value)
