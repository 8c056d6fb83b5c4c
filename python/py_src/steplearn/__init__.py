"""steplearn: online function approximators from the steplearn Rust crate.

The classes are compiled (``steplearn._steplearn``); this package re-exports them. The river
wrapper is in :mod:`steplearn.river` (it needs ``river`` only for river's own tools).
"""

from ._steplearn import MAX_INPUT, MAX_TARGET, Grid, KernelRidge, Lwpr, Rbf
from ._steplearn import Bench, InputBox, Registry, StepOutcome

__all__ = ["Lwpr", "Rbf", "Grid", "KernelRidge", "MAX_INPUT", "MAX_TARGET"]
__all__ += ["Registry", "Bench", "InputBox", "StepOutcome"]
__version__ = "0.1.0"
