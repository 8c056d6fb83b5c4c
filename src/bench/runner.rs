//! [`Bench`]: a selection of registered names, run and reported.

use super::leaderboard::Leaderboard;
use super::robots::{RobotLeaderboard, check_distinct, robot_column, robot_config};
use super::{BenchError, Registry};
use crate::config::limits::MAX_SEEDS;
use crate::control::LearnSet;
use crate::experiments::config_file::ConfigFile;
use crate::experiments::index_page::ReplayLink;
use crate::experiments::sweep::{
    RunOutcome, RunStatus, Shard, SweepGrid, SweepOptions, check_distinct_sets, run_sweep,
};
use crate::report::write_file;
use crate::robot::Feet;
use std::path::{Path, PathBuf};

/// The file in a bench's output directory that records the configuration its runs used.
pub const CONFIG_RECORD: &str = "bench-config.toml";

/// The default baseline combination of the leaderboard: the paper's learner.
pub const DEFAULT_BASELINE: (&str, &str) = ("lwpr", "pendulum-cart");

/// A benchmark: approximators x rules x sets of learned parameters x experiments x seeds from
/// a [`Registry`], run into one
/// directory (one sub-directory per run, finished runs reused) and reported as a
/// [`Leaderboard`] (`leaderboard.json`, `.md`, `.csv`, `forest.svg`, `index.html`).
///
/// Unset selections take every registered name; seeds default to 5, the scale to the
/// configuration's (1 = the paper's protocols), the output to `results/bench`.
pub struct Bench<'r> {
    registry: &'r Registry,
    approximators: Option<Vec<String>>,
    rules: Option<Vec<String>>,
    experiments: Option<Vec<String>>,
    learn_sets: Option<Vec<LearnSet>>,
    seeds: u64,
    first_seed: u64,
    scale: Option<f64>,
    out: PathBuf,
    config: ConfigFile,
    shard: Shard,
    threads: Option<usize>,
    baseline: Option<(String, String)>,
    command: String,
    on_run: Option<Box<OnRun<'r>>>,
    replays: Option<Box<Replays<'r>>>,
    /// Each robot's file and, where named, the links that end its legs.
    robots: Vec<(PathBuf, Option<Feet>)>,
}

/// A callback called as each run ends.
type OnRun<'r> = dyn Fn(&RunOutcome) + Sync + 'r;

/// A callback that writes replay pages beside the leaderboard's `index.html` and returns the
/// links to them.
type Replays<'r> = dyn Fn(&Leaderboard, &Path) -> Vec<ReplayLink> + 'r;

/// What a bench did: every run's outcome and the leaderboard over the runs finished in its
/// directory.
#[derive(Debug, Clone)]
pub struct Report {
    /// The runs of this call (its shard), in grid order.
    pub outcomes: Vec<RunOutcome>,
    /// The leaderboard of the whole selection (runs of other shards included once finished);
    /// over several robots, every robot's rows, each naming its robot.
    pub leaderboard: Leaderboard,
    /// The output directory.
    pub out: PathBuf,
    /// Over several robots ([`Bench::robots`]): the robots, and the leaderboard with one
    /// column per robot.
    pub robots: Option<RobotLeaderboard>,
}

/// Checks that each of `names` is among the registered `known` names of a `what` and appears
/// once.
fn check_selection(what: &str, names: &[String], known: &[&str]) -> Result<(), BenchError> {
    if names.is_empty() {
        return Err(BenchError::Selection(format!("no {what} selected")));
    }
    for (i, n) in names.iter().enumerate() {
        if !known.contains(&n.as_str()) {
            return Err(BenchError::unknown(what, n, known));
        }
        if names[..i].contains(n) {
            return Err(BenchError::Selection(format!(
                "{what} {n:?} selected twice"
            )));
        }
    }
    Ok(())
}

fn owned<I: IntoIterator<Item = S>, S: AsRef<str>>(names: I) -> Vec<String> {
    names.into_iter().map(|s| s.as_ref().to_string()).collect()
}

impl<'r> Bench<'r> {
    /// A bench over `registry` with the defaults.
    pub fn new(registry: &'r Registry) -> Self {
        Bench {
            registry,
            approximators: None,
            rules: None,
            experiments: None,
            learn_sets: None,
            seeds: 5,
            first_seed: 0,
            scale: None,
            out: PathBuf::from("results/bench"),
            config: ConfigFile::default(),
            shard: Shard::ALL,
            threads: None,
            baseline: None,
            command: String::new(),
            on_run: None,
            replays: None,
            robots: Vec::new(),
        }
    }

