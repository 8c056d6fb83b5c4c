//! The bench from Rust: this crate's approximator and rule against the paper's, on two of the
//! paper's experiments and this crate's own, checked for a paired verdict in every row.
//! `cargo run --example bench -- [SCALE] [SEEDS] [OUT]`.

use steplearn::approx::InputBox;
use steplearn::approx::conformance::check_approximator;
use steplearn::bench::Bench;
use steplearn_user_crate::{knn::Knn, registry};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scale: f64 = args.first().map_or(Ok(0.05), |s| s.parse())?;
    let seeds: u64 = args.get(1).map_or(Ok(2), |s| s.parse())?;
    let out = args
        .get(2)
        .cloned()
        .unwrap_or_else(|| "results/user-bench".into());
    let bounds = InputBox::new(vec![-0.5, -3.0, -0.1], vec![0.5, 3.0, 0.2])?;
    check_approximator(|| Knn::new(&bounds).expect("valid box"))?;
    let registry = registry();
    let report = Bench::new(&registry)
        .approximators(["knn", "lwpr"])
        .rules(["softsign-cart", "pendulum-cart"])
        .experiments(["stability", "robustness", "forward-pushes"])
        .seeds(seeds)
        .scale(scale)
        .out(&out)
        .run()?;
    print!("{}", report.leaderboard.to_markdown());
    for row in &report.leaderboard.rows {
        let verdicts = row.vs_model.iter().filter(|c| c.verdict.is_some()).count();
        if seeds >= 2 && verdicts == 0 {
            return Err(format!(
                "no paired verdict for {} + {} on {}",
                row.approx, row.rule, row.experiment
            )
            .into());
        }
    }
    println!(
        "{} rows, each with a paired verdict against the model",
        report.leaderboard.rows.len()
    );
    Ok(())
}
