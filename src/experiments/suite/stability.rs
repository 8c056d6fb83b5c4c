//! Experiment C (paper Fig. 6): fall probability against push impulse for the open-loop
//! walker, the Capture Step *model* and the *learned* walker, walking in place with forward
//! pushes of random impulse at random gait phases.

use crate::config::{self, ConfigError};
use crate::control::{FootstepPolicy, WalkerMode};
use crate::experiments::catch_step::{CatchStepReach, catch_step_reach};
use crate::experiments::claim::{Claim, by_seed};
use crate::experiments::error::ExperimentError;
use crate::experiments::fall_causes::{
    ClassifiedFall, FallCause, FallEvent, cause_by_push, count, push_rows, run_classified_with,
};
use crate::experiments::paired::{Direction, Paired};
use crate::experiments::protocol::{Protocol, ProtocolTables, Table};
use crate::experiments::replay_plan::{
    Moment, ReplayPlan, ReplayWalker, learned_versus_model_moment,
};
use crate::experiments::schedule::PushPlan;
use crate::experiments::settings::{LearnerFactory, Settings};
use crate::experiments::summary::{
    ExperimentResult, Summary, TypedResult, check_causes, finite_non_negative,
};
use crate::experiments::trial::{PushRecord, TrialLog, TrialSetup};
use crate::experiments::{
    Experiment, Headline, PushOptions, PushOptionsError, Replayable, RunContext,
};
use crate::report::ReportError;
use crate::report::band::{Labels, band, band_plot};
use crate::report::csv_read::{number, read_rows};
use crate::report::fall_rate::{Fall50Estimate, PushResult, fall_rate_bins, impulse_at_50pct_fall};
use crate::report::figures::{FallCurve, FallPlot, fall_probability_plot};
use crate::report::write_rows;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The experiment's registered name.
pub const NAME: &str = "stability";

/// The protocol (paper: 400 pushes uniform in [0, 20] Ns, walking in place).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StabilityProtocol {
    /// Pushes per controller (before [`Settings::scale`]).
    pub pushes: usize,
    /// Impulse range (Ns).
    pub impulse: (f64, f64),
    /// Time between pushes (s), random so pushes hit random gait phases.
    pub gap_s: (f64, f64),
    /// Unit push direction (forward by default).
    pub direction: [f64; 3],
}

impl Default for StabilityProtocol {
    fn default() -> Self {
        StabilityProtocol {
            pushes: 400,
            impulse: (0.0, 20.0),
            gap_s: (3.0, 4.0),
            direction: [1.0, 0.0, 0.0],
        }
    }
}

impl Protocol for StabilityProtocol {
    /// Checks at least one push, a non-negative ordered impulse range, a positive ordered gap
    /// and a unit direction; errors name the field (relative to the protocol's section).
    fn validate(&self) -> Result<(), ConfigError> {
        config::push_series(self.pushes, self.impulse, self.gap_s)?;
        config::unit_direction("direction", &self.direction)
    }
}

/// One controller's pushes and its 50% fall impulse.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ControllerPushes {
    /// Every delivered push and its outcome.
    pub pushes: Vec<PushRecord>,
    /// The impulse at 50% falls.
    pub fall50: Fall50Estimate,
    /// Every fall of the trial (within a push window or not) with its cause, in time order.
    #[serde(default)]
    pub classified_falls: Vec<ClassifiedFall>,
    /// The catch step's reach over the pushes (see [`crate::experiments::catch_step`]).
    pub catch_step: CatchStepReach,
}

impl ControllerPushes {
    fn new(
        log: TrialLog,
        classified_falls: Vec<ClassifiedFall>,
        events: &[FallEvent],
    ) -> Result<Self, ExperimentError> {
        let samples: Vec<PushResult> = log.pushes.iter().map(|p| (p.impulse, p.fell)).collect();
        let fall50 = impulse_at_50pct_fall(&samples)?;
        Ok(ControllerPushes {
            catch_step: catch_step_reach(events, &log.pushes),
            pushes: log.pushes,
            fall50,
            classified_falls,
        })
    }

