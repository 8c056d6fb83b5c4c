"""The bench from Python: Python approximators and rules run inside the Rust walker."""

import json
import pathlib

import numpy as np
import pytest

import steplearn

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHEAP = dict(experiments=["stability"], seeds=2, scale=0.01)
CALLS = {"predict": 0, "update": 0, "gradient": 0}


class Bins:
    """A pure-Python table: 3 bins per input over the box, each moved toward its targets."""

    n_out = 1

    def __init__(self, lo, hi, rate=0.5):
        self.lo, self.hi = [float(v) for v in lo], [float(v) for v in hi]
        self.rate = rate
        self.values = [0.0] * 3 ** len(self.lo)

    def _bin(self, x):
        k = 0
        for xi, lo, hi in zip(x, self.lo, self.hi):
            k = 3 * k + min(2, max(0, int(3 * (xi - lo) / (hi - lo))))
        return k

    def predict(self, x):
        CALLS["predict"] += 1
        return [self.values[self._bin(x)]]

    def update(self, x, y):
        CALLS["update"] += 1
        k = self._bin(x)
        self.values[k] += self.rate * (y[0] - self.values[k])


class Balance:
    """G = gain * theta_E (the crate's balance-only rule, scaled)."""

    def __init__(self, gain=1.0):
        self.gain = gain

    def gradient(self, outcome):
        CALLS["gradient"] += 1
        return self.gain * outcome.theta_e


class Raises:
    """A model whose `method` raises."""

    n_out = 1

    def __init__(self, method):
        self.method = method

    def predict(self, x):
        if self.method == "predict":
            raise ZeroDivisionError("predict went wrong")
        return [0.0]

    def update(self, x, y):
        if self.method == "update":
            raise ZeroDivisionError("update went wrong")


class Wrapped:
    """steplearn.Lwpr behind a Python object: every call goes through Python."""

    n_out = 1

    def __init__(self, model):
        self.model = model

    def predict(self, x):
        return self.model.predict(x)

    def update(self, x, y):
        self.model.update(x, y)


def registry(rate=0.5, gain=1.0):
    return (
        steplearn.Registry.builtin()
        .approximator("py-bins", lambda b: Bins(b.lo, b.hi, rate))
        .rule("py-balance", lambda: Balance(gain))
    )


def bench(reg, out, approx=("lwpr", "py-bins"), rules=("pendulum-cart", "py-balance")):
    b = steplearn.Bench(reg).approximators(list(approx)).rules(list(rules))
    return b.experiments(CHEAP["experiments"]).seeds(CHEAP["seeds"]).scale(CHEAP["scale"]).out(out)


def reset_calls():
    for k in CALLS:
        CALLS[k] = 0


@pytest.fixture(scope="module")
def ran(tmp_path_factory):
    """The four combinations of lwpr / py-bins x pendulum-cart / py-balance, run once."""
    out = tmp_path_factory.mktemp("bench")
    reset_calls()
    rows = bench(registry(), out).run()
    return out, rows, dict(CALLS)


def test_rows_cover_every_combination_with_the_keys_of_leaderboard_json(ran):
    out, rows, calls = ran
    on_disk = json.loads((out / "leaderboard.json").read_text())["rows"]
    assert rows == on_disk
    combos = sorted((r["approx"], r["rule"], r["experiment"]) for r in rows)
    assert combos == sorted(
        (a, r, "stability") for a in ["lwpr", "py-bins"] for r in ["pendulum-cart", "py-balance"]
    )
    for r in rows:
        assert set(r) >= {"approx", "rule", "learn", "experiment", "seeds", "headline",
                          "vs_model", "vs_baseline"}
        assert r["seeds"] == [0, 1]
        assert r["learn"] == ["step-x"]
        assert r["vs_model"], r
        for c in r["vs_model"] + r["vs_baseline"]:
            assert set(c) >= {"quantity", "mean", "ci95", "verdict"}
            assert isinstance(c["verdict"], str)
        baseline = (r["approx"], r["rule"]) == ("lwpr", "pendulum-cart")
        assert bool(r["vs_baseline"]) != baseline
    # The Python objects ran inside the walker.
    assert calls["predict"] > 0 and calls["update"] > 0 and calls["gradient"] > 0


