//! A user's own experiment: stepping in place, pushed forward with one impulse; how many pushes
//! end in a fall, with and without the learned offset. Its protocol is its own table of the
//! config file, `[protocols.forward-pushes]`.

use serde::{Deserialize, Serialize};
use std::path::Path;
use steplearn::config::{ConfigError, at_least, positive};
use steplearn::control::WalkerMode;
use steplearn::experiments::ExperimentError;
use steplearn::experiments::compare::run_model_and_learned;
use steplearn::experiments::paired::{Direction, Paired};
use steplearn::experiments::protocol::{Protocol, ProtocolTables, Table};
use steplearn::experiments::schedule::PushPlan;
use steplearn::experiments::summary::{CustomResult, ExperimentResult, Summary};
use steplearn::experiments::{Experiment, Headline, RunContext};

/// The experiment, registered as `forward-pushes`.
#[derive(Debug, Clone, Copy, Default)]
pub struct ForwardPushes;

/// Its protocol: `pushes` forward pushes of `impulse_ns` (scaled by the bench's `scale`, at
/// least 2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ForwardPushesProtocol {
    /// Pushes per walker at scale 1.
    pub pushes: usize,
    /// The impulse (Ns).
    pub impulse_ns: f64,
}

impl Default for ForwardPushesProtocol {
    fn default() -> Self {
        ForwardPushesProtocol {
            pushes: 60,
            impulse_ns: 11.0,
        }
    }
}

impl Protocol for ForwardPushesProtocol {
    fn validate(&self) -> Result<(), ConfigError> {
        at_least("pushes", self.pushes, 1)?;
        positive("impulse_ns", self.impulse_ns)
    }
}

/// What one run reports (`summary.json` beside the common fields).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct PushFalls {
    /// Pushes delivered to each walker.
    pub pushes: [usize; 2],
    /// Pushes that ended in a fall: model, learned.
    pub falls: [usize; 2],
}

impl PushFalls {
    fn rates(&self) -> [f64; 2] {
        [0, 1].map(|i| self.falls[i] as f64 / self.pushes[i].max(1) as f64)
    }
}

fn parse(runs: &[&Summary]) -> Vec<PushFalls> {
    let custom = |s: &&Summary| match &s.result {
        ExperimentResult::Custom(c) => c.parse::<PushFalls>().ok(),
        _ => None,
    };
    runs.iter().filter_map(custom).collect()
}

impl Experiment for ForwardPushes {
    fn name(&self) -> &str {
        "forward-pushes"
    }

    fn description(&self) -> &str {
        "stepping in place, forward pushes of one impulse: pushes ending in a fall"
    }

    fn protocol(&self, tables: &ProtocolTables) -> Result<Option<Table>, ConfigError> {
        tables.resolve::<ForwardPushesProtocol>(self.name())
    }

    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError> {
        let p: ForwardPushesProtocol = ctx.protocols.get(self.name())?;
        let plan = PushPlan {
            count: ctx.settings.scaled(p.pushes, 2),
            impulse: (p.impulse_ns, p.impulse_ns),
            settle: 3.0,
            gap: (3.0, 4.0),
        };
        let setup = ctx.settings.push_trial(
            WalkerMode::CaptureStep,
            0.0,
            &plan,
            ctx.seed,
            [1.0, 0.0, 0.0],
        );
        let runs = run_model_and_learned(&setup, &|| ctx.make_learner())?;
        runs.write_pushes(&dir.join("forward_pushes.csv"))?;
        let count = |f: bool| {
            [&runs.model, &runs.learned].map(|l| l.pushes.iter().filter(|p| p.fell || !f).count())
        };
        let result = PushFalls {
            pushes: count(false),
            falls: count(true),
        };
        Ok(ExperimentResult::Custom(CustomResult::new(
            self.name(),
            &result,
        )?))
    }

    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired> {
        let diff: Vec<f64> = parse(runs)
            .iter()
            .map(|f| f.rates()[1] - f.rates()[0])
            .collect();
        vec![Paired::new(
            "falls per push, learned - model",
            &diff,
            0.0,
            Direction::LowerIsBetter,
        )]
    }

    fn headline(&self, runs: &[&Summary]) -> Vec<Headline> {
        let runs = parse(runs);
        vec![
            Headline::mean_of("falls per push, model", runs.iter().map(|f| f.rates()[0])),
            Headline::mean_of("falls per push, learned", runs.iter().map(|f| f.rates()[1])),
        ]
    }
}
