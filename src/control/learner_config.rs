//! The learner's settings: [`LearnerConfig`] as a config file writes it (`[settings.learner]`,
//! flat keys, with a table per learned parameter for the settings a parameter may change), and
//! [`CheckedLearnerConfig`], the same settings checked once ([`LearnerConfig::check`]) and
//! grouped by the safeguard they belong to. A learner holds only checked settings.

use super::learner_error::LearnerError;
use super::step_parameter::{Gate, LearnSet, Plane, Planes, StepParameter};
use serde::{Deserialize, Serialize};

/// Number of inputs of the learner's approximator: (theta_E, theta_E_dot, F_R).
pub const LEARNER_INPUTS: usize = 3;

/// One query point of the learner.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
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
    /// If set, the offset returned by
    /// [`FootstepLearner::query`](super::learner::FootstepLearner::query) is clamped to +-this
    /// (m); training targets are not clamped by it (see `anti_windup`). Must be finite and > 0.
    pub max_offset: Option<f64>,
    /// If set, `[lo, hi]`: the offsets the learner may apply, one end possibly at 0 (a
    /// one-sided offset, such as a sole pressed on its heel only). The query is clamped into it
    /// (after `max_offset`) and, with `anti_windup`, a training target goes no further past its
    /// ends than the prediction already is. Finite, `lo <= 0 <= hi`, `lo < hi`; default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset_range: Option<[f64; 2]>,
    /// Stability guard: the largest learning gain one touch-down may apply, in metres of dF per
    /// unit of G (see [`TouchDownReport::gain`](super::learner::TouchDownReport::gain) and
    /// [`FootstepLearner`](super::FootstepLearner) for the limit). If the approximator's response to the full step eta G would
    /// exceed it, the step is scaled down and applied again to the approximator as it was.
    /// `None` turns the guard off (eq. 6 as written). Default 0.2. Must be finite and > 0.
    pub max_gain: Option<f64>,
    /// Anti-windup (conditional integration): a training target never goes further past an end
    /// of the offsets that could still change the step at that tick than the prediction already
    /// is (the reach told by
    /// [`FootstepLearner::set_reach`](super::learner::FootstepLearner::set_reach): on the
    /// walker, the step range minus the analytic step). Default on.
    pub anti_windup: bool,
    /// Learn from a step that ended in a fall
    /// ([`FootstepLearner::fall`](super::learner::FootstepLearner::fall)): the step in progress
    /// at the fall is treated as if it had touched down, with theta_E clamped to
    /// +-`fall_theta_limit`. On by default: the paper's robot "learned from this experience"
    /// when its first pushes made it fall (both ways are compared in `docs/learner.md`).
    pub learn_from_falls: bool,
    /// |theta_E| and |theta_E_dot| / 10 at a fall are clamped to this before the rule sees them
    /// (rad, finite, > 0; default 0.3): past the fall threshold the angle says nothing more.
    pub fall_theta_limit: f64,
    /// The prior held from the start: dF = 0, trained into the approximator at
    /// [`Prior::samples`] evenly spread points of its box by
    /// [`FootstepLearner::new`](super::learner::FootstepLearner::new).
    pub prior: Prior,
    /// Dead zone on G (robust adaptive control's dead-zone modification): the rule's G is
    /// shrunk towards 0 by this much, `sign(G) max(|G| - dead_zone, 0)`, before eq. (6), so
    /// gradients within the step-to-step noise teach nothing. Finite, >= 0; default 0 (eq. 6).
    /// A run's `step-x`, `step-time`, `ankle-pitch` and `ankle-roll` learners take it from the
    /// settings (default there: about the model's median |G| stepping undisturbed,
    /// docs/learner.md; for the sole's pitch and roll above every undisturbed |G_A| and |G_R|,
    /// which keeps a held sole tilt, whose loop no gain stabilises, from being taught); its `step-y`
    /// learner, whose lateral G is of that size, and the coupled learner learn without it.
    pub dead_zone: f64,
    /// Leakage (sigma-modification): each target is pulled back towards the prior dF = 0 by
    /// this share of the current prediction, `F + eta G - leakage F`, so offsets that G stops
    /// asking for decay. In [0, 1); default 0 (eq. 6).
    pub leakage: f64,
    /// If set, a touch-down teaches nothing (the step is discarded) when the step error
    /// without the learner's part, |F_E - dF| with dF the offset of the step's last query,
    /// exceeds this (m): a step the model itself missed by that much was disturbed (a push, a
    /// reference change), and the rule's saturated tracking term only winds the offset up
    /// there. Errors the learner's own offset causes still teach. It is in metres and holds
    /// only for the offsets measured in metres (`step-x`, `step-y`); a step time or a sole
    /// tilt is never discarded by it. Finite and > 0; default none (eq. 6 learns from every
    /// step).
    pub max_step_error: Option<f64>,
    /// If set (k > 0), the learner acts only where it has learned: the offset is applied in
    /// full where every input lies within k standard deviations of the mean of the inputs it
    /// was trained at, fades linearly to 0 at 1.5 k and is 0 beyond (the model alone decides
    /// in states the learner never learned from). Default 2: without it the offset learned
    /// walking reaches the catch steps after pushes (docs/learner.md has what that cost).
    pub trust_region: Option<f64>,
    /// What the offset fades to outside the trust region (default [`TrustFallback::Zero`]).
    pub trust_fallback: TrustFallback,
    /// Share of a step's recorded inputs that are trained at touch-down: the latest ones
    /// (in (0, 1]; default 1, eq. 6: every input of the step). The swing foot lands where the
    /// last commands put it (the generator filters the commanded placement over 0.05 s), so
    /// offsets queried early in a step barely move the step that G measures.
    pub train_share: f64,
    /// The step parameters a walker's learner learns, each with a learner of these settings
    /// ([`StepLearner`](super::step_learner::StepLearner)); default the paper's `step-x`
    /// (left out of written configs).
    #[serde(skip_serializing_if = "LearnSet::is_paper")]
    pub learn: LearnSet,
    /// `[settings.learner.step-x]`: what the `step-x` offset changes of the settings above
    /// (default: nothing).
    #[serde(rename = "step-x", skip_serializing_if = "ParameterSettings::is_empty")]
    pub step_x: ParameterSettings,
    /// `[settings.learner.step-y]`: what the `step-y` offset changes (default: nothing).
    #[serde(rename = "step-y", skip_serializing_if = "ParameterSettings::is_empty")]
    pub step_y: ParameterSettings,
    /// `[settings.learner.step-time]`: what the `step-time` offset changes (default: nothing).
    #[serde(
        rename = "step-time",
        skip_serializing_if = "ParameterSettings::is_empty"
    )]
    pub step_time: ParameterSettings,
    /// `[settings.learner.ankle-pitch]`: what the `ankle-pitch` offset changes (default:
    /// nothing).
    #[serde(
        rename = "ankle-pitch",
        skip_serializing_if = "ParameterSettings::is_empty"
    )]
    pub ankle_pitch: ParameterSettings,
    /// `[settings.learner.ankle-roll]`: what the `ankle-roll` offset changes (default:
    /// nothing).
    #[serde(
        rename = "ankle-roll",
        skip_serializing_if = "ParameterSettings::is_empty"
    )]
    pub ankle_roll: ParameterSettings,
}

