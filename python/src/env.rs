//! The footstep environment (`steplearn._steplearn.FootstepEnv`), the compiled core of
//! `steplearn.gym`: one `step` is one footstep of the simulated walker (see the Rust
//! `steplearn::experiments::footstep_env` and docs/footstep-env.md).
//!
//! Options become a [`FootstepEnvConfig`] through its serde form, as the approximators'
//! settings do ([`settings::apply`]); the simulation runs with the GIL released, and every
//! Rust error (or a panic, which the crate never intends) is a Python exception.

use crate::arrays;
use crate::settings;
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt, PyList, PyString, PyTuple};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use steplearn::control::LearnSet;
use steplearn::experiments::footstep_env::{
    EnvError, FootstepEnv as RustEnv, FootstepEnvConfig, PushProtocol,
};
use steplearn::experiments::settings::Settings;
use steplearn::rules::PendulumCart;

/// A Rust error as a Python exception: `ValueError` for a refused action or option (the
/// environment is unchanged), `RuntimeError` for a call out of order or a failed simulation.
fn env_err(e: EnvError) -> PyErr {
    match e {
        EnvError::ActionLength { .. }
        | EnvError::ActionNotFinite { .. }
        | EnvError::ActionOutOfRange { .. }
        | EnvError::Config(_)
        | EnvError::Robot(_) => PyValueError::new_err(e.to_string()),
        EnvError::NotReset
        | EnvError::EpisodeOver
        | EnvError::Sim(_)
        | EnvError::Walker(_)
        | EnvError::NoDecisionPoint(_) => PyRuntimeError::new_err(e.to_string()),
    }
}

/// Runs `f`, turning a panic into a `RuntimeError`.
fn guarded<T>(f: impl FnOnce() -> Result<T, EnvError>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r.map_err(env_err),
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(PyRuntimeError::new_err(format!(
                "internal error in steplearn (please report; call reset): {message}"
            )))
        }
    }
}

/// The fields of [`PushProtocol::Random`], for a `pushes` dictionary (defaults: experiment C).
#[derive(Serialize, Deserialize)]
struct RandomPushes {
    impulse: (f64, f64),
    gap_s: (f64, f64),
    settle_s: f64,
    direction: [f64; 3],
}

/// `pushes`: `"experiment-c"`, `"none"`, or a dictionary of the random protocol's fields.
fn pushes(obj: Option<&Bound<'_, PyAny>>) -> PyResult<PushProtocol> {
    let Some(obj) = obj else {
        return Ok(PushProtocol::default());
    };
    if let Ok(s) = obj.cast::<PyString>() {
        return match s.to_cow()?.as_ref() {
            "experiment-c" => Ok(PushProtocol::default()),
            "none" => Ok(PushProtocol::None),
            other => Err(PyValueError::new_err(format!(
                "pushes must be 'experiment-c', 'none' or a dict of the random protocol's \
                 fields (impulse, gap_s, settle_s, direction), got '{other}'"
            ))),
        };
    }
    let Ok(d) = obj.cast::<PyDict>() else {
        return Err(PyTypeError::new_err(format!(
            "pushes must be a str or a dict, got {}",
            obj.get_type().name()?
        )));
    };
    let PushProtocol::Random {
        impulse,
        gap_s,
        settle_s,
        direction,
    } = PushProtocol::default()
    else {
        unreachable!("the default protocol is experiment C's random pushes")
    };
    let defaults = RandomPushes {
        impulse,
        gap_s,
        settle_s,
        direction,
    };
    let r: RandomPushes = settings::apply(&defaults, Some(d), &[], |_| Ok(()))
        .map_err(|e| prefixed(obj.py(), e, "pushes"))?;
    Ok(PushProtocol::Random {
        impulse: r.impulse,
        gap_s: r.gap_s,
        settle_s: r.settle_s,
        direction: r.direction,
    })
}