    /// The robots to run on, from URDF files ([`crate::experiments::robot_setup::use_robot`]:
    /// the gait and the protocols follow each robot's size). One robot runs in the output
    /// directory, as `--robot PATH` does; with several, each robot's runs go into a
    /// directory of its own, named by its file ([`RobotColumn::id`](super::RobotColumn::id)), and the output
    /// directory gets the leaderboard with one column per robot ([`RobotLeaderboard`]).
    /// Default: none, the configuration's robot.
    pub fn robots<I: IntoIterator<Item = P>, P: AsRef<Path>>(mut self, paths: I) -> Self {
        self.robots = paths
            .into_iter()
            .map(|p| (p.as_ref().to_path_buf(), None))
            .collect();
        self
    }

    /// Adds the robot at `path` to the robots ([`Bench::robots`]), its legs ending at the
    /// links `feet` names where given (as `--feet LEFT,RIGHT`: for a robot whose lowest link
    /// on a side is not its foot).
    pub fn robot(mut self, path: impl AsRef<Path>, feet: Option<Feet>) -> Self {
        self.robots.push((path.as_ref().to_path_buf(), feet));
        self
    }

    /// The approximators to run, by registered name.
    pub fn approximators<I: IntoIterator<Item = S>, S: AsRef<str>>(mut self, names: I) -> Self {
        self.approximators = Some(owned(names));
        self
    }

    /// The rules to run, by registered name.
    pub fn rules<I: IntoIterator<Item = S>, S: AsRef<str>>(mut self, names: I) -> Self {
        self.rules = Some(owned(names));
        self
    }

    /// The experiments to run, by registered name.
    pub fn experiments<I: IntoIterator<Item = S>, S: AsRef<str>>(mut self, names: I) -> Self {
        self.experiments = Some(owned(names));
        self
    }

    /// The sets of learned step parameters to run, each a dimension of the grid like the
    /// approximators (default: the configuration's `settings.learner.learn`, the paper's
    /// `step-x` unless changed). Runs of the paper's set keep their plain directory ids; any
    /// other set's add a suffix ([`RunSpec::id`](crate::experiments::sweep::RunSpec::id)), and
    /// every leaderboard row names its set.
    pub fn learn_sets<I: IntoIterator<Item = LearnSet>>(mut self, sets: I) -> Self {
        self.learn_sets = Some(sets.into_iter().collect());
        self
    }

    /// `n` seeds (at least 1): `0..n`, or from [`Bench::first_seed`] on.
    pub fn seeds(mut self, n: u64) -> Self {
        self.seeds = n;
        self
    }

    /// The first seed (default 0): the seeds are `first..first + n`, so that a combination
    /// can be judged on seeds other than those its parameters were chosen on.
    pub fn first_seed(mut self, first: u64) -> Self {
        self.first_seed = first;
        self
    }

    /// The protocols' length as a fraction of the paper's, in (0, 1] (`--quick` is 0.1).
    pub fn scale(mut self, scale: f64) -> Self {
        self.scale = Some(scale);
        self
    }

    /// The output directory.
    pub fn out(mut self, dir: impl AsRef<Path>) -> Self {
        self.out = dir.as_ref().to_path_buf();
        self
    }

    /// Settings and protocols (`steplearn config` format); the scale set by
    /// [`Bench::scale`] takes precedence over the file's.
    pub fn config(mut self, config: ConfigFile) -> Self {
        self.config = config;
        self
    }

    /// Runs only shard `shard` of the grid (the leaderboard covers every finished run).
    pub fn shard(mut self, shard: Shard) -> Self {
        self.shard = shard;
        self
    }

    /// Worker threads (default: rayon's global pool). Results do not depend on it.
    pub fn threads(mut self, n: usize) -> Self {
        self.threads = Some(n);
        self
    }

    /// The combination every other is compared with (default `lwpr` + `pendulum-cart` when
    /// both are selected, else the first approximator and rule selected).
    pub fn baseline(mut self, approx: &str, rule: &str) -> Self {
        self.baseline = Some((approx.to_string(), rule.to_string()));
        self
    }

    /// The command line shown on `index.html`.
    pub fn command(mut self, command: &str) -> Self {
        self.command = command.to_string();
        self
    }

    /// Called as each run ends (from worker threads), e.g. to advance a progress bar.
    pub fn on_run(mut self, f: impl Fn(&RunOutcome) + Sync + 'r) -> Self {
        self.on_run = Some(Box::new(f));
        self
    }

