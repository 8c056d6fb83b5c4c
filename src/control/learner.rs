//! The footstep learner: a function approximator trained online with a learning rule (paper,
//! section IV-C, eq. 6).

use super::learner_config::check_range;
use super::learner_config::{
    CheckedLearnerConfig, LEARNER_INPUTS, LearnerConfig, LearnerInput, MAX_OFFSET_INPUTS,
    OffsetSettings, TrustFallback,
};
use super::learner_error::LearnerError;
use super::step_parameter::{FallDirection, Plane, StepParameter};
use super::step_samples::{StepSamples, trust_share};
use crate::approx::{ApproxError, FunctionApproximator, InputBox, Persist};
use crate::rules::{LearningRule, StepOutcome};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Retries of the gain guard before it gives up on a touch-down (and leaves the model as it
/// was).
const GUARD_RETRIES: usize = 6;

/// What a touch-down did. The default (all zero) is a touch-down that taught nothing.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct TouchDownReport {
    /// The rule's gradient G.
    pub gradient: f64,
    /// Number of training samples applied (the recorded inputs of the step).
    pub samples: usize,
    /// The approximator's response r to the full step: the share of the desired change
    /// (eta G, after anti-windup) that its predictions at the recorded inputs moved,
    /// `<dy, d> / <d, d>` (0 when nothing was asked).
    pub response: f64,
    /// The learning gain applied: eta times the share of the desired change the predictions
    /// finally moved (after the guard), metres of dF per unit of G.
    pub gain: f64,
    /// The factor the guard scaled the step by (1: not scaled).
    pub scale: f64,
}

/// An axis-aligned box over (theta_E, theta_E_dot, F_R) sampled on an even grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
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

use crate::stats::{MeanStd, linspace};

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
#[serde(default, deny_unknown_fields)]
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

/// What [`OffsetLearner::save`] writes (JSON): everything the learner holds but its rules, and
/// each rule's state if it keeps one ([`LearningRule::state`]), so that a learner loaded mid-step
/// continues exactly as the saved one would have. The rule itself is supplied by the caller on
/// load.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedLearner<A> {
    /// The learner's settings.
    pub config: LearnerConfig,
    /// The step parameter it learns (left out for the paper's `step-x`, and absent from files
    /// from before other parameters could be learned).
    #[serde(default, skip_serializing_if = "StepParameter::is_step_x")]
    pub parameter: StepParameter,
    /// The trained approximator.
    pub approximator: A,
    /// Per-input mean and std of the inputs the learner was trained at (its trust region),
    /// one per input; empty in files from before it existed (nothing trained yet).
    #[serde(default)]
    pub trained: Vec<MeanStd>,
    /// The step in progress (with the first offset's reach, last value and exploration); an
    /// empty step in files from before checkpoints.
    #[serde(default)]
    pub step: StepInProgress,
    /// The first offset's rule state ([`LearningRule::state`]); absent for a stateless rule
    /// and in files from before rules could keep one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rule_state: Option<serde_json::Value>,
    /// The offsets after the first, in output order, for a learner of several (the coupled
    /// learner's dW); absent for a learner of one.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub more_offsets: Vec<SavedOffset>,
}

/// What a checkpoint holds of an offset after the first: its parameter, the reach of each
/// input recorded in the step, its last value, its exploration and its rule's state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedOffset {
    /// The step parameter it learns.
    pub parameter: StepParameter,
    /// The reach `[lo, hi]` of each input recorded in the step (as [`StepInProgress::reach`]).
    pub reach: Vec<[Option<f64>; 2]>,
    /// The value the last query returned.
    pub last_offset: f64,
    /// Its rule's exploration perturbation of this step; absent when 0.
    #[serde(default, skip_serializing_if = "crate::config::is_zero")]
    pub exploration: f64,
    /// Its rule's state; absent for a stateless rule.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rule_state: Option<serde_json::Value>,
}

/// The current step as the learner has seen it: the inputs recorded for the touch-down update,
/// their reach and the query counters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepInProgress {
    /// Inputs recorded in this step, in query order (each with one value per input).
    pub recorded: Vec<Vec<f64>>,
    /// The reach `[lo, hi]` of each recorded input; `None` for an unbounded side.
    pub reach: Vec<[Option<f64>; 2]>,
    /// Whether the last query was recorded.
    pub last_recorded: bool,
    /// Every `stride`-th query of this step is recorded (a power of two).
    pub stride: usize,
    /// Queries seen in this step.
    pub queries: usize,
    /// The offset the last query returned (m).
    pub last_offset: f64,
    /// The rule's exploration perturbation of this step (m; [`LearningRule::explore`]);
    /// absent when 0.
    #[serde(default, skip_serializing_if = "crate::config::is_zero")]
    pub exploration: f64,
}

impl Default for StepInProgress {
    fn default() -> Self {
        StepInProgress {
            recorded: Vec::new(),
            reach: Vec::new(),
            last_recorded: false,
            stride: 1,
            queries: 0,
            last_offset: 0.0,
            exploration: 0.0,
        }
    }
}

/// Checks one offset's saved state against a step of `recorded` inputs and `queries`
/// queries: a reach per recorded input, each an interval, a finite last value and exploration,
/// and no exploration before the step's first query (`what` names the offset in the error).
fn check_saved_offset(
    what: &str,
    reach: &[[Option<f64>; 2]],
    last_offset: f64,
    exploration: f64,
    recorded: usize,
    queries: usize,
) -> Result<(), ApproxError> {
    let corrupt = |msg: String| {
        Err(ApproxError::Corrupt(format!(
            "step in progress: {what}: {msg}"
        )))
    };
    if reach.len() != recorded {
        return corrupt(format!(
            "{} reaches for {recorded} recorded inputs",
            reach.len()
        ));
    }
    if !last_offset.is_finite() || !exploration.is_finite() {
        return corrupt("the last offset or the exploration is not finite".into());
    }
    if exploration != 0.0 && queries == 0 {
        return corrupt("an exploration perturbation before the step's first query".into());
    }
    for [lo, hi] in reach {
        let (lo, hi) = (lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY));
        if !is_reach(lo, hi) {
            return corrupt(format!("reach [{lo}, {hi}] is not an interval"));
        }
    }
    Ok(())
}

