//! Experiment D (paper Figs. 7-8): robustness, learning without initialisation. The analytic
//! footstep is switched off, so the learned offset dF is the whole sagittal step
//! ([`WalkerMode::LearnerOnly`]); the robot steps in place and is pushed forward (the paper:
//! 8 Ns; here by default the impulse calibrated in [`RobustnessProtocol::impulse`]), one push
//! per episode, starting with an untrained learner that keeps everything it learns
//! from one episode to the next (a fall ends the episode, the robot is reset). Counted: the
//! pushes until the first one absorbed, the falls, and, after every push, the learning metric
//! (norm of dF over an even grid of the input space) and a map of dF.
//!
//! The same episodes (push times, impulse, direction) are walked again without learning: the
//! same [`WalkerMode::LearnerOnly`] walker with no policy, so dF = 0 and it steps in place
//! whatever happens. What learning adds is the difference in pushes absorbed.

use crate::approx::FunctionApproximator;
use crate::config::limits::{MAX_GAP_S, MAX_GRID_POINTS, MAX_IMPULSE_NS, MAX_PUSHES};
use crate::config::{self, ConfigError};
use crate::control::WalkerMode;
use crate::control::{
    FootstepLearner, InputGrid, LearnerConfig, LearnerError, MapSpec, OffsetMap, Prior,
};
use crate::experiments::claim::{Claim, by_seed};
use crate::experiments::error::ExperimentError;
use crate::experiments::paired::{Direction, Paired};
use crate::experiments::protocol::{Protocol, ProtocolTables, Table};
use crate::experiments::replay_plan::{Moment, PushOutcome, ReplayPlan, differing_push, outcome};
use crate::experiments::schedule::{Push, ReferenceSchedule};
use crate::experiments::settings::Settings;
use crate::experiments::summary::{ExperimentResult, Summary, TypedResult, finite_non_negative};
use crate::experiments::trial::{StepCells, StepRecord, TrialSetup, run_trial};
use crate::experiments::{
    Experiment, Headline, PushOptions, PushOptionsError, Replayable, RunContext,
};
use crate::report::ReportError;
use crate::report::band::{Labels, band, band_plot};
use crate::report::csv_read::read_rows;
use crate::report::figures::{HeatMapGrid, HeatPanel, LinePlot, Series, heat_map_grid, line_plot};
use crate::report::{Fixed, write_rows};
use crate::rules::LearningRule;
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The experiment's registered name.
pub const NAME: &str = "robustness";

/// The protocol (paper: stepping in place, 8 Ns forward pushes, no analytic footstep; here
/// the impulse is calibrated so that the walker without learning falls).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RobustnessProtocol {
    /// Push impulse (Ns). Default 6 Ns: the smallest of 4, 5, 6, 8 and 10 Ns at which the
    /// walker *without* learning (dF = 0) falls from at least 80% of the pushes pooled over
    /// seeds 0-4 and 70% of each seed's, so that an absorbed push is the learner's doing (the
    /// calibration is in docs/reproducing.md, experiment D).
    pub impulse: f64,
    /// Episodes (one push each) before [`Settings::scale`].
    pub pushes: usize,
    /// Stepping time before the push in each episode (s), random so that pushes hit random
    /// gait phases.
    pub settle_s: (f64, f64),
    /// Unit push direction (forward by default).
    pub direction: [f64; 3],
    /// The input grid of the learning metric (a figure's resolution, not a config key).
    #[serde(skip)]
    pub metric_grid: InputGrid,
    /// The dF maps drawn after every push, 31 x 31 (a figure's resolution, not a config key).
    #[serde(skip)]
    pub map: MapSpec,
    /// Whether the learner holds its dF = 0 prior ([`crate::control::Prior`]) from
    /// the start. Default false: D's learner is not initialised, so it neither has the analytic
    /// footstep nor believes dF = 0 is right; [`run`] builds it with
    /// `Prior::none()` unless this is set.
    pub learner_prior: bool,
}

