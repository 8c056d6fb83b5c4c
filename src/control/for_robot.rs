//! The walker and the learner for a robot other than the paper's, by dynamic similarity
//! ([`Scale`]): the walker's lengths, times, rates and forces scaled from the paper robot's
//! settings, and a learner that keeps seeing the paper robot's units.
//!
//! The learner is wrapped, not rescaled: [`ScaledPolicy`] hands any policy its inputs and
//! outcomes divided into the paper robot's units (lengths by `l`, rates by `1/sqrt(l)`) and
//! multiplies the offsets it returns back. So the paper's `p_F`, eta, the gain guard, the
//! prior's box and the approximator's input scales hold for every robot, and a user's own
//! rule or approximator needs no change.

use super::LearnerInput;
use super::learner_error::LearnerError;
use super::motion::GaitShape;
use super::policy::{FootstepPolicy, StepReports};
use super::step_parameter::{LearnSet, PerParameter, StepParameter};
use super::walker::WalkerConfig;
use crate::robot::Scale;
use crate::rules::StepOutcome;

impl WalkerConfig {
    /// These settings (for the paper's robot) for a robot of `scale`: every length, time, rate
    /// and force scaled; the LIPM constant from the robot's centre-of-mass height; the
    /// estimator's centre of mass shifted to the robot's, and the reference point on each
    /// sole placed where the stance centre of mass lies as on the paper's robot. The paper's
    /// robot gets them back unchanged, bit for bit.
    pub fn for_robot(&self, s: &Scale) -> WalkerConfig {
        let mut w = *self;
        let l = |x: f64| s.length(x);
        let t = |x: f64| s.time(x);
        w.start_ramp_s = t(w.start_ramp_s);
        w.sole_reference_x = l(w.sole_reference_x) + s.sole_shift_x;
        let c = &mut w.capture_step;
        c.c = s.lipm_c(c.c);
        c.nominal_step_time = t(c.nominal_step_time);
        c.delta = s.width(c.delta);
        c.omega = s.width(c.omega);
        c.zmp_x = c.zmp_x.map(l);
        c.zmp_y = l(c.zmp_y);
        c.max_com_x = l(c.max_com_x);
        c.max_step_time = t(c.max_step_time);
        c.min_step_duration = t(c.min_step_duration);
        c.zmp_hold_time = t(c.zmp_hold_time);
        c.max_reference_step = l(c.max_reference_step);
        c.max_step_x = l(c.max_step_x);
        let e = &mut w.estimator;
        e.com_offset = std::array::from_fn(|i| l(e.com_offset[i]) + s.com_shift[i]);
        e.min_total_force = s.force(e.min_total_force);
        e.min_support_time = t(e.min_support_time);
        e.velocity_time_constant = t(e.velocity_time_constant);
        let m = &mut w.motion;
        m.step_x_range = m.step_x_range.map(l);
        m.step_y_range = m.step_y_range.map(|y| s.width(y));
        m.period = t(m.period);
        m.fade_in = t(m.fade_in);
        m.tilt_settle_s = t(m.tilt_settle_s);
        m.gait = m.gait.for_robot(s);
        w
    }
}

impl GaitShape {
    /// This gait's primitives for a robot of `scale`.
    pub fn for_robot(&self, s: &Scale) -> GaitShape {
        // The extensions are fractions of the leg's length: the same for every robot.
        GaitShape {
            sway: s.width(self.sway),
            lean_per_step: self.lean_per_step / s.length,
            filter_time: s.time(self.filter_time),
            ..*self
        }
    }
}

/// A policy that learns in the paper robot's units on a robot of another size.
pub struct ScaledPolicy<'a, 'p> {
    inner: &'a mut (dyn FootstepPolicy + 'p),
    scale: Scale,
}

impl<'a, 'p> ScaledPolicy<'a, 'p> {
    /// `inner`, seeing a robot of `scale` as the paper's.
    pub fn new(inner: &'a mut (dyn FootstepPolicy + 'p), scale: Scale) -> Self {
        ScaledPolicy { inner, scale }
    }

    /// A parameter's offset in the robot's units from the paper robot's.
    fn to_robot(&self, p: StepParameter, x: f64) -> f64 {
        match p {
            StepParameter::StepX => self.scale.length(x),
            StepParameter::StepY => self.scale.length(x),
            StepParameter::StepTime => self.scale.time(x),
            StepParameter::AnklePitch | StepParameter::AnkleRoll => x,
        }
    }

    fn to_paper(&self, p: StepParameter, x: f64) -> f64 {
        x / self.to_robot(p, 1.0)
    }

    fn input(&self, i: LearnerInput) -> LearnerInput {
        LearnerInput {
            theta_e: i.theta_e,
            theta_e_dot: i.theta_e_dot * self.scale.time_factor(),
            f_r: i.f_r / self.scale.length,
        }
    }

    fn outcomes(&self, o: &PerParameter<StepOutcome>) -> PerParameter<StepOutcome> {
        o.map(|o| StepOutcome {
            theta_e: o.theta_e,
            theta_e_dot: o.theta_e_dot * self.scale.time_factor(),
            f_e: o.f_e / self.scale.length,
            f_r: o.f_r / self.scale.length,
        })
    }
}

impl FootstepPolicy for ScaledPolicy<'_, '_> {
    fn learns(&self) -> LearnSet {
        self.inner.learns()
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        let paper = self.inner.offsets(&inputs.map(|i| self.input(i)))?;
        let mut out = paper;
        for p in StepParameter::ALL {
            out[p] = self.to_robot(p, paper[p]);
        }
        Ok(out)
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        let mut paper = *reach;
        for p in StepParameter::ALL {
            paper[p] = reach[p].map(|x| self.to_paper(p, x));
        }
        self.inner.set_reach(&paper)
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        let o = self.outcomes(outcomes);
        self.inner.touch_down(&o)
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        let o = self.outcomes(outcomes);
        self.inner.fall(&o)
    }
    fn discard_step(&mut self) {
        self.inner.discard_step()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A robot of half the paper robot's leg length and 0.8 of its hip width.
    fn small() -> Scale {
        Scale {
            length: 0.5,
            width: 0.8,
            ..Scale::ONE
        }
    }

    /// The legs' extensions are fractions of each robot's own leg: scaling them by the length
    /// factor as well would lift a small robot's swing foot by a smaller share of its leg.
    #[test]
    fn a_gait_keeps_its_extensions_and_scales_its_lengths_and_times() {
        let paper = GaitShape {
            push_extension: 0.01,
            ..GaitShape::default()
        };
        let s = small();
        let robot = paper.for_robot(&s);
        assert_eq!(robot.halt_extension, paper.halt_extension);
        assert_eq!(robot.lift_extension, paper.lift_extension);
        assert_eq!(robot.push_extension, paper.push_extension);
        assert_eq!(robot.sway, paper.sway * 0.8);
        assert_eq!(robot.lean_per_step, paper.lean_per_step / 0.5);
        assert_eq!(robot.filter_time, paper.filter_time * 0.5f64.sqrt());
        assert_eq!(paper.for_robot(&Scale::ONE), paper);
    }
}