    /// Calls `f` with the leaderboard and the output directory before `index.html` is
    /// written; `f` writes pages beside it (replays: the command line writes those of the best
    /// and the worst row) and returns the links the page shows. This crate's `bench` layer
    /// does not make replays itself (`crate::replay` depends on it).
    pub fn replays(mut self, f: impl Fn(&Leaderboard, &Path) -> Vec<ReplayLink> + 'r) -> Self {
        self.replays = Some(Box::new(f));
        self
    }

    /// The selection with defaults filled in and checked: (approximators, rules, experiments).
    fn selection(&self) -> Result<[Vec<String>; 3], BenchError> {
        let r = self.registry;
        r.check()?;
        let pick = |given: &Option<Vec<String>>, all: Vec<&str>| {
            given.clone().unwrap_or_else(|| owned(all))
        };
        let approx = pick(&self.approximators, r.approximator_names());
        let rules = pick(&self.rules, r.rule_names());
        let experiments = pick(&self.experiments, r.experiment_names());
        check_selection("approximator", &approx, &r.approximator_names())?;
        check_selection("rule", &rules, &r.rule_names())?;
        check_selection("experiment", &experiments, &r.experiment_names())?;
        Ok([approx, rules, experiments])
    }

    /// The grid of runs this bench covers (every shard).
    pub fn grid(&self) -> Result<SweepGrid, BenchError> {
        let [approx, rules, experiments] = self.selection()?;
        if self.seeds == 0 || self.seeds > MAX_SEEDS {
            return Err(BenchError::Selection(format!(
                "seeds must be in [1, {MAX_SEEDS}], got {}",
                self.seeds
            )));
        }
        let end = self.first_seed.checked_add(self.seeds).ok_or_else(|| {
            BenchError::Selection(format!(
                "first seed {} + {} seeds overflows",
                self.first_seed, self.seeds
            ))
        })?;
        let learn = self
            .learn_sets
            .clone()
            .unwrap_or_else(|| vec![self.config.settings.learner.learn]);
        if learn.is_empty() {
            return Err(BenchError::Selection(
                "no set of learned step parameters selected".into(),
            ));
        }
        check_distinct_sets(&learn).map_err(BenchError::Selection)?;
        Ok(SweepGrid {
            experiments,
            approx,
            rules,
            seeds: (self.first_seed..end).collect(),
            learn,
        })
    }

    /// The configuration of the runs: the scale set here, and the set of learned parameters
    /// left at the paper's, since each run learns its own set ([`Bench::learn_sets`]), so
    /// that the record of a directory does not depend on the sets selected.
    fn resolved_config(&self, config: &ConfigFile) -> Result<ConfigFile, BenchError> {
        let mut config = config.clone();
        if let Some(scale) = self.scale {
            config.settings.scale = scale;
        }
        config.settings.learner.learn = LearnSet::default();
        self.registry.resolve_config(&config)
    }

    /// Refuses, before any run, a selected approximator whose factory cannot build.
    fn check_builds(&self, grid: &SweepGrid) -> Result<(), BenchError> {
        for approx in &grid.approx {
            for rule in &grid.rules {
                self.registry.check_combination(approx, rule)?;
            }
        }
        Ok(())
    }

    fn baseline_of(&self, grid: &SweepGrid) -> Result<(String, String), BenchError> {
        let default = (
            DEFAULT_BASELINE.0.to_string(),
            DEFAULT_BASELINE.1.to_string(),
        );
        let chosen = self.baseline.clone().unwrap_or_else(|| {
            if grid.approx.contains(&default.0) && grid.rules.contains(&default.1) {
                default
            } else {
                (grid.approx[0].clone(), grid.rules[0].clone())
            }
        });
        if !grid.approx.contains(&chosen.0) || !grid.rules.contains(&chosen.1) {
            return Err(BenchError::Selection(format!(
                "baseline {} + {} is not among the selected approximators and rules",
                chosen.0, chosen.1
            )));
        }
        Ok(chosen)
    }

