//! Descriptions of objects, rooms and openings for the template generator: class synonyms,
//! colour shade, material, size and shape (from [`super::lexicon`]), a relation to a nearby
//! object from the scene graph, and where the object stands in its room (corner, wall,
//! middle, doorway). Every other object a description names is returned as grounding.

use super::lexicon::{
    color_phrases, distinct_uses, feature_modifiers, material_noun, material_words,
    modifier_phrases, object_names, room_names, shape_words,
};
use super::path::{env_side, footprint, rect_distance};
use super::phrases::{self as ph, pick};
use super::room_facts::{self, FloorKind};
use super::spatial;
use super::PathContext;
use glam::Vec2;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::cell::RefCell;
use std::collections::BTreeMap;
use vlnverse_env::scene_graph::{is_landmark, side_of_heading, Relation};
use vlnverse_env::{
    Door, DoorKind, Room, RoomId, RoomType, Scene, SceneObject, SemanticClass as C,
};
use vlnverse_score::episode::{GroundedObject, Role, Side};

/// Where grounded references are seen from: a path segment (or the last point) and its
/// heading, as `check_grounding` reads them.
#[derive(Clone, Copy)]
pub(crate) struct Viewpoint<'a> {
    pub pts: &'a [Vec2],
    pub headings: &'a [Vec2],
    pub index: usize,
}

impl Viewpoint<'_> {
    /// Distance from the viewpoint's segment to `o`'s footprint and the side of its centre
    /// seen from the closest point (the first of the 2 cm samples at the least distance).
    pub fn side_of(&self, o: &SceneObject) -> Option<(Side, f32)> {
        let i = self.index;
        let (a, b, h) = if i + 1 < self.pts.len() {
            (self.pts[i], self.pts[i + 1], *self.headings.get(i)?)
        } else {
            (*self.pts.get(i)?, self.pts[i], *self.headings.last()?)
        };
        let (lo, hi) = footprint(o);
        let steps = ((b - a).length() / 0.02).ceil().max(1.0) as usize;
        let mut best = (f32::INFINITY, a);
        for s in 0..=steps {
            let p = a.lerp(b, s as f32 / steps as f32);
            let d = rect_distance(p, lo, hi);
            if d < best.0 {
                best = (d, p);
            }
        }
        let side = env_side(side_of_heading(best.1, h, (lo + hi) * 0.5));
        Some((side, best.0))
    }
}

/// Options of one object description.
#[derive(Clone, Copy)]
pub(crate) struct NpOptions {
    /// Probability of naming the class by a synonym rather than its vocabulary name.
    pub synonym: f64,
    /// Probability of adding a relation to another object or a place in the room.
    pub relation: f64,
    /// Use the colour whenever the object has one.
    pub force_color: bool,
}