    /// Number of pushes followed by a fall within the push window.
    pub fn falls(&self) -> usize {
        self.pushes.iter().filter(|p| p.fell).count()
    }

    /// Falls per cause (every cause present); sums to all falls of the trial, of which the
    /// ones other than `no_push` are the pushes' [`ControllerPushes::falls`].
    pub fn fall_causes(&self) -> BTreeMap<String, u32> {
        count(&self.classified_falls)
    }

    /// The cause of the fall after each push, `None` where it was absorbed.
    pub fn cause_by_push(&self) -> Vec<Option<FallCause>> {
        cause_by_push(&self.classified_falls, self.pushes.len())
    }
}

/// The three controllers' results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StabilityResult {
    /// Fixed-frequency stepping in place, no feedback.
    pub open_loop: ControllerPushes,
    /// Capture Step alone.
    pub model: ControllerPushes,
    /// Capture Step plus the learner, learning throughout.
    pub learned: ControllerPushes,
}

/// Runs experiment C. The three controllers see the same push sequence.
pub fn run(
    settings: &Settings,
    protocol: &StabilityProtocol,
    seed: u64,
    learner: &(impl LearnerFactory + Sync),
) -> Result<StabilityResult, ExperimentError> {
    settings.validate()?;
    protocol
        .validate()
        .map_err(|e| e.within("protocols.stability"))?;
    let plan = PushPlan {
        count: settings.scaled(protocol.pushes, 1),
        impulse: protocol.impulse,
        settle: 3.0,
        gap: protocol.gap_s,
    };
    let trial = |mode| settings.push_trial(mode, 0.0, &plan, seed, protocol.direction);
    let (open_loop, (model, learned)) = rayon::join(
        || observed(trial(WalkerMode::OpenLoop), None),
        || {
            rayon::join(
                || observed(trial(WalkerMode::CaptureStep), None),
                || {
                    let mut l = learner.make()?;
                    observed(trial(WalkerMode::CaptureStep), Some(&mut l))
                },
            )
        },
    );
    Ok(StabilityResult {
        open_loop: open_loop?,
        model: model?,
        learned: learned?,
    })
}

/// C's trial of one controller for `seed`, as [`run`] builds it: walking in place, the
/// protocol's pushes (the same sequence for every controller), for `mode`
/// ([`WalkerMode::OpenLoop`] or [`WalkerMode::CaptureStep`], the model and, with the run's
/// learner, the learned walker). For replays and probes that run it with their own observers.
pub fn trial_setup(
    settings: &Settings,
    protocol: &StabilityProtocol,
    seed: u64,
    mode: WalkerMode,
) -> TrialSetup {
    let plan = PushPlan {
        count: settings.scaled(protocol.pushes, 1),
        impulse: protocol.impulse,
        settle: 3.0,
        gap: protocol.gap_s,
    };
    settings.push_trial(mode, 0.0, &plan, seed, protocol.direction)
}

