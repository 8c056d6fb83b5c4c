//! The names most programs need, in one import: `use steplearn::prelude::*;`.
//!
//! The learning layer (approximators, rules, the learner) always; with the feature
//! `experiments`, the harness, the experiment trait and the bench.

pub use crate::approx::{
    AnyApproximator, ApproxError, BoxedApproximator, FunctionApproximator, InputBox, Lwpr,
    LwprConfig, Persist,
};
pub use crate::control::{
    FootstepLearner, FootstepPolicy, LearnSet, LearnerConfig, LearnerError, LearnerInput,
    StepParameter,
};
pub use crate::rules::{LearningRule, PendulumCart, StepOutcome};

#[cfg(feature = "experiments")]
pub use crate::bench::{Bench, BenchError, Registry};
#[cfg(feature = "experiments")]
pub use crate::experiments::{
    ConfigFile, CustomResult, Experiment, ExperimentError, ExperimentResult, RunContext, Settings,
    Summary, TypedResult,
};
