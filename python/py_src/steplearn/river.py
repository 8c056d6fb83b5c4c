"""river-compatible regressors over steplearn's approximators.

``Regressor(model)`` wraps any single-output steplearn approximator (``Lwpr``, ``Rbf``,
``Grid``, ``KernelRidge``) as a river regressor: ``learn_one(x: dict, y)`` and
``predict_one(x: dict)``. The feature order is ``features`` if given, else the keys of the
first dict seen, sorted. ``LwprRegressor(**settings)`` builds the LWPR from the first sample's
number of features.

The class subclasses ``river.base.Regressor`` when river is installed (so pipelines and
``river.evaluate`` accept it) and works without river otherwise.
"""

from __future__ import annotations

import copy
from typing import Any, Callable, Dict, Optional, Sequence

import numpy as np

from . import Lwpr

try:  # river is optional
    from river import base as _river_base

    _Base: Any = _river_base.Regressor
except ImportError:  # pragma: no cover - exercised only without river
    _Base = object

__all__ = ["Regressor", "LwprRegressor"]


class Regressor(_Base):
    """A river regressor around a steplearn approximator with one output.

    ``model`` is an approximator, or a callable ``factory(n_features)`` returning one (built
    at the first sample). ``features`` fixes the input order; otherwise it is the sorted keys
    of the first sample. Before any training, ``predict_one`` returns ``default``.
    """

    def __init__(
        self,
        model: Any = None,
        features: Optional[Sequence[str]] = None,
        default: float = 0.0,
    ) -> None:
        self.model = model
        self.features = list(features) if features is not None else None
        self.default = default
        self._model: Any = None if callable(model) and not hasattr(model, "update") else model
        self._features: Optional[list] = self.features
        self._trained = False

    def _vector(self, x: Dict[str, Any]) -> np.ndarray:
        if self._features is None:
            self._features = sorted(x)
        try:
            return np.array([float(x[k]) for k in self._features], dtype=np.float64)
        except KeyError as e:
            raise ValueError(
                f"feature {e.args[0]!r} is missing; the features are {self._features}"
            ) from None

    def _ensure_model(self) -> Any:
        if self._model is None:
            factory: Callable[[int], Any] = self.model
            self._model = factory(len(self._features or ()))
            if self._model.n_out != 1:
                raise ValueError(
                    f"a river regressor needs a model with one output, got {self._model.n_out}"
                )
        return self._model

    def learn_one(self, x: Dict[str, Any], y: float, **kwargs: Any) -> None:
        v = self._vector(x)
        self._ensure_model().update(v, np.array([float(y)]))
        self._trained = True

    def predict_one(self, x: Dict[str, Any], **kwargs: Any) -> float:
        if self._model is None or not self._trained:
            return self.default
        return float(self._model.predict(self._vector(x))[0])

    # river clones estimators from their constructor parameters; a fresh clone must not share
    # the trained model.
    def clone(self, new_params: Optional[dict] = None, include_attributes: bool = False):
        params = {"model": self.model, "features": self.features, "default": self.default}
        params.update(new_params or {})
        if hasattr(params["model"], "update"):
            params["model"] = copy.deepcopy(params["model"])
        return type(self)(**params)

    @classmethod
    def _unit_test_params(cls):
        yield {"model": lambda n: Lwpr(n, 1)}


class LwprRegressor(Regressor):
    """``Regressor`` over ``steplearn.Lwpr(n_features, 1, **settings)``, built at the first
    sample. ``settings`` are ``Lwpr``'s keywords (``init_d``, ``w_gen``, ``norm_in``, ...)."""

    def __init__(
        self,
        features: Optional[Sequence[str]] = None,
        default: float = 0.0,
        **settings: Any,
    ) -> None:
        self.settings = dict(settings)
        super().__init__(
            model=lambda n: Lwpr(n, 1, **self.settings), features=features, default=default
        )

    def clone(self, new_params: Optional[dict] = None, include_attributes: bool = False):
        params = {"features": self.features, "default": self.default, **self.settings}
        params.update(new_params or {})
        return type(self)(**params)

    @property
    def lwpr(self) -> Optional[Lwpr]:
        """The LWPR model (None before the first sample)."""
        return self._model

    @classmethod
    def _unit_test_params(cls):
        yield {}
