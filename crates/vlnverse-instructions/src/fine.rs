//! Fine-grained instructions of the template generator: the path is simplified into legs
//! (turn, length, landmarks, room changes), then written by one of several writers (terse,
//! plain, chatty, precise) who pick sentence plans per leg, leave things out and reorder them
//! the way people do. Every object named is grounded.

use super::describe::{
    door_between, door_kind_noun, door_np, end_place, is_closed_leaf, object_np, room_np,
    unique_landmarks_in, NpOptions, RoomNaming, Viewpoint,
};
use super::door_order;
use super::groups;
use super::lexicon::{class_names, number_word, object_names, ordinal_word, plural};
use super::openings::{self, Nearest, OpeningCount};
use super::path::{
    classify_turn, direction_of_yaw, env_side, floor_points, footprint, rect_distance,
    segment_headings, side_word, signed_turn_deg, visible, wall_rects, Turn,
};
use super::phrases::{self as ph, capitalize, fill, pick, Bank};
use super::room_facts::{self, FloorKind};
use super::spatial;
use super::stairwell;
use super::templates::{same_class_in_room, TemplateConfig};
use super::PathContext;
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::{BTreeMap, BTreeSet};
use vlnverse_env::scene_graph::{is_landmark, rooms_along_path, side_of_heading, Landmark};
use vlnverse_env::{
    ClassKind, DoorKind, ObjectId, RoomId, RoomType, Scene, SceneObject, SemanticClass as C,
};
use vlnverse_score::episode::{GroundedObject, Instruction, Role, Side};
use vlnverse_score::{DataError, Result};

/// Waypoints closer than this to the simplified line are dropped (m).
const SIMPLIFY_TOLERANCE: f32 = 0.5;
/// Legs shorter than this are folded into the next one (m).
const MIN_LEG: f32 = 1.0;
/// Objects a description names besides the landmark must be this close to the path (m).
const MAX_REFERENCE_DISTANCE: f32 = 2.5;
/// A clear turn of at least this many degrees is "sharp".
const SHARP_TURN_DEG: f32 = 115.0;

/// How an instruction's writer writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Writer {
    /// Few words, distances and landmarks often left out.
    Terse,
    /// Plain directions.
    Plain,
    /// Openers, remarks and contractions.
    Chatty,
    /// Metres and degrees.
    Precise,
}

impl Writer {
    fn draw(rng: &mut ChaCha8Rng) -> Writer {
        match rng.random_range(0..10) {
            0..=2 => Writer::Terse,
            3..=5 => Writer::Plain,
            6 | 7 => Writer::Chatty,
            _ => Writer::Precise,
        }
    }
    /// Probability of giving a leg's distance.
    fn distance(self) -> f64 {
        match self {
            Writer::Terse => 0.2,
            Writer::Plain => 0.35,
            Writer::Chatty => 0.3,
            Writer::Precise => 0.75,
        }
    }
    fn np(self) -> NpOptions {
        NpOptions {
            synonym: if self == Writer::Precise { 0.2 } else { 0.3 },
            relation: match self {
                Writer::Terse => 0.05,
                Writer::Precise => 0.25,
                _ => 0.15,
            },
            force_color: false,
        }
    }
}

/// A straight stretch of the path: segments `first..=last`, entered with `turn` (signed angle
/// `angle` degrees, positive to the right).
struct Leg {
    first: usize,
    last: usize,
    turn: Turn,
    angle: f32,
    len: f32,
}

/// Kept vertex indices of the polyline (Douglas-Peucker), first and last always kept.
fn simplify(pts: &[Vec2], tol: f32) -> Vec<usize> {
    fn rec(pts: &[Vec2], a: usize, b: usize, tol: f32, keep: &mut Vec<usize>) {
        if b <= a + 1 {
            return;
        }
        let (pa, pb) = (pts[a], pts[b]);
        let ab = pb - pa;
        let mut best = (0.0f32, a);
        for (i, &p) in pts.iter().enumerate().take(b).skip(a + 1) {
            let t = ((p - pa).dot(ab) / ab.length_squared().max(1e-9)).clamp(0.0, 1.0);
            let d = (pa + ab * t).distance(p);
            if d > best.0 {
                best = (d, i);
            }
        }
        if best.0 > tol {
            rec(pts, a, best.1, tol, keep);
            keep.push(best.1);
            rec(pts, best.1, b, tol, keep);
        }
    }
    let n = pts.len();
    let mut keep = vec![0];
    rec(pts, 0, n - 1, tol, &mut keep);
    keep.push(n - 1);
    // Fold short legs into the next one.
    let mut out = vec![0];
    for &k in &keep[1..keep.len() - 1] {
        let prev = pts[*out.last().unwrap_or(&0)];
        if pts[k].distance(prev) >= MIN_LEG {
            out.push(k);
        }
    }
    out.push(n - 1);
    out.dedup();
    out
}

fn legs_of(pts: &[Vec2], start: Vec2, cfg: &TemplateConfig) -> Vec<Leg> {
    let keep = simplify(pts, SIMPLIFY_TOLERANCE);
    let mut legs: Vec<Leg> = Vec::new();
    let mut prev = start;
    for w in keep.windows(2) {
        let (a, b) = (w[0], w[1]);
        let Some(h) = (pts[b] - pts[a]).try_normalize() else {
            continue;
        };
        let turn = classify_turn(prev, h, &cfg.turns);
        let len = pts[a].distance(pts[b]);
        let angle = signed_turn_deg(prev, h);
        prev = h;
        match legs.last_mut() {
            Some(l) if turn == Turn::Straight => {
                l.last = b - 1;
                l.len += len;
            }
            _ => legs.push(Leg {
                first: a,
                last: b - 1,
                turn,
                angle,
                len,
            }),
        }
    }
    if legs.is_empty() {
        legs.push(Leg {
            first: 0,
            last: pts.len().saturating_sub(2),
            turn: Turn::Straight,
            angle: 0.0,
            len: pts
                .first()
                .zip(pts.last())
                .map_or(0.0, |(a, b)| a.distance(*b)),
        });
    }
    legs
}

/// A distance in one of the ways people give it: metres, steps or feet, a number or a word.
fn distance_phrase(d: f32, w: Writer, rng: &mut ChaCha8Rng) -> String {
    if d < 1.25 {
        return pick(rng, &ph::DIST_SHORT).to_string();
    }
    let n = d.round().max(1.0) as u32;
    let steps = (d / 0.75).round().max(2.0) as u32;
    let about = pick(rng, &ph::ABOUT);
    let half = (0.35..0.65).contains(&d.fract());
    let metres = |rng: &mut ChaCha8Rng| fill(pick(rng, &ph::METRES), &[("n", &n.to_string())]);
    let form = if w == Writer::Precise {
        rng.random_range(0..3)
    } else {
        rng.random_range(0..8)
    };
    match form {
        // One metre is said in the singular ("about a metre", not "about 1 metres").
        0 | 1 if n == 1 && !(form == 1 && half) => {
            format!("{about} {}", pick(rng, &ph::ONE_METRE))
        }
        // "a little more than four metres" for 4.3 m, "just under five metres" for 4.7 m.
        0 if n >= 3 && (0.2..0.35).contains(&d.fract()) => {
            format!("a little more than {}", metres(rng))
        }
        0 if n >= 3 && (0.65..0.8).contains(&d.fract()) => format!("just under {}", metres(rng)),
        0 => format!("{about} {}", metres(rng)),
        1 if half => {
            format!(
                "{about} {} and a half metres",
                number_word(d.trunc() as u32)
            )
        }
        1 => format!("{about} {} metres", number_word(n)),
        2 if w == Writer::Precise => format!("{d:.1} metres"),
        2 | 3 => format!("{about} {} steps", number_word(steps)),
        4 => format!("{} or {} steps", number_word(steps), number_word(steps + 1)),
        5 => match n {
            0..=2 => "a couple of metres".into(),
            3 | 4 => "a few metres".into(),
            _ => "several metres".into(),
        },
        6 => format!("{about} {} feet", (d * 3.28).round().max(4.0) as u32),
        _ => format!("{about} {steps} steps"),
    }
}

/// "turn left", "bear towards your two o'clock", "turn 90 degrees to the right", "make a
/// sharp right", "turn left again", "bear left again" (`prev`: the turn before, when it went
/// the same way).
fn turn_clause(
    turn: Turn,
    angle: f32,
    start: bool,
    prev: Option<Turn>,
    w: Writer,
    rng: &mut ChaCha8Rng,
) -> Option<String> {
    match turn {
        Turn::Straight => None,
        Turn::Around => Some(pick(rng, &ph::TURN_AROUND).to_string()),
        Turn::Slight(s) => {
            let dir = side_word(s);
            if !start && prev == Some(Turn::Slight(s)) && rng.random_bool(0.5) {
                Some(fill(pick(rng, &ph::SLIGHT_AGAIN), &[("dir", dir)]))
            } else if (40.0..50.0).contains(&angle.abs()) && rng.random_bool(0.2) {
                // A bend of about 45 degrees is often given as its angle.
                Some(turn_by_degrees(45, dir, rng))
            } else if rng.random_bool(0.05) {
                let k = ((angle.abs() / 30.0).round() as u32).clamp(1, 2);
                let hour = if s == Side::Right { k } else { 12 - k };
                let clock = if rng.random_bool(0.5) {
                    number_word(hour)
                } else {
                    hour.to_string()
                };
                // The clock alone hides the side; the side is named with it.
                let c = fill(pick(rng, &ph::SLIGHT_CLOCK), &[("clock", &clock)]);
                Some(format!("{c}, slightly {dir}"))
            } else {
                Some(fill(pick(rng, &ph::SLIGHT_TURN), &[("dir", dir)]))
            }
        }
        Turn::Turn(s) => {
            let dir = side_word(s);
            if angle.abs() >= SHARP_TURN_DEG && rng.random_bool(0.5) {
                Some(fill(pick(rng, &ph::SHARP_TURN), &[("dir", dir)]))
            } else if !start && prev == Some(Turn::Turn(s)) && rng.random_bool(0.45) {
                Some(fill(pick(rng, &ph::TURN_AGAIN), &[("dir", dir)]))
            } else if w == Writer::Precise && rng.random_bool(0.3) {
                let deg = ((angle.abs() / 15.0).round() * 15.0) as u32;
                Some(turn_by_degrees(deg, dir, rng))
            } else {
                let bank = if start { ph::START_TURN } else { ph::TURN };
                Some(fill(pick(rng, &bank), &[("dir", dir)]))
            }
        }
    }
}

/// "turn 90 degrees to the left", "turn right about forty-five degrees": the angle as a number
/// or in words.
fn turn_by_degrees(deg: u32, dir: &str, rng: &mut ChaCha8Rng) -> String {
    let deg = if rng.random_bool(0.5) {
        number_word(deg)
    } else {
        deg.to_string()
    };
    fill(pick(rng, &ph::TURN_DEG), &[("dir", dir), ("deg", &deg)])
}

/// "walk forward about 3 metres", "stroll on slowly".
fn move_clause(len: f32, w: Writer, landmark: bool, rng: &mut ChaCha8Rng) -> String {
    if rng.random_bool(0.12) {
        return pick(rng, &ph::MOVE_WHOLE).to_string();
    }
    let verb = pick(rng, &ph::MOVE_VERB);
    // "walk on" takes no direction word ("walk on straight on").
    let dir = if verb.ends_with(" on") {
        ""
    } else {
        pick(rng, &ph::ONWARD)
    };
    let manner = if w == Writer::Terse || rng.random_bool(0.65) {
        ""
    } else {
        pick(rng, &ph::MANNER)
    };
    let mut s = verb.to_string();
    for part in [dir, manner] {
        if !part.is_empty() {
            s.push(' ');
            s.push_str(part);
        }
    }
    // A landmark on the leg often stands in for its distance.
    let p = if landmark { 0.5 } else { 1.0 } * w.distance();
    if rng.random_bool(p) {
        let d = distance_phrase(len, w, rng);
        // "walk on for three metres" reads worse than "walk on three metres".
        let join = if d.starts_with("a ")
            || d.starts_with("for ")
            || verb.ends_with(" on")
            || rng.random_bool(0.5)
        {
            " "
        } else {
            " for "
        };
        s.push_str(join);
        s.push_str(&d);
    }
    s
}

