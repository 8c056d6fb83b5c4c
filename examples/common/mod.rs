#![allow(dead_code)]
//! Shared by the stand and step-in-place examples: one open-loop run with optional pushes,
//! recorded for the run picture, and the search for the largest push survived.

use steplearn::control::motion::{MotionConfig, MotionGenerator};
use steplearn::sim::picture::RunRecord;
use steplearn::sim::{Humanoid, SimConfig};

/// Open-loop behaviour of a run.
#[derive(Clone, Copy, PartialEq)]
pub enum Mode {
    /// Hold the halt pose.
    Stand,
    /// Step with this step size (m; 0 = in place).
    Step(f64),
}

/// Result of one run.
pub struct Outcome {
    /// Time of the fall, if any.
    pub fell_at: Option<f64>,
    /// The recording.
    pub record: RunRecord,
    /// Wall-clock seconds.
    pub wall: f64,
}

/// Runs `seconds` of `mode`, delivering `pushes` (time, impulse). Stops at a fall.
pub fn run(mode: Mode, seconds: f64, pushes: &[(f64, [f64; 3])], title: &str) -> Outcome {
    let config = SimConfig::default();
    let dt = config.tick();
    let mut sim = Humanoid::new(config).expect("default config is valid");
    let mut generator = MotionGenerator::new(
        MotionConfig::default()
            .check()
            .expect("default motion settings are valid"),
        &sim.body().leg_geometry(),
    );
    let mut record = RunRecord::new(title);
    let mut pending: Vec<_> = pushes.to_vec();
    let start = std::time::Instant::now();
    let mut fell_at = None;
    record.record(&sim.ground_truth());
    while sim.time() < seconds {
        if let Some(k) = pending.iter().position(|(t, _)| sim.time() >= *t) {
            let (_, impulse) = pending.remove(k);
            sim.push(impulse).expect("finite push impulse");
            record.push(sim.time(), impulse);
        }
        let targets = match mode {
            Mode::Stand => generator.halt_targets(),
            Mode::Step(x) => {
                let cmd = generator.open_loop(x);
                generator.update(&cmd, dt)
            }
        };
        sim.step(&targets).expect("simulation step");
        record.record(&sim.ground_truth());
        if let Some(f) = sim.fall() {
            fell_at = Some(f.time);
            record.fall(f.time);
            // Keep a little of the fall in the picture.
            for _ in 0..30 {
                if sim.step(&targets).is_err() {
                    break;
                }
                record.record(&sim.ground_truth());
            }
            break;
        }
    }
    Outcome {
        fell_at,
        record,
        wall: start.elapsed().as_secs_f64(),
    }
}

/// Largest forward push (N s, 0.5 N s resolution, up to `max`) survived for 4 s after being
/// delivered at `push_time`, found by scanning upward from 0.5 N s until the first fall.
pub fn largest_push(mode: Mode, push_time: f64, max: f64) -> f64 {
    let mut best = 0.0;
    let mut p = 0.5;
    while p <= max + 1e-9 {
        let out = run(
            mode,
            push_time + 4.0,
            &[(push_time, [p, 0.0, 0.0])],
            "push trial",
        );
        if out.fell_at.is_some() {
            break;
        }
        best = p;
        p += 0.5;
    }
    best
}
