//! What happens at the catch step? Runs experiment C's protocol (forward or backward pushes,
//! walking in place) for the model and for a learner of a set of step parameters (LWPR, the
//! pendulum-cart rule for `step-x`, the LIPM step-time rule for `step-time`), and prints, over
//! the steps under way at each push and the catch steps after them (the catch step's command at
//! least 0.1 m beyond the reference): the mean commanded and realised length, the step's
//! duration, the learned dT at its last tick, and each walker's I50.
//!
//! `cargo run --release -p steplearn-probes --bin catch_steps -- --seed 0 --learn step-x,step-time [--backward] [--config FILE]`

use clap::Parser;
use std::path::PathBuf;
use steplearn::approx::ApproxKind;
use steplearn::control::StepLearner;
use steplearn::control::{FootstepLearner, InputGrid};
use steplearn::control::{LearnSet, StepParameter};
use steplearn::control::{Tick, WalkerMode};
use steplearn::experiments::schedule::PushPlan;
use steplearn::experiments::trial::{FallRecord, Observer, PushRecord};
use steplearn::report::fall_rate::impulse_at_50pct_fall;
use steplearn::rules::{LearningRule, PendulumCart, StepTime};
use steplearn_probes::{ProbeError, model_and_learned};

#[derive(Parser)]
struct Args {
    /// Seed of the push sequence.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Pushes per walker (impulse uniform in [0, 20] Ns).
    #[arg(long, default_value_t = 400)]
    pushes: usize,
    /// The learned step parameters.
    #[arg(long, default_value = "step-x")]
    learn: LearnSet,
    /// Push backward instead of forward.
    #[arg(long)]
    backward: bool,
    /// Scale of the step-time rule's gradient (negative: the opposite sign).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    time_scale: f64,
    /// Settings file (`steplearn config` format).
    #[arg(long)]
    config: Option<PathBuf>,
}

/// One touch-down: time, last command (step x, step time, dT), realised step x.
#[derive(Debug, Clone, Copy)]
struct Landing {
    time: f64,
    commanded: f64,
    dt: f64,
    realised: f64,
}

#[derive(Default)]
struct Recorder {
    last: (f64, f64),
    landings: Vec<Landing>,
    pushes: Vec<PushRecord>,
    falls: Vec<f64>,
}

impl Observer for Recorder {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        if let Some(step) = &tick.step {
            self.landings.push(Landing {
                time,
                commanded: self.last.0,
                dt: self.last.1,
                realised: step.f_e + step.f_r,
            });
        }
        if let Some(d) = tick.decision {
            self.last = (d.step[0], d.time_offset);
        }
    }
    fn on_push(&mut self, push: &PushRecord) {
        self.pushes.push(*push);
    }
    fn on_fall(&mut self, fall: &FallRecord) {
        self.falls.push(fall.time);
    }
}

fn report(name: &str, r: &Recorder) -> Result<(), Box<dyn std::error::Error>> {
    let samples: Vec<(f64, bool)> = r.pushes.iter().map(|p| (p.impulse, p.fell)).collect();
    let i50 = impulse_at_50pct_fall(&samples)?.impulse_ns;
    println!("{name}: I50 {i50:.2} Ns");
    let calm: Vec<&Landing> = r
        .landings
        .iter()
        .filter(|l| {
            l.time > 3.0
                && !r
                    .pushes
                    .iter()
                    .any(|p| l.time > p.time - 0.1 && l.time < p.time + 2.5)
        })
        .collect();
    let n = calm.len().max(1) as f64;
    println!(
        "  undisturbed ({} steps): commanded {:+.4} m, realised {:+.4} m",
        calm.len(),
        calm.iter().map(|l| l.commanded).sum::<f64>() / n,
        calm.iter().map(|l| l.realised).sum::<f64>() / n
    );
    let mut pushes = r.pushes.clone();
    pushes.sort_by(|a, b| a.time.total_cmp(&b.time));
    for (which, offset) in [("under way", 0usize), ("catch", 1)] {
        let mut sums = [0.0; 4];
        let mut n = 0;
        for p in &pushes {
            let first = r.landings.partition_point(|l| l.time <= p.time);
            let (Some(prev), Some(l)) = (
                r.landings
                    .get(first + offset - 1)
                    .filter(|_| first + offset > 0),
                r.landings.get(first + offset),
            ) else {
                continue;
            };
            if r.falls.iter().any(|&t| t > p.time && t <= l.time) || l.commanded.abs() < 0.1 {
                continue;
            }
            sums[0] += l.commanded;
            sums[1] += l.realised;
            sums[2] += l.time - prev.time;
            sums[3] += l.dt;
            n += 1;
        }
        let m = |i: usize| sums[i] / n.max(1) as f64;
        println!(
            "  {which} ({n} steps): commanded {:+.3} m, realised {:+.3} m, duration {:.3} s, dT {:+.3} s",
            m(0),
            m(1),
            m(2),
            m(3)
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let settings = steplearn_probes::settings(args.config.as_deref()).map_err(|e| e.to_string())?;
    let plan = PushPlan {
        count: args.pushes,
        impulse: (0.0, 20.0),
        settle: 3.0,
        gap: (3.0, 4.0),
    };
    let direction = if args.backward {
        [-1.0, 0.0, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let setup = settings.push_trial(WalkerMode::CaptureStep, 0.0, &plan, args.seed, direction);
    let bounds = InputGrid::default().input_box()?;
    let (model, learned) = model_and_learned::<Recorder>(&setup, || {
        let learners = args
            .learn
            .iter()
            .map(|p| {
                let rule: Box<dyn LearningRule> = match p {
                    StepParameter::StepTime => Box::new(StepTime {
                        scale: args.time_scale,
                        ..StepTime::default()
                    }),
                    _ => Box::new(PendulumCart::default()),
                };
                Ok((
                    p,
                    FootstepLearner::new(ApproxKind::Lwpr.build(&bounds)?, rule, settings.learner)?,
                ))
            })
            .collect::<Result<Vec<_>, ProbeError>>()?;
        Ok(Box::new(StepLearner::new(learners)?))
    })?;
    report("model", &model)?;
    report(&format!("learned {}", args.learn), &learned)?;
    Ok(())
}
