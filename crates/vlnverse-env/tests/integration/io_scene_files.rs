//! Scene files: glTF validity and extras, lossless save/load, clear errors, atomic folders.

use crate::io_common;

use io_common::fixture_scene;
use std::path::Path;
use vlnverse_env::io::{self, glb};
use vlnverse_env::{EnvError, Shape};

fn err_text(e: EnvError) -> String {
    e.to_string()
}

#[test]
fn glb_reloads_with_gltf_crate_with_every_object_node_and_extras() {
    let scene = fixture_scene();
    let bytes = glb::write_glb(&scene);
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!(bytes.len() % 4, 0);
    // Gltf::from_slice validates the document (indices, accessors, min/max of POSITION...).
    let doc = gltf::Gltf::from_slice(&bytes).expect("valid glTF");
    let blob = doc.blob.clone().expect("BIN chunk");
    let roots: Vec<_> = doc.default_scene().unwrap().nodes().collect();
    assert_eq!(roots.len(), scene.objects.len());
    for (node, o) in roots.iter().zip(&scene.objects) {
        assert_eq!(node.name(), Some(o.name.as_str()));
        let (t, r, s) = node.transform().decomposed();
        assert_eq!(t, o.pose.position);
        for (a, b) in r.iter().zip(o.pose.rotation) {
            assert!((a - b).abs() < 1e-6);
        }
        assert_eq!(s, [1.0; 3]);
        let extras: serde_json::Value =
            serde_json::from_str(node.extras().as_ref().expect("extras").get()).unwrap();
        assert_eq!(extras["id"], o.id);
        assert_eq!(extras["class"], o.class.name());
        assert_eq!(extras["class_id"], o.class.id());
        assert_eq!(extras["mass"].as_f64().unwrap() as f32, o.physics.mass);
        assert_eq!(
            extras["friction"].as_f64().unwrap() as f32,
            o.physics.friction
        );
        assert_eq!(extras["room"], serde_json::json!(o.room));
        assert_eq!(extras["supported_by"], serde_json::json!(o.supported_by));
        assert_eq!(extras["color"], o.color);
        assert_eq!(extras["material"], o.material);
        let motion = serde_json::to_value(o.physics.motion).unwrap();
        assert_eq!(extras["motion"], motion);
    }
    // Object-local geometry placed by the node transform reproduces the world bounding box.
    let table = &scene.objects[1];
    let mesh = roots[1].mesh().expect("table mesh");
    // Top (brown) and legs (black): one primitive per colour.
    assert_eq!(mesh.primitives().count(), 2);
    let mut world = vlnverse_env::Aabb::EMPTY;
    for p in mesh.primitives() {
        let bb = p.bounding_box();
        let r = p.reader(|_| Some(&blob[..]));
        for v in r.read_positions().unwrap() {
            for (i, x) in v.iter().enumerate() {
                assert!(*x >= bb.min[i] && *x <= bb.max[i]);
            }
            world.extend(table.pose.transform_point(glam::Vec3::from_array(v)));
        }
        let mat = p.material().pbr_metallic_roughness().base_color_factor();
        assert!(table
            .parts
            .iter()
            .any(|pt| pt.color == [mat[0], mat[1], mat[2]]));
    }
    for i in 0..3 {
        assert!(
            (world.min[i] - table.bbox.min[i]).abs() < 0.02,
            "{world:?} vs {:?}",
            table.bbox
        );
        assert!(
            (world.max[i] - table.bbox.max[i]).abs() < 0.02,
            "{world:?} vs {:?}",
            table.bbox
        );
    }
    // The mesh part is a child node holding the part transform and glTF mesh 0.
    let statue = &roots[3];
    let child = statue.children().next().expect("mesh part child node");
    assert_eq!(child.mesh().unwrap().index(), 0);
    assert_eq!(
        child.transform().decomposed().0,
        scene.objects[3].parts[0].transform.position
    );
}

