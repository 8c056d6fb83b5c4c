//! Walks the humanoid with a chosen walker (open-loop, Capture Step model) at a reference step
//! size, optionally with forward pushes, and prints every step and fall.
//!
//! `cargo run --release -p steplearn-probes --bin walk -- --mode capture-step --step-x 0.1 --seconds 30 --push 8`
//! `cargo run --release -p steplearn-probes --bin walk -- --learn --eta 0.2 --seconds 60 --push 6,8,10,12,14`
//! `cargo run --release -p steplearn-probes --bin walk -- --step-x 0.1 --step-y 0.04 --seconds 30`

use clap::Parser;
use steplearn::approx::{Lwpr, LwprConfig};
use steplearn::control::Tick;
use steplearn::control::WalkerMode;
use steplearn::control::capture_step::StepDecision;
use steplearn::control::{FootstepLearner, InputGrid, LearnerConfig};
use steplearn::experiments::schedule::{Push, ReferenceSchedule};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{FallRecord, Observer, PushRecord, StepRecord, run_trial};
use steplearn::robot::Side;
use steplearn::rules::PendulumCart;
use steplearn::sim::GroundTruth;
use steplearn::sim::picture::{RunRecord, StepAnnotation};

#[derive(Parser)]
struct Args {
    /// Walker: open-loop or capture-step.
    #[arg(long, default_value = "capture-step")]
    mode: String,
    /// Reference step size F_R (m).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    step_x: f64,
    /// Lateral reference F_R,y (m per step, positive to the left).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    step_y: f64,
    /// Simulated seconds.
    #[arg(long, default_value_t = 30.0)]
    seconds: f64,
    /// Forward push impulses (Ns), one every 5 s from t = 5 s.
    #[arg(long, value_delimiter = ',')]
    push: Vec<f64>,
    /// Steps before this time (s) are left out of the mean figures.
    #[arg(long, default_value_t = 5.0)]
    settle: f64,
    /// Print every step.
    #[arg(long)]
    verbose: bool,
    /// Add the learner (LWPR + pendulum-cart) to the capture-step walker.
    #[arg(long)]
    learn: bool,
    /// The learner's rate eta (the paper: 1).
    #[arg(long, default_value_t = 1.0)]
    eta: f64,
    /// Clamp the learned offset to +-this (m); none by default.
    #[arg(long)]
    max_offset: Option<f64>,
    /// Write a run picture (stick figures, CoM and feet, pushes, falls, and the controller's
    /// Z, F and T at the start of every step) to this SVG file.
    #[arg(long)]
    picture: Option<std::path::PathBuf>,
    /// LWPR's initial distance metric (init_D = value * I on inputs scaled by their ranges).
    #[arg(long, default_value_t = 10.0)]
    init_d: f64,
}

struct Printer {
    verbose: bool,
    /// (time, width error W - W_R, W_R) of every step.
    widths: Vec<(f64, f64, f64)>,
    /// The CoM's (x, y) at the first and the last tick (m, world).
    com: Option<([f64; 2], [f64; 2])>,
}

impl Observer for Printer {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        if let Some(l) = tick.lateral_step {
            let w_r = l.f_r + 0.24;
            self.widths.push((time, l.f_e, w_r));
            if self.verbose {
                println!(
                    "t {time:7.2}  W_R {w_r:.3}  W_E {:+.3}  lean {:+.3}",
                    l.f_e, l.theta_e
                );
            }
        }
    }
    fn wants_truth(&self) -> bool {
        true
    }
    fn on_truth(&mut self, _time: f64, truth: &GroundTruth) {
        let xy = [truth.com[0], truth.com[1]];
        self.com = Some((self.com.map_or(xy, |c| c.0), xy));
    }
    fn on_step(&mut self, s: &StepRecord) {
        if self.verbose {
            println!(
                "t {:7.2}  F_R {:+.3}  F_hat {:+.3}  theta_E {:+.3}  dtheta {:+.3}  dF {:+.3}",
                s.time, s.f_r, s.f_hat, s.theta_e, s.theta_e_dot, s.learned_offset
            );
        }
    }
    fn on_fall(&mut self, f: &FallRecord) {
        println!("FALL at {:.2} s: {:?}", f.time, f.fall.trigger);
    }
}

/// Records the run for the picture: ground truth every tick, the controller's decision at the
/// first tick of every step (placed in the world at the support sole).
struct Picture {
    record: RunRecord,
    decision: Option<StepDecision>,
    support: Option<Side>,
}