impl StepInProgress {
    /// Checks that the step could have come from a learner with `max_samples` per step and
    /// `inputs` inputs.
    fn check(&self, max_samples: usize, inputs: usize) -> Result<(), ApproxError> {
        let corrupt = |msg: String| Err(ApproxError::Corrupt(format!("step in progress: {msg}")));
        let n = self.recorded.len();
        if n > max_samples {
            return corrupt(format!("{n} recorded inputs, at most {max_samples}"));
        }
        if !self.stride.is_power_of_two()
            || n > self.queries
            || self.stride > self.queries.max(1)
            || self.queries as u64 > crate::stats::MAX_COUNT
        {
            return corrupt(format!(
                "stride {} and {} queries do not fit {n} recorded inputs",
                self.stride, self.queries
            ));
        }
        if self.last_recorded && n == 0 {
            return corrupt("the last query is recorded but nothing is".into());
        }
        if let Some(x) = self.recorded.iter().find(|x| x.len() != inputs) {
            return corrupt(format!(
                "a recorded input has {} values, the approximator {inputs} inputs",
                x.len()
            ));
        }
        if !self.recorded.iter().flatten().all(|v| v.is_finite()) {
            return corrupt("a recorded input is not finite".into());
        }
        check_saved_offset(
            "the first offset",
            &self.reach,
            self.last_offset,
            self.exploration,
            n,
            self.queries,
        )
    }
}

impl SavedOffset {
    /// Checks that the offset could have come from a learner whose step recorded `recorded`
    /// inputs in `queries` queries.
    fn check(&self, recorded: usize, queries: usize) -> Result<(), ApproxError> {
        check_saved_offset(
            &format!("offset {}", self.parameter),
            &self.reach,
            self.last_offset,
            self.exploration,
            recorded,
            queries,
        )
    }
}

/// Anti-windup (conditional integration): `change` of a prediction `before` limited so that
/// the target goes no further past an end of `reach` than the prediction already is (and is
/// never pulled into it: outside the reach every offset has the same effect at that tick).
pub(crate) fn windup(change: f64, before: f64, reach: [f64; 2]) -> f64 {
    if change > 0.0 {
        change.min((reach[1] - before).max(0.0))
    } else if change < 0.0 {
        change.max((reach[0] - before).min(0.0))
    } else {
        change
    }
}

/// The outputs of `approx` at `x`, checked to be finite.
fn predict_at<A: FunctionApproximator, const I: usize, const O: usize>(
    approx: &A,
    x: &[f64; I],
) -> Result<[f64; O], LearnerError> {
    let mut y = [0.0; O];
    approx.predict(x, &mut y).map_err(LearnerError::approx)?;
    if let Some(v) = y.iter().find(|v| !v.is_finite()) {
        return Err(LearnerError::NonFinite {
            what: "approximator prediction",
            value: *v,
        });
    }
    Ok(y)
}

/// Trains `approx` toward `before + scale * desired` at every input.
fn train_towards<A: FunctionApproximator, const I: usize, const O: usize>(
    approx: &mut A,
    inputs: &[[f64; I]],
    before: &[[f64; O]],
    desired: &[[f64; O]],
    scale: f64,
) -> Result<(), LearnerError> {
    for (applied, ((x, b), d)) in inputs.iter().zip(before).zip(desired).enumerate() {
        let target: [f64; O] = std::array::from_fn(|k| b[k] + scale * d[k]);
        approx
            .update(x, &target)
            .map_err(|source| LearnerError::Approx { applied, source })?;
    }
    Ok(())
}

/// Per output, the share `<dy, d> / <d, d>` of the desired change the predictions at `inputs`
/// moved (0 for an output where nothing was `asked`, `<d, d>` = 0).
fn response<A: FunctionApproximator, const I: usize, const O: usize>(
    approx: &A,
    inputs: &[[f64; I]],
    before: &[[f64; O]],
    desired: &[[f64; O]],
    asked: [f64; O],
) -> Result<[f64; O], LearnerError> {
    if asked.iter().all(|a| *a == 0.0) {
        return Ok([0.0; O]);
    }
    let mut moved = [0.0; O];
    for ((x, b), d) in inputs.iter().zip(before).zip(desired) {
        let y: [f64; O] = predict_at(approx, x)?;
        for k in 0..O {
            moved[k] += (y[k] - b[k]) * d[k];
        }
    }
    Ok(std::array::from_fn(|k| {
        if asked[k] == 0.0 {
            0.0
        } else {
            moved[k] / asked[k]
        }
    }))
}

/// `step` as a learner sees it after a fall: theta_E clamped to +-`limit`, its rate to ten
/// times that (past the fall threshold the angle says nothing more).
pub(crate) fn clamped_at_fall(step: &StepOutcome, limit: f64) -> StepOutcome {
    StepOutcome {
        theta_e: step.theta_e.clamp(-limit, limit),
        theta_e_dot: step.theta_e_dot.clamp(-10.0 * limit, 10.0 * limit),
        ..*step
    }
}

/// How a guarded update ended ([`guarded_update`]).
pub(crate) struct Guarded<T> {
    /// The factor the step was scaled by (1: not scaled; 0: no scale within the retries, the
    /// approximator is as it was).
    pub(crate) scale: f64,
    /// The response to the full step (the first attempt).
    pub(crate) first: T,
    /// The response of the update finally applied (`none` when none was).
    pub(crate) applied: T,
}

/// Why a guarded update failed: while training (the caller discards the step) or while
/// measuring the response.
pub(crate) enum GuardError {
    /// `apply` failed.
    Apply(LearnerError),
    /// `measure` failed.
    Measure(LearnerError),
}

