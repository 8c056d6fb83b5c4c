//! Unit tests of the PLS and distance-metric updates against hand-derived values.
