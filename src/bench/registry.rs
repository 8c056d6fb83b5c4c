//! [`Registry`]: approximators, learning rules and experiments by name, built-ins first, a
//! user's own added with one call each.

use super::BenchError;
use crate::Named;
use crate::approx::{
    ApproxError, ApproxKind, BoxedApproximator, FunctionApproximator, InputBox, Persist,
};
use crate::config::ConfigError;
use crate::control::{LearnerConfig, LearnerError};
use crate::experiments::ExperimentError;
use crate::experiments::config_file::ConfigFile;
use crate::experiments::protocol::{ProtocolTables, Table};
use crate::experiments::settings::{LwprSettings, Settings};
use crate::experiments::suite;
use crate::experiments::summary::{Summary, check_name};
use crate::experiments::sweep::{RunError, RunSpec, Runner};
use crate::experiments::{
    Experiment, RunComponents, RunContext, RunLearner, learner_bounds, step_x_learner,
};
use crate::report::ReportError;
use crate::rules::{
    BalanceOnly, LearningRule, Linear, PendulumCart, PolicyGradient, RateDamped, TrackingOnly,
};
use std::path::Path;
use std::sync::Arc;

/// Builds a fresh approximator over a box; the built-in `lwpr` takes the run's
/// `[settings.lwpr]`, the others ignore them.
type ApproxFactory =
    Arc<dyn Fn(&InputBox, &LwprSettings) -> Result<BoxedApproximator, ApproxError> + Send + Sync>;
type RuleFactory = Arc<dyn Fn() -> Box<dyn LearningRule> + Send + Sync>;

/// Approximators, rules and experiments by name: what the bench and the command line choose
/// from.
///
/// Registering a name twice, or a name that is not lowercase letters, digits and `-`, is
/// recorded and reported as a [`BenchError`] when the registry is used ([`Registry::check`]),
/// never a panic.
///
/// ```
/// use steplearn::approx::{Grid, GridConfig, InputBox};
/// use steplearn::bench::Registry;
/// use steplearn::rules::BalanceOnly;
///
/// let registry = Registry::builtin()
///     .approximator("coarse-grid", |bounds: &InputBox| {
///         Grid::new(GridConfig::new(bounds.clone(), vec![3, 3, 3], 1))
///     })
///     .rule("my-balance", || BalanceOnly);
/// registry.check()?;
/// assert!(registry.approximator_names().contains(&"coarse-grid"));
/// assert!(Registry::builtin().rule("lwpr", || BalanceOnly).check().is_ok());
/// assert!(Registry::builtin().rule("pendulum-cart", || BalanceOnly).check().is_err());
/// # Ok::<(), steplearn::bench::BenchError>(())
/// ```
#[derive(Clone, Default)]
pub struct Registry {
    approximators: Vec<(String, ApproxFactory)>,
    rules: Vec<(String, RuleFactory)>,
    experiments: Vec<Arc<dyn Experiment>>,
    problems: Vec<String>,
    /// `"approximator NAME"` and `"rule NAME"` of the built-ins, whose parameters are
    /// steplearn's (covered by [`RESULTS_FORMAT`]) and so are not fingerprinted.
    builtin: Vec<String>,
}

impl std::fmt::Debug for Registry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Registry")
            .field("approximators", &self.approximator_names())
            .field("rules", &self.rule_names())
            .field("experiments", &self.experiment_names())
            .field("problems", &self.problems)
            .finish()
    }
}

/// The factory registered as `name` among `entries` (of kind `what`).
fn find<'a, T>(what: &str, entries: &'a [(String, T)], name: &str) -> Result<&'a T, BenchError> {
    entries
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, f)| f)
        .ok_or_else(|| {
            let known: Vec<&str> = entries.iter().map(|(n, _)| n.as_str()).collect();
            BenchError::unknown(what, name, &known)
        })
}

/// The learner's input box ([`learner_bounds`]) that approximator factories receive.
fn bench_bounds() -> Result<InputBox, BenchError> {
    learner_bounds().map_err(|e| BenchError::Selection(e.to_string()))
}

impl Registry {
    /// An empty registry.
    pub fn new() -> Self {
        Registry::default()
    }