impl Observer for Picture {
    fn on_tick(&mut self, _time: f64, tick: &Tick) {
        self.decision = tick.decision;
    }
    fn on_push(&mut self, p: &PushRecord) {
        self.record.push(p.time, [p.impulse, 0.0, 0.0]);
    }
    fn on_fall(&mut self, f: &FallRecord) {
        self.record.fall(f.time);
    }
    fn wants_truth(&self) -> bool {
        true
    }
    fn on_truth(&mut self, time: f64, truth: &GroundTruth) {
        let mut truth = *truth;
        truth.time = time;
        self.record.record(&truth);
        // The controller's first decision on a new support foot.
        if let Some(d) = self.decision
            && self.support != Some(d.support)
        {
            self.support = Some(d.support);
            let sole = truth.soles[d.support.index()].position;
            self.record.annotate(StepAnnotation {
                time,
                zmp: Some([sole[0] + d.zmp[0], sole[1] + d.zmp[1]]),
                footstep: Some([sole[0] + d.step[0], sole[1] + d.step[1]]),
                step_time: Some(d.time_to_step),
            });
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let mode = match args.mode.as_str() {
        "open-loop" => WalkerMode::OpenLoop,
        "capture-step" => WalkerMode::CaptureStep,
        other => return Err(format!("unknown mode {other}").into()),
    };
    let settings = Settings::default();
    let pushes = args
        .push
        .iter()
        .enumerate()
        .map(|(i, &impulse)| Push {
            time: 5.0 * (i + 1) as f64,
            impulse,
        })
        .collect();
    let mut setup = settings.trial(
        mode,
        ReferenceSchedule::constant(args.step_x),
        pushes,
        [1.0, 0.0, 0.0],
        args.seconds,
    );
    setup.lateral_reference = Some(ReferenceSchedule::constant(args.step_y));
    let wall = std::time::Instant::now();
    // LWPR over (theta_E, theta_E_dot, F_R), inputs scaled by the learner grid's half-ranges.
    let grid = InputGrid::default();
    let half: Vec<f64> = grid
        .lo
        .to_array()
        .iter()
        .zip(grid.hi.to_array())
        .map(|(l, h)| 0.5 * (h - l))
        .collect();
    let lwpr = Lwpr::new(LwprConfig::new(3, 1).norm_in(half).init_d(args.init_d))?;
    let mut learner = FootstepLearner::new(
        lwpr,
        PendulumCart::default(),
        LearnerConfig {
            max_offset: args.max_offset,
            eta: args.eta,
            ..LearnerConfig::default()
        },
    )?;
    let mut printer = Printer {
        verbose: args.verbose,
        widths: Vec::new(),
        com: None,
    };

    let mut picture = Picture {
        record: RunRecord::new(&format!("{} walker, F_R {:+.2} m", args.mode, args.step_x)),
        decision: None,
        support: None,
    };
    let mut observers: Vec<&mut dyn Observer> = vec![&mut printer];
    if args.picture.is_some() {
        observers.push(&mut picture);
    }
    let log = run_trial(
        &setup,
        if args.learn { Some(&mut learner) } else { None },
        &mut observers,
    )?;
    if let Some(path) = &args.picture {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir)?;
        }
        picture.record.write_svg(path, 0.5)?;
        println!("wrote {}", path.display());
    }
    let wall = wall.elapsed().as_secs_f64();
    let n = log.steps.len().max(1) as f64;
    let settled: Vec<_> = log.steps.iter().filter(|s| s.time > args.settle).collect();
    let m = settled.len().max(1) as f64;
    let mean_step = settled.iter().map(|s| s.f_hat).sum::<f64>() / m;
    let mean_abs_err = settled.iter().map(|s| s.f_e().abs()).sum::<f64>() / m;
    println!(
        "{} steps, {} falls, pushes {:?}, after {} s: mean F_hat {:+.4} m (mean error {:+.4} m, mean |error| {:.4} m), {:.1}x real time",
        n,
        log.falls.len(),
        log.pushes
            .iter()
            .map(|p| (p.impulse, p.fell))
            .collect::<Vec<_>>(),
        args.settle,
        mean_step,
        mean_step - args.step_x,
        mean_abs_err,
        log.sim_time_s / wall
    );
    let widths: Vec<_> = printer
        .widths
        .iter()
        .filter(|w| w.0 > args.settle)
        .collect();
    let k = widths.len().max(1) as f64;
    let (start, end) = printer.com.unwrap_or_default();
    println!(
        "lateral: mean |W_E| {:.4} m, mean W_E {:+.4} m over {} steps; the CoM moved ({:+.3}, {:+.3}) m in {:.1} s",
        widths.iter().map(|w| w.1.abs()).sum::<f64>() / k,
        widths.iter().map(|w| w.1).sum::<f64>() / k,
        widths.len(),
        end[0] - start[0],
        end[1] - start[1],
        log.sim_time_s,
    );
    Ok(())
}
