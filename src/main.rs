//! The `steplearn` command: run the paper's experiments for any approximator and rule, sweep the
//! ablation grid (sharded for clusters), merge the results. It only parses arguments and calls
//! the library.

use clap::{Parser, Subcommand, ValueEnum};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use steplearn::approx::ApproxKind;
use steplearn::experiments::ExperimentKind;
use steplearn::experiments::run::{Protocols, run_spec};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::sweep::{
    RunOutcome, RunSpec, Shard, SweepGrid, SweepOptions, merge, run_sweep,
};
use steplearn::rules::RuleKind;

#[derive(Parser)]
#[command(
    name = "steplearn",
    version,
    about = "Online learning of foot placement: the paper's experiments"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Runs one experiment; writes CSV, SVG and DIR/summary.json.
    Experiment {
        /// Which experiment (only stability is implemented so far).
        experiment: ExperimentKind,
        /// The approximator.
        #[arg(long, default_value = "lwpr")]
        approx: ApproxKind,
        /// The learning rule.
        #[arg(long, default_value = "pendulum-cart")]
        rule: RuleKind,
        /// Seed of every random choice.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Number of pushes (default: the protocol's).
        #[arg(long)]
        pushes: Option<usize>,
        /// Push impulse range in Ns, "A,B".
        #[arg(long, value_parser = parse_range)]
        impulse_range: Option<(f64, f64)>,
        /// Direction of the pushes.
        #[arg(long, value_enum, default_value = "forward")]
        push_direction: Direction,
        /// Settings and protocols as TOML or JSON (`[settings]`, `[protocols]`).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
    },
    /// Runs the ablation grid (approximator x rule x seed on the implemented experiments),
    /// skipping runs whose summary.json exists.
    Sweep {
        /// Run only shard I of N (0-based), e.g. 3/50.
        #[arg(long)]
        shard: Option<Shard>,
        /// Seeds per configuration.
        #[arg(long, default_value_t = 5)]
        seeds: u64,
        /// Pushes per controller in experiment C (default: the protocol's 400).
        #[arg(long)]
        pushes: Option<usize>,
        /// Output directory (one sub-directory per run).
        #[arg(long)]
        out: PathBuf,
    },
    /// Builds ablation.md and ablation.csv from a sweep's directory.
    Merge {
        /// The sweep's output directory.
        dir: PathBuf,
    },
}

/// A push direction on the command line.
#[derive(Clone, Copy, ValueEnum)]
enum Direction {
    Forward,
    Backward,
    Left,
    Right,
}

impl Direction {
    fn unit(self) -> [f64; 3] {
        match self {
            Direction::Forward => [1.0, 0.0, 0.0],
            Direction::Backward => [-1.0, 0.0, 0.0],
            Direction::Left => [0.0, 1.0, 0.0],
            Direction::Right => [0.0, -1.0, 0.0],
        }
    }
}

fn parse_range(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("expected A,B, got '{s}'"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<f64>()
            .map_err(|e| format!("'{v}' is not a number: {e}"))
    };
    let (a, b) = (parse(a)?, parse(b)?);
    if !(a.is_finite() && b.is_finite() && 0.0 <= a && a <= b) {
        return Err(format!("need 0 <= A <= B, got {a},{b}"));
    }
    Ok((a, b))
}

/// The optional configuration file.
#[derive(Default, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
struct FileConfig {
    settings: Settings,
    protocols: Protocols,
}

fn load_config(path: &Path) -> Result<FileConfig, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let config: FileConfig = if path.extension().is_some_and(|e| e == "json") {
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?
    } else {
        toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?
    };
    config
        .settings
        .validate()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(config)
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Experiment {
            experiment,
            approx,
            rule,
            seed,
            pushes,
            impulse_range,
            push_direction,
            config,
            out,
        } => {
            let mut config = match config {
                Some(path) => load_config(&path)?,
                None => FileConfig::default(),
            };
            let p = &mut config.protocols.stability;
            if let Some(n) = pushes {
                if n == 0 {
                    return Err("--pushes must be at least 1".into());
                }
                p.pushes = n;
            }
            if let Some(r) = impulse_range {
                p.impulse = r;
            }
            p.direction = push_direction.unit();
            let spec = RunSpec {
                experiment,
                approx: approx.name().to_string(),
                rule,
                seed,
            };
            std::fs::create_dir_all(&out)
                .map_err(|e| format!("cannot create {}: {e}", out.display()))?;
            let summary = run_spec(&spec, &out, &config.settings, &config.protocols)
                .map_err(|e| e.to_string())?;
            summary
                .write(&out.join("summary.json"))
                .map_err(|e| e.to_string())?;
            println!("{}", summary.to_json().map_err(|e| e.to_string())?);
            Ok(())
        }
        Command::Sweep {
            shard,
            seeds,
            pushes,
            out,
        } => {
            let approx: Vec<&str> = ApproxKind::ALL.iter().map(|k| k.name()).collect();
            let grid = SweepGrid {
                experiments: vec![ExperimentKind::Stability],
                ..SweepGrid::full(&approx, seeds)
            };
            let runs = grid.runs().map_err(|e| e.to_string())?;
            let runs = match shard {
                Some(s) => s.select(&runs),
                None => runs,
            };
            let mut protocols = Protocols::default();
            if let Some(n) = pushes {
                protocols.stability.pushes = n.max(1);
            }
            let settings = Settings::default();
            let bar = indicatif::ProgressBar::new(runs.len() as u64);
            let runner = |spec: &RunSpec, dir: &Path| {
                run_spec(spec, dir, &settings, &protocols).map_err(|e| e.into())
            };
            let outcomes = run_sweep(
                &runs,
                &out,
                &runner,
                &SweepOptions::default(),
                &|_: &RunOutcome| bar.inc(1),
            )
            .map_err(|e| e.to_string())?;
            bar.finish_and_clear();
            println!("{} runs in {}", outcomes.len(), out.display());
            Ok(())
        }
        Command::Merge { dir } => {
            let merged = merge(&dir).map_err(|e| e.to_string())?;
            merged.write(&dir).map_err(|e| e.to_string())?;
            for p in &merged.problems {
                eprintln!("skipped: {p:?}");
            }
            println!(
                "{} runs merged into {}",
                merged.runs_read,
                dir.join("ablation.md").display()
            );
            Ok(())
        }
    }
}