fn grounded(o: &SceneObject, role: Role, side: Option<Side>, idx: usize) -> GroundedObject {
    GroundedObject {
        object_id: o.id,
        class: o.class.name().to_string(),
        role,
        side,
        path_index: Some(idx as u32),
    }
}

pub(crate) fn check_path(path: &[[f32; 3]]) -> Result<()> {
    if path.len() < 2 {
        return Err(DataError::invalid(
            "path",
            format!("{} points", path.len()),
            "a fine-grained instruction needs a path of at least two points",
        ));
    }
    if let Some((i, p)) = path
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|v| v.is_finite()))
    {
        return Err(DataError::invalid(
            format!("path[{i}]"),
            format!("{p:?}"),
            "coordinates must be finite",
        ));
    }
    Ok(())
}

/// The landmark-sized object closest to the goal within `end_object_distance`, in sight.
fn end_object<'s>(
    cfg: &TemplateConfig,
    ctx: &PathContext<'s>,
    end: Vec2,
    walls: &[(Vec2, Vec2)],
) -> Option<&'s SceneObject> {
    let mut best: Option<((bool, f32), &SceneObject)> = None;
    for o in ctx.scene.objects.iter().filter(|o| is_landmark(o)) {
        let (lo, hi) = footprint(o);
        let d = rect_distance(end, lo, hi);
        if d > cfg.end_object_distance {
            continue;
        }
        let near = end.clamp(lo, hi);
        let aim = match (end - near).try_normalize() {
            Some(dir) if d > 0.15 => near + dir * 0.15,
            _ => end,
        };
        if !visible(ctx.navigable, walls, end, aim, cfg.sight_slack) {
            continue;
        }
        // A door stands by nearly every end point near a doorway; people name the furniture
        // there and the door only when nothing else is in reach.
        let door = o.class == vlnverse_env::SemanticClass::Door;
        let better = |(bdoor, bd): (bool, f32), bo: &SceneObject| {
            if door != bdoor {
                return bdoor;
            }
            d < bd - 1e-6 || (d <= bd + 1e-6 && o.id < bo.id)
        };
        if best.is_none_or(|(b, bo)| better(b, bo)) {
            best = Some(((door, d), o));
        }
    }
    best.map(|(_, o)| o)
}

/// A landmark as written: its phrase and side.
struct Named {
    text: String,
    side: Side,
    /// Several objects of one class named together ("the two chairs").
    group: bool,
    /// Two objects the path goes between, one on each side ("the sofa and the coffee table").
    between: bool,
    /// Named by a plural noun ("the stairs", "the curtains", a group, a pair): "are", no "a".
    plural: bool,
    /// Named by a mass noun ("the exercise equipment"): "is", but no "a" either.
    mass: bool,
}

/// "the second door on your left", "the last doorway on your right", "the door on your left"
/// (the only one on that side): a door taken out of a room, counted along the walk to it;
/// `None` past the fifth.
fn nth_door_np(n: door_order::NthDoor, rng: &mut ChaCha8Rng) -> Option<String> {
    let noun = if n.leaf { "door" } else { "doorway" };
    let side = side_word(n.side);
    let ord = if n.ordinal == 1 && n.last {
        None
    } else if n.last && rng.random_bool(0.5) {
        Some(if rng.random_bool(0.3) {
            pick(rng, &["farthest", "furthest"])
        } else {
            "last"
        })
    } else {
        let word = ordinal_word(n.ordinal as u32).filter(|_| n.ordinal <= 5)?;
        // People often type a door's count in digits ("the 2nd door").
        let digits = ["", "", "2nd", "3rd", "4th", "5th"][n.ordinal];
        Some(if n.ordinal >= 2 && rng.random_bool(0.15) {
            digits
        } else {
            word
        })
    };
    Some(match ord {
        Some(o) => format!("the {o} {noun} on your {side}"),
        None => format!("the {noun} on your {side}"),
    })
}

/// A room change as written; `nth` is the door taken, counted along the walk to it ("the
/// second door on your left"), said now and then when there is one.
fn room_change(
    ctx: &PathContext<'_>,
    from: RoomId,
    to: RoomId,
    at: Vec2,
    nth: Option<String>,
    naming: &RoomNaming,
    rng: &mut ChaCha8Rng,
) -> String {
    let scene = ctx.scene;
    let from_np = room_np(scene, from, naming, rng);
    // The room entered is named by its type (unless it already has a name), so a reader can
    // tell where they are.
    let mut to_np = scene
        .room(to)
        .map(|r| {
            naming
                .content(scene, to, true, rng)
                .unwrap_or_else(|| format!("the {}", naming.entered(to, r.kind)))
        })
        .unwrap_or_else(|| "the next room".into());
    let same = scene.room(from).map(|r| r.kind) == scene.room(to).map(|r| r.kind);
    let by_type = scene
        .room(to)
        .is_some_and(|r| to_np == format!("the {}", naming.entered(to, r.kind)));
    if same && by_type {
        to_np = to_np.replacen("the ", pick(rng, &["the next ", "the other "]), 1);
    }
    if scene.room(to).map(|r| r.kind) == Some(RoomType::Hallway) && rng.random_bool(0.3) {
        return pick(rng, &["go out into {room}", "walk out into {room}"])
            .replace("{room}", &to_np);
    }
    let outside = matches!(
        scene.room(to).map(|r| r.kind),
        Some(RoomType::Balcony | RoomType::Porch)
    );
    if outside && rng.random_bool(0.6) {
        // Out through the glass door people name ("step out through the sliding door onto
        // the balcony"), or just outside.
        let glass = door_between(scene, from, to, at)
            .filter(|d| d.kind.is_glass() && rng.random_bool(0.5))
            .and_then(|d| door_kind_noun(d.kind, rng));
        if let Some(noun) = glass {
            let door = format!("the {noun}");
            return fill(
                pick(rng, &ph::OUT_THROUGH_DOOR),
                &[("door", &door), ("room", &to_np)],
            );
        }
        return fill(pick(rng, &ph::GO_OUTSIDE), &[("room", &to_np)]);
    }
    // People count doors along a hallway whenever they can ("the second door on your left").
    if let Some(d) = nth.filter(|_| rng.random_bool(0.8)) {
        return fill(
            pick(rng, &ph::THROUGH_DOOR),
            &[("door", &d), ("room", &to_np)],
        );
    }
    let door = door_np(scene, from, to, at, rng);
    // Mostly just the room entered, as people say it ("go into the kitchen").
    match (rng.random_range(0..12), door) {
        (0 | 1, Some(d)) => fill(
            pick(rng, &ph::THROUGH_DOOR),
            &[("door", &d), ("room", &to_np)],
        ),
        (2, Some(d)) if rng.random_bool(0.5) => fill(
            pick(rng, &ph::LEAVE_BY_DOOR),
            &[("from", &from_np), ("door", &d), ("room", &to_np)],
        ),
        (3, _) => fill(
            pick(rng, &ph::ROOM_TO_ROOM),
            &[("from", &from_np), ("room", &to_np)],
        ),
        (4, _) => format!(
            "{} and {}",
            fill(pick(rng, &ph::LEAVE_ROOM), &[("room", &from_np)]),
            fill(pick(rng, &ph::ENTER_ROOM), &[("room", &to_np)])
        ),
        _ => fill(pick(rng, &ph::ENTER_ROOM), &[("room", &to_np)]),
    }
}

/// The room that walking on past the goal, straight ahead and in sight, leads into within 3 m
/// ("the kitchen"), when it is another room of another type than the goal's.
fn room_beyond(
    ctx: &PathContext<'_>,
    end: Vec2,
    heading: Vec2,
    walls: &[(Vec2, Vec2)],
    slack: f32,
) -> Option<String> {
    let here = ctx.scene.room_at(end.x, end.y)?;
    for k in 1..=4 {
        let q = end + heading * (0.75 * k as f32);
        let r = ctx.scene.room_at(q.x, q.y)?;
        if r.id == here.id {
            continue;
        }
        if r.kind == here.kind || !visible(ctx.navigable, walls, end, q, slack.min(0.2)) {
            return None;
        }
        return Some(format!("the {}", r.kind.words()));
    }
    None
}

/// Join clauses with varied connectors.
fn join(clauses: &[String], rng: &mut ChaCha8Rng) -> String {
    let mut s = String::new();
    for (i, c) in clauses.iter().enumerate() {
        if i > 0 {
            s.push_str(if i + 1 == clauses.len() || rng.random_bool(0.5) {
                pick(rng, &ph::AND)
            } else {
                ", "
            });
        }
        s.push_str(c);
    }
    s
}

fn sentence(s: &str) -> String {
    let s = s.trim();
    let s = capitalize(s);
    if s.ends_with(['.', '!', '?']) {
        s
    } else {
        format!("{s}.")
    }
}

/// The fine-grained instruction of `ctx.path` (see the module docs): an opening, then each leg
/// in turn, then the stop and the remarks people add after it.
pub(crate) fn fine(cfg: &TemplateConfig, ctx: &PathContext<'_>, seed: u64) -> Result<Instruction> {
    check_path(ctx.path)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6669_6e65);
    let writer = Writer::draw(&mut rng);
    let route = Route::new(cfg, ctx, writer);
    let mut draft = opening(&route, rng);
    for li in 0..route.legs.len() {
        leg_sentences(&route, li, &mut draft);
    }
    let stop = stop_sentence(&route, &mut draft);
    draft.sentences.push(sentence(&stop));
    closing_remarks(&route, &mut draft);
    Ok(Instruction {
        instruction_text: mend_joins(&draft.sentences.join(" ")),
        instruction_tokens: None,
        style: None,
        grounding: draft.grounding,
        sub_instructions: Vec::new(),
    })
}

/// What an instruction describes, fixed before its first sentence: the path on the floor and
/// its legs, the rooms and landmarks along it, the object at the goal, and how its writer names
/// things.
struct Route<'c, 's> {
    cfg: &'c TemplateConfig,
    ctx: &'c PathContext<'s>,
    writer: Writer,
    /// The path on the floor, and the heading of each segment.
    pts: Vec<Vec2>,
    headings: Vec<Vec2>,
    walls: Vec<(Vec2, Vec2)>,
    legs: Vec<Leg>,
    /// The goal, and the object there worth naming.
    end: Vec2,
    end_obj: Option<&'s SceneObject>,
    landmarks: Vec<Landmark>,
    /// The rooms the path runs through: (first path index in the room, room).
    rooms: Vec<(usize, RoomId)>,
    np_opts: NpOptions,
    /// The noun each room goes by.
    rooms_named: RoomNaming,
}

