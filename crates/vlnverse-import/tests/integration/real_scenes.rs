//! The real third-party scenes of `../shared/scenes/` (see its README). Each test is skipped,
//! with a message, when that folder is absent.

use glam::Vec2;
use std::path::PathBuf;
use vlnverse_env::occupancy::{
    build_maps, squared_distance_transform, CellState, GridMap, OccupancyConfig,
};
use vlnverse_env::{RoomType, Scene, SceneSource, SemanticClass};
use vlnverse_import::{import_scene, ImportOptions, ImportReport, Importer, UpAxis};

fn shared(rel: &str) -> Option<PathBuf> {
    let p = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/scenes"
    ))
    .join(rel);
    if p.exists() {
        Some(p)
    } else {
        eprintln!("skipped: {} is absent", p.display());
        None
    }
}

fn aws_mapping() -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../configs/import/aws_small_house.toml"
    ))
}

fn import_aws() -> Option<(Scene, ImportReport)> {
    let file = shared("aws_small_house/aws_small_house_yup.glb")?;
    let opts = ImportOptions {
        mapping: Some(aws_mapping()),
        ..Default::default()
    };
    Some(import_scene(&file, &opts).expect("the AWS house imports"))
}

fn object<'a>(scene: &'a Scene, name: &str) -> &'a vlnverse_env::SceneObject {
    scene
        .objects
        .iter()
        .find(|o| o.name == name)
        .unwrap_or_else(|| panic!("no object {name}"))
}

#[test]
fn aws_house_has_the_right_scale_and_orientation() {
    let Some((scene, report)) = import_aws() else {
        return;
    };
    let s = scene.bounds().size();
    assert!((s.x - 19.0).abs() < 0.2, "x size {}", s.x);
    assert!((s.y - 3.0).abs() < 0.2, "height {}", s.y);
    assert!((s.z - 11.4).abs() < 0.2, "z size {}", s.z);
    assert!(
        scene.floor_height.abs() < 0.02,
        "floor {}",
        scene.floor_height
    );
    assert_eq!(report.nodes, 87);
    assert!(report.triangles > 140_000, "{}", report.triangles);
    // Upright: the fridge is taller than wide and stands on the floor; the bed's top is below
    // 1.5 m.
    let fridge = object(&scene, "Refrigerator_01_001").bbox;
    assert!(
        fridge.size().y > 1.5 && fridge.size().y > fridge.size().x,
        "{fridge:?}"
    );
    assert!(fridge.min[1].abs() < 0.05);
    let bed = object(&scene, "Bed_01_001").bbox;
    assert!(
        bed.max[1] < 1.5 && bed.size().x > 1.5 && bed.size().z > 1.5,
        "{bed:?}"
    );
}

#[test]
fn aws_house_mapping_labels_at_least_30_objects() {
    let Some((scene, report)) = import_aws() else {
        return;
    };
    let from_mapping = report
        .objects_by_source
        .get("mapping")
        .copied()
        .unwrap_or(0);
    let labelled = scene
        .objects
        .iter()
        .filter(|o| o.class != SemanticClass::Unknown && !report.unmatched_names.contains(&o.name))
        .count();
    println!(
        "AWS house: {from_mapping} objects matched by the mapping, {labelled} of them with a class"
    );
    assert!(labelled >= 30, "{report}");
    assert_eq!(object(&scene, "Bed_01_001").class, SemanticClass::Bed);
    assert_eq!(
        object(&scene, "Refrigerator_01_001").class,
        SemanticClass::Fridge
    );
    assert_eq!(
        object(&scene, "HouseWallB_01_001").class,
        SemanticClass::Wall
    );
    assert_eq!(object(&scene, "FloorB_01_001").class, SemanticClass::Floor);
    let chair = object(&scene, "ChairA_01_001");
    assert_eq!(chair.class, SemanticClass::Chair);
    assert_eq!(chair.physics.motion, vlnverse_env::Motion::Dynamic);
    assert_eq!(chair.physics.mass, 6.0);
    assert_eq!(
        object(&scene, "SofaC_01_001").physics.motion,
        vlnverse_env::Motion::Static
    );
    // Every name nothing matched is counted.
    assert!(report
        .unmatched_names
        .contains(&"Chandelier_01_001".to_string()));
    assert_eq!(
        report.objects_by_class.values().sum::<usize>(),
        scene.objects.len()
    );
}

