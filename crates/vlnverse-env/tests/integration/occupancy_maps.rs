//! Occupancy and navigable maps built from hand-made scenes, and their ROS map_server files.

use crate::occupancy_fixtures;

use glam::{Vec2, Vec3};
use occupancy_fixtures::*;
use vlnverse_env::occupancy::{build_maps, CellState, GridMap, OccupancyConfig};
use vlnverse_env::{EnvError, Pose, SemanticClass, Shape};

fn maps(scene: &vlnverse_env::Scene) -> vlnverse_env::occupancy::OccupancyMaps {
    build_maps(scene, &OccupancyConfig::default()).expect("maps")
}

fn state_at(m: &GridMap, p: Vec2) -> CellState {
    let (c, r) = m.world_to_cell(p).expect("inside the map");
    m.state(c, r)
}

#[test]
fn door_of_090_is_passable_gap_of_050_is_not() {
    let wide = maps(&two_rooms(0.9));
    assert!(wide.navigable.is_free_at(ROOM_A));
    assert!(wide.navigable.is_free_at(ROOM_B));
    // Right in the doorway, on the wall line.
    assert!(wide.navigable.is_free_at(Vec2::new(4.0, 2.0)));

    let narrow = maps(&two_rooms(0.5));
    // The agent (radius 0.3) does not fit through 0.5 m: room B becomes a separate, smaller
    // island and is dropped; the raw map still sees the gap as free.
    assert!(narrow.navigable.is_free_at(ROOM_A));
    assert!(!narrow.navigable.is_free_at(ROOM_B));
    assert_eq!(state_at(&narrow.occupancy, ROOM_B), CellState::Free);
    assert_eq!(
        state_at(&narrow.occupancy, Vec2::new(4.0, 2.0)),
        CellState::Free
    );
    assert!(!narrow.navigable.is_free_at(Vec2::new(4.0, 2.0)));
}

#[test]
fn dilation_keeps_agent_radius_from_walls() {
    let m = maps(&open_room(4.0));
    // Inner wall face at x = 0.05; the agent centre must stay >= 0.3 m from it.
    assert!(!m.navigable.is_free_at(Vec2::new(0.30, 2.0)));
    assert!(m.navigable.is_free_at(Vec2::new(0.45, 2.0)));
    assert!(!m.navigable.is_free_at(Vec2::new(3.70, 2.0)));
    assert!(m.navigable.is_free_at(Vec2::new(3.55, 2.0)));
    // Navigable area is the inner 3.9 m square shrunk by about the radius on each side.
    let area = m.navigable.free_area_m2();
    let lo = (3.9 - 2.0 * 0.4f32).powi(2);
    let hi = (3.9 - 2.0 * 0.3f32).powi(2) * 1.001;
    assert!(area > lo && area <= hi, "area {area} not in ({lo}, {hi})");
}

#[test]
fn largest_island_drops_the_closed_room() {
    let m = maps(&room_and_closed_room());
    assert_eq!(state_at(&m.occupancy, CLOSED_ROOM), CellState::Free);
    assert!(!m.navigable.is_free_at(CLOSED_ROOM));
    assert!(m.navigable.is_free_at(Vec2::new(3.0, 2.5)));
    // Outside the floor: unknown in both maps.
    assert_eq!(
        state_at(&m.occupancy, Vec2::new(7.8, 3.5)),
        CellState::Unknown
    );
    assert_eq!(
        state_at(&m.navigable, Vec2::new(7.8, 3.5)),
        CellState::Unknown
    );
}

#[test]
fn only_geometry_in_the_height_band_counts() {
    let mut s = open_room(6.0);
    let id = 100;
    let boxes = [
        // Above the agent (1.5 m): ignored.
        (SemanticClass::Bookshelf, [1.0, 1.6, 1.0], [1.6, 1.7, 1.6]),
        // A rug below the floor clearance: ignored.
        (SemanticClass::Rug, [3.0, 0.0, 1.0], [4.0, 0.01, 2.0]),
        // A floating table top inside the band: an obstacle.
        (
            SemanticClass::DiningTable,
            [1.0, 0.70, 3.5],
            [2.0, 0.75, 4.5],
        ),
        // Ceiling and floor classes are never obstacles, whatever their height.
        (SemanticClass::Ceiling, [3.5, 0.9, 3.5], [4.5, 1.0, 4.5]),
        (SemanticClass::Floor, [4.5, 0.5, 1.0], [5.0, 1.0, 1.5]),
    ];
    for (k, (class, min, max)) in boxes.into_iter().enumerate() {
        s.objects.push(boxed(id + k as u32, class, min, max));
    }
    let m = maps(&s);
    let occ = |x: f32, z: f32| state_at(&m.occupancy, Vec2::new(x, z));
    assert_eq!(occ(1.3, 1.3), CellState::Free);
    assert_eq!(occ(3.5, 1.5), CellState::Free);
    assert_eq!(occ(1.5, 4.0), CellState::Occupied);
    assert_eq!(occ(4.0, 4.0), CellState::Free);
    assert_eq!(occ(4.75, 1.25), CellState::Free);
}

