//! Why does a robot's Capture Step model step short of its reference, undisturbed? The model
//! walks at experiment B's reference step (the paper robot's 0.2 m, scaled to the robot) for
//! `--seconds` without pushes, and per touch-down after the first 10 s the probe compares the
//! realised step with what was commanded: the controller's step S (`decision.step[0]`) and the
//! motion generator's `step_x` at the step's last tick, the analytic step before the limit, the
//! reference F_R, the step time, and the centre of mass's velocity at touch-down against the
//! velocity the controller's end-of-step target asked for. Prints the medians, in metres and as
//! shares of F_R.
//!
//! `--trace T` prints the touch-down ticks (`--every-tick`: every tick) of the ten seconds
//! from T: the support, the centre of mass's state and the controller's decision in both
//! planes, the feet and the step commanded.
//!
//! `cargo run --release -p steplearn-probes --bin short_steps -- [--robot robots/igus_like.urdf] [--config FILE] [--seconds 40] [--trace T [--every-tick]]`

use clap::Parser;
use std::path::PathBuf;
use steplearn::control::{Tick, WalkerMode};
use steplearn::experiments::config_file::ConfigFile;
use steplearn::experiments::robot_setup::use_robot;
use steplearn::experiments::schedule::ReferenceSchedule;
use steplearn::experiments::trial::{Observer, StepRecord, run_trial};
use steplearn::sim::GroundTruth;

#[derive(Parser)]
struct Args {
    /// A robot's URDF (default: the built-in humanoid).
    #[arg(long)]
    robot: Option<PathBuf>,
    /// A config file (default: the defaults).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Seconds of walking.
    #[arg(long, default_value_t = 40.0)]
    seconds: f64,
    /// The reference step in the paper robot's metres (scaled to the robot).
    #[arg(long, default_value_t = 0.2)]
    f_r: f64,
    /// Print the touch-down ticks of the ten seconds from this time.
    #[arg(long)]
    trace: Option<f64>,
    /// With `--trace`: print every tick, not only the touch-downs.
    #[arg(long)]
    every_tick: bool,
}

/// One step's figures, gathered tick by tick.
#[derive(Default, Clone, Copy)]
struct Step {
    start: f64,
    command_x: f64,
    decision_x: f64,
    analytic_x: f64,
    target_vel: f64,
    first_target_vel: f64,
    touch_down_vel: f64,
    com_x: f64,
    zmp_sum: f64,
    ticks: f64,
    true_vel_sum: f64,
    est_vel_sum: f64,
    truth_ticks: f64,
    last_est_vel: f64,
    last_est_pos: f64,
    last_support: usize,
    pos_err_sum: f64,
}

#[derive(Default)]
struct Trace {
    trace: Option<f64>,
    every_tick: bool,
    current: Step,
    fresh: bool,
    done: Vec<(Step, f64, f64)>,
}

impl Observer for Trace {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        if tick.estimate.touch_down.is_some() {
            // The step that just ended: the CoM state at the exchange, relative to the old
            // support foot, is what the target described.
            self.current.touch_down_vel = tick.estimate.com[0].vel;
            self.fresh = true;
        }
        if let (Some(t0), Some(d)) = (self.trace, &tick.decision)
            && time >= t0
            && time < t0 + 10.0
            && (self.every_tick || tick.estimate.touch_down.is_some())
        {
            let e = &tick.estimate;
            println!(
                "t {time:.3} sup {:?} on {:.3} com {:+.4} {:+.4} zmp {:+.4} T {:.3} target {:+.4} {:+.4} eos {:+.4} {:+.4} step {:+.4} cmd {:+.4} cmdT {:.3} | y com {:+.4} {:+.4} zmp {:+.4} target {:+.4} {:+.4} eos {:+.4} {:+.4} feet y {:+.4} {:+.4} stepy {:+.4} cmdy {:+.4}{}",
                e.support,
                e.time_on_support,
                e.com[0].pos,
                e.com[0].vel,
                d.zmp[0],
                d.time_to_step,
                d.target[0].pos,
                d.target[0].vel,
                d.end_of_step[0].pos,
                d.end_of_step[0].vel,
                d.step[0],
                tick.command.step_x,
                tick.command.step_time,
                e.com[1].pos,
                e.com[1].vel,
                d.zmp[1],
                d.target[1].pos,
                d.target[1].vel,
                d.end_of_step[1].pos,
                d.end_of_step[1].vel,
                e.feet[0][1],
                e.feet[1][1],
                d.step[1],
                tick.command.step_y,
                if e.touch_down.is_some() {
                    " TOUCH-DOWN"
                } else {
                    ""
                }
            );
        }
        if let Some(d) = &tick.decision {
            if self.fresh {
                self.current.first_target_vel = d.target[0].vel;
                self.fresh = false;
            }
            self.current.zmp_sum += d.zmp[0];
            self.current.ticks += 1.0;
            self.current.decision_x = d.step[0];
            self.current.analytic_x = d.analytic_step_x;
            self.current.target_vel = d.target[0].vel;
            self.current.com_x = tick.estimate.com[0].pos;
        }
        self.current.command_x = tick.command.step_x;
        self.current.last_est_vel = tick.estimate.com[0].vel;
        self.current.last_est_pos = tick.estimate.com[0].pos;
        self.current.last_support = tick.estimate.support.index();
    }
    fn wants_truth(&self) -> bool {
        true
    }
    fn on_truth(&mut self, _time: f64, truth: &GroundTruth) {
        self.current.true_vel_sum += truth.com_vel[0];
        self.current.est_vel_sum += self.current.last_est_vel;
        self.current.truth_ticks += 1.0;
        let sole = truth.soles[self.current.last_support].position[0];
        self.current.pos_err_sum += (truth.com[0] - sole) - self.current.last_est_pos;
    }
    fn on_step(&mut self, step: &StepRecord) {
        let mut s = self.current;
        s.start = step.time;
        self.done.push((s, step.f_hat, step.f_r));
        self.current = Step::default();
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        f64::NAN
    } else {
        v[v.len() / 2]
    }
}

