//! The step-time learner's loop gain on the humanoid: walks undisturbed with a fixed step-time
//! offset dT (no learning) and measures the LIPM step-time gradient G_T (`rules::StepTime`) at
//! every touch-down. The slope k_T = -dG_T/d(dT) sets the stability limit of the step-time
//! update dT <- dT + gain G_T: it settles monotonically for gain < 1/k_T, oscillates but
//! settles below 2/k_T and grows beyond (the learner's gain guard, `max_gain`, caps the gain).
//!
//! A run with a fall is printed but left out of the slope.
//!
//! Prints, per reference F_R and offset dT: the touch-downs counted, falls, mean G_T and its
//! standard error; then the least-squares slope per F_R and the limits it implies.
//!
//! `--parameter ankle-pitch` measures the same for the support sole's pitch offset dA and its
//! rule (`rules::SoleTilt`, G_A): the slope k_A = -dG_A/d(dA) bounds the gain of
//! dA <- dA + gain G_A the same way; `--parameter ankle-roll --plane frontal` for its roll dR
//! (G_R, the frontal plane's).
//!
//! `cargo run --release -p steplearn-probes --bin step_time_gain -- --seconds 40 [--plane frontal]
//! [--parameter ankle-pitch | ankle-roll]`

use clap::Parser;
use std::path::PathBuf;
use steplearn::control::{FootstepPolicy, StepReports, WalkerMode};
use steplearn::control::{LearnSet, PerParameter, Plane, StepParameter};
use steplearn::control::{LearnerError, LearnerInput, TouchDownReport};
use steplearn::experiments::schedule::ReferenceSchedule;
use steplearn::experiments::trial::run_trial;
use steplearn::experiments::{sole_tilt_rule, step_time_rule};
use steplearn::rules::{LearningRule, StepOutcome};
use steplearn::stats::MeanStd;

#[derive(Parser)]
struct Args {
    /// Walking time per run (s).
    #[arg(long, default_value_t = 40.0)]
    seconds: f64,
    /// Touch-downs before this time are not counted (s).
    #[arg(long, default_value_t = 5.0)]
    settle: f64,
    /// The fixed offsets dT (s), comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "-0.08,-0.04,0,0.04,0.08"
    )]
    offsets: Vec<f64>,
    /// The references F_R (m per step), comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0,0.1"
    )]
    references: Vec<f64>,
    /// Settings file (`steplearn config` format) for the robot and walker.
    #[arg(long)]
    config: Option<PathBuf>,
    /// The plane whose outcome G_T is measured in (`sagittal` or `frontal`, the rule of
    /// `[settings.learner.step-time] plane`).
    #[arg(long, default_value = "sagittal")]
    plane: Plane,
    /// The parameter held fixed and whose gradient is measured: `step-time` (G_T),
    /// `ankle-pitch` (G_A, sagittal only; offsets in rad) or `ankle-roll` (G_R, frontal only;
    /// offsets in rad).
    #[arg(long, default_value = "step-time")]
    parameter: StepParameter,
}

/// A fixed offset of one parameter that records its rule's gradient at every touch-down.
struct FixedTime {
    parameter: StepParameter,
    offset: f64,
    rule: Box<dyn LearningRule>,
    plane: Plane,
    gradients: Vec<f64>,
}

