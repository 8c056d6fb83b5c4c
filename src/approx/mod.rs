//! Online function approximators behind one trait.
//!
//! [`FunctionApproximator`] is the whole contract the learning layer needs: predict at a point,
//! and take one training sample. Every implementation validates its inputs (length, finiteness)
//! and leaves its state untouched when it rejects a call. [`Persist`] adds JSON save/load with an
//! invariant check on load, so a corrupt file is an error, never a broken model.

mod any;
mod batch;
mod boxed;
pub mod conformance;
mod error;
mod exact_kernel_ridge;
mod grid;
mod input_box;
mod kernel_ridge;
pub mod lattice;
mod lwpr;
mod persist;
pub mod problems;
mod rbf;
mod square_matrix;
mod stacked;

pub use any::{AnyApproximator, ApproxKind};
pub use batch::BatchApproximator;
pub use boxed::{BoxedApproximator, DynApproximator};
pub use error::{ApproxError, check_output, check_vector};
pub use exact_kernel_ridge::ExactKernelRidge;
pub use grid::{Grid, GridConfig};
pub use input_box::InputBox;
pub use kernel_ridge::{KernelRidge, KernelRidgeConfig};
pub use lwpr::{Kernel, Lwpr, LwprConfig, MAX_INPUT, MAX_TARGET, ReceptiveField, SubModel};
pub use persist::Persist;
pub use rbf::{Rbf, RbfConfig, RbfUpdate};
pub use stacked::Stacked;

/// An online regressor from `input_dim` inputs to `output_dim` outputs.
///
/// The trait is object safe: the learner and the command line use `Box<dyn FunctionApproximator>`
/// as readily as a concrete type.
pub trait FunctionApproximator: Send + Sync {
    /// Number of inputs.
    fn input_dim(&self) -> usize;
    /// Number of outputs.
    fn output_dim(&self) -> usize;
    /// Writes the prediction at `x` into `y` (len == output_dim).
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError>;
    /// One online training sample: moves the model toward `y` at `x`.
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError>;
}

impl<A: FunctionApproximator + ?Sized> FunctionApproximator for Box<A> {
    fn input_dim(&self) -> usize {
        (**self).input_dim()
    }
    fn output_dim(&self) -> usize {
        (**self).output_dim()
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        (**self).predict(x, y)
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        (**self).update(x, y)
    }
}
