//! State estimation: from [`Sensors`] and the [`LegGeometry`] to the quantities the balance
//! controller and the learner read.
//!
//! - **Heading frame**: the world frame turned by the trunk's yaw (x forward along the heading,
//!   y left, z up). A vector `v` in the torso frame is `Ry(pitch) Rx(roll) v` in the heading
//!   frame, with roll and pitch from the IMU ([`Imu::roll_pitch_yaw`](crate::robot::Imu)).
//! - **CoM model**: the CoM is a fixed point `com_offset` of the torso frame (the default is
//!   the simulated 2 m humanoid's CoM in its torso frame, averaged while stepping in place:
//!   2.1 cm ahead of and 11.6 cm above the hip centres; the legs' motion moves the true CoM by
//!   a few cm, which this model ignores, as the authors' gait does). Its position
//!   relative to the support foot's sole centre is `R (com_offset - sole)`, with `sole` from
//!   forward kinematics and `R` the IMU attitude without yaw.
//! - **CoM velocity**: the finite difference of that position between ticks, low-pass filtered
//!   (first order, time constant `velocity_time_constant`). Each foot keeps its own previous
//!   relative position; on the tick of a support exchange the velocity is held (the new
//!   support's previous position was taken while it swung).
//! - **Support foot**: the foot carrying the load, with hysteresis: the support passes to the
//!   other foot only when it carries more than `switch_fraction` of the total normal force, the
//!   total exceeds `min_total_force`, and the current support has lasted `min_support_time`.
//! - **Touch-down**: at each support exchange, the measured step `F_hat`: new support sole
//!   minus old support sole in the heading frame (x: sagittal step size, positive forward).
//! - **Trunk deviation**: `theta_E = pitch - theta_R` and its rate from the gyro,
//!   `pitch' = w_y cos(roll) - w_z sin(roll)` (body rates, z-y-x Euler angles).

use nalgebra::{Rotation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::lipm::LipmState;
use crate::robot::kinematics::{KinematicsError, LegGeometry};
use crate::robot::{Sensors, Side};

/// What can go wrong estimating the state.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EstimatorError {
    /// A configuration value is out of range.
    #[error("invalid estimator config: {param} {reason}")]
    InvalidConfig {
        /// The parameter's name.
        param: &'static str,
        /// Why it is invalid.
        reason: String,
    },
    /// The leg geometry is invalid.
    #[error(transparent)]
    Geometry(#[from] KinematicsError),
    /// A sensor value was NaN/infinite, the orientation was not a rotation, or time did not
    /// advance.
    #[error("invalid sensor input: {0}")]
    InvalidInput(String),
}

/// Parameters of the state estimator. Validated by [`StateEstimator::new`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EstimatorConfig {
    /// The CoM as a fixed point of the torso frame (m).
    pub com_offset: [f64; 3],
    /// Share of the total normal force the other foot must carry to become the support, in
    /// (0.5, 1].
    pub switch_fraction: f64,
    /// Least total normal force for a support exchange (N); below it (both feet in the air)
    /// the support is kept.
    pub min_total_force: f64,
    /// Least time on one support foot before the next exchange (s).
    pub min_support_time: f64,
    /// Time constant of the CoM velocity low-pass filter (s); 0 disables filtering.
    pub velocity_time_constant: f64,
}

impl Default for EstimatorConfig {
    fn default() -> Self {
        EstimatorConfig {
            com_offset: [0.021, 0.0, 0.116],
            switch_fraction: 0.6,
            min_total_force: 5.0,
            min_support_time: 0.1,
            velocity_time_constant: 0.02,
        }
    }
}

