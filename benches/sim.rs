//! One control tick of the open-loop stepping robot: read the sensors, run the step motion
//! generator, advance the physics by one tick (5 steps of 2 ms by default), check for a fall.
//! Real-time factor = tick duration / measured time.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use steplearn::control::motion::{MotionConfig, MotionGenerator};
use steplearn::sim::{Humanoid, SimConfig};

fn control_tick(c: &mut Criterion) {
    let config = SimConfig::default();
    let tick = config.tick();
    let mut sim = Humanoid::new(config).unwrap();
    let mut generator = MotionGenerator::new(
        MotionConfig::default().check().unwrap(),
        &sim.body().leg_geometry(),
    );
    // Warm up into steady stepping.
    while sim.time() < 2.0 {
        let cmd = generator.open_loop(0.0);
        sim.step(&generator.update(&cmd, tick)).unwrap();
    }
    let name = format!("stepping robot control tick ({:.0} ms)", tick * 1e3);
    c.bench_function(&name, |b| {
        b.iter(|| {
            let sensors = sim.sensors();
            black_box(&sensors);
            let cmd = generator.open_loop(0.0);
            let targets = generator.update(&cmd, tick);
            sim.step(&targets).unwrap();
            if sim.fall().is_some() {
                sim.reset();
                generator = MotionGenerator::new(
                    MotionConfig::default().check().unwrap(),
                    &sim.body().leg_geometry(),
                );
            }
        })
    });
}

/// The physics alone: one control tick of the standing robot with fixed targets.
fn physics_tick(c: &mut Criterion) {
    let config = SimConfig::default();
    let tick = config.tick();
    let mut sim = Humanoid::new(config).unwrap();
    let generator = MotionGenerator::new(
        MotionConfig::default().check().unwrap(),
        &sim.body().leg_geometry(),
    );
    let targets = generator.halt_targets();
    let name = format!("standing robot physics only ({:.0} ms)", tick * 1e3);
    c.bench_function(&name, |b| b.iter(|| sim.step(black_box(&targets)).unwrap()));
}

criterion_group!(benches, control_tick, physics_tick);
criterion_main!(benches);
