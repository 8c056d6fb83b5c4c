//! `summary.json`: the one-file result of a run, with exactly the fields the command line
//! contract (issue 6) promises, read back by `merge`.
//!
//! ```json
//! {"approx": "lwpr", "rule": "pendulum-cart", "seed": 3, "experiment": "stability",
//!  "controllers": {"open_loop": {"pushes": 400, "falls": 150, "impulse_at_50pct_fall_ns": 6.1},
//!                  "model": {...}, "learned": {...}}}
//! ```

use crate::Named;
use crate::control::step_parameter::LearnSet;
use crate::experiments::ExperimentKind;
use crate::experiments::fall_causes::FallCause;
use crate::report::{ReportError, write_file};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::collections::BTreeMap;
use std::path::Path;

/// A pair of results for the Capture Step model alone and with learning.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelLearned<T> {
    /// The Capture Step controller alone.
    pub model: T,
    /// With the learned offset.
    pub learned: T,
}

/// Pushes, falls and the 50% fall impulse of one controller (experiment C).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControllerFalls {
    /// Pushes applied.
    pub pushes: u32,
    /// Falls among them.
    pub falls: u32,
    /// Impulse (Ns) at which half the pushes make the robot fall, from
    /// [`crate::report::fall_rate::impulse_at_50pct_fall`] (with its documented fallbacks).
    pub impulse_at_50pct_fall_ns: f64,
}

/// Experiment C's three controllers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Controllers {
    /// Walking in place at a fixed frequency, not reacting to pushes.
    pub open_loop: ControllerFalls,
    /// The Capture Step controller.
    pub model: ControllerFalls,
    /// Capture Step plus the learned offset.
    pub learned: ControllerFalls,
}

/// Experiment C: falls per cause (names from [`crate::experiments::fall_causes::FallCause`])
/// of each controller, over every fall of its trial. Empty in summaries written before the
/// causes were recorded.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FallCauseCounts {
    /// The open-loop walker.
    pub open_loop: BTreeMap<String, u32>,
    /// The Capture Step controller.
    pub model: BTreeMap<String, u32>,
    /// Capture Step plus the learned offset.
    pub learned: BTreeMap<String, u32>,
}

/// Experiment B: pushes delivered and pushes that ended in a fall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PushFalls {
    /// Pushes delivered, per controller.
    pub pushes: ModelLearned<u32>,
    /// Pushes followed by a fall, per controller.
    pub falls: ModelLearned<u32>,
    /// Every fall of the trial per cause (names from
    /// [`crate::experiments::fall_causes::FallCause`]), per controller; absent in older
    /// summaries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub causes: Option<ModelLearned<BTreeMap<String, u32>>>,
    /// Pushes followed by a fall before the next push, per controller: `falls` plus the
    /// pushes whose fall came after the push window closed; absent in older summaries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub before_next_push: Option<ModelLearned<u32>>,
}

/// Experiment D: the same episodes walked without learning (dF = 0 throughout).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoLearning {
    /// Whether each push (in order) was absorbed.
    pub absorbed_by_push: Vec<bool>,
    /// Falls over the whole run.
    pub falls: u32,
}

