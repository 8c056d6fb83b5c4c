//! The open-loop step motion generator, in "abstract leg space" (after Missura & Behnke,
//! "Self-stable omnidirectional walking with compliant joints", 2013).
//!
//! Each leg is commanded by a [`LegPose`]: its extension (how much shorter the hip-to-ankle
//! distance is than the straight leg, as a fraction), its leg angle (roll, pitch, yaw of the
//! hip-to-ankle line) and its foot angle (roll, pitch of the sole), all relative to the torso
//! frame and following the right-hand rule of [`crate::control`] (a positive leg pitch swings
//! the foot backward, a positive leg roll swings it to the left). [`LegSpace`] converts a leg
//! pose to the six joint angles and back, exactly.
//!
//! A step is built from motion primitives added to a halt pose over the step phase
//! `p in [0, 1)`: the swing leg lifts (extension bump) while the support leg pushes (extends);
//! the swing leg swings from where it was to the commanded placement (cosine profile) while
//! the support leg sweeps back linearly until the hips are half the nominal gait step
//! ([`StepCommand::gait_x`]) ahead of the support foot; both legs roll together to sway the hips over the
//! support foot; the trunk leans with the nominal gait step. The generator takes a
//! [`StepCommand`] every tick: where the swing foot should land relative to the support foot,
//! the turn, and the time left until touch-down; changing them mid-step is smooth (the
//! commanded placement is low-pass filtered and the phase itself never jumps).

use serde::{Deserialize, Serialize};

use crate::config::{self, ConfigError};
use crate::robot::kinematics::LegGeometry;
use crate::robot::{JOINTS_PER_LEG, JointTargets, LegJoint, Side};

/// The pose of one leg in abstract leg space (angles in rad, relative to the torso frame).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct LegPose {
    /// Leg shortening as a fraction of the straight hip-to-ankle length, in [0, 1).
    pub extension: f64,
    /// Leg angle: roll, pitch, yaw of the hip-to-ankle line.
    pub angle: [f64; 3],
    /// Foot angle: roll and pitch of the sole.
    pub foot: [f64; 2],
}

/// Exact conversion between abstract leg poses and joint angles for one leg geometry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LegSpace {
    thigh: f64,
    shank: f64,
}

impl LegSpace {
    /// The leg space of `geometry` (thigh and shank lengths).
    pub fn new(geometry: &LegGeometry) -> Self {
        LegSpace {
            thigh: geometry.thigh,
            shank: geometry.shank,
        }
    }

    /// Straight hip-to-ankle length (m).
    pub fn leg_length(&self) -> f64 {
        self.thigh + self.shank
    }

    /// Joint angles ([`LegJoint::ALL`] order) of `pose`. The extension is clamped to
    /// `[0, 0.95]`. The hip-to-ankle line keeps the leg angle; the thigh and shank fold about
    /// it by the law of cosines; the ankle keeps the commanded foot angle.
    pub fn to_joints(&self, pose: &LegPose) -> [f64; JOINTS_PER_LEG] {
        let (t, s) = (self.thigh, self.shank);
        let d = (t + s) * (1.0 - pose.extension.clamp(0.0, 0.95));
        let beta = ((t * t + d * d - s * s) / (2.0 * t * d))
            .clamp(-1.0, 1.0)
            .acos();
        let gamma = ((s * s + d * d - t * t) / (2.0 * s * d))
            .clamp(-1.0, 1.0)
            .acos();
        let [roll, pitch, yaw] = pose.angle;
        let [foot_roll, foot_pitch] = pose.foot;
        [
            yaw,
            roll,
            pitch - beta,
            beta + gamma,
            foot_pitch - pitch - gamma,
            foot_roll - roll,
        ]
    }

    /// The leg pose of joint angles `q` (inverse of [`LegSpace::to_joints`] for knee angles in
    /// `[0, pi]`).
    pub fn from_joints(&self, q: &[f64; JOINTS_PER_LEG]) -> LegPose {
        let (t, s) = (self.thigh, self.shank);
        let knee = q[LegJoint::Knee as usize];
        let d = (t * t + s * s + 2.0 * t * s * knee.cos()).max(0.0).sqrt();
        let beta = ((t * t + d * d - s * s) / (2.0 * t * d))
            .clamp(-1.0, 1.0)
            .acos();
        let gamma = ((s * s + d * d - t * t) / (2.0 * s * d))
            .clamp(-1.0, 1.0)
            .acos();
        let yaw = q[LegJoint::HipYaw as usize];
        let roll = q[LegJoint::HipRoll as usize];
        let pitch = q[LegJoint::HipPitch as usize] + beta;
        LegPose {
            extension: 1.0 - d / (t + s),
            angle: [roll, pitch, yaw],
            foot: [
                q[LegJoint::AnkleRoll as usize] + roll,
                q[LegJoint::AnklePitch as usize] + pitch + gamma,
            ],
        }
    }

    /// Joint targets of both legs (left, right).
    pub fn targets(&self, legs: &[LegPose; 2]) -> JointTargets {
        let mut out = JointTargets::default();
        for side in Side::BOTH {
            let q = self.to_joints(&legs[side.index()]);
            for j in LegJoint::ALL {
                out.pos[j.index(side)] = q[j as usize];
            }
        }
        out
    }
}

