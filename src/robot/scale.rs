//! Dynamic similarity between a robot and the paper's: [`Scale`].

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::description::Description;
use super::{NUM_JOINTS, Side};

/// The factors of one robot against the paper's (all exactly 1 for the paper's robot).
///
/// Dynamic similarity: how a robot's gait, learner and protocols follow from the paper's
/// robot. A gait scaled by leg length `l` and by `sqrt(l/g)` in time, and pushes in units of
/// `m sqrt(g l)`, transfer across body sizes (Alexander's dynamic similarity, Froude scaling).
/// [`Scale`] holds the factors of one robot against the paper's; it is computed once, from
/// both descriptions, and every scaled setting is derived from it in one place
/// ([`crate::control::for_robot`] for the walker and learner, the experiments' config for the
/// protocols).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Scale {
    /// Leg length (hip centre to sole, straight) over the paper robot's.
    pub length: f64,
    /// Mass over the paper robot's.
    pub mass: f64,
    /// Lateral hip distance over the paper robot's (step widths follow it).
    pub width: f64,
    /// Height of the centre of mass in the stance over the paper robot's (C follows it).
    pub com_height: f64,
    /// The robot's centre of mass in the trunk frame in the stance, minus `length` times the
    /// paper robot's (m): what the estimator's centre of mass is shifted by.
    pub com_shift: [f64; 3],
    /// How far the stance centre of mass lies ahead of the soles' centre, minus `length`
    /// times the paper robot's (m): what the walker's reference point on each sole is moved
    /// forward by, so that the stance centre of mass lies ahead of it as the paper robot's
    /// does, scaled.
    #[serde(default)]
    pub sole_shift_x: f64,
}

impl Scale {
    /// The identity: the paper's robot.
    pub const ONE: Scale = Scale {
        length: 1.0,
        mass: 1.0,
        width: 1.0,
        com_height: 1.0,
        com_shift: [0.0; 3],
        sole_shift_x: 0.0,
    };

    /// The factors of `robot` against `paper`, both in the joint angles `stance`.
    pub fn between(robot: &Description, paper: &Description, stance: &[f64; NUM_JOINTS]) -> Self {
        let length = robot.leg_length() / paper.leg_length();
        let hip_y =
            |d: &Description| (d.hip_centre(Side::Left).y - d.hip_centre(Side::Right).y) / 2.0;
        let (robot_com, paper_com) = (robot.com_in_trunk(stance), paper.com_in_trunk(stance));
        let com: Vector3<f64> = robot_com - paper_com * length;
        // The mean of both soles' centres, x in the trunk frame (m).
        let soles_x = |d: &Description| {
            Side::BOTH
                .iter()
                .flat_map(|s| d.sole_corners_in_trunk(*s, stance))
                .map(|c| c.x)
                .sum::<f64>()
                / 8.0
        };
        Scale {
            length,
            mass: robot.mass() / paper.mass(),
            width: hip_y(robot) / hip_y(paper),
            com_height: robot.com_height(stance) / paper.com_height(stance),
            com_shift: [com.x, com.y, com.z],
            sole_shift_x: (robot_com.x - soles_x(robot)) - (paper_com.x - soles_x(paper)) * length,
        }
    }

    /// Whether this is [`Scale::ONE`].
    pub fn is_one(&self) -> bool {
        *self == Scale::ONE
    }

    /// A length (m) of the paper's robot, for this robot.
    pub fn length(&self, x: f64) -> f64 {
        x * self.length
    }

    /// The time factor `sqrt(l/g)` over the paper robot's, with `l` the leg length. (Times
    /// from the centre-of-mass height instead, which keeps the Capture Step's `C T`, were
    /// measured weaker on the igus-like robot: docs/robot.md.)
    pub fn time_factor(&self) -> f64 {
        self.length.sqrt()
    }

    /// A time (s).
    pub fn time(&self, t: f64) -> f64 {
        t * self.time_factor()
    }

    /// A rate (1/s, rad/s).
    pub fn rate(&self, r: f64) -> f64 {
        r / self.time_factor()
    }

    /// A force (N): forces scale with `m g`.
    pub fn force(&self, f: f64) -> f64 {
        f * self.mass
    }

    /// An impulse (N s): impulses scale with `m sqrt(g l)`.
    pub fn impulse(&self, p: f64) -> f64 {
        p * self.mass * self.length.sqrt()
    }

    /// A lateral distance between the feet (m).
    pub fn width(&self, y: f64) -> f64 {
        y * self.width
    }

    /// The LIPM constant `C = sqrt(g/h)` (1/s) from the paper robot's.
    pub fn lipm_c(&self, c: f64) -> f64 {
        c / self.com_height.sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::{STANCE_KNEE, ServoReference, standing_pose};

    #[test]
    fn soles_moved_forward_move_the_reference_point_back_by_as_much() {
        let urdf =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("robots/steplearn_humanoid.urdf");
        let paper = Description::from_urdf(&urdf, &ServoReference::default()).unwrap();
        let stance = standing_pose(STANCE_KNEE);
        assert_eq!(Scale::between(&paper, &paper, &stance), Scale::ONE);
        let mut robot = paper.clone();
        for leg in &mut robot.legs {
            leg.sole.centre[0] += 0.01;
        }
        let s = Scale::between(&robot, &paper, &stance);
        assert!((s.sole_shift_x + 0.01).abs() < 1e-12, "{}", s.sole_shift_x);
        assert_eq!(s.length, 1.0);
    }
}
