"""The walker as a Gymnasium environment: ``import steplearn.gym`` registers
``"steplearn/Footstep-v0"``.

One ``step`` is one footstep of the simulated humanoid walking with the Capture Step
controller; the action is the offset(s) added to the controller's step (dF by default), held
over the whole step. The observation is the learner's input at the decision point (the
touch-down) plus the step error F_E of the step that just ended; ``terminated`` means a fall.
See docs/python.md ("The footstep environment") and docs/footstep-env.md.

    import gymnasium, steplearn.gym
    env = gymnasium.make("steplearn/Footstep-v0", pushes="experiment-c", max_footsteps=50)
    obs, info = env.reset(seed=11)   # seed 11: experiment C's pushes of seed 11
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Sequence, Tuple, Union

import gymnasium
import numpy as np
from gymnasium import spaces

from ._steplearn import FootstepEnv as _RustEnv

ENV_ID = "steplearn/Footstep-v0"

__all__ = ["ENV_ID", "FootstepEnv"]


class FootstepEnv(gymnasium.Env):
    """Gymnasium environment over ``steplearn._steplearn.FootstepEnv``.

    Options (also through ``gymnasium.make(ENV_ID, **options)``):

    - ``robot``: a URDF path, or None for the built-in humanoid;
    - ``pushes``: ``"experiment-c"`` (default: forward pushes of 0-20 N s every 3-4 s after
      3 s), ``"none"``, or a dict of ``impulse``, ``gap_s``, ``settle_s``, ``direction``
      (unspecified fields keep experiment C's values);
    - ``learn``: the learned step parameters, one action entry each (``"step-x"`` default; a
      comma-separated string or a list such as ``["step-x", "step-y"]``);
    - ``max_footsteps`` (default 200): footsteps before truncation;
    - ``reference``: the sagittal reference step F_R (m, paper robot; 0 walks in place);
    - ``reward``: a dict of the pendulum-cart ``p_theta``, ``p_f``;
    - ``settings``: a dict of top-level fields of the Rust ``Settings``.

    ``reset(seed=s)`` uses ``s`` itself as the Rust seed (so the pushes are experiment C's
    trial of seed ``s``) and seeds ``self.np_random`` with it; ``reset()`` without a seed draws
    the Rust seed from ``self.np_random`` (seeded from entropy on the first reset, as
    Gymnasium does). ``options`` must be None or empty: everything is chosen at construction.
    """

    metadata: Dict[str, Any] = {"render_modes": []}

    def __init__(
        self,
        robot: Optional[str] = None,
        pushes: Union[str, Dict[str, Any]] = "experiment-c",
        learn: Union[str, Sequence[str]] = "step-x",
        max_footsteps: int = 200,
        reference: float = 0.0,
        reward: Optional[Dict[str, float]] = None,
        settings: Optional[Dict[str, Any]] = None,
        render_mode: Optional[str] = None,
    ) -> None:
        if render_mode is not None:
            raise ValueError(f"render_mode {render_mode!r} is not supported (no rendering)")
        self.render_mode = None
        self._env = _RustEnv(
            robot=None if robot is None else str(robot),
            pushes=pushes,
            learn=learn,
            max_footsteps=max_footsteps,
            reference=reference,
            reward=reward,
            settings=settings,
        )
        b = self._env.action_bounds
        self.action_space = spaces.Box(low=b[:, 0].copy(), high=b[:, 1].copy(), dtype=np.float64)
        n = len(self._env.observation_names)
        self.observation_space = spaces.Box(-np.inf, np.inf, shape=(n,), dtype=np.float64)
        self.action_names = list(self._env.action_names)
        self.observation_names = list(self._env.observation_names)
        self.rust_seed: Optional[int] = None

    @property
    def core(self) -> _RustEnv:
        """The compiled environment."""
        return self._env

    def reset(
        self, *, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None
    ) -> Tuple[np.ndarray, Dict[str, Any]]:
        if options:
            raise ValueError(
                f"options are not used (got {sorted(options)}); choose the robot, pushes and "
                "learned set when constructing the environment"
            )
        if seed is not None and not (isinstance(seed, (int, np.integer)) and 0 <= seed < 2**64):
            raise ValueError(f"seed must be an int in [0, 2**64), got {seed!r}")
        super().reset(seed=seed)
        if seed is None:
            seed = int(self.np_random.integers(0, 2**63))
        self.rust_seed = int(seed)
        obs = self._env.reset(self.rust_seed)
        return obs, {"rust_seed": self.rust_seed, "time_s": self._env.time}

    def step(self, action: Any) -> Tuple[np.ndarray, float, bool, bool, Dict[str, Any]]:
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self.action_space.shape:
            raise ValueError(
                f"action has shape {a.shape}, expected {self.action_space.shape} "
                f"(one entry per learned parameter: {', '.join(self.action_names)})"
            )
        obs, reward, terminated, truncated, info = self._env.step(a)
        return obs, float(reward), bool(terminated), bool(truncated), info

    def render(self) -> None:
        return None

    def close(self) -> None:
        pass


if ENV_ID not in gymnasium.registry:
    gymnasium.register(id=ENV_ID, entry_point="steplearn.gym:FootstepEnv")