/// What a balance controller asks of the generator, every tick.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct StepCommand {
    /// Sagittal placement of the swing foot at touch-down relative to the support foot (m,
    /// forward positive; 0 steps in place).
    pub step_x: f64,
    /// Lateral placement of the swing foot relative to the support foot (m, left positive; it
    /// must lie on the swing leg's side and is clamped to the configured width range).
    pub step_y: f64,
    /// Turn of the swing foot relative to the support foot (rad, counter-clockwise positive).
    pub turn: f64,
    /// Time left until touch-down (s).
    pub step_time: f64,
    /// Sagittal step size of the nominal gait (m): the support leg sweeps the hips from where
    /// the step began to `gait_x / 2` ahead of the support foot, whatever `step_x` is, and the
    /// trunk leans with it. With stiff joints the sweep moves the CoM kinematically, so a
    /// balance controller's footstep must not feed back into it (a backward catch step would
    /// drive the CoM further back). The open-loop walker sets it to `step_x`.
    pub gait_x: f64,
    /// The trunk's measured tilt `[roll, pitch]` and its rate `[roll rate, pitch rate]` (rad,
    /// rad/s; roll positive tilting the top to the right, pitch positive leaning forward), for
    /// the [`Swing::Tracking`] swing. `None`: the trunk is assumed to hold the lean the
    /// generator commands (the paper's swing never reads it).
    pub tilt: Option<[[f64; 2]; 2]>,
    /// Whether the swing foot has landed (the state estimator stands on it), for
    /// [`MotionConfig::early_landing_phase`]. `None`: unknown, the step ends on time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub swing_landed: Option<bool>,
    /// A learned pitch offset of the support sole (rad, toe down positive), clamped to
    /// +-[`ANKLE_LIMIT`]. 0: the sole flat as the generator turns it.
    #[serde(default, skip_serializing_if = "crate::config::is_zero")]
    pub ankle_pitch: f64,
    /// A learned roll offset of the support sole (rad, positive presses the sole's right edge
    /// down, against a trunk whose top tilts to the right), clamped to +-[`ANKLE_LIMIT`]. 0:
    /// the sole flat as the generator turns it.
    #[serde(default, skip_serializing_if = "crate::config::is_zero")]
    pub ankle_roll: f64,
}

/// How the swing leg reaches its placement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Swing {
    /// The paper's open-loop swing: leg angles relative to the trunk, as if the trunk held its
    /// commanded lean, at a fixed leg extension. When a push tilts the whole body, the swing
    /// foot lands where the tilted legs put it, short of the command. The default.
    #[default]
    Paper,
    /// The swing tracks the commanded footstep on the ground to touch-down: every tick it
    /// re-targets the swing leg's end angle from the measured trunk tilt, so that
    /// with the support leg tilted as the trunk is, the swing leg's angle in the world puts its sole at the
    /// commanded distance ahead of the support sole, landing flat. The support leg and the
    /// legs' extension are not changed. `configs/improved.toml`.
    Tracking,
}

/// The shape of the gait's motion primitives: the halt pose, the lift, the sway and the
/// trunk's lean. They belong to the gait the controller's gains were tuned on and are not
/// settings of a config file.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GaitShape {
    /// Extension of both legs in the halt pose.
    pub halt_extension: f64,
    /// Forward trunk lean in the halt pose (rad).
    pub halt_lean: f64,
    /// Extra extension of the swing leg at the top of its lift.
    pub lift_extension: f64,
    /// Extension removed from the support leg at the top of the lift (the ground push).
    pub push_extension: f64,
    /// Lateral hip sway over the support foot (m, at the middle of a step).
    pub sway: f64,
    /// Phase by which the sway leads the step (fraction of a step).
    pub sway_lead: f64,
    /// Part of the step (phase interval) during which the swing foot is lifted.
    pub lift_window: [f64; 2],
    /// Part of the step during which the swing leg swings.
    pub swing_window: [f64; 2],
    /// Extra trunk lean per metre of commanded step (rad/m).
    pub lean_per_step: f64,
    /// Time constant of the low-pass filter on the commanded placement (s; 0 = off).
    pub filter_time: f64,
}

impl Default for GaitShape {
    fn default() -> Self {
        GaitShape {
            halt_extension: 0.04,
            halt_lean: 0.0,
            lift_extension: 0.06,
            push_extension: 0.0,
            sway: 0.035,
            sway_lead: 0.0,
            lift_window: [0.1, 0.9],
            swing_window: [0.1, 0.9],
            lean_per_step: 0.2,
            filter_time: 0.05,
        }
    }
}