impl Default for RobustnessProtocol {
    fn default() -> Self {
        RobustnessProtocol {
            impulse: 6.0,
            pushes: 15,
            settle_s: (3.0, 4.0),
            direction: [1.0, 0.0, 0.0],
            metric_grid: InputGrid::default(),
            map: MapSpec {
                resolution: (31, 31),
                ..MapSpec::default()
            },
            learner_prior: false,
        }
    }
}

impl Protocol for RobustnessProtocol {
    /// Checks the numbers, the grid and the map; errors name the field (relative to the
    /// protocol's section).
    fn validate(&self) -> Result<(), ConfigError> {
        config::in_range("impulse", self.impulse, 0.0, MAX_IMPULSE_NS)?;
        config::count_in("pushes", self.pushes, 1, MAX_PUSHES)?;
        config::positive_range("settle_s", self.settle_s)?;
        config::range_in("settle_s", self.settle_s, 0.0, MAX_GAP_S)?;
        for (axis, n) in ["theta_e", "theta_e_dot", "f_r"]
            .iter()
            .zip(self.metric_grid.points)
        {
            config::count_in(&format!("metric_grid.points.{axis}"), n, 1, MAX_GRID_POINTS)?;
        }
        config::unit_direction("direction", &self.direction)?;
        self.metric_grid
            .validate()
            .map_err(|e| ConfigError::new("metric_grid", e.to_string()))?;
        config::ordered("map.theta_e", self.map.theta_e)?;
        config::ordered("map.theta_e_dot", self.map.theta_e_dot)?;
        config::ensure(self.map.f_r.is_finite(), "map.f_r", || {
            format!("must be finite, got {}", self.map.f_r)
        })?;
        config::count_in("map.resolution", self.map.resolution.0, 1, MAX_GRID_POINTS)?;
        config::count_in("map.resolution", self.map.resolution.1, 1, MAX_GRID_POINTS)
    }
}

/// One episode: a push and what the learner knew after it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Episode {
    /// 1-based push number.
    pub push: usize,
    /// When the push came, in the episode's time (s).
    pub push_time: f64,
    /// Whether the robot fell within the push window.
    pub fell: bool,
    /// Falls in the episode (a fall before the push counts too).
    pub falls: usize,
    /// The episode's steps.
    pub steps: Vec<StepRecord>,
    /// The learning metric after the episode.
    pub learning_metric: f64,
    /// dF over (theta_E, theta_E_dot) at the map's F_R after the episode.
    pub map: OffsetMap,
}

/// One episode of the walker without learning.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BaselineEpisode {
    /// 1-based push number (the learned walker's episode with the same push).
    pub push: usize,
    /// Whether the robot fell within the push window (or the push was never delivered).
    pub fell: bool,
    /// Falls in the episode.
    pub falls: usize,
}

/// Experiment D's result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobustnessResult {
    /// The push impulse (Ns).
    #[serde(default)]
    pub impulse: f64,
    /// The learning metric before the first push (0 for an untrained learner).
    pub initial_metric: f64,
    /// The episodes in order.
    pub episodes: Vec<Episode>,
    /// The same episodes without learning (dF = 0), in order.
    #[serde(default)]
    pub no_learning: Vec<BaselineEpisode>,
}

impl RobustnessResult {
    /// 1-based number of the first push absorbed without a fall, if any.
    pub fn pushes_until_first_absorbed(&self) -> Option<usize> {
        self.episodes.iter().find(|e| !e.fell).map(|e| e.push)
    }

    /// Falls over all episodes.
    pub fn falls(&self) -> usize {
        self.episodes.iter().map(|e| e.falls).sum()
    }

    /// Whether the learned walker absorbed each push, in order.
    pub fn absorbed_by_push(&self) -> Vec<bool> {
        self.episodes.iter().map(|e| !e.fell).collect()
    }

    /// Whether the walker without learning absorbed each push, in order.
    pub fn no_learning_absorbed_by_push(&self) -> Vec<bool> {
        self.no_learning.iter().map(|e| !e.fell).collect()
    }

