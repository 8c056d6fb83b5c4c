"""Type stubs of the compiled module ``steplearn._steplearn``."""

from os import PathLike
from typing import Any, Dict, Sequence, Tuple, TypeVar, Union

import numpy as np
import numpy.typing as npt

_Vec = Union[npt.ArrayLike, Sequence[float]]
_Mat = Union[npt.ArrayLike, Sequence[Sequence[float]]]
_Path = Union[str, PathLike]
_T = TypeVar("_T", bound="_Approximator")

MAX_INPUT: float
MAX_TARGET: float

class _Approximator:
    @property
    def n_in(self) -> int: ...
    @property
    def n_out(self) -> int: ...
    @property
    def settings(self) -> Dict[str, Any]: ...
    def update(self, x: _Vec, y: _Vec) -> None: ...
    def predict(self, x: _Vec) -> np.ndarray: ...
    def update_many(self, X: _Mat, Y: _Mat) -> None: ...
    def predict_many(self, X: _Mat) -> np.ndarray: ...
    def to_json(self) -> str: ...
    def save(self, path: _Path) -> None: ...
    def __reduce__(self) -> Tuple[Any, Tuple[str]]: ...
    def __copy__(self: _T) -> _T: ...
    def __deepcopy__(self: _T, memo: Any) -> _T: ...

class Lwpr(_Approximator):
    def __init__(
        self,
        n_in: int,
        n_out: int,
        *,
        init_d: Union[float, Sequence[float], Sequence[Sequence[float]]] = ...,
        init_alpha: float = ...,
        w_gen: float = ...,
        w_prune: float = ...,
        meta: bool = ...,
        meta_rate: float = ...,
        penalty: float = ...,
        diag_only: bool = ...,
        update_d: bool = ...,
        init_lambda: float = ...,
        final_lambda: float = ...,
        tau_lambda: float = ...,
        init_s2: float = ...,
        add_threshold: float = ...,
        kernel: str = ...,
        norm_in: Sequence[float] = ...,
        norm_out: Sequence[float] = ...,
        cutoff: float = ...,
        max_rfs: Union[int, None] = ...,
    ) -> None: ...
    def predict_conf(self, x: _Vec) -> Tuple[np.ndarray, np.ndarray]: ...
    @property
    def num_receptive_fields(self) -> int: ...
    @property
    def n_data(self) -> int: ...
    @staticmethod
    def from_json(json: str) -> Lwpr: ...
    @staticmethod
    def load(path: _Path) -> Lwpr: ...

class Rbf(_Approximator):
    def __init__(
        self,
        lo: _Vec,
        hi: _Vec,
        centres: Sequence[int],
        output_dim: int = 1,
        *,
        widths: Sequence[float] = ...,
        update: Dict[str, Dict[str, float]] = ...,
        cutoff: float = ...,
        max_centres: int = ...,
    ) -> None: ...
    @property
    def num_centres(self) -> int: ...
    @staticmethod
    def from_json(json: str) -> Rbf: ...
    @staticmethod
    def load(path: _Path) -> Rbf: ...

class Grid(_Approximator):
    def __init__(
        self,
        lo: _Vec,
        hi: _Vec,
        resolution: Sequence[int],
        output_dim: int = 1,
        *,
        learning_rate: float = ...,
        max_nodes: int = ...,
    ) -> None: ...
    @property
    def num_nodes(self) -> int: ...
    @staticmethod
    def from_json(json: str) -> Grid: ...
    @staticmethod
    def load(path: _Path) -> Grid: ...

class KernelRidge(_Approximator):
    def __init__(
        self,
        length_scales: _Vec,
        output_dim: int = 1,
        *,
        regularisation: float = ...,
        budget: int = ...,
        novelty_threshold: float = ...,
        forgetting: float = ...,
    ) -> None: ...
    @property
    def dictionary_size(self) -> int: ...
    def predict_variance(self, x: _Vec) -> float: ...
    @staticmethod
    def from_json(json: str) -> KernelRidge: ...
    @staticmethod
    def load(path: _Path) -> KernelRidge: ...

class FootstepEnv:
    """The walker as a footstep environment; the Gymnasium class is ``steplearn.gym.FootstepEnv``."""

    def __init__(
        self,
        robot: Union[str, PathLike, None] = ...,
        pushes: Union[str, Dict[str, Any], None] = ...,
        learn: Union[str, Sequence[str], None] = ...,
        max_footsteps: int = ...,
        reference: float = ...,
        reward: Union[Dict[str, float], None] = ...,
        settings: Union[Dict[str, Any], None] = ...,
    ) -> None: ...
    def reset(self, seed: int) -> np.ndarray: ...
    def step(self, action: _Vec) -> Tuple[np.ndarray, float, bool, bool, Dict[str, Any]]: ...
    @property
    def action_names(self) -> list[str]: ...
    @property
    def observation_names(self) -> list[str]: ...
    @property
    def action_bounds(self) -> np.ndarray: ...
    @property
    def observation_bounds(self) -> np.ndarray: ...
    @property
    def max_footsteps(self) -> int: ...
    @property
    def time(self) -> float: ...
    @property
    def length_scale(self) -> float: ...
    @property
    def config(self) -> Dict[str, Any]: ...