/// Settings of the step motion generator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MotionConfig {
    /// The gait's motion primitives (not a config key).
    #[serde(skip)]
    pub gait: GaitShape,
    /// Sagittal step range (m): commanded steps are clamped to it. The default is the paper's
    /// setup, 0.15 m backward and 0.45 m forward (`configs/improved.toml` reaches 0.45 m
    /// backward).
    pub step_x_range: [f64; 2],
    /// Lateral foot distance range (m, magnitude).
    pub step_y_range: [f64; 2],
    /// Largest turn per step (rad).
    pub max_turn: f64,
    /// Nominal step period used by [`MotionGenerator::open_loop`] (s).
    pub period: f64,
    /// Time over which the step primitives fade in after start (s).
    pub fade_in: f64,
    /// Share of the commanded sagittal swing-foot placement the leg realises (1: all). A value
    /// below 1 models a leg that under-reaches (a kinematic calibration error, a soft hip): a
    /// robot that differs from the controller's model in a way the model does not absorb
    /// (`configs/mismatch.toml`). The estimator measures the real step.
    pub swing_step_scale: f64,
    /// How the swing leg reaches its placement (see [`Swing`]).
    pub swing: Swing,
    /// [`Swing::Tracking`]: the share of the trunk's tilt deviation the swing compensates
    /// (default 1.3: a little more than all of it, which lands a pushed body's catch step
    /// nearer its command; 1: all of it; 0: none, the end angle only from the support leg's
    /// geometry).
    pub tilt_gain: f64,
    /// [`Swing::Tracking`]: tilt deviations within this band are compensated once and only the
    /// part beyond it by [`MotionConfig::tilt_gain`] (rad, in [0, 1]; default 0.05; 0: all of
    /// it by the gain). The trunk's pitch and roll in undisturbed walking stay within a few
    /// hundredths of a radian, a push tilts it by tenths: with a band, a gain above 1 lands a
    /// pushed body's catch step without biasing the undisturbed gait.
    pub tilt_gain_band: f64,
    /// [`Swing::Tracking`]: time constant of the trunk's settled tilt (s, > 0): the swing
    /// compensates the measured tilt's deviation from its low-pass filtered value, so a
    /// steady lean (the trunk's sag on its hips, a lean the gait settles into) is left to the
    /// balance controller and only the fast tilt of a push is compensated.
    pub tilt_settle_s: f64,
    /// [`Swing::Tracking`]: tilt deviations within this band are not compensated, and larger
    /// ones only beyond it (rad, >= 0): the trunk's sway within a step of undisturbed walking
    /// is not a tilt of the body.
    pub tilt_dead_band: f64,
    /// The earliest phase of a step at which its swing foot's landing ends it (in [0, 1];
    /// default 1: off, every step ends on time as in the paper; `configs/improved.toml`: 0.5). A swing foot that lands
    /// early (the state estimator stands on it, having changed to it during this step) bears
    /// the body; ending the step there lets the controller plan the next step from it instead
    /// of sweeping a loaded foot on to its placement. Needs the walker's
    /// [`StepCommand::swing_landed`]; without it the step ends on time.
    pub early_landing_phase: f64,
    /// [`Swing::Tracking`]: extra lift of the swing foot per radian of the trunk's tilt
    /// deviation (as the tracking swing measures it, beyond its dead band), in leg lengths
    /// (in [0, 1]; default 0.3; 0: off). A body tilted towards the swing foot brings the
    /// ground up to it; the extra lift follows the lift's own profile, so the foot still
    /// lands at the step's end.
    pub tilt_lift: f64,
}

/// The largest support-sole angle the generator commands (rad): the learned pitch and roll
/// offsets of the support sole ([`StepCommand::ankle_pitch`], [`StepCommand::ankle_roll`]) are
/// clamped to it.
pub const ANKLE_LIMIT: f64 = 0.3;

impl Default for MotionConfig {
    fn default() -> Self {
        MotionConfig {
            gait: GaitShape::default(),
            step_x_range: [-0.15, 0.45],
            step_y_range: [0.16, 0.4],
            max_turn: 0.5,
            period: 0.4,
            fade_in: 1.0,
            swing_step_scale: 1.0,
            swing: Swing::Paper,
            tilt_gain: 1.3,
            tilt_gain_band: 0.05,
            tilt_settle_s: 3.0,
            tilt_dead_band: 0.01,
            early_landing_phase: 1.0,
            tilt_lift: 0.3,
        }
    }
}

