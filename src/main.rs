//! The `steplearn` command: reproduce the paper (all four experiments over several seeds, with a
//! per-claim report), run one experiment for any approximator and rule, sweep the ablation grid
//! (sharded for clusters), merge the results. It only parses arguments and calls the library.

use clap::{Parser, Subcommand, ValueEnum};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use steplearn::Named;
use steplearn::approx::ApproxKind;
use steplearn::experiments::ExperimentKind;
use steplearn::experiments::config_file::ConfigFile;
use steplearn::experiments::experiment::PushOptions;
use steplearn::experiments::index_page::{command_line, write_index};
use steplearn::experiments::reproduce::{self, Claims};
use steplearn::experiments::run::{Protocols, run_spec};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::sweep::{
    RunOutcome, RunSpec, RunStatus, SUMMARY_FILE, Shard, SweepGrid, SweepOptions, merge, run_sweep,
};
use steplearn::rules::{PendulumCart, RuleKind};
use strum::VariantArray;

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
    /// The main job: all four experiments with LWPR + pendulum-cart over several seeds; writes
    /// one directory per run (CSV, SVG, summary.json) and DIR/claims.{md,json}, whether each of
    /// the paper's claims holds. Finished runs in DIR are reused.
    Reproduce {
        /// Output directory [default: results/paper, or results/quick with --quick].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Seeds 0..N [default: 5, or 2 with --quick].
        #[arg(long)]
        seeds: Option<u64>,
        /// A fast look: every experiment at a tenth of its length.
        #[arg(long)]
        quick: bool,
        /// Settings and protocols as TOML or JSON (`[settings]`, `[protocols]`).
        #[arg(long)]
        config: Option<PathBuf>,
    },
    /// Runs one experiment; writes CSV, SVG and DIR/summary.json.
    Experiment {
        /// Which experiment.
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
        /// Number of pushes (default: the protocol's; not for tracking).
        #[arg(long)]
        pushes: Option<usize>,
        /// Push impulse range in Ns, "A,B" (disturbance and robustness use one impulse: A,A).
        #[arg(long, value_parser = parse_range)]
        impulse_range: Option<(f64, f64)>,
        /// Direction of the pushes (default: the protocol's, forward unless a config file
        /// sets `direction`).
        #[arg(long, value_enum)]
        push_direction: Option<Direction>,
        /// Settings and protocols as TOML or JSON (`[settings]`, `[protocols]`).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
    },
    /// Runs the ablation grid (approximator x rule x seed on experiments C and D), skipping
    /// runs whose summary.json exists.
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
    /// Prints the complete default configuration (every section and key) as TOML, a
    /// starting point for `--config`; with --check, validates a config file instead.
    Config {
        /// Check FILE (TOML, or JSON if it ends in .json): prints `ok`, or what is wrong and
        /// exits with an error.
        #[arg(long, value_name = "FILE")]
        check: Option<PathBuf>,
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
        Command::Reproduce {
            out,
            seeds,
            quick,
            config,
        } => {
            let mut config = match config {
                Some(path) => ConfigFile::load(&path)?,
                None => ConfigFile::default(),
            };
            if quick {
                config.settings.scale = 0.1;
            }
            let seeds = seeds.unwrap_or(if quick { 2 } else { 5 });
            if seeds == 0 {
                return Err("--seeds must be at least 1".into());
            }
            let out = out.unwrap_or_else(|| {
                PathBuf::from(if quick {
                    "results/quick"
                } else {
                    "results/paper"
                })
            });
            let grid = reproduce::grid(seeds);
            let runs = grid.runs().map_err(|e| e.to_string())?;
            let started = std::time::Instant::now();
            let failed = sweep_with_progress(&runs, &out, &config.settings, &config.protocols)?;
            let (summaries, missing) =
                reproduce::read_summaries(&grid, &out).map_err(|e| e.to_string())?;
            let claims = Claims::from_summaries(&summaries, PendulumCart::default().p_theta);
            claims.write(&out).map_err(|e| e.to_string())?;
            let config_toml = config.to_toml().map_err(|e| e.to_string())?;
            write_index(
                &out,
                "steplearn reproduce: the paper's claims",
                &["claims.md"],
                &command_line(),
                Some(&config_toml),
            )
            .map_err(|e| e.to_string())?;
            for c in claims.all() {
                let k = c.seeds.iter().filter(|s| s.1).count();
                println!(
                    "{} {} ({k}/{} seeds)",
                    if c.holds {
                        "REPRODUCED    "
                    } else {
                        "NOT REPRODUCED"
                    },
                    c.statement,
                    c.seeds.len()
                );
                for p in &c.over_seeds {
                    println!("    over seeds: {}", p.describe(3));
                }
            }
            println!(
                "{} runs in {} ({:.0} s); report: {}",
                runs.len(),
                out.display(),
                started.elapsed().as_secs_f64(),
                out.join("claims.md").display()
            );
            if failed > 0 || !missing.is_empty() {
                return Err(format!(
                    "{failed} runs failed; missing results: {}",
                    missing.join(", ")
                ));
            }
            Ok(())
        }
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
                Some(path) => ConfigFile::load(&path)?,
                None => ConfigFile::default(),
            };
            apply_push_options(
                &mut config.protocols,
                experiment,
                pushes,
                impulse_range,
                push_direction.map(Direction::unit),
            )?;
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
            let config_toml = config.to_toml().map_err(|e| e.to_string())?;
            write_index(
                &out,
                &format!(
                    "steplearn experiment {experiment} ({}, {rule}, seed {seed})",
                    approx.name()
                ),
                &["summary.json"],
                &command_line(),
                Some(&config_toml),
            )
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
            let approx: Vec<&str> = ApproxKind::VARIANTS.iter().map(|k| k.name()).collect();
            let grid = SweepGrid {
                experiments: vec![ExperimentKind::Stability, ExperimentKind::Robustness],
                ..SweepGrid::full(&approx, seeds)
            };
            let runs = grid.runs().map_err(|e| e.to_string())?;
            let runs = match shard {
                Some(s) => s.select(&runs),
                None => runs,
            };
            let mut protocols = Protocols::default();
            if let Some(n) = pushes {
                protocols.stability.pushes = n;
            }
            protocols.validate().map_err(|e| format!("--pushes: {e}"))?;
            let failed = sweep_with_progress(&runs, &out, &Settings::default(), &protocols)?;
            println!("{} runs in {}", runs.len(), out.display());
            if failed > 0 {
                return Err(format!("{failed} runs failed"));
            }
            Ok(())
        }
        Command::Config { check: None } => {
            print!("{}", ConfigFile::default_toml());
            Ok(())
        }
        Command::Config { check: Some(path) } => {
            ConfigFile::load(&path)?;
            println!("ok");
            Ok(())
        }
        Command::Merge { dir } => {
            let merged = merge(&dir).map_err(|e| e.to_string())?;
            for p in &merged.problems {
                eprintln!("skipped {p}");
            }
            if merged.runs_read == 0 {
                // Nothing to tabulate: an empty table would overwrite a real one.
                return Err(format!(
                    "no finished runs to merge in {} (a run is a directory with {SUMMARY_FILE}; {} unfinished, {} unreadable)",
                    dir.display(),
                    merged.unfinished.len(),
                    merged.problems.len()
                ));
            }
            merged.write(&dir).map_err(|e| e.to_string())?;
            write_index(
                &dir,
                "steplearn merge: the ablation table",
                &["ablation.md"],
                &command_line(),
                None,
            )
            .map_err(|e| e.to_string())?;
            println!(
                "{} runs merged into {}",
                merged.runs_read,
                dir.join("ablation.md").display()
            );
            Ok(())
        }
    }
}

