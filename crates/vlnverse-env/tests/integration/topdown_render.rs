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