impl<'c, 's> Route<'c, 's> {
    fn new(cfg: &'c TemplateConfig, ctx: &'c PathContext<'s>, writer: Writer) -> Self {
        let pts = floor_points(ctx.path);
        let headings = segment_headings(&pts);
        let path3: Vec<Vec3> = ctx.path.iter().map(|p| Vec3::from(*p)).collect();
        let walls = wall_rects(ctx.scene);
        let legs = legs_of(&pts, direction_of_yaw(ctx.start_yaw), cfg);
        let end = pts[pts.len() - 1];
        let end_obj = end_object(cfg, ctx, end, &walls);
        let mut landmarks = ctx.graph.landmarks_along_path(
            ctx.scene,
            &path3,
            |a, b| visible(ctx.navigable, &walls, a, b, cfg.sight_slack),
            cfg.landmark_distance,
        );
        let rooms = rooms_along_path(ctx.scene, &path3);
        // The door walked through is "the door" of a room change, not a landmark passed.
        let walked: Vec<ObjectId> = rooms
            .windows(2)
            .filter_map(|w| {
                let at = pts[w[1].0.min(pts.len() - 1)];
                door_between(ctx.scene, w[0].1, w[1].1, at)
            })
            .flat_map(|d| d.leaves())
            .collect();
        landmarks.retain(|l| !walked.contains(&l.object));
        Route {
            cfg,
            ctx,
            writer,
            pts,
            headings,
            walls,
            legs,
            end,
            end_obj,
            landmarks,
            rooms,
            np_opts: writer.np(),
            rooms_named: RoomNaming::new(if writer == Writer::Precise { 0.15 } else { 0.4 }),
        }
    }

    /// The number of path points.
    fn n(&self) -> usize {
        self.pts.len()
    }

    fn chatty(&self) -> bool {
        self.writer == Writer::Chatty
    }

    /// The leg that path segment `seg` belongs to.
    fn leg_of(&self, seg: usize) -> usize {
        let seg = seg.min(self.n() - 2);
        self.legs
            .iter()
            .position(|l| l.first <= seg && seg <= l.last)
            .unwrap_or(self.legs.len() - 1)
    }

    /// The indices into [`Route::rooms`] of the rooms entered on leg `li`.
    fn rooms_entered_on(&self, li: usize) -> impl DoubleEndedIterator<Item = usize> + '_ {
        (1..self.rooms.len()).filter(move |&k| self.leg_of(self.rooms[k].0) == li)
    }

    /// How to describe an object seen from path point `index`.
    fn view(&self, index: usize) -> Viewpoint<'_> {
        Viewpoint {
            pts: &self.pts,
            headings: &self.headings,
            index,
        }
    }
}

/// The instruction as it is written: the sentences so far, the objects they ground, and what
/// carries over from one leg to the next.
struct Draft {
    rng: ChaCha8Rng,
    grounding: Vec<GroundedObject>,
    sentences: Vec<String>,
    /// A start-room prefix ("From the kitchen, ") waiting for the next sentence.
    prefix: String,
    /// Whether the writer numbers the steps, in which form, and the last number used.
    numbered: bool,
    number_form: &'static str,
    step_no: u32,
    /// A landmark held back from the previous leg to open this leg's turn ("once you've passed
    /// the sofa, turn left").
    after: Option<String>,
    /// How many more landmarks may be named (people name a handful per route, not every one
    /// they pass).
    budget: u32,
    /// The last leg walked to the end of its hallway ("walk to the end of the hallway"), so
    /// the next turn does not say so again.
    hall_end_said: bool,
}

/// The start of the instruction: now and then an opener, whether the steps are numbered, and
/// now and then the room the walk starts in.
fn opening(route: &Route<'_, '_>, mut rng: ChaCha8Rng) -> Draft {
    let writer = route.writer;
    let mut sentences: Vec<String> = Vec::new();
    if rng.random_bool(if route.chatty() { 0.15 } else { 0.02 }) {
        sentences.push(pick(&mut rng, &ph::OPEN).to_string());
    }
    // Now and then how many rooms the route goes through (three or more).
    let mut rooms: Vec<RoomId> = route.rooms.iter().map(|&(_, r)| r).collect();
    rooms.sort_unstable();
    rooms.dedup();
    if rooms.len() >= 3 && writer != Writer::Terse && rng.random_bool(0.02) {
        let num = number_word(rooms.len() as u32);
        sentences.push(fill(pick(&mut rng, &ph::ROUTE_ROOMS), &[("num", &num)]));
    }
    // Some writers number their steps ("First, ...", "Step two: ...").
    let numbered = matches!(writer, Writer::Plain | Writer::Precise) && rng.random_bool(0.06);
    let number_form = pick(&mut rng, &ph::NUMBERED);
    let mut prefix = String::new();
    let start_p = if writer == Writer::Terse { 0.05 } else { 0.2 };
    if let Some(&(_, r0)) = route.rooms.first() {
        if rng.random_bool(start_p) {
            let room = room_np(route.ctx.scene, r0, &route.rooms_named, &mut rng);
            let s = fill(pick(&mut rng, &ph::START_ROOM), &[("room", &room)]);
            if s.ends_with(',') {
                if !numbered {
                    prefix = format!("{s} ");
                }
            } else if !s.is_empty() {
                sentences.push(s);
            }
        }
    }
    Draft {
        rng,
        grounding: Vec::new(),
        sentences,
        prefix,
        numbered,
        number_form,
        step_no: 0,
        after: None,
        budget: 2,
        hall_end_said: false,
    }
}

/// The sentences of leg `li`: its landmarks, turn, movement and room changes, in one of several
/// sentence plans, then now and then a word on the room entered or an aside.
fn leg_sentences(route: &Route<'_, '_>, li: usize, draft: &mut Draft) {
    let leg = &route.legs[li];
    let Some(chosen) = leg_landmarks(route, li, draft) else {
        return;
    };
    let pair = between_pair(route, li).filter(|_| draft.rng.random_bool(0.15));
    let mut named = match pair {
        Some((a, b)) => vec![name_between(route, a, b, draft)],
        None => name_landmarks(route, &chosen, draft),
    };
    // With nothing else to name on the way, a room passed by its open doorway.
    let mut passed_room = None;
    if named.is_empty() && route.writer != Writer::Terse && draft.rng.random_bool(0.35) {
        if let Some(m) = room_passed(route, li) {
            passed_room = Some(m.text.clone());
            named.push(m);
        }
    }
    // Or, upstairs, the stairwell's railing beside the path.
    if named.is_empty() && route.writer != Writer::Terse {
        let beside = stairwell::railing_beside(
            route.ctx.scene,
            &route.pts,
            &route.headings,
            leg.first,
            leg.last,
        );
        if let Some((_, side)) = beside.filter(|_| draft.rng.random_bool(0.5)) {
            named.push(Named {
                text: stairwell::railing_np(&mut draft.rng),
                side,
                group: false,
                between: false,
                plural: false,
                mass: false,
            });
        }
    }
    // A slight bend on the way into another room or past a landmark often goes unsaid.
    let unsaid = matches!(leg.turn, Turn::Slight(_))
        && li > 0
        && draft.after.is_none()
        && (!named.is_empty() || route.rooms_entered_on(li).next().is_some())
        && draft.rng.random_bool(0.5);
    let prev = li.checked_sub(1).map(|k| route.legs[k].turn);
    let mut turn = if unsaid {
        None
    } else {
        turn_clause(
            leg.turn,
            leg.angle,
            li == 0,
            prev,
            route.writer,
            &mut draft.rng,
        )
    };
    if let (Some(t), Some(a)) = (turn.as_mut(), draft.after.take()) {
        *t = format!("{a}, {t}");
    } else if let Some(t) = turn.as_mut().filter(|_| li > 0) {
        if let Some(now) = immediate_turn(route, li, draft) {
            *t = now;
        } else if let Some(w) = turn_prefix(route, li, draft) {
            *t = format!("{w} {t}");
        }
    }
    hold_back_landmark(route, li, &mut named, draft);
    let changes = room_changes(route, li, &mut draft.rng);
    let entered_at = route.rooms_entered_on(li).next_back();
    let entered = entered_at.map(|k| route.rooms[k].1);
    let left = entered_at
        .and_then(|k| k.checked_sub(1))
        .map(|k| route.rooms[k].1);
    let mv = movement(
        route,
        leg,
        &changes,
        !named.is_empty(),
        &mut draft.hall_end_said,
        &mut draft.rng,
    );
    let mut out = leg_plan(
        route,
        li,
        turn,
        mv,
        &named,
        changes,
        entered,
        &mut draft.rng,
    );
    out.extend(room_size_remark(route, left, entered, &mut draft.rng));
    // A room passed by its doorway is not the way: now and then said so.
    if let Some(room) = passed_room.filter(|_| draft.rng.random_bool(0.6)) {
        out.push(fill(
            pick(&mut draft.rng, &ph::NOT_INTO),
            &[("room", &room)],
        ));
    }
    number_and_add(li, out, draft);
    if route.chatty() && draft.rng.random_bool(0.08) {
        draft
            .sentences
            .push(pick(&mut draft.rng, &ph::ASIDE).to_string());
    }
}

/// The landmarks named on leg `li`: left / right / ahead of the path, closest first, of
/// distinct classes, within the writer's limits, in path order. `None` when the leg is a slight
/// bend with nothing on it, left out as people often do.
fn leg_landmarks<'r>(
    route: &'r Route<'_, '_>,
    li: usize,
    draft: &mut Draft,
) -> Option<Vec<&'r Landmark>> {
    let scene = route.ctx.scene;
    let leg = &route.legs[li];
    let mut mine: Vec<&Landmark> = route
        .landmarks
        .iter()
        .filter(|l| route.leg_of(l.path_index) == li)
        .filter(|l| Some(l.object) != route.end_obj.map(|o| o.id))
        .filter(|l| !matches!(env_side(l.side), Side::Behind))
        .collect();
    mine.sort_by(|a, b| {
        a.distance
            .total_cmp(&b.distance)
            .then(a.object.cmp(&b.object))
    });
    // A slight bend with nothing on it and no room change is often not mentioned at all.
    let has_change = route.rooms_entered_on(li).next().is_some();
    if mine.is_empty()
        && !has_change
        && matches!(leg.turn, Turn::Slight(_))
        && li > 0
        && li + 1 < route.legs.len()
        && draft.rng.random_bool(0.8)
    {
        return None;
    }
    // People name a handful of landmarks per route, not every one they pass.
    let max_lm = match route.writer {
        Writer::Precise => route.cfg.max_landmarks_per_leg,
        _ => route.cfg.max_landmarks_per_leg.min(1),
    };
    let mut chosen: Vec<&Landmark> = Vec::new();
    for l in mine {
        if chosen.len() >= max_lm || draft.budget == 0 {
            break;
        }
        let Some(o) = scene.object(l.object) else {
            continue;
        };
        if chosen
            .iter()
            .any(|c| scene.object(c.object).is_some_and(|x| x.class == o.class))
        {
            continue;
        }
        // People leave out landmarks now and then, never the only one.
        if !chosen.is_empty() && draft.rng.random_bool(0.3) {
            continue;
        }
        chosen.push(l);
        draft.budget -= 1;
    }
    chosen.sort_by_key(|l| (l.path_index, l.object));
    Some(chosen)
}

/// The phrases of the chosen landmarks, grounded. A landmark passed beside others of its class
/// on the same side of the same leg is often named with them ("the two chairs on your left").
fn name_landmarks(route: &Route<'_, '_>, chosen: &[&Landmark], draft: &mut Draft) -> Vec<Named> {
    let mut named: Vec<Named> = Vec::new();
    // Objects already named in a group of their kind, not named again on their own.
    let mut in_group: Vec<ObjectId> = Vec::new();
    for l in chosen {
        let Some(o) = route.ctx.scene.object(l.object) else {
            continue;
        };
        if in_group.contains(&o.id) {
            continue;
        }
        let side = env_side(l.side);
        let mates = group_mates(route, l, o);
        if mates.is_empty() {
            if let Some(group) = kind_group(route, l, o, draft) {
                in_group.extend(group.1);
                named.push(group.0);
                continue;
            }
        }
        if !mates.is_empty() && draft.rng.random_bool(0.7) {
            let text = group_np(o, &mates, &mut draft.rng);
            draft
                .grounding
                .push(grounded(o, Role::Landmark, Some(side), l.path_index));
            for (m, ml) in &mates {
                draft
                    .grounding
                    .push(grounded(m, Role::Landmark, Some(side), ml.path_index));
            }
            named.push(Named {
                text,
                side,
                group: true,
                between: false,
                plural: true,
                mass: false,
            });
            continue;
        }
        let (text, extra) = match door_by_room(route, o, l.path_index, &mut draft.rng) {
            Some(t) => (t, Vec::new()),
            None => object_np(
                route.ctx,
                o,
                route.view(l.path_index),
                route.np_opts,
                MAX_REFERENCE_DISTANCE,
                &mut draft.rng,
            ),
        };
        // A shut door is worth saying so: it is not the way through.
        let text = if text.starts_with("the ")
            && is_closed_leaf(route.ctx.scene, o)
            && draft.rng.random_bool(0.7)
        {
            text.replacen("the ", "the closed ", 1)
        } else {
            text
        };
        draft
            .grounding
            .push(grounded(o, Role::Landmark, Some(side), l.path_index));
        draft.grounding.extend(extra);
        let plural = np_is_plural(o, &text);
        named.push(Named {
            text,
            side,
            group: false,
            between: false,
            plural,
            mass: false,
        });
    }
    named
}

