//! Small files written by the tests themselves: glTF hierarchies and labels, broken files that
//! must give clear errors, and an OBJ + MTL home.

use serde_json::json;
use std::path::{Path, PathBuf};
use vlnverse_env::{Motion, SemanticClass, Shape};
use vlnverse_import::{import_scene, ImportOptions, Unit, UpAxis};

/// Options without room segmentation (these fixtures have no floor plan).
fn opts() -> ImportOptions {
    ImportOptions {
        segment_rooms: false,
        ..Default::default()
    }
}

/// A unit cube centred at the origin: 8 vertices, 12 triangles (counter-clockwise outside).
fn cube() -> (Vec<[f32; 3]>, Vec<u32>) {
    let mut v = Vec::new();
    for i in 0..8 {
        v.push([
            if i & 1 == 0 { -0.5 } else { 0.5 },
            if i & 2 == 0 { -0.5 } else { 0.5 },
            if i & 4 == 0 { -0.5 } else { 0.5 },
        ]);
    }
    let idx = vec![
        0, 2, 1, 1, 2, 3, // -z
        4, 5, 6, 5, 7, 6, // +z
        0, 1, 4, 1, 5, 4, // -y
        2, 6, 3, 3, 6, 7, // +y
        0, 4, 2, 2, 4, 6, // -x
        1, 3, 5, 3, 7, 5, // +x
    ];
    (v, idx)
}

/// Binary buffer with the cube's positions then indices, and the JSON pieces describing it.
fn cube_buffer() -> (Vec<u8>, serde_json::Value, serde_json::Value) {
    let (v, idx) = cube();
    let mut bin = Vec::new();
    for p in &v {
        for c in p {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    let pos_len = bin.len();
    for i in &idx {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let views = json!([
        {"buffer": 0, "byteOffset": 0, "byteLength": pos_len},
        {"buffer": 0, "byteOffset": pos_len, "byteLength": idx.len() * 4}
    ]);
    let accessors = json!([
        {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
         "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
        {"bufferView": 1, "componentType": 5125, "count": idx.len(), "type": "SCALAR"}
    ]);
    (bin, views, accessors)
}

fn glb_bytes(mut doc: serde_json::Value, bin: &[u8]) -> Vec<u8> {
    doc["buffers"] = json!([{"byteLength": bin.len()}]);
    vlnverse_env::io::glb::glb_container(&serde_json::to_vec(&doc).unwrap(), bin)
}

/// A document with one cube mesh (index 0) and the given nodes; material 0 is red.
fn doc_with_nodes(nodes: serde_json::Value, roots: Vec<usize>) -> (serde_json::Value, Vec<u8>) {
    let (bin, views, accessors) = cube_buffer();
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": roots}],
        "nodes": nodes,
        "meshes": [{"name": "CubeMesh", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"name": "red_paint", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.05, 0.05, 1.0]}}],
        "accessors": accessors,
        "bufferViews": views
    });
    (doc, bin)
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

#[test]
fn hierarchy_transforms_are_baked_and_extras_label_the_subtree() {
    // Parent "Thing" with extras class bed, translated and scaled non-uniformly; child with a
    // 4x4 matrix (translation +1 on x in the parent frame); a separate unlabelled floor slab.
    let nodes = json!([
        {"name": "Thing", "translation": [2.0, 0.5, -1.0], "scale": [2.0, 1.0, 1.0],
         "extras": {"class": "bed", "motion": "dynamic", "mass": 33.0}, "mesh": 0, "children": [1]},
        {"name": "ThingPart", "mesh": 0,
         "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 1.0,0,0,1]},
        {"name": "Slab", "mesh": 0, "translation": [0.0, -0.05, 0.0], "scale": [8.0, 0.1, 8.0]}
    ]);
    let (doc, bin) = doc_with_nodes(nodes, vec![0, 2]);
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "thing.glb", &glb_bytes(doc, &bin));
    let (scene, report) = import_scene(&path, &opts()).unwrap();
    assert_eq!(scene.objects.len(), 2, "{report}");
    let bed = scene.objects.iter().find(|o| o.name == "Thing").unwrap();
    assert_eq!(bed.class, SemanticClass::Bed);
    assert_eq!(bed.physics.motion, Motion::Dynamic);
    assert_eq!(bed.physics.mass, 33.0);
    assert_eq!(bed.parts.len(), 2, "child merged into the labelled parent");
    // Parent cube spans x in [1, 3]; the child sits at parent-local x = 1 -> world x = 4, and is
    // 2 m wide, so it spans [3, 5].
    assert!((bed.bbox.min[0] - 1.0).abs() < 1e-4 && (bed.bbox.max[0] - 5.0).abs() < 1e-4);
    assert!((bed.bbox.min[2] + 1.5).abs() < 1e-4 && (bed.bbox.max[2] + 0.5).abs() < 1e-4);
    // Floor detected at the slab's top (y = 0) -> no shift; the bed's bottom at y = 0.
    assert!(scene.floor_height.abs() < 1e-4);
    assert!(bed.bbox.min[1].abs() < 1e-4, "{:?}", bed.bbox);
    let slab = scene.objects.iter().find(|o| o.name == "Slab").unwrap();
    assert_eq!(
        slab.class,
        SemanticClass::Floor,
        "heuristic: thin, large, at floor height"
    );
    assert_eq!(report.unmatched_names, vec!["Slab".to_string()]);
    // Object-local vertices: pose at the bbox bottom centre, parts in world space around it.
    let Shape::Mesh(m) = &bed.parts[0].shape else {
        panic!("mesh part expected")
    };
    assert_eq!(bed.pose.position, [3.0, 0.0, -1.0]);
    let xs: Vec<f32> = m.positions.iter().map(|p| p[0]).collect();
    assert!(
        xs.iter().all(|x| (-2.0 - 1e-4..=0.0 + 1e-4).contains(x)),
        "{xs:?}"
    );
    assert_eq!(bed.color, "red");
    assert!((bed.parts[0].color[0] - 0.8).abs() < 1e-6);
}

#[test]
fn z_up_and_units_are_converted() {
    // A 1 x 1 x 1 cube scaled to 100 x 200 x 300 (cm), Z up: 1 m wide (x), 3 m tall, 2 m deep.
    let nodes = json!([{"name": "Box", "mesh": 0, "scale": [100.0, 200.0, 300.0]}]);
    let (doc, bin) = doc_with_nodes(nodes, vec![0]);
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "box.glb", &glb_bytes(doc, &bin));
    let o = ImportOptions {
        up: UpAxis::Z,
        unit: Unit::Cm,
        ..opts()
    };
    let (scene, _) = import_scene(&path, &o).unwrap();
    let s = scene.bounds().size();
    assert!(
        (s.x - 1.0).abs() < 1e-4 && (s.y - 3.0).abs() < 1e-4 && (s.z - 2.0).abs() < 1e-4,
        "{s}"
    );
}

