//! Reading the simulated sensors: the trunk IMU and the foot contacts.

use rapier3d_f64::prelude::*;

use crate::robot::{FootContact, Imu};

/// The IMU of a torso at `pose` turning at `angvel_world` (rad/s, world frame).
pub(crate) fn imu_of(pose: &Pose, angvel_world: [f64; 3]) -> Imu {
    let r = pose.rotation;
    let w = Vector::new(angvel_world[0], angvel_world[1], angvel_world[2]);
    let gyro = r.inverse() * w;
    Imu {
        orientation: [r.w, r.x, r.y, r.z],
        gyro: [gyro.x, gyro.y, gyro.z],
    }
}

/// Contact of the foot collider `foot` with `ground` during the last physics step of length
/// `dt`: normal force from the contact impulses, centre of pressure in the foot frame (the
/// point on the sole below the ankle centre; x forward, y left).
pub(crate) fn foot_contact(
    world: &PhysicsWorld,
    foot: ColliderHandle,
    ground: ColliderHandle,
    dt: f64,
) -> FootContact {
    let Some(pair) = world.narrow_phase.contact_pair(foot, ground) else {
        return FootContact::default();
    };
    if !pair.has_any_active_contact() {
        return FootContact::default();
    }
    let foot_is_1 = pair.collider1 == foot;
    let collider = &world.colliders[foot];
    let offset = collider.position_wrt_parent().copied().unwrap_or_default();
    let mut total = 0.0;
    let mut moment = [0.0; 2];
    for manifold in pair.manifolds() {
        for point in &manifold.points {
            let imp = point.data.impulse;
            if imp <= 0.0 {
                continue;
            }
            let local = if foot_is_1 {
                point.local_p1
            } else {
                point.local_p2
            };
            let p = offset.transform_point(local);
            total += imp;
            moment[0] += imp * p.x;
            moment[1] += imp * p.y;
        }
    }
    if total <= 0.0 {
        return FootContact {
            in_contact: true,
            normal_force: 0.0,
            cop: [0.0; 2],
        };
    }
    FootContact {
        in_contact: true,
        normal_force: total / dt,
        cop: [moment[0] / total, moment[1] / total],
    }
}
