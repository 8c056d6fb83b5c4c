//! URDF in and out: [`Description::from_urdf`] reads a biped, finds its legs, holds every other
//! joint and merges it into the trunk; [`Description::to_urdf`] writes a description back.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

use super::description::{
    Description, Figure, Geometry, Inertia, Joint, Leg, Link, RobotError, Servo, Shape, Sole, quat,
};
use super::{JOINTS_PER_LEG, LegJoint, Side};

/// The links that end the legs, named where the loader's choice (the lowest leaf on each side)
/// is not the foot: a toe, a cable or a sensor hanging lower, say.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Feet {
    /// The left foot's link.
    pub left: String,
    /// The right foot's link.
    pub right: String,
}

impl Feet {
    /// The foot link on `side`.
    pub fn on(&self, side: Side) -> &str {
        match side {
            Side::Left => &self.left,
            Side::Right => &self.right,
        }
    }
}

/// How far (cosine) a leg joint's axis may stray from its steplearn axis.
const AXIS_COS: f64 = 0.99;

#[derive(Debug, Clone, Copy)]
struct Origin {
    xyz: Vector3<f64>,
    rot: Rotation3<f64>,
    plain: bool,
}

impl Origin {
    fn identity() -> Self {
        Origin {
            xyz: Vector3::zeros(),
            rot: Rotation3::identity(),
            plain: true,
        }
    }
}

#[derive(Debug, Clone)]
enum UGeometry {
    Shape(Geometry),
    Mesh { path: PathBuf, scale: Vector3<f64> },
}

#[derive(Debug, Clone)]
struct ULink {
    name: String,
    inertial: Option<(Origin, f64, Matrix3<f64>)>,
    /// Why its own inertia is not physical, if it is not: refused on the trunk and the legs,
    /// remarked on a held link (whose inertia counts only in the trunk's sum).
    inertia_problem: Option<String>,
    collisions: Vec<(Origin, UGeometry)>,
}

#[derive(Debug, Clone)]
struct UJoint {
    name: String,
    kind: String,
    parent: usize,
    child: usize,
    origin: Origin,
    axis: Vector3<f64>,
    limits: Option<[f64; 2]>,
    mimic: bool,
}

fn link_el(name: &str) -> String {
    format!("link '{name}'")
}

fn joint_el(name: &str) -> String {
    format!("joint '{name}'")
}

fn numbers(el: &str, what: &str, text: &str, n: usize) -> Result<Vec<f64>, RobotError> {
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|t| {
            t.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    RobotError::invalid(el, format!("{what}: '{t}' is not a finite number"))
                })
        })
        .collect::<Result<_, _>>()?;
    if v.len() != n {
        return Err(RobotError::invalid(
            el,
            format!("{what}: expected {n} numbers, got '{text}'"),
        ));
    }
    Ok(v)
}

fn number(el: &str, node: roxmltree::Node, attr: &str) -> Result<f64, RobotError> {
    let text = node.attribute(attr).ok_or_else(|| {
        RobotError::invalid(el, format!("<{}> has no '{attr}'", node.tag_name().name()))
    })?;
    Ok(numbers(el, attr, text, 1)?[0])
}

fn origin_of(el: &str, parent: roxmltree::Node) -> Result<Origin, RobotError> {
    let Some(o) = child(parent, "origin") else {
        return Ok(Origin::identity());
    };
    let xyz = match o.attribute("xyz") {
        Some(t) => Vector3::from_vec(numbers(el, "origin xyz", t, 3)?),
        None => Vector3::zeros(),
    };
    let rpy = match o.attribute("rpy") {
        Some(t) => numbers(el, "origin rpy", t, 3)?,
        None => vec![0.0; 3],
    };
    let plain = rpy.iter().all(|a| *a == 0.0);
    let rot = if plain {
        Rotation3::identity()
    } else {
        Rotation3::from_euler_angles(rpy[0], rpy[1], rpy[2])
    };
    Ok(Origin { xyz, rot, plain })
}

fn child<'a, 'i>(node: roxmltree::Node<'a, 'i>, tag: &str) -> Option<roxmltree::Node<'a, 'i>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == tag)
}

fn children<'a, 'i>(
    node: roxmltree::Node<'a, 'i>,
    tag: &'static str,
) -> impl Iterator<Item = roxmltree::Node<'a, 'i>> {
    node.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == tag)
}

/// Where a mesh file lies: `package://` through `ROS_PACKAGE_PATH`, else through the
/// directories above the URDF; `file://` and plain paths as given (relative to the URDF).
fn resolve_mesh(el: &str, filename: &str, urdf_dir: &Path) -> Result<PathBuf, RobotError> {
    let mut tried = Vec::new();
    let found = if let Some(rest) = filename.strip_prefix("package://") {
        let (package, inner) = rest.split_once('/').unwrap_or((rest, ""));
        let mut roots: Vec<PathBuf> = std::env::var("ROS_PACKAGE_PATH")
            .map(|p| std::env::split_paths(&p).collect())
            .unwrap_or_default();
        // Every directory above the URDF, up to the file system's root, whether the URDF was
        // named by an absolute or a relative path.
        let here = if urdf_dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            urdf_dir
        };
        let urdf_dir = std::path::absolute(here).unwrap_or_else(|_| here.to_path_buf());
        roots.extend(urdf_dir.ancestors().map(Path::to_path_buf));
        roots.into_iter().find_map(|root| {
            let candidates = [
                (root.file_name().and_then(|n| n.to_str()) == Some(package))
                    .then(|| root.join(inner)),
                Some(root.join(package).join(inner)),
            ];
            candidates.into_iter().flatten().find(|c| {
                tried.push(c.display().to_string());
                c.is_file()
            })
        })
    } else {
        let path = filename.strip_prefix("file://").unwrap_or(filename);
        let p = urdf_dir.join(path);
        tried.push(p.display().to_string());
        p.is_file().then_some(p)
    };
    found.ok_or_else(|| {
        RobotError::invalid(
            el,
            format!(
                "mesh '{filename}' not found (ROS_PACKAGE_PATH, then the directories above the \
                 URDF; tried {} places)",
                tried.len()
            ),
        )
    })
}

