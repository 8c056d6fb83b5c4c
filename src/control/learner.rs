//! The footstep learner: a function approximator trained online with a learning rule (paper,
//! section IV-C, eq. 6).
//!
//! Every control tick the controller calls [`FootstepLearner::query`] with the current
//! (theta_E, theta_E_dot, F_R) and adds the returned offset dF to its footstep. The learner
//! remembers (a bounded, evenly spread subset of) the inputs it was queried at during the step.
//! At touch-down the controller calls [`FootstepLearner::touch_down`] with the measured
//! [`StepOutcome`]; the rule turns it into a gradient G and, for every recorded input x_i, the
//! approximator is trained toward F(x_i) + eta G.
//!
//! The learner knows nothing about whether the analytic footstep is on ("initialised") or off
//! ("not initialised", experiment D): that switch belongs to the controller, which either adds
//! dF to the Capture Step footstep or uses dF as the whole step. The learner trains dF the same
//! way in both cases.
//!
//! Stability note: near the reference, eq. (5) changes by p_theta p_F = 4.5 per metre of step
//! error, and eta = 1 adds G (in metres) to dF. If the approximator moved a fraction r of the
//! way to its targets per step, the step error would evolve as e <- (1 - 4.5 r) e, which
//! overshoots for r > 0.22 and no longer settles for r > 0.44 (a limit cycle bounded by the
//! saturation). LWPR's receptive fields average over their history, so r shrinks quickly; an
//! approximator with a large fixed learning rate needs a smaller eta (see the toy-walker test
//! in `tests/learner.rs`).
//!
//! On the simulated humanoid the loop is harder than this estimate (measured, see the README):
//! the Capture Step controller feeds back on the CoM, so a constant dF is largely cancelled by
//! the next analytic footsteps (the first step realises about 0.6 dF, later ones less), while
//! the trunk angle at touch-down follows the realised step (about +0.55 rad per metre). With
//! eta = 1 dF runs away within seconds even without pushes.

use crate::approx::{ApproxError, FunctionApproximator, InputBox, Persist};
use crate::rules::{LearningRule, StepOutcome};
use serde::{Deserialize, Serialize};
use std::path::Path;
use thiserror::Error;

/// Number of inputs of the learner's approximator: (theta_E, theta_E_dot, F_R).
pub const LEARNER_INPUTS: usize = 3;

/// One query point of the learner.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct LearnerInput {
    /// Trunk deviation angle theta_E (rad).
    pub theta_e: f64,
    /// Its rate theta_E_dot (rad/s).
    pub theta_e_dot: f64,
    /// Reference step size F_R (m).
    pub f_r: f64,
}

impl LearnerInput {
    /// The input at (theta_E, theta_E_dot, F_R).
    pub fn new(theta_e: f64, theta_e_dot: f64, f_r: f64) -> Self {
        LearnerInput {
            theta_e,
            theta_e_dot,
            f_r,
        }
    }

    /// The input as the approximator sees it: `[theta_E, theta_E_dot, F_R]`.
    pub fn to_array(self) -> [f64; LEARNER_INPUTS] {
        [self.theta_e, self.theta_e_dot, self.f_r]
    }
}

/// Errors of the learner. A rejected call leaves the learner as it was (see each method).
#[derive(Debug, Error)]
pub enum LearnerError {
    /// The configuration is invalid.
    #[error("invalid learner configuration: {param} {reason}")]
    InvalidConfig {
        /// The field's name.
        param: &'static str,
        /// Why, with the value.
        reason: String,
    },
    /// The approximator does not map 3 inputs to 1 output.
    #[error(
        "approximator must map {LEARNER_INPUTS} inputs to 1 output, it maps {inputs} to {outputs}"
    )]
    WrongApproximatorShape {
        /// Its input dimension.
        inputs: usize,
        /// Its output dimension.
        outputs: usize,
    },
    /// A query input or a step outcome held NaN or an infinity.
    #[error("{what} is not finite: {value}")]
    NonFinite {
        /// What was not finite (e.g. `"theta_e"`, `"gradient G"`).
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// The approximator rejected a call; `applied` training samples of this touch-down had
    /// already been applied (0 unless the approximator fails on a sample the learner had
    /// checked to be finite).
    #[error("approximator error after {applied} applied updates: {source}")]
    Approx {
        /// Updates of this touch-down applied before the error.
        applied: usize,
        /// The approximator's error.
        source: ApproxError,
    },
}

