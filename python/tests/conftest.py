import numpy as np
import pytest

import steplearn


def cross(X):
    """The classic LWPR test function on [-1, 1]^2."""
    X = np.atleast_2d(X)
    return np.maximum.reduce(
        [np.exp(-10 * X[:, 0] ** 2), np.exp(-50 * X[:, 1] ** 2),
         1.25 * np.exp(-5 * (X[:, 0] ** 2 + X[:, 1] ** 2))]
    )


def stream(n, seed=0, noise=0.05):
    rng = np.random.default_rng(seed)
    X = rng.uniform(-1, 1, size=(n, 2))
    Y = (cross(X) + noise * rng.standard_normal(n))[:, None]
    return X, Y


# One factory per class, each a fresh 2-input, 1-output model.
FACTORIES = {
    "Lwpr": lambda: steplearn.Lwpr(2, 1, init_d=50.0, init_alpha=250.0, w_gen=0.2),
    "Rbf": lambda: steplearn.Rbf([-1, -1], [1, 1], [11, 11]),
    "Grid": lambda: steplearn.Grid([-1, -1], [1, 1], [11, 11]),
    "KernelRidge": lambda: steplearn.KernelRidge([0.3, 0.3], budget=50),
}


@pytest.fixture(params=sorted(FACTORIES))
def make(request):
    return FACTORIES[request.param]