/// The gain guard (see [`FootstepLearner`]), for any learner: `apply(approx, scale)` trains the
/// step scaled by `scale`, `measure` gives the response and `gain` the largest |gain| it
/// means. With `limit` set, while that gain exceeds it the step is scaled to just below the
/// limit and applied again to the approximator as it was (a copy), at most [`GUARD_RETRIES`]
/// times; then the approximator is restored and the scale is 0.
pub(crate) fn guarded_update<A: Clone, T: Copy>(
    approx: &mut A,
    limit: Option<f64>,
    none: T,
    mut apply: impl FnMut(&mut A, f64) -> Result<(), LearnerError>,
    mut measure: impl FnMut(&A) -> Result<T, LearnerError>,
    gain: impl Fn(&T) -> f64,
) -> Result<Guarded<T>, GuardError> {
    let original = limit.map(|_| approx.clone());
    let mut scale = 1.0;
    let mut first = none;
    let mut applied = none;
    for attempt in 0..=GUARD_RETRIES {
        if attempt > 0
            && let Some(o) = &original
        {
            *approx = o.clone();
        }
        apply(approx, scale).map_err(GuardError::Apply)?;
        applied = measure(approx).map_err(GuardError::Measure)?;
        if attempt == 0 {
            first = applied;
        }
        let g = gain(&applied);
        match limit {
            Some(limit) if g > limit => {
                if attempt == GUARD_RETRIES {
                    // No scale found within the retries: keep the model as it was.
                    if let Some(o) = original {
                        *approx = o;
                    }
                    return Ok(Guarded {
                        scale: 0.0,
                        first,
                        applied: none,
                    });
                }
                // Aim a little below the limit: responses are not quite linear.
                scale *= 0.95 * limit / g;
            }
            _ => break,
        }
    }
    Ok(Guarded {
        scale,
        first,
        applied,
    })
}

/// A reach bound as saved: `None` for an infinite side.
fn finite_or_none(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// Whether `[lo, hi]` is a reach: a non-empty interval, bounds possibly infinite.
pub(crate) fn is_reach(lo: f64, hi: f64) -> bool {
    lo <= hi && lo < f64::INFINITY && hi > f64::NEG_INFINITY
}

impl<A: Persist + FunctionApproximator> Persist for SavedLearner<A> {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        self.config
            .validate()
            .map_err(|e| ApproxError::Corrupt(e.to_string()))?;
        self.approximator.check_invariants()?;
        let (inputs, outputs) = (
            self.approximator.input_dim(),
            self.approximator.output_dim(),
        );
        if inputs == 0
            || !inputs.is_multiple_of(LEARNER_INPUTS)
            || inputs > MAX_OFFSET_INPUTS
            || outputs != 1 + self.more_offsets.len()
        {
            return Err(ApproxError::Corrupt(format!(
                "saved approximator maps {inputs} inputs to {outputs} outputs, the learner needs \
                 a multiple of {LEARNER_INPUTS} inputs (at most {MAX_OFFSET_INPUTS}) and one \
                 output per saved offset ({})",
                1 + self.more_offsets.len()
            )));
        }
        self.step.check(self.config.max_samples_per_step, inputs)?;
        for offset in &self.more_offsets {
            offset.check(self.step.recorded.len(), self.step.queries)?;
        }
        if !(self.trained.is_empty() || self.trained.len() == inputs)
            || !self.trained.iter().all(MeanStd::is_consistent)
        {
            return Err(ApproxError::Corrupt(format!(
                "trained-input statistics: {} entries for {inputs} inputs, or not consistent",
                self.trained.len()
            )));
        }
        Ok(())
    }
}

/// The name of input `axis` in errors: each group of three is (lean, lean rate, reference).
fn input_name(axis: usize) -> &'static str {
    const NAMES: [&str; 6] = [
        "theta_e",
        "theta_e_dot",
        "f_r",
        "lateral lean",
        "lateral lean rate",
        "lateral f_r",
    ];
    NAMES.get(axis).copied().unwrap_or("learner input")
}

/// Refuses settings that learn one of `parameters` in both planes: one learner reads one
/// plane; a [`StepLearner`](super::step_learner::StepLearner) learns both with one each.
fn single_planes(
    settings: &CheckedLearnerConfig,
    parameters: &[StepParameter],
) -> Result<(), LearnerError> {
    match parameters
        .iter()
        .find(|p| settings.planes(**p).single().is_none())
    {
        Some(p) => Err(LearnerError::config(
            super::learner_config::PLANE_KEYS[p.index()],
            format!(
                "a learner of {p} reads one plane; in both planes it is learned by a StepLearner, \
                 one learner per plane"
            ),
        )),
        None => Ok(()),
    }
}

/// The one learner of step offsets: `O` offsets over `I` inputs (a group of three per plane,
/// (lean, lean rate, reference), each spread over the prior's box), learned online with one
/// rule per offset (eq. 6).
///
/// Two shapes are used: [`FootstepLearner`] (one offset over the paper's three inputs, one per
/// learned step parameter) and [`CoupledLearner`](super::coupled::CoupledLearner) (dF and dW
/// over both planes' six inputs, one approximator with two outputs). Every safeguard of
/// [`LearnerConfig`] holds for each offset: the prior, the gain guard (on the largest of the
/// offsets' gains, one scale for all), anti-windup per offset, the trust region over all
/// inputs with either fallback, learning from falls, dead zone, leakage, `max_step_error` (a
/// touch-down any of whose footstep offsets, `step-x` or `step-y`, the model missed by more
/// metres teaches nothing; it does not gate the step time or the soles) and train share.
pub struct OffsetLearner<A: FunctionApproximator, R: LearningRule, const I: usize, const O: usize> {
    approx: A,
    /// One rule per offset, in output order.
    rules: [R; O],
    /// The settings as given (what [`Self::config`] returns and a checkpoint saves).
    config: LearnerConfig,
    /// The same settings, checked and grouped.
    settings: CheckedLearnerConfig,
    /// The step parameter of each offset, in output order.
    parameters: [StepParameter; O],
    /// Inputs recorded in the current step (at most `max_samples_per_step`), each with each
    /// offset's reach (lowest, highest offset that can still change the step; unbounded unless
    /// told by [`OffsetLearner::set_reach_of`]).
    step: StepSamples<[f64; I], [[f64; 2]; O]>,
    /// Scratch at touch-down: predictions before the update and desired changes.
    before: Vec<[f64; O]>,
    desired: Vec<[f64; O]>,
    /// Mean and std of the inputs the learner was trained at, per axis (the trust region).
    trained: [MeanStd; I],
    /// The offsets the last query returned.
    last_offset: [f64; O],
    /// Each rule's exploration perturbation of the current step (drawn at its first query).
    exploration: [f64; O],
    /// The fall direction of each plane, sagittal first, that the gates of its offsets hold
    /// from tick to tick (not saved in a checkpoint).
    fall: [FallDirection; 2],
}

