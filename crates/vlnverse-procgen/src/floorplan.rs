//! Floorplans: room kinds and sizes drawn from the config, a house footprint cut into
//! rectangular rooms by recursive (guillotine) subdivision, and the openings between rooms
//! (a random spanning tree of the room adjacency graph plus some extra doors).

use crate::config::ProcgenConfig;
use crate::rect::Rect;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use vlnverse_env::RoomType;

/// Layout attempts before a home is given up (each attempt redraws the order and footprint).
const LAYOUT_ATTEMPTS: usize = 400;

/// A room of a plan: its kind and its rectangle between wall centre lines.
#[derive(Clone, Debug)]
pub(crate) struct PlanRoom {
    pub kind: RoomType,
    pub rect: Rect,
    /// Left without furniture and clutter (the stair hall of a two-storey home).
    pub bare: bool,
}

/// An opening in the wall line between two rooms.
#[derive(Clone, Debug)]
pub(crate) struct Opening {
    pub rooms: [usize; 2],
    /// True when the wall line runs along z (`x = line`), false when along x (`z = line`).
    pub along_z: bool,
    /// Coordinate of the wall centre line.
    pub line: f32,
    /// Centre of the opening along the wall.
    pub center: f32,
    /// Clear width.
    pub width: f32,
    /// Open-plan (no frame).
    pub open_plan: bool,
}

impl Opening {
    /// Width of the gap cut in the wall (clear width plus the frame posts).
    pub fn gap(&self, cfg: &ProcgenConfig) -> f32 {
        if self.open_plan {
            self.width
        } else {
            self.width + 2.0 * cfg.doors.frame_width
        }
    }

    /// World `(x, z)` of the opening's centre.
    pub fn position(&self) -> (f32, f32) {
        if self.along_z {
            (self.line, self.center)
        } else {
            (self.center, self.line)
        }
    }

    /// Unit normal of the wall, pointing from `rooms[0]` towards `rooms[1]`.
    pub fn normal(&self, plan: &Plan) -> [f32; 2] {
        let (ax, az) = plan.rooms[self.rooms[0]].rect.center();
        if self.along_z {
            [(self.line - ax).signum(), 0.0]
        } else {
            [0.0, (self.line - az).signum()]
        }
    }
}

/// A home's floorplan.
#[derive(Clone, Debug)]
pub(crate) struct Plan {
    pub rooms: Vec<PlanRoom>,
    pub openings: Vec<Opening>,
}

/// Whether rooms of kind `k` are shared by the household (living, kitchen, dining, halls).
pub(crate) fn is_public(k: RoomType) -> bool {
    matches!(
        k,
        RoomType::LivingRoom
            | RoomType::Kitchen
            | RoomType::DiningRoom
            | RoomType::Hallway
            | RoomType::EntranceHall
    )
}

/// Rooms that are only ever reached through one neighbour of the kinds given (a closet off a
/// bedroom or hallway, a balcony off the living room or a bedroom, a pantry off the kitchen, a
/// garage off the kitchen, a hall or the laundry room, a porch off a hall or the living room,
/// a sauna off a bathroom, the gym, the spa or a hallway, a wine cellar off the kitchen, the
/// dining room, the living room or a hall, a mud room off a hall, the kitchen or the laundry
/// room); `None` for other rooms.
fn leaf_of(k: RoomType) -> Option<&'static [RoomType]> {
    use RoomType as R;
    match k {
        R::Closet => Some(&[R::Bedroom, R::Hallway, R::EntranceHall]),
        R::Balcony => Some(&[R::LivingRoom, R::Bedroom]),
        R::Pantry => Some(&[R::Kitchen]),
        R::Garage => Some(&[R::Kitchen, R::Hallway, R::EntranceHall, R::LaundryRoom]),
        R::Porch => Some(&[R::EntranceHall, R::LivingRoom, R::Hallway]),
        R::Sauna => Some(&[R::Bathroom, R::Gym, R::Spa, R::Hallway]),
        R::WineCellar => Some(&[
            R::Kitchen,
            R::DiningRoom,
            R::LivingRoom,
            R::Hallway,
            R::EntranceHall,
        ]),
        R::MudRoom => Some(&[R::EntranceHall, R::Hallway, R::Kitchen, R::LaundryRoom]),
        _ => None,
    }
}

