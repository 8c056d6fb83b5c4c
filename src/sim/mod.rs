//! The simulated humanoid in rapier3d: a 2 m, 13.5 kg biped with 12 position-controlled joints,
//! pushes, fall detection and resets. It fills [`crate::control::Sensors`] and applies
//! [`crate::control::JointTargets`]; control never sees rapier.
