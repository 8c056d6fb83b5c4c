//! The comparison every experiment but D makes: the same trial for the Capture Step *model*
//! alone and for the *learned* walker (model plus a fresh learner), run in parallel.

use super::error::ExperimentError;
use super::settings::LearnerFactory;
use super::trial::{ControllerCell, StepCells, TrialLog, TrialSetup, run_trial};
use crate::approx::FunctionApproximator;
use crate::report::ReportError;
use crate::report::{Fixed, write_rows};
use crate::rules::LearningRule;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The two runs of one comparison.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelAndLearned {
    /// The Capture Step controller alone.
    pub model: TrialLog,
    /// The Capture Step controller with the learner, learning from the start.
    pub learned: TrialLog,
}

impl ModelAndLearned {
    /// Writes every step of both runs as CSV (a `controller` column, `model` or `learned`,
    /// then [`StepCells`]).
    pub fn write_steps(&self, path: &Path) -> Result<(), ReportError> {
        let rows: Vec<(ControllerCell, StepCells)> =
            [("model", &self.model), ("learned", &self.learned)]
                .into_iter()
                .flat_map(|(controller, log)| {
                    log.steps
                        .iter()
                        .map(move |s| (ControllerCell { controller }, s.cells()))
                })
                .collect();
        write_rows(path, &rows)
    }

    /// Writes every push of both runs as CSV: controller, time (s), impulse (Ns), whether a
    /// fall followed.
    pub fn write_pushes(&self, path: &Path) -> Result<(), ReportError> {
        let rows: Vec<PushCells> = [("model", &self.model), ("learned", &self.learned)]
            .into_iter()
            .flat_map(|(controller, log)| {
                log.pushes.iter().map(move |p| PushCells {
                    controller,
                    time_s: Fixed(p.time),
                    impulse_ns: Fixed(p.impulse),
                    fell: p.fell,
                })
            })
            .collect();
        write_rows(path, &rows)
    }
}

/// A row of [`ModelAndLearned::write_pushes`].
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
struct PushCells<'a> {
    controller: &'a str,
    time_s: Fixed<4>,
    impulse_ns: Fixed<4>,
    fell: bool,
}

/// Runs `setup` without a learner and with a fresh learner from `learner`, in parallel (the
/// results do not depend on the number of threads: each run is sequential and seeded).
pub fn run_model_and_learned<A, R>(
    setup: &TrialSetup,
    learner: &(impl LearnerFactory<A, R> + Sync),
) -> Result<ModelAndLearned, ExperimentError>
where
    A: FunctionApproximator + Clone,
    R: LearningRule,
{
    let (model, learned) = rayon::join(
        || run_trial(setup, None, &mut []),
        || -> Result<TrialLog, ExperimentError> {
            let mut l = learner.make()?;
            Ok(run_trial(setup, Some(&mut l), &mut [])?)
        },
    );
    Ok(ModelAndLearned {
        model: model?,
        learned: learned?,
    })
}