#[test]
fn yawed_box_and_cylinder_use_their_true_footprint() {
    let mut s = open_room(6.0);
    let yaw = std::f32::consts::FRAC_PI_4;
    s.objects.push(object(
        100,
        SemanticClass::Sofa,
        Pose::from_yaw(Vec3::new(2.0, 0.4, 2.0), yaw),
        Shape::Cuboid {
            half_extents: [1.0, 0.4, 0.1],
            bevel: 0.0,
        },
    ));
    s.objects.push(object(
        101,
        SemanticClass::PottedPlant,
        Pose::from_yaw(Vec3::new(4.5, 0.5, 4.5), 0.3),
        Shape::Cylinder {
            radius: 0.2,
            half_height: 0.5,
        },
    ));
    let m = maps(&s);
    // Local +x maps to world (cos yaw, -sin yaw) in (x, z).
    let axis = Vec2::new(yaw.cos(), -yaw.sin());
    for t in [-0.9f32, -0.5, 0.0, 0.5, 0.9] {
        let p = Vec2::new(2.0, 2.0) + axis * t;
        assert_eq!(state_at(&m.occupancy, p), CellState::Occupied, "t = {t}");
    }
    // Corners of the axis-aligned bounding box are not part of the rotated box.
    let perp = Vec2::new(axis.y, -axis.x);
    for p in [
        Vec2::new(2.0, 2.0) + perp * 0.3,
        Vec2::new(2.0, 2.0) - perp * 0.3,
        Vec2::new(2.6, 2.6),
        Vec2::new(1.4, 1.4),
    ] {
        assert_eq!(state_at(&m.occupancy, p), CellState::Free, "{p}");
    }
    assert_eq!(
        state_at(&m.occupancy, Vec2::new(4.5, 4.5)),
        CellState::Occupied
    );
    assert_eq!(
        state_at(&m.occupancy, Vec2::new(4.5, 4.66)),
        CellState::Occupied
    );
    assert_eq!(state_at(&m.occupancy, Vec2::new(4.5, 4.8)), CellState::Free);
    assert_eq!(
        state_at(&m.occupancy, Vec2::new(4.66, 4.66)),
        CellState::Free
    );
}