/// Share of the SLAM map's occupied cells that lie within `tol` metres of one of our occupied
/// cells.
fn slam_agreement(ours: &GridMap, slam: &GridMap, tol: f32) -> (f32, usize) {
    let cells = ours.cells();
    let d2 =
        squared_distance_transform(ours.width, ours.height, |i| cells[i] == CellState::Occupied);
    let reach = (tol / ours.resolution).ceil() as i64 + 1;
    let (mut hit, mut total) = (0usize, 0usize);
    for (i, c) in slam.cells().iter().enumerate() {
        if *c != CellState::Occupied {
            continue;
        }
        total += 1;
        let (sc, sr) = slam.cell_of_index(i);
        let p = slam.cell_center(sc, sr);
        let Some((c0, r0)) = ours.world_to_cell(p) else {
            continue;
        };
        // Cheap reject: the nearest occupied cell centre is too far.
        if (d2[ours.index(c0, r0)].sqrt() as f32 - 1.5) * ours.resolution > tol {
            continue;
        }
        let mut near = false;
        'search: for dr in -reach..=reach {
            for dc in -reach..=reach {
                let (c, r) = (c0 as i64 + dc, r0 as i64 + dr);
                if c < 0 || r < 0 || c >= ours.width as i64 || r >= ours.height as i64 {
                    continue;
                }
                if ours.state(c as u32, r as u32) != CellState::Occupied {
                    continue;
                }
                // Distance from p to the square of that cell.
                let q = ours.cell_center(c as u32, r as u32);
                let h = ours.resolution * 0.5;
                let d = Vec2::new(
                    ((p.x - q.x).abs() - h).max(0.0),
                    ((p.y - q.y).abs() - h).max(0.0),
                );
                if d.length() <= tol {
                    near = true;
                    break 'search;
                }
            }
        }
        hit += usize::from(near);
    }
    (hit as f32 / total.max(1) as f32, total)
}

#[test]
fn aws_house_occupancy_agrees_with_the_slam_map() {
    let Some((scene, _)) = import_aws() else {
        return;
    };
    let Some(yaml) = shared("aws_small_house/map.yaml") else {
        return;
    };
    let slam = GridMap::load_ros(&yaml).expect("SLAM map loads");
    let maps = build_maps(&scene, &OccupancyConfig::default()).unwrap();
    let (share, total) = slam_agreement(&maps.occupancy, &slam, 0.10);
    println!(
        "AWS house: {:.1} % of {total} SLAM-occupied cells lie within 10 cm of our occupied cells",
        share * 100.0
    );
    assert!(total > 1000, "the SLAM map has occupied cells");
    assert!(share >= 0.85, "only {:.1} % agree", share * 100.0);
    // A control: the same map shifted by 1 m agrees much less, so the figure is not trivial.
    let mut shifted = maps.occupancy.clone();
    shifted.origin += Vec2::new(1.0, 0.0);
    let (bad, _) = slam_agreement(&shifted, &slam, 0.10);
    assert!(bad < share - 0.2, "shifted {bad} vs {share}");
}

