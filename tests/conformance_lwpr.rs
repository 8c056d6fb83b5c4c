//! LWPR passes the shared approximator conformance suite.
mod common;

use steplearn::approx::{Lwpr, LwprConfig};

/// The reference library's defaults (init_D = 25 I, w_gen = 0.1), no tuning for the suite.
fn make(n_out: usize) -> Lwpr {
    Lwpr::new(LwprConfig::new(2, n_out)).expect("default config is valid")
}

#[test]
fn lwpr_passes_the_conformance_suite() {
    common::conformance::check_all(make);
}