/// The experiment-specific part of a summary; serialized flat next to the common fields, with
/// the `"experiment"` name as its tag.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "experiment", rename_all = "lowercase")]
pub enum ExperimentResult {
    /// A: std of the step size error per time bin after a reference change.
    Tracking {
        /// Std of F_E (m) in consecutive bins of `bin_s` after each change; `null` where fewer
        /// than two steps of that controller fell into the bin (e.g. a walker that kept
        /// falling).
        step_error_std_m: ModelLearned<Vec<Option<f64>>>,
        /// Bin width (s).
        bin_s: f64,
    },
    /// B: recovery after 8 Ns pushes.
    Disturbance {
        /// Time (s) from the push until the step size is back at the reference step (within
        /// the protocol's tolerance; the horizon if never).
        return_time_s: ModelLearned<f64>,
        /// Time (s) from the push until the step size is back at the walker's own undisturbed
        /// mean step (recovery without a steady bias); absent in older summaries.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        settle_time_s: Option<ModelLearned<f64>>,
        /// Mean |F_hat - F_R| (m) of the touch-downs within the horizon after an absorbed
        /// push; absent in older summaries and when a walker absorbed no push.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        step_error_after_push_m: Option<ModelLearned<f64>>,
        /// Largest |theta_E| (rad) after the push.
        max_tda_rad: ModelLearned<f64>,
        /// Pushes delivered and pushes that ended in a fall, per controller (the return time
        /// and TDA cover the absorbed pushes only); absent in older summaries.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        falls: Option<PushFalls>,
    },
    /// C: falls vs impulse for three controllers.
    Stability {
        /// Per controller.
        controllers: Controllers,
        /// Falls per cause, per controller (empty in older summaries).
        #[serde(default)]
        fall_causes: FallCauseCounts,
        /// The catch step's reach of the model and the learned walker (see
        /// [`crate::experiments::catch_step`]); absent in older summaries.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        catch_step_reach: Option<CatchStepReaches>,
    },
    /// D: learning from scratch.
    Robustness {
        /// 1-based index of the first push absorbed without a fall; `null` if none was.
        pushes_until_first_absorbed: Option<u32>,
        /// Falls over the whole run.
        falls: u32,
        /// The push impulse (Ns); absent in older summaries.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        impulse_ns: Option<f64>,
        /// The learned walker: whether each push (in order) was absorbed (empty in older
        /// summaries).
        #[serde(default)]
        absorbed_by_push: Vec<bool>,
        /// The same episodes without learning; absent in older summaries.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        no_learning: Option<NoLearning>,
    },
    /// A user's experiment: its name and its own fields.
    #[serde(skip)]
    Custom(CustomResult),
}

/// The result of an experiment outside the paper's four: its name and whatever fields it
/// reports (numbers, lists, objects), written flat into `summary.json` beside the common
/// fields.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CustomResult {
    /// The experiment's registered name.
    pub experiment: String,
    /// Its fields.
    pub fields: serde_json::Map<String, serde_json::Value>,
}

impl CustomResult {
    /// The result of experiment `name` with the fields of `value` (a struct or map that
    /// serializes to a JSON object).
    pub fn new(name: &str, value: &impl Serialize) -> Result<Self, ReportError> {
        match serde_json::to_value(value) {
            Ok(serde_json::Value::Object(fields)) => Ok(CustomResult {
                experiment: name.to_string(),
                fields,
            }),
            Ok(other) => Err(ReportError::invalid(format!(
                "the result of {name} must serialize to a JSON object, got {other}"
            ))),
            Err(e) => Err(ReportError::invalid(e.to_string())),
        }
    }

    /// Its fields read back as `T`.
    pub fn parse<T: serde::de::DeserializeOwned>(&self) -> Result<T, ReportError> {
        serde_json::from_value(serde_json::Value::Object(self.fields.clone()))
            .map_err(|e| ReportError::invalid(format!("the result of {}: {e}", self.experiment)))
    }
}

impl ExperimentResult {
    /// The experiment's name, as in `summary.json`.
    pub fn name(&self) -> &str {
        match self {
            ExperimentResult::Tracking { .. } => ExperimentKind::Tracking.name(),
            ExperimentResult::Disturbance { .. } => ExperimentKind::Disturbance.name(),
            ExperimentResult::Stability { .. } => ExperimentKind::Stability.name(),
            ExperimentResult::Robustness { .. } => ExperimentKind::Robustness.name(),
            ExperimentResult::Custom(c) => &c.experiment,
        }
    }
}

/// The catch step's mean reach (realised / commanded length) of the two Capture Step
/// walkers; `null` where no push had a catch step that counts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CatchStepReaches {
    /// The Capture Step model.
    pub model: Option<f64>,
    /// The learned walker.
    pub learned: Option<f64>,
}

/// The content of `summary.json`: the common fields, then `"experiment"` and the experiment's
/// own fields.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Approximator name (`lwpr`, `rbf`, `grid`, `kernel-ridge`, or a user's).
    pub approx: String,
    /// Learning rule name (`pendulum-cart`, ..., or a user's).
    pub rule: String,
    /// Seed of the run.
    pub seed: u64,
    /// The step parameters the run's learner learned (`[settings.learner] learn`; older
    /// summaries: the paper's `step-x`).
    pub learn: LearnSet,
    /// `"experiment"` and the experiment's fields.
    pub result: ExperimentResult,
}

