//! Beyond the paper: push recovery from every direction with a lateral learner beside the
//! sagittal one (the paper's future work: "two uncoupled learners").
//!
//! Stepping in place, the walker is pushed from 8 azimuths (0 = forward, counter-clockwise,
//! 45 degrees apart), each sector with its own pushes of random impulse over the protocol's
//! range at random gait phases, the same pushes for four walkers: open-loop, the Capture Step
//! model, the model with the paper's sagittal learner, and the model with both learners
//! (a [`StepLearner`](crate::control::StepLearner) of `step-x` and `step-y`: the
//! sagittal learner and a lateral one of the same approximator and rule).
//! With a set of step parameters other than the paper's (`--learn`), a fifth walker, `learned`,
//! learns exactly that set. Each walker learns afresh in each sector. Per sector and walker: the
//! impulse at 50% falls
//! (I50, as in experiment C) and the falls per cause.
//!
//! Then an omnidirectional walk (the paper's Fig. 4 in two dimensions): the reference step
//! `(F_R, F_R,y)` jumps to a point uniform over a disc every 4-8 s, the same sequence for the
//! model and for both learners (learning as they walk). Every step's error is the sagittal
//! step error and the width error against the reference width
//! ([`crate::control::Walker::width_reference`]); per direction sector of the reference,
//! the mean of its norm. Registered as `omnidirectional`; its result is a [`crate::experiments::summary::CustomResult`] written in alphabetical order, as
//! a user's experiment would write it.

use crate::config::limits::{MAX_GAP_S, MAX_STEP_M, MAX_TRIAL_S};
use crate::config::{self, ConfigError};
use crate::control::{FootstepPolicy, Tick, WalkerMode};
use crate::control::{LearnSet, StepParameter};
use crate::experiments::error::ExperimentError;
use crate::experiments::fall_causes::{count, run_classified};
use crate::experiments::paired::{Direction, Paired};
use crate::experiments::protocol::{Protocol, ProtocolTables, Table};
use crate::experiments::schedule::{PushPlan, ReferenceSchedule};
use crate::experiments::summary::{ExperimentResult, Summary};
use crate::experiments::trial::{Observer, PushRecord, TrialLog, run_trial};
use crate::experiments::{Experiment, Headline, PushOptions, PushOptionsError, RunContext};
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

/// The walker that learns the run's set of step parameters (`--learn`), pushed beside
/// [`WALKERS`] when the set is not the paper's `step-x`.
pub const LEARNED_WALKER: &str = "learned";

/// The walkers of the omnidirectional walk, in the order of the summary's lists.
pub const WALK_WALKERS: [&str; 2] = ["model", "both"];

/// The protocol: per sector, `pushes` pushes (scaled by the run's scale, at least 2) uniform
/// in `impulse`, `gap_s` apart, walking in place; then the walk: `walk_s` seconds (scaled, at
/// least four of the longest holds) of references uniform over the disc of `walk_radius`,
/// each held for a time uniform in `walk_hold_s`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OmnidirectionalProtocol {
    /// Pushes per sector and walker at scale 1.
    pub pushes: usize,
    /// Impulse range (Ns).
    pub impulse: (f64, f64),
    /// Time between pushes (s).
    pub gap_s: (f64, f64),
    /// Simulated time of the walk per walker at scale 1 (s).
    pub walk_s: f64,
    /// Radius of the disc of references `(F_R, F_R,y)` (m); the lateral reference is realised
    /// up to `omega - delta` (0.08 m with the default controller).
    pub walk_radius: f64,
    /// How long each reference of the walk is held (s).
    pub walk_hold_s: (f64, f64),
    /// How the walker `both` learns the two planes: two uncoupled learners (the paper's
    /// proposal, the default) or one coupled learner with two outputs over both planes' inputs.
    #[serde(skip_serializing_if = "BothPlanes::is_uncoupled")]
    pub both_planes: BothPlanes,
}

/// How the walker `both` learns its two planes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, strum::Display)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum BothPlanes {
    /// Two learners, one per plane, each from its own plane only (a
    /// [`StepLearner`](crate::control::StepLearner) of `step-x` and `step-y`).
    #[default]
    Uncoupled,
    /// One learner with two outputs (dF, dW) over both planes' inputs
    /// ([`CoupledLearner`](crate::control::coupled::CoupledLearner)).
    Coupled,
}

