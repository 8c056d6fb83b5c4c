//! One learner for any set of step parameters.
//!
//! A [`StepLearner`] learns each parameter of its [`LearnSet`] with a [`FootstepLearner`] of
//! its own (the uncoupled setting): its own approximator over that parameter's inputs, and its
//! own rule, which turns that parameter's outcome into the gradient G. Every safeguard of the
//! footstep learner (prior, gain guard, anti-windup against the parameter's reach, trust
//! region, learning from falls, dead zone, leakage, `max_step_error`, the nominal fallback)
//! and its checkpoints therefore work for every parameter, and a user's rule for any parameter
//! plugs in as the learner's rule does. The built-in rules per parameter: the run's rule for
//! `step-x` and `step-y` (the lateral learner sees the mirrored frontal plane, see
//! [`super::policy`]), [`StepTime`](crate::rules::StepTime) for `step-time`.
//!
//! Each parameter's learner reads the plane its settings name
//! ([`CheckedLearnerConfig::plane`](super::learner_config::CheckedLearnerConfig::plane)):
//! `step-x` the sagittal, `step-y` the frontal, `step-time` the sagittal unless
//! `[settings.learner.step-time] plane = "frontal"`, which learns the step time from the lean
//! sideways and its outcome.

use super::learner::{FootstepLearner, LearnerError, LearnerInput, SavedLearner};
use super::policy::{FootstepPolicy, StepReports};
use super::step_parameter::{LearnSet, PerParameter, StepParameter};
use crate::approx::{FunctionApproximator, Persist};
use crate::rules::{LearningRule, StepOutcome};
use serde::{Deserialize, Serialize};

/// One [`FootstepLearner`] per learned step parameter (see the module docs).
pub struct StepLearner<A: FunctionApproximator, R: LearningRule> {
    /// In the order of [`StepParameter::ALL`], each parameter once.
    learners: Vec<(StepParameter, FootstepLearner<A, R>)>,
    set: LearnSet,
}

impl<A: FunctionApproximator, R: LearningRule> std::fmt::Debug for StepLearner<A, R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StepLearner")
            .field("learn", &self.set.to_string())
            .finish_non_exhaustive()
    }
}

/// A [`StepLearner`]'s checkpoint: each parameter's learner's.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedStepLearner<A> {
    /// Each learned parameter with its learner's checkpoint.
    pub learners: Vec<(StepParameter, SavedLearner<A>)>,
}

impl<A: FunctionApproximator, R: LearningRule> StepLearner<A, R> {
    /// The learner of `learners`, one per parameter (any order; each parameter at most once,
    /// at least one).
    pub fn new(
        mut learners: Vec<(StepParameter, FootstepLearner<A, R>)>,
    ) -> Result<Self, LearnerError> {
        let parameters: Vec<StepParameter> = learners.iter().map(|(p, _)| *p).collect();
        let set = LearnSet::of(&parameters).map_err(|e| LearnerError::InvalidConfig {
            param: "learn",
            reason: e.to_string(),
        })?;
        learners.sort_by_key(|(p, _)| p.index());
        Ok(StepLearner { learners, set })
    }

    /// The learner of `parameter`, if it is learned.
    pub fn learner(&self, parameter: StepParameter) -> Option<&FootstepLearner<A, R>> {
        self.learners
            .iter()
            .find(|(p, _)| *p == parameter)
            .map(|(_, l)| l)
    }

    /// Every learned parameter with its learner, in order.
    pub fn learners(&self) -> impl Iterator<Item = (StepParameter, &FootstepLearner<A, R>)> {
        self.learners.iter().map(|(p, l)| (*p, l))
    }

    /// Reseeds every parameter's rule with `seed`.
    pub fn reseed(&mut self, seed: u64) {
        for (_, l) in &mut self.learners {
            l.reseed(seed);
        }
    }
}

