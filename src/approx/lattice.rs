//! A regular lattice of nodes over an [`InputBox`] and sparse tensor-product weights on it.
//!
//! [`Grid`](super::Grid) (multilinear interpolation: 2 weights per dimension) and
//! [`Rbf`](super::Rbf) (a window of normalised 1-D Gaussians per dimension) both express a
//! prediction as `sum_j phi_j(x) w_j` where `phi_j` is a product of per-dimension weights.
//! [`TensorWeights`] holds those per-dimension factors on the stack, so neither model allocates
//! per prediction or update.

use super::{ApproxError, InputBox};
use serde::{Deserialize, Serialize};

/// Largest number of inputs a lattice model accepts (a tensor grid beyond that is hopeless).
pub const MAX_LATTICE_DIM: usize = 16;

/// A regular lattice: `counts[i]` nodes along dimension `i`, evenly spaced over the box
/// (a single node sits at the centre of its dimension). Node `(j_0, ..., j_{d-1})` has flat
/// index `sum_i j_i * strides[i]`, dimension 0 varying fastest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Lattice {
    /// The box the lattice spans.
    pub bounds: InputBox,
    /// Nodes per dimension (each >= 1).
    pub counts: Vec<usize>,
}

impl Lattice {
    /// A checked lattice with at most `max_nodes` nodes.
    ///
    /// `what` names the count parameter in errors (e.g. `"resolution"`).
    pub fn new(
        bounds: InputBox,
        counts: Vec<usize>,
        max_nodes: usize,
        what: &'static str,
    ) -> Result<Self, ApproxError> {
        let lattice = Lattice { bounds, counts };
        lattice.validate(max_nodes, what)?;
        Ok(lattice)
    }

    /// Checks the box, the counts and the node budget.
    pub fn validate(&self, max_nodes: usize, what: &'static str) -> Result<(), ApproxError> {
        self.bounds.validate()?;
        let d = self.bounds.dim();
        if d > MAX_LATTICE_DIM {
            return Err(ApproxError::config(
                "bounds",
                format!("{d} inputs: a tensor lattice supports at most {MAX_LATTICE_DIM}"),
            ));
        }
        if self.counts.len() != d {
            return Err(ApproxError::config(
                what,
                format!("has {} entries for {d} inputs", self.counts.len()),
            ));
        }
        if let Some(i) = self.counts.iter().position(|&c| c == 0) {
            return Err(ApproxError::config(
                what,
                format!("dimension {i} has 0 nodes"),
            ));
        }
        // Product in f64 so that absurd requests are reported with their size, not overflow.
        let total: f64 = self.counts.iter().map(|&c| c as f64).product();
        if total > max_nodes as f64 {
            return Err(ApproxError::config(
                what,
                format!(
                    "{:?} needs {total:.3e} nodes, more than the limit of {max_nodes} \
                     (a tensor lattice grows exponentially with the number of inputs)",
                    self.counts
                ),
            ));
        }
        Ok(())
    }

    /// Checks a loaded model's table against its lattice: `self` must be the lattice the
    /// model's config builds (`expected`) and `table` must hold one finite `entry` per node and
    /// output. Returns what is wrong, for the model's `Corrupt` error.
    pub(crate) fn check_table(
        &self,
        expected: Result<Lattice, ApproxError>,
        table: &[f64],
        outputs: usize,
        entry: &str,
    ) -> Result<(), String> {
        let lattice = expected.map_err(|e| format!("invalid config: {e}"))?;
        if lattice != *self {
            return Err("lattice does not match the config".into());
        }
        if Some(table.len()) != self.len().checked_mul(outputs) {
            return Err(format!(
                "{} {entry}s for {} nodes x {outputs} outputs",
                table.len(),
                self.len()
            ));
        }
        match table.iter().position(|v| !v.is_finite()) {
            Some(i) => Err(format!("{entry} {i} is not finite")),
            None => Ok(()),
        }
    }

    /// Number of inputs.
    pub fn dim(&self) -> usize {
        self.counts.len()
    }

    /// Total number of nodes.
    pub fn len(&self) -> usize {
        self.counts.iter().product()
    }

    /// Always false: a valid lattice has at least one node.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Distance between neighbouring nodes along dimension `i` (the box width if it has one node).
    pub fn spacing(&self, i: usize) -> f64 {
        let n = self.counts[i];
        if n > 1 {
            self.bounds.width(i) / (n - 1) as f64
        } else {
            self.bounds.width(i)
        }
    }

    /// Coordinate of node `j` along dimension `i`.
    pub fn coordinate(&self, i: usize, j: usize) -> f64 {
        let n = self.counts[i];
        if n > 1 {
            self.bounds.lo[i] + j as f64 * self.spacing(i)
        } else {
            0.5 * (self.bounds.lo[i] + self.bounds.hi[i])
        }
    }

    /// Multilinear interpolation weights of `x` (clamped into the box): per dimension the two
    /// neighbouring nodes, weighted by proximity. `x.len()` must equal [`Lattice::dim`].
    pub fn multilinear(&self, x: &[f64], out: &mut TensorWeights<2>) {
        out.dim = self.dim();
        for (i, &xi) in x.iter().enumerate() {
            let n = self.counts[i];
            if n == 1 {
                out.set(i, 0, &[1.0]);
                continue;
            }
            let (lo, hi) = (self.bounds.lo[i], self.bounds.hi[i]);
            let t = (xi.clamp(lo, hi) - lo) / (hi - lo) * (n - 1) as f64;
            let j = (t.floor() as usize).min(n - 2);
            let frac = (t - j as f64).clamp(0.0, 1.0);
            out.set(i, j, &[1.0 - frac, frac]);
        }
    }

