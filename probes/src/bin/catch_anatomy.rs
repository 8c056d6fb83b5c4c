//! Why is the catch step's reach (`catch_step_reach` of experiment C) what it is? Runs C's
//! model and learned trials exactly as `steplearn experiment stability` builds them (the
//! config's settings and `[protocols.stability]`, the learner from the registry's `lwpr` and
//! `pendulum-cart`, reseeded with the seed) and writes one CSV row per push and walker: the
//! impulse, whether it fell, whether the push counts for the reach and its ratio (as
//! `steplearn::experiments::catch_step`), and for the step under way at the push, the catch
//! step and the step after it: the length commanded at the step's first tick and at its last
//! tick (and at half and three quarters of its duration, the share of the step after which it
//! last had the other sign, the placement the motion generator got, how long before the
//! touch-down the generator exchanged its legs and the command it released the swing foot at),
//! the last tick's analytic part and learned dF and dT, the step time planned and the dT
//! at the first tick, the
//! duration, the realised length and F_R. The `lib_` columns are the catch step as the library
//! counts it (`catch_step_reach`: the command at release where the generator exchanged its legs
//! first, the realised length, the time since the touch-down before). Prints each walker's reach
//! against the last tick's command beside the library's and the counted pushes split by their
//! ratio; `--trace T0 T1` prints the model walker's ticks between two times.
//!
//! `cargo run --release -p steplearn-probes --bin catch_anatomy -- --seed 0 --learn step-x,step-time [--backward] [--pushes 400] [--config FILE] [--csv FILE] [--trace T0 T1]`

use clap::Parser;
use std::fmt::Write as _;
use std::path::PathBuf;
use steplearn::control::LearnSet;
use steplearn::control::{Tick, WalkerMode};
use steplearn::experiments::catch_step::{
    MIN_CATCH_BEYOND_REFERENCE, catch_step_reach, catch_steps,
};
use steplearn::experiments::fall_causes::FallCauseObserver;
use steplearn::experiments::stability::{self, StabilityProtocol};
use steplearn::experiments::trial::{FallRecord, Observer, TrialSetup, run_trial};

#[derive(Parser)]
struct Args {
    /// Seed (as `steplearn experiment stability --seed`).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Pushes per walker (default: the config's protocol, 400).
    #[arg(long)]
    pushes: Option<usize>,
    /// The learned step parameters.
    #[arg(long, default_value = "step-x,step-time")]
    learn: LearnSet,
    /// Push backward instead of forward.
    #[arg(long)]
    backward: bool,
    /// Settings and protocols (`steplearn config` format).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Where to write the per-push CSV (default: stdout after the summary).
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Print the model walker's ticks between these two times (s): estimator support, the
    /// generator's support, feet x relative to the CoM, CoM x and velocity, pitch, command.
    #[arg(long, num_args = 2)]
    trace: Option<Vec<f64>>,
}

/// One step, at its touch-down.
#[derive(Debug, Clone, Copy, Default)]
struct Landing {
    time: f64,
    /// Last tick's command: step x, its analytic part, learned dF, dT, time to step.
    commanded: f64,
    analytic: f64,
    df: f64,
    dt: f64,
    /// The command, step time planned (s) and dT at the step's first tick.
    first_commanded: f64,
    planned_t: f64,
    planned_dt: f64,
    /// The command at half and three quarters of the step's duration, and the share of the
    /// duration after which the command last had the other sign than at touch-down (0: never).
    half_commanded: f64,
    late_commanded: f64,
    flip: f64,
    /// The sagittal placement the motion generator was given at the last tick.
    generator: f64,
    /// How long before this touch-down (the estimator's) the generator exchanged its legs
    /// (the controller's support changed) within the step (s; NaN: it had not yet), and the
    /// command of the tick before that exchange: where the swing foot was sent when the
    /// generator let it go.
    lead: f64,
    released: f64,
    realised: f64,
    f_r: f64,
    /// Whether the step had a decision (a step after a reset may not).
    decided: bool,
}

#[derive(Default)]
struct Recorder {
    last: Option<Landing>,
    start: Option<(f64, f64, f64)>,
    landings: Vec<Landing>,
    falls: Vec<f64>,
    /// The current step's (time, command) per tick.
    path: Vec<(f64, f64)>,
    /// The controller's support foot at the last tick, and the last generator exchange within
    /// the current step: (time, command the tick before).
    support: Option<steplearn::robot::Side>,
    exchange: Option<(f64, f64)>,
    /// The window to trace and the traced lines.
    trace: Option<(f64, f64)>,
    lines: String,
}

/// The command at `time` along `path` (the last tick at or before it).
fn command_at(path: &[(f64, f64)], time: f64) -> f64 {
    let i = path.partition_point(|p| p.0 <= time);
    path.get(i.saturating_sub(1)).map_or(f64::NAN, |p| p.1)
}