/// "the tall dark brown wooden wardrobe next to the bed": the phrase and the grounding of every
/// other object it names (role reference, seen from `view`; only objects within
/// `max_ref_distance` of the viewpoint are named).
pub(crate) fn object_np(
    ctx: &PathContext<'_>,
    o: &SceneObject,
    view: Viewpoint<'_>,
    opts: NpOptions,
    max_ref_distance: f32,
    rng: &mut ChaCha8Rng,
) -> (String, Vec<GroundedObject>) {
    let scene = ctx.scene;
    let peers: Vec<&SceneObject> = ctx
        .graph
        .objects_of_class(o.class)
        .iter()
        .filter_map(|&id| scene.object(id))
        .collect();
    let ambiguous = peers.len() > 1;
    let names = object_names(o);
    let name = if rng.random_bool(opts.synonym) {
        pick(rng, &names)
    } else {
        names[0]
    };
    let mut adj: Vec<String> = Vec::new();
    // Never an adjective the name already says ("the low-slung low table").
    let shapes: Vec<&str> = shape_words(o, &peers)
        .into_iter()
        .filter(|a| !name.split(' ').any(|w| a.contains(w) || w.contains(a)))
        .collect();
    if !shapes.is_empty() && rng.random_bool(0.25) {
        adj.push(pick(rng, &shapes).to_string());
    }
    // A plant's colour and material are its pot's.
    if matches!(o.class, C::PottedPlant | C::SmallPlant) {
        let colors = color_phrases(o);
        let mut s = format!(
            "the {}{name}",
            adj.first().map(|a| format!("{a} ")).unwrap_or_default()
        );
        if !colors.is_empty() && (opts.force_color || ambiguous || rng.random_bool(0.45)) {
            let c = &colors[rng.random_range(0..colors.len())];
            let m = material_words(o).first().copied().unwrap_or("");
            let pot = if m.is_empty() || rng.random_bool(0.5) {
                format!("{c} pot")
            } else {
                format!("{c} {m} pot")
            };
            s = format!("{s} in {} {pot}", pick(rng, &["a", "the", "its"]));
        }
        let mut extra = Vec::new();
        if rng.random_bool(opts.relation) {
            if let Some(r) = relation_phrase(ctx, o, view, max_ref_distance, rng, &mut extra) {
                s.push(' ');
                s.push_str(&r);
            }
        }
        return (s, extra);
    }
    let colors = color_phrases(o);
    let color = !colors.is_empty() && (opts.force_color || ambiguous || rng.random_bool(0.35));
    if color {
        // The plain colour word half the time, a shade otherwise.
        let c = if colors.len() == 1 || rng.random_bool(0.5) {
            colors[0].clone()
        } else {
            colors[rng.random_range(1..colors.len())].clone()
        };
        adj.push(c);
    }
    let mats = material_words(o);
    let mut material_after = None;
    if !mats.is_empty() && rng.random_bool(0.2) {
        let m = pick(rng, mats);
        if rng.random_bool(0.3) {
            material_after = Some(m);
        } else if !adj.iter().any(|a| a == m) {
            adj.push(m.to_string());
        }
    }
    // A painting's subject or a worktop's stone as a noun before the name ("the blue zebra
    // painting", "the marble counter"), now and then.
    let modifier = noun_modifier(o, &peers, name, &adj, rng);
    if let Some(m) = modifier {
        if STONE_TOPS.contains(&m) {
            // The colour and material words are the cabinet's under the stone top.
            adj.clear();
            material_after = None;
        }
        adj.push(m.to_string());
    }
    let mut s = String::from("the ");
    for a in &adj {
        s.push_str(a);
        s.push(' ');
    }
    s.push_str(name);
    if let Some(m) = material_after {
        s.push_str(" made of ");
        s.push_str(material_noun(m));
    }
    let mut extra = Vec::new();
    if rng.random_bool(opts.relation) {
        if let Some(r) = relation_phrase(ctx, o, view, max_ref_distance, rng, &mut extra) {
            s.push(' ');
            s.push_str(&r);
        }
    } else if material_after.is_none()
        && rng.random_bool(if o.class == C::PictureFrame {
            // What a painting shows is how people tell it ("the painting of a lighthouse").
            0.3
        } else {
            0.12
        })
    {
        // Not after "made of metal": "the stove made of metal you cook on" runs two phrases
        // after the name together. Not the subject said twice: "the windmill painting of a
        // windmill".
        let said = modifier.map_or_else(Vec::new, |m| modifier_phrases(o, m));
        let uses: Vec<&str> = distinct_uses(o, &peers)
            .into_iter()
            .filter(|u| !said.contains(u))
            .collect();
        if !uses.is_empty() {
            s.push(' ');
            s.push_str(pick(rng, &uses));
        }
    }
    (s, extra)
}

/// Modifier words of a stone worktop (`data/features.toml` `[modifiers]`), which describe the
/// top and not the cabinet the colour and material words describe.
const STONE_TOPS: [&str; 2] = ["marble", "granite"];

/// One of `o`'s feature nouns to say before `name` (a third of the time): a painting's subject
/// only before "painting" or "picture" (not "the zebra photo frame"), a stone only before a
/// counter's name, never a word already said.
fn noun_modifier(
    o: &SceneObject,
    peers: &[&SceneObject],
    name: &str,
    adj: &[String],
    rng: &mut ChaCha8Rng,
) -> Option<&'static str> {
    let words: Vec<&'static str> = feature_modifiers(o, peers)
        .into_iter()
        .filter(|w| !adj.iter().any(|a| a == w))
        .collect();
    let fits = o.class != C::PictureFrame || matches!(name, "painting" | "picture");
    if words.is_empty() || !fits || !rng.random_bool(0.35) {
        return None;
    }
    let m = pick(rng, &words);
    // A sink's marble top is not the basin: "the sink with a marble top", not "the marble sink".
    (!STONE_TOPS.contains(&m) || matches!(o.class, C::Counter | C::KitchenIsland)).then_some(m)
}