impl LearnerError {
    fn config(param: &'static str, reason: impl Into<String>) -> Self {
        LearnerError::InvalidConfig {
            param,
            reason: reason.into(),
        }
    }

    fn approx(source: ApproxError) -> Self {
        LearnerError::Approx { applied: 0, source }
    }
}

/// Settings of the learner.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LearnerConfig {
    /// Learning rate eta of eq. (6) (paper: 1). Must be finite and > 0.
    pub eta: f64,
    /// At most this many inputs are kept per step (>= 2). When the buffer is full, every
    /// second sample is dropped and only every second later query is recorded (the stride
    /// doubles), so the kept samples stay evenly spread over the whole step and memory is
    /// bounded whatever the tick rate and step duration. A step of n ticks keeps between
    /// `max_samples_per_step / 2` and `max_samples_per_step` samples once n exceeds the bound;
    /// all of them otherwise. Default 128 (every tick of a 0.5 s step at 250 Hz).
    pub max_samples_per_step: usize,
    /// If set, the offset returned by [`FootstepLearner::query`] is clamped to +-this (m);
    /// training targets are not clamped. Must be finite and > 0.
    pub max_offset: Option<f64>,
}

impl Default for LearnerConfig {
    /// eta = 1, 128 samples per step, no clamp.
    fn default() -> Self {
        LearnerConfig {
            eta: 1.0,
            max_samples_per_step: 128,
            max_offset: None,
        }
    }
}

impl LearnerConfig {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), LearnerError> {
        if !(self.eta.is_finite() && self.eta > 0.0) {
            return Err(LearnerError::config(
                "eta",
                format!("must be finite and > 0, got {}", self.eta),
            ));
        }
        if self.max_samples_per_step < 2 {
            return Err(LearnerError::config(
                "max_samples_per_step",
                format!("must be >= 2, got {}", self.max_samples_per_step),
            ));
        }
        if let Some(m) = self.max_offset
            && !(m.is_finite() && m > 0.0)
        {
            return Err(LearnerError::config(
                "max_offset",
                format!("must be finite and > 0, got {m}"),
            ));
        }
        Ok(())
    }
}

/// What a touch-down did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TouchDownReport {
    /// The rule's gradient G.
    pub gradient: f64,
    /// Number of training samples applied (the recorded inputs of the step).
    pub samples: usize,
}

/// An axis-aligned box over (theta_E, theta_E_dot, F_R) sampled on an even grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputGrid {
    /// Lower corner.
    pub lo: LearnerInput,
    /// Upper corner.
    pub hi: LearnerInput,
    /// Points per axis (>= 1; with 1 the axis is sampled at the box's centre).
    pub points: [usize; LEARNER_INPUTS],
}

impl Default for InputGrid {
    /// theta_E in [-0.5, 0.5] rad, theta_E_dot in [-3, 3] rad/s, F_R in [-0.1, 0.2] m (the
    /// paper's reference range), 21 x 21 x 7 points.
    fn default() -> Self {
        InputGrid {
            lo: LearnerInput {
                theta_e: -0.5,
                theta_e_dot: -3.0,
                f_r: -0.1,
            },
            hi: LearnerInput {
                theta_e: 0.5,
                theta_e_dot: 3.0,
                f_r: 0.2,
            },
            points: [21, 21, 7],
        }
    }
}

/// `n` evenly spaced values from `lo` to `hi` (the midpoint when `n == 1`).
pub fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![0.5 * (lo + hi)],
        _ => (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect(),
    }
}

fn check_range(param: &'static str, lo: f64, hi: f64, n: usize) -> Result<(), LearnerError> {
    if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
        return Err(LearnerError::config(
            param,
            format!("needs finite bounds with lo <= hi, got [{lo}, {hi}]"),
        ));
    }
    if n == 0 {
        return Err(LearnerError::config(param, "needs at least 1 point"));
    }
    Ok(())
}