impl MotionConfig {
    /// Checks every setting once and groups them into the values a generator holds; an error
    /// names the key.
    pub fn check(&self) -> Result<CheckedMotionConfig, ConfigError> {
        let [lo, hi] = self.step_x_range;
        config::ensure(
            lo.is_finite() && hi.is_finite() && lo <= 0.0 && 0.0 <= hi && lo < hi && hi - lo <= 2.0,
            "step_x_range",
            || format!("must be finite with lo <= 0 <= hi, lo < hi, within 2 m, got [{lo}, {hi}]"),
        )?;
        let [lo, hi] = self.step_y_range;
        config::ensure(
            lo.is_finite() && hi.is_finite() && 0.0 < lo && lo < hi && hi <= 1.0,
            "step_y_range",
            || format!("must be finite with 0 < lo < hi <= 1, got [{lo}, {hi}]"),
        )?;
        config::in_range("max_turn", self.max_turn, 0.0, 1.5)?;
        config::in_range("period", self.period, 0.05, 10.0)?;
        config::in_range("fade_in", self.fade_in, 0.0, 60.0)?;
        config::ensure(
            self.swing_step_scale > 0.0 && self.swing_step_scale <= 2.0,
            "swing_step_scale",
            || format!("must be in (0, 2], got {}", self.swing_step_scale),
        )?;
        config::in_range("tilt_gain", self.tilt_gain, 0.0, 2.0)?;
        config::in_range("tilt_gain_band", self.tilt_gain_band, 0.0, 1.0)?;
        config::positive("tilt_settle_s", self.tilt_settle_s)?;
        config::non_negative("tilt_dead_band", self.tilt_dead_band)?;
        config::in_range("early_landing_phase", self.early_landing_phase, 0.0, 1.0)?;
        config::in_range("tilt_lift", self.tilt_lift, 0.0, 1.0)?;
        Ok(CheckedMotionConfig {
            gait: self.gait,
            steps: StepLimits {
                x_range: self.step_x_range,
                y_range: self.step_y_range,
                max_turn: self.max_turn,
            },
            timing: Timing {
                period: self.period,
                fade_in: self.fade_in,
            },
            swing: SwingSettings {
                mode: self.swing,
                step_scale: self.swing_step_scale,
            },
            tilt: TiltSettings {
                gain: self.tilt_gain,
                gain_band: self.tilt_gain_band,
                settle_s: self.tilt_settle_s,
                dead_band: self.tilt_dead_band,
                lift: self.tilt_lift,
            },
            landing: LandingSettings {
                early_phase: self.early_landing_phase,
            },
        })
    }

    /// A gait tuned for walking without balance control (found by a hill-climbing search over
    /// the primitives' amplitudes and windows, scored by open-loop survival time; probe
    /// `walk_open_loop`). The closed-loop walker keeps the default, which its controller gains
    /// were tuned on.
    pub fn open_loop_gait() -> Self {
        MotionConfig {
            gait: GaitShape {
                halt_extension: 0.0344,
                halt_lean: 0.0213,
                lift_extension: 0.0665,
                push_extension: 0.0,
                sway: 0.0347,
                sway_lead: -0.007,
                lift_window: [0.0874, 0.982],
                swing_window: [0.103, 0.8739],
                lean_per_step: -0.0582,
                ..GaitShape::default()
            },
            // Walking without feedback: the swing never reads the trunk's tilt, and every
            // step ends on time.
            swing: Swing::Paper,
            early_landing_phase: 1.0,
            ..MotionConfig::default()
        }
    }
}

/// The limits commanded steps are clamped to.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StepLimits {
    /// Sagittal step range `[lo, hi]` (m, `step_x_range`): finite, `lo <= 0 <= hi`, `lo < hi`,
    /// at most 2 m wide.
    pub x_range: [f64; 2],
    /// Lateral foot distance range `[lo, hi]` (m, magnitude, `step_y_range`): `0 < lo < hi <=
    /// 1`.
    pub y_range: [f64; 2],
    /// Largest turn per step (rad, `max_turn`), in [0, 1.5].
    pub max_turn: f64,
}

/// The generator's clock: the open-loop period and the fade-in after a start.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Timing {
    /// Nominal step period of [`MotionGenerator::open_loop`] (s, `period`), in [0.05, 10].
    pub period: f64,
    /// Time over which the step primitives fade in after a start (s, `fade_in`), in [0, 60].
    pub fade_in: f64,
}

/// How the swing leg reaches its placement.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SwingSettings {
    /// The swing (`swing`): the paper's open-loop one or the tracking one.
    pub mode: Swing,
    /// Share of the commanded sagittal placement the leg realises (`swing_step_scale`), in
    /// (0, 2].
    pub step_scale: f64,
}

/// What the [`Swing::Tracking`] swing makes of the trunk's tilt.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TiltSettings {
    /// Share of the tilt deviation beyond the band the swing compensates (`tilt_gain`), in
    /// [0, 2].
    pub gain: f64,
    /// Tilt deviations within this band are compensated once, before the gain (rad,
    /// `tilt_gain_band`), in [0, 1].
    pub gain_band: f64,
    /// Time constant of the trunk's settled tilt (s, `tilt_settle_s`), > 0.
    pub settle_s: f64,
    /// Tilt deviations within this band are not compensated (rad, `tilt_dead_band`), >= 0.
    pub dead_band: f64,
    /// Extra lift of the swing foot per radian of tilt deviation (leg lengths, `tilt_lift`),
    /// in [0, 1].
    pub lift: f64,
}

/// When a swing foot's landing ends its step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LandingSettings {
    /// The earliest phase of a step at which its swing foot's landing ends it
    /// (`early_landing_phase`), in [0, 1]; 1: every step ends on time.
    pub early_phase: f64,
}

/// A [`MotionConfig`] that [`MotionConfig::check`] accepted, grouped by what each setting
/// does. Only `check` makes one, so a generator that holds one holds valid settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CheckedMotionConfig {
    pub(crate) gait: GaitShape,
    pub(crate) steps: StepLimits,
    pub(crate) timing: Timing,
    pub(crate) swing: SwingSettings,
    pub(crate) tilt: TiltSettings,
    pub(crate) landing: LandingSettings,
}

impl CheckedMotionConfig {
    /// The gait's motion primitives.
    pub fn gait(&self) -> GaitShape {
        self.gait
    }

    /// The step limits.
    pub fn steps(&self) -> StepLimits {
        self.steps
    }

