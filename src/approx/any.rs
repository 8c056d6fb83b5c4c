//! Approximators chosen by name at run time: [`ApproxKind`] (the command line's
//! `--approx lwpr|rbf|grid|kernel-ridge`) and [`AnyApproximator`], one serde type that holds any
//! of them, so a learner with a run-time choice of approximator can still be saved and loaded.

use super::{
    ApproxError, FunctionApproximator, Grid, GridConfig, InputBox, KernelRidge, KernelRidgeConfig,
    Lwpr, LwprConfig, Persist, Rbf, RbfConfig,
};
use crate::Named;
use serde::{Deserialize, Serialize};

/// The approximators of this crate, by their command-line names.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    serde::Serialize,
    serde::Deserialize,
    strum::Display,
    strum::IntoStaticStr,
    strum::VariantArray,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum ApproxKind {
    /// Locally weighted projection regression (the paper's choice).
    Lwpr,
    /// Normalised Gaussian radial basis function network.
    Rbf,
    /// Multilinearly interpolated grid.
    Grid,
    /// Online sparse kernel ridge regression.
    KernelRidge,
}

impl ApproxKind {
    /// A fresh, untrained approximator of this kind with one output over the input box
    /// `bounds`, with the settings documented for each type as good defaults for a box of that
    /// size (inputs are scaled by the box's half-widths).
    pub fn build(self, bounds: &InputBox) -> Result<AnyApproximator, ApproxError> {
        let half = half_widths(bounds);
        let n = half.len();
        Ok(match self {
            ApproxKind::Lwpr => AnyApproximator::Lwpr(Lwpr::new(Self::lwpr_config(bounds))?),
            ApproxKind::Rbf => {
                let centres = vec![7; n];
                let mut config = RbfConfig::new(bounds.clone(), centres, 1);
                config.widths = config.widths.iter().map(|w| 0.7 * w).collect();
                AnyApproximator::Rbf(Rbf::new(config)?)
            }
            ApproxKind::Grid => {
                AnyApproximator::Grid(Grid::new(GridConfig::new(bounds.clone(), vec![9; n], 1))?)
            }
            ApproxKind::KernelRidge => {
                let scales = half.iter().map(|h| 0.5 * h).collect();
                AnyApproximator::KernelRidge(KernelRidge::new(KernelRidgeConfig::new(scales, 1))?)
            }
        })
    }
}

impl ApproxKind {
    /// The settings of the built-in `lwpr` over the input box `bounds` (what
    /// [`ApproxKind::build`] uses): the reference defaults of [`LwprConfig::new`] with one
    /// output, inputs divided by the box's half-widths (`norm_in`) and a spherical initial
    /// distance metric of 10 (`init_d`, in those normalised units). A config file's
    /// `[settings.lwpr]` table changes them from here.
    pub fn lwpr_config(bounds: &InputBox) -> LwprConfig {
        let half = half_widths(bounds);
        LwprConfig::new(half.len(), 1).norm_in(half).init_d(10.0)
    }
}

/// The half-widths of `bounds`, one per input.
fn half_widths(bounds: &InputBox) -> Vec<f64> {
    bounds
        .lo
        .iter()
        .zip(&bounds.hi)
        .map(|(l, h)| 0.5 * (h - l))
        .collect()
}

impl std::str::FromStr for ApproxKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ApproxKind::from_name(s).ok_or_else(|| {
            format!(
                "unknown approximator '{s}' (expected {})",
                ApproxKind::names()
            )
        })
    }
}

/// Any approximator of this crate, as one serializable type.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "approx", rename_all = "kebab-case")]
#[allow(clippy::large_enum_variant)]
pub enum AnyApproximator {
    /// See [`Lwpr`].
    Lwpr(Lwpr),
    /// See [`Rbf`].
    Rbf(Rbf),
    /// See [`Grid`].
    Grid(Grid),
    /// See [`KernelRidge`].
    KernelRidge(KernelRidge),
}

impl AnyApproximator {
    /// Which kind this is.
    pub fn kind(&self) -> ApproxKind {
        match self {
            AnyApproximator::Lwpr(_) => ApproxKind::Lwpr,
            AnyApproximator::Rbf(_) => ApproxKind::Rbf,
            AnyApproximator::Grid(_) => ApproxKind::Grid,
            AnyApproximator::KernelRidge(_) => ApproxKind::KernelRidge,
        }
    }

    fn inner(&self) -> &dyn FunctionApproximator {
        match self {
            AnyApproximator::Lwpr(a) => a,
            AnyApproximator::Rbf(a) => a,
            AnyApproximator::Grid(a) => a,
            AnyApproximator::KernelRidge(a) => a,
        }
    }

    fn inner_mut(&mut self) -> &mut dyn FunctionApproximator {
        match self {
            AnyApproximator::Lwpr(a) => a,
            AnyApproximator::Rbf(a) => a,
            AnyApproximator::Grid(a) => a,
            AnyApproximator::KernelRidge(a) => a,
        }
    }
}

impl FunctionApproximator for AnyApproximator {
    fn input_dim(&self) -> usize {
        self.inner().input_dim()
    }
    fn output_dim(&self) -> usize {
        self.inner().output_dim()
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        self.inner().predict(x, y)
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        self.inner_mut().update(x, y)
    }
}

impl Persist for AnyApproximator {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        match self {
            AnyApproximator::Lwpr(a) => a.check_invariants(),
            AnyApproximator::Rbf(a) => a.check_invariants(),
            AnyApproximator::Grid(a) => a.check_invariants(),
            AnyApproximator::KernelRidge(a) => a.check_invariants(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strum::VariantArray;

    #[test]
    fn names_round_trip() {
        for &k in ApproxKind::VARIANTS {
            assert_eq!(k.name().parse::<ApproxKind>().unwrap(), k);
        }
        assert!("lwrp".parse::<ApproxKind>().is_err());
    }

    #[test]
    fn every_kind_builds_learns_and_round_trips() {
        let bounds = InputBox::new(vec![-0.5, -3.0, -0.1], vec![0.5, 3.0, 0.2]).unwrap();
        for &k in ApproxKind::VARIANTS {
            let mut a = k.build(&bounds).unwrap();
            assert_eq!((a.kind(), a.input_dim(), a.output_dim()), (k, 3, 1));
            for i in 0..200 {
                let t = i as f64 / 200.0;
                let x = [t - 0.5, 6.0 * t - 3.0, 0.3 * t - 0.1];
                a.update(&x, &[0.5 * x[0]]).unwrap();
            }
            let back = AnyApproximator::from_json(&a.to_json().unwrap()).unwrap();
            let (mut y1, mut y2) = ([0.0], [0.0]);
            a.predict(&[0.1, 0.0, 0.0], &mut y1).unwrap();
            back.predict(&[0.1, 0.0, 0.0], &mut y2).unwrap();
            assert_eq!(y1[0].to_bits(), y2[0].to_bits(), "{k}");
        }
    }
}
