//! [`BoxedApproximator`]: any approximator behind one cloneable, saveable type, so that a
//! learner whose approximator is chosen at run time (a built-in or a user's own, by name) is
//! still one concrete type.

use super::{ApproxError, FunctionApproximator, Persist};

/// What a boxed approximator can do: the [`FunctionApproximator`] contract, a clone of itself
/// and its JSON. Blanket-implemented for every `FunctionApproximator + Clone + Persist`.
pub trait DynApproximator: FunctionApproximator {
    /// A boxed copy.
    fn clone_boxed(&self) -> Box<dyn DynApproximator>;
    /// The model as JSON ([`Persist::to_json`]).
    fn json(&self) -> Result<String, ApproxError>;
}

impl<A: FunctionApproximator + Clone + Persist + 'static> DynApproximator for A {
    fn clone_boxed(&self) -> Box<dyn DynApproximator> {
        Box::new(self.clone())
    }
    fn json(&self) -> Result<String, ApproxError> {
        self.to_json()
    }
}

/// Any approximator, boxed: cloneable (the learner's gain guard trials an update on a copy)
/// and writable as JSON, whatever its concrete type.
///
/// ```
/// use steplearn::approx::{BoxedApproximator, FunctionApproximator, Grid, GridConfig, InputBox};
/// let bounds = InputBox::new(vec![-1.0], vec![1.0])?;
/// let grid = Grid::new(GridConfig::new(bounds, vec![5], 1))?;
/// let mut a = BoxedApproximator::new(grid);
/// a.update(&[0.0], &[1.0])?;
/// let copy = a.clone();
/// let (mut y1, mut y2) = ([0.0], [0.0]);
/// a.predict(&[0.0], &mut y1)?;
/// copy.predict(&[0.0], &mut y2)?;
/// assert_eq!(y1, y2);
/// # Ok::<(), steplearn::approx::ApproxError>(())
/// ```
pub struct BoxedApproximator(Box<dyn DynApproximator>);

impl BoxedApproximator {
    /// Boxes `approx`.
    pub fn new(approx: impl FunctionApproximator + Clone + Persist + 'static) -> Self {
        BoxedApproximator(Box::new(approx))
    }

    /// The model as JSON, as its own type writes it.
    pub fn to_json(&self) -> Result<String, ApproxError> {
        self.0.json()
    }
}

impl Clone for BoxedApproximator {
    fn clone(&self) -> Self {
        BoxedApproximator(self.0.clone_boxed())
    }
}

impl std::fmt::Debug for BoxedApproximator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "BoxedApproximator({} -> {})",
            self.0.input_dim(),
            self.0.output_dim()
        )
    }
}

impl FunctionApproximator for BoxedApproximator {
    fn input_dim(&self) -> usize {
        self.0.input_dim()
    }
    fn output_dim(&self) -> usize {
        self.0.output_dim()
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        self.0.predict(x, y)
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        self.0.update(x, y)
    }
}