#[test]
fn thin_mesh_wall_splits_a_room_and_mesh_parts_are_clipped_to_the_band() {
    let mut s = open_room(6.0);
    // A zero-thickness vertical quad across the room at x = 2.02, a bit taller than the room.
    s.objects.push(mesh(
        100,
        SemanticClass::Unknown,
        vec![
            [2.02, -0.5, -0.2],
            [2.02, -0.5, 6.2],
            [2.02, 3.0, 6.2],
            [2.02, 3.0, -0.2],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    ));
    // A slanted triangle that only dips into the band near x = 5 (y from 3 down to 1).
    s.objects.push(mesh(
        101,
        SemanticClass::Unknown,
        vec![[3.0, 3.0, 5.0], [5.5, 1.0, 5.0], [3.0, 3.0, 5.4]],
        vec![[0, 1, 2]],
    ));
    let m = maps(&s);
    for z in [0.3f32, 1.0, 3.0, 5.7] {
        assert_eq!(
            state_at(&m.occupancy, Vec2::new(2.02, z)),
            CellState::Occupied
        );
    }
    // The larger side survives in the navigable map, the smaller is cut off.
    assert!(m.navigable.is_free_at(Vec2::new(4.0, 3.0)));
    assert!(!m.navigable.is_free_at(Vec2::new(1.0, 3.0)));
    // Band top is y = 1.5, reached at x = 3 + 2.5 * 0.75 = 4.875 along the slanted edge.
    assert_eq!(
        state_at(&m.occupancy, Vec2::new(5.2, 5.02)),
        CellState::Occupied
    );
    assert_eq!(
        state_at(&m.occupancy, Vec2::new(4.5, 5.02)),
        CellState::Free
    );
}

#[test]
fn pgm_orientation_follows_ros_map_frame() {
    // An asymmetric fixture: a pillar near the min-x, min-z corner of a 4 x 3 m room.
    let mut s = open_room(4.0);
    s.objects.push(boxed(
        100,
        SemanticClass::Wardrobe,
        [0.5, 0.0, 0.5],
        [1.0, 2.0, 0.8],
    ));
    let m = maps(&s).occupancy;
    let pgm = m.to_pgm_bytes();
    let header = format!("P5\n{} {}\n255\n", m.width, m.height);
    assert!(pgm.starts_with(header.as_bytes()));
    let pixels = &pgm[header.len()..];
    // Read the YAML the way a ROS tool does and locate world points in the image from it.
    let yaml = m.to_yaml("occupancy.pgm");
    let origin_line = yaml
        .lines()
        .find_map(|l| l.strip_prefix("origin: ["))
        .expect("origin");
    let o: Vec<f64> = origin_line
        .trim_end_matches(']')
        .split(',')
        .map(|v| v.trim().parse().expect("number"))
        .collect();
    let res = m.resolution as f64;
    let pixel = |x: f32, z: f32| {
        // map frame: mx = x, my = -z; image row 0 is the top (largest my).
        let (mx, my) = (x as f64, -(z as f64));
        let col = ((mx - o[0]) / res).floor() as usize;
        let row_from_bottom = ((my - o[1]) / res).floor() as usize;
        let row = m.height as usize - 1 - row_from_bottom;
        pixels[row * m.width as usize + col]
    };
    assert_eq!(pixel(0.75, 0.65), 0, "pillar");
    assert_eq!(pixel(3.25, 0.65), 254, "mirror in x is free");
    assert_eq!(pixel(0.75, 3.35), 254, "mirror in z is free");
    assert_eq!(pixel(2.0, 2.0), 254);
    assert_eq!(pixel(0.0, 2.0), 0, "wall");
    // Outside the floor slab but inside the padding: unknown.
    assert_eq!(pixel(-0.2, 2.0), 205);
}

#[test]
fn ros_files_round_trip() {
    let dir = tempfile::tempdir().expect("tempdir");
    let built = maps(&room_and_closed_room());
    for (stem, map) in [
        ("occupancy", &built.occupancy),
        ("navigable", &built.navigable),
    ] {
        map.save_ros(dir.path(), stem).expect("save");
        let yaml = std::fs::read_to_string(dir.path().join(format!("{stem}.yaml"))).expect("yaml");
        assert!(yaml.contains(&format!("image: {stem}.pgm")));
        assert!(yaml.contains("negate: 0"));
        assert!(yaml.contains("occupied_thresh: 0.65"));
        assert!(yaml.contains("free_thresh: 0.196"));
        let back = GridMap::load_ros(dir.path().join(format!("{stem}.yaml"))).expect("load");
        assert_eq!((back.width, back.height), (map.width, map.height));
        assert_eq!(back.resolution, map.resolution);
        assert!(
            back.origin.distance(map.origin) < 1e-5,
            "{} vs {}",
            back.origin,
            map.origin
        );
        assert_eq!(back.cells(), map.cells());
        // No temporary files left behind.
        assert!(!dir.path().join(format!("{stem}.pgm.tmp")).exists());
    }
}

#[test]
fn load_ros_errors_name_the_file_and_the_problem() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let missing = GridMap::load_ros(d.join("nope.yaml")).unwrap_err();
    assert!(matches!(missing, EnvError::Io { .. }));
    assert!(missing.to_string().contains("nope.yaml"));

    let good_yaml = "image: m.pgm\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\n\
                     occupied_thresh: 0.65\nfree_thresh: 0.196\n";
    std::fs::write(d.join("m.yaml"), good_yaml).expect("write");
    // The image is missing.
    let e = GridMap::load_ros(d.join("m.yaml")).unwrap_err();
    assert!(e.to_string().contains("m.pgm"), "{e}");
    // Corrupt images.
    for (bytes, what) in [
        (b"P2\n2 2\n255\n0 0 0 0".to_vec(), "P5"),
        (b"P5\n2 2\n255\n\x00\x00\x00".to_vec(), "truncated"),
        (b"P5\nx 2\n255\n\x00\x00\x00\x00".to_vec(), "width"),
        (b"P5\n2 2\n65535\n\x00\x00\x00\x00".to_vec(), "maxval"),
    ] {
        std::fs::write(d.join("m.pgm"), &bytes).expect("write");
        let e = GridMap::load_ros(d.join("m.yaml")).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("m.pgm") && msg.contains(what), "{msg}");
    }
    std::fs::write(
        d.join("m.pgm"),
        b"P5\n# comment\n2 2\n255\n\xfe\x00\xcd\xfe",
    )
    .expect("write");
    let ok = GridMap::load_ros(d.join("m.yaml")).expect("valid");
    assert_eq!(ok.state(0, 0), CellState::Free);
    assert_eq!(ok.state(1, 0), CellState::Occupied);
    assert_eq!(ok.state(0, 1), CellState::Unknown);
    // YAML origin is the lower-left corner in the map frame: world z of row 0 = -(oy + h*res).
    assert!((ok.origin - Vec2::new(-1.0, 2.0 - 0.1)).length() < 1e-6);

    for (yaml, field) in [
        (good_yaml.replace("resolution: 0.05\n", ""), "resolution"),
        (good_yaml.replace("0.05", "-0.05"), "resolution"),
        (good_yaml.replace("0.05", "abc"), "resolution"),
        (
            good_yaml.replace("[-1.0, -2.0, 0.0]", "[-1.0, -2.0]"),
            "origin",
        ),
        (good_yaml.replace("[-1.0, -2.0, 0.0]", "-1.0"), "origin"),
        (good_yaml.replace("image: m.pgm\n", ""), "image"),
        (
            good_yaml.replace("free_thresh: 0.196", "free_thresh: 0.9"),
            "free_thresh",
        ),
        (good_yaml.replace("negate: 0", "negate: maybe"), "negate"),
    ] {
        std::fs::write(d.join("bad.yaml"), &yaml).expect("write");
        let e = GridMap::load_ros(d.join("bad.yaml")).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("bad.yaml") && msg.contains(field), "{msg}");
    }
}

