//! The `steplearn` command line over any [`Registry`]: reproduce the paper (all four
//! experiments over several seeds, with a per-claim report), benchmark approximators x rules x
//! experiments into a leaderboard, run one experiment, sweep the ablation grid (sharded for
//! clusters), merge the results. It only parses arguments and calls the library.
//!
//! A user's own binary gets the whole command line with their names:
//!
//! ```no_run
//! use steplearn::bench::Registry;
//! use steplearn::rules::BalanceOnly;
//! fn main() -> std::process::ExitCode {
//!     steplearn::cli::main_with(Registry::builtin().rule("my-balance", || BalanceOnly))
//! }
//! ```

use crate::bench::{Bench, BenchError, Registry};
use crate::config::limits::{MAX_PUSHES, MAX_SEEDS};
use crate::control::LearnSet;
use crate::experiments::PushOptions;
use crate::experiments::ablation::{self, merge};
use crate::experiments::config_file::ConfigFile;
use crate::experiments::index_page::{
    INDEX_FILE, command_line, write_index, write_index_with_replays,
};
use crate::experiments::omnidirectional;
use crate::experiments::protocol::ProtocolTables;
use crate::experiments::reproduce::{self, Claims};
use crate::experiments::settings::Settings;
use crate::experiments::summary::Summary;
use crate::experiments::sweep::{
    IDENTITY_FILE, RunOutcome, RunSpec, RunStatus, SUMMARY_FILE, Shard, SweepGrid, SweepOptions,
    check_identity, run_sweep,
};
use crate::report::write_file;
use crate::robot::Feet;
use crate::rules::PendulumCart;
use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
    /// The main job: all four experiments with one approximator and rule (default LWPR +
    /// pendulum-cart) over several seeds; writes one directory per run (CSV, SVG, summary.json)
    /// and DIR/claims.{md,json}, whether each of the paper's claims holds. Finished runs in DIR
    /// are reused.
    Reproduce(ReproduceArgs),
    /// Runs one experiment; writes CSV, SVG and DIR/summary.json.
    Experiment(ExperimentArgs),
    /// Benchmarks approximators x rules x experiments x seeds: one directory per run (finished
    /// runs reused, shardable), then DIR/leaderboard.{json,md,csv}, forest.svg and index.html
    /// with paired verdicts against the model and the baseline.
    Bench(BenchArgs),
    /// Lists the registered approximators, rules and experiments.
    List,
    /// Runs the ablation grid (every registered approximator x rule x seed on experiments C
    /// and D), skipping runs whose summary.json exists.
    Sweep(SweepArgs),
    /// Prints the complete default configuration (every section and key) as TOML, a
    /// starting point for `--config`; with --check, validates a config file instead.
    Config {
        /// Check FILE (TOML, or JSON if it ends in .json): prints `ok`, or what is wrong and
        /// exits with an error.
        #[arg(long, value_name = "FILE", conflicts_with = "table")]
        check: Option<PathBuf>,
        /// Print the reference table of every key (default, range, meaning) as Markdown, as
        /// docs/configuration.md holds it.
        #[arg(long)]
        table: bool,
    },
    /// Builds ablation.md and ablation.csv from a sweep's directory.
    Merge {
        /// The sweep's output directory.
        dir: PathBuf,
    },
    /// Describes a robot from a URDF file (what was found, the scale and the gait derived), or
    /// exports the built-in humanoid as URDF.
    #[command(subcommand)]
    Robot(RobotCommand),
    /// Re-simulates push K (disturbance, stability, robustness) or a span of time (tracking,
    /// disturbance, stability) of a finished run (from its run-config.toml) and writes one
    /// self-contained HTML page that draws it in 3D.
    Replay(ReplayArgs),
}

#[derive(Subcommand)]
enum RobotCommand {
    /// Prints what the loader found in PATH: name, mass, centre-of-mass height, C, the two
    /// legs' joints (hip yaw, roll, pitch, knee, ankle pitch, roll), the held joints, the leg
    /// geometry and the gait derived. A refused robot exits non-zero, naming the link or joint.
    Show {
        /// The URDF file.
        path: PathBuf,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        /// The links that end the robot's legs, LEFT,RIGHT, where the lowest leaf link on each
        /// side is not the foot (docs/robot.md).
        #[arg(long, value_name = "LEFT,RIGHT", value_parser = parse_feet)]
        feet: Option<Feet>,
    },
    /// Writes the built-in humanoid as URDF (loaded with --robot it runs bit for bit as the
    /// built-in one).
    Export {
        /// Where to write it.
        #[arg(long)]
        out: PathBuf,
    },
}

