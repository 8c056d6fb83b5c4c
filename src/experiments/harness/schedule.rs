//! Seeded schedules of what the experiments do to the robot: reference step-size changes and
//! pushes.
//!
//! Both are drawn up front from a [`ChaCha8Rng`], so that the *model* and *learned* controllers
//! of one experiment see exactly the same sequence (the paper: "the same random step size
//! sequence was presented to both controllers").

use crate::experiments::ExperimentError;
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};

/// A piecewise-constant reference step size F_R(t).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceSchedule {
    /// `(start time s, F_R m)`, sorted by time, the first at t = 0.
    pub segments: Vec<(f64, f64)>,
}

impl ReferenceSchedule {
    /// A constant reference.
    pub fn constant(f_r: f64) -> Self {
        ReferenceSchedule {
            segments: vec![(0.0, f_r)],
        }
    }

    /// Random references uniform in `range` (m), each held for a time uniform in `hold` (s),
    /// covering `[0, duration]` (experiment A: [-0.1, 0.2] m held 4-8 s).
    ///
    /// # Errors
    /// [`ExperimentError::Invalid`] if `range` is not finite and ordered, `hold` not positive,
    /// finite and ordered, or `duration` not finite and non-negative.
    pub fn random(
        seed: u64,
        duration: f64,
        range: (f64, f64),
        hold: (f64, f64),
    ) -> Result<Self, ExperimentError> {
        let ordered = |(lo, hi): (f64, f64)| lo.is_finite() && hi.is_finite() && lo <= hi;
        if !ordered(range) {
            return Err(ExperimentError::Invalid(format!(
                "reference range [{}, {}] must be finite and ordered",
                range.0, range.1
            )));
        }
        if !(ordered(hold) && hold.0 > 0.0) {
            return Err(ExperimentError::Invalid(format!(
                "hold [{}, {}] s must be positive, finite and ordered",
                hold.0, hold.1
            )));
        }
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(ExperimentError::Invalid(format!(
                "duration {duration} s must be finite and non-negative"
            )));
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut segments = Vec::new();
        let mut t = 0.0;
        while t < duration {
            segments.push((t, uniform(&mut rng, range)));
            t += uniform(&mut rng, hold);
        }
        Ok(ReferenceSchedule { segments })
    }

    /// Random two-dimensional references `[F_R, F_R,y]` uniform over the disc of `radius` (m)
    /// around 0, each held for a time uniform in `hold` (s), covering `[0, duration]`: the
    /// sagittal and the lateral schedule, changing together.
    ///
    /// # Errors
    /// [`ExperimentError::Invalid`] if `radius` is not finite and non-negative, or `hold` or
    /// `duration` are invalid as for [`ReferenceSchedule::random`].
    pub fn random_disc(
        seed: u64,
        duration: f64,
        radius: f64,
        hold: (f64, f64),
    ) -> Result<[Self; 2], ExperimentError> {
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(ExperimentError::Invalid(format!(
                "reference radius {radius} m must be finite and non-negative"
            )));
        }
        // The hold and the duration are checked as for a one-dimensional schedule.
        Self::random(seed, duration, (0.0, 0.0), hold)?;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let [mut x, mut y] = [Vec::new(), Vec::new()];
        let mut t = 0.0;
        while t < duration {
            // Uniform over the disc's area.
            let r = radius * uniform(&mut rng, (0.0, 1.0)).sqrt();
            let a = uniform(&mut rng, (0.0, std::f64::consts::TAU));
            x.push((t, r * a.cos()));
            y.push((t, r * a.sin()));
            t += uniform(&mut rng, hold);
        }
        Ok([
            ReferenceSchedule { segments: x },
            ReferenceSchedule { segments: y },
        ])
    }

    /// The reference in force at time `t`.
    pub fn at(&self, t: f64) -> f64 {
        let i = self.segments.partition_point(|&(start, _)| start <= t);
        self.segments[i.saturating_sub(1)].1
    }

    /// The times at which the reference changes (every segment start after the first).
    pub fn change_times(&self) -> Vec<f64> {
        self.segments.iter().skip(1).map(|&(t, _)| t).collect()
    }
}

/// Whether `direction` is a finite unit vector (norm within 1e-6 of 1), as every push
/// direction must be.
pub fn is_unit_direction(direction: &[f64; 3]) -> bool {
    let norm = direction.iter().map(|d| d * d).sum::<f64>().sqrt();
    norm.is_finite() && (norm - 1.0).abs() < 1e-6
}

/// One scheduled push on the trunk.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Push {
    /// When it starts (s since the start of the trial).
    pub time: f64,
    /// Impulse magnitude (Ns).
    pub impulse: f64,
}

/// How to draw pushes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PushPlan {
    /// Number of pushes.
    pub count: usize,
    /// Impulse magnitudes are uniform in this range (Ns); equal ends give a constant impulse.
    pub impulse: (f64, f64),
    /// Time before the first push (s), to let the gait settle.
    pub settle: f64,
    /// Gap between pushes is uniform in this range (s); its randomness spreads the pushes over
    /// the gait phase.
    pub gap: (f64, f64),
}

