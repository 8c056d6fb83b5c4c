//! Checked configuration: the one error type every config check returns (naming the field and
//! the reason), and the serde helper that lets a partial section override a default that is
//! not the field type's own `Default` (the thigh and the shank share a type but not their
//! defaults).

use serde::de::{DeserializeOwned, Deserializer, Error as _};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A configuration value that is out of range, named by its path in the config file.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("{field}: {reason}")]
pub struct ConfigError {
    /// Dotted path of the offending key, e.g. `protocols.stability.pushes`.
    pub field: String,
    /// What is wrong with it.
    pub reason: String,
}

impl ConfigError {
    /// An error of `field` because of `reason`.
    pub fn new(field: impl Into<String>, reason: impl Into<String>) -> Self {
        ConfigError {
            field: field.into(),
            reason: reason.into(),
        }
    }

    /// A deserialization error, named by the path where it happened (empty at the top).
    pub fn from_path<E: std::fmt::Display>(e: serde_path_to_error::Error<E>) -> Self {
        let path = e.path().to_string();
        let field = if path == "." { String::new() } else { path };
        ConfigError::new(field, e.inner().to_string())
    }

    /// The same error with `prefix.` put before its field (the section that holds it).
    pub fn within(mut self, prefix: &str) -> Self {
        self.field = if self.field.is_empty() {
            prefix.to_string()
        } else {
            format!("{prefix}.{}", self.field)
        };
        self
    }
}

/// Whether `v` is 0 (either sign): for `skip_serializing_if`, a value left out of written
/// configs and saved files when it has its default.
pub(crate) fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// `Err(ConfigError)` for `field` with `reason` unless `ok`.
pub fn ensure(ok: bool, field: &str, reason: impl FnOnce() -> String) -> Result<(), ConfigError> {
    if ok {
        Ok(())
    } else {
        Err(ConfigError::new(field, reason()))
    }
}

/// Checks that `v` is finite and > 0.
pub fn positive(field: &str, v: f64) -> Result<(), ConfigError> {
    ensure(v.is_finite() && v > 0.0, field, || {
        format!("must be finite and > 0, got {v}")
    })
}

/// Checks that `v` is finite and >= 0.
pub fn non_negative(field: &str, v: f64) -> Result<(), ConfigError> {
    ensure(v.is_finite() && v >= 0.0, field, || {
        format!("must be finite and >= 0, got {v}")
    })
}

/// Checks that `(lo, hi)` is finite with `lo <= hi`.
pub fn ordered(field: &str, (lo, hi): (f64, f64)) -> Result<(), ConfigError> {
    ensure(lo.is_finite() && hi.is_finite() && lo <= hi, field, || {
        format!("must be finite with lo <= hi, got [{lo}, {hi}]")
    })
}

/// Checks that `(lo, hi)` is finite with `0 <= lo <= hi`.
pub fn non_negative_range(field: &str, r: (f64, f64)) -> Result<(), ConfigError> {
    ordered(field, r)?;
    ensure(r.0 >= 0.0, field, || {
        format!("must not be negative, got [{}, {}]", r.0, r.1)
    })
}

/// Checks that `(lo, hi)` is finite with `0 < lo <= hi`.
pub fn positive_range(field: &str, r: (f64, f64)) -> Result<(), ConfigError> {
    ordered(field, r)?;
    ensure(r.0 > 0.0, field, || {
        format!("must be positive, got [{}, {}]", r.0, r.1)
    })
}

/// Checks that `d` is a finite unit vector (a zero or non-finite direction is an error).
pub fn unit_direction(field: &str, d: &[f64; 3]) -> Result<(), ConfigError> {
    let norm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
    ensure(norm.is_finite() && (norm - 1.0).abs() < 1e-6, field, || {
        format!("must be a finite unit vector, got {d:?} (length {norm})")
    })
}

/// Checks that a count is at least `min`.
pub fn at_least(field: &str, n: usize, min: usize) -> Result<(), ConfigError> {
    ensure(n >= min, field, || {
        format!("must be at least {min}, got {n}")
    })
}

/// Checks that a count lies in `[min, max]`.
pub fn count_in(field: &str, n: usize, min: usize, max: usize) -> Result<(), ConfigError> {
    ensure(n >= min && n <= max, field, || {
        format!("must be in [{min}, {max}], got {n}")
    })
}

/// Checks that `v` is finite and in `[lo, hi]`.
pub fn in_range(field: &str, v: f64, lo: f64, hi: f64) -> Result<(), ConfigError> {
    ensure(v.is_finite() && v >= lo && v <= hi, field, || {
        format!("must be finite and in [{lo}, {hi}], got {v}")
    })
}