/// The settings one learned parameter may set apart from the others
/// (`[settings.learner.step-x]`, `[settings.learner.step-y]`, `[settings.learner.step-time]`):
/// each key given replaces `[settings.learner]`'s value for that parameter's offset; a key left
/// out keeps it. They are the settings that act on one offset (its rate, dead zone, leakage and
/// clamp); the rest act on the whole learner (one approximator, one trust region, one guard).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ParameterSettings {
    /// The offset's learning rate eta.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eta: Option<f64>,
    /// The dead zone on the offset's gradient.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dead_zone: Option<f64>,
    /// The offset's leakage.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub leakage: Option<f64>,
    /// The clamp on the offset's query.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_offset: Option<f64>,
    /// The range of the offset (`[lo, hi]`, one end possibly 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub offset_range: Option<[f64; 2]>,
    /// The plane whose state the offset's learner reads and whose outcome teaches it
    /// (default: [`StepParameter::default_plane`]). Only `step-time` may name another: `plane =
    /// "frontal"` learns the step time from the lean sideways (docs/lateral.md), `"both"` from
    /// both planes at once (one learner per plane, their offsets summed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plane: Option<Planes>,
    /// With `plane = "both"`, the frontal part's own settings
    /// (`[settings.learner.step-time.frontal]`, its dead zone): each key given replaces this
    /// table's value for the learner of the frontal plane; the sagittal part keeps this
    /// table's. Only with `plane = "both"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frontal: Option<PartSettings>,
    /// What the offset is weighted by each tick (default [`Gate::Off`]); in both planes each
    /// part by its own plane.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gate: Option<Gate>,
}

