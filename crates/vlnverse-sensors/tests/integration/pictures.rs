//! What a framed canvas shows is drawn: a recorded subject ("sailboat", "zebra") gives its
//! picture, spread once over the canvas, in the rendered image.

use crate::common;

use glam::Vec3;
use std::sync::Arc;
use vlnverse_env::{Part, Pose, Scene, SceneObject, SemanticClass, Shape};
use vlnverse_sensors::{Channels, RasterRenderer, Renderer, SceneMesh};

/// A box part centred at `c` (object frame) of size `s`.
fn slab(c: Vec3, s: Vec3, rgb: [f32; 3]) -> Part {
    Part {
        shape: Shape::Cuboid {
            half_extents: (s * 0.5).to_array(),
            bevel: 0.0,
        },
        transform: Pose {
            position: c.to_array(),
            rotation: [0.0, 0.0, 0.0, 1.0],
        },
        color: rgb,
    }
}

/// A 4 m room whose far wall (z = -2) holds a 1.2 m x 0.9 m painting of `subject` (none: an
/// older scene's canvas) at eye height, a frame then a canvas, as the generator builds them.
fn room_with_painting(subject: Option<&str>) -> Scene {
    let grey = [0.7; 3];
    let wall = |id: u32, c: Vec3, s: Vec3| {
        let mut o = SceneObject::from_parts(
            id,
            SemanticClass::Wall,
            Pose::from_yaw(c, 0.0),
            vec![slab(Vec3::ZERO, s, grey)],
        );
        o.room = Some(0);
        o.material = "plaster".into();
        o
    };
    let mut floor = wall(1, Vec3::new(0.0, -0.05, 0.0), Vec3::new(4.0, 0.1, 4.0));
    floor.class = SemanticClass::Floor;
    let mut painting = SceneObject::from_parts(
        6,
        SemanticClass::PictureFrame,
        Pose::from_yaw(Vec3::new(0.0, 0.0, -1.95), 0.0),
        vec![
            slab(
                Vec3::new(0.0, 1.4, 0.01),
                Vec3::new(1.2, 0.9, 0.02),
                [0.2, 0.15, 0.1],
            ),
            slab(
                Vec3::new(0.0, 1.4, 0.025),
                Vec3::new(1.14, 0.84, 0.01),
                [0.8, 0.8, 0.75],
            ),
        ],
    );
    painting.room = Some(0);
    painting.material = "canvas".into();
    painting.features = subject.map(|s| vec![s.to_string()]).unwrap_or_default();
    let objects = vec![
        floor,
        wall(2, Vec3::new(-2.0, 1.3, 0.0), Vec3::new(0.1, 2.6, 4.1)),
        wall(3, Vec3::new(2.0, 1.3, 0.0), Vec3::new(0.1, 2.6, 4.1)),
        wall(4, Vec3::new(0.0, 1.3, -2.0), Vec3::new(4.1, 2.6, 0.1)),
        wall(5, Vec3::new(0.0, 1.3, 2.0), Vec3::new(4.1, 2.6, 0.1)),
        painting,
    ];
    common::living_room("gallery", objects)
}

/// The grey values (0..=255) of the canvas's pixels, in raster order, seen from the middle of
/// the room facing the painting.
fn canvas_pixels(subject: Option<&str>) -> Vec<f32> {
    let scene = room_with_painting(subject);
    let mut r = RasterRenderer::new();
    r.set_scene(Arc::new(SceneMesh::new(&scene).unwrap()))
        .unwrap();
    let base = Pose::from_yaw(Vec3::new(0.0, 0.0, 0.2), 0.0);
    let frame = r
        .render(&[common::view(&base, 224, 224, Channels::ALL)])
        .unwrap()
        .remove(0);
    // The canvas's middle: pixels of the painting whose four neighbours are too (the frame's
    // border is a few pixels wide and darker).
    let (w, h) = (frame.width as usize, frame.height as usize);
    let on = |x: usize, y: usize| frame.instance[y * w + x] == 6;
    let mut out = Vec::new();
    for y in 4..h - 4 {
        for x in 4..w - 4 {
            if on(x, y) && on(x - 4, y) && on(x + 4, y) && on(x, y - 4) && on(x, y + 4) {
                let i = 3 * (y * w + x);
                let rgb = &frame.rgb[i..i + 3];
                out.push(rgb.iter().map(|&c| c as f32).sum::<f32>() / 3.0);
            }
        }
    }
    out
}

#[test]
fn a_painting_shows_its_subject_and_subjects_look_different() {
    let sd = |v: &[f32]| {
        let m = v.iter().sum::<f32>() / v.len() as f32;
        (v.iter().map(|x| (x - m).powi(2)).sum::<f32>() / v.len() as f32).sqrt()
    };
    let boat = canvas_pixels(Some("sailboat"));
    let zebra = canvas_pixels(Some("zebra"));
    let old = canvas_pixels(None);
    assert!(boat.len() > 1500, "the canvas covers {} pixels", boat.len());
    // Same geometry, so the same pixels; the pictures differ.
    assert_eq!(boat.len(), zebra.len());
    assert_eq!(boat.len(), old.len());
    // The old landscape is soft bands; a subject has shapes of strong contrast.
    for (what, v, least) in [
        ("sailboat", &boat, 20.0),
        ("zebra", &zebra, 20.0),
        ("landscape", &old, 10.0),
    ] {
        assert!(
            sd(v) > least,
            "the {what} is nearly blank (sd {:.1})",
            sd(v)
        );
    }
    let diff = |a: &[f32], b: &[f32]| {
        a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f32>() / a.len() as f32
    };
    assert!(diff(&boat, &zebra) > 15.0, "{}", diff(&boat, &zebra));
    assert!(diff(&boat, &old) > 15.0, "{}", diff(&boat, &old));
    // Deterministic.
    assert_eq!(canvas_pixels(Some("zebra")), zebra);
}