/// `e` with `what: ` before its message, same type.
fn prefixed(py: Python<'_>, e: PyErr, what: &str) -> PyErr {
    let message = format!("{what}: {}", e.value(py));
    if e.is_instance_of::<PyTypeError>(py) {
        PyTypeError::new_err(message)
    } else {
        PyValueError::new_err(message)
    }
}

/// `learn`: a comma-separated string (`"step-x,step-y"`) or a sequence of names.
fn learn_set(obj: Option<&Bound<'_, PyAny>>) -> PyResult<LearnSet> {
    let Some(obj) = obj else {
        return Ok(LearnSet::default());
    };
    let parsed = if let Ok(s) = obj.cast::<PyString>() {
        s.to_cow()?.parse::<LearnSet>()
    } else if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let names: Vec<String> = obj.extract().map_err(|_| {
            PyTypeError::new_err("learn must be a str or a sequence of str (step parameter names)")
        })?;
        LearnSet::try_from(names)
    } else {
        return Err(PyTypeError::new_err(format!(
            "learn must be a str or a list of str, got {}",
            obj.get_type().name()?
        )));
    };
    parsed.map_err(|e| PyValueError::new_err(format!("learn: {e}")))
}

/// A serde value as Python objects (dicts, lists, floats, ints, str, None).
fn to_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) if !n.is_f64() => u.into_pyobject(py)?.into_any(),
            (_, Some(i)) if !n.is_f64() => i.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(a) => {
            let items = a
                .iter()
                .map(|x| to_py(py, x))
                .collect::<PyResult<Vec<_>>>()?;
            PyList::new(py, items)?.into_any()
        }
        Value::Object(m) => {
            let d = PyDict::new(py);
            for (k, x) in m {
                d.set_item(k, to_py(py, x)?)?;
            }
            d.into_any()
        }
    })
}

fn json<T: Serialize>(v: &T) -> PyResult<Value> {
    serde_json::to_value(v).map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))
}

/// Bounds `[[lo, hi], ...]` as an `(n, 2)` float64 array.
fn bounds_array<'py>(py: Python<'py>, b: &[[f64; 2]]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows: Vec<Vec<f64>> = b.iter().map(|r| r.to_vec()).collect();
    Ok(PyArray2::from_vec2(py, &rows)?)
}

/// The walker as a footstep environment: `reset(seed)` walks to the first decision point,
/// `step(action)` takes one footstep with the action's offsets added to the Capture Step
/// controller's step. The Gymnasium class is `steplearn.gym.FootstepEnv`.
#[pyclass(module = "steplearn")]
pub(crate) struct FootstepEnv {
    env: RustEnv,
}