/// The settings of one part of an offset learned in both planes, apart from its parameter's
/// (`[settings.learner.step-time.frontal]`): each key given replaces the parameter's value.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PartSettings {
    /// The dead zone on the part's gradient.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dead_zone: Option<f64>,
}

impl ParameterSettings {
    /// Nothing set apart.
    pub fn is_empty(&self) -> bool {
        *self == ParameterSettings::default()
    }
}

/// The settings of one learned offset, resolved ([`LearnerConfig::offset`]): the learner-wide
/// value unless the parameter's table sets its own.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OffsetSettings {
    /// Learning rate eta of eq. (6), finite and > 0.
    pub eta: f64,
    /// Dead zone on G, finite and >= 0.
    pub dead_zone: f64,
    /// Leakage, in [0, 1).
    pub leakage: f64,
    /// Clamp on the queried offset, finite and > 0 if set.
    pub max_offset: Option<f64>,
    /// The range of the offset, `[lo, hi]` with `lo <= 0 <= hi`, `lo < hi`, if set: the query
    /// is clamped into it and anti-windup stops training targets at its ends.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub offset_range: Option<[f64; 2]>,
}

impl OffsetSettings {
    /// The values the query is clamped to: `+-max_offset` within `offset_range` (infinite
    /// ends where neither is set).
    pub fn bounds(&self) -> [f64; 2] {
        let m = self.max_offset.unwrap_or(f64::INFINITY);
        let [lo, hi] = self
            .offset_range
            .unwrap_or([f64::NEG_INFINITY, f64::INFINITY]);
        [lo.max(-m), hi.min(m)]
    }
}

/// The gain guard and anti-windup: what bounds one touch-down's update.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GuardSettings {
    /// The largest learning gain one touch-down may apply (finite and > 0; none: unguarded).
    pub max_gain: Option<f64>,
    /// Conditional integration against each offset's reach.
    pub anti_windup: bool,
}

/// Learning from a step that ended in a fall.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FallSettings {
    /// Whether a fall teaches.
    pub learn: bool,
    /// The clamp on |theta_E| at a fall (rad, finite and > 0).
    pub theta_limit: f64,
}

/// Where the learner acts and which steps teach it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrustSettings {
    /// Trust region in standard deviations of the trained inputs (finite and > 0; none: the
    /// offset acts everywhere).
    pub region: Option<f64>,
    /// What the offset fades to outside it.
    pub fallback: TrustFallback,
    /// A touch-down the model missed by more than this (m) teaches nothing.
    pub max_step_error: Option<f64>,
}

/// What the learner remembers of a step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MemorySettings {
    /// Inputs kept per step, in [2, [`MAX_SAMPLES_PER_STEP`]].
    pub max_samples_per_step: usize,
    /// Share of a step's recorded inputs trained at touch-down, in (0, 1].
    pub train_share: f64,
}

/// A [`LearnerConfig`] that [`LearnerConfig::check`] accepted, grouped by what each setting
/// does. Only `check` makes one, so a learner that holds one holds valid settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CheckedLearnerConfig {
    pub(crate) offsets: [OffsetSettings; StepParameter::ALL.len()],
    pub(crate) guard: GuardSettings,
    pub(crate) falls: FallSettings,
    pub(crate) trust: TrustSettings,
    pub(crate) memory: MemorySettings,
    pub(crate) prior: Prior,
    pub(crate) learn: LearnSet,
    pub(crate) planes: [Planes; StepParameter::ALL.len()],
    pub(crate) gates: [Gate; StepParameter::ALL.len()],
}

impl CheckedLearnerConfig {
    /// The settings of `parameter`'s offset.
    pub fn offset(&self, parameter: StepParameter) -> OffsetSettings {
        self.offsets[parameter.index()]
    }

    /// The planes `parameter` is learned in.
    pub fn planes(&self, parameter: StepParameter) -> Planes {
        self.planes[parameter.index()]
    }

    /// What `parameter`'s offset is weighted by.
    pub fn gate(&self, parameter: StepParameter) -> Gate {
        self.gates[parameter.index()]
    }

    /// The gain guard and anti-windup.
    pub fn guard(&self) -> GuardSettings {
        self.guard
    }

