//! Experiment C, short: three controllers see the same pushes; results and files are written.

use steplearn::approx::ApproxKind;
use steplearn::control::{FootstepLearner, InputGrid, LearnerConfig};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::stability::{self, StabilityProtocol};
use steplearn::rules::PendulumCart;

#[test]
fn same_pushes_for_every_controller_and_files_written() {
    let protocol = StabilityProtocol {
        pushes: 4,
        impulse: (0.0, 20.0),
        ..StabilityProtocol::default()
    };
    let bounds = InputGrid::default().input_box().unwrap();
    let make = || {
        FootstepLearner::new(
            ApproxKind::Lwpr.build(&bounds).unwrap(),
            PendulumCart::default(),
            LearnerConfig::default(),
        )
    };
    let r = stability::run(&Settings::default(), &protocol, 7, &make).unwrap();
    let impulses =
        |c: &stability::ControllerPushes| c.pushes.iter().map(|p| p.impulse).collect::<Vec<_>>();
    assert_eq!(r.open_loop.pushes.len(), 4);
    assert_eq!(impulses(&r.open_loop), impulses(&r.model));
    assert_eq!(impulses(&r.open_loop), impulses(&r.learned));
    assert!(impulses(&r.model).iter().all(|i| (0.0..20.0).contains(i)));
    for (_, c) in r.controllers() {
        assert!(c.fall50.impulse_ns.is_finite());
    }

    let dir = std::env::temp_dir().join(format!("steplearn-stability-{}", std::process::id()));
    r.write(&dir, protocol.impulse, protocol.direction).unwrap();
    let csv = std::fs::read_to_string(dir.join("pushes.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 12);
    let svg = std::fs::read_to_string(dir.join("fall_probability.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("open-loop") && svg.contains("learned"));
    std::fs::remove_dir_all(&dir).ok();

    // Same seed, same result.
    let again = stability::run(&Settings::default(), &protocol, 7, &make).unwrap();
    assert_eq!(r, again);
}
