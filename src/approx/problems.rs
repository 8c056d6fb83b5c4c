//! Seeded regression problems used to test, benchmark and compare approximators.
//!
//! Each problem draws a training stream (with noise) and a noiseless test set from a
//! [`ChaCha8Rng`] seeded by the caller, so every figure computed from them is reproducible.

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use rand_distr::{Distribution, Normal};

/// A regression problem: a target function over a box of inputs.
#[derive(Debug, Clone)]
pub struct Problem {
    /// Short name (used in tables).
    pub name: &'static str,
    /// Lower corner of the input box.
    pub lo: Vec<f64>,
    /// Upper corner of the input box.
    pub hi: Vec<f64>,
    /// Standard deviation of the Gaussian noise added to training targets.
    pub noise: f64,
    target: fn(&[f64]) -> f64,
}

/// The "cross" function of the LWPR papers: max(exp(-10 x1^2), exp(-50 x2^2), 1.25 exp(-5 |x|^2)).
pub fn cross(x: &[f64]) -> f64 {
    let (a, b) = (x[0], x[1]);
    (-10.0 * a * a)
        .exp()
        .max((-50.0 * b * b).exp())
        .max(1.25 * (-5.0 * (a * a + b * b)).exp())
}

/// The 3-input step-offset map: 0.3 tanh(2 theta) + 0.05 theta_dot + 0.5 F_R.
pub fn step_offset(x: &[f64]) -> f64 {
    0.3 * (2.0 * x[0]).tanh() + 0.05 * x[1] + 0.5 * x[2]
}

/// Ten inputs of which only the first two matter: cross(x1, x2).
pub fn cross_in_10d(x: &[f64]) -> f64 {
    cross(&x[..2])
}

impl Problem {
    /// Cross 2D on [-1, 1]^2 with noise 0.1 (the LWPR library's demo).
    pub fn cross_2d() -> Self {
        Problem {
            name: "cross-2d",
            lo: vec![-1.0; 2],
            hi: vec![1.0; 2],
            noise: 0.1,
            target: cross,
        }
    }

    /// The step-offset map over (theta in +-0.5 rad, theta_dot in +-3 rad/s, F_R in [-0.1, 0.2] m),
    /// noise 0.01: the shape of the map the walker's learner builds.
    pub fn step_offset_3d() -> Self {
        Problem {
            name: "step-offset-3d",
            lo: vec![-0.5, -3.0, -0.1],
            hi: vec![0.5, 3.0, 0.2],
            noise: 0.01,
            target: step_offset,
        }
    }

    /// Cross 2D embedded in 10 inputs on [-1, 1]^10, 8 of them irrelevant; noise 0.1.
    pub fn cross_10d() -> Self {
        Problem {
            name: "cross-10d",
            lo: vec![-1.0; 10],
            hi: vec![1.0; 10],
            noise: 0.1,
            target: cross_in_10d,
        }
    }

    /// Number of inputs.
    pub fn dim(&self) -> usize {
        self.lo.len()
    }

    /// Half the width of the input box per dimension (a natural input normalisation).
    pub fn half_ranges(&self) -> Vec<f64> {
        self.lo
            .iter()
            .zip(&self.hi)
            .map(|(l, h)| 0.5 * (h - l))
            .collect()
    }

    /// The noiseless target at `x`.
    pub fn eval(&self, x: &[f64]) -> f64 {
        (self.target)(x)
    }