impl EstimatorConfig {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), EstimatorError> {
        let bad = |param, reason: String| Err(EstimatorError::InvalidConfig { param, reason });
        if self.com_offset.iter().any(|v| !v.is_finite()) {
            return bad(
                "com_offset",
                format!("must be finite, got {:?}", self.com_offset),
            );
        }
        if !(self.switch_fraction > 0.5 && self.switch_fraction <= 1.0) {
            return bad(
                "switch_fraction",
                format!("must be in (0.5, 1], got {}", self.switch_fraction),
            );
        }
        for (param, v) in [
            ("min_total_force", self.min_total_force),
            ("min_support_time", self.min_support_time),
            ("velocity_time_constant", self.velocity_time_constant),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(param, format!("must be >= 0 and finite, got {v}"));
            }
        }
        Ok(())
    }
}

/// A support exchange, with the measured step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TouchDown {
    /// Time of the exchange (s).
    pub time: f64,
    /// The new support foot.
    pub support: Side,
    /// New support sole minus old support sole in the heading frame (x, y; m). `step[0]` is
    /// the measured step size `F_hat`.
    pub step: [f64; 2],
}

/// The estimated state in one tick.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// Time (s).
    pub time: f64,
    /// The support foot.
    pub support: Side,
    /// Time since the last support exchange (or the first tick) (s).
    pub time_on_support: f64,
    /// CoM position and velocity relative to the support sole centre, heading frame, per axis
    /// (x, y): the controller's input.
    pub com: [LipmState; 2],
    /// CoM height above the support sole (m).
    pub com_height: f64,
    /// Sole centres relative to the CoM in the heading frame, left then right (m).
    pub feet: [[f64; 3]; 2],
    /// Trunk pitch from the IMU (rad, positive leaning forward).
    pub pitch: f64,
    /// Trunk deviation angle `theta_E = pitch - theta_R` (rad).
    pub theta_e: f64,
    /// Its rate (rad/s), from the gyro.
    pub theta_e_rate: f64,
    /// Trunk roll from the IMU (rad, about the forward axis: positive tilts the trunk's top to
    /// the right).
    pub roll: f64,
    /// Its rate (rad/s), from the gyro.
    pub roll_rate: f64,
    /// The support exchange that happened this tick, if any.
    pub touch_down: Option<TouchDown>,
}

impl Estimate {
    /// The controller's input for this estimate.
    pub fn com_state(&self) -> super::capture_step::ComState {
        super::capture_step::ComState {
            time: self.time,
            support: self.support,
            axes: self.com,
        }
    }
}

/// Memory kept between ticks.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct Memory {
    time: f64,
    support: Side,
    support_since: f64,
    /// CoM relative to each sole, heading frame, at the previous tick.
    com_rel: [Vector3<f64>; 2],
    velocity: Vector3<f64>,
}

/// Estimates CoM state, support foot, touch-downs and trunk deviation from sensors.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StateEstimator {
    geometry: LegGeometry,
    config: EstimatorConfig,
    memory: Option<Memory>,
}

