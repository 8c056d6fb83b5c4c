//! The humanoid in a rapier3d world: building the multibody, servoing the joints, stepping,
//! pushes, falls and resets.
//!
//! The robot is one reduced-coordinate multibody: the torso is the floating root; each leg is
//! a chain of six 1-DoF revolute joints (rapier's multibodies cannot integrate joints with two
//! free angular DoFs). Every joint servo is a torque-limited PD controller realised with
//! rapier's implicit joint spring and implicit joint damping: each physics step the spring's
//! rest angle is set so that `k (rest - q) - d q' = clamp(k (target - q) - d q', +-max_torque)`.
//! Being implicit, it stays stable with stiff gains at a 2 ms step and adds no solver
//! constraints. Targets are clamped to the joint limits.

use rapier3d_f64::prelude::*;

use std::sync::Arc;

use super::body::BodyConfig;
use super::config::SimConfig;
use super::error::SimError;
use super::fall::{BodyPart, Fall, FallTrigger};
use super::sensors::{foot_contact, imu_of};
use super::truth::{GroundTruth, Skeleton, pose_of};
use crate::robot::Scale;
use crate::robot::{Description, Geometry, Link, Shape};
use crate::robot::{JOINTS_PER_LEG, JointTargets, LegJoint, NUM_JOINTS, Sensors, Side};

/// Index of the free angular axis of a revolute joint in rapier's spatial layout.
const REVOLUTE_AXIS: usize = 3;

/// The simulated humanoid: a rapier world holding the robot and the ground.
pub struct Humanoid {
    config: SimConfig,
    robot: Arc<Description>,
    scale: Scale,
    world: PhysicsWorld,
    multibody: MultibodyIndex,
    torso: RigidBodyHandle,
    /// Body moved by each joint, [`LegJoint::index`] order.
    links: [RigidBodyHandle; NUM_JOINTS],
    /// Link id of that body inside the multibody.
    link_ids: [usize; NUM_JOINTS],
    /// Generalized-coordinate index of each joint.
    dofs: [usize; NUM_JOINTS],
    feet: [ColliderHandle; 2],
    ground: ColliderHandle,
    /// Every robot collider and the body part it belongs to.
    parts: Vec<(ColliderHandle, BodyPart)>,
    /// Every link with its mass (kg) and local centre of mass.
    masses: Vec<(RigidBodyHandle, f64, Vector)>,
    targets: [f64; NUM_JOINTS],
    time: f64,
    push_force: [f64; 3],
    push_steps_left: usize,
    forces_applied: bool,
}

fn v3(a: [f64; 3]) -> Vector {
    Vector::new(a[0], a[1], a[2])
}

/// The robot's colliders as they are attached, each with its body part, all with the ground's
/// friction.
struct Parts {
    friction: f64,
    list: Vec<(ColliderHandle, BodyPart)>,
}

impl Parts {
    fn attach(
        &mut self,
        world: &mut PhysicsWorld,
        mut collider: Collider,
        body: RigidBodyHandle,
        part: BodyPart,
    ) -> ColliderHandle {
        collider.set_friction(self.friction);
        let h = world
            .colliders
            .insert_with_parent(collider, body, &mut world.bodies);
        self.list.push((h, part));
        h
    }
}

/// An empty world with the config's gravity and solver settings, and the ground: a thick fixed
/// slab whose top face is z = 0.
fn world_with_ground(config: &SimConfig) -> (PhysicsWorld, ColliderHandle) {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0, -config.gravity);
    let p = &mut world.integration_parameters;
    p.dt = config.dt;
    p.num_solver_iterations = config.solver_iterations;
    p.num_internal_pgs_iterations = config.pgs_iterations;
    let ground_rb = world.bodies.insert(RigidBodyBuilder::fixed());
    let ground = world.colliders.insert_with_parent(
        ColliderBuilder::cuboid(100.0, 100.0, 0.5)
            .translation(Vector::new(0.0, 0.0, -0.5))
            .friction(config.friction),
        ground_rb,
        &mut world.bodies,
    );
    (world, ground)
}