    /// Learning from falls.
    pub fn falls(&self) -> FallSettings {
        self.falls
    }

    /// The trust region and the step-error filter.
    pub fn trust(&self) -> TrustSettings {
        self.trust
    }

    /// The per-step memory.
    pub fn memory(&self) -> MemorySettings {
        self.memory
    }

    /// The prior.
    pub fn prior(&self) -> Prior {
        self.prior
    }

    /// The learned step parameters.
    pub fn learn(&self) -> LearnSet {
        self.learn
    }
}

/// What the learned offset fades to where the trust region does not cover the input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, strum::Display)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum TrustFallback {
    /// dF = 0: the model alone decides in states the learner never learned from.
    #[default]
    Zero,
    /// The offset learned at the nominal state: the prediction at the mean trained theta_E
    /// and theta_E_dot, with F_R clamped into the trust region. A steady correction of a
    /// model error (a leg that under-reaches) is kept after a push, while the state-dependent
    /// part is used only near the data.
    Nominal,
}

/// The most samples a prior may hold (each trains the approximator once at construction).
pub const MAX_PRIOR_SAMPLES: usize = 1_000_000;

/// The most samples the learner may record in one step (its memory per step is this many
/// inputs).
pub const MAX_SAMPLES_PER_STEP: usize = 100_000;

/// The learner's initial belief dF = 0, trained into the approximator before any step so
/// that it holds it with confidence (an untrained LWPR moves nearly all the way to its first
/// targets, which makes eq. 6 at eta = 1 unstable; see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Prior {
    /// Number of samples (0: no prior, the approximator starts as built; at most
    /// [`MAX_PRIOR_SAMPLES`]).
    pub samples: usize,
    /// Lower corner of the box the samples cover.
    pub lo: LearnerInput,
    /// Upper corner.
    pub hi: LearnerInput,
}

impl Default for Prior {
    /// 1000 points of a Halton sequence over theta_E in [-0.3, 0.3] rad, theta_E_dot in
    /// [-1.5, 1.5] rad/s and F_R in [-0.1, 0.2] m: the states the walker meets without pushes.
    fn default() -> Self {
        Prior {
            samples: 1000,
            lo: LearnerInput::new(-0.3, -1.5, -0.1),
            hi: LearnerInput::new(0.3, 1.5, 0.2),
        }
    }
}

impl Prior {
    /// No prior: the approximator starts as built.
    pub fn none() -> Self {
        Prior {
            samples: 0,
            ..Prior::default()
        }
    }

    /// The `i`-th point of the prior (Halton sequence, bases 2, 3, 5, scaled to the box).
    pub fn point(&self, i: usize) -> [f64; LEARNER_INPUTS] {
        self.point_of(i)
    }

    /// The `i`-th point of the prior over `I` inputs (at most [`MAX_OFFSET_INPUTS`]), each
    /// group of three spread over the box: Halton, one prime base per input (2, 3, 5, 7, ...).
    pub(crate) fn point_of<const I: usize>(&self, i: usize) -> [f64; I] {
        let (lo, hi) = (self.lo.to_array(), self.hi.to_array());
        std::array::from_fn(|a| {
            let (l, h) = (lo[a % LEARNER_INPUTS], hi[a % LEARNER_INPUTS]);
            l + (h - l) * radical_inverse(i + 1, HALTON_BASES[a])
        })
    }
}

/// The van der Corput radical inverse of `i` in `base`, in [0, 1).
pub(crate) fn radical_inverse(mut i: usize, base: usize) -> f64 {
    let (mut inv, mut f) = (0.0, 1.0 / base as f64);
    while i > 0 {
        inv += (i % base) as f64 * f;
        i /= base;
        f /= base as f64;
    }
    inv
}

impl Default for LearnerConfig {
    /// eta = 1, 128 samples per step, no output clamp, gain guard 0.2, anti-windup on,
    /// learning from falls, the default [`Prior`], no dead zone (eq. 6), trust region 2.
    fn default() -> Self {
        LearnerConfig {
            eta: 1.0,
            max_samples_per_step: 128,
            max_offset: None,
            offset_range: None,
            max_gain: Some(0.2),
            anti_windup: true,
            learn_from_falls: true,
            fall_theta_limit: 0.3,
            prior: Prior::default(),
            dead_zone: 0.0,
            leakage: 0.0,
            max_step_error: None,
            trust_region: Some(2.0),
            trust_fallback: TrustFallback::Zero,
            train_share: 1.0,
            learn: LearnSet::default(),
            step_x: ParameterSettings::default(),
            step_y: ParameterSettings::default(),
            step_time: ParameterSettings::default(),
            ankle_pitch: ParameterSettings::default(),
            ankle_roll: ParameterSettings::default(),
        }
    }
}