impl StateEstimator {
    /// An estimator for a robot with leg geometry `geometry`.
    pub fn new(geometry: LegGeometry, config: EstimatorConfig) -> Result<Self, EstimatorError> {
        geometry.validate()?;
        config.validate()?;
        Ok(StateEstimator {
            geometry,
            config,
            memory: None,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &EstimatorConfig {
        &self.config
    }

    /// Forgets all history (after a reset of the robot).
    pub fn reset(&mut self) {
        self.memory = None;
    }

    /// One tick: the estimate from `sensors`, with the desired trunk pitch `theta_reference`
    /// (rad) from the motion generator.
    ///
    /// Rejects non-finite sensors, a zero orientation quaternion and non-increasing time
    /// without changing the estimator.
    pub fn update(
        &mut self,
        sensors: &Sensors,
        theta_reference: f64,
    ) -> Result<Estimate, EstimatorError> {
        check_sensors(sensors, theta_reference)?;
        if let Some(m) = &self.memory
            && sensors.time <= m.time
        {
            return Err(EstimatorError::InvalidInput(format!(
                "time must increase: {} after {}",
                sensors.time, m.time
            )));
        }
        let [w, x, y, z] = sensors.imu.orientation;
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        let (roll, pitch, _yaw) = q.euler_angles();
        let tilt = Rotation3::from_euler_angles(roll, pitch, 0.0);

        // CoM relative to each sole, heading frame.
        let com = Vector3::from(self.config.com_offset);
        let soles = Side::BOTH.map(|side| {
            let angles = LegGeometry::leg_angles(&sensors.joint_pos, side);
            self.geometry.forward(side, &angles).translation.vector
        });
        let com_rel = soles.map(|s| tilt * (com - s));

        // Support foot with hysteresis.
        let forces = sensors.feet.map(|f| f.normal_force.max(0.0));
        let total = forces[0] + forces[1];
        let (support, support_since, touch_down) = match &self.memory {
            None => {
                let s = if forces[1] > forces[0] {
                    Side::Right
                } else {
                    Side::Left
                };
                (s, sensors.time, None)
            }
            Some(m) => {
                let other = m.support.other();
                let switch = total >= self.config.min_total_force
                    && forces[other.index()] > self.config.switch_fraction * total
                    && sensors.time - m.support_since >= self.config.min_support_time;
                if switch {
                    let old = com_rel[m.support.index()];
                    let new = com_rel[other.index()];
                    // Sole difference = (com - old) - (com - new).
                    let step = old - new;
                    let td = TouchDown {
                        time: sensors.time,
                        support: other,
                        step: [step.x, step.y],
                    };
                    (other, sensors.time, Some(td))
                } else {
                    (m.support, m.support_since, None)
                }
            }
        };

        // Velocity: filtered difference relative to the support foot. At an exchange the new
        // support's previous position is from its swing, so the velocity is held for a tick.
        let velocity = match &self.memory {
            None => Vector3::zeros(),
            Some(m) if touch_down.is_some() => m.velocity,
            Some(m) => {
                let dt = sensors.time - m.time;
                let i = support.index();
                let raw = (com_rel[i] - m.com_rel[i]) / dt;
                let gain = dt / (self.config.velocity_time_constant + dt);
                m.velocity + (raw - m.velocity) * gain
            }
        };

        let p = com_rel[support.index()];
        let [_, gy, gz] = sensors.imu.gyro;
        let pitch_rate = gy * roll.cos() - gz * roll.sin();
        let [gx, ..] = sensors.imu.gyro;
        let roll_rate = gx + (gy * roll.sin() + gz * roll.cos()) * pitch.tan();
        let feet = com_rel.map(|r| [-r.x, -r.y, -r.z]);

        self.memory = Some(Memory {
            time: sensors.time,
            support,
            support_since,
            com_rel,
            velocity,
        });
        Ok(Estimate {
            time: sensors.time,
            support,
            time_on_support: sensors.time - support_since,
            com: [
                LipmState::new(p.x, velocity.x),
                LipmState::new(p.y, velocity.y),
            ],
            com_height: p.z,
            feet,
            pitch,
            theta_e: pitch - theta_reference,
            theta_e_rate: pitch_rate,
            roll,
            roll_rate,
            touch_down,
        })
    }
}

fn check_sensors(s: &Sensors, theta_reference: f64) -> Result<(), EstimatorError> {
    let finite = s.time.is_finite()
        && theta_reference.is_finite()
        && s.joint_pos.iter().all(|v| v.is_finite())
        && s.joint_vel.iter().all(|v| v.is_finite())
        && s.imu.orientation.iter().all(|v| v.is_finite())
        && s.imu.gyro.iter().all(|v| v.is_finite())
        && s.feet
            .iter()
            .all(|f| f.normal_force.is_finite() && f.cop.iter().all(|v| v.is_finite()));
    if !finite {
        return Err(EstimatorError::InvalidInput(
            "non-finite sensor value or reference".into(),
        ));
    }
    let norm2: f64 = s.imu.orientation.iter().map(|v| v * v).sum();
    if norm2 < 1e-12 {
        return Err(EstimatorError::InvalidInput(
            "IMU orientation quaternion is zero".into(),
        ));
    }
    Ok(())
}