/// A relation of `o` to another object ("next to the sofa", "on the desk", "with the lamp on
/// it"), or to its room ("in the corner", "against the wall").
fn relation_phrase(
    ctx: &PathContext<'_>,
    o: &SceneObject,
    view: Viewpoint<'_>,
    max_ref_distance: f32,
    rng: &mut ChaCha8Rng,
    extra: &mut Vec<GroundedObject>,
) -> Option<String> {
    let scene = ctx.scene;
    let g = ctx.graph;
    // Candidates: (kind, object). kind 0 support below, 1 object on top, 2 next to, 3 near.
    let mut cands: Vec<(u8, &SceneObject)> = Vec::new();
    if let Some(s) = o.supported_by.and_then(|s| scene.object(s)) {
        cands.push((0, s));
    }
    for s in g
        .supported(o.id)
        .into_iter()
        .filter_map(|s| scene.object(s))
    {
        if is_landmark(s) || s.bbox.size().max_element() > 0.2 {
            cands.push((1, s));
        }
    }
    for (kind, rel) in [(2u8, Relation::NextTo), (3, Relation::Near)] {
        for (n, _) in g.neighbours(o.id, rel).into_iter().take(3) {
            if let Some(x) = scene.object(n) {
                if !x.is_structure() && x.class != o.class && is_landmark(x) {
                    cands.push((kind, x));
                }
            }
        }
    }
    // Only objects named unambiguously (unique class in the scene) and in view of the path.
    cands.retain(|(_, x)| g.objects_of_class(x.class).len() == 1 && x.id != o.id);
    let seen = |x: &SceneObject| view.side_of(x).filter(|&(_, d)| d <= max_ref_distance);
    // A place people single a thing out by: in front of a piece, under a window, between two.
    let seen_places: Vec<(Place<'_>, Vec<Side>)> = places(ctx, o)
        .into_iter()
        .filter_map(|p| {
            let sides = p.objects().into_iter().map(|x| seen(x).map(|s| s.0));
            let sides = sides.collect::<Option<Vec<Side>>>()?;
            Some((p, sides))
        })
        .collect();
    if !seen_places.is_empty() && rng.random_bool(0.4) {
        let (p, sides) = &seen_places[rng.random_range(0..seen_places.len())];
        for (x, side) in p.objects().into_iter().zip(sides) {
            extra.push(reference(x, *side, view.index));
        }
        return Some(p.phrase(rng));
    }
    let feature = room_feature(scene, o);
    if cands.is_empty() || (feature.is_some() && rng.random_bool(0.35)) {
        return feature.map(|f| pick(rng, f).to_string());
    }
    let (kind, x) = cands[rng.random_range(0..cands.len())];
    let Some((side, _)) = seen(x) else {
        return feature.map(|f| pick(rng, f).to_string());
    };
    let xn = reference_name(x, rng);
    let bank: &[&str] = match kind {
        0 => &["on {x}", "on top of {x}", "sitting on {x}"],
        1 => &["with {x} on it", "with {x} on top"],
        2 => &["next to {x}", "beside {x}", "by {x}"],
        _ => &["near {x}", "close to {x}", "not far from {x}"],
    };
    let phrase = fill1(pick(rng, bank), &xn);
    extra.push(reference(x, side, view.index));
    Some(phrase)
}

/// "the sofa", now and then by a synonym ("the couch"): how a reference object is named.
fn reference_name(x: &SceneObject, rng: &mut ChaCha8Rng) -> String {
    let names = object_names(x);
    let name = if rng.random_bool(0.3) {
        pick(rng, &names)
    } else {
        names[0]
    };
    format!("the {name}")
}

/// The grounding of a reference object seen from path point `index` on `side`.
fn reference(x: &SceneObject, side: Side, index: usize) -> GroundedObject {
    GroundedObject {
        object_id: x.id,
        class: x.class.name().to_string(),
        role: Role::Reference,
        side: Some(side),
        path_index: Some(index as u32),
    }
}

/// Landmark objects in `o`'s room of another class than `o`'s, each the only one of its class
/// in the scene (so "the sofa" names one thing), in id order.
fn room_landmarks<'s>(
    ctx: &PathContext<'s>,
    o: &SceneObject,
) -> impl Iterator<Item = &'s SceneObject> + use<'s> {
    let (ctx, class) = (*ctx, o.class);
    o.room
        .into_iter()
        .flat_map(move |r| unique_landmarks_in(&ctx, r))
        .filter(move |x| x.class != class)
}

/// Landmark objects in room `room` (no structure, no door leaves), each the only one of its
/// class in the scene, in id order.
pub(crate) fn unique_landmarks_in<'s>(
    ctx: &PathContext<'s>,
    room: RoomId,
) -> impl Iterator<Item = &'s SceneObject> + use<'s> {
    let (scene, g) = (ctx.scene, ctx.graph);
    scene.objects.iter().filter(move |x| {
        x.room == Some(room)
            && !x.is_structure()
            && x.class != C::Door
            && is_landmark(x)
            && g.objects_of_class(x.class).len() == 1
    })
}