    /// Falls of the walker without learning over all episodes.
    pub fn no_learning_falls(&self) -> usize {
        self.no_learning.iter().map(|e| e.falls).sum()
    }

    /// The experiment's part of `summary.json`.
    pub fn summary(&self) -> RobustnessSummary {
        RobustnessSummary {
            pushes_until_first_absorbed: self.pushes_until_first_absorbed().map(|n| n as u32),
            falls: self.falls() as u32,
            impulse_ns: Some(self.impulse),
            absorbed_by_push: self.absorbed_by_push(),
            no_learning: Some(NoLearning {
                absorbed_by_push: self.no_learning_absorbed_by_push(),
                falls: self.no_learning_falls() as u32,
            }),
        }
    }
}

/// The same episodes walked without learning (dF = 0 throughout).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoLearning {
    /// Whether each push (in order) was absorbed.
    pub absorbed_by_push: Vec<bool>,
    /// Falls over the whole run.
    pub falls: u32,
}

/// Experiment D's part of `summary.json`: learning from scratch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobustnessSummary {
    /// 1-based index of the first push absorbed without a fall; `null` if none was.
    pub pushes_until_first_absorbed: Option<u32>,
    /// Falls over the whole run.
    pub falls: u32,
    /// The push impulse (Ns); absent in older summaries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impulse_ns: Option<f64>,
    /// The learned walker: whether each push (in order) was absorbed (empty in older
    /// summaries).
    #[serde(default)]
    pub absorbed_by_push: Vec<bool>,
    /// The same episodes without learning; absent in older summaries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub no_learning: Option<NoLearning>,
}

/// D: the first absorbed push agrees with the per-push record; a missed push means a fall.
impl TypedResult for RobustnessSummary {
    const EXPERIMENT: &'static str = NAME;

    fn validate(&self) -> Result<(), ReportError> {
        let RobustnessSummary {
            pushes_until_first_absorbed,
            falls,
            impulse_ns,
            absorbed_by_push,
            no_learning,
        } = self;
        if *pushes_until_first_absorbed == Some(0) {
            return Err(ReportError::invalid(
                "pushes_until_first_absorbed is 1-based, got 0",
            ));
        }
        if let Some(i) = impulse_ns {
            finite_non_negative("impulse_ns", *i)?;
        }
        let first = absorbed_by_push
            .iter()
            .position(|&a| a)
            .map(|i| i as u32 + 1);
        if !absorbed_by_push.is_empty() && first != *pushes_until_first_absorbed {
            return Err(ReportError::invalid(format!(
                "absorbed_by_push first absorbs push {first:?}, \
                 pushes_until_first_absorbed says {pushes_until_first_absorbed:?}"
            )));
        }
        // A push not absorbed means at least one fall in its episode.
        let check_falls = |what: &str, absorbed: &[bool], falls: u32| {
            let missed = absorbed.iter().filter(|&&a| !a).count();
            if (falls as usize) < missed {
                Err(ReportError::invalid(format!(
                    "{what}: {missed} pushes not absorbed but only {falls} falls"
                )))
            } else {
                Ok(())
            }
        };
        check_falls("learned", absorbed_by_push, *falls)?;
        if let Some(n) = no_learning {
            if n.absorbed_by_push.len() != absorbed_by_push.len() {
                return Err(ReportError::invalid(format!(
                    "no_learning has {} pushes, the learned walker {}",
                    n.absorbed_by_push.len(),
                    absorbed_by_push.len()
                )));
            }
            check_falls("no_learning", &n.absorbed_by_push, n.falls)?;
        }
        Ok(())
    }
}