/// Runs one controller's trial and classifies its falls.
fn observed(
    setup: TrialSetup,
    policy: Option<&mut (dyn FootstepPolicy + '_)>,
) -> Result<ControllerPushes, ExperimentError> {
    let (log, falls, events) = run_classified_with(&setup, policy)?;
    ControllerPushes::new(log, falls, &events)
}

impl StabilityResult {
    /// The three controllers with their display names, in plot order.
    pub fn controllers(&self) -> [(&'static str, &ControllerPushes); 3] {
        [
            ("open-loop", &self.open_loop),
            ("model", &self.model),
            ("learned", &self.learned),
        ]
    }

    /// Falls per cause of each controller, for `summary.json`.
    pub fn fall_cause_counts(&self) -> FallCauseCounts {
        FallCauseCounts {
            open_loop: self.open_loop.fall_causes(),
            model: self.model.fall_causes(),
            learned: self.learned.fall_causes(),
        }
    }

    /// Writes `pushes.csv` (controller, time, impulse, fell, the cause of the fall) and
    /// `fall_probability.svg` (logistic fits and 2 Ns bins, as the paper's Fig. 6, titled by
    /// the push `direction`) into `dir`.
    pub fn write(
        &self,
        dir: &Path,
        impulse: (f64, f64),
        direction: [f64; 3],
    ) -> Result<(), ExperimentError> {
        std::fs::create_dir_all(dir).map_err(|e| ReportError::io(dir, e))?;
        let rows: Vec<_> = self
            .controllers()
            .into_iter()
            .flat_map(|(controller, c)| push_rows(controller, &c.pushes, &c.classified_falls))
            .collect();
        write_rows(&dir.join("pushes.csv"), &rows)?;
        let bins_per_controller = ((impulse.1 - impulse.0) / 2.0).ceil().max(1.0) as usize;
        let mut curves = Vec::new();
        for (name, c) in self.controllers() {
            let samples: Vec<PushResult> = c.pushes.iter().map(|p| (p.impulse, p.fell)).collect();
            let bins: Vec<(f64, f64)> =
                fall_rate_bins(&samples, impulse.0, impulse.1, bins_per_controller)?
                    .iter()
                    .filter_map(|b| b.fraction().map(|f| (b.center(), f)))
                    .collect();
            // The logistic fit where one exists, else the binned fractions joined by lines.
            let (x, y) = match c.fall50.fit {
                Some(fit) => fit.curve(impulse.0, impulse.1, 101),
                None => bins.iter().copied().unzip(),
            };
            curves.push((name, x, y, bins));
        }
        let curves: Vec<FallCurve> = curves
            .iter()
            .map(|(name, x, y, bins)| FallCurve {
                name,
                impulse: x,
                probability: y,
                bins,
            })
            .collect();
        let title = format!(
            "Probability to fall vs {} push impulse",
            direction_name(direction)
        );
        fall_probability_plot(
            &dir.join("fall_probability.svg"),
            &FallPlot {
                title: &title,
                x_label: "push impulse (Ns)",
                curves: &curves,
            },
        )?;
        Ok(())
    }
}

/// `forward`, `backward`, `left` or `right` for the unit axes of the horizontal plane, else the
/// vector itself.
pub(crate) fn direction_name(d: [f64; 3]) -> String {
    match d {
        [1.0, 0.0, 0.0] => "forward".into(),
        [-1.0, 0.0, 0.0] => "backward".into(),
        [0.0, 1.0, 0.0] => "left".into(),
        [0.0, -1.0, 0.0] => "right".into(),
        [x, y, z] => format!("({x}, {y}, {z})"),
    }
}

/// Pushes, falls and the 50% fall impulse of one controller (experiment C).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControllerFalls {
    /// Pushes applied.
    pub pushes: u32,
    /// Falls among them.
    pub falls: u32,
    /// Impulse (Ns) at which half the pushes make the robot fall, from
    /// [`crate::report::fall_rate::impulse_at_50pct_fall`] (with its documented fallbacks).
    pub impulse_at_50pct_fall_ns: f64,
}

/// Experiment C's three controllers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Controllers {
    /// Walking in place at a fixed frequency, not reacting to pushes.
    pub open_loop: ControllerFalls,
    /// The Capture Step controller.
    pub model: ControllerFalls,
    /// Capture Step plus the learned offset.
    pub learned: ControllerFalls,
}

/// Experiment C: falls per cause (names from [`crate::experiments::fall_causes::FallCause`])
/// of each controller, over every fall of its trial. Empty in summaries written before the
/// causes were recorded.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FallCauseCounts {
    /// The open-loop walker.
    pub open_loop: BTreeMap<String, u32>,
    /// The Capture Step controller.
    pub model: BTreeMap<String, u32>,
    /// Capture Step plus the learned offset.
    pub learned: BTreeMap<String, u32>,
}

/// The catch step's mean reach (realised / commanded length) of the two Capture Step
/// walkers; `null` where no push had a catch step that counts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CatchStepReaches {
    /// The Capture Step model.
    pub model: Option<f64>,
    /// The learned walker.
    pub learned: Option<f64>,
}

