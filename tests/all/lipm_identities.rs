//! Property tests of the closed-form LIPM identities.

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use steplearn::control::lipm::{Lipm, LipmState};

fn lipm() -> impl Strategy<Value = Lipm> {
    (1.0f64..6.0).prop_map(|c| Lipm::new(c).unwrap())
}

fn state() -> impl Strategy<Value = LipmState> {
    (-0.3f64..0.3, -1.5f64..1.5).prop_map(|(p, v)| LipmState::new(p, v))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, rng_seed: RngSeed::Fixed(1), ..ProptestConfig::default() })]

    /// Running forward `T` with the ZMP solved for target `s` lands exactly on `s`.
    #[test]
    fn zmp_to_reach_lands_on_target(l in lipm(), s in state(), target in -0.3f64..0.3, t in 0.05f64..1.0) {
        let z = l.zmp_to_reach(s, target, t).unwrap();
        let end = l.state_after(s, z, t);
        prop_assert!((end.pos - target).abs() < 1e-9 * (1.0 + z.abs()), "end {} target {}", end.pos, target);
    }

    /// The time to reach a location is consistent with the state after that time.
    #[test]
    fn time_to_location_consistent(l in lipm(), s in state(), z in -0.1f64..0.1, t in 0.0f64..1.0) {
        let x = l.state_after(s, z, t).pos;
        let t_hit = l.time_to_location(s, z, x).expect("a visited location is reachable");
        // The latest of (at most two) solutions: not earlier than t, and it is at x.
        prop_assert!(t_hit >= t - 1e-6, "t_hit {} < t {}", t_hit, t);
        prop_assert!((l.state_after(s, z, t_hit).pos - x).abs() < 1e-8);
    }

    /// The time to reach a velocity is consistent with the state after that time.
    #[test]
    fn time_to_velocity_consistent(l in lipm(), s in state(), z in -0.1f64..0.1, t in 0.0f64..1.0) {
        let v = l.state_after(s, z, t).vel;
        let t_hit = l.time_to_velocity(s, z, v).expect("a visited velocity is reachable");
        prop_assert!(t_hit >= t - 1e-6, "t_hit {} < t {}", t_hit, t);
        prop_assert!((l.state_after(s, z, t_hit).vel - v).abs() < 1e-8);
    }

    /// Orbital energy about the pivot is conserved along a trajectory.
    #[test]
    fn energy_conserved(l in lipm(), s in state(), z in -0.1f64..0.1, t in -1.0f64..1.0) {
        let e0 = l.energy(s, z);
        let e1 = l.energy(l.state_after(s, z, t), z);
        let scale = 1.0 + s.vel * s.vel + l.c() * l.c() * (s.pos - z).powi(2);
        prop_assert!((e0 - e1).abs() < 1e-9 * scale * (l.c() * t).cosh().powi(2));
    }

    /// State propagation composes: running t1 then t2 equals running t1 + t2.
    #[test]
    fn propagation_composes(l in lipm(), s in state(), z in -0.1f64..0.1, t1 in 0.0f64..0.6, t2 in 0.0f64..0.6) {
        let a = l.state_after(l.state_after(s, z, t1), z, t2);
        let b = l.state_after(s, z, t1 + t2);
        prop_assert!((a.pos - b.pos).abs() < 1e-9 && (a.vel - b.vel).abs() < 1e-8);
    }

    /// A pivot placed with `pivot_for` makes the mass pass the requested state.
    #[test]
    fn pivot_reaches_requested_apex(l in lipm(), s in state(), apex in 0.02f64..0.2, side in prop::bool::ANY) {
        // Request rest (velocity 0) at `apex` on one side of the new pivot: always feasible.
        let target = if side { apex } else { -apex };
        let offset = l.pivot_for(s, target, 0.0).unwrap();
        let pivot = s.pos + offset;
        // The mass, seen from the new pivot, must reach velocity 0 at position `target`.
        let rel = LipmState::new(s.pos - pivot, s.vel);
        prop_assert!((l.energy(rel, 0.0) - l.energy(LipmState::new(target, 0.0), 0.0)).abs() < 1e-9);
        prop_assert!(rel.pos * target > 0.0 || rel.pos == 0.0);
        if let Some(t) = l.time_to_velocity(rel, 0.0, 0.0) {
            let at = l.state_after(rel, 0.0, t);
            prop_assert!((at.pos - target).abs() < 1e-6, "apex at {} wanted {}", at.pos, target);
        }
    }
}

#[test]
fn capture_point_brings_mass_to_rest() {
    let l = Lipm::new(3.0).unwrap();
    let s = LipmState::new(0.05, 0.4);
    let cp = l.capture_point(s);
    // With the pivot at the capture point, the mass approaches it with vanishing velocity.
    let late = l.state_after(s, cp, 5.0);
    assert!((late.pos - cp).abs() < 1e-6 && late.vel.abs() < 1e-5);
    assert!(l.energy(s, cp).abs() < 1e-12);
}
