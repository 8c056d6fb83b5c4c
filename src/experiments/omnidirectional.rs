//! Beyond the paper: push recovery from every direction with a lateral learner beside the
//! sagittal one (the paper's future work: "two uncoupled learners").
//!
//! Stepping in place, the walker is pushed from 8 azimuths (0 = forward, counter-clockwise,
//! 45 degrees apart), each sector with its own pushes of random impulse over the protocol's
//! range at random gait phases, the same pushes for four walkers: open-loop, the Capture Step
//! model, the model with the paper's sagittal learner, and the model with both learners
//! ([`TwoPlanes`]: the sagittal learner and a lateral one of the same approximator and rule).
//! Each walker learns afresh in each sector. Per sector and walker: the impulse at 50% falls
//! (I50, as in experiment C) and the falls per cause. Registered as `omnidirectional`; its
//! result is a [`CustomResult`], as a user's experiment would write it.

use super::error::ExperimentError;
use super::experiment::{Experiment, Headline, PushOptions, RunContext};
use super::fall_causes::{count, run_classified};
use super::paired::{Direction, Paired};
use super::protocol::{Protocol, ProtocolTables, Table};
use super::schedule::PushPlan;
use super::summary::{CustomResult, ExperimentResult, Summary};
use crate::config::limits::{MAX_GAP_S, MAX_IMPULSE_NS, MAX_PUSHES};
use crate::config::{self, ConfigError};
use crate::control::two_planes::TwoPlanes;
use crate::control::walker::{FootstepPolicy, WalkerMode};
use crate::report::fall_rate::{PushResult, impulse_at_50pct_fall};
use crate::report::figures::{PolarPlot, Series, polar_plot};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The number of push sectors.
pub const SECTORS: usize = 8;

/// The walkers compared, in the order of the summary's lists.
pub const WALKERS: [&str; 4] = ["open_loop", "model", "sagittal", "both"];

/// The protocol: per sector, `pushes` pushes (scaled by the run's scale, at least 2) uniform
/// in `impulse`, `gap_s` apart, walking in place.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OmnidirectionalProtocol {
    /// Pushes per sector and walker at scale 1.
    pub pushes: usize,
    /// Impulse range (Ns).
    pub impulse: (f64, f64),
    /// Time between pushes (s).
    pub gap_s: (f64, f64),
}

impl Default for OmnidirectionalProtocol {
    fn default() -> Self {
        OmnidirectionalProtocol {
            pushes: 100,
            impulse: (0.0, 20.0),
            gap_s: (3.0, 4.0),
        }
    }
}

impl Protocol for OmnidirectionalProtocol {
    fn validate(&self) -> Result<(), ConfigError> {
        config::count_in("pushes", self.pushes, 1, MAX_PUSHES)?;
        config::non_negative_range("impulse", self.impulse)?;
        config::range_in("impulse", self.impulse, 0.0, MAX_IMPULSE_NS)?;
        config::positive_range("gap_s", self.gap_s)?;
        config::range_in("gap_s", self.gap_s, 0.0, MAX_GAP_S)
    }
}

/// One run's result, as `summary.json` holds it beside the common fields: per walker a list
/// over the sectors.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OmnidirectionalResult {
    /// The sectors' azimuths (degrees; 0 forward, counter-clockwise).
    pub sectors_deg: Vec<f64>,
    /// Pushes delivered per sector (the same for every walker).
    pub pushes: Vec<usize>,
    /// Impulse at 50% falls per walker (`open_loop`, `model`, `sagittal`, `both`), per sector
    /// (Ns).
    pub i50_ns: BTreeMap<String, Vec<f64>>,
    /// Pushes that ended in a fall, per walker and sector.
    pub falls: BTreeMap<String, Vec<usize>>,
    /// Falls per cause (experiment C's classes), per walker and sector.
    pub fall_causes: BTreeMap<String, Vec<BTreeMap<String, u32>>>,
}

