//! A k-nearest-neighbour table: a user's own approximator.

use serde::{Deserialize, Serialize};
use steplearn::approx::{
    ApproxError, FunctionApproximator, InputBox, Persist, check_output, check_vector,
};

/// Keeps up to `capacity` samples; predicts a kernel-weighted mean of the `k` nearest targets
/// (distances in units of the input box's half-widths), fading to 0 away from the data. A
/// sample closer than `merge` to a stored one replaces it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Knn {
    k: usize,
    capacity: usize,
    width: f64,
    merge: f64,
    half: Vec<f64>,
    xs: Vec<Vec<f64>>,
    ys: Vec<f64>,
    next: usize,
}

impl Knn {
    /// An empty table over `bounds`: k = 8, 4000 samples, kernel width 0.15, merge radius 0.02.
    pub fn new(bounds: &InputBox) -> Result<Self, ApproxError> {
        let half = bounds
            .lo
            .iter()
            .zip(&bounds.hi)
            .map(|(l, h)| 0.5 * (h - l))
            .collect();
        let knn = Knn {
            k: 8,
            capacity: 4000,
            width: 0.15,
            merge: 0.02,
            half,
            xs: vec![],
            ys: vec![],
            next: 0,
        };
        knn.check_invariants()?;
        Ok(knn)
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        let d2: f64 = a
            .iter()
            .zip(b)
            .zip(&self.half)
            .map(|((a, b), h)| ((a - b) / h).powi(2))
            .sum();
        d2.sqrt()
    }

    /// The `k` nearest stored samples: (distance, index), nearest first.
    fn nearest(&self, x: &[f64]) -> Vec<(f64, usize)> {
        let mut d: Vec<(f64, usize)> = self
            .xs
            .iter()
            .enumerate()
            .map(|(i, s)| (self.distance(x, s), i))
            .collect();
        d.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        d.truncate(self.k);
        d
    }
}

impl FunctionApproximator for Knn {
    fn input_dim(&self) -> usize {
        self.half.len()
    }
    fn output_dim(&self) -> usize {
        1
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("x", x, self.half.len())?;
        check_output("y", y, 1)?;
        // A prior weight of exp(-2) at 0: predictions fade to 0 beyond two kernel widths.
        let (mut num, mut den) = (0.0, (-2.0f64).exp());
        for (d, i) in self.nearest(x) {
            let w = (-0.5 * (d / self.width).powi(2)).exp();
            num += w * self.ys[i];
            den += w;
        }
        y[0] = num / den;
        Ok(())
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        check_vector("x", x, self.half.len())?;
        check_vector("y", y, 1)?;
        match self.nearest(x).first() {
            Some(&(d, i)) if d < self.merge => {
                self.xs[i] = x.to_vec();
                self.ys[i] = y[0];
            }
            _ if self.xs.len() < self.capacity => {
                self.xs.push(x.to_vec());
                self.ys.push(y[0]);
            }
            _ => {
                self.xs[self.next] = x.to_vec();
                self.ys[self.next] = y[0];
                self.next = (self.next + 1) % self.capacity;
            }
        }
        Ok(())
    }
}

impl Persist for Knn {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        let ok = self.k >= 1
            && (1..=1_000_000).contains(&self.capacity)
            && self.width > 0.0
            && self.width.is_finite()
            && (0.0..1.0).contains(&self.merge)
            && !self.half.is_empty()
            && self.half.iter().all(|h| h.is_finite() && *h > 0.0)
            && self.xs.len() == self.ys.len()
            && self.xs.len() <= self.capacity
            && self.next < self.capacity
            && self
                .xs
                .iter()
                .all(|x| x.len() == self.half.len() && finite(x))
            && finite(&self.ys);
        if ok {
            Ok(())
        } else {
            Err(ApproxError::Corrupt("inconsistent k-NN table".into()))
        }
    }
}
