//! Spatial relations people use to single out a thing in a room, read from the scene's boxes:
//! in front of a piece standing against a wall ("the rug in front of the sofa", "at the foot
//! of the bed"), under a window, between two pieces, and a point between two pieces or in a
//! doorway, and a thing hanging on a wall above a piece ("the painting above the sofa"). Each
//! test is strict, so a relation said is true of the scene.

use glam::Vec2;
use vlnverse_env::scene_graph::is_landmark;
use vlnverse_env::{Door, Room, Scene, SceneObject, SemanticClass as C};

use super::path::{footprint, rect_distance};

/// The nearest edge of `room`'s polygon to the rectangle `[lo, hi]`: its distance and the
/// unit normal pointing from the edge into the room, towards the rectangle.
pub(crate) fn nearest_wall(room: &Room, lo: Vec2, hi: Vec2) -> Option<(f32, Vec2)> {
    let n = room.polygon.len();
    if n < 3 {
        return None;
    }
    let c = (lo + hi) * 0.5;
    let mut best: Option<(f32, Vec2)> = None;
    for i in 0..n {
        let a = Vec2::from(room.polygon[i]);
        let b = Vec2::from(room.polygon[(i + 1) % n]);
        let ab = b - a;
        let Some(along) = ab.try_normalize() else {
            continue;
        };
        let t = ((c - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        let q = a + ab * t;
        // The edge's normal, turned to face the rectangle's centre.
        let mut normal = along.perp();
        if normal.dot(c - q) < 0.0 {
            normal = -normal;
        }
        let d = rect_distance(q, lo, hi);
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, normal));
        }
    }
    best
}

/// Half the extent of the rectangle `[lo, hi]` along the unit direction `dir`.
fn half_extent(lo: Vec2, hi: Vec2, dir: Vec2) -> f32 {
    let h = (hi - lo) * 0.5;
    h.x * dir.x.abs() + h.y * dir.y.abs()
}

/// Whether `o` stands in front of `x`: `x` has its back to a wall of its room, and `o` stands
/// on the floor of the same room away from the walls, out from `x` into the room, within a
/// metre of it and no wider off its sides than `x` itself. For a bed (headboard to the wall)
/// this is the foot of the bed.
pub(crate) fn in_front_of(scene: &Scene, o: &SceneObject, x: &SceneObject) -> bool {
    if o.room.is_none() || o.room != x.room || o.id == x.id {
        return false;
    }
    let Some(room) = x.room.and_then(|r| scene.room(r)) else {
        return false;
    };
    // Only a thing standing out on the floor: a sink against the wall under a mirror, or a
    // curtain across the room from a bed, is not "in front of" it as people say it.
    let (olo, ohi) = footprint(o);
    if o.bbox.min[1] > 0.05 || nearest_wall(room, olo, ohi).is_none_or(|(d, _)| d < 0.15) {
        return false;
    }
    out_in_front(room, x, olo, ohi, 0.3)
}

/// Whether the rectangle `[lo, hi]` lies out from `x` into `room`, where `x` has its back to a
/// wall: within a metre of its front, and no further off its sides than `x` itself (or
/// `min_side`).
fn out_in_front(room: &Room, x: &SceneObject, lo: Vec2, hi: Vec2, min_side: f32) -> bool {
    let (xlo, xhi) = footprint(x);
    let Some((wall, n)) = nearest_wall(room, xlo, xhi) else {
        return false;
    };
    if wall > 0.25 {
        return false;
    }
    let d = (lo + hi) * 0.5 - (xlo + xhi) * 0.5;
    let side = n.perp();
    let gap = d.dot(n) - half_extent(xlo, xhi, n) - half_extent(lo, hi, n);
    let off = d.dot(side).abs();
    (-0.05..=1.0).contains(&gap) && off <= half_extent(xlo, xhi, side).max(min_side)
}