/// Experiment C's part of `summary.json`: falls vs impulse for three controllers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StabilitySummary {
    /// Per controller.
    pub controllers: Controllers,
    /// Falls per cause, per controller (empty in older summaries).
    #[serde(default)]
    pub fall_causes: FallCauseCounts,
    /// The catch step's reach of the model and the learned walker (see
    /// [`crate::experiments::catch_step`]); absent in older summaries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub catch_step_reach: Option<CatchStepReaches>,
}

/// C: falls within pushes per controller, causes adding up, finite reaches.
impl TypedResult for StabilitySummary {
    const EXPERIMENT: &'static str = NAME;

    fn validate(&self) -> Result<(), ReportError> {
        let (controllers, fall_causes, catch_step_reach) =
            (&self.controllers, &self.fall_causes, &self.catch_step_reach);
        for (name, c, causes) in [
            ("open_loop", &controllers.open_loop, &fall_causes.open_loop),
            ("model", &controllers.model, &fall_causes.model),
            ("learned", &controllers.learned, &fall_causes.learned),
        ] {
            c.validate(name)?;
            check_causes(name, causes, c.falls)?;
        }
        if let Some(r) = catch_step_reach {
            for (name, v) in [
                ("catch_step_reach.model", r.model),
                ("catch_step_reach.learned", r.learned),
            ] {
                if v.is_some_and(|v| !v.is_finite()) {
                    return Err(ReportError::invalid(format!("{name} must be finite")));
                }
            }
        }
        Ok(())
    }
}

impl ControllerFalls {
    fn validate(&self, name: &str) -> Result<(), ReportError> {
        if self.falls > self.pushes {
            return Err(ReportError::invalid(format!(
                "{name}: {} falls out of {} pushes",
                self.falls, self.pushes
            )));
        }
        finite_non_negative(
            &format!("{name}.impulse_at_50pct_fall_ns"),
            self.impulse_at_50pct_fall_ns,
        )
    }
}

/// Experiment C as a registered [`Experiment`].
#[derive(Debug, Clone, Copy, Default)]
pub struct Stability;

impl Experiment for Stability {
    fn name(&self) -> &str {
        NAME
    }

    fn replay(&self) -> Option<&dyn Replayable> {
        Some(self)
    }

    fn description(&self) -> &str {
        "C (Fig. 6): stability; impulse at 50% falls stepping in place"
    }

    fn protocol(&self, tables: &ProtocolTables) -> Result<Option<Table>, ConfigError> {
        tables.resolve::<StabilityProtocol>(self.name())
    }

    fn check_result(&self, result: &ExperimentResult) -> Result<(), ReportError> {
        StabilitySummary::from_result(result).map(|_| ())
    }

    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired> {
        claim(runs).over_seeds
    }

    fn headline(&self, runs: &[&Summary]) -> Vec<Headline> {
        let mut h: [Vec<f64>; 4] = Default::default();
        for s in runs {
            if let Some(StabilitySummary { controllers: c, .. }) = StabilitySummary::of(s) {
                h[0].push(c.open_loop.impulse_at_50pct_fall_ns);
                h[1].push(c.model.impulse_at_50pct_fall_ns);
                h[2].push(c.learned.impulse_at_50pct_fall_ns);
                h[3].push(f64::from(c.learned.falls) / f64::from(c.learned.pushes));
            }
        }
        let [a, b, c, d] = h;
        vec![
            Headline::mean_of("I50 open-loop (Ns)", a),
            Headline::mean_of("I50 model (Ns)", b),
            Headline::mean_of("I50 learned (Ns)", c),
            Headline::mean_of("falls per push, learned", d),
        ]
    }