impl Observer for Recorder {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        if let Some((t0, t1)) = self.trace
            && time >= t0
            && time <= t1
        {
            let e = &tick.estimate;
            let _ = writeln!(
                self.lines,
                "t {time:.3} est {:?} gen {:?} feetx L {:+.3} R {:+.3} comx {:+.3} v {:+.3} pitch {:+.3} cmd {:+.3} T {:.3} td {}",
                e.support,
                tick.decision.map(|d| d.support),
                e.feet[0][0],
                e.feet[1][0],
                e.com[0].pos,
                e.com[0].vel,
                e.pitch,
                tick.command.step_x,
                tick.command.step_time,
                tick.step
                    .map_or(String::new(), |s| format!("realised {:+.3}", s.f_e + s.f_r)),
            );
        }
        if let Some(step) = &tick.step {
            let mut l = self.last.unwrap_or_default();
            l.decided = self.last.is_some();
            l.time = time;
            l.realised = step.f_e + step.f_r;
            l.f_r = step.f_r;
            (l.first_commanded, l.planned_t, l.planned_dt) =
                self.start.unwrap_or((f64::NAN, f64::NAN, f64::NAN));
            if let Some(&(t0, _)) = self.path.first() {
                let d = time - t0;
                l.half_commanded = command_at(&self.path, t0 + 0.5 * d);
                l.late_commanded = command_at(&self.path, t0 + 0.75 * d);
                l.flip = self
                    .path
                    .iter()
                    .rev()
                    .find(|p| p.1 * l.commanded < 0.0)
                    .map_or(0.0, |p| (p.0 - t0) / d);
            } else {
                (l.half_commanded, l.late_commanded, l.flip) = (f64::NAN, f64::NAN, f64::NAN);
            }
            (l.lead, l.released) = match self.exchange {
                Some((t, c)) => (time - t, c),
                None => (f64::NAN, l.commanded),
            };
            self.landings.push(l);
            self.start = None;
            self.path.clear();
            self.exchange = None;
        }
        if let Some(d) = tick.decision {
            if self.support.is_some_and(|s| s != d.support) && tick.step.is_none() {
                self.exchange = Some((time, self.last.map_or(f64::NAN, |l| l.commanded)));
            }
            self.support = Some(d.support);
        }
        let generator = tick.command.step_x;
        self.last = tick.decision.map(|d| Landing {
            commanded: d.step[0],
            analytic: d.analytic_step_x,
            df: d.learned_offset,
            dt: d.time_offset,
            generator,
            ..Landing::default()
        });
        if let Some(d) = tick.decision {
            self.path.push((time, d.step[0]));
        }
        if self.start.is_none()
            && let Some(d) = tick.decision
        {
            self.start = Some((d.step[0], d.time_to_step, d.time_offset));
        }
    }
    fn on_fall(&mut self, fall: &FallRecord) {
        self.falls.push(fall.time);
        self.last = None;
        self.start = None;
        self.path.clear();
        self.exchange = None;
        self.support = None;
    }
}