fn geometry_of(
    el: &str,
    node: roxmltree::Node,
    urdf_dir: &Path,
) -> Result<Option<UGeometry>, RobotError> {
    let Some(g) = child(node, "geometry") else {
        return Err(RobotError::invalid(
            el,
            "a collision or visual without <geometry>",
        ));
    };
    let Some(shape) = g.children().find(|c| c.is_element()) else {
        return Err(RobotError::invalid(el, "an empty <geometry>"));
    };
    let positive = |v: f64, what: &str| {
        if v > 0.0 {
            Ok(v)
        } else {
            Err(RobotError::invalid(
                el,
                format!("{what} must be positive, got {v}"),
            ))
        }
    };
    Ok(Some(match shape.tag_name().name() {
        "box" => {
            let t = shape
                .attribute("size")
                .ok_or_else(|| RobotError::invalid(el, "<box> has no 'size'"))?;
            let s = numbers(el, "box size", t, 3)?;
            let h = [
                positive(s[0], "box size")? / 2.0,
                positive(s[1], "box size")? / 2.0,
                positive(s[2], "box size")? / 2.0,
            ];
            UGeometry::Shape(Geometry::Box { half_extents: h })
        }
        "sphere" => UGeometry::Shape(Geometry::Sphere {
            radius: positive(number(el, shape, "radius")?, "radius")?,
        }),
        tag @ ("cylinder" | "capsule") => {
            let radius = positive(number(el, shape, "radius")?, "radius")?;
            let half_height = positive(number(el, shape, "length")?, "length")? / 2.0;
            UGeometry::Shape(if tag == "cylinder" {
                Geometry::Cylinder {
                    half_height,
                    radius,
                }
            } else {
                Geometry::Capsule {
                    half_height,
                    radius,
                }
            })
        }
        "mesh" => {
            let f = shape
                .attribute("filename")
                .ok_or_else(|| RobotError::invalid(el, "<mesh> has no 'filename'"))?;
            let path = resolve_mesh(el, f, urdf_dir)?;
            let scale = match shape.attribute("scale") {
                Some(t) => Vector3::from_vec(numbers(el, "mesh scale", t, 3)?),
                None => Vector3::new(1.0, 1.0, 1.0),
            };
            UGeometry::Mesh { path, scale }
        }
        _ => return Ok(None),
    }))
}

fn parse_link(node: roxmltree::Node, urdf_dir: &Path) -> Result<ULink, RobotError> {
    let name = node
        .attribute("name")
        .ok_or_else(|| RobotError::invalid("a <link>", "has no name"))?
        .to_string();
    let el = link_el(&name);
    let mut inertia_problem = None;
    let inertial = match child(node, "inertial") {
        None => None,
        Some(i) => {
            let origin = origin_of(&el, i)?;
            let m = child(i, "mass")
                .ok_or_else(|| RobotError::invalid(&el, "<inertial> has no <mass>"))?;
            let mass = number(&el, m, "value")?;
            if mass < 0.0 {
                return Err(RobotError::invalid(
                    &el,
                    format!("mass must be positive, got {mass}"),
                ));
            }
            let t = child(i, "inertia")
                .ok_or_else(|| RobotError::invalid(&el, "<inertial> has no <inertia>"))?;
            let g = |a: &str| number(&el, t, a);
            let (xx, yy, zz) = (g("ixx")?, g("iyy")?, g("izz")?);
            let off = |a: &str| -> Result<f64, RobotError> {
                if t.attribute(a).is_some() {
                    g(a)
                } else {
                    Ok(0.0)
                }
            };
            let (xy, xz, yz) = (off("ixy")?, off("ixz")?, off("iyz")?);
            let m3 = Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
            let inertia = Inertia::from_matrix(&m3);
            let [a, b, c] = inertia.principal;
            // Relative to the moments, with a floor far below any real link's (kg m^2), so
            // that rounding in a file's digits passes.
            let tol = 1e-9 * (a.abs() + b.abs() + c.abs()) + 1e-12;
            // A frame without mass (mass 0) or a point mass (inertia 0) is allowed; the body
            // it joins must have both.
            if a < -tol || b < -tol || c < -tol {
                inertia_problem = Some(format!(
                    "inertia is not positive definite (principal moments {a}, {b}, {c})"
                ));
            } else if a + b < c - tol || a + c < b - tol || b + c < a - tol {
                inertia_problem = Some(format!(
                    "inertia breaks the triangle inequality (principal moments {a}, {b}, {c})"
                ));
            }
            (mass > 0.0).then_some((origin, mass, m3))
        }
    };
    let mut collisions = Vec::new();
    for c in children(node, "collision") {
        let origin = origin_of(&el, c)?;
        if let Some(g) = geometry_of(&el, c, urdf_dir)? {
            collisions.push((origin, g));
        }
    }
    for v in children(node, "visual") {
        // Only checked: a visual mesh must exist.
        origin_of(&el, v)?;
        geometry_of(&el, v, urdf_dir)?;
    }
    Ok(ULink {
        name,
        inertial,
        inertia_problem,
        collisions,
    })
}

