//! What `steplearn replay` needs from an experiment: how to re-simulate one of its runs (a
//! [`ReplayPlan`] of the trials the experiment itself builds) and which moment of a finished
//! run tells the most ([`Moment`]), with the helpers that pick one from a run's pushes table.
//!
//! An experiment with a replay implements [`crate::experiments::Replayable`]; the
//! replay module runs the plan with the trial code every experiment uses.

use crate::control::LearnerConfig;
use crate::experiments::trial::TrialSetup;
use crate::report::ReportError;
use crate::report::csv_read::read_rows;
use serde::Deserialize;
use std::path::Path;

/// What to replay of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Moment {
    /// Push K (1-based) of a run with pushes.
    Push(usize),
    /// The span `[from, to]` of trial time (s) of a run made of one trial per walker.
    Span(f64, f64),
}

/// One walker of a replay: its name in the scene, the trial the experiment walks it through,
/// and whether it walks with the run's learner.
#[derive(Debug, Clone)]
pub struct ReplayWalker {
    /// Its name in the scene (`learned`, `model`, `open-loop`).
    pub name: String,
    /// Its whole trial, as the experiment builds it for the run's seed.
    pub setup: TrialSetup,
    /// Whether it walks with the run's learner.
    pub learns: bool,
}

impl ReplayWalker {
    /// Walker `name` on `setup`, learning if `learns`.
    pub fn new(name: &str, setup: TrialSetup, learns: bool) -> Self {
        ReplayWalker {
            name: name.to_string(),
            setup,
            learns,
        }
    }
}

/// How a run of an experiment is re-simulated.
#[derive(Debug, Clone)]
pub enum ReplayPlan {
    /// One long trial per walker, each walked from its start to the end of the moment (the
    /// learned walker learns throughout). Pushes are the first walker's trial's pushes.
    Trials {
        /// The walkers, the learned one first.
        walkers: Vec<ReplayWalker>,
        /// The pushes' direction (world unit vector).
        direction: [f64; 3],
        /// Seconds recorded after a replayed push.
        after_push_s: f64,
        /// Whether the run has pushes to replay (`--push`); a span (`--time`) always works.
        pushes: bool,
    },
    /// One short episode per push: the learned walker learns from the episodes before push K
    /// (one learner of the run's approximator and rule with `learner`), then walks push K's
    /// episode beside the same walker without learning. Spans do not apply.
    Episodes {
        /// The episodes in push order.
        episodes: Vec<TrialSetup>,
        /// The learner's settings.
        learner: Box<LearnerConfig>,
        /// The pushes' impulse (Ns).
        impulse: f64,
        /// Their direction (world unit vector).
        direction: [f64; 3],
    },
}

/// One push of a walker: its impulse (Ns) and whether the walker fell after it.
pub type PushOutcome = (f64, bool);

/// A row of a pushes table with a walker (`controller`) column, such as C's `pushes.csv`.
#[derive(Deserialize)]
struct PushRow {
    controller: String,
    impulse_ns: f64,
    fell: bool,
}

/// The pushes of walker `controller` in the pushes table at `path` (columns `controller`,
/// `impulse_ns`, `fell`), in order.
pub fn pushes_of(path: &Path, controller: &str) -> Result<Vec<PushOutcome>, ReportError> {
    Ok(read_rows::<PushRow>(path)?
        .into_iter()
        .filter(|r| r.controller == controller)
        .map(|r| (r.impulse_ns, r.fell))
        .collect())
}

/// How a walker came out of a push, in a moment's description.
pub fn outcome(fell: bool) -> &'static str {
    if fell { "fell" } else { "absorbed it" }
}

/// The push (1-based) where `a` and `b` differ, of smallest impulse (ties: the first); else
/// the first where either fell, of smallest impulse; else push 1.
pub fn differing_push(a: &[PushOutcome], b: &[PushOutcome]) -> usize {
    let pick = |pred: &dyn Fn(bool, bool) -> bool| {
        a.iter()
            .zip(b)
            .enumerate()
            .filter(|(_, (x, y))| pred(x.1, y.1))
            .min_by(|(i, (x, _)), (j, (y, _))| x.0.total_cmp(&y.0).then(i.cmp(j)))
            .map(|(i, _)| i + 1)
    };
    pick(&|x, y| x != y)
        .or_else(|| pick(&|x, y| x || y))
        .unwrap_or(1)
}

/// The [`differing_push`] of walkers `a` (named `an`) and `b` (`bn`) as a moment, with its
/// description: the push, its impulse and how each walker came out of it.
pub fn differing_push_moment(
    a: &[PushOutcome],
    b: &[PushOutcome],
    an: &str,
    bn: &str,
) -> (Moment, String) {
    let k = differing_push(a, b);
    let fell = |x: &[PushOutcome]| x.get(k - 1).is_some_and(|p| p.1);
    let impulse = a.get(k - 1).map_or(0.0, |p| p.0);
    (
        Moment::Push(k),
        format!(
            "push {k} ({impulse:.1} Ns): {an} {}, {bn} {}",
            outcome(fell(a)),
            outcome(fell(b))
        ),
    )
}

/// The [`differing_push_moment`] of the `learned` and `model` walkers in the pushes table at
/// `path` (columns `controller`, `impulse_ns`, `fell`).
pub fn learned_versus_model_moment(path: &Path) -> Result<(Moment, String), ReportError> {
    let (l, m) = (pushes_of(path, "learned")?, pushes_of(path, "model")?);
    Ok(differing_push_moment(&l, &m, "learned", "model"))
}

/// Decimals a replay keeps of every recorded number.
pub const DECIMALS: i32 = 4;

/// `x` rounded to [`DECIMALS`] decimals (without a negative zero), as a replay records it.
pub fn round(x: f64) -> f64 {
    let k = 10f64.powi(DECIMALS);
    let r = (x * k).round() / k;
    if r == 0.0 { 0.0 } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_differing_push_of_smallest_impulse_else_the_first_fall_else_push_one() {
        let a = [(5.0, true), (2.0, false), (1.0, true)];
        let b = [(5.0, false), (2.0, false), (1.0, false)];
        assert_eq!(differing_push(&a, &b), 3);
        let same = [(5.0, true), (2.0, true)];
        assert_eq!(differing_push(&same, &same), 2);
        let none = [(5.0, false)];
        assert_eq!(differing_push(&none, &none), 1);
        let (m, why) = differing_push_moment(&a, &b, "learned", "model");
        assert_eq!(m, Moment::Push(3));
        assert_eq!(why, "push 3 (1.0 Ns): learned fell, model absorbed it");
    }
}