#[test]
fn truncated_glb_is_a_clear_error_naming_the_file() {
    let nodes = json!([{"name": "Box", "mesh": 0}]);
    let (doc, bin) = doc_with_nodes(nodes, vec![0]);
    let bytes = glb_bytes(doc, &bin);
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "cut.glb", &bytes[..bytes.len() / 2]);
    let e = import_scene(&path, &opts()).unwrap_err().to_string();
    assert!(e.contains("cut.glb") && e.contains("truncated"), "{e}");
    // Cut inside the header too.
    let path = write(dir.path(), "cut2.glb", &bytes[..10]);
    let e = import_scene(&path, &opts()).unwrap_err().to_string();
    assert!(e.contains("cut2.glb"), "{e}");
}

#[test]
fn missing_buffer_file_is_a_clear_error() {
    let nodes = json!([{"name": "Box", "mesh": 0}]);
    let (mut doc, bin) = doc_with_nodes(nodes, vec![0]);
    doc["buffers"] = json!([{"byteLength": bin.len(), "uri": "absent.bin"}]);
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "scene.gltf", &serde_json::to_vec(&doc).unwrap());
    let e = import_scene(&path, &opts()).unwrap_err().to_string();
    assert!(
        e.contains("scene.gltf") && e.contains("absent.bin") && e.contains("not found"),
        "{e}"
    );
    // With the buffer beside it, the same file imports.
    write(dir.path(), "absent.bin", &bin);
    let (scene, _) = import_scene(&path, &opts()).unwrap();
    assert_eq!(scene.objects.len(), 1);
}

#[test]
fn draco_required_extension_is_a_clear_error() {
    let nodes = json!([{"name": "Box", "mesh": 0}]);
    let (mut doc, bin) = doc_with_nodes(nodes, vec![0]);
    doc["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    doc["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "draco.glb", &glb_bytes(doc, &bin));
    let e = import_scene(&path, &opts()).unwrap_err().to_string();
    assert!(
        e.contains("draco.glb")
            && e.contains("KHR_draco_mesh_compression")
            && e.contains("not supported"),
        "{e}"
    );
}

#[test]
fn unknown_extension_and_format_errors() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "house.fbx", b"xx");
    let e = import_scene(&path, &opts()).unwrap_err().to_string();
    assert!(e.contains("house.fbx") && e.contains(".glb"), "{e}");
    let missing = dir.path().join("nothing.glb");
    let e = import_scene(&missing, &opts()).unwrap_err().to_string();
    assert!(e.contains("nothing.glb"), "{e}");
}