impl FootstepPolicy for FixedTime {
    fn learns(&self) -> LearnSet {
        LearnSet::of(&[self.parameter]).expect("one parameter")
    }
    fn offsets(
        &mut self,
        _inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        Ok(PerParameter::only(self.parameter, self.offset))
    }
    fn set_reach(&mut self, _reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        Ok(())
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        let outcome = outcomes.in_plane(self.parameter, self.plane);
        self.gradients.push(self.rule.gradient(outcome));
        Ok(PerParameter::only(
            self.parameter,
            Some(TouchDownReport::default()),
        ))
    }
    fn fall(&mut self, _outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        Ok(StepReports::default())
    }
    fn discard_step(&mut self) {}
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    if !(args.seconds.is_finite() && args.seconds > args.settle && args.settle >= 0.0) {
        return Err("--seconds must exceed --settle >= 0".into());
    }
    if args.offsets.len() < 2 || args.offsets.iter().any(|o| !o.is_finite()) {
        return Err("--offsets needs at least two finite values".into());
    }
    let rule = |settings: &steplearn::experiments::settings::Settings| -> Result<Box<dyn LearningRule>, String> {
        match (args.parameter, args.plane) {
            (StepParameter::StepTime, plane) => Ok(Box::new(step_time_rule(plane, &settings.walker))),
            (p @ StepParameter::AnklePitch, Plane::Sagittal)
            | (p @ StepParameter::AnkleRoll, Plane::Frontal) => {
                Ok(Box::new(sole_tilt_rule(p, &settings.walker)))
            }
            (p, plane) => Err(format!("--parameter {p} in the {plane} plane is not measured here")),
        }
    };
    let settings = steplearn_probes::settings(args.config.as_deref()).map_err(|e| e.to_string())?;
    rule(&settings)?;
    // The offset's symbol and unit in the printed lines.
    let (x, unit) = match args.parameter {
        StepParameter::AnklePitch => ("A", "rad"),
        StepParameter::AnkleRoll => ("R", "rad"),
        _ => ("T", "s"),
    };
    let g = format!("g_{}", x.to_lowercase());
    println!("f_r_m,offset_{unit},touch_downs,falls,mean_{g},se_{g}");
    for &f_r in &args.references {
        let mut points = Vec::new();
        for &offset in &args.offsets {
            let setup = settings.trial(
                WalkerMode::CaptureStep,
                ReferenceSchedule::constant(f_r),
                Vec::new(),
                [1.0, 0.0, 0.0],
                args.seconds,
            );
            let mut policy = FixedTime {
                parameter: args.parameter,
                offset,
                rule: rule(&settings)?,
                plane: args.plane,
                gradients: Vec::new(),
            };
            let log = run_trial(&setup, Some(&mut policy), &mut [])?;
            let counted: Vec<f64> = log
                .steps
                .iter()
                .zip(&policy.gradients)
                .filter(|(s, _)| s.time >= args.settle)
                .map(|(_, g)| *g)
                .collect();
            let s = MeanStd::of(counted.iter().copied());
            let se = s.sample_std() / (s.count().max(1) as f64).sqrt();
            println!(
                "{f_r},{offset},{},{},{:.6},{:.6}",
                s.count(),
                log.falls.len(),
                s.mean(),
                se
            );
            if log.falls.is_empty() && s.count() > 0 {
                points.push((offset, s.mean()));
            }
        }
        for w in points.windows(2) {
            let k = -(w[1].1 - w[0].1) / (w[1].0 - w[0].0);
            println!(
                "# F_R {f_r}: d{x} {} to {}: k_{x} {k:.4} per {unit}{}",
                w[0].0,
                w[1].0,
                if k < 0.0 {
                    " (the gradient grows with the offset: the iteration runs away from here whatever the gain)"
                } else {
                    ""
                }
            );
        }
        if points.len() >= 2 {
            let n = points.len() as f64;
            let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
            let my = points.iter().map(|p| p.1).sum::<f64>() / n;
            let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
            let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
            let k = -sxy / sxx;
            if k > 0.0 {
                println!(
                    "# F_R {f_r}: fitted k_{x} = -dG_{x}/d(d{x}) = {k:.4} per {unit}; monotone below gain \
                     {:.3}, stable below {:.3} ({unit} per unit of G_{x})",
                    1.0 / k,
                    2.0 / k
                );
            } else {
                println!(
                    "# F_R {f_r}: fitted k_{x} = {k:.4} per {unit}: G_{x} grows with d{x}, no gain is stable"
                );
            }
        }
    }
    Ok(())
}
