//! `LwprConfig::max_rfs`: on a drifting input stream the receptive fields stay under the cap
//! (bounded memory and cost per update) while the model keeps learning where the inputs are
//! now; a cap never reached changes nothing; the cap survives save and load.

use steplearn::approx::problems::Drift;
use steplearn::approx::{ApproxError, FunctionApproximator, Lwpr, LwprConfig, Persist};

/// The drift of the tests: one input unit per 10,000 samples, spread +-0.3.
fn drift(seed: u64) -> Drift {
    Drift::new(seed, 1e-4, 0.3)
}

fn config(cap: Option<usize>) -> LwprConfig {
    let c = LwprConfig::new(3, 1).init_d(25.0);
    match cap {
        Some(n) => c.max_rfs(n),
        None => c,
    }
}

#[test]
fn a_million_drifting_updates_stay_under_the_cap_and_keep_learning() {
    const CAP: usize = 100;
    let mut capped = Lwpr::new(config(Some(CAP))).unwrap();
    let mut free = Lwpr::new(config(None)).unwrap();
    let mut stream = drift(1);
    let mut sizes = Vec::new();
    for block in 0..10 {
        let mut recent = Vec::new();
        for (i, (x, y)) in stream.by_ref().take(100_000).enumerate() {
            capped.update(&x, &[y]).unwrap();
            free.update(&x, &[y]).unwrap();
            if i >= 99_000 {
                recent.push((x, y));
            }
        }
        let n = capped.num_receptive_fields();
        assert!(n <= CAP, "block {block}: {n} fields");
        sizes.push(capped.to_json().unwrap().len());
        // Where the inputs are now, the capped model predicts as well as the free one.
        let (e_capped, e_free) = (nmse(&capped, &recent), nmse(&free, &recent));
        assert!(
            e_capped <= 1.25 * e_free + 0.01,
            "block {block}: nMSE {e_capped} capped, {e_free} without the cap"
        );
    }
    assert!(free.num_receptive_fields() > 3 * CAP);
    let sub = capped.submodel(0).unwrap();
    assert_eq!(
        capped.num_receptive_fields(),
        CAP,
        "the drift reaches the cap"
    );
    assert!(sub.n_replaced > 250, "{} replaced", sub.n_replaced);
    // Memory: once at the cap, the saved model stops growing.
    let (first, last) = (sizes[1] as f64, *sizes.last().unwrap() as f64);
    assert!(last < 1.2 * first, "saved size {sizes:?}");
    let back = Lwpr::from_json(&capped.to_json().unwrap()).unwrap();
    assert_eq!(back.to_json().unwrap(), capped.to_json().unwrap());
}

/// Normalised mean squared error of `m` on `data`.
fn nmse(m: &Lwpr, data: &[([f64; 3], f64)]) -> f64 {
    let mean = data.iter().map(|r| r.1).sum::<f64>() / data.len() as f64;
    let (mut se, mut var) = (0.0, 0.0);
    for (x, y) in data {
        let mut p = [0.0];
        m.predict(x, &mut p).unwrap();
        se += (p[0] - y).powi(2);
        var += (y - mean).powi(2);
    }
    se / var
}

#[test]
fn a_cap_never_reached_changes_nothing() {
    let (mut capped, mut free) = (
        Lwpr::new(config(Some(10_000))).unwrap(),
        Lwpr::new(config(None)).unwrap(),
    );
    for (x, y) in drift(2).take(20_000) {
        capped.update(&x, &[y]).unwrap();
        free.update(&x, &[y]).unwrap();
    }
    assert!(free.num_receptive_fields() > 20);
    for (x, _) in drift(3).take(500) {
        let (mut a, mut b) = ([0.0], [0.0]);
        capped.predict(&x, &mut a).unwrap();
        free.predict(&x, &mut b).unwrap();
        assert_eq!(a[0].to_bits(), b[0].to_bits());
    }
    assert_eq!(
        capped.submodel(0).unwrap().rfs,
        free.submodel(0).unwrap().rfs
    );
    // Without the cap the saved file is the uncapped format (no stamps, no cap key).
    assert!(!free.to_json().unwrap().contains("max_rfs"));
}

#[test]
fn the_cap_is_replacement_by_least_recent_training() {
    // Two far-apart regions and a cap of 2: a third region replaces the region trained least
    // recently, not the one trained last.
    let mut m = Lwpr::new(LwprConfig::new(1, 1).init_d(400.0).max_rfs(2)).unwrap();
    for _ in 0..50 {
        m.update(&[0.0], &[1.0]).unwrap();
    }
    for _ in 0..50 {
        m.update(&[10.0], &[2.0]).unwrap();
    }
    for _ in 0..50 {
        m.update(&[20.0], &[3.0]).unwrap();
    }
    let centres: Vec<f64> = m
        .submodel(0)
        .unwrap()
        .rfs
        .iter()
        .map(|rf| rf.c[0])
        .collect();
    assert_eq!(centres.len(), 2);
    assert!(
        centres.contains(&10.0) && centres.contains(&20.0),
        "{centres:?}"
    );
    assert_eq!(m.submodel(0).unwrap().n_replaced, 1);
}

#[test]
fn a_zero_cap_is_refused_and_a_broken_capped_file_does_not_load() {
    assert!(matches!(
        Lwpr::new(LwprConfig::new(2, 1).max_rfs(0)),
        Err(ApproxError::InvalidConfig {
            param: "max_rfs",
            ..
        })
    ));
    let mut m = Lwpr::new(config(Some(5))).unwrap();
    for (x, y) in drift(4).take(30_000) {
        m.update(&x, &[y]).unwrap();
    }
    let json: serde_json::Value = serde_json::from_str(&m.to_json().unwrap()).unwrap();
    let mut tampered = [json.clone(), json.clone(), json];
    tampered[0]["config"]["max_rfs"] = serde_json::json!(3);
    tampered[1]["sub"][0]["last_trained"]
        .as_array_mut()
        .unwrap()
        .pop();
    tampered[2]["sub"][0]["last_trained"][0] = serde_json::json!(u64::MAX);
    for (i, t) in tampered.iter().enumerate() {
        assert!(
            matches!(
                Lwpr::from_json(&t.to_string()),
                Err(ApproxError::Corrupt(_))
            ),
            "tampering {i} loaded"
        );
    }
}