def test_the_python_combinations_differ_from_the_baseline(ran):
    _, rows, _ = ran
    by = {(r["approx"], r["rule"]): r["headline"] for r in rows}
    assert by[("py-bins", "pendulum-cart")] != by[("lwpr", "pendulum-cart")]


def test_a_second_run_resumes_to_the_same_rows_without_calling_python(ran):
    out, rows, _ = ran
    reset_calls()
    again = bench(registry(), out).run()
    assert again == rows
    # Finished runs are reused: no Python model was trained or queried in the walker.
    assert CALLS["update"] == 0 and CALLS["predict"] == 0


def test_two_shards_together_give_the_rows_of_an_unsharded_run(ran, tmp_path):
    _, rows, _ = ran
    first = bench(registry(), tmp_path).shard(0, 2).run()
    assert first != rows  # only the first shard's runs are finished
    both = bench(registry(), tmp_path).shard(1, 2).run()
    assert both == rows


@pytest.mark.parametrize("index, count", [(2, 2), (3, 2), (0, 0)])
def test_a_bad_shard_is_a_value_error(tmp_path, index, count):
    with pytest.raises(ValueError, match=rf"shard\(index={index}, count={count}\)"):
        bench(registry(), tmp_path).shard(index, count)


def test_a_changed_parameter_under_the_same_name_is_refused_as_in_rust(ran):
    # The identity of a Python approximator is its name and its fresh model's pickle, of a
    # rule its gradients on fixed outcomes: finished runs of another parameter are refused.
    out, _, _ = ran
    reset_calls()
    with pytest.raises(RuntimeError, match="another configuration.*approx_model"):
        bench(registry(rate=0.9), out, approx=["py-bins"], rules=["pendulum-cart"]).run()
    with pytest.raises(RuntimeError, match="another configuration.*rule_model"):
        bench(registry(gain=2.0), out, approx=["lwpr"], rules=["py-balance"]).run()
    assert CALLS["update"] == 0


def test_a_native_or_wrapped_lwpr_gives_the_rows_of_the_builtin_lwpr(ran):
    # Resumes the fixture's directory: its lwpr runs are reused, the new names run.
    out, rows, _ = ran

    def native(b):
        half = list((np.asarray(b.hi) - np.asarray(b.lo)) / 2)
        return steplearn.Lwpr(3, 1, norm_in=half, init_d=10.0)

    reg = registry().approximator("my-lwpr", native)
    reg.approximator("py-lwpr", lambda b: Wrapped(native(b)))
    got = bench(reg, out, approx=["lwpr", "my-lwpr", "py-lwpr"], rules=["pendulum-cart"]).run()
    by = {r["approx"]: r for r in got}
    base = [r for r in rows if (r["approx"], r["rule"]) == ("lwpr", "pendulum-cart")]
    assert [by["lwpr"]] == base
    for name in ["my-lwpr", "py-lwpr"]:
        assert by[name]["headline"] == by["lwpr"]["headline"]
        assert by[name]["vs_model"] == by["lwpr"]["vs_model"]


def test_the_factory_receives_the_learner_input_box():
    seen = []

    def factory(b):
        seen.append((b.lo, b.hi, b.dim))
        return Bins(b.lo, b.hi)

    reg = steplearn.Registry.builtin().approximator("peek", factory)
    with pytest.raises(ValueError, match="unknown experiment"):
        steplearn.Bench(reg).approximators(["peek"]).experiments(["nope"]).run()
    b = steplearn.InputBox([-1.0, 0.0], [1.0, 2.0])
    assert list(b.lo) == [-1.0, 0.0] and list(b.hi) == [1.0, 2.0] and b.dim == 2
    with pytest.raises(ValueError):
        steplearn.InputBox([1.0], [0.0])
    o = steplearn.StepOutcome(theta_e=0.1, f_r=0.2)
    assert Balance(2.0).gradient(o) == pytest.approx(0.2)


