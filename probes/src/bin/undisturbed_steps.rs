//! How the swing's landing settings move the model's undisturbed steps: for each setting given
//! as `EARLY,GAIN,LIFT,BAND` (`early_landing_phase`, `tilt_gain`, `tilt_lift`,
//! `tilt_gain_band`), the Capture Step model walks 15 s at F_R -0.1, 0, 0.1 and 0.2 m without
//! pushes and prints the mean realised step after 5 s, its error against F_R and the mean |error|
//! (the figures the tests `capture_step_walker_steps_in_place_on_the_spot` and
//! `capture_step_walker_tracks_the_reference_step` bound).
//!
//! `cargo run --release -p steplearn-probes --bin undisturbed_steps -- 1,1,0,0 0.5,1.3,0.3,0 0.5,1.3,0.3,0.05`

use steplearn::control::WalkerMode;
use steplearn::experiments::schedule::ReferenceSchedule;
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::run_trial;

/// Mean realised step, mean |F_hat - F_R|, falls and steps after 5 s of a 15 s walk at `f_r`.
fn figures(settings: &Settings, f_r: f64) -> (f64, f64, usize, usize) {
    let setup = settings.trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(f_r),
        vec![],
        [1.0, 0.0, 0.0],
        15.0,
    );
    let log = run_trial(&setup, None, &mut []).expect("a valid trial");
    let settled: Vec<_> = log.steps.iter().filter(|s| s.time > 5.0).collect();
    let n = settled.len().max(1) as f64;
    let mean = settled.iter().map(|s| s.f_hat).sum::<f64>() / n;
    let err = settled.iter().map(|s| s.f_e().abs()).sum::<f64>() / n;
    (mean, err, log.falls.len(), settled.len())
}

fn main() {
    for arg in std::env::args().skip(1) {
        let v: Vec<f64> = arg
            .split(',')
            .map(|x| x.parse().expect("EARLY,GAIN,LIFT,BAND as numbers"))
            .collect();
        assert_eq!(v.len(), 4, "give EARLY,GAIN,LIFT,BAND");
        let mut s = Settings::default();
        s.walker.motion.early_landing_phase = v[0];
        s.walker.motion.tilt_gain = v[1];
        s.walker.motion.tilt_lift = v[2];
        s.walker.motion.tilt_gain_band = v[3];
        s.validate().expect("settings in range");
        for f_r in [-0.1, 0.0, 0.1, 0.2] {
            let (m, err, falls, n) = figures(&s, f_r);
            println!(
                "{arg:18} F_R {f_r:+.1}: mean step {m:+.4} m, error {:+.4} m, mean |error| {err:.4} m, falls {falls}, steps {n}",
                m - f_r
            );
        }
    }
}
