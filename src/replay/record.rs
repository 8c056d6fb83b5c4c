//! What a replay records of one walker on one push: frames of the simulator's ground truth and
//! of the walker's own quantities, subsampled in time, plus every touch-down and the fall.

use crate::control::StepParameter;
use crate::control::Tick;
use crate::experiments::trial::{FallRecord, Observer, PushRecord, StepRecord};
use crate::robot::Side;
use crate::robot::{Description, Geometry};
use crate::sim::GroundTruth;
use serde::{Deserialize, Serialize};

pub(crate) use crate::experiments::replay_plan::round;

fn round3(p: [f64; 3]) -> [f64; 3] {
    p.map(round)
}

/// One moment of a walker: where its bodies are and what its controller did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Frame {
    /// Trial time (s).
    pub t: f64,
    /// Centre of mass (world, m).
    pub com: [f64; 3],
    /// The instantaneous capture point on the ground, `com + v / omega` with
    /// `omega = sqrt(g / com height)` (world, m; z = 0).
    pub cp: [f64; 3],
    /// Stick figure: pelvis, neck, head centre, then per leg (left, right) hip, knee, ankle,
    /// heel, toe (world, m).
    pub pts: Vec<[f64; 3]>,
    /// The commanded footstep of the swing foot (world, m; z = 0), when the walker is
    /// stepping.
    pub cmd: Option<[f64; 3]>,
    /// The learned sagittal offset dF used this tick (m).
    pub d_f: f64,
    /// The learned lateral offset dW used this tick (m).
    pub d_w: f64,
    /// The learned step-time offset dT used this tick (s).
    pub d_t: f64,
    /// The learned pitch offset dA of the support sole used this tick (rad, toe down
    /// positive; left out when 0).
    #[serde(default, skip_serializing_if = "crate::config::is_zero")]
    pub d_a: f64,
    /// The learned roll offset dR of the support sole used this tick (rad, positive pressing
    /// its right edge; left out when 0).
    #[serde(default, skip_serializing_if = "crate::config::is_zero")]
    pub d_r: f64,
    /// Trunk deviation angle theta_E (rad, positive leaning forward).
    pub lean: f64,
    /// Every drawn link's frame `[x, y, z, qw, qx, qy, qz]`, in [`Walk::bodies`]' order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub links: Vec<[f64; 7]>,
}

/// A shape drawn for a link, in the link's frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DrawnShape {
    /// `box`, `sphere`, `capsule` or `cylinder` (capsules and cylinders along z).
    pub kind: String,
    /// A box's full extents; a sphere's `[r, 0, 0]`; a capsule's or cylinder's `[r, length, 0]`
    /// (length of the straight part) (m).
    pub size: [f64; 3],
    /// Centre in the link frame (m).
    pub pos: [f64; 3],
    /// Orientation in the link frame `[w, x, y, z]`.
    pub quat: [f64; 4],
}

/// The shapes drawn for each link of `robot` (the trunk, then the legs' links): its collision
/// shapes, or for a link without any a box of its mass and inertia; links lighter than 0.5% of
/// the robot without shapes (joint gimbals) are left undrawn.
pub fn drawn_bodies(robot: &Description) -> Vec<Vec<DrawnShape>> {
    let total = robot.mass();
    let links = std::iter::once(&robot.trunk).chain(robot.legs.iter().flat_map(|l| l.links.iter()));
    links
        .map(|link| {
            if link.shapes.is_empty() {
                if link.mass < 0.005 * total {
                    return Vec::new();
                }
                let [a, b, c] = link.inertia.principal;
                let side = |x: f64| (6.0 * x.max(0.0) / link.mass).sqrt();
                return vec![DrawnShape {
                    kind: "box".into(),
                    size: [side(b + c - a), side(a + c - b), side(a + b - c)],
                    pos: link.com,
                    quat: link.inertia.axes,
                }];
            }
            link.shapes
                .iter()
                .map(|s| {
                    let (kind, size) = match s.geometry {
                        Geometry::Box { half_extents: h } => ("box", h.map(|v| 2.0 * v)),
                        Geometry::Sphere { radius } => ("sphere", [radius, 0.0, 0.0]),
                        Geometry::Capsule {
                            half_height,
                            radius,
                        } => ("capsule", [radius, 2.0 * half_height, 0.0]),
                        Geometry::Cylinder {
                            half_height,
                            radius,
                        } => ("cylinder", [radius, 2.0 * half_height, 0.0]),
                    };
                    DrawnShape {
                        kind: kind.into(),
                        size: round3(size),
                        pos: round3(s.position),
                        quat: s.orientation.map(round),
                    }
                })
                .collect()
        })
        .collect()
}

/// A touch-down: where the step was commanded and where the foot landed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Touchdown {
    /// Trial time (s).
    pub t: f64,
    /// The command of the tick before the touch-down (world, m; z = 0), if there was one.
    pub cmd: Option<[f64; 3]>,
    /// The sole centre of the foot that landed (world, m).
    pub landed: [f64; 3],
}

