//! `summary.json`: the one-file result of a run, with exactly the fields the command line
//! contract (issue 6) promises, read back by `merge`.
//!
//! ```json
//! {"approx": "lwpr", "rule": "pendulum-cart", "seed": 3, "experiment": "stability",
//!  "controllers": {"open_loop": {"pushes": 400, "falls": 150, "impulse_at_50pct_fall_ns": 6.1},
//!                  "model": {...}, "learned": {...}}}
//! ```

use crate::control::LearnSet;
use crate::experiments::fall_causes::FallCause;
use crate::report::{ReportError, write_file};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// A pair of results for the Capture Step model alone and with learning.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelLearned<T> {
    /// The Capture Step controller alone.
    pub model: T,
    /// With the learned offset.
    pub learned: T,
}

/// The experiment-specific part of a summary, serialized flat next to the common fields with
/// the experiment's name as `"experiment"`. Every experiment, the paper's and a user's,
/// reports a [`CustomResult`]: its name and its own fields; an experiment with a typed result
/// implements [`TypedResult`] for it.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ExperimentResult {
    /// An experiment's name and its own fields.
    Custom(CustomResult),
}

impl ExperimentResult {
    /// The result of experiment `name` with the fields of `value` (a struct or map that
    /// serializes to a JSON object), written in alphabetical order ([`CustomResult::new`]).
    pub fn new(name: &str, value: &impl Serialize) -> Result<Self, ReportError> {
        CustomResult::new(name, value).map(ExperimentResult::Custom)
    }

    /// The experiment's name, as in `summary.json`.
    pub fn name(&self) -> &str {
        &self.custom().experiment
    }

    /// The experiment's name and fields.
    pub fn custom(&self) -> &CustomResult {
        let ExperimentResult::Custom(c) = self;
        c
    }

    /// Its fields read back as `T`.
    pub fn parse<T: serde::de::DeserializeOwned>(&self) -> Result<T, ReportError> {
        self.custom().parse()
    }
}

/// The result of one experiment: its name and whatever fields it reports (numbers, lists,
/// objects), written flat into `summary.json` beside the common fields.
#[derive(Clone, Default)]
pub struct CustomResult {
    /// The experiment's registered name.
    pub experiment: String,
    /// Its fields.
    pub fields: serde_json::Map<String, serde_json::Value>,
    /// The typed value the fields came from ([`CustomResult::in_order`]): written in its own
    /// field order while `fields` still holds what it serializes to.
    ordered: Option<Arc<dyn erased_serde::Serialize + Send + Sync>>,
}

impl std::fmt::Debug for CustomResult {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CustomResult")
            .field("experiment", &self.experiment)
            .field("fields", &self.fields)
            .finish()
    }
}

impl PartialEq for CustomResult {
    fn eq(&self, other: &Self) -> bool {
        self.experiment == other.experiment && self.fields == other.fields
    }
}

impl CustomResult {
    /// The result of experiment `name` with the fields of `value` (a struct or map that
    /// serializes to a JSON object), written in alphabetical order.
    pub fn new(name: &str, value: &impl Serialize) -> Result<Self, ReportError> {
        Ok(CustomResult {
            experiment: name.to_string(),
            fields: object_of(name, value)?,
            ordered: None,
        })
    }

    /// The result of experiment `name` with the fields of `value`, written in `value`'s own
    /// field order (read back, the fields are the same).
    pub fn in_order<T: Serialize + Send + Sync + 'static>(
        name: &str,
        value: T,
    ) -> Result<Self, ReportError> {
        Ok(CustomResult {
            experiment: name.to_string(),
            fields: object_of(name, &value)?,
            ordered: Some(Arc::new(value)),
        })
    }

    /// Its fields read back as `T`.
    pub fn parse<T: serde::de::DeserializeOwned>(&self) -> Result<T, ReportError> {
        serde_json::from_value(serde_json::Value::Object(self.fields.clone()))
            .map_err(|e| ReportError::invalid(format!("the result of {}: {e}", self.experiment)))
    }

    /// The typed value to write in its own order, if there is one and `fields` is still what
    /// it serializes to.
    fn ordered(&self) -> Option<&(dyn erased_serde::Serialize + Send + Sync)> {
        let typed = self.ordered.as_deref()?;
        match serde_json::to_value(typed) {
            Ok(serde_json::Value::Object(fields)) if fields == self.fields => Some(typed),
            _ => None,
        }
    }
}