/// Runs `runs` into `out` with a progress bar on stderr (hidden when stderr is not a terminal);
/// prints each failure and returns how many failed.
fn sweep_with_progress(
    runs: &[RunSpec],
    out: &Path,
    settings: &Settings,
    protocols: &Protocols,
) -> Result<usize, String> {
    let bar = indicatif::ProgressBar::new(runs.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {msg}")
            .map_err(|e| e.to_string())?,
    );
    let runner =
        |spec: &RunSpec, dir: &Path| run_spec(spec, dir, settings, protocols).map_err(|e| e.into());
    let outcomes = run_sweep(
        runs,
        out,
        &runner,
        &SweepOptions::default(),
        &|o: &RunOutcome| {
            bar.set_message(o.spec.id());
            bar.inc(1)
        },
    )
    .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    let mut failed = 0;
    for o in &outcomes {
        if let RunStatus::Failed(message) = &o.status {
            eprintln!("failed: {}: {message}", o.spec.id());
            failed += 1;
        }
    }
    Ok(failed)
}

/// Applies the command line's push options to the protocol of `experiment`.
fn apply_push_options(
    protocols: &mut Protocols,
    experiment: ExperimentKind,
    pushes: Option<usize>,
    impulse_range: Option<(f64, f64)>,
    direction: Option<[f64; 3]>,
) -> Result<(), String> {
    if pushes == Some(0) {
        return Err("--pushes must be at least 1".into());
    }
    let options = PushOptions {
        pushes,
        impulse_range,
        direction,
    };
    experiment
        .experiment()
        .apply_push_options(protocols, &options)
}