/// Whether the floor point `p` is at the foot of bed `bed`: in its room, out from the end
/// opposite its headboard wall, within a metre and no wider than the bed.
pub(crate) fn at_foot_of(scene: &Scene, p: Vec2, bed: &SceneObject) -> bool {
    let Some(room) = bed.room.and_then(|r| scene.room(r)) else {
        return false;
    };
    bed.class == C::Bed && room.contains(p.x, p.y) && out_in_front(room, bed, p, p, 0.0)
}

/// The window `o` stands under: `o` is against a wall, its top below the window's sill, and
/// the window's centre within 30 cm of its footprint, seen from above.
pub(crate) fn window_above<'s>(scene: &'s Scene, o: &SceneObject) -> Option<&'s SceneObject> {
    let room = o.room.and_then(|r| scene.room(r))?;
    let (lo, hi) = footprint(o);
    if nearest_wall(room, lo, hi)?.0 > 0.3 {
        return None;
    }
    scene
        .objects
        .iter()
        .filter(|w| w.class == C::Window && o.bbox.max[1] <= w.bbox.min[1] + 0.02)
        .find(|w| {
            let (wlo, whi) = footprint(w);
            rect_distance((wlo + whi) * 0.5, lo, hi) < 0.3
        })
}

/// Whether `o` hangs on a wall above `x` ("the painting above the sofa"): both in one room,
/// `x` standing on the floor, `o` on nothing, its bottom at least 80 cm above the floor and no
/// lower than `x`'s top, and its centre over `x`'s footprint (within 20 cm), seen from above.
pub(crate) fn hangs_above(o: &SceneObject, x: &SceneObject) -> bool {
    if o.room.is_none() || o.room != x.room || o.id == x.id {
        return false;
    }
    if o.supported_by.is_some() || x.supported_by.is_some() {
        return false;
    }
    let (bottom, floor) = (o.bbox.min[1], x.bbox.min[1]);
    if bottom - floor < 0.8 || bottom < x.bbox.max[1] - 0.02 {
        return false;
    }
    let (olo, ohi) = footprint(o);
    let (xlo, xhi) = footprint(x);
    rect_distance((olo + ohi) * 0.5, xlo, xhi) < 0.2
}

/// The thing hanging above `o` that people would name it by ("the sofa under the painting"):
/// a landmark, not a window, the only one of its class in the room.
pub(crate) fn hung_above<'s>(scene: &'s Scene, o: &SceneObject) -> Option<&'s SceneObject> {
    let in_room = |x: &&SceneObject| x.room.is_some() && x.room == o.room;
    scene
        .objects
        .iter()
        .filter(in_room)
        .filter(|h| !h.is_structure() && h.class != C::Window && is_landmark(h))
        .find(|h| {
            hangs_above(h, o)
                && scene
                    .objects
                    .iter()
                    .filter(in_room)
                    .filter(|x| x.class == h.class)
                    .count()
                    == 1
        })
}

/// Whether the floor point `p` lies between the footprints of `x` and `y`: on the line joining
/// their centres, in its middle half, within 40 cm of it, the two no more than 3.5 m apart
/// and `p` clear of both.
pub(crate) fn point_between(p: Vec2, x: &SceneObject, y: &SceneObject) -> bool {
    let (xlo, xhi) = footprint(x);
    let (ylo, yhi) = footprint(y);
    let (a, b) = ((xlo + xhi) * 0.5, (ylo + yhi) * 0.5);
    let ab = b - a;
    let len2 = ab.length_squared();
    if !(0.25..=3.5 * 3.5).contains(&len2) {
        return false;
    }
    let t = (p - a).dot(ab) / len2;
    let off = (a + ab * t).distance(p);
    (0.25..=0.75).contains(&t)
        && off < 0.4
        && rect_distance(p, xlo, xhi) > 0.05
        && rect_distance(p, ylo, yhi) > 0.05
}

/// Whether `o` stands between `x` and `y` (its centre, [`point_between`]), all in one room.
pub(crate) fn between(o: &SceneObject, x: &SceneObject, y: &SceneObject) -> bool {
    let (lo, hi) = footprint(o);
    o.room.is_some() && o.room == x.room && o.room == y.room && point_between((lo + hi) * 0.5, x, y)
}

