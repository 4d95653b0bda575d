//! Furniture that comes in sets, as people furnish rooms and name them when they give
//! directions ("walk between the two armchairs", "past the stools at the island", "the
//! bathroom with two sinks"): a matching armchair across the coffee table, a second sofa
//! facing the first, stools along a kitchen island or a bar, a double vanity, twin beds, wall sconces
//! either side of a headboard, two desks side by side.
//!
//! A set is placed last in its room, after the feature pieces, from an rng of its own seeded by
//! the home and room, beside the piece it belongs with (its anchor). Every object is added at
//! once and kept only if the whole set passes the placement checks of `furnish.rs` (inside the
//! room, clear of the doorways' keep-outs and of the other groups' footprints, the room's free
//! space still one island reaching every doorway with its least free share); otherwise nothing
//! of it stays. Nothing placed before moves, and `furniture.sets = 0` gives the homes of
//! before. The second of a pair is a copy of the first (same model, colour and features), as
//! people buy them.

use crate::furnish::{RoomState, WALL_GAP};
use crate::home::Builder;
use crate::models;
use crate::pieces;
use crate::rect::Rect;
use glam::Vec3;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f32::consts::{FRAC_PI_2, PI};
use vlnverse_env::{ClassKind, ObjectId, Pose, RoomType, SceneObject, SemanticClass as C};

/// Salt of the sets' rng, apart from the pieces' one.
const SALT: u64 = 0x5E75_0F5E_75C0_FFEE;
/// Least floor area (m²) of a living room that gets a second armchair, and of one that may get
/// a second sofa.
const ARMCHAIR_AREA: f32 = 14.0;
const SOFA_AREA: f32 = 22.0;
/// Least floor area (m²) of a bathroom with two sinks, and of a study with two desks.
const VANITY_AREA: f32 = 5.5;
const DESKS_AREA: f32 = 10.0;
/// Gaps (m) tried between two desks side by side.
const DESK_GAPS: [f32; 3] = [0.1, 0.4, 0.8];
/// Widest bed (m) that counts as a single bed for twin beds.
const SINGLE_BED: f32 = 1.3;
/// Height (m) above which an object hangs on the wall and takes no floor (mirrors, sconces).
const HUNG: f32 = 0.9;
/// Flat objects (rugs, mats) lie under furniture.
const FLAT: f32 = 0.03;

/// Place the room's sets, each with its chance times `furniture.sets`.
pub(crate) fn add_sets(st: &mut RoomState, kind: RoomType, rng: &ChaCha8Rng, b: &mut Builder) {
    let salt = u64::from(st.id).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ SALT;
    let mut own = ChaCha8Rng::seed_from_u64(crate::tones::stream_hash(rng) ^ salt);
    let rng = &mut own;
    let area = st.interior.area();
    let scale = st.cfg.furniture.sets;
    let chance = |rng: &mut ChaCha8Rng, p: f32| rng.random_bool((p * scale).clamp(0.0, 1.0) as f64);
    match kind {
        RoomType::LivingRoom => {
            if chance(rng, 0.7) && area >= ARMCHAIR_AREA {
                armchairs(st, rng, b);
            }
            if chance(rng, 0.3) && area >= SOFA_AREA {
                second_sofa(st, b);
            }
            if chance(rng, 0.9) {
                bar_stools(st, rng, b, C::Bar, &[-1.0]);
            }
        }
        RoomType::Kitchen if chance(rng, 0.9) => {
            bar_stools(st, rng, b, C::KitchenIsland, &[1.0, -1.0]);
        }
        RoomType::Bathroom if chance(rng, 0.6) && area >= VANITY_AREA => {
            double_vanity(st, rng, b);
        }
        RoomType::Bedroom => {
            if chance(rng, 0.5) {
                twin_beds(st, rng, b);
            }
            // Sconces are feature pieces: none where pieces are off.
            if chance(rng, 0.2) && st.cfg.furniture.pieces > 0.0 {
                bedside_sconces(st, rng, b);
            }
        }
        RoomType::DiningRoom | RoomType::HomeTheater | RoomType::Room | RoomType::WineCellar
            if chance(rng, 0.9) =>
        {
            bar_stools(st, rng, b, C::Bar, &[-1.0]);
        }
        RoomType::Office if chance(rng, 0.45) && area >= DESKS_AREA => {
            two_desks(st, rng, b);
        }
        _ => {}
    }
}