/// Where `o` stands relative to other things in its room, as people single a thing out.
pub(crate) enum Place<'s> {
    /// In front of a piece with its back to a wall; for a bed, at its foot.
    Front(&'s SceneObject),
    /// Under a window.
    Window(&'s SceneObject),
    /// Between two pieces.
    Between(&'s SceneObject, &'s SceneObject),
    /// Hanging on the wall above a piece.
    Above(&'s SceneObject),
    /// Under a thing hanging above it (a painting, a mirror, a clock).
    Under(&'s SceneObject),
}

impl<'s> Place<'s> {
    /// The objects the place names.
    pub(crate) fn objects(&self) -> Vec<&'s SceneObject> {
        match *self {
            Place::Front(x) | Place::Window(x) | Place::Above(x) | Place::Under(x) => vec![x],
            Place::Between(x, y) => vec![x, y],
        }
    }

    /// "in front of the sofa", "at the foot of the bed", "under the window", "between the
    /// bed and the dresser".
    pub(crate) fn phrase(&self, rng: &mut ChaCha8Rng) -> String {
        match *self {
            Place::Front(x) => {
                let bank: &[&str] = if x.class == C::Bed {
                    &["at the foot of {x}", "at the end of {x}"]
                } else {
                    &[
                        "in front of {x}",
                        "just in front of {x}",
                        "out in front of {x}",
                    ]
                };
                fill1(pick(rng, bank), &reference_name(x, rng))
            }
            Place::Window(_) => {
                let bank = [
                    "under the window",
                    "below the window",
                    "beneath the window",
                    "underneath the window",
                ];
                pick(rng, &bank).to_string()
            }
            Place::Above(x) => {
                let bank = [
                    "above {x}",
                    "over {x}",
                    "hanging above {x}",
                    "on the wall above {x}",
                ];
                fill1(pick(rng, &bank), &reference_name(x, rng))
            }
            Place::Under(x) => {
                let bank = ["under {x}", "below {x}", "beneath {x}", "underneath {x}"];
                fill1(pick(rng, &bank), &reference_name(x, rng))
            }
            Place::Between(x, y) => {
                let (xn, yn) = (reference_name(x, rng), reference_name(y, rng));
                format!("between {xn} and {yn}")
            }
        }
    }
}

/// Every [`Place`] that holds of `o`: each piece it is in front of, the window above it, each
/// piece it hangs above, the thing hanging above it, and each pair it stands between (pieces the scene has one of, so "the sofa" names one thing).
pub(crate) fn places<'s>(ctx: &PathContext<'s>, o: &SceneObject) -> Vec<Place<'s>> {
    let scene = ctx.scene;
    let near: Vec<&SceneObject> = room_landmarks(ctx, o).collect();
    let mut out: Vec<Place<'s>> = near
        .iter()
        .filter(|x| spatial::in_front_of(scene, o, x))
        .map(|x| Place::Front(x))
        .collect();
    out.extend(spatial::window_above(scene, o).map(Place::Window));
    out.extend(
        near.iter()
            .filter(|x| spatial::hangs_above(o, x))
            .map(|x| Place::Above(x)),
    );
    out.extend(spatial::hung_above(scene, o).map(Place::Under));
    for (i, x) in near.iter().enumerate() {
        for y in &near[i + 1..] {
            if x.class != y.class && spatial::between(o, x, y) {
                out.push(Place::Between(x, y));
            }
        }
    }
    out
}

fn fill1(t: &str, x: &str) -> String {
    t.replace("{x}", x)
}

/// Where an object stands in its room: a corner, against a wall, by a doorway or in the
/// middle (from the room polygon and the doors); `None` when it is none of these clearly.
pub(crate) fn room_feature(scene: &Scene, o: &SceneObject) -> Option<&'static [&'static str]> {
    let room = o.room.and_then(|r| scene.room(r))?;
    let (lo, hi) = footprint(o);
    if room.polygon.len() < 3 {
        return None;
    }
    let corner = room
        .polygon
        .iter()
        .map(|p| rect_distance(Vec2::from(*p), lo, hi))
        .fold(f32::INFINITY, f32::min);
    if corner < 0.4 {
        return Some(ph::IN_CORNER.entries());
    }
    if scene.doors.iter().any(|d| {
        d.rooms.contains(&room.id)
            && rect_distance(Vec2::new(d.position[0], d.position[2]), lo, hi) < 0.6
    }) {
        return Some(ph::BY_DOOR.entries());
    }
    let wall = edge_distance(room, lo, hi);
    if wall < 0.2 {
        return Some(ph::AT_WALL.entries());
    }
    if wall > 1.2 {
        return Some(ph::MID_ROOM.entries());
    }
    None
}

/// Least distance from the rectangle `[lo, hi]` to the room polygon's edges (sampled).
fn edge_distance(room: &Room, lo: Vec2, hi: Vec2) -> f32 {
    let n = room.polygon.len();
    let mut best = f32::INFINITY;
    for i in 0..n {
        let a = Vec2::from(room.polygon[i]);
        let b = Vec2::from(room.polygon[(i + 1) % n]);
        let steps = ((b - a).length() / 0.1).ceil().max(1.0) as usize;
        for s in 0..=steps {
            best = best.min(rect_distance(a.lerp(b, s as f32 / steps as f32), lo, hi));
        }
    }
    best
}

