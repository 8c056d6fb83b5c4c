"""The river wrapper, inside river's own pipeline and evaluation."""

import math
import random

import pytest

river = pytest.importorskip("river")
from river import compose, evaluate, metrics, preprocessing, stats  # noqa: E402

import steplearn  # noqa: E402
from steplearn.river import LwprRegressor, Regressor  # noqa: E402


def synthetic(n, seed):
    rnd = random.Random(seed)
    for _ in range(n):
        a, b = rnd.uniform(-1, 1), rnd.uniform(-1, 1)
        y = math.sin(3 * a) * math.exp(-b * b) + 0.5 * b + rnd.gauss(0, 0.05)
        yield {"a": a, "b": b}, y


def mean_mae(n, seed):
    """MAE of river's running mean on the same stream (the baseline to beat)."""
    mean, mae = stats.Mean(), metrics.MAE()
    for _, y in synthetic(n, seed):
        mae.update(y, mean.get())
        mean.update(y)
    return mae.get()


def test_lwpr_regressor_learns_in_progressive_validation():
    model = compose.Pipeline(
        preprocessing.StandardScaler(),
        LwprRegressor(init_d=25.0, init_alpha=100.0, w_gen=0.2),
    )
    mae = evaluate.progressive_val_score(synthetic(4000, 1), model, metrics.MAE())
    baseline = mean_mae(4000, 1)
    assert mae.get() < 0.3 * baseline, (mae.get(), baseline)


def test_generic_wrapper_over_other_models_learns():
    for make in (
        lambda n: steplearn.Grid([-1] * n, [1] * n, [15] * n, learning_rate=0.5),
        lambda n: steplearn.KernelRidge([0.3] * n, budget=60),
    ):
        mae = evaluate.progressive_val_score(synthetic(3000, 2), Regressor(make), metrics.MAE())
        assert mae.get() < 0.4 * mean_mae(3000, 2)


def test_feature_order_and_missing_features():
    r = LwprRegressor(features=["b", "a"])
    r.learn_one({"a": 0.1, "b": 0.2}, 1.0)
    assert r.lwpr.n_in == 2
    assert isinstance(r.predict_one({"a": 0.1, "b": 0.2}), float)
    with pytest.raises(ValueError, match="feature 'b' is missing"):
        r.predict_one({"a": 0.1})
    fresh = LwprRegressor()
    assert fresh.predict_one({"a": 1.0}) == 0.0  # before any training: the default
    # order from the first sample, sorted: the same dict in another order gives the same input
    fresh.learn_one({"z": 0.5, "a": -0.5}, 1.0)
    assert fresh.predict_one({"a": -0.5, "z": 0.5}) == fresh.predict_one({"z": 0.5, "a": -0.5})


def test_clone_does_not_share_the_model():
    r = LwprRegressor(w_gen=0.3)
    for x, y in synthetic(50, 3):
        r.learn_one(x, y)
    c = r.clone()
    assert c.lwpr is None and c.settings == {"w_gen": 0.3}
    wrapped = Regressor(steplearn.Lwpr(2, 1))
    wrapped.learn_one({"a": 0.0, "b": 0.0}, 1.0)
    assert wrapped.clone()._model is not wrapped._model


def test_multi_output_model_is_refused():
    with pytest.raises(ValueError, match="one output"):
        Regressor(lambda n: steplearn.Lwpr(n, 2)).learn_one({"a": 0.0}, 1.0)
