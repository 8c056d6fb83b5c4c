//! Stands still for 60 s, then searches the largest forward push survived standing, and
//! writes the run picture of the 60 s stand with a 2 N s push at 30 s.
//!
//! `cargo run --release --example stand -- [results/stand.svg]`

mod common;

use common::{Mode, largest_push, run};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "results/stand.svg".to_string());
    let out = run(
        Mode::Stand,
        60.0,
        &[(30.0, [2.0, 0.0, 0.0])],
        "standing 60 s, 2 Ns forward push at 30 s",
    );
    let last = out.record.frames.last().expect("frames");
    println!(
        "stand 60 s with a 2 Ns push: fell at {:?}; CoM at end {:.3?}; {:.1}x real time",
        out.fell_at,
        last.com,
        last.time / out.wall
    );
    out.record.write_svg(std::path::Path::new(&path), 1.5)?;
    println!("wrote {path}");
    let best = largest_push(Mode::Stand, 1.0, 20.0);
    println!("largest forward push survived standing: {best:.1} Ns (0.5 Ns steps)");
    Ok(())
}