    /// The built-ins: the approximators `lwpr`, `rbf`, `grid`, `kernel-ridge`; the rules
    /// `pendulum-cart`, `balance-only`, `tracking-only`, `linear`, `rate-damped`,
    /// `policy-gradient` (each with its default parameters); the experiments `tracking`,
    /// `disturbance`, `stability`, `robustness` (A-D, in the paper's order) and
    /// `omnidirectional` (beyond the paper).
    pub fn builtin() -> Self {
        let mut r = Registry::new();
        for &kind in <ApproxKind as strum::VariantArray>::VARIANTS {
            r.add_approximator(
                kind.name(),
                Arc::new(move |b: &InputBox, lwpr: &LwprSettings| {
                    match kind {
                        ApproxKind::Lwpr => lwpr.build(b),
                        _ => kind.build(b),
                    }
                    .map(BoxedApproximator::new)
                }),
            );
        }
        let mut r = r
            .rule("pendulum-cart", PendulumCart::default)
            .rule("balance-only", || BalanceOnly)
            .rule("tracking-only", TrackingOnly::default)
            .rule("linear", Linear::default)
            .rule("rate-damped", RateDamped::default)
            .rule("policy-gradient", PolicyGradient::default);
        for e in suite::builtin() {
            r.add_experiment(e);
        }
        r.builtin = r
            .approximator_names()
            .iter()
            .map(|n| format!("approximator {n}"))
            .chain(r.rule_names().iter().map(|n| format!("rule {n}")))
            .collect();
        r
    }

    /// A fingerprint of a user's approximator `approx`: a stable hash of its freshly built
    /// model's saved JSON ([`Persist`]), so that a changed parameter under the same name
    /// changes the run's identity. `None` for a built-in.
    fn approx_fingerprint(&self, approx: &str) -> Result<Option<String>, BenchError> {
        if self.builtin.contains(&format!("approximator {approx}")) {
            return Ok(None);
        }
        let model = find("approximator", &self.approximators, approx)?(
            &bench_bounds()?,
            &LwprSettings::default(),
        )
        .and_then(|a| a.to_json())
        .map_err(|e| BenchError::Selection(format!("approximator {approx:?}: {e}")))?;
        Ok(Some(fingerprint(model.as_bytes())))
    }

    /// A fingerprint of a user's rule `rule`: a stable hash of a fresh rule's gradients on
    /// fixed step outcomes and its state ([`LearningRule::state`]), so that a changed
    /// parameter under the same name changes the run's identity. `None` for a built-in.
    fn rule_fingerprint(&self, rule: &str) -> Result<Option<String>, BenchError> {
        if self.builtin.contains(&format!("rule {rule}")) {
            return Ok(None);
        }
        let r = find("rule", &self.rules, rule)?();
        let mut bytes = Vec::new();
        for (i, &a) in [-0.07, -0.01, 0.0, 0.02, 0.09].iter().enumerate() {
            let b = [0.3, -0.5, 0.1, 0.0, -0.2][i];
            let step = crate::rules::StepOutcome {
                theta_e: a,
                theta_e_dot: b,
                f_e: 0.5 * a - 0.1 * b,
                f_r: 0.05 + a,
            };
            bytes.extend_from_slice(&r.gradient(&step).to_bits().to_le_bytes());
        }
        if let Some(state) = r.state() {
            bytes.extend_from_slice(state.to_string().as_bytes());
        }
        Ok(Some(fingerprint(&bytes)))
    }

    /// Why `name` cannot be registered as a `what` beside `names`, if it cannot (malformed,
    /// or taken).
    fn refusal(what: &str, name: &str, names: &[&str]) -> Option<String> {
        match check_name(what, name) {
            Err(e) => Some(e),
            Ok(()) if names.contains(&name) => Some(format!("{what} {name:?} is registered twice")),
            Ok(()) => None,
        }
    }

    /// Records `refusal`; true if there was one.
    fn refused(&mut self, refusal: Option<String>) -> bool {
        let refused = refusal.is_some();
        self.problems.extend(refusal);
        refused
    }