/// A rotation from a unit quaternion `[w, x, y, z]`.
fn rotation(q: [f64; 4]) -> Rotation {
    Rotation::from_xyzw(q[1], q[2], q[3], q[0])
}

/// The collider of one shape of a description (density 0: a link's mass is its own).
fn collider(shape: &Shape) -> Collider {
    let builder = match shape.geometry {
        Geometry::Box { half_extents: h } => ColliderBuilder::cuboid(h[0], h[1], h[2]),
        Geometry::Sphere { radius } => ColliderBuilder::ball(radius),
        Geometry::Capsule {
            half_height,
            radius,
        } => ColliderBuilder::capsule_z(half_height, radius),
        Geometry::Cylinder {
            half_height,
            radius,
        } => ColliderBuilder::cylinder(half_height, radius),
    };
    let mut builder = builder.translation(v3(shape.position));
    // rapier's cylinder runs along y; the description's along z.
    let turn = match shape.geometry {
        Geometry::Cylinder { .. } => Some(
            rotation(shape.orientation) * Rotation::from_rotation_x(std::f64::consts::FRAC_PI_2),
        ),
        _ if shape.orientation != [1.0, 0.0, 0.0, 0.0] => Some(rotation(shape.orientation)),
        _ => None,
    };
    if let Some(r) = turn {
        builder = builder.rotation(r.to_scaled_axis());
    }
    builder.density(0.0).build()
}

/// A dynamic body with a link's mass properties that never sleeps.
fn link_body(link: &Link) -> RigidBodyBuilder {
    RigidBodyBuilder::dynamic()
        .can_sleep(false)
        .additional_mass_properties(MassProperties::with_principal_inertia_frame(
            v3(link.com),
            link.mass,
            v3(link.inertia.principal),
            rotation(link.inertia.axes),
        ))
}

/// A link's body and its colliders, each counted as `part`.
fn add_link(
    world: &mut PhysicsWorld,
    parts: &mut Parts,
    link: &Link,
    part: BodyPart,
) -> (RigidBodyHandle, Vec<ColliderHandle>) {
    let handle = world.bodies.insert(link_body(link));
    let colliders = link
        .shapes
        .iter()
        .map(|s| parts.attach(world, collider(s), handle, part))
        .collect();
    (handle, colliders)
}

/// The body part a leg's link belongs to: hip links and thigh, shank, ankle link and foot.
fn leg_part(k: usize, side: Side) -> BodyPart {
    match k {
        0..=2 => BodyPart::Thigh(side),
        3 => BodyPart::Shank(side),
        _ => BodyPart::Foot(side),
    }
}

/// One leg on `side`, hung from the trunk: its bodies, their colliders and the six revolute
/// joints. Writes the body each joint moves into `links` and returns the sole's collider.
fn add_leg(
    world: &mut PhysicsWorld,
    robot: &Description,
    parts: &mut Parts,
    torso: RigidBodyHandle,
    side: Side,
    links: &mut [RigidBodyHandle; NUM_JOINTS],
) -> Result<ColliderHandle, SimError> {
    let leg = &robot.legs[side.index()];
    let mut bodies = [torso; JOINTS_PER_LEG];
    let mut sole = None;
    for (k, link) in leg.links.iter().enumerate() {
        let (handle, colliders) = add_link(world, parts, link, leg_part(k, side));
        bodies[k] = handle;
        if k == JOINTS_PER_LEG - 1 {
            sole = colliders.get(leg.sole.shape).copied();
        }
    }
    let sole = sole.ok_or_else(|| SimError::BlowUp {
        time: 0.0,
        what: format!("leg {side:?} has no sole collider"),
    })?;
    let mut parent = torso;
    for (k, (j, joint)) in LegJoint::ALL.iter().zip(&leg.joints).enumerate() {
        let child = bodies[k];
        let revolute = RevoluteJointBuilder::new(v3(joint.axis))
            .local_anchor1(v3(joint.origin))
            .local_anchor2(Vector::ZERO)
            .contacts_enabled(false);
        world
            .multibody_joints
            .insert(parent, child, revolute, true)
            .ok_or_else(|| SimError::BlowUp {
                time: 0.0,
                what: format!("rapier refused joint '{}'", joint.name),
            })?;
        links[j.index(side)] = child;
        parent = child;
    }
    Ok(sole)
}

