//! How many experiences does each rule need? Reads the experiment-D (`robustness`) summaries
//! of a bench directory and prints, per rule, the share of pushes absorbed in blocks of pushes
//! (mean over seeds with its 95% Student-t interval), with and without learning, and writes the
//! curves as `learning_curve.svg` beside them.
//!
//! ```text
//! printf '[protocols.robustness]\npushes = 100\n\n[protocols.robustness.map]\nresolution = [3, 3]\n' > curve.toml
//! cargo run --release -- bench --approx lwpr --rule pendulum-cart,policy-gradient \
//!     --experiments robustness --seeds 10 --config curve.toml --out results/curve
//! cargo run --release -p steplearn-probes --bin learning_curve -- results/curve 10
//! ```

use std::collections::BTreeMap;
use std::path::PathBuf;
use steplearn::report::figures::{LinePlot, Series, line_plot};
use steplearn::stats::MeanStd;

/// One seed's pushes: absorbed by push with learning, and without.
type SeedRun = (Vec<bool>, Vec<bool>);

/// A curve: its name, block ends, mean shares and their 95% half-widths.
type Curve = (String, Vec<f64>, Vec<f64>, Vec<f64>);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let dir = PathBuf::from(
        args.next()
            .ok_or("usage: learning_curve BENCH_DIR [BLOCK]")?,
    );
    let block: usize = args.next().map_or(Ok(10), |b| b.parse())?;
    if block == 0 {
        return Err("BLOCK must be at least 1".into());
    }
    // Per "approx + rule": per seed, absorbed by push (learned, without learning).
    let mut runs: BTreeMap<String, Vec<SeedRun>> = BTreeMap::new();
    for (_, json) in steplearn_probes::summaries(&dir, "robustness")? {
        let flags = |v: &serde_json::Value| -> Vec<bool> {
            v.as_array()
                .map(|a| a.iter().filter_map(|b| b.as_bool()).collect())
                .unwrap_or_default()
        };
        let name = format!(
            "{} + {}",
            json["approx"].as_str().unwrap_or("?"),
            json["rule"].as_str().unwrap_or("?")
        );
        runs.entry(name).or_default().push((
            flags(&json["absorbed_by_push"]),
            flags(&json["no_learning"]["absorbed_by_push"]),
        ));
    }
    if runs.is_empty() {
        return Err(format!("no robustness summaries in {}", dir.display()).into());
    }
    let mut curves: Vec<Curve> = Vec::new();
    for (name, seeds) in &runs {
        for (label, pick) in [("learned", 0), ("without learning", 1)] {
            let pushes = seeds
                .iter()
                .map(|s| if pick == 0 { s.0.len() } else { s.1.len() })
                .min()
                .unwrap_or(0);
            let (mut x, mut y, mut band) = (Vec::new(), Vec::new(), Vec::new());
            let mut cells = Vec::new();
            for start in (0..pushes).step_by(block) {
                let end = (start + block).min(pushes);
                let stats = MeanStd::of(seeds.iter().map(|s| {
                    let v = if pick == 0 { &s.0 } else { &s.1 };
                    v[start..end].iter().filter(|a| **a).count() as f64 / (end - start) as f64
                }));
                let half = stats.ci95_half_width().unwrap_or(0.0);
                x.push(end as f64);
                y.push(stats.mean());
                band.push(half);
                cells.push(format!(
                    "{:.2} [{:.2}, {:.2}]",
                    stats.mean(),
                    stats.mean() - half,
                    stats.mean() + half
                ));
            }
            println!(
                "{name}, {label} ({} seeds), absorbed share per {block} pushes: {}",
                seeds.len(),
                cells.join(" | ")
            );
            curves.push((format!("{name}, {label}"), x, y, band));
        }
    }
    let series: Vec<Series> = curves
        .iter()
        .map(|(name, x, y, band)| Series {
            name,
            x,
            y,
            spread: Some(band),
        })
        .collect();
    let out = dir.join("learning_curve.svg");
    line_plot(
        &out,
        &LinePlot {
            title: "Learning from scratch (experiment D): pushes absorbed",
            x_label: "pushes (end of block)",
            y_label: "share absorbed in the block",
            series: &series,
        },
    )?;
    println!("wrote {}", out.display());
    Ok(())
}