/// The fields every summary has.
const COMMON_FIELDS: [&str; 5] = ["approx", "rule", "seed", "learn", "experiment"];

#[derive(Serialize)]
struct BuiltinOut<'a> {
    approx: &'a str,
    rule: &'a str,
    seed: u64,
    learn: LearnSet,
    #[serde(flatten)]
    result: &'a ExperimentResult,
}

#[derive(Serialize)]
struct CustomOut<'a> {
    approx: &'a str,
    rule: &'a str,
    seed: u64,
    learn: LearnSet,
    experiment: &'a str,
    #[serde(flatten)]
    fields: &'a serde_json::Map<String, serde_json::Value>,
}

#[derive(Deserialize)]
struct SummaryIn {
    approx: String,
    rule: String,
    seed: u64,
    #[serde(default)]
    learn: LearnSet,
    experiment: String,
    #[serde(flatten)]
    fields: serde_json::Map<String, serde_json::Value>,
}

impl Serialize for Summary {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match &self.result {
            ExperimentResult::Custom(c) => CustomOut {
                approx: &self.approx,
                rule: &self.rule,
                seed: self.seed,
                learn: self.learn,
                experiment: &c.experiment,
                fields: &c.fields,
            }
            .serialize(serializer),
            result => BuiltinOut {
                approx: &self.approx,
                rule: &self.rule,
                seed: self.seed,
                learn: self.learn,
                result,
            }
            .serialize(serializer),
        }
    }
}

impl<'de> Deserialize<'de> for Summary {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let SummaryIn {
            approx,
            rule,
            seed,
            learn,
            experiment,
            mut fields,
        } = SummaryIn::deserialize(deserializer)?;
        let result = if ExperimentKind::from_name(&experiment).is_some() {
            fields.insert(
                "experiment".into(),
                serde_json::Value::String(experiment.clone()),
            );
            serde_json::from_value(serde_json::Value::Object(fields))
                .map_err(serde::de::Error::custom)?
        } else {
            ExperimentResult::Custom(CustomResult { experiment, fields })
        };
        Ok(Summary {
            approx,
            rule,
            seed,
            learn,
            result,
        })
    }
}

/// Checks a registered name (approximator, rule or experiment): non-empty lowercase ASCII
/// letters, digits and `-`, so that it is safe in run ids and paths.
pub(crate) fn check_name(what: &str, name: &str) -> Result<(), String> {
    let ok = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-');
    if ok {
        Ok(())
    } else {
        Err(format!(
            "{what} name {name:?} must be non-empty lowercase letters, digits or '-'"
        ))
    }
}

/// Checks one controller's falls per cause: known causes only, and (where any are recorded)
/// exactly one fall with a cause after a push for each push that ended in a fall.
fn check_causes(name: &str, causes: &BTreeMap<String, u32>, falls: u32) -> Result<(), ReportError> {
    let mut pushed = 0u64;
    for (k, &n) in causes {
        match FallCause::from_name(k) {
            Some(cause) => pushed += u64::from(cause.after_push()) * u64::from(n),
            None => {
                return Err(ReportError::invalid(format!(
                    "{name}: unknown fall cause {k:?}"
                )));
            }
        }
    }
    if !causes.is_empty() && pushed != u64::from(falls) {
        return Err(ReportError::invalid(format!(
            "{name}: fall causes count {pushed} falls after pushes, the pushes {falls}"
        )));
    }
    Ok(())
}

fn finite_non_negative(what: &str, v: f64) -> Result<(), ReportError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(ReportError::invalid(format!(
            "{what} must be finite and >= 0, got {v}"
        )))
    }
}

/// A user's result: a valid name, not a built-in's, and no field every summary has already.
fn validate_custom(c: &CustomResult) -> Result<(), ReportError> {
    check_name("experiment", &c.experiment).map_err(ReportError::invalid)?;
    if ExperimentKind::from_name(&c.experiment).is_some() {
        return Err(ReportError::invalid(format!(
            "{} is a built-in experiment; its result cannot be custom",
            c.experiment
        )));
    }
    if let Some(k) = COMMON_FIELDS.iter().find(|k| c.fields.contains_key(**k)) {
        return Err(ReportError::invalid(format!(
            "the result of {} has a field {k:?}, which every summary has already",
            c.experiment
        )));
    }
    Ok(())
}

