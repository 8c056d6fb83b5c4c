//! The run picture of a short recorded run.

use steplearn::control::motion::{MotionConfig, MotionGenerator};
use steplearn::sim::picture::{RunRecord, StepAnnotation};
use steplearn::sim::{Humanoid, SimConfig};

#[test]
fn picture_shows_figures_paths_pushes_falls_and_annotations() {
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    let g = MotionGenerator::new(
        MotionConfig::default().check().unwrap(),
        &sim.body().leg_geometry(),
    );
    let mut rec = RunRecord::new("test run");
    rec.record(&sim.ground_truth());
    while sim.time() < 0.5 {
        sim.step(&g.halt_targets()).unwrap();
        rec.record(&sim.ground_truth());
    }
    rec.push(0.2, [3.0, 0.0, 0.0]);
    rec.fall(0.4);
    rec.annotate(StepAnnotation {
        time: 0.1,
        zmp: Some([0.02, 0.1]),
        footstep: Some([0.1, -0.2]),
        step_time: Some(0.45),
    });
    let svg = rec.to_svg(0.1);
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("side view") && svg.contains("front view"));
    assert!(svg.contains("3.0Ns"), "push label");
    assert!(svg.contains(">fall<"), "fall marker");
    assert!(svg.contains(">Z<") && svg.contains(">F<") && svg.contains("T0.45"));
    // One stick figure per 0.1 s (6 heads per strip, two strips).
    assert_eq!(svg.matches("<circle").count() / 2, 2 * 6);
    let dir = std::env::temp_dir().join("steplearn_picture_test");
    let path = dir.join("run.svg");
    rec.write_svg(&path, 0.1).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), svg);
}
