//! `Grid` passes the public approximator conformance suite.

use steplearn::approx::conformance::{check_approximator, check_learns};
use steplearn::approx::{Grid, GridConfig, InputBox};

fn make(n_out: usize) -> Grid {
    let config = GridConfig {
        learning_rate: 0.2,
        ..GridConfig::new(InputBox::cube(2, -1.0, 1.0).unwrap(), vec![11, 11], n_out)
    };
    Grid::new(config).unwrap()
}

#[test]
fn grid_passes_the_conformance_suite() {
    for n_out in [1, 2] {
        check_approximator(|| make(n_out)).unwrap();
        check_learns(|| make(n_out), 5000, 0.05).unwrap();
    }
}