    /// Refuses a directory whose runs used another configuration; records this one otherwise.
    /// Another configuration means other settings, or another protocol table for an
    /// experiment both records hold: an experiment registered since (or not any more) changes
    /// nothing its runs measured, so its table joins the record.
    fn guard_config(
        &self,
        out: &Path,
        config_toml: &str,
        selected: &[String],
    ) -> Result<(), BenchError> {
        let path = out.join(CONFIG_RECORD);
        match std::fs::read_to_string(&path) {
            Ok(existing) if existing == config_toml => Ok(()),
            Ok(existing) => match merged_record(&existing, config_toml, selected) {
                Some(merged) => {
                    if merged != existing {
                        write_file(&path, merged.as_bytes())?;
                    }
                    Ok(())
                }
                None => Err(BenchError::ConfigChanged(format!(
                    "{} holds runs of another configuration ({} differs from this run's \
                     settings and protocols); choose another --out, or delete the directory to \
                     start over",
                    out.display(),
                    path.display()
                ))),
            },
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                std::fs::create_dir_all(out).map_err(|e| crate::report::ReportError::io(out, e))?;
                write_file(&path, config_toml.as_bytes())?;
                Ok(())
            }
            Err(e) => Err(crate::report::ReportError::io(&path, e).into()),
        }
    }

    /// Runs the selection (this shard of it), then writes the leaderboard of every finished
    /// run of the selection into the output directory. Errors before any run on a bad
    /// selection or configuration, or an approximator that cannot be built
    /// ([`BenchError::CannotBuild`]: nothing is written); [`BenchError::RunsFailed`] after
    /// writing the leaderboard if some runs failed.
    pub fn run(&self) -> Result<Report, BenchError> {
        match self.robots.as_slice() {
            [] => self.run_in(&self.config, &self.out)?.finished(),
            [(one, feet)] => {
                let base = self.registry.resolve_config(&self.config)?;
                let (config, _) = robot_config(one, feet.as_ref(), &base)?;
                self.run_in(&config, &self.out)?.finished()
            }
            many => self.run_robots(many),
        }
    }

    /// Every robot's bench in its own directory, then the leaderboard over them. Every robot
    /// is loaded and checked before any run.
    fn run_robots(&self, robots: &[(PathBuf, Option<Feet>)]) -> Result<Report, BenchError> {
        // Every protocol table in full before the robot rewrites them for its size.
        let base = self.registry.resolve_config(&self.config)?;
        let mut configs = Vec::new();
        let mut columns = Vec::new();
        for (path, feet) in robots {
            let (config, run) = robot_config(path, feet.as_ref(), &base)?;
            columns.push(robot_column(path, &run, &config)?);
            configs.push(config);
        }
        check_distinct(&columns)?;
        let (mut outcomes, mut boards, mut failed) = (Vec::new(), Vec::new(), Vec::new());
        for (column, config) in columns.iter().zip(&configs) {
            let ran = self.run_in(config, &self.out.join(&column.id))?;
            outcomes.extend(ran.report.outcomes);
            boards.push(ran.report.leaderboard);
            failed.extend(
                ran.failed
                    .into_iter()
                    .map(|(id, m)| (format!("{}/{id}", column.id), m)),
            );
        }
        let robots = RobotLeaderboard::join(columns, boards);
        robots.write(&self.out, &self.command)?;
        if !failed.is_empty() {
            return Err(BenchError::RunsFailed(failed));
        }
        Ok(Report {
            outcomes,
            leaderboard: robots.leaderboard.clone(),
            out: self.out.clone(),
            robots: Some(robots),
        })
    }

    /// The selection run with `config` into `out`, and its leaderboard written there; the
    /// runs that failed beside the report.
    fn run_in(&self, config: &ConfigFile, out: &Path) -> Result<Ran, BenchError> {
        let grid = self.grid()?;
        let baseline = self.baseline_of(&grid)?;
        self.check_builds(&grid)?;
        let config = self.resolved_config(config)?;
        let config_toml = config
            .to_toml()
            .map_err(|e| BenchError::Selection(e.to_string()))?;
        let runs = self.shard.select(&grid.runs()?);
        self.guard_config(out, &config_toml, &grid.experiments)?;
        let runner = self.registry.runner(&config.settings, &config.protocols);
        let options = SweepOptions {
            threads: self.threads,
        };
        let noop = |_: &RunOutcome| {};
        let on_run: &(dyn Fn(&RunOutcome) + Sync) = match &self.on_run {
            Some(f) => f.as_ref(),
            None => &noop,
        };
        let outcomes = run_sweep(&runs, out, &runner, &options, on_run)?;
        let leaderboard = Leaderboard::collect(
            self.registry,
            &grid,
            out,
            &baseline,
            config.settings.scale,
            &runner,
        )?;
        let replays = self
            .replays
            .as_ref()
            .map_or_else(Vec::new, |f| f(&leaderboard, out));
        leaderboard.write_with_replays(out, &self.command, &config_toml, &replays)?;
        let failed: Vec<(String, String)> = outcomes
            .iter()
            .filter_map(|o| match &o.status {
                RunStatus::Failed(m) => Some((o.spec.id(), m.clone())),
                _ => None,
            })
            .collect();
        Ok(Ran {
            report: Report {
                outcomes,
                leaderboard,
                out: out.to_path_buf(),
                robots: None,
            },
            failed,
        })
    }
}