/// Two landmarks a leg within one room goes between: one on each side, passed within a metre
/// of each other along the path, each within 1.5 m of it (the closest pair).
fn between_pair<'r>(route: &'r Route<'_, '_>, li: usize) -> Option<(&'r Landmark, &'r Landmark)> {
    // Only on a leg within one room: a clause after a room change would place them in the
    // room entered.
    if route.rooms_entered_on(li).next().is_some() {
        return None;
    }
    let end = route.end_obj.map(|o| o.id);
    let on_leg: Vec<&Landmark> = route
        .landmarks
        .iter()
        .filter(|l| route.leg_of(l.path_index) == li && Some(l.object) != end)
        .filter(|l| l.distance < 1.5)
        .collect();
    let class = |l: &Landmark| route.ctx.scene.object(l.object).map(|o| o.class);
    let mut best: Option<(f32, &Landmark, &Landmark)> = None;
    for a in on_leg.iter().filter(|l| env_side(l.side) == Side::Left) {
        for b in on_leg.iter().filter(|l| env_side(l.side) == Side::Right) {
            let gap = a.point.distance(b.point);
            let plural_twins = class(a) == class(b) && class(a).is_some_and(plural_class);
            if gap < 1.0 && !plural_twins && best.is_none_or(|(g, _, _)| gap < g) {
                best = Some((gap, a, b));
            }
        }
    }
    best.map(|(_, a, b)| (a, b))
}

/// "the sofa and the coffee table", or "the two armchairs" for two of one class: the pair a leg
/// goes between, grounded, in path order.
fn name_between(route: &Route<'_, '_>, a: &Landmark, b: &Landmark, draft: &mut Draft) -> Named {
    let objs: Vec<(&SceneObject, &Landmark)> = [a, b]
        .into_iter()
        .filter_map(|l| Some((route.ctx.scene.object(l.object)?, l)))
        .collect();
    let text = match objs.as_slice() {
        // (`between_pair` gives no two of a class named in the plural: "the two dumbbells"
        // would not say how many pairs.)
        [(x, _), (y, _)] if x.class == y.class => {
            format!("the two {}", plural(group_noun(&[x, y], &mut draft.rng)))
        }
        _ => {
            let texts: Vec<String> = objs
                .iter()
                .map(|(o, _)| {
                    // Plain names, the colour only where the class alone is not enough.
                    let twins = route.ctx.graph.objects_of_class(o.class).len() > 1;
                    let colour = if twins && !o.color.is_empty() {
                        format!("{} ", o.color)
                    } else {
                        String::new()
                    };
                    format!("the {colour}{}", object_names(o)[0])
                })
                .collect();
            texts.join(" and ")
        }
    };
    for (o, l) in &objs {
        let side = Some(env_side(l.side));
        draft
            .grounding
            .push(grounded(o, Role::Landmark, side, l.path_index));
    }
    draft.budget = draft.budget.saturating_sub(1);
    Named {
        text,
        side: Side::Left,
        group: false,
        between: true,
        plural: true,
        mass: false,
    }
}

/// A room the leg passes by without entering it ("the kitchen" on your left): an open doorway
/// of the room walked through, beside one of the leg's segments (within 1.2 m of it, passed
/// along its middle), in sight, into a room of another type the path never enters.
fn room_passed(route: &Route<'_, '_>, li: usize) -> Option<Named> {
    let scene = route.ctx.scene;
    let leg = &route.legs[li];
    let entered: Vec<RoomId> = route.rooms.iter().map(|&(_, r)| r).collect();
    for seg in leg.first..=leg.last.min(route.n() - 2) {
        let (a, b) = (route.pts[seg], route.pts[seg + 1]);
        let ab = b - a;
        let Some(here) = scene.room_at(a.x, a.y) else {
            continue;
        };
        for d in scene.doors.iter().filter(|d| !d.is_closed()) {
            let Some(&other) = d.rooms.iter().find(|&&r| r != here.id) else {
                continue;
            };
            if !d.rooms.contains(&here.id) || entered.contains(&other) {
                continue;
            }
            let Some(kind) = scene.room(other).map(|r| r.kind) else {
                continue;
            };
            let c = Vec2::new(d.position[0], d.position[2]);
            let t = (c - a).dot(ab) / ab.length_squared().max(1e-9);
            let q = a + ab * t.clamp(0.0, 1.0);
            if kind == here.kind || !(0.15..=0.85).contains(&t) || q.distance(c) > 1.2 {
                continue;
            }
            if !visible(route.ctx.navigable, &route.walls, q, c, 0.3) {
                continue;
            }
            let side = env_side(side_of_heading(q, route.headings[seg], c));
            if matches!(side, Side::Left | Side::Right) {
                return Some(Named {
                    text: format!("the {}", kind.words()),
                    side,
                    group: false,
                    between: false,
                    plural: false,
                    mass: false,
                });
            }
        }
    }
    None
}

/// A door leaf passed, named now and then by the room behind it as people do ("the bathroom
/// door", "the door to the kitchen"): the room of its doorway that the path is not in there.
fn door_by_room(
    route: &Route<'_, '_>,
    o: &SceneObject,
    path_index: usize,
    rng: &mut ChaCha8Rng,
) -> Option<String> {
    if o.class != vlnverse_env::SemanticClass::Door {
        return None;
    }
    let scene = route.ctx.scene;
    let door = scene.doors.iter().find(|d| d.leaves().any(|l| l == o.id))?;
    let p = route.pts[path_index.min(route.n() - 1)];
    let here = scene.room_at(p.x, p.y)?.id;
    if !door.rooms.contains(&here) || !rng.random_bool(0.5) {
        return None;
    }
    let other = door.rooms.iter().copied().find(|&r| r != here)?;
    let kind = scene.room(other)?.kind;
    if kind == scene.room(here)?.kind {
        return None;
    }
    let room = kind.words();
    // A glass leaf is named as a glass door: "the sliding door to the porch".
    let noun = match door.kind {
        DoorKind::Sliding => pick(rng, &ph::DOOR_SLIDING),
        DoorKind::French => pick(rng, &ph::DOOR_FRENCH_LEAF),
        DoorKind::Hinged | DoorKind::Arched => "door",
    };
    let bank = [
        "the {r} {n}",
        "the {n} to the {r}",
        "the {n} into the {r}",
        "the {n} that opens into the {r}",
    ];
    // "the bathroom door", but not "the porch sliding glass door": only a plain door takes the
    // first form.
    let bank = &bank[usize::from(noun != "door")..];
    Some(pick(rng, bank).replace("{r}", &room).replace("{n}", noun))
}

/// The other landmarks of `o`'s class passed on the same side of the same leg as `l` (at most
/// three, so a group is two to four objects); none when `l` is straight ahead.
fn group_mates<'r>(
    route: &'r Route<'_, '_>,
    l: &Landmark,
    o: &SceneObject,
) -> Vec<(&'r SceneObject, &'r Landmark)> {
    // A class named in the plural ("dumbbells", "shoes") has no plural to group by.
    if plural_class(o.class) {
        return Vec::new();
    }
    let end = route.end_obj.map(|e| e.id);
    let mates: Vec<_> = beside_on_leg(route, l)
        .into_iter()
        .filter(|(x, _)| Some(x.id) != end && x.class == o.class)
        .collect();
    if mates.len() > 3 {
        Vec::new()
    } else {
        mates
    }
}

/// The other landmarks passed on the same side of the same leg as `l`, with their objects, in
/// the route's order; none when `l` is not passed on a side.
fn beside_on_leg<'r>(
    route: &'r Route<'_, '_>,
    l: &Landmark,
) -> Vec<(&'r SceneObject, &'r Landmark)> {
    let side = env_side(l.side);
    if !matches!(side, Side::Left | Side::Right) {
        return Vec::new();
    }
    let li = route.leg_of(l.path_index);
    route
        .landmarks
        .iter()
        .filter(|m| m.object != l.object)
        .filter(|m| route.leg_of(m.path_index) == li && env_side(m.side) == side)
        .filter_map(|m| Some((route.ctx.scene.object(m.object)?, m)))
        .collect()
}

/// Now and then, `l` named with the landmarks of its kind but other classes passed on the same
/// side of the same leg ("the exercise equipment on your left": a treadmill and a bike;
/// `data/groups.toml`), grounded; the group and the objects in it. At most four objects, and
/// only when every landmark of the kind on that side of the leg is in it.
fn kind_group(
    route: &Route<'_, '_>,
    l: &Landmark,
    o: &SceneObject,
    draft: &mut Draft,
) -> Option<(Named, Vec<ObjectId>)> {
    let kind = groups::kind_of(o.class)?;
    let side = env_side(l.side);
    if !matches!(side, Side::Left | Side::Right) {
        return None;
    }
    let end = route.end_obj.map(|e| e.id);
    let mut members: Vec<(&SceneObject, &Landmark)> = vec![(o, l)];
    for (x, m) in beside_on_leg(route, l) {
        if groups::kind_of(x.class).is_some_and(|k| std::ptr::eq(k, kind)) {
            if Some(x.id) == end || members.iter().any(|(y, _)| y.id == x.id) {
                return None;
            }
            members.push((x, m));
        }
    }
    let mixed = members.iter().any(|(x, _)| x.class != o.class);
    if !mixed || members.len() > 4 || !draft.rng.random_bool(0.6) {
        return None;
    }
    let names: Vec<&str> = kind.names.iter().map(String::as_str).collect();
    let noun = pick(&mut draft.rng, &names);
    let text = if kind.mass {
        match draft.rng.random_range(0..3) {
            0 | 1 => format!("the {noun}"),
            _ => format!("some {noun}"),
        }
    } else {
        let n = number_word(members.len() as u32);
        match draft.rng.random_range(0..6) {
            0..=2 => format!("the {noun}"),
            3 => format!("{n} {noun}"),
            4 => format!("the {n} {noun}"),
            _ => format!("some {noun}"),
        }
    };
    for (x, m) in &members {
        draft
            .grounding
            .push(grounded(x, Role::Landmark, Some(side), m.path_index));
    }
    let named = Named {
        text,
        side,
        group: !kind.mass,
        between: false,
        plural: !kind.mass,
        mass: kind.mass,
    };
    Some((named, members.iter().map(|(x, _)| x.id).collect()))
}