impl BothPlanes {
    /// Whether this is the default, [`BothPlanes::Uncoupled`] (left out of written tables).
    pub fn is_uncoupled(&self) -> bool {
        *self == BothPlanes::Uncoupled
    }
}

/// The learners of the walker `both`, as the protocol's [`BothPlanes`] asks.
fn both_learners(
    ctx: &RunContext<'_>,
    how: BothPlanes,
) -> Result<Box<dyn FootstepPolicy>, ExperimentError> {
    Ok(match how {
        BothPlanes::Uncoupled => Box::new(ctx.make_learner_of(
            LearnSet::of(&[StepParameter::StepX, StepParameter::StepY]).expect("two parameters"),
        )?),
        BothPlanes::Coupled => Box::new(ctx.make_coupled_learner()?),
    })
}

impl Default for OmnidirectionalProtocol {
    fn default() -> Self {
        OmnidirectionalProtocol {
            pushes: 100,
            impulse: (0.0, 20.0),
            gap_s: (3.0, 4.0),
            walk_s: 450.0,
            walk_radius: 0.08,
            walk_hold_s: (4.0, 8.0),
            both_planes: BothPlanes::Uncoupled,
        }
    }
}

impl Protocol for OmnidirectionalProtocol {
    fn validate(&self) -> Result<(), ConfigError> {
        config::push_series(self.pushes, self.impulse, self.gap_s)?;
        config::in_range("walk_s", self.walk_s, 1.0, MAX_TRIAL_S)?;
        config::in_range("walk_radius", self.walk_radius, 0.0, MAX_STEP_M)?;
        config::positive_range("walk_hold_s", self.walk_hold_s)?;
        config::range_in("walk_hold_s", self.walk_hold_s, 0.0, MAX_GAP_S)
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
    /// The walk: mean norm of the step error `(F_E, W_E)` per walker (`model`, `both`) and
    /// sector of the reference's direction (m; null where no step had its reference there).
    #[serde(default)]
    pub walk_error_m: BTreeMap<String, Vec<Option<f64>>>,
    /// The walk: mean |F_E| (sagittal step error), per walker and sector (m).
    #[serde(default)]
    pub walk_step_error_m: BTreeMap<String, Vec<Option<f64>>>,
    /// The walk: mean |W_E| (width error), per walker and sector (m).
    #[serde(default)]
    pub walk_width_error_m: BTreeMap<String, Vec<Option<f64>>>,
    /// The walk: steps counted per walker and sector.
    #[serde(default)]
    pub walk_steps: BTreeMap<String, Vec<usize>>,
    /// The walk: falls per walker.
    #[serde(default)]
    pub walk_falls: BTreeMap<String, usize>,
    /// How the walker `both` learned its two planes (left out when uncoupled).
    #[serde(default, skip_serializing_if = "BothPlanes::is_uncoupled")]
    pub both_planes: BothPlanes,
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

/// The sector (0..[`SECTORS`]) of the direction of `(x, y)`: sector k is centred on the
/// azimuth `45 k` degrees.
pub fn sector_of(x: f64, y: f64) -> usize {
    let deg = y.atan2(x).to_degrees().rem_euclid(360.0);
    ((deg / 45.0).round() as usize) % SECTORS
}

/// References shorter than this (m) have no direction: their steps are not counted.
const MIN_REFERENCE_M: f64 = 0.01;

/// One step of the walk: the reference `(F_R, F_R,y)`, `F_E` and `W_E` (m); also a row of
/// `omnidirectional_walk.csv`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
struct WalkStep {
    walker: &'static str,
    time_s: f64,
    f_r_m: f64,
    f_r_y_m: f64,
    f_e_m: f64,
    w_e_m: f64,
}

/// Records `walker`'s steps: both planes' outcomes come on the tick of the touch-down.
struct WalkSteps {
    walker: &'static str,
    steps: Vec<WalkStep>,
}

impl Observer for WalkSteps {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        if let (Some(step), Some(lateral)) = (tick.step, tick.lateral_step) {
            self.steps.push(WalkStep {
                walker: self.walker,
                time_s: time,
                f_r_m: tick.f_r,
                f_r_y_m: tick.f_r_y,
                f_e_m: step.f_e,
                w_e_m: lateral.f_e,
            });
        }
    }
}

impl WalkStep {
    /// The sector of the step's reference; none for a reference without a direction.
    fn sector(&self) -> Option<usize> {
        (self.f_r_m.hypot(self.f_r_y_m) >= MIN_REFERENCE_M)
            .then(|| sector_of(self.f_r_m, self.f_r_y_m))
    }
}

/// Per sector: the steps with a reference in that sector, and the mean of `value` over them.
fn by_sector(steps: &[WalkStep], value: impl Fn(&WalkStep) -> f64) -> Vec<(usize, Option<f64>)> {
    let mut sums = [(0usize, 0.0); SECTORS];
    for s in steps {
        if let Some(k) = s.sector() {
            sums[k].0 += 1;
            sums[k].1 += value(s);
        }
    }
    sums.iter()
        .map(|&(n, sum)| (n, (n > 0).then(|| sum / n as f64)))
        .collect()
}

/// The means of [`by_sector`] alone.
fn means_by_sector(steps: &[WalkStep], value: impl Fn(&WalkStep) -> f64) -> Vec<Option<f64>> {
    by_sector(steps, value)
        .into_iter()
        .map(|(_, m)| m)
        .collect()
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

/// Added to the run's seed for the walk's references (the pushes use `seed * 8 + sector`).
const WALK_SEED: u64 = 0x5741_4c4b;

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

/// What one walker did in one sector: its pushes, I50, falls and falls per cause.
struct SectorOutcome {
    pushes: Vec<PushRecord>,
    i50: f64,
    fell: usize,
    causes: BTreeMap<String, u32>,
}

/// Every (sector, walker) job's pushes, in parallel: each sector its own pushes, the same for
/// every walker; walker 0 open-loop, 1 the model, 2 the sagittal learner, 3 both planes' and 4
/// the learner of the run's set.
fn push_sectors(
    ctx: &RunContext<'_>,
    p: &OmnidirectionalProtocol,
    sectors: &[f64],
    jobs: &[(usize, usize)],
) -> Vec<Result<SectorOutcome, ExperimentError>> {
    let plan = PushPlan {
        count: ctx.settings.scaled(p.pushes, 2),
        impulse: p.impulse,
        settle: 3.0,
        gap: p.gap_s,
    };
    jobs.par_iter()
        .map(|&(k, w)| {
            let seed = ctx.seed.wrapping_mul(SECTORS as u64).wrapping_add(k as u64);
            let mode = if w == 0 {
                WalkerMode::OpenLoop
            } else {
                WalkerMode::CaptureStep
            };
            let setup = ctx
                .settings
                .push_trial(mode, 0.0, &plan, seed, direction(sectors[k]));
            let mut learners: Option<Box<dyn FootstepPolicy>> = match w {
                2 => Some(Box::new(ctx.make_learner()?)),
                3 => Some(both_learners(ctx, p.both_planes)?),
                4 => Some(Box::new(ctx.make_step_learner()?)),
                _ => None,
            };
            let policy = learners.as_deref_mut();
            let (log, falls) = run_classified(&setup, policy)?;
            let samples: Vec<PushResult> = log.pushes.iter().map(|p| (p.impulse, p.fell)).collect();
            let i50 = impulse_at_50pct_fall(&samples)?.impulse_ns;
            let fell = log.pushes.iter().filter(|p| p.fell).count();
            Ok(SectorOutcome {
                pushes: log.pushes,
                i50,
                fell,
                causes: count(&falls),
            })
        })
        .collect()
}

/// One walker's walk: its log and its steps.
type WalkOutcome = Result<(TrialLog, Vec<WalkStep>), ExperimentError>;

/// The walk of [`WALK_WALKERS`] through the same random 2-D references, in parallel: each
/// walker's log and steps.
fn walk(
    ctx: &RunContext<'_>,
    p: &OmnidirectionalProtocol,
) -> Result<Vec<WalkOutcome>, ExperimentError> {
    let walk_s = (p.walk_s * ctx.settings.scale).max(4.0 * p.walk_hold_s.1);
    let [walk_x, walk_y] = ReferenceSchedule::random_disc(
        ctx.seed.wrapping_add(WALK_SEED),
        walk_s,
        p.walk_radius,
        p.walk_hold_s,
    )?;
    Ok(WALK_WALKERS
        .par_iter()
        .map(|&walker| {
            let mut setup = ctx.settings.trial(
                WalkerMode::CaptureStep,
                walk_x.clone(),
                Vec::new(),
                [1.0, 0.0, 0.0],
                walk_s,
            );
            setup.lateral_reference = Some(walk_y.clone());
            let mut learners = if walker == "both" {
                Some(both_learners(ctx, p.both_planes)?)
            } else {
                None
            };
            let policy = learners.as_deref_mut();
            let mut steps = WalkSteps {
                walker,
                steps: Vec::new(),
            };
            let log = run_trial(&setup, policy, &mut [&mut steps])?;
            Ok((log, steps.steps))
        })
        .collect())
}

/// Writes each walker's walk figures into `result` (steps while the walker ramps its
/// reference in after a start, before `start_ramp_s`, left out) and returns the steps kept.
fn record_walks(
    result: &mut OmnidirectionalResult,
    walks: Vec<WalkOutcome>,
    start_ramp_s: f64,
) -> Result<Vec<WalkStep>, ExperimentError> {
    let mut walk_rows = Vec::new();
    for (walker, walk) in WALK_WALKERS.iter().zip(walks) {
        let (log, steps) = walk?;
        let steps: Vec<WalkStep> = steps
            .into_iter()
            .filter(|s| s.time_s > start_ramp_s)
            .collect();
        let name = walker.to_string();
        let (counts, errors) = by_sector(&steps, |s| s.f_e_m.hypot(s.w_e_m))
            .into_iter()
            .unzip();
        result.walk_steps.insert(name.clone(), counts);
        result.walk_error_m.insert(name.clone(), errors);
        result
            .walk_step_error_m
            .insert(name.clone(), means_by_sector(&steps, |s| s.f_e_m.abs()));
        result
            .walk_width_error_m
            .insert(name.clone(), means_by_sector(&steps, |s| s.w_e_m.abs()));
        result.walk_falls.insert(name, log.falls.len());
        walk_rows.extend(steps);
    }
    Ok(walk_rows)
}

/// `omnidirectional_i50.svg` (I50 by push direction, every walker) and, where any reference
/// pointed into a sector, `omnidirectional_walk_error.svg`.
fn write_figures(
    dir: &Path,
    result: &OmnidirectionalResult,
    walkers: &[&str],
    sectors: &[f64],
) -> Result<(), ExperimentError> {
    let series: Vec<(String, Vec<f64>)> = walkers
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
            x: sectors,
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
    let errors: Vec<(String, Vec<f64>, Vec<f64>)> = WALK_WALKERS
        .iter()
        .map(|w| {
            let (x, y): (Vec<f64>, Vec<f64>) = result.walk_error_m[*w]
                .iter()
                .zip(sectors)
                .filter_map(|(e, deg)| e.map(|e| (*deg, 100.0 * e)))
                .unzip();
            (w.to_string(), x, y)
        })
        .collect();
    let series: Vec<Series> = errors
        .iter()
        .filter(|(_, x, _)| !x.is_empty())
        .map(|(name, x, y)| Series {
            name,
            x,
            y,
            spread: None,
        })
        .collect();
    if !series.is_empty() {
        polar_plot(
            &dir.join("omnidirectional_walk_error.svg"),
            &PolarPlot {
                title: "Walk: mean step error by reference direction",
                radius_label: "|(F_E, W_E)| (cm)",
                series: &series,
            },
        )?;
    }
    Ok(())
}

fn parse(runs: &[&Summary]) -> Vec<OmnidirectionalResult> {
    runs.iter()
        .filter(|s| s.experiment() == "omnidirectional")
        .filter_map(|s| s.result.parse::<OmnidirectionalResult>().ok())
        .collect()
}

impl Experiment for Omnidirectional {
    fn name(&self) -> &str {
        "omnidirectional"
    }

    fn description(&self) -> &str {
        "beyond the paper: I50 from 8 push directions, model vs sagittal vs both learners; \
         tracking a 2-D reference"
    }

    fn protocol(&self, tables: &ProtocolTables) -> Result<Option<Table>, ConfigError> {
        tables.resolve::<OmnidirectionalProtocol>(self.name())
    }

    fn apply_push_options(
        &self,
        protocols: &mut ProtocolTables,
        options: &PushOptions,
    ) -> Result<(), PushOptionsError> {
        if options.direction.is_some() {
            return Err(PushOptionsError::NotApplicable {
                experiment: self.name().to_string(),
                option: "--push-direction",
                why: "pushes from every direction",
            });
        }
        let mut p: OmnidirectionalProtocol = protocols.get(self.name())?;
        p.pushes = options.pushes.unwrap_or(p.pushes);
        p.impulse = options.impulse_range.unwrap_or(p.impulse);
        Ok(protocols.set(self.name(), &p)?)
    }

    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError> {
        let p: OmnidirectionalProtocol = ctx.protocols.get(self.name())?;
        ctx.settings.validate()?;
        p.validate()
            .map_err(|e| e.within(&format!("protocols.{}", self.name())))?;
        let sectors: Vec<f64> = (0..SECTORS).map(|k| 45.0 * k as f64).collect();
        let learned = !ctx.settings.learner.learn.is_paper();
        let walkers: Vec<&'static str> = WALKERS
            .iter()
            .copied()
            .chain(learned.then_some(LEARNED_WALKER))
            .collect();
        let jobs: Vec<(usize, usize)> = (0..SECTORS)
            .flat_map(|k| (0..walkers.len()).map(move |w| (k, w)))
            .collect();
        let outcomes = push_sectors(ctx, &p, &sectors, &jobs);
        let walks = walk(ctx, &p)?;
        let mut result = OmnidirectionalResult {
            sectors_deg: sectors.clone(),
            pushes: vec![0; SECTORS],
            i50_ns: BTreeMap::new(),
            falls: BTreeMap::new(),
            fall_causes: BTreeMap::new(),
            walk_error_m: BTreeMap::new(),
            walk_step_error_m: BTreeMap::new(),
            walk_width_error_m: BTreeMap::new(),
            walk_steps: BTreeMap::new(),
            walk_falls: BTreeMap::new(),
            both_planes: p.both_planes,
        };
        let walk_rows = record_walks(&mut result, walks, ctx.settings.walker.start_ramp_s)?;
        let mut rows: Vec<PushRow> = Vec::new();
        for (&(k, w), outcome) in jobs.iter().zip(outcomes) {
            let sector = outcome?;
            let name = walkers[w].to_string();
            result.pushes[k] = sector.pushes.len();
            result
                .i50_ns
                .entry(name.clone())
                .or_default()
                .push(sector.i50);
            result
                .falls
                .entry(name.clone())
                .or_default()
                .push(sector.fell);
            result
                .fall_causes
                .entry(name)
                .or_default()
                .push(sector.causes);
            rows.extend(sector.pushes.iter().map(|push| PushRow {
                azimuth_deg: sectors[k],
                walker: walkers[w],
                time_s: push.time,
                impulse_ns: push.impulse,
                fell: push.fell,
            }));
        }
        crate::report::write_rows(&dir.join("omnidirectional_pushes.csv"), &rows)?;
        crate::report::write_rows(&dir.join("omnidirectional_walk.csv"), &walk_rows)?;
        write_figures(dir, &result, &walkers, &sectors)?;
        Ok(ExperimentResult::new(self.name(), &result)?)
    }

    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired> {
        let runs = parse(runs);
        let mut out = Vec::new();
        for walker in ["both", "sagittal", LEARNED_WALKER] {
            if walker == LEARNED_WALKER && !runs.iter().any(|r| r.i50_ns.contains_key(walker)) {
                continue;
            }
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
        // The walk: the sectors' mean error, both learners over the model.
        let walk: Vec<f64> = runs
            .iter()
            .filter_map(|r| {
                let mean = |w: &str| -> Option<f64> {
                    let v: Vec<f64> = r.walk_error_m.get(w)?.iter().flatten().copied().collect();
                    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
                };
                Some(mean("both")? / mean("model")?)
            })
            .collect();
        if !walk.is_empty() {
            out.push(Paired::new(
                "walk error both / model, sectors' mean",
                &walk,
                1.0,
                Direction::LowerIsBetter,
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
        let walk_error = |w: &str| -> Vec<f64> {
            runs.iter()
                .filter_map(|r| {
                    let v: Vec<f64> = r.walk_error_m.get(w)?.iter().flatten().copied().collect();
                    (!v.is_empty()).then(|| 100.0 * v.iter().sum::<f64>() / v.len() as f64)
                })
                .collect()
        };
        vec![
            Headline::mean_of("I50 model, mean over sectors (Ns)", mean_i50("model")),
            Headline::mean_of("I50 sagittal, mean over sectors (Ns)", mean_i50("sagittal")),
            Headline::mean_of("I50 both, mean over sectors (Ns)", mean_i50("both")),
            Headline::mean_of(
                "walk error model, mean over sectors (cm)",
                walk_error("model"),
            ),
            Headline::mean_of(
                "walk error both, mean over sectors (cm)",
                walk_error("both"),
            ),
        ]
    }
}