    /// The period and the fade-in.
    pub fn timing(&self) -> Timing {
        self.timing
    }

    /// The swing.
    pub fn swing(&self) -> SwingSettings {
        self.swing
    }

    /// The tracking swing's use of the trunk's tilt.
    pub fn tilt(&self) -> TiltSettings {
        self.tilt
    }

    /// The early end of a step at landing.
    pub fn landing(&self) -> LandingSettings {
        self.landing
    }
}

impl From<CheckedMotionConfig> for MotionConfig {
    /// The flat settings the checked ones were made from.
    fn from(c: CheckedMotionConfig) -> Self {
        MotionConfig {
            gait: c.gait,
            step_x_range: c.steps.x_range,
            step_y_range: c.steps.y_range,
            max_turn: c.steps.max_turn,
            period: c.timing.period,
            fade_in: c.timing.fade_in,
            swing_step_scale: c.swing.step_scale,
            swing: c.swing.mode,
            tilt_gain: c.tilt.gain,
            tilt_gain_band: c.tilt.gain_band,
            tilt_settle_s: c.tilt.settle_s,
            tilt_dead_band: c.tilt.dead_band,
            early_landing_phase: c.landing.early_phase,
            tilt_lift: c.tilt.lift,
        }
    }
}

/// A generator's settings in its serialized form: flat, as a [`MotionConfig`] (the gait not
/// included), and checked again when read.
mod flat_config {
    use super::{CheckedMotionConfig, MotionConfig};
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub(super) fn serialize<S: Serializer>(
        c: &CheckedMotionConfig,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        MotionConfig::from(*c).serialize(s)
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<CheckedMotionConfig, D::Error> {
        MotionConfig::deserialize(d)?
            .check()
            .map_err(serde::de::Error::custom)
    }
}

/// The open-loop step motion generator. It knows the leg geometry and nothing of any
/// simulator.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MotionGenerator {
    /// The settings, checked (serialized flat, as a [`MotionConfig`], and checked again when
    /// read).
    #[serde(with = "flat_config")]
    config: CheckedMotionConfig,
    space: LegSpace,
    hip_width: f64,
    phase: f64,
    support: Side,
    steps: u64,
    time: f64,
    /// Filtered placement: step_x, step_y offset beyond nominal width, turn, gait_x.
    filtered: [f64; 4],
    /// Leg angle (roll, pitch, yaw) placement of each leg at the start of the step.
    start: [[f64; 3]; 2],
    /// Leg angles of the placement primitive alone (without sway and lean) at the last update.
    placement: [[f64; 3]; 2],
    /// Last commanded leg poses.
    legs: [LegPose; 2],
    /// The trunk tilt's deviation `[roll, pitch]` from its settled value, predicted at
    /// touch-down from the last command's measurement, if it had one.
    #[serde(default)]
    tilt: Option<[f64; 2]>,
    /// The trunk's settled tilt `[roll, pitch]` (low-pass filtered measurement).
    #[serde(default)]
    tilt_settled: Option<[f64; 2]>,
    /// Time since the last exchange of legs (or the start) (s).
    #[serde(default)]
    step_elapsed: f64,
    /// The last command's learned pitch offset of the support sole (rad,
    /// [`StepCommand::ankle_pitch`]).
    #[serde(default, skip_serializing_if = "crate::config::is_zero")]
    ankle_pitch: f64,
    /// The last command's learned roll offset of the support sole (rad,
    /// [`StepCommand::ankle_roll`]).
    #[serde(default, skip_serializing_if = "crate::config::is_zero")]
    ankle_roll: f64,
}

/// Cosine ramp from 0 at `x <= 0` to 1 at `x >= 1`.
pub(crate) fn smooth(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    0.5 - 0.5 * (std::f64::consts::PI * x).cos()
}

fn window(p: f64, w: [f64; 2]) -> f64 {
    ((p - w[0]) / (w[1] - w[0]).max(1e-6)).clamp(0.0, 1.0)
}

impl MotionGenerator {
    /// A generator of `config` ([`MotionConfig::check`]) for legs of `geometry`, halted, with
    /// the left leg supporting the first step.
    pub fn new(config: CheckedMotionConfig, geometry: &LegGeometry) -> Self {
        let mut g = MotionGenerator {
            config,
            space: LegSpace::new(geometry),
            hip_width: 2.0 * geometry.hip_offset[1].abs(),
            phase: 0.0,
            support: Side::Left,
            steps: 0,
            time: 0.0,
            filtered: [0.0; 4],
            start: [[0.0; 3]; 2],
            placement: [[0.0; 3]; 2],
            legs: [LegPose::default(); 2],
            tilt: None,
            tilt_settled: None,
            step_elapsed: 0.0,
            ankle_pitch: 0.0,
            ankle_roll: 0.0,
        };
        g.legs = [g.halt_pose(); 2];
        g
    }

    /// The settings.
    pub fn config(&self) -> &CheckedMotionConfig {
        &self.config
    }

    /// The leg space (pose <-> joints).
    pub fn leg_space(&self) -> &LegSpace {
        &self.space
    }