fn main() -> Result<(), String> {
    let args = Args::parse();
    let mut config = match &args.config {
        Some(p) => ConfigFile::load(p).map_err(|e| e.to_string())?,
        None => ConfigFile::default(),
    };
    let mut f_r = args.f_r;
    if let Some(path) = &args.robot {
        let run = use_robot(path, None, &mut config.settings, &mut config.protocols)
            .map_err(|e| e.to_string())?;
        f_r = run.scale.length(f_r);
    }
    let setup = config.settings.trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(f_r),
        vec![],
        [1.0, 0.0, 0.0],
        args.seconds,
    );
    let mut trace = Trace {
        trace: args.trace,
        every_tick: args.every_tick,
        ..Trace::default()
    };
    let log = run_trial(&setup, None, &mut [&mut trace]).map_err(|e| e.to_string())?;
    let steps: Vec<_> = trace
        .done
        .iter()
        .filter(|(s, _, _)| s.start > 10.0)
        .collect();
    let times: Vec<f64> = log.steps.iter().map(|s| s.time).collect();
    let durations: Vec<f64> = times
        .windows(2)
        .filter(|w| w[0] > 10.0)
        .map(|w| w[1] - w[0])
        .collect();
    let m = |f: &dyn Fn(&(Step, f64, f64)) -> f64| median(steps.iter().map(|x| f(x)).collect());
    println!(
        "{} steps after 10 s, {} falls; F_R {f_r:.4} m",
        steps.len(),
        log.falls.len()
    );
    let share = |x: f64| x / f_r;
    let rows: [(&str, f64); 4] = [
        ("realised F_hat", m(&|x| x.1)),
        ("commanded step_x, last tick", m(&|x| x.0.command_x)),
        ("controller's step S, last tick", m(&|x| x.0.decision_x)),
        ("analytic step, last tick", m(&|x| x.0.analytic_x)),
    ];
    for (name, v) in rows {
        println!("{name:32} {v:+.4} m  ({:.2} F_R)", share(v));
    }
    println!(
        "step time (median)               {:.3} s",
        median(durations)
    );
    println!(
        "CoM velocity at touch-down       {:+.4} m/s; the end-of-step target asked {:+.4} (first tick) {:+.4} (last)",
        m(&|x| x.0.touch_down_vel),
        m(&|x| x.0.first_target_vel),
        m(&|x| x.0.target_vel)
    );
    println!(
        "CoM x rel. support, last tick    {:+.4} m",
        m(&|x| x.0.com_x)
    );
    println!(
        "CoM x, true - estimated (rel. support sole), mean over the step {:+.4} m",
        m(&|x| x.0.pos_err_sum / x.0.truth_ticks)
    );
    println!(
        "ZMP x, mean over the step        {:+.4} m",
        m(&|x| x.0.zmp_sum / x.0.ticks)
    );
    println!(
        "CoM velocity, mean over the step: true {:+.4} m/s, estimated {:+.4} m/s",
        m(&|x| x.0.true_vel_sum / x.0.truth_ticks),
        m(&|x| x.0.est_vel_sum / x.0.truth_ticks)
    );
    Ok(())
}
