//! `Rbf` passes the shared approximator conformance suite, with either update rule.
mod common;

use steplearn::approx::{InputBox, Rbf, RbfConfig, RbfUpdate};

fn make(update: RbfUpdate, n_out: usize) -> Rbf {
    let config = RbfConfig {
        widths: vec![0.25; 2],
        update,
        ..RbfConfig::new(InputBox::cube(2, -1.0, 1.0).unwrap(), vec![9, 9], n_out)
    };
    Rbf::new(config).unwrap()
}

#[test]
fn rbf_with_least_mean_squares_passes_the_conformance_suite() {
    common::conformance::check_all(|n_out| make(RbfUpdate::Nlms { learning_rate: 0.3 }, n_out));
}

#[test]
fn rbf_with_recursive_least_squares_passes_the_conformance_suite() {
    common::conformance::check_all(|n_out| {
        make(
            RbfUpdate::Rls {
                forgetting: 1.0,
                prior_variance: 100.0,
            },
            n_out,
        )
    });
}
