//! `KernelRidge` passes the public approximator conformance suite, with and without
//! forgetting.

use steplearn::approx::conformance::{check_approximator, check_learns};
use steplearn::approx::{KernelRidge, KernelRidgeConfig};

fn make(n_out: usize, forgetting: f64) -> KernelRidge {
    KernelRidge::new(KernelRidgeConfig {
        budget: 40,
        forgetting,
        ..KernelRidgeConfig::new(vec![0.5, 0.5], n_out)
    })
    .unwrap()
}

#[test]
fn kernel_ridge_passes_the_conformance_suite() {
    for n_out in [1, 2] {
        check_approximator(|| make(n_out, 1.0)).unwrap();
        check_learns(|| make(n_out, 1.0), 5000, 0.05).unwrap();
    }
}

#[test]
fn kernel_ridge_with_forgetting_passes_the_conformance_suite() {
    for n_out in [1, 2] {
        check_approximator(|| make(n_out, 0.999)).unwrap();
        check_learns(|| make(n_out, 0.999), 5000, 0.05).unwrap();
    }
}
