//! Properties of the interpolated grid: interpolation weights, clamping, exact reproduction
//! of multilinear functions, the learning rate, and config errors.

use proptest::prelude::*;
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use steplearn::approx::{ApproxError, FunctionApproximator, Grid, GridConfig, InputBox};

fn grid(lo: Vec<f64>, hi: Vec<f64>, resolution: Vec<usize>, learning_rate: f64) -> Grid {
    let config = GridConfig {
        learning_rate,
        ..GridConfig::new(InputBox::new(lo, hi).unwrap(), resolution, 1)
    };
    Grid::new(config).unwrap()
}

fn predict(g: &Grid, x: &[f64]) -> f64 {
    let mut y = [0.0];
    g.predict(x, &mut y).unwrap();
    y[0]
}

/// A multilinear function of up to 3 inputs: sum over subsets S of c_S prod_{i in S} x_i.
fn multilinear(coef: &[f64], x: &[f64]) -> f64 {
    coef.iter()
        .enumerate()
        .map(|(s, c)| {
            c * x
                .iter()
                .enumerate()
                .filter(|(i, _)| s >> i & 1 == 1)
                .map(|(_, v)| v)
                .product::<f64>()
        })
        .sum()
}

proptest! {
    // A fixed seed: the same cases on every run.
    #![proptest_config(ProptestConfig {
        cases: 64,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20_260_322),
        ..ProptestConfig::default()
    })]

    #[test]
    fn weights_are_a_partition_of_unity(
        x in prop::collection::vec(-3.0..3.0f64, 3),
        res in prop::collection::vec(1usize..7, 3),
    ) {
        let g = grid(vec![-1.0, 0.0, -2.0], vec![1.0, 0.5, 2.0], res, 0.1);
        let w = g.corner_weights(&x).unwrap();
        let sum: f64 = w.iter().map(|(_, w)| w).sum();
        prop_assert!((sum - 1.0).abs() < 1e-12, "weights sum to {}", sum);
        prop_assert!(w.iter().all(|&(j, w)| (0.0..=1.0).contains(&w) && j < g.num_nodes()));
        prop_assert!(w.len() <= 8);
    }

    #[test]
    fn inputs_outside_the_box_are_clamped(
        x in prop::collection::vec(-10.0..10.0f64, 2),
        seed in 0u64..1000,
    ) {
        let mut g = grid(vec![-1.0, -1.0], vec![1.0, 1.0], vec![5, 4], 0.5);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for _ in 0..50 {
            let p = [rng.random_range(-1.5..1.5), rng.random_range(-1.5..1.5)];
            g.update(&p, &[rng.random_range(-1.0..1.0)]).unwrap();
        }
        let clamped: Vec<f64> = x.iter().map(|v| v.clamp(-1.0, 1.0)).collect();
        prop_assert_eq!(predict(&g, &x).to_bits(), predict(&g, &clamped).to_bits());
    }

    #[test]
    fn multilinear_functions_are_reproduced_exactly(
        coef in prop::collection::vec(-2.0..2.0f64, 8),
        res in prop::collection::vec(2usize..5, 3),
        seed in 0u64..1000,
    ) {
        let (lo, hi) = (vec![-1.0, 0.0, 2.0], vec![1.0, 3.0, 2.5]);
        let mut g = grid(lo.clone(), hi.clone(), res, 1.0);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let draw = |rng: &mut ChaCha8Rng| -> Vec<f64> {
            lo.iter().zip(&hi).map(|(l, h)| rng.random_range(*l..*h)).collect()
        };
        for _ in 0..20_000 {
            let x = draw(&mut rng);
            g.update(&x, &[multilinear(&coef, &x)]).unwrap();
        }
        for _ in 0..100 {
            let x = draw(&mut rng);
            let err = (predict(&g, &x) - multilinear(&coef, &x)).abs();
            prop_assert!(err < 1e-9, "error {} at {:?}", err, x);
        }
    }

    #[test]
    fn one_update_removes_the_learning_rate_share_of_the_error(
        x in prop::collection::vec(-1.2..1.2f64, 2),
        target in -5.0..5.0f64,
        rate in 0.05..1.0f64,
    ) {
        let mut g = grid(vec![-1.0, -1.0], vec![1.0, 1.0], vec![6, 3], rate);
        g.update(&[0.1, 0.2], &[1.0]).unwrap();
        let before = predict(&g, &x);
        g.update(&x, &[target]).unwrap();
        let after = predict(&g, &x);
        let expected = before + rate * (target - before);
        prop_assert!((after - expected).abs() < 1e-9, "{} vs {}", after, expected);
    }
}

