//! Runs on a robot from a URDF file: the file named in the settings (the walker and learner
//! follow it inside every trial, [`crate::control::for_robot`]) and the protocols rewritten
//! for its size, by dynamic similarity ([`Scale`]).
//!
//! A protocol key is scaled by its name: `impulse` as an impulse (`m sqrt(g l)`), keys ending
//! in `_s` as times (`sqrt(l/g)`), and `f_r`, `reference`, `walk_radius` and keys ending in
//! `_m` as lengths. The harness's own times (`push_window_s`, `recovery_s`, `resettle_s`)
//! scale as times. Every other key keeps its value.

use std::path::Path;

use crate::experiments::protocol::ProtocolTables;
use crate::experiments::settings::Settings;
use crate::experiments::summary::RobotSummary;
use crate::robot::Feet;
use crate::robot::Scale;
use crate::robot::{Description, RobotError};
use crate::robot::{RobotFile, sha256_hex};

/// What `--robot PATH` found: the description and its scale against the paper's robot.
#[derive(Debug, Clone)]
pub struct RobotRun {
    /// The robot.
    pub description: Description,
    /// Its factors against the paper's robot (`settings.sim.body`).
    pub scale: Scale,
}

/// Loads the robot at `path` (checked, standing in the settings' initial pose; its legs ending
/// at `feet` where given), names it in `settings`, and rewrites `settings`' harness times and
/// every protocol table for it.
pub fn use_robot(
    path: &Path,
    feet: Option<&Feet>,
    settings: &mut Settings,
    protocols: &mut ProtocolTables,
) -> Result<RobotRun, RobotError> {
    let sim = &settings.sim;
    let (file, description) =
        RobotFile::open(path, feet, &sim.body.servo_reference(), &sim.initial_joints)?;
    let scale = Scale::between(&description, &sim.body.description(), &sim.initial_joints);
    settings.sim.robot = Some(file);
    settings.push_window_s = scale.time(settings.push_window_s);
    settings.recovery_s = scale.time(settings.recovery_s);
    settings.resettle_s = scale.time(settings.resettle_s);
    let names: Vec<String> = protocols.names().map(str::to_string).collect();
    for name in names {
        if let Some(table) = protocols.table(&name) {
            let mut table = table.clone();
            scale_table(&mut table, &scale);
            protocols.set_table(&name, Some(table));
        }
    }
    Ok(RobotRun { description, scale })
}

/// The factor a protocol key's values are multiplied by.
fn factor(key: &str, s: &Scale) -> f64 {
    match key {
        "impulse" => s.impulse(1.0),
        "f_r" | "reference" | "walk_radius" => s.length(1.0),
        k if k.ends_with("_s") => s.time(1.0),
        k if k.ends_with("_m") => s.length(1.0),
        _ => 1.0,
    }
}

fn scale_value(v: &mut toml::Value, f: f64) {
    match v {
        toml::Value::Float(x) => *x *= f,
        toml::Value::Array(a) => a.iter_mut().for_each(|x| scale_value(x, f)),
        _ => {}
    }
}

fn scale_table(table: &mut toml::Table, s: &Scale) {
    for (key, value) in table.iter_mut() {
        match value {
            toml::Value::Table(t) => scale_table(t, s),
            v => {
                let f = factor(key, s);
                if f != 1.0 {
                    scale_value(v, f);
                }
            }
        }
    }
}

/// The robot a run with `settings` walks on, for its summary: the file's, or the built-in
/// humanoid's (hashed as its URDF export).
pub fn robot_summary(settings: &Settings) -> Result<RobotSummary, RobotError> {
    let sim = &settings.sim;
    match &sim.robot {
        Some(file) => {
            let d = file.load(&sim.body.servo_reference())?;
            Ok(RobotSummary {
                name: d.name.clone(),
                mass_kg: d.mass(),
                sha256: file.sha256.clone(),
            })
        }
        None => {
            let d = sim.body.description();
            Ok(RobotSummary {
                name: d.name.clone(),
                mass_kg: d.mass(),
                sha256: sha256_hex(d.to_urdf().as_bytes()),
            })
        }
    }
}

/// One leg as `steplearn robot show` prints it.
#[derive(Debug, Clone, serde::Serialize)]
pub struct LegReport {
    /// Hip yaw, hip roll, hip pitch, knee, ankle pitch, ankle roll.
    pub joints: [String; 6],
    /// +1 where the robot's axis is steplearn's, -1 where it is reversed.
    pub signs: [f64; 6],
    /// The foot link (the ankle roll's child).
    pub foot: String,
}

/// The gait a robot gets: the paper robot's scaled.
#[derive(Debug, Clone, serde::Serialize)]
pub struct GaitReport {
    /// Nominal step time (s).
    pub step_time_s: f64,
    /// Nominal distance between the feet (m).
    pub step_width_m: f64,
    /// Range of the commanded sagittal step (m).
    pub step_x_range_m: [f64; 2],
    /// The unit of impulse `m sqrt(g l)` over the paper robot's: what protocol impulses are
    /// multiplied by.
    pub impulse_factor: f64,
    /// Experiment C's impulse range for this robot (N s).
    pub stability_impulse_ns: [f64; 2],
}

