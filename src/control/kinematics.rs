//! Leg geometry shared by the simulator (which builds the body to match it) and by control
//! (state estimation and the step motion generator compute with it).
//!
//! The kinematic chain of one leg, from the torso frame (the rigid trunk and pelvis, which
//! carries the IMU): hip centre at `hip_offset` (left leg; the right leg mirrors y); hip yaw (z),
//! hip roll (x) and hip pitch (y) axes all through the hip centre; the thigh of length `thigh`
//! down to the knee pitch axis (y); the shank of length `shank` down to the ankle centre where the
//! ankle pitch (y) and ankle roll (x) axes cross; the sole `ankle_height` below the ankle centre.
//! With every joint at zero the leg is straight and vertical and the sole is horizontal.

use serde::{Deserialize, Serialize};

/// Dimensions of one leg and foot (m). The right leg mirrors the left in y.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LegGeometry {
    /// Left hip centre in the torso frame (x forward, y left, z up).
    pub hip_offset: [f64; 3],
    /// Hip centre to knee axis.
    pub thigh: f64,
    /// Knee axis to ankle centre.
    pub shank: f64,
    /// Ankle centre above the sole.
    pub ankle_height: f64,
    /// Sole length (x).
    pub foot_length: f64,
    /// Sole width (y).
    pub foot_width: f64,
    /// Sole centre forward of the point below the ankle centre.
    pub sole_offset_x: f64,
}