/// Runs experiment D with one learner that learns through all episodes. `learner` builds a
/// learner from a config: it is given the settings' learner config, without its dF = 0 prior
/// unless `protocol.learner_prior` (D's learner is not initialised).
pub fn run<A, R>(
    settings: &Settings,
    protocol: &RobustnessProtocol,
    seed: u64,
    learner: &(dyn Fn(LearnerConfig) -> Result<FootstepLearner<A, R>, LearnerError> + Sync),
) -> Result<RobustnessResult, ExperimentError>
where
    A: FunctionApproximator + Clone,
    R: LearningRule,
{
    settings.validate()?;
    protocol
        .validate()
        .map_err(|e| e.within("protocols.robustness"))?;
    let push_times = push_times(settings, protocol, seed);
    let setup = |push_time: f64| episode_setup(settings, protocol, push_time);
    // A fall before the push resets the robot and delays the push; without a delivered push
    // the episode counts as a fall.
    let fell =
        |log: &crate::experiments::trial::TrialLog| log.pushes.first().is_none_or(|p| p.fell);
    let learned = || -> Result<(f64, Vec<Episode>), ExperimentError> {
        let mut learner = learner(learner_config(settings, protocol))?;
        let initial_metric = learner.learning_metric(&protocol.metric_grid)?;
        let mut episodes = Vec::new();
        for (i, &push_time) in push_times.iter().enumerate() {
            let log = run_trial(&setup(push_time), Some(&mut learner), &mut [])?;
            episodes.push(Episode {
                push: i + 1,
                push_time,
                fell: fell(&log),
                falls: log.falls.len(),
                steps: log.steps,
                learning_metric: learner.learning_metric(&protocol.metric_grid)?,
                map: learner.offset_map(&protocol.map)?,
            });
        }
        Ok((initial_metric, episodes))
    };
    let baseline = || -> Result<Vec<BaselineEpisode>, ExperimentError> {
        push_times
            .iter()
            .enumerate()
            .map(|(i, &push_time)| {
                let log = run_trial(&setup(push_time), None, &mut [])?;
                Ok(BaselineEpisode {
                    push: i + 1,
                    fell: fell(&log),
                    falls: log.falls.len(),
                })
            })
            .collect()
    };
    let (learned, no_learning) = rayon::join(learned, baseline);
    let (initial_metric, episodes) = learned?;
    Ok(RobustnessResult {
        impulse: protocol.impulse,
        initial_metric,
        episodes,
        no_learning: no_learning?,
    })
}

impl RobustnessResult {
    /// Writes `robustness_pushes.csv` (per push: fell, falls, learning metric, and the same
    /// push without learning),
    /// `robustness_steps.csv`, `learning_metric.svg` (Fig. 7) and `df_maps.svg` (Fig. 8: dF
    /// over theta_E x theta_E_dot after every push, the episode's touch-downs as crosses).
    pub fn write(&self, dir: &Path) -> Result<(), ExperimentError> {
        std::fs::create_dir_all(dir).map_err(|e| ReportError::io(dir, e))?;
        let rows: Vec<PushRow> = self
            .episodes
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let base = self.no_learning.get(i);
                PushRow {
                    push: e.push,
                    push_time_s: Fixed(e.push_time),
                    fell: e.fell,
                    falls: e.falls,
                    learning_metric: Fixed(e.learning_metric),
                    no_learning_fell: base.map(|b| b.fell),
                    no_learning_falls: base.map(|b| b.falls),
                }
            })
            .collect();
        write_rows(&dir.join("robustness_pushes.csv"), &rows)?;
        let rows: Vec<(PushCell, StepCells)> = self
            .episodes
            .iter()
            .flat_map(|e| {
                e.steps
                    .iter()
                    .map(move |s| (PushCell { push: e.push }, s.cells()))
            })
            .collect();
        write_rows(&dir.join("robustness_steps.csv"), &rows)?;
        let x: Vec<f64> = (0..=self.episodes.len()).map(|i| i as f64).collect();
        let y: Vec<f64> = std::iter::once(self.initial_metric)
            .chain(self.episodes.iter().map(|e| e.learning_metric))
            .map(|m| 100.0 * m)
            .collect();
        line_plot(
            &dir.join("learning_metric.svg"),
            &LinePlot {
                title: "Learning metric (norm of ΔF over the input grid) after each push",
                x_label: "push",
                y_label: "learning metric (cm)",
                series: &[Series {
                    name: "learner only",
                    x: &x,
                    y: &y,
                    spread: None,
                }],
            },
        )?;
        let titles: Vec<String> = self
            .episodes
            .iter()
            .map(|e| {
                format!(
                    "after push {} ({})",
                    e.push,
                    if e.fell { "fell" } else { "absorbed" }
                )
            })
            .collect();
        let points: Vec<Vec<(f64, f64)>> = self
            .episodes
            .iter()
            .map(|e| e.steps.iter().map(|s| (s.theta_e, s.theta_e_dot)).collect())
            .collect();
        let values_cm: Vec<Vec<f64>> = self
            .episodes
            .iter()
            .map(|e| e.map.values.iter().map(|v| 100.0 * v).collect())
            .collect();
        let panels: Vec<HeatPanel> = self
            .episodes
            .iter()
            .zip(&titles)
            .zip(&points)
            .zip(&values_cm)
            .map(|(((e, title), pts), values)| HeatPanel {
                title,
                xs: &e.map.theta_e,
                ys: &e.map.theta_e_dot,
                values,
                points: pts,
            })
            .collect();
        if !panels.is_empty() {
            heat_map_grid(
                &dir.join("df_maps.svg"),
                &HeatMapGrid {
                    title: "Learned step offset ΔF (cm) over the trunk angle and rate, after each push",
                    x_label: "θ_E (rad)",
                    y_label: "θ̇_E (rad/s)",
                    value_label: "ΔF (cm)",
                    panels: &panels,
                    columns: 5,
                },
            )?;
        }
        Ok(())
    }
}

