//! The walker as a footstep-level reinforcement-learning environment, Gymnasium style: one
//! [`FootstepEnv::step`] is one footstep, the action is the offset(s) added to the Capture Step
//! controller's step, and the reward is derived from the paper's pendulum-cart cost.
//!
//! An episode starts from the standing robot ([`FootstepEnv::reset`]): the Capture Step
//! walker (the *model*) walks with zero offsets until the generator has faded in and the
//! learned offsets are fully engaged, and stops at the next touch-down, the first decision
//! point. From there each step:
//!
//! 1. holds the action (one offset per learned step parameter, in the robot's own units) over
//!    the whole next step, as a [`FootstepPolicy`] that returns it as its offsets every tick;
//! 2. runs control ticks, delivering the pushes of the protocol when they are due, until the
//!    next touch-down (the next decision point), a fall (`terminated`), or the footstep limit
//!    (`truncated`).
//!
//! The decision point is the touch-down tick itself: the walker is cloned before every tick,
//! and a tick that detects a touch-down is undone and run again once the action for the new
//! step is known, so the action acts from the touch-down tick on, exactly as a learner's
//! offset does, and the observation is what the learner's query at that tick reads.
//!
//! **Observation**, per plane in which a learned parameter acts (sagittal first, then
//! frontal), four entries: `theta_E` (rad), `theta_E_dot` (rad/s) and the plane's reference
//! `F_R` (m) as the learner's input at the decision point, and the error `F_E` (m) of the step
//! that just ended. In the frontal plane these are the lean towards the swing leg, its rate,
//! `W_R - 2 delta` and `W - W_R` (see [`crate::control::Walker`]). `F_E` is there
//! because the reward depends on it and the input alone does not show it.
//!
//! **Reward**, at a touch-down: `-min(sum over the observed planes of G^2, 1)`, with
//! `G = theta_E - p_theta tanh(p_F F_E)` the pendulum-cart error of eq. (5) (the quantity the
//! learning rule drives to zero; `e = h G` is the capture-point error), `F_E` in the paper
//! robot's units (divided by the robot's length factor, as the learner sees it). At a fall the
//! reward is `-(1 + the footsteps left before the limit)`: at least the cost of walking every
//! remaining step at the worst clipped cost, so a fall never pays.
//!
//! **Actions** are checked before anything changes: wrong length, NaN or infinity, or an
//! offset outside [`FootstepEnv::action_bounds`] is an [`EnvError`] and the environment is
//! left as it was. Within the bounds the walker still clamps the step to its range, as it
//! does a learner's offset; [`StepInfo::reach`] says which offsets could change the step.
//!
//! The loop is written here rather than shared with [`crate::experiments::trial::run_trial`]:
//! a trial runs to its end, resets the robot after falls and delays pushes around them, while
//! an environment must stop at every touch-down and hand control back; sharing the loop would
//! mean turning `run_trial` into a resumable state machine, whose stored results the archive
//! tests pin bit for bit. What it shares: the simulator, the walker, the robot loading and
//! scaling ([`use_robot`], [`WalkerConfig::for_robot`]), experiment C's push protocol and its
//! draw order ([`PushPlan::draw`]), and the pendulum-cart rule.

use std::path::PathBuf;

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::config::ConfigError;
use crate::control::LearnerError;
use crate::control::LearnerInput;
use crate::control::motion::ANKLE_LIMIT;
use crate::control::{FootstepPolicy, StepReports};
use crate::control::{LearnSet, PerParameter, Plane, StepParameter};
use crate::control::{Walker, WalkerConfig, WalkerError, WalkerMode};
use crate::experiments::protocol::{Protocol, ProtocolTables};
use crate::experiments::robot_setup::use_robot;
use crate::experiments::settings::Settings;
use crate::experiments::stability::StabilityProtocol;
use crate::robot::RobotError;
use crate::robot::Scale;
use crate::robot::Sensors;
use crate::rules::{LearningRule, PendulumCart, StepOutcome};
use crate::sim::{Fall, Humanoid, SimError};

#[cfg(doc)]
use crate::experiments::schedule::PushPlan;