#[test]
fn aws_house_rooms_are_segmented() {
    let Some((scene, report)) = import_aws() else {
        return;
    };
    println!("{report}");
    let n = scene.rooms.len();
    assert!((3..=8).contains(&n), "{n} rooms: {report}");
    let total: f32 = scene.rooms.iter().map(|r| r.area()).sum();
    assert!((100.0..=217.0).contains(&total), "room area {total}");
    for r in &scene.rooms {
        assert!(r.area() >= 2.5, "{} is {} m^2", r.name, r.area());
        assert!(r.polygon.len() >= 4);
    }
    let room_of = |name: &str| {
        let id = object(&scene, name)
            .room
            .unwrap_or_else(|| panic!("{name} has no room"));
        scene.room(id).unwrap()
    };
    assert_eq!(room_of("Bed_01_001").kind, RoomType::Bedroom);
    assert_eq!(room_of("Refrigerator_01_001").kind, RoomType::Kitchen);
    assert_eq!(room_of("SofaC_01_001").kind, RoomType::LivingRoom);
    assert_eq!(room_of("FitnessEquipment_01_001").kind, RoomType::Gym);
    // Bed, sofa and fridge are in three different rooms, each 10-60 m^2.
    let ids = ["Bed_01_001", "SofaC_01_001", "Refrigerator_01_001"].map(|n| room_of(n).id);
    assert!(ids[0] != ids[1] && ids[1] != ids[2] && ids[0] != ids[2]);
    for id in ids {
        let a = scene.room(id).unwrap().area();
        assert!((10.0..=60.0).contains(&a), "room {id}: {a} m^2");
    }
    // Rooms are connected by doors or openings, each between two different rooms.
    assert!(scene.doors.len() >= n - 1, "{} doors", scene.doors.len());
    for d in &scene.doors {
        assert_ne!(d.rooms[0], d.rooms[1]);
        assert!(d.width > 0.3 && d.width < 12.0, "{d:?}");
    }
    // Most furniture got a room.
    assert!(
        report.objects_in_rooms as f32 >= 0.9 * scene.items().count() as f32,
        "{report}"
    );
}

#[test]
fn simple_room_is_right_side_up_with_the_z_up_option() {
    let Some(file) = shared("habitat_simple_room/simple_room.glb") else {
        return;
    };
    let opts = ImportOptions {
        up: UpAxis::Z,
        ..Default::default()
    };
    let (scene, report) = import_scene(&file, &opts).unwrap();
    assert!(scene.floor_height.abs() < 1e-4);
    // The floor slab becomes a floor; the table top is the thin 0.7 x 0.7 m plate.
    let floor = object(&scene, "Cube");
    assert_eq!(floor.class, SemanticClass::Floor, "{report}");
    let top = object(&scene, "Cube.002").bbox;
    assert!(
        top.size().y < 0.1 && top.size().x > 0.5 && top.size().z > 0.5,
        "{top:?}"
    );
    assert!(
        (1.0..=1.25).contains(&top.max[1]),
        "table top at {}",
        top.max[1]
    );
    // Everything but the floor slab stands on or above the floor.
    for o in scene
        .objects
        .iter()
        .filter(|o| o.class != SemanticClass::Floor)
    {
        assert!(o.bbox.min[1] > -0.02, "{}: {:?}", o.name, o.bbox);
    }
    // Read as Y up, the same file is lying on its side: the floor slab is vertical.
    let (side, _) = import_scene(&file, &ImportOptions::default()).unwrap();
    assert!(object(&side, "Cube").bbox.size().y > 5.0);
}

#[test]
fn godot_living_room_splits_by_material_names() {
    let Some(file) = shared("godot_living_room/living_room.glb") else {
        return;
    };
    let (scene, report) = import_scene(&file, &ImportOptions::default()).unwrap();
    let has = |c: SemanticClass| scene.objects.iter().any(|o| o.class == c);
    assert!(
        has(SemanticClass::Wall) && has(SemanticClass::Ceiling),
        "{report}"
    );
    assert!(scene.objects.iter().any(|o| o.name == "Cube/ceiling"));
    assert!(!scene.rooms.is_empty());
    // The floor is the room's (2.5 m under its ceiling, the table standing on it), not the
    // lower terrace outside the window.
    let ceiling = scene
        .objects
        .iter()
        .find(|o| o.name == "Cube/ceiling")
        .unwrap();
    let height = ceiling.bbox.min[1] - scene.floor_height;
    assert!(
        (height - 2.5).abs() < 0.05,
        "ceiling {height} m above the floor"
    );
    // The navigable island is the room under the ceiling, not the larger terrace outside.
    let maps = build_maps(&scene, &OccupancyConfig::default()).unwrap();
    let nav = &maps.navigable;
    let (mut inside, mut all) = (0, 0);
    for (c, r) in nav.free_cells() {
        let p = nav.cell_center(c, r);
        all += 1;
        let (lo, hi) = (ceiling.bbox.min, ceiling.bbox.max);
        inside += (p.x >= lo[0] && p.x <= hi[0] && p.y >= lo[2] && p.y <= hi[2]) as usize;
    }
    assert!(
        all > 0 && inside == all,
        "{inside} of {all} navigable cells under the ceiling"
    );
    let table = scene.objects.iter().find(|o| o.name == "Cylinder").unwrap();
    assert!(
        (table.bbox.min[1] - scene.floor_height).abs() < 0.05,
        "{:?}",
        table.bbox
    );
}