/// `value` as a JSON object, or why it is not one.
fn object_of(
    name: &str,
    value: &impl Serialize,
) -> Result<serde_json::Map<String, serde_json::Value>, ReportError> {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::Object(fields)) => Ok(fields),
        Ok(other) => Err(ReportError::invalid(format!(
            "the result of {name} must serialize to a JSON object, got {other}"
        ))),
        Err(e) => Err(ReportError::invalid(e.to_string())),
    }
}

/// The typed result of one experiment: what its `run` reports, checked on the way out and
/// on the way back in.
pub trait TypedResult: Serialize + serde::de::DeserializeOwned + Send + Sync + 'static {
    /// The experiment's registered name.
    const EXPERIMENT: &'static str;

    /// Checks what JSON cannot (finite numbers, counts that add up, equal lengths).
    fn validate(&self) -> Result<(), ReportError>;

    /// The checked result, written in the type's own field order.
    fn into_result(self) -> Result<ExperimentResult, ReportError> {
        self.validate()?;
        CustomResult::in_order(Self::EXPERIMENT, self).map(ExperimentResult::Custom)
    }

    /// The checked typed result of `result`; an error if it is another experiment's or does
    /// not parse or check.
    fn from_result(result: &ExperimentResult) -> Result<Self, ReportError> {
        if result.name() != Self::EXPERIMENT {
            return Err(ReportError::invalid(format!(
                "a result of {} is not one of {}",
                result.name(),
                Self::EXPERIMENT
            )));
        }
        let typed: Self = result.parse()?;
        typed.validate()?;
        Ok(typed)
    }

    /// The checked typed result of `summary`; `None` if it is another experiment's or does
    /// not check (readers check every summary they read with
    /// [`crate::experiments::Experiment::check_result`] first).
    fn of(summary: &Summary) -> Option<Self> {
        Self::from_result(&summary.result).ok()
    }
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
    /// The robot it ran on (older summaries: none).
    pub robot: Option<RobotSummary>,
    /// `"experiment"` and the experiment's fields.
    pub result: ExperimentResult,
}

/// The robot a run walked on: its name, mass and the SHA-256 of its URDF (the built-in
/// humanoid's: of its `steplearn robot export`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotSummary {
    /// The robot's name.
    pub name: String,
    /// Its mass (kg).
    pub mass_kg: f64,
    /// SHA-256 of its URDF, lower-case hex.
    pub sha256: String,
}

/// The fields every summary has.
const COMMON_FIELDS: [&str; 6] = ["approx", "rule", "seed", "learn", "robot", "experiment"];

#[derive(Serialize)]
struct Out<'a, F: Serialize + ?Sized> {
    approx: &'a str,
    rule: &'a str,
    seed: u64,
    learn: LearnSet,
    #[serde(skip_serializing_if = "Option::is_none")]
    robot: &'a Option<RobotSummary>,
    experiment: &'a str,
    #[serde(flatten)]
    fields: &'a F,
}

#[derive(Deserialize)]
struct SummaryIn {
    approx: String,
    rule: String,
    seed: u64,
    #[serde(default)]
    learn: LearnSet,
    #[serde(default)]
    robot: Option<RobotSummary>,
    experiment: String,
    #[serde(flatten)]
    fields: serde_json::Map<String, serde_json::Value>,
}