/// The doorway whose opening the floor point `p` stands in (within 45 cm of its centre).
pub(crate) fn doorway_at(scene: &Scene, p: Vec2) -> Option<&Door> {
    scene
        .doors
        .iter()
        .filter(|d| !d.open_plan && !d.is_closed())
        .find(|d| Vec2::new(d.position[0], d.position[2]).distance(p) < 0.45)
}

/// Whether the walk `a -> b` crosses `room` diagonally, as people say "walk diagonally across
/// the room": both ends in the room, at 30 to 60 degrees to its longest wall, and at least
/// 0.6 times the side of a square of the room's area long.
pub(crate) fn diagonal_across(room: &Room, a: Vec2, b: Vec2) -> bool {
    let n = room.polygon.len();
    if n < 3 || !room.contains(a.x, a.y) || !room.contains(b.x, b.y) {
        return false;
    }
    let ab = b - a;
    if ab.length() < 0.6 * room.area().sqrt() {
        return false;
    }
    let wall = (0..n)
        .map(|i| Vec2::from(room.polygon[(i + 1) % n]) - Vec2::from(room.polygon[i]))
        .max_by(|x, y| x.length().total_cmp(&y.length()));
    let Some(wall) = wall.filter(|w| w.length() > 1e-3) else {
        return false;
    };
    let cos = (ab.normalize().dot(wall.normalize())).abs().clamp(0.0, 1.0);
    let deg = cos.acos().to_degrees();
    (30.0..=60.0).contains(&deg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_env::{Aabb, Pose, RoomType};

    fn object(id: u32, class: C, lo: [f32; 3], hi: [f32; 3]) -> SceneObject {
        let mut o = SceneObject::from_parts(id, class, Pose::IDENTITY, Vec::new());
        o.bbox = Aabb { min: lo, max: hi };
        o.room = Some(0);
        o
    }

    fn room() -> Room {
        Room {
            id: 0,
            kind: RoomType::Bedroom,
            name: "bedroom_0".into(),
            polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]],
        }
    }

    fn scene(objects: Vec<SceneObject>) -> Scene {
        // Through JSON, so fields the format gains later keep their defaults.
        serde_json::from_value(serde_json::json!({
            "format_version": 1, "id": "t", "source": "test", "seed": null,
            "floor_height": 0.0, "rooms": [room()], "doors": [], "objects": objects,
        }))
        .unwrap()
    }

    #[test]
    fn a_bench_at_the_foot_of_a_bed_against_the_wall_is_in_front_of_it() {
        // Bed with its head to the wall z = 0, foot at z = 2; a bench just past the foot.
        let bed = object(1, C::Bed, [1.0, 0.0, 0.0], [2.6, 0.6, 2.0]);
        let bench = object(2, C::Bench, [1.2, 0.0, 2.2], [2.4, 0.45, 2.6]);
        let far = object(3, C::Bench, [1.2, 0.0, 3.2], [2.4, 0.45, 3.6]);
        let aside = object(4, C::Chair, [3.2, 0.0, 0.5], [3.7, 0.9, 1.0]);
        let s = scene(vec![bed.clone(), bench.clone(), far.clone(), aside.clone()]);
        assert!(in_front_of(&s, &bench, &bed));
        assert!(!in_front_of(&s, &far, &bed), "more than a metre away");
        assert!(!in_front_of(&s, &aside, &bed), "off its side");
        assert!(
            !in_front_of(&s, &bed, &bench),
            "the bench is not against a wall"
        );
    }

    #[test]
    fn a_point_past_the_end_of_a_bed_is_at_its_foot() {
        let bed = object(1, C::Bed, [1.0, 0.0, 0.0], [2.6, 0.6, 2.0]);
        let s = scene(vec![bed.clone()]);
        assert!(at_foot_of(&s, Vec2::new(1.8, 2.5), &bed));
        assert!(!at_foot_of(&s, Vec2::new(1.8, 3.5), &bed), "too far");
        assert!(!at_foot_of(&s, Vec2::new(3.2, 1.0), &bed), "at its side");
        assert!(
            !at_foot_of(&s, Vec2::new(3.2, 2.5), &bed),
            "off past a corner"
        );
    }

    #[test]
    fn a_radiator_below_a_window_is_under_it_and_a_tall_wardrobe_is_not() {
        let window = object(1, C::Window, [1.0, 0.9, -0.1], [2.2, 2.1, 0.1]);
        let radiator = object(2, C::Radiator, [1.1, 0.1, 0.0], [2.0, 0.7, 0.12]);
        let wardrobe = object(3, C::Wardrobe, [1.0, 0.0, 0.0], [2.0, 2.0, 0.6]);
        let s = scene(vec![window.clone(), radiator.clone(), wardrobe.clone()]);
        assert_eq!(window_above(&s, &radiator).map(|w| w.id), Some(1));
        assert!(window_above(&s, &wardrobe).is_none());
    }

    #[test]
    fn a_painting_over_a_sofa_hangs_above_it_and_names_it() {
        // Sofa against the wall z = 0; a painting on that wall over it, another to its side.
        let sofa = object(1, C::Sofa, [1.0, 0.0, 0.0], [3.0, 0.85, 0.9]);
        let mut painting = object(2, C::PictureFrame, [1.6, 1.2, 0.0], [2.4, 1.8, 0.03]);
        painting.material = "canvas".into();
        let mut aside = object(3, C::Clock, [3.4, 1.5, 0.0], [3.7, 1.8, 0.05]);
        aside.material = "plastic".into();
        let mut low = object(4, C::Mirror, [1.2, 0.5, 0.0], [1.5, 1.0, 0.03]);
        low.material = "glass".into();
        let s = scene(vec![
            sofa.clone(),
            painting.clone(),
            aside.clone(),
            low.clone(),
        ]);
        assert!(hangs_above(&painting, &sofa));
        assert!(!hangs_above(&aside, &sofa), "not over its footprint");
        assert!(!hangs_above(&low, &sofa), "below the sofa's top");
        assert!(!hangs_above(&sofa, &painting));
        assert_eq!(hung_above(&s, &sofa).map(|h| h.id), Some(2));
        // A second painting in the room: "under the painting" no longer names one.
        let mut other = object(5, C::PictureFrame, [0.1, 1.2, 3.97], [0.9, 1.8, 4.0]);
        other.material = "canvas".into();
        let s = scene(vec![sofa.clone(), painting, other]);
        assert!(hung_above(&s, &sofa).is_none());
    }

    #[test]
    fn between_needs_the_middle_of_the_line_joining_the_two() {
        let a = object(1, C::Nightstand, [0.0, 0.0, 0.0], [0.5, 0.5, 0.5]);
        let b = object(2, C::Dresser, [2.5, 0.0, 0.0], [3.0, 0.8, 0.5]);
        let mid = object(3, C::PottedPlant, [1.3, 0.0, 0.1], [1.7, 0.8, 0.4]);
        let end = object(4, C::PottedPlant, [2.0, 0.0, 0.1], [2.3, 0.8, 0.4]);
        let off = object(5, C::PottedPlant, [1.3, 0.0, 1.1], [1.7, 0.8, 1.4]);
        assert!(between(&mid, &a, &b));
        assert!(!between(&end, &a, &b));
        assert!(!between(&off, &a, &b));
    }

    #[test]
    fn a_walk_corner_to_corner_is_diagonal_and_one_along_a_wall_is_not() {
        let r = room();
        let v = |x: f32, y: f32| Vec2::new(x, y);
        assert!(diagonal_across(&r, v(0.5, 0.5), v(3.5, 3.5)));
        assert!(diagonal_across(&r, v(3.5, 0.5), v(0.5, 3.0)));
        // Along a wall, too short, or leaving the room.
        assert!(!diagonal_across(&r, v(0.5, 0.5), v(3.5, 0.5)));
        assert!(!diagonal_across(&r, v(1.0, 1.0), v(2.0, 2.0)));
        assert!(!diagonal_across(&r, v(0.5, 0.5), v(5.0, 5.0)));
    }
}
