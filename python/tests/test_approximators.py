"""Every binding of the four approximators: construction, update/predict, batches, LWPR's
extras, and learning itself."""

import threading

import numpy as np
import pytest

import steplearn
from conftest import FACTORIES, cross, stream


def test_dims_and_repr(make):
    m = make()
    assert (m.n_in, m.n_out) == (2, 1)
    assert type(m).__name__ in repr(m)


def test_predict_returns_1d_float_array(make):
    m = make()
    y = m.predict(np.array([0.1, 0.2]))
    assert isinstance(y, np.ndarray) and y.shape == (1,) and y.dtype == np.float64
    assert m.predict([0.1, 0.2]).shape == (1,)
    assert m.predict((0.1, 0.2)).shape == (1,)
    # other dtypes and non-contiguous arrays are accepted
    m.update(np.array([0, 1], dtype=np.int32), np.array([1.0], dtype=np.float32))
    col = np.arange(6.0).reshape(2, 3)[:, 1] / 10
    assert m.predict(col).shape == (1,)


def test_each_class_learns(make):
    X, Y = stream(3000, seed=1)
    m = make()
    m.update_many(X, Y)
    Xt, _ = stream(500, seed=2)
    rmse = np.sqrt(np.mean((m.predict_many(Xt)[:, 0] - cross(Xt)) ** 2))
    baseline = np.sqrt(np.mean((cross(Xt) - cross(Xt).mean()) ** 2))
    assert rmse < 0.5 * baseline, (rmse, baseline)


def test_update_many_is_bit_identical_to_update_loop(make):
    X, Y = stream(700, seed=3)
    a, b = make(), make()
    for x, y in zip(X, Y):
        a.update(x, y)
    b.update_many(X, Y)
    assert a.to_json() == b.to_json()
    Xt, _ = stream(200, seed=4)
    pa = np.array([a.predict(x) for x in Xt])
    pb = b.predict_many(Xt)
    assert pb.shape == (200, 1)
    assert np.array_equal(pa, pb)


def test_update_many_accepts_lists_and_non_contiguous(make):
    X, Y = stream(50, seed=5)
    a, b, c = make(), make(), make()
    a.update_many(X, Y)
    b.update_many(X.tolist(), Y.tolist())
    wide = np.zeros((50, 4))
    wide[:, ::2] = X
    c.update_many(wide[:, ::2], np.asfortranarray(Y))
    assert a.to_json() == b.to_json() == c.to_json()
    assert np.array_equal(a.predict_many(X), b.predict_many(X.tolist()))


def test_empty_batches(make):
    m = make()
    before = m.to_json()
    m.update_many(np.zeros((0, 2)), np.zeros((0, 1)))
    assert m.to_json() == before
    assert m.predict_many(np.zeros((0, 2))).shape == (0, 1)


def test_batches_release_the_gil():
    m = steplearn.Lwpr(2, 1)
    X, Y = stream(20000, seed=6)
    ticks = []
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            ticks.append(1)

    t = threading.Thread(target=spin)
    t.start()
    try:
        n0 = len(ticks)
        m.update_many(X, Y)
        during = len(ticks) - n0
    finally:
        stop.set()
        t.join()
    # with the GIL held for the whole call the other thread could only tick at the switch
    # interval boundaries around it; released, it spins freely
    assert during > 1000, during


def test_lwpr_predict_conf_and_receptive_fields():
    m = steplearn.Lwpr(2, 1, init_d=50.0, init_alpha=250.0, w_gen=0.2)
    assert m.num_receptive_fields == 0
    y, conf = m.predict_conf([0.0, 0.0])
    assert y.shape == conf.shape == (1,)
    assert np.isinf(conf[0])  # nothing trusted yet
    X, Y = stream(2000, seed=7)
    m.update_many(X, Y)
    assert m.num_receptive_fields > 0 and m.n_data == 2000
    y, conf = m.predict_conf([0.0, 0.0])
    assert np.array_equal(y, m.predict([0.0, 0.0]))
    assert np.isfinite(conf[0]) and conf[0] > 0


def test_lwpr_two_outputs():
    m = steplearn.Lwpr(2, 2, norm_out=[1.0, 2.0])
    X, Y = stream(300, seed=8)
    Y2 = np.hstack([Y, -2 * Y])
    m.update_many(X, Y2)
    assert m.predict([0.1, 0.1]).shape == (2,)
    assert m.predict_many(X).shape == (300, 2)
    assert m.predict_conf([0.1, 0.1])[1].shape == (2,)


def test_lwpr_settings_reach_the_rust_config():
    m = steplearn.Lwpr(2, 1, init_d=[10.0, 20.0], w_gen=0.3, kernel="BiSquare", meta=True,
                       norm_in=np.array([2.0, 3.0]), max_rfs=40)
    s = m.settings
    assert s["init_d"] == [10.0, 0.0, 0.0, 20.0]
    assert (s["w_gen"], s["kernel"], s["meta"], s["max_rfs"]) == (0.3, "BiSquare", True, 40)
    assert s["norm_in"] == [2.0, 3.0]
    assert steplearn.Lwpr(2, 1, init_d=7).settings["init_d"] == [7.0, 0.0, 0.0, 7.0]
    full = steplearn.Lwpr(2, 1, diag_only=False, init_d=[[2.0, 0.5], [0.5, 1.0]])
    assert full.settings["init_d"] == [2.0, 0.5, 0.5, 1.0]
    assert steplearn.Lwpr(2, 1).settings["init_d"] == [25.0, 0.0, 0.0, 25.0]


def test_other_settings_reach_the_rust_configs():
    r = steplearn.Rbf([0, 0], [1, 2], [3, 5], widths=[0.4, 0.4],
                      update={"Rls": {"forgetting": 1.0, "prior_variance": 100.0}}, cutoff=2.5)
    assert r.settings["update"] == {"Rls": {"forgetting": 1.0, "prior_variance": 100.0}}
    assert r.num_centres == 15 and r.settings["cutoff"] == 2.5
    g = steplearn.Grid([0], [1], [5], output_dim=2, learning_rate=0.5)
    assert (g.n_in, g.n_out, g.num_nodes, g.settings["learning_rate"]) == (1, 2, 5, 0.5)
    k = steplearn.KernelRidge([0.5], regularisation=0.1, budget=7, forgetting=0.99)
    assert (k.settings["budget"], k.settings["forgetting"]) == (7, 0.99)
    X = np.linspace(0, 1, 30)[:, None]
    k.update_many(X, np.sin(X))
    assert 0 < k.dictionary_size <= 7
    assert k.predict_variance([0.5]) >= 0


def test_rbf_rls_and_grid_learn_a_line():
    X = np.linspace(0, 1, 200)[:, None]
    Y = 2 * X + 1
    r = steplearn.Rbf([0], [1], [6], update={"Rls": {"forgetting": 1.0, "prior_variance": 100.0}})
    g = steplearn.Grid([0], [1], [6], learning_rate=1.0)
    for m in (r, g):
        for _ in range(5):
            m.update_many(X, Y)
        assert abs(m.predict([0.5])[0] - 2.0) < 0.05
