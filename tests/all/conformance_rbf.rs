//! `Rbf` passes the public approximator conformance suite, with either update rule.

use steplearn::approx::conformance::{check_approximator, check_learns};
use steplearn::approx::{InputBox, Rbf, RbfConfig, RbfUpdate};

fn make(update: RbfUpdate, n_out: usize) -> Rbf {
    let config = RbfConfig {
        widths: vec![0.25; 2],
        update,
        ..RbfConfig::new(InputBox::cube(2, -1.0, 1.0).unwrap(), vec![9, 9], n_out)
    };
    Rbf::new(config).unwrap()
}

fn passes(update: RbfUpdate) {
    for n_out in [1, 2] {
        check_approximator(|| make(update, n_out)).unwrap();
        check_learns(|| make(update, n_out), 5000, 0.05).unwrap();
    }
}

#[test]
fn rbf_with_least_mean_squares_passes_the_conformance_suite() {
    passes(RbfUpdate::Nlms { learning_rate: 0.3 });
}

#[test]
fn rbf_with_recursive_least_squares_passes_the_conformance_suite() {
    passes(RbfUpdate::Rls {
        forgetting: 1.0,
        prior_variance: 100.0,
    });
}
