//! Experiment A (paper Fig. 4): reference tracking. The reference step size jumps to a value
//! uniform in [-0.10, 0.20] m every 4-8 s; the model and the learned walker see the same
//! sequence. The step size error F_E of every step is binned by the time since the last
//! change: its mean and standard deviation per bin are the figure.

use crate::config::limits::{MAX_BINS, MAX_GAP_S, MAX_STEP_M, MAX_TRIAL_S, MIN_BIN_S};
use crate::config::{self, ConfigError};
use crate::control::WalkerMode;
use crate::experiments::aligned::AlignedStats;
use crate::experiments::claim::{Claim, by_seed};
use crate::experiments::compare::{ModelAndLearned, run_model_and_learned};
use crate::experiments::error::ExperimentError;
use crate::experiments::paired::{Direction, Paired};
use crate::experiments::protocol::{Protocol, ProtocolTables, Table};
use crate::experiments::replay_plan::{Moment, ReplayPlan, ReplayWalker, round};
use crate::experiments::schedule::ReferenceSchedule;
use crate::experiments::settings::{LearnerFactory, Settings};
use crate::experiments::summary::{
    ExperimentResult, ModelLearned, Summary, TypedResult, finite_non_negative,
};
use crate::experiments::trial::TrialLog;
use crate::experiments::{
    Experiment, Headline, PushOptions, PushOptionsError, Replayable, RunContext,
};
use crate::report::ReportError;
use crate::report::band::{Labels, band, band_plot};
use crate::report::figures::{EventPlot, LinePlot, Series, event_plot, line_plot};
use crate::report::{Fixed, write_rows};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The experiment's registered name.
pub const NAME: &str = "tracking";

/// The protocol (paper: F_R uniform in [-0.1, 0.2] m held 4-8 s, statistics over 1000 steps).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TrackingProtocol {
    /// Reference range (m).
    pub reference: (f64, f64),
    /// How long each reference is held (s).
    pub hold_s: (f64, f64),
    /// Simulated time per controller (s) before [`Settings::scale`] (about 1000 steps).
    pub duration_s: f64,
    /// Width of a time bin after a change (s).
    pub bin_s: f64,
    /// Statistics cover this long after each change (s); at most the shortest hold.
    pub horizon_s: f64,
}

impl Default for TrackingProtocol {
    fn default() -> Self {
        TrackingProtocol {
            reference: (-0.10, 0.20),
            hold_s: (4.0, 8.0),
            duration_s: 450.0,
            bin_s: 0.5,
            horizon_s: 4.0,
        }
    }
}

impl Protocol for TrackingProtocol {
    /// Checks ranges, positive times and a horizon within the shortest hold; errors name the
    /// field (relative to the protocol's section).
    fn validate(&self) -> Result<(), ConfigError> {
        config::ordered("reference", self.reference)?;
        config::range_in("reference", self.reference, -MAX_STEP_M, MAX_STEP_M)?;
        config::positive_range("hold_s", self.hold_s)?;
        config::range_in("hold_s", self.hold_s, 0.0, MAX_GAP_S)?;
        config::in_range("duration_s", self.duration_s, MIN_BIN_S, MAX_TRIAL_S)?;
        config::in_range("bin_s", self.bin_s, MIN_BIN_S, MAX_GAP_S)?;
        config::positive("horizon_s", self.horizon_s)?;
        config::ensure(self.horizon_s / self.bin_s <= MAX_BINS, "bin_s", || {
            format!(
                "gives more than {MAX_BINS} bins over the horizon {} s",
                self.horizon_s
            )
        })?;
        config::ensure(self.horizon_s <= self.hold_s.0, "horizon_s", || {
            format!(
                "{} s exceeds the shortest hold {} s",
                self.horizon_s, self.hold_s.0
            )
        })?;
        config::ensure(self.bin_s <= self.horizon_s, "bin_s", || {
            format!("{} s exceeds the horizon {} s", self.bin_s, self.horizon_s)
        })
    }
}

/// Experiment A's result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrackingResult {
    /// The reference both controllers followed.
    pub reference: ReferenceSchedule,
    /// Both runs.
    pub runs: ModelAndLearned,
    /// F_E statistics by time since a change, model.
    pub model: AlignedStats,
    /// F_E statistics by time since a change, learned.
    pub learned: AlignedStats,
}