    fn add_approximator(&mut self, name: &str, factory: ApproxFactory) {
        if !self.refused(Self::refusal(
            "approximator",
            name,
            &self.approximator_names(),
        )) {
            self.approximators.push((name.to_string(), factory));
        }
    }

    /// Registers approximator `name`: `factory` builds a fresh, untrained one over the
    /// learner's input box (theta_E, theta_E_dot, F_R) for every learner of a run.
    pub fn approximator<A, F>(mut self, name: &str, factory: F) -> Self
    where
        A: FunctionApproximator + Clone + Persist + 'static,
        F: Fn(&InputBox) -> Result<A, ApproxError> + Send + Sync + 'static,
    {
        self.add_approximator(
            name,
            Arc::new(move |b: &InputBox, _: &LwprSettings| factory(b).map(BoxedApproximator::new)),
        );
        self
    }

    /// Registers learning rule `name`: `factory` builds it for every learner of a run.
    pub fn rule<R, F>(mut self, name: &str, factory: F) -> Self
    where
        R: LearningRule + 'static,
        F: Fn() -> R + Send + Sync + 'static,
    {
        if !self.refused(Self::refusal("rule", name, &self.rule_names())) {
            let boxed: RuleFactory = Arc::new(move || Box::new(factory()));
            self.rules.push((name.to_string(), boxed));
        }
        self
    }

    /// Registers an experiment under its [`Experiment::name`].
    pub fn experiment(mut self, experiment: impl Experiment + 'static) -> Self {
        self.add_experiment(Arc::new(experiment));
        self
    }

    fn add_experiment(&mut self, experiment: Arc<dyn Experiment>) {
        let name = experiment.name().to_string();
        if !self.refused(Self::refusal("experiment", &name, &self.experiment_names())) {
            self.experiments.push(experiment);
        }
    }

    /// The registered experiments, in order.
    pub fn experiments(&self) -> &[Arc<dyn Experiment>] {
        &self.experiments
    }

    /// `config` checked against the registered experiments (every protocol table accepted by
    /// its experiment, none of an unknown one) with every experiment's whole protocol table:
    /// what a run records.
    pub fn resolve_config(&self, config: &ConfigFile) -> Result<ConfigFile, BenchError> {
        config
            .resolved_for(&self.experiments)
            .map_err(|e| BenchError::Selection(format!("invalid config: {e}")))
    }

    /// Every problem of the registrations (a name taken twice, a malformed name), as one error.
    pub fn check(&self) -> Result<(), BenchError> {
        if self.problems.is_empty() {
            Ok(())
        } else {
            Err(BenchError::Registry(self.problems.join("; ")))
        }
    }

