//! The comparison every experiment but D makes: the same trial for the Capture Step *model*
//! alone and for the *learned* walker (model plus a fresh learner), run in parallel.

use crate::experiments::error::ExperimentError;
use crate::experiments::fall_causes::{ClassifiedFall, count, push_rows, run_classified};
use crate::experiments::settings::LearnerFactory;
use crate::experiments::summary::ModelLearned;
use crate::experiments::trial::{ControllerCell, StepCells, TrialLog, TrialSetup};
use crate::report::ReportError;
use crate::report::write_rows;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The two runs of one comparison.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelAndLearned {
    /// The Capture Step controller alone.
    pub model: TrialLog,
    /// The Capture Step controller with the learner, learning from the start.
    pub learned: TrialLog,
    /// Every fall of either run with its cause, in time order (empty in results saved before
    /// the causes were recorded).
    #[serde(default)]
    pub classified_falls: ModelLearned<Vec<ClassifiedFall>>,
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
    /// fall followed and its cause
    /// ([`crate::experiments::fall_causes::FallCause::name`], empty where absorbed).
    pub fn write_pushes(&self, path: &Path) -> Result<(), ReportError> {
        let falls = &self.classified_falls;
        let mut rows = push_rows("model", &self.model.pushes, &falls.model);
        rows.extend(push_rows("learned", &self.learned.pushes, &falls.learned));
        write_rows(path, &rows)
    }

    /// Falls per cause of each run, every cause present (zero where none).
    pub fn fall_causes(&self) -> ModelLearned<BTreeMap<String, u32>> {
        ModelLearned {
            model: count(&self.classified_falls.model),
            learned: count(&self.classified_falls.learned),
        }
    }
}

/// Runs `setup` without a learner and with a fresh learner from `learner`, in parallel (the
/// results do not depend on the number of threads: each run is sequential and seeded).
pub fn run_model_and_learned(
    setup: &TrialSetup,
    learner: &(impl LearnerFactory + Sync),
) -> Result<ModelAndLearned, ExperimentError> {
    let (model, learned) = rayon::join(
        || run_classified(setup, None),
        || -> Result<_, ExperimentError> {
            let mut l = learner.make()?;
            Ok(run_classified(setup, Some(&mut l))?)
        },
    );
    let ((model, model_falls), (learned, learned_falls)) = (model?, learned?);
    Ok(ModelAndLearned {
        model,
        learned,
        classified_falls: ModelLearned {
            model: model_falls,
            learned: learned_falls,
        },
    })
}
