//! What lies on the furniture of some homes and the pulls of some dressers (a folded blanket,
//! throw pillows or a quilt on a bed, a blanket or more cushions on a sofa, a blanket on an
//! armchair, a seat cushion on a chair, knobs or handles on a dresser, flowers on a plant or
//! in a vase, glass panes in a pantry's top door): each is recorded as a feature of the objects that have it (instructions say
//! it: vlnverse-instructions data/features.toml) and each object with the feature has the
//! parts that show it.

use std::collections::BTreeMap;
use vlnverse_env::{Part, Scene, SceneObject, SceneSource, SemanticClass as C, Shape};
use vlnverse_procgen::{HomeGenerator, Preset};

/// The tiny homes and some more from other seeds.
fn homes() -> Vec<Scene> {
    let g = HomeGenerator::from_preset(Preset::Tiny).expect("tiny preset");
    let mut out: Vec<Scene> = (0..g.len()).map(|i| g.scene(i).expect("tiny")).collect();
    out.extend((0..40).map(|s| g.generate(2000 + s, "extra").expect("home")));
    out
}

/// A box part's size and the height of its bottom, in the object's frame.
fn boxed(p: &Part) -> Option<([f32; 3], f32)> {
    match p.shape {
        Shape::Cuboid {
            half_extents: h, ..
        } => Some((h.map(|x| 2.0 * x), p.transform.position[1] - h[1])),
        _ => None,
    }
}

fn near(a: f32, b: f32) -> bool {
    (a - b).abs() < 2e-3
}

/// Boxes `height` high whose bottom is at `bottom` (any when `None`).
fn boxes(o: &SceneObject, height: f32, bottom: Option<f32>) -> usize {
    o.parts
        .iter()
        .filter_map(boxed)
        .filter(|(s, y)| near(s[1], height) && bottom.is_none_or(|b| near(*y, b)))
        .count()
}

/// Whether `o`, which has `feature`, has the parts that show it.
fn shows(o: &SceneObject, feature: &str) -> bool {
    match feature {
        // A 7 cm band on the blanket (its top at 0.53 m).
        "folded blanket" => boxes(o, 0.07, Some(0.53)) == 1,
        // Two upright cushions on the mattress (its top at 0.5 m).
        "throw pillows" => boxes(o, 0.28, Some(0.5)) == 2,
        // Squares on the mattress in place of the one blanket.
        "quilt" => boxes(o, 0.03, Some(0.5)) >= 6,
        // A 3 cm layer on the top of an arm; a 5 cm one on the seat.
        "blanket over arm" => boxes(o, 0.03, None) == 1,
        "blanket on seat" => boxes(o, 0.05, Some(0.45)) == 1,
        // Two throw cushions and two more.
        "four cushions" => boxes(o, 0.35, Some(0.45)) == 2 && boxes(o, 0.3, Some(0.45)) == 2,
        // A 2 cm layer over the back.
        "blanket over back" => boxes(o, 0.02, None) == 1,
        "seat cushion" => boxes(o, 0.035, None) == 1,
        // Knobs 4 cm square, two a row or one a drawer.
        "knobs" => boxes(o, 0.04, None) >= 4,
        "handles" => boxes(o, 0.022, None) >= 4,
        // Blossoms: small boxes, 4.5 cm on a plant, 5 cm in a vase.
        "flowers" => boxes(o, 0.045, None) == 10,
        "flowers in vase" => boxes(o, 0.05, None) == 3,
        // The frame and bars of four panes.
        "glass panes" => boxes(o, 0.03, None) == 1 && boxes(o, 0.05, None) == 2,
        other => panic!("no check for {other:?}"),
    }
}

#[test]
fn dressings_are_recorded_and_seen() {
    let classes: [(&str, &[C]); 13] = [
        ("folded blanket", &[C::Bed]),
        ("throw pillows", &[C::Bed]),
        ("quilt", &[C::Bed]),
        ("blanket over arm", &[C::Sofa]),
        ("blanket on seat", &[C::Sofa]),
        ("four cushions", &[C::Sofa]),
        ("blanket over back", &[C::Armchair]),
        ("seat cushion", &[C::Chair]),
        ("knobs", &[C::Dresser]),
        ("handles", &[C::Dresser]),
        ("flowers", &[C::PottedPlant]),
        ("flowers in vase", &[C::Vase]),
        ("glass panes", &[C::KitchenCabinet]),
    ];
    let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
    for scene in homes() {
        for o in &scene.objects {
            for &(f, of) in &classes {
                let has = o.features.iter().any(|x| x == f);
                if !has {
                    // None of these parts without the feature ("quilt": a bed's blanket is one
                    // 3 cm box at 0.5 m, not six).
                    if of.contains(&o.class) {
                        assert!(!shows(o, f), "{} shows {f:?} unrecorded", o.name);
                    }
                    continue;
                }
                assert!(of.contains(&o.class), "{}: {f:?}", o.name);
                assert!(shows(o, f), "{} has {f:?} but does not show it", o.name);
                *seen.entry(f).or_default() += 1;
            }
        }
    }
    for &(f, _) in &classes {
        assert!(seen.get(f).is_some_and(|n| *n > 0), "no {f:?} in {seen:?}");
    }
}