impl<A: FunctionApproximator, R: LearningRule, const I: usize, const O: usize> std::fmt::Debug
    for OffsetLearner<A, R, I, O>
{
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OffsetLearner")
            .field("inputs", &I)
            .field("offsets", &O)
            .field("config", &self.config)
            .field("recorded", &self.step.inputs.len())
            .finish_non_exhaustive()
    }
}

impl<A: FunctionApproximator, R: LearningRule, const I: usize, const O: usize>
    OffsetLearner<A, R, I, O>
{
    /// A learner around `approx` (`I` inputs, `O` outputs) with one rule per output, holding
    /// the prior of `config` (zero offsets trained in at `config.prior.samples` Halton points
    /// of the prior's box, repeated for every group of three inputs; none if 0). Its offsets
    /// are the first `O` step parameters in their fixed order ([`StepParameter::ALL`]: `step-x`,
    /// then `step-y`, then `step-time`), each with its parameter's settings
    /// ([`LearnerConfig::offset`]).
    pub fn with_rules(
        approx: A,
        rules: [R; O],
        config: LearnerConfig,
    ) -> Result<Self, LearnerError> {
        if O > StepParameter::ALL.len() {
            return Err(LearnerError::config(
                "shape",
                format!("{O} offsets need their step parameters named (for_parameters)"),
            ));
        }
        Self::for_parameters(
            approx,
            rules,
            std::array::from_fn(|k| StepParameter::ALL[k]),
            config,
        )
    }

    /// A learner of the step parameters `parameters` (one per output, each taught by its rule
    /// and with its parameter's settings, [`LearnerConfig::offset`]) around `approx`, holding
    /// the prior of `config` as [`Self::with_rules`] does.
    pub fn for_parameters(
        approx: A,
        rules: [R; O],
        parameters: [StepParameter; O],
        config: LearnerConfig,
    ) -> Result<Self, LearnerError> {
        let mut learner = Self::assemble(approx, rules, parameters, config)?;
        for i in 0..config.prior.samples {
            let x = config.prior.point_of::<I>(i);
            learner
                .approx
                .update(&x, &[0.0; O])
                .map_err(LearnerError::approx)?;
        }
        Ok(learner)
    }

    /// A learner around `approx` as it is (no prior trained in).
    fn assemble(
        approx: A,
        rules: [R; O],
        parameters: [StepParameter; O],
        config: LearnerConfig,
    ) -> Result<Self, LearnerError> {
        let settings = config.check()?;
        single_planes(&settings, &parameters)?;
        if I == 0 || !I.is_multiple_of(LEARNER_INPUTS) || I > MAX_OFFSET_INPUTS || O == 0 {
            return Err(LearnerError::config(
                "shape",
                format!(
                    "needs a multiple of {LEARNER_INPUTS} inputs, at most {MAX_OFFSET_INPUTS}, \
                     and at least one offset, got {I} inputs and {O} offsets"
                ),
            ));
        }
        if approx.input_dim() != I || approx.output_dim() != O {
            return Err(LearnerError::WrongApproximatorShape {
                expected: (I, O),
                inputs: approx.input_dim(),
                outputs: approx.output_dim(),
            });
        }
        Ok(OffsetLearner {
            approx,
            rules,
            config,
            settings,
            parameters,
            step: StepSamples::with_capacity(config.max_samples_per_step),
            before: Vec::with_capacity(config.max_samples_per_step),
            desired: Vec::with_capacity(config.max_samples_per_step),
            trained: [MeanStd::new(); I],
            last_offset: [0.0; O],
            exploration: [0.0; O],
            fall: [FallDirection::default(); 2],
        })
    }

    /// The settings.
    pub fn config(&self) -> &LearnerConfig {
        &self.config
    }

    /// The settings, checked and grouped.
    pub fn settings(&self) -> &CheckedLearnerConfig {
        &self.settings
    }

    /// The fall direction held for `plane`'s gates ([`Gate::weight_held`](super::step_parameter::Gate::weight_held)).
    pub(crate) fn fall_direction(&mut self, plane: Plane) -> &mut FallDirection {
        &mut self.fall[plane as usize]
    }

    /// The step parameter of each offset, in output order.
    pub fn parameters(&self) -> [StepParameter; O] {
        self.parameters
    }

    /// The settings of offset `k` (its parameter's, [`LearnerConfig::offset`]).
    fn offset(&self, k: usize) -> OffsetSettings {
        self.settings.offset(self.parameters[k])
    }

    /// The approximator.
    pub fn approximator(&self) -> &A {
        &self.approx
    }

    /// The rules, in output order.
    pub fn rules(&self) -> &[R; O] {
        &self.rules
    }

    /// Reseeds every rule's randomness ([`LearningRule::reseed`]); nothing else changes.
    pub fn reseed(&mut self, seed: u64) {
        for rule in &mut self.rules {
            rule.reseed(seed);
        }
    }

    /// The raw approximator outputs at `x` (no trust region, nothing recorded), checked to be
    /// finite.
    pub fn predict_all(&self, x: &[f64; I]) -> Result<[f64; O], LearnerError> {
        predict_at(&self.approx, x)
    }

    /// The control-tick query: returns the offsets at `x` (faded by the trust region), plus
    /// each rule's exploration perturbation of the step (drawn at the step's first query),
    /// clamped to `max_offset` and `offset_range` if set, and records `x` for the touch-down
    /// update (subject to the per-step bound). On error nothing is recorded (a non-finite
    /// perturbation is an error; the rule has then drawn it).
    pub fn query_all(&mut self, x: [f64; I]) -> Result<[f64; O], LearnerError> {
        for (a, v) in x.iter().enumerate() {
            if !v.is_finite() {
                return Err(LearnerError::NonFinite {
                    what: input_name(a),
                    value: *v,
                });
            }
        }
        let trust = self.trust(&x);
        let mut y = self.predict_all(&x)?.map(|v| v * trust);
        if trust < 1.0 && self.settings.trust.fallback == TrustFallback::Nominal {
            let nominal = self.predict_all(&self.nominal_input(&x))?;
            for (v, n) in y.iter_mut().zip(nominal) {
                *v += (1.0 - trust) * n;
            }
        }
        if self.step.queries == 0 {
            let mut drawn = [0.0; O];
            for (e, rule) in drawn.iter_mut().zip(&mut self.rules) {
                *e = rule.explore();
                if !e.is_finite() {
                    return Err(LearnerError::NonFinite {
                        what: "exploration",
                        value: *e,
                    });
                }
            }
            self.exploration = drawn;
        }
        for (v, e) in y.iter_mut().zip(self.exploration) {
            if e != 0.0 {
                *v += e;
            }
        }
        self.step.record(
            x,
            [[f64::NEG_INFINITY, f64::INFINITY]; O],
            self.settings.memory.max_samples_per_step,
        );
        for (k, v) in y.iter_mut().enumerate() {
            let [lo, hi] = self.offset(k).bounds();
            *v = v.clamp(lo, hi);
        }
        self.last_offset = y;
        Ok(y)
    }

    /// Index of the first recorded input trained at touch-down (`train_share`).
    fn first_trained(&self) -> usize {
        self.step.first_trained(self.settings.memory.train_share)
    }

    /// The nominal state near `x`: the mean trained lean and lean rate of every group, its
    /// reference clamped into the trust region (the prior's centre before any training).
    fn nominal_input(&self, x: &[f64; I]) -> [f64; I] {
        let (lo, hi) = (
            self.settings.prior.lo.to_array(),
            self.settings.prior.hi.to_array(),
        );
        std::array::from_fn(|a| {
            let t = &self.trained[a];
            if t.count() == 0 {
                0.5 * (lo[a % LEARNER_INPUTS] + hi[a % LEARNER_INPUTS])
            } else if a % LEARNER_INPUTS == 2 {
                let half = self.settings.trust.region.unwrap_or(0.0) * self.trust_std(a);
                x[a].clamp(t.mean() - half, t.mean() + half)
            } else {
                t.mean()
            }
        })
    }

    /// The spread the trust region measures distances in along `axis`: the std of the trained
    /// inputs, at least 2% of the prior box's width.
    fn trust_std(&self, axis: usize) -> f64 {
        let (lo, hi) = (
            self.settings.prior.lo.to_array(),
            self.settings.prior.hi.to_array(),
        );
        let a = axis % LEARNER_INPUTS;
        self.trained[axis]
            .population_std()
            .max(0.02 * (hi[a] - lo[a]))
    }

    /// The share of the offsets applied at `x` (1 without a trust region).
    fn trust(&self, x: &[f64; I]) -> f64 {
        match self.settings.trust.region {
            Some(k) => trust_share(k, x, &self.trained, |a| self.trust_std(a)),
            None => 1.0,
        }
    }

    /// Tells the learner which values of offset `k` could change the step at the last query:
    /// `lo..=hi` (infinite bounds allowed); with `anti_windup` the training targets of that
    /// input stop at its ends. Errors (no such offset, NaN, `lo > hi`, or an empty interval at
    /// infinity) leave the learner unchanged.
    pub fn set_reach_of(&mut self, k: usize, lo: f64, hi: f64) -> Result<(), LearnerError> {
        if k >= O || !is_reach(lo, hi) {
            return Err(LearnerError::config(
                "reach",
                format!("needs an offset below {O} and lo <= hi, got {k}: [{lo}, {hi}]"),
            ));
        }
        if let Some(r) = self.step.last_reach_mut() {
            r[k] = [lo, hi];
        }
        Ok(())
    }

    /// Forgets the inputs of the current step without learning from it (e.g. after a fall and
    /// reset, when the step never touched down).
    pub fn discard_step(&mut self) {
        self.step.clear();
        self.exploration = [0.0; O];
    }
}