#[pymethods]
impl FootstepEnv {
    /// `robot`: a URDF path or None (the built-in humanoid); `pushes`: "experiment-c",
    /// "none" or a dict of the random protocol's fields; `learn`: the learned step parameters
    /// (one action entry each); `max_footsteps`; `reference`: the sagittal reference step (m,
    /// the paper robot's); `reward`: a dict of the pendulum-cart `p_theta`, `p_f`; `settings`:
    /// a dict of top-level fields of the experiments' `Settings` (sim, walker, ...).
    #[new]
    #[allow(clippy::too_many_arguments)] // one per Python keyword
    #[pyo3(signature = (robot=None, pushes=None, learn=None, max_footsteps=200, reference=0.0, reward=None, settings=None))]
    fn new(
        py: Python<'_>,
        robot: Option<PathBuf>,
        pushes: Option<&Bound<'_, PyAny>>,
        learn: Option<&Bound<'_, PyAny>>,
        max_footsteps: i64,
        reference: f64,
        reward: Option<&Bound<'_, PyDict>>,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        if max_footsteps < 1 {
            return Err(PyValueError::new_err(format!(
                "invalid footstep environment config: max_footsteps must be at least 1, got \
                 {max_footsteps}"
            )));
        }
        let reward = match reward {
            None => PendulumCart::default(),
            Some(d) => settings::apply(&PendulumCart::default(), Some(d), &[], |_| Ok(()))
                .map_err(|e| prefixed(py, e, "reward"))?,
        };
        let settings = match settings {
            None => Settings::default(),
            Some(d) => settings::apply(&Settings::default(), Some(d), &[], |_| Ok(()))
                .map_err(|e| prefixed(py, e, "settings"))?,
        };
        let config = FootstepEnvConfig {
            settings,
            robot,
            pushes: self::pushes(pushes)?,
            learn: learn_set(learn)?,
            max_footsteps: max_footsteps as usize,
            reference_m: reference,
            reward,
        };
        let env = py.detach(|| guarded(|| RustEnv::new(config)))?;
        Ok(FootstepEnv { env })
    }

    /// Starts an episode with the pushes drawn from `seed` (an int in [0, 2**64)); returns
    /// the observation at the first decision point.
    fn reset<'py>(
        &mut self,
        py: Python<'py>,
        seed: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        if !seed.is_instance_of::<PyInt>() {
            return Err(PyTypeError::new_err(format!(
                "seed must be an int, got {}",
                seed.get_type().name()?
            )));
        }
        let seed: u64 = seed.extract().map_err(|_| {
            PyValueError::new_err(format!("seed must be in [0, 2**64), got {seed}"))
        })?;
        let env = &mut self.env;
        let obs = py.detach(|| guarded(|| env.reset(seed)))?;
        Ok(PyArray1::from_vec(py, obs.values()))
    }

    /// One footstep with `action` (a 1-D sequence, one offset per learned parameter, within
    /// `action_bounds`): `(observation, reward, terminated, truncated, info)`. A refused
    /// action raises ValueError and changes nothing.
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        action: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let action = arrays::vector(action, "action")?;
        let env = &mut self.env;
        let r = py.detach(|| guarded(|| env.step(&action)))?;
        let info = to_py(py, &json(&r.info)?)?;
        PyTuple::new(
            py,
            [
                PyArray1::from_vec(py, r.observation.values()).into_any(),
                r.reward.into_pyobject(py)?.into_any(),
                r.terminated.into_pyobject(py)?.to_owned().into_any(),
                r.truncated.into_pyobject(py)?.to_owned().into_any(),
                info,
            ],
        )
    }

    /// The learned parameters, in action order.
    #[getter]
    fn action_names(&self) -> Vec<&'static str> {
        self.env.action_names()
    }

    /// The observation's entry names (`sagittal.theta_e`, ...).
    #[getter]
    fn observation_names(&self) -> Vec<String> {
        self.env.observation_names()
    }

    /// `(n_action, 2)`: `[lo, hi]` of each action entry, in the robot's units.
    #[getter]
    fn action_bounds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        bounds_array(py, &self.env.action_bounds())
    }

    /// `(n_observation, 2)`: unbounded (a fall can show any value).
    #[getter]
    fn observation_bounds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        bounds_array(py, &self.env.observation_bounds())
    }

    /// Footsteps per episode before truncation.
    #[getter]
    fn max_footsteps(&self) -> usize {
        self.env.config().max_footsteps
    }

    /// Time since the reset (s).
    #[getter]
    fn time(&self) -> f64 {
        self.env.time()
    }

    /// The robot's length factor against the paper's robot (1 for the built-in humanoid).
    #[getter]
    fn length_scale(&self) -> f64 {
        self.env.scale().length
    }

    /// The whole configuration, as the Rust crate's serde form (a dict).
    #[getter]
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &json(self.env.config())?)
    }

    fn __repr__(&self) -> String {
        let c = self.env.config();
        format!(
            "FootstepEnv(robot={}, learn={:?}, max_footsteps={})",
            c.robot.as_ref().map_or("None".to_string(), |p| format!(
                "{:?}",
                p.display().to_string()
            )),
            c.learn.to_string(),
            c.max_footsteps
        )
    }
}