/// Why the environment refused a call or could not go on.
#[derive(Debug, Error)]
pub enum EnvError {
    /// `step` before the first `reset`.
    #[error("step called before reset")]
    NotReset,
    /// `step` after the episode ended (terminated or truncated).
    #[error("the episode has ended: call reset")]
    EpisodeOver,
    /// The action has the wrong number of entries.
    #[error("action has {got} entries, expected {expected} (one per learned parameter: {names})")]
    ActionLength {
        /// Entries expected.
        expected: usize,
        /// Entries given.
        got: usize,
        /// The learned parameters, in action order.
        names: String,
    },
    /// An action entry is NaN or infinite.
    #[error("action[{index}] ({name}) is not finite: {value}")]
    ActionNotFinite {
        /// Its index.
        index: usize,
        /// Its step parameter.
        name: &'static str,
        /// The value.
        value: f64,
    },
    /// An action entry is outside [`FootstepEnv::action_bounds`].
    #[error("action[{index}] ({name}) = {value} is outside [{lo}, {hi}]")]
    ActionOutOfRange {
        /// Its index.
        index: usize,
        /// Its step parameter.
        name: &'static str,
        /// The value.
        value: f64,
        /// The lower bound.
        lo: f64,
        /// The upper bound.
        hi: f64,
    },
    /// The environment's configuration is invalid.
    #[error("invalid footstep environment config: {0}")]
    Config(#[from] ConfigError),
    /// The robot file could not be used.
    #[error("robot: {0}")]
    Robot(#[from] RobotError),
    /// The simulator failed; the episode is over.
    #[error("simulation: {0}")]
    Sim(#[from] SimError),
    /// The walker failed; the episode is over.
    #[error("walker: {0}")]
    Walker(#[from] WalkerError),
    /// The reset robot fell or did not reach a touch-down with the learner engaged.
    #[error("no first decision point after reset: {0}")]
    NoDecisionPoint(String),
}

/// The pushes of an episode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PushProtocol {
    /// No pushes.
    None,
    /// Experiment C's random forward pushes: after `settle_s`, one push every gap uniform in
    /// `gap_s`, of impulse uniform in `impulse`, drawn from the reset's seed in the order
    /// experiment C draws them. The values are the paper robot's; for another robot the
    /// impulse and the gaps are scaled as experiment C's protocol is ([`use_robot`]).
    Random {
        /// Impulse range (N s).
        impulse: (f64, f64),
        /// Gap between pushes (s).
        gap_s: (f64, f64),
        /// Time before the first gap (s), unscaled as in experiment C.
        settle_s: f64,
        /// Unit push direction, world frame.
        direction: [f64; 3],
    },
}

impl Default for PushProtocol {
    /// Experiment C's protocol ([`StabilityProtocol::default`], settled 3 s).
    fn default() -> Self {
        let c = StabilityProtocol::default();
        PushProtocol::Random {
            impulse: c.impulse,
            gap_s: c.gap_s,
            settle_s: STABILITY_SETTLE_S,
            direction: c.direction,
        }
    }
}

/// Experiment C's time before its first gap (s).
const STABILITY_SETTLE_S: f64 = 3.0;

/// Everything that configures a [`FootstepEnv`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FootstepEnvConfig {
    /// The robot, physics and walker (the walker runs in Capture Step mode whatever its mode).
    pub settings: Settings,
    /// A URDF robot instead of the built-in humanoid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot: Option<PathBuf>,
    /// The pushes.
    pub pushes: PushProtocol,
    /// The step parameters the action sets, one action entry each, in the order of
    /// [`StepParameter::ALL`].
    pub learn: LearnSet,
    /// Footsteps per episode before it is truncated (>= 1).
    pub max_footsteps: usize,
    /// The sagittal reference step F_R (m, the paper robot's; scaled for another robot).
    /// Experiment C walks in place (0).
    pub reference_m: f64,
    /// The pendulum-cart parameters of the reward.
    pub reward: PendulumCart,
}

impl Default for FootstepEnvConfig {
    fn default() -> Self {
        FootstepEnvConfig {
            settings: Settings::default(),
            robot: None,
            pushes: PushProtocol::default(),
            learn: LearnSet::default(),
            max_footsteps: 200,
            reference_m: 0.0,
            reward: PendulumCart::default(),
        }
    }
}

impl FootstepEnvConfig {
    /// Checks every value; errors name the field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.settings.validate()?;
        crate::config::ensure(self.max_footsteps >= 1, "max_footsteps", || {
            "must be at least 1".to_string()
        })?;
        crate::config::ensure(self.reference_m.is_finite(), "reference_m", || {
            format!("must be finite, got {}", self.reference_m)
        })?;
        let PendulumCart { p_theta, p_f } = self.reward;
        crate::config::non_negative("reward.p_theta", p_theta)?;
        crate::config::non_negative("reward.p_f", p_f)?;
        if let Some(c) = self.stability() {
            c.validate().map_err(|e| e.within("pushes"))?;
            crate::config::non_negative("pushes.settle_s", self.settle_s())?;
        }
        Ok(())
    }

    /// The random pushes as experiment C's protocol (one push: only its ranges matter).
    fn stability(&self) -> Option<StabilityProtocol> {
        match self.pushes {
            PushProtocol::None => None,
            PushProtocol::Random {
                impulse,
                gap_s,
                direction,
                ..
            } => Some(StabilityProtocol {
                pushes: 1,
                impulse,
                gap_s,
                direction,
            }),
        }
    }

    fn settle_s(&self) -> f64 {
        match self.pushes {
            PushProtocol::None => 0.0,
            PushProtocol::Random { settle_s, .. } => settle_s,
        }
    }
}

/// One plane's entries of an [`Observation`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PlaneObservation {
    /// theta_E (rad): the trunk's deviation (frontal: the lean towards the swing leg).
    pub theta_e: f64,
    /// Its rate (rad/s).
    pub theta_e_dot: f64,
    /// The plane's reference F_R (m; frontal: `W_R - 2 delta`).
    pub f_r: f64,
    /// The error F_E of the step that just ended (m; frontal: `W - W_R`); at a fall, that of
    /// the step in progress.
    pub f_e: f64,
}