fn parse_joint(
    node: roxmltree::Node,
    index: &HashMap<String, usize>,
) -> Result<UJoint, RobotError> {
    let name = node
        .attribute("name")
        .ok_or_else(|| RobotError::invalid("a <joint>", "has no name"))?
        .to_string();
    let el = joint_el(&name);
    let kind = node
        .attribute("type")
        .ok_or_else(|| RobotError::invalid(&el, "has no type"))?
        .to_string();
    let end = |tag: &str| -> Result<usize, RobotError> {
        let n = child(node, tag)
            .and_then(|c| c.attribute("link"))
            .ok_or_else(|| RobotError::invalid(&el, format!("has no <{tag} link=...>")))?;
        index
            .get(n)
            .copied()
            .ok_or_else(|| RobotError::invalid(&el, format!("{tag} link '{n}' is not defined")))
    };
    let (parent, child_link) = (end("parent")?, end("child")?);
    let origin = origin_of(&el, node)?;
    let axis = match child(node, "axis").and_then(|a| a.attribute("xyz")) {
        Some(t) => Vector3::from_vec(numbers(&el, "axis", t, 3)?),
        None => Vector3::x(),
    };
    let limits = match child(node, "limit") {
        Some(l) if l.attribute("lower").is_some() || l.attribute("upper").is_some() => {
            let get = |a: &str| -> Result<f64, RobotError> {
                if l.attribute(a).is_some() {
                    number(&el, l, a)
                } else {
                    Ok(0.0)
                }
            };
            Some([get("lower")?, get("upper")?])
        }
        _ => None,
    };
    Ok(UJoint {
        name,
        kind,
        parent,
        child: child_link,
        origin,
        axis,
        limits,
        mimic: child(node, "mimic").is_some(),
    })
}

fn is_moving(kind: &str) -> bool {
    matches!(kind, "revolute" | "continuous" | "prismatic")
}

/// A link's place in the zero pose: position and rotation in the root frame.
#[derive(Debug, Clone, Copy)]
struct Place {
    pos: Vector3<f64>,
    rot: Rotation3<f64>,
    plain: bool,
}

struct Tree {
    links: Vec<ULink>,
    joints: Vec<UJoint>,
    root: usize,
    /// Joint whose child each link is.
    parent_joint: Vec<Option<usize>>,
    place: Vec<Place>,
    /// Links in breadth-first order from the root.
    order: Vec<usize>,
}

impl Tree {
    fn new(links: Vec<ULink>, joints: Vec<UJoint>) -> Result<Self, RobotError> {
        let mut parent_joint: Vec<Option<usize>> = vec![None; links.len()];
        for (k, j) in joints.iter().enumerate() {
            if let Some(other) = parent_joint[j.child] {
                return Err(RobotError::invalid(
                    link_el(&links[j.child].name),
                    format!(
                        "is the child of two joints, '{}' and '{}' (a cycle or a second parent)",
                        joints[other].name, j.name
                    ),
                ));
            }
            parent_joint[j.child] = Some(k);
        }
        let roots: Vec<usize> = (0..links.len())
            .filter(|l| parent_joint[*l].is_none())
            .collect();
        let root = match roots.as_slice() {
            [r] => *r,
            [] => {
                return Err(RobotError::invalid(
                    "the robot",
                    "has no root link: its joints form a cycle",
                ));
            }
            many => {
                return Err(RobotError::invalid(
                    link_el(&links[many[1]].name),
                    format!(
                        "is not connected to the root link '{}' (the robot has {} roots)",
                        links[many[0]].name,
                        many.len()
                    ),
                ));
            }
        };
        let mut kids: Vec<Vec<usize>> = vec![Vec::new(); links.len()];
        for (k, j) in joints.iter().enumerate() {
            kids[j.parent].push(k);
        }
        let mut place = vec![
            Place {
                pos: Vector3::zeros(),
                rot: Rotation3::identity(),
                plain: true,
            };
            links.len()
        ];
        let mut order = vec![root];
        let mut seen = vec![false; links.len()];
        seen[root] = true;
        let mut i = 0;
        while i < order.len() {
            let l = order[i];
            for &k in &kids[l] {
                let j = &joints[k];
                if seen[j.child] {
                    return Err(RobotError::invalid(joint_el(&j.name), "closes a cycle"));
                }
                seen[j.child] = true;
                let p = place[l];
                let offset = if p.plain {
                    j.origin.xyz
                } else {
                    p.rot * j.origin.xyz
                };
                place[j.child] = Place {
                    pos: p.pos + offset,
                    rot: if j.origin.plain {
                        p.rot
                    } else {
                        p.rot * j.origin.rot
                    },
                    plain: p.plain && j.origin.plain,
                };
                order.push(j.child);
            }
            i += 1;
        }
        if let Some(l) = (0..links.len()).find(|l| !seen[*l]) {
            return Err(RobotError::invalid(
                link_el(&links[l].name),
                "is on a cycle of joints, not reachable from the root",
            ));
        }
        Ok(Tree {
            links,
            joints,
            root,
            parent_joint,
            place,
            order,
        })
    }

    fn is_leaf(&self, l: usize) -> bool {
        !self.joints.iter().any(|j| j.parent == l)
    }

    /// Joints from the root down to link `l`.
    fn path(&self, mut l: usize) -> Vec<usize> {
        let mut out = Vec::new();
        while let Some(k) = self.parent_joint[l] {
            out.push(k);
            l = self.joints[k].parent;
        }
        out.reverse();
        out
    }

    fn axis_world(&self, k: usize) -> Vector3<f64> {
        let j = &self.joints[k];
        let r = self.place[j.child].rot;
        (r * j.axis).normalize()
    }
}

