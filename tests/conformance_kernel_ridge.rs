//! `KernelRidge` passes the shared approximator conformance suite, with and without
//! forgetting.
mod common;

use steplearn::approx::{KernelRidge, KernelRidgeConfig};

#[test]
fn kernel_ridge_passes_the_conformance_suite() {
    common::conformance::check_all(|n_out| {
        KernelRidge::new(KernelRidgeConfig {
            budget: 40,
            ..KernelRidgeConfig::new(vec![0.5, 0.5], n_out)
        })
        .unwrap()
    });
}

#[test]
fn kernel_ridge_with_forgetting_passes_the_conformance_suite() {
    common::conformance::check_all(|n_out| {
        KernelRidge::new(KernelRidgeConfig {
            budget: 40,
            forgetting: 0.999,
            ..KernelRidgeConfig::new(vec![0.5, 0.5], n_out)
        })
        .unwrap()
    });
}
