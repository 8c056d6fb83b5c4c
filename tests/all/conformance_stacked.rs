//! `Stacked` (approximators side by side, one per output) passes the public approximator
//! conformance suite, and refuses heads that disagree on their inputs.

use steplearn::approx::conformance::{check_approximator, check_learns};
use steplearn::approx::{FunctionApproximator, Grid, GridConfig, InputBox, Persist, Stacked};

fn head(dim: usize, n_out: usize) -> Grid {
    let config = GridConfig {
        learning_rate: 0.2,
        ..GridConfig::new(
            InputBox::cube(dim, -1.0, 1.0).unwrap(),
            vec![11; dim],
            n_out,
        )
    };
    Grid::new(config).unwrap()
}

#[test]
fn stacked_grids_pass_the_conformance_suite() {
    let make = || Stacked::new(vec![head(2, 1), head(2, 2)]).unwrap();
    assert_eq!(make().output_dim(), 3);
    check_approximator(make).unwrap();
    check_learns(make, 5000, 0.05).unwrap();
}

#[test]
fn heads_must_exist_and_agree_on_their_inputs() {
    assert!(Stacked::<Grid>::new(Vec::new()).is_err());
    let err = Stacked::new(vec![head(2, 1), head(3, 1)]).unwrap_err();
    assert!(err.to_string().contains("head 1 has 3 inputs"), "{err}");
}

#[test]
fn a_saved_stack_whose_output_count_was_edited_is_rejected() {
    let stack = Stacked::new(vec![head(2, 1), head(2, 1)]).unwrap();
    let json = stack.to_json().unwrap();
    let edited = json.replace("\"outputs\":2", "\"outputs\":3");
    assert_ne!(json, edited);
    assert!(Stacked::<Grid>::from_json(&edited).is_err());
    assert!(Stacked::<Grid>::from_json(&json).is_ok());
}
