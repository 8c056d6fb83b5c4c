//! Where does the learned walker win or lose against the model in experiment C? Runs the model
//! and the learned walker (LWPR + pendulum-cart) on the same forward pushes, walking in place,
//! with two switches that isolate the learner's phases:
//!
//! - `--learn-steps N`: learn from the first N touch-downs only, then keep the learned offsets
//!   frozen (with `--settle 60`, a learner trained on undisturbed stepping, never on pushes);
//! - `--gate-rate R`: apply dF only where |theta_E_dot| <= R rad/s (the model alone decides in
//!   the fast transients after a push; learning is unchanged).
//!
//! Prints each controller's falls and impulse at 50% falls, and the mean analytic step, dF
//! and realised step of the five steps after pushes of 10-18 Ns. `--p-theta P` sets the
//! pendulum-cart rule's trunk-angle tolerance (the paper's 0.15 by default).
//!
//! `cargo run --release -p steplearn-probes --bin learner_phases -- --seed 0 --pushes 200 --settle 60 --learn-steps 120`

use clap::Parser;
use rand::SeedableRng;
use rand::rngs::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use std::path::PathBuf;
use steplearn::approx::ApproxKind;
use steplearn::control::{FootstepLearner, InputGrid, LearnerError, LearnerInput, TouchDownReport};
use steplearn::control::{FootstepPolicy, StepReports, Tick, WalkerMode};
use steplearn::control::{LearnSet, PerParameter, StepParameter};
use steplearn::experiments::schedule::PushPlan;
use steplearn::experiments::trial::{Observer, PushRecord, StepRecord};
use steplearn::report::fall_rate::impulse_at_50pct_fall;
use steplearn::rules::{PendulumCart, StepOutcome};
use steplearn_probes::model_and_learned;

#[derive(Parser)]
struct Args {
    /// Seed of the push sequence.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Pushes per controller (impulse uniform in [0, 20] Ns).
    #[arg(long, default_value_t = 200)]
    pushes: usize,
    /// Undisturbed stepping before the first push (s).
    #[arg(long, default_value_t = 3.0)]
    settle: f64,
    /// Learn from the first N touch-downs only (default: always).
    #[arg(long)]
    learn_steps: Option<usize>,
    /// Apply dF only where |theta_E_dot| <= this (rad/s; default: everywhere).
    #[arg(long)]
    gate_rate: Option<f64>,
    /// Settings file (`steplearn config` format) for the robot, walker and learner.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Instead of the learner, a random offset: dF drawn from N(0, SIGMA^2) (m) once per step
    /// and held for the whole step (no learning). Tells whether any perturbation of the
    /// model's gait of this size costs push recovery.
    #[arg(long)]
    noise_offset: Option<f64>,
    /// The pendulum-cart rule's trunk-angle tolerance p_theta (rad; paper 0.15).
    #[arg(long, default_value_t = 0.15)]
    p_theta: f64,
}

/// A random offset, constant within a step, redrawn at every touch-down and fall.
struct NoiseOffset {
    rng: ChaCha8Rng,
    normal: Normal<f64>,
    current: f64,
}

impl NoiseOffset {
    fn redraw(&mut self) {
        self.current = self.normal.sample(&mut self.rng);
    }
}

impl FootstepPolicy for NoiseOffset {
    fn offsets(
        &mut self,
        _inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        Ok(PerParameter::only(StepParameter::StepX, self.current))
    }
    fn set_reach(&mut self, _reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        Ok(())
    }
    fn touch_down(
        &mut self,
        _outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        self.redraw();
        Ok(PerParameter::only(
            StepParameter::StepX,
            Some(TouchDownReport::default()),
        ))
    }
    fn fall(&mut self, _outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        self.redraw();
        Ok(StepReports::default())
    }
    fn discard_step(&mut self) {}
}

/// The learner with the two switches.
struct Phased<P> {
    inner: P,
    gate_rate: f64,
    learn_steps: usize,
    seen: usize,
}

impl<P: FootstepPolicy> FootstepPolicy for Phased<P> {
    fn learns(&self) -> LearnSet {
        self.inner.learns()
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        let offsets = self.inner.offsets(inputs)?;
        Ok(
            if inputs[StepParameter::StepX].theta_e_dot.abs() <= self.gate_rate {
                offsets
            } else {
                PerParameter::default()
            },
        )
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        self.inner.set_reach(reach)
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        self.seen += 1;
        if self.seen > self.learn_steps {
            self.inner.discard_step();
            return Ok(PerParameter::only(
                StepParameter::StepX,
                Some(TouchDownReport::default()),
            ));
        }
        self.inner.touch_down(outcomes)
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        if self.seen >= self.learn_steps {
            self.inner.discard_step();
            return Ok(StepReports::default());
        }
        self.inner.fall(outcomes)
    }
    fn discard_step(&mut self) {
        self.inner.discard_step()
    }
}

/// Steps (time, analytic step, dF, realised step) and pushes of one run.
#[derive(Default)]
struct Recorder {
    last: (f64, f64),
    steps: Vec<(f64, f64, f64, f64)>,
    /// (time, theta_E, F_E) of every touch-down.
    touch_downs: Vec<(f64, f64, f64)>,
    pushes: Vec<PushRecord>,
}

