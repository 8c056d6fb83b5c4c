//! An ideal walking plant: a 2-D point-mass LIPM that steps where it is told.
//!
//! The plant stands on one foot (a `foot_length x foot_width` rectangle centred on the foot
//! position); its ZMP is the commanded one clamped to that rectangle, and when the commanded
//! time to step runs out the support moves to the commanded footstep (relative to the CoM at
//! that instant). Its pendulum constant may differ from the controller's, to test model
//! mismatch. No physics engine: it is exact between events.

use serde::{Deserialize, Serialize};

use super::capture_step::{ComState, StepDecision};
use super::lipm::{Lipm, LipmState};
use crate::robot::Side;

/// A support exchange of the plant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PlantTouchDown {
    /// Time of the exchange (s).
    pub time: f64,
    /// The new support foot.
    pub support: Side,
    /// New foot minus old foot (world x, y; m): the measured step.
    pub step: [f64; 2],
}

/// A 2-D point-mass LIPM walker.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LipmPlant {
    lipm: Lipm,
    half_foot: [f64; 2],
    /// Time (s).
    pub time: f64,
    /// Support foot.
    pub support: Side,
    /// Support foot centre in the world (x, y).
    pub foot: [f64; 2],
    /// CoM position and velocity in the world, per axis (x, y).
    pub com: [LipmState; 2],
    /// The ZMP applied during the last advance, in the world (x, y).
    pub last_zmp: [f64; 2],
    /// Execution error of the step: the new foot lands at `step_gain * S` from the old foot
    /// instead of the commanded step `S` (per axis; 1 = exact).
    pub step_gain: [f64; 2],
}

impl LipmPlant {
    /// A plant with its own pendulum and foot size (m), standing on `support` at the origin with
    /// the CoM state `com` relative to that foot.
    pub fn new(
        lipm: Lipm,
        foot_length: f64,
        foot_width: f64,
        support: Side,
        com: [LipmState; 2],
    ) -> Self {
        LipmPlant {
            lipm,
            half_foot: [0.5 * foot_length, 0.5 * foot_width],
            time: 0.0,
            support,
            foot: [0.0, 0.0],
            com,
            last_zmp: [0.0, 0.0],
            step_gain: [1.0, 1.0],
        }
    }

    /// The CoM state relative to the support foot, as the controller reads it.
    pub fn com_state(&self) -> ComState {
        ComState {
            time: self.time,
            support: self.support,
            axes: [0, 1].map(|i| LipmState::new(self.com[i].pos - self.foot[i], self.com[i].vel)),
        }
    }

    /// Adds a velocity change (m/s) to the CoM: a push of impulse `mass * dv`.
    pub fn push(&mut self, dv: [f64; 2]) {
        self.com[0].vel += dv[0];
        self.com[1].vel += dv[1];
    }

    /// Whether `zmp` (relative to the support foot) lies in the foot rectangle.
    pub fn zmp_in_foot(&self, zmp: [f64; 2]) -> bool {
        (0..2).all(|i| zmp[i].abs() <= self.half_foot[i] + 1e-12)
    }

    fn advance(&mut self, zmp_rel: [f64; 2], t: f64) {
        for (i, zr) in zmp_rel.into_iter().enumerate() {
            let z = zr.clamp(-self.half_foot[i], self.half_foot[i]) + self.foot[i];
            self.last_zmp[i] = z;
            self.com[i] = self.lipm.state_after(self.com[i], z, t);
        }
        self.time += t;
    }

    /// Runs the plant for `dt` under `decision`; returns the support exchange if one happened.
    pub fn step(&mut self, decision: &StepDecision, dt: f64) -> Option<PlantTouchDown> {
        let t_step = decision.time_to_step.max(0.0);
        if t_step > dt {
            self.advance(decision.zmp, dt);
            return None;
        }
        self.advance(decision.zmp, t_step);
        let old = self.foot;
        self.foot = [0, 1].map(|i| {
            let step = self.com[i].pos + decision.footstep[i] - old[i];
            old[i] + self.step_gain[i] * step
        });
        self.support = self.support.other();
        let touch_down = PlantTouchDown {
            time: self.time,
            support: self.support,
            step: [self.foot[0] - old[0], self.foot[1] - old[1]],
        };
        self.advance([0.0, 0.0], dt - t_step);
        Some(touch_down)
    }
}