/// The noun a group of objects of one class goes by: the first name of `objs[0]` that holds of
/// them all, now and then another such name ("couches"; "loveseats" only when each is a sofa
/// for two), one that takes a plain plural (not "chest of drawers", "bookshelves", "pair of
/// shoes").
fn group_noun(objs: &[&SceneObject], rng: &mut ChaCha8Rng) -> &'static str {
    let Some((first, rest)) = objs.split_first() else {
        return "things";
    };
    let shared: Vec<&'static str> = object_names(first)
        .into_iter()
        .filter(|n| rest.iter().all(|x| object_names(x).contains(n)))
        .collect();
    let default = shared
        .first()
        .copied()
        .unwrap_or(class_names(first.class)[0]);
    let plain: Vec<&'static str> = shared
        .iter()
        .copied()
        .filter(|n| *n != default && !n.contains(" of ") && !n.ends_with('s'))
        .collect();
    if !plain.is_empty() && rng.random_bool(0.45) {
        pick(rng, &plain)
    } else {
        default
    }
}

/// A group of objects of one class: "the two chairs", "the white chairs", "three stools",
/// "some chairs".
fn group_np(o: &SceneObject, mates: &[(&SceneObject, &Landmark)], rng: &mut ChaCha8Rng) -> String {
    let objs: Vec<&SceneObject> = std::iter::once(o)
        .chain(mates.iter().map(|m| m.0))
        .collect();
    let noun = plural(group_noun(&objs, rng));
    let colour = mates
        .iter()
        .all(|(m, _)| m.color == o.color)
        .then_some(o.color.as_str())
        .filter(|c| !c.is_empty() && rng.random_bool(0.4));
    let adj = colour.map(|c| format!("{c} ")).unwrap_or_default();
    let n = number_word(mates.len() as u32 + 1);
    match rng.random_range(0..7) {
        0 | 1 => format!("the {adj}{noun}"),
        2 | 3 => format!("{n} {adj}{noun}"),
        4 | 5 => format!("the {n} {adj}{noun}"),
        _ => format!("some {adj}{noun}"),
    }
}
/// Now and then hold back this leg's last lateral landmark to open the next leg's turn.
fn hold_back_landmark(route: &Route<'_, '_>, li: usize, named: &mut Vec<Named>, draft: &mut Draft) {
    let next_turns = route
        .legs
        .get(li + 1)
        .is_some_and(|l| matches!(l.turn, Turn::Turn(_) | Turn::Slight(_)));
    if next_turns
        && named.last().is_some_and(|m| m.side != Side::Ahead)
        && draft.rng.random_bool(0.25)
    {
        if let Some(m) = named.pop() {
            draft.after = Some(fill(
                pick(&mut draft.rng, &ph::AFTER_OBJ),
                &[("obj", &m.text)],
            ));
        }
    }
}

/// The room changes of leg `li`. Several rooms crossed on one leg are often said in one go
/// ("go through the bedroom into the office"); every room entered is still named by its type.
fn room_changes(route: &Route<'_, '_>, li: usize, rng: &mut ChaCha8Rng) -> Vec<String> {
    let ctx = route.ctx;
    let rooms = &route.rooms;
    let ks: Vec<usize> = route.rooms_entered_on(li).collect();
    // "through the bedroom into the bedroom" would not say which is which: rooms of one type
    // in a row are said one by one ("into the other bedroom").
    let kinds: Vec<Option<RoomType>> = ks
        .iter()
        .map(|&k| ctx.scene.room(rooms[k].1).map(|r| r.kind))
        .collect();
    let distinct = kinds.windows(2).all(|w| w[0] != w[1]);
    if ks.len() >= 2 && distinct && rng.random_bool(0.7) {
        let kind = |k: usize| {
            ctx.scene
                .room(rooms[k].1)
                .map(|r| format!("the {}", route.rooms_named.entered(r.id, r.kind)))
                .unwrap_or_else(|| "the next room".into())
        };
        let mids: Vec<String> = ks[..ks.len() - 1].iter().map(|&k| kind(k)).collect();
        let last = kind(ks[ks.len() - 1]);
        vec![fill(
            pick(rng, &ph::THROUGH_ROOMS),
            &[("mid", &mids.join(" and then ")), ("room", &last)],
        )]
    } else {
        ks.iter()
            .map(|&k| {
                let at = route.pts[rooms[k].0.min(route.n() - 1)];
                let (from, to) = (rooms[k - 1].1, rooms[k].1);
                let door = door_between(ctx.scene, from, to, at);
                let nth = door
                    .and_then(|d| door_order::nth_door(ctx.scene, &route.pts, rooms[k].0, from, d))
                    .and_then(|n| nth_door_np(n, rng))
                    .or_else(|| {
                        // Leaving the start room: its only door, or the nearest.
                        let d = door.filter(|d| k == 1 && !d.open_plan && rng.random_bool(0.5))?;
                        let near = openings::nearest_opening(ctx.scene, from, d, route.pts[0])?;
                        // Nearest to the start: only true while the walk is still there.
                        if near == Nearest::Nearest && li != 0 {
                            return None;
                        }
                        let noun = if d.leaf.is_some() { "door" } else { "doorway" };
                        Some(match near {
                            Nearest::Only => format!("the only {noun}"),
                            Nearest::Nearest => format!("the nearest {noun}"),
                        })
                    });
                room_change(ctx, from, to, at, nth, &route.rooms_named, rng)
            })
            .collect()
    }
}

/// The movement of a leg: along the hallway it starts in, through the room it stays in, or a
/// plain movement clause.
fn movement(
    route: &Route<'_, '_>,
    leg: &Leg,
    changes: &[String],
    landmark: bool,
    hall_end_said: &mut bool,
    rng: &mut ChaCha8Rng,
) -> String {
    let scene = route.ctx.scene;
    let here = route
        .rooms
        .iter()
        .rev()
        .find(|(s, _)| *s <= leg.first)
        .map(|&(_, r)| r);
    let here_kind = here.and_then(|r| scene.room(r)).map(|r| r.kind);
    let ends_hall = hall_end_at(route, leg.last + 1).is_some() && leg.last + 2 < route.n();
    match here {
        Some(r) if changes.is_empty() && ends_hall && rng.random_bool(0.5) => {
            *hall_end_said = true;
            let hall = room_np(scene, r, &route.rooms_named, rng);
            fill(pick(rng, &ph::TO_HALL_END), &[("room", &hall)])
        }
        Some(r)
            if changes.is_empty()
                && here_kind == Some(RoomType::Hallway)
                && rng.random_bool(0.35) =>
        {
            let hall = room_np(scene, r, &route.rooms_named, rng);
            fill(pick(rng, &ph::ALONG_HALL), &[("room", &hall)])
        }
        Some(r)
            if changes.is_empty()
                && scene.room(r).is_some_and(|room| {
                    let end = route.pts.get(leg.last + 1);
                    end.is_some_and(|&b| spatial::diagonal_across(room, route.pts[leg.first], b))
                })
                && rng.random_bool(0.3) =>
        {
            let room = room_np(scene, r, &route.rooms_named, rng);
            fill(pick(rng, &ph::DIAGONAL), &[("room", &room)])
        }
        Some(r) if changes.is_empty() && leg.len > 2.5 && rng.random_bool(0.12) => {
            let room = room_np(scene, r, &route.rooms_named, rng);
            fill(pick(rng, &ph::THROUGH_ROOM), &[("room", &room)])
        }
        _ => move_clause(leg.len, route.writer, landmark, rng),
    }
}

/// The hallway that ends just past path point `vertex` (walking on along the segment before
/// it leaves the hallway within 90 cm), where people say "at the end of the hallway".
fn hall_end_at(route: &Route<'_, '_>, vertex: usize) -> Option<RoomId> {
    let (p, h) = (
        *route.pts.get(vertex)?,
        *route.headings.get(vertex.checked_sub(1)?)?,
    );
    let scene = route.ctx.scene;
    let hall = scene
        .room_at(p.x, p.y)
        .filter(|r| r.kind == RoomType::Hallway)?;
    let q = p + h * 0.9;
    (scene.room_at(q.x, q.y).map(|r| r.id) != Some(hall.id)).then_some(hall.id)
}

/// Where a turn at path point `vertex` falls along the hallway it is in: the hallway, and the
/// metres of it behind and ahead along the heading walked there. `None` outside hallways.
fn hall_span(route: &Route<'_, '_>, vertex: usize) -> Option<(RoomId, f32, f32)> {
    let (p, h) = (
        *route.pts.get(vertex)?,
        *route.headings.get(vertex.checked_sub(1)?)?,
    );
    let hall = route
        .ctx
        .scene
        .room_at(p.x, p.y)
        .filter(|r| r.kind == RoomType::Hallway)?;
    let reach = |dir: Vec2| {
        (1..300)
            .map(|k| k as f32 * 0.1)
            .find(|&d| {
                let q = p + dir * d;
                !hall.contains(q.x, q.y)
            })
            .unwrap_or(30.0)
    };
    Some((hall.id, reach(-h), reach(h)))
}

/// What comes before the turn opening leg `li` when it holds: "at the end of the hallway,"
/// where the hallway ends there, "halfway down the hallway," or "just before the end of the
/// hallway," where a long hallway goes on, "immediately" where the leg before entered a room
/// within a step or so of the turn.
fn turn_prefix(route: &Route<'_, '_>, li: usize, draft: &mut Draft) -> Option<String> {
    let leg = &route.legs[li];
    let rng = &mut draft.rng;
    if let Some(hall) = hall_end_at(route, leg.first) {
        if !std::mem::take(&mut draft.hall_end_said) && rng.random_bool(0.5) {
            let hall = room_np(route.ctx.scene, hall, &route.rooms_named, rng);
            return Some(fill(pick(rng, &ph::HALL_END), &[("room", &hall)]));
        }
        return None;
    }
    if let Some((hall, back, ahead)) = hall_span(route, leg.first) {
        let length = back + ahead;
        let bank = if length < 4.0 || back < 1.5 {
            None
        } else if (0.35..=0.65).contains(&(back / length)) {
            Some(&ph::HALFWAY)
        } else if (0.9..=2.2).contains(&ahead) {
            Some(&ph::BEFORE_HALL_END)
        } else {
            None
        };
        if let Some(bank) = bank.filter(|_| rng.random_bool(0.4)) {
            let hall = room_np(route.ctx.scene, hall, &route.rooms_named, rng);
            return Some(fill(pick(rng, bank), &[("room", &hall)]));
        }
    }
    if entered_just_before(route, li) {
        if rng.random_bool(0.3) {
            return Some(pick(rng, &ph::AT_ONCE).to_string());
        }
        // Or by the room just left: "after leaving the bedroom, turn left".
        let left = left_just_before(route, li).filter(|_| rng.random_bool(0.15))?;
        let room = room_np(route.ctx.scene, left, &route.rooms_named, rng);
        return Some(fill(pick(rng, &ph::AFTER_LEAVING), &[("room", &room)]));
    }
    still_in(route, li)
        .filter(|_| rng.random_bool(0.2))
        .map(|r| {
            let room = room_np(route.ctx.scene, r, &route.rooms_named, rng);
            fill(pick(rng, &ph::STILL_IN), &[("room", &room)])
        })
}

/// The room left by the last room change of the leg before `li`, when that change is within a
/// step or so of the turn opening `li`.
fn left_just_before(route: &Route<'_, '_>, li: usize) -> Option<RoomId> {
    let turn_at = route.pts[route.legs[li].first];
    let k = route.rooms_entered_on(li - 1).next_back()?;
    let at = route.pts[route.rooms[k].0.min(route.n() - 1)];
    (k > 0 && at.distance(turn_at) < 1.2).then(|| route.rooms[k - 1].1)
}

/// The room a turn opening leg `li` is made in, when the leg before it was a long one (3 m or
/// more) walked all within that room: where "still in the hallway, turn left" helps.
fn still_in(route: &Route<'_, '_>, li: usize) -> Option<RoomId> {
    let prev = &route.legs[li - 1];
    if prev.len < 3.0 || route.rooms_entered_on(li - 1).next().is_some() {
        return None;
    }
    let room_at = |i: usize| {
        route
            .rooms
            .iter()
            .rev()
            .find(|(s, _)| *s <= i)
            .map(|&(_, r)| r)
    };
    let here = room_at(route.legs[li].first)?;
    (room_at(prev.first) == Some(here)).then_some(here)
}