/// What people call a room from what it holds and how it sits in the home ("master bedroom",
/// "nursery", "en suite bathroom", "half bath", "walk-in closet", "the kitchen area" of an
/// open-plan space, "the landing" upstairs): the bank of such names, `None` when none holds.
pub(crate) fn room_by_content(scene: &Scene, room: RoomId) -> Option<ph::Bank> {
    let r = scene.room(room)?;
    let of_kind = |k: RoomType| scene.rooms.iter().filter(move |x| x.kind == k);
    let holds = |id: RoomId, c: C| scene.items().any(|o| o.room == Some(id) && o.class == c);
    // The rooms the openings of `id` lead to.
    let neighbours = |id: RoomId| -> Vec<RoomId> {
        scene
            .doors
            .iter()
            .filter(|d| d.rooms.contains(&id))
            .map(|d| {
                if d.rooms[0] == id {
                    d.rooms[1]
                } else {
                    d.rooms[0]
                }
            })
            .collect()
    };
    let open_plan = |id: RoomId| {
        scene
            .doors
            .iter()
            .any(|d| d.open_plan && d.rooms.contains(&id))
    };
    let off_a_bedroom = |id: RoomId| {
        let n = neighbours(id);
        !n.is_empty()
            && n.iter().all(|&x| x == n[0])
            && scene
                .room(n[0])
                .is_some_and(|x| x.kind == RoomType::Bedroom)
    };
    match r.kind {
        RoomType::Bedroom if holds(room, C::Crib) => Some(ph::ROOM_NURSERY),
        RoomType::Bedroom => {
            let mut areas: Vec<(f32, RoomId)> = of_kind(RoomType::Bedroom)
                .map(|x| (x.area(), x.id))
                .collect();
            areas.sort_by(|a, b| b.0.total_cmp(&a.0));
            let master = areas.len() >= 2 && areas[0].0 >= 1.15 * areas[1].0;
            if master && areas[0].1 == room {
                Some(ph::ROOM_MASTER)
            } else if master {
                Some(ph::ROOM_GUEST)
            } else {
                None
            }
        }
        RoomType::Bathroom if off_a_bedroom(room) => Some(ph::ROOM_EN_SUITE),
        RoomType::Bathroom if super::openings::is_half_bath(scene, room) => {
            Some(ph::ROOM_HALF_BATH)
        }
        RoomType::Bathroom => {
            let tubs = of_kind(RoomType::Bathroom)
                .filter(|x| holds(x.id, C::Bathtub))
                .count();
            let baths = of_kind(RoomType::Bathroom).count();
            (baths >= 2 && tubs == 1 && holds(room, C::Bathtub)).then_some(ph::ROOM_MAIN_BATH)
        }
        RoomType::Closet if off_a_bedroom(room) => Some(ph::ROOM_WALK_IN),
        // The upstairs hallway round the stairwell (its railings stand in it).
        RoomType::Hallway
            if scene
                .objects
                .iter()
                .any(|o| o.class == C::Railing && o.room == Some(room)) =>
        {
            Some(ph::ROOM_LANDING)
        }
        // A long, narrow hallway.
        RoomType::Hallway if narrow_and_long(r) => Some(ph::ROOM_PASSAGE),
        RoomType::Kitchen if r.area() < 9.0 && !open_plan(room) => Some(ph::ROOM_KITCHENETTE),
        RoomType::Porch | RoomType::Balcony
            if room_facts::floor_kind(scene, room) == Some(FloorKind::Wood) =>
        {
            Some(ph::ROOM_DECK)
        }
        // A room open to the next one, with no doorway between: an area of one open space.
        RoomType::Kitchen if open_plan(room) => Some(ph::ROOM_OPEN_KITCHEN),
        RoomType::DiningRoom if open_plan(room) => Some(ph::ROOM_OPEN_DINING),
        RoomType::LivingRoom if open_plan(room) => Some(ph::ROOM_OPEN_LIVING),
        // An office or a spare room kept for games, or for painting.
        RoomType::Office | RoomType::Room
            if [C::PoolTable, C::PingPongTable, C::FoosballTable]
                .iter()
                .any(|&c| holds(room, c)) =>
        {
            Some(ph::ROOM_GAME)
        }
        RoomType::Office | RoomType::Room if holds(room, C::Easel) => Some(ph::ROOM_STUDIO),
        _ => None,
    }
}

