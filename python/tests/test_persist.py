"""save/load and pickle: the Rust crate's files, exact round trips, corrupt files refused."""

import copy
import json
import pickle

import numpy as np
import pytest

import steplearn
from conftest import stream

PROBE = np.random.default_rng(21).uniform(-1, 1, size=(100, 2))


def trained(make):
    m = make()
    X, Y = stream(500, seed=22)
    m.update_many(X, Y)
    return m


def test_save_load_round_trip_is_exact(make, tmp_path):
    m = trained(make)
    path = tmp_path / "model.json"
    m.save(path)
    loaded = type(m).load(path)
    assert type(loaded) is type(m)
    assert np.array_equal(loaded.predict_many(PROBE), m.predict_many(PROBE))
    assert loaded.to_json() == m.to_json()
    # the file is the Rust crate's JSON of the model
    assert json.loads(path.read_text()) == json.loads(m.to_json())
    m.save(str(path))  # str paths too
    # training continues identically after a load
    X, Y = stream(100, seed=23)
    m.update_many(X, Y)
    loaded.update_many(X, Y)
    assert np.array_equal(loaded.predict_many(PROBE), m.predict_many(PROBE))


def test_pickle_and_copy_round_trips_are_exact(make):
    m = trained(make)
    for proto in range(2, pickle.HIGHEST_PROTOCOL + 1):
        back = pickle.loads(pickle.dumps(m, protocol=proto))
        assert type(back) is type(m)
        assert np.array_equal(back.predict_many(PROBE), m.predict_many(PROBE))
    c = copy.deepcopy(m)
    c.update([0.0, 0.0], [5.0])
    assert not np.array_equal(c.predict_many(PROBE), m.predict_many(PROBE))
    assert np.array_equal(copy.copy(m).predict_many(PROBE), m.predict_many(PROBE))


def test_lwpr_file_has_the_rust_layout(tmp_path):
    m = trained(lambda: steplearn.Lwpr(2, 1, w_gen=0.2))
    m.save(tmp_path / "m.json")
    doc = json.loads((tmp_path / "m.json").read_text())
    assert doc["config"]["w_gen"] == 0.2 and doc["config"]["n_in"] == 2
    assert doc["n_data"] == 500


@pytest.mark.parametrize("corrupt", [
    lambda s: s[: len(s) // 2],                       # truncated
    lambda s: "",                                     # empty
    lambda s: "not json at all",
    lambda s: s.replace('"n_in":2', '"n_in":3', 1),  # dimensions disagree
    lambda s: json.dumps({**json.loads(s), "config": 7}),
])
def test_corrupt_file_is_a_value_error(tmp_path, corrupt):
    m = trained(lambda: steplearn.Lwpr(2, 1))
    path = tmp_path / "bad.json"
    path.write_text(corrupt(m.to_json()))
    with pytest.raises(ValueError, match="corrupt or incompatible saved model"):
        steplearn.Lwpr.load(path)
    with pytest.raises(ValueError, match="corrupt or incompatible saved model"):
        steplearn.Lwpr.from_json(corrupt(m.to_json()))


def test_corrupt_files_of_every_class(make, tmp_path):
    m = trained(make)
    good = m.to_json()
    for bad in (good[:-10], good.replace("[", "{", 1), "{}"):
        with pytest.raises(ValueError, match="corrupt or incompatible saved model"):
            type(m).from_json(bad)
    (tmp_path / "bin.json").write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(ValueError, match="corrupt or incompatible saved model"):
        type(m).load(tmp_path / "bin.json")


def test_a_model_of_another_class_is_refused(tmp_path):
    lwpr = trained(lambda: steplearn.Lwpr(2, 1))
    with pytest.raises(ValueError, match="corrupt or incompatible"):
        steplearn.Grid.from_json(lwpr.to_json())


def test_missing_file_is_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        steplearn.Lwpr.load(tmp_path / "nope.json")
    m = steplearn.Lwpr(2, 1)
    with pytest.raises(OSError):
        m.save(tmp_path / "no" / "such" / "dir" / "m.json")