/// The chain of six leg joints ending at leaf `foot`, checked: `moving` are the moving joints
/// of its path below those both legs share.
fn leg_chain(
    tree: &Tree,
    foot: usize,
    side: Side,
    moving: &[usize],
) -> Result<[usize; JOINTS_PER_LEG], RobotError> {
    let names = |ks: &[usize]| {
        ks.iter()
            .map(|k| tree.joints[*k].name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let foot_el = link_el(&tree.links[foot].name);
    if moving.len() < JOINTS_PER_LEG {
        // A fixed joint between the hip and the foot is a locked leg joint.
        if let (Some(first), Some(last)) = (moving.first(), moving.last()) {
            let path = tree.path(foot);
            let (a, b) = (
                path.iter().position(|k| k == first).unwrap_or(0),
                path.iter().position(|k| k == last).unwrap_or(0),
            );
            if let Some(k) = path[a..b].iter().find(|k| tree.joints[**k].kind == "fixed") {
                return Err(RobotError::invalid(
                    joint_el(&tree.joints[*k].name),
                    format!(
                        "is fixed inside the {side:?} leg: the gait needs six moving leg joints \
                         (hip yaw, roll, pitch, knee, ankle pitch, roll); the leg has {}: {}",
                        moving.len(),
                        names(moving)
                    ),
                ));
            }
        }
        return Err(RobotError::invalid(
            foot_el,
            format!(
                "ends the {side:?} leg, whose path from the trunk has {} moving joints ({}); a \
                 leg needs six: hip yaw, roll, pitch, knee, ankle pitch, roll",
                moving.len(),
                names(moving)
            ),
        ));
    }
    if moving.len() > JOINTS_PER_LEG {
        let extra = &moving[..moving.len() - JOINTS_PER_LEG];
        return Err(RobotError::invalid(
            joint_el(&tree.joints[extra[0]].name),
            format!(
                "is an extra joint: the path from the trunk to the {side:?} foot '{}' has {} \
                 moving joints ({}); a leg needs six, from the link both legs hang from",
                tree.links[foot].name,
                moving.len(),
                names(moving)
            ),
        ));
    }
    let chain: [usize; JOINTS_PER_LEG] = std::array::from_fn(|i| moving[i]);
    for (k, j) in chain.iter().zip(LegJoint::ALL) {
        let joint = &tree.joints[*k];
        let el = joint_el(&joint.name);
        if joint.kind == "prismatic" {
            return Err(RobotError::invalid(
                el,
                "is prismatic; leg joints must be revolute",
            ));
        }
        if joint.mimic {
            return Err(RobotError::invalid(
                el,
                "is a mimic joint; the leg's joints must move on their own",
            ));
        }
        let a = tree.axis_world(*k);
        let want = Vector3::from(j.axis());
        if a.dot(&want).abs() < AXIS_COS {
            return Err(RobotError::invalid(
                el,
                format!(
                    "turns about ({:.3}, {:.3}, {:.3}) in the zero pose; as the {j:?} joint of \
                     the {side:?} leg it must turn about {} (the leg's joints turn about {}; \
                     the supported chain, hip yaw, roll, pitch, knee, ankle pitch, roll, turns \
                     about {})",
                    a.x,
                    a.y,
                    a.z,
                    axis_name(&want),
                    axis_names(chain.iter().map(|&k| tree.axis_world(k))),
                    axis_names(LegJoint::ALL.iter().map(|j| Vector3::from(j.axis())))
                ),
            ));
        }
        if let Some([lo, hi]) = joint.limits
            && lo >= hi
        {
            return Err(RobotError::invalid(
                el,
                format!("is locked (limits [{lo}, {hi}]): the gait needs it to move"),
            ));
        }
    }
    Ok(chain)
}

/// An axis-aligned box: lower and upper corner.
use super::mesh::{self, Bounds};

/// A rigid body made of link `base` and every link hanging from it through non-leg joints;
/// its frame is aligned with the root frame, its origin at `base`'s.
fn merged_body(
    tree: &Tree,
    base: usize,
    members: &[usize],
    shapes_from_meshes: bool,
) -> Result<(Link, Vec<Bounds>), RobotError> {
    let origin = tree.place[base].pos;
    let rel = |l: usize| -> (Vector3<f64>, Place) {
        let p = tree.place[l];
        (
            if l == base {
                Vector3::zeros()
            } else {
                p.pos - origin
            },
            p,
        )
    };
    let mut parts: Vec<(f64, Vector3<f64>, Matrix3<f64>)> = Vec::new();
    let mut shapes = Vec::new();
    let mut mesh_bounds = Vec::new();
    for &l in members {
        let (r, place) = rel(l);
        let link = &tree.links[l];
        let to_body = |o: &Origin| -> (Vector3<f64>, Rotation3<f64>, bool) {
            let (p, rot, plain) = if place.plain {
                (o.xyz, o.rot, o.plain)
            } else {
                (place.rot * o.xyz, place.rot * o.rot, false)
            };
            (if l == base { p } else { r + p }, rot, plain)
        };
        if let Some((o, m, inertia)) = &link.inertial {
            let (com, rot, plain) = to_body(o);
            let i = if plain {
                *inertia
            } else {
                rot.matrix() * inertia * rot.matrix().transpose()
            };
            parts.push((*m, com, i));
        }
        for (o, g) in &link.collisions {
            let (pos, rot, plain) = to_body(o);
            match g {
                UGeometry::Shape(geometry) => {
                    let (geometry, plain) = match (geometry, axis_permutation(&rot)) {
                        // A box turned by quarter turns is a level box of permuted extents.
                        (Geometry::Box { half_extents }, Some(p)) if !plain => {
                            let h = p * Vector3::from(*half_extents);
                            let h = [h.x.abs(), h.y.abs(), h.z.abs()];
                            (Geometry::Box { half_extents: h }, true)
                        }
                        _ => (*geometry, plain),
                    };
                    let q = UnitQuaternion::from_rotation_matrix(&rot);
                    shapes.push(Shape {
                        geometry,
                        position: [pos.x, pos.y, pos.z],
                        orientation: if plain {
                            [1.0, 0.0, 0.0, 0.0]
                        } else {
                            [q.w, q.i, q.j, q.k]
                        },
                    });
                }
                UGeometry::Mesh { path, scale } if shapes_from_meshes => {
                    let (lo, hi) = mesh::bounds(&link_el(&link.name), path)?;
                    let corners = (0..8).map(|c| {
                        let v = Vector3::new(
                            if c & 1 == 0 { lo.x } else { hi.x },
                            if c & 2 == 0 { lo.y } else { hi.y },
                            if c & 4 == 0 { lo.z } else { hi.z },
                        );
                        pos + rot * v.component_mul(scale)
                    });
                    let (mut a, mut b) = (
                        Vector3::repeat(f64::INFINITY),
                        -Vector3::repeat(f64::INFINITY),
                    );
                    for c in corners {
                        a = a.inf(&c);
                        b = b.sup(&c);
                    }
                    mesh_bounds.push((a, b));
                }
                UGeometry::Mesh { .. } => {}
            }
        }
    }
    let name = tree.links[base].name.clone();
    let el = link_el(&name);
    let mass: f64 = parts.iter().map(|p| p.0).sum();
    if parts.is_empty() || mass <= 0.0 || mass.is_nan() {
        return Err(RobotError::invalid(
            el,
            "has no mass (no <inertial> in it or in the links fixed to it)",
        ));
    }
    let (com, inertia) = if let [(m, c, i)] = parts.as_slice() {
        let _ = m;
        (*c, Inertia::from_matrix(i))
    } else {
        let com = parts.iter().map(|(m, c, _)| c * *m).sum::<Vector3<f64>>() / mass;
        let mut total = Matrix3::zeros();
        for (m, c, i) in &parts {
            let d = c - com;
            total += i + (Matrix3::identity() * d.dot(&d) - d * d.transpose()) * *m;
        }
        (com, Inertia::from_matrix(&total))
    };
    Ok((
        Link {
            name,
            mass,
            com: [com.x, com.y, com.z],
            inertia,
            shapes,
        },
        mesh_bounds,
    ))
}

/// `rot` rounded to a signed permutation of the axes, if it is one (within 1e-6).
fn axis_permutation(rot: &Rotation3<f64>) -> Option<Matrix3<f64>> {
    let m = rot.matrix().map(|v| v.round());
    ((rot.matrix() - m).abs().max() < 1e-6).then_some(m)
}

/// The sole of a foot: its lowest level box, else a box from its mesh bounds (added to its
/// shapes).
fn sole_of(foot: &mut Link, meshes: &[Bounds]) -> Result<Sole, RobotError> {
    let el = link_el(&foot.name);
    let boxes = foot
        .shapes
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match s.geometry {
            Geometry::Box { half_extents } => Some((i, s, half_extents)),
            _ => None,
        });
    if let Some((i, s, h)) =
        boxes.min_by(|a, b| (a.1.position[2] - a.2[2]).total_cmp(&(b.1.position[2] - b.2[2])))
    {
        let q = quat(s.orientation);
        if q.angle() > 1e-6 {
            return Err(RobotError::invalid(
                el,
                "the sole's collision box must be level and aligned with the foot",
            ));
        }
        return Ok(Sole {
            shape: i,
            centre: [s.position[0], s.position[1], s.position[2] - h[2]],
            length: 2.0 * h[0],
            width: 2.0 * h[1],
        });
    }
    let Some((lo, hi)) = meshes.iter().min_by(|a, b| a.0.z.total_cmp(&b.0.z)) else {
        return Err(RobotError::invalid(
            el,
            "the foot has no collision box or mesh to take its sole from",
        ));
    };
    let h = (hi - lo) / 2.0;
    let c = (hi + lo) / 2.0;
    foot.shapes.push(Shape {
        geometry: Geometry::Box {
            half_extents: [h.x, h.y, h.z],
        },
        position: [c.x, c.y, c.z],
        orientation: [1.0, 0.0, 0.0, 0.0],
    });
    Ok(Sole {
        shape: foot.shapes.len() - 1,
        centre: [c.x, c.y, lo.z],
        length: 2.0 * h.x,
        width: 2.0 * h.y,
    })
}

/// The built-in humanoid's servo of each leg joint, its leg length and mass: servos of any
/// other robot are scaled from these by dynamic similarity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoReference {
    /// Servo of each joint, in [`LegJoint::ALL`] order.
    pub servos: [Servo; JOINTS_PER_LEG],
    /// Default limits of each joint (left leg) for joints that give none.
    pub limits: [[f64; 2]; JOINTS_PER_LEG],
    /// Leg length (m).
    pub leg_length: f64,
    /// Mass (kg).
    pub mass: f64,
    /// A leg's moment of inertia about the hip pitch axis in the zero pose (kg m^2).
    pub leg_inertia: f64,
}