/// One walker's recording of a push.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Walk {
    /// Which walker (`learned`, `no learning`, `model`, ...).
    pub name: String,
    /// The frames in time order.
    pub frames: Vec<Frame>,
    /// Touch-downs within the recorded span.
    pub steps: Vec<Touchdown>,
    /// When the push was delivered (trial time, s), if it was.
    pub push_time: Option<f64>,
    /// When the walker fell within the recorded span (trial time, s), if it did.
    pub fall_time: Option<f64>,
    /// Whether the walker fell within the push's window (the trial's own verdict).
    pub fell: bool,
    /// Falls in the whole trial.
    pub falls: usize,
    /// Touch-downs in the whole trial.
    pub trial_steps: usize,
    /// The robot's drawn links (trunk, then the legs'); each frame's `links` places them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<Vec<DrawnShape>>,
}

/// Records frames between `from` and `to` (trial time), one every `every` seconds, and the
/// touch-downs, push and fall in that span. The walker is not recorded after its first fall in
/// the span (the trial resets the robot there).
///
/// [`Recorder::around_push`] records instead around the K-th push of a trial with many pushes,
/// whose delivery time is known only once it happened (falls delay pushes).
///
/// [`Recorder`] is an [`Observer`] of [`run_trial`](crate::experiments::trial::run_trial): the
/// replay re-runs the experiment's own trial with it attached, so what it records is what the
/// trial produced. Every number is rounded to
/// [`DECIMALS`](crate::experiments::replay_plan::DECIMALS) decimals when it is recorded, so the
/// JSON a page embeds parses back to exactly the recorded values.
#[derive(Debug)]
pub struct Recorder {
    from: f64,
    to: f64,
    every: f64,
    /// Around-push mode: (the push to record, 1-based; seconds before it; seconds after it).
    target: Option<(usize, f64, f64)>,
    /// Pushes whose outcome came so far.
    pushes_seen: usize,
    next: f64,
    frames: Vec<Frame>,
    steps: Vec<Touchdown>,
    push: Option<PushRecord>,
    fall_time: Option<f64>,
    /// The tick waiting for its ground truth: (time, tick quantities).
    pending: Option<(f64, Pending)>,
    /// The world command of the last tick, for the touch-down that follows it.
    last_cmd: Option<[f64; 3]>,
    last_support: Option<Side>,
    falls: usize,
    trial_steps: usize,
    /// Gravity of the capture point drawn (m/s^2).
    gravity: f64,
    bodies: Vec<Vec<DrawnShape>>,
}

#[derive(Debug, Clone, Copy)]
struct Pending {
    step_x: f64,
    step_y: f64,
    stepping: bool,
    support: Side,
    touch_down: bool,
    d_f: f64,
    d_w: f64,
    d_t: f64,
    d_a: f64,
    d_r: f64,
    lean: f64,
}

fn yaw(q: [f64; 4]) -> f64 {
    let [w, x, y, z] = q;
    (2.0 * (w * z + x * y)).atan2(1.0 - 2.0 * (y * y + z * z))
}

fn side_index(side: Side) -> usize {
    match side {
        Side::Left => 0,
        Side::Right => 1,
    }
}

impl Recorder {
    /// A recorder of `[from, to]` (trial time, s), one frame every `every` seconds.
    pub fn new(from: f64, to: f64, every: f64) -> Self {
        Recorder {
            from,
            to,
            every,
            target: None,
            pushes_seen: 0,
            next: from,
            frames: Vec::new(),
            steps: Vec::new(),
            push: None,
            fall_time: None,
            pending: None,
            last_cmd: None,
            last_support: None,
            falls: 0,
            trial_steps: 0,
            gravity: crate::sim::SimConfig::default().gravity,
            bodies: Vec::new(),
        }
    }

    /// The same recorder for a trial of `sim`: the capture point with its gravity, and its
    /// robot's own links drawn.
    pub fn for_sim(self, sim: &crate::sim::SimConfig) -> Self {
        let robot = match &sim.robot {
            None => Some(sim.body.description()),
            Some(file) => file.load(&sim.body.servo_reference()).ok(),
        };
        Recorder {
            gravity: sim.gravity,
            bodies: robot.as_ref().map(drawn_bodies).unwrap_or_default(),
            ..self
        }
    }

    /// A recorder of the `push`-th push (1-based) of a trial: from `before` seconds before its
    /// delivery to `after` seconds after it (or to the walker's fall), one frame every `every`
    /// seconds. Until that push's outcome arrives it keeps only the last `before + after`
    /// seconds; falls before it are not recorded.
    pub fn around_push(push: usize, before: f64, after: f64, every: f64) -> Self {
        Recorder {
            target: Some((push, before, after)),
            ..Recorder::new(0.0, f64::INFINITY, every)
        }
    }

    /// Whether the recorded push is still to come (around-push mode).
    fn searching(&self) -> bool {
        self.target.is_some() && self.push.is_none()
    }

    fn recording(&self, t: f64) -> bool {
        t >= self.from && t <= self.to && self.fall_time.is_none()
    }