/// Runs experiment A.
pub fn run(
    settings: &Settings,
    protocol: &TrackingProtocol,
    seed: u64,
    learner: &(impl LearnerFactory + Sync),
) -> Result<TrackingResult, ExperimentError> {
    settings.validate()?;
    protocol
        .validate()
        .map_err(|e| e.within("protocols.tracking"))?;
    // At least enough time for a few changes, whatever the scale.
    let duration = (protocol.duration_s * settings.scale).max(4.0 * protocol.hold_s.1);
    let reference = ReferenceSchedule::random(seed, duration, protocol.reference, protocol.hold_s)?;
    let setup = settings.trial(
        WalkerMode::CaptureStep,
        reference.clone(),
        Vec::new(),
        [1.0, 0.0, 0.0],
        duration,
    );
    let runs = run_model_and_learned(&setup, learner)?;
    let changes = reference.change_times();
    let stats = |log: &TrialLog| {
        let samples: Vec<(f64, f64)> = log.steps.iter().map(|s| (s.time, s.f_e())).collect();
        AlignedStats::compute(&samples, &changes, protocol.bin_s, protocol.horizon_s)
    };
    Ok(TrackingResult {
        model: stats(&runs.model)?,
        learned: stats(&runs.learned)?,
        reference,
        runs,
    })
}

/// A's trial for `seed`, as [`run`] builds it (the same for the model and, with the run's
/// learner, the learned walker): walking after the protocol's random reference, no pushes.
/// For replays and probes that run it with their own observers.
pub fn trial_setup(
    settings: &Settings,
    protocol: &TrackingProtocol,
    seed: u64,
) -> Result<crate::experiments::trial::TrialSetup, ExperimentError> {
    let duration = (protocol.duration_s * settings.scale).max(4.0 * protocol.hold_s.1);
    let reference = ReferenceSchedule::random(seed, duration, protocol.reference, protocol.hold_s)?;
    Ok(settings.trial(
        WalkerMode::CaptureStep,
        reference,
        Vec::new(),
        [1.0, 0.0, 0.0],
        duration,
    ))
}

impl TrackingResult {
    /// The standard deviation of F_E per bin for (model, learned); `None` where fewer than two
    /// of that controller's steps fell into the bin.
    pub fn std_per_bin(&self) -> (Vec<Option<f64>>, Vec<Option<f64>>) {
        let pick = |st: &AlignedStats| -> Vec<Option<f64>> {
            st.std
                .iter()
                .zip(&st.count)
                .map(|(s, c)| (*c >= 2).then_some(*s))
                .collect()
        };
        (pick(&self.model), pick(&self.learned))
    }

