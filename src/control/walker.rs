//! The control tick that joins state estimation, Capture Step balance control, an optional
//! footstep learner and the step motion generator.

use super::capture_step::{
    CaptureStep, CaptureStepConfig, CaptureStepError, ComState, GaitReference, StepDecision,
};
use super::estimator::{Estimate, EstimatorConfig, EstimatorError, StateEstimator};
use super::lipm::LipmState;
use super::motion::{
    ANKLE_LIMIT, CheckedMotionConfig, MotionConfig, MotionGenerator, StepCommand, smooth,
};
use super::step_parameter::{PerParameter, StepParameter};
use super::{LearnerError, LearnerInput, TouchDownReport};
use crate::config::{self, ConfigError};
use crate::robot::kinematics::LegGeometry;
use crate::robot::{JointTargets, Sensors, Side};
use crate::rules::StepOutcome;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// How the walker chooses its steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WalkerMode {
    /// Fixed period, the reference step size, no feedback (the paper's open-loop controller).
    OpenLoop,
    /// Capture Step balance control with its analytic footstep (the paper's *model*); a
    /// learner, if given, adds its offset (the *learned* walker).
    CaptureStep,
    /// Capture Step timing and lateral control, but no analytic sagittal footstep: the
    /// learner alone decides the sagittal step (experiment D, "not initialised").
    LearnerOnly,
}

/// Everything that configures a walker.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WalkerConfig {
    /// How steps are chosen.
    pub mode: WalkerMode,
    /// The balance controller.
    #[serde(default)]
    pub capture_step: CaptureStepConfig,
    /// State estimation.
    #[serde(default)]
    pub estimator: EstimatorConfig,
    /// The step motion generator.
    #[serde(default)]
    pub motion: MotionConfig,
    /// Feed the learned offset into the support leg's sweep as well as the footstep
    /// (`gait_x = F_R + dF`), as the authors' gait turns the step into a gait velocity. Off:
    /// the sweep follows F_R alone. Default on: the learned walker is harder to push over with
    /// it (measured both ways in docs/learner.md). Without a learner dF = 0, so the model is
    /// the same either way.
    #[serde(default = "default_offset_in_gait")]
    pub offset_in_gait: bool,
    /// Use the learner while the generator is still fading its primitives in after a start or
    /// a reset ([`MotionGenerator::fade`] < 1): apply its offset and learn from the steps that
    /// touch down then. Those steps realise only part of any command, so they are a reach
    /// limit the offset cannot act on (the reason for the learner's anti-windup); off, the
    /// model alone starts the walker, the learner learns once the gait has faded in and its
    /// offset ramps in over the following fade-in time (switched on at once, its jolt costs
    /// push recovery where a push follows a reset). Default off: with it on (every touch-down
    /// teaches, as in the paper) the restarts after falls teach large offsets, since their
    /// first steps miss F_R far (docs/learner.md). Ignored in
    /// learner-only mode, where the learned offset is the whole step.
    #[serde(default)]
    pub learner_during_fade_in: bool,
    /// Where the learned offset dF enters the Capture Step controller (see [`OffsetTarget`]).
    #[serde(default)]
    pub offset_target: OffsetTarget,
    /// After a start or a reset the walker tracks a reference that rises from 0 to the
    /// requested one over this time (s, cosine; 0: the full reference at once), as a gait
    /// command ramps up from standing. Without it the Capture Step walker fails to start from
    /// standing at larger references (docs/control.md has the references measured); the
    /// default 2 s starts it at every reference the experiments use.
    #[serde(default = "default_start_ramp_s")]
    pub start_ramp_s: f64,
    /// The walker's reference point on each sole, forward of the sole's centre (m): the
    /// point the estimator measures the centre of mass from and the generator places. The
    /// sole's centre (0) for the paper's robot; [`WalkerConfig::for_robot`] sets it from the
    /// robot's [`Scale::sole_shift_x`](crate::robot::Scale). Derived from the robot, so not a
    /// configuration key.
    #[serde(skip)]
    pub sole_reference_x: f64,
}

/// Where the learned sagittal offset dF enters the Capture Step controller.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OffsetTarget {
    /// Added to the analytic footstep F (the paper's learner).
    #[default]
    Footstep,
    /// Added to the reference step the controller plans for (F_R + dF): the controller's
    /// whole step (target state, ZMP, footstep) follows, as for a changed reference. The
    /// learner's inputs and its error F_E still use the true F_R. Capture Step mode only: in
    /// learner-only mode the offset is the whole step either way.
    Reference,
}

