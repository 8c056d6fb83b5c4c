//! The names most programs need, in one import: `use steplearn::prelude::*;`.
//!
//! The learning layer (approximators, rules, the learner), the walker and the robot interface
//! (a robot's description, the sensors it gives, the joint targets it takes) always; with the
//! feature `experiments`, the harness, the experiment trait and the bench.

pub use crate::approx::{
    AnyApproximator, ApproxError, ApproxKind, BoxedApproximator, FunctionApproximator, InputBox,
    Lwpr, LwprConfig, Persist,
};
pub use crate::control::{
    FootstepLearner, FootstepPolicy, InputGrid, LearnSet, LearnerConfig, LearnerError,
    LearnerInput, PerParameter, StepLearner, StepParameter, Walker, WalkerConfig, WalkerMode,
};
pub use crate::robot::{Description, JointTargets, Sensors};
pub use crate::rules::{LearningRule, PendulumCart, StepOutcome, StepTime};

#[cfg(feature = "experiments")]
pub use crate::bench::{Bench, BenchError, Registry};
#[cfg(feature = "experiments")]
pub use crate::experiments::config_file::ConfigFile;
#[cfg(feature = "experiments")]
pub use crate::experiments::settings::Settings;
#[cfg(feature = "experiments")]
pub use crate::experiments::summary::{CustomResult, ExperimentResult, Summary, TypedResult};
#[cfg(feature = "experiments")]
pub use crate::experiments::{Experiment, ExperimentError, RunContext};

#[cfg(test)]
mod tests {
    use super::*;

    /// A program learning the footstep and the step time needs no name beyond the prelude.
    #[test]
    fn a_step_learner_is_built_and_taught_from_the_prelude_alone() {
        let config = LearnerConfig::default();
        let bounds = InputGrid::default().input_box().unwrap();
        let part = |p: StepParameter, rule: Box<dyn LearningRule>| {
            let approx = ApproxKind::Grid.build(&bounds).unwrap();
            (
                p,
                FootstepLearner::for_parameters(approx, [rule], [p], config).unwrap(),
            )
        };
        let mut learner = StepLearner::new(vec![
            part(StepParameter::StepX, Box::<PendulumCart>::default()),
            part(StepParameter::StepTime, Box::<StepTime>::default()),
        ])
        .unwrap();
        let set: LearnSet = "step-x,step-time".parse().unwrap();
        assert_eq!(learner.learns(), set);
        let x = LearnerInput::new(0.05, 0.3, 0.1);
        let inputs = PerParameter::from_planes(x, LearnerInput::default());
        learner.offsets(&inputs).unwrap();
        let falling = StepOutcome {
            theta_e: 0.1,
            theta_e_dot: 0.5,
            f_e: 0.0,
            f_r: 0.1,
        };
        let reports = learner.touch_down(&PerParameter::splat(falling)).unwrap();
        for p in [StepParameter::StepX, StepParameter::StepTime] {
            assert!(reports[p].is_some_and(|r| r.samples > 0), "{p} learned");
        }
        assert!(reports[StepParameter::StepY].is_none());
    }

    /// A walker for a robot in URDF takes its sensors and gives its joint targets with the
    /// prelude's names (and the servo reference the loader scales from).
    #[test]
    fn a_walker_for_a_urdf_robot_ticks_from_the_prelude() {
        let text = include_str!("../tests/robots/minimal.urdf");
        let reference = crate::robot::ServoReference::default();
        let robot =
            Description::from_urdf_str(text, std::path::Path::new("."), &reference).unwrap();
        let config = WalkerConfig::new(WalkerMode::CaptureStep);
        let mut walker = Walker::new(config, robot.leg_geometry()).unwrap();
        let tick = walker.tick(&Sensors::default(), 0.1, None).unwrap();
        let targets: JointTargets = tick.targets;
        assert!(targets.pos.iter().all(|q| q.is_finite()));
    }
}
