//! How much could any learner of `step-x` and `step-time` gain? Runs experiment C's protocol
//! (forward and backward pushes, walking in place) for the model and for fixed, hand-set
//! offset laws of the learner's own inputs (no learning):
//!
//! dF = kx_theta theta_E + kx_rate theta_E_dot,  dT = kt_theta |theta_E| + kt_rate |theta_E_dot|
//!
//! optionally only while |theta_E_dot| is at least a gate
//!
//! (dT negative: sooner). A learner of these parameters can at best converge to some function
//! of those inputs; if no law of this family makes the walker harder to push over than the
//! model, the learner's gradient is not what holds it back. Prints one CSV line per seed,
//! direction and law with both walkers' I50, then per law and direction the mean I50 ratio
//! (law / model, paired by seed) and its 95% interval.
//!
//! `cargo run --release -p steplearn-probes --bin offset_ceiling -- --seeds 0,1,2 --pushes 200 --law 0:0.05:0:-0.03 --law 0:0:0:-0.05`

use clap::Parser;
use rayon::prelude::*;
use std::path::PathBuf;
use std::str::FromStr;
use steplearn::control::LearnerInput;
use steplearn::control::{FootstepPolicy, WalkerMode};
use steplearn::control::{LearnSet, PerParameter, StepParameter};
use steplearn::experiments::schedule::PushPlan;
use steplearn::experiments::trial::run_trial;
use steplearn::report::fall_rate::impulse_at_50pct_fall;
use steplearn::stats::MeanStd;
use steplearn_probes::FixedPolicy;

/// One fixed offset law: `kx_theta:kx_rate:kt_theta:kt_rate[:gate]` (gate: the law acts only
/// while |theta_E_dot| exceeds it, rad/s; 0 by default, always).
#[derive(Debug, Clone, Copy)]
struct Law([f64; 4], f64);

impl FromStr for Law {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let k: Vec<f64> = s
            .split(':')
            .map(|v| v.trim().parse::<f64>().map_err(|e| format!("{v:?}: {e}")))
            .collect::<Result<_, _>>()?;
        match k.as_slice() {
            [a, b, c, d] if k.iter().all(|v| v.is_finite()) => Ok(Law([*a, *b, *c, *d], 0.0)),
            [a, b, c, d, g] if k.iter().all(|v| v.is_finite()) && *g >= 0.0 => {
                Ok(Law([*a, *b, *c, *d], *g))
            }
            _ => Err(format!(
                "a law is four finite numbers kx_theta:kx_rate:kt_theta:kt_rate and an optional \
                 gate >= 0, not {s:?}"
            )),
        }
    }
}

impl std::fmt::Display for Law {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [a, b, c, d] = self.0;
        write!(f, "{a}:{b}:{c}:{d}")?;
        if self.1 > 0.0 {
            write!(f, ":{}", self.1)?;
        }
        Ok(())
    }
}