/// The push time of every episode of a run with `seed` (episode time, s), in order: what
/// [`run`] draws before its episodes.
pub fn push_times(settings: &Settings, protocol: &RobustnessProtocol, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (s0, s1) = protocol.settle_s;
    (0..settings.scaled(protocol.pushes, 1))
        .map(|_| {
            if s1 > s0 {
                rng.random_range(s0..s1)
            } else {
                s0
            }
        })
        .collect()
}

/// The trial of one episode whose push comes at `push_time` (episode time, s): the same for
/// the learned walker and the walker without learning.
pub fn episode_setup(
    settings: &Settings,
    protocol: &RobustnessProtocol,
    push_time: f64,
) -> TrialSetup {
    settings.trial(
        WalkerMode::LearnerOnly,
        ReferenceSchedule::constant(protocol.map.f_r),
        vec![Push {
            time: push_time,
            impulse: protocol.impulse,
        }],
        protocol.direction,
        push_time + settings.push_window_s,
    )
}

/// The learner config of experiment D: the settings' without the dF = 0 prior unless the
/// protocol asks for it (not initialised).
pub fn learner_config(settings: &Settings, protocol: &RobustnessProtocol) -> LearnerConfig {
    if protocol.learner_prior {
        settings.learner
    } else {
        LearnerConfig {
            prior: Prior::none(),
            ..settings.learner
        }
    }
}

/// Experiment D as a registered [`Experiment`].
#[derive(Debug, Clone, Copy, Default)]
pub struct Robustness;

impl Experiment for Robustness {
    fn name(&self) -> &str {
        NAME
    }

    fn replay(&self) -> Option<&dyn Replayable> {
        Some(self)
    }

    fn description(&self) -> &str {
        "D (Fig. 7): robustness; learning from scratch without the analytic footstep"
    }

    fn protocol(&self, tables: &ProtocolTables) -> Result<Option<Table>, ConfigError> {
        tables.resolve::<RobustnessProtocol>(self.name())
    }

    fn check_result(&self, result: &ExperimentResult) -> Result<(), ReportError> {
        RobustnessSummary::from_result(result).map(|_| ())
    }