/// The multibody of the robot rooted at `torso`, with each joint's link id and
/// generalized-coordinate index; self-contacts off, no damping on the floating base and each
/// joint's servo damping on its own coordinate.
fn configure_multibody(
    world: &mut PhysicsWorld,
    robot: &Description,
    torso: RigidBodyHandle,
    links: &[RigidBodyHandle; NUM_JOINTS],
) -> Result<(MultibodyIndex, [usize; NUM_JOINTS], [usize; NUM_JOINTS]), SimError> {
    let multibody = world
        .multibody_joints
        .rigid_body_link(torso)
        .map(|l| l.multibody)
        .ok_or_else(|| SimError::BlowUp {
            time: 0.0,
            what: "torso is not in a multibody".into(),
        })?;
    let mut link_ids = [0; NUM_JOINTS];
    for (i, h) in links.iter().enumerate() {
        link_ids[i] = world
            .multibody_joints
            .rigid_body_link(*h)
            .map(|l| l.id)
            .unwrap_or(0);
    }
    let mb = world
        .multibody_joints
        .get_multibody_mut(multibody)
        .expect("multibody just built");
    mb.set_self_contacts_enabled(false);
    let mut dofs = [0; NUM_JOINTS];
    for (i, id) in link_ids.iter().enumerate() {
        dofs[i] = mb.link(*id).expect("link").assembly_id();
    }
    // No artificial damping on the floating base; joint damping is the servo's.
    let damping = mb.damping_mut();
    for k in 0..6 {
        damping[k] = 0.0;
    }
    for side in Side::BOTH {
        for j in LegJoint::ALL {
            damping[dofs[j.index(side)]] =
                robot.legs[side.index()].joints[j as usize].servo.damping;
        }
    }
    Ok((multibody, link_ids, dofs))
}

/// Every dynamic body's mass and local centre of mass, after recomputing all mass properties
/// from the colliders.
fn link_masses(world: &mut PhysicsWorld) -> Vec<(RigidBodyHandle, f64, Vector)> {
    let handles: Vec<_> = world.bodies.iter().map(|(h, _)| h).collect();
    for h in handles {
        world.bodies[h].recompute_mass_properties_from_colliders(&world.colliders);
    }
    world
        .bodies
        .iter()
        .filter(|(_, rb)| rb.is_dynamic())
        .map(|(h, rb)| {
            let mp = rb.mass_properties().local_mprops;
            (h, mp.mass(), mp.local_com)
        })
        .collect()
}

impl Humanoid {
    /// Builds the robot standing in `config.initial_joints` with its soles
    /// `config.initial_clearance` above the ground. Rejects invalid configs.
    pub fn new(config: SimConfig) -> Result<Self, SimError> {
        config.validate()?;
        let robot = match &config.robot {
            None => config.body.description(),
            Some(file) => file.load(&config.body.servo_reference())?,
        };
        let scale = match config.robot {
            None => Scale::ONE,
            Some(_) => Scale::between(&robot, &config.body.description(), &config.initial_joints),
        };
        Self::with_robot(config, Arc::new(robot), scale)
    }

    /// The robot built from its description and scale (both computed once, in [`Self::new`],
    /// and kept across resets).
    fn with_robot(
        config: SimConfig,
        robot: Arc<Description>,
        scale: Scale,
    ) -> Result<Self, SimError> {
        let (mut world, ground) = world_with_ground(&config);
        let mut parts = Parts {
            friction: config.friction,
            list: Vec::new(),
        };
        let (torso, _) = add_link(&mut world, &mut parts, &robot.trunk, BodyPart::Torso);
        let mut links = [torso; NUM_JOINTS];
        let mut feet = [ground; 2];
        for side in Side::BOTH {
            feet[side.index()] = add_leg(&mut world, &robot, &mut parts, torso, side, &mut links)?;
        }
        let (multibody, link_ids, dofs) = configure_multibody(&mut world, &robot, torso, &links)?;
        let masses = link_masses(&mut world);
        let mut sim = Humanoid {
            masses,
            targets: config.initial_joints,
            config,
            robot,
            scale,
            world,
            multibody,
            torso,
            links,
            link_ids,
            dofs,
            feet,
            ground,
            parts: parts.list,
            time: 0.0,
            push_force: [0.0; 3],
            push_steps_left: 0,
            forces_applied: false,
        };
        sim.place_standing();
        Ok(sim)
    }

