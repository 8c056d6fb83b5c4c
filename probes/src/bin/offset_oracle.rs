//! Could *any* `step-x,step-time` offsets save the model from the pushes it falls to? A ceiling
//! beyond the learner's inputs: each case is one push (its gait phase and impulse drawn from the
//! case's seed, the impulse uniform in `--impulse`) on the model walking in place, run once for
//! the model and once for every constant offset pair (dF, dT) of a grid, held from the push for
//! `--hold` seconds (zero before and after; dF positive is a longer step in the push's
//! direction, dT negative a sooner step).
//!
//! Each run's row gives its pair (dF in the push's direction) and the case's gait phase at the
//! push (time since the last touch-down).
//! Per direction it prints the I50 (logistic fit over the cases, as experiment C's) of:
//! - the model;
//! - each pair of the grid (a fixed reflex that knows when a push came and its direction);
//! - the *oracle*: a case counts as survived if any pair of the grid survives it (a policy that
//!   knows each push's outcome under every offset in advance: an upper bound for any policy of
//!   these offsets held over the recovery);
//! - the *chaos envelope*: the same over `--chaos` null pairs (dF of +-1, +-2, ... times
//!   `--chaos-step`, far below what a step lands to), which change little but the run's chaos;
//!   what the oracle gains beyond it is what the offsets themselves buy.
//!
//! `cargo run --release -p steplearn-probes --bin offset_oracle -- --cases 60 --direction forward --impulse 12,30`

use clap::Parser;
use rayon::prelude::*;
use std::cell::Cell;
use std::path::PathBuf;
use std::rc::Rc;
use steplearn::control::{FootstepPolicy, Tick, WalkerMode};
use steplearn::control::{LearnSet, PerParameter, StepParameter};
use steplearn::experiments::schedule::PushPlan;
use steplearn::experiments::trial::{Observer, run_trial};
use steplearn::report::fall_rate::impulse_at_50pct_fall;
use steplearn_probes::FixedPolicy;

#[derive(Parser)]
struct Args {
    /// Number of cases (one push each, seeds `first_case..`).
    #[arg(long, default_value_t = 60)]
    cases: u64,
    /// The first case's seed.
    #[arg(long, default_value_t = 0)]
    first_case: u64,
    /// `forward` or `backward`.
    #[arg(long, default_value = "forward")]
    direction: String,
    /// Impulse range "A,B" (Ns), uniform.
    #[arg(long, value_delimiter = ',', default_values_t = [12.0, 30.0])]
    impulse: Vec<f64>,
    /// dF values of the grid (m, in the push's direction).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values_t = [-0.1, -0.05, 0.0, 0.05, 0.1])]
    dx: Vec<f64>,
    /// dT values of the grid (s, negative sooner).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values_t = [-0.1, -0.05, 0.0, 0.05])]
    dt: Vec<f64>,
    /// How long the offsets are held from the push (s).
    #[arg(long, default_value_t = 1.0)]
    hold: f64,
    /// Number of null pairs, dF = +-step, +-2 step, ... (dT 0): the chaos envelope.
    #[arg(long, default_value_t = 20)]
    chaos: usize,
    /// The null pairs' step (m): far below what a step lands to.
    #[arg(long, default_value_t = 1e-6)]
    chaos_step: f64,
    /// Settings file (`steplearn config` format).
    #[arg(long)]
    config: Option<PathBuf>,
}

/// Tells the policy the trial time of the last tick, and measures the gait phase at the push.
struct Clock {
    now: Rc<Cell<f64>>,
    push_at: f64,
    last_touch_down: f64,
    /// Time since the last touch-down at the tick the push came.
    phase: Option<f64>,
}

