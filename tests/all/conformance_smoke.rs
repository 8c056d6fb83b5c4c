//! The conformance suite's own generators behave, and the suite fails approximators that break
//! the contract, naming the check that caught them.

use serde::{Deserialize, Serialize};
use std::cell::Cell;
use steplearn::approx::conformance::{
    CHECKS, ConformanceError, check_approximator, probe_points, stream, target,
};
use steplearn::approx::{
    ApproxError, FunctionApproximator, Grid, GridConfig, InputBox, Persist, check_vector,
};

#[test]
fn stream_is_seeded() {
    assert_eq!(stream(1, 10, 2, 2), stream(1, 10, 2, 2));
    assert_ne!(stream(1, 10, 2, 2), stream(2, 10, 2, 2));
    assert_eq!(target(&[0.0, 0.0], 1), vec![0.0]);
    assert_eq!(probe_points(2).len(), 121);
    assert_eq!(probe_points(1).len(), 121);
    assert!(probe_points(3).iter().all(|x| x.len() == 3));
    assert_eq!(probe_points(20).len(), 128);
}

fn grid() -> Grid {
    Grid::new(GridConfig::new(
        InputBox::cube(2, -1.0, 1.0).unwrap(),
        vec![5, 5],
        1,
    ))
    .unwrap()
}

#[test]
fn a_correct_approximator_passes() {
    check_approximator(grid).unwrap();
}

/// How a [`Broken`] grid breaks the contract.
const NAN_ACCEPTED: u8 = 0;
const NONDETERMINISTIC: u8 = 1;
const LOAD_IGNORES_FILE: u8 = 2;
const LEARNS_DIFFERENTLY_AFTER_LOAD: u8 = 3;
const BAD_UPDATE_CHANGES_MODEL: u8 = 4;
const PANICS_ON_SHORT_INPUT: u8 = 5;
const WRONG_OUTPUT_DIM: u8 = 6;
const UNTRAINED_NAN: u8 = 7;
const SAVE_NOT_ATOMIC: u8 = 8;
const DEPENDS_ON_INSTANCE: u8 = 9;
const LOAD_UNCHECKED: u8 = 10;
const IGNORES_INPUT: u8 = 11;

/// A grid with one deliberate defect, selected by `FAULT`.
#[derive(Clone, Serialize, Deserialize)]
struct Broken<const FAULT: u8> {
    inner: Grid,
    /// Updates since construction or load (not saved).
    #[serde(skip)]
    since_load: u64,
    /// Extra outputs it claims (the `WRONG_OUTPUT_DIM` fault: one model in two claims one).
    #[serde(skip)]
    extra_out: usize,
    /// A bias on every target, different for each fresh model (the `DEPENDS_ON_INSTANCE`
    /// fault), saved with the model so that a loaded one learns as the saved one would.
    bias: f64,
}

thread_local! {
    /// Models made on this thread (per thread: tests run in parallel, and the
    /// `WRONG_OUTPUT_DIM` fault needs two consecutive models of the suite to alternate).
    static MADE: Cell<u64> = const { Cell::new(0) };
    /// Predictions made on this thread (the `NONDETERMINISTIC` fault).
    static CALLS: Cell<u64> = const { Cell::new(0) };
}

/// `counter`'s value, then one more.
fn next(counter: &'static std::thread::LocalKey<Cell<u64>>) -> u64 {
    counter.with(|c| {
        let n = c.get();
        c.set(n + 1);
        n
    })
}

impl<const FAULT: u8> Broken<FAULT> {
    fn new() -> Self {
        Broken {
            inner: grid(),
            since_load: 1,
            extra_out: usize::from(FAULT == WRONG_OUTPUT_DIM && next(&MADE) % 2 == 1),
            bias: if FAULT == DEPENDS_ON_INSTANCE {
                1e-3 * (next(&MADE) % 5) as f64
            } else {
                0.0
            },
        }
    }
}