    /// Sets the initial joint angles and lifts the root so the lowest sole corner sits
    /// `initial_clearance` above the ground.
    fn place_standing(&mut self) {
        let q0 = self.config.initial_joints;
        let ndofs = self.mb().ndofs();
        let mut disp = vec![0.0; ndofs];
        for (i, q) in q0.iter().enumerate() {
            disp[self.dofs[i]] = *q;
        }
        self.apply_displacement(&disp);
        let lowest = Side::BOTH
            .iter()
            .flat_map(|s| self.sole_corners(*s))
            .map(|c| c[2])
            .fold(f64::INFINITY, f64::min);
        let mut disp = vec![0.0; ndofs];
        disp[2] = self.config.initial_clearance - lowest;
        self.apply_displacement(&disp);
        for (i, q) in q0.iter().enumerate() {
            self.set_servo(i, *q, 0.0);
        }
    }

    fn apply_displacement(&mut self, disp: &[f64]) {
        let mb = self
            .world
            .multibody_joints
            .get_multibody_mut(self.multibody)
            .expect("multibody");
        mb.apply_displacements(disp);
        mb.forward_kinematics(&self.world.bodies, false);
        mb.update_rigid_bodies(&mut self.world.bodies, true);
    }

    fn mb(&self) -> &Multibody {
        self.world
            .multibody_joints
            .get_multibody(self.multibody)
            .expect("multibody")
    }

    /// The configuration this robot was built from.
    pub fn config(&self) -> &SimConfig {
        &self.config
    }

    /// The built-in body's parameters (meaningless when the robot comes from a file: see
    /// [`Humanoid::robot`]).
    pub fn body(&self) -> &BodyConfig {
        &self.config.body
    }

    /// The robot being simulated.
    pub fn robot(&self) -> &Description {
        &self.robot
    }

    /// The robot's factors against the paper's robot (`config.body`): [`Scale::ONE`] for the
    /// built-in humanoid.
    pub fn scale(&self) -> Scale {
        self.scale
    }

    /// Simulation time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Current joint angle of joint `i` (rad).
    fn joint_angle(&self, i: usize) -> f64 {
        self.mb()
            .link(self.link_ids[i])
            .expect("link")
            .joint()
            .coords()[REVOLUTE_AXIS]
    }

    /// Everything control may read now.
    pub fn sensors(&self) -> Sensors {
        let mb = self.mb();
        let gv = mb.generalized_velocity();
        let mut joint_pos = [0.0; NUM_JOINTS];
        let mut joint_vel = [0.0; NUM_JOINTS];
        for i in 0..NUM_JOINTS {
            joint_pos[i] = self.joint_angle(i);
            joint_vel[i] = gv[self.dofs[i]];
        }
        let torso = &self.world.bodies[self.torso];
        let imu = imu_of(torso.position(), [gv[3], gv[4], gv[5]]);
        let dt = self.config.dt;
        let feet =
            Side::BOTH.map(|s| foot_contact(&self.world, self.feet[s.index()], self.ground, dt));
        Sensors {
            time: self.time,
            joint_pos,
            joint_vel,
            imu,
            feet,
        }
    }

    /// Applies `targets` (clamped to the joint limits) and advances one control tick.
    /// A non-finite target is rejected before anything changes; a physics blow-up is an error.
    pub fn step(&mut self, targets: &JointTargets) -> Result<(), SimError> {
        for (index, value) in targets.pos.iter().enumerate() {
            if !value.is_finite() {
                return Err(SimError::BadTarget {
                    index,
                    value: *value,
                });
            }
        }
        for side in Side::BOTH {
            for j in LegJoint::ALL {
                let i = j.index(side);
                let [lo, hi] = self.limits(j, side);
                self.targets[i] = targets.pos[i].clamp(lo, hi);
            }
        }
        for _ in 0..self.config.steps_per_tick {
            self.physics_step()?;
        }
        Ok(())
    }