impl<A: FunctionApproximator + Clone, R: LearningRule, const I: usize, const O: usize>
    OffsetLearner<A, R, I, O>
{
    /// Ends the step with each offset's outcome: each rule gives its G and eq. (6) is applied
    /// to every recorded input, then a new step starts (see [`FootstepLearner::touch_down`]
    /// for the one-offset case, which every offset follows). Returns each offset's report.
    pub fn touch_down_all(
        &mut self,
        outcomes: [&StepOutcome; O],
    ) -> Result<[TouchDownReport; O], LearnerError> {
        self.end_step(outcomes, false)
    }

    /// A step that ended in a fall: with `learn_from_falls`, learns from it as from a
    /// touch-down, each outcome's theta_E clamped to +-`fall_theta_limit` and theta_E_dot to
    /// ten times that; otherwise discards the step. Returns what the update did, if one was
    /// made.
    pub fn fall_all(
        &mut self,
        outcomes: [&StepOutcome; O],
    ) -> Result<Option<[TouchDownReport; O]>, LearnerError> {
        if !self.settings.falls.learn || self.step.inputs.is_empty() {
            self.discard_step();
            return Ok(None);
        }
        let clamped = outcomes.map(|o| clamped_at_fall(o, self.settings.falls.theta_limit));
        match self.end_step(std::array::from_fn(|k| &clamped[k]), true) {
            Ok(r) => Ok(Some(r)),
            Err(e) => {
                self.discard_step();
                Err(e)
            }
        }
    }

    /// [`Self::touch_down_all`] of a step that ended in a fall (`fell`) or not.
    fn end_step(
        &mut self,
        outcomes: [&StepOutcome; O],
        fell: bool,
    ) -> Result<[TouchDownReport; O], LearnerError> {
        for o in outcomes {
            for (what, v) in [
                ("theta_e", o.theta_e),
                ("theta_e_dot", o.theta_e_dot),
                ("f_e", o.f_e),
                ("f_r", o.f_r),
            ] {
                if !v.is_finite() {
                    return Err(LearnerError::NonFinite { what, value: v });
                }
            }
        }
        // `max_step_error` is in metres: only an offset whose step error is a length
        // ([`StepParameter::is_length`]) is compared with it; the step time's (s) and the
        // soles' (rad) errors never discard a step.
        if let Some(m) = self.settings.trust.max_step_error
            && (0..O).any(|k| {
                self.parameters[k].is_length() && (outcomes[k].f_e - self.last_offset[k]).abs() > m
            })
        {
            self.discard_step();
            return Ok([TouchDownReport::default(); O]);
        }
        let mut raw = [0.0; O];
        for k in 0..O {
            raw[k] = self.rules[k].learn(outcomes[k], self.exploration[k], fell);
            if !raw[k].is_finite() {
                return Err(LearnerError::NonFinite {
                    what: "gradient G",
                    value: raw[k],
                });
            }
        }
        let offsets: [OffsetSettings; O] = std::array::from_fn(|k| self.offset(k));
        let g: [f64; O] = std::array::from_fn(|k| {
            let dz = offsets[k].dead_zone;
            raw[k].signum() * (raw[k].abs() - dz).max(0.0)
        });
        let step_size: [f64; O] = std::array::from_fn(|k| offsets[k].eta * g[k]);
        self.before.clear();
        self.desired.clear();
        let first = self.first_trained();
        for (x, reach) in self.step.inputs[first..]
            .iter()
            .zip(&self.step.reach[first..])
        {
            let before = self.predict_all(x)?;
            let mut desired = [0.0; O];
            for k in 0..O {
                let mut change = step_size[k] - offsets[k].leakage * before[k];
                if self.settings.guard.anti_windup {
                    change = windup(change, before[k], reach[k]);
                    if let Some(range) = offsets[k].offset_range {
                        change = windup(change, before[k], range);
                    }
                }
                let target = before[k] + change;
                if !target.is_finite() {
                    return Err(LearnerError::NonFinite {
                        what: "training target",
                        value: target,
                    });
                }
                desired[k] = target - before[k];
            }
            self.before.push(before);
            self.desired.push(desired);
        }
        let samples = self.step.inputs.len() - first;
        let asked: [f64; O] =
            std::array::from_fn(|k| self.desired.iter().map(|d| d[k] * d[k]).sum());
        let gain_of = |k: usize, response: f64| {
            if g[k] == 0.0 {
                0.0
            } else {
                response * step_size[k] / g[k]
            }
        };
        let guard = self
            .settings
            .guard
            .max_gain
            .filter(|_| asked.iter().any(|a| *a > 0.0));
        let (inputs, before, desired) = (&self.step.inputs[first..], &self.before, &self.desired);
        let guarded = guarded_update(
            &mut self.approx,
            guard,
            [0.0; O],
            |approx, scale| train_towards(approx, inputs, before, desired, scale),
            |approx| response(approx, inputs, before, desired, asked),
            |r: &[f64; O]| (0..O).map(|k| gain_of(k, r[k]).abs()).fold(0.0, f64::max),
        );
        let Guarded {
            scale,
            first: first_response,
            applied: applied_response,
        } = match guarded {
            Ok(g) => g,
            Err(GuardError::Apply(e)) => {
                self.discard_step();
                return Err(e);
            }
            Err(GuardError::Measure(e)) => return Err(e),
        };
        if scale > 0.0 {
            self.step.add_trained(first, &mut self.trained);
        }
        self.discard_step();
        Ok(std::array::from_fn(|k| TouchDownReport {
            gradient: raw[k],
            samples,
            response: first_response[k],
            gain: gain_of(k, applied_response[k]),
            scale,
        }))
    }
}

