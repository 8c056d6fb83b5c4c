//! Why are the steps short for ~3 s after the catch steps in experiment B? Runs B's trial for the
//! model alone and prints, per touch-down k = 1..8 after an absorbed push (and for calm steps),
//! the commanded vs realised step, step timing, estimated vs true CoM velocity and offset, the
//! controller's predicted end-of-step velocity, theta_E and sole pitches (columns: `COLS`).
//!
//! `cargo run --release -p steplearn-probes --bin push_dip -- --seed 0 [--pushes 60] [--out FILE.csv]`

use clap::Parser;
use std::io::Write;
use std::path::PathBuf;
use steplearn::control::Tick;
use steplearn::experiments::disturbance::{self, DisturbanceProtocol};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{FallRecord, Observer, PushRecord, run_trial};
use steplearn::sim::GroundTruth;

#[derive(Parser)]
struct Args {
    /// Seed of the push sequence (as `steplearn experiment disturbance --seed`).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Number of pushes.
    #[arg(long, default_value_t = 60)]
    pushes: usize,
    /// Optional CSV of every step's row.
    #[arg(long)]
    out: Option<PathBuf>,
}

#[rustfmt::skip]
const COLS: [&str; 20] = [
    "dt_push", "f_hat", "cmd_td", "cmd_mean", "anal_mean", "dur", "plan_T", "T_left", "v_est_td",
    "v_tru_td", "v_est_m", "v_tru_m", "x_est_td", "x_tru_td", "cpv_mean", "theta_e", "gen_lag",
    "sole_td", "sole_m", "land_td",
];
const N: usize = COLS.len();

/// Sums over the ticks of the step in progress.
#[derive(Default)]
struct Acc {
    start: Option<f64>,
    n: f64,
    cmd: f64,
    analytic: f64,
    plan: f64,
    v_est: f64,
    v_tru: f64,
    n_tru: f64,
    cp_vel: f64,
    sole: f64,
}

#[derive(Default)]
struct Rec {
    acc: Acc,
    /// (command step_x, T left, est v, est x, support index) of the previous tick.
    prev: Option<(f64, f64, f64, f64, usize)>,
    truth: Option<GroundTruth>,
    /// Rows (time, values) of every touch-down; values[0] is filled in later.
    rows: Vec<(f64, [f64; N])>,
    pushes: Vec<PushRecord>,
    falls: Vec<f64>,
    /// Times the generator exchanged support (the decision's support changed).
    gen_ex: Vec<f64>,
    gen_support: Option<usize>,
}

impl Observer for Rec {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        let e = &tick.estimate;
        if let Some(td) = e.touch_down
            && let (Some(start), Some((cmd_td, t_left, v_est, x_est, sup))) =
                (self.acc.start, self.prev)
        {
            let a = &self.acc;
            let n = a.n.max(1.0);
            let (v_tru, x_tru) = match &self.truth {
                Some(t) => (t.com_vel[0], t.com[0] - t.soles[sup].position[0]),
                None => (f64::NAN, f64::NAN),
            };
            let mut v = [f64::NAN; N];
            v[1] = td.step[0];
            v[2] = cmd_td;
            v[3] = a.cmd / n;
            v[4] = a.analytic / n;
            v[5] = time - start;
            v[6] = a.plan / n;
            v[7] = t_left;
            v[8] = v_est;
            v[9] = v_tru;
            v[10] = a.v_est / n;
            v[11] = a.v_tru / a.n_tru.max(1.0);
            v[12] = x_est;
            v[13] = x_tru;
            v[14] = a.cp_vel / n;
            v[15] = e.theta_e;
            v[17] = self.truth.map_or(f64::NAN, |t| sole_pitch(&t, sup));
            v[18] = a.sole / a.n_tru.max(1.0);
            v[19] = self.truth.map_or(f64::NAN, |t| sole_pitch(&t, 1 - sup));
            self.rows.push((time, v));
        }
        if e.touch_down.is_some() || self.acc.start.is_none() {
            self.acc = Acc {
                start: Some(time),
                ..Acc::default()
            };
        }
        let a = &mut self.acc;
        a.n += 1.0;
        a.cmd += tick.command.step_x;
        a.plan += e.time_on_support + tick.command.step_time;
        a.v_est += e.com[0].vel;
        if let Some(d) = tick.decision {
            let s = d.support.index();
            if self.gen_support.is_some_and(|g| g != s) {
                self.gen_ex.push(time);
            }
            self.gen_support = Some(s);
            a.analytic += d.analytic_step_x;
            a.cp_vel += d.end_of_step[0].vel;
        }
        self.prev = Some((
            tick.command.step_x,
            tick.command.step_time,
            e.com[0].vel,
            e.com[0].pos,
            e.support.index(),
        ));
    }
    fn on_push(&mut self, push: &PushRecord) {
        self.pushes.push(*push);
    }
    fn on_fall(&mut self, fall: &FallRecord) {
        self.falls.push(fall.time);
        self.acc = Acc::default();
        self.prev = None;
        self.gen_support = None;
    }
    fn wants_truth(&self) -> bool {
        true
    }
    fn on_truth(&mut self, _time: f64, truth: &GroundTruth) {
        self.acc.v_tru += truth.com_vel[0];
        self.acc.n_tru += 1.0;
        if let Some(p) = self.prev {
            self.acc.sole += sole_pitch(truth, p.4);
        }
        self.truth = Some(*truth);
    }
}