/// A bench directory's runs done: the report, and the runs that failed (id, message).
struct Ran {
    report: Report,
    failed: Vec<(String, String)>,
}

impl Ran {
    /// The report, or [`BenchError::RunsFailed`] if some runs failed.
    fn finished(self) -> Result<Report, BenchError> {
        if self.failed.is_empty() {
            Ok(self.report)
        } else {
            Err(BenchError::RunsFailed(self.failed))
        }
    }
}

/// The union of two configuration records (`existing` first, then what `new` adds), if they
/// agree: the same settings (every key but `protocols`) and the same table for every protocol
/// both hold of the experiments `selected` (an experiment outside the selection keeps the
/// existing record's table, which describes its runs there). `None` if they differ or either
/// does not parse.
fn merged_record(existing: &str, new: &str, selected: &[String]) -> Option<String> {
    let old: toml::Table = toml::from_str(existing).ok()?;
    let new: toml::Table = toml::from_str(new).ok()?;
    let without = |t: &toml::Table| {
        let mut t = t.clone();
        t.remove("protocols");
        t
    };
    if without(&old) != without(&new) {
        return None;
    }
    let tables = |t: &toml::Table| match t.get("protocols") {
        Some(toml::Value::Table(p)) => Some(p.clone()),
        None => Some(toml::Table::new()),
        Some(_) => None,
    };
    let (mut merged, added) = (tables(&old)?, tables(&new)?);
    for (name, table) in added {
        match merged.get(&name) {
            Some(t) if *t != table && selected.contains(&name) => return None,
            Some(_) => {}
            None => {
                merged.insert(name, table);
            }
        }
    }
    let mut record = old;
    if !merged.is_empty() {
        record.insert("protocols".into(), toml::Value::Table(merged));
    }
    toml::to_string_pretty(&record).ok()
}

#[cfg(test)]
mod tests {
    use super::merged_record;

    const OLD: &str = "[settings]\nscale = 1.0\n\n[protocols.a]\npushes = 3\n";

    #[test]
    fn a_record_takes_new_experiments_but_no_other_configuration() {
        // The same configuration, and one with another experiment's table beside it.
        let a = ["a".to_string(), "b".to_string()];
        assert!(merged_record(OLD, OLD, &a).is_some());
        let more = "[settings]\nscale = 1.0\n\n[protocols.a]\npushes = 3\n\n[protocols.b]\nn = 1\n";
        let merged: toml::Table = toml::from_str(&merged_record(OLD, more, &a).unwrap()).unwrap();
        assert_eq!(merged["protocols"]["a"]["pushes"].as_integer(), Some(3));
        assert_eq!(merged["protocols"]["b"]["n"].as_integer(), Some(1));
        // An experiment no longer registered keeps its table in the record.
        let fewer = "[settings]\nscale = 1.0\n";
        let kept: toml::Table = toml::from_str(&merged_record(OLD, fewer, &a).unwrap()).unwrap();
        assert_eq!(kept["protocols"]["a"]["pushes"].as_integer(), Some(3));
        // Other settings, another table for a shared experiment, or a damaged record: refused.
        assert!(
            merged_record(
                OLD,
                "[settings]\nscale = 0.5\n\n[protocols.a]\npushes = 3\n",
                &a
            )
            .is_none()
        );
        assert!(
            merged_record(
                OLD,
                "[settings]\nscale = 1.0\n\n[protocols.a]\npushes = 4\n",
                &a
            )
            .is_none()
        );
        // Another table for an experiment outside the selection: the record keeps its own.
        let other: toml::Table = toml::from_str(
            &merged_record(
                OLD,
                "[settings]\nscale = 1.0\n\n[protocols.a]\npushes = 4\n",
                &["b".to_string()],
            )
            .unwrap(),
        )
        .unwrap();
        assert_eq!(other["protocols"]["a"]["pushes"].as_integer(), Some(3));
        assert!(merged_record("[settings\n", OLD, &a).is_none());
        assert!(merged_record(OLD, "[settings]\nscale = 1.0\nextra = 1\n", &a).is_none());
    }
}
