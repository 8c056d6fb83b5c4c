//! One learner for any set of step parameters.

use super::policy::{FootstepPolicy, StepReports, gate_weight};
use super::step_parameter::{FallDirection, LearnSet, PerParameter, Plane, StepParameter};
use super::{FootstepLearner, LearnerError, LearnerInput, SavedLearner, TouchDownReport};
use crate::approx::{FunctionApproximator, Persist};
use crate::rules::{LearningRule, StepOutcome};
use serde::{Deserialize, Serialize};

/// One [`FootstepLearner`] per learned step parameter and plane.
///
/// A [`StepLearner`] learns each parameter of its [`LearnSet`] with a [`FootstepLearner`] of
/// its own (the uncoupled setting): its own approximator over that parameter's inputs, and its
/// own rule, which turns that parameter's outcome into the gradient G. Every safeguard of the
/// footstep learner (prior, gain guard, anti-windup against the parameter's reach, trust
/// region, learning from falls, dead zone, leakage, `max_step_error`, the nominal fallback)
/// and its checkpoints therefore work for every parameter, and a user's rule for any parameter
/// plugs in as the learner's rule does. The built-in rules per parameter: the run's rule for
/// `step-x` and `step-y` (the lateral learner sees the mirrored frontal plane, see
/// [`FootstepPolicy`](super::FootstepPolicy)), [`StepTime`](crate::rules::StepTime) for `step-time`.
///
/// Each parameter's learner reads the plane its settings name
/// ([`CheckedLearnerConfig::planes`](super::learner_config::CheckedLearnerConfig::planes)):
/// `step-x` the sagittal, `step-y` the frontal, `step-time` the sagittal unless
/// `[settings.learner.step-time] plane = "frontal"`, which learns the step time from the lean
/// sideways and its outcome, or `"both"`: then the step time has two learners, one per plane,
/// each reading its plane's state and taught by its plane's outcome with its plane's rule, and
/// the offset is their sum (an additive model, dT = dT_s(sagittal state) + dT_f(frontal
/// state)). Each part's reach is the parameter's, less the other part's offset.
pub struct StepLearner<A: FunctionApproximator, R: LearningRule> {
    /// In the order of [`StepParameter::ALL`], the sagittal plane first; each parameter and
    /// plane once.
    slots: Vec<Slot<A, R>>,
    set: LearnSet,
}

/// A learner in its place: the parameter it gives the offset of (or a part of it) and the
/// plane it reads, the one its settings name for that parameter.
struct Slot<A: FunctionApproximator, R: LearningRule> {
    parameter: StepParameter,
    plane: Plane,
    learner: FootstepLearner<A, R>,
    /// The weight of its offset at the last query (its parameter's [`Gate`]).
    weight: f64,
    /// Its plane's fall direction, held from tick to tick for [`Gate::WithTheFall`].
    fall: FallDirection,
}

impl<A: FunctionApproximator, R: LearningRule> std::fmt::Debug for StepLearner<A, R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StepLearner")
            .field("learn", &self.set.to_string())
            .finish_non_exhaustive()
    }
}

/// A [`StepLearner`]'s checkpoint: each parameter's learner's (per plane).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedStepLearner<A> {
    /// Each learned parameter with its learner's checkpoint.
    pub learners: Vec<(StepParameter, SavedLearner<A>)>,
}

impl<A: FunctionApproximator, R: LearningRule> StepLearner<A, R> {
    /// The learner of `learners`, each learning the offset of its parameter in the plane its
    /// settings name for that parameter (any order; at least one; a parameter more than once
    /// only in different planes).
    pub fn new(
        learners: Vec<(StepParameter, FootstepLearner<A, R>)>,
    ) -> Result<Self, LearnerError> {
        let invalid = |reason: String| LearnerError::InvalidConfig {
            param: "learn",
            reason,
        };
        let mut slots = Vec::with_capacity(learners.len());
        for (parameter, learner) in learners {
            let Some(plane) = learner.settings().planes(parameter).single() else {
                return Err(invalid(format!(
                    "the learner given for {parameter} names both planes; give one per plane"
                )));
            };
            slots.push(Slot {
                parameter,
                plane,
                learner,
                weight: 1.0,
                fall: FallDirection::default(),
            });
        }
        slots.sort_by_key(|s| (s.parameter.index(), s.plane as usize));
        if let Some(w) = slots
            .windows(2)
            .find(|w| (w[0].parameter, w[0].plane) == (w[1].parameter, w[1].plane))
        {
            return Err(invalid(format!(
                "{} is learned twice in the {} plane",
                w[0].parameter, w[0].plane
            )));
        }
        let mut parameters: Vec<StepParameter> = slots.iter().map(|s| s.parameter).collect();
        parameters.dedup();
        let set = LearnSet::of(&parameters).map_err(|e| invalid(e.to_string()))?;
        Ok(StepLearner { slots, set })
    }