/// Whether the leg before `li` entered a room within a step or so of the turn opening `li`.
fn entered_just_before(route: &Route<'_, '_>, li: usize) -> bool {
    let turn_at = route.pts[route.legs[li].first];
    route
        .rooms_entered_on(li - 1)
        .any(|k| route.pts[route.rooms[k].0.min(route.n() - 1)].distance(turn_at) < 1.2)
}

/// "take an immediate left", now and then, for a clear turn right after entering a room.
fn immediate_turn(route: &Route<'_, '_>, li: usize, draft: &mut Draft) -> Option<String> {
    let leg = &route.legs[li];
    let Turn::Turn(side) = leg.turn else {
        return None;
    };
    // A sharp turn or a second turn the same way has words of its own.
    let again = li > 0 && route.legs[li - 1].turn == leg.turn;
    if leg.angle.abs() >= SHARP_TURN_DEG || again {
        return None;
    }
    if hall_end_at(route, route.legs[li].first).is_some() || !entered_just_before(route, li) {
        return None;
    }
    let rng = &mut draft.rng;
    rng.random_bool(0.2)
        .then(|| fill(pick(rng, &ph::IMMEDIATE_TURN), &[("dir", side_word(side))]))
}

/// A landmark as a clause of a movement: "towards the lamp", "passing the sofa on your left".
fn landmark_clause(m: &Named, rng: &mut ChaCha8Rng) -> String {
    if m.between {
        fill(pick(rng, &ph::PASS_BETWEEN), &[("obj", &m.text)])
    } else if m.side == Side::Ahead {
        fill(pick(rng, &ph::TOWARDS), &[("obj", &m.text)])
    } else {
        let sp = fill(pick(rng, &ph::SIDE), &[("dir", side_word(m.side))]);
        fill(
            pick(rng, &ph::PASS_SIDE),
            &[("obj", &first_mention(m, rng)), ("side", &sp)],
        )
    }
}

/// A landmark as it is named when first met: now and then "a sofa" rather than "the sofa"
/// (one object, not a group or a pair).
fn first_mention(m: &Named, rng: &mut ChaCha8Rng) -> String {
    match m.text.strip_prefix("the ") {
        Some(rest) if !m.plural && !m.mass && rng.random_bool(0.15) => {
            format!("{} {rest}", indefinite_article(rest))
        }
        _ => m.text.clone(),
    }
}

/// A landmark as a sentence of its own: "you'll see the sofa on your right".
fn see_sentence(m: &Named, rng: &mut ChaCha8Rng) -> String {
    if m.between {
        fill(pick(rng, &ph::SEE_BETWEEN), &[("obj", &m.text)])
    } else if m.side == Side::Ahead {
        let verb = if m.plural { "are" } else { "is" };
        format!("{} {verb} ahead of you", m.text)
    } else {
        let sp = fill(pick(rng, &ph::SIDE), &[("dir", side_word(m.side))]);
        if m.group {
            return fill(
                pick(rng, &ph::SEE_SIDE_GROUP),
                &[("obj", &m.text), ("side", &sp)],
            );
        }
        // First met, a landmark is often "a sofa" ("there is a sofa on your left").
        if let Some(rest) = m
            .text
            .strip_prefix("the ")
            .filter(|_| !m.plural && !m.mass && rng.random_bool(0.25))
        {
            let obj = format!("{} {rest}", indefinite_article(rest));
            return fill(pick(rng, &ph::SEE_SIDE_A), &[("obj", &obj), ("side", &sp)]);
        }
        fill(pick(rng, &ph::SEE_SIDE), &[("obj", &m.text), ("side", &sp)])
    }
}

/// Mend a word said twice where two phrases meet: "keep going going by the sofa" and "proceed
/// straight straight towards" lose the second word; "the bean bag to sit on on the left" takes
/// a comma.
fn mend_joins(text: &str) -> String {
    let words: Vec<&str> = text.split(' ').collect();
    let mut out: Vec<String> = Vec::with_capacity(words.len());
    for w in words {
        match out.last_mut() {
            Some(prev) if prev.as_str() == w && matches!(w, "going" | "walking" | "straight") => {}
            Some(prev) if prev.as_str() == "on" && w == "on" => {
                prev.push(',');
                out.push(w.to_string());
            }
            _ => out.push(w.to_string()),
        }
    }
    out.join(" ")
}

/// Whether class `c` goes by a plural name ("dumbbells", "shoes", "lockers").
fn plural_class(c: vlnverse_env::SemanticClass) -> bool {
    is_plural_name(class_names(c)[0])
}

/// Whether a name is a plural noun: its head word ("stairs", "storage shelves") ends in a
/// plural "s"; in "X of Y" the head is X ("flight of stairs", "pair of shoes" are one thing).
fn is_plural_name(name: &str) -> bool {
    let head = match name.split_once(" of ") {
        Some((h, _)) => h,
        None => name,
    };
    let word = head.rsplit(' ').next().unwrap_or(head);
    // "glass" and "cactus" are one thing.
    word.ends_with('s') && !word.ends_with("ss") && !word.ends_with("us")
}

/// Whether a noun phrase naming `o` is plural: by the name of `o` it uses (the first to
/// appear, the longest of those that start there).
fn np_is_plural(o: &SceneObject, np: &str) -> bool {
    object_names(o)
        .iter()
        .filter_map(|n| np.find(n).map(|at| (at, std::cmp::Reverse(n.len()), *n)))
        .min()
        .is_some_and(|(_, _, n)| is_plural_name(n))
}

/// "a" or "an" before `words`, by the sound of its first letter.
fn indefinite_article(words: &str) -> &'static str {
    let vowel = words.starts_with(['a', 'e', 'i', 'o'])
        || (words.starts_with('u') && !words.starts_with("uni") && !words.starts_with("use"));
    if vowel {
        "an"
    } else {
        "a"
    }
}

/// "continue", "keep going", ...: walking on to the next landmark.
const GO_ON: &[&str] = &["continue", "keep going", "keep walking", "walk on"];

/// The sentences of a leg in one of several sentence plans, from its turn, movement, named
/// landmarks and room changes.
fn leg_plan(
    route: &Route<'_, '_>,
    li: usize,
    turn: Option<String>,
    mv: String,
    named: &[Named],
    changes: Vec<String>,
    entered: Option<RoomId>,
    rng: &mut ChaCha8Rng,
) -> Vec<String> {
    let writer = route.writer;
    // A bare turn with nothing on the way is often all people say of a leg.
    let bare = named.is_empty()
        && changes.is_empty()
        && turn.is_some()
        && li + 1 < route.legs.len()
        && (writer == Writer::Terse || rng.random_bool(if li >= 2 { 0.95 } else { 0.8 }));
    let lateral_first = named
        .first()
        .is_some_and(|m| m.side != Side::Ahead && !m.between);
    let ahead_last = named.last().is_some_and(|m| m.side == Side::Ahead);
    // A leg into another room is often only its turn and the room change ("Turn left into
    // the kitchen"), more so further along a long route.
    let plan = if bare {
        0
    } else if !changes.is_empty() && rng.random_bool(if li >= 1 { 0.6 } else { 0.4 }) {
        4
    } else {
        rng.random_range(0..6)
    };
    match plan {
        1 if lateral_first => plan_with_side(turn, mv, named, changes, rng),
        2 if ahead_last || !changes.is_empty() => {
            plan_until(turn, mv, named, changes, ahead_last, rng)
        }
        3 => plan_short(route, turn, mv, named, changes, entered, rng),
        4 if !changes.is_empty() => plan_room_first(turn, named, changes, rng),
        _ => plan_walk_on(turn, mv, named, changes, bare, rng),
    }
}

/// "With the sofa on your left, turn right and walk on."
fn plan_with_side(
    turn: Option<String>,
    mv: String,
    named: &[Named],
    changes: Vec<String>,
    rng: &mut ChaCha8Rng,
) -> Vec<String> {
    let m = &named[0];
    let sp = fill(pick(rng, &ph::SIDE), &[("dir", side_word(m.side))]);
    let head = fill(
        pick(rng, &ph::WITH_SIDE),
        &[("obj", &m.text), ("side", &sp)],
    );
    let mut cl: Vec<String> = turn.into_iter().collect();
    cl.push(mv);
    for m in &named[1..] {
        let c = landmark_clause(m, rng);
        let go = pick(rng, GO_ON);
        cl.push(format!("{go} {c}"));
    }
    cl.extend(changes);
    vec![format!("{head}, {}", join(&cl, rng))]
}

/// "Turn left and walk on until you reach the table." (or until the room change).
fn plan_until(
    turn: Option<String>,
    mv: String,
    named: &[Named],
    changes: Vec<String>,
    ahead_last: bool,
    rng: &mut ChaCha8Rng,
) -> Vec<String> {
    let mut cl: Vec<String> = turn.into_iter().collect();
    let mut m2 = mv;
    let k = named.len().saturating_sub(usize::from(ahead_last));
    for m in &named[..k] {
        m2 = format!("{m2}, {}", landmark_clause(m, rng));
    }
    if ahead_last {
        let m = &named[named.len() - 1];
        m2 = format!(
            "{m2} {}",
            fill(pick(rng, &ph::UNTIL_OBJ), &[("obj", &m.text)])
        );
        cl.push(m2);
        cl.extend(changes);
    } else {
        let mut ch = changes.into_iter();
        let first = ch.next().unwrap_or_default();
        cl.push(format!("{m2} until you {first}"));
        cl.extend(ch);
    }
    vec![join(&cl, rng)]
}

/// Short sentences: "Turn left. Walk on. You'll pass the sofa on your right." Now and then
/// the room entered ("You are now in the kitchen").
fn plan_short(
    route: &Route<'_, '_>,
    turn: Option<String>,
    mv: String,
    named: &[Named],
    changes: Vec<String>,
    entered: Option<RoomId>,
    rng: &mut ChaCha8Rng,
) -> Vec<String> {
    let mut out: Vec<String> = turn.into_iter().collect();
    out.push(mv);
    for m in named {
        out.push(see_sentence(m, rng));
    }
    out.extend(changes);
    if let Some(r) = entered.and_then(|r| route.ctx.scene.room(r)) {
        if rng.random_bool(0.25) {
            let room = format!("the {}", route.rooms_named.entered(r.id, r.kind));
            out.push(fill(pick(rng, &ph::NOW_IN), &[("room", &room)]));
        }
    }
    out
}

/// Room first: "Turn right, go through the doorway into the kitchen, passing ..."
fn plan_room_first(
    turn: Option<String>,
    named: &[Named],
    changes: Vec<String>,
    rng: &mut ChaCha8Rng,
) -> Vec<String> {
    let mut cl: Vec<String> = turn.into_iter().collect();
    let mut ch = changes.into_iter();
    let mut c0 = ch.next().unwrap_or_default();
    for m in named {
        c0 = format!("{c0}, {}", landmark_clause(m, rng));
    }
    cl.push(c0);
    cl.extend(ch);
    vec![join(&cl, rng)]
}