impl Description {
    /// Reads a biped from a URDF file (what is supported: below). Servo gains
    /// are scaled from `reference` by the robot's mass and leg length.
    ///
    /// The supported robot: the root link is the trunk. On each side (left: positive y in the
    /// zero pose) the lowest leaf link ends a leg (or the link [`Feet`] names, where the lowest
    /// leaf is not the foot), and its path from the trunk has exactly six revolute (or
    /// continuous) joints turning, in the zero pose, about z, x, y, y, y and x (hip yaw, roll,
    /// pitch, knee, ankle pitch, roll), each with either sign. Links hanging from a leg link
    /// through fixed joints (a sole frame, a sensor) join that link; every other joint is held,
    /// those above the link both legs hang from (a waist below a chest that is the root) among
    /// them. The foot's sole is the bottom face of its lowest collision box, or of the bounds of
    /// its collision mesh (STL, COLLADA or OBJ). Collision shapes other than boxes, spheres,
    /// cylinders and capsules (`<capsule radius length>`, an extension) are left out: falls are
    /// told by the trunk's tilt.
    pub fn from_urdf(path: &Path, reference: &ServoReference) -> Result<Self, RobotError> {
        let text = std::fs::read_to_string(path).map_err(|e| RobotError::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?;
        let dir = path.parent().unwrap_or(Path::new("."));
        Self::from_urdf_str(&text, dir, reference)
    }

    /// Reads a biped from URDF text; relative mesh paths resolve against `dir`.
    pub fn from_urdf_str(
        text: &str,
        dir: &Path,
        reference: &ServoReference,
    ) -> Result<Self, RobotError> {
        Self::from_urdf_feet(text, dir, reference, None)
    }

    /// [`Description::from_urdf_str`], the legs ending at the links `feet` names when given.
    pub fn from_urdf_feet(
        text: &str,
        dir: &Path,
        reference: &ServoReference,
        feet: Option<&Feet>,
    ) -> Result<Self, RobotError> {
        let doc = roxmltree::Document::parse(text).map_err(|e| RobotError::Xml(e.to_string()))?;
        let robot = doc.root_element();
        if robot.tag_name().name() != "robot" {
            return Err(RobotError::Xml(format!(
                "the root element is <{}>, not <robot>",
                robot.tag_name().name()
            )));
        }
        let name = robot.attribute("name").unwrap_or("robot").to_string();
        let mut links = Vec::new();
        let mut index = HashMap::new();
        for l in children(robot, "link") {
            let link = parse_link(l, dir)?;
            if index.insert(link.name.clone(), links.len()).is_some() {
                return Err(RobotError::invalid(link_el(&link.name), "is defined twice"));
            }
            links.push(link);
        }
        let mut joints = Vec::new();
        let mut joint_names = HashMap::new();
        for j in children(robot, "joint") {
            let joint = parse_joint(j, &index)?;
            if joint_names.insert(joint.name.clone(), ()).is_some() {
                return Err(RobotError::invalid(
                    joint_el(&joint.name),
                    "is defined twice",
                ));
            }
            joints.push(joint);
        }
        if links.is_empty() {
            return Err(RobotError::invalid("the robot", "has no links"));
        }
        let tree = Tree::new(links, joints)?;
        let feet = match feet {
            None => None,
            Some(f) => {
                let mut found = [0; 2];
                for (slot, side) in found.iter_mut().zip(Side::BOTH) {
                    *slot = *index.get(f.on(side)).ok_or_else(|| {
                        RobotError::invalid(
                            link_el(f.on(side)),
                            format!("is named as the {side:?} foot but the robot has no such link"),
                        )
                    })?;
                }
                Some(found)
            }
        };
        build(&tree, name, reference, feet)
    }
}

fn build(
    tree: &Tree,
    name: String,
    reference: &ServoReference,
    feet: Option<[usize; 2]>,
) -> Result<Description, RobotError> {
    // The lowest leaf on each side ends a leg.
    let lowest = |side: Side| {
        tree.order
            .iter()
            .copied()
            .filter(|l| tree.is_leaf(*l) && *l != tree.root)
            .filter(|l| tree.place[*l].pos.y * side.sign() > 1e-9)
            .min_by(|a, b| {
                let (pa, pb) = (tree.place[*a].pos, tree.place[*b].pos);
                pa.z.total_cmp(&pb.z)
                    .then(tree.path(*b).len().cmp(&tree.path(*a).len()))
            })
    };
    let mut found = Vec::new();
    for (i, side) in Side::BOTH.into_iter().enumerate() {
        let foot = match feet {
            Some(named) => {
                let foot = named[i];
                if tree.place[foot].pos.y * side.sign() <= 1e-9 {
                    return Err(RobotError::invalid(
                        link_el(&tree.links[foot].name),
                        format!("is named as the {side:?} foot but is not on that side (y)"),
                    ));
                }
                foot
            }
            None => lowest(side).ok_or_else(|| {
                RobotError::invalid(
                    "the robot",
                    format!("has one leg only: no leg found on the {side:?} side (y of that sign)"),
                )
            })?,
        };
        found.push((foot, side));
    }
    // Moving joints on both feet's paths lie above the link the legs branch from (a waist
    // below the root link): they are held, and each leg is what follows them.
    let moving = |foot: usize| -> Vec<usize> {
        tree.path(foot)
            .into_iter()
            .filter(|k| is_moving(&tree.joints[*k].kind))
            .collect()
    };
    let paths: Vec<Vec<usize>> = found.iter().map(|(foot, _)| moving(*foot)).collect();
    let shared = paths[0]
        .iter()
        .zip(&paths[1])
        .take_while(|(a, b)| a == b)
        .count();
    let mut chains = Vec::new();
    for ((foot, side), path) in found.into_iter().zip(&paths) {
        chains.push(leg_chain(tree, foot, side, &path[shared..])?);
    }
    if tree.joints[chains[0][0]].parent != tree.joints[chains[1][0]].parent {
        return Err(RobotError::invalid(
            joint_el(&tree.joints[chains[1][0]].name),
            "the two legs must hang from the same link",
        ));
    }
    let leg_joints: Vec<usize> = chains.iter().flatten().copied().collect();
    // Each link belongs to the body of its nearest ancestor moved by a leg joint (or the trunk).
    let mut body_of = vec![None::<usize>; tree.links.len()];
    for &l in &tree.order {
        body_of[l] = match tree.parent_joint[l] {
            None => None,
            Some(k) if leg_joints.contains(&k) => Some(k),
            Some(k) => body_of[tree.joints[k].parent],
        };
    }
    let members = |body: Option<usize>| -> Vec<usize> {
        tree.order
            .iter()
            .copied()
            .filter(|l| body_of[*l] == body)
            .collect()
    };
    // A link's own inertia that is not physical is refused where the link is simulated as
    // its own body or is the trunk's base, and remarked where it is held in the trunk.
    let mut remarks = Vec::new();
    for &l in &tree.order {
        let link = &tree.links[l];
        if let Some(problem) = &link.inertia_problem {
            if l == tree.root || body_of[l].is_some() {
                return Err(RobotError::invalid(link_el(&link.name), problem.clone()));
            }
            remarks.push(format!(
                "{}: {problem}; held, it counts only in the trunk's inertia, which is checked",
                link_el(&link.name)
            ));
        }
    }
    let held_joints: Vec<String> = tree
        .joints
        .iter()
        .enumerate()
        .filter(|(k, j)| is_moving(&j.kind) && !leg_joints.contains(k))
        .map(|(_, j)| j.name.clone())
        .collect();
    let (trunk, _) = merged_body(tree, tree.root, &members(None), false)?;
    let mut legs = Vec::new();
    let mut raw_limits = Vec::new();
    for (side, chain) in Side::BOTH.iter().zip(&chains) {
        let mut links = Vec::new();
        let mut foot_meshes = Vec::new();
        for (i, k) in chain.iter().enumerate() {
            let base = tree.joints[*k].child;
            let (link, meshes) = merged_body(tree, base, &members(Some(*k)), i == 5)?;
            links.push(link);
            foot_meshes = meshes;
        }
        let mut links: [Link; JOINTS_PER_LEG] = links
            .try_into()
            .map_err(|_| RobotError::invalid("leg", "six links"))?;
        let sole = sole_of(&mut links[5], &foot_meshes)?;
        let mut joints = Vec::new();
        for (i, (k, j)) in chain.iter().zip(LegJoint::ALL).enumerate() {
            let joint = &tree.joints[*k];
            let a = tree.axis_world(*k);
            let sign = if a.dot(&Vector3::from(j.axis())) >= 0.0 {
                1.0
            } else {
                -1.0
            };
            let axis = if a == Vector3::from(j.axis()) {
                a
            } else {
                a * sign
            };
            // The joint centre in the parent body's frame.
            let parent_base = if i == 0 {
                tree.root
            } else {
                tree.joints[chain[i - 1]].child
            };
            let p = tree.place[joint.child].pos;
            let origin = if joint.parent == parent_base {
                let pp = tree.place[parent_base];
                if pp.plain {
                    joint.origin.xyz
                } else {
                    pp.rot * joint.origin.xyz
                }
            } else {
                p - tree.place[parent_base].pos
            };
            let limits = match joint.limits {
                Some([lo, hi]) if sign > 0.0 => [lo, hi],
                Some([lo, hi]) => [-hi, -lo],
                None => {
                    let [lo, hi] = reference.limits[i];
                    match (j, side) {
                        (
                            LegJoint::HipYaw | LegJoint::HipRoll | LegJoint::AnkleRoll,
                            Side::Right,
                        ) => [-hi, -lo],
                        _ => [lo, hi],
                    }
                }
            };
            raw_limits.push(limits);
            joints.push(Joint {
                name: joint.name.clone(),
                origin: [origin.x, origin.y, origin.z],
                axis: [axis.x, axis.y, axis.z],
                sign,
                limits,
                servo: reference.servos[i],
            });
        }
        let joints: [Joint; JOINTS_PER_LEG] = joints
            .try_into()
            .map_err(|_| RobotError::invalid("leg", "six joints"))?;
        legs.push(Leg {
            joints,
            links,
            sole,
        });
    }
    let legs: [Leg; 2] = legs
        .try_into()
        .map_err(|_| RobotError::invalid("the robot", "two legs"))?;
    let figure = figure_of(&trunk);
    let mut d = Description {
        name,
        trunk,
        legs,
        held_joints,
        figure,
        remarks,
    };
    // Servos: torque limits by dynamic similarity (m g l); stiffness and damping keep the
    // servo's bandwidth on the leg's own inertia about the hip, I g / l and I sqrt(g / l).
    let length = d.leg_length() / reference.leg_length;
    let mass = d.mass() / reference.mass;
    let inertia = d.leg_inertia() / reference.leg_inertia;
    for leg in &mut d.legs {
        for (joint, r) in leg.joints.iter_mut().zip(&reference.servos) {
            joint.servo = Servo {
                stiffness: r.stiffness * inertia / length,
                damping: r.damping * inertia / length.sqrt(),
                max_torque: r.max_torque * mass * length,
            };
        }
    }
    Ok(d)
}

/// The name of the coordinate axis `a` turns about (`x`, `y`, `z`), or `oblique`.
fn axis_name(a: &Vector3<f64>) -> &'static str {
    let i = a.iamax();
    if a[i].abs() >= AXIS_COS {
        ["x", "y", "z"][i]
    } else {
        "oblique"
    }
}

