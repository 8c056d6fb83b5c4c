//! The input count of a receptive field, known at compile time for small inputs.
//!
//! Training is written once, generic over [`InputDim`]; [`ReceptiveField::train`] dispatches
//! 1 to 4 inputs to [`Fixed`] so that the compiler unrolls the per-input loops and drops
//! their bounds checks, and anything larger to [`Dynamic`]. The floating-point operations
//! and their order are the same either way, so the results are bit-identical.
//!
//! [`ReceptiveField::train`]: super::ReceptiveField

/// A number of inputs.
pub(crate) trait InputDim: Copy {
    /// The number of inputs.
    fn n(self) -> usize;
}

/// `N` inputs, a compile-time constant.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Fixed<const N: usize>;

impl<const N: usize> InputDim for Fixed<N> {
    #[inline(always)]
    fn n(self) -> usize {
        N
    }
}

/// A number of inputs known at run time.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Dynamic(pub usize);

impl InputDim for Dynamic {
    #[inline(always)]
    fn n(self) -> usize {
        self.0
    }
}