    fn apply_push_options(
        &self,
        protocols: &mut ProtocolTables,
        options: &PushOptions,
    ) -> Result<(), PushOptionsError> {
        let mut p: StabilityProtocol = protocols.get(self.name())?;
        p.pushes = options.pushes.unwrap_or(p.pushes);
        p.impulse = options.impulse_range.unwrap_or(p.impulse);
        p.direction = options.direction.unwrap_or(p.direction);
        Ok(protocols.set(self.name(), &p)?)
    }

    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError> {
        let p: StabilityProtocol = ctx.protocols.get(self.name())?;
        let p = &p;
        let r = run(ctx.settings, p, ctx.seed, &|| ctx.make_step_learner())?;
        r.write(dir, p.impulse, p.direction)?;
        let falls = |c: &ControllerPushes| ControllerFalls {
            pushes: c.pushes.len() as u32,
            falls: c.falls() as u32,
            impulse_at_50pct_fall_ns: c.fall50.impulse_ns,
        };
        Ok(StabilitySummary {
            controllers: Controllers {
                open_loop: falls(&r.open_loop),
                model: falls(&r.model),
                learned: falls(&r.learned),
            },
            fall_causes: r.fall_cause_counts(),
            catch_step_reach: Some(CatchStepReaches {
                model: r.model.catch_step.reach,
                learned: r.learned.catch_step.reach,
            }),
        }
        .into_result()?)
    }
}

impl Replayable for Stability {
    /// The learned, model and open-loop walkers on the run's pushes.
    fn replay_plan(
        &self,
        settings: &Settings,
        protocols: &ProtocolTables,
        seed: u64,
    ) -> Result<ReplayPlan, ExperimentError> {
        let p: StabilityProtocol = protocols.get(NAME)?;
        let setup = |mode| trial_setup(settings, &p, seed, mode);
        let capture = setup(WalkerMode::CaptureStep);
        Ok(ReplayPlan::Trials {
            walkers: vec![
                ReplayWalker::new("learned", capture.clone(), true),
                ReplayWalker::new("model", capture, false),
                ReplayWalker::new("open-loop", setup(WalkerMode::OpenLoop), false),
            ],
            direction: p.direction,
            after_push_s: settings.push_window_s,
            pushes: true,
        })
    }

    /// The push of smallest impulse where one of learned and model fell and the other
    /// recovered; else the first (of smallest impulse) where one fell; else push 1.
    fn telling_moment(
        &self,
        _settings: &Settings,
        _protocols: &ProtocolTables,
        _seed: u64,
        dir: &Path,
    ) -> Result<(Moment, String), ExperimentError> {
        Ok(learned_versus_model_moment(&dir.join("pushes.csv"))?)
    }
}

/// The columns of `pushes.csv` the figure across seeds reads.
#[derive(Debug, Deserialize)]
struct PushCells {
    controller: String,
    impulse_ns: String,
    fell: bool,
}

/// `stability_fall_probability_over_seeds.svg` in `dir`: the share of pushes ending in a fall
/// per 2 Ns impulse bin, per controller, mean over the runs in `run_dirs` (one per seed, each
/// with its `pushes.csv`) with its 95% band; runs without the file are left out, false when
/// none has it.
pub fn figure_over_seeds(
    dir: &Path,
    run_dirs: &[std::path::PathBuf],
) -> Result<bool, ExperimentError> {
    const BIN_NS: f64 = 2.0;
    let names = ["open-loop", "model", "learned"];
    // Per controller and bin, one fall share per seed.
    let mut shares: Vec<Vec<Vec<f64>>> = vec![Vec::new(); names.len()];
    for run in run_dirs {
        let path = run.join("pushes.csv");
        if !path.is_file() {
            continue;
        }
        // (falls, pushes) per controller and bin for this seed.
        let mut counts: Vec<Vec<(u32, u32)>> = vec![Vec::new(); names.len()];
        for row in read_rows::<PushCells>(&path)? {
            let (Some(c), impulse) = (
                names.iter().position(|n| *n == row.controller),
                number(&row.impulse_ns),
            ) else {
                continue;
            };
            if impulse.is_nan() || impulse < 0.0 {
                continue;
            }
            let k = (impulse / BIN_NS) as usize;
            if counts[c].len() <= k {
                counts[c].resize(k + 1, (0, 0));
            }
            counts[c][k].0 += u32::from(row.fell);
            counts[c][k].1 += 1;
        }
        for (c, bins) in counts.iter().enumerate() {
            for (k, &(falls, pushes)) in bins.iter().enumerate() {
                if shares[c].len() <= k {
                    shares[c].resize(k + 1, Vec::new());
                }
                if pushes > 0 {
                    shares[c][k].push(f64::from(falls) / f64::from(pushes));
                }
            }
        }
    }
    let bands: Vec<(&str, _)> = names
        .iter()
        .zip(&shares)
        .map(|(name, s)| {
            let x: Vec<f64> = (0..s.len()).map(|k| (k as f64 + 0.5) * BIN_NS).collect();
            (*name, band(&x, s))
        })
        .collect();
    Ok(band_plot(
        &dir.join("stability_fall_probability_over_seeds.svg"),
        Labels {
            title: "Probability to fall per 2 Ns impulse bin",
            x: "push impulse (Ns)",
            y: "fall probability",
            integer_x: false,
            y_range: 0.0..1.0,
        },
        &bands,
    )?)
}