/// "Turn left and walk forward, passing the sofa on your left; continue past ..." (a bare
/// turn alone when `bare`).
fn plan_walk_on(
    turn: Option<String>,
    mv: String,
    named: &[Named],
    changes: Vec<String>,
    bare: bool,
    rng: &mut ChaCha8Rng,
) -> Vec<String> {
    let mut out = Vec::new();
    let mut cl: Vec<String> = turn.into_iter().collect();
    let mut m2 = mv;
    if let Some(m) = named.first() {
        let c = landmark_clause(m, rng);
        let sep = if m.side == Side::Ahead { " " } else { ", " };
        m2 = format!("{m2}{sep}{c}");
    }
    if !bare {
        cl.push(m2);
    }
    for m in named.iter().skip(1) {
        if rng.random_bool(0.5) {
            cl.push(format!("{} {}", pick(rng, GO_ON), landmark_clause(m, rng)));
        } else {
            out.push(join(&cl, rng));
            // A sentence of its own after the first landmark: "You will also pass ...".
            let also = !m.between && !m.group && m.side != Side::Ahead && rng.random_bool(0.3);
            cl = vec![if also {
                let sp = fill(pick(rng, &ph::SIDE), &[("dir", side_word(m.side))]);
                fill(
                    pick(rng, &ph::SEE_SIDE_ALSO),
                    &[("obj", &m.text), ("side", &sp)],
                )
            } else {
                see_sentence(m, rng)
            }];
        }
    }
    cl.extend(changes);
    out.push(join(&cl, rng));
    out
}

/// Now and then a word on the room just entered (from room `left`): its size, windows, floor,
/// doors or furniture.
fn room_size_remark(
    route: &Route<'_, '_>,
    left: Option<RoomId>,
    entered: Option<RoomId>,
    rng: &mut ChaCha8Rng,
) -> Option<String> {
    let r = entered.and_then(|r| route.ctx.scene.room(r))?;
    if route.writer == Writer::Terse || !rng.random_bool(0.2) {
        return None;
    }
    // A hallway by the rooms off it, now and then.
    if r.kind == RoomType::Hallway && rng.random_bool(0.4) {
        if let Some(list) = openings::rooms_off(route.ctx.scene, r.id) {
            return Some(fill(pick(rng, &ph::HALL_LEADS), &[("obj", &list)]));
        }
    }
    let area = r.area();
    let size = if r.kind == RoomType::Hallway {
        (area > 6.0).then_some(ph::HALL_LONG)
    } else if area < 8.0 {
        Some(ph::ROOM_SMALL)
    } else if area > 24.0 {
        Some(ph::ROOM_BIG)
    } else {
        None
    };
    // Its size, its windows or its floor, whichever the room has to say.
    let scene = route.ctx.scene;
    let windows = match room_facts::window_count(scene, r.id) {
        0 if r.kind != RoomType::Hallway => Some((ph::ROOM_NO_WINDOW, 0)),
        1 => Some((ph::ROOM_WINDOW, 1)),
        n @ 2..=4 => Some((ph::ROOM_WINDOWS, n)),
        _ => None,
    };
    let floor = room_facts::floor_kind(scene, r.id).map(|k| match k {
        FloorKind::Wood => ph::FLOOR_WOOD,
        FloorKind::Tile => ph::FLOOR_TILE,
        FloorKind::Carpet => ph::FLOOR_CARPET,
        FloorKind::Stone => ph::FLOOR_STONE,
        FloorKind::Concrete => ph::FLOOR_CONCRETE,
    });
    // Its openings, counted as doors, doorways or openings.
    let (openings, closed) = match openings::opening_count(scene, r.id) {
        Some(OpeningCount::Doors { total, closed }) => (Some((ph::ROOM_DOORS, total)), closed),
        Some(OpeningCount::Doorways(n)) => (Some((ph::ROOM_DOORWAYS, n)), 0),
        Some(OpeningCount::Openings(n)) => (Some((ph::ROOM_OPENINGS, n)), 0),
        None => (None, 0),
    };
    // A kind of furniture it holds several of.
    let several = furniture_counts(scene, r.id);
    // A hallway with no furniture in it.
    let empty = (r.kind == RoomType::Hallway
        && !scene
            .items()
            .any(|o| o.room == Some(r.id) && o.class.kind() == ClassKind::Furniture))
    .then_some(ph::HALL_EMPTY);
    // The floor underfoot changing from the last room's to this one's.
    let floors = left
        .and_then(|l| room_facts::floor_kind(scene, l))
        .zip(room_facts::floor_kind(scene, r.id))
        .filter(|(a, b)| a != b);
    let mut said: Vec<(Bank, usize)> = size
        .into_iter()
        .chain(floor)
        .chain(empty)
        .chain(floors.map(|_| ph::FLOOR_CHANGE))
        .map(|b| (b, 0))
        .collect();
    said.extend(windows);
    said.extend(openings);
    if !several.is_empty() {
        said.push((ph::ROOM_HAS, 0));
    }
    if said.is_empty() {
        return None;
    }
    let (bank, n) = said[rng.random_range(0..said.len())];
    if let Some((from, to)) = floors.filter(|_| bank == ph::FLOOR_CHANGE) {
        return Some(fill(
            pick(rng, &bank),
            &[("from", from.material()), ("to", to.material())],
        ));
    }
    if bank == ph::ROOM_HAS {
        let (o, count) = several[rng.random_range(0..several.len())];
        let obj = plural(count_noun(scene, r.id, o, rng));
        if count >= 5 && rng.random_bool(0.5) {
            return Some(fill(pick(rng, &ph::ROOM_HAS_MANY), &[("obj", &obj)]));
        }
        let num = number_word(count as u32);
        return Some(fill(pick(rng, &bank), &[("num", &num), ("obj", &obj)]));
    }
    let s = fill(pick(rng, &bank), &[("num", &number_word(n as u32))]);
    if bank == ph::ROOM_DOORS && closed > 0 {
        let shut = fill(
            pick(rng, &ph::ROOM_DOORS_CLOSED),
            &[("n", &number_word(closed as u32))],
        );
        return Some(format!("{}, {shut}.", s.trim_end_matches('.')));
    }
    Some(s)
}

/// The noun to count the objects of `o`'s class in room `room` by ([`group_noun`] of them all,
/// `o` first).
fn count_noun(scene: &Scene, room: RoomId, o: &SceneObject, rng: &mut ChaCha8Rng) -> &'static str {
    let mut mates: Vec<&SceneObject> = vec![o];
    mates.extend(
        scene
            .objects
            .iter()
            .filter(|x| x.class == o.class && x.room == Some(room) && x.id != o.id),
    );
    group_noun(&mates, rng)
}

/// The kinds of furniture room `room` holds two to six of, each as one of its objects and the
/// count, in class order. Doors, stairs, railings, curtains and windows are counted elsewhere
/// or not at all, and a class named in the plural ("shoes", "curtains") has no plural to say.
fn furniture_counts(scene: &Scene, room: RoomId) -> Vec<(&SceneObject, usize)> {
    // The head noun of a class ("chair" of "office chair"): a count of chairs must not leave
    // out the office chairs or rocking chairs beside them.
    let head = |c: C| class_names(c)[0].rsplit(' ').next().unwrap_or_default();
    let mut by_class: BTreeMap<C, (&SceneObject, usize)> = BTreeMap::new();
    let mut classes_by_head: BTreeMap<&str, BTreeSet<C>> = BTreeMap::new();
    for o in scene.items().filter(|o| o.room == Some(room)) {
        classes_by_head
            .entry(head(o.class))
            .or_default()
            .insert(o.class);
        let counted = o.class.kind() == ClassKind::Furniture
            && !matches!(o.class, C::Door | C::Stairs | C::Curtain | C::Rug);
        if counted {
            by_class.entry(o.class).or_insert((o, 0)).1 += 1;
        }
    }
    by_class
        .into_values()
        .filter(|(o, n)| {
            (2..=6).contains(n)
                && !plural_class(o.class)
                && classes_by_head[head(o.class)].len() == 1
        })
        .collect()
}

/// Add a leg's sentences: the first numbered ("Second, ...") or opened ("Next, ...") and
/// taking the start-room prefix if one is waiting.
fn number_and_add(li: usize, out: Vec<String>, draft: &mut Draft) {
    for (k, s) in out.into_iter().enumerate() {
        let mut s = s;
        let ord = if draft.numbered && k == 0 {
            draft.step_no += 1;
            ordinal_word(draft.step_no).filter(|_| draft.step_no <= 10)
        } else {
            None
        };
        if let Some(o) = ord {
            let form = if draft.number_form.contains("ly") && draft.step_no > 4 {
                "{ord}, "
            } else {
                draft.number_form
            };
            let head = fill(form, &[("ord", o), ("num", &number_word(draft.step_no))]);
            s = format!("{head}{s}");
        } else if k == 0 && li > 0 {
            s = format!("{}{s}", pick(&mut draft.rng, &ph::NEXT));
        }
        if k == 0 && !draft.prefix.is_empty() {
            s = format!("{}{}", std::mem::take(&mut draft.prefix), s);
        }
        draft.sentences.push(sentence(&s));
    }
}

/// The stop: at the object at the goal (and its side), or in the last room (and where in it),
/// or a plain stop; opened by a last-step word and taking a waiting start-room prefix.
fn stop_sentence(route: &Route<'_, '_>, draft: &mut Draft) -> String {
    let ctx = route.ctx;
    let (end, n) = (route.end, route.n());
    let rng = &mut draft.rng;
    let last_room = route.rooms.last().map(|&(_, r)| r);
    let end_heading = route
        .headings
        .last()
        .copied()
        .unwrap_or(Vec2::new(0.0, -1.0));
    let mut stop = if let Some(s) = stop_in_doorway(route, end_heading, rng) {
        s
    } else if let Some((x, y, sx, sy)) = end_between(route).filter(|_| rng.random_bool(0.4)) {
        draft
            .grounding
            .push(grounded(x, Role::Reference, Some(sx), n - 1));
        draft
            .grounding
            .push(grounded(y, Role::Reference, Some(sy), n - 1));
        let pair = format!("the {} and the {}", x.class.words(), y.class.words());
        fill(pick(rng, &ph::STOP_BETWEEN), &[("obj", &pair)])
    } else if let Some(o) = route.end_obj {
        let (lo, hi) = footprint(o);
        let side = Some(env_side(side_of_heading(end, end_heading, (lo + hi) * 0.5)));
        let (obj, extra) = object_np(
            ctx,
            o,
            route.view(n - 1),
            route.np_opts,
            MAX_REFERENCE_DISTANCE,
            rng,
        );
        draft.grounding.push(grounded(o, Role::Target, side, n - 1));
        draft.grounding.extend(extra);
        // A rug is stood on, or at its edge (within 30 cm of its outline, on it or off it).
        let rug = (o.class == vlnverse_env::SemanticClass::Rug)
            .then(|| rect_distance(end, lo, hi))
            .filter(|&d| d < 0.6 && rng.random_bool(0.6));
        let bank = if let Some(d) = rug {
            let inside = (end - lo).min(hi - end).min_element();
            if d <= 0.0 && inside > 0.3 {
                &ph::STOP_ON
            } else {
                &ph::STOP_EDGE
            }
        } else if spatial::at_foot_of(ctx.scene, end, o) && rng.random_bool(0.5) {
            &ph::STOP_FOOT
        } else {
            &ph::STOP_AT
        };
        let mut s = fill(pick(rng, bank), &[("obj", &obj)]);
        if let Some(sd @ (Side::Left | Side::Right)) = side.filter(|_| *bank != ph::STOP_ON) {
            if rng.random_bool(0.35) {
                let sp = fill(pick(rng, &ph::SIDE), &[("dir", side_word(sd))]);
                let plural = np_is_plural(o, &obj);
                s = match (rng.random_range(0..2), plural) {
                    (0, false) => format!("{s}, which is {sp}"),
                    (0, true) => format!("{s}, which are {sp}"),
                    (_, false) => format!("{s}. It will be {sp}"),
                    (_, true) => format!("{s}. They will be {sp}"),
                };
            }
        }
        s
    } else if route.rooms.len() <= 1 {
        // The walk never leaves its room: no "stop once you enter the kitchen".
        match end_place(ctx.scene, last_room, end, end_heading, rng) {
            Some(w) => format!("{} {w}", pick(rng, &["stop", "wait", "come to a stop"])),
            None => pick(rng, &ph::STOP).to_string(),
        }
    } else if let Some(r) = last_room {
        let room = room_np(ctx.scene, r, &route.rooms_named, rng);
        match end_place(ctx.scene, Some(r), end, end_heading, rng) {
            // "stop in the far left corner of the kitchen"; other places after a comma
            // ("wait just inside the kitchen, with the wall behind you").
            Some(w) if w.contains("corner") && rng.random_bool(0.6) => fill(
                pick(rng, &ph::STOP_ROOM_WHERE),
                &[("room", &room), ("where", &w)],
            ),
            Some(w) if rng.random_bool(0.6) => format!(
                "{}, {w}",
                fill(pick(rng, &ph::STOP_ROOM), &[("room", &room)])
            ),
            _ => fill(pick(rng, &ph::STOP_ROOM), &[("room", &room)]),
        }
    } else {
        pick(rng, &ph::STOP).to_string()
    };
    stop = format!("{}{stop}", pick(rng, &ph::LAST));
    if !draft.prefix.is_empty() {
        stop = format!("{}{stop}", draft.prefix);
    }
    stop
}