impl<A: FunctionApproximator + Persist + Clone, R: LearningRule> StepLearner<A, R> {
    /// A checkpoint of every parameter's learner (see [`FootstepLearner::checkpoint`]).
    pub fn checkpoint(&self) -> SavedStepLearner<A> {
        SavedStepLearner {
            learners: self
                .learners
                .iter()
                .map(|(p, l)| (*p, l.checkpoint()))
                .collect(),
        }
    }

    /// The learner of a checkpoint, each parameter's rule from `rule`: it continues bit for bit
    /// as the learner that wrote it. Errors as [`FootstepLearner::from_checkpoint`], or if the
    /// checkpoint names a parameter twice or none.
    pub fn from_checkpoint(
        saved: SavedStepLearner<A>,
        mut rule: impl FnMut(StepParameter) -> R,
    ) -> Result<Self, LearnerError> {
        let learners = saved
            .learners
            .into_iter()
            .map(|(p, s)| Ok((p, FootstepLearner::from_checkpoint(s, rule(p))?)))
            .collect::<Result<Vec<_>, LearnerError>>()?;
        Self::new(learners)
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
        for (p, l) in &mut self.learners {
            let input = *inputs.in_plane(*p, l.settings().plane(*p));
            out[*p] = l.query(input)?;
        }
        Ok(out)
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        for (p, l) in &mut self.learners {
            let [lo, hi] = reach[*p];
            l.set_reach(lo, hi)?;
        }
        Ok(())
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        let mut out = StepReports::default();
        for (p, l) in &mut self.learners {
            let outcome = *outcomes.in_plane(*p, l.settings().plane(*p));
            out[*p] = Some(l.touch_down(&outcome)?);
        }
        Ok(out)
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        let mut out = StepReports::default();
        for (p, l) in &mut self.learners {
            let outcome = *outcomes.in_plane(*p, l.settings().plane(*p));
            out[*p] = l.fall(&outcome)?;
        }
        Ok(out)
    }
    fn discard_step(&mut self) {
        for (_, l) in &mut self.learners {
            l.discard_step();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::approx::{AnyApproximator, ApproxKind};
    use crate::control::learner::{InputGrid, LearnerConfig};
    use crate::rules::{PendulumCart, StepTime};

    fn learner(p: StepParameter) -> FootstepLearner<AnyApproximator, Box<dyn LearningRule>> {
        let bounds = InputGrid::default().input_box().unwrap();
        let rule: Box<dyn LearningRule> = match p {
            StepParameter::StepTime => Box::new(StepTime::default()),
            _ => Box::new(PendulumCart::default()),
        };
        let approx = ApproxKind::Grid.build(&bounds).unwrap();
        FootstepLearner::new(approx, rule, LearnerConfig::default()).unwrap()
    }

    fn rule(p: StepParameter) -> Box<dyn LearningRule> {
        match p {
            StepParameter::StepTime => Box::new(StepTime::default()),
            _ => Box::new(PendulumCart::default()),
        }
    }

    fn inputs(k: usize) -> PerParameter<LearnerInput> {
        let x = LearnerInput::new(0.01 * k as f64, 0.1, 0.0);
        PerParameter([x, LearnerInput::new(-0.02, 0.0, 0.0), x])
    }

    fn outcome(theta_e: f64) -> PerParameter<StepOutcome> {
        let o = StepOutcome {
            theta_e,
            theta_e_dot: 0.0,
            f_e: 0.2,
            f_r: 0.0,
        };
        PerParameter([o, o, o])
    }

    #[test]
    fn each_parameter_learns_with_its_own_rule_and_the_rest_stay_zero() {
        let mut l = StepLearner::new(vec![
            (StepParameter::StepTime, learner(StepParameter::StepTime)),
            (StepParameter::StepX, learner(StepParameter::StepX)),
        ])
        .unwrap();
        assert_eq!(l.learns().to_string(), "step-x,step-time");
        let reach = PerParameter([[-1.0, 1.0]; 3]);
        for k in 0..5 {
            let o = l.offsets(&inputs(k)).unwrap();
            assert_eq!(o[StepParameter::StepY], 0.0);
            l.set_reach(&reach).unwrap();
        }
        let r = l.touch_down(&outcome(0.3)).unwrap();
        // Leaning forward after a long step: a longer step (G > 0) and a sooner one (G_T < 0).
        assert!(r[StepParameter::StepX].unwrap().gradient > 0.0);
        assert!(r[StepParameter::StepTime].unwrap().gradient < 0.0);
        assert!(r[StepParameter::StepY].is_none());
        let o = l.offsets(&inputs(2)).unwrap();
        assert!(
            o[StepParameter::StepX] > 0.0 && o[StepParameter::StepTime] < 0.0,
            "{o:?}"
        );
    }

    #[test]
    fn a_frontal_step_time_reads_and_learns_the_frontal_plane() {
        use crate::control::learner_config::ParameterSettings;
        use crate::control::step_parameter::Plane;
        let frontal = LearnerConfig {
            step_time: ParameterSettings {
                plane: Some(Plane::Frontal),
                ..ParameterSettings::default()
            },
            ..LearnerConfig::default()
        };
        let bounds = InputGrid::default().input_box().unwrap();
        let time = FootstepLearner::for_parameters(
            ApproxKind::Grid.build(&bounds).unwrap(),
            [rule(StepParameter::StepTime)],
            [StepParameter::StepTime],
            frontal,
        )
        .unwrap();
        let mut l = StepLearner::new(vec![
            (StepParameter::StepX, learner(StepParameter::StepX)),
            (StepParameter::StepTime, time),
        ])
        .unwrap();
        let reach = PerParameter([[-1.0, 1.0]; 3]);
        for k in 0..3 {
            l.offsets(&inputs(k)).unwrap();
            l.set_reach(&reach).unwrap();
        }
        let lateral = inputs(0)[StepParameter::StepY];
        let time = l.learner(StepParameter::StepTime).unwrap();
        assert!(time.recorded_inputs().all(|x| x == lateral));
        let sagittal = l.learner(StepParameter::StepX).unwrap();
        assert!(sagittal.recorded_inputs().any(|x| x != lateral));
        // Taught by the frontal outcome: a lean towards the swing leg, where the sagittal one
        // leans back.
        let mut o = outcome(-0.1);
        o[StepParameter::StepY] = StepOutcome {
            theta_e: 0.1,
            theta_e_dot: 0.0,
            f_e: 0.0,
            f_r: 0.0,
        };
        let r = l.touch_down(&o).unwrap();
        let want = StepTime::default().gradient(&o[StepParameter::StepY]);
        assert_eq!(r[StepParameter::StepTime].unwrap().gradient, want);
        assert!(r[StepParameter::StepX].unwrap().gradient < 0.0);
    }

    #[test]
    fn a_checkpoint_continues_bit_for_bit_mid_step() {
        let mut a = StepLearner::new(vec![
            (StepParameter::StepX, learner(StepParameter::StepX)),
            (StepParameter::StepTime, learner(StepParameter::StepTime)),
        ])
        .unwrap();
        let reach = PerParameter([[-1.0, 1.0]; 3]);
        for k in 0..4 {
            a.offsets(&inputs(k)).unwrap();
            a.set_reach(&reach).unwrap();
        }
        a.touch_down(&outcome(0.2)).unwrap();
        a.offsets(&inputs(1)).unwrap();
        a.set_reach(&reach).unwrap();
        let json = serde_json::to_string(&a.checkpoint()).unwrap();
        let mut b = StepLearner::from_checkpoint(
            serde_json::from_str::<SavedStepLearner<AnyApproximator>>(&json).unwrap(),
            rule,
        )
        .unwrap();
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
    }
}