/// Whether a door may join rooms of kinds `a` and `b`.
pub(crate) fn may_join(a: RoomType, b: RoomType) -> bool {
    let ok = |x: RoomType, y: RoomType| leaf_of(x).is_none_or(|list| list.contains(&y));
    ok(a, b) && ok(b, a)
}

/// Zone rank: public rooms first, then the hallway, then private rooms, so that recursive
/// splitting keeps each zone together (a pantry goes with the kitchen it opens off).
fn zone(k: RoomType) -> u8 {
    match k {
        RoomType::LivingRoom
        | RoomType::Kitchen
        | RoomType::DiningRoom
        | RoomType::Pantry
        | RoomType::WineCellar => 0,
        RoomType::Hallway
        | RoomType::EntranceHall
        | RoomType::Garage
        | RoomType::Porch
        | RoomType::MudRoom
        | RoomType::Workshop => 1,
        _ => 2,
    }
}

/// Draw the room kinds and target areas of one home.
fn draw_rooms(cfg: &ProcgenConfig, rng: &mut ChaCha8Rng) -> Vec<(RoomType, f32)> {
    let rc = &cfg.rooms;
    let n = rng.random_range(rc.count_min..=rc.count_max);
    let mut counts = vec![0usize; rc.kinds.len()];
    let mut total = 0;
    for (i, k) in rc.kinds.iter().enumerate() {
        let take = k.count_min.min(n - total);
        counts[i] = take;
        total += take;
    }
    while total < n {
        let weights: Vec<f32> = rc
            .kinds
            .iter()
            .zip(&counts)
            .map(|(k, &c)| if c < k.count_max { k.weight } else { 0.0 })
            .collect();
        let Some(i) = weighted_index(&weights, rng) else {
            break;
        };
        counts[i] += 1;
        total += 1;
    }
    let scale = rng.random_range(rc.area_scale_min..=rc.area_scale_max);
    let mut rooms = Vec::with_capacity(n);
    for (k, &c) in rc.kinds.iter().zip(&counts) {
        for _ in 0..c {
            rooms.push((k.kind, rng.random_range(k.area_min..=k.area_max) * scale));
        }
    }
    rooms
}

/// Index drawn with probability proportional to `weights` (None if all are zero).
pub(crate) fn weighted_index(weights: &[f32], rng: &mut ChaCha8Rng) -> Option<usize> {
    let sum: f32 = weights.iter().sum();
    if sum <= 0.0 {
        return None;
    }
    let mut x = rng.random::<f32>() * sum;
    for (i, &w) in weights.iter().enumerate() {
        if w > 0.0 {
            if x < w {
                return Some(i);
            }
            x -= w;
        }
    }
    weights.iter().rposition(|&w| w > 0.0)
}

pub(crate) fn split(
    rect: Rect,
    rooms: &[(RoomType, f32)],
    rng: &mut ChaCha8Rng,
    out: &mut Vec<Rect>,
) {
    if rooms.len() == 1 {
        out.push(rect);
        return;
    }
    let total: f32 = rooms.iter().map(|r| r.1).sum();
    // Split point closest to half the area, sometimes the second closest for variety.
    let mut best = (f32::INFINITY, 1);
    let mut second = (f32::INFINITY, 1);
    let mut acc = 0.0;
    for k in 1..rooms.len() {
        acc += rooms[k - 1].1;
        let err = (acc - total * 0.5).abs();
        if err < best.0 {
            second = best;
            best = (err, k);
        } else if err < second.0 {
            second = (err, k);
        }
    }
    let k = if second.0.is_finite() && rng.random_bool(0.3) {
        second.1
    } else {
        best.1
    };
    let frac: f32 = rooms[..k].iter().map(|r| r.1).sum::<f32>() / total;
    let cut_x = if (rect.aspect()) < 1.15 {
        rng.random_bool(0.5)
    } else {
        rect.w() > rect.d()
    };
    let (a, b) = if cut_x {
        let x = rect.x0 + rect.w() * frac;
        (Rect { x1: x, ..rect }, Rect { x0: x, ..rect })
    } else {
        let z = rect.z0 + rect.d() * frac;
        (Rect { z1: z, ..rect }, Rect { z0: z, ..rect })
    };
    split(a, &rooms[..k], rng, out);
    split(b, &rooms[k..], rng, out);
}