    /// The claim's comparison (pushes absorbed), then the falls while learning and the pushes
    /// until the first absorbed one (a run without any counts as one more than its pushes),
    /// each learned minus without learning.
    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired> {
        let mut out = claim(runs).over_seeds;
        let (mut falls, mut first) = (Vec::new(), Vec::new());
        for (_, result) in by_seed(runs, RobustnessSummary::of) {
            if let RobustnessSummary {
                pushes_until_first_absorbed,
                falls: learned_falls,
                absorbed_by_push,
                no_learning: Some(b),
                ..
            } = &result
            {
                falls.push(f64::from(*learned_falls) - f64::from(b.falls));
                let learned_first =
                    pushes_until_first_absorbed.map_or(absorbed_by_push.len() + 1, |n| n as usize);
                let b_first = b
                    .absorbed_by_push
                    .iter()
                    .position(|&a| a)
                    .map_or(b.absorbed_by_push.len() + 1, |i| i + 1);
                first.push(learned_first as f64 - b_first as f64);
            }
        }
        out.push(Paired::new(
            "falls, learned - without learning",
            &falls,
            0.0,
            Direction::LowerIsBetter,
        ));
        out.push(Paired::new(
            "pushes until the first absorbed, learned - without learning",
            &first,
            0.0,
            Direction::LowerIsBetter,
        ));
        out
    }

    fn headline(&self, runs: &[&Summary]) -> Vec<Headline> {
        let mut h: [Vec<f64>; 4] = Default::default();
        for s in runs {
            if let Some(RobustnessSummary {
                pushes_until_first_absorbed,
                absorbed_by_push,
                no_learning,
                falls,
                ..
            }) = &RobustnessSummary::of(s)
            {
                let count = |v: &[bool]| v.iter().filter(|&&a| a).count() as f64;
                h[0].push(pushes_until_first_absorbed.map_or(f64::NAN, f64::from));
                h[1].push(count(absorbed_by_push));
                h[2].push(
                    no_learning
                        .as_ref()
                        .map_or(f64::NAN, |b| count(&b.absorbed_by_push)),
                );
                h[3].push(f64::from(*falls));
            }
        }
        let [a, b, c, d] = h;
        vec![
            Headline::mean_of("pushes until the first absorbed", a),
            Headline::mean_of("pushes absorbed, learned", b),
            Headline::mean_of("pushes absorbed, without learning", c),
            Headline::mean_of("falls, learned", d),
        ]
    }

    fn apply_push_options(
        &self,
        protocols: &mut ProtocolTables,
        options: &PushOptions,
    ) -> Result<(), PushOptionsError> {
        let mut p: RobustnessProtocol = protocols.get(self.name())?;
        options.apply_single(self.name(), &mut p.pushes, &mut p.impulse, &mut p.direction)?;
        Ok(protocols.set(self.name(), &p)?)
    }

    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError> {
        let p: RobustnessProtocol = ctx.protocols.get(self.name())?;
        let p = &p;
        let r = run(ctx.settings, p, ctx.seed, &|config| {
            ctx.make_learner_with(config)
        })?;
        r.write(dir)?;
        Ok(r.summary().into_result()?)
    }
}

impl Replayable for Robustness {
    /// One episode per push; the learned walker learns from the episodes before the push
    /// replayed, beside the walker without learning.
    fn replay_plan(
        &self,
        settings: &Settings,
        protocols: &ProtocolTables,
        seed: u64,
    ) -> Result<ReplayPlan, ExperimentError> {
        let p: RobustnessProtocol = protocols.get(NAME)?;
        Ok(ReplayPlan::Episodes {
            episodes: push_times(settings, &p, seed)
                .into_iter()
                .map(|t| episode_setup(settings, &p, t))
                .collect(),
            learner: Box::new(learner_config(settings, &p)),
            impulse: p.impulse,
            direction: p.direction,
        })
    }