impl Observer for Clock {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        self.now.set(time);
        if tick.step.is_some() {
            self.last_touch_down = time;
        }
        if self.phase.is_none() && time >= self.push_at {
            self.phase = Some(time - self.last_touch_down);
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let settings = steplearn_probes::settings(args.config.as_deref()).map_err(|e| e.to_string())?;
    let sign = match args.direction.as_str() {
        "forward" => 1.0,
        "backward" => -1.0,
        other => return Err(format!("unknown direction {other:?}").into()),
    };
    let [lo, hi] = args.impulse[..] else {
        return Err("--impulse takes two numbers A,B".into());
    };
    if !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo <= hi) {
        return Err(format!("--impulse needs 0 <= A <= B, not {lo},{hi}").into());
    }
    let plan = PushPlan {
        count: 1,
        impulse: (lo, hi),
        settle: 4.0,
        gap: (0.0, 1.0),
    };
    // Walkers: None is the model; then the grid's pairs, then the null pairs (dF in the push's
    // direction).
    let mut pairs: Vec<[f64; 2]> = Vec::new();
    for &dx in &args.dx {
        for &dt in &args.dt {
            pairs.push([dx, dt]);
        }
    }
    let grid = pairs.len();
    if !(args.chaos_step.is_finite() && args.chaos_step > 0.0) {
        return Err("--chaos-step must be positive".into());
    }
    for k in 1..=args.chaos {
        let side = if k % 2 == 1 { 1.0 } else { -1.0 };
        pairs.push([k.div_ceil(2) as f64 * args.chaos_step * side, 0.0]);
    }
    let mut runs = Vec::new();
    for case in args.first_case..args.first_case + args.cases {
        runs.push((case, None));
        for k in 0..pairs.len() {
            runs.push((case, Some(k)));
        }
    }
    // (impulse, fell, gait phase at the push) per run.
    let outcomes: Vec<Result<(f64, bool, f64), String>> = runs
        .par_iter()
        .map(|&(case, pair)| {
            let setup =
                settings.push_trial(WalkerMode::CaptureStep, 0.0, &plan, case, [sign, 0.0, 0.0]);
            let push = setup.pushes[0];
            let now = Rc::new(Cell::new(0.0));
            let (from, hold) = (push.time, args.hold);
            let clock = now.clone();
            // Constant offsets from the push for `hold` seconds (the last tick's time).
            let mut policy = pair.map(|k| pairs[k]).map(|offsets| FixedPolicy {
                learns: LearnSet::of(&[StepParameter::StepX, StepParameter::StepTime])
                    .expect("two parameters"),
                offsets: move |_: &_| {
                    let mut out = PerParameter::default();
                    let t = clock.get();
                    if t >= from && t < from + hold {
                        out[StepParameter::StepX] = offsets[0] * sign;
                        out[StepParameter::StepTime] = offsets[1];
                    }
                    out
                },
            });
            let mut clock = Clock {
                now,
                push_at: push.time,
                last_touch_down: 0.0,
                phase: None,
            };
            let log = run_trial(
                &setup,
                policy.as_mut().map(|p| p as &mut dyn FootstepPolicy),
                &mut [&mut clock],
            )
            .map_err(|e| e.to_string())?;
            let p = log
                .pushes
                .first()
                .ok_or_else(|| format!("case {case}: the push was not delivered"))?;
            Ok((p.impulse, p.fell, clock.phase.unwrap_or(f64::NAN)))
        })
        .collect();
    let outcomes: Vec<(f64, bool, f64)> = outcomes.into_iter().collect::<Result<_, _>>()?;
    let walkers = pairs.len() + 1;
    println!("case,impulse_ns,walker,dx,dt,fell,phase_s");
    for (r, &(case, pair)) in runs.iter().enumerate() {
        let (j, fell, phase) = outcomes[r];
        let (name, [dx, dt]) = match pair {
            None => ("model".to_string(), [0.0, 0.0]),
            Some(k) if k < grid => ("pair".to_string(), pairs[k]),
            Some(k) => ("null".to_string(), pairs[k]),
        };
        println!("{case},{j:.4},{name},{dx},{dt},{},{phase:.3}", fell as u8);
    }
    // Per walker, the (impulse, fell) of every case.
    let of = |w: usize| -> Vec<(f64, bool)> {
        (0..args.cases as usize)
            .map(|c| {
                let (j, fell, _) = outcomes[c * walkers + w];
                (j, fell)
            })
            .collect()
    };
    let i50 = |samples: &[(f64, bool)]| -> Result<f64, Box<dyn std::error::Error>> {
        Ok(impulse_at_50pct_fall(samples)?.impulse_ns)
    };
    // A case survived by any of `ws`.
    let envelope = |ws: &[usize]| -> Vec<(f64, bool)> {
        (0..args.cases as usize)
            .map(|c| {
                let j = outcomes[c * walkers].0;
                (j, ws.iter().all(|&w| outcomes[c * walkers + w].1))
            })
            .collect()
    };
    let model = i50(&of(0))?;
    println!("\nwalker,i50_ns,ratio_to_model,falls");
    let line = |name: &str, s: &[(f64, bool)]| -> Result<(), Box<dyn std::error::Error>> {
        let v = i50(s)?;
        let falls = s.iter().filter(|x| x.1).count();
        println!("{name},{v:.3},{:.4},{falls}", v / model);
        Ok(())
    };
    line("model", &of(0))?;
    for (k, pair) in pairs[..grid].iter().enumerate() {
        line(
            &format!("pair dx {:+} dt {:+}", pair[0], pair[1]),
            &of(k + 1),
        )?;
    }
    let oracle: Vec<usize> = (0..=grid).collect();
    line(
        &format!("oracle (any of the {grid} pairs or the model)"),
        &envelope(&oracle),
    )?;
    if args.chaos > 0 {
        let null: Vec<usize> = std::iter::once(0).chain(grid + 1..walkers).collect();
        line(
            &format!(
                "chaos envelope (any of {} null pairs or the model)",
                args.chaos
            ),
            &envelope(&null),
        )?;
    }
    Ok(())
}