impl PushPlan {
    /// Draws the pushes from `seed`.
    pub fn draw(&self, seed: u64) -> Vec<Push> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut t = self.settle;
        (0..self.count)
            .map(|_| {
                t += uniform(&mut rng, self.gap);
                Push {
                    time: t,
                    impulse: uniform(&mut rng, self.impulse),
                }
            })
            .collect()
    }
}

fn uniform(rng: &mut ChaCha8Rng, (lo, hi): (f64, f64)) -> f64 {
    if hi > lo {
        rng.random_range(lo..hi)
    } else {
        lo
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disc_references_stay_in_the_disc_and_change_together() {
        let [x, y] = ReferenceSchedule::random_disc(3, 200.0, 0.08, (4.0, 8.0)).unwrap();
        assert_eq!(x.change_times(), y.change_times());
        assert!(x.segments.len() >= 25, "{}", x.segments.len());
        let radii: Vec<f64> = x
            .segments
            .iter()
            .zip(&y.segments)
            .map(|(a, b)| a.1.hypot(b.1))
            .collect();
        assert!(radii.iter().all(|r| *r <= 0.08 + 1e-12));
        // Uniform over the area: about a quarter inside half the radius.
        let inner = radii.iter().filter(|r| **r < 0.04).count() as f64 / radii.len() as f64;
        assert!((0.05..0.5).contains(&inner), "{inner}");
        // Every quadrant is visited.
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
            assert!(
                x.segments
                    .iter()
                    .zip(&y.segments)
                    .any(|(a, b)| a.1 * sx > 0.0 && b.1 * sy > 0.0)
            );
        }
        assert!(ReferenceSchedule::random_disc(3, 10.0, f64::NAN, (4.0, 8.0)).is_err());
        assert!(ReferenceSchedule::random_disc(3, 10.0, 0.1, (0.0, 8.0)).is_err());
    }

    #[test]
    fn unit_direction_check() {
        assert!(is_unit_direction(&[1.0, 0.0, 0.0]));
        assert!(is_unit_direction(&[0.6, 0.8, 0.0]));
        assert!(!is_unit_direction(&[1.0, 1.0, 0.0]));
        assert!(!is_unit_direction(&[0.0, 0.0, 0.0]));
        assert!(!is_unit_direction(&[f64::NAN, 0.0, 0.0]));
        assert!(!is_unit_direction(&[f64::INFINITY, 0.0, 0.0]));
    }

    #[test]
    fn random_reference_covers_duration_within_bounds() {
        let r = ReferenceSchedule::random(3, 100.0, (-0.1, 0.2), (4.0, 8.0)).unwrap();
        assert_eq!(
            r,
            ReferenceSchedule::random(3, 100.0, (-0.1, 0.2), (4.0, 8.0)).unwrap()
        );
        assert_eq!(r.segments[0].0, 0.0);
        for w in r.segments.windows(2) {
            let hold = w[1].0 - w[0].0;
            assert!((4.0..8.0).contains(&hold), "hold {hold}");
        }
        assert!(r.segments.last().unwrap().0 < 100.0);
        assert!(r.segments.iter().all(|&(_, f)| (-0.1..0.2).contains(&f)));
        assert_eq!(r.at(0.0), r.segments[0].1);
        let (t1, f1) = r.segments[1];
        assert_eq!(r.at(t1), f1);
        assert_eq!(r.at(t1 - 1e-9), r.segments[0].1);
        assert_eq!(r.change_times().len(), r.segments.len() - 1);
    }

    #[test]
    fn random_reference_rejects_bad_ranges() {
        let bad = [
            (100.0, (0.2, -0.1), (4.0, 8.0)),
            (100.0, (f64::NAN, 0.2), (4.0, 8.0)),
            (100.0, (-0.1, 0.2), (0.0, 8.0)),
            (100.0, (-0.1, 0.2), (8.0, 4.0)),
            (100.0, (-0.1, 0.2), (4.0, f64::INFINITY)),
            (f64::INFINITY, (-0.1, 0.2), (4.0, 8.0)),
            (-1.0, (-0.1, 0.2), (4.0, 8.0)),
        ];
        for (duration, range, hold) in bad {
            assert!(
                matches!(
                    ReferenceSchedule::random(1, duration, range, hold),
                    Err(ExperimentError::Invalid(_))
                ),
                "{duration} {range:?} {hold:?}"
            );
        }
    }

    #[test]
    fn pushes_are_seeded_spaced_and_in_range() {
        let plan = PushPlan {
            count: 50,
            impulse: (0.0, 20.0),
            settle: 5.0,
            gap: (3.0, 4.0),
        };
        let p = plan.draw(9);
        assert_eq!(p, plan.draw(9));
        assert_ne!(p, plan.draw(10));
        assert!(p[0].time >= 8.0 && p[0].time < 9.0);
        for w in p.windows(2) {
            assert!((3.0..4.0).contains(&(w[1].time - w[0].time)));
        }
        assert!(p.iter().all(|x| (0.0..20.0).contains(&x.impulse)));
        let constant = PushPlan {
            impulse: (8.0, 8.0),
            ..plan
        };
        assert!(constant.draw(1).iter().all(|x| x.impulse == 8.0));
    }
}