impl Observer for Recorder {
    fn on_tick(&mut self, _time: f64, tick: &Tick) {
        if let Some(d) = tick.decision {
            self.last = (d.analytic_step_x, tick.learned_offset);
        }
    }
    fn on_step(&mut self, step: &StepRecord) {
        self.steps
            .push((step.time, self.last.0, self.last.1, step.f_hat));
        self.touch_downs.push((step.time, step.theta_e, step.f_e()));
    }
    fn on_push(&mut self, push: &PushRecord) {
        self.pushes.push(*push);
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    if args.pushes == 0 || !(args.settle.is_finite() && args.settle >= 0.0) {
        return Err("--pushes must be >= 1 and --settle >= 0".into());
    }
    if args.gate_rate.is_some_and(|r| r.is_nan() || r < 0.0) {
        return Err("--gate-rate must be >= 0".into());
    }
    if !(args.p_theta.is_finite() && args.p_theta > 0.0) {
        return Err("--p-theta must be > 0".into());
    }
    let settings = steplearn_probes::settings(args.config.as_deref()).map_err(|e| e.to_string())?;
    let plan = PushPlan {
        count: args.pushes,
        impulse: (0.0, 20.0),
        settle: args.settle,
        gap: (3.0, 4.0),
    };
    let setup = settings.push_trial(
        WalkerMode::CaptureStep,
        0.0,
        &plan,
        args.seed,
        [1.0, 0.0, 0.0],
    );
    let bounds = InputGrid::default().input_box()?;
    let (model, learned) = model_and_learned::<Recorder>(&setup, || {
        if let Some(sigma) = args.noise_offset {
            return Ok(Box::new(NoiseOffset {
                rng: ChaCha8Rng::seed_from_u64(args.seed ^ 0x006e_6f69_7365),
                normal: Normal::new(0.0, sigma)?,
                current: 0.0,
            }));
        }
        let approx = ApproxKind::Lwpr.build(&bounds)?;
        let learner = FootstepLearner::new(
            approx,
            PendulumCart {
                p_theta: args.p_theta,
                ..PendulumCart::default()
            },
            settings.learner,
        )?;
        Ok(Box::new(Phased {
            inner: learner,
            gate_rate: args.gate_rate.unwrap_or(f64::INFINITY),
            learn_steps: args.learn_steps.unwrap_or(usize::MAX),
            seen: 0,
        }))
    })?;
    for (name, r) in [("model", &model), ("learned", &learned)] {
        let samples: Vec<(f64, bool)> = r.pushes.iter().map(|p| (p.impulse, p.fell)).collect();
        let i50 = impulse_at_50pct_fall(&samples)?.impulse_ns;
        let falls = r.pushes.iter().filter(|p| p.fell).count();
        println!(
            "{name}: seed {} falls {falls} / {} impulse at 50% falls {i50:.2} Ns",
            args.seed,
            r.pushes.len()
        );
        // Undisturbed: no push from 0.1 s after the touch-down to 2.5 s before it.
        let calm_at = |t: f64| {
            !r.pushes
                .iter()
                .any(|p| t > p.time - 0.1 && t < p.time + 2.5)
        };
        let calm: Vec<&(f64, f64, f64)> = r.touch_downs.iter().filter(|s| calm_at(s.0)).collect();
        let n = calm.len().max(1) as f64;
        println!(
            "  undisturbed touch-downs (none within 2.5 s after a push): {}, mean theta_E {:+.4} rad, mean F_E {:+.4} m",
            calm.len(),
            calm.iter().map(|s| s.1).sum::<f64>() / n,
            calm.iter().map(|s| s.2).sum::<f64>() / n
        );
        let calm_df: Vec<f64> = r
            .steps
            .iter()
            .filter(|s| calm_at(s.0))
            .map(|s| s.2)
            .collect();
        let rms = (calm_df.iter().map(|d| d * d).sum::<f64>() / calm_df.len().max(1) as f64).sqrt();
        println!("  undisturbed dF at touch-down: rms {rms:.4} m");
        let mut sums = [[0.0; 3]; 5];
        let mut counts = [0usize; 5];
        for p in r
            .pushes
            .iter()
            .filter(|p| p.impulse > 10.0 && p.impulse < 18.0)
        {
            let after = r
                .steps
                .iter()
                .filter(|s| s.0 > p.time && s.0 < p.time + 2.5)
                .take(5);
            for (k, s) in after.enumerate() {
                sums[k][0] += s.1;
                sums[k][1] += s.2;
                sums[k][2] += s.3;
                counts[k] += 1;
            }
        }
        for k in 0..5 {
            let c = counts[k].max(1) as f64;
            println!(
                "  step {k} after a 10-18 Ns push (n {:3}): analytic {:+.3} dF {:+.3} realised {:+.3} m",
                counts[k],
                sums[k][0] / c,
                sums[k][1] / c,
                sums[k][2] / c
            );
        }
    }
    Ok(())
}