impl InputGrid {
    /// Checks that the bounds are finite and ordered and every axis has at least one point.
    pub fn validate(&self) -> Result<(), LearnerError> {
        let (lo, hi) = (self.lo.to_array(), self.hi.to_array());
        for (axis, name) in ["theta_e", "theta_e_dot", "f_r"].into_iter().enumerate() {
            check_range(name, lo[axis], hi[axis], self.points[axis])?;
        }
        Ok(())
    }

    /// The grid's box as an [`InputBox`], what [`crate::approx::ApproxKind::build`] sizes a
    /// fresh approximator from. Errors if the box is degenerate (an axis with `lo >= hi`).
    pub fn input_box(&self) -> Result<InputBox, ApproxError> {
        InputBox::new(self.lo.to_array().to_vec(), self.hi.to_array().to_vec())
    }
}

/// dF sampled on a 2-D grid over (theta_E, theta_E_dot) at a fixed F_R (for Fig. 8 maps).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OffsetMap {
    /// The theta_E values (columns), ascending.
    pub theta_e: Vec<f64>,
    /// The theta_E_dot values (rows), ascending.
    pub theta_e_dot: Vec<f64>,
    /// The fixed reference step size.
    pub f_r: f64,
    /// Raw approximator output (unclamped), row-major: `values[row * theta_e.len() + col]`.
    pub values: Vec<f64>,
}

/// Where and how finely to sample an [`OffsetMap`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapSpec {
    /// theta_E range (rad).
    pub theta_e: (f64, f64),
    /// theta_E_dot range (rad/s).
    pub theta_e_dot: (f64, f64),
    /// The fixed F_R (m).
    pub f_r: f64,
    /// Columns (theta_E points) and rows (theta_E_dot points), each >= 1.
    pub resolution: (usize, usize),
}

impl Default for MapSpec {
    /// theta_E in [-0.5, 0.5], theta_E_dot in [-3, 3], F_R = 0 (stepping in place), 41 x 41.
    fn default() -> Self {
        MapSpec {
            theta_e: (-0.5, 0.5),
            theta_e_dot: (-3.0, 3.0),
            f_r: 0.0,
            resolution: (41, 41),
        }
    }
}

/// What [`FootstepLearner::save`] writes: the config and the approximator (JSON). The rule is
/// not part of the saved model; the caller supplies it on load.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedLearner<A> {
    /// The learner's settings.
    pub config: LearnerConfig,
    /// The trained approximator.
    pub approximator: A,
}

impl<A: Persist + FunctionApproximator> Persist for SavedLearner<A> {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        self.config
            .validate()
            .map_err(|e| ApproxError::Corrupt(e.to_string()))?;
        self.approximator.check_invariants()?;
        if self.approximator.input_dim() != LEARNER_INPUTS || self.approximator.output_dim() != 1 {
            return Err(ApproxError::Corrupt(format!(
                "saved approximator maps {} inputs to {} outputs, the learner needs 3 to 1",
                self.approximator.input_dim(),
                self.approximator.output_dim()
            )));
        }
        Ok(())
    }
}

/// Learns the footstep offset dF over (theta_E, theta_E_dot, F_R) online (eq. 6).
pub struct FootstepLearner<A: FunctionApproximator, R: LearningRule> {
    approx: A,
    rule: R,
    config: LearnerConfig,
    /// Inputs recorded in the current step (capacity `max_samples_per_step`, never grows).
    recorded: Vec<[f64; LEARNER_INPUTS]>,
    /// Record every `stride`-th query of this step.
    stride: usize,
    /// Queries seen in this step.
    queries: usize,
    /// Scratch for the targets at touch-down (capacity `max_samples_per_step`).
    targets: Vec<f64>,
}

impl<A: FunctionApproximator, R: LearningRule> FootstepLearner<A, R> {
    /// A learner around `approx` (3 inputs, 1 output) and `rule`.
    pub fn new(approx: A, rule: R, config: LearnerConfig) -> Result<Self, LearnerError> {
        config.validate()?;
        if approx.input_dim() != LEARNER_INPUTS || approx.output_dim() != 1 {
            return Err(LearnerError::WrongApproximatorShape {
                inputs: approx.input_dim(),
                outputs: approx.output_dim(),
            });
        }
        Ok(FootstepLearner {
            approx,
            rule,
            config,
            recorded: Vec::with_capacity(config.max_samples_per_step),
            stride: 1,
            queries: 0,
            targets: Vec::with_capacity(config.max_samples_per_step),
        })
    }