    /// Writes `tracking_steps.csv` (every step of both controllers), `tracking_aligned.csv`
    /// (mean, std and count per bin), `tracking_std.svg` (Fig. 4 left: mean and std of F_E
    /// against the time since a change) and `tracking_series.svg` (Fig. 4 right: reference and
    /// measured step sizes over the first minute).
    pub fn write(&self, dir: &Path) -> Result<(), ExperimentError> {
        std::fs::create_dir_all(dir).map_err(|e| ReportError::io(dir, e))?;
        self.runs.write_steps(&dir.join("tracking_steps.csv"))?;
        let mut rows = Vec::new();
        for (controller, st) in [("model", &self.model), ("learned", &self.learned)] {
            for (k, t) in st.times().into_iter().enumerate() {
                rows.push(AlignedRow {
                    controller,
                    time_since_change_s: Fixed(t),
                    mean_f_e_m: Fixed(st.mean[k]),
                    std_f_e_m: Fixed(st.std[k]),
                    steps: st.count[k],
                });
            }
        }
        write_rows(&dir.join("tracking_aligned.csv"), &rows)?;
        // Figure: bins with at least two steps of the controller.
        let cm = |v: Vec<f64>| v.into_iter().map(|v| 100.0 * v).collect::<Vec<_>>();
        let (mt, model_mean, model_std) = self.model.populated(2);
        let (model_mean, model_std) = (cm(model_mean), cm(model_std));
        let (lt, learned_mean, learned_std) = self.learned.populated(2);
        let (learned_mean, learned_std) = (cm(learned_mean), cm(learned_std));
        let mut series = Vec::new();
        if !mt.is_empty() {
            series.push(Series {
                name: "model",
                x: &mt,
                y: &model_mean,
                spread: Some(&model_std),
            });
        }
        if !lt.is_empty() {
            series.push(Series {
                name: "learned",
                x: &lt,
                y: &learned_mean,
                spread: Some(&learned_std),
            });
        }
        line_plot(
            &dir.join("tracking_std.svg"),
            &LinePlot {
                title: "Step size error after a reference change (mean, band: +-1 std)",
                x_label: "time since the change (s)",
                y_label: "F_E (cm)",
                series: &series,
            },
        )?;
        let window = 60.0;
        let series = |log: &TrialLog| -> (Vec<f64>, Vec<f64>) {
            log.steps
                .iter()
                .filter(|s| s.time <= window)
                .map(|s| (s.time, 100.0 * s.f_hat))
                .unzip()
        };
        let (mt, mf) = series(&self.runs.model);
        let (lt, lf) = series(&self.runs.learned);
        let (rt, rf): (Vec<f64>, Vec<f64>) = (0..=(window * 10.0) as usize)
            .map(|i| {
                let t = i as f64 * 0.1;
                (t, 100.0 * self.reference.at(t))
            })
            .unzip();
        let changes: Vec<f64> = self
            .reference
            .change_times()
            .into_iter()
            .filter(|t| *t <= window)
            .collect();
        event_plot(
            &dir.join("tracking_series.svg"),
            &EventPlot {
                title: "Reference and measured step sizes",
                x_label: "time (s)",
                y_label: "step size (cm)",
                series: &[
                    Series {
                        name: "reference F_R",
                        x: &rt,
                        y: &rf,
                        spread: None,
                    },
                    Series {
                        name: "model",
                        x: &mt,
                        y: &mf,
                        spread: None,
                    },
                    Series {
                        name: "learned",
                        x: &lt,
                        y: &lf,
                        spread: None,
                    },
                ],
                secondary: None,
                events: &changes,
                event_label: "reference change",
            },
        )?;
        Ok(())
    }
}

/// Experiment A's part of `summary.json`: the std of the step size error per time bin after
/// a reference change.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackingSummary {
    /// Std of F_E (m) in consecutive bins of `bin_s` after each change; `null` where fewer
    /// than two steps of that controller fell into the bin (e.g. a walker that kept falling).
    pub step_error_std_m: ModelLearned<Vec<Option<f64>>>,
    /// Bin width (s).
    pub bin_s: f64,
}

/// A: a positive bin width, equal-length series, finite non-negative spreads.
impl TypedResult for TrackingSummary {
    const EXPERIMENT: &'static str = NAME;

    fn validate(&self) -> Result<(), ReportError> {
        let (step_error_std_m, bin_s) = (&self.step_error_std_m, &self.bin_s);
        if !(bin_s.is_finite() && *bin_s > 0.0) {
            return Err(ReportError::invalid(format!(
                "bin_s must be finite and > 0, got {bin_s}"
            )));
        }
        if step_error_std_m.model.len() != step_error_std_m.learned.len() {
            return Err(ReportError::invalid(
                "step_error_std_m: model and learned have different lengths",
            ));
        }
        for v in step_error_std_m
            .model
            .iter()
            .chain(&step_error_std_m.learned)
            .flatten()
        {
            finite_non_negative("step_error_std_m", *v)?;
        }
        Ok(())
    }
}

/// Experiment A as a registered [`Experiment`].
#[derive(Debug, Clone, Copy, Default)]
pub struct Tracking;

impl Experiment for Tracking {
    fn name(&self) -> &str {
        NAME
    }

    fn replay(&self) -> Option<&dyn Replayable> {
        Some(self)
    }

    fn description(&self) -> &str {
        "A (Fig. 4): reference tracking; std of the step error after a reference change"
    }

    fn protocol(&self, tables: &ProtocolTables) -> Result<Option<Table>, ConfigError> {
        tables.resolve::<TrackingProtocol>(self.name())
    }

    fn check_result(&self, result: &ExperimentResult) -> Result<(), ReportError> {
        TrackingSummary::from_result(result).map(|_| ())
    }

    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired> {
        claim(runs).over_seeds
    }

    fn headline(&self, runs: &[&Summary]) -> Vec<Headline> {
        let mut model = Vec::new();
        let mut learned = Vec::new();
        for s in runs {
            if let Some(TrackingSummary {
                step_error_std_m, ..
            }) = TrackingSummary::of(s)
            {
                model.extend(step_error_std_m.model.iter().flatten().map(|v| 100.0 * v));
                learned.extend(step_error_std_m.learned.iter().flatten().map(|v| 100.0 * v));
            }
        }
        vec![
            Headline::mean_of("std of F_E, model (cm)", model),
            Headline::mean_of("std of F_E, learned (cm)", learned),
        ]
    }