// The arguments of `steplearn reproduce` (no doc comment: the variant's is the command's help).
#[derive(Args)]
struct ReproduceArgs {
    /// The approximator (any registered name).
    #[arg(long, default_value = "lwpr")]
    approx: String,
    /// The learning rule (any registered name).
    #[arg(long, default_value = "pendulum-cart")]
    rule: String,
    /// Output directory [default: results/paper, or results/quick with --quick].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Seeds 0..N [default: 10, or 2 with --quick].
    #[arg(long)]
    seeds: Option<u64>,
    /// A fast look: every experiment at a tenth of its length.
    #[arg(long)]
    quick: bool,
    /// The step parameters the learner learns, comma-separated: step-x (the paper's dF),
    /// step-y (the lateral dW), step-time (dT), ankle-pitch (the support sole's pitch dA),
    /// ankle-roll (its roll dR) [default: the config's, step-x].
    #[arg(long)]
    learn: Option<LearnSet>,
    /// Settings and protocols as TOML or JSON (`[settings]`, `[protocols]`).
    #[arg(long)]
    config: Option<PathBuf>,
    /// A robot from a URDF file instead of the built-in humanoid; its gait, learner units and
    /// protocols follow it by dynamic similarity (docs/robot.md).
    #[arg(long, value_name = "PATH")]
    robot: Option<PathBuf>,
    /// The links that end the robot's legs, LEFT,RIGHT, where the lowest leaf link on each
    /// side is not the foot (docs/robot.md).
    #[arg(long, value_name = "LEFT,RIGHT", value_parser = parse_feet)]
    feet: Option<Feet>,
}

// The arguments of `steplearn experiment`.
#[derive(Args)]
struct ExperimentArgs {
    /// Which experiment (any registered name).
    experiment: String,
    /// The approximator (any registered name).
    #[arg(long, default_value = "lwpr")]
    approx: String,
    /// The learning rule (any registered name).
    #[arg(long, default_value = "pendulum-cart")]
    rule: String,
    /// Seed of every random choice.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Number of pushes (default: the protocol's; not for tracking).
    #[arg(long)]
    pushes: Option<usize>,
    /// Push impulse range in Ns, "A,B" (disturbance and robustness use one impulse: A,A).
    #[arg(long, value_parser = parse_range)]
    impulse_range: Option<(f64, f64)>,
    /// Direction of the pushes: forward, backward, left, right, or an azimuth in degrees
    /// (0 forward, 90 left, as the omnidirectional experiment's sectors) [default: the
    /// protocol's, forward unless a config file sets `direction`].
    #[arg(long, value_parser = parse_push_direction, allow_hyphen_values = true)]
    push_direction: Option<[f64; 3]>,
    /// The step parameters the learner learns, comma-separated: step-x (the paper's dF),
    /// step-y (the lateral dW), step-time (dT), ankle-pitch (the support sole's pitch dA),
    /// ankle-roll (its roll dR) [default: the config's, step-x].
    #[arg(long)]
    learn: Option<LearnSet>,
    /// Settings and protocols as TOML or JSON (`[settings]`, `[protocols]`).
    #[arg(long)]
    config: Option<PathBuf>,
    /// A robot from a URDF file instead of the built-in humanoid; its gait, learner units and
    /// protocols follow it by dynamic similarity (docs/robot.md).
    #[arg(long, value_name = "PATH")]
    robot: Option<PathBuf>,
    /// The links that end the robot's legs, LEFT,RIGHT, where the lowest leaf link on each
    /// side is not the foot (docs/robot.md).
    #[arg(long, value_name = "LEFT,RIGHT", value_parser = parse_feet)]
    feet: Option<Feet>,
    /// Output directory: new or empty, or holding this same run (then reused); anything
    /// else is refused unless --overwrite is given.
    #[arg(long)]
    out: PathBuf,
    /// Replace what DIR holds, once the new run has finished (a failed run leaves it as
    /// it was).
    #[arg(long)]
    overwrite: bool,
}

