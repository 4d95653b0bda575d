//! Top-down pictures: the world -> pixel mapping, and what lands where.

use crate::io_common;

use glam::Vec2;
use io_common::fixture_scene;
use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
use vlnverse_env::topdown::{class_color, render_topdown, room_color, TopdownOptions};
use vlnverse_env::{RoomType, SemanticClass};

fn px(td: &vlnverse_env::topdown::Topdown, p: Vec2) -> [u8; 3] {
    let q = td.frame.to_pixel(p);
    td.image.get_pixel(q.x as u32, q.y as u32).0
}

#[test]
fn frame_round_trips_and_scale_follows_options() {
    let scene = fixture_scene();
    let opts = TopdownOptions {
        px_per_m: 40.0,
        ..Default::default()
    };
    let td = render_topdown(&scene, None, &opts);
    assert_eq!(td.frame.px_per_m, 40.0);
    let p = Vec2::new(0.3, -1.1);
    assert!((td.frame.to_world(td.frame.to_pixel(p)) - p).length() < 1e-4);
    // One metre along +x is 40 pixels to the right; +z goes down.
    let d = td.frame.to_pixel(Vec2::new(1.0, 1.0)) - td.frame.to_pixel(Vec2::ZERO);
    assert_eq!(d, Vec2::new(40.0, 40.0));
    // The scene (4 m room + margins) fits.
    assert!(td.image.width() as f32 >= 4.0 * 40.0 && td.image.height() as f32 >= 4.0 * 40.0);
}

#[test]
fn walls_objects_rooms_doors_and_navigable_area_are_drawn() {
    let scene = fixture_scene();
    let plain = render_topdown(&scene, None, &TopdownOptions::default());
    // Wall (z = -2, 10 cm thick): dark.
    assert_eq!(
        px(&plain, Vec2::new(-1.0, -2.0)),
        class_color(SemanticClass::Wall)
    );
    // Table top centre (no label there with labels off), vase drawn on top of the table.
    let no_text = TopdownOptions {
        labels: false,
        room_names: false,
        ..Default::default()
    };
    let td = render_topdown(&scene, None, &no_text);
    let table = &scene.objects[1];
    let edge = Vec2::new(table.pose.position[0], table.pose.position[2])
        + Vec2::from_angle(-table.pose.yaw()).rotate(Vec2::new(0.45, 0.0));
    assert_eq!(px(&td, edge), class_color(SemanticClass::DiningTable));
    assert_eq!(
        px(&td, Vec2::new(0.5, 0.25)),
        class_color(SemanticClass::Vase)
    );
    // Empty floor of the dining room: its room tint.
    assert_eq!(
        px(&td, Vec2::new(1.5, 1.5)),
        room_color(RoomType::DiningRoom)
    );
    // The door at (2, 0): orange bar.
    assert_eq!(px(&td, Vec2::new(2.0, 0.0)), [230, 130, 30]);

    // With the navigable map the free floor is shaded (no longer the plain tint), and the
    // space right next to the wall (inside the agent radius) is not.
    let maps = build_maps(&scene, &OccupancyConfig::default()).unwrap();
    let nav = render_topdown(&scene, Some(&maps.navigable), &no_text);
    let free = Vec2::new(1.5, 1.5);
    assert!(maps.navigable.is_free_at(free));
    assert_ne!(px(&nav, free), room_color(RoomType::DiningRoom));
    let near_wall = Vec2::new(1.0, -1.85);
    assert!(!maps.navigable.is_free_at(near_wall));
    assert_eq!(px(&nav, near_wall), room_color(RoomType::DiningRoom));
}