/// Learns the footstep offset dF over (theta_E, theta_E_dot, F_R) online (eq. 6): the
/// [`OffsetLearner`] of one offset over the paper's three inputs, one per learned step
/// parameter in a [`StepLearner`](super::step_learner::StepLearner).
///
/// Every control tick the controller calls [`FootstepLearner::query`] with the current
/// (theta_E, theta_E_dot, F_R) and adds the returned offset dF to its footstep. The learner
/// remembers (a bounded, evenly spread subset of) the inputs it was queried at during the step.
/// At touch-down the controller calls [`FootstepLearner::touch_down`] with the measured
/// [`StepOutcome`]; the rule turns it into a gradient G and, for every recorded input x_i, the
/// approximator is trained toward F(x_i) + eta G.
///
/// The learner knows nothing about whether the analytic footstep is on ("initialised") or off
/// ("not initialised", experiment D): that switch belongs to the controller, which either adds
/// dF to the Capture Step footstep or uses dF as the whole step. The learner trains dF the same
/// way in both cases.
///
/// # Stability by construction
///
/// One touch-down moves the prediction at the step's inputs by `gain * G`, where the gain is
/// eta times the approximator's response r (the share of a requested change its predictions
/// actually move: near 1 for a fresh local model, far less for one that has seen many
/// samples). Near the reference the walker answers a sustained offset with dG/dF = -k (k is
/// the tanh slope p_theta p_F plus the trunk's own response d theta_E / dF), so the step error
/// evolves as e <- (1 - gain k) e: it settles monotonically for gain < 1/k, oscillates but
/// settles below 2/k and grows beyond (bounded only by saturation and falls). Eq. (6) at the
/// paper's eta = 1 with an untrained approximator has gain ~ 1, beyond that limit on the
/// humanoid (docs/learner.md has k as measured there). Three settings of
/// [`LearnerConfig`] make it stable for any approximator and any eta:
///
/// - **Gain guard** (`max_gain`, default 0.2, about 1/k on the humanoid): the update is
///   tried on a copy of the approximator; if its response gives a larger gain, the step is
///   scaled to just below the limit and applied to the original (never above it: if retries
///   do not get there, that touch-down changes nothing). [`TouchDownReport`] carries r, the gain
///   applied and the scale; the trial log records the gain of every touch-down.
/// - **Anti-windup** (`anti_windup`, conditional integration): no target goes further past the
///   offsets that could still change the step at that tick (the walker tells the learner this
///   reach: the step range minus the analytic step). Without it eq. (6) keeps integrating
///   where the step range is exhausted. Targets are not pulled *into* the reach: where the
///   analytic step lies beyond an end of the range, clamping targets into the reach would
///   drive the offset the wrong way (docs/learner.md has both measured).
/// - **Prior** (`prior`): the paper's initialised learner starts at dF = 0 everywhere; training
///   that belief in makes the approximator hold it with confidence, so that early steps do not
///   move it all the way (its response to the first step drops, `tests/all/learner.rs`).
///
/// A fourth, the **trust region** (`trust_region`, default 2), applies the offset only near
/// the inputs the learner was trained at, so that what it learned stepping or walking does
/// not reach states it never learned from (the catch step after a push). By default the
/// learner also learns from a step that ends in a fall (`learn_from_falls`), as the paper's
/// robot learned from its first falls.
///
/// [`LearnerConfig::literal`] is eq. (6) as written, without the four, the dead zone and learning
/// from falls.
///
/// # Exploration
///
/// A rule that explores ([`LearningRule::explore`], e.g. [`crate::rules::PolicyGradient`])
/// gives a perturbation at the first query of every step; the learner adds it to every offset
/// of that step (after the trust region, before the `max_offset` clamp) and hands it back to
/// [`LearningRule::learn`] at the step's end. Gradient rules perturb nothing and learn exactly
/// as before. The rule's state travels in the learner's checkpoint.
pub type FootstepLearner<A, R> = OffsetLearner<A, R, LEARNER_INPUTS, 1>;