// The arguments of `steplearn bench`.
#[derive(Args)]
struct BenchArgs {
    /// Approximators, comma-separated [default: every registered one].
    #[arg(long, value_delimiter = ',')]
    approx: Vec<String>,
    /// Rules, comma-separated [default: every registered one].
    #[arg(long, value_delimiter = ',')]
    rule: Vec<String>,
    /// Experiments, comma-separated [default: every registered one].
    #[arg(long, value_delimiter = ',')]
    experiments: Vec<String>,
    /// A set of step parameters the learners learn, comma-separated: step-x (the paper's
    /// dF), step-y (the lateral dW), step-time (dT), ankle-pitch (the support sole's pitch
    /// dA), ankle-roll (its roll dR). Give it several times to bench several sets side by side (`--learn step-x
    /// --learn step-x,step-time`) [default: the config's, step-x].
    #[arg(long)]
    learn: Vec<LearnSet>,
    /// Number of seeds: FIRST..FIRST+N.
    #[arg(long, default_value_t = 5)]
    seeds: u64,
    /// The first seed (seeds other than 0-4 judge parameters chosen on 0-4).
    #[arg(long, default_value_t = 0)]
    first_seed: u64,
    /// Protocol length as a fraction of the paper's, in (0, 1] [default: the config's, 1].
    #[arg(long)]
    scale: Option<f64>,
    /// Settings and protocols as TOML or JSON (`[settings]`, `[protocols]`).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Robots from URDF files instead of the built-in humanoid (repeat, or separate by commas);
    /// each one's gait, learner units and protocols follow it by dynamic similarity
    /// (docs/robot.md). With several, each robot's runs get a directory of their own and the
    /// leaderboard one column per robot.
    #[arg(long, value_name = "PATH", value_delimiter = ',')]
    robot: Vec<PathBuf>,
    /// The links that end the robot's legs (one robot only), LEFT,RIGHT, where the lowest leaf link on each
    /// side is not the foot (docs/robot.md).
    #[arg(long, value_name = "LEFT,RIGHT", value_parser = parse_feet)]
    feet: Option<Feet>,
    /// The combination every other is compared with, APPROX+RULE [default:
    /// lwpr+pendulum-cart when selected].
    #[arg(long, value_parser = parse_baseline)]
    baseline: Option<(String, String)>,
    /// Run only shard I of N (0-based), e.g. 3/50.
    #[arg(long)]
    shard: Option<Shard>,
    /// Worker threads [default: one per core]; results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Output directory (one sub-directory per run).
    #[arg(long, default_value = "results/bench")]
    out: PathBuf,
}

// The arguments of `steplearn sweep`.
#[derive(Args)]
struct SweepArgs {
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
}

// The arguments of `steplearn replay`.
#[derive(Args)]
struct ReplayArgs {
    /// The run's directory (what `steplearn experiment --out` wrote).
    run_dir: PathBuf,
    /// The push to replay (1-based).
    #[arg(long, conflicts_with = "time", required_unless_present = "time")]
    push: Option<usize>,
    /// The span of trial time to replay, A..B seconds (e.g. 10..16).
    #[arg(long, value_parser = parse_span)]
    time: Option<(f64, f64)>,
    /// The page to write.
    #[arg(long)]
    out: PathBuf,
}