impl OmnidirectionalResult {
    /// `walker`'s I50 over `model`'s, per sector (NaN where either is missing).
    pub fn ratio_to_model(&self, walker: &str) -> Vec<f64> {
        let get = |w: &str| self.i50_ns.get(w).cloned().unwrap_or_default();
        let (w, m) = (get(walker), get("model"));
        (0..SECTORS)
            .map(|k| match (w.get(k), m.get(k)) {
                (Some(a), Some(b)) if *b > 0.0 => a / b,
                _ => f64::NAN,
            })
            .collect()
    }
}

/// One row of `omnidirectional_pushes.csv`.
#[derive(Debug, Default, Serialize)]
struct PushRow {
    azimuth_deg: f64,
    walker: &'static str,
    time_s: f64,
    impulse_ns: f64,
    fell: bool,
}

/// The unit push direction of azimuth `deg` (0 forward, 90 left).
pub fn direction(deg: f64) -> [f64; 3] {
    let a = deg.to_radians();
    // Exact axes where the azimuth is a multiple of 90 degrees.
    let snap = |v: f64| if v.abs() < 1e-12 { 0.0 } else { v };
    [snap(a.cos()), snap(a.sin()), 0.0]
}

/// The experiment, registered as `omnidirectional`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Omnidirectional;

fn parse(runs: &[&Summary]) -> Vec<OmnidirectionalResult> {
    runs.iter()
        .filter_map(|s| match &s.result {
            ExperimentResult::Custom(c) => c.parse::<OmnidirectionalResult>().ok(),
            _ => None,
        })
        .collect()
}

impl Experiment for Omnidirectional {
    fn name(&self) -> &str {
        "omnidirectional"
    }

    fn description(&self) -> &str {
        "beyond the paper: I50 from 8 push directions, model vs sagittal vs both learners"
    }

    fn protocol(&self, tables: &ProtocolTables) -> Result<Option<Table>, ConfigError> {
        tables.resolve::<OmnidirectionalProtocol>(self.name())
    }