/// [`axis_name`] of each axis, comma separated.
fn axis_names(axes: impl Iterator<Item = Vector3<f64>>) -> String {
    axes.map(|a| axis_name(&a)).collect::<Vec<_>>().join(", ")
}

/// The stick figure of a trunk: the head on its highest sphere, or above its highest point.
fn figure_of(trunk: &Link) -> Figure {
    let top = |s: &Shape| {
        let r = match s.geometry {
            Geometry::Box { half_extents } => Vector3::from(half_extents).norm(),
            Geometry::Sphere { radius } => radius,
            Geometry::Capsule {
                half_height,
                radius,
            }
            | Geometry::Cylinder {
                half_height,
                radius,
            } => half_height + radius,
        };
        s.position[2] + r
    };
    let sphere = trunk
        .shapes
        .iter()
        .filter(|s| matches!(s.geometry, Geometry::Sphere { .. }))
        .max_by(|a, b| a.position[2].total_cmp(&b.position[2]));
    let high = trunk
        .shapes
        .iter()
        .map(top)
        .fold(2.0 * trunk.com[2].max(0.05), f64::max);
    match sphere {
        Some(s) => {
            let r = match s.geometry {
                Geometry::Sphere { radius } => radius,
                _ => 0.0,
            };
            Figure {
                neck: [s.position[0], s.position[1], s.position[2] - r],
                head: s.position,
                head_radius: r,
            }
        }
        None => {
            let r = 0.15 * high.abs().max(0.05);
            Figure {
                neck: [0.0, 0.0, high],
                head: [0.0, 0.0, high + r],
                head_radius: r,
            }
        }
    }
}

