//! The bounds of a mesh file, which is all the loader takes from a mesh (a foot's sole): STL
//! (binary or ASCII), COLLADA (`.dae`: every geometry placed by its scene's nodes, in metres
//! with z up) and Wavefront OBJ.

use std::collections::HashMap;
use std::path::Path;

use nalgebra::{Matrix4, Rotation3, Unit, Vector3};

use super::description::RobotError;

/// The lowest and highest corner of an axis-aligned box.
pub(crate) type Bounds = (Vector3<f64>, Vector3<f64>);

/// The bounds of the vertices of the mesh at `path` (by its extension: `.dae` COLLADA, `.obj`
/// OBJ, anything else STL); errors name `el`.
pub(crate) fn bounds(el: &str, path: &Path) -> Result<Bounds, RobotError> {
    let bytes = std::fs::read(path).map_err(|e| {
        RobotError::invalid(el, format!("cannot read mesh {}: {e}", path.display()))
    })?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (kind, points) = match ext.as_deref() {
        Some("dae") => ("COLLADA", text(&bytes).and_then(collada)),
        Some("obj") => ("OBJ", text(&bytes).and_then(obj)),
        _ => ("STL", stl(&bytes)),
    };
    let bad = |why: String| {
        RobotError::invalid(
            el,
            format!(
                "mesh {} is not a readable {kind} file: {why}",
                path.display()
            ),
        )
    };
    let points = points.map_err(bad)?;
    let mut lo = Vector3::repeat(f64::INFINITY);
    let mut hi = -lo;
    for p in &points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    if points.is_empty() {
        Err(bad("it has no vertices".into()))
    } else if lo.iter().chain(hi.iter()).all(|v| v.is_finite()) {
        Ok((lo, hi))
    } else {
        Err(bad("a vertex is not finite".into()))
    }
}

fn text(bytes: &[u8]) -> Result<&str, String> {
    std::str::from_utf8(bytes).map_err(|e| format!("not UTF-8 ({e})"))
}

fn floats(t: &str, what: &str) -> Result<Vec<f64>, String> {
    words(t.split_whitespace(), what)
}

fn words<'a>(words: impl Iterator<Item = &'a str>, what: &str) -> Result<Vec<f64>, String> {
    words
        .map(|w| {
            w.parse::<f64>()
                .map_err(|_| format!("{what}: '{w}' is not a number"))
        })
        .collect()
}