impl Serialize for Summary {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        fn out<'a, F: Serialize + ?Sized>(s: &'a Summary, fields: &'a F) -> Out<'a, F> {
            Out {
                approx: &s.approx,
                rule: &s.rule,
                seed: s.seed,
                learn: s.learn,
                robot: &s.robot,
                experiment: s.result.name(),
                fields,
            }
        }
        let custom = self.result.custom();
        match custom.ordered() {
            Some(typed) => out(self, typed).serialize(serializer),
            None => out(self, &custom.fields).serialize(serializer),
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
            robot,
            experiment,
            fields,
        } = SummaryIn::deserialize(deserializer)?;
        Ok(Summary {
            approx,
            rule,
            seed,
            learn,
            robot,
            result: ExperimentResult::Custom(CustomResult {
                experiment,
                fields,
                ordered: None,
            }),
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

/// Checks one controller's falls per cause (names from
/// [`crate::experiments::fall_causes::FallCause`]): known causes only, and (where any are
/// recorded) exactly one fall with a cause after a push for each push that ended in a fall.
pub fn check_causes(
    name: &str,
    causes: &BTreeMap<String, u32>,
    falls: u32,
) -> Result<(), ReportError> {
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

/// `v` if it is finite and >= 0; otherwise an error naming `what`.
pub fn finite_non_negative(what: &str, v: f64) -> Result<(), ReportError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(ReportError::invalid(format!(
            "{what} must be finite and >= 0, got {v}"
        )))
    }
}

impl Summary {
    /// Which experiment this is.
    pub fn experiment(&self) -> &str {
        self.result.name()
    }

    /// Checks what every summary must hold: valid approximator, rule and experiment names,
    /// and no experiment field that every summary has already. An experiment's own fields are
    /// checked by its [`TypedResult`] (or its [`crate::experiments::Experiment::check_result`]).
    pub fn validate(&self) -> Result<(), ReportError> {
        check_name("approximator", &self.approx).map_err(ReportError::invalid)?;
        check_name("rule", &self.rule).map_err(ReportError::invalid)?;
        let r = self.result.custom();
        check_name("experiment", &r.experiment).map_err(ReportError::invalid)?;
        if let Some(k) = COMMON_FIELDS.iter().find(|k| r.fields.contains_key(**k)) {
            return Err(ReportError::invalid(format!(
                "the result of {} has a field {k:?}, which every summary has already",
                r.experiment
            )));
        }
        Ok(())
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

    /// A typed result whose field order is not alphabetical.
    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Probe {
        zeta: f64,
        alpha: Vec<Option<f64>>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        middle: Option<ModelLearned<u32>>,
    }

    impl TypedResult for Probe {
        const EXPERIMENT: &'static str = "probe";

        fn validate(&self) -> Result<(), ReportError> {
            finite_non_negative("zeta", self.zeta)
        }
    }

    fn probe(zeta: f64) -> Probe {
        Probe {
            zeta,
            alpha: vec![Some(0.5), None],
            middle: Some(ModelLearned {
                model: 3,
                learned: 4,
            }),
        }
    }

    fn summary(result: ExperimentResult) -> Summary {
        Summary {
            approx: "lwpr".into(),
            rule: "pendulum-cart".into(),
            seed: 3,
            learn: LearnSet::default(),
            robot: None,
            result,
        }
    }

    #[test]
    fn typed_results_keep_their_field_order_and_read_back_equal() {
        let s = summary(probe(1.5).into_result().unwrap());
        let json = s.to_json().unwrap();
        let at = |k: &str| json.find(&format!("\"{k}\"")).unwrap();
        // The common fields, then the type's own order (not alphabetical).
        assert!(at("approx") < at("rule") && at("rule") < at("seed"));
        assert!(at("seed") < at("learn") && at("learn") < at("experiment"));
        assert!(at("experiment") < at("zeta") && at("zeta") < at("alpha"));
        assert!(at("alpha") < at("middle"));
        let back = Summary::from_json(&json).unwrap();
        assert_eq!(back, s);
        assert_eq!(Probe::from_result(&back.result).unwrap(), probe(1.5));
        assert_eq!(Probe::of(&back), Some(probe(1.5)));
        // The same fields through `new` are written in alphabetical order, equal read back.
        let plain = summary(ExperimentResult::new("probe", &probe(1.5)).unwrap());
        let plain_json = plain.to_json().unwrap();
        assert!(plain_json.find("\"alpha\"").unwrap() < plain_json.find("\"zeta\"").unwrap());
        assert_eq!(Summary::from_json(&plain_json).unwrap(), s);
        // Absent optional fields stay absent.
        let none = summary(
            Probe {
                middle: None,
                ..probe(1.0)
            }
            .into_result()
            .unwrap(),
        );
        assert!(!none.to_json().unwrap().contains("middle"));
    }

    #[test]
    fn typed_results_are_checked_both_ways() {
        assert!(matches!(
            probe(f64::NAN).into_result(),
            Err(ReportError::Invalid(_))
        ));
        assert!(probe(-1.0).into_result().is_err());
        // Read back: another experiment's result, a field of the wrong type, an unknown field,
        // a value that fails the check.
        let other = ExperimentResult::new("other", &probe(1.0)).unwrap();
        assert!(Probe::from_result(&other).is_err());
        let wrong =
            ExperimentResult::new("probe", &serde_json::json!({"zeta": "x", "alpha": []})).unwrap();
        assert!(Probe::from_result(&wrong).is_err());
        let extra = ExperimentResult::new(
            "probe",
            &serde_json::json!({"zeta": 1.0, "alpha": [], "gremlins": 1}),
        )
        .unwrap();
        assert!(Probe::from_result(&extra).is_err());
        let negative =
            ExperimentResult::new("probe", &serde_json::json!({"zeta": -2.0, "alpha": []}))
                .unwrap();
        assert!(Probe::from_result(&negative).is_err());
        assert_eq!(Probe::of(&summary(negative)), None);
        // Not an object, or a common field.
        assert!(ExperimentResult::new("probe", &3.0).is_err());
        let common = ExperimentResult::new("probe", &serde_json::json!({"seed": 3})).unwrap();
        assert!(summary(common).validate().is_err());
        let bad_name = ExperimentResult::new("Probe!", &probe(1.0)).unwrap();
        assert!(summary(bad_name).validate().is_err());
    }

    #[test]
    fn write_read_round_trip_and_no_clobber() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("summary.json");
        let s = summary(probe(2.0).into_result().unwrap());
        s.write(&path).unwrap();
        assert_eq!(Summary::read(&path).unwrap(), s);
        // an invalid summary is refused and the file stays as it was
        let bad = Summary {
            approx: String::new(),
            ..s.clone()
        };
        assert!(matches!(bad.write(&path), Err(ReportError::Invalid(_))));
        assert_eq!(Summary::read(&path).unwrap(), s);
        // malformed files are parse errors that name the file
        let broken = dir.path().join("broken.json");
        std::fs::write(&broken, "{\"approx\": \"lwpr\"").unwrap();
        match Summary::read(&broken) {
            Err(ReportError::Parse { path, .. }) => assert_eq!(path, broken),
            other => panic!("{other:?}"),
        }
        std::fs::write(
            &broken,
            s.to_json()
                .unwrap()
                .replace("\"rule\": \"pendulum-cart\"", "\"rule\": \"\""),
        )
        .unwrap();
        assert!(matches!(
            Summary::read(&broken),
            Err(ReportError::Parse { .. })
        ));
    }

    #[test]
    fn fall_causes_must_add_up_to_the_falls() {
        let causes = |pairs: &[(&str, u32)]| -> BTreeMap<String, u32> {
            pairs.iter().map(|&(k, n)| (k.to_string(), n)).collect()
        };
        check_causes(
            "m",
            &causes(&[("no_push", 4), ("catch_step_clamped", 2)]),
            2,
        )
        .unwrap();
        check_causes("m", &BTreeMap::new(), 5).unwrap();
        assert!(check_causes("m", &causes(&[("catch_step_clamped", 1)]), 2).is_err());
        assert!(check_causes("m", &causes(&[("gremlins", 0)]), 0).is_err());
    }
}