/// "stop in the doorway to the kitchen" when the goal is in an open doorway, the walker
/// facing through it (now and then).
fn stop_in_doorway(route: &Route<'_, '_>, heading: Vec2, rng: &mut ChaCha8Rng) -> Option<String> {
    let scene = route.ctx.scene;
    let d = spatial::doorway_at(scene, route.end)?;
    let room_at = |p: Vec2| scene.room_at(p.x, p.y).map(|r| r.id);
    let ahead = room_at(route.end + heading * 0.6)?;
    let behind = room_at(route.end - heading * 0.6)?;
    if ahead == behind || !d.rooms.contains(&ahead) || !d.rooms.contains(&behind) {
        return None;
    }
    if !rng.random_bool(0.5) {
        return None;
    }
    // Where the floor changes from one material to another, that is what people go by.
    let floor = |r: RoomId| room_facts::floor_kind(scene, r);
    if let (Some(from), Some(to)) = (floor(behind), floor(ahead)) {
        if from != to && rng.random_bool(0.3) {
            return Some(fill(
                pick(rng, &ph::STOP_FLOOR_CHANGE),
                &[("from", from.material()), ("to", to.material())],
            ));
        }
    }
    let kind = |r: RoomId| scene.room(r).map(|r| r.kind);
    let room = format!("the {}", kind(ahead)?.words());
    let mut from = format!("the {}", kind(behind)?.words());
    if from == room {
        from = format!("the other {}", kind(behind)?.words());
    }
    Some(fill(
        pick(rng, &ph::STOP_DOORWAY),
        &[("room", &room), ("from", &from)],
    ))
}

/// Two pieces of furniture in the goal's room that the goal lies between, each the only one of
/// its class in the home and within 2 m of the goal (in id order), with their sides seen from
/// the last point.
fn end_between<'s>(
    route: &Route<'_, 's>,
) -> Option<(&'s SceneObject, &'s SceneObject, Side, Side)> {
    let ctx = route.ctx;
    let view = route.view(route.n() - 1);
    let here = ctx.scene.room_at(route.end.x, route.end.y)?.id;
    let near: Vec<(&SceneObject, Side)> = unique_landmarks_in(ctx, here)
        .filter(|o| o.class.kind() == vlnverse_env::ClassKind::Furniture)
        .filter_map(|o| {
            let (side, d) = view.side_of(o)?;
            (d <= 2.0 && side != Side::Ahead).then_some((o, side))
        })
        .collect();
    for (i, &(x, sx)) in near.iter().enumerate() {
        for &(y, sy) in &near[i + 1..] {
            if sx != sy && spatial::point_between(route.end, x, y) {
                return Some((x, y, sx, sy));
            }
        }
    }
    None
}

/// Remarks people add after the stop, only where they hold: a big end object, the only one of
/// its class in the home, the room that walking on past the goal would lead into, how long the
/// walk takes; and now and then a closer.
fn closing_remarks(route: &Route<'_, '_>, draft: &mut Draft) {
    let (ctx, writer, chatty) = (route.ctx, route.writer, route.chatty());
    let rng = &mut draft.rng;
    let sentences = &mut draft.sentences;
    let end_heading = route
        .headings
        .last()
        .copied()
        .unwrap_or(Vec2::new(0.0, -1.0));
    if let Some(o) = route.end_obj {
        let (lo, hi) = footprint(o);
        let size = hi - lo;
        let big = size.x * size.y > 1.0 || o.bbox.size().y > 1.6;
        let in_home = |h: &Scene| h.objects.iter().filter(|x| x.class == o.class).count();
        let only = ctx.graph.objects_of_class(o.class).len() == 1
            && ctx.whole_home.is_none_or(|h| in_home(h) == 1)
            && !plural_class(o.class);
        let p = if chatty { 0.2 } else { 0.06 };
        // "It's hard to miss" says "it": not of the stairs.
        if big && !plural_class(o.class) && rng.random_bool(p) {
            sentences.push(pick(rng, &ph::CANT_MISS).to_string());
        } else if only && rng.random_bool(p) {
            let name = o.class.words();
            sentences.push(fill(pick(rng, &ph::ONLY_ONE), &[("name", &name)]));
        } else if rng.random_bool(p * 0.5) {
            // "There are three chairs in the room": the count of its class in its room.
            if let Some((n, names)) = same_class_in_room(ctx, o, &o.class.words()) {
                sentences.push(fill(
                    pick(rng, &ph::END_COUNT),
                    &[("n", &n), ("names", &names)],
                ));
            }
        }
    }
    if writer != Writer::Terse && rng.random_bool(0.25) {
        if let Some(room) = room_beyond(
            ctx,
            route.end,
            end_heading,
            &route.walls,
            route.cfg.sight_slack,
        ) {
            sentences.push(fill(pick(rng, &ph::OVERSHOOT), &[("room", &room)]));
        }
    }
    if matches!(writer, Writer::Chatty | Writer::Plain) && rng.random_bool(0.03) {
        let t = walk_time(&route.pts, rng);
        sentences.push(fill(pick(rng, &ph::WALK_TIME), &[("t", &t)]));
    }
    if rng.random_bool(if chatty { 0.15 } else { 0.02 }) {
        sentences.push(pick(rng, &ph::CLOSE).to_string());
    }
}

/// How long walking the path takes at an easy pace of about a metre a second ("about twenty
/// seconds", "a minute or two").
fn walk_time(pts: &[Vec2], rng: &mut ChaCha8Rng) -> String {
    let secs = pts.windows(2).map(|w| w[0].distance(w[1])).sum::<f32>();
    match secs {
        s if s < 8.0 => "a few seconds".to_string(),
        s if (25.0..35.0).contains(&s) => {
            pick(rng, &["about half a minute", "about thirty seconds"]).to_string()
        }
        s if s < 50.0 => format!(
            "{} {} seconds",
            pick(rng, &["about", "around"]),
            number_word(((s / 5.0).round() * 5.0) as u32)
        ),
        s if s < 75.0 => "about a minute".to_string(),
        _ => "a minute or two".to_string(),
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn a_word_said_twice_at_a_join_is_mended() {
        assert_eq!(
            mend_joins("Keep going going by the sofa and proceed straight straight towards it."),
            "Keep going by the sofa and proceed straight towards it."
        );
        assert_eq!(
            mend_joins("Pass the bean bag to sit on on the left."),
            "Pass the bean bag to sit on, on the left."
        );
        assert_eq!(mend_joins("Walk on. On the left"), "Walk on. On the left");
    }
    use super::*;

    #[test]
    fn plural_names_take_are_and_no_article() {
        for n in ["stairs", "curtains", "storage shelves", "pair of slippers"] {
            assert_eq!(is_plural_name(n), !n.starts_with("pair"), "{n}");
        }
        for n in [
            "flight of stairs",
            "box of tissues",
            "clothes airer",
            "glass",
            "staircase",
        ] {
            assert!(!is_plural_name(n), "{n}");
        }
        let stairs = SceneObject::from_parts(
            1,
            vlnverse_env::SemanticClass::Stairs,
            vlnverse_env::Pose::default(),
            Vec::new(),
        );
        assert!(np_is_plural(&stairs, "the wooden stairs along the wall"));
        assert!(!np_is_plural(&stairs, "the grey flight of stairs"));
        assert!(!np_is_plural(&stairs, "the long staircase"));
    }

    #[test]
    fn a_group_is_named_by_a_plain_plural_of_one_of_its_names() {
        use vlnverse_env::{Pose, SemanticClass as C};
        let mut by_synonym = 0;
        for &class in C::ALL {
            let o = SceneObject::from_parts(0, class, Pose::IDENTITY, Vec::new());
            let names = object_names(&o);
            for seed in 0..40 {
                let noun = plural(group_noun(&[&o], &mut ChaCha8Rng::seed_from_u64(seed)));
                let from = names.iter().find(|n| plural(n) == noun);
                let Some(n) = from else {
                    panic!("{class:?}: `{noun}` is the plural of none of {names:?}");
                };
                if *n != names[0] {
                    by_synonym += 1;
                    assert!(
                        !n.contains(" of ") && !n.ends_with('s'),
                        "{class:?}: `{noun}`"
                    );
                }
            }
        }
        assert!(by_synonym > 0, "never another name");
    }

    #[test]
    fn classes_named_in_the_plural_are_never_grouped_or_paired() {
        use vlnverse_env::SemanticClass as C;
        assert!(plural_class(C::Dumbbells) && plural_class(C::Lockers));
        assert!(!plural_class(C::Chair) && !plural_class(C::Sofa));
    }

    #[test]
    fn a_group_noun_holds_of_every_object_in_it() {
        use vlnverse_env::{Pose, SemanticClass as C};
        let sofa = |features: Vec<String>| {
            let mut o = SceneObject::from_parts(0, C::Sofa, Pose::IDENTITY, Vec::new());
            o.features = features;
            o
        };
        let (two, three) = (sofa(vec!["two seats".into()]), sofa(Vec::new()));
        let (mut mixed, mut pair) = (0, 0);
        for seed in 0..60 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            mixed += usize::from(group_noun(&[&two, &three], &mut rng) == "loveseat");
            pair += usize::from(group_noun(&[&two, &two.clone()], &mut rng) == "loveseat");
        }
        assert_eq!(mixed, 0, "a sofa for three counted among loveseats");
        assert!(pair > 0, "two sofas for two never called loveseats");
    }

    #[test]
    fn simplify_keeps_corners_and_drops_zigzags() {
        let pts: Vec<Vec2> = [
            (0.0, 0.0),
            (0.05, -1.0),
            (0.0, -2.0),
            (0.0, -5.0),
            (3.0, -5.0),
        ]
        .iter()
        .map(|&(x, z)| Vec2::new(x, z))
        .collect();
        assert_eq!(simplify(&pts, 0.3), vec![0, 3, 4]);
    }

    #[test]
    fn distances_come_in_several_forms() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let forms: std::collections::BTreeSet<String> = (0..200)
            .map(|_| distance_phrase(3.4, Writer::Plain, &mut rng))
            .collect();
        assert!(forms.len() > 12, "{forms:?}");
        assert!(forms.iter().any(|f| f.contains("three")));
        assert!(forms.iter().any(|f| f.contains("steps")));
        assert!(forms.iter().any(|f| f.contains("feet")));
    }

    #[test]
    fn one_metre_is_said_in_the_singular() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let forms: std::collections::BTreeSet<String> = (0..300)
            .map(|_| distance_phrase(1.3, Writer::Plain, &mut rng))
            .collect();
        assert!(forms
            .iter()
            .any(|f| f.ends_with("a metre") || f.ends_with("one metre")));
        for f in &forms {
            assert!(!f.contains(" 1 met") && !f.contains("one metres"), "{f}");
        }
    }
}
