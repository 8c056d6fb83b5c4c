//! Paired comparisons over seeds: the learned walker against the model, seed by seed,
//! summarised by the mean of the per-seed differences (or ratios) and its two-sided 95%
//! Student-t interval.
//!
//! When two walkers are equally good, "learned >= model on every seed" is a coin toss per seed:
//! with 10 seeds it fails almost surely. The interval says whether a difference is larger than
//! the seed-to-seed noise, so a reproduction can tell "level" from "worse" (or "better").
//!
//! ```
//! use steplearn::experiments::paired::{Direction, Paired, Verdict};
//! // I50 learned / model on five seeds.
//! let p = Paired::new("I50 learned / model", &[0.97, 1.00, 1.03, 0.97, 1.00], 1.0, Direction::HigherIsBetter);
//! assert_eq!(p.verdict, Some(Verdict::Level));
//! assert!(p.ci95.0 < 1.0 && p.ci95.1 > 1.0);
//! ```

use crate::stats::MeanStd;
use serde::{Deserialize, Serialize};

/// Which way is better for the learned walker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Direction {
    /// A larger value is better (an impulse ratio, pushes absorbed).
    HigherIsBetter,
    /// A smaller value is better (a step error spread, a return time, falls).
    LowerIsBetter,
}

/// The learned walker's standing against the model at 95% confidence.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, strum::Display)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum Verdict {
    /// The interval lies on the better side of the no-difference value.
    Better,
    /// The interval contains the no-difference value: no difference beyond the seed noise.
    Level,
    /// The interval lies on the worse side.
    Worse,
}

/// One paired comparison over seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paired {
    /// What is compared, in words (for example `"I50 learned / model"`).
    pub quantity: String,
    /// The per-seed values (differences or ratios), in seed order.
    pub values: Vec<f64>,
    /// The value at which learned and model are equal (0 for differences, 1 for ratios).
    pub null: f64,
    /// Which way is better for the learned walker.
    pub direction: Direction,
    /// Mean of `values` (NaN without values).
    pub mean: f64,
    /// Two-sided 95% Student-t interval of the mean; NaN with fewer than two values.
    pub ci95: (f64, f64),
    /// Standing at 95% confidence; `None` with fewer than two values.
    pub verdict: Option<Verdict>,
}

impl Paired {
    /// Summarises the per-seed `values` (non-finite values are left out: a seed without the
    /// figure does not count).
    pub fn new(quantity: &str, values: &[f64], null: f64, direction: Direction) -> Self {
        let values: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
        let stats = MeanStd::of(values.iter().copied());
        let (ci95, verdict) = match stats.ci95_half_width() {
            None => ((f64::NAN, f64::NAN), None),
            Some(half) => {
                let (lo, hi) = (stats.mean() - half, stats.mean() + half);
                let higher = lo > null;
                let lower = hi < null;
                let verdict =
                    match (higher, lower, direction) {
                        (true, _, Direction::HigherIsBetter)
                        | (_, true, Direction::LowerIsBetter) => Verdict::Better,
                        (true, _, Direction::LowerIsBetter)
                        | (_, true, Direction::HigherIsBetter) => Verdict::Worse,
                        _ => Verdict::Level,
                    };
                ((lo, hi), Some(verdict))
            }
        };
        Paired {
            quantity: quantity.to_string(),
            null,
            direction,
            mean: stats.mean(),
            ci95,
            verdict,
            values,
        }
    }

    /// One line: `"I50 learned / model: 1.003 [0.981, 1.025] over 10 seeds: level"`, numbers
    /// with `decimals` decimals.
    pub fn describe(&self, decimals: usize) -> String {
        let n = self.values.len();
        match self.verdict {
            Some(v) => format!(
                "{}: {:.d$} [{:.d$}, {:.d$}] over {n} seeds: {v}",
                self.quantity,
                self.mean,
                self.ci95.0,
                self.ci95.1,
                d = decimals
            ),
            None => format!(
                "{}: {:.d$} over {n} seed(s): too few seeds for an interval",
                self.quantity,
                self.mean,
                d = decimals
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interval_and_verdicts() {
        // mean 2, sample std 1, n 4: half width 3.182 / 2.
        let p = Paired::new("x", &[1.0, 2.0, 3.0, 2.0], 0.0, Direction::HigherIsBetter);
        let half = 3.182446 * (2.0f64 / 3.0).sqrt() / 2.0;
        assert!((p.ci95.0 - (2.0 - half)).abs() < 1e-5);
        assert!((p.ci95.1 - (2.0 + half)).abs() < 1e-5);
        assert_eq!(p.verdict, Some(Verdict::Better));
        let q = Paired::new("x", &[1.0, 2.0, 3.0, 2.0], 0.0, Direction::LowerIsBetter);
        assert_eq!(q.verdict, Some(Verdict::Worse));
        let level = Paired::new("x", &[-1.0, 1.0, -0.5, 0.5], 0.0, Direction::LowerIsBetter);
        assert_eq!(level.verdict, Some(Verdict::Level));
        assert!(
            level.describe(2).ends_with("over 4 seeds: level"),
            "{}",
            level.describe(2)
        );
    }

    #[test]
    fn too_few_or_non_finite_values_give_no_verdict() {
        let p = Paired::new("x", &[1.0, f64::NAN], 0.0, Direction::HigherIsBetter);
        assert_eq!(p.values, vec![1.0]);
        assert_eq!(p.verdict, None);
        assert!(p.ci95.0.is_nan());
        let empty = Paired::new("x", &[], 1.0, Direction::HigherIsBetter);
        assert!(empty.mean.is_nan());
        assert!(empty.describe(1).contains("too few seeds"));
    }
}