/// A shared wall segment between two rooms.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Shared {
    pub a: usize,
    pub b: usize,
    pub along_z: bool,
    pub line: f32,
    pub lo: f32,
    pub hi: f32,
}

pub(crate) fn shared_walls(rects: &[Rect], min_len: f32) -> Vec<Shared> {
    const EPS: f32 = 1e-3;
    let mut out = Vec::new();
    for a in 0..rects.len() {
        for b in a + 1..rects.len() {
            let (ra, rb) = (rects[a], rects[b]);
            let mut push = |along_z: bool, line: f32, lo: f32, hi: f32| {
                if hi - lo >= min_len {
                    out.push(Shared {
                        a,
                        b,
                        along_z,
                        line,
                        lo,
                        hi,
                    });
                }
            };
            for (p, q) in [(ra.x1, rb.x0), (ra.x0, rb.x1)] {
                if (p - q).abs() < EPS {
                    push(true, p, ra.z0.max(rb.z0), ra.z1.min(rb.z1));
                }
            }
            for (p, q) in [(ra.z1, rb.z0), (ra.z0, rb.z1)] {
                if (p - q).abs() < EPS {
                    push(false, p, ra.x0.max(rb.x0), ra.x1.min(rb.x1));
                }
            }
        }
    }
    out
}

/// Whether a room lies along the house footprint's outline.
fn touches_outside(r: &Rect, footprint: &Rect) -> bool {
    const EPS: f32 = 1e-3;
    (r.x0 - footprint.x0).abs() < EPS
        || (r.x1 - footprint.x1).abs() < EPS
        || (r.z0 - footprint.z0).abs() < EPS
        || (r.z1 - footprint.z1).abs() < EPS
}

/// Whether the rooms not marked `skip` are connected by `edges`.
pub(crate) fn connected_without(skip: &[bool], edges: &[Shared]) -> bool {
    let Some(first) = skip.iter().position(|&s| !s) else {
        return true;
    };
    let mut seen = skip.to_vec();
    let mut stack = vec![first];
    seen[first] = true;
    while let Some(u) = stack.pop() {
        for e in edges {
            for (p, q) in [(e.a, e.b), (e.b, e.a)] {
                if p == u && !seen[q] {
                    seen[q] = true;
                    stack.push(q);
                }
            }
        }
    }
    seen.iter().all(|&s| s)
}

/// How much a room wants to be a hub of the door tree.
fn hub_weight(k: RoomType) -> f32 {
    match k {
        RoomType::Hallway => 6.0,
        RoomType::EntranceHall => 5.0,
        RoomType::LivingRoom => 4.0,
        RoomType::DiningRoom => 2.0,
        RoomType::Kitchen => 1.2,
        RoomType::Bathroom
        | RoomType::LaundryRoom
        | RoomType::Closet
        | RoomType::Balcony
        | RoomType::Pantry
        | RoomType::Garage
        | RoomType::Porch
        | RoomType::Sauna
        | RoomType::WineCellar
        | RoomType::MudRoom => 0.03,
        // Rooms kept for one use: reached, rarely walked through.
        RoomType::Bedroom
        | RoomType::Gym
        | RoomType::HomeTheater
        | RoomType::Library
        | RoomType::Spa
        | RoomType::Playroom
        | RoomType::Workshop => 0.15,
        _ => 0.5,
    }
}

