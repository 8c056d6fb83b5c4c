//! One control tick of the Capture Step walker stepping in place, per robot: the built-in
//! humanoid, the igus-like robot and Talos as shipped (20 held upper-body joints merged into
//! its trunk). Time per simulated second = measured time / tick duration.
//!
//! `cargo bench --bench robots` (Talos is installed by scripts/install-robots.sh).

use criterion::{Criterion, criterion_group, criterion_main};
use std::path::PathBuf;
use steplearn::control::{Walker, WalkerConfig, WalkerMode};
use steplearn::robot::RobotFile;
use steplearn::sim::{BodyConfig, Humanoid, SimConfig};

fn robots() -> Vec<(String, Option<PathBuf>)> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut out = vec![
        ("built-in humanoid".to_string(), None),
        (
            "igus-like".to_string(),
            Some(root.join("robots/igus_like.urdf")),
        ),
    ];
    let talos = std::process::Command::new("bash")
        .arg(root.join("scripts/install-robots.sh"))
        .output()
        .expect("bash");
    if let Some(path) = String::from_utf8_lossy(&talos.stdout).lines().last() {
        out.push(("talos".to_string(), Some(PathBuf::from(path))));
    }
    out
}

fn walker_tick(c: &mut Criterion) {
    for (name, path) in robots() {
        let mut config = SimConfig::default();
        if let Some(p) = path {
            let body = BodyConfig::default();
            let (file, _) =
                RobotFile::open(&p, None, &body.servo_reference(), &config.initial_joints)
                    .expect("robot loads");
            config.robot = Some(file);
        }
        let tick = config.tick();
        let mut sim = Humanoid::new(config).unwrap();
        let walker_config = WalkerConfig::new(WalkerMode::CaptureStep).for_robot(&sim.scale());
        let mut walker = Walker::new(walker_config, sim.robot().leg_geometry()).unwrap();
        while sim.time() < 2.0 {
            let t = walker.tick(&sim.sensors(), 0.0, None).unwrap();
            sim.step(&t.targets).unwrap();
        }
        let label = format!(
            "{name}: walker stepping in place, one control tick ({:.0} ms)",
            tick * 1e3
        );
        c.bench_function(&label, |b| {
            b.iter(|| {
                let t = walker.tick(&sim.sensors(), 0.0, None).unwrap();
                sim.step(&t.targets).unwrap();
                assert!(sim.fall().is_none(), "{name} fell stepping in place");
            })
        });
    }
}

criterion_group!(benches, walker_tick);
criterion_main!(benches);
