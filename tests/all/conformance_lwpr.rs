//! LWPR passes the public approximator conformance suite.

use steplearn::approx::conformance::{check_approximator, check_learns};
use steplearn::approx::{Lwpr, LwprConfig};

/// The reference library's defaults (init_D = 25 I, w_gen = 0.1), no tuning for the suite.
fn make(n_out: usize) -> Lwpr {
    Lwpr::new(LwprConfig::new(2, n_out)).expect("default config is valid")
}

#[test]
fn lwpr_passes_the_conformance_suite() {
    for n_out in [1, 2] {
        check_approximator(|| make(n_out)).unwrap();
        check_learns(|| make(n_out), 5000, 0.05).unwrap();
    }
}