    /// The settings.
    pub fn config(&self) -> &LearnerConfig {
        &self.config
    }

    /// The approximator.
    pub fn approximator(&self) -> &A {
        &self.approx
    }

    /// The rule.
    pub fn rule(&self) -> &R {
        &self.rule
    }

    /// Takes the learner apart into its approximator and rule.
    pub fn into_parts(self) -> (A, R) {
        (self.approx, self.rule)
    }

    /// The inputs recorded so far in the current step, in query order.
    pub fn recorded_inputs(&self) -> impl ExactSizeIterator<Item = LearnerInput> + '_ {
        self.recorded.iter().map(|x| LearnerInput {
            theta_e: x[0],
            theta_e_dot: x[1],
            f_r: x[2],
        })
    }

    /// The raw approximator output at `input` (no clamp, nothing recorded).
    pub fn predict(&self, input: LearnerInput) -> Result<f64, LearnerError> {
        self.predict_array(&input.to_array())
    }

    fn predict_array(&self, x: &[f64; LEARNER_INPUTS]) -> Result<f64, LearnerError> {
        let mut y = [0.0];
        self.approx
            .predict(x, &mut y)
            .map_err(LearnerError::approx)?;
        if !y[0].is_finite() {
            return Err(LearnerError::NonFinite {
                what: "approximator prediction",
                value: y[0],
            });
        }
        Ok(y[0])
    }

    /// The control-tick query: returns dF at `input` (clamped to `max_offset` if set) and
    /// records the input for the touch-down update (subject to the per-step bound). Does not
    /// allocate. On error nothing is recorded.
    pub fn query(&mut self, input: LearnerInput) -> Result<f64, LearnerError> {
        let x = input.to_array();
        for (what, v) in ["theta_e", "theta_e_dot", "f_r"].into_iter().zip(x) {
            if !v.is_finite() {
                return Err(LearnerError::NonFinite { what, value: v });
            }
        }
        let df = self.predict_array(&x)?;
        self.record(x);
        Ok(match self.config.max_offset {
            Some(m) => df.clamp(-m, m),
            None => df,
        })
    }

    fn record(&mut self, x: [f64; LEARNER_INPUTS]) {
        if self.queries.is_multiple_of(self.stride) {
            if self.recorded.len() == self.config.max_samples_per_step {
                // Keep samples 0, 2, 4, ... (query indices that are multiples of 2 * stride).
                let mut keep = 0;
                for i in (0..self.recorded.len()).step_by(2) {
                    self.recorded[keep] = self.recorded[i];
                    keep += 1;
                }
                self.recorded.truncate(keep);
                self.stride *= 2;
            }
            if self.queries.is_multiple_of(self.stride) {
                self.recorded.push(x);
            }
        }
        self.queries += 1;
    }

    /// Forgets the inputs of the current step without learning from it (e.g. after a fall and
    /// reset, when the step never touched down).
    pub fn discard_step(&mut self) {
        self.recorded.clear();
        self.stride = 1;
        self.queries = 0;
    }

    /// Ends the step: computes G with the rule and applies eq. (6) to every recorded input,
    /// then starts a new step.
    ///
    /// All predictions F(x_i) are taken before the first update, so every target is
    /// F_old(x_i) + eta G whatever the order of the updates (eq. 6 read literally; otherwise an
    /// update at x_1 would shift the target at a nearby x_2). Everything the learner can check
    /// (G finite, predictions and targets finite) is checked before the first update: such a
    /// rejection changes nothing, the recorded inputs included (call [`Self::discard_step`] to
    /// drop them). If the approximator still fails during an update, the updates already
    /// applied stay (each one is all-or-nothing by the [`FunctionApproximator`] contract, so the
    /// model is valid), the error reports how many were applied, and the step is discarded.
    pub fn touch_down(&mut self, step: &StepOutcome) -> Result<TouchDownReport, LearnerError> {
        for (what, v) in [
            ("theta_e", step.theta_e),
            ("theta_e_dot", step.theta_e_dot),
            ("f_e", step.f_e),
            ("f_r", step.f_r),
        ] {
            if !v.is_finite() {
                return Err(LearnerError::NonFinite { what, value: v });
            }
        }
        let g = self.rule.gradient(step);
        if !g.is_finite() {
            return Err(LearnerError::NonFinite {
                what: "gradient G",
                value: g,
            });
        }
        let step_size = self.config.eta * g;
        self.targets.clear();
        for x in &self.recorded {
            let target = self.predict_array(x)? + step_size;
            if !target.is_finite() {
                return Err(LearnerError::NonFinite {
                    what: "training target",
                    value: target,
                });
            }
            self.targets.push(target);
        }
        let samples = self.recorded.len();
        let mut result = Ok(TouchDownReport {
            gradient: g,
            samples,
        });
        for (applied, (x, t)) in self.recorded.iter().zip(&self.targets).enumerate() {
            if let Err(source) = self.approx.update(x, &[*t]) {
                result = Err(LearnerError::Approx { applied, source });
                break;
            }
        }
        self.discard_step();
        result
    }

    /// The learning metric of experiment D: the Euclidean norm of the approximator's outputs
    /// over an even grid of the input space (zero for an untrained, zero-initialised model).
    pub fn learning_metric(&self, grid: &InputGrid) -> Result<f64, LearnerError> {
        grid.validate()?;
        let (lo, hi) = (grid.lo.to_array(), grid.hi.to_array());
        let axes: Vec<Vec<f64>> = (0..LEARNER_INPUTS)
            .map(|a| linspace(lo[a], hi[a], grid.points[a]))
            .collect();
        let mut sum = 0.0;
        for &a in &axes[0] {
            for &b in &axes[1] {
                for &c in &axes[2] {
                    let y = self.predict_array(&[a, b, c])?;
                    sum += y * y;
                }
            }
        }
        Ok(sum.sqrt())
    }

    /// Samples dF (raw approximator output) over (theta_E, theta_E_dot) at a fixed F_R.
    pub fn offset_map(&self, spec: &MapSpec) -> Result<OffsetMap, LearnerError> {
        check_range("theta_e", spec.theta_e.0, spec.theta_e.1, spec.resolution.0)?;
        check_range(
            "theta_e_dot",
            spec.theta_e_dot.0,
            spec.theta_e_dot.1,
            spec.resolution.1,
        )?;
        if !spec.f_r.is_finite() {
            return Err(LearnerError::NonFinite {
                what: "f_r",
                value: spec.f_r,
            });
        }
        let theta_e = linspace(spec.theta_e.0, spec.theta_e.1, spec.resolution.0);
        let theta_e_dot = linspace(spec.theta_e_dot.0, spec.theta_e_dot.1, spec.resolution.1);
        let mut values = Vec::with_capacity(theta_e.len() * theta_e_dot.len());
        for &rate in &theta_e_dot {
            for &angle in &theta_e {
                values.push(self.predict_array(&[angle, rate, spec.f_r])?);
            }
        }
        Ok(OffsetMap {
            theta_e,
            theta_e_dot,
            f_r: spec.f_r,
            values,
        })
    }
}

impl<A: FunctionApproximator + Persist + Clone, R: LearningRule> FootstepLearner<A, R> {
    /// Saves the config and the approximator to `path` as JSON (atomically: temporary file and
    /// rename, so a failed save leaves an existing file intact). The current step's recorded
    /// inputs are not saved.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), LearnerError> {
        SavedLearner {
            config: self.config,
            approximator: self.approx.clone(),
        }
        .save(path)
        .map_err(LearnerError::approx)
    }

    /// Loads a learner saved by [`Self::save`] with `rule`; it keeps learning from there. A
    /// corrupt file or a wrongly shaped approximator is an error.
    pub fn load(path: impl AsRef<Path>, rule: R) -> Result<Self, LearnerError> {
        let saved = SavedLearner::<A>::load(path).map_err(LearnerError::approx)?;
        Self::new(saved.approximator, rule, saved.config)
    }
}
