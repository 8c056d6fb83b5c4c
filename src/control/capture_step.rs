//! The Capture Step balance controller (Missura & Behnke): where, when and with which ZMP to
//! step, from the CoM state relative to the support foot.
//!
//! Each axis is a [`Lipm`]. Once per control tick, with the CoM state `c` relative to the
//! support foot's sole centre (heading frame: x forward, y left):
//!
//! 1. target end-of-step state `s` from the reference: the desired sagittal step size `F_R`
//!    and the lateral gait (support-exchange offset `xi` between `delta` and `omega`);
//! 2. lateral ZMP `Z_y` that brings `c_y` to `s_y` in the nominal remaining step time (reset to
//!    `2 tau` at every support exchange), clamped to the foot;
//! 3. step time `T`: when the lateral pendulum reaches `s_y` (with fallbacks while the CoM is
//!    crossing towards the support leg or stalling), shortened so that the sagittal CoM stays
//!    within a maximum excursion, and never shorter than what remains of the minimum step
//!    duration (the swing leg's speed limit);
//! 4. sagittal ZMP `Z_x` that brings `c_x` to `s_x` at `T`, clamped to the foot;
//! 5. achievable end-of-step state `c'`: the LIPM run forward by `T` with `Z`;
//! 6. footstep `F` relative to the CoM at the end of the step:
//!    `F_x = (c'_x' / C) tanh(C tau) + dF` (`dF` is the learned offset; with the analytic
//!    footstep switched off the step is the nominal step in place plus `dF`:
//!    `F_x = dF - c'_x`), `F_y = l sqrt(c'_y'^2 / C^2 + alpha^2)`; the step vector from the
//!    support foot to the new foot is `S = c' + F`.
//!
//! `l = -support.sign()` is the side of the support foot the CoM travels on (+1 on the right
//! foot, where the CoM is to its left).
//!
//! ```
//! use steplearn::robot::Side;
//! use steplearn::control::capture_step::{CaptureStep, CaptureStepConfig, GaitReference};
//! use steplearn::control::lipm::LipmState;
//! use steplearn::control::lipm_plant::LipmPlant;
//!
//! let mut controller = CaptureStep::new(CaptureStepConfig::default())?;
//! let reference = GaitReference { step_x: 0.1, lateral: 0.0 };
//! // An ideal pendulum walker standing on its left foot, CoM 12 cm to the right of it.
//! let start = [LipmState::new(0.0, 0.0), LipmState::new(-0.12, 0.25)];
//! let mut plant = LipmPlant::new(controller.lipm(), 0.30, 0.11, Side::Left, start);
//! let mut steps = Vec::new();
//! while plant.time < 5.0 {
//!     let decision = controller.update(&plant.com_state(), &reference, 0.0)?;
//!     if let Some(touch_down) = plant.step(&decision, 0.005) {
//!         steps.push(touch_down.step[0]);
//!     }
//! }
//! assert!((steps.last().unwrap() - 0.1).abs() < 0.01);
//! # Ok::<(), steplearn::control::capture_step::CaptureStepError>(())
//! ```
//!
//! ## Deriving the target from a step size
//! Nominal walking is symmetric: the CoM passes the lateral apex `l alpha` at mid-step and
//! reaches the support exchange `l xi` after `tau = acosh(xi / alpha) / C`. Sagittally the CoM
//! is at `-s_x` at touch-down and `s_x` at the exchange, so a step of size `F_R` (foot to foot)
//! needs `s_x = F_R / 2` and, with the apex half a step earlier, `s_x' = C s_x / tanh(C tau)`.
//! (Equivalent to the paper's velocity form with apex speed `C s_x / sinh(C tau)`.)
//!
//! ## The robot the defaults are for
//! One place for the numbers (the simulated humanoid of the paper, built after Winter's
//! anthropometric fractions of a 2.0 m, 13.5 kg body; see also
//! [`LegGeometry::default`](crate::robot::kinematics::LegGeometry)):
//!
//! | quantity | value | from |
//! |---|---|---|
//! | CoM height while walking | 1.13 m | measured on the simulated body (1.16 m standing) |
//! | `C = sqrt(g/h)` | 2.95 1/s | g = 9.81 |
//! | hip half-width | 0.10 m | Winter hip width 0.191 H, joint centres inside |
//! | foot (sole) | 0.30 x 0.11 m | 0.152 H x 0.055 H |
//! | nominal step time `2 tau` | 0.40 s | the step generator's period ([`MotionConfig::period`](crate::control::motion::MotionConfig)) |
//! | `delta` (support exchange) | 0.12 m | feet 0.24 m apart in place |
//! | `alpha` (lateral apex) | `delta / cosh(C tau)` = 0.102 m | derived |
//! | `omega` (long lateral step) | 0.20 m | |
//! | ZMP x range | [-0.08, 0.08] m | inside the 0.30 m sole with margin; symmetric because the stiff generator realises no ZMP of its own (see below) |
//! | ZMP y range | +-0.02 m | inside the 0.11 m sole with margin |
//!
//! ## On a stiff, position-controlled robot
//! The step generator does not realise `Z`: with stiff servos the support leg's sweep moves
//! the CoM kinematically and the ZMP goes wherever that motion needs it. The walker therefore
//! drives the support leg's sweep with the *reference* step, not with the controller's step
//! (see [`StepCommand::gait_x`](crate::control::motion::StepCommand)); the controller's
//! footstep only places the swing foot. The sagittal ZMP range is then a model parameter, not
//! a realised bound, chosen so that the humanoid stepping in place with `F_R = 0` takes no
//! mean step (`tests/all/walker_humanoid.rs` checks the chosen default).

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::lipm::{Lipm, LipmState};
use crate::robot::Side;