/// What the environment shows at a decision point (or at a fall).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Observation {
    /// The sagittal plane's entries, if a learned parameter acts in it.
    pub sagittal: Option<PlaneObservation>,
    /// The frontal plane's entries, if a learned parameter acts in it.
    pub frontal: Option<PlaneObservation>,
}

impl Observation {
    /// The entries in [`FootstepEnv::observation_names`] order.
    pub fn values(&self) -> Vec<f64> {
        [self.sagittal, self.frontal]
            .into_iter()
            .flatten()
            .flat_map(|p| [p.theta_e, p.theta_e_dot, p.f_r, p.f_e])
            .collect()
    }
}

/// A push delivered during a step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DeliveredPush {
    /// When (s since the reset).
    pub time: f64,
    /// Its impulse (N s).
    pub impulse: f64,
}

/// What else a step measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepInfo {
    /// Time since the reset at the step's end (s).
    pub time_s: f64,
    /// How long the step lasted (s).
    pub step_duration_s: f64,
    /// Footsteps taken this episode, this one included.
    pub footsteps: usize,
    /// Pushes delivered this episode so far.
    pub pushes_delivered: usize,
    /// The pushes delivered during this step.
    pub pushes: Vec<DeliveredPush>,
    /// The pendulum-cart error G per observed plane (sagittal first; rad).
    pub g: Vec<f64>,
    /// The offsets the walker applied at the step's first tick, per action entry.
    pub applied_offsets: Vec<f64>,
    /// The offsets `[lo, hi]` that could change the step at its first tick, per action entry:
    /// beyond them the walker clamps the step.
    pub reach: Vec<[f64; 2]>,
    /// The fall that ended the episode, if any.
    pub fall: Option<Fall>,
    /// The walker did not touch down within the time limit of a step; the episode is
    /// truncated.
    pub stalled: bool,
}

/// What [`FootstepEnv::step`] returns.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepResult {
    /// The observation at the next decision point (or at the fall).
    pub observation: Observation,
    /// The reward (see the module documentation).
    pub reward: f64,
    /// The robot fell.
    pub terminated: bool,
    /// The footstep limit was reached (or the walker stalled).
    pub truncated: bool,
    /// What else the step measured.
    pub info: StepInfo,
}

/// The policy that holds the action: it returns it as its offsets and records what the walker
/// showed it.
#[derive(Debug, Clone, Copy)]
struct HeldAction {
    learn: LearnSet,
    offsets: PerParameter<f64>,
    inputs: Option<PerParameter<LearnerInput>>,
    reach: Option<PerParameter<[f64; 2]>>,
}