    /// `n` training samples, inputs uniform in the box, targets with Gaussian noise.
    pub fn train_stream(&self, seed: u64, n: usize) -> Vec<(Vec<f64>, f64)> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let noise = Normal::new(0.0, self.noise).expect("noise is a finite non-negative sd");
        (0..n)
            .map(|_| {
                let x: Vec<f64> = self
                    .lo
                    .iter()
                    .zip(&self.hi)
                    .map(|(&l, &h)| rng.random_range(l..h))
                    .collect();
                let y = self.eval(&x) + noise.sample(&mut rng);
                (x, y)
            })
            .collect()
    }

    /// A noiseless test set: a regular grid with `per_dim` points per axis for up to 3 inputs
    /// (41 x 41 for cross 2D, as in the LWPR demo), otherwise `per_dim^2` seeded uniform points.
    pub fn test_set(&self, per_dim: usize) -> Vec<(Vec<f64>, f64)> {
        let d = self.dim();
        let xs: Vec<Vec<f64>> = if d <= 3 {
            let total = per_dim.pow(d as u32);
            (0..total)
                .map(|mut k| {
                    (0..d)
                        .map(|i| {
                            let j = k % per_dim;
                            k /= per_dim;
                            self.lo[i]
                                + (self.hi[i] - self.lo[i]) * j as f64 / (per_dim - 1).max(1) as f64
                        })
                        .collect()
                })
                .collect()
        } else {
            let mut rng = ChaCha8Rng::seed_from_u64(0x7e57);
            (0..per_dim * per_dim)
                .map(|_| {
                    self.lo
                        .iter()
                        .zip(&self.hi)
                        .map(|(&l, &h)| rng.random_range(l..h))
                        .collect()
                })
                .collect()
        };
        xs.into_iter()
            .map(|x| {
                let y = self.eval(&x);
                (x, y)
            })
            .collect()
    }
}

/// Normalised mean squared error: MSE of `predicted` against `truth`, divided by the variance
/// of `truth`.
pub fn nmse(predicted: &[f64], truth: &[f64]) -> f64 {
    assert_eq!(predicted.len(), truth.len(), "nmse needs equal lengths");
    let n = truth.len() as f64;
    let mean = truth.iter().sum::<f64>() / n;
    let var = truth.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / n;
    let mse = predicted
        .iter()
        .zip(truth)
        .map(|(p, t)| (p - t).powi(2))
        .sum::<f64>()
        / n;
    mse / var
}

/// An endless 3-input stream whose inputs drift: they move along a path (the first input
/// grows by `speed` per sample, the second follows its sine) with uniform spread `+-spread`
/// around it, the target a smooth function of where they are. A model that never forgets keeps
/// adding local models along the path; the test of [`LwprConfig::max_rfs`](super::LwprConfig::max_rfs).
#[derive(Debug)]
pub struct Drift {
    rng: ChaCha8Rng,
    t: u64,
    speed: f64,
    spread: f64,
}

impl Drift {
    /// A drift of `speed` input units per sample with spread `+-spread`, seeded.
    pub fn new(seed: u64, speed: f64, spread: f64) -> Self {
        Drift {
            rng: ChaCha8Rng::seed_from_u64(seed),
            t: 0,
            speed,
            spread,
        }
    }

    /// The target at `x`: sin(2 x_0) + x_1 x_2 / 2.
    pub fn target(x: &[f64; 3]) -> f64 {
        (2.0 * x[0]).sin() + 0.5 * x[1] * x[2]
    }
}

impl Iterator for Drift {
    type Item = ([f64; 3], f64);
    fn next(&mut self) -> Option<Self::Item> {
        let p = self.t as f64 * self.speed;
        self.t += 1;
        let s = self.spread;
        let mut r = || self.rng.random_range(-s..s);
        let x = [p + r(), p.sin() + r(), r()];
        Some((x, Drift::target(&x)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_seeded_and_in_the_box() {
        let p = Problem::step_offset_3d();
        let a = p.train_stream(7, 100);
        assert_eq!(a, p.train_stream(7, 100));
        assert_ne!(a, p.train_stream(8, 100));
        for (x, _) in &a {
            for ((v, lo), hi) in x.iter().zip(&p.lo).zip(&p.hi) {
                assert!(v >= lo && v < hi);
            }
        }
    }

    #[test]
    fn cross_test_grid_is_41_by_41_and_peaks_at_origin() {
        let t = Problem::cross_2d().test_set(41);
        assert_eq!(t.len(), 41 * 41);
        let max = t.iter().map(|(_, y)| *y).fold(f64::MIN, f64::max);
        assert_eq!(max, 1.25);
        assert_eq!(cross(&[0.0, 0.0]), 1.25);
    }

    #[test]
    fn nmse_of_truth_is_zero_and_of_mean_is_one() {
        let truth = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(nmse(&truth, &truth), 0.0);
        assert!((nmse(&[2.5; 4], &truth) - 1.0).abs() < 1e-12);
    }
}
