//! Bevelled boxes: the chamfered mesh is a closed outward surface of the right volume, sharp
//! boxes are drawn as before, `bevel` survives `scene.json` and bad values are refused, and
//! `scene.glb` carries the chamfered triangles.

use crate::common;

use glam::Vec3;
use std::collections::HashMap;
use std::path::Path;
use vlnverse_env::geometry::{
    drawn_bevel, triangle_count, triangle_count_cells, triangulate, triangulate_cells, TriMesh,
    BEVELLED_BOX_TRIANGLES, MAX_BEVEL_FRACTION,
};
use vlnverse_env::io::{glb, json};
use vlnverse_env::{Part, Pose, Scene, SemanticClass, Shape};

fn cuboid(half_extents: [f32; 3], bevel: f32) -> Shape {
    Shape::Cuboid {
        half_extents,
        bevel,
    }
}

/// Every undirected edge is used by exactly two triangles, once in each direction (corners
/// compared bit for bit, as the rasteriser's closed-surface test does).
fn assert_closed(m: &TriMesh) {
    let key = |i: u32| m.positions[i as usize].map(|c| (c + 0.0).to_bits());
    let mut uses: HashMap<([u32; 3], [u32; 3]), i32> = HashMap::new();
    for t in &m.indices {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let (ka, kb) = (key(a), key(b));
            assert_ne!(ka, kb, "degenerate edge in {t:?}");
            *uses.entry((ka, kb)).or_insert(0) += 1;
        }
    }
    for ((a, b), n) in &uses {
        assert_eq!(*n, 1, "directed edge {a:?} -> {b:?} used {n} times");
        assert_eq!(
            uses.get(&(*b, *a)),
            Some(&1),
            "edge {a:?} -> {b:?} has no opposite"
        );
    }
}

/// Signed volume enclosed (divergence theorem), in f64.
fn volume(m: &TriMesh) -> f64 {
    m.indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| Vec3::from_array(m.positions[i as usize]).as_dvec3());
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Volume of a box whose top edges are chamfered by `b`: the four strips cut a prism of
/// section `b^2 / 2` swept with mitred corners around the top, whose section's centroid (`b / 3`
/// in from both faces) runs `4 (h_x + h_z) - 8 b / 3` (Pappus).
fn chamfered_volume(h: [f32; 3], b: f32) -> f64 {
    let h = h.map(f64::from);
    let b = b as f64;
    let full = 8.0 * h[0] * h[1] * h[2];
    full - (b * b / 2.0) * (4.0 * (h[0] + h[2]) - 8.0 * b / 3.0)
}

#[test]
fn bevelled_box_is_closed_outward_inside_the_box_with_the_chamfered_volume() {
    for (h, bevel) in [
        ([0.5, 0.4, 0.3], 0.02),
        ([1.0, 2.0, 0.5], 0.2),
        ([0.6, 0.02, 0.4], 0.01), // a table top
        ([0.3, 0.01, 0.3], 0.5),  // thin panel: clamped to 0.45 of its thickness
    ] {
        let s = cuboid(h, bevel);
        let b = drawn_bevel(h, bevel);
        let min = h.into_iter().fold(f32::MAX, f32::min);
        assert!(
            b > 0.0 && b <= bevel && b <= MAX_BEVEL_FRACTION * min,
            "{b}"
        );
        let m = triangulate(&s);
        assert_eq!(m.triangle_count(), BEVELLED_BOX_TRIANGLES, "{s:?}");
        assert_eq!(triangle_count(&s), m.triangle_count(), "{s:?}");
        assert_eq!(m.positions.len(), m.normals.len());
        assert_closed(&m);
        // Inside the box, and touching each face (the faces are only inset at their rims).
        for p in &m.positions {
            for k in 0..3 {
                assert!(p[k].abs() <= h[k], "{p:?} outside {h:?}");
            }
        }
        for k in 0..3 {
            let max = m.positions.iter().map(|p| p[k]).fold(f32::MIN, f32::max);
            assert_eq!(max, h[k]);
        }
        let v = volume(&m);
        let want = chamfered_volume(h, b);
        assert!((v - want).abs() < 1e-4, "{s:?}: volume {v} vs {want}");
        assert!(v < 8.0 * (h[0] * h[1] * h[2]) as f64, "nothing was cut");
        // Flat normals: unit, the same at a triangle's three corners, along its winding
        // (outward: the box is convex around the origin).
        for t in &m.indices {
            let [a, b, c] = t.map(|i| Vec3::from_array(m.positions[i as usize]));
            let geo = (b - a).cross(c - a).normalize();
            let n = Vec3::from_array(m.normals[t[0] as usize]);
            assert!((n.length() - 1.0).abs() < 1e-5);
            for i in t {
                assert_eq!(m.normals[*i as usize], n.to_array(), "{t:?} not flat");
            }
            assert!(geo.dot(n) > 0.999, "{t:?}: normal {n} vs winding {geo}");
            assert!(n.dot(a + b + c) > 0.0, "{t:?} faces inwards");
        }
        // Two kinds of normal: 6 faces and 4 chamfers at 45 degrees, two triangles each.
        let mut kinds = [0usize; 4];
        for t in &m.indices {
            let n = Vec3::from_array(m.normals[t[0] as usize]);
            kinds[(0..3).filter(|&k| n[k].abs() > 0.1).count()] += 1;
        }
        assert_eq!(kinds, [0, 12, 8, 0]);
    }
}