/// Indices of the room's objects of class `class` standing on the floor, in scene order.
fn of_class(st: &RoomState, b: &Builder, class: C) -> Vec<usize> {
    b.objects
        .iter()
        .enumerate()
        .filter(|(_, o)| o.room == Some(st.id) && o.class == class && o.supported_by.is_none())
        .map(|(i, _)| i)
        .collect()
}

/// Floor footprint of an object.
fn foot(o: &SceneObject) -> Rect {
    Rect {
        x0: o.bbox.min[0],
        z0: o.bbox.min[2],
        x1: o.bbox.max[0],
        z1: o.bbox.max[2],
    }
}

fn centre(o: &SceneObject) -> (f32, f32) {
    foot(o).center()
}

/// Where an object stands (its pose's origin, the middle of its model's footprint).
fn at(o: &SceneObject) -> (f32, f32) {
    (o.pose.position[0], o.pose.position[2])
}

/// Width (its own x) and depth (its own z) of an object turned by a multiple of 90 degrees.
fn size(o: &SceneObject) -> (f32, f32) {
    let r = foot(o);
    let q = ((o.pose.yaw() / FRAC_PI_2).round() as i32).rem_euclid(2);
    if q == 1 {
        (r.d(), r.w())
    } else {
        (r.w(), r.d())
    }
}

/// `o`'s position moved by `(x, z)` in its own frame, turned by `turn`.
fn beside(o: &SceneObject, x: f32, z: f32, turn: f32) -> Pose {
    let p = o.pose.transform_point(Vec3::new(x, 0.0, z));
    Pose::from_yaw(p, o.pose.yaw() + turn)
}

/// The offset `(x, z)` of point `p` in `o`'s frame.
fn local(o: &SceneObject, p: (f32, f32)) -> (f32, f32) {
    let pos = o.pose.translation();
    let v = o.pose.quat().inverse() * Vec3::new(p.0 - pos.x, 0.0, p.1 - pos.z);
    (v.x, v.z)
}

/// Add a copy of object `src` (same model, finish and features) at `pose`.
fn copy(b: &mut Builder, src: usize, pose: Pose) -> ObjectId {
    let mut o = b.objects[src].clone();
    let id = b.objects.len() as ObjectId + 1;
    o.id = id;
    o.name = format!("{}_{id}", o.class.name());
    o.pose = pose;
    o.supported_by = None;
    o.bbox = o.compute_bbox();
    b.objects.push(o);
    id
}

/// Keep the objects added from `start` on if they pass the placement checks together, else
/// remove them all; `anchors` are the objects the set belongs with, which it may touch.
fn settle(st: &mut RoomState, b: &mut Builder, start: usize, anchors: &[usize]) -> bool {
    if b.objects.len() == start {
        return false;
    }
    match fits(st, b, start, anchors) {
        Ok(()) => true,
        Err(why) => {
            let class = b.objects[start].class;
            tracing::debug!(room = st.id, ?class, why, "set left out");
            b.objects.truncate(start);
            false
        }
    }
}