impl FootstepPolicy for HeldAction {
    fn learns(&self) -> LearnSet {
        self.learn
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        self.inputs = Some(*inputs);
        Ok(self.offsets)
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        self.reach = Some(*reach);
        Ok(())
    }
    fn touch_down(&mut self, _: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        Ok(StepReports::default())
    }
    fn fall(&mut self, _: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        Ok(StepReports::default())
    }
    fn discard_step(&mut self) {}
}

/// A touch-down detected and undone: the walker as it was before that tick, and the tick's
/// sensors.
#[derive(Debug, Clone)]
struct Decision {
    walker: Walker,
    sensors: Sensors,
}

/// The random pushes of [`PushProtocol::Random`], scaled for the robot.
#[derive(Debug, Clone, Copy)]
struct RandomPushes {
    impulse: (f64, f64),
    gap_s: (f64, f64),
    settle_s: f64,
    direction: [f64; 3],
}

/// Where an episode stands.
#[derive(Debug, Clone)]
enum Phase {
    NotReset,
    AtDecision(Box<Decision>),
    Over,
}

/// The walker as an environment: see the module documentation.
pub struct FootstepEnv {
    config: FootstepEnvConfig,
    robot: Humanoid,
    walker_config: WalkerConfig,
    scale: Scale,
    /// The random pushes, scaled for the robot.
    pushes: Option<RandomPushes>,
    reference: f64,
    planes: Vec<Plane>,
    parameters: Vec<StepParameter>,
    bounds: Vec<[f64; 2]>,
    max_step_s: f64,
    max_warmup_s: f64,
    phase: Phase,
    walker: Walker,
    rng: ChaCha8Rng,
    next_push: Option<(f64, f64)>,
    pushes_delivered: usize,
    footsteps: usize,
    last_touch_down: f64,
}

impl std::fmt::Debug for FootstepEnv {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FootstepEnv")
            .field("config", &self.config)
            .field("footsteps", &self.footsteps)
            .field("time", &self.robot.time())
            .finish_non_exhaustive()
    }
}