/// What `steplearn robot show` prints.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RobotReport {
    /// The robot's name.
    pub name: String,
    /// SHA-256 of the file.
    pub sha256: String,
    /// Total mass (kg), held links included.
    pub mass_kg: f64,
    /// Height of the centre of mass above the soles in the initial stance (m).
    pub com_height_m: f64,
    /// The LIPM constant C = sqrt(g/h) the Capture Step controller uses (1/s).
    pub c: f64,
    /// The legs.
    pub legs: Legs,
    /// Joints outside the legs, held fixed in the trunk.
    pub held_joints: Vec<String>,
    /// The leg geometry control computes with.
    pub leg_geometry: crate::robot::kinematics::LegGeometry,
    /// Leg length, hip to sole (m).
    pub leg_length_m: f64,
    /// The factors against the paper's robot.
    pub scale: Scale,
    /// The gait derived.
    pub gait: GaitReport,
    /// What the loader accepted with a remark, one line each.
    pub remarks: Vec<String>,
}

/// Both legs.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Legs {
    /// The left leg.
    pub left: LegReport,
    /// The right leg.
    pub right: LegReport,
}

/// Loads and checks the robot at `path` (its legs ending at `feet` where given) against the
/// default settings, and describes it.
pub fn robot_report(path: &Path, feet: Option<&Feet>) -> Result<RobotReport, RobotError> {
    let mut settings = Settings::default();
    let mut protocols = ProtocolTables::new();
    let stability: crate::experiments::stability::StabilityProtocol = Default::default();
    protocols
        .set("stability", &stability)
        .map_err(|e| RobotError::invalid("protocols.stability", e.to_string()))?;
    let run = use_robot(path, feet, &mut settings, &mut protocols)?;
    let d = &run.description;
    let s = &run.scale;
    let walker = settings.walker.for_robot(s);
    let leg = |side: crate::robot::Side| {
        let l = &d.legs[side.index()];
        LegReport {
            joints: std::array::from_fn(|k| l.joints[k].name.clone()),
            signs: std::array::from_fn(|k| l.joints[k].sign),
            foot: l.links[5].name.clone(),
        }
    };
    let stability: crate::experiments::stability::StabilityProtocol = protocols
        .get("stability")
        .map_err(|e| RobotError::invalid("protocols.stability", e.to_string()))?;
    Ok(RobotReport {
        name: d.name.clone(),
        sha256: settings
            .sim
            .robot
            .as_ref()
            .map(|f| f.sha256.clone())
            .unwrap_or_default(),
        mass_kg: d.mass(),
        com_height_m: d.com_height(&settings.sim.initial_joints),
        c: walker.capture_step.c,
        legs: Legs {
            left: leg(crate::robot::Side::Left),
            right: leg(crate::robot::Side::Right),
        },
        held_joints: d.held_joints.clone(),
        leg_geometry: d.leg_geometry(),
        leg_length_m: d.leg_length(),
        scale: *s,
        gait: GaitReport {
            step_time_s: walker.capture_step.nominal_step_time,
            step_width_m: 2.0 * walker.capture_step.delta,
            step_x_range_m: walker.motion.step_x_range,
            impulse_factor: s.impulse(1.0),
            stability_impulse_ns: [stability.impulse.0, stability.impulse.1],
        },
        remarks: d.remarks.clone(),
    })
}

impl RobotReport {
    /// The report as lines of text.
    pub fn to_text(&self) -> String {
        let remarks: String = self
            .remarks
            .iter()
            .map(|r| format!("  remark: {r}\n"))
            .collect();
        let g = &self.leg_geometry;
        let joints = |l: &LegReport| {
            l.joints
                .iter()
                .zip(&l.signs)
                .map(|(n, s)| if *s < 0.0 { format!("-{n}") } else { n.clone() })
                .collect::<Vec<_>>()
                .join(", ")
        };
        format!(
            "robot {}\n  mass {:.3} kg, centre of mass {:.3} m above the soles, C = {:.3} 1/s\n  \
             legs (hip yaw, roll, pitch, knee, ankle pitch, roll; - where reversed):\n    \
             left:  {} (foot {})\n    right: {} (foot {})\n  held joints ({}): {}\n  \
             leg: thigh {:.3} m, shank {:.3} m, ankle {:.3} m above a {:.3} x {:.3} m sole, \
             hips {:.3} m apart\n  scale against the paper's robot: length {:.3}, mass {:.3}, \
             width {:.3}\n  gait: step time {:.3} s, step width {:.3} m, steps in [{:.3}, {:.3}] m, \
             impulses x {:.3} (C: {:.2}-{:.2} Ns)\n{}",
            self.name,
            self.mass_kg,
            self.com_height_m,
            self.c,
            joints(&self.legs.left),
            self.legs.left.foot,
            joints(&self.legs.right),
            self.legs.right.foot,
            self.held_joints.len(),
            if self.held_joints.is_empty() {
                "none".to_string()
            } else {
                self.held_joints.join(", ")
            },
            g.thigh,
            g.shank,
            g.ankle_height,
            g.foot_length,
            g.foot_width,
            2.0 * g.hip_offset[1],
            self.scale.length,
            self.scale.mass,
            self.scale.width,
            self.gait.step_time_s,
            self.gait.step_width_m,
            self.gait.step_x_range_m[0],
            self.gait.step_x_range_m[1],
            self.gait.impulse_factor,
            self.gait.stability_impulse_ns[0],
            self.gait.stability_impulse_ns[1],
            remarks,
        )
    }
}
