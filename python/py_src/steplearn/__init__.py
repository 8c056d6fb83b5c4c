"""steplearn: online function approximators from the steplearn Rust crate.

The classes are compiled (``steplearn._steplearn``); this package re-exports them. The river
wrapper is in :mod:`steplearn.river` (it needs ``river`` only for river's own tools).
"""

from ._steplearn import MAX_INPUT, MAX_TARGET, Grid, KernelRidge, Lwpr, Rbf

__all__ = ["Lwpr", "Rbf", "Grid", "KernelRidge", "MAX_INPUT", "MAX_TARGET"]
__version__ = "0.1.0"