/// Whether `room` is under 1.3 m across and over 3 m long (its outline's bounding box).
fn narrow_and_long(room: &Room) -> bool {
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for p in &room.polygon {
        lo = lo.min(Vec2::from(*p));
        hi = hi.max(Vec2::from(*p));
    }
    let size = hi - lo;
    size.min_element() < 1.3 && size.max_element() > 3.0
}

/// A name for the room from [`room_by_content`] now and then (with probability `p`), else
/// `None`; with `keep_kind`, only a name holding the room type's own words ("master bedroom",
/// not "nursery"), so a reader still knows the type.
pub(crate) fn content_name(
    scene: &Scene,
    room: RoomId,
    p: f64,
    keep_kind: bool,
    rng: &mut ChaCha8Rng,
) -> Option<String> {
    let bank = room_by_content(scene, room)?;
    if !rng.random_bool(p) {
        return None;
    }
    let name = pick(rng, &bank);
    let kind = scene.room(room)?.kind;
    (!keep_kind || tells_kind(name, kind)).then(|| format!("the {name}"))
}

/// Whether the room name `name` still tells a reader the room type `kind`: it holds the type's
/// own words or [`kind_words_also`].
fn tells_kind(name: &str, kind: RoomType) -> bool {
    name.contains(kind.words().as_str()) || kind_words_also(kind).iter().any(|w| name.contains(w))
}

/// Words that still tell a reader the room type when the type's own name is not in a room's
/// name ("passageway" is a hallway, a "walk-in wardrobe" a closet).
fn kind_words_also(kind: RoomType) -> &'static [&'static str] {
    match kind {
        RoomType::Hallway => &["passage"],
        RoomType::Closet => &["wardrobe"],
        RoomType::Porch | RoomType::Balcony => &["deck"],
        _ => &[],
    }
}

/// "the kitchen with the tiled floor", "the carpeted bedroom": a room by its floor (the
/// material of its largest slab, drawn as that material); `None` for a plain floor.
fn room_by_floor(scene: &Scene, r: &Room, name: &str, rng: &mut ChaCha8Rng) -> Option<String> {
    // The same reading of the floor as the room remarks ("The room has a carpeted floor.").
    let bank: &[&str] = match room_facts::floor_kind(scene, r.id)? {
        FloorKind::Tile => &[
            "the {r} with the tiled floor",
            "the {r} with the tile floor",
            "the tiled {r}",
        ],
        FloorKind::Carpet => &[
            "the carpeted {r}",
            "the {r} with the carpet",
            "the {r} with the carpeted floor",
        ],
        FloorKind::Wood => &[
            "the {r} with the wooden floor",
            "the {r} with the wood floor",
            "the {r} with the hardwood floor",
        ],
        FloorKind::Stone => &["the {r} with the stone floor", "the stone-floored {r}"],
        FloorKind::Concrete => &["the {r} with the concrete floor"],
    };
    Some(pick(rng, bank).replace("{r}", name))
}

/// "the kitchen", now and then "the lounge", "the big kitchen" or "the master bedroom" (room
/// names and sizes from the room's type, floor area and what it holds).
pub(crate) fn room_np(
    scene: &Scene,
    room: RoomId,
    naming: &RoomNaming,
    rng: &mut ChaCha8Rng,
) -> String {
    let Some(r) = scene.room(room) else {
        return "the room".into();
    };
    if let Some(name) = naming.content(scene, room, false, rng) {
        return name;
    }
    if rng.random_bool(0.06) {
        // By the noun it already goes by ("the lounge with the wooden floor").
        let name = naming.noun(room, r.kind, rng);
        if let Some(np) = room_by_floor(scene, r, name, rng) {
            return np;
        }
    }
    let name = naming.noun(room, r.kind, rng);
    let area = r.area();
    let adj: &[&str] = if r.kind == RoomType::Hallway && area > 6.0 {
        &["long", "narrow"]
    } else if area > 45.0 {
        &["large", "big", "huge"]
    } else if area > 24.0 {
        &["large", "big"]
    } else if area < 8.0 {
        &["small", "little"]
    } else {
        &[]
    };
    if !adj.is_empty() && rng.random_bool(0.2) {
        format!("the {} {name}", pick(rng, adj))
    } else {
        format!("the {name}")
    }
}

/// The noun each room goes by in one instruction: its type's name, or now and then one of its
/// synonyms, and then the same one every time it comes up (a living room is not "the den" two
/// sentences later).
pub(crate) struct RoomNaming {
    /// How often a room goes by a synonym rather than its type's name.
    synonym: f64,
    nouns: RefCell<BTreeMap<RoomId, &'static str>>,
}

impl RoomNaming {
    /// A writer who names a room by a synonym with probability `synonym`.
    pub(crate) fn new(synonym: f64) -> Self {
        RoomNaming {
            synonym,
            nouns: RefCell::new(BTreeMap::new()),
        }
    }