const MTL: &str = "newmtl red_wood\nKd 0.6 0.02 0.02\n\nnewmtl blue_fabric\nKd 0.1 0.2 0.8\n";

fn obj_text() -> String {
    // A floor (5 x 5 m), a table top (1 x 1 m at 75 cm) and a lamp column, in centimetres.
    let mut s = String::from("mtllib home.mtl\n");
    let quad = |s: &mut String,
                name: &str,
                mat: &str,
                y: f32,
                x0: f32,
                x1: f32,
                z0: f32,
                z1: f32,
                base: usize| {
        s.push_str(&format!("o {name}\nusemtl {mat}\n"));
        for (x, z) in [(x0, z0), (x1, z0), (x1, z1), (x0, z1)] {
            s.push_str(&format!("v {x} {y} {z}\n"));
        }
        s.push_str(&format!(
            "f {} {} {} {}\n",
            base + 1,
            base + 4,
            base + 3,
            base + 2
        ));
    };
    quad(
        &mut s,
        "Floor_main",
        "red_wood",
        0.0,
        -250.0,
        250.0,
        -250.0,
        250.0,
        0,
    );
    quad(
        &mut s, "Table_01", "red_wood", 75.0, 0.0, 100.0, 0.0, 100.0, 4,
    );
    s.push_str("o Lamp_01\nusemtl blue_fabric\n");
    s.push_str("v 200 0 200\nv 210 0 200\nv 210 150 200\nv 200 150 200\n");
    s.push_str("f 9 10 11\nf 9 11 12\n");
    s
}

#[test]
fn obj_with_mtl_imports_with_colours_and_names() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "home.mtl", MTL.as_bytes());
    let path = write(dir.path(), "home.obj", obj_text().as_bytes());
    let o = ImportOptions {
        unit: Unit::Cm,
        ..opts()
    };
    let (scene, report) = import_scene(&path, &o).unwrap();
    assert_eq!(report.format, "obj");
    assert_eq!(scene.objects.len(), 3, "{report}");
    let by = |n: &str| scene.objects.iter().find(|o| o.name == n).unwrap();
    assert_eq!(by("Floor_main").class, SemanticClass::Floor);
    assert_eq!(by("Table_01").class, SemanticClass::DiningTable);
    assert_eq!(by("Lamp_01").class, SemanticClass::FloorLamp);
    assert_eq!(by("Table_01").color, "red");
    assert_eq!(by("Lamp_01").color, "blue");
    assert_eq!(by("Lamp_01").parts[0].color, [0.1, 0.2, 0.8]);
    assert!((by("Table_01").bbox.min[1] - 0.75).abs() < 1e-4);
    assert!((scene.bounds().size().x - 5.0).abs() < 1e-4);
    assert_eq!(report.objects_by_source.get("mapping"), Some(&3));
}

#[test]
fn obj_without_its_mtl_still_imports_in_grey() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "home.obj", obj_text().as_bytes());
    let (scene, _) = import_scene(&path, &opts()).unwrap();
    assert_eq!(scene.objects.len(), 3);
    assert!(scene
        .objects
        .iter()
        .all(|o| o.parts[0].color == vlnverse_import::DEFAULT_COLOR));
}

#[test]
fn mapping_file_overrides_and_drops() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "home.mtl", MTL.as_bytes());
    let path = write(dir.path(), "home.obj", obj_text().as_bytes());
    let mapping = write(
        dir.path(),
        "map.toml",
        b"[[rule]]\npattern = \"^Table\"\nclass = \"desk\"\nmotion = \"dynamic\"\nfriction = 0.9\n\n[[rule]]\npattern = \"^Lamp\"\ndrop = true\n",
    );
    let o = ImportOptions {
        unit: Unit::Cm,
        mapping: Some(mapping),
        ..opts()
    };
    let (scene, report) = import_scene(&path, &o).unwrap();
    let t = scene.objects.iter().find(|o| o.name == "Table_01").unwrap();
    assert_eq!(t.class, SemanticClass::Desk);
    assert_eq!(t.physics.motion, Motion::Dynamic);
    assert_eq!(t.physics.friction, 0.9);
    assert_eq!(report.dropped, vec!["Lamp_01".to_string()]);
    assert_eq!(scene.objects.len(), 2);
    // The floor was matched by no rule of this file: geometry heuristics make it a floor.
    assert_eq!(report.unmatched_names, vec!["Floor_main".to_string()]);
    assert_eq!(
        scene.objects.iter().map(|o| o.id).collect::<Vec<_>>(),
        vec![1, 2]
    );
}