def test_unknown_or_bad_selections_raise_value_error(tmp_path):
    reg = registry()
    for kw, msg in [
        (dict(approx=["nope"]), "unknown approximator 'nope'"),
        (dict(rules=["nope"]), "unknown rule 'nope'"),
        (dict(approx=["lwpr", "lwpr"]), "selected twice"),
    ]:
        with pytest.raises(ValueError, match=msg):
            bench(reg, tmp_path / "x", **kw).run()
    with pytest.raises(ValueError, match="seeds"):
        bench(reg, tmp_path / "x").seeds(0).run()
    with pytest.raises(ValueError, match="baseline"):
        bench(reg, tmp_path / "x").baseline("grid", "linear").run()
    with pytest.raises(ValueError, match="unknown step parameter"):
        steplearn.Bench(reg).learn_sets(["step-z"])
    assert not (tmp_path / "x").exists()


def test_bad_registrations_raise_and_leave_the_registry_unchanged():
    reg = registry()
    with pytest.raises(ValueError, match="registered twice"):
        reg.approximator("py-bins", lambda b: Bins(b.lo, b.hi))
    with pytest.raises(ValueError, match="registered twice"):
        reg.rule("pendulum-cart", lambda: Balance())
    with pytest.raises(ValueError):
        reg.rule("Bad Name", lambda: Balance())
    with pytest.raises(TypeError, match="callable"):
        reg.approximator("not-callable", 3)
    assert reg.approximator_names.count("py-bins") == 1
    assert "Bad Name" not in reg.rule_names and "not-callable" not in reg.approximator_names
    assert steplearn.Registry().approximator_names == []


def test_a_raising_factory_is_a_value_error_before_any_run(tmp_path):
    def factory(b):
        raise RuntimeError("no model today")

    reg = steplearn.Registry.builtin().approximator("broken", factory)
    with pytest.raises(ValueError, match="no model today"):
        bench(reg, tmp_path / "b", approx=["broken"], rules=["pendulum-cart"]).run()
    reg.approximator("no-update", lambda b: object())
    with pytest.raises(ValueError, match="without a method predict"):
        bench(reg, tmp_path / "b", approx=["no-update"], rules=["pendulum-cart"]).run()


@pytest.mark.parametrize("method", ["predict", "update"])
def test_a_raising_python_model_fails_its_runs_naming_the_exception(tmp_path, method):
    reg = steplearn.Registry.builtin().approximator("raises", lambda b: Raises(method))
    with pytest.raises(RuntimeError, match=f"{method} went wrong") as e:
        bench(reg, tmp_path, approx=["raises"], rules=["pendulum-cart"]).run()
    message = str(e.value)
    assert f"ZeroDivisionError: {method} went wrong" in message
    assert "the user's approximator failed" in message
    assert "invalid configuration" not in message


def test_a_raising_factory_names_the_exception_not_a_configuration(tmp_path):
    def factory(b):
        raise ZeroDivisionError("no model today")

    reg = steplearn.Registry.builtin().approximator("broken", factory)
    with pytest.raises(ValueError) as e:
        bench(reg, tmp_path, approx=["broken"], rules=["pendulum-cart"]).run()
    assert "ZeroDivisionError: no model today" in str(e.value)
    assert "invalid configuration" not in str(e.value)


def test_a_raising_python_rule_fails_its_runs_naming_the_exception(tmp_path):
    class Bad:
        def gradient(self, outcome):
            raise KeyError("no gradient")

    reg = steplearn.Registry.builtin().rule("bad-rule", Bad)
    with pytest.raises(RuntimeError, match="no gradient") as e:
        bench(reg, tmp_path, approx=["lwpr"], rules=["bad-rule"]).run()
    assert "KeyError: 'no gradient'" in str(e.value)
    assert "invalid configuration" not in str(e.value)


def test_a_config_file_sets_the_settings_of_every_run(tmp_path):
    def one(out):
        return bench(registry(), out, approx=["lwpr"], rules=["pendulum-cart"]).seeds(1)

    default = one(tmp_path / "default").run()
    improved = one(tmp_path / "improved").config(str(ROOT / "configs" / "improved.toml")).run()
    tracking = 'swing = "tracking"'
    configs = list((tmp_path / "improved").rglob("run-config.toml"))
    assert configs and all(tracking in p.read_text() for p in configs)
    assert not any(tracking in p.read_text() for p in (tmp_path / "default").rglob("run-config.toml"))
    assert improved != default