#[test]
fn importer_is_a_scene_source() {
    let Some(file) = shared("habitat_simple_room/simple_room.glb") else {
        return;
    };
    let src = Importer::new(
        vec![file],
        ImportOptions {
            up: UpAxis::Z,
            ..Default::default()
        },
    );
    assert_eq!(src.len(), 1);
    assert_eq!(src.scene_id(0), "simple_room");
    let a = src.scene(0).unwrap();
    let b = src.scene(0).unwrap();
    assert_eq!(a, b, "deterministic");
    assert_eq!(a.id, "simple_room");
    assert!(src.scene(1).is_err());
}

#[test]
fn imported_scene_round_trips_through_a_scene_folder() {
    let Some(file) = shared("habitat_simple_room/simple_room.glb") else {
        return;
    };
    let opts = ImportOptions {
        up: UpAxis::Z,
        ..Default::default()
    };
    let (scene, _) = import_scene(&file, &opts).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (_, folder) =
        vlnverse_env::io::write_scene_bundle(dir.path(), scene.clone(), &opts.occupancy).unwrap();
    assert!(vlnverse_env::io::is_complete_scene_dir(&folder));
    let back = vlnverse_env::io::load_scene(&folder).unwrap();
    assert_eq!(back.objects.len(), scene.objects.len());
    assert_eq!(back.triangle_count(), scene.triangle_count());
    for (a, b) in scene.objects.iter().zip(&back.objects) {
        assert_eq!(
            (a.id, &a.name, a.class, a.room),
            (b.id, &b.name, b.class, b.room)
        );
        for k in 0..3 {
            assert!(
                (a.bbox.min[k] - b.bbox.min[k]).abs() < 1e-4
                    && (a.bbox.max[k] - b.bbox.max[k]).abs() < 1e-4
            );
        }
    }
    assert_eq!(back.rooms.len(), scene.rooms.len());
}

/// The ceiling of `_ceiling_yup` is named `RoomCeiling_01_001`: the mapping must make it a
/// `ceiling` (structure), so that the scene graph relates no furniture to it.
#[test]
fn aws_house_ceiling_is_structure_with_no_neighbours() {
    use vlnverse_env::scene_graph::{NodeRef, Relation, SceneGraph};
    let Some(file) = shared("aws_small_house/aws_small_house_ceiling_yup.glb") else {
        return;
    };
    let opts = ImportOptions {
        mapping: Some(aws_mapping()),
        ..Default::default()
    };
    let (scene, report) = import_scene(&file, &opts).expect("the AWS house imports");
    let ceiling = object(&scene, "RoomCeiling_01_001");
    assert_eq!(ceiling.class, SemanticClass::Ceiling, "{report}");
    assert!(!report
        .unmatched_names
        .contains(&"RoomCeiling_01_001".to_string()));
    let graph = SceneGraph::build(&scene);
    for relation in [Relation::Near, Relation::NextTo] {
        let related = graph.related(NodeRef::Object(ceiling.id), relation);
        assert!(
            related.is_empty(),
            "ceiling is {relation:?} {} objects",
            related.len()
        );
    }
}