    /// The noun of room `room` of type `kind`: chosen at its first mention, kept after.
    pub(crate) fn noun(&self, room: RoomId, kind: RoomType, rng: &mut ChaCha8Rng) -> &'static str {
        if let Some(n) = self.nouns.borrow().get(&room) {
            return n;
        }
        let names = room_names(kind);
        let n = if rng.random_bool(self.synonym) {
            pick(rng, names)
        } else {
            names[0]
        };
        self.nouns.borrow_mut().insert(room, n);
        n
    }

    /// A name for `room` from what it holds ([`content_name`], now and then), when the room has
    /// no noun yet; kept as its noun after, so it goes by that name every time it comes up.
    pub(crate) fn content(
        &self,
        scene: &Scene,
        room: RoomId,
        keep_kind: bool,
        rng: &mut ChaCha8Rng,
    ) -> Option<String> {
        if self.nouns.borrow().contains_key(&room) {
            return None;
        }
        let bank = room_by_content(scene, room)?;
        if !rng.random_bool(0.3) {
            return None;
        }
        let name: &'static str = pick(rng, bank.entries());
        if keep_kind && !tells_kind(name, scene.room(room)?.kind) {
            return None;
        }
        self.nouns.borrow_mut().insert(room, name);
        Some(format!("the {name}"))
    }

    /// The noun of a room entered, which is named by its type unless it already has a noun.
    pub(crate) fn entered(&self, room: RoomId, kind: RoomType) -> &'static str {
        self.nouns
            .borrow_mut()
            .entry(room)
            .or_insert(room_names(kind)[0])
    }
}

/// The opening between rooms `a` and `b` nearest `at`, where the path crosses from one to the
/// other.
pub(crate) fn door_between(scene: &Scene, a: RoomId, b: RoomId, at: Vec2) -> Option<&Door> {
    scene
        .doors
        .iter()
        .filter(|d| d.rooms.contains(&a) && d.rooms.contains(&b))
        .min_by(|x, y| {
            let dx = Vec2::new(x.position[0], x.position[2]).distance(at);
            let dy = Vec2::new(y.position[0], y.position[2]).distance(at);
            dx.total_cmp(&dy).then(x.id.cmp(&y.id))
        })
}

/// The leaf hung in an opening, if it has one.
pub(crate) fn door_leaf<'s>(scene: &'s Scene, door: &Door) -> Option<&'s SceneObject> {
    door.leaf.and_then(|id| scene.object(id))
}

/// Whether `o` is the leaf of a closed door.
pub(crate) fn is_closed_leaf(scene: &Scene, o: &SceneObject) -> bool {
    o.class == C::Door
        && scene
            .doors
            .iter()
            .any(|d| d.leaves().any(|l| l == o.id) && d.is_closed())
}

/// The opening a path crosses from room `a` into room `b` near `at`, described ("the
/// doorway", "the open archway").
pub(crate) fn door_np(
    scene: &Scene,
    a: RoomId,
    b: RoomId,
    at: Vec2,
    rng: &mut ChaCha8Rng,
) -> Option<String> {
    let door = door_between(scene, a, b, at)?;
    // A glass door or an arch goes by its kind, as people tell it from the other doors.
    if let Some(noun) = door_kind_noun(door.kind, rng) {
        let open = door.leaf.is_some() && rng.random_bool(0.3);
        return Some(format!("the {}{noun}", if open { "open " } else { "" }));
    }
    // A doorway with a leaf in it is a door, and people name its colour now and then.
    if let Some(leaf) = door_leaf(scene, door) {
        let plain = match rng.random_range(0..5) {
            0 => Some("the door".to_string()),
            1 => Some("the open door".to_string()),
            2 => Some("the doorway".to_string()),
            3 => Some(format!("the {} door", leaf.color)),
            _ => None,
        };
        if plain.is_some() {
            return plain;
        }
        // Its shade, now and then its material, and that it stands open.
        let shades = color_phrases(leaf);
        let c = match shades.len() {
            0 => leaf.color.clone(),
            n => shades[rng.random_range(0..n)].clone(),
        };
        let m = material_words(leaf)
            .first()
            .copied()
            .filter(|m| !c.contains(m) && rng.random_bool(0.4));
        let open = if rng.random_bool(0.4) { "open " } else { "" };
        return Some(match m {
            Some(m) => format!("the {open}{c} {m} door"),
            None => format!("the {open}{c} door"),
        });
    }
    let bank: &[&str] = if door.open_plan {
        // (Not "the archway": an arched doorway is a kind of its own, `DoorKind::Arched`.)
        &["the wide opening", "the opening"]
    } else if door.width < 0.85 {
        &["the narrow doorway", "the narrow door", "the small doorway"]
    } else if door.width > 1.1 {
        &["the wide doorway", "the large doorway", "the wide door"]
    } else {
        &[
            "the doorway",
            "the door",
            "the open door",
            "the open doorway",
        ]
    };
    Some(pick(rng, bank).to_string())
}