#[derive(Parser)]
struct Args {
    /// Seeds of the push sequences, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "0,1,2")]
    seeds: Vec<u64>,
    /// Pushes per walker (impulse uniform in [0, 20] Ns).
    #[arg(long, default_value_t = 200)]
    pushes: usize,
    /// A fixed offset law `kx_theta:kx_rate:kt_theta:kt_rate` (repeatable).
    #[arg(long = "law", allow_hyphen_values = true, required = true)]
    laws: Vec<Law>,
    /// Only these directions (`forward`, `backward`; both by default).
    #[arg(long, value_delimiter = ',', default_value = "forward,backward")]
    directions: Vec<String>,
    /// Settings file (`steplearn config` format).
    #[arg(long)]
    config: Option<PathBuf>,
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
    let mut directions = Vec::new();
    for d in &args.directions {
        directions.push(match d.as_str() {
            "forward" => ("forward", 1.0),
            "backward" => ("backward", -1.0),
            other => return Err(format!("unknown direction {other:?}").into()),
        });
    }
    // Every (seed, direction, walker) run; walker None is the model.
    let mut runs = Vec::new();
    for &seed in &args.seeds {
        for &(name, sign) in &directions {
            runs.push((seed, name, sign, None));
            for k in 0..args.laws.len() {
                runs.push((seed, name, sign, Some(k)));
            }
        }
    }
    let i50s: Vec<Result<f64, String>> = runs
        .par_iter()
        .map(|&(seed, _, sign, law)| {
            let setup =
                settings.push_trial(WalkerMode::CaptureStep, 0.0, &plan, seed, [sign, 0.0, 0.0]);
            // The inputs' |theta_E| and |theta_E_dot| at every tick, for their quantiles.
            let mut seen: Vec<[f64; 2]> = Vec::new();
            let mut policy = law.map(|k| {
                let Law([kxa, kxr, kta, ktr], gate) = args.laws[k];
                let seen = &mut seen;
                FixedPolicy {
                    learns: LearnSet::of(&[StepParameter::StepX, StepParameter::StepTime])
                        .expect("two parameters"),
                    offsets: move |inputs: &PerParameter<LearnerInput>| {
                        let x = inputs[StepParameter::StepX];
                        seen.push([x.theta_e.abs(), x.theta_e_dot.abs()]);
                        let mut out = PerParameter::default();
                        if x.theta_e_dot.abs() >= gate {
                            out[StepParameter::StepX] = kxa * x.theta_e + kxr * x.theta_e_dot;
                            out[StepParameter::StepTime] =
                                kta * x.theta_e.abs() + ktr * x.theta_e_dot.abs();
                        }
                        out
                    },
                }
            });
            let log = run_trial(
                &setup,
                policy.as_mut().map(|p| p as &mut dyn FootstepPolicy),
                &mut [],
            )
            .map_err(|e| e.to_string())?;
            if law.is_some() {
                let q = |i: usize| {
                    let mut v: Vec<f64> = seen.iter().map(|a| a[i]).collect();
                    v.sort_by(f64::total_cmp);
                    [0.5, 0.9, 0.99, 0.999].map(|f| v[((v.len() as f64 - 1.0) * f) as usize])
                };
                eprintln!(
                    "inputs' |theta_E| q50/90/99/99.9 {:?}, |rate| {:?}",
                    q(0),
                    q(1)
                );
            }
            let samples: Vec<(f64, bool)> =
                log.pushes.iter().map(|p| (p.impulse, p.fell)).collect();
            impulse_at_50pct_fall(&samples)
                .map(|e| e.impulse_ns)
                .map_err(|e| e.to_string())
        })
        .collect();
    println!("seed,direction,law,model_i50_ns,law_i50_ns,ratio");
    // (law's index, direction, ratio)
    let mut ratios: Vec<(usize, &str, f64)> = Vec::new();
    let mut model = 0.0;
    for (&(seed, direction, _, law), i50) in runs.iter().zip(&i50s) {
        let i50 = i50.clone()?;
        match law {
            None => model = i50,
            Some(k) => {
                println!(
                    "{seed},{direction},{},{model:.3},{i50:.3},{:.4}",
                    args.laws[k],
                    i50 / model
                );
                ratios.push((k, direction, i50 / model));
            }
        }
    }
    println!("\nlaw,direction,mean_ratio,lo95,hi95");
    for (k, law) in args.laws.iter().enumerate() {
        for &(direction, _) in &directions {
            let r = MeanStd::of(
                ratios
                    .iter()
                    .filter(|(l, d, _)| *l == k && *d == direction)
                    .map(|r| r.2),
            );
            // One seed has no interval: printed as the mean alone (lo = hi).
            let half = r.ci95_half_width().unwrap_or(0.0);
            println!(
                "{law},{direction},{:.4},{:.4},{:.4}",
                r.mean(),
                r.mean() - half,
                r.mean() + half
            );
        }
    }
    Ok(())
}