/// A: a positive bin width, equal-length series, finite non-negative spreads.
fn validate_tracking(
    step_error_std_m: &ModelLearned<Vec<Option<f64>>>,
    bin_s: &f64,
) -> Result<(), ReportError> {
    if !(bin_s.is_finite() && *bin_s > 0.0) {
        return Err(ReportError::invalid(format!(
            "bin_s must be finite and > 0, got {bin_s}"
        )));
    }
    if step_error_std_m.model.len() != step_error_std_m.learned.len() {
        return Err(ReportError::invalid(
            "step_error_std_m: model and learned have different lengths",
        ));
    }
    for v in step_error_std_m
        .model
        .iter()
        .chain(&step_error_std_m.learned)
        .flatten()
    {
        finite_non_negative("step_error_std_m", *v)?;
    }
    Ok(())
}

/// B: finite non-negative times, errors and angles; falls within pushes, causes adding up.
fn validate_disturbance(
    return_time_s: &ModelLearned<f64>,
    settle_time_s: &Option<ModelLearned<f64>>,
    step_error_after_push_m: &Option<ModelLearned<f64>>,
    max_tda_rad: &ModelLearned<f64>,
    falls: &Option<PushFalls>,
) -> Result<(), ReportError> {
    if let Some(t) = settle_time_s {
        finite_non_negative("settle_time_s.model", t.model)?;
        finite_non_negative("settle_time_s.learned", t.learned)?;
    }
    if let Some(e) = step_error_after_push_m {
        finite_non_negative("step_error_after_push_m.model", e.model)?;
        finite_non_negative("step_error_after_push_m.learned", e.learned)?;
    }
    if let Some(f) = falls {
        if f.falls.model > f.pushes.model || f.falls.learned > f.pushes.learned {
            return Err(ReportError::invalid(format!(
                "falls: more falls than pushes ({f:?})"
            )));
        }
        if let Some(causes) = &f.causes {
            check_causes("model", &causes.model, f.falls.model)?;
            check_causes("learned", &causes.learned, f.falls.learned)?;
        }
        if let Some(late) = &f.before_next_push {
            let within = |late: u32, falls: u32, pushes: u32| (falls..=pushes).contains(&late);
            if !within(late.model, f.falls.model, f.pushes.model)
                || !within(late.learned, f.falls.learned, f.pushes.learned)
            {
                return Err(ReportError::invalid(format!(
                    "falls: falls before the next push {late:?} outside [falls, pushes]"
                )));
            }
        }
    }
    finite_non_negative("return_time_s.model", return_time_s.model)?;
    finite_non_negative("return_time_s.learned", return_time_s.learned)?;
    finite_non_negative("max_tda_rad.model", max_tda_rad.model)?;
    finite_non_negative("max_tda_rad.learned", max_tda_rad.learned)?;
    Ok(())
}

/// C: falls within pushes per controller, causes adding up, finite reaches.
fn validate_stability(
    controllers: &Controllers,
    fall_causes: &FallCauseCounts,
    catch_step_reach: &Option<CatchStepReaches>,
) -> Result<(), ReportError> {
    for (name, c, causes) in [
        ("open_loop", &controllers.open_loop, &fall_causes.open_loop),
        ("model", &controllers.model, &fall_causes.model),
        ("learned", &controllers.learned, &fall_causes.learned),
    ] {
        c.validate(name)?;
        check_causes(name, causes, c.falls)?;
    }
    if let Some(r) = catch_step_reach {
        for (name, v) in [
            ("catch_step_reach.model", r.model),
            ("catch_step_reach.learned", r.learned),
        ] {
            if v.is_some_and(|v| !v.is_finite()) {
                return Err(ReportError::invalid(format!("{name} must be finite")));
            }
        }
    }
    Ok(())
}