impl WalkerConfig {
    /// Defaults for `mode` with the default controller, estimator and generator.
    pub fn new(mode: WalkerMode) -> Self {
        WalkerConfig {
            mode,
            capture_step: CaptureStepConfig::default(),
            estimator: EstimatorConfig::default(),
            motion: MotionConfig::default(),
            offset_in_gait: true,
            learner_during_fade_in: false,
            offset_target: OffsetTarget::Footstep,
            start_ramp_s: default_start_ramp_s(),
            sole_reference_x: 0.0,
        }
    }

    /// The reference step width in place (m): the Capture Step controller's stance, the feet
    /// `2 delta` apart.
    pub fn stance_width(&self) -> f64 {
        2.0 * self.capture_step.delta
    }

    /// Checks the walker's own values and its controller's and estimator's; errors name the
    /// field relative to the walker's section.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.check().map(|_| ())
    }

    /// [`WalkerConfig::validate`], returning the checked motion settings a generator holds.
    fn check(&self) -> Result<CheckedMotionConfig, ConfigError> {
        config::non_negative("start_ramp_s", self.start_ramp_s)?;
        let motion = self.motion.check().map_err(|e| e.within("motion"))?;
        self.capture_step
            .validate()
            .map_err(|e| ConfigError::new("capture_step", e.to_string()))?;
        self.estimator
            .validate()
            .map_err(|e| ConfigError::new("estimator", e.to_string()))?;
        Ok(motion)
    }
}

impl Default for WalkerConfig {
    /// A Capture Step walker with the default controller, estimator and generator (what a
    /// config file's `[settings.walker]` starts from; each experiment sets its own mode).
    fn default() -> Self {
        WalkerConfig::new(WalkerMode::CaptureStep)
    }
}

fn default_offset_in_gait() -> bool {
    true
}

fn default_start_ramp_s() -> f64 {
    START_RAMP_S
}

/// The default [`WalkerConfig::start_ramp_s`].
pub const START_RAMP_S: f64 = 2.0;

