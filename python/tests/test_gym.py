"""The footstep environment as a Gymnasium environment: registration and check_env, episodes
that repeat bit for bit, truncation, falls, refused actions, options (robot, pushes, learned
set). Episodes are short (a few footsteps, about 20 ms each; a reset walks about 3 s of
simulated time first)."""

import pathlib
import warnings

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import steplearn.gym
from steplearn._steplearn import FootstepEnv as RustEnv

ROOT = pathlib.Path(__file__).resolve().parents[2]
IGUS = ROOT / "robots" / "igus_like.urdf"


def make(**options):
    return gymnasium.make(steplearn.gym.ENV_ID, **options)


def wobble(k):
    return np.array([0.03 * np.sin(0.7 * k)])


def episode(env, seed, policy, limit=10_000):
    """(first obs, [(obs, reward, terminated, truncated, info)...]) of one episode."""
    obs, _ = env.reset(seed=seed)
    steps = []
    for k in range(limit):
        r = env.step(policy(k))
        steps.append(r)
        if r[2] or r[3]:
            break
    return obs, steps


def assert_same(a, b):
    (obs_a, steps_a), (obs_b, steps_b) = a, b
    np.testing.assert_array_equal(obs_a, obs_b)
    assert len(steps_a) == len(steps_b)
    for (oa, ra, ta, ua, ia), (ob, rb, tb, ub, ib) in zip(steps_a, steps_b):
        assert oa.tobytes() == ob.tobytes()  # bit for bit
        assert (ra, ta, ua) == (rb, tb, ub)
        assert ia == ib


def test_registered_and_spaces():
    assert steplearn.gym.ENV_ID in gymnasium.registry
    env = make(max_footsteps=3)
    assert isinstance(env.unwrapped, steplearn.gym.FootstepEnv)
    a, o = env.action_space, env.observation_space
    assert a.shape == (1,) and a.dtype == np.float64
    assert a.low[0] == -a.high[0] > -1.0
    assert o.shape == (4,) and o.dtype == np.float64 and np.all(np.isinf(o.low))
    assert env.unwrapped.observation_names == [
        "sagittal.theta_e", "sagittal.theta_e_dot", "sagittal.f_r", "sagittal.f_e"]
    assert env.unwrapped.action_names == ["step-x"]


def test_check_env_passes():
    env = steplearn.gym.FootstepEnv(max_footsteps=4)
    check_env(env, skip_render_check=True)
    with warnings.catch_warnings():  # it warns that make's env is wrapped, and of inf bounds
        warnings.simplefilter("ignore")
        check_env(make(max_footsteps=4), skip_render_check=True)


def test_same_seed_and_actions_repeat_bit_for_bit_and_seeds_differ():
    a, b = make(max_footsteps=12), make(max_footsteps=12)
    run = episode(a, 7, wobble)
    assert_same(run, episode(b, 7, wobble))
    episode(a, 8, wobble)  # another episode in between
    assert_same(run, episode(a, 7, wobble))
    # Another seed: other pushes, another episode.
    other = episode(a, 8, wobble)
    assert any(
        x[0].tobytes() != y[0].tobytes() for x, y in zip(run[1], other[1])
    ) or len(run[1]) != len(other[1])
    # The steps are real: they take time and the observation moves.
    assert all(s[4]["step_duration_s"] > 0.1 for s in run[1])
    assert run[1][0][4]["applied_offsets"] == [wobble(0)[0]]


def test_reset_without_seed_draws_from_np_random():
    env = make(max_footsteps=2, pushes="none")
    _, info = env.reset(seed=5)
    assert info["rust_seed"] == 5
    _, info1 = env.reset()
    env.reset(seed=5)
    _, info2 = env.reset()
    assert info1["rust_seed"] == info2["rust_seed"] != 5
    with pytest.raises(ValueError, match="options are not used"):
        env.reset(seed=1, options={"pushes": "none"})
    with pytest.raises(ValueError, match="seed"):
        env.reset(seed=-1)


def test_the_footstep_limit_truncates():
    env = make(max_footsteps=4, pushes="none")
    _, steps = episode(env, 3, lambda k: np.zeros(1))
    assert len(steps) == 4
    assert [s[3] for s in steps] == [False, False, False, True]
    assert not any(s[2] for s in steps)
    assert steps[-1][4]["footsteps"] == 4 and not steps[-1][4]["stalled"]
    assert all(-0.05 < s[1] <= 0.0 for s in steps)
    with pytest.raises(RuntimeError, match="episode has ended"):
        env.step(np.zeros(1))


def test_harmful_actions_fall():
    env = make(max_footsteps=60, pushes="none")
    lo, hi = env.action_space.low, env.action_space.high
    _, steps = episode(env, 1, lambda k: hi if k % 2 == 0 else lo)
    last = steps[-1]
    assert last[2] and not last[3], f"{len(steps)} steps without a fall"
    assert last[4]["fall"] is not None and last[4]["fall"]["time"] > 0
    assert last[1] == -(1.0 + 60 - len(steps))
    assert all(s[1] >= -1.0 for s in steps[:-1])