/// D: the first absorbed push agrees with the per-push record; a missed push means a fall.
fn validate_robustness(
    pushes_until_first_absorbed: &Option<u32>,
    falls: &u32,
    impulse_ns: &Option<f64>,
    absorbed_by_push: &[bool],
    no_learning: &Option<NoLearning>,
) -> Result<(), ReportError> {
    if *pushes_until_first_absorbed == Some(0) {
        return Err(ReportError::invalid(
            "pushes_until_first_absorbed is 1-based, got 0",
        ));
    }
    if let Some(i) = impulse_ns {
        finite_non_negative("impulse_ns", *i)?;
    }
    let first = absorbed_by_push
        .iter()
        .position(|&a| a)
        .map(|i| i as u32 + 1);
    if !absorbed_by_push.is_empty() && first != *pushes_until_first_absorbed {
        return Err(ReportError::invalid(format!(
            "absorbed_by_push first absorbs push {first:?}, \
                 pushes_until_first_absorbed says {pushes_until_first_absorbed:?}"
        )));
    }
    // A push not absorbed means at least one fall in its episode.
    let check_falls = |what: &str, absorbed: &[bool], falls: u32| {
        let missed = absorbed.iter().filter(|&&a| !a).count();
        if (falls as usize) < missed {
            Err(ReportError::invalid(format!(
                "{what}: {missed} pushes not absorbed but only {falls} falls"
            )))
        } else {
            Ok(())
        }
    };
    check_falls("learned", absorbed_by_push, *falls)?;
    if let Some(n) = no_learning {
        if n.absorbed_by_push.len() != absorbed_by_push.len() {
            return Err(ReportError::invalid(format!(
                "no_learning has {} pushes, the learned walker {}",
                n.absorbed_by_push.len(),
                absorbed_by_push.len()
            )));
        }
        check_falls("no_learning", &n.absorbed_by_push, n.falls)?;
    }
    Ok(())
}

impl ControllerFalls {
    fn validate(&self, name: &str) -> Result<(), ReportError> {
        if self.falls > self.pushes {
            return Err(ReportError::invalid(format!(
                "{name}: {} falls out of {} pushes",
                self.falls, self.pushes
            )));
        }
        finite_non_negative(
            &format!("{name}.impulse_at_50pct_fall_ns"),
            self.impulse_at_50pct_fall_ns,
        )
    }
}

impl Summary {
    /// Which experiment this is.
    pub fn experiment(&self) -> &str {
        self.result.name()
    }

    /// Checks what JSON cannot: a non-empty approximator name and finite, non-negative
    /// numbers (serde_json would write NaN as `null` and fail to read it back), falls <= pushes,
    /// equal-length model/learned series and a positive bin width.
    pub fn validate(&self) -> Result<(), ReportError> {
        check_name("approximator", &self.approx).map_err(ReportError::invalid)?;
        check_name("rule", &self.rule).map_err(ReportError::invalid)?;
        match &self.result {
            ExperimentResult::Custom(c) => validate_custom(c),
            ExperimentResult::Tracking {
                step_error_std_m,
                bin_s,
            } => validate_tracking(step_error_std_m, bin_s),
            ExperimentResult::Disturbance {
                return_time_s,
                settle_time_s,
                step_error_after_push_m,
                max_tda_rad,
                falls,
            } => validate_disturbance(
                return_time_s,
                settle_time_s,
                step_error_after_push_m,
                max_tda_rad,
                falls,
            ),
            ExperimentResult::Stability {
                controllers,
                fall_causes,
                catch_step_reach,
            } => validate_stability(controllers, fall_causes, catch_step_reach),
            ExperimentResult::Robustness {
                pushes_until_first_absorbed,
                falls,
                impulse_ns,
                absorbed_by_push,
                no_learning,
            } => validate_robustness(
                pushes_until_first_absorbed,
                falls,
                impulse_ns,
                absorbed_by_push,
                no_learning,
            ),
        }
    }

    /// Pretty JSON of a validated summary.
    pub fn to_json(&self) -> Result<String, ReportError> {
        self.validate()?;
        serde_json::to_string_pretty(self).map_err(|e| ReportError::invalid(e.to_string()))
    }

    /// Parses and validates a summary.
    pub fn from_json(json: &str) -> Result<Self, ReportError> {
        let s: Summary =
            serde_json::from_str(json).map_err(|e| ReportError::invalid(e.to_string()))?;
        s.validate()?;
        Ok(s)
    }

