//! Golden regression: pins the exact bits of LWPR's outputs (predictions, confidence bounds,
//! receptive-field counts) after seeded training, so that any optimisation of the update or
//! prediction path must stay bit-identical (the implementation matches the reference C library
//! bit for bit with diagonal metrics; reassociating a floating-point sum would break that).
//!
//! The pinned hashes were produced by the code at the commit that added this test. If a change
//! alters them, it changed the numerics.

use steplearn::approx::problems::Problem;
use steplearn::approx::{FunctionApproximator, Kernel, Lwpr, LwprConfig};

/// FNV-1a over the bit patterns of a stream of f64s.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn push(&mut self, v: f64) {
        for b in v.to_bits().to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// Trains on `n` seeded samples, then hashes predictions and confidence bounds on a grid and
/// the number of receptive fields. Returns (hash, rf count).
fn fingerprint(problem: &Problem, config: LwprConfig, seed: u64, n: usize) -> (u64, usize) {
    let mut model = Lwpr::new(config).unwrap();
    let mut h = Fnv::new();
    for (i, (x, y)) in problem.train_stream(seed, n).into_iter().enumerate() {
        model.update(&x, &[y]).unwrap();
        if i % 97 == 0 {
            h.push(model.num_receptive_fields() as f64);
        }
    }
    let per_dim = if problem.dim() == 2 { 11 } else { 6 };
    let (mut y, mut c) = ([0.0], [0.0]);
    for (x, _) in problem.test_set(per_dim) {
        model.predict_with_confidence(&x, &mut y, &mut c).unwrap();
        h.push(y[0]);
        h.push(c[0]);
        model.predict(&x, &mut y).unwrap();
        h.push(y[0]);
    }
    (h.0, model.num_receptive_fields())
}

fn demo(problem: &Problem) -> LwprConfig {
    LwprConfig::new(problem.dim(), 1)
        .init_d(50.0)
        .init_alpha(250.0)
        .w_gen(0.2)
        .norm_in(problem.half_ranges())
}

fn check(label: &str, got: (u64, usize), want: (u64, usize)) {
    assert_eq!(
        got, want,
        "{label}: outputs changed (hash {:#018x}, {} RFs)",
        got.0, got.1
    );
}

#[test]
fn cross_2d_diagonal_is_pinned() {
    let p = Problem::cross_2d();
    check(
        "cross diag",
        fingerprint(&p, demo(&p), 7, 5000),
        (0x5a83_e488_6353_5dfd, 56),
    );
}

#[test]
fn cross_2d_meta_is_pinned() {
    let p = Problem::cross_2d();
    check(
        "cross meta",
        fingerprint(&p, demo(&p).meta(true), 8, 4000),
        (0xc55a_8d49_ea4e_0c21, 53),
    );
}

#[test]
fn cross_2d_full_metric_bisquare_is_pinned() {
    let p = Problem::cross_2d();
    let config = demo(&p)
        .diag_only(false)
        .kernel(Kernel::BiSquare)
        .w_prune(0.9);
    check(
        "cross full bisquare",
        fingerprint(&p, config, 9, 4000),
        (0x60dd_623a_d7fd_1ac1, 67),
    );
}

#[test]
fn step_offset_3d_diagonal_is_pinned() {
    let p = Problem::step_offset_3d();
    check(
        "3d diag",
        fingerprint(&p, demo(&p), 10, 5000),
        (0xdf5b_3c4d_27a4_aef1, 310),
    );
}

#[test]
fn step_offset_3d_full_metric_meta_is_pinned() {
    let p = Problem::step_offset_3d();
    let config = demo(&p).diag_only(false).meta(true);
    check(
        "3d full meta",
        fingerprint(&p, config, 11, 4000),
        (0x365d_2c80_6860_6af0, 310),
    );
}

/// Saving and loading mid-stream (the scan index is derived, not saved) and then continuing
/// to train gives exactly the model that was never saved, with diagonal and full metrics.
#[test]
fn training_continues_identically_after_a_round_trip() {
    let p = Problem::step_offset_3d();
    for config in [demo(&p), demo(&p).diag_only(false).w_prune(0.9)] {
        let stream = p.train_stream(12, 3000);
        let mut a = Lwpr::new(config.clone()).unwrap();
        for (x, y) in &stream[..1500] {
            a.update(x, &[*y]).unwrap();
        }
        let json = serde_json::to_string(&a).unwrap();
        let mut b: Lwpr = serde_json::from_str(&json).unwrap();
        for (x, y) in &stream[1500..] {
            a.update(x, &[*y]).unwrap();
            b.update(x, &[*y]).unwrap();
        }
        assert_eq!(
            serde_json::to_string(&a).unwrap(),
            serde_json::to_string(&b).unwrap()
        );
        let (mut ya, mut yb) = ([0.0], [0.0]);
        for (x, _) in p.test_set(5) {
            a.predict(&x, &mut ya).unwrap();
            b.predict(&x, &mut yb).unwrap();
            assert_eq!(ya[0].to_bits(), yb[0].to_bits());
        }
    }
}