    /// How far the step primitives have faded in since the start (0 at the start, 1 after
    /// [`MotionConfig::fade_in`]): the share of the commanded placement the legs realise.
    pub fn fade(&self) -> f64 {
        self.fade_after(0.0)
    }

    /// Time since the start or the last reset (s).
    pub fn time_since_start(&self) -> f64 {
        self.time
    }

    /// The same fade (cosine over [`MotionConfig::fade_in`]) begun `delay` seconds after the
    /// start: 0 until then, 1 from `delay + fade_in` on (1 throughout without a fade-in).
    pub fn fade_after(&self, delay: f64) -> f64 {
        let fade_in = self.config.timing.fade_in;
        if fade_in > 0.0 {
            smooth((self.time - delay) / fade_in)
        } else {
            1.0
        }
    }

    /// Step phase in [0, 1).
    pub fn phase(&self) -> f64 {
        self.phase
    }

    /// The supporting leg of the current step.
    pub fn support(&self) -> Side {
        self.support
    }

    /// Time since the legs were last exchanged (or since the start) (s).
    pub fn step_elapsed(&self) -> f64 {
        self.step_elapsed
    }

    /// The swinging leg of the current step.
    pub fn swing(&self) -> Side {
        self.support.other()
    }

    /// Number of support exchanges so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The leg poses last commanded (left, right).
    pub fn legs(&self) -> &[LegPose; 2] {
        &self.legs
    }

    /// Lateral foot distance when stepping in place (m): the hip width.
    pub fn nominal_width(&self) -> f64 {
        self.hip_width
    }

    /// The halt pose of one leg.
    pub fn halt_pose(&self) -> LegPose {
        let gait = &self.config.gait;
        LegPose {
            extension: gait.halt_extension,
            angle: [0.0, -gait.halt_lean, 0.0],
            foot: [0.0, -gait.halt_lean],
        }
    }

    /// Joint targets of the halt pose (standing still).
    pub fn halt_targets(&self) -> JointTargets {
        let h = self.halt_pose();
        self.space.targets(&[h, h])
    }

    /// An open-loop command: step `step_x` forward at the configured period, feet at hip width.
    pub fn open_loop(&self, step_x: f64) -> StepCommand {
        StepCommand {
            step_x,
            step_y: self.swing().sign() * self.hip_width,
            turn: 0.0,
            step_time: (1.0 - self.phase) * self.config.timing.period,
            gait_x: step_x,
            tilt: None,
            swing_landed: None,
            ankle_pitch: 0.0,
            ankle_roll: 0.0,
        }
    }

    /// Advances by `dt` (s) under `command` and returns the joint targets. Non-finite command
    /// fields are ignored (the previous filtered value is kept).
    pub fn update(&mut self, command: &StepCommand, dt: f64) -> JointTargets {
        let CheckedMotionConfig {
            gait,
            steps,
            timing,
            swing: swing_settings,
            tilt: tilt_settings,
            landing,
        } = self.config;
        let dt = if dt.is_finite() && dt > 0.0 { dt } else { 0.0 };
        self.time += dt;
        let swing = self.swing();
        // Desired placement: step_x, lateral offset beyond nominal width (in the swing
        // side's direction), turn.
        let mut want = self.filtered;
        if command.step_x.is_finite() {
            want[0] = swing_settings.step_scale
                * command.step_x.clamp(steps.x_range[0], steps.x_range[1]);
        }
        if command.step_y.is_finite() {
            let w = (command.step_y * swing.sign()).clamp(steps.y_range[0], steps.y_range[1]);
            want[1] = w - self.hip_width;
        }
        if command.turn.is_finite() {
            want[2] = command.turn.clamp(-steps.max_turn, steps.max_turn);
        }
        if command.gait_x.is_finite() {
            want[3] = command.gait_x.clamp(steps.x_range[0], steps.x_range[1]);
        }
        let alpha = if gait.filter_time > 0.0 {
            1.0 - (-dt / gait.filter_time).exp()
        } else {
            1.0
        };
        for (f, w) in self.filtered.iter_mut().zip(want) {
            *f += alpha * (w - *f);
        }
        // Phase: reach 1 after the time left.
        let left = if command.step_time.is_finite() {
            command.step_time.max(dt)
        } else {
            (1.0 - self.phase) * timing.period
        };
        if dt > 0.0 {
            self.phase += dt * (1.0 - self.phase) / left.max(dt);
        }
        self.tilt = match (swing_settings.mode, command.tilt) {
            (Swing::Tracking, Some([tilt, rate]))
                if tilt.iter().chain(&rate).all(|v| v.is_finite()) =>
            {
                let beta = 1.0 - (-dt / tilt_settings.settle_s).exp();
                let settled = self.tilt_settled.get_or_insert(tilt);
                for (m, t) in settled.iter_mut().zip(tilt) {
                    *m += beta * (t - *m);
                }
                let band = tilt_settings.dead_band;
                Some([0, 1].map(|k| {
                    let dev = tilt[k] - settled[k];
                    dev.signum() * (dev.abs() - band).max(0.0)
                }))
            }
            _ => None,
        };
        if command.ankle_pitch.is_finite() {
            self.ankle_pitch = command.ankle_pitch;
        }
        if command.ankle_roll.is_finite() {
            self.ankle_roll = command.ankle_roll;
        }
        self.step_elapsed += dt;
        let landed_early = landing.early_phase < 1.0
            && command.swing_landed == Some(true)
            && self.phase >= landing.early_phase;
        if landed_early {
            self.phase = 1.0;
        }
        if self.phase >= 1.0 - 1e-9 {
            self.exchange();
        }
        let (placement, legs) = self.poses();
        self.placement = placement;
        self.legs = legs;
        self.space.targets(&self.legs)
    }