    fn apply_push_options(
        &self,
        _protocols: &mut ProtocolTables,
        options: &PushOptions,
    ) -> Result<(), PushOptionsError> {
        if !options.is_empty() {
            return Err(PushOptionsError::NoPushes {
                experiment: self.name().to_string(),
            });
        }
        Ok(())
    }

    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError> {
        let p: TrackingProtocol = ctx.protocols.get(self.name())?;
        let p = &p;
        let r = run(ctx.settings, p, ctx.seed, &|| ctx.make_step_learner())?;
        r.write(dir)?;
        let (model, learned) = r.std_per_bin();
        Ok(TrackingSummary {
            step_error_std_m: ModelLearned { model, learned },
            bin_s: p.bin_s,
        }
        .into_result()?)
    }
}

impl Replayable for Tracking {
    /// The learned and model walkers through the run's reference changes (no pushes).
    fn replay_plan(
        &self,
        settings: &Settings,
        protocols: &ProtocolTables,
        seed: u64,
    ) -> Result<ReplayPlan, ExperimentError> {
        let p: TrackingProtocol = protocols.get(NAME)?;
        let setup = trial_setup(settings, &p, seed)?;
        Ok(ReplayPlan::Trials {
            walkers: vec![
                ReplayWalker::new("learned", setup.clone(), true),
                ReplayWalker::new("model", setup, false),
            ],
            direction: [1.0, 0.0, 0.0],
            after_push_s: 0.0,
            pushes: false,
        })
    }

    /// The largest reference change in the run's first two minutes, from 1 s before it to
    /// the protocol's horizon after it.
    fn telling_moment(
        &self,
        settings: &Settings,
        protocols: &ProtocolTables,
        seed: u64,
        _dir: &Path,
    ) -> Result<(Moment, String), ExperimentError> {
        let protocol: TrackingProtocol = protocols.get(NAME)?;
        let setup = trial_setup(settings, &protocol, seed)?;
        let reference = &setup.reference;
        let last = (setup.duration_s - protocol.horizon_s).min(120.0);
        let jump = |t: f64| (reference.at(t) - reference.at(t - 1e-6)).abs();
        let change = reference
            .change_times()
            .into_iter()
            .filter(|&t| t >= 1.0 && t <= last)
            .max_by(|&a, &b| jump(a).total_cmp(&jump(b)))
            .ok_or_else(|| {
                ExperimentError::NothingToMeasure("no reference change to replay".into())
            })?;
        let (from, to) = (round(change - 1.0), round(change + protocol.horizon_s));
        Ok((
            Moment::Span(from, to),
            format!(
                "the reference change at {change:.2} s (F_R {:.3} to {:.3} m), {from}..{to} s",
                reference.at(change - 1e-6),
                reference.at(change)
            ),
        ))
    }
}

/// A row of `tracking_aligned.csv`: one controller's step error in one bin after a reference
/// change.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
struct AlignedRow<'a> {
    controller: &'a str,
    time_since_change_s: Fixed<3>,
    mean_f_e_m: Fixed<6>,
    std_f_e_m: Fixed<6>,
    steps: usize,
}