/// What can go wrong configuring or running the controller.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CaptureStepError {
    /// A configuration value is out of range.
    #[error("invalid capture step config: {param} {reason}")]
    InvalidConfig {
        /// The parameter's name.
        param: &'static str,
        /// Why it is invalid.
        reason: String,
    },
    /// An input was NaN or infinite, or time ran backwards.
    #[error("invalid controller input: {0}")]
    InvalidInput(String),
}

fn invalid(param: &'static str, reason: impl Into<String>) -> CaptureStepError {
    CaptureStepError::InvalidConfig {
        param,
        reason: reason.into(),
    }
}

/// Parameters of the Capture Step controller. Validated by [`CaptureStep::new`].
///
/// Defaults are derived for the 2 m, 13.5 kg humanoid (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CaptureStepConfig {
    /// LIPM constant `C = sqrt(g/h)` (1/s); not `C^2`.
    pub c: f64,
    /// Nominal step time `2 tau` (s) when walking without lateral command; sets the lateral
    /// apex offset `alpha = delta / cosh(C tau)`.
    pub nominal_step_time: f64,
    /// Lateral CoM offset from the support foot at the support exchange, in place (m).
    pub delta: f64,
    /// Largest lateral support-exchange offset, for a full lateral command (m).
    pub omega: f64,
    /// Sagittal ZMP range `[min, max]` in the support foot frame (m).
    pub zmp_x: [f64; 2],
    /// Lateral ZMP bound: `|Z_y| <= zmp_y` (m).
    pub zmp_y: f64,
    /// Largest sagittal CoM offset from the support foot before the step must happen (m).
    pub max_com_x: f64,
    /// Longest step time the controller outputs (s).
    pub max_step_time: f64,
    /// Shortest duration of a whole step, from the support exchange (s): the swing leg's
    /// speed limit. The step time is never shorter than what remains of it.
    pub min_step_duration: f64,
    /// Below this nominal remaining time the lateral ZMP is held, not recomputed (s).
    pub zmp_hold_time: f64,
    /// Bound on the reference step size `|F_R|` (m).
    pub max_reference_step: f64,
    /// Bound on the commanded sagittal step `|S_x|`, foot to foot (m): the legs' reach.
    pub max_step_x: f64,
    /// Whether the analytic sagittal footstep is used. When false the step is the nominal step
    /// in place plus the learned offset `dF` (the learner alone decides the step).
    pub analytic_footstep: bool,
}

