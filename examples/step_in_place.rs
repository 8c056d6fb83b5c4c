//! Steps in place open-loop for 60 s, writes its run picture, then searches the largest
//! forward push survived while stepping in place (pushed at several gait phases).
//!
//! `cargo run --release --example step_in_place -- [results/step_in_place.svg]`

mod common;

use common::{Mode, largest_push, run};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "results/step_in_place.svg".to_string());
    let out = run(
        Mode::Step(0.0),
        60.0,
        &[],
        "open-loop stepping in place, 60 s",
    );
    let first = out.record.frames.first().expect("frames");
    let last = out.record.frames.last().expect("frames");
    println!(
        "step in place 60 s: fell at {:?}; CoM drift x {:+.3} y {:+.3} m; {:.1}x real time",
        out.fell_at,
        last.com[0] - first.com[0],
        last.com[1] - first.com[1],
        last.time / out.wall
    );
    out.record.write_svg(std::path::Path::new(&path), 1.0)?;
    println!("wrote {path}");
    // Push at four phases of a 0.4 s step; report each and the smallest.
    let mut worst = f64::INFINITY;
    for k in 0..4 {
        let t = 3.0 + 0.1 * k as f64;
        let best = largest_push(Mode::Step(0.0), t, 20.0);
        println!(
            "largest forward push survived stepping in place, pushed at {t:.1} s: {best:.1} Ns"
        );
        worst = worst.min(best);
    }
    println!("largest push survived at every tested phase: {worst:.1} Ns");
    Ok(())
}