/// Claim 1, checked on `runs` (this experiment's summaries, any order): with learning, the
/// std of the step error is below the model's in every time bin after a reference change but
/// at most one, on every seed; paired over seeds bin by bin.
pub fn claim(runs: &[&Summary]) -> Claim {
    let mut seeds = Vec::new();
    let mut bin_diff: Vec<Vec<f64>> = Vec::new();
    let mut bin_s_all = f64::NAN;
    for (seed, (std, bin_s)) in by_seed(runs, bins) {
        let (m, l) = (&std.model, &std.learned);
        let better = m
            .iter()
            .zip(l)
            .filter(|(m, l)| matches!((m, l), (Some(m), Some(l)) if l < m))
            .count();
        bin_s_all = bin_s;
        if bin_diff.len() < m.len() {
            bin_diff.resize(m.len(), Vec::new());
        }
        for (k, (m, l)) in m.iter().zip(l).enumerate() {
            if let (Some(m), Some(l)) = (m, l) {
                bin_diff[k].push(100.0 * (l - m));
            }
        }
        // Every bin but at most one (the reading of "at every time").
        let holds = !m.is_empty() && better + 1 >= m.len();
        seeds.push((
            seed,
            holds,
            format!("learned std lower in {better} of {} bins", m.len()),
        ));
    }
    // The headline first: each seed's learned - model std averaged over its bins with data.
    let mean_diff: Vec<f64> = by_seed(runs, bins)
        .iter()
        .map(|(_, (std, _))| {
            let d = std
                .model
                .iter()
                .zip(&std.learned)
                .filter_map(|(m, l)| Some(100.0 * (l.as_ref()? - m.as_ref()?)));
            let d = crate::stats::MeanStd::of(d);
            if d.count() == 0 { f64::NAN } else { d.mean() }
        })
        .collect();
    let over_seeds = std::iter::once(Paired::new(
        "std of F_E averaged over the bins after a change, learned - model (cm)",
        &mean_diff,
        0.0,
        Direction::LowerIsBetter,
    ))
    .chain(bin_diff.iter().enumerate().map(|(k, v)| {
        let (a, b) = (k as f64 * bin_s_all, (k + 1) as f64 * bin_s_all);
        Paired::new(
            &format!("std of F_E {a:.1}-{b:.1} s after a change, learned - model (cm)"),
            v,
            0.0,
            Direction::LowerIsBetter,
        )
    }))
    .collect();
    Claim::new(
        "1. With learning, the std of the step error is lower than the model's at every time bin after a reference change, all bins but at most one (every seed).",
        seeds,
        Claim::every,
        over_seeds,
    )
}

/// The std of F_E per bin, (bin centre s, model, learned), averaged over the seeds of `runs`
/// with data in every bin (the bins of the first seed); empty if no seed has.
pub fn std_over_seeds(runs: &[&Summary]) -> Vec<(f64, f64, f64)> {
    let mut sum: Vec<(f64, f64, f64)> = Vec::new();
    let mut n = 0usize;
    for (_, (std, bin_s)) in by_seed(runs, bins) {
        let (m, l) = (&std.model, &std.learned);
        if sum.is_empty() {
            sum = (0..m.len())
                .map(|k| ((k as f64 + 0.5) * bin_s, 0.0, 0.0))
                .collect();
        }
        if sum.len() == m.len() && m.iter().chain(l).all(Option::is_some) {
            for (acc, (m, l)) in sum.iter_mut().zip(m.iter().zip(l)) {
                acc.1 += m.unwrap_or(0.0);
                acc.2 += l.unwrap_or(0.0);
            }
            n += 1;
        }
    }
    if n == 0 {
        return Vec::new();
    }
    sum.into_iter()
        .map(|(t, m, l)| (t, m / n as f64, l / n as f64))
        .collect()
}

/// `tracking_std_over_seeds.svg` in `dir`: the std of F_E (cm) per bin after a reference
/// change, mean over the seeds of `runs` with its 95% band; false when no run has bins.
pub fn figure_over_seeds(dir: &Path, runs: &[&Summary]) -> Result<bool, ReportError> {
    let mut x = Vec::new();
    let (mut model, mut learned): (Vec<Vec<f64>>, Vec<Vec<f64>>) = (Vec::new(), Vec::new());
    for (_, (std, bin_s)) in by_seed(runs, bins) {
        for (k, (m, l)) in std.model.iter().zip(&std.learned).enumerate() {
            if x.len() <= k {
                x.push((k as f64 + 0.5) * bin_s);
                model.push(Vec::new());
                learned.push(Vec::new());
            }
            model[k].extend(m.map(|v| 100.0 * v));
            learned[k].extend(l.map(|v| 100.0 * v));
        }
    }
    band_plot(
        &dir.join("tracking_std_over_seeds.svg"),
        Labels {
            title: "Std of the step error after a reference change",
            x: "time since the change (s)",
            y: "std of F_E (cm)",
            integer_x: false,
            y_range: 0.0..f64::INFINITY,
        },
        &[("model", band(&x, &model)), ("learned", band(&x, &learned))],
    )
}

/// A tracking summary's std of F_E per bin and its bin width.
fn bins(s: &Summary) -> Option<(ModelLearned<Vec<Option<f64>>>, f64)> {
    TrackingSummary::of(s).map(|r| (r.step_error_std_m, r.bin_s))
}