#[test]
fn draw_path_paints_along_the_segment_only() {
    let scene = fixture_scene();
    let mut td = render_topdown(&scene, None, &TopdownOptions::default());
    let before = td.image.clone();
    let red = [255, 0, 0];
    td.draw_path(&[Vec2::new(-1.5, 1.7), Vec2::new(1.5, 1.7)], red, 3.0);
    assert_eq!(px(&td, Vec2::new(0.0, 1.7)), red);
    assert_eq!(px(&td, Vec2::new(-1.5, 1.7)), red);
    assert_ne!(px(&td, Vec2::new(0.0, 1.5)), red);
    let changed = td
        .image
        .pixels()
        .zip(before.pixels())
        .filter(|(a, b)| a != b)
        .count();
    // About 3 m * 50 px/m long and 3 px wide.
    assert!((350..=600).contains(&changed), "{changed} pixels changed");
    td.draw_marker(Vec2::new(-1.0, 1.0), [0, 0, 255], 5.0);
    assert_eq!(px(&td, Vec2::new(-1.0, 1.0)), [0, 0, 255]);
}

#[test]
fn same_scene_gives_same_pixels() {
    let scene = fixture_scene();
    let a = render_topdown(&scene, None, &TopdownOptions::default());
    let b = render_topdown(&scene, None, &TopdownOptions::default());
    assert_eq!(a.image, b.image);
}

/// A mesh part from quads `[x0, z0, x1, z1, y0, y1]` (vertical when x or z is constant,
/// horizontal when `y0 == y1`).
fn quads(qs: &[[f32; 6]]) -> vlnverse_env::Part {
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for &[x0, z0, x1, z1, y0, y1] in qs {
        let b = positions.len() as u32;
        if y0 == y1 {
            positions.extend([[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]]);
        } else {
            positions.extend([[x0, y0, z0], [x1, y0, z1], [x1, y1, z1], [x0, y1, z0]]);
        }
        indices.extend([[b, b + 1, b + 2], [b, b + 2, b + 3]]);
    }
    vlnverse_env::Part {
        shape: vlnverse_env::Shape::Mesh(vlnverse_env::MeshData {
            positions,
            indices,
            glb_mesh: None,
            ..Default::default()
        }),
        transform: vlnverse_env::Pose::IDENTITY,
        color: [0.5, 0.5, 0.5],
    }
}

/// Imported meshes are drawn by their triangles within the agent's height band, not by the
/// hull of their bounding box: one mesh holding the walls of a whole house leaves the rooms
/// visible, and a box-shaped mesh is filled.
#[test]
fn mesh_walls_are_lines_and_mesh_furniture_is_filled() {
    use vlnverse_env::{Pose, SceneObject};
    let mut scene = fixture_scene();
    scene.objects.retain(|o| o.class != SemanticClass::Wall);
    let next = scene.objects.iter().map(|o| o.id).max().unwrap() + 1;
    // Three walls of a 4 x 4 m room in one mesh, 2.5 m high, and a ceiling slab in the same
    // mesh (above the band: not drawn).
    let walls = quads(&[
        [-2.0, -2.0, 2.0, -2.0, 0.0, 2.5],
        [-2.0, -2.0, -2.0, 2.0, 0.0, 2.5],
        [-2.0, 2.0, 2.0, 2.0, 0.0, 2.5],
        [-2.0, -2.0, 2.0, 2.0, 2.5, 2.5],
    ]);
    let mut w = SceneObject::from_parts(next, SemanticClass::Wall, Pose::IDENTITY, vec![walls]);
    w.bbox = w.compute_bbox();
    // A 0.6 m cube of furniture at (-1.2, 1.2).
    let (x0, x1, z0, z1) = (-1.5, -0.9, 0.9, 1.5);
    let cube = quads(&[
        [x0, z0, x1, z0, 0.0, 0.6],
        [x1, z0, x1, z1, 0.0, 0.6],
        [x1, z1, x0, z1, 0.0, 0.6],
        [x0, z1, x0, z0, 0.0, 0.6],
        [x0, z0, x1, z1, 0.6, 0.6],
    ]);
    let mut c =
        SceneObject::from_parts(next + 1, SemanticClass::Cabinet, Pose::IDENTITY, vec![cube]);
    c.bbox = c.compute_bbox();
    scene.objects.extend([w, c]);
    let opts = TopdownOptions {
        labels: false,
        room_names: false,
        ..Default::default()
    };
    let td = render_topdown(&scene, None, &opts);
    let wall = class_color(SemanticClass::Wall);
    // The walls are drawn where they stand...
    assert_eq!(px(&td, Vec2::new(-2.0, 0.5)), wall);
    assert_eq!(px(&td, Vec2::new(0.0, 2.0)), wall);
    // ...the room inside the walls' bounding box is not painted (it was, as a filled hull).
    assert_ne!(px(&td, Vec2::new(-1.0, -0.5)), wall);
    assert_ne!(px(&td, Vec2::new(1.5, 1.5)), wall);
    // The cube's inside is filled with its class colour.
    assert_eq!(
        px(&td, Vec2::new(-1.2, 1.2)),
        class_color(SemanticClass::Cabinet)
    );
    // Walls are thin: few pixels of a row crossing the room are wall-coloured.
    let y = td.frame.to_pixel(Vec2::new(0.0, 0.5)).y as u32;
    let (xa, xb) = (
        td.frame.to_pixel(Vec2::new(-2.3, 0.0)).x as u32,
        td.frame.to_pixel(Vec2::new(1.9, 0.0)).x as u32,
    );
    let dark = (xa..xb)
        .filter(|&x| td.image.get_pixel(x, y).0 == wall)
        .count();
    assert!(
        (1..=4).contains(&dark),
        "{dark} wall pixels across the room"
    );
}