impl LearnerConfig {
    /// Eq. (6) as written: no gain guard, no anti-windup, no prior (the approximator starts as
    /// built), no trust region, no dead zone, no learning from falls, eta = 1. On the humanoid
    /// this learner is unstable (see the module docs).
    pub fn literal() -> Self {
        LearnerConfig {
            max_gain: None,
            anti_windup: false,
            prior: Prior::none(),
            trust_region: None,
            dead_zone: 0.0,
            learn_from_falls: false,
            ..LearnerConfig::default()
        }
    }

    /// Checks every field ([`Self::check`] without keeping the result).
    pub fn validate(&self) -> Result<(), LearnerError> {
        self.check().map(|_| ())
    }

    /// The table of settings `parameter` sets apart.
    pub fn parameter_settings(&self, parameter: StepParameter) -> &ParameterSettings {
        match parameter {
            StepParameter::StepX => &self.step_x,
            StepParameter::StepY => &self.step_y,
            StepParameter::StepTime => &self.step_time,
            StepParameter::AnklePitch => &self.ankle_pitch,
            StepParameter::AnkleRoll => &self.ankle_roll,
        }
    }

    fn parameter_settings_mut(&mut self, parameter: StepParameter) -> &mut ParameterSettings {
        match parameter {
            StepParameter::StepX => &mut self.step_x,
            StepParameter::StepY => &mut self.step_y,
            StepParameter::StepTime => &mut self.step_time,
            StepParameter::AnklePitch => &mut self.ankle_pitch,
            StepParameter::AnkleRoll => &mut self.ankle_roll,
        }
    }

    /// The settings of `parameter`'s offset: `[settings.learner]`'s, with what the parameter's
    /// table sets apart (not checked; see [`Self::check`]).
    pub fn offset(&self, parameter: StepParameter) -> OffsetSettings {
        let own = self.parameter_settings(parameter);
        OffsetSettings {
            eta: own.eta.unwrap_or(self.eta),
            dead_zone: own.dead_zone.unwrap_or(self.dead_zone),
            leakage: own.leakage.unwrap_or(self.leakage),
            max_offset: own.max_offset.or(self.max_offset),
            offset_range: own.offset_range.or(self.offset_range),
        }
    }

    /// The planes `parameter` is learned in: its table's `plane`, else
    /// [`StepParameter::default_plane`] (not checked; see [`Self::check`]).
    pub fn planes(&self, parameter: StepParameter) -> Planes {
        self.parameter_settings(parameter)
            .plane
            .unwrap_or(parameter.default_plane().into())
    }

    /// The same settings with `parameter` learned in `planes` alone.
    pub fn in_planes(mut self, parameter: StepParameter, planes: Planes) -> Self {
        self.parameter_settings_mut(parameter).plane = Some(planes);
        self
    }

    /// The settings of `parameter`'s learner in `plane`: these, with `parameter` learned in
    /// `plane` alone and, in the frontal plane, its `frontal` table's values in place of its
    /// own (what a learner of a parameter in both planes gives each part).
    pub fn part(mut self, parameter: StepParameter, plane: Plane) -> Self {
        let own = self.parameter_settings_mut(parameter);
        if let (Plane::Frontal, Some(f)) = (plane, own.frontal) {
            own.dead_zone = f.dead_zone.or(own.dead_zone);
        }
        own.frontal = None;
        self.in_planes(parameter, plane.into())
    }