impl<const FAULT: u8> FunctionApproximator for Broken<FAULT> {
    fn input_dim(&self) -> usize {
        self.inner.input_dim()
    }
    fn output_dim(&self) -> usize {
        self.inner.output_dim() + self.extra_out
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        if FAULT == PANICS_ON_SHORT_INPUT {
            let _ = x[1];
        }
        if FAULT == IGNORES_INPUT {
            // Checks its input, then answers what it learned at the origin, wherever asked.
            check_vector("input x", x, self.input_dim())?;
            self.inner.predict(&vec![0.0; x.len()], y)?;
        } else {
            self.inner.predict(x, y)?;
        }
        if FAULT == UNTRAINED_NAN && self.since_load == 1 {
            y[0] = f64::NAN;
        }
        if FAULT == NONDETERMINISTIC {
            y[0] += 1e-12 * (next(&CALLS) % 7) as f64;
        }
        Ok(())
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        if FAULT == NAN_ACCEPTED && x.iter().chain(y).any(|v| v.is_nan()) {
            return Ok(());
        }
        if FAULT == BAD_UPDATE_CHANGES_MODEL && y.len() != self.output_dim() {
            self.inner.update(x, &[0.5])?;
            return Err(ApproxError::DimensionMismatch {
                what: "target y",
                expected: 1,
                got: y.len(),
            });
        }
        self.since_load = self.since_load.wrapping_add(1);
        if FAULT == LEARNS_DIFFERENTLY_AFTER_LOAD && self.since_load == 0 {
            return self.inner.update(x, &[y[0] + 1.0]);
        }
        check_vector("target y", y, self.output_dim())?;
        self.inner.update(x, &[y[0] + self.bias])
    }
}

impl<const FAULT: u8> Persist for Broken<FAULT> {
    fn save(&self, path: impl AsRef<std::path::Path>) -> Result<(), ApproxError> {
        if FAULT == SAVE_NOT_ATOMIC {
            // Clears the way first, then writes: a failure destroys what was there.
            let path = path.as_ref();
            let _ = std::fs::remove_dir_all(path);
            let _ = std::fs::remove_file(path);
            return Ok(std::fs::write(path, self.to_json()?)?);
        }
        let json = self.to_json()?;
        Ok(steplearn::atomic_file::write_atomic(
            path.as_ref(),
            json.as_bytes(),
        )?)
    }
    fn check_invariants(&self) -> Result<(), ApproxError> {
        self.inner.check_invariants()
    }
    fn from_json(json: &str) -> Result<Self, ApproxError> {
        if FAULT == LOAD_IGNORES_FILE {
            return Ok(Self::new());
        }
        let mut model: Self =
            serde_json::from_str(json).map_err(|e| ApproxError::Corrupt(e.to_string()))?;
        if FAULT != LOAD_UNCHECKED {
            model.check_invariants()?;
        }
        model.since_load = u64::MAX;
        Ok(model)
    }
}

fn rejected_by<A: FunctionApproximator + Persist + Clone>(
    make: impl Fn() -> A,
    check: &str,
) -> ConformanceError {
    assert!(CHECKS.contains(&check));
    let err = check_approximator(make).expect_err("a broken approximator passed the suite");
    assert_eq!(err.check, check, "caught by the wrong check: {err}");
    assert!(err.to_string().contains(check));
    err
}

#[test]
fn silently_accepting_nan_is_caught() {
    let err = rejected_by(Broken::<NAN_ACCEPTED>::new, "bad_input_rejected");
    assert!(err.reason.contains("NonFinite"), "{err}");
}

#[test]
fn nondeterministic_predictions_are_caught() {
    rejected_by(Broken::<NONDETERMINISTIC>::new, "predict_deterministic");
}

#[test]
fn a_load_that_ignores_the_file_is_caught() {
    rejected_by(Broken::<LOAD_IGNORES_FILE>::new, "save_load_exact");
}

#[test]
fn learning_differently_after_a_load_is_caught() {
    rejected_by(
        Broken::<LEARNS_DIFFERENTLY_AFTER_LOAD>::new,
        "learning_after_round_trip",
    );
}

#[test]
fn a_rejected_update_that_changes_the_model_is_caught() {
    let err = rejected_by(
        Broken::<BAD_UPDATE_CHANGES_MODEL>::new,
        "bad_input_rejected",
    );
    assert!(err.reason.contains("changed the model"), "{err}");
}