    /// Joint limits of joint `j` of leg `side` (roll and yaw limits mirror on the right leg).
    pub fn limits(&self, j: LegJoint, side: Side) -> [f64; 2] {
        self.robot.legs[side.index()].joints[j as usize].limits
    }

    fn set_servo(&mut self, i: usize, target: f64, max_torque_override: f64) {
        let spec = self.robot.legs[i / JOINTS_PER_LEG].joints[i % JOINTS_PER_LEG].servo;
        let q = self.joint_angle(i);
        let v = self.mb().generalized_velocity()[self.dofs[i]];
        let k = spec.stiffness;
        let max = if max_torque_override > 0.0 {
            max_torque_override
        } else {
            spec.max_torque
        };
        let pd = k * (target - q) - spec.damping * v;
        let rest = if pd.abs() <= max {
            target
        } else {
            q + (pd.clamp(-max, max) + spec.damping * v) / k
        };
        let id = self.link_ids[i];
        let mb = self
            .world
            .multibody_joints
            .get_multibody_mut(self.multibody)
            .expect("multibody");
        mb.link_mut(id)
            .expect("link")
            .joint
            .set_spring(REVOLUTE_AXIS, k, rest);
    }

    fn physics_step(&mut self) -> Result<(), SimError> {
        for i in 0..NUM_JOINTS {
            self.set_servo(i, self.targets[i], 0.0);
        }
        let torso = &mut self.world.bodies[self.torso];
        if self.push_steps_left > 0 {
            torso.reset_forces(false);
            torso.add_force(v3(self.push_force), true);
            self.push_steps_left -= 1;
            self.forces_applied = true;
        } else if self.forces_applied {
            torso.reset_forces(false);
            self.forces_applied = false;
        }
        self.world.step();
        self.time += self.config.dt;
        self.check_finite()
    }

    fn check_finite(&self) -> Result<(), SimError> {
        let mb = self.mb();
        let gv = mb.generalized_velocity();
        let torso = self.world.bodies[self.torso].position().translation;
        let bad = if !torso.is_finite() || torso.length() > 1e4 {
            Some(format!("torso position {torso:?}"))
        } else {
            gv.iter()
                .find(|v| !v.is_finite() || v.abs() > 1e3)
                .map(|v| format!("generalized velocity {v}"))
        };
        match bad {
            Some(what) => Err(SimError::BlowUp {
                time: self.time,
                what,
            }),
            None => Ok(()),
        }
    }

    /// Pushes the torso (at its centre of mass) with `impulse_ns` (N s, world frame), spread as
    /// a constant force over the next `config.push_steps` physics steps, so the momentum of
    /// the robot changes by exactly the impulse (plus what gravity and contacts add). A push
    /// still under way is replaced. A non-finite impulse is rejected and changes nothing.
    pub fn push(&mut self, impulse_ns: [f64; 3]) -> Result<(), SimError> {
        if impulse_ns.iter().any(|v| !v.is_finite()) {
            return Err(SimError::BadImpulse {
                impulse: impulse_ns,
            });
        }
        let duration = self.config.dt * self.config.push_steps as f64;
        self.push_force = impulse_ns.map(|p| p / duration);
        self.push_steps_left = self.config.push_steps;
        Ok(())
    }

    /// Whether a push is still being delivered.
    pub fn pushing(&self) -> bool {
        self.push_steps_left > 0
    }

    /// The fall, if the trunk tilts beyond `config.fall_tilt` or a body other than a foot
    /// touches the ground.
    pub fn fall(&self) -> Option<Fall> {
        let r = self.world.bodies[self.torso].position().rotation;
        let up = r * Vector::Z;
        let tilt = up.z.clamp(-1.0, 1.0).acos();
        if tilt > self.config.fall_tilt {
            return Some(Fall {
                time: self.time,
                trigger: FallTrigger::Tilt { angle: tilt },
            });
        }
        for pair in self.world.narrow_phase.contact_pairs_with(self.ground) {
            if !pair.has_any_active_contact() {
                continue;
            }
            let other = if pair.collider1 == self.ground {
                pair.collider2
            } else {
                pair.collider1
            };
            if let Some((_, part)) = self.parts.iter().find(|(h, _)| *h == other)
                && !matches!(part, BodyPart::Foot(_))
            {
                return Some(Fall {
                    time: self.time,
                    trigger: FallTrigger::Contact { part: *part },
                });
            }
        }
        None
    }