impl FootstepEnv {
    /// An environment for `config`: the robot is loaded and checked once; call
    /// [`Self::reset`] to start an episode.
    pub fn new(config: FootstepEnvConfig) -> Result<Self, EnvError> {
        config.validate()?;
        let mut settings = config.settings.clone();
        let mut protocols = ProtocolTables::new();
        let stability = config.stability();
        if let Some(c) = &stability {
            protocols.set(crate::experiments::stability::NAME, c)?;
        }
        if let Some(path) = &config.robot {
            use_robot(path, None, &mut settings, &mut protocols)?;
        }
        let pushes = match stability {
            None => None,
            Some(_) => {
                let c: StabilityProtocol = protocols.get(crate::experiments::stability::NAME)?;
                Some(RandomPushes {
                    impulse: c.impulse,
                    gap_s: c.gap_s,
                    settle_s: config.settle_s(),
                    direction: c.direction,
                })
            }
        };
        let robot = Humanoid::new(settings.sim.clone())?;
        let scale = robot.scale();
        let walker = WalkerConfig {
            mode: WalkerMode::CaptureStep,
            ..settings.walker
        };
        let walker_config = if scale.is_one() {
            walker
        } else {
            walker.for_robot(&scale)
        };
        let walker = Walker::new(walker_config, robot.robot().leg_geometry())?;
        let parameters: Vec<StepParameter> = config.learn.iter().collect();
        let planes: Vec<Plane> = [Plane::Sagittal, Plane::Frontal]
            .into_iter()
            .filter(|pl| parameters.iter().any(|p| p.default_plane() == *pl))
            .collect();
        let m = &walker_config.motion;
        let cs = &walker_config.capture_step;
        let bounds = parameters
            .iter()
            .map(|p| {
                let half = match p {
                    StepParameter::StepX => m.step_x_range[1] - m.step_x_range[0],
                    StepParameter::StepY => m.step_y_range[1] - m.step_y_range[0],
                    StepParameter::StepTime => cs.max_step_time,
                    StepParameter::AnklePitch | StepParameter::AnkleRoll => ANKLE_LIMIT,
                };
                [-half, half]
            })
            .collect();
        let max_step_s = 4.0 * cs.max_step_time;
        let max_warmup_s = walker_config.start_ramp_s + 2.0 * m.fade_in + max_step_s;
        Ok(FootstepEnv {
            reference: scale.length(config.reference_m),
            config,
            robot,
            walker_config,
            scale,
            pushes,
            planes,
            parameters,
            bounds,
            max_step_s,
            max_warmup_s,
            phase: Phase::NotReset,
            walker,
            rng: ChaCha8Rng::seed_from_u64(0),
            next_push: None,
            pushes_delivered: 0,
            footsteps: 0,
            last_touch_down: 0.0,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &FootstepEnvConfig {
        &self.config
    }

    /// The robot's factors against the paper's robot.
    pub fn scale(&self) -> Scale {
        self.scale
    }

    /// The walker's settings (scaled for the robot).
    pub fn walker_config(&self) -> &WalkerConfig {
        &self.walker_config
    }

    /// Entries in an action: one per learned parameter.
    pub fn action_len(&self) -> usize {
        self.parameters.len()
    }

    /// The learned parameters' names, in action order.
    pub fn action_names(&self) -> Vec<&'static str> {
        self.parameters.iter().map(|p| p.name()).collect()
    }

    /// The range `[lo, hi]` of each action entry, in the robot's units (m for `step-x` and
    /// `step-y`, s for `step-time`, rad for the soles): the width of the walker's step range
    /// (`step-x`, `step-y`), the controller's longest step time (`step-time`), the generator's
    /// sole limit (`ankle-pitch`, `ankle-roll`), either way. No offset beyond them could
    /// change the step more than the bound does.
    pub fn action_bounds(&self) -> Vec<[f64; 2]> {
        self.bounds.clone()
    }

    /// Entries in an observation: four per observed plane.
    pub fn observation_len(&self) -> usize {
        4 * self.planes.len()
    }

    /// The observation's entry names, in [`Observation::values`] order.
    pub fn observation_names(&self) -> Vec<String> {
        self.planes
            .iter()
            .flat_map(|pl| {
                let p = match pl {
                    Plane::Sagittal => "sagittal",
                    Plane::Frontal => "frontal",
                };
                ["theta_e", "theta_e_dot", "f_r", "f_e"].map(|n| format!("{p}.{n}"))
            })
            .collect()
    }

    /// The range of each observation entry: unbounded (a fall can show any value).
    pub fn observation_bounds(&self) -> Vec<[f64; 2]> {
        vec![[f64::NEG_INFINITY, f64::INFINITY]; self.observation_len()]
    }

    /// Time since the reset (s).
    pub fn time(&self) -> f64 {
        self.robot.time()
    }

    /// Starts an episode: the robot standing, a fresh walker, the pushes drawn from `seed`;
    /// walks with zero offsets to the first decision point.
    pub fn reset(&mut self, seed: u64) -> Result<Observation, EnvError> {
        self.phase = Phase::Over;
        self.robot.reset();
        self.walker = Walker::new(self.walker_config, self.robot.robot().leg_geometry())?;
        self.rng = ChaCha8Rng::seed_from_u64(seed);
        self.next_push = None;
        self.draw_push(self.pushes.map_or(0.0, |p| p.settle_s));
        self.pushes_delivered = 0;
        self.footsteps = 0;
        let mut policy = self.held(&vec![0.0; self.action_len()]);
        let fade_in = self.walker.generator().config().timing().fade_in;
        loop {
            let sensors = self.robot.sensors();
            if sensors.time > self.max_warmup_s {
                return Err(EnvError::NoDecisionPoint(format!(
                    "no touch-down with the offsets engaged within {:.3} s",
                    self.max_warmup_s
                )));
            }
            let before = self.walker.clone();
            policy.inputs = None;
            let tick = self
                .walker
                .tick_2d(&sensors, [self.reference, 0.0], Some(&mut policy))?;
            if tick.step.is_some() && before.generator().fade_after(fade_in) >= 1.0 {
                let (Some(inputs), Some(step), Some(lateral)) =
                    (policy.inputs, tick.step, tick.lateral_step)
                else {
                    return Err(EnvError::NoDecisionPoint(
                        "the walker did not query its policy at the touch-down".into(),
                    ));
                };
                self.walker = before;
                self.phase = Phase::AtDecision(Box::new(Decision {
                    walker: self.walker.clone(),
                    sensors,
                }));
                self.last_touch_down = sensors.time;
                return Ok(self.observation(&inputs, &PerParameter::from_planes(step, lateral)));
            }
            self.deliver_push(sensors.time, &mut Vec::new())?;
            self.robot.step(&tick.targets)?;
            if let Some(fall) = self.robot.fall() {
                return Err(EnvError::NoDecisionPoint(format!(
                    "the robot fell at {:.3} s ({:?})",
                    fall.time, fall.trigger
                )));
            }
        }
    }

    /// One footstep with `action` (see the module documentation). A refused action leaves
    /// the environment as it was; a simulator or walker error ends the episode.
    pub fn step(&mut self, action: &[f64]) -> Result<StepResult, EnvError> {
        let decision = match &self.phase {
            Phase::NotReset => return Err(EnvError::NotReset),
            Phase::Over => return Err(EnvError::EpisodeOver),
            Phase::AtDecision(d) => d.as_ref().clone(),
        };
        self.check(action)?;
        self.phase = Phase::Over;
        let mut policy = self.held(action);
        let mut pushes = Vec::new();
        // The touch-down tick, again, with the new step's action.
        self.walker = decision.walker;
        let mut sensors = decision.sensors;
        let tick = self
            .walker
            .tick_2d(&sensors, [self.reference, 0.0], Some(&mut policy))?;
        let applied: Vec<f64> = self.parameters.iter().map(|p| tick.offsets[*p]).collect();
        let reach = policy.reach.map_or_else(Vec::new, |r| {
            self.parameters.iter().map(|p| r[*p]).collect()
        });
        let mut last = (tick.estimate, tick.f_r);
        let mut targets = tick.targets;
        self.footsteps += 1;
        let start = self.last_touch_down;
        let info = |env: &Self, pushes: Vec<DeliveredPush>, g, fall, stalled| StepInfo {
            time_s: env.robot.time(),
            step_duration_s: env.robot.time() - start,
            footsteps: env.footsteps,
            pushes_delivered: env.pushes_delivered,
            pushes,
            g,
            applied_offsets: applied.clone(),
            reach: reach.clone(),
            fall,
            stalled,
        };
        loop {
            self.deliver_push(sensors.time, &mut pushes)?;
            self.robot.step(&targets)?;
            if let Some(fall) = self.robot.fall() {
                let outcomes = self.walker.outcomes_at(&last.0, last.1);
                let inputs = outcomes.map(|o| LearnerInput::new(o.theta_e, o.theta_e_dot, o.f_r));
                let observation = self.observation(&inputs, &outcomes);
                let left = self.config.max_footsteps - self.footsteps;
                return Ok(StepResult {
                    observation,
                    reward: -(1.0 + left as f64),
                    terminated: true,
                    truncated: false,
                    info: info(self, pushes, self.g(&outcomes), Some(fall), false),
                });
            }
            sensors = self.robot.sensors();
            if sensors.time - start > self.max_step_s {
                let outcomes = self.walker.outcomes_at(&last.0, last.1);
                let inputs = outcomes.map(|o| LearnerInput::new(o.theta_e, o.theta_e_dot, o.f_r));
                // As the worst touch-down's reward.
                return Ok(StepResult {
                    observation: self.observation(&inputs, &outcomes),
                    reward: -1.0,
                    terminated: false,
                    truncated: true,
                    info: info(self, pushes, self.g(&outcomes), None, true),
                });
            }
            let before = self.walker.clone();
            policy.inputs = None;
            let tick = self
                .walker
                .tick_2d(&sensors, [self.reference, 0.0], Some(&mut policy))?;
            if let (Some(step), Some(lateral), Some(inputs)) =
                (tick.step, tick.lateral_step, policy.inputs)
            {
                let outcomes = PerParameter::from_planes(step, lateral);
                self.walker = before;
                self.last_touch_down = sensors.time;
                let g = self.g(&outcomes);
                let reward = -g.iter().map(|g| g * g).sum::<f64>().min(1.0);
                let truncated = self.footsteps >= self.config.max_footsteps;
                if !truncated {
                    self.phase = Phase::AtDecision(Box::new(Decision {
                        walker: self.walker.clone(),
                        sensors,
                    }));
                }
                return Ok(StepResult {
                    observation: self.observation(&inputs, &outcomes),
                    reward,
                    terminated: false,
                    truncated,
                    info: info(self, pushes, g, None, false),
                });
            }
            last = (tick.estimate, tick.f_r);
            targets = tick.targets;
        }
    }

    /// Refuses an action of the wrong length, not finite, or out of bounds.
    fn check(&self, action: &[f64]) -> Result<(), EnvError> {
        if action.len() != self.action_len() {
            return Err(EnvError::ActionLength {
                expected: self.action_len(),
                got: action.len(),
                names: self.action_names().join(", "),
            });
        }
        for (index, ((&value, p), [lo, hi])) in action
            .iter()
            .zip(&self.parameters)
            .zip(&self.bounds)
            .enumerate()
        {
            if !value.is_finite() {
                return Err(EnvError::ActionNotFinite {
                    index,
                    name: p.name(),
                    value,
                });
            }
            if value < *lo || value > *hi {
                return Err(EnvError::ActionOutOfRange {
                    index,
                    name: p.name(),
                    value,
                    lo: *lo,
                    hi: *hi,
                });
            }
        }
        Ok(())
    }

    /// The policy holding `action` (checked).
    fn held(&self, action: &[f64]) -> HeldAction {
        let mut offsets = PerParameter::<f64>::default();
        for (p, a) in self.parameters.iter().zip(action) {
            offsets[*p] = *a;
        }
        HeldAction {
            learn: self.config.learn,
            offsets,
            inputs: None,
            reach: None,
        }
    }

    fn plane_outcome(&self, plane: Plane, outcomes: &PerParameter<StepOutcome>) -> StepOutcome {
        match plane {
            Plane::Sagittal => outcomes[StepParameter::StepX],
            Plane::Frontal => outcomes[StepParameter::StepY],
        }
    }

    fn observation(
        &self,
        inputs: &PerParameter<LearnerInput>,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Observation {
        let entry = |plane: Plane| {
            self.planes.contains(&plane).then(|| {
                let input = match plane {
                    Plane::Sagittal => inputs[StepParameter::StepX],
                    Plane::Frontal => inputs[StepParameter::StepY],
                };
                PlaneObservation {
                    theta_e: input.theta_e,
                    theta_e_dot: input.theta_e_dot,
                    f_r: input.f_r,
                    f_e: self.plane_outcome(plane, outcomes).f_e,
                }
            })
        };
        Observation {
            sagittal: entry(Plane::Sagittal),
            frontal: entry(Plane::Frontal),
        }
    }

    /// G per observed plane, F_E in the paper robot's units.
    fn g(&self, outcomes: &PerParameter<StepOutcome>) -> Vec<f64> {
        self.planes
            .iter()
            .map(|pl| {
                let o = self.plane_outcome(*pl, outcomes);
                self.config.reward.gradient(&StepOutcome {
                    f_e: o.f_e / self.scale.length,
                    ..o
                })
            })
            .collect()
    }

    /// Draws the next push after `after` (s), as [`PushPlan::draw`] does.
    fn draw_push(&mut self, after: f64) {
        self.next_push = self.pushes.map(|p| {
            let time = after + uniform(&mut self.rng, p.gap_s);
            (time, uniform(&mut self.rng, p.impulse))
        });
    }

    /// Delivers the next push if it is due at `t`.
    fn deliver_push(&mut self, t: f64, out: &mut Vec<DeliveredPush>) -> Result<(), EnvError> {
        if let (Some((time, impulse)), Some(p)) = (self.next_push, self.pushes)
            && t >= time
        {
            self.robot.push(p.direction.map(|d| d * impulse))?;
            self.pushes_delivered += 1;
            out.push(DeliveredPush { time: t, impulse });
            self.draw_push(time);
        }
        Ok(())
    }
}

/// As the push schedules draw: uniform in `[lo, hi)`, `lo` for an empty range.
fn uniform(rng: &mut ChaCha8Rng, (lo, hi): (f64, f64)) -> f64 {
    if hi > lo {
        rng.random_range(lo..hi)
    } else {
        lo
    }
}