#[test]
fn glb_is_deterministic_and_read_glb_sees_everything() {
    let scene = fixture_scene();
    let a = glb::write_glb(&scene);
    assert_eq!(a, glb::write_glb(&scene.clone()));
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.glb");
    io::write_atomic(&p, &a).unwrap();
    let c = glb::read_glb(&p).unwrap();
    assert_eq!(c.roots.len(), scene.objects.len());
    assert_eq!(c.nodes.len(), scene.objects.len() + 1);
    let Shape::Mesh(m) = &scene.objects[3].parts[0].shape else {
        unreachable!()
    };
    assert_eq!(c.meshes[0].positions, m.positions);
    assert_eq!(c.meshes[0].indices, m.indices);
    let tris: usize = c.meshes.iter().map(|m| m.indices.len()).sum();
    assert_eq!(tris, scene.triangle_count());
}

#[test]
fn save_then_load_is_lossless() {
    let scene = fixture_scene();
    let dir = tempfile::tempdir().unwrap();
    let out = io::write_scene_dir(dir.path(), &scene, &[("notes.txt", b"hi".to_vec())]).unwrap();
    assert_eq!(out, dir.path().join("fixture_0001"));
    let json = std::fs::read_to_string(out.join("scene.json")).unwrap();
    assert!(json.contains("\"glb_mesh\": 0"));
    assert!(
        !json.contains("0.12345679"),
        "mesh vertices must not be in scene.json"
    );
    let back = io::load_scene(&out).unwrap();
    assert_eq!(back, scene);
    assert_eq!(std::fs::read(out.join("notes.txt")).unwrap(), b"hi");
}

#[test]
fn noncanonical_mesh_index_is_rewritten_and_still_round_trips() {
    let mut scene = fixture_scene();
    if let Shape::Mesh(m) = &mut scene.objects[3].parts[0].shape {
        m.glb_mesh = Some(9);
    }
    let dir = tempfile::tempdir().unwrap();
    let out = io::write_scene_dir(dir.path(), &scene, &[]).unwrap();
    let back = io::load_scene(&out).unwrap();
    glb::assign_glb_mesh_indices(&mut scene);
    assert_eq!(back, scene);
}

fn written() -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let out = io::write_scene_dir(dir.path(), &fixture_scene(), &[]).unwrap();
    (dir, out)
}

#[test]
fn missing_files_are_named() {
    let (_d, out) = written();
    std::fs::remove_file(out.join("scene.glb")).unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(e.contains("scene.glb"), "{e}");
    let e = err_text(io::load_scene(out.join("nope")).unwrap_err());
    assert!(e.contains("scene.json"), "{e}");
}

#[test]
fn corrupt_and_truncated_glb_are_reported_with_the_file() {
    let (_d, out) = written();
    let glb_path = out.join("scene.glb");
    let good = std::fs::read(&glb_path).unwrap();
    std::fs::write(&glb_path, &good[..good.len() / 2]).unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(e.contains("scene.glb") && e.contains("truncated"), "{e}");
    std::fs::write(&glb_path, b"this is not a glb file at all").unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(e.contains("scene.glb") && e.contains("glTF"), "{e}");
    // Header intact, JSON chunk damaged.
    let mut bad = good.clone();
    for b in &mut bad[20..60] {
        *b = b'#';
    }
    std::fs::write(&glb_path, &bad).unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(
        e.contains("scene.glb") && e.contains("not a valid glTF"),
        "{e}"
    );
    let e = err_text(glb::read_glb(&glb_path).unwrap_err());
    assert!(e.contains("scene.glb"), "{e}");
}

#[test]
fn bad_json_is_reported_with_file_line_and_field() {
    let (_d, out) = written();
    let p = out.join("scene.json");
    let good = std::fs::read_to_string(&p).unwrap();
    std::fs::write(&p, &good[..good.len() / 3]).unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(e.contains("scene.json") && e.contains("line"), "{e}");
    std::fs::write(&p, good.replace("\"friction\"", "\"frixion\"")).unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(
        e.contains("scene.json") && e.contains("friction") && e.contains("line"),
        "{e}"
    );
    std::fs::write(&p, good.replace("\"dining_table\"", "\"spaceship\"")).unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(
        e.contains("scene.json") && e.contains("\"class\"") && e.contains("spaceship"),
        "{e}"
    );
    // A wrongly typed value: the message quotes the line, so field and value are both named.
    std::fs::write(
        &p,
        good.replacen("\"mass\": ", "\"mass\": \"heavy\", \"m\": ", 1),
    )
    .unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(
        e.contains("scene.json") && e.contains("\"mass\"") && e.contains("heavy"),
        "{e}"
    );
    std::fs::write(
        &p,
        good.replace("\"format_version\": 1", "\"format_version\": 99"),
    )
    .unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(
        e.contains("scene.json") && e.contains("format_version") && e.contains("99"),
        "{e}"
    );
}