    /// The approximators' names, in registration order.
    pub fn approximator_names(&self) -> Vec<&str> {
        self.approximators.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// The rules' names, in registration order.
    pub fn rule_names(&self) -> Vec<&str> {
        self.rules.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// The experiments' names, in registration order.
    pub fn experiment_names(&self) -> Vec<&str> {
        self.experiments.iter().map(|e| e.name()).collect()
    }

    /// The experiment called `name`.
    pub fn find_experiment(&self, name: &str) -> Result<&dyn Experiment, BenchError> {
        self.experiments
            .iter()
            .find(|e| e.name() == name)
            .map(|e| &**e)
            .ok_or_else(|| BenchError::unknown("experiment", name, &self.experiment_names()))
    }

    /// Checks that `approx` and `rule` are registered and that the approximator builds, so
    /// that a factory that cannot build is an error before any run
    /// ([`BenchError::CannotBuild`]).
    pub fn check_combination(&self, approx: &str, rule: &str) -> Result<(), BenchError> {
        find("rule", &self.rules, rule)?;
        find("approximator", &self.approximators, approx)?(
            &bench_bounds()?,
            &LwprSettings::default(),
        )
        .map(|_| ())
        .map_err(|e| BenchError::CannotBuild {
            approx: approx.to_string(),
            rule: rule.to_string(),
            reason: e.to_string(),
        })
    }

    /// The run components ([`RunComponents`]) of approximator `approx` and rule `rule`, the
    /// built-in `lwpr` with the settings `lwpr` (`[settings.lwpr]`): what a [`RunContext`]
    /// builds every learner of a run from.
    pub fn components(
        &self,
        approx: &str,
        rule: &str,
        lwpr: &LwprSettings,
    ) -> Result<RegisteredComponents, BenchError> {
        Ok(RegisteredComponents {
            approx: find("approximator", &self.approximators, approx)?.clone(),
            rule: find("rule", &self.rules, rule)?.clone(),
            lwpr: lwpr.clone(),
        })
    }

    /// A learner builder of approximator `approx` and rule `rule`: each call gives a fresh,
    /// untrained `step-x` learner with the config it is given (its rule not reseeded); the
    /// built-in `lwpr` with the settings `lwpr` (`[settings.lwpr]`).
    pub fn learner_builder(
        &self,
        approx: &str,
        rule: &str,
        lwpr: &LwprSettings,
    ) -> Result<impl Fn(LearnerConfig) -> Result<RunLearner, LearnerError> + Sync + '_, BenchError>
    {
        let components = self.components(approx, rule, lwpr)?;
        Ok(move |config: LearnerConfig| step_x_learner(&components, config))
    }

    /// Runs `spec` with `settings` and the protocol tables `protocols`: writes its figures and
    /// CSV into `dir` and returns its summary (the caller writes `summary.json`). The run's
    /// learners learn the spec's set ([`RunSpec::learn`]) where it gives one, else the
    /// settings'. Every learner of the run has its rule reseeded with the run's seed
    /// ([`FootstepLearner::reseed`](crate::control::FootstepLearner::reseed)).
    pub fn run_spec(
        &self,
        spec: &RunSpec,
        dir: &Path,
        settings: &Settings,
        protocols: &ProtocolTables,
    ) -> Result<Summary, ExperimentError> {
        let settings = &settings_of(spec, settings);
        let invalid = |e: BenchError| ExperimentError::Invalid(e.to_string());
        let experiment = self.find_experiment(&spec.experiment).map_err(invalid)?;
        let components = self
            .components(&spec.approx, &spec.rule, &settings.lwpr)
            .map_err(invalid)?;
        let ctx = RunContext {
            settings,
            protocols,
            seed: spec.seed,
            approx: &spec.approx,
            rule: &spec.rule,
            components: &components,
        };
        let result = experiment.run(&ctx, dir)?;
        if result.name() != spec.experiment {
            return Err(ExperimentError::Invalid(format!(
                "experiment {} returned the result of {}",
                spec.experiment,
                result.name()
            )));
        }
        let robot = crate::experiments::robot_setup::robot_summary(settings)
            .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
        Ok(Summary {
            approx: spec.approx.clone(),
            rule: spec.rule.clone(),
            seed: spec.seed,
            learn: settings.learner.learn,
            robot: Some(robot),
            result,
        })
    }
}

/// `settings` with the spec's set of learned parameters, where it gives one.
fn settings_of(spec: &RunSpec, settings: &Settings) -> Settings {
    let mut settings = settings.clone();
    if let Some(set) = spec.learn {
        settings.learner.learn = set;
    }
    settings
}

/// `fnv1a-64:` and the 64-bit FNV-1a hash of `bytes` in hex: stable across platforms and
/// releases (not a cryptographic hash: it tells changes apart, it does not resist forgery).
fn fingerprint(bytes: &[u8]) -> String {
    let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("fnv1a-64:{hash:016x}")
}

/// The version of the results' format, recorded in every run's identity: raised when a
/// change of steplearn makes earlier results differ from what it would produce now.
pub const RESULTS_FORMAT: u32 = 1;

/// The version of the rules that carry the paper robot's settings to another robot
/// ([`crate::robot::Scale`], [`crate::control::WalkerConfig::for_robot`]), recorded in the
/// identity of every run on another robot than the built-in one: raised when a change of
/// them makes such runs differ, so that the paper robot's results stay reusable.
pub const ROBOT_RULES: u32 = 2;

/// What determines a run's results, recorded as its `run-config.toml`.
#[derive(serde::Serialize)]
struct RunIdentity<'a> {
    format: u32,
    /// [`ROBOT_RULES`] for a run on another robot than the built-in one.
    #[serde(skip_serializing_if = "Option::is_none")]
    robot_rules: Option<u32>,
    experiment: &'a str,
    approx: &'a str,
    rule: &'a str,
    /// A user's approximator's fingerprint (absent for the built-ins).
    #[serde(skip_serializing_if = "Option::is_none")]
    approx_model: Option<String>,
    /// A user's rule's fingerprint (absent for the built-ins).
    #[serde(skip_serializing_if = "Option::is_none")]
    rule_model: Option<String>,
    seed: u64,
    settings: &'a Settings,
    #[serde(skip_serializing_if = "Option::is_none")]
    protocol: Option<Table>,
}

impl Registry {
    /// The identity of `spec` with `settings` and `protocols`: the run, for a user's
    /// approximator and rule a fingerprint of what they build (`approx_model`, `rule_model`:
    /// a changed parameter under the same name is another identity, so its finished runs are
    /// never reused), the whole settings
    /// (with the spec's set of learned parameters, recorded when not the paper's), the
    /// experiment's whole protocol table and [`RESULTS_FORMAT`], as TOML. Two runs with
    /// the same identity give the same bytes.
    pub fn run_identity(
        &self,
        spec: &RunSpec,
        settings: &Settings,
        protocols: &ProtocolTables,
    ) -> Result<String, BenchError> {
        let settings = &settings_of(spec, settings);
        let invalid = |e: ConfigError| BenchError::Selection(format!("invalid config: {e}"));
        settings.validate().map_err(invalid)?;
        let protocol = self
            .find_experiment(&spec.experiment)?
            .protocol(protocols)
            .map_err(invalid)?;
        toml::to_string_pretty(&RunIdentity {
            format: RESULTS_FORMAT,
            robot_rules: settings.sim.robot.as_ref().map(|_| ROBOT_RULES),
            experiment: &spec.experiment,
            approx: &spec.approx,
            rule: &spec.rule,
            approx_model: self.approx_fingerprint(&spec.approx)?,
            rule_model: self.rule_fingerprint(&spec.rule)?,
            seed: spec.seed,
            settings,
            protocol,
        })
        .map_err(|e| BenchError::Selection(e.to_string()))
    }

