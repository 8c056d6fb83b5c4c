//! A learner that runs for days sees drifting inputs. Trains LWPR on a million samples of a
//! drifting 3-input stream, without and with `max_rfs(500)`, and prints, every 100,000
//! updates, the receptive fields, the saved model's size and the seconds the last 100,000
//! updates took.
//!
//! Run with `cargo run --release --example lwpr_drift`.

use std::time::Instant;
use steplearn::approx::problems::Drift;
use steplearn::approx::{FunctionApproximator, Lwpr, LwprConfig, Persist};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("| max_rfs | updates | receptive fields | saved size (MB) | s per 100k updates |");
    println!("|---|---|---|---|---|");
    for cap in [None, Some(500)] {
        let config = LwprConfig::new(3, 1);
        let mut model = Lwpr::new(match cap {
            Some(n) => config.max_rfs(n),
            None => config,
        })?;
        let mut stream = Drift::new(1, 1e-3, 1.0);
        for block in 1..=10 {
            let start = Instant::now();
            for (x, y) in stream.by_ref().take(100_000) {
                model.update(&x, &[y])?;
            }
            let secs = start.elapsed().as_secs_f64();
            let mb = model.to_json()?.len() as f64 / 1e6;
            let cap = cap.map_or("none".to_string(), |n| n.to_string());
            let (n, k) = (model.num_receptive_fields(), block * 100_000);
            println!("| {cap} | {k} | {n} | {mb:.1} | {secs:.2} |");
        }
    }
    Ok(())
}