/// The vertices of a binary or ASCII STL file.
fn stl(bytes: &[u8]) -> Result<Vec<Vector3<f64>>, String> {
    let binary_len = bytes
        .get(80..84)
        .map(|b| 84 + 50 * u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
    let mut points = Vec::new();
    if binary_len == Some(bytes.len()) {
        for tri in bytes[84..].chunks_exact(50) {
            for v in 0..3 {
                let f = |k: usize| {
                    let o = 12 + 12 * v + 4 * k;
                    f32::from_le_bytes([tri[o], tri[o + 1], tri[o + 2], tri[o + 3]]) as f64
                };
                points.push(Vector3::new(f(0), f(1), f(2)));
            }
        }
    } else {
        for line in text(bytes)?.lines() {
            let mut w = line.split_whitespace();
            if w.next() == Some("vertex") {
                let v = words(w, "vertex")?;
                if v.len() != 3 {
                    return Err(format!("a vertex has {} coordinates", v.len()));
                }
                points.push(Vector3::new(v[0], v[1], v[2]));
            }
        }
    }
    Ok(points)
}

/// The vertices (`v x y z`) of an OBJ file.
fn obj(t: &str) -> Result<Vec<Vector3<f64>>, String> {
    let mut points = Vec::new();
    for line in t.lines() {
        let mut w = line.split_whitespace();
        if w.next() == Some("v") {
            let v = words(w, "vertex")?;
            // x y z, optionally w or a colour.
            if v.len() < 3 {
                return Err(format!("a vertex has {} coordinates", v.len()));
            }
            points.push(Vector3::new(v[0], v[1], v[2]));
        }
    }
    Ok(points)
}

fn is<'a, 'i>(n: &roxmltree::Node<'a, 'i>, tag: &str) -> bool {
    n.is_element() && n.tag_name().name() == tag
}

fn first<'a, 'i>(n: roxmltree::Node<'a, 'i>, tag: &str) -> Option<roxmltree::Node<'a, 'i>> {
    n.children().find(|c| is(c, tag))
}

/// A COLLADA document's elements by their `id`.
struct Ids<'a, 'i>(HashMap<&'a str, roxmltree::Node<'a, 'i>>);

impl<'a, 'i> Ids<'a, 'i> {
    fn of(doc: &'a roxmltree::Document<'i>) -> Self {
        let mut ids = HashMap::new();
        for n in doc.descendants().filter(|n| n.is_element()) {
            if let Some(id) = n.attribute("id") {
                // The first of repeated ids, as a search from the top finds.
                ids.entry(id).or_insert(n);
            }
        }
        Ids(ids)
    }

    /// The element with id `url` (`#id`).
    fn get(&self, url: &str) -> Option<roxmltree::Node<'a, 'i>> {
        self.0.get(url.strip_prefix('#').unwrap_or(url)).copied()
    }
}

/// The positions of one `<geometry>`: the sources its meshes' `<vertices>` name as POSITION.
fn geometry_points(ids: &Ids, geometry: roxmltree::Node) -> Result<Vec<Vector3<f64>>, String> {
    let mut points = Vec::new();
    for vertices in geometry.descendants().filter(|n| is(n, "vertices")) {
        for input in vertices.children().filter(|n| is(n, "input")) {
            if input.attribute("semantic") != Some("POSITION") {
                continue;
            }
            let url = input.attribute("source").unwrap_or_default();
            let source = ids.get(url).ok_or_else(|| format!("no source '{url}'"))?;
            let array = first(source, "float_array")
                .ok_or_else(|| format!("source '{url}' has no float_array"))?;
            let values = floats(array.text().unwrap_or_default(), "float_array")?;
            let stride = first(source, "technique_common")
                .and_then(|t| first(t, "accessor"))
                .and_then(|a| a.attribute("stride"))
                .map_or(Ok(3), |s| {
                    s.parse::<usize>().map_err(|_| "a bad stride".to_string())
                })?;
            if stride < 3 {
                return Err(format!("source '{url}' has stride {stride}"));
            }
            points.extend(
                values
                    .chunks_exact(stride)
                    .map(|v| Vector3::new(v[0], v[1], v[2])),
            );
        }
    }
    Ok(points)
}

/// A node's own transform: its `matrix`, `translate`, `rotate` and `scale` children in order.
fn node_transform(node: roxmltree::Node) -> Result<Matrix4<f64>, String> {
    let mut m = Matrix4::identity();
    for c in node.children().filter(|c| c.is_element()) {
        let v = || floats(c.text().unwrap_or_default(), c.tag_name().name());
        let step = match c.tag_name().name() {
            "matrix" => {
                let v = v()?;
                if v.len() != 16 {
                    return Err("a matrix without 16 numbers".into());
                }
                Matrix4::from_row_slice(&v)
            }
            "translate" => match v()?.as_slice() {
                [x, y, z] => Matrix4::new_translation(&Vector3::new(*x, *y, *z)),
                _ => return Err("a translate without 3 numbers".into()),
            },
            "rotate" => match v()?.as_slice() {
                [x, y, z, deg] => {
                    let axis = Vector3::new(*x, *y, *z);
                    if axis.norm() == 0.0 {
                        Matrix4::identity()
                    } else {
                        Rotation3::from_axis_angle(&Unit::new_normalize(axis), deg.to_radians())
                            .to_homogeneous()
                    }
                }
                _ => return Err("a rotate without 4 numbers".into()),
            },
            "scale" => match v()?.as_slice() {
                [x, y, z] => Matrix4::new_nonuniform_scaling(&Vector3::new(*x, *y, *z)),
                _ => return Err("a scale without 3 numbers".into()),
            },
            _ => continue,
        };
        m *= step;
    }
    Ok(m)
}

/// The geometries a scene node and its children instance, each placed by the nodes above it.
fn scene_points(
    ids: &Ids,
    node: roxmltree::Node,
    above: &Matrix4<f64>,
    depth: usize,
    out: &mut Vec<Vector3<f64>>,
) -> Result<(), String> {
    if depth > 64 {
        return Err("scene nodes nested deeper than 64".into());
    }
    let here = above * node_transform(node)?;
    for c in node.children().filter(|c| c.is_element()) {
        match c.tag_name().name() {
            "instance_geometry" => {
                let url = c.attribute("url").unwrap_or_default();
                let g = ids.get(url).ok_or_else(|| format!("no geometry '{url}'"))?;
                out.extend(
                    geometry_points(ids, g)?
                        .iter()
                        .map(|p| here.transform_point(&(*p).into()).coords),
                );
            }
            "instance_node" => {
                let url = c.attribute("url").unwrap_or_default();
                let n = ids.get(url).ok_or_else(|| format!("no node '{url}'"))?;
                scene_points(ids, n, &here, depth + 1, out)?;
            }
            "node" => scene_points(ids, c, &here, depth + 1, out)?,
            _ => {}
        }
    }
    Ok(())
}

/// The vertices of a COLLADA document: the geometries its scene instances, placed by the
/// scene's nodes (every geometry as stored where it has no scene), in metres with z up.
fn collada(t: &str) -> Result<Vec<Vector3<f64>>, String> {
    let doc = roxmltree::Document::parse(t).map_err(|e| format!("malformed XML ({e})"))?;
    let root = doc.root_element();
    if !is(&root, "COLLADA") {
        return Err("the root element is not <COLLADA>".into());
    }
    let asset = first(root, "asset");
    let meter = asset
        .and_then(|a| first(a, "unit"))
        .and_then(|u| u.attribute("meter"))
        .map_or(Ok(1.0), |m| {
            m.parse::<f64>().map_err(|_| "a bad unit".to_string())
        })?;
    // COLLADA's default is y up.
    let up = asset
        .and_then(|a| first(a, "up_axis"))
        .and_then(|u| u.text())
        .map_or("Y_UP", str::trim);
    let ids = Ids::of(&doc);
    let scene = first(root, "scene")
        .and_then(|s| first(s, "instance_visual_scene"))
        .and_then(|i| i.attribute("url"))
        .and_then(|url| ids.get(url));
    let mut points = Vec::new();
    match scene {
        Some(scene) => scene_points(&ids, scene, &Matrix4::identity(), 0, &mut points)?,
        None => {
            for g in doc.descendants().filter(|n| is(n, "geometry")) {
                points.extend(geometry_points(&ids, g)?);
            }
        }
    }
    let to_z_up = |p: Vector3<f64>| match up {
        "X_UP" => Vector3::new(-p.y, p.x, p.z),
        "Y_UP" => Vector3::new(p.x, -p.z, p.y),
        _ => p,
    };
    Ok(points.into_iter().map(|p| to_z_up(p) * meter).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dae(up: &str, unit: f64, node: &str) -> String {
        format!(
            r##"<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="{unit}"/><up_axis>{up}</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="g-pos"><float_array id="g-arr" count="6">0 0 0 1 2 3</float_array>
      <technique_common><accessor source="#g-arr" count="2" stride="3"/></technique_common></source>
    <vertices id="g-v"><input semantic="POSITION" source="#g-pos"/></vertices>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node>{node}<instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>"##
        )
    }

    fn span(points: &[Vector3<f64>]) -> (Vector3<f64>, Vector3<f64>) {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = -lo;
        for p in points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        (lo, hi)
    }

    #[test]
    fn collada_vertices_follow_the_unit_the_up_axis_and_the_nodes() {
        let z = span(&collada(&dae("Z_UP", 1.0, "")).unwrap());
        assert_eq!(z, (Vector3::zeros(), Vector3::new(1.0, 2.0, 3.0)));
        let mm = span(&collada(&dae("Z_UP", 0.001, "")).unwrap());
        assert!((mm.1 - Vector3::new(0.001, 0.002, 0.003)).norm() < 1e-15);
        // y up: the file's y is the world's z, its z the world's -y.
        let y = span(&collada(&dae("Y_UP", 1.0, "")).unwrap());
        assert_eq!(
            y,
            (Vector3::new(0.0, -3.0, 0.0), Vector3::new(1.0, 0.0, 2.0))
        );
        let moved = span(&collada(&dae("Z_UP", 1.0, "<translate>0 0 -1</translate>")).unwrap());
        assert_eq!(
            moved,
            (Vector3::new(0.0, 0.0, -1.0), Vector3::new(1.0, 2.0, 2.0))
        );
        let turned = span(&collada(&dae("Z_UP", 1.0, "<rotate>0 0 1 90</rotate>")).unwrap());
        assert!((turned.0 - Vector3::new(-2.0, 0.0, 0.0)).norm() < 1e-12);
        assert!((turned.1 - Vector3::new(0.0, 1.0, 3.0)).norm() < 1e-12);
    }

    #[test]
    fn obj_and_ascii_stl_vertices_are_read() {
        let o = span(&obj("# c\nv 1 2 3\nvn 0 0 1\nv -1 0 0.5 1\nf 1 2 2\n").unwrap());
        assert_eq!(
            o,
            (Vector3::new(-1.0, 0.0, 0.5), Vector3::new(1.0, 2.0, 3.0))
        );
        let s = "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 2 -1\nendloop\nendfacet\nendsolid a\n";
        assert_eq!(
            span(&stl(s.as_bytes()).unwrap()),
            (Vector3::new(0.0, 0.0, -1.0), Vector3::new(1.0, 2.0, 0.0))
        );
    }

    #[test]
    fn bad_meshes_are_refused_with_the_reason() {
        assert!(
            collada("<COLLADA><oops")
                .unwrap_err()
                .contains("malformed XML")
        );
        assert!(collada("<mesh/>").unwrap_err().contains("<COLLADA>"));
        let broken = dae("Z_UP", 1.0, "").replace("1 2 3", "1 x 3");
        assert!(
            collada(&broken)
                .unwrap_err()
                .contains("'x' is not a number")
        );
        assert!(obj("v 1 2\n").unwrap_err().contains("2 coordinates"));
        let dir = std::env::temp_dir().join(format!("steplearn-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let empty = dir.join("empty.obj");
        std::fs::write(&empty, "# nothing\n").unwrap();
        let e = bounds("link 'foot'", &empty).unwrap_err().to_string();
        assert!(
            e.contains("link 'foot'") && e.contains("no vertices"),
            "{e}"
        );
        let nan = dir.join("nan.obj");
        std::fs::write(&nan, "v NaN 0 0\n").unwrap();
        let e = bounds("link 'foot'", &nan).unwrap_err().to_string();
        assert!(e.contains("not finite"), "{e}");
    }
}