#[test]
fn sharp_boxes_are_drawn_exactly_as_before() {
    let h = [1.0, 2.0, 3.0];
    let m = triangulate(&cuboid(h, 0.0));
    // The mesh of the two-triangles-per-face box, as written before bevels existed.
    let signs: [[i8; 3]; 24] = [
        [1, -2, 3],
        [1, -2, -3],
        [1, 2, 3],
        [1, 2, -3],
        [-1, -2, -3],
        [-1, -2, 3],
        [-1, 2, -3],
        [-1, 2, 3],
        [-1, 2, 3],
        [1, 2, 3],
        [-1, 2, -3],
        [1, 2, -3],
        [-1, -2, -3],
        [1, -2, -3],
        [-1, -2, 3],
        [1, -2, 3],
        [-1, -2, 3],
        [1, -2, 3],
        [-1, 2, 3],
        [1, 2, 3],
        [1, -2, -3],
        [-1, -2, -3],
        [1, 2, -3],
        [-1, 2, -3],
    ];
    let want: Vec<[f32; 3]> = signs.iter().map(|s| s.map(f32::from)).collect();
    assert_eq!(m.positions, want);
    let mut indices = Vec::new();
    for f in 0..6u32 {
        indices.push([4 * f, 4 * f + 1, 4 * f + 3]);
        indices.push([4 * f, 4 * f + 3, 4 * f + 2]);
    }
    assert_eq!(m.indices, indices);
    let normals: Vec<[f32; 3]> = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ]
    .iter()
    .flat_map(|n| [*n; 4])
    .collect();
    assert_eq!(m.normals, normals);
    // Bevels that cannot be drawn leave the box sharp; so do cells (walls of lit homes).
    for bevel in [-0.0, -0.1, f32::NAN, f32::INFINITY] {
        assert_eq!(triangulate(&cuboid(h, bevel)), m, "bevel {bevel}");
    }
    assert_eq!(triangulate(&cuboid([1.0, 0.0, 1.0], 0.1)), {
        triangulate(&cuboid([1.0, 0.0, 1.0], 0.0))
    });
    let cut = triangulate_cells(&cuboid(h, 0.0), Some(0.75));
    assert_eq!(triangulate_cells(&cuboid(h, 0.1), Some(0.75)), cut);
    assert_eq!(
        triangle_count_cells(&cuboid(h, 0.1), Some(0.75)),
        cut.triangle_count()
    );
    // A box small enough to stay one cell per face is bevelled as without cells.
    let small = cuboid([0.18, 0.0125, 0.18], 0.006);
    assert_eq!(triangulate_cells(&small, Some(1.5)), triangulate(&small));
    assert_eq!(
        triangle_count_cells(&small, Some(1.5)),
        BEVELLED_BOX_TRIANGLES
    );
    assert_eq!(triangle_count(&cuboid(h, 0.1)), BEVELLED_BOX_TRIANGLES);
    assert_eq!(triangle_count(&cuboid(h, 0.0)), 12);
}

/// A one-object scene holding a bevelled box and a sharp one.
fn bevel_scene(bevel: f32) -> Scene {
    let parts = vec![
        Part {
            shape: cuboid([0.4, 0.3, 0.25], bevel),
            transform: Pose::from_yaw(Vec3::new(0.0, 0.3, 0.0), 0.0),
            color: [0.5, 0.3, 0.2],
        },
        Part {
            shape: cuboid([0.1, 0.1, 0.1], 0.0),
            transform: Pose::from_yaw(Vec3::new(0.0, 0.7, 0.0), 0.4),
            color: [0.5, 0.3, 0.2],
        },
    ];
    let o = common::object(
        1,
        SemanticClass::Cabinet,
        Pose::from_yaw(Vec3::new(1.0, 0.0, -1.0), 0.5),
        parts,
    );
    common::scene("bevel_0001", vec![], vec![], vec![o])
}

#[test]
fn scene_json_keeps_the_bevel_and_files_without_it_load_sharp() {
    let path = Path::new("scene.json");
    let scene = bevel_scene(0.015);
    let bytes = json::scene_to_json(&scene);
    let text = String::from_utf8(bytes.clone()).unwrap();
    // Written for the bevelled part only (0 is left out).
    assert_eq!(text.matches("\"bevel\"").count(), 1, "{text}");
    let back = json::scene_from_json(&bytes, path).unwrap();
    assert_eq!(back, scene);
    assert_eq!(
        back.objects[0].parts[0].shape,
        cuboid([0.4, 0.3, 0.25], 0.015)
    );
    // A file written before bevels existed: no field, sharp edges.
    let sharp = bevel_scene(0.0);
    let old = json::scene_to_json(&sharp);
    assert!(!String::from_utf8_lossy(&old).contains("\"bevel\""));
    let loaded = json::scene_from_json(&old, path).unwrap();
    for p in &loaded.objects[0].parts {
        assert!(matches!(p.shape, Shape::Cuboid { bevel, .. } if bevel == 0.0));
    }
    assert_eq!(loaded.triangle_count(), 24);
    assert_eq!(back.triangle_count(), BEVELLED_BOX_TRIANGLES + 12);
}