@pytest.mark.parametrize(
    "bad, match",
    [
        (np.zeros(2), "shape"),
        (np.zeros((1, 1)), "shape"),
        (np.array([]), "shape"),
        (np.array([np.nan]), "not finite"),
        (np.array([np.inf]), "not finite"),
        (np.array([10.0]), "outside"),
        (np.array([-10.0]), "outside"),
    ],
)
def test_bad_actions_raise_and_change_nothing(bad, match):
    env, reference = make(max_footsteps=6, pushes="none"), make(max_footsteps=6, pushes="none")
    env.reset(seed=4)
    reference.reset(seed=4)
    with pytest.raises(ValueError, match=match):
        env.step(bad)
    for k in range(3):
        assert_same((np.zeros(0), [env.step(wobble(k))]), (np.zeros(0), [reference.step(wobble(k))]))


def test_compiled_env_refuses_bad_input():
    env = RustEnv(pushes="none", max_footsteps=3)
    with pytest.raises(RuntimeError, match="before reset"):
        env.step([0.0])
    env.reset(2)
    hi = env.action_bounds[0, 1]
    with pytest.raises(ValueError, match=r"outside \["):
        env.step([hi + 1e-9])
    with pytest.raises(ValueError, match="expected 1"):
        env.step([0.0, 0.0])
    with pytest.raises(TypeError):
        env.step("0.1")
    with pytest.raises(TypeError):
        env.step([[0.0]])
    with pytest.raises(TypeError):
        env.reset(1.5)
    with pytest.raises(ValueError):
        env.reset(-1)
    obs, reward, terminated, truncated, info = env.step([hi])  # the bound itself is allowed
    assert obs.dtype == np.float64 and obs.shape == (4,)
    assert info["applied_offsets"] == [hi]


@pytest.mark.parametrize(
    "options, error, match",
    [
        (dict(max_footsteps=0), ValueError, "max_footsteps"),
        (dict(pushes="sometimes"), ValueError, "pushes must be"),
        (dict(pushes=3), TypeError, "pushes must be"),
        (dict(pushes={"impulse": (5.0, 1.0)}), ValueError, "impulse"),
        (dict(pushes={"strength": 1.0}), TypeError, "strength"),
        (dict(learn="step-z"), ValueError, "step-z"),
        (dict(learn=5), TypeError, "learn"),
        (dict(reward={"p_theta": -1.0}), ValueError, "p_theta"),
        (dict(robot=str(ROOT / "robots" / "missing.urdf")), ValueError, "robot"),
        (dict(reference=float("nan")), ValueError, "reference"),
    ],
)
def test_bad_options_raise(options, error, match):
    with pytest.raises(error, match=match):
        RustEnv(**options)


def test_push_protocols():
    # Pushes arrive in the chosen window; without pushes none arrive.
    env = make(max_footsteps=12, pushes={"impulse": [5.0, 5.0], "gap_s": [1.0, 1.0]})
    _, steps = episode(env, 0, lambda k: np.zeros(1))
    pushes = [p for s in steps for p in s[4]["pushes"]]
    assert pushes and all(p["impulse"] == 5.0 for p in pushes)
    quiet = make(max_footsteps=12, pushes="none")
    _, steps = episode(quiet, 0, lambda k: np.zeros(1))
    assert all(s[4]["pushes_delivered"] == 0 for s in steps)
    # A push during the walk to the first decision point that fells the robot: reset raises.
    harsh = make(max_footsteps=2, pushes={"impulse": [60.0, 60.0], "gap_s": [0.5, 0.5],
                                          "settle_s": 0.0})
    with pytest.raises(RuntimeError, match="no first decision point"):
        harsh.reset(seed=0)


def test_igus_like_robot():
    paper = make(max_footsteps=5, pushes="none")
    env = make(robot=str(IGUS), max_footsteps=5, pushes="none")
    scale = env.unwrapped.core.length_scale
    assert scale != 1.0
    np.testing.assert_allclose(env.action_space.high, paper.action_space.high * scale, rtol=1e-12)
    check_env(env.unwrapped, skip_render_check=True)
    _, steps = episode(env, 5, lambda k: np.zeros(1))
    assert len(steps) == 5 and steps[-1][3] and not any(s[2] for s in steps)


def test_two_learned_parameters_give_a_2d_action():
    env = make(learn=["step-x", "step-y"], max_footsteps=3, pushes="none")
    assert env.action_space.shape == (2,) and env.observation_space.shape == (8,)
    assert env.unwrapped.observation_names[4] == "frontal.theta_e"
    obs, _ = env.reset(seed=2)
    assert obs.shape == (8,)
    obs, _, _, _, info = env.step(np.array([0.0, 0.02]))
    assert len(info["g"]) == 2 and abs(info["applied_offsets"][1]) == 0.02
    same = make(learn="step-x,step-y", max_footsteps=3, pushes="none")
    assert same.action_space == env.action_space
    check_env(same.unwrapped, skip_render_check=True)