fn run(
    setup: &TrialSetup,
    policy: Option<&mut (dyn steplearn::control::FootstepPolicy + '_)>,
    name: &str,
    csv: &mut String,
    out: &mut String,
    trace: Option<(f64, f64)>,
) -> Result<(), Box<dyn std::error::Error>> {
    let mut rec = Recorder {
        trace: trace.filter(|_| name == "model"),
        ..Recorder::default()
    };
    let mut causes = FallCauseObserver::new();
    let log = run_trial(setup, policy, &mut [&mut rec, &mut causes])?;
    let library = catch_step_reach(causes.events(), &log.pushes);
    // The library's catch step of each push, for its per-push row.
    let lib = catch_steps(causes.events(), &log.pushes);
    let l = &rec.landings;
    let mut sum = 0.0;
    let mut n = 0;
    // Counted pushes split by the catch step's realised / commanded ratio.
    let mut bins = [(0usize, 0.0f64); 4];
    for (k, p) in log.pushes.iter().enumerate() {
        let next_push = log.pushes.get(k + 1).map_or(f64::INFINITY, |q| q.time);
        let first = l.partition_point(|x| x.time <= p.time);
        let (prev, under, catch, after) = (
            first.checked_sub(1).and_then(|i| l.get(i)),
            l.get(first),
            l.get(first + 1),
            l.get(first + 2),
        );
        let mut counted = false;
        let mut ratio = f64::NAN;
        if let Some(c) = catch {
            let fell = rec.falls.iter().any(|&t| t > p.time && t <= c.time);
            if c.decided
                && !fell
                && c.time < next_push
                && (c.commanded - c.f_r).abs() >= MIN_CATCH_BEYOND_REFERENCE
                && c.commanded != 0.0
            {
                counted = true;
                ratio = c.realised / c.commanded;
                sum += ratio;
                n += 1;
                let b = if ratio < 0.0 {
                    0
                } else if ratio < 0.5 {
                    1
                } else if ratio < 1.0 {
                    2
                } else {
                    3
                };
                bins[b].0 += 1;
                bins[b].1 += ratio;
            }
        }
        write!(
            csv,
            "{name},{k},{:.3},{:.3},{},{},{:.4}",
            p.time, p.impulse, p.fell, counted, ratio
        )?;
        // As the library counts it: its command (at release where the generator exchanged
        // first), realised, the time since the touch-down before it.
        match lib[k] {
            Some(c) => write!(
                csv,
                ",{},{:.4},{:.4},{:.4},{:.3}",
                c.counted,
                c.realised / c.commanded,
                c.commanded,
                c.realised,
                c.duration
            )?,
            None => write!(csv, ",false,,,,")?,
        }
        let mut before = prev.map(|x| x.time);
        for s in [under, catch, after] {
            match s {
                Some(s) => {
                    write!(
                        csv,
                        ",{:.3},{:.4},{:.4},{:.4},{:.3},{:.4},{:.4},{:.3},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4}",
                        s.time,
                        s.first_commanded,
                        s.half_commanded,
                        s.late_commanded,
                        s.flip,
                        s.commanded,
                        s.generator,
                        s.lead,
                        s.released,
                        s.analytic,
                        s.df,
                        s.dt,
                        s.planned_t,
                        s.planned_dt,
                        before.map_or(f64::NAN, |b| s.time - b),
                        s.realised,
                        s.f_r
                    )?;
                    before = Some(s.time);
                }
                None => write!(csv, "{}", ",".repeat(17))?,
            }
        }
        writeln!(csv)?;
    }
    out.push_str(&rec.lines);
    let reach = sum / n.max(1) as f64;
    writeln!(
        out,
        "{name}: reach {reach:.4} over {n} pushes (library {:?} over {})",
        library.reach, library.pushes
    )?;
    for (label, (m, s)) in ["<0", "[0,0.5)", "[0.5,1)", ">=1"].iter().zip(bins) {
        writeln!(
            out,
            "  ratio {label:>8}: {m:3} pushes, mean {:+.3}, share of the sum {:+.3}",
            s / m.max(1) as f64,
            s / n.max(1) as f64
        )?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let mut config = steplearn_probes::config_file(args.config.as_deref())?;
    config.settings.learner.learn = args.learn;
    let mut protocol: StabilityProtocol = config.protocols.get("stability")?;
    if let Some(p) = args.pushes {
        protocol.pushes = p;
    }
    if args.backward {
        protocol.direction = [-1.0, 0.0, 0.0];
    }
    let settings = &config.settings;
    let setup = stability::trial_setup(settings, &protocol, args.seed, WalkerMode::CaptureStep);
    let mut learner = steplearn_probes::builtin_learner(&config, args.seed, args.learn)?;
    let mut csv = String::from(
        "walker,push,time,impulse,fell,counted,ratio,lib_counted,lib_ratio,lib_commanded,lib_realised,lib_duration",
    );
    for s in ["under", "catch", "after"] {
        for c in [
            "time",
            "first_commanded",
            "half_commanded",
            "late_commanded",
            "flip",
            "commanded",
            "generator",
            "lead",
            "released",
            "analytic",
            "df",
            "dt",
            "planned_t",
            "planned_dt",
            "duration",
            "realised",
            "f_r",
        ] {
            write!(csv, ",{s}_{c}")?;
        }
    }
    csv.push('\n');
    let trace = args.trace.as_ref().map(|t| (t[0], t[1]));
    let (mut a, mut b) = (String::new(), String::new());
    let (mut sa, mut sb) = (String::new(), String::new());
    let (model, learned) = rayon::join(
        || run(&setup, None, "model", &mut a, &mut sa, trace).map_err(|e| e.to_string()),
        || {
            run(
                &setup,
                Some(&mut learner),
                "learned",
                &mut b,
                &mut sb,
                trace,
            )
            .map_err(|e| e.to_string())
        },
    );
    model?;
    learned?;
    let o = settings
        .learner
        .offset(steplearn::control::StepParameter::StepTime);
    println!(
        "learner {}: dead zone {} (step-time {}), eta {}",
        args.learn, settings.learner.dead_zone, o.dead_zone, settings.learner.eta
    );
    print!("{sa}{sb}");
    csv.push_str(&a);
    csv.push_str(&b);
    match &args.csv {
        Some(path) => std::fs::write(path, csv)?,
        None => print!("{csv}"),
    }
    Ok(())
}