impl<A: FunctionApproximator, R: LearningRule> OffsetLearner<A, R, LEARNER_INPUTS, 1> {
    /// A learner around `approx` (3 inputs, 1 output) and `rule`, holding the prior of
    /// `config` (dF = 0 trained in at `config.prior.samples` points; none if 0).
    pub fn new(approx: A, rule: R, config: LearnerConfig) -> Result<Self, LearnerError> {
        Self::with_rules(approx, [rule], config)
    }

    /// The rule.
    pub fn rule(&self) -> &R {
        &self.rules[0]
    }

    /// The rule's exploration perturbation of the current step (m; 0 before its first query
    /// and for a rule that does not explore).
    pub fn exploration(&self) -> f64 {
        self.exploration[0]
    }

    /// The offset the last query returned (0 before any).
    pub fn last_offset(&self) -> f64 {
        self.last_offset[0]
    }

    /// The same learner, learning `parameter` from now on (with that parameter's settings,
    /// [`LearnerConfig::offset`]); the rule is unchanged. An error if its settings learn
    /// `parameter` in both planes (a learner reads one).
    pub fn as_parameter(mut self, parameter: StepParameter) -> Result<Self, LearnerError> {
        single_planes(&self.settings, &[parameter])?;
        self.parameters = [parameter];
        Ok(self)
    }

    /// The step parameter this learner learns.
    pub fn parameter(&self) -> StepParameter {
        self.parameters[0]
    }

    /// The plane it reads and is taught in (its settings' for its parameter).
    pub fn plane(&self) -> Plane {
        let p = self.parameter();
        // A learner is only made with one plane for each of its parameters (`single_planes`).
        self.settings
            .planes(p)
            .single()
            .unwrap_or(p.default_plane())
    }

    /// The same learner (approximator, prior, trust-region statistics, step in progress),
    /// taught by `rule` from now on: with [`Self::as_parameter`], how a learner of another
    /// step parameter is built from a fresh one of the run's approximator (the prior does not
    /// depend on the rule).
    pub fn with_rule<R2: LearningRule>(self, rule: R2) -> FootstepLearner<A, R2> {
        OffsetLearner {
            approx: self.approx,
            rules: [rule],
            config: self.config,
            settings: self.settings,
            parameters: self.parameters,
            step: self.step,
            before: self.before,
            desired: self.desired,
            trained: self.trained,
            last_offset: self.last_offset,
            exploration: self.exploration,
            fall: self.fall,
        }
    }

    /// Takes the learner apart into its approximator and rule.
    pub fn into_parts(self) -> (A, R) {
        let [rule] = self.rules;
        (self.approx, rule)
    }