/// What can go wrong in a control tick.
#[derive(Debug, Error)]
pub enum WalkerError {
    /// The state estimator rejected its input or configuration.
    #[error("state estimation: {0}")]
    Estimator(#[from] EstimatorError),
    /// The balance controller rejected its input or configuration.
    #[error("capture step: {0}")]
    CaptureStep(#[from] CaptureStepError),
    /// The learner failed.
    #[error("learner: {0}")]
    Learner(#[from] LearnerError),
    /// The walker's configuration is invalid.
    #[error("walker config: {0}")]
    Config(#[from] ConfigError),
}

use super::policy::{FootstepPolicy, StepReports};

/// What one tick decided and measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tick {
    /// Joint targets for the robot.
    pub targets: JointTargets,
    /// The state estimate of this tick.
    pub estimate: Estimate,
    /// The balance controller's decision (none in open-loop mode).
    pub decision: Option<StepDecision>,
    /// The command given to the motion generator.
    pub command: StepCommand,
    /// The reference step the walker tracked this tick (m): the requested one, ramped in after
    /// a start ([`WalkerConfig::start_ramp_s`]).
    pub f_r: f64,
    /// The lateral reference tracked this tick (m per step, positive to the left; ramped in
    /// like `f_r`; 0 unless given to [`Walker::tick_2d`]).
    pub f_r_y: f64,
    /// The learned offset used this tick (0 without a policy).
    pub learned_offset: f64,
    /// The learned lateral offset added to the step's y this tick (m, heading frame, positive
    /// to the left; 0 without a lateral learner).
    pub lateral_offset: f64,
    /// The learned step-time offset added to the step time this tick (s; 0 without a
    /// step-time learner).
    pub time_offset: f64,
    /// The learned pitch offset of the support sole this tick (rad, toe down positive; 0
    /// without an `ankle-pitch` learner).
    pub ankle_offset: f64,
    /// Every learned offset used this tick, per step parameter (0 for one not learned), as
    /// the generator and controller got it: `step-y` positive to the left, `ankle-roll` in
    /// the sole's roll ([`StepCommand::ankle_roll`]).
    pub offsets: PerParameter<f64>,
    /// The step that ended this tick, if a touch-down was detected.
    pub step: Option<StepOutcome>,
    /// The same step in the frontal plane, mirrored to the side of the leg that landed (see
    /// [`Walker::tick`]).
    pub lateral_step: Option<StepOutcome>,
    /// What the learner did with that step, if it learned from it.
    pub learning: Option<TouchDownReport>,
    /// What the lateral learner did with it, if there is one and it learned.
    pub lateral_learning: Option<TouchDownReport>,
    /// What the step-time learner did with it, if there is one and it learned.
    pub time_learning: Option<TouchDownReport>,
    /// What the `ankle-pitch` learner did with it, if there is one and it learned.
    pub ankle_learning: Option<TouchDownReport>,
    /// What each parameter's learner did with it, per step parameter.
    pub reports: StepReports,
}

/// The walker: estimator, balance controller and motion generator, ticked together.
///
/// ```text
/// Sensors -> StateEstimator -> CaptureStep (+ dF from the policy) -> MotionGenerator -> JointTargets
/// ```
///
/// The open-loop walker (fixed period, no reaction to pushes), the *model* (Capture Step), the
/// *learned* walker (Capture Step + learner) and the learner without initialisation (analytic
/// footstep off) are all configurations of this one type.
///
/// In the Capture Step modes the controller's step places only the swing foot; the support
/// leg's sweep follows the reference step `F_R` plus the learned offset
/// ([`StepCommand::gait_x`], [`WalkerConfig::offset_in_gait`]) and the trunk lean follows
/// `F_R`. Driving the sweep with the controller's step fed back
/// positively on the stiff robot: a backward catch step swept the hips backward over the
/// support foot, the controller saw more backward velocity and stepped further back (the
/// robot walked backward with -0.116 m steps whatever `F_R` was).
#[derive(Debug, Clone)]
pub struct Walker {
    config: WalkerConfig,
    geometry: LegGeometry,
    estimator: StateEstimator,
    controller: CaptureStep,
    generator: MotionGenerator,
    last_time: Option<f64>,
    /// The reference of the last tick (ramped), for the lateral reference width.
    gait: GaitReference,
}

impl Walker {
    /// A walker for a robot with legs `geometry`.
    pub fn new(config: WalkerConfig, geometry: LegGeometry) -> Result<Self, WalkerError> {
        let motion = config.check()?;
        let geometry = LegGeometry {
            sole_offset_x: geometry.sole_offset_x + config.sole_reference_x,
            ..geometry
        };
        let mut capture_step = config.capture_step;
        capture_step.analytic_footstep = config.mode != WalkerMode::LearnerOnly;
        Ok(Walker {
            config,
            geometry,
            estimator: StateEstimator::new(geometry, config.estimator)?,
            controller: CaptureStep::new(capture_step)?,
            generator: MotionGenerator::new(motion, &geometry),
            last_time: None,
            gait: GaitReference::default(),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &WalkerConfig {
        &self.config
    }

    /// The step motion generator (phase, support leg, leg poses).
    pub fn generator(&self) -> &MotionGenerator {
        &self.generator
    }

    /// Joint targets of the standing pose the walker starts from.
    pub fn halt_targets(&self) -> JointTargets {
        self.generator.halt_targets()
    }

    /// Back to the initial state (after the robot was reset), keeping the configuration.
    pub fn reset(&mut self) {
        self.estimator.reset();
        self.controller.reset();
        self.generator = MotionGenerator::new(*self.generator.config(), &self.geometry);
        self.last_time = None;
        self.gait = GaitReference::default();
    }

    /// One control tick: reads `sensors`, tracks the reference step size `f_r` (m), asks
    /// `policy` (if any) for dF and tells it about finished steps.
    ///
    /// Errors leave the robot's command unchanged for this tick (the caller decides whether to
    /// stop); the estimator and controller reject bad input without changing their state.
    pub fn tick(
        &mut self,
        sensors: &Sensors,
        f_r: f64,
        policy: Option<&mut (dyn FootstepPolicy + '_)>,
    ) -> Result<Tick, WalkerError> {
        self.tick_2d(sensors, [f_r, 0.0], policy)
    }

    /// [`Self::tick`] with a lateral reference as well: `reference = [F_R, F_R,y]`, the
    /// sagittal step size and the lateral displacement per step (m, positive to the left;
    /// the mean over a left and a right step). The controller walks sideways by widening every
    /// step towards `F_R,y` ([`CaptureStep::reference_width`]; at most
    /// [`Self::max_lateral_step`] per step); the open-loop walker ignores `F_R,y`.
    pub fn tick_2d(
        &mut self,
        sensors: &Sensors,
        reference: [f64; 2],
        mut policy: Option<&mut (dyn FootstepPolicy + '_)>,
    ) -> Result<Tick, WalkerError> {
        let ramp = if self.config.start_ramp_s > 0.0 {
            smooth(self.generator.time_since_start() / self.config.start_ramp_s)
        } else {
            1.0
        };
        let [f_r, f_r_y] = reference.map(|r| r * ramp);
        let gait = GaitReference {
            step_x: f_r,
            lateral: self.lateral_command(f_r_y),
        };
        self.gait = gait;
        // The desired trunk pitch theta_R: the lean the generator gives the trunk for the
        // reference gait (its halt lean plus the lean with the nominal step, which follows F_R).
        let m = self.generator.config();
        let (shape, x_range) = (m.gait(), m.steps().x_range);
        let theta_r = shape.halt_lean + shape.lean_per_step * f_r.clamp(x_range[0], x_range[1]);
        let estimate = self.estimator.update(sensors, theta_r)?;
        let dt = self.last_time.map_or(0.0, |t| (sensors.time - t).max(0.0));
        self.last_time = Some(sensors.time);

        let (step, lateral_step, reports) =
            self.teach_at_touch_down(&estimate, f_r, policy.as_deref_mut())?;
        let mut offsets = PerParameter::<f64>::default();
        let (command, decision) = match self.config.mode {
            WalkerMode::OpenLoop => (self.generator.open_loop(f_r), None),
            WalkerMode::CaptureStep | WalkerMode::LearnerOnly => {
                let (command, d) =
                    self.capture_step_command(&estimate, f_r, gait, policy, &mut offsets)?;
                (command, Some(d))
            }
        };
        let targets = self.generator.update(&command, dt);
        Ok(Tick {
            targets,
            estimate,
            decision,
            command,
            f_r,
            f_r_y,
            learned_offset: offsets[StepParameter::StepX],
            lateral_offset: offsets[StepParameter::StepY],
            time_offset: offsets[StepParameter::StepTime],
            ankle_offset: offsets[StepParameter::AnklePitch],
            offsets,
            step,
            lateral_step,
            learning: reports[StepParameter::StepX],
            lateral_learning: reports[StepParameter::StepY],
            time_learning: reports[StepParameter::StepTime],
            ankle_learning: reports[StepParameter::AnklePitch],
            reports,
        })
    }

    /// At a touch-down, the step's outcome in both planes (the frontal one mirrored to the
    /// side of the leg that landed), handed to the policy once the learner is engaged (a step
    /// before that is discarded).
    fn teach_at_touch_down(
        &mut self,
        estimate: &Estimate,
        f_r: f64,
        policy: Option<&mut (dyn FootstepPolicy + '_)>,
    ) -> Result<(Option<StepOutcome>, Option<StepOutcome>, StepReports), WalkerError> {
        let step = estimate.touch_down.map(|td| StepOutcome {
            theta_e: estimate.theta_e,
            theta_e_dot: estimate.theta_e_rate,
            f_e: td.step[0] - f_r,
            f_r,
        });
        let lateral_step = estimate.touch_down.map(|td| {
            let width = td.support.sign() * td.step[1];
            self.lateral_outcome(estimate, td.support, width)
        });
        let mut reports = StepReports::default();
        if let (Some(outcome), Some(lateral), Some(p)) = (&step, &lateral_step, policy) {
            if self.learner_engaged() {
                reports = p.touch_down(&PerParameter::from_planes(*outcome, *lateral))?;
            } else {
                p.discard_step();
            }
        }
        Ok((step, lateral_step, reports))
    }

    /// Whether the learner learns and acts at all: always in learner-only mode or with
    /// `learner_during_fade_in`, otherwise once the generator has faded in.
    fn learner_engaged(&self) -> bool {
        self.learner_always_engaged() || self.generator.fade() >= 1.0
    }

    fn learner_always_engaged(&self) -> bool {
        self.config.learner_during_fade_in || self.config.mode == WalkerMode::LearnerOnly
    }

    /// The share of the learned offsets applied: bumpless engagement ramps them in like the
    /// generator's fade, one fade-in time later, so that switching the learner on does not
    /// jolt the gait.
    fn engagement(&self) -> f64 {
        if self.learner_always_engaged() {
            1.0
        } else {
            self.generator
                .fade_after(self.generator.config().timing().fade_in)
        }
    }

    /// The Capture Step walker's command for this tick: the policy's offsets (scaled by the
    /// engagement, the lateral one towards the swing leg's side, written to `offsets`) enter
    /// the controller's footstep or its reference, the policy is told each offset's reach, and
    /// the generator gets the step, its time, the support leg's sweep and the trunk's tilt.
    fn capture_step_command(
        &mut self,
        estimate: &Estimate,
        f_r: f64,
        gait: GaitReference,
        mut policy: Option<&mut (dyn FootstepPolicy + '_)>,
        offsets: &mut PerParameter<f64>,
    ) -> Result<(StepCommand, StepDecision), WalkerError> {
        let support = self.generator.support();
        // The lateral learner's input and width offset, towards the swing leg's side.
        let swing_sign = support.other().sign();
        let [lean, lean_rate] = lean_towards(estimate, support.other());
        let width_r = self.width_reference(support.other()) - self.reference_width();
        if let Some(p) = policy.as_deref_mut() {
            let learned = p.offsets(&PerParameter::from_planes(
                LearnerInput::new(estimate.theta_e, estimate.theta_e_rate, f_r),
                LearnerInput::new(lean, lean_rate, width_r),
            ))?;
            let engagement = self.engagement();
            *offsets = learned.map(|v| v * engagement);
            offsets[StepParameter::StepY] *= swing_sign;
            offsets[StepParameter::AnkleRoll] *= sole_roll_towards(support.other());
        }
        let learned_offset = offsets[StepParameter::StepX];
        let lateral_offset = offsets[StepParameter::StepY];
        let com = com_relative_to(estimate, support);
        // In learner-only mode the offset is the whole sagittal step.
        let into_reference = self.config.offset_target == OffsetTarget::Reference
            && self.config.mode == WalkerMode::CaptureStep;
        let (planned_f_r, footstep_offset) = if into_reference {
            (f_r + learned_offset, 0.0)
        } else {
            (f_r, learned_offset)
        };
        let reference = GaitReference {
            step_x: planned_f_r,
            ..gait
        };
        let d = self.controller.update_with_offsets(
            &com,
            &reference,
            [
                footstep_offset,
                lateral_offset,
                offsets[StepParameter::StepTime],
            ],
        )?;
        if let Some(p) = policy {
            // The step without the offset (in reference mode the analytic step holds it, at
            // about one metre of step per metre of reference).
            let base = if into_reference {
                d.analytic_step_x - learned_offset
            } else {
                d.analytic_step_x
            };
            let width = swing_sign * (d.step[1] - lateral_offset);
            p.set_reach(&self.reach(base, width, d.time_reach))?;
        }
        let gait_x = if self.config.offset_in_gait {
            f_r + learned_offset
        } else {
            f_r
        };
        let command = StepCommand {
            step_x: d.step[0],
            step_y: d.step[1],
            turn: 0.0,
            step_time: d.time_to_step,
            gait_x,
            tilt: Some([
                [estimate.roll, estimate.pitch],
                [estimate.roll_rate, estimate.theta_e_rate],
            ]),
            // The estimator changed to the swing foot since this step began.
            swing_landed: Some(
                estimate.support == support.other()
                    && estimate.time_on_support < self.generator.step_elapsed(),
            ),
            ankle_pitch: offsets[StepParameter::AnklePitch],
            ankle_roll: offsets[StepParameter::AnkleRoll],
        };
        Ok((command, d))
    }

    /// The offsets that can still change the step, per parameter: beyond the step range's
    /// ends (and the controller's largest step) an offset would be clamped away, as would a
    /// width beyond the generator's width range, or a sole's pitch or roll beyond
    /// [`ANKLE_LIMIT`]; `time_reach` is the controller's.
    fn reach(
        &self,
        base_step: f64,
        base_width: f64,
        time_reach: [f64; 2],
    ) -> PerParameter<[f64; 2]> {
        let steps = self.generator.config().steps();
        let cap = self.config.capture_step.max_step_x;
        let lo = steps.x_range[0].max(-cap);
        let hi = steps.x_range[1].min(cap);
        let [w_lo, w_hi] = steps.y_range;
        PerParameter([
            [lo - base_step, hi - base_step],
            [w_lo - base_width, w_hi - base_width],
            time_reach,
            [-ANKLE_LIMIT, ANKLE_LIMIT],
            [-ANKLE_LIMIT, ANKLE_LIMIT],
        ])
    }

    /// The reference step width in place (m): the Capture Step controller's stance, the feet
    /// `2 delta` apart.
    pub fn reference_width(&self) -> f64 {
        self.config.stance_width()
    }

    /// The largest lateral reference `F_R,y` the controller realises (m per step): a full
    /// lateral command, `omega - delta`.
    pub fn max_lateral_step(&self) -> f64 {
        self.config.capture_step.omega - self.config.capture_step.delta
    }

    /// The lateral command in [-1, 1] for a lateral reference `f_r_y` (m per step).
    fn lateral_command(&self, f_r_y: f64) -> f64 {
        let max = self.max_lateral_step();
        if max > 0.0 {
            (f_r_y / max).clamp(-1.0, 1.0)
        } else {
            0.0
        }
    }

    /// The reference width W_R (m) of a step of the leg on `side` under the lateral reference
    /// of the last tick: [`Self::reference_width`] in place, wider for steps towards the
    /// direction of a lateral walk.
    pub fn width_reference(&self, side: Side) -> f64 {
        self.controller.reference_width(side.other(), &self.gait)
    }

    /// The frontal-plane outcome of a step of the leg on `side` with width `width` (m, towards
    /// `side`), mirrored to that side: the trunk's lean and its rate towards `side` as theta_E
    /// and its rate, the width error `W - W_R` ([`Self::width_reference`]) as F_E, and as F_R
    /// the reference width beyond the stance in place, `W_R - 2 delta` (0 stepping in place).
    fn lateral_outcome(&self, estimate: &Estimate, side: Side, width: f64) -> StepOutcome {
        let [lean, lean_rate] = lean_towards(estimate, side);
        let width_r = self.width_reference(side);
        StepOutcome {
            theta_e: lean,
            theta_e_dot: lean_rate,
            f_e: width - width_r,
            f_r: width_r - self.reference_width(),
        }
    }

    /// The outcome of the step in progress at `estimate` for every step parameter
    /// ([`Self::outcome_at`] and [`Self::lateral_outcome_at`]): what a trial hands the policy
    /// at a fall.
    pub fn outcomes_at(&self, estimate: &Estimate, f_r: f64) -> PerParameter<StepOutcome> {
        PerParameter::from_planes(
            Self::outcome_at(estimate, f_r),
            self.lateral_outcome_at(estimate),
        )
    }

    /// [`Self::outcome_at`] in the frontal plane: the step in progress at `estimate` with the
    /// swing foot's lateral distance from the support foot as its width, mirrored to the swing
    /// leg's side.
    pub fn lateral_outcome_at(&self, estimate: &Estimate) -> StepOutcome {
        let support = estimate.support;
        let swing = support.other();
        let width =
            swing.sign() * (estimate.feet[swing.index()][1] - estimate.feet[support.index()][1]);
        self.lateral_outcome(estimate, swing, width)
    }

    /// The outcome of the step in progress at `estimate` (the last estimate before a fall):
    /// the trunk angle and rate, and the swing foot's sagittal distance from the support foot
    /// as the step, against the reference `f_r`.
    pub fn outcome_at(estimate: &Estimate, f_r: f64) -> StepOutcome {
        let support = estimate.support;
        let step = estimate.feet[support.other().index()][0] - estimate.feet[support.index()][0];
        StepOutcome {
            theta_e: estimate.theta_e,
            theta_e_dot: estimate.theta_e_rate,
            f_e: step - f_r,
            f_r,
        }
    }
}

/// The trunk's lean towards `side` and its rate (rad, rad/s): the roll mirrored to that side
/// (positive roll tilts the trunk's top to the right).
fn lean_towards(estimate: &Estimate, side: Side) -> [f64; 2] {
    [
        -side.sign() * estimate.roll,
        -side.sign() * estimate.roll_rate,
    ]
}

/// The sign that turns a sole roll pressing the edge on `side` into the sole's roll
/// ([`StepCommand::ankle_roll`], positive pressing the right edge), and back.
fn sole_roll_towards(side: Side) -> f64 {
    -side.sign()
}

/// The CoM state relative to the sole of `support` (the motion generator's support leg, which
/// may differ from the estimator's for a tick around the exchange).
fn com_relative_to(estimate: &Estimate, support: Side) -> ComState {
    let foot = estimate.feet[support.index()];
    ComState {
        time: estimate.time,
        support,
        axes: [
            LipmState::new(-foot[0], estimate.com[0].vel),
            LipmState::new(-foot[1], estimate.com[1].vel),
        ],
    }
}