def test_a_bad_config_file_is_a_value_error_and_the_bench_keeps_its_choices(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[settings.walker.motion]\nno_such_key = 1\n")
    b = bench(registry(), tmp_path / "out", approx=["lwpr"], rules=["pendulum-cart"]).seeds(1)
    with pytest.raises(ValueError, match="no_such_key"):
        b.config(str(bad))
    with pytest.raises(ValueError, match="missing.toml"):
        b.config(str(tmp_path / "missing.toml"))
    rows = b.run()
    assert len(rows) == 1
    assert not any("no_such_key" in p.read_text() for p in (tmp_path / "out").rglob("run-config.toml"))


def test_on_run_reports_each_run_as_it_ends(tmp_path):
    seen = []
    b = bench(registry(), tmp_path, approx=["lwpr"], rules=["pendulum-cart"]).on_run(seen.append)
    rows = b.run()
    assert len(seen) == CHEAP["seeds"] and len(rows) == 1
    assert sorted(r["seed"] for r in seen) == list(range(CHEAP["seeds"]))
    for r in seen:
        assert (r["experiment"], r["approx"], r["rule"]) == ("stability", "lwpr", "pendulum-cart")
        assert r["learn"] == ["step-x"]
        assert r["status"] == "done" and r["wall_time_s"] > 0
    # A second run finds every run finished.
    again = []
    b.on_run(again.append).run()
    assert [r["status"] for r in again] == ["skipped"] * CHEAP["seeds"]


def test_an_on_run_callback_that_raises_fails_the_run_call_after_the_bench(tmp_path):
    def boom(run):
        raise KeyError("progress bar")

    b = bench(registry(), tmp_path, approx=["lwpr"], rules=["pendulum-cart"]).on_run(boom)
    with pytest.raises(RuntimeError, match="on_run callback raised KeyError"):
        b.run()
    # The bench itself finished: its leaderboard is written.
    assert (tmp_path / "leaderboard.json").exists()
    with pytest.raises(TypeError, match="on_run: the callback must be callable"):
        b.on_run(3)


def test_replays_are_written_only_when_asked(tmp_path):
    def one(out):
        return bench(registry(), out, approx=["lwpr"], rules=["pendulum-cart"]).seeds(1)

    one(tmp_path / "plain").run()
    assert not list((tmp_path / "plain").glob("replay-*.html"))
    one(tmp_path / "replays").replays(True).run()
    pages = sorted(p.name for p in (tmp_path / "replays").glob("replay-*.html"))
    assert pages == ["replay-best.html", "replay-worst.html"]
    assert "replay-best.html" in (tmp_path / "replays" / "index.html").read_text()


def test_two_robots_give_rows_naming_their_robot(tmp_path):
    robots = [ROOT / "robots" / "igus_like.urdf", ROOT / "tests" / "robots" / "minimal.urdf"]
    rows = (
        bench(registry(), tmp_path, approx=["py-bins"], rules=["py-balance"])
        .seeds(1)
        .robots([str(p) for p in robots])
        .run()
    )
    assert len(rows) == 2
    assert len({r["robot"] for r in rows}) == 2
    assert all((r["approx"], r["rule"]) == ("py-bins", "py-balance") for r in rows)
    assert json.loads((tmp_path / "leaderboard.json").read_text())["robots"]


def test_an_approximator_that_does_not_pickle_is_refused_with_the_reason(tmp_path):
    class Local:  # a local class: pickle cannot name it
        n_out = 1

        def predict(self, x):
            return [0.0]

        def update(self, x, y):
            pass

    reg = steplearn.Registry.builtin().approximator("local", lambda b: Local())
    with pytest.raises(RuntimeError, match="cannot be pickled"):
        bench(reg, tmp_path, approx=["local"], rules=["pendulum-cart"]).run()
