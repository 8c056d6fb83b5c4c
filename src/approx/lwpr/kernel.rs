//! The locality kernels that turn a squared Mahalanobis distance into an activation.

use serde::{Deserialize, Serialize};

/// Activation function of a receptive field, applied to `q = (x - c)^T D (x - c)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Kernel {
    /// `w = exp(-q / 2)` (the reference default).
    #[default]
    Gaussian,
    /// `w = (1 - q / 4)^2` for `q < 4`, else 0 (the formula the reference code implements).
    BiSquare,
}

/// An activation and its first two derivatives with respect to `q`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Activation {
    /// The activation `w`.
    pub w: f64,
    /// `dw/dq`.
    pub dwdq: f64,
    /// `d^2 w / dq^2`.
    pub ddwdqdq: f64,
}

impl Kernel {
    /// The activation at squared distance `q`.
    pub(crate) fn weight(self, q: f64) -> f64 {
        match self {
            Kernel::Gaussian => (-0.5 * q).exp(),
            Kernel::BiSquare => {
                let e = 1.0 - 0.25 * q;
                if e < 0.0 { 0.0 } else { e * e }
            }
        }
    }

    /// The activation and its derivatives at squared distance `q`.
    pub(crate) fn activation(self, q: f64) -> Activation {
        match self {
            Kernel::Gaussian => {
                let w = (-0.5 * q).exp();
                Activation {
                    w,
                    dwdq: -0.5 * w,
                    ddwdqdq: 0.25 * w,
                }
            }
            Kernel::BiSquare => {
                let e = 1.0 - 0.25 * q;
                if e < 0.0 {
                    Activation {
                        w: 0.0,
                        dwdq: 0.0,
                        ddwdqdq: 0.0,
                    }
                } else {
                    Activation {
                        w: e * e,
                        dwdq: -0.5 * e,
                        ddwdqdq: 0.125,
                    }
                }
            }
        }
    }

    /// A squared distance beyond which the activation is certainly `<= threshold`.
    ///
    /// The bound is padded by a relative margin so that skipping every receptive field with
    /// `q > q_limit` never skips one whose exactly computed activation would exceed
    /// `threshold`: skipping is an optimisation that cannot change any result.
    pub(crate) fn q_limit(self, threshold: f64) -> f64 {
        if threshold <= 0.0 {
            return f64::INFINITY;
        }
        let exact = match self {
            Kernel::Gaussian => -2.0 * threshold.ln(),
            Kernel::BiSquare => 4.0 * (1.0 - threshold.sqrt()),
        };
        exact * (1.0 + 1e-9) + 1e-12
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        for kernel in [Kernel::Gaussian, Kernel::BiSquare] {
            for q in [0.1, 0.7, 2.5, 3.3] {
                let a = kernel.activation(q);
                assert_eq!(a.w, kernel.weight(q));
                let h = 1e-6;
                let fd = (kernel.weight(q + h) - kernel.weight(q - h)) / (2.0 * h);
                assert!((fd - a.dwdq).abs() < 1e-8, "{kernel:?} dw/dq at {q}");
                let fd2 =
                    (kernel.activation(q + h).dwdq - kernel.activation(q - h).dwdq) / (2.0 * h);
                assert!((fd2 - a.ddwdqdq).abs() < 1e-6, "{kernel:?} d2w/dq2 at {q}");
            }
        }
        assert_eq!(Kernel::BiSquare.weight(4.5), 0.0);
    }

    #[test]
    fn q_limit_never_cuts_an_activation_above_the_threshold() {
        for kernel in [Kernel::Gaussian, Kernel::BiSquare] {
            for t in [1e-3, 0.02, 0.1, 0.5] {
                let q = kernel.q_limit(t);
                assert!(kernel.weight(q) <= t);
                assert!(kernel.weight(q * (1.0 - 1e-6)) > t);
            }
            assert_eq!(kernel.q_limit(0.0), f64::INFINITY);
        }
    }
}