    /// Validates and writes the summary to `path` atomically (an invalid summary or a failed
    /// write leaves any existing file untouched).
    pub fn write(&self, path: &Path) -> Result<(), ReportError> {
        let json = self.to_json()?;
        write_file(path, json.as_bytes())
    }

    /// Reads and validates `path`; a malformed file is a [`ReportError::Parse`] naming it.
    pub fn read(path: &Path) -> Result<Self, ReportError> {
        let text = std::fs::read_to_string(path).map_err(|e| ReportError::io(path, e))?;
        Summary::from_json(&text).map_err(|e| ReportError::Parse {
            path: path.to_path_buf(),
            message: match e {
                ReportError::Invalid(m) => m,
                other => other.to_string(),
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn falls(pushes: u32, falls: u32, x: f64) -> ControllerFalls {
        ControllerFalls {
            pushes,
            falls,
            impulse_at_50pct_fall_ns: x,
        }
    }

    fn causes(no_push: u32, pushed: [u32; 2]) -> BTreeMap<String, u32> {
        [
            ("no_push".to_string(), no_push),
            ("before_touch_down".to_string(), pushed[0]),
            ("tipped_after_catch_step".to_string(), pushed[1]),
        ]
        .into()
    }

    fn stability() -> Summary {
        Summary {
            approx: "lwpr".into(),
            rule: "pendulum-cart".into(),
            seed: 3,
            learn: LearnSet::default(),
            result: ExperimentResult::Stability {
                controllers: Controllers {
                    open_loop: falls(400, 250, 4.5),
                    model: falls(400, 120, 11.0),
                    learned: falls(400, 90, 13.25),
                },
                fall_causes: FallCauseCounts {
                    open_loop: causes(3, [200, 50]),
                    model: causes(0, [100, 20]),
                    learned: causes(1, [60, 30]),
                },
                catch_step_reach: Some(CatchStepReaches {
                    model: Some(0.93),
                    learned: None,
                }),
            },
        }
    }

    fn robustness() -> ExperimentResult {
        ExperimentResult::Robustness {
            pushes_until_first_absorbed: Some(3),
            falls: 2,
            impulse_ns: Some(8.0),
            absorbed_by_push: vec![false, false, true],
            no_learning: Some(NoLearning {
                absorbed_by_push: vec![false, false, false],
                falls: 4,
            }),
        }
    }

    #[test]
    fn json_has_exactly_the_promised_fields() {
        let v: serde_json::Value = serde_json::from_str(&stability().to_json().unwrap()).unwrap();
        let mut keys: Vec<_> = v.as_object().unwrap().keys().cloned().collect();
        keys.sort();
        assert_eq!(
            keys,
            [
                "approx",
                "catch_step_reach",
                "controllers",
                "experiment",
                "fall_causes",
                "learn",
                "rule",
                "seed"
            ]
        );
        assert_eq!(v["learn"], serde_json::json!(["step-x"]));
        assert_eq!(v["catch_step_reach"]["model"], 0.93);
        assert!(v["catch_step_reach"]["learned"].is_null());
        assert_eq!(v["fall_causes"]["model"]["before_touch_down"], 100);
        assert_eq!(v["experiment"], "stability");
        assert_eq!(v["rule"], "pendulum-cart");
        assert_eq!(
            v["controllers"]["open_loop"]["impulse_at_50pct_fall_ns"],
            4.5
        );
        assert_eq!(v["controllers"]["learned"]["falls"], 90);

        let others = [
            (
                ExperimentResult::Tracking {
                    step_error_std_m: ModelLearned {
                        model: vec![Some(0.05), Some(0.03)],
                        learned: vec![Some(0.04), None],
                    },
                    bin_s: 0.5,
                },
                vec!["bin_s", "step_error_std_m"],
            ),
            (
                ExperimentResult::Disturbance {
                    return_time_s: ModelLearned {
                        model: 3.0,
                        learned: 2.0,
                    },
                    settle_time_s: Some(ModelLearned {
                        model: 2.5,
                        learned: 2.0,
                    }),
                    step_error_after_push_m: Some(ModelLearned {
                        model: 0.05,
                        learned: 0.04,
                    }),
                    max_tda_rad: ModelLearned {
                        model: 0.1,
                        learned: 0.14,
                    },
                    falls: Some(PushFalls {
                        pushes: ModelLearned {
                            model: 60,
                            learned: 60,
                        },
                        falls: ModelLearned {
                            model: 0,
                            learned: 3,
                        },
                        causes: Some(ModelLearned {
                            model: cause_counts(&[("no_push", 1)]),
                            learned: cause_counts(&[("tipped_after_catch_step", 3)]),
                        }),
                        before_next_push: Some(ModelLearned {
                            model: 1,
                            learned: 3,
                        }),
                    }),
                },
                vec![
                    "falls",
                    "max_tda_rad",
                    "return_time_s",
                    "settle_time_s",
                    "step_error_after_push_m",
                ],
            ),
            (
                robustness(),
                vec![
                    "absorbed_by_push",
                    "falls",
                    "impulse_ns",
                    "no_learning",
                    "pushes_until_first_absorbed",
                ],
            ),
        ];
        for (result, fields) in others {
            let s = Summary {
                result,
                ..stability()
            };
            let v: serde_json::Value = serde_json::from_str(&s.to_json().unwrap()).unwrap();
            let mut keys: Vec<_> = v.as_object().unwrap().keys().cloned().collect();
            keys.sort();
            let mut want = vec!["approx", "experiment", "learn", "rule", "seed"];
            want.extend(fields);
            want.sort();
            assert_eq!(keys, want);
            assert_eq!(v["experiment"], s.experiment());
            assert_eq!(Summary::from_json(&s.to_json().unwrap()).unwrap(), s);
        }
    }

    #[test]
    fn write_read_round_trip_and_no_clobber() {
        let dir = std::env::temp_dir().join(format!("steplearn-summary-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("summary.json");
        let s = stability();
        s.write(&path).unwrap();
        assert_eq!(Summary::read(&path).unwrap(), s);
        // an invalid summary is refused and the file stays as it was
        let mut bad = s.clone();
        if let ExperimentResult::Stability { controllers, .. } = &mut bad.result {
            controllers.model.impulse_at_50pct_fall_ns = f64::NAN;
        }
        assert!(matches!(bad.write(&path), Err(ReportError::Invalid(_))));
        assert_eq!(Summary::read(&path).unwrap(), s);
        // malformed files are parse errors that name the file
        let broken = dir.join("broken.json");
        std::fs::write(&broken, "{\"approx\": \"lwpr\"").unwrap();
        match Summary::read(&broken) {
            Err(ReportError::Parse { path, .. }) => assert_eq!(path, broken),
            other => panic!("{other:?}"),
        }
        std::fs::write(
            &broken,
            s.to_json()
                .unwrap()
                .replace("\"falls\": 90", "\"falls\": 900"),
        )
        .unwrap();
        assert!(matches!(
            Summary::read(&broken),
            Err(ReportError::Parse { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn older_summaries_without_causes_or_baseline_still_read() {
        let old_c = r#"{"approx": "lwpr", "rule": "pendulum-cart", "seed": 1,
            "experiment": "stability", "controllers": {
            "open_loop": {"pushes": 4, "falls": 2, "impulse_at_50pct_fall_ns": 5.0},
            "model": {"pushes": 4, "falls": 1, "impulse_at_50pct_fall_ns": 9.0},
            "learned": {"pushes": 4, "falls": 1, "impulse_at_50pct_fall_ns": 10.0}}}"#;
        match Summary::from_json(old_c).unwrap().result {
            ExperimentResult::Stability { fall_causes, .. } => {
                assert_eq!(fall_causes, FallCauseCounts::default())
            }
            other => panic!("{other:?}"),
        }
        let old_d = r#"{"approx": "lwpr", "rule": "pendulum-cart", "seed": 1,
            "experiment": "robustness", "pushes_until_first_absorbed": 2, "falls": 1}"#;
        let s = Summary::from_json(old_d).unwrap();
        assert_eq!(
            s.result,
            ExperimentResult::Robustness {
                pushes_until_first_absorbed: Some(2),
                falls: 1,
                impulse_ns: None,
                absorbed_by_push: vec![],
                no_learning: None,
            }
        );
        // Written back, it has no invented fields.
        assert!(!s.to_json().unwrap().contains("no_learning"));
    }

    /// Every cause at zero but `nonzero`.
    fn cause_counts(nonzero: &[(&str, u32)]) -> BTreeMap<String, u32> {
        let mut m: BTreeMap<String, u32> = FallCause::ALL
            .iter()
            .map(|c| (c.name().to_string(), 0))
            .collect();
        for &(k, n) in nonzero {
            m.insert(k.to_string(), n);
        }
        m
    }

    #[test]
    fn disturbance_fall_causes_must_match_its_falls() {
        let b = |model: &[(&str, u32)], learned: &[(&str, u32)]| Summary {
            result: ExperimentResult::Disturbance {
                return_time_s: ModelLearned {
                    model: 1.0,
                    learned: 1.0,
                },
                settle_time_s: None,
                step_error_after_push_m: None,
                max_tda_rad: ModelLearned {
                    model: 0.1,
                    learned: 0.1,
                },
                falls: Some(PushFalls {
                    pushes: ModelLearned {
                        model: 10,
                        learned: 10,
                    },
                    falls: ModelLearned {
                        model: 2,
                        learned: 1,
                    },
                    causes: Some(ModelLearned {
                        model: cause_counts(model),
                        learned: cause_counts(learned),
                    }),
                    before_next_push: Some(ModelLearned {
                        model: 3,
                        learned: 1,
                    }),
                }),
            },
            ..stability()
        };
        let ok = b(
            &[("later_step_clamped", 2), ("no_push", 4)],
            &[("catch_step_clamped", 1)],
        );
        ok.validate().unwrap();
        assert_eq!(Summary::from_json(&ok.to_json().unwrap()).unwrap(), ok);
        // one fall after a push short, one too many, an unknown cause
        assert!(
            b(&[("later_step_clamped", 1)], &[("catch_step_clamped", 1)])
                .validate()
                .is_err()
        );
        assert!(
            b(&[("later_step_clamped", 2)], &[("before_touch_down", 2)])
                .validate()
                .is_err()
        );
        assert!(
            b(
                &[("later_step_clamped", 2), ("gremlins", 0)],
                &[("no_push", 0), ("before_touch_down", 1)]
            )
            .validate()
            .is_err()
        );
    }

    #[test]
    fn inconsistent_causes_and_robustness_series_are_refused() {
        let mut s = stability();
        if let ExperimentResult::Stability { fall_causes, .. } = &mut s.result {
            // 91 falls after pushes for 90 fell pushes.
            *fall_causes.learned.get_mut("before_touch_down").unwrap() += 1;
        }
        assert!(s.validate().is_err());
        // no_push falls are outside the pushes' count.
        let mut s = stability();
        if let ExperimentResult::Stability { fall_causes, .. } = &mut s.result {
            *fall_causes.learned.get_mut("no_push").unwrap() += 5;
        }
        s.validate().unwrap();
        let mut s = stability();
        if let ExperimentResult::Stability { fall_causes, .. } = &mut s.result {
            fall_causes.model.insert("gremlins".into(), 0);
        }
        assert!(s.validate().is_err());

        let with = |f: &dyn Fn(&mut ExperimentResult)| {
            let mut r = robustness();
            f(&mut r);
            Summary {
                result: r,
                ..stability()
            }
            .validate()
        };
        with(&|_| {}).unwrap();
        // the first absorbed push disagrees with the series
        assert!(
            with(&|r| if let ExperimentResult::Robustness {
                absorbed_by_push, ..
            } = r
            {
                absorbed_by_push[1] = true;
            })
            .is_err()
        );
        // different lengths
        assert!(
            with(&|r| if let ExperimentResult::Robustness {
                no_learning: Some(n),
                ..
            } = r
            {
                n.absorbed_by_push.push(true);
            })
            .is_err()
        );
        // fewer falls than pushes not absorbed
        assert!(
            with(&|r| if let ExperimentResult::Robustness {
                no_learning: Some(n),
                ..
            } = r
            {
                n.falls = 2;
            })
            .is_err()
        );
        assert!(
            with(
                &|r| if let ExperimentResult::Robustness { impulse_ns, .. } = r {
                    *impulse_ns = Some(f64::NAN);
                }
            )
            .is_err()
        );
    }
}