fn try_layout(
    cfg: &ProcgenConfig,
    kinds: &[(RoomType, f32)],
    rng: &mut ChaCha8Rng,
) -> Option<(Vec<PlanRoom>, Vec<Shared>)> {
    let rc = &cfg.rooms;
    // Order: zones in sequence, shuffled inside each zone.
    let mut order: Vec<(RoomType, f32, u8, u32)> = kinds
        .iter()
        .map(|&(k, a)| (k, a, zone(k), rng.random::<u32>()))
        .collect();
    let flip = rng.random_bool(0.5);
    order.sort_by(|p, q| {
        let (zp, zq) = if flip { (2 - p.2, 2 - q.2) } else { (p.2, q.2) };
        (zp, p.3).cmp(&(zq, q.3))
    });
    let list: Vec<(RoomType, f32)> = order.iter().map(|o| (o.0, o.1)).collect();
    let total: f32 = list.iter().map(|r| r.1).sum();
    let aspect = rng.random_range(1.0f32..1.6);
    let w = (total * aspect).sqrt();
    let d = total / w;
    let (w, d) = if rng.random_bool(0.5) { (w, d) } else { (d, w) };
    let footprint = Rect::centered(0.0, 0.0, w, d);
    let mut rects = Vec::with_capacity(list.len());
    split(footprint, &list, rng, &mut rects);
    for (r, (k, _)) in rects.iter().zip(&list) {
        let max_aspect = if *k == RoomType::Hallway {
            rc.max_aspect * 1.5
        } else {
            rc.max_aspect
        };
        if r.w().min(r.d()) < rc.min_side || r.aspect() > max_aspect {
            return None;
        }
    }
    let d = &cfg.doors;
    let min_len = d.width_min + 2.0 * (d.frame_width + d.corner_margin) + cfg.walls.thickness;
    let mut shared = shared_walls(&rects, min_len);
    shared.retain(|s| may_join(list[s.a].0, list[s.b].0));
    // Leaf rooms (closets, balconies, pantries, garages) must hang off an allowed neighbour,
    // and the other rooms must connect without passing through one; a balcony, a garage and a
    // porch also need an outside wall.
    let inner: Vec<Shared> = shared
        .iter()
        .filter(|s| leaf_of(list[s.a].0).is_none() && leaf_of(list[s.b].0).is_none())
        .copied()
        .collect();
    let is_leaf: Vec<bool> = list.iter().map(|(k, _)| leaf_of(*k).is_some()).collect();
    if !connected_without(&is_leaf, &inner) {
        return None;
    }
    for (i, (k, _)) in list.iter().enumerate() {
        if is_leaf[i] && !shared.iter().any(|s| s.a == i || s.b == i) {
            return None;
        }
        let outdoor = matches!(k, RoomType::Balcony | RoomType::Garage | RoomType::Porch);
        if outdoor && !touches_outside(&rects[i], &footprint) {
            return None;
        }
    }
    let rooms = rects
        .into_iter()
        .zip(list)
        .map(|(rect, (kind, _))| PlanRoom {
            kind,
            rect,
            bare: false,
        })
        .collect();
    Some((rooms, shared))
}

pub(crate) fn make_opening(
    cfg: &ProcgenConfig,
    rooms: &[PlanRoom],
    s: &Shared,
    rng: &mut ChaCha8Rng,
) -> Opening {
    let d = &cfg.doors;
    let t = cfg.walls.thickness;
    let usable = (s.hi - s.lo) - t - 2.0 * d.corner_margin;
    let want_open = is_public(rooms[s.a].kind)
        && is_public(rooms[s.b].kind)
        && rng.random_bool(d.open_plan_probability as f64);
    let (width, gap, open_plan) = if want_open && usable >= d.open_plan_width_min {
        let w = rng.random_range(d.open_plan_width_min..=d.open_plan_width_max.min(usable));
        (w, w, true)
    } else {
        let max = d
            .width_max
            .min(usable - 2.0 * d.frame_width)
            .max(d.width_min);
        let w = rng.random_range(d.width_min..=max);
        (w, w + 2.0 * d.frame_width, false)
    };
    let lo = s.lo + t * 0.5 + d.corner_margin + gap * 0.5;
    let hi = s.hi - t * 0.5 - d.corner_margin - gap * 0.5;
    let center = if hi > lo {
        rng.random_range(lo..=hi)
    } else {
        (s.lo + s.hi) * 0.5
    };
    Opening {
        rooms: [s.a, s.b],
        along_z: s.along_z,
        line: s.line,
        center,
        width,
        open_plan,
    }
}