/// The noun a doorway of kind `kind` goes by when its kind is said ("sliding glass door",
/// "French door", "archway"); `None` for a plain hinged door.
pub(crate) fn door_kind_noun(kind: DoorKind, rng: &mut ChaCha8Rng) -> Option<&'static str> {
    let bank = match kind {
        DoorKind::Hinged => return None,
        DoorKind::Sliding => &ph::DOOR_SLIDING,
        DoorKind::French => &ph::DOOR_FRENCH,
        DoorKind::Arched => &ph::DOOR_ARCHED,
    };
    Some(pick(rng, bank))
}

/// The nearest corner or wall of the room holding `p`, seen facing `heading`: "in the corner",
/// "in the far left corner", "by the wall on your right", or `None` in the open.
pub(crate) fn end_place(
    scene: &Scene,
    room: Option<RoomId>,
    p: Vec2,
    heading: Vec2,
    rng: &mut ChaCha8Rng,
) -> Option<String> {
    let r = room.and_then(|r| scene.room(r))?;
    let n = r.polygon.len();
    if n < 3 {
        return None;
    }
    let (ci, cd) = r
        .polygon
        .iter()
        .enumerate()
        .map(|(i, q)| (i, Vec2::from(*q).distance(p)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    if cd < 1.0 {
        let c = Vec2::from(r.polygon[ci]);
        return Some(match env_side(side_of_heading(p, heading, c)) {
            s @ (Side::Left | Side::Right) if rng.random_bool(0.6) => {
                let w = super::path::side_word(s);
                pick(rng, &["in the {d} corner", "in the far {d} corner"]).replace("{d}", w)
            }
            _ => pick(rng, &["in the corner", "near the corner"]).to_string(),
        });
    }
    let mut best = (f32::INFINITY, p);
    for i in 0..n {
        let a = Vec2::from(r.polygon[i]);
        let b = Vec2::from(r.polygon[(i + 1) % n]);
        let ab = b - a;
        let t = ((p - a).dot(ab) / ab.length_squared().max(1e-9)).clamp(0.0, 1.0);
        let q = a + ab * t;
        let d = q.distance(p);
        if d < best.0 {
            best = (d, q);
        }
    }
    if best.0 < 0.8 {
        return Some(match env_side(side_of_heading(p, heading, best.1)) {
            s @ (Side::Left | Side::Right) => {
                let w = super::path::side_word(s);
                pick(
                    rng,
                    &["by the wall on your {d}", "next to the wall on your {d}"],
                )
                .replace("{d}", w)
            }
            Side::Ahead => pick(rng, &["facing the wall", "in front of the wall"]).to_string(),
            Side::Behind => "with the wall behind you".to_string(),
        });
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_env::SceneSource;
    use vlnverse_procgen::{HomeGenerator, Preset};

    #[test]
    fn rooms_open_to_the_next_are_areas_and_half_baths_have_no_tub() {
        let g = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
        let mut areas = 0;
        for i in 0..8 {
            let scene = g.scene(i).unwrap();
            for r in &scene.rooms {
                let open = scene
                    .doors
                    .iter()
                    .any(|d| d.open_plan && d.rooms.contains(&r.id));
                let bank = room_by_content(&scene, r.id);
                let area = [
                    ph::ROOM_OPEN_KITCHEN,
                    ph::ROOM_OPEN_DINING,
                    ph::ROOM_OPEN_LIVING,
                ];
                if bank.is_some_and(|b| area.contains(&b)) {
                    areas += 1;
                    assert!(open, "{} room {} is no area", scene.id, r.id);
                }
                if bank == Some(ph::ROOM_HALF_BATH) {
                    assert!(
                        !scene
                            .items()
                            .any(|o| o.room == Some(r.id)
                                && matches!(o.class, C::Bathtub | C::Shower))
                    );
                }
            }
        }
        assert!(areas > 0, "no open-plan room in the first homes");
    }

    #[test]
    fn a_passage_is_narrow_and_long() {
        let room = |w: f32, l: f32| Room {
            id: 0,
            kind: RoomType::Hallway,
            name: "hallway_0".into(),
            polygon: vec![[0.0, 0.0], [w, 0.0], [w, l], [0.0, l]],
        };
        assert!(narrow_and_long(&room(1.1, 5.0)));
        assert!(narrow_and_long(&room(6.0, 1.2)));
        assert!(!narrow_and_long(&room(1.5, 5.0)));
        assert!(!narrow_and_long(&room(1.1, 2.5)));
    }
}