    /// The first push the learned walker absorbed and the walker without learning did not;
    /// else the first where they differ; else push 1.
    fn telling_moment(
        &self,
        _settings: &Settings,
        _protocols: &ProtocolTables,
        _seed: u64,
        dir: &Path,
    ) -> Result<(Moment, String), ExperimentError> {
        /// A push of `robustness_pushes.csv`; `no_learning_fell` is empty where the run had
        /// no walker without learning.
        #[derive(Deserialize)]
        struct Row {
            fell: bool,
            #[serde(default)]
            no_learning_fell: Option<bool>,
        }
        let rows: Vec<Row> = read_rows(&dir.join("robustness_pushes.csv"))?;
        // Equal impulses: the first push that differs.
        let learned: Vec<PushOutcome> = rows.iter().map(|r| (0.0, r.fell)).collect();
        let without: Vec<PushOutcome> = rows
            .iter()
            .map(|r| (0.0, r.no_learning_fell.unwrap_or(false)))
            .collect();
        let k = learned
            .iter()
            .zip(&without)
            .position(|(l, w)| !l.1 && w.1)
            .map_or_else(|| differing_push(&learned, &without), |i| i + 1);
        let fell = |x: &[PushOutcome]| x.get(k - 1).is_some_and(|p| p.1);
        Ok((
            Moment::Push(k),
            format!(
                "push {k}: learned {}, without learning {}",
                outcome(fell(&learned)),
                outcome(fell(&without))
            ),
        ))
    }
}

/// A row of `robustness_pushes.csv`: one push of the learning run, and the same push without
/// learning (empty when there was no such run).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
struct PushRow {
    push: usize,
    push_time_s: Fixed<4>,
    fell: bool,
    falls: usize,
    learning_metric: Fixed<6>,
    no_learning_fell: Option<bool>,
    no_learning_falls: Option<usize>,
}

/// The label column of `robustness_steps.csv`: the push whose episode the step belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
struct PushCell {
    push: usize,
}

/// `robustness_absorbed_over_seeds.svg` in `dir`: pushes absorbed so far against the push
/// number, learning from scratch and without learning, mean over the seeds of `runs` with its
/// 95% band; false when no run recorded its pushes.
pub fn figure_over_seeds(dir: &Path, runs: &[&Summary]) -> Result<bool, ReportError> {
    let (mut learned, mut without): (Vec<Vec<f64>>, Vec<Vec<f64>>) = (Vec::new(), Vec::new());
    let add = |to: &mut Vec<Vec<f64>>, absorbed: &[bool]| {
        let mut so_far = 0.0;
        for (k, a) in absorbed.iter().enumerate() {
            so_far += f64::from(u8::from(*a));
            if to.len() <= k {
                to.resize(k + 1, Vec::new());
            }
            to[k].push(so_far);
        }
    };
    for (_, (absorbed, no_learning)) in by_seed(runs, |s| {
        RobustnessSummary::of(s).map(|r| (r.absorbed_by_push, r.no_learning))
    }) {
        add(&mut learned, &absorbed);
        if let Some(n) = no_learning {
            add(&mut without, &n.absorbed_by_push);
        }
    }
    let x = |v: &[Vec<f64>]| (1..=v.len()).map(|k| k as f64).collect::<Vec<_>>();
    band_plot(
        &dir.join("robustness_absorbed_over_seeds.svg"),
        Labels {
            title: "Pushes absorbed so far, learning from scratch",
            x: "push",
            y: "pushes absorbed",
            integer_x: true,
            y_range: 0.0..f64::INFINITY,
        },
        &[
            ("learned", band(&x(&learned), &learned)),
            ("no learning (ΔF = 0)", band(&x(&without), &without)),
        ],
    )
}