/// Pitch of a sole (rad, toe down positive) from its world orientation `[w, x, y, z]`.
fn sole_pitch(truth: &GroundTruth, side: usize) -> f64 {
    let [w, x, y, z] = truth.soles[side].orientation;
    (2.0 * (w * y - z * x)).clamp(-1.0, 1.0).asin()
}

fn corr(xs: &[(f64, f64)]) -> f64 {
    let n = xs.len() as f64;
    let (mx, my) = (
        xs.iter().map(|p| p.0).sum::<f64>() / n,
        xs.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (x, y) in xs {
        sxy += (x - mx) * (y - my);
        sxx += (x - mx).powi(2);
        syy += (y - my).powi(2);
    }
    sxy / (sxx * syy).sqrt()
}

fn print_row(label: &str, count: usize, v: &[f64; N]) {
    print!("{label:>6} {count:4}");
    for x in v {
        print!(" {x:8.3}");
    }
    println!();
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let settings = Settings::default();
    let protocol = DisturbanceProtocol {
        pushes: args.pushes,
        ..DisturbanceProtocol::default()
    };
    let setup = disturbance::trial_setup(&settings, &protocol, args.seed);
    let mut rec = Rec::default();
    run_trial(&setup, None, &mut [&mut rec])?;
    // Generator exchange nearest to each touch-down, minus the touch-down time.
    for r in rec.rows.iter_mut() {
        r.1[16] = rec
            .gen_ex
            .iter()
            .map(|&g| g - r.0)
            .filter(|d| d.abs() < 0.35)
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(f64::NAN);
    }
    let absorbed: Vec<f64> = rec
        .pushes
        .iter()
        .filter(|p| !p.fell)
        .map(|p| p.time)
        .collect();
    println!(
        "seed {} pushes {} absorbed {} falls {} steps {}",
        args.seed,
        rec.pushes.len(),
        absorbed.len(),
        rec.falls.len(),
        rec.rows.len()
    );
    let mut by_k: Vec<Vec<[f64; N]>> = vec![Vec::new(); 9];
    // (push id, k) of each row after an absorbed push, for the CSV.
    let mut tag = vec![(-1i64, 0usize); rec.rows.len()];
    for (id, &tp) in absorbed.iter().enumerate() {
        let after = rec
            .rows
            .iter()
            .enumerate()
            .filter(|(_, r)| r.0 > tp && r.0 < tp + protocol.horizon_s)
            .take(8);
        for (k, (i, r)) in after.enumerate() {
            let mut v = r.1;
            v[0] = r.0 - tp;
            by_k[k + 1].push(v);
            tag[i] = (id as i64, k + 1);
        }
    }
    // Undisturbed: > 5 s into the trial, not within [-0.1, horizon] of a push, 3 s from a fall.
    let all_push: Vec<f64> = rec.pushes.iter().map(|p| p.time).collect();
    for r in &rec.rows {
        let calm = r.0 > 5.0
            && !all_push
                .iter()
                .any(|&p| r.0 > p - 0.1 && r.0 < p + protocol.horizon_s)
            && !rec.falls.iter().any(|&f| r.0 > f && r.0 < f + 3.0);
        if calm {
            let mut v = r.1;
            v[0] = f64::NAN;
            by_k[0].push(v);
        }
    }
    print!("{:>6} {:>4}", "k", "n");
    for c in COLS {
        print!(" {c:>8}");
    }
    println!();
    for (k, rows) in by_k.iter().enumerate() {
        let mut mean = [0.0; N];
        for i in 0..N {
            let ok: Vec<f64> = rows
                .iter()
                .map(|v| v[i])
                .filter(|x| x.is_finite())
                .collect();
            mean[i] = ok.iter().sum::<f64>() / ok.len() as f64;
        }
        let label = if k == 0 { "calm".into() } else { k.to_string() };
        print_row(&label, rows.len(), &mean);
    }
    // Does the command or the velocity predict the short third step?
    for k in [2, 3, 4] {
        let pick = |i: usize| -> Vec<(f64, f64)> { by_k[k].iter().map(|v| (v[i], v[1])).collect() };
        println!(
            "k={k}: corr(F_hat, cmd_td) {:+.2}  corr(F_hat, v_tru_td) {:+.2}  corr(F_hat, v_est_td) {:+.2}  corr(F_hat, dt_push) {:+.2}",
            corr(&pick(2)),
            corr(&pick(9)),
            corr(&pick(8)),
            corr(&pick(0))
        );
    }
    if let Some(path) = args.out {
        let mut f = std::fs::File::create(&path)?;
        writeln!(f, "push,k,time,{}", COLS.join(","))?;
        for ((t, v), (id, k)) in rec.rows.iter().zip(&tag) {
            let cells: Vec<String> = v.iter().map(|x| format!("{x:.5}")).collect();
            writeln!(f, "{id},{k},{t:.4},{}", cells.join(","))?;
        }
    }
    Ok(())
}