#[test]
fn bad_bevels_are_refused_naming_the_field_and_value() {
    let path = Path::new("homes/x/scene.json");
    let good = String::from_utf8(json::scene_to_json(&bevel_scene(0.015))).unwrap();
    assert!(good.contains("\"bevel\": 0.015"), "{good}");
    for (value, shown) in [("-0.01", "-0.01"), ("1e39", "inf"), ("null", "null")] {
        let bad = good.replace("\"bevel\": 0.015", &format!("\"bevel\": {value}"));
        let e = json::scene_from_json(bad.as_bytes(), path)
            .expect_err(value)
            .to_string();
        assert!(e.contains("bevel"), "{value}: {e}");
        assert!(e.contains(shown), "{value}: {e}");
        assert!(e.contains("homes/x/scene.json"), "{value}: {e}");
        assert!(e.contains("object 1 (`cabinet_1`) part 0"), "{value}: {e}");
    }
    // A scene built in code with a NaN bevel is written as null, which does not load.
    let nan = json::scene_to_json(&bevel_scene(f32::NAN));
    let e = json::scene_from_json(&nan, path).unwrap_err().to_string();
    assert!(e.contains("bevel"), "{e}");
}

#[test]
fn scene_glb_holds_the_chamfered_triangles() {
    let scene = bevel_scene(0.03);
    let bytes = glb::write_glb(&scene);
    let doc = gltf::Gltf::from_slice(&bytes).expect("valid glTF");
    let blob = doc.blob.clone().expect("BIN chunk");
    let node = doc.default_scene().unwrap().nodes().next().unwrap();
    let mesh = node.mesh().expect("object mesh");
    let mut triangles = 0;
    let mut vertices = 0;
    for p in mesh.primitives() {
        let r = p.reader(|_| Some(&blob[..]));
        triangles += r.read_indices().unwrap().into_u32().count() / 3;
        vertices += r.read_positions().unwrap().count();
        assert_eq!(
            r.read_normals().unwrap().count(),
            r.read_positions().unwrap().count()
        );
    }
    // Both parts share one material: the chamfered box and the sharp one.
    assert_eq!(triangles, BEVELLED_BOX_TRIANGLES + 12);
    assert_eq!(
        vertices,
        triangulate(&scene.objects[0].parts[0].shape)
            .positions
            .len()
            + 24
    );
    // Placed by the node, the file's triangles are the ones the renderers draw (so a ray cast
    // of scene.glb sees the chamfers too).
    let (t, r, _) = node.transform().decomposed();
    let pose = Pose {
        position: t,
        rotation: r,
    };
    let mut from_file: Vec<[f32; 9]> = Vec::new();
    for p in mesh.primitives() {
        let rd = p.reader(|_| Some(&blob[..]));
        let pos: Vec<Vec3> = rd
            .read_positions()
            .unwrap()
            .map(|v| pose.transform_point(Vec3::from_array(v)))
            .collect();
        let idx: Vec<u32> = rd.read_indices().unwrap().into_u32().collect();
        for t in idx.chunks_exact(3) {
            let v = [0, 1, 2].map(|k| pos[t[k] as usize]);
            from_file.push(std::array::from_fn(|i| v[i / 3][i % 3]));
        }
    }
    let mut drawn: Vec<[f32; 9]> = vlnverse_env::geometry::scene_triangles(&scene)
        .iter()
        .map(|t| std::array::from_fn(|i| t.v[i / 3][i % 3]))
        .collect();
    let order = |a: &[f32; 9], b: &[f32; 9]| a.partial_cmp(b).unwrap();
    // Quantised to 0.1 mm so rounding in the two placements sorts alike.
    let q = |t: &mut Vec<[f32; 9]>| {
        for x in t.iter_mut().flatten() {
            *x = (*x * 1e4).round() / 1e4;
        }
        t.sort_by(order);
    };
    q(&mut from_file);
    q(&mut drawn);
    assert_eq!(from_file, drawn);
    let sharp = glb::write_glb(&bevel_scene(0.0));
    let doc = gltf::Gltf::from_slice(&sharp).unwrap();
    let blob = doc.blob.clone().unwrap();
    let mesh = doc
        .default_scene()
        .unwrap()
        .nodes()
        .next()
        .unwrap()
        .mesh()
        .unwrap();
    let n: usize = mesh
        .primitives()
        .map(|p| {
            let r = p.reader(|_| Some(&blob[..]));
            r.read_indices().unwrap().into_u32().count() / 3
        })
        .sum();
    assert_eq!(n, 24);
}