#[test]
fn a_node_has_weight_one_and_the_table_layout_is_dimension_0_fastest() {
    let g = grid(vec![0.0, 0.0], vec![4.0, 2.0], vec![5, 3], 0.1);
    let w = g.corner_weights(&[1.0, 2.0]).unwrap();
    let ones: Vec<usize> = w
        .iter()
        .filter(|(_, w)| *w == 1.0)
        .map(|(j, _)| *j)
        .collect();
    assert_eq!(ones, vec![1 + 2 * 5]);
    assert_eq!(w.iter().map(|(_, w)| w).sum::<f64>(), 1.0);
}

#[test]
fn single_node_dimensions_make_the_table_constant_along_them() {
    let mut g = grid(vec![-1.0, -1.0], vec![1.0, 1.0], vec![3, 1], 1.0);
    g.update(&[0.5, -0.7], &[2.0]).unwrap();
    assert_eq!(predict(&g, &[0.5, 0.9]), predict(&g, &[0.5, -0.7]));
    assert!((predict(&g, &[0.5, 0.0]) - 2.0).abs() < 1e-12);
}

#[test]
fn multiple_outputs_learn_independently() {
    let config = GridConfig::new(InputBox::cube(1, 0.0, 1.0).unwrap(), vec![2], 2);
    let mut g = Grid::new(GridConfig {
        learning_rate: 1.0,
        ..config
    })
    .unwrap();
    g.update(&[0.25], &[1.0, -3.0]).unwrap();
    let mut y = [0.0; 2];
    g.predict(&[0.25], &mut y).unwrap();
    assert!((y[0] - 1.0).abs() < 1e-12 && (y[1] + 3.0).abs() < 1e-12);
}

#[test]
fn invalid_configs_name_the_parameter() {
    let cube = InputBox::cube(2, -1.0, 1.0).unwrap();
    let param = |c: GridConfig| match Grid::new(c) {
        Err(ApproxError::InvalidConfig { param, .. }) => param,
        other => panic!("expected a config error, got {other:?}"),
    };
    let base = GridConfig::new(cube.clone(), vec![5, 5], 1);
    assert_eq!(
        param(GridConfig {
            resolution: vec![5],
            ..base.clone()
        }),
        "resolution"
    );
    assert_eq!(
        param(GridConfig {
            resolution: vec![5, 0],
            ..base.clone()
        }),
        "resolution"
    );
    assert_eq!(
        param(GridConfig {
            output_dim: 0,
            ..base.clone()
        }),
        "output_dim"
    );
    for lr in [0.0, -0.1, 1.5, f64::NAN] {
        assert_eq!(
            param(GridConfig {
                learning_rate: lr,
                ..base.clone()
            }),
            "learning_rate"
        );
    }
    // The curse of dimensionality is a clear error, not an attempt to allocate 10^13 floats.
    let big = GridConfig::new(InputBox::cube(10, -1.0, 1.0).unwrap(), vec![21; 10], 1);
    let err = Grid::new(big).unwrap_err().to_string();
    assert!(err.contains("resolution") && err.contains("nodes"), "{err}");
    let bad_box = InputBox {
        lo: vec![0.0, 1.0],
        hi: vec![1.0, 1.0],
    };
    assert_eq!(
        param(GridConfig {
            bounds: bad_box,
            ..base.clone()
        }),
        "bounds"
    );
    assert!(InputBox::new(vec![0.0], vec![f64::INFINITY]).is_err());
    assert!(InputBox::new(vec![], vec![]).is_err());
    assert!(InputBox::new(vec![0.0, 0.0], vec![1.0]).is_err());
}

#[test]
fn many_outputs_beyond_the_stack_buffer_work_too() {
    let n_out = 11;
    let config = GridConfig::new(InputBox::cube(2, 0.0, 1.0).unwrap(), vec![4, 4], n_out);
    let mut g = Grid::new(GridConfig {
        learning_rate: 1.0,
        ..config
    })
    .unwrap();
    let target: Vec<f64> = (0..n_out).map(|k| k as f64 - 5.0).collect();
    g.update(&[0.3, 0.8], &target).unwrap();
    let mut y = vec![0.0; n_out];
    g.predict(&[0.3, 0.8], &mut y).unwrap();
    for (a, b) in y.iter().zip(&target) {
        assert!((a - b).abs() < 1e-12);
    }
}