/// Whether the objects from `start` on pass the placement checks; the reason when not.
fn fits(
    st: &mut RoomState,
    b: &Builder,
    start: usize,
    anchors: &[usize],
) -> Result<(), &'static str> {
    let gap = st.cfg.furniture.gap;
    let inside = st.interior.inset(WALL_GAP);
    let anchor_feet: Vec<Rect> = anchors.iter().map(|&a| foot(&b.objects[a])).collect();
    // The group footprints the anchors belong to: the set may stand in them.
    let own_group = |r: &Rect| {
        anchor_feet.iter().any(|a| {
            let (x, z) = a.center();
            r.distance(x, z) == 0.0
        })
    };
    let new = &b.objects[start..];
    let mut floor = Vec::new();
    for (k, n) in new.iter().enumerate() {
        let r = foot(n);
        if !inside.contains_rect(&r, 1e-3) {
            return Err("outside the room");
        }
        let (lo, hi) = (n.bbox.min[1], n.bbox.max[1]);
        let hung = lo > HUNG;
        for (i, o) in b.objects[..start].iter().enumerate() {
            if o.room != Some(st.id)
                || !matches!(o.class.kind(), ClassKind::Furniture | ClassKind::Small)
                || o.bbox.max[1] < FLAT
                || o.bbox.min[1] >= hi
                || o.bbox.max[1] <= lo
            {
                continue;
            }
            let margin = if anchors.contains(&i) || hung {
                0.0
            } else {
                -gap
            };
            if foot(o).overlaps(&r, margin) {
                return Err("on another object");
            }
        }
        for m in new[..k].iter().filter(|m| !hung && m.bbox.min[1] <= HUNG) {
            let vertical = m.bbox.min[1] < hi && lo < m.bbox.max[1];
            if vertical && foot(m).overlaps(&r, 0.0) {
                return Err("on its own set");
            }
        }
        if hung {
            continue;
        }
        if st.keepout.iter().any(|k| k.overlaps(&r, 0.0)) {
            return Err("in a doorway's keep-out");
        }
        if st
            .placed
            .iter()
            .any(|p| !own_group(p) && p.overlaps(&r, -gap))
        {
            return Err("in another group's footprint");
        }
        floor.push(r);
    }
    for r in &floor {
        st.grid.stamp(r, true);
    }
    if !st.grid.connected(&st.seeds) || st.grid.free_cells() < st.min_free {
        for r in &floor {
            st.grid.stamp(r, false);
        }
        return Err("closes the free space");
    }
    st.placed.extend(floor);
    Ok(())
}