    /// The learner of `parameter`, if it is learned (in the sagittal plane if in both).
    pub fn learner(&self, parameter: StepParameter) -> Option<&FootstepLearner<A, R>> {
        self.slots
            .iter()
            .find(|s| s.parameter == parameter)
            .map(|s| &s.learner)
    }

    /// The learner of `parameter` in `plane`, if it is learned there.
    pub fn learner_in(
        &self,
        parameter: StepParameter,
        plane: Plane,
    ) -> Option<&FootstepLearner<A, R>> {
        self.slots
            .iter()
            .find(|s| (s.parameter, s.plane) == (parameter, plane))
            .map(|s| &s.learner)
    }

    /// Every learned parameter with its learner (one per plane it is learned in), in order.
    pub fn learners(&self) -> impl Iterator<Item = (StepParameter, &FootstepLearner<A, R>)> {
        self.slots.iter().map(|s| (s.parameter, &s.learner))
    }

    /// Reseeds every parameter's rule with `seed`.
    pub fn reseed(&mut self, seed: u64) {
        for s in &mut self.slots {
            s.learner.reseed(seed);
        }
    }
}

impl<A: FunctionApproximator + Persist + Clone, R: LearningRule> StepLearner<A, R> {
    /// A checkpoint of every parameter's learner (see [`FootstepLearner::checkpoint`]).
    pub fn checkpoint(&self) -> SavedStepLearner<A> {
        SavedStepLearner {
            learners: self
                .slots
                .iter()
                .map(|s| (s.parameter, s.learner.checkpoint()))
                .collect(),
        }
    }

    /// The learner of a checkpoint, each learner's rule from `rule` (given its parameter and
    /// plane): it continues bit for bit as the learner that wrote it. Errors as
    /// [`FootstepLearner::from_checkpoint`], or as [`Self::new`].
    pub fn from_checkpoint(
        saved: SavedStepLearner<A>,
        mut rule: impl FnMut(StepParameter, Plane) -> R,
    ) -> Result<Self, LearnerError> {
        let learners = saved
            .learners
            .into_iter()
            .map(|(p, s)| {
                let plane = s.config.planes(p).single().unwrap_or(p.default_plane());
                Ok((p, FootstepLearner::from_checkpoint(s, rule(p, plane))?))
            })
            .collect::<Result<Vec<_>, LearnerError>>()?;
        Self::new(learners)
    }
}

/// Two parts of one parameter's offset (two planes) reported as one: their gradients and
/// samples add, the gain and response are the mean, the guard's scale the smaller.
fn combined(a: TouchDownReport, b: TouchDownReport) -> TouchDownReport {
    TouchDownReport {
        gradient: a.gradient + b.gradient,
        samples: a.samples + b.samples,
        response: 0.5 * (a.response + b.response),
        gain: 0.5 * (a.gain + b.gain),
        scale: a.scale.min(b.scale),
    }
}

impl<A: FunctionApproximator + Clone, R: LearningRule> StepLearner<A, R> {
    /// Each learner's report of a step, `end` ending it (touch-down or fall), per parameter.
    fn end_step(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
        mut end: impl FnMut(
            &mut FootstepLearner<A, R>,
            &StepOutcome,
        ) -> Result<Option<TouchDownReport>, LearnerError>,
    ) -> Result<StepReports, LearnerError> {
        let mut out = StepReports::default();
        for s in &mut self.slots {
            let p = s.parameter;
            if let Some(r) = end(&mut s.learner, outcomes.in_plane(p, s.plane))? {
                out[p] = Some(match out[p] {
                    Some(first) => combined(first, r),
                    None => r,
                });
            }
        }
        Ok(out)
    }
}

