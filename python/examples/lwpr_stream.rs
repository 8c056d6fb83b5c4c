//! The Rust side of `python/bench_lwpr.py`: trains LWPR on a stream read from a file, times the
//! updates, and writes the test predictions, so that Python and Rust run on the same data.
//!
//! Usage: `lwpr_stream <config.json> <stream.f64> <n_train> <n_test> <reps> <predictions.f64>`.
//! The stream file holds little-endian f64: `n_train x n_in` inputs, `n_train x n_out` targets,
//! `n_test x n_in` test inputs. The trained model is also saved (`Persist::save`) to
//! `<predictions.f64>.json`. Prints `{"ns_per_update": [..one per rep..], "rfs": N}`.

use std::time::Instant;
use steplearn::approx::{FunctionApproximator, Lwpr, LwprConfig, Persist};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 7 {
        return Err(
            "usage: lwpr_stream <config.json> <stream.f64> <n_train> <n_test> <reps> <out.f64>"
                .into(),
        );
    }
    let config: LwprConfig = serde_json::from_str(&std::fs::read_to_string(&args[1])?)?;
    let bytes = std::fs::read(&args[2])?;
    let data: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
        .collect();
    let (n_train, n_test, reps): (usize, usize, usize) =
        (args[3].parse()?, args[4].parse()?, args[5].parse()?);
    let (n_in, n_out) = (config.n_in, config.n_out);
    if data.len() != n_train * (n_in + n_out) + n_test * n_in {
        return Err("stream file has the wrong length".into());
    }
    let (x, rest) = data.split_at(n_train * n_in);
    let (y, test) = rest.split_at(n_train * n_out);
    let mut times = Vec::new();
    let mut model = Lwpr::new(config.clone())?;
    for _ in 0..reps {
        model = Lwpr::new(config.clone())?;
        let start = Instant::now();
        for (xi, yi) in x.chunks_exact(n_in).zip(y.chunks_exact(n_out)) {
            model.update(xi, yi)?;
        }
        times.push(start.elapsed().as_nanos() as f64 / n_train as f64);
    }
    let mut out = Vec::with_capacity(n_test * n_out * 8);
    let mut yo = vec![0.0; n_out];
    for xi in test.chunks_exact(n_in) {
        model.predict(xi, &mut yo)?;
        yo.iter()
            .for_each(|v| out.extend_from_slice(&v.to_le_bytes()));
    }
    std::fs::write(&args[6], out)?;
    model.save(format!("{}.json", args[6]))?;
    println!(
        "{{\"ns_per_update\": {times:?}, \"rfs\": {}}}",
        model.num_receptive_fields()
    );
    Ok(())
}