fn fmt3(v: [f64; 3]) -> String {
    format!("{} {} {}", v[0], v[1], v[2])
}

fn shape_urdf(s: &Shape) -> String {
    let q = quat(s.orientation);
    let (r, p, y) = q.euler_angles();
    let geometry = match s.geometry {
        Geometry::Box { half_extents: h } => {
            format!(
                "<box size=\"{}\"/>",
                fmt3([2.0 * h[0], 2.0 * h[1], 2.0 * h[2]])
            )
        }
        Geometry::Sphere { radius } => format!("<sphere radius=\"{radius}\"/>"),
        Geometry::Capsule {
            half_height,
            radius,
        } => format!(
            "<capsule radius=\"{radius}\" length=\"{}\"/>",
            2.0 * half_height
        ),
        Geometry::Cylinder {
            half_height,
            radius,
        } => format!(
            "<cylinder radius=\"{radius}\" length=\"{}\"/>",
            2.0 * half_height
        ),
    };
    let rpy = if s.orientation == [1.0, 0.0, 0.0, 0.0] {
        String::new()
    } else {
        format!(" rpy=\"{r} {p} {y}\"")
    };
    format!(
        "    <collision>\n      <origin xyz=\"{}\"{rpy}/>\n      <geometry>{geometry}</geometry>\n    </collision>\n",
        fmt3(s.position)
    )
}