#[test]
fn a_panic_is_an_error_not_a_panic() {
    let err = rejected_by(Broken::<PANICS_ON_SHORT_INPUT>::new, "bad_input_rejected");
    assert!(err.reason.contains("panicked"), "{err}");
}

#[test]
fn models_that_disagree_on_their_dimensions_are_caught() {
    let err = rejected_by(Broken::<WRONG_OUTPUT_DIM>::new, "dimensions");
    assert!(err.reason.contains("differ in their dimensions"), "{err}");
}

#[test]
fn non_finite_untrained_predictions_are_caught() {
    rejected_by(Broken::<UNTRAINED_NAN>::new, "untrained_predictions_finite");
}

#[test]
fn a_save_that_destroys_what_was_there_is_caught() {
    let err = rejected_by(Broken::<SAVE_NOT_ATOMIC>::new, "failed_save_harmless");
    assert!(
        err.reason.contains("non-empty directory succeeded"),
        "{err}"
    );
}

#[test]
fn a_model_that_depends_on_more_than_its_data_is_caught() {
    let err = rejected_by(Broken::<DEPENDS_ON_INSTANCE>::new, "same_data_same_model");
    assert!(err.reason.contains("differ"), "{err}");
}

#[test]
fn a_load_that_skips_the_invariants_is_caught() {
    let err = rejected_by(
        Broken::<LOAD_UNCHECKED>::new,
        "corrupt_saved_model_rejected",
    );
    assert!(
        err.reason.contains("tampered") || err.reason.contains("panicked"),
        "{err}"
    );
}

#[test]
fn a_predict_that_ignores_its_input_is_caught() {
    let err = rejected_by(Broken::<IGNORES_INPUT>::new, "predictions_depend_on_input");
    assert!(err.reason.contains("do not depend on the input"), "{err}");
}

/// Runs the whole suite on one broken approximator.
type Suite = fn() -> Result<(), ConformanceError>;

/// Each check with a broken approximator that reaches it (every earlier check passes it) and
/// fails there.
const BROKEN: &[(&str, Suite)] = &[
    ("dimensions", || {
        check_approximator(Broken::<WRONG_OUTPUT_DIM>::new)
    }),
    ("predict_deterministic", || {
        check_approximator(Broken::<NONDETERMINISTIC>::new)
    }),
    ("untrained_predictions_finite", || {
        check_approximator(Broken::<UNTRAINED_NAN>::new)
    }),
    ("predictions_depend_on_input", || {
        check_approximator(Broken::<IGNORES_INPUT>::new)
    }),
    ("bad_input_rejected", || {
        check_approximator(Broken::<NAN_ACCEPTED>::new)
    }),
    ("save_load_exact", || {
        check_approximator(Broken::<LOAD_IGNORES_FILE>::new)
    }),
    ("learning_after_round_trip", || {
        check_approximator(Broken::<LEARNS_DIFFERENTLY_AFTER_LOAD>::new)
    }),
    ("same_data_same_model", || {
        check_approximator(Broken::<DEPENDS_ON_INSTANCE>::new)
    }),
    ("corrupt_saved_model_rejected", || {
        check_approximator(Broken::<LOAD_UNCHECKED>::new)
    }),
    ("failed_save_harmless", || {
        check_approximator(Broken::<SAVE_NOT_ATOMIC>::new)
    }),
];

#[test]
fn every_check_has_a_broken_approximator_that_only_it_catches() {
    // Run, not searched for: every check of the suite fails its broken approximator (which
    // passed every check before it), so a check added without one, or one that stops catching
    // its defect, fails here.
    for check in CHECKS {
        let (_, suite) = BROKEN
            .iter()
            .find(|(name, _)| name == check)
            .unwrap_or_else(|| panic!("no broken approximator for {check}"));
        let err = suite().expect_err("a broken approximator passed the suite");
        assert_eq!(err.check, *check, "caught by the wrong check: {err}");
    }
    assert_eq!(
        BROKEN.len(),
        CHECKS.len(),
        "a broken approximator for no check"
    );
}