impl Default for CaptureStepConfig {
    fn default() -> Self {
        CaptureStepConfig {
            c: crate::robot::HUMANOID_C,
            nominal_step_time: 0.40,
            delta: 0.12,
            omega: 0.20,
            zmp_x: [-0.08, 0.08],
            zmp_y: 0.02,
            max_com_x: 0.30,
            max_step_time: 1.0,
            min_step_duration: 0.3,
            zmp_hold_time: 0.05,
            max_reference_step: 0.30,
            max_step_x: 0.50,
            analytic_footstep: true,
        }
    }
}

impl CaptureStepConfig {
    /// Checks every field; the first violation is returned.
    pub fn validate(&self) -> Result<(), CaptureStepError> {
        let pos = |name: &'static str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(invalid(
                    name,
                    format!("must be positive and finite, got {v}"),
                ))
            }
        };
        pos("c", self.c)?;
        pos("nominal_step_time", self.nominal_step_time)?;
        pos("delta", self.delta)?;
        pos("omega", self.omega)?;
        pos("zmp_y", self.zmp_y)?;
        pos("max_com_x", self.max_com_x)?;
        pos("max_step_time", self.max_step_time)?;
        pos("max_reference_step", self.max_reference_step)?;
        pos("max_step_x", self.max_step_x)?;
        if !(self.min_step_duration.is_finite()
            && self.min_step_duration >= 0.0
            && self.min_step_duration <= self.nominal_step_time)
        {
            return Err(invalid(
                "min_step_duration",
                format!(
                    "must be in [0, nominal_step_time], got {}",
                    self.min_step_duration
                ),
            ));
        }
        if !(self.zmp_hold_time.is_finite() && self.zmp_hold_time >= 0.0) {
            return Err(invalid(
                "zmp_hold_time",
                format!("must be >= 0 and finite, got {}", self.zmp_hold_time),
            ));
        }
        if self.omega < self.delta {
            return Err(invalid(
                "omega",
                format!("must be >= delta ({}), got {}", self.delta, self.omega),
            ));
        }
        let [lo, hi] = self.zmp_x;
        if !(lo.is_finite() && hi.is_finite() && lo <= 0.0 && hi >= 0.0) {
            return Err(invalid(
                "zmp_x",
                format!("must be finite with min <= 0 <= max, got [{lo}, {hi}]"),
            ));
        }
        if self.nominal_step_time > self.max_step_time {
            return Err(invalid(
                "nominal_step_time",
                format!(
                    "must not exceed max_step_time ({}), got {}",
                    self.max_step_time, self.nominal_step_time
                ),
            ));
        }
        Ok(())
    }

    /// Lateral apex offset `alpha = delta / cosh(C tau)` implied by the nominal step time.
    pub fn alpha(&self) -> f64 {
        self.delta / (0.5 * self.c * self.nominal_step_time).cosh()
    }
}

/// What the gait should do: the reference the controller tracks.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct GaitReference {
    /// Desired sagittal step size `F_R`, foot to foot (m; positive forward).
    pub step_x: f64,
    /// Lateral walking command in [-1, 1] (positive to the left; 0 steps in place laterally).
    pub lateral: f64,
}

/// The CoM state the controller reads: relative to the support foot's sole centre, in the
/// heading frame (x forward, y left), per axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ComState {
    /// Time of the measurement (s); must not decrease between calls.
    pub time: f64,
    /// The foot the robot stands on.
    pub support: Side,
    /// Sagittal (index 0) and lateral (index 1) CoM position and velocity.
    pub axes: [LipmState; 2],
}

/// The controller's decision for one tick.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepDecision {
    /// The support foot this decision is for.
    pub support: Side,
    /// ZMP `Z` in the support foot frame, clamped to the configured range (m).
    pub zmp: [f64; 2],
    /// Time until the support exchange `T` (s).
    pub time_to_step: f64,
    /// Target end-of-step state `s`, relative to the support foot.
    pub target: [LipmState; 2],
    /// Achievable end-of-step state `c'`, relative to the support foot.
    pub end_of_step: [LipmState; 2],
    /// Footstep `F`: the new foot relative to the CoM at the end of the step (m).
    pub footstep: [f64; 2],
    /// Step vector `S = c' + F`: the new foot relative to the support foot (m).
    pub step: [f64; 2],
    /// The learned sagittal offset that was added (m).
    pub learned_offset: f64,
    /// The learned lateral offset that was added to the step's y (m, positive to the left).
    pub lateral_offset: f64,
    /// The sagittal step without the learned offset and before the step limit (m; 0 when the
    /// analytic footstep is off): the step is `clamp(analytic_step_x + learned_offset)`.
    pub analytic_step_x: f64,
    /// The learned step-time offset that was added (s).
    pub time_offset: f64,
    /// The step time without the learned offset (s): `time_to_step` is it plus the offset,
    /// kept within the step's time limits.
    pub analytic_time_to_step: f64,
    /// The step-time offsets `[lo, hi]` that can change the step time this tick (s): beyond
    /// them the limits (the swing's shortest duration, the longest step time) clamp it away.
    pub time_reach: [f64; 2],
    /// Whether the CoM is crossing towards the support leg (the step time is then the maximum).
    pub crossing: bool,
}