/// Claim 4, checked on `runs` (this experiment's summaries, any order): without
/// initialisation the learner absorbs a push within its first three pushes and absorbs more
/// pushes than the same walker without learning, on most seeds; the difference in pushes
/// absorbed paired over seeds.
pub fn claim(runs: &[&Summary]) -> Claim {
    let mut seeds = Vec::new();
    let mut absorbed_diff = Vec::new();
    for (seed, result) in by_seed(runs, RobustnessSummary::of) {
        let RobustnessSummary {
            pushes_until_first_absorbed,
            falls,
            impulse_ns,
            absorbed_by_push,
            no_learning,
        } = &result;
        let n = *pushes_until_first_absorbed;
        let early = n.is_some_and(|n| n <= 3);
        let absorbed = absorbed_by_push.iter().filter(|&&a| a).count();
        let impulse = impulse_ns.map_or(String::new(), |i| format!(" at {i} Ns"));
        let first = match n {
            Some(n) => format!("first absorbed: push {n}"),
            None => "no push absorbed".to_string(),
        };
        // Without the baseline (older summaries) the comparison is not measured and the claim
        // does not hold for the seed.
        let (more, baseline) = match no_learning {
            Some(b) => {
                let b_absorbed = b.absorbed_by_push.iter().filter(|&&a| a).count();
                absorbed_diff.push(absorbed as f64 - b_absorbed as f64);
                (
                    absorbed > b_absorbed,
                    format!(
                        "absorbed {absorbed} of {} pushes{impulse} ({falls} falls) vs {b_absorbed} of {} without learning ({} falls)",
                        absorbed_by_push.len(),
                        b.absorbed_by_push.len(),
                        b.falls
                    ),
                )
            }
            None => (false, format!("{falls} falls; no run without learning")),
        };
        seeds.push((seed, early && more, format!("{first}; {baseline}")));
    }
    Claim::new(
        "4. Without initialisation, the learner absorbs a push within its first three pushes and absorbs more pushes than the same walker without learning (ΔF = 0) on the same episodes (most seeds).",
        seeds,
        Claim::most,
        vec![Paired::new(
            "pushes absorbed, learned - without learning",
            &absorbed_diff,
            0.0,
            Direction::HigherIsBetter,
        )],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn typed() -> RobustnessSummary {
        RobustnessSummary {
            pushes_until_first_absorbed: Some(3),
            falls: 2,
            impulse_ns: Some(8.0),
            absorbed_by_push: vec![false, false, true],
            no_learning: Some(NoLearning {
                absorbed_by_push: vec![false, false, false],
                falls: 4,
            }),
        }
    }

    /// Whether `r` is refused, written and read back alike.
    fn refused(r: RobustnessSummary) -> bool {
        let read = Robustness
            .check_result(&ExperimentResult::new(NAME, &r).unwrap())
            .is_err();
        assert_eq!(r.into_result().is_err(), read);
        read
    }

    #[test]
    fn inconsistent_series_are_refused() {
        assert!(!refused(typed()));
        let with = |f: &dyn Fn(&mut RobustnessSummary)| {
            let mut r = typed();
            f(&mut r);
            refused(r)
        };
        // the first absorbed push disagrees with the series
        assert!(with(&|r| r.absorbed_by_push[1] = true));
        // 1-based
        assert!(with(&|r| {
            r.pushes_until_first_absorbed = Some(0);
            r.absorbed_by_push.clear();
        }));
        // different lengths
        assert!(with(&|r| r
            .no_learning
            .as_mut()
            .unwrap()
            .absorbed_by_push
            .push(true)));
        // fewer falls than pushes not absorbed
        assert!(with(&|r| r.no_learning.as_mut().unwrap().falls = 2));
        assert!(with(&|r| r.falls = 1));
        // A NaN impulse cannot be written; in JSON it could only be `null`, no impulse.
        let mut r = typed();
        r.impulse_ns = Some(f64::NAN);
        assert!(r.into_result().is_err());
    }

    #[test]
    fn older_summaries_read_and_write_back_without_invented_fields() {
        let old_d = r#"{"approx": "lwpr", "rule": "pendulum-cart", "seed": 1,
            "experiment": "robustness", "pushes_until_first_absorbed": 2, "falls": 1}"#;
        let s = Summary::from_json(old_d).unwrap();
        let r = RobustnessSummary::of(&s).unwrap();
        assert_eq!(
            r,
            RobustnessSummary {
                pushes_until_first_absorbed: Some(2),
                falls: 1,
                impulse_ns: None,
                absorbed_by_push: vec![],
                no_learning: None,
            }
        );
        let written = Summary {
            result: r.into_result().unwrap(),
            ..s
        };
        assert!(!written.to_json().unwrap().contains("no_learning"));
    }
}