#[test]
fn mesh_index_out_of_range_is_an_error() {
    let (_d, out) = written();
    let p = out.join("scene.json");
    let good = std::fs::read_to_string(&p).unwrap();
    std::fs::write(&p, good.replace("\"glb_mesh\": 0", "\"glb_mesh\": 42")).unwrap();
    let e = err_text(io::load_scene(&out).unwrap_err());
    assert!(e.contains("scene.glb") && e.contains("42"), "{e}");
}

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn write_scene_dir_replaces_incomplete_folder_and_leaves_no_temp() {
    let dir = tempfile::tempdir().unwrap();
    let scene = fixture_scene();
    // A half-written folder from an interrupted run, and a stale temp folder.
    let stale = dir.path().join("fixture_0001");
    std::fs::create_dir_all(&stale).unwrap();
    std::fs::write(stale.join("scene.json"), b"{").unwrap();
    std::fs::write(stale.join("junk"), b"x").unwrap();
    assert!(!io::is_complete_scene_dir(&stale));
    let tmp = dir
        .path()
        .join(format!(".fixture_0001.tmp-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let extra: Vec<(&str, Vec<u8>)> = io::BUNDLE_FILES[2..]
        .iter()
        .map(|f| (*f, f.as_bytes().to_vec()))
        .collect();
    let out = io::write_scene_dir(dir.path(), &scene, &extra).unwrap();
    assert_eq!(entries(dir.path()), vec!["fixture_0001".to_string()]);
    let mut want: Vec<String> = io::BUNDLE_FILES.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(entries(&out), want);
    assert!(io::is_complete_scene_dir(&out));
    // Any missing file or an unreadable scene.json makes it incomplete again.
    std::fs::remove_file(out.join("navigable.yaml")).unwrap();
    assert!(!io::is_complete_scene_dir(&out));
    std::fs::write(out.join("navigable.yaml"), b"x").unwrap();
    assert!(io::is_complete_scene_dir(&out));
    std::fs::write(out.join("scene.json"), b"{}").unwrap();
    assert!(!io::is_complete_scene_dir(&out));
}

#[test]
fn write_scene_dir_rejects_bad_ids_and_file_names() {
    let dir = tempfile::tempdir().unwrap();
    let mut scene = fixture_scene();
    let e = io::write_scene_dir(dir.path(), &scene, &[("../x", vec![])]).unwrap_err();
    assert!(e.to_string().contains("../x"), "{e}");
    scene.id = "../evil".into();
    let e = io::write_scene_dir(dir.path(), &scene, &[]).unwrap_err();
    assert!(e.to_string().contains("evil"), "{e}");
    assert!(entries(dir.path()).is_empty());
}

#[test]
fn write_atomic_replaces_and_cleans_up() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("a.bin");
    io::write_atomic(&p, b"one").unwrap();
    io::write_atomic(&p, b"two").unwrap();
    assert_eq!(std::fs::read(&p).unwrap(), b"two");
    assert_eq!(entries(dir.path()), vec!["a.bin".to_string()]);
    let e = io::write_atomic(dir.path().join("missing/a.bin"), b"x").unwrap_err();
    assert!(e.to_string().contains("missing"), "{e}");
}

struct Fixed(Vec<vlnverse_env::Scene>);

impl vlnverse_env::SceneSource for Fixed {
    fn len(&self) -> usize {
        self.0.len()
    }
    fn scene_id(&self, index: usize) -> String {
        self.0[index].id.clone()
    }
    fn scene(&self, index: usize) -> vlnverse_env::Result<vlnverse_env::Scene> {
        Ok(self.0[index].clone())
    }
}

#[test]
fn source_bundles_write_every_file_then_resume_and_force() {
    use vlnverse_env::io::BundleOutcome;
    use vlnverse_env::occupancy::OccupancyConfig;
    let scenes: Vec<_> = (0..3)
        .map(|i| {
            let mut s = fixture_scene();
            s.id = format!("fx_{i}");
            s
        })
        .collect();
    let src = Fixed(scenes);
    let dir = tempfile::tempdir().unwrap();
    let occ = OccupancyConfig::default();
    let count = std::sync::atomic::AtomicUsize::new(0);
    let tick = |_: &BundleOutcome| {
        count.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    };
    let out = io::write_source_bundles(&src, &[2, 0, 1], dir.path(), &occ, false, &tick).unwrap();
    let ids: Vec<_> = out
        .iter()
        .map(|o| match o {
            BundleOutcome::Written { id, rooms, .. } => {
                assert_eq!(*rooms, 1);
                id.clone()
            }
            BundleOutcome::Skipped { .. } => panic!("nothing to skip yet"),
        })
        .collect();
    assert_eq!(ids, ["fx_2", "fx_0", "fx_1"]);
    assert_eq!(count.load(std::sync::atomic::Ordering::Relaxed), 3);
    for i in 0..3 {
        let d = dir.path().join(format!("fx_{i}"));
        assert!(io::is_complete_scene_dir(&d));
        // The graph file is the scene graph's own JSON, readable back.
        let g = std::fs::read_to_string(d.join("scene_graph.json")).unwrap();
        assert!(vlnverse_env::scene_graph::SceneGraph::from_json(&g).is_ok());
        let nav = vlnverse_env::occupancy::GridMap::load_ros(d.join("navigable.yaml")).unwrap();
        assert!(nav.free_area_m2() > 1.0);
    }
    let again = io::write_source_bundles(&src, &[0, 1, 2], dir.path(), &occ, false, &tick).unwrap();
    assert!(again
        .iter()
        .all(|o| matches!(o, BundleOutcome::Skipped { .. })));
    let forced = io::write_source_bundles(&src, &[1], dir.path(), &occ, true, &tick).unwrap();
    assert!(matches!(forced[0], BundleOutcome::Written { .. }));
}

/// The whole error chain, as `anyhow`'s `{:#}` prints it.
fn chain_text(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut next = e.source();
    while let Some(c) = next {
        s += &format!(": {c}");
        next = c.source();
    }
    s
}

/// Regression: `topdown` on a missing folder printed the OS error twice.
#[test]
fn missing_file_error_chain_names_the_os_error_once() {
    let dir = tempfile::tempdir().unwrap();
    let e = io::load_scene(dir.path().join("nope")).unwrap_err();
    let EnvError::Io { error, path } = &e else {
        panic!("{e:?}")
    };
    assert!(path.ends_with("scene.json"));
    let text = chain_text(&e);
    assert_eq!(text.matches(&error.to_string()).count(), 1, "{text}");
    assert!(text.contains("scene.json"), "{text}");
}

#[test]
fn negative_mass_and_friction_are_rejected_naming_the_object() {
    for (from, to, field) in [
        ("\"mass\": 1.5,", "\"mass\": -1.5,", "`physics.mass` = -1.5"),
        (
            "\"friction\": 0.6,",
            "\"friction\": -0.6,",
            "`physics.friction` = -0.6",
        ),
    ] {
        let (_d, out) = written();
        let json_path = out.join("scene.json");
        let json = std::fs::read_to_string(&json_path).unwrap();
        assert!(
            json.contains(from),
            "fixture changed: {from} not in scene.json"
        );
        std::fs::write(&json_path, json.replacen(from, to, 1)).unwrap();
        let e = err_text(io::load_scene(&out).unwrap_err());
        assert!(e.contains("scene.json"), "{e}");
        assert!(e.contains("object 1 (`"), "{e}");
        assert!(e.contains(field), "{e}");
    }
}
