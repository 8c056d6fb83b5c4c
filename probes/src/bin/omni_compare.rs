//! Is one `both` walker better than another? Reads the `omnidirectional` summaries of two bench
//! directories run on the same seeds (for example the uncoupled and the coupled learners) and
//! prints, per sector, the mean I50 of the model and of each directory's walker `both`, then
//! the second's `both` against the first's, paired by seed: the sectors' mean I50 ratio and
//! the walk's mean step error ratio, each with its 95% Student-t interval. Then, for each
//! directory, the lateral pushes (the sectors at 90 and 270 degrees) paired against the model
//! for the walkers `sagittal` and `both`, and the falls by cause per sector (summed over the
//! seeds) of the model and of `both`.
//!
//! ```text
//! cargo run --release -p steplearn-probes --bin omni_compare -- \
//!     results-archive/omnidirectional results-archive/omnidirectional-coupled
//! ```

use std::collections::BTreeMap;
use std::path::Path;
use steplearn::experiments::omnidirectional::{OmnidirectionalResult, SECTORS};
use steplearn::experiments::paired::{Direction, Paired};

/// The `omnidirectional` results of a bench directory, by seed (one approximator and rule).
fn results(dir: &Path) -> Result<BTreeMap<u64, OmnidirectionalResult>, Box<dyn std::error::Error>> {
    let mut by_seed = BTreeMap::new();
    for (path, json) in steplearn_probes::summaries(dir, "omnidirectional")? {
        let seed = json["seed"]
            .as_u64()
            .ok_or_else(|| format!("{}: no seed", path.display()))?;
        let result: OmnidirectionalResult = serde_json::from_value(json)?;
        if by_seed.insert(seed, result).is_some() {
            return Err(format!("{}: two runs of seed {seed}", dir.display()).into());
        }
    }
    Ok(by_seed)
}

/// Mean of the finite values.
fn mean(values: impl IntoIterator<Item = f64>) -> f64 {
    let v: Vec<f64> = values.into_iter().filter(|v| v.is_finite()).collect();
    v.iter().sum::<f64>() / v.len() as f64
}

/// The walk's mean step error of walker `both` over the sectors it visited (m).
fn walk_error(r: &OmnidirectionalResult) -> f64 {
    mean(r.walk_error_m["both"].iter().flatten().copied())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [first, second] = args.as_slice() else {
        return Err("usage: omni_compare FIRST_BENCH_DIR SECOND_BENCH_DIR".into());
    };
    let (a, b) = (results(Path::new(first))?, results(Path::new(second))?);
    let seeds: Vec<u64> = a.keys().filter(|s| b.contains_key(s)).copied().collect();
    if seeds.len() < 2 {
        return Err(format!("need two seeds in both directories, found {seeds:?}").into());
    }
    println!("seeds {seeds:?}; I50 (Ns), mean over the seeds");
    println!("| azimuth | model | both, {first} | both, {second} | second / model |");
    println!("|---|---|---|---|---|");
    for k in 0..SECTORS {
        let m = mean(seeds.iter().map(|s| b[s].i50_ns["model"][k]));
        let x = mean(seeds.iter().map(|s| a[s].i50_ns["both"][k]));
        let y = mean(seeds.iter().map(|s| b[s].i50_ns["both"][k]));
        let deg = b[&seeds[0]].sectors_deg[k];
        println!("| {deg:.0} | {m:.2} | {x:.2} | {y:.2} | {:.2} |", y / m);
    }
    // The sectors' mean as the experiment defines it: the ratio of the sectors' mean I50s (a
    // sector with an I50 near 0 does not dominate it, as it would a mean of ratios).
    let i50: Vec<f64> = seeds
        .iter()
        .map(|s| {
            let sum =
                |r: &OmnidirectionalResult| (0..SECTORS).map(|k| r.i50_ns["both"][k]).sum::<f64>();
            sum(&b[s]) / sum(&a[s])
        })
        .collect();
    let walk: Vec<f64> = seeds
        .iter()
        .map(|s| walk_error(&b[s]) / walk_error(&a[s]))
        .collect();
    for p in [
        Paired::new(
            "I50 both, second / first, sectors' mean",
            &i50,
            1.0,
            Direction::HigherIsBetter,
        ),
        Paired::new(
            "walk error both, second / first, sectors' mean",
            &walk,
            1.0,
            Direction::LowerIsBetter,
        ),
    ] {
        println!("{}", p.describe(3));
    }
    for (name, runs) in [(first, &a), (second, &b)] {
        println!(
            "\n{name}: lateral pushes (90 and 270 degrees), I50 over the model's, paired by seed"
        );
        for walker in ["sagittal", "both"] {
            let lateral: Vec<f64> = seeds
                .iter()
                .map(|s| {
                    let ratio = runs[s].ratio_to_model(walker);
                    (ratio[LEFT] + ratio[RIGHT]) / 2.0
                })
                .collect();
            let label = format!("I50 {walker} / model, lateral");
            println!(
                "{}",
                Paired::new(&label, &lateral, 1.0, Direction::HigherIsBetter).describe(3)
            );
        }
        println!("{name}: falls by cause, summed over the seeds (model / both)");
        println!("| azimuth | {} |", CAUSES.join(" | "));
        println!("|---|{}", "---|".repeat(CAUSES.len()));
        for k in 0..SECTORS {
            let count = |walker: &str, cause: &str| -> u32 {
                seeds
                    .iter()
                    .map(|s| {
                        runs[s].fall_causes[walker][k]
                            .get(cause)
                            .copied()
                            .unwrap_or(0)
                    })
                    .sum()
            };
            let cells: Vec<String> = CAUSES
                .iter()
                .map(|c| format!("{} / {}", count("model", c), count("both", c)))
                .collect();
            println!("| {} | {} |", k * 360 / SECTORS, cells.join(" | "));
        }
    }
    Ok(())
}

/// The sectors of the lateral pushes (90 and 270 degrees).
const LEFT: usize = SECTORS / 4;
const RIGHT: usize = 3 * SECTORS / 4;

/// The fall causes reported, in the order of a push's course (experiment C's classes; the
/// falls without a push are left out).
const CAUSES: [&str; 4] = [
    "before_touch_down",
    "tipped_after_catch_step",
    "catch_step_clamped",
    "later_step_clamped",
];