/// Memory kept between ticks.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct Memory {
    support: Side,
    time: f64,
    support_since: f64,
    nominal_remaining: f64,
    time_to_step: f64,
    zmp_y: f64,
}

/// The Capture Step balance controller (sagittal and lateral).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaptureStep {
    config: CaptureStepConfig,
    lipm: Lipm,
    alpha: f64,
    memory: Option<Memory>,
}

impl CaptureStep {
    /// A controller from a validated config.
    pub fn new(config: CaptureStepConfig) -> Result<Self, CaptureStepError> {
        config.validate()?;
        let lipm = Lipm::new(config.c).map_err(|e| invalid("c", e.to_string()))?;
        Ok(CaptureStep {
            config,
            lipm,
            alpha: config.alpha(),
            memory: None,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &CaptureStepConfig {
        &self.config
    }

    /// The pendulum model the controller assumes.
    pub fn lipm(&self) -> Lipm {
        self.lipm
    }

    /// Lateral apex offset `alpha` (m), derived from the config.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// Switches the analytic sagittal footstep on or off (see [`CaptureStepConfig`]).
    pub fn set_analytic_footstep(&mut self, on: bool) {
        self.config.analytic_footstep = on;
    }

    /// Forgets the step timing (after a reset of the robot).
    pub fn reset(&mut self) {
        self.memory = None;
    }

    /// `l`: +1 when the CoM travels on the left of the support foot (right support), else -1.
    pub fn lateral_sign(support: Side) -> f64 {
        -support.sign()
    }

    /// Lateral support-exchange offset `xi` for a support foot and lateral command.
    fn exchange_offset(&self, support: Side, reference: &GaitReference) -> f64 {
        let l = Self::lateral_sign(support);
        let lat = reference.lateral.clamp(-1.0, 1.0);
        if l * lat > 0.0 {
            self.config.delta + lat.abs() * (self.config.omega - self.config.delta)
        } else {
            self.config.delta
        }
    }

    /// The nominal width (m) of the step taken from `support` under `reference`: the feet
    /// `2 xi` apart, `2 delta` in place and up to `2 omega` for steps towards a full lateral
    /// command (the steps away from it keep `2 delta`, so a full command walks `omega - delta`
    /// per step on average).
    pub fn reference_width(&self, support: Side, reference: &GaitReference) -> f64 {
        2.0 * self.exchange_offset(support, reference)
    }

    /// Nominal half step time `tau = acosh(xi / alpha) / C` (s).
    pub fn half_step_time(&self, support: Side, reference: &GaitReference) -> f64 {
        (self.exchange_offset(support, reference) / self.alpha).acosh() / self.lipm.c()
    }

    /// Target end-of-step state `s` (sagittal, lateral) relative to the support foot.
    pub fn target_state(&self, support: Side, reference: &GaitReference) -> [LipmState; 2] {
        let c = self.lipm.c();
        let l = Self::lateral_sign(support);
        let xi = self.exchange_offset(support, reference);
        let tau = self.half_step_time(support, reference);
        let step = reference.step_x.clamp(
            -self.config.max_reference_step,
            self.config.max_reference_step,
        );
        let sx = 0.5 * step;
        let vx = if sx == 0.0 {
            0.0
        } else {
            c * sx / (c * tau).tanh()
        };
        let vy = l * c * (xi * xi - self.alpha * self.alpha).max(0.0).sqrt();
        [LipmState::new(sx, vx), LipmState::new(l * xi, vy)]
    }

    /// One control tick: the decision `(F, Z, T)` for the CoM state `com`, the reference and
    /// the learned sagittal offset `learned_offset` (`dF`, m; 0 without a learner).
    ///
    /// Rejects non-finite inputs and decreasing time without changing the controller.
    pub fn update(
        &mut self,
        com: &ComState,
        reference: &GaitReference,
        learned_offset: f64,
    ) -> Result<StepDecision, CaptureStepError> {
        self.update_with_offsets(com, reference, [learned_offset, 0.0, 0.0])
    }

    /// [`Self::update`] with learned offsets of every step parameter: `offsets[0]` is the
    /// sagittal `dF` added to the footstep's x, `offsets[1]` a lateral offset added to its y
    /// (m, heading frame, positive to the left), `offsets[2]` a step-time offset `dT` added to
    /// the step time before its limits (s; the sagittal ZMP, the end-of-step state and the
    /// footstep follow the offset time). 0 for a parameter without a learner.
    pub fn update_with_offsets(
        &mut self,
        com: &ComState,
        reference: &GaitReference,
        offsets: [f64; 3],
    ) -> Result<StepDecision, CaptureStepError> {
        check_inputs(com, reference, offsets)?;
        let [learned_offset, lateral_offset, time_offset] = offsets;
        if let Some(m) = &self.memory
            && com.time < m.time
        {
            return Err(CaptureStepError::InvalidInput(format!(
                "time went backwards: {} after {}",
                com.time, m.time
            )));
        }
        let cfg = self.config;
        let lipm = self.lipm;
        let c = lipm.c();
        let support = com.support;
        let l = Self::lateral_sign(support);
        let tau = self.half_step_time(support, reference);
        let target = self.target_state(support, reference);
        let [cx, cy] = com.axes;

        // Support exchange (or first tick): restart the nominal step clock.
        let (mut mem, dt) = match self.memory {
            Some(m) if m.support == support => {
                let dt = com.time - m.time;
                let mem = Memory {
                    time: com.time,
                    nominal_remaining: m.nominal_remaining - dt,
                    ..m
                };
                (mem, dt)
            }
            _ => {
                let mem = Memory {
                    support,
                    time: com.time,
                    support_since: com.time,
                    nominal_remaining: 2.0 * tau,
                    time_to_step: 2.0 * tau,
                    zmp_y: 0.0,
                };
                (mem, 0.0)
            }
        };

        // 1. Lateral ZMP towards the target in the nominal remaining time.
        if mem.nominal_remaining > cfg.zmp_hold_time
            && let Some(z) = lipm.zmp_to_reach(cy, target[1].pos, mem.nominal_remaining)
        {
            mem.zmp_y = z.clamp(-cfg.zmp_y, cfg.zmp_y);
        }
        let zy = mem.zmp_y;

        // 2. Step time from the lateral pendulum.
        let energy_y = lipm.energy(cy, zy);
        let inward = l * cy.vel < 0.0;
        let crossing = (inward && (energy_y > 0.0 || l * cy.pos < 0.0))
            || (l * cy.pos < 0.0 && energy_y < 0.0);
        let stalling = energy_y < lipm.energy(LipmState::new(target[1].pos, 0.0), zy);
        let mut t_step = if crossing {
            cfg.max_step_time
        } else if let Some(t) = lipm
            .time_to_location(cy, zy, target[1].pos)
            .filter(|t| *t > 0.0)
        {
            t
        } else if let Some(t) = lipm
            .time_to_velocity(cy, zy, 0.0)
            .filter(|t| *t > 0.0 && stalling)
        {
            t
        } else {
            mem.time_to_step - dt
        };
        // Keep the sagittal CoM within its excursion limit.
        for bound in [cfg.max_com_x, -cfg.max_com_x] {
            if let Some(t) = lipm.time_to_location(cx, 0.0, bound)
                && t > 0.0
                && t < t_step
            {
                t_step = t;
            }
        }
        if cx.pos.abs() > cfg.max_com_x {
            t_step = 0.0;
        }
        let min_left = cfg.min_step_duration - (com.time - mem.support_since);
        t_step = t_step.max(min_left).clamp(0.0, cfg.max_step_time);
        mem.time_to_step = t_step;
        let analytic_time_to_step = t_step;
        let time_reach = [
            min_left.clamp(0.0, cfg.max_step_time) - t_step,
            cfg.max_step_time - t_step,
        ];
        if time_offset != 0.0 {
            t_step = (t_step + time_offset)
                .max(min_left)
                .clamp(0.0, cfg.max_step_time);
        }

        // 3. Sagittal ZMP towards the target at the step time.
        let zx = lipm
            .zmp_to_reach(cx, target[0].pos, t_step)
            .unwrap_or(0.0)
            .clamp(cfg.zmp_x[0], cfg.zmp_x[1]);
        let zmp = [zx, zy];

        // 4. Achievable end-of-step state.
        let end = [
            lipm.state_after(cx, zx, t_step),
            lipm.state_after(cy, zy, t_step),
        ];

        // 5. Footstep relative to the CoM at the end of the step.
        let fy = lipm
            .pivot_for(end[1], -l * self.alpha, 0.0)
            .unwrap_or(l * self.alpha);
        // The sagittal state the footstep is placed for: at the step time.
        let placed_for = end[0];
        let analytic_step_x = if cfg.analytic_footstep {
            placed_for.pos + placed_for.vel / c * (c * tau).tanh()
        } else {
            0.0
        };
        let step_x = (analytic_step_x + learned_offset).clamp(-cfg.max_step_x, cfg.max_step_x);
        let footstep = [step_x - end[0].pos, fy + lateral_offset];
        let step = [step_x, end[1].pos + fy + lateral_offset];

        self.memory = Some(mem);
        Ok(StepDecision {
            support,
            zmp,
            time_to_step: t_step,
            target,
            end_of_step: end,
            footstep,
            step,
            learned_offset,
            lateral_offset,
            analytic_step_x,
            time_offset,
            analytic_time_to_step,
            time_reach,
            crossing,
        })
    }
}

fn check_inputs(
    com: &ComState,
    reference: &GaitReference,
    learned_offsets: [f64; 3],
) -> Result<(), CaptureStepError> {
    let ok = com.time.is_finite()
        && com.axes.iter().all(LipmState::is_finite)
        && reference.step_x.is_finite()
        && reference.lateral.is_finite()
        && learned_offsets.iter().all(|v| v.is_finite());
    if ok {
        Ok(())
    } else {
        Err(CaptureStepError::InvalidInput(format!(
            "non-finite value in {com:?}, {reference:?} or learned offsets {learned_offsets:?}"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_width_widens_only_the_steps_towards_a_lateral_command() {
        let cs = CaptureStep::new(CaptureStepConfig::default()).unwrap();
        let (delta, omega) = (cs.config.delta, cs.config.omega);
        let place = GaitReference::default();
        for support in Side::BOTH {
            assert_eq!(cs.reference_width(support, &place), 2.0 * delta);
        }
        let left = GaitReference {
            step_x: 0.0,
            lateral: 0.5,
        };
        // The left foot swings from right support: towards the command.
        let wide = 2.0 * (delta + 0.5 * (omega - delta));
        assert!((cs.reference_width(Side::Right, &left) - wide).abs() < 1e-12);
        assert_eq!(cs.reference_width(Side::Left, &left), 2.0 * delta);
        let right = GaitReference {
            step_x: 0.0,
            lateral: -1.0,
        };
        assert!((cs.reference_width(Side::Left, &right) - 2.0 * omega).abs() < 1e-12);
        assert_eq!(cs.reference_width(Side::Right, &right), 2.0 * delta);
    }

    fn nominal(cs: &CaptureStep, support: Side, r: &GaitReference) -> ComState {
        // Start of step: mirror of the target (CoM behind the foot, moving towards the apex).
        let s = cs.target_state(support, r);
        ComState {
            time: 0.0,
            support,
            axes: [
                LipmState::new(-s[0].pos, s[0].vel),
                LipmState::new(s[1].pos, -s[1].vel),
            ],
        }
    }

    #[test]
    fn after_a_push_a_sooner_step_is_a_shorter_step() {
        let r = GaitReference {
            step_x: 0.2,
            lateral: 0.0,
        };
        let decide = |dt: f64| {
            let mut cs = CaptureStep::new(CaptureStepConfig::default()).unwrap();
            // Pushed forward: the ZMP saturates and the capture point runs ahead.
            let mut com = nominal(&cs, Side::Left, &r);
            com.axes[0].vel += 0.3;
            cs.update_with_offsets(&com, &r, [0.0, 0.0, dt]).unwrap()
        };
        let (analytic, sooner) = (decide(0.0), decide(-0.05));
        assert!(sooner.time_to_step < analytic.time_to_step - 0.04);
        assert!(sooner.step[0] < analytic.step[0] - 0.01, "{sooner:?}");
    }

    #[test]
    fn default_config_is_valid_and_alpha_matches_step_time() {
        let cfg = CaptureStepConfig::default();
        cfg.validate().unwrap();
        let cs = CaptureStep::new(cfg).unwrap();
        let tau = cs.half_step_time(Side::Left, &GaitReference::default());
        assert!((2.0 * tau - cfg.nominal_step_time).abs() < 1e-12);
    }

    #[test]
    fn bad_configs_are_rejected() {
        let base = CaptureStepConfig::default();
        let bad = [
            CaptureStepConfig { c: 0.0, ..base },
            CaptureStepConfig {
                c: f64::NAN,
                ..base
            },
            CaptureStepConfig {
                omega: 0.05,
                ..base
            },
            CaptureStepConfig {
                zmp_x: [0.01, 0.1],
                ..base
            },
            CaptureStepConfig {
                zmp_y: -0.01,
                ..base
            },
            CaptureStepConfig {
                nominal_step_time: 2.0,
                ..base
            },
        ];
        for cfg in bad {
            assert!(CaptureStep::new(cfg).is_err(), "{cfg:?}");
        }
    }

    #[test]
    fn nominal_state_gives_nominal_decision() {
        let mut cs = CaptureStep::new(CaptureStepConfig::default()).unwrap();
        for support in Side::BOTH {
            for fr in [-0.1, 0.0, 0.2] {
                cs.reset();
                let r = GaitReference {
                    step_x: fr,
                    lateral: 0.0,
                };
                let d = cs.update(&nominal(&cs, support, &r), &r, 0.0).unwrap();
                assert!(
                    (d.time_to_step - cs.config().nominal_step_time).abs() < 1e-9,
                    "{d:?}"
                );
                assert!(d.zmp[0].abs() < 1e-9 && d.zmp[1].abs() < 1e-9, "{d:?}");
                assert!((d.step[0] - fr).abs() < 1e-9, "{d:?}");
                let l = CaptureStep::lateral_sign(support);
                assert!((d.step[1] - 2.0 * l * 0.12).abs() < 1e-9, "{d:?}");
            }
        }
    }

    #[test]
    fn rejected_input_leaves_state_unchanged() {
        let mut cs = CaptureStep::new(CaptureStepConfig::default()).unwrap();
        let r = GaitReference::default();
        let mut s = nominal(&cs, Side::Left, &r);
        cs.update(&s, &r, 0.0).unwrap();
        let before = cs.clone();
        s.axes[0].vel = f64::NAN;
        assert!(cs.update(&s, &r, 0.0).is_err());
        assert_eq!(cs, before);
        s.axes[0].vel = 0.0;
        s.time = -1.0;
        assert!(cs.update(&s, &r, 0.0).is_err());
        assert_eq!(cs, before);
    }

    #[test]
    fn learned_offset_adds_to_step_and_switch_removes_analytic_part() {
        let mut cs = CaptureStep::new(CaptureStepConfig::default()).unwrap();
        let r = GaitReference {
            step_x: 0.2,
            lateral: 0.0,
        };
        let s = nominal(&cs, Side::Right, &r);
        let d0 = cs.update(&s, &r, 0.0).unwrap();
        cs.reset();
        let d1 = cs.update(&s, &r, 0.03).unwrap();
        assert!((d1.step[0] - d0.step[0] - 0.03).abs() < 1e-12);
        cs.reset();
        cs.set_analytic_footstep(false);
        let d2 = cs.update(&s, &r, 0.03).unwrap();
        assert!((d2.step[0] - 0.03).abs() < 1e-12);
        assert!((d2.footstep[0] + d2.end_of_step[0].pos - 0.03).abs() < 1e-12);
    }
}