#[test]
fn an_open_leaf_sweeps_its_arc_a_pair_two_half_arcs_a_sliding_leaf_none() {
    use glam::Vec3;
    use vlnverse_env::{Aabb, DoorKind, Pose, SceneObject};
    let opts = TopdownOptions {
        labels: false,
        room_names: false,
        ..Default::default()
    };
    // The fixture's door: at x = 2 across z in [-0.45, 0.45], opening onto -x. A leaf stands
    // open into the room from the jamb on its side of the opening (thin, near the wall).
    let leaf = |id, z: f32| {
        let mut o = SceneObject::from_parts(id, SemanticClass::Door, Pose::IDENTITY, vec![]);
        o.bbox = Aabb::new(
            Vec3::new(1.9, 0.0, z - 0.02),
            Vec3::new(1.98, 2.0, z + 0.02),
        );
        o
    };
    let with = |kind: DoorKind, leaves: &[(u32, f32)]| {
        let mut scene = fixture_scene();
        for &(id, z) in leaves {
            scene.objects.push(leaf(id, z));
        }
        let d = &mut scene.doors[0];
        d.kind = kind;
        d.leaf = leaves.first().map(|l| l.0);
        d.second_leaf = leaves.get(1).map(|l| l.0);
        render_topdown(&scene, None, &opts)
    };
    let bare = render_topdown(&fixture_scene(), None, &opts);
    // Midpoints of the arcs: a full leaf (radius 0.9) hinged at z = 0.45, and the two half
    // leaves (radius 0.45) hinged at z = +-0.45.
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let full = Vec2::new(2.0 - 0.9 * s, 0.45 - 0.9 * s);
    let half_a = Vec2::new(2.0 - 0.45 * s, 0.45 - 0.45 * s);
    let half_b = Vec2::new(2.0 - 0.45 * s, -0.45 + 0.45 * s);
    for p in [full, half_a, half_b] {
        assert_eq!(px(&bare, p), room_color(RoomType::DiningRoom), "{p}");
    }
    let hinged = with(DoorKind::Hinged, &[(90, 0.4)]);
    assert_ne!(px(&hinged, full), px(&bare, full));
    let pair = with(DoorKind::French, &[(90, 0.4), (91, -0.4)]);
    assert_ne!(px(&pair, half_a), px(&bare, half_a));
    assert_ne!(px(&pair, half_b), px(&bare, half_b));
    assert_eq!(
        px(&pair, full),
        px(&bare, full),
        "a half leaf swept a whole one's arc"
    );
    let sliding = with(DoorKind::Sliding, &[(90, 0.4)]);
    for p in [full, half_a, half_b] {
        assert_eq!(px(&sliding, p), px(&bare, p), "a sliding leaf swept {p}");
    }
}