    /// The sweep runner of this registry's runs with `settings` and `protocols`; it records
    /// each run's identity, so a finished run is reused only for the same configuration.
    pub fn runner<'a>(
        &'a self,
        settings: &'a Settings,
        protocols: &'a ProtocolTables,
    ) -> RegistryRunner<'a> {
        RegistryRunner {
            registry: self,
            settings,
            protocols,
        }
    }
}

/// Runs a registry's runs with one configuration ([`Registry::runner`]).
#[derive(Debug, Clone, Copy)]
pub struct RegistryRunner<'a> {
    registry: &'a Registry,
    settings: &'a Settings,
    protocols: &'a ProtocolTables,
}

impl Runner for RegistryRunner<'_> {
    fn run(&self, spec: &RunSpec, dir: &Path) -> Result<Summary, RunError> {
        Ok(self
            .registry
            .run_spec(spec, dir, self.settings, self.protocols)?)
    }

    fn identity(&self, spec: &RunSpec) -> Result<Option<String>, RunError> {
        Ok(Some(self.registry.run_identity(
            spec,
            self.settings,
            self.protocols,
        )?))
    }

    fn check(&self, summary: &Summary) -> Result<(), ReportError> {
        match self.registry.find_experiment(summary.experiment()) {
            Ok(experiment) => experiment.check_result(&summary.result),
            Err(e) => Err(ReportError::invalid(e.to_string())),
        }
    }
}

/// A registered approximator and rule, as a run's [`RunComponents`] ([`Registry::components`]).
pub struct RegisteredComponents {
    approx: ApproxFactory,
    rule: RuleFactory,
    lwpr: LwprSettings,
}

impl RunComponents for RegisteredComponents {
    fn approximator(&self, bounds: &InputBox) -> Result<BoxedApproximator, ApproxError> {
        (self.approx)(bounds, &self.lwpr)
    }

    fn rule(&self) -> Box<dyn LearningRule> {
        (self.rule)()
    }
}
