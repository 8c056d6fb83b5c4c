//! Locally weighted projection regression (LWPR).
//!
//! A Rust implementation of LWPR (Vijayakumar, D'Souza & Schaal, "Incremental online learning
//! in high dimensions", Neural Computation 2005), following the reference library LWPR 1.2.6
//! (Klanke & Vijayakumar; `lwpr.c`, `lwpr_aux.c`, `doc/lwpr_doc.tex`) step by step, written
//! anew.
//!
//! # Algorithm
//! Each output is learned by its own set of receptive fields. A receptive field has a centre
//! `c` and a distance metric `D = M^T M` (`M` upper triangular, or diagonal with `diag_only`);
//! its activation is a kernel of `q = (x - c)^T D (x - c)` on the normalised input
//! `x / norm_in`. For every training sample, every field with activation `w > 0.001`
//! 1. updates its weighted input mean and intercept `beta0`;
//! 2. takes one step of weighted incremental partial least squares: projection directions
//!    `u_r` from the forgetting sums `SXresYres` (forgotten 10x more slowly), loadings `s_r`,
//!    input reductions `p_r` and coefficients `beta_r` from `SSXres`, `SSYres`, `SSs2`, with
//!    leave-one-out (cross-validation) errors per projection count;
//! 3. if `update_d`, takes a gradient step on `M` for the leave-one-out cost plus the penalty
//!    `gamma / n * sum D_ij^2`, scaled by the transient multiplier
//!    `min(1, (sum_e2 / sum_e_cv2)^4)`, with per-element learning rates `alpha` that are halved
//!    when a step exceeds `0.1 max |M|`, and optionally adapted by incremental
//!    delta-bar-delta (`meta`);
//! 4. adds a projection when the newest one cut the CV error below `add_threshold` of the
//!    previous one with enough data support;
//! 5. counts the sample (`n_data`) and anneals its forgetting factor
//!    `lambda <- tau_lambda lambda + (1 - tau_lambda) final_lambda`.
//!
//! If no field is activated above `w_gen`, a new one is centred at the sample (copying the
//! metric of the most active field if that one is trustworthy and activated above
//! `0.1 w_gen`). If two fields are activated above `w_prune`, one is removed. A prediction is
//! the activation-weighted mean of the trustworthy fields activated above `cutoff`;
//! [`Lwpr::predict_with_confidence`] adds the reference's confidence bound.
//!
//! # Deliberate differences from the reference C code
//! - **Pruning** removes the *narrower* of the two fields (larger trace of `D`), as the
//!   documentation and the MATLAB code do; the C code removes the wider one and carries a
//!   comment that its logic was reversed. With the default `w_prune = 1.0` pruning never
//!   triggers for the Gaussian kernel (activations are at most 1), so results with defaults
//!   are unaffected.
//! - **`w_prune` default** is 1.0 as in the code (the documentation says 0.9), and it must
//!   lie in `(w_gen, 1]`.
//! - **Bisquare kernel** is `(1 - q/4)^2` for `q < 4`, the formula the C code implements and
//!   differentiates (the header documents `(1 - q/2)^2`).
//! - **Out-of-bounds read**: while a field with a single projection (one input) has not yet
//!   trusted that projection, the C code reads the element before the CV-error array. Here
//!   the CV error of "no projection" is the mean-free target itself, which is what the
//!   prediction without projections (the intercept) gets wrong.
//! - **Skipping far fields**: the kernel is evaluated only for fields whose squared distance
//!   is within the distance at which the activation drops below the update threshold
//!   (`min(0.001, 0.1 w_gen)`) or the prediction cutoff. The bound is padded so that
//!   skipping never changes a result; it only saves work. An update computes the distances of
//!   all fields in one vectorised pass over a column-wise index of centres and metrics. For
//!   full metrics the distance is computed as `|M (x - c)|^2` (the C code uses `D`).
//! - **Saved models** whose fields have fewer projections than training starts with
//!   (`min(2, n_in)`) are rejected on load: the C code would read before an array when
//!   deciding whether to add a projection.
//! - **No confidence** where no trustworthy field is active is `f64::INFINITY` (the C code
//!   returns `1e20`).
//! - **Prediction cutoff** is a configuration parameter ([`LwprConfig::cutoff`], default
//!   0.001 as in the C demo) instead of an argument of every prediction.
//! - Transient per-sample quantities of the C structure (`w`, `s`, the slope cache) live in
//!   a scratch workspace, not in the saved model.
//! - Everything else, including the order of operations within an update, follows `lwpr_aux.c`.
//!
//! Checked against the reference: fed the same 20,000 cross-2D samples (C demo settings), the C
//! library (1.2.6, gcc -O2) and this implementation give bit-identical predictions and
//! confidence bounds on an 11 x 11 grid with diagonal metrics (with and without meta learning),
//! and agree to 5e-15 with full metrics (where the distance is computed via `M`, not `D`).
//!
//! # Cost
//! Updates and predictions allocate nothing (a preallocated workspace whose distance buffer
//! grows only with the field count; predictions use a stack buffer for up to 32 inputs).
//! Creating a receptive field allocates its storage once, with room for all projections.
//! Training is compiled separately for 1 to 4 inputs so that its small loops unroll. Measured
//! against the C library on the same machine, updates are 2.0-3.3x and predictions 2.6-2.8x
//! faster (see the README).

// Column-major matrix code reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

mod config;
mod dim;
mod invariants;
mod kernel;
mod linalg;
mod metric;
mod model;
mod receptive_field;
mod scan;
mod workspace;

#[cfg(test)]
mod tests;

pub use config::LwprConfig;
pub use kernel::Kernel;
pub use model::{Lwpr, MAX_INPUT, MAX_TARGET, SubModel};
pub use receptive_field::ReceptiveField;
