//! LWPR reaches the reference library's accuracy on the cross 2D demo and learns the cross
//! function embedded in 10 inputs, 8 of them irrelevant.

use steplearn::approx::problems::{Problem, nmse};
use steplearn::approx::{FunctionApproximator, Lwpr, LwprConfig};

fn train_and_score(problem: &Problem, config: LwprConfig, seed: u64, n: usize) -> (f64, usize) {
    let mut model = Lwpr::new(config).unwrap();
    for (x, y) in problem.train_stream(seed, n) {
        model.update(&x, &[y]).unwrap();
    }
    let test = problem.test_set(41);
    let mut out = [0.0];
    let pred: Vec<f64> = test
        .iter()
        .map(|(x, _)| {
            model.predict(x, &mut out).unwrap();
            out[0]
        })
        .collect();
    let truth: Vec<f64> = test.iter().map(|(_, y)| *y).collect();
    (nmse(&pred, &truth), model.num_receptive_fields())
}

/// The full bar of issue 2: C demo settings, 100,000 fresh samples, 5 seeds, median nMSE
/// <= 0.017 with <= 70 receptive fields (the reference: 0.0159 with 60).
#[test]
fn cross_2d_matches_the_reference_demo() {
    let problem = Problem::cross_2d();
    // The seeds are independent: run them on parallel threads (each is deterministic).
    let mut runs: Vec<(f64, usize)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (1..=5)
            .map(|seed| {
                let problem = &problem;
                scope.spawn(move || {
                    let config = LwprConfig::new(2, 1)
                        .init_d(50.0)
                        .init_alpha(250.0)
                        .w_gen(0.2);
                    train_and_score(problem, config, seed, 100_000)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (median_nmse, _) = runs[2];
    let mut rfs: Vec<usize> = runs.iter().map(|r| r.1).collect();
    rfs.sort();
    assert!(median_nmse <= 0.017, "median nMSE {median_nmse} ({runs:?})");
    assert!(rfs[2] <= 70, "median RF count {} ({runs:?})", rfs[2]);
}

/// Cross 2D in 10 inputs: the PLS projections and the metric adaptation must find the two
/// relevant inputs. Plain spherical initial metric: nothing tells LWPR which inputs matter.
/// The reference C library's setting for this problem (init_D 1, init_alpha 250, w_gen 0.2,
/// meta learning, 50,000 samples), held to the reference's figures: nMSE 0.062 with 7679
/// receptive fields (measured here: 0.036 with 7002, seed 1).
#[test]
fn cross_10d_learns_despite_irrelevant_inputs() {
    let problem = Problem::cross_10d();
    let config = LwprConfig::new(10, 1)
        .init_d(1.0)
        .init_alpha(250.0)
        .w_gen(0.2)
        .meta(true);
    let (e, rfs) = train_and_score(&problem, config, 1, 50_000);
    assert!(e <= 0.062, "nMSE {e} with {rfs} RFs");
    assert!(rfs <= 7679, "{rfs} RFs (nMSE {e})");
}