    fn apply_push_options(
        &self,
        protocols: &mut ProtocolTables,
        options: &PushOptions,
    ) -> Result<(), String> {
        if options.direction.is_some() {
            return Err(format!(
                "{} pushes from every direction: --push-direction does not apply",
                self.name()
            ));
        }
        let mut p: OmnidirectionalProtocol =
            protocols.get(self.name()).map_err(|e| e.to_string())?;
        p.pushes = options.pushes.unwrap_or(p.pushes);
        p.impulse = options.impulse_range.unwrap_or(p.impulse);
        protocols.set(self.name(), &p).map_err(|e| e.to_string())
    }

    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError> {
        let p: OmnidirectionalProtocol = ctx.protocols.get(self.name())?;
        ctx.settings.validate()?;
        p.validate()
            .map_err(|e| e.within(&format!("protocols.{}", self.name())))?;
        let plan = PushPlan {
            count: ctx.settings.scaled(p.pushes, 2),
            impulse: p.impulse,
            settle: 3.0,
            gap: p.gap_s,
        };
        let sectors: Vec<f64> = (0..SECTORS).map(|k| 45.0 * k as f64).collect();
        let jobs: Vec<(usize, usize)> = (0..SECTORS)
            .flat_map(|k| (0..WALKERS.len()).map(move |w| (k, w)))
            .collect();
        let outcomes: Vec<Result<_, ExperimentError>> = jobs
            .par_iter()
            .map(|&(k, w)| {
                // Each sector its own pushes, the same for the four walkers.
                let seed = ctx.seed.wrapping_mul(SECTORS as u64).wrapping_add(k as u64);
                let mode = if w == 0 {
                    WalkerMode::OpenLoop
                } else {
                    WalkerMode::CaptureStep
                };
                let setup = ctx
                    .settings
                    .push_trial(mode, 0.0, &plan, seed, direction(sectors[k]));
                let mut sagittal;
                let mut both;
                let policy: Option<&mut dyn FootstepPolicy> = match w {
                    2 => {
                        sagittal = ctx.make_learner()?;
                        Some(&mut sagittal)
                    }
                    3 => {
                        both = TwoPlanes {
                            sagittal: ctx.make_learner()?,
                            lateral: ctx.make_learner()?,
                        };
                        Some(&mut both)
                    }
                    _ => None,
                };
                let (log, falls) = run_classified(&setup, policy)?;
                let samples: Vec<PushResult> =
                    log.pushes.iter().map(|p| (p.impulse, p.fell)).collect();
                let i50 = impulse_at_50pct_fall(&samples)?.impulse_ns;
                let fell = log.pushes.iter().filter(|p| p.fell).count();
                Ok((log.pushes, i50, fell, count(&falls)))
            })
            .collect();
        let mut result = OmnidirectionalResult {
            sectors_deg: sectors.clone(),
            pushes: vec![0; SECTORS],
            i50_ns: BTreeMap::new(),
            falls: BTreeMap::new(),
            fall_causes: BTreeMap::new(),
        };
        let mut rows: Vec<PushRow> = Vec::new();
        for (&(k, w), outcome) in jobs.iter().zip(outcomes) {
            let (pushes, i50, fell, causes) = outcome?;
            let name = WALKERS[w].to_string();
            result.pushes[k] = pushes.len();
            result.i50_ns.entry(name.clone()).or_default().push(i50);
            result.falls.entry(name.clone()).or_default().push(fell);
            result.fall_causes.entry(name).or_default().push(causes);
            rows.extend(pushes.iter().map(|push| PushRow {
                azimuth_deg: sectors[k],
                walker: WALKERS[w],
                time_s: push.time,
                impulse_ns: push.impulse,
                fell: push.fell,
            }));
        }
        crate::report::write_rows(&dir.join("omnidirectional_pushes.csv"), &rows)?;
        let series: Vec<(String, Vec<f64>)> = WALKERS
            .iter()
            .map(|w| {
                let v = result.i50_ns[*w].iter().map(|v| v.max(0.0)).collect();
                (w.replace('_', "-"), v)
            })
            .collect();
        let series: Vec<Series> = series
            .iter()
            .map(|(name, y)| Series {
                name,
                x: &sectors,
                y,
                spread: None,
            })
            .collect();
        polar_plot(
            &dir.join("omnidirectional_i50.svg"),
            &PolarPlot {
                title: "Impulse at 50% falls by push direction",
                radius_label: "I50 (Ns)",
                series: &series,
            },
        )?;
        Ok(ExperimentResult::Custom(CustomResult::new(
            self.name(),
            &result,
        )?))
    }

    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired> {
        let runs = parse(runs);
        let mut out = Vec::new();
        for walker in ["both", "sagittal"] {
            let ratios: Vec<Vec<f64>> = runs.iter().map(|r| r.ratio_to_model(walker)).collect();
            // The ratio of the sectors' mean I50s: a sector where the model's I50 is near 0
            // does not dominate it, as it would a mean of ratios.
            let mean: Vec<f64> = runs
                .iter()
                .map(|r| {
                    let sum = |w: &str| r.i50_ns.get(w).map_or(f64::NAN, |v| v.iter().sum());
                    sum(walker) / sum("model")
                })
                .collect();
            let worst: Vec<f64> = ratios
                .iter()
                .map(|r| r.iter().copied().fold(f64::INFINITY, f64::min))
                .collect();
            out.push(Paired::new(
                &format!("I50 {walker} / model, sectors' mean"),
                &mean,
                1.0,
                Direction::HigherIsBetter,
            ));
            out.push(Paired::new(
                &format!("I50 {walker} / model, worst sector"),
                &worst,
                1.0,
                Direction::HigherIsBetter,
            ));
        }
        out
    }

    fn headline(&self, runs: &[&Summary]) -> Vec<Headline> {
        let runs = parse(runs);
        let mean_i50 = |w: &str| -> Vec<f64> {
            runs.iter()
                .filter_map(|r| {
                    let v = r.i50_ns.get(w)?;
                    Some(v.iter().sum::<f64>() / v.len().max(1) as f64)
                })
                .collect()
        };
        vec![
            Headline::mean_of("I50 model, mean over sectors (Ns)", mean_i50("model")),
            Headline::mean_of("I50 sagittal, mean over sectors (Ns)", mean_i50("sagittal")),
            Headline::mean_of("I50 both, mean over sectors (Ns)", mean_i50("both")),
        ]
    }
}