    /// The inputs recorded so far in the current step, in query order.
    pub fn recorded_inputs(&self) -> impl ExactSizeIterator<Item = LearnerInput> + '_ {
        self.step.inputs.iter().map(|x| LearnerInput {
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
        Ok(self.predict_all(x)?[0])
    }

    /// The control-tick query: returns dF at `input` plus the step's exploration perturbation
    /// (drawn from the rule at the step's first query; clamped to `max_offset` and
    /// `offset_range` if set) and records the input for the touch-down update (subject to the
    /// per-step bound). Does not allocate. On error nothing is recorded (a non-finite
    /// perturbation is an error; the rule has then drawn it).
    pub fn query(&mut self, input: LearnerInput) -> Result<f64, LearnerError> {
        Ok(self.query_all(input.to_array())?[0])
    }

    /// Tells the learner which offsets could change the step at the last query: `lo..=hi`
    /// (m; infinite bounds allowed). With `anti_windup` the training targets of that input are
    /// clamped to it, so eq. (6) stops integrating where a larger offset has no effect (the
    /// step range is exhausted). The walker calls this every tick after [`Self::query`].
    /// Errors (NaN, `lo > hi`, or an empty interval at infinity) leave the learner unchanged.
    pub fn set_reach(&mut self, lo: f64, hi: f64) -> Result<(), LearnerError> {
        self.set_reach_of(0, lo, hi)
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

impl<A: FunctionApproximator + Clone, R: LearningRule> OffsetLearner<A, R, LEARNER_INPUTS, 1> {
    /// Ends the step: computes G with the rule and applies eq. (6) to every recorded input,
    /// then starts a new step.
    ///
    /// The target at each recorded input x_i is F_old(x_i) + eta G; with `anti_windup` the
    /// change stops at the end of the input's reach (it is not pulled into the reach). All
    /// predictions are taken before the first update, so every target is independent of the
    /// update order (eq. 6 read literally). With `max_gain` set, the approximator is updated
    /// on a copy first; if its predictions moved by more than `max_gain` per unit of G, the
    /// step is scaled to just below the limit and applied to the approximator as it was
    /// (retried, as approximators respond not quite linearly; if no retry lands within the
    /// limit, the approximator is left as it was and the report says scale 0). The applied
    /// gain never exceeds `max_gain`.
    ///
    /// Everything the learner can check (G finite, predictions and targets finite) is checked
    /// before the first update: such a rejection changes nothing, the recorded inputs included
    /// (call [`Self::discard_step`] to drop them). If the approximator still fails during an
    /// update, the updates already applied stay (each one is all-or-nothing by the
    /// [`FunctionApproximator`] contract, so the model is valid), the error reports how many
    /// were applied, and the step is discarded.
    ///
    /// The rule gives G through [`LearningRule::learn`] with the step's exploration
    /// perturbation (for a gradient rule, [`LearningRule::gradient`]).
    pub fn touch_down(&mut self, step: &StepOutcome) -> Result<TouchDownReport, LearnerError> {
        let [report] = self.touch_down_all([step])?;
        Ok(report)
    }

    /// A step that ended in a fall: with `learn_from_falls`, learns from `step` (the step in
    /// progress when the robot fell) as from a touch-down, with theta_E clamped to
    /// +-`fall_theta_limit` and theta_E_dot to ten times that; otherwise discards the step.
    /// Returns what the update did, if one was made.
    pub fn fall(&mut self, step: &StepOutcome) -> Result<Option<TouchDownReport>, LearnerError> {
        Ok(self.fall_all([step])?.map(|[report]| report))
    }
}

impl<A: FunctionApproximator + Persist + Clone, R: LearningRule, const I: usize, const O: usize>
    OffsetLearner<A, R, I, O>
{
    /// Everything the learner holds but its rules, with the rules' states, as [`Self::save`]
    /// writes it.
    pub fn checkpoint(&self) -> SavedLearner<A> {
        let mut offsets: Vec<SavedOffset> = (0..O)
            .map(|k| SavedOffset {
                parameter: self.parameters[k],
                reach: self
                    .step
                    .reach
                    .iter()
                    .map(|r| [finite_or_none(r[k][0]), finite_or_none(r[k][1])])
                    .collect(),
                last_offset: self.last_offset[k],
                exploration: self.exploration[k],
                rule_state: self.rules[k].state(),
            })
            .collect();
        // The first offset's state lives beside the step, as in files of one-offset learners.
        let first = offsets.remove(0);
        SavedLearner {
            config: self.config,
            parameter: first.parameter,
            approximator: self.approx.clone(),
            trained: self.trained.to_vec(),
            step: StepInProgress {
                recorded: self.step.inputs.iter().map(|x| x.to_vec()).collect(),
                reach: first.reach,
                last_recorded: self.step.last_recorded,
                stride: self.step.stride,
                queries: self.step.queries,
                last_offset: first.last_offset,
                exploration: first.exploration,
            },
            rule_state: first.rule_state,
            more_offsets: offsets,
        }
    }

    /// The learner of a checkpoint (checked) with one rule per offset, in output order: it
    /// continues bit for bit as the learner that wrote it, mid-step included. Saved rule states
    /// are restored into `rules` (an error if a rule cannot take its state); without one, the
    /// rule is used as given. A checkpoint of another shape (inputs, offsets) is an error.
    pub fn from_checkpoint_with(
        saved: SavedLearner<A>,
        rules: [R; O],
    ) -> Result<Self, LearnerError> {
        saved.check_invariants().map_err(LearnerError::approx)?;
        Self::from_checked(saved, rules)
    }

    /// Loads a learner saved by [`Self::save`] with one rule per offset; it continues exactly
    /// where the saved one was, mid-step included. A corrupt file or a checkpoint of another
    /// shape is an error.
    pub fn load_with(path: impl AsRef<Path>, rules: [R; O]) -> Result<Self, LearnerError> {
        // `Persist::load` has checked the invariants.
        let saved = SavedLearner::<A>::load(path).map_err(LearnerError::approx)?;
        Self::from_checked(saved, rules)
    }

    /// [`Self::from_checkpoint_with`] of a checkpoint whose invariants hold.
    fn from_checked(saved: SavedLearner<A>, mut rules: [R; O]) -> Result<Self, LearnerError> {
        let SavedLearner {
            config,
            parameter,
            approximator,
            trained,
            step,
            rule_state,
            more_offsets,
        } = saved;
        // Every offset's state in output order, the first's from beside the step.
        let offsets: Vec<SavedOffset> = std::iter::once(SavedOffset {
            parameter,
            reach: step.reach,
            last_offset: step.last_offset,
            exploration: step.exploration,
            rule_state,
        })
        .chain(more_offsets)
        .collect();
        if offsets.len() != O {
            return Err(LearnerError::WrongApproximatorShape {
                expected: (I, O),
                inputs: approximator.input_dim(),
                outputs: offsets.len(),
            });
        }
        for (rule, offset) in rules.iter_mut().zip(&offsets) {
            if let Some(state) = &offset.rule_state {
                rule.set_state(state)?;
            }
        }
        let parameters = std::array::from_fn(|k| offsets[k].parameter);
        let mut learner = Self::assemble(approximator, rules, parameters, config)?;
        if !trained.is_empty() {
            learner.trained = std::array::from_fn(|a| trained[a]);
        }
        for (i, x) in step.recorded.iter().enumerate() {
            learner.step.inputs.push(std::array::from_fn(|a| x[a]));
            learner.step.reach.push(std::array::from_fn(|k| {
                let [lo, hi] = offsets[k].reach[i];
                [lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY)]
            }));
        }
        learner.step.last_recorded = step.last_recorded;
        learner.step.stride = step.stride;
        learner.step.queries = step.queries;
        learner.last_offset = std::array::from_fn(|k| offsets[k].last_offset);
        learner.exploration = std::array::from_fn(|k| offsets[k].exploration);
        Ok(learner)
    }

    /// Saves the learner to `path` as JSON: config, approximator, trust-region statistics, the
    /// step in progress and each rule's state, if any (atomically: temporary file and rename,
    /// so a failed save leaves an existing file intact).
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), LearnerError> {
        self.checkpoint().save(path).map_err(LearnerError::approx)
    }
}

impl<A: FunctionApproximator + Persist + Clone, R: LearningRule>
    OffsetLearner<A, R, LEARNER_INPUTS, 1>
{
    /// The learner of a checkpoint (checked) with `rule`: it continues bit for bit as the
    /// learner that wrote it, mid-step included. A saved rule state is restored into `rule`
    /// (an error if `rule` cannot take it); without one, `rule` is used as given.
    pub fn from_checkpoint(saved: SavedLearner<A>, rule: R) -> Result<Self, LearnerError> {
        Self::from_checkpoint_with(saved, [rule])
    }

    /// Loads a learner saved by [`Self::save`] with `rule`; it continues exactly where the
    /// saved one was, mid-step included. A corrupt file or a wrongly shaped approximator is an
    /// error.
    pub fn load(path: impl AsRef<Path>, rule: R) -> Result<Self, LearnerError> {
        Self::load_with(path, [rule])
    }
}