    /// Normalised Gaussian weights of `x` along each dimension: centres within
    /// `cutoff * widths[i]` of `x[i]` (at least the nearest one) get
    /// `exp(-(x - c)^2 / (2 widths[i]^2))`, normalised to sum to 1 per dimension, so the products
    /// sum to 1 over the lattice. Windows longer than `W` are cut to `W` centres, so callers
    /// check [`Lattice::gaussian_window`] `<= W` when they validate.
    pub fn normalised_gaussian<const W: usize>(
        &self,
        x: &[f64],
        widths: &[f64],
        cutoff: f64,
        out: &mut TensorWeights<W>,
    ) {
        out.dim = self.dim();
        for (i, &xi) in x.iter().enumerate() {
            let n = self.counts[i];
            if n == 1 {
                out.set(i, 0, &[1.0]);
                continue;
            }
            let (lo, h) = (self.bounds.lo[i], self.spacing(i));
            let reach = cutoff * widths[i];
            let last = (n - 1) as f64;
            let first = ((xi - reach - lo) / h).ceil().clamp(0.0, last) as usize;
            let end = ((xi + reach - lo) / h).floor().clamp(0.0, last) as usize;
            let (first, end) = if first > end || (xi - self.coordinate(i, first)).abs() > reach {
                let nearest = ((xi - lo) / h).round().clamp(0.0, last) as usize;
                (nearest, nearest)
            } else {
                (first, end)
            };
            let len = (end - first + 1).min(W);
            if len == 1 {
                // Also keeps inputs so far out that `d * d` overflows well defined.
                out.set(i, first, &[1.0]);
                continue;
            }
            let inv = 1.0 / (2.0 * widths[i] * widths[i]);
            // Shift exponents by the nearest centre's so far-away inputs do not underflow.
            let mut dmin = f64::INFINITY;
            for k in 0..len {
                dmin = dmin.min((xi - self.coordinate(i, first + k)).abs());
            }
            let row = &mut out.weights[i];
            let mut sum = 0.0;
            for (k, w) in row.iter_mut().take(len).enumerate() {
                let d = xi - self.coordinate(i, first + k);
                *w = (-(d * d - dmin * dmin) * inv).exp();
                sum += *w;
            }
            for w in row.iter_mut().take(len) {
                *w /= sum;
            }
            out.start[i] = first;
            out.len[i] = len;
        }
    }

    /// Number of centres per dimension that [`Lattice::normalised_gaussian`] may touch at most.
    pub fn gaussian_window(&self, i: usize, width: f64, cutoff: f64) -> f64 {
        if self.counts[i] == 1 {
            1.0
        } else {
            (2.0 * cutoff * width / self.spacing(i)).floor() + 1.0
        }
    }

    /// Calls `f(flat_index, weight)` for every node with a (possibly zero) weight in `w`.
    #[inline]
    pub fn for_each<const W: usize>(&self, w: &TensorWeights<W>, mut f: impl FnMut(usize, f64)) {
        let d = w.dim;
        let mut idx = [0usize; MAX_LATTICE_DIM];
        loop {
            let mut flat = 0;
            let mut stride = 1;
            let mut weight = 1.0;
            for (i, &j) in idx[..d].iter().enumerate() {
                flat += (w.start[i] + j) * stride;
                stride *= self.counts[i];
                weight *= w.weights[i][j];
            }
            f(flat, weight);
            let mut i = 0;
            loop {
                if i == d {
                    return;
                }
                idx[i] += 1;
                if idx[i] < w.len[i] {
                    break;
                }
                idx[i] = 0;
                i += 1;
            }
        }
    }
}

/// Per-dimension weights of a point on a [`Lattice`]: along dimension `i`, nodes
/// `start[i] .. start[i] + len[i]` have weights `weights[i][..len[i]]`; a node's weight is the
/// product over dimensions. At most `W` nodes per dimension; lives on the stack.
#[derive(Debug, Clone)]
pub struct TensorWeights<const W: usize> {
    dim: usize,
    start: [usize; MAX_LATTICE_DIM],
    len: [usize; MAX_LATTICE_DIM],
    weights: [[f64; W]; MAX_LATTICE_DIM],
}

impl<const W: usize> Default for TensorWeights<W> {
    fn default() -> Self {
        TensorWeights {
            dim: 0,
            start: [0; MAX_LATTICE_DIM],
            len: [0; MAX_LATTICE_DIM],
            weights: [[0.0; W]; MAX_LATTICE_DIM],
        }
    }
}

impl<const W: usize> TensorWeights<W> {
    fn set(&mut self, i: usize, start: usize, w: &[f64]) {
        self.start[i] = start;
        self.len[i] = w.len();
        self.weights[i][..w.len()].copy_from_slice(w);
    }

    /// Number of nodes with a weight: the product of the per-dimension window lengths.
    pub fn support(&self) -> usize {
        self.len[..self.dim].iter().product()
    }

    /// Sum of squared node weights (the squared norm of the feature vector).
    pub fn squared_norm(&self) -> f64 {
        (0..self.dim)
            .map(|i| {
                self.weights[i][..self.len[i]]
                    .iter()
                    .map(|w| w * w)
                    .sum::<f64>()
            })
            .product()
    }
}