/// Claim 3, checked on `runs` (this experiment's summaries, any order): the impulse at 50%
/// falls of the learned walker at least the model's, and the model's at least 1.5 times the
/// open-loop walker's, on every seed; both ratios paired over seeds.
pub fn claim(runs: &[&Summary]) -> Claim {
    let mut seeds = Vec::new();
    let (mut i50_ratio, mut model_over_open) = (Vec::new(), Vec::new());
    for (seed, c) in by_seed(runs, |s| StabilitySummary::of(s).map(|r| r.controllers)) {
        let (o, m, l) = (
            c.open_loop.impulse_at_50pct_fall_ns,
            c.model.impulse_at_50pct_fall_ns,
            c.learned.impulse_at_50pct_fall_ns,
        );
        i50_ratio.push(l / m);
        model_over_open.push(m / o);
        seeds.push((
            seed,
            l >= m && m >= 1.5 * o,
            format!(
                "I50 learned {l:.2}, model {m:.2}, open-loop {o:.2} Ns (learned/model {:.2})",
                l / m
            ),
        ));
    }
    Claim::new(
        "3. Impulse at 50% falls: learned >= model >= 1.5 x open-loop (every seed).",
        seeds,
        Claim::every,
        vec![
            Paired::new(
                "I50 learned / model",
                &i50_ratio,
                1.0,
                Direction::HigherIsBetter,
            ),
            Paired::new(
                "I50 model / open-loop",
                &model_over_open,
                1.5,
                Direction::HigherIsBetter,
            ),
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::LearnSet;

    fn falls(pushes: u32, falls: u32, x: f64) -> ControllerFalls {
        ControllerFalls {
            pushes,
            falls,
            impulse_at_50pct_fall_ns: x,
        }
    }

    fn causes(no_push: u32, pushed: [u32; 2]) -> BTreeMap<String, u32> {
        [
            ("no_push".to_string(), no_push),
            ("before_touch_down".to_string(), pushed[0]),
            ("tipped_after_catch_step".to_string(), pushed[1]),
        ]
        .into()
    }

    fn typed() -> StabilitySummary {
        StabilitySummary {
            controllers: Controllers {
                open_loop: falls(400, 250, 4.5),
                model: falls(400, 120, 11.0),
                learned: falls(400, 90, 13.25),
            },
            fall_causes: FallCauseCounts {
                open_loop: causes(3, [200, 50]),
                model: causes(0, [100, 20]),
                learned: causes(1, [60, 30]),
            },
            catch_step_reach: Some(CatchStepReaches {
                model: Some(0.93),
                learned: None,
            }),
        }
    }

    fn summary(r: StabilitySummary) -> Summary {
        Summary {
            approx: "lwpr".into(),
            rule: "pendulum-cart".into(),
            seed: 3,
            learn: LearnSet::default(),
            robot: None,
            result: r.into_result().unwrap(),
        }
    }

    #[test]
    fn json_has_exactly_the_promised_fields_in_order() {
        let json = summary(typed()).to_json().unwrap();
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        let mut keys: Vec<_> = v.as_object().unwrap().keys().cloned().collect();
        keys.sort();
        assert_eq!(
            keys,
            [
                "approx",
                "catch_step_reach",
                "controllers",
                "experiment",
                "fall_causes",
                "learn",
                "rule",
                "seed"
            ]
        );
        assert_eq!(v["learn"], serde_json::json!(["step-x"]));
        assert_eq!(v["catch_step_reach"]["model"], 0.93);
        assert!(v["catch_step_reach"]["learned"].is_null());
        assert_eq!(v["fall_causes"]["model"]["before_touch_down"], 100);
        assert_eq!(v["experiment"], "stability");
        assert_eq!(
            v["controllers"]["open_loop"]["impulse_at_50pct_fall_ns"],
            4.5
        );
        assert_eq!(v["controllers"]["learned"]["falls"], 90);
        // Written in the order summaries have always had: the type's, not alphabetical.
        let at = |k: &str| json.find(&format!("\"{k}\"")).unwrap();
        assert!(at("experiment") < at("controllers"));
        assert!(at("controllers") < at("fall_causes"));
        assert!(at("fall_causes") < at("catch_step_reach"));
        assert!(at("pushes") < at("falls") && at("falls") < at("impulse_at_50pct_fall_ns"));
        let back = Summary::from_json(&json).unwrap();
        assert_eq!(StabilitySummary::of(&back), Some(typed()));
        Stability.check_result(&back.result).unwrap();
    }

    #[test]
    fn inconsistent_results_are_refused_both_ways() {
        let refused = |f: &dyn Fn(&mut StabilitySummary)| {
            let mut r = typed();
            f(&mut r);
            let written = r.clone().into_result().is_err();
            let read = Stability
                .check_result(&ExperimentResult::new(NAME, &r).unwrap())
                .is_err();
            assert_eq!(written, read);
            written
        };
        assert!(!refused(&|_| {}));
        // 91 falls after pushes for 90 fell pushes.
        assert!(refused(&|r| {
            *r.fall_causes.learned.get_mut("before_touch_down").unwrap() += 1
        }));
        // no_push falls are outside the pushes' count.
        assert!(!refused(&|r| {
            *r.fall_causes.learned.get_mut("no_push").unwrap() += 5
        }));
        assert!(refused(&|r| {
            r.fall_causes.model.insert("gremlins".into(), 0);
        }));
        assert!(refused(&|r| r.controllers.model.falls = 401));
        assert!(refused(&|r| {
            r.controllers.model.impulse_at_50pct_fall_ns = f64::NAN
        }));
        // A non-finite reach cannot be written; in JSON it could only be `null`, no reach.
        let mut r = typed();
        r.catch_step_reach = Some(CatchStepReaches {
            model: Some(f64::INFINITY),
            learned: None,
        });
        assert!(r.into_result().is_err());
    }

    #[test]
    fn older_summaries_without_causes_still_read() {
        let old_c = r#"{"approx": "lwpr", "rule": "pendulum-cart", "seed": 1,
            "experiment": "stability", "controllers": {
            "open_loop": {"pushes": 4, "falls": 2, "impulse_at_50pct_fall_ns": 5.0},
            "model": {"pushes": 4, "falls": 1, "impulse_at_50pct_fall_ns": 9.0},
            "learned": {"pushes": 4, "falls": 1, "impulse_at_50pct_fall_ns": 10.0}}}"#;
        let r = StabilitySummary::of(&Summary::from_json(old_c).unwrap()).unwrap();
        assert_eq!(r.fall_causes, FallCauseCounts::default());
        assert_eq!(r.catch_step_reach, None);
    }

    #[test]
    fn titles_name_the_push_direction() {
        assert_eq!(direction_name([1.0, 0.0, 0.0]), "forward");
        assert_eq!(direction_name([-1.0, 0.0, 0.0]), "backward");
        assert_eq!(direction_name([0.0, 1.0, 0.0]), "left");
        assert_eq!(direction_name([0.0, -1.0, 0.0]), "right");
        assert_eq!(direction_name([0.6, 0.8, 0.0]), "(0.6, 0.8, 0)");
    }
}