    fn exchange(&mut self) {
        self.phase = 0.0;
        self.step_elapsed = 0.0;
        self.steps += 1;
        self.support = self.support.other();
        self.start = self.placement;
    }

    /// Leg roll that shifts the hips by the sway at phase `p` (towards the support foot).
    fn sway_roll(&self, p: f64) -> f64 {
        let gait = &self.config.gait;
        let d = self.space.leg_length() * (1.0 - gait.halt_extension);
        let y = gait.sway * (std::f64::consts::PI * (p + gait.sway_lead)).sin();
        // Hips move towards the support side: feet move away from it relative to the hips.
        -self.support.sign() * (y / d).clamp(-0.5, 0.5).asin()
    }

    /// The placement angles and the full leg poses at the current phase.
    fn poses(&self) -> ([[f64; 3]; 2], [LegPose; 2]) {
        let (gait, tilt) = (&self.config.gait, &self.config.tilt);
        let fade = self.fade();
        let p = self.phase;
        let d = self.space.leg_length() * (1.0 - gait.halt_extension);
        let half = |x: f64| (x / 2.0 / d).clamp(-0.9, 0.9).asin();
        // Placement fades in with the lift so a barely lifted foot is not dragged.
        let [sx, sy, turn, gx] = self.filtered.map(|v| v * fade);
        let swing = self.swing();
        // End-of-step leg angles: the support leg has swept the hips gait_x / 2 ahead of its
        // foot; the swing foot lands step_x ahead of the support foot, outward by sy, turned
        // by turn.
        let end_support_pitch = half(gx);
        let end_swing = [
            swing.sign() * half(sy.abs()) * sy.signum(),
            -(((sx - 0.5 * gx) / d).clamp(-0.9, 0.9)).asin(),
            turn / 2.0,
        ];
        let end_support = [-end_swing[0], end_support_pitch, -turn / 2.0];
        let s_swing = smooth(window(p, gait.swing_window));
        let lift = (std::f64::consts::PI * window(p, gait.lift_window)).sin();
        let lean = gait.halt_lean + gait.lean_per_step * gx;
        // The tracking swing: the swing leg's end pose that puts its sole `sx` ahead of the
        // support sole on the ground, for the trunk's predicted tilt.
        let tracking = self.tilt.map(|[roll, pitch]| {
            // Within the band once, beyond it by the gain. Without a band all of it by the
            // gain, computed as before the band existed, so such runs stay bit for bit.
            let gained = |x: f64| {
                if tilt.gain_band == 0.0 {
                    tilt.gain * x
                } else {
                    x + (tilt.gain - 1.0) * x.signum() * (x.abs() - tilt.gain_band).max(0.0)
                }
            };
            let roll = gained(roll);
            let pitch = lean + gained(pitch);
            // The hip over the support sole at the end of the step, with the support leg
            // tilted by the trunk's tilt beyond its settled value.
            let support_world = end_support_pitch - lean + pitch;
            let hip_x = d * support_world.sin();
            let hip_z = d * support_world.cos();
            // The swing leg's angle in the world that puts its sole `sx` ahead of the support
            // sole, then in the trunk's frame.
            let world = -(sx - hip_x).atan2(hip_z);
            ([end_swing[0] - roll, world + lean - pitch], [roll, pitch])
        });
        let end_swing =
            tracking.map_or(end_swing, |([roll, pitch], _)| [roll, pitch, end_swing[2]]);
        let sway = self.sway_roll(p) * fade;
        let mut out = [self.halt_pose(); 2];
        let mut placement = [[0.0; 3]; 2];
        for side in Side::BOTH {
            let i = side.index();
            let start = self.start[i];
            let (end, s, ext) = if side == swing {
                // A tilted body brings the ground up to the swing foot: lift it the more.
                let tilted = self.tilt.map_or(0.0, |[roll, pitch]| roll.hypot(pitch));
                let height = gait.lift_extension + tilt.lift * tilted;
                (end_swing, s_swing, height * lift * fade)
            } else {
                (end_support, p, -gait.push_extension * lift * fade)
            };
            let mut foot = [0.0, -lean];
            if side == swing
                && let Some((_, [roll, pitch])) = tracking
            {
                // Land the sole flat on the ground.
                foot = [-s * roll, -lean - s * (pitch - lean)];
            } else if side != swing {
                // Learned offsets of the support sole's roll and pitch turn it.
                if self.ankle_pitch != 0.0 || self.ankle_roll != 0.0 {
                    let roll = self.ankle_roll.clamp(-ANKLE_LIMIT, ANKLE_LIMIT);
                    let pitch = self.ankle_pitch.clamp(-ANKLE_LIMIT, ANKLE_LIMIT);
                    foot = [roll, -lean + pitch];
                }
            }
            let mut angle = [0.0; 3];
            for k in 0..3 {
                angle[k] = start[k] + s * (end[k] - start[k]);
            }
            placement[i] = angle;
            angle[0] += sway;
            angle[1] -= lean;
            out[i] = LegPose {
                extension: gait.halt_extension + ext,
                angle,
                foot,
            };
        }
        (placement, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Valid settings, every key its own value (none a default, no two alike), and a gait
    /// other than the default.
    fn distinct() -> MotionConfig {
        MotionConfig {
            gait: MotionConfig::open_loop_gait().gait,
            step_x_range: [-0.21, 0.37],
            step_y_range: [0.17, 0.39],
            max_turn: 0.43,
            period: 0.47,
            fade_in: 1.9,
            swing_step_scale: 0.83,
            swing: Swing::Tracking,
            tilt_gain: 1.1,
            tilt_gain_band: 0.07,
            tilt_settle_s: 2.3,
            tilt_dead_band: 0.019,
            early_landing_phase: 0.61,
            tilt_lift: 0.29,
        }
    }

    #[test]
    fn check_groups_each_key_into_its_group() {
        let flat = distinct();
        let c = flat.check().unwrap();
        assert_eq!(c.gait(), flat.gait);
        assert_ne!(c.gait(), GaitShape::default());
        let steps = c.steps();
        assert_eq!(steps.x_range, [-0.21, 0.37]);
        assert_eq!(steps.y_range, [0.17, 0.39]);
        assert_eq!(steps.max_turn, 0.43);
        let timing = c.timing();
        assert_eq!(timing.period, 0.47);
        assert_eq!(timing.fade_in, 1.9);
        let swing = c.swing();
        assert_eq!(swing.mode, Swing::Tracking);
        assert_eq!(swing.step_scale, 0.83);
        let tilt = c.tilt();
        assert_eq!(tilt.gain, 1.1);
        assert_eq!(tilt.gain_band, 0.07);
        assert_eq!(tilt.settle_s, 2.3);
        assert_eq!(tilt.dead_band, 0.019);
        assert_eq!(tilt.lift, 0.29);
        assert_eq!(c.landing().early_phase, 0.61);
        // And back: the flat settings the checked ones came from, every key in its place.
        assert_eq!(MotionConfig::from(c), flat);
        assert_eq!(
            MotionConfig::default().check().unwrap().gait(),
            GaitShape::default()
        );
    }

    #[test]
    fn check_refuses_a_bad_value_naming_its_key() {
        type Spoil = fn(&mut MotionConfig);
        let cases: [(&str, Spoil); 13] = [
            ("step_x_range", |c| c.step_x_range = [0.1, 0.4]),
            ("step_y_range", |c| c.step_y_range = [0.0, 0.4]),
            ("max_turn", |c| c.max_turn = 1.6),
            ("period", |c| c.period = 0.01),
            ("fade_in", |c| c.fade_in = f64::NAN),
            ("swing_step_scale", |c| c.swing_step_scale = 0.0),
            ("tilt_gain", |c| c.tilt_gain = -0.1),
            ("tilt_gain_band", |c| c.tilt_gain_band = 1.5),
            ("tilt_settle_s", |c| c.tilt_settle_s = 0.0),
            ("tilt_dead_band", |c| c.tilt_dead_band = -0.01),
            ("early_landing_phase", |c| c.early_landing_phase = 1.1),
            ("tilt_lift", |c| c.tilt_lift = f64::INFINITY),
            ("step_x_range", |c| c.step_x_range = [-1.5, 1.0]),
        ];
        for (key, spoil) in cases {
            let mut c = distinct();
            spoil(&mut c);
            let e = c.check().unwrap_err();
            assert_eq!(e.field, key, "{e}");
        }
        assert_eq!(
            MotionConfig {
                max_turn: 2.0,
                ..MotionConfig::default()
            }
            .check()
            .unwrap_err()
            .to_string(),
            "max_turn: must be finite and in [0, 1.5], got 2"
        );
    }

    #[test]
    fn a_generator_is_saved_flat_and_read_back_checked() {
        let geometry = LegGeometry::default();
        let flat = MotionConfig {
            gait: GaitShape::default(),
            ..distinct()
        };
        let mut g = MotionGenerator::new(flat.check().unwrap(), &geometry);
        let command = g.open_loop(0.1);
        g.update(&command, 0.01);
        let json = serde_json::to_value(&g).unwrap();
        // The settings are saved as the config file writes them.
        assert_eq!(
            json["config"],
            serde_json::to_value(MotionConfig::from(*g.config())).unwrap()
        );
        assert_eq!(json["config"]["tilt_dead_band"], 0.019);
        let back: MotionGenerator = serde_json::from_value(json.clone()).unwrap();
        assert_eq!(back, g);
        // A saved generator whose settings fail the check is refused, naming the key.
        let mut bad = json;
        bad["config"]["tilt_settle_s"] = serde_json::json!(-1.0);
        let e = serde_json::from_value::<MotionGenerator>(bad).unwrap_err();
        assert!(e.to_string().contains("tilt_settle_s"), "{e}");
    }
}
