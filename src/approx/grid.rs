//! An interpolated lookup table: node values on a regular grid, multilinear interpolation.

use super::lattice::{Lattice, TensorWeights};
use super::{ApproxError, FunctionApproximator, InputBox, Persist, check_output, check_vector};
use serde::{Deserialize, Serialize};

/// Settings of a [`Grid`].
///
/// Recommended settings (as compared by `probes/src/bin/compare_approximators.rs`; its figures are in
/// docs/approximators.md):
/// - cross 2D on [-1, 1]^2, noise 0.1: `resolution = [31, 31]`, `learning_rate = 0.1`;
/// - the 3-input step-offset map (theta, theta_dot, F_R), noise 0.01: `resolution = [11, 5, 5]`,
///   `learning_rate = 0.05`.
///
/// Choose the spacing so that the target is close to linear between neighbouring nodes; more
/// nodes resolve more detail but see fewer samples each (more noise). The node count is the
/// product of the resolutions, so it explodes with the number of inputs: a config that needs
/// more than `max_nodes` nodes is rejected by [`Grid::new`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridConfig {
    /// The box covered by the table; inputs outside it are clamped onto it.
    pub bounds: InputBox,
    /// Nodes per input dimension (>= 1; 1 makes the table constant along that input).
    pub resolution: Vec<usize>,
    /// Number of outputs (>= 1).
    pub output_dim: usize,
    /// Step size in (0, 1]: the fraction of the prediction error at `x` that one update
    /// removes (1 makes the table interpolate the latest sample exactly). Default 0.1.
    pub learning_rate: f64,
    /// Upper limit on the number of nodes (default 2^22, i.e. 32 MiB per output).
    pub max_nodes: usize,
}

impl GridConfig {
    /// A config with the default learning rate (0.1) and node limit (2^22).
    pub fn new(bounds: InputBox, resolution: Vec<usize>, output_dim: usize) -> Self {
        GridConfig {
            bounds,
            resolution,
            output_dim,
            learning_rate: 0.1,
            max_nodes: 1 << 22,
        }
    }

    fn lattice(&self) -> Result<Lattice, ApproxError> {
        Lattice::new(
            self.bounds.clone(),
            self.resolution.clone(),
            self.max_nodes,
            "resolution",
        )
    }

    fn validate(&self) -> Result<Lattice, ApproxError> {
        if self.output_dim == 0 {
            return Err(ApproxError::config("output_dim", "must be >= 1"));
        }
        if !(self.learning_rate > 0.0 && self.learning_rate <= 1.0) {
            return Err(ApproxError::config(
                "learning_rate",
                format!("must be in (0, 1], got {}", self.learning_rate),
            ));
        }
        let lattice = self.lattice()?;
        if lattice.len().checked_mul(self.output_dim).is_none() {
            return Err(ApproxError::config("output_dim", "table size overflows"));
        }
        Ok(lattice)
    }
}

/// A lookup table over a box with multilinear interpolation, trained online.
///
/// The prediction at `x` (clamped into the box) interpolates the values at the `2^d` corners
/// of its cell with weights `w_c` (products of per-dimension linear weights; they sum to 1).
/// An update with error `e = y - f(x)` moves each corner by
/// `learning_rate * e * w_c / sum_c w_c^2` (normalised least mean squares): the error is
/// shared among the corners in proportion to their weights, and `f(x)` moves by exactly
/// `learning_rate * e`. Untrained nodes are 0. A multilinear target is reproduced exactly.
///
/// Cost: predict and update `O(2^d (d + output_dim))` (4 corners in 2D, 8 in 3D), no
/// allocation (up to 8 outputs); memory `prod(resolution) * output_dim` floats.
///
/// ```
/// use steplearn::approx::{FunctionApproximator, Grid, GridConfig, InputBox};
/// let bounds = InputBox::cube(2, -1.0, 1.0)?;
/// let mut grid = Grid::new(GridConfig { learning_rate: 1.0, ..GridConfig::new(bounds, vec![3, 3], 1) })?;
/// grid.update(&[0.5, 0.5], &[2.0])?;
/// let mut y = [0.0];
/// grid.predict(&[0.5, 0.5], &mut y)?;
/// assert!((y[0] - 2.0).abs() < 1e-12);
/// # Ok::<(), steplearn::approx::ApproxError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Grid {
    config: GridConfig,
    lattice: Lattice,
    /// Node values, `values[node * output_dim + k]`.
    values: Vec<f64>,
}

impl Grid {
    /// A zero table, after checking the config (positive sizes, learning rate in (0, 1],
    /// node count within `max_nodes`, at most 16 inputs).
    pub fn new(config: GridConfig) -> Result<Self, ApproxError> {
        let lattice = config.validate()?;
        let values = vec![0.0; lattice.len() * config.output_dim];
        Ok(Grid {
            config,
            lattice,
            values,
        })
    }

    /// The validated settings.
    pub fn config(&self) -> &GridConfig {
        &self.config
    }

    /// Number of grid nodes.
    pub fn num_nodes(&self) -> usize {
        self.lattice.len()
    }

    /// Node values, `values()[node * output_dim + k]`, dimension 0 varying fastest.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Interpolation weights of the cell corners at `x`, as `(node index, weight)` pairs.
    pub fn corner_weights(&self, x: &[f64]) -> Result<Vec<(usize, f64)>, ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        let mut w = TensorWeights::default();
        self.lattice.multilinear(x, &mut w);
        let mut out = Vec::with_capacity(w.support());
        self.lattice.for_each(&w, |j, wj| out.push((j, wj)));
        Ok(out)
    }

    fn interpolate(&self, w: &TensorWeights<2>, y: &mut [f64]) {
        let n_out = self.config.output_dim;
        y.fill(0.0);
        self.lattice.for_each(w, |j, wj| {
            for (yk, v) in y.iter_mut().zip(&self.values[j * n_out..(j + 1) * n_out]) {
                *yk += wj * v;
            }
        });
    }
}

impl FunctionApproximator for Grid {
    fn input_dim(&self) -> usize {
        self.lattice.dim()
    }

    fn output_dim(&self) -> usize {
        self.config.output_dim
    }

    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        check_output("output y", y, self.output_dim())?;
        let mut w = TensorWeights::default();
        self.lattice.multilinear(x, &mut w);
        self.interpolate(&w, y);
        Ok(())
    }

    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        check_vector("target y", y, self.output_dim())?;
        const MAX_OUT_ON_STACK: usize = 8;
        let n_out = self.config.output_dim;
        let mut w = TensorWeights::default();
        self.lattice.multilinear(x, &mut w);
        let mut stack = [0.0; MAX_OUT_ON_STACK];
        let mut heap = Vec::new();
        let err: &mut [f64] = if n_out <= MAX_OUT_ON_STACK {
            &mut stack[..n_out]
        } else {
            heap.resize(n_out, 0.0);
            &mut heap
        };
        self.interpolate(&w, err);
        let scale = self.config.learning_rate / w.squared_norm();
        for (e, target) in err.iter_mut().zip(y) {
            *e = (target - *e) * scale;
        }
        let values = &mut self.values;
        self.lattice.for_each(&w, |j, wj| {
            for (v, e) in values[j * n_out..(j + 1) * n_out]
                .iter_mut()
                .zip(err.iter())
            {
                *v += wj * e;
            }
        });
        Ok(())
    }
}

impl Persist for Grid {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        self.lattice
            .check_table(
                self.config.validate(),
                &self.values,
                self.config.output_dim,
                "value",
            )
            .map_err(|m| ApproxError::Corrupt(format!("grid: {m}")))
    }
}