impl<A: FunctionApproximator + Clone, R: LearningRule> FootstepPolicy for StepLearner<A, R> {
    fn learns(&self) -> LearnSet {
        self.set
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        let mut out = PerParameter::default();
        for s in &mut self.slots {
            let p = s.parameter;
            let offset = s.learner.query(*inputs.in_plane(p, s.plane))?;
            let gate = s.learner.settings().gate(p);
            s.weight = gate_weight(gate, s.plane, inputs, offset, &mut s.fall);
            out[p] += s.weight * offset;
        }
        Ok(out)
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        // Each part's reach is the parameter's less the other parts' (weighted) offsets; a
        // part weighted below 1 keeps that reach, which bounds its weighted offset too (the
        // reach holds 0).
        let mut total = PerParameter::splat(0.0);
        for s in &self.slots {
            total[s.parameter] += s.weight * s.learner.last_offset();
        }
        for s in &mut self.slots {
            let others = total[s.parameter] - s.weight * s.learner.last_offset();
            let [lo, hi] = reach[s.parameter];
            s.learner.set_reach(lo - others, hi - others)?;
        }
        Ok(())
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        self.end_step(outcomes, |l, o| l.touch_down(o).map(Some))
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        self.end_step(outcomes, |l, o| l.fall(o))
    }
    fn discard_step(&mut self) {
        for s in &mut self.slots {
            s.learner.discard_step();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::approx::{AnyApproximator, ApproxKind};
    use crate::control::Gate;
    use crate::control::{InputGrid, LearnerConfig};
    use crate::rules::{PendulumCart, SoleTilt, StepTime};

    fn learner(p: StepParameter) -> FootstepLearner<AnyApproximator, Box<dyn LearningRule>> {
        learner_with(p, LearnerConfig::default())
    }

    fn learner_with(
        p: StepParameter,
        config: LearnerConfig,
    ) -> FootstepLearner<AnyApproximator, Box<dyn LearningRule>> {
        let bounds = InputGrid::default().input_box().unwrap();
        let approx = ApproxKind::Grid.build(&bounds).unwrap();
        let plane = config.planes(p).single().unwrap();
        FootstepLearner::for_parameters(approx, [rule(p, plane)], [p], config).unwrap()
    }

    fn rule(p: StepParameter, plane: Plane) -> Box<dyn LearningRule> {
        match (p, plane) {
            (StepParameter::StepTime, Plane::Sagittal) => Box::new(StepTime::default()),
            (StepParameter::StepTime, Plane::Frontal) => Box::new(StepTime::frontal(0.2)),
            (StepParameter::AnklePitch, _) => Box::new(SoleTilt::pitch()),
            (StepParameter::AnkleRoll, _) => Box::new(roll_rule()),
            _ => Box::new(PendulumCart::default()),
        }
    }

    /// The roll's rule with a lever of its own: the humanoid's roll and pitch levers are
    /// equal, and a roll taught by the pitch's rule would not show with them.
    fn roll_rule() -> SoleTilt {
        SoleTilt {
            lever: 2.0 * SoleTilt::ROLL_LEVER,
            ..SoleTilt::roll()
        }
    }

    /// `outcome(theta_e)` in the sagittal plane, leaning 0.1 rad towards the swing leg at a
    /// width on the reference in the frontal plane.
    fn leaning_sideways(theta_e: f64) -> PerParameter<StepOutcome> {
        let mut o = outcome(theta_e);
        o[StepParameter::StepY] = StepOutcome {
            theta_e: 0.1,
            theta_e_dot: 0.0,
            f_e: 0.0,
            f_r: 0.0,
        };
        o
    }

    /// The step time in both planes: the sagittal and the frontal learner.
    fn both_planes() -> StepLearner<AnyApproximator, Box<dyn LearningRule>> {
        use crate::control::Planes;
        let config = LearnerConfig::default();
        let time = |plane: Plane| {
            learner_with(
                StepParameter::StepTime,
                config.in_planes(StepParameter::StepTime, plane.into()),
            )
        };
        let both = config.in_planes(StepParameter::StepTime, Planes::Both);
        assert!(both.check().is_ok());
        StepLearner::new(vec![
            (StepParameter::StepTime, time(Plane::Frontal)),
            (StepParameter::StepX, learner(StepParameter::StepX)),
            (StepParameter::StepTime, time(Plane::Sagittal)),
        ])
        .unwrap()
    }

    fn inputs(k: usize) -> PerParameter<LearnerInput> {
        let x = LearnerInput::new(0.01 * k as f64, 0.1, 0.0);
        PerParameter::from_planes(x, LearnerInput::new(-0.02, 0.0, 0.0))
    }

    /// Every reach [-1, 1], the step time's `time`.
    fn reach_of_time(time: [f64; 2]) -> PerParameter<[f64; 2]> {
        let mut reach = PerParameter::splat([-1.0, 1.0]);
        reach[StepParameter::StepTime] = time;
        reach
    }

    fn outcome(theta_e: f64) -> PerParameter<StepOutcome> {
        let o = StepOutcome {
            theta_e,
            theta_e_dot: 0.0,
            f_e: 0.2,
            f_r: 0.0,
        };
        PerParameter::splat(o)
    }

    /// A step learner of `parameters`, each with its default learner ([`learner`]).
    fn of(parameters: &[StepParameter]) -> StepLearner<AnyApproximator, Box<dyn LearningRule>> {
        StepLearner::new(parameters.iter().map(|&p| (p, learner(p))).collect()).unwrap()
    }

    /// `n` ticks of `l`: the offsets at `inputs(0..n)`, each reach [-1, 1].
    fn query(l: &mut StepLearner<AnyApproximator, Box<dyn LearningRule>>, n: usize) {
        for k in 0..n {
            l.offsets(&inputs(k)).unwrap();
            l.set_reach(&PerParameter::splat([-1.0, 1.0])).unwrap();
        }
    }

    #[test]
    fn each_parameter_learns_with_its_own_rule_and_the_rest_stay_zero() {
        let mut l = StepLearner::new(vec![
            (
                StepParameter::AnklePitch,
                learner(StepParameter::AnklePitch),
            ),
            (StepParameter::StepTime, learner(StepParameter::StepTime)),
            (StepParameter::StepX, learner(StepParameter::StepX)),
        ])
        .unwrap();
        assert_eq!(l.learns().to_string(), "step-x,step-time,ankle-pitch");
        let reach = PerParameter::splat([-1.0, 1.0]);
        for k in 0..5 {
            let o = l.offsets(&inputs(k)).unwrap();
            assert_eq!(o[StepParameter::StepY], 0.0);
            l.set_reach(&reach).unwrap();
        }
        let r = l.touch_down(&outcome(0.3)).unwrap();
        // Leaning forward after a long step: a longer step (G > 0), a sooner one (G_T < 0) and
        // the toe pressed harder (G_A > 0, a third of G).
        let g = r[StepParameter::StepX].unwrap().gradient;
        assert!(g > 0.0);
        assert!(r[StepParameter::StepTime].unwrap().gradient < 0.0);
        let g_a = r[StepParameter::AnklePitch].unwrap().gradient;
        assert!((g_a - SoleTilt::pitch().factor() * g).abs() < 1e-12);
        assert!(r[StepParameter::StepY].is_none());
        let o = l.offsets(&inputs(2)).unwrap();
        assert!(
            o[StepParameter::StepX] > 0.0
                && o[StepParameter::StepTime] < 0.0
                && o[StepParameter::AnklePitch] > 0.0,
            "{o:?}"
        );
    }

    #[test]
    fn a_frontal_step_time_reads_and_learns_the_frontal_plane() {
        use crate::control::ParameterSettings;
        let frontal = LearnerConfig {
            step_time: ParameterSettings {
                plane: Some(Plane::Frontal.into()),
                ..ParameterSettings::default()
            },
            ..LearnerConfig::default()
        };
        let bounds = InputGrid::default().input_box().unwrap();
        let time = FootstepLearner::for_parameters(
            ApproxKind::Grid.build(&bounds).unwrap(),
            [rule(StepParameter::StepTime, Plane::Frontal)],
            [StepParameter::StepTime],
            frontal,
        )
        .unwrap();
        let mut l = StepLearner::new(vec![
            (StepParameter::StepX, learner(StepParameter::StepX)),
            (StepParameter::StepTime, time),
        ])
        .unwrap();
        query(&mut l, 3);
        let lateral = inputs(0)[StepParameter::StepY];
        let time = l.learner(StepParameter::StepTime).unwrap();
        assert!(time.recorded_inputs().all(|x| x == lateral));
        let sagittal = l.learner(StepParameter::StepX).unwrap();
        assert!(sagittal.recorded_inputs().any(|x| x != lateral));
        // Taught by the frontal outcome: a lean towards the swing leg, where the sagittal one
        // leans back.
        let o = leaning_sideways(-0.1);
        let r = l.touch_down(&o).unwrap();
        let want = StepTime::frontal(0.2).gradient(&o[StepParameter::StepY]);
        assert_eq!(r[StepParameter::StepTime].unwrap().gradient, want);
        assert!(r[StepParameter::StepX].unwrap().gradient < 0.0);
    }

    #[test]
    fn the_soles_roll_reads_and_learns_the_frontal_plane() {
        let mut l = of(&[
            StepParameter::AnkleRoll,
            StepParameter::StepX,
            StepParameter::AnklePitch,
        ]);
        assert_eq!(l.learns().to_string(), "step-x,ankle-pitch,ankle-roll");
        query(&mut l, 3);
        let lateral = inputs(0)[StepParameter::AnkleRoll];
        let roll = l.learner(StepParameter::AnkleRoll).unwrap();
        assert_eq!(roll.plane(), Plane::Frontal);
        assert!(roll.recorded_inputs().all(|x| x == lateral));
        // Leaning back sagittally, towards the swing leg sideways: the roll presses the
        // sole's edge on the swing leg's side (G_R > 0, the frontal G times the roll's factor).
        let lean = StepOutcome {
            theta_e: 0.1,
            theta_e_dot: 0.0,
            f_e: 0.0,
            f_r: 0.0,
        };
        let back = outcome(-0.1)[StepParameter::StepX];
        let o = PerParameter::from_planes(back, lean);
        let r = l.touch_down(&o).unwrap();
        let g_r = r[StepParameter::AnkleRoll].unwrap().gradient;
        let g_a = r[StepParameter::AnklePitch].unwrap().gradient;
        assert!(g_r > 0.0 && g_a < 0.0, "{g_r} {g_a}");
        // Each sole by its own rule (levers differ) from its own plane's outcome.
        let g = |o: &StepOutcome| PendulumCart::default().gradient(o);
        let (roll, pitch) = (roll_rule().factor(), SoleTilt::pitch().factor());
        assert!((roll - pitch).abs() > 0.1 * pitch);
        assert!((g_r - roll * g(&lean)).abs() < 1e-12, "{g_r}");
        assert!((g_a - pitch * g(&back)).abs() < 1e-12, "{g_a}");
        assert!(r[StepParameter::StepX].unwrap().gradient < 0.0);
    }

    #[test]
    fn a_step_time_in_both_planes_sums_one_learner_per_plane() {
        let mut l = both_planes();
        assert_eq!(l.learns().to_string(), "step-x,step-time");
        let planes: Vec<_> = l.learners().map(|(p, l)| (p, l.plane())).collect();
        assert_eq!(
            planes,
            [
                (StepParameter::StepX, Plane::Sagittal),
                (StepParameter::StepTime, Plane::Sagittal),
                (StepParameter::StepTime, Plane::Frontal),
            ]
        );
        query(&mut l, 3);
        // Each part reads its own plane.
        let lateral = inputs(0)[StepParameter::StepY];
        let frontal = l
            .learner_in(StepParameter::StepTime, Plane::Frontal)
            .unwrap();
        assert!(frontal.recorded_inputs().all(|x| x == lateral));
        let sagittal = l
            .learner_in(StepParameter::StepTime, Plane::Sagittal)
            .unwrap();
        assert!(sagittal.recorded_inputs().any(|x| x != lateral));
        // Leaning forward and towards the swing leg: each part is taught by its own plane's
        // outcome and rule, and the report sums the two gradients.
        let o = leaning_sideways(0.2);
        let r = l.touch_down(&o).unwrap();
        let g_s = StepTime::default().gradient(&o[StepParameter::StepX]);
        let g_f = StepTime::frontal(0.2).gradient(&o[StepParameter::StepY]);
        assert!(g_s < 0.0 && g_f < 0.0, "{g_s} {g_f}");
        let time = r[StepParameter::StepTime].unwrap();
        assert!((time.gradient - (g_s + g_f)).abs() < 1e-15);
        // The offset is the sum of the parts at their planes' inputs.
        let x = inputs(1);
        let parts = [
            (Plane::Sagittal, StepParameter::StepX),
            (Plane::Frontal, StepParameter::StepY),
        ]
        .map(|(plane, at)| {
            let part = l.learner_in(StepParameter::StepTime, plane).unwrap();
            part.predict(x[at]).unwrap()
        });
        assert!(parts[0] < 0.0 && parts[1] < 0.0, "{parts:?}");
        let o = l.offsets(&x).unwrap();
        assert!((o[StepParameter::StepTime] - (parts[0] + parts[1])).abs() < 1e-12);
    }

    #[test]
    fn a_rate_share_gate_weights_each_part_by_its_planes_share_of_the_rate() {
        use crate::control::Planes;
        let config = LearnerConfig::default();
        let mut gated = config.in_planes(StepParameter::StepTime, Planes::Both);
        gated.step_time.gate = Some(Gate::RateShare);
        let time = |plane: Plane| {
            learner_with(
                StepParameter::StepTime,
                gated.part(StepParameter::StepTime, plane),
            )
        };
        let mut l = StepLearner::new(vec![
            (StepParameter::StepTime, time(Plane::Sagittal)),
            (StepParameter::StepTime, time(Plane::Frontal)),
        ])
        .unwrap();
        // Teach both parts a negative offset.
        let mut o = outcome(0.3);
        o[StepParameter::StepY].theta_e = 0.2;
        for k in 0..3 {
            l.offsets(&inputs(k)).unwrap();
            l.touch_down(&o).unwrap();
        }
        let last = |l: &StepLearner<_, _>, plane| {
            l.learner_in(StepParameter::StepTime, plane)
                .unwrap()
                .last_offset()
        };
        let mut x = inputs(1);
        for (sagittal_rate, frontal_rate) in [(0.1, 0.0), (0.1, 0.05), (0.05, 0.1), (0.0, 0.0)] {
            // The planes' rates: the sagittal input's (`step-x`, also the step time's own) and
            // the frontal one's.
            x[StepParameter::StepX].theta_e_dot = sagittal_rate;
            x[StepParameter::StepTime].theta_e_dot = sagittal_rate;
            x[StepParameter::StepY].theta_e_dot = frontal_rate;
            let got = l.offsets(&x).unwrap()[StepParameter::StepTime];
            let (s, f) = (last(&l, Plane::Sagittal), last(&l, Plane::Frontal));
            let w = |plane| Gate::RateShare.weight(plane, sagittal_rate, frontal_rate, 0.1);
            let (ws, wf) = (w(Plane::Sagittal), w(Plane::Frontal));
            assert!((ws + wf - 1.0).abs() < 1e-15);
            assert!((got - (ws * s + wf * f)).abs() < 1e-12, "{got} {s} {f}");
            if frontal_rate == 0.0 && sagittal_rate > 0.0 {
                // Where both parts were trained: the sagittal part alone acts.
                assert!(s < 0.0 && f < 0.0 && got == s, "{got} {s} {f}");
            }
        }
        assert_eq!(Gate::RateShare.weight(Plane::Frontal, 1.0, 0.0, 0.1), 0.0);
        assert_eq!(Gate::RateShare.weight(Plane::Frontal, 0.0, -2.0, 0.1), 1.0);
        assert_eq!(Gate::RateShare.weight(Plane::Sagittal, 0.0, 0.0, 0.1), 0.5);
        assert_eq!(Gate::Off.weight(Plane::Frontal, 1.0, 0.0, -0.1), 1.0);
        // With the fall: the sign of the offset against that of its own plane's rate.
        assert_eq!(
            Gate::WithTheFall.weight(Plane::Sagittal, -0.2, 0.5, -0.1),
            1.0
        );
        assert_eq!(
            Gate::WithTheFall.weight(Plane::Sagittal, 0.2, -0.5, -0.1),
            0.0
        );
        assert_eq!(Gate::WithTheFall.weight(Plane::Frontal, 0.2, 0.5, 0.1), 1.0);
        assert_eq!(Gate::WithTheFall.weight(Plane::Frontal, 0.2, 0.0, 0.1), 0.0);
        assert!(!Gate::WithTheFall.allows(StepParameter::StepTime));
        assert!(Gate::WithTheFall.allows(StepParameter::AnklePitch));
        // A checkpoint keeps the gate (it is each part's setting).
        let back = StepLearner::from_checkpoint(l.checkpoint(), rule).unwrap();
        let part = back
            .learner_in(StepParameter::StepTime, Plane::Frontal)
            .unwrap();
        assert_eq!(
            part.settings().gate(StepParameter::StepTime),
            Gate::RateShare
        );
    }

    #[test]
    fn each_part_of_a_summed_offset_reaches_what_the_other_leaves() {
        let mut l = both_planes();
        // Train both parts to a negative offset, then tell the learner the total may not go
        // below its sum: neither part may then move further down.
        let mut o = outcome(0.3);
        o[StepParameter::StepY].theta_e = 0.2;
        for _ in 0..3 {
            l.offsets(&inputs(0)).unwrap();
            l.touch_down(&o).unwrap();
        }
        let total = l.offsets(&inputs(0)).unwrap()[StepParameter::StepTime];
        assert!(total < 0.0);
        l.set_reach(&reach_of_time([total, 1.0])).unwrap();
        let before = l.offsets(&inputs(0)).unwrap()[StepParameter::StepTime];
        l.set_reach(&reach_of_time([total, 1.0])).unwrap();
        l.touch_down(&o).unwrap();
        let after = l.offsets(&inputs(0)).unwrap()[StepParameter::StepTime];
        assert!(after >= before - 1e-12, "{before} -> {after}");
    }

    /// The learner of `l`'s checkpoint written as JSON and read back.
    fn through_json(
        l: &StepLearner<AnyApproximator, Box<dyn LearningRule>>,
    ) -> StepLearner<AnyApproximator, Box<dyn LearningRule>> {
        let json = serde_json::to_string(&l.checkpoint()).unwrap();
        let saved: SavedStepLearner<AnyApproximator> = serde_json::from_str(&json).unwrap();
        StepLearner::from_checkpoint(saved, rule).unwrap()
    }

    #[test]
    fn a_checkpoint_continues_bit_for_bit_mid_step() {
        let mut a = of(&[StepParameter::StepX, StepParameter::StepTime]);
        let reach = PerParameter::splat([-1.0, 1.0]);
        query(&mut a, 4);
        a.touch_down(&outcome(0.2)).unwrap();
        a.offsets(&inputs(1)).unwrap();
        a.set_reach(&reach).unwrap();
        let mut b = through_json(&a);
        assert_eq!(b.learns(), a.learns());
        // The step time in both planes: each part comes back in its plane with its rule.
        let mut c = both_planes();
        query(&mut c, 2);
        let mut d = through_json(&c);
        let o = leaning_sideways(0.2);
        let (rc, rd) = (c.touch_down(&o).unwrap(), d.touch_down(&o).unwrap());
        assert_eq!(format!("{rc:?}"), format!("{rd:?}"));
        assert_eq!(
            c.offsets(&inputs(1)).unwrap(),
            d.offsets(&inputs(1)).unwrap()
        );
        assert_eq!(b.learns(), a.learns());
        let (ra, rb) = (
            a.touch_down(&outcome(-0.1)).unwrap(),
            b.touch_down(&outcome(-0.1)).unwrap(),
        );
        assert_eq!(format!("{ra:?}"), format!("{rb:?}"));
        assert_eq!(
            a.offsets(&inputs(3)).unwrap(),
            b.offsets(&inputs(3)).unwrap()
        );
    }

    #[test]
    fn a_set_names_each_parameter_once() {
        let twice = StepLearner::new(vec![
            (StepParameter::StepX, learner(StepParameter::StepX)),
            (StepParameter::StepX, learner(StepParameter::StepX)),
        ]);
        assert!(matches!(
            twice,
            Err(LearnerError::InvalidConfig { param: "learn", .. })
        ));
        assert!(StepLearner::<AnyApproximator, Box<dyn LearningRule>>::new(vec![]).is_err());
        // A parameter twice in the same plane.
        let same_plane = StepLearner::new(vec![
            (StepParameter::StepTime, learner(StepParameter::StepTime)),
            (StepParameter::StepTime, learner(StepParameter::StepTime)),
        ]);
        assert!(matches!(
            same_plane,
            Err(LearnerError::InvalidConfig { param: "learn", .. })
        ));
        // A learner whose settings learn its slot's parameter in both planes (here a step-x
        // learner, which may be given for any slot).
        use crate::control::Planes;
        let both = LearnerConfig::default().in_planes(StepParameter::StepTime, Planes::Both);
        let other = StepLearner::new(vec![(
            StepParameter::StepTime,
            learner_with(StepParameter::StepX, both),
        )]);
        assert!(matches!(
            other,
            Err(LearnerError::InvalidConfig { param: "learn", .. })
        ));
    }
}
