//! `Grid` passes the shared approximator conformance suite.
mod common;

use steplearn::approx::{Grid, GridConfig, InputBox};

#[test]
fn grid_passes_the_conformance_suite() {
    common::conformance::check_all(|n_out| {
        let config = GridConfig {
            learning_rate: 0.2,
            ..GridConfig::new(InputBox::cube(2, -1.0, 1.0).unwrap(), vec![11, 11], n_out)
        };
        Grid::new(config).unwrap()
    });
}