fn link_urdf(l: &Link) -> String {
    let m = l.inertia.matrix();
    let inertia = if l.inertia.is_diagonal() {
        let [a, b, c] = l.inertia.principal;
        format!("ixx=\"{a}\" ixy=\"0\" ixz=\"0\" iyy=\"{b}\" iyz=\"0\" izz=\"{c}\"")
    } else {
        format!(
            "ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"",
            m[(0, 0)],
            m[(0, 1)],
            m[(0, 2)],
            m[(1, 1)],
            m[(1, 2)],
            m[(2, 2)]
        )
    };
    let shapes: String = l.shapes.iter().map(shape_urdf).collect();
    format!(
        "  <link name=\"{}\">\n    <inertial>\n      <origin xyz=\"{}\"/>\n      <mass value=\"{}\"/>\n      <inertia {inertia}/>\n    </inertial>\n{shapes}  </link>\n",
        l.name,
        fmt3(l.com),
        l.mass
    )
}

impl Description {
    /// This robot as URDF text: the trunk and the twelve leg links with their inertials and
    /// collision shapes (capsules as `<capsule>`), and the twelve revolute joints.
    pub fn to_urdf(&self) -> String {
        let mut out = format!(
            "<?xml version=\"1.0\"?>\n<!-- Written by steplearn's `robot export`. -->\n<robot name=\"{}\">\n",
            self.name
        );
        out += &link_urdf(&self.trunk);
        for leg in &self.legs {
            let mut parent = &self.trunk.name;
            for (joint, link) in leg.joints.iter().zip(&leg.links) {
                out += &link_urdf(link);
                let axis = joint.axis.map(|a| a * joint.sign);
                let [lo, hi] = if joint.sign > 0.0 {
                    joint.limits
                } else {
                    [-joint.limits[1], -joint.limits[0]]
                };
                out += &format!(
                    "  <joint name=\"{}\" type=\"revolute\">\n    <parent link=\"{parent}\"/>\n    <child link=\"{}\"/>\n    <origin xyz=\"{}\"/>\n    <axis xyz=\"{}\"/>\n    <limit lower=\"{lo}\" upper=\"{hi}\" effort=\"{}\" velocity=\"20\"/>\n    <dynamics damping=\"{}\"/>\n  </joint>\n",
                    joint.name,
                    link.name,
                    fmt3(joint.origin),
                    fmt3(axis),
                    joint.servo.max_torque,
                    joint.servo.damping
                );
                parent = &link.name;
            }
        }
        out += "</robot>\n";
        out
    }
}

impl Default for ServoReference {
    /// The built-in humanoid's servos, limits, leg length and mass (what
    /// `sim::BodyConfig::servo_reference` gives for the default body, to within rounding).
    fn default() -> Self {
        let servo = |stiffness, damping, max_torque| Servo {
            stiffness,
            damping,
            max_torque,
        };
        ServoReference {
            servos: [
                servo(300.0, 6.0, 60.0),
                servo(800.0, 15.0, 150.0),
                servo(800.0, 15.0, 150.0),
                servo(800.0, 15.0, 150.0),
                servo(500.0, 8.0, 80.0),
                servo(500.0, 8.0, 80.0),
            ],
            limits: [
                [-0.6, 0.6],
                [-0.6, 0.6],
                [-1.8, 0.8],
                [0.0, 2.4],
                [-0.9, 0.9],
                [-0.6, 0.6],
            ],
            leg_length: 0.245 * 2.0 + 0.246 * 2.0 + 0.039 * 2.0,
            mass: 13.5,
            leg_inertia: 0.620_594,
        }
    }
}