/// The object of class `class` nearest to object `of`, within `reach` metres.
fn nearest(st: &RoomState, b: &Builder, class: C, of: usize, reach: f32) -> Option<usize> {
    let (x, z) = centre(&b.objects[of]);
    of_class(st, b, class)
        .into_iter()
        .map(|i| {
            let (tx, tz) = centre(&b.objects[i]);
            (i, (tx - x).hypot(tz - z))
        })
        .filter(|&(_, d)| d < reach)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// A living room's armchair gets its twin across the coffee table, the two facing each other;
/// a sofa with a coffee table and no armchair gets a matching pair, one at each end of the
/// table.
fn armchairs(st: &mut RoomState, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let start = b.objects.len();
    if let Some(&a) = of_class(st, b, C::Armchair).first() {
        let Some(t) = nearest(st, b, C::CoffeeTable, a, 2.5) else {
            return;
        };
        // Point-mirrored through the table's centre, turned round to face it.
        let (ax, az) = local(&b.objects[t], at(&b.objects[a]));
        let p = beside(&b.objects[t], -ax, -az, 0.0).translation();
        copy(b, a, Pose::from_yaw(p, b.objects[a].pose.yaw() + PI));
        settle(st, b, start, &[a, t]);
        return;
    }
    let Some(&s) = of_class(st, b, C::Sofa).first() else {
        return;
    };
    let Some(t) = nearest(st, b, C::CoffeeTable, s, 2.0) else {
        return;
    };
    let m = models::armchair(rng);
    let tw = size(&b.objects[t]).0;
    let x = tw * 0.5 + 0.45 + m.d * 0.5;
    // As `sofa_group` seats one: facing the table from its end.
    for (k, side) in [1.0f32, -1.0].into_iter().enumerate() {
        let pose = beside(&b.objects[t], side * x, 0.0, side * FRAC_PI_2);
        if k == 0 {
            b.add_model(&m, st.id, pose, None);
        } else {
            copy(b, start, pose);
        }
    }
    settle(st, b, start, &[s, t]);
}

/// A large living room's sofa gets a second one: facing it across the coffee table, or at
/// one end of the table (an L).
fn second_sofa(st: &mut RoomState, b: &mut Builder) {
    let Some(&s) = of_class(st, b, C::Sofa).first() else {
        return;
    };
    let Some(t) = nearest(st, b, C::CoffeeTable, s, 2.0) else {
        return;
    };
    let start = b.objects.len();
    let (sx, sz) = local(&b.objects[t], at(&b.objects[s]));
    let p = beside(&b.objects[t], -sx, -sz, 0.0).translation();
    copy(b, s, Pose::from_yaw(p, b.objects[s].pose.yaw() + PI));
    if settle(st, b, start, &[s, t]) {
        return;
    }
    // The L: the sofa's length runs along the table's end, clear of the first sofa's front.
    let (sw, sd) = size(&b.objects[s]);
    let tw = size(&b.objects[t]).0;
    let fx = local(&b.objects[s], at(&b.objects[t])).0;
    let z = -sd * 0.5 - 0.1 - sw * 0.5;
    for side in [1.0f32, -1.0] {
        let x = fx + side * (tw * 0.5 + 0.45 + sd * 0.5);
        let pose = beside(&b.objects[s], x, z, side * FRAC_PI_2);
        copy(b, s, pose);
        if settle(st, b, start, &[s, t]) {
            return;
        }
    }
}

/// Two to four matching stools tucked along a counter of class `class`, on the first of
/// `sides` (+1: its back, -1: its front) that has room: a kitchen island's back, away from its
/// doors, or its front; a bar's front, by its foot rail. A stool already in the room sets the
/// model.
fn bar_stools(st: &mut RoomState, rng: &mut ChaCha8Rng, b: &mut Builder, class: C, sides: &[f32]) {
    let Some(&island) = of_class(st, b, class).first() else {
        return;
    };
    let template = of_class(st, b, C::Stool).first().copied();
    // A new stool is the tallest of a few: a bar stool's seat is near the worktop.
    let model = (0..3)
        .map(|_| models::stool(rng))
        .max_by(|a, b| a.h.total_cmp(&b.h))
        .expect("three stools");
    let sw = template.map_or(model.w.max(model.d), |t| {
        let (w, d) = size(&b.objects[t]);
        w.max(d)
    });
    let (w, d) = size(&b.objects[island]);
    let most = (((w - 0.1) / (sw + 0.12)).floor() as usize).min(4);
    if most < 2 {
        return;
    }
    let want = rng.random_range(2..=most);
    for &side in sides {
        for n in (2..=want).rev() {
            let start = b.objects.len();
            let pitch = ((w - sw) / (n - 1) as f32).min(sw + 0.3);
            let z = side * (d * 0.5 + 0.03 + sw * 0.5);
            // Facing the island.
            let turn = if side > 0.0 { 0.0 } else { PI };
            for k in 0..n {
                let x = (k as f32 - (n - 1) as f32 * 0.5) * pitch;
                let pose = beside(&b.objects[island], x, z, turn);
                match template {
                    Some(t) => {
                        copy(b, t, pose);
                    }
                    None if k == 0 => {
                        b.add_model(&model, st.id, pose, None);
                    }
                    None => {
                        copy(b, start, pose);
                    }
                }
            }
            if settle(st, b, start, &[island]) {
                return;
            }
        }
    }
}

/// The mirror hanging over object `i` (a sink's), if any.
fn mirror_over(st: &RoomState, b: &Builder, i: usize) -> Option<usize> {
    let r = foot(&b.objects[i]).inset(-0.05);
    of_class(st, b, C::Mirror).into_iter().find(|&m| {
        let (x, z) = centre(&b.objects[m]);
        r.distance(x, z) == 0.0
    })
}

/// A double vanity: a second sink, the same as the first, beside it along the wall, with a
/// copy of its mirror above.
fn double_vanity(st: &mut RoomState, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let Some(&s) = of_class(st, b, C::Sink).first() else {
        return;
    };
    let mirror = mirror_over(st, b, s);
    let (w, _) = size(&b.objects[s]);
    let mut sides = [1.0f32, -1.0];
    sides.shuffle(rng);
    for side in sides {
        if twin_beside(st, b, s, mirror, side * (w + 0.02)) {
            return;
        }
    }
}

/// The room's nightstands beside bed `bed`, with their offset across the bed's frame.
fn stands_of(st: &RoomState, b: &Builder, bed: usize) -> Vec<(usize, f32)> {
    let (w, d) = size(&b.objects[bed]);
    of_class(st, b, C::Nightstand)
        .into_iter()
        .filter_map(|n| {
            let (x, z) = local(&b.objects[bed], at(&b.objects[n]));
            (x.abs() < w * 0.5 + 0.7 && x.abs() > w * 0.5 && z.abs() < d * 0.5).then_some((n, x))
        })
        .collect()
}

/// Twin beds: a single bed gets a second one the same, with a nightstand between the two (its
/// own, or a new one).
fn twin_beds(st: &mut RoomState, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let Some(&bed) = of_class(st, b, C::Bed).first() else {
        return;
    };
    let (w, d) = size(&b.objects[bed]);
    if w > SINGLE_BED {
        return;
    }
    let mut stands = stands_of(st, b, bed);
    stands.shuffle(rng);
    for (n, x) in stands {
        let start = b.objects.len();
        let nw = size(&b.objects[n]).0;
        let off = x.abs() + nw * 0.5 + 0.04 + w * 0.5;
        copy(b, bed, beside(&b.objects[bed], x.signum() * off, 0.0, 0.0));
        if settle(st, b, start, &[bed, n]) {
            return;
        }
    }
    let ns = models::nightstand(rng);
    let mut sides = [1.0f32, -1.0];
    sides.shuffle(rng);
    for side in sides {
        let start = b.objects.len();
        let nx = side * (w * 0.5 + 0.04 + ns.w * 0.5);
        let pose = beside(&b.objects[bed], nx, d * 0.5 - ns.d * 0.5, 0.0);
        b.add_model(&ns, st.id, pose, None);
        let bx = side * (w + 0.08 + ns.w);
        copy(b, bed, beside(&b.objects[bed], bx, 0.0, 0.0));
        if settle(st, b, start, &[bed]) {
            return;
        }
    }
}

/// A pair of wall sconces either side of a headboard, over the two nightstands of a bed that
/// stands with its head to a wall.
fn bedside_sconces(st: &mut RoomState, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let Some(&bed) = of_class(st, b, C::Bed).first() else {
        return;
    };
    let stands = stands_of(st, b, bed);
    let (left, right) = (
        stands.iter().find(|s| s.1 < 0.0),
        stands.iter().find(|s| s.1 > 0.0),
    );
    let (Some(&(l, lx)), Some(&(r, rx))) = (left, right) else {
        return;
    };
    let d = size(&b.objects[bed]).1;
    // The head is the bed's +Z end; it must be at a wall.
    let head = b.objects[bed]
        .pose
        .transform_point(Vec3::new(0.0, 0.0, d * 0.5 + 0.05));
    if st.interior.distance(head.x, head.z) == 0.0 {
        return;
    }
    let ceiling = st.cfg.walls.height - 0.03;
    let m = pieces::model(C::WallSconce, ceiling, rng);
    let start = b.objects.len();
    let z = d * 0.5 - m.d * 0.5;
    for (k, x) in [lx, rx].into_iter().enumerate() {
        let pose = beside(&b.objects[bed], x, z, 0.0);
        if k == 0 {
            b.add_model(&m, st.id, pose, None);
        } else {
            copy(b, start, pose);
        }
    }
    settle(st, b, start, &[bed, l, r]);
}

/// Two desks side by side in a study, each with its chair: copies of the first desk and its
/// chair beside them along the wall.
fn two_desks(st: &mut RoomState, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let Some(&desk) = of_class(st, b, C::Desk).first() else {
        return;
    };
    let chair =
        nearest(st, b, C::OfficeChair, desk, 1.2).or_else(|| nearest(st, b, C::Chair, desk, 1.2));
    let (w, _) = size(&b.objects[desk]);
    let mut sides = [1.0f32, -1.0];
    sides.shuffle(rng);
    // Side by side, or a step apart where something stands right beside the first.
    let spots = sides
        .into_iter()
        .flat_map(|side| DESK_GAPS.map(|g| side * (w + g)));
    for dx in spots {
        if twin_beside(st, b, desk, chair, dx) {
            return;
        }
    }
}

/// A copy of object `first` `dx` along its own width, with a copy of `with` (its mirror, its
/// chair) where `with` stands from it, kept if the set settles ([`settle`]).
fn twin_beside(
    st: &mut RoomState,
    b: &mut Builder,
    first: usize,
    with: Option<usize>,
    dx: f32,
) -> bool {
    let start = b.objects.len();
    copy(b, first, beside(&b.objects[first], dx, 0.0, 0.0));
    if let Some(c) = with {
        let (cx, cz) = local(&b.objects[first], at(&b.objects[c]));
        let p = beside(&b.objects[first], cx + dx, cz, 0.0);
        copy(
            b,
            c,
            Pose::from_yaw(p.translation(), b.objects[c].pose.yaw()),
        );
    }
    let anchors: Vec<usize> = std::iter::once(first).chain(with).collect();
    settle(st, b, start, &anchors)
}
