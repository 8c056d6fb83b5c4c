//! Does a learned step time change undisturbed walking? Walks in place (F_R = 0) without pushes
//! for `--seconds`, once as the model and once with the run's learner of `--learn` (built as
//! `steplearn experiment` builds it: the config's settings, the registry's `lwpr` and
//! `pendulum-cart`, reseeded with the seed), and prints, per walker and per 10 s window after
//! the first 5 s, the steps taken, their mean duration and the mean learned dT at touch-down.
//! A step-time learner whose loop runs away near the gait (docs/learner.md) shows as a dT that
//! drifts and steps that shorten window by window.
//!
//! `cargo run --release -p steplearn-probes --bin learned_cadence -- --learn step-x,step-y,step-time --config FILE [--seconds 60]`

use clap::Parser;
use std::path::PathBuf;
use steplearn::control::LearnSet;
use steplearn::control::{Tick, WalkerMode};
use steplearn::experiments::schedule::ReferenceSchedule;
use steplearn::experiments::trial::{Observer, StepRecord, run_trial};

#[derive(Parser)]
struct Args {
    /// The learned set.
    #[arg(long, default_value = "step-x,step-y,step-time")]
    learn: LearnSet,
    /// Settings file (`steplearn config` format).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Walking time (s).
    #[arg(long, default_value_t = 60.0)]
    seconds: f64,
    /// The learner's seed.
    #[arg(long, default_value_t = 0)]
    seed: u64,
}

/// Every touch-down's time and the learned dT of the last tick before it.
#[derive(Default)]
struct Cadence {
    dt: f64,
    steps: Vec<(f64, f64)>,
}

impl Observer for Cadence {
    fn on_tick(&mut self, _time: f64, tick: &Tick) {
        self.dt = tick.time_offset;
    }
    fn on_step(&mut self, step: &StepRecord) {
        self.steps.push((step.time, self.dt));
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    if !(args.seconds.is_finite() && args.seconds > 15.0) {
        return Err("--seconds must exceed 15".into());
    }
    let mut config = steplearn_probes::config_file(args.config.as_deref())?;
    config.settings.learner.learn = args.learn;
    let settings = &config.settings;
    let setup = settings.trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(0.0),
        Vec::new(),
        [1.0, 0.0, 0.0],
        args.seconds,
    );
    let mut learner = steplearn_probes::builtin_learner(&config, args.seed, args.learn)?;
    let mut model = Cadence::default();
    let log_model = run_trial(&setup, None, &mut [&mut model])?;
    let mut learned = Cadence::default();
    let log_learned = run_trial(&setup, Some(&mut learner), &mut [&mut learned])?;
    println!("walker,window_s,steps,mean_duration_s,mean_dt_s,falls");
    for (name, c, falls) in [
        ("model", &model, log_model.falls.len()),
        ("learned", &learned, log_learned.falls.len()),
    ] {
        let mut from = 5.0;
        while from + 10.0 <= args.seconds + 1e-9 {
            let w: Vec<_> = c
                .steps
                .windows(2)
                .filter(|p| p[1].0 > from && p[1].0 <= from + 10.0)
                .collect();
            let n = w.len().max(1) as f64;
            let dur = w.iter().map(|p| p[1].0 - p[0].0).sum::<f64>() / n;
            let dt = w.iter().map(|p| p[1].1).sum::<f64>() / n;
            println!(
                "{name},{from}-{},{},{dur:.4},{dt:+.4},{falls}",
                from + 10.0,
                w.len()
            );
            from += 10.0;
        }
    }
    Ok(())
}