    /// Checks every setting, each parameter's table included, once, and groups them into the
    /// values a learner holds.
    pub fn check(&self) -> Result<CheckedLearnerConfig, LearnerError> {
        let shared = OffsetSettings {
            eta: self.eta,
            dead_zone: self.dead_zone,
            leakage: self.leakage,
            max_offset: self.max_offset,
            offset_range: self.offset_range,
        };
        check_offset(SHARED_OFFSET_KEYS, &shared)?;
        self.check_shared()?;
        let mut offsets = [shared; StepParameter::ALL.len()];
        let mut planes = [Planes::Sagittal; StepParameter::ALL.len()];
        let mut gates = [Gate::Off; StepParameter::ALL.len()];
        for p in StepParameter::ALL {
            let o = self.offset(p);
            check_offset(PARAMETER_OFFSET_KEYS[p.index()], &o)?;
            offsets[p.index()] = o;
            let plane = self.planes(p);
            if !p.allows(plane) {
                return Err(LearnerError::config(
                    PLANE_KEYS[p.index()],
                    format!(
                        "{p} is learned in the {} plane only, got {plane}",
                        p.default_plane()
                    ),
                ));
            }
            planes[p.index()] = plane;
            let gate = self.parameter_settings(p).gate.unwrap_or_default();
            if !gate.allows(p) {
                return Err(LearnerError::config(
                    GATE_KEYS[p.index()],
                    format!(
                        "{p} has no direction in space to fall with; gate = \"with-the-fall\" is for {}",
                        StepParameter::ALL
                            .into_iter()
                            .filter(|&q| gate.allows(q))
                            .map(StepParameter::name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            }
            gates[p.index()] = gate;
            if self.parameter_settings(p).frontal.is_some() {
                if plane != Planes::Both {
                    return Err(LearnerError::config(
                        FRONTAL_KEYS[p.index()],
                        format!(
                            "sets the frontal part of {p} learned in both planes; needs plane = \"both\", got {plane}"
                        ),
                    ));
                }
                // The frontal part differs from the parameter's table in its dead zone only.
                let mut keys = PARAMETER_OFFSET_KEYS[p.index()];
                keys[1] = FRONTAL_DEAD_ZONE_KEY;
                check_offset(keys, &self.part(p, Plane::Frontal).offset(p))?;
            }
        }
        Ok(CheckedLearnerConfig {
            offsets,
            guard: GuardSettings {
                max_gain: self.max_gain,
                anti_windup: self.anti_windup,
            },
            falls: FallSettings {
                learn: self.learn_from_falls,
                theta_limit: self.fall_theta_limit,
            },
            trust: TrustSettings {
                region: self.trust_region,
                fallback: self.trust_fallback,
                max_step_error: self.max_step_error,
            },
            memory: MemorySettings {
                max_samples_per_step: self.max_samples_per_step,
                train_share: self.train_share,
            },
            prior: self.prior,
            learn: self.learn,
            planes,
            gates,
        })
    }

    /// The learner-wide checks.
    fn check_shared(&self) -> Result<(), LearnerError> {
        if !(2..=MAX_SAMPLES_PER_STEP).contains(&self.max_samples_per_step) {
            return Err(LearnerError::config(
                "max_samples_per_step",
                format!(
                    "must be in [2, {MAX_SAMPLES_PER_STEP}], got {}",
                    self.max_samples_per_step
                ),
            ));
        }
        if self.prior.samples > MAX_PRIOR_SAMPLES {
            return Err(LearnerError::config(
                "prior.samples",
                format!(
                    "must be at most {MAX_PRIOR_SAMPLES}, got {}",
                    self.prior.samples
                ),
            ));
        }
        for (name, v) in [
            ("max_gain", self.max_gain),
            ("max_step_error", self.max_step_error),
            ("trust_region", self.trust_region),
        ] {
            if let Some(m) = v
                && !(m.is_finite() && m > 0.0)
            {
                return Err(LearnerError::config(
                    name,
                    format!("must be finite and > 0, got {m}"),
                ));
            }
        }
        if !(self.fall_theta_limit.is_finite() && self.fall_theta_limit > 0.0) {
            return Err(LearnerError::config(
                "fall_theta_limit",
                format!("must be finite and > 0, got {}", self.fall_theta_limit),
            ));
        }
        if !(self.train_share > 0.0 && self.train_share <= 1.0) {
            return Err(LearnerError::config(
                "train_share",
                format!("must be in (0, 1], got {}", self.train_share),
            ));
        }
        let (lo, hi) = (self.prior.lo.to_array(), self.prior.hi.to_array());
        for (axis, name) in ["prior.theta_e", "prior.theta_e_dot", "prior.f_r"]
            .into_iter()
            .enumerate()
        {
            check_range(name, lo[axis], hi[axis], 1)?;
        }
        Ok(())
    }
}

pub(crate) fn check_range(
    param: &'static str,
    lo: f64,
    hi: f64,
    n: usize,
) -> Result<(), LearnerError> {
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

/// Bases of the Halton sequence the prior is spread over, one per input (the first primes).
const HALTON_BASES: [usize; MAX_OFFSET_INPUTS] = [2, 3, 5, 7, 11, 13, 17, 19, 23];

/// Most inputs an [`OffsetLearner`](super::learner::OffsetLearner) takes: three per learned
/// plane or parameter.
pub const MAX_OFFSET_INPUTS: usize = 9;

/// The keys of the offset settings in `[settings.learner]`: eta, dead zone, leakage, clamp,
/// range.
const SHARED_OFFSET_KEYS: [&str; 5] = ["eta", "dead_zone", "leakage", "max_offset", "offset_range"];

/// The same keys in each parameter's table, in [`StepParameter::ALL`]'s order.
const PARAMETER_OFFSET_KEYS: [[&str; 5]; StepParameter::COUNT] = [
    [
        "step-x.eta",
        "step-x.dead_zone",
        "step-x.leakage",
        "step-x.max_offset",
        "step-x.offset_range",
    ],
    [
        "step-y.eta",
        "step-y.dead_zone",
        "step-y.leakage",
        "step-y.max_offset",
        "step-y.offset_range",
    ],
    [
        "step-time.eta",
        "step-time.dead_zone",
        "step-time.leakage",
        "step-time.max_offset",
        "step-time.offset_range",
    ],
    [
        "ankle-pitch.eta",
        "ankle-pitch.dead_zone",
        "ankle-pitch.leakage",
        "ankle-pitch.max_offset",
        "ankle-pitch.offset_range",
    ],
    [
        "ankle-roll.eta",
        "ankle-roll.dead_zone",
        "ankle-roll.leakage",
        "ankle-roll.max_offset",
        "ankle-roll.offset_range",
    ],
];

/// The `frontal` table of each parameter's table, in [`StepParameter::ALL`]'s order.
const FRONTAL_KEYS: [&str; StepParameter::COUNT] = [
    "step-x.frontal",
    "step-y.frontal",
    "step-time.frontal",
    "ankle-pitch.frontal",
    "ankle-roll.frontal",
];

/// The key of the frontal part's dead zone (only the step time is learned in both planes).
const FRONTAL_DEAD_ZONE_KEY: &str = "step-time.frontal.dead_zone";

/// The `gate` key of each parameter's table, in [`StepParameter::ALL`]'s order.
const GATE_KEYS: [&str; StepParameter::COUNT] = [
    "step-x.gate",
    "step-y.gate",
    "step-time.gate",
    "ankle-pitch.gate",
    "ankle-roll.gate",
];

/// The `plane` key of each parameter's table, in [`StepParameter::ALL`]'s order.
pub(crate) const PLANE_KEYS: [&str; StepParameter::COUNT] = [
    "step-x.plane",
    "step-y.plane",
    "step-time.plane",
    "ankle-pitch.plane",
    "ankle-roll.plane",
];

/// Checks one offset's settings; an error names the value by its key in `keys` (eta, dead
/// zone, leakage, clamp, range), so a value from a parameter's table is named with its table.
fn check_offset(keys: [&'static str; 5], o: &OffsetSettings) -> Result<(), LearnerError> {
    if !(o.eta.is_finite() && o.eta > 0.0) {
        return Err(LearnerError::config(
            keys[0],
            format!("must be finite and > 0, got {}", o.eta),
        ));
    }
    if !(o.dead_zone.is_finite() && o.dead_zone >= 0.0) {
        return Err(LearnerError::config(
            keys[1],
            format!("must be finite and >= 0, got {}", o.dead_zone),
        ));
    }
    if !(o.leakage >= 0.0 && o.leakage < 1.0) {
        return Err(LearnerError::config(
            keys[2],
            format!("must be in [0, 1), got {}", o.leakage),
        ));
    }
    if let Some(m) = o.max_offset
        && !(m.is_finite() && m > 0.0)
    {
        return Err(LearnerError::config(
            keys[3],
            format!("must be finite and > 0, got {m}"),
        ));
    }
    if let Some([lo, hi]) = o.offset_range
        && !(lo.is_finite() && hi.is_finite() && lo <= 0.0 && 0.0 <= hi && lo < hi)
    {
        return Err(LearnerError::config(
            keys[4],
            format!("must be finite [lo, hi] with lo <= 0 <= hi and lo < hi, got [{lo}, {hi}]"),
        ));
    }
    Ok(())
}