/// The unit push direction of `--push-direction`: a name (forward, backward, left, right) or
/// an azimuth in degrees within +-360 (0 forward, counter-clockwise), as
/// [`omnidirectional::direction`] gives the experiment's sectors.
fn parse_push_direction(s: &str) -> Result<[f64; 3], String> {
    let deg = match s.trim() {
        "forward" => 0.0,
        "left" => 90.0,
        "backward" => 180.0,
        "right" => 270.0,
        other => other
            .parse::<f64>()
            .ok()
            .filter(|d| d.is_finite() && d.abs() <= 360.0)
            .ok_or_else(|| {
                format!(
                    "expected forward, backward, left, right or an azimuth in degrees within \
                     +-360 (0 forward, 90 left), got {other:?}"
                )
            })?,
    };
    Ok(omnidirectional::direction(deg))
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

/// `A..B` seconds, checked as the replay checks it ([`crate::replay::check_span`]).
fn parse_span(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once("..")
        .ok_or_else(|| format!("expected A..B (seconds), got '{s}'"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<f64>()
            .map_err(|e| format!("'{v}' is not a number: {e}"))
    };
    let (a, b) = (parse(a)?, parse(b)?);
    crate::replay::check_span(a, b).map_err(|e| e.to_string())?;
    Ok((a, b))
}

fn parse_feet(s: &str) -> Result<Feet, String> {
    match s.split(',').map(str::trim).collect::<Vec<_>>()[..] {
        [left, right] if !left.is_empty() && !right.is_empty() => Ok(Feet {
            left: left.to_string(),
            right: right.to_string(),
        }),
        _ => Err(format!("expected LEFT,RIGHT (two link names), got '{s}'")),
    }
}

fn parse_baseline(s: &str) -> Result<(String, String), String> {
    let (a, r) = s
        .split_once('+')
        .ok_or_else(|| format!("expected APPROX+RULE, got '{s}'"))?;
    Ok((a.trim().to_string(), r.trim().to_string()))
}

/// The whole `steplearn` command line over `registry`: parses the process's arguments, runs
/// the command, prints errors, and returns the exit status. A registry with a duplicate or
/// malformed name is an error here, before any command runs.
pub fn main_with(registry: Registry) -> ExitCode {
    main_from(registry, std::env::args_os())
}

/// [`main_with`] on the given arguments (the first is the program name).
pub fn main_from<I, T>(registry: Registry, args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            // Help and version go to stdout with success; usage errors to stderr.
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    match registry
        .check()
        .map_err(|e| e.to_string())
        .and_then(|()| run(&registry, cli))
    {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

/// The config file at `path` (the defaults without one), checked against the registry's
/// experiments, with every experiment's whole protocol table.
fn load_config(registry: &Registry, config: Option<PathBuf>) -> Result<ConfigFile, String> {
    let config = match config {
        Some(path) => {
            ConfigFile::load_for(&path, registry.experiments()).map_err(|e| e.to_string())?
        }
        None => ConfigFile::default(),
    };
    registry.resolve_config(&config).map_err(|e| e.to_string())
}

/// With `--robot PATH`: the robot named in `config`'s settings and its protocols rewritten for
/// it.
fn use_robot_option(
    robot: Option<&Path>,
    feet: Option<&Feet>,
    config: &mut ConfigFile,
) -> Result<(), String> {
    match (robot, feet) {
        (Some(path), feet) => {
            crate::experiments::robot_setup::use_robot(
                path,
                feet,
                &mut config.settings,
                &mut config.protocols,
            )
            .map_err(|e| format!("robot {}: {e}", path.display()))?;
        }
        (None, Some(_)) => return Err("--feet names the feet of a --robot; none given".into()),
        (None, None) => {}
    }
    Ok(())
}

/// `steplearn robot show` and `steplearn robot export`.
fn robot_command(command: RobotCommand) -> Result<(), String> {
    match command {
        RobotCommand::Show { path, json, feet } => {
            let report = crate::experiments::robot_setup::robot_report(&path, feet.as_ref())
                .map_err(|e| format!("robot {}: {e}", path.display()))?;
            if json {
                println!(
                    "{}",
                    serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?
                );
            } else {
                print!("{}", report.to_text());
            }
            Ok(())
        }
        RobotCommand::Export { out } => {
            let text = crate::sim::BodyConfig::default().description().to_urdf();
            crate::atomic_file::write_atomic(&out, text.as_bytes())
                .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
            println!("wrote {}", out.display());
            Ok(())
        }
    }
}

/// Runs the parsed command: one function per subcommand.
fn run(registry: &Registry, cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Reproduce(args) => reproduce(registry, args),
        Command::Experiment(args) => experiment(registry, args),
        Command::Bench(args) => bench(registry, args),
        Command::List => {
            list(registry);
            Ok(())
        }
        Command::Sweep(args) => sweep(registry, args),
        Command::Config { check, table } => config(registry, check, table),
        Command::Replay(args) => replay(registry, args),
        Command::Robot(command) => robot_command(command),
        Command::Merge { dir } => merge_dir(&dir),
    }
}

/// Checks `--seeds` against [`MAX_SEEDS`].
fn check_seeds(seeds: u64) -> Result<(), String> {
    if seeds == 0 || seeds > MAX_SEEDS {
        return Err(format!("--seeds must be in [1, {MAX_SEEDS}], got {seeds}"));
    }
    Ok(())
}

/// [`load_config`] with `--learn`, if given, as the learned step parameters.
fn load_config_learning(
    registry: &Registry,
    config: Option<PathBuf>,
    learn: Option<LearnSet>,
) -> Result<ConfigFile, String> {
    let mut config = load_config(registry, config)?;
    if let Some(set) = learn {
        config.settings.learner.learn = set;
    }
    Ok(config)
}

/// `steplearn reproduce`: the paper's four experiments over seeds, the claims report and the
/// results page with a replay per experiment.
fn reproduce(registry: &Registry, args: ReproduceArgs) -> Result<(), String> {
    let ReproduceArgs {
        approx,
        rule,
        out,
        seeds,
        quick,
        learn,
        config,
        robot,
        feet,
    } = args;
    let mut config = load_config_learning(registry, config, learn)?;
    use_robot_option(robot.as_deref(), feet.as_ref(), &mut config)?;
    if quick {
        config.settings.scale = 0.1;
    }
    let seeds = seeds.unwrap_or(if quick { 2 } else { 10 });
    check_seeds(seeds)?;
    let out = out.unwrap_or_else(|| {
        PathBuf::from(if quick {
            "results/quick"
        } else {
            "results/paper"
        })
    });
    let grid = reproduce::grid(&approx, &rule, seeds);
    for e in &grid.experiments {
        registry.find_experiment(e).map_err(|e| e.to_string())?;
    }
    registry
        .check_combination(&approx, &rule)
        .map_err(|e| e.to_string())?;
    let runs = grid.runs().map_err(|e| e.to_string())?;
    let started = std::time::Instant::now();
    let failed = sweep_with_progress(registry, &runs, &out, &config.settings, &config.protocols)?;
    if failed > 0 {
        return Err(format!(
            "{failed} of {} runs failed (see above); the claims report was not written",
            runs.len()
        ));
    }
    let runner = registry.runner(&config.settings, &config.protocols);
    let (summaries, missing) =
        reproduce::read_summaries(&grid, &out, &runner).map_err(|e| e.to_string())?;
    let claims = Claims::from_summaries(&summaries, PendulumCart::default().p_theta);
    claims
        .write(&out, &approx, &rule)
        .map_err(|e| e.to_string())?;
    let config_toml = config.to_toml().map_err(|e| e.to_string())?;
    // One replay per experiment (its first seed's run), beside index.html.
    let mut first_runs: Vec<(String, PathBuf)> = Vec::new();
    for spec in &runs {
        if !first_runs.iter().any(|(e, _)| *e == spec.experiment) {
            first_runs.push((spec.experiment.clone(), out.join(spec.id())));
        }
    }
    let replays = crate::replay::moments::write_results_replays(registry, &out, &first_runs);
    write_index_with_replays(
        &out,
        &format!("steplearn reproduce: the paper's claims ({approx} + {rule})"),
        &["claims.md"],
        &command_line(),
        Some(&config_toml),
        &replays,
    )
    .map_err(|e| e.to_string())?;
    // One line per claim with both verdicts, then every paired quantity.
    for (line, c) in claims.lead_lines().iter().zip(claims.all()) {
        println!("{line}");
        for p in &c.over_seeds {
            println!("    over seeds: {}", p.describe(3));
        }
    }
    println!(
        "{} runs in {} ({:.0} s); open {} (or claims.md beside it)",
        runs.len(),
        out.display(),
        started.elapsed().as_secs_f64(),
        out.join(INDEX_FILE).display()
    );
    if !missing.is_empty() {
        return Err(format!("missing results: {}", missing.join(", ")));
    }
    Ok(())
}

/// Prints `summary` as JSON on stdout.
fn print_summary(summary: &Summary) -> Result<(), String> {
    println!("{}", summary.to_json().map_err(|e| e.to_string())?);
    Ok(())
}

/// `steplearn experiment`: one run into `--out`, reusing a finished run of the same identity
/// there, refusing anything else in it unless `--overwrite`.
fn experiment(registry: &Registry, args: ExperimentArgs) -> Result<(), String> {
    let ExperimentArgs {
        experiment,
        approx,
        rule,
        seed,
        pushes,
        impulse_range,
        push_direction,
        learn,
        config,
        robot,
        feet,
        out,
        overwrite,
    } = args;
    let mut config = load_config_learning(registry, config, learn)?;
    use_robot_option(robot.as_deref(), feet.as_ref(), &mut config)?;
    registry
        .check_combination(&approx, &rule)
        .map_err(|e| e.to_string())?;
    apply_push_options(
        registry,
        &mut config.protocols,
        &experiment,
        pushes,
        impulse_range,
        push_direction,
    )?;
    let spec = RunSpec {
        experiment: experiment.clone(),
        approx: approx.clone(),
        rule: rule.clone(),
        seed,
        learn: None,
    };
    let identity = registry
        .run_identity(&spec, &config.settings, &config.protocols)
        .map_err(|e| e.to_string())?;
    let summary_path = out.join(SUMMARY_FILE);
    let finished = summary_path
        .exists()
        .then(|| check_identity(&out, &identity));
    if !overwrite && finished == Some(Ok(())) {
        let summary = Summary::read(&summary_path).map_err(|e| e.to_string())?;
        eprintln!("{} holds this run, finished earlier: reused", out.display());
        return print_summary(&summary);
    }
    let holds = std::fs::read_dir(&out).is_ok_and(|mut d| d.next().is_some());
    if holds && !overwrite {
        let why = match finished {
            Some(Err(why)) => why,
            _ => format!("{} is not empty", out.display()),
        };
        return Err(format!(
            "{why}; nothing was changed. Choose another --out, or pass --overwrite to \
             replace its contents once the new run has finished"
        ));
    }
    let staging = Staging::new(&out)?;
    let summary = registry
        .run_spec(&spec, staging.path(), &config.settings, &config.protocols)
        .map_err(|e| e.to_string())?;
    write_file(&staging.path().join(IDENTITY_FILE), identity.as_bytes())
        .map_err(|e| e.to_string())?;
    summary
        .write(&staging.path().join(SUMMARY_FILE))
        .map_err(|e| e.to_string())?;
    let config_toml = config.to_toml().map_err(|e| e.to_string())?;
    write_index(
        staging.path(),
        &format!("steplearn experiment {experiment} ({approx}, {rule}, seed {seed})"),
        &["summary.json"],
        &command_line(),
        Some(&config_toml),
    )
    .map_err(|e| e.to_string())?;
    staging.replace(&out)?;
    print_summary(&summary)
}

/// The [`Bench`] the command line's bench arguments select.
fn bench_of<'r>(registry: &'r Registry, args: &BenchArgs) -> Result<Bench<'r>, String> {
    let mut config = load_config(registry, args.config.clone())?;
    // Named feet go with one robot, named in the configuration.
    let robots: &[PathBuf] = match (args.robot.as_slice(), &args.feet) {
        (_, None) => &args.robot,
        ([one], Some(feet)) => {
            use_robot_option(Some(one), Some(feet), &mut config)?;
            &[]
        }
        _ => return Err("--feet names the feet of one --robot".into()),
    };
    let mut bench = Bench::new(registry)
        .seeds(args.seeds)
        .first_seed(args.first_seed)
        .config(config)
        .out(&args.out)
        .command(&command_line());
    if !robots.is_empty() {
        bench = bench.robots(robots);
    }
    if !args.approx.is_empty() {
        bench = bench.approximators(&args.approx);
    }
    if !args.rule.is_empty() {
        bench = bench.rules(&args.rule);
    }
    if !args.experiments.is_empty() {
        bench = bench.experiments(&args.experiments);
    }
    if !args.learn.is_empty() {
        bench = bench.learn_sets(args.learn.iter().copied());
    }
    if let Some(s) = args.scale {
        bench = bench.scale(s);
    }
    if let Some((a, r)) = &args.baseline {
        bench = bench.baseline(a, r);
    }
    if let Some(s) = args.shard {
        bench = bench.shard(s);
    }
    if let Some(n) = args.threads {
        if n == 0 {
            return Err("--threads must be at least 1".into());
        }
        bench = bench.threads(n);
    }
    Ok(bench)
}

/// `steplearn bench`: the selection's runs, then the leaderboard, its page linking the replays
/// of its best and its worst row.
fn bench(registry: &Registry, args: BenchArgs) -> Result<(), String> {
    let bench = bench_of(registry, &args)?;
    let out = &args.out;
    let grid = bench.grid().map_err(|e| e.to_string())?;
    let runs = grid.runs().map_err(|e| e.to_string())?;
    let total = args.shard.map_or(runs.len(), |s| s.select(&runs).len()) * args.robot.len().max(1);
    let bar = progress_bar(total)?;
    let started = std::time::Instant::now();
    let result = bench
        .on_run(|o: &RunOutcome| {
            progress(&bar, o);
        })
        .replays(|leaderboard, dir| {
            crate::replay::moments::write_bench_replays(registry, dir, leaderboard)
        })
        .run();
    bar.finish_and_clear();
    let report = match result {
        Ok(r) => r,
        Err(BenchError::RunsFailed(failed)) => {
            for (id, m) in &failed {
                eprintln!("failed: {id}: {m}");
            }
            return Err(format!(
                "{} runs failed; the leaderboard in {} covers the others",
                failed.len(),
                out.display()
            ));
        }
        Err(e) => return Err(e.to_string()),
    };
    match &report.robots {
        Some(robots) => print!("{}", robots.to_markdown()),
        None => print!("{}", report.leaderboard.to_markdown()),
    }
    println!(
        "{} runs ({} finished earlier) in {:.0} s; leaderboard: {}",
        report.outcomes.len(),
        report
            .outcomes
            .iter()
            .filter(|o| o.status == RunStatus::Skipped)
            .count(),
        started.elapsed().as_secs_f64(),
        out.join("index.html").display()
    );
    Ok(())
}

/// `steplearn list`: the registered names.
fn list(registry: &Registry) {
    println!(
        "approximators: {}",
        registry.approximator_names().join(", ")
    );
    println!("rules: {}", registry.rule_names().join(", "));
    println!("experiments: {}", registry.experiment_names().join(", "));
}

/// `steplearn sweep`: the ablation grid on experiments C and D.
fn sweep(registry: &Registry, args: SweepArgs) -> Result<(), String> {
    let SweepArgs {
        shard,
        seeds,
        pushes,
        out,
    } = args;
    check_seeds(seeds)?;
    let grid = SweepGrid::new(
        &ablation::EXPERIMENTS,
        &registry.approximator_names(),
        &registry.rule_names(),
        seeds,
    );
    let runs = grid.runs().map_err(|e| e.to_string())?;
    let runs = match shard {
        Some(s) => s.select(&runs),
        None => runs,
    };
    let mut config = ConfigFile::default();
    apply_push_options(
        registry,
        &mut config.protocols,
        ablation::PUSHED,
        pushes,
        None,
        None,
    )
    .map_err(|e| format!("--pushes: {e}"))?;
    let config = registry
        .resolve_config(&config)
        .map_err(|e| format!("--pushes: {e}"))?;
    let failed = sweep_with_progress(registry, &runs, &out, &config.settings, &config.protocols)?;
    println!("{} runs in {}", runs.len(), out.display());
    if failed > 0 {
        return Err(format!("{failed} runs failed"));
    }
    Ok(())
}

/// `steplearn config`: the default configuration, or `ok` for a valid `--check FILE`.
fn config(registry: &Registry, check: Option<PathBuf>, table: bool) -> Result<(), String> {
    if table {
        print!("{}", crate::experiments::config_keys::key_table());
        return Ok(());
    }
    match check {
        None => print!(
            "{}",
            crate::experiments::config_keys::with_absent_keys(
                &ConfigFile::default_toml_for(registry.experiments()).map_err(|e| e.to_string())?
            )
        ),
        Some(path) => {
            ConfigFile::load_for(&path, registry.experiments()).map_err(|e| e.to_string())?;
            println!("ok");
        }
    }
    Ok(())
}

/// `steplearn replay`: one page of a push or a span of a finished run.
fn replay(registry: &Registry, args: ReplayArgs) -> Result<(), String> {
    let ReplayArgs {
        run_dir,
        push,
        time,
        out,
    } = args;
    let moment = match (push, time) {
        (Some(push), _) => crate::experiments::replay_plan::Moment::Push(push),
        (None, Some((from, to))) => crate::experiments::replay_plan::Moment::Span(from, to),
        (None, None) => return Err("give --push K or --time A..B".into()),
    };
    let replay = crate::replay::moment_to_file(registry, &run_dir, moment, &out)
        .map_err(|e| e.to_string())?;
    println!("{}", crate::replay::summary_line(&replay, &out));
    Ok(())
}

/// `steplearn merge`: the ablation table of a sweep's directory.
fn merge_dir(dir: &Path) -> Result<(), String> {
    let merged = merge(dir).map_err(|e| e.to_string())?;
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
    merged.write(dir).map_err(|e| e.to_string())?;
    write_index(
        dir,
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

/// A progress bar of `len` runs on stderr (hidden when stderr is not a terminal).
fn progress_bar(len: usize) -> Result<indicatif::ProgressBar, String> {
    let bar = indicatif::ProgressBar::new(len as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{elapsed_precise} [{bar:30}] {pos}/{len} ({eta_precise} left) {msg}",
        )
        .map_err(|e| e.to_string())?,
    );
    Ok(bar)
}

/// Advances `bar` by one finished run; off a terminal (CI, nohup, Slurm), prints one line per
/// run instead: its count, status, the time elapsed and an estimate of the time left. A run
/// finished earlier is taken off the bar's length, so that the count and the estimate cover
/// only the runs this command computes.
fn progress(bar: &indicatif::ProgressBar, o: &RunOutcome) {
    bar.set_message(o.spec.id());
    let status = match &o.status {
        RunStatus::Done { wall_time_s } => format!("done in {wall_time_s:.1} s"),
        RunStatus::Skipped => {
            bar.dec_length(1);
            if bar.is_hidden() {
                eprintln!("{}: finished earlier", o.spec.id());
            }
            return;
        }
        RunStatus::Failed(_) => "failed".to_string(),
    };
    bar.inc(1);
    if bar.is_hidden() {
        let (k, n) = (bar.position(), bar.length().unwrap_or(0));
        let elapsed = bar.elapsed().as_secs_f64();
        // The mean time per computed run so far, for the runs still to come.
        let left = if k < n && k > 0 {
            format!(
                ", about {} left",
                clock(elapsed / k as f64 * (n - k) as f64)
            )
        } else {
            String::new()
        };
        eprintln!(
            "[{k}/{n}] {}: {status} ({} elapsed{left})",
            o.spec.id(),
            clock(elapsed)
        );
    }
}

/// `seconds` as `1h02m03s`, `2m03s` or `3s`.
fn clock(seconds: f64) -> String {
    let s = seconds.max(0.0).round() as u64;
    match (s / 3600, s / 60 % 60, s % 60) {
        (0, 0, sec) => format!("{sec}s"),
        (0, m, sec) => format!("{m}m{sec:02}s"),
        (h, m, sec) => format!("{h}h{m:02}m{sec:02}s"),
    }
}

/// Runs `runs` into `out` with a progress bar; prints each failure and returns how many
/// failed.
fn sweep_with_progress(
    registry: &Registry,
    runs: &[RunSpec],
    out: &Path,
    settings: &Settings,
    protocols: &ProtocolTables,
) -> Result<usize, String> {
    let bar = progress_bar(runs.len())?;
    let runner = registry.runner(settings, protocols);
    let outcomes = run_sweep(
        runs,
        out,
        &runner,
        &SweepOptions::default(),
        &|o: &RunOutcome| progress(&bar, o),
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

/// Checks `--pushes` against [`MAX_PUSHES`].
fn check_pushes(pushes: Option<usize>) -> Result<(), String> {
    match pushes {
        Some(n) if n == 0 || n > MAX_PUSHES => {
            Err(format!("--pushes must be in [1, {MAX_PUSHES}], got {n}"))
        }
        _ => Ok(()),
    }
}

/// Applies the command line's push options to the protocol of `experiment`.
fn apply_push_options(
    registry: &Registry,
    protocols: &mut ProtocolTables,
    experiment: &str,
    pushes: Option<usize>,
    impulse_range: Option<(f64, f64)>,
    direction: Option<[f64; 3]>,
) -> Result<(), String> {
    check_pushes(pushes)?;
    let options = PushOptions {
        pushes,
        impulse_range,
        direction,
    };
    registry
        .find_experiment(experiment)
        .map_err(|e| e.to_string())?
        .apply_push_options(protocols, &options)
        .map_err(|e| e.to_string())
}

/// A fresh directory beside an output directory, where a run writes until it has finished;
/// removed on drop unless it replaced the output ([`Staging::replace`]).
struct Staging(tempfile::TempDir);

impl Staging {
    fn new(out: &Path) -> Result<Self, String> {
        let parent = match out.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent)
            .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
        let name = out
            .file_name()
            .map_or("run".into(), |n| n.to_string_lossy().into_owned());
        tempfile::Builder::new()
            .prefix(&format!(".{name}.partial-"))
            .tempdir_in(&parent)
            .map(Staging)
            .map_err(|e| format!("cannot create a directory in {}: {e}", parent.display()))
    }

    fn path(&self) -> &Path {
        self.0.path()
    }

    /// Puts the finished run at `out`, replacing what was there.
    fn replace(self, out: &Path) -> Result<(), String> {
        let old = self.path().with_extension("old");
        let had = out.exists();
        if had {
            std::fs::rename(out, &old)
                .map_err(|e| format!("cannot move {} aside: {e}", out.display()))?;
        }
        if let Err(e) = std::fs::rename(self.path(), out) {
            if had {
                let _ = std::fs::rename(&old, out);
            }
            return Err(format!("cannot move the run to {}: {e}", out.display()));
        }
        // Moved into place: nothing left for the guard to remove.
        let _ = self.0.keep();
        if had {
            let _ = std::fs::remove_dir_all(&old);
        }
        Ok(())
    }
}