#[test]
fn bad_config_names_the_field() {
    let s = open_room(3.0);
    for (cfg, field) in [
        (
            OccupancyConfig {
                agent_radius: -0.1,
                ..Default::default()
            },
            "agent_radius",
        ),
        (
            OccupancyConfig {
                resolution: 0.0,
                ..Default::default()
            },
            "resolution",
        ),
        (
            OccupancyConfig {
                resolution: f32::NAN,
                ..Default::default()
            },
            "resolution",
        ),
        (
            OccupancyConfig {
                agent_height: 0.01,
                ..Default::default()
            },
            "agent_height",
        ),
        (
            OccupancyConfig {
                padding: -1.0,
                ..Default::default()
            },
            "padding",
        ),
    ] {
        let e = build_maps(&s, &cfg).unwrap_err();
        match &e {
            EnvError::InvalidConfig { field: f, .. } => assert_eq!(f, field),
            other => panic!("expected InvalidConfig, got {other}"),
        }
        assert!(e.to_string().contains(field));
    }
    assert!(OccupancyConfig::default().validate().is_ok());
    let tiny = OccupancyConfig {
        resolution: 1e-5,
        ..Default::default()
    };
    let e = build_maps(&s, &tiny).unwrap_err();
    assert!(e.to_string().contains("resolution"), "{e}");
}

#[test]
fn config_parses_from_toml_with_defaults() {
    let cfg: OccupancyConfig =
        toml::from_str("resolution = 0.1\nagent_radius = 0.2").expect("toml");
    assert_eq!(cfg.resolution, 0.1);
    assert_eq!(cfg.agent_radius, 0.2);
    assert_eq!(cfg.agent_height, 1.5);
    assert!(toml::from_str::<OccupancyConfig>("radius = 0.2").is_err());
}

#[test]
fn coarser_resolution_gives_consistent_areas() {
    let s = two_rooms(0.9);
    let fine = maps(&s);
    let coarse = build_maps(
        &s,
        &OccupancyConfig {
            resolution: 0.1,
            ..Default::default()
        },
    )
    .expect("maps");
    let (a, b) = (
        fine.navigable.free_area_m2(),
        coarse.navigable.free_area_m2(),
    );
    // Conservative rasterisation loses more at coarse resolution, but not much.
    assert!(b <= a * 1.02 && b > a * 0.8, "fine {a} coarse {b}");
    assert!(coarse.navigable.is_free_at(ROOM_B));
}

#[test]
fn floor_gaps_under_doorways_stay_free_and_the_outside_is_unknown() {
    let mut s = two_rooms(0.9);
    // Two slabs that stop short of the partition wall's centre line, leaving a floor gap under
    // the doorway.
    s.objects.retain(|o| o.class != SemanticClass::Floor);
    s.objects.push(floor(50, -0.05, -0.05, 3.97, 4.05));
    s.objects.push(floor(51, 4.03, -0.05, 7.05, 4.05));
    let m = maps(&s);
    assert_eq!(state_at(&m.occupancy, Vec2::new(4.0, 2.0)), CellState::Free);
    assert!(m.navigable.is_free_at(ROOM_A) && m.navigable.is_free_at(ROOM_B));
    for p in [
        Vec2::new(-0.2, 2.0),
        Vec2::new(3.5, 4.2),
        Vec2::new(7.2, 0.0),
    ] {
        assert_eq!(state_at(&m.occupancy, p), CellState::Unknown, "{p}");
    }
}