    /// Around-push mode, before the push: forget a fall of another push, and what is older
    /// than the span the push can need.
    fn forget_old(&mut self, t: f64) {
        let Some((_, before, after)) = self.target.filter(|_| self.push.is_none()) else {
            return;
        };
        if self.fall_time.take().is_some() {
            self.frames.clear();
            self.steps.clear();
        }
        let keep = t - before - after - self.every;
        if self.frames.first().is_some_and(|f| f.t < keep) {
            self.frames.retain(|f| f.t >= keep);
            self.steps.retain(|s| s.t >= keep);
        }
    }

    /// The recording, named `name`.
    pub fn finish(self, name: &str) -> Walk {
        Walk {
            name: name.to_string(),
            frames: self.frames,
            steps: self.steps,
            push_time: self.push.map(|p| round(p.time)),
            fall_time: self.fall_time,
            fell: self.push.is_none_or(|p| p.fell),
            falls: self.falls,
            trial_steps: self.trial_steps,
            bodies: self.bodies,
        }
    }
}

impl Observer for Recorder {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        let stepping = tick.decision.is_some() || tick.command.step_time > 0.0;
        self.pending = Some((
            time,
            Pending {
                step_x: tick.command.step_x,
                step_y: tick.command.step_y,
                stepping,
                support: tick.estimate.support,
                touch_down: tick.step.is_some(),
                d_f: tick.offsets[StepParameter::StepX],
                d_w: tick.offsets[StepParameter::StepY],
                d_t: tick.offsets[StepParameter::StepTime],
                d_a: tick.offsets[StepParameter::AnklePitch],
                d_r: tick.offsets[StepParameter::AnkleRoll],
                lean: tick.estimate.theta_e,
            },
        ));
    }

    fn on_step(&mut self, _step: &StepRecord) {
        self.trial_steps += 1;
    }

    fn on_push(&mut self, push: &PushRecord) {
        self.pushes_seen += 1;
        match self.target {
            None => self.push = Some(*push),
            Some((k, before, after)) if k == self.pushes_seen => {
                self.push = Some(*push);
                self.from = push.time - before;
                self.to = push.time + after;
                let from = round(self.from);
                self.frames.retain(|f| f.t >= from);
                self.steps.retain(|s| s.t >= from);
            }
            Some(_) => {}
        }
    }

    fn on_fall(&mut self, fall: &FallRecord) {
        self.falls += 1;
        if self.recording(fall.time) {
            self.fall_time = Some(round(fall.time));
        }
        self.last_cmd = None;
        self.last_support = None;
    }

    fn wants_truth(&self) -> bool {
        true
    }

    fn on_truth(&mut self, time: f64, truth: &GroundTruth) {
        // Ticks while getting up after a fall have no walker tick: nothing pending.
        let Some((t, p)) = self.pending.take().filter(|(t, _)| *t == time) else {
            return;
        };
        if self.searching() {
            self.forget_old(t);
        }
        let support = &truth.soles[side_index(p.support)];
        let (s, c) = yaw(support.orientation).sin_cos();
        let cmd = p.stepping.then(|| {
            [
                support.position[0] + c * p.step_x - s * p.step_y,
                support.position[1] + s * p.step_x + c * p.step_y,
                0.0,
            ]
        });
        if p.touch_down && self.recording(t) {
            // The foot that landed is the one that was swinging: not the previous support.
            let landed = match self.last_support {
                Some(prev) => 1 - side_index(prev),
                None => side_index(p.support),
            };
            self.steps.push(Touchdown {
                t: round(t),
                cmd: self.last_cmd.map(round3),
                landed: round3(truth.soles[landed].position),
            });
        }
        self.last_cmd = cmd;
        self.last_support = Some(p.support);
        if !self.recording(t) || t < self.next {
            return;
        }
        self.next += self.every * ((t - self.next) / self.every).floor().max(0.0) + self.every;
        let h = truth.com[2].max(1e-3);
        let omega = (self.gravity / h).sqrt();
        let cp = [
            truth.com[0] + truth.com_vel[0] / omega,
            truth.com[1] + truth.com_vel[1] / omega,
            0.0,
        ];
        let sk = &truth.skeleton;
        let mut pts = vec![sk.pelvis, sk.neck, sk.head];
        for leg in &sk.legs {
            pts.extend_from_slice(leg);
        }
        self.frames.push(Frame {
            t: round(t),
            com: round3(truth.com),
            cp: round3(cp),
            pts: pts.into_iter().map(round3).collect(),
            cmd: cmd.map(round3),
            d_f: round(p.d_f),
            d_w: round(p.d_w),
            d_t: round(p.d_t),
            d_a: round(p.d_a),
            d_r: round(p.d_r),
            lean: round(p.lean),
            links: if self.bodies.is_empty() {
                Vec::new()
            } else {
                truth
                    .links
                    .iter()
                    .map(|l| {
                        let [x, y, z] = round3(l.position);
                        let [w, i, j, k] = l.orientation.map(round);
                        [x, y, z, w, i, j, k]
                    })
                    .collect()
            },
        });
    }
}