/// Generate the floorplan of one home; None when no valid layout was found.
pub(crate) fn generate(cfg: &ProcgenConfig, rng: &mut ChaCha8Rng) -> Option<Plan> {
    let mut kinds = draw_rooms(cfg, rng);
    let mut found = None;
    for attempt in 0..LAYOUT_ATTEMPTS {
        // Hard cases (many small rooms) get their areas redrawn now and then.
        if attempt > 0 && attempt % 50 == 0 {
            kinds = draw_rooms(cfg, rng);
            // Past half the attempts, at most one room that hangs off given neighbours: two or
            // three of them (a sauna, a pantry, a porch) rarely all find theirs in one plan.
            if attempt >= LAYOUT_ATTEMPTS / 2 {
                let mut leaves = 0;
                kinds.retain(|(k, _)| {
                    leaves += usize::from(leaf_of(*k).is_some());
                    leaf_of(*k).is_none() || leaves == 1
                });
            }
        }
        if let Some(x) = try_layout(cfg, &kinds, rng) {
            found = Some(x);
            break;
        }
    }
    let (rooms, shared) = found?;

    // Random spanning tree (Prim) from the living room, preferring hubs.
    let start = rooms
        .iter()
        .position(|r| r.kind == RoomType::LivingRoom)
        .or_else(|| rooms.iter().position(|r| leaf_of(r.kind).is_none()))
        .unwrap_or(0);
    let openings = connect(cfg, &rooms, &shared, start, rng)?;
    Some(Plan { rooms, openings })
}

/// The openings of a plan: a random spanning tree (Prim) of the shared walls from room `start`,
/// preferring hubs, then extra doors between rooms people walk through; None when the shared
/// walls do not connect every room.
pub(crate) fn connect(
    cfg: &ProcgenConfig,
    rooms: &[PlanRoom],
    shared: &[Shared],
    start: usize,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Opening>> {
    let n = rooms.len();
    let mut in_tree = vec![false; n];
    in_tree[start] = true;
    let mut used = vec![false; shared.len()];
    let mut openings = Vec::with_capacity(n + 2);
    for _ in 1..n {
        let weights: Vec<f32> = shared
            .iter()
            .map(|s| {
                if in_tree[s.a] != in_tree[s.b] {
                    let (u, v) = if in_tree[s.a] { (s.a, s.b) } else { (s.b, s.a) };
                    if leaf_of(rooms[u].kind).is_some() {
                        // Nothing is reached through a closet or a balcony.
                        return 0.0;
                    }
                    hub_weight(rooms[u].kind) * (0.5 + 0.5 * hub_weight(rooms[v].kind).min(1.0))
                } else {
                    0.0
                }
            })
            .collect();
        let i = weighted_index(&weights, rng)?;
        used[i] = true;
        in_tree[shared[i].a] = true;
        in_tree[shared[i].b] = true;
        openings.push(make_opening(cfg, rooms, &shared[i], rng));
    }
    for (i, s) in shared.iter().enumerate() {
        // Extra doors only between rooms people walk through, so private rooms keep their
        // walls for furniture.
        let walk_through = |k: RoomType| {
            matches!(
                k,
                RoomType::LivingRoom
                    | RoomType::Kitchen
                    | RoomType::DiningRoom
                    | RoomType::Hallway
                    | RoomType::EntranceHall
                    | RoomType::Office
            )
        };
        let private_only = !walk_through(rooms[s.a].kind) || !walk_through(rooms[s.b].kind);
        if !used[i] && !private_only && rng.random_bool(cfg.doors.extra_door_probability as f64) {
            openings.push(make_opening(cfg, rooms, s, rng));
        }
    }
    Some(openings)
}