    /// Puts the robot back in its initial standing pose at time zero, as if newly built.
    pub fn reset(&mut self) {
        *self = Humanoid::with_robot(self.config.clone(), self.robot.clone(), self.scale)
            .expect("robot built at construction");
    }

    fn sole_corners(&self, side: Side) -> [[f64; 3]; 4] {
        let sole = &self.robot.legs[side.index()].sole;
        let pose = self.world.bodies[self.links[LegJoint::AnkleRoll.index(side)]].position();
        let mut out = [[0.0; 3]; 4];
        for (k, (sx, sy)) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]
            .into_iter()
            .enumerate()
        {
            let p = pose.transform_point(Vector::new(
                sole.centre[0] + sx * sole.length / 2.0,
                sole.centre[1] + sy * sole.width / 2.0,
                sole.centre[2],
            ));
            out[k] = [p.x, p.y, p.z];
        }
        out
    }

    /// Ground truth for tests and figures (control must not use it): centre of mass, its
    /// velocity, linear momentum, torso and sole poses, and stick-figure points.
    pub fn ground_truth(&self) -> GroundTruth {
        let bodies = &self.world.bodies;
        let mut m = 0.0;
        let mut com = Vector::ZERO;
        let mut momentum = Vector::ZERO;
        for (h, mi, local_com) in &self.masses {
            let rb = &bodies[*h];
            m += mi;
            com += rb.position().transform_point(*local_com) * *mi;
            momentum += rb.linvel() * *mi;
        }
        let com = com / m;
        let vel = momentum / m;
        let robot = &self.robot;
        let torso = bodies[self.torso].position();
        let point = |pose: &Pose, p: [f64; 3]| {
            let w = pose.transform_point(v3(p));
            [w.x, w.y, w.z]
        };
        let sole_point = |s: Side, dx: f64| {
            let sole = &robot.legs[s.index()].sole;
            [
                sole.centre[0] + dx * sole.length / 2.0,
                sole.centre[1],
                sole.centre[2],
            ]
        };
        let legs = Side::BOTH.map(|s| {
            let h = robot.hip_centre(s);
            let hip = point(torso, [h.x, h.y, h.z]);
            let knee = point(
                bodies[self.links[LegJoint::Knee.index(s)]].position(),
                [0.0; 3],
            );
            let foot = bodies[self.links[LegJoint::AnkleRoll.index(s)]].position();
            let ankle = point(foot, [0.0; 3]);
            let heel = point(foot, sole_point(s, -1.0));
            let toe = point(foot, sole_point(s, 1.0));
            [hip, knee, ankle, heel, toe]
        });
        let figure = &robot.figure;
        let skeleton = Skeleton {
            pelvis: point(torso, [0.0; 3]),
            neck: point(torso, figure.neck),
            head: point(torso, figure.head),
            head_radius: figure.head_radius,
            legs,
        };
        let soles = Side::BOTH.map(|s| {
            let foot = bodies[self.links[LegJoint::AnkleRoll.index(s)]].position();
            let sole = foot.transform_point(v3(robot.legs[s.index()].sole.centre));
            pose_of(sole, foot.rotation)
        });
        let links = std::array::from_fn(|k| {
            let h = if k == 0 {
                self.torso
            } else {
                self.links[k - 1]
            };
            let p = bodies[h].position();
            pose_of(p.translation, p.rotation)
        });
        GroundTruth {
            links,
            time: self.time,
            mass: m,
            com: [com.x, com.y, com.z],
            com_vel: [vel.x, vel.y, vel.z],
            momentum: [momentum.x, momentum.y, momentum.z],
            torso: pose_of(torso.translation, torso.rotation),
            soles,
            skeleton,
        }
    }
}