/// Checks that both ends of `(a, b)` lie in `[lo, hi]` (after [`ordered`] or the like).
pub fn range_in(field: &str, (a, b): (f64, f64), lo: f64, hi: f64) -> Result<(), ConfigError> {
    ensure(a >= lo && b <= hi, field, || {
        format!("must lie within [{lo}, {hi}], got [{a}, {b}]")
    })
}

/// Checks a series of pushes as experiments C and `omnidirectional` take it: `pushes` in
/// [1, [`limits::MAX_PUSHES`]], a non-negative ordered `impulse` range up to
/// [`limits::MAX_IMPULSE_NS`] and a positive ordered `gap_s` range up to [`limits::MAX_GAP_S`];
/// errors name the keys `pushes`, `impulse` and `gap_s`.
pub fn push_series(
    pushes: usize,
    impulse: (f64, f64),
    gap_s: (f64, f64),
) -> Result<(), ConfigError> {
    count_in("pushes", pushes, 1, limits::MAX_PUSHES)?;
    non_negative_range("impulse", impulse)?;
    range_in("impulse", impulse, 0.0, limits::MAX_IMPULSE_NS)?;
    positive_range("gap_s", gap_s)?;
    range_in("gap_s", gap_s, 0.0, limits::MAX_GAP_S)
}

/// The ranges of the experiments' counts, sizes, durations and magnitudes: what one run can
/// do in bounded memory and time. A config or command line outside them is refused before
/// anything runs.
pub mod limits {
    /// Pushes per controller in one run (at 3-7 s a push, at most about 20 h simulated).
    pub const MAX_PUSHES: usize = 10_000;
    /// Seeds of one command (`--seeds`).
    pub const MAX_SEEDS: u64 = 10_000;
    /// Simulated time of one trial (s): one day.
    pub const MAX_TRIAL_S: f64 = 86_400.0;
    /// A time between pushes, a settle time or a hold (s).
    pub const MAX_GAP_S: f64 = 600.0;
    /// The shortest time bin (s): one control tick of the paper's 100 Hz controller.
    pub const MIN_BIN_S: f64 = 0.01;
    /// Time bins after a change or a push (horizon / bin).
    pub const MAX_BINS: f64 = 10_000.0;
    /// A push impulse (Ns): 1000 Ns sends a 90 kg robot off at 11 m/s, far past every fall.
    pub const MAX_IMPULSE_NS: f64 = 1000.0;
    /// A reference step size or its range (m), either way.
    pub const MAX_STEP_M: f64 = 1.0;
    /// Points per axis of a dF map or an input grid.
    pub const MAX_GRID_POINTS: usize = 1_000;
}

/// Deserializes a partial `T` over `base`: keys given override `base`'s, tables merge at every
/// depth (arrays of tables of the same length merge element by element), anything else
/// replaces. Unknown keys stay errors when `T` denies them.
pub fn patch<'de, D, T>(base: &T, deserializer: D) -> Result<T, D::Error>
where
    D: Deserializer<'de>,
    T: Serialize + DeserializeOwned,
{
    let over = serde_json::Value::deserialize(deserializer)?;
    let mut merged = serde_json::to_value(base).map_err(D::Error::custom)?;
    merge(&mut merged, over);
    serde_json::from_value(merged).map_err(D::Error::custom)
}

fn merge(base: &mut serde_json::Value, over: serde_json::Value) {
    use serde_json::Value;
    match (base, over) {
        (Value::Object(b), Value::Object(o)) => {
            for (k, v) in o {
                match b.get_mut(&k) {
                    Some(slot) => merge(slot, v),
                    None => {
                        b.insert(k, v);
                    }
                }
            }
        }
        (Value::Array(b), Value::Array(o))
            if b.len() == o.len() && o.iter().all(Value::is_object) =>
        {
            for (slot, v) in b.iter_mut().zip(o) {
                merge(slot, v);
            }
        }
        (slot, v) => *slot = v,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_field_with_its_section() {
        let e = ConfigError::new("pushes", "must be at least 1, got 0").within("stability");
        assert_eq!(e.field, "stability.pushes");
        assert_eq!(e.to_string(), "stability.pushes: must be at least 1, got 0");
    }

    #[test]
    fn checks_reject_out_of_range_values() {
        assert!(unit_direction("d", &[0.0, 0.0, 0.0]).is_err());
        assert!(unit_direction("d", &[f64::NAN, 0.0, 0.0]).is_err());
        assert!(unit_direction("d", &[0.0, 1.0, 0.0]).is_ok());
        assert!(non_negative_range("r", (2.0, 1.0)).is_err());
        assert!(non_negative_range("r", (-1.0, 1.0)).is_err());
        assert!(positive_range("r", (0.0, 1.0)).is_err());
        assert!(positive("x", 0.0).is_err());
        assert!(at_least("n", 0, 1).is_err());
    }
}
