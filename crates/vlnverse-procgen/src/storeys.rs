//! Homes on two floors (docs/storeys.md): a stair hall added beside the ground floor, an upper
//! floor plan over the same footprint with a landing above the hall, and the staircase between
//! them (the flight, the stairwell cut out of the upper floor and the ceiling below it, railings
//! round the stairwell). Everything here draws from streams of its own, so a home that stays on
//! one floor is generated exactly as before.

use crate::config::ProcgenConfig;
use crate::floorplan::{self, is_public, Opening, Plan, PlanRoom, Shared};
use crate::home::{box_part, Builder};
use crate::palette::{f, Finish};
use crate::rect::Rect;
use glam::Vec3;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{ObjectId, Pose, RoomId, RoomType, SceneObject, SemanticClass as C};

/// Stream of the two-storey decision and the upper floor plan.
const SALT: u64 = 0x5703_e75e_5eed_0003;
/// Streams of the upper floor's door leaves and decoration (the ground floor's use the seed).
pub(crate) const UPPER_SALT: u64 = 0x0bbe_7f10_0a7e_0004;

/// Depth of the landings at the foot and at the head of the flight (m, inside the walls).
const LANDING: f32 = 1.2;
/// Width of the walkway beside the flight (m, inside the walls).
const WALKWAY: f32 = 1.2;
/// How far `foot` and `head` lie from the first and last riser (m).
const APPROACH: f32 = 0.5;
/// Layout attempts for the upper floor.
const UPPER_ATTEMPTS: usize = 200;
/// Height and thickness of a railing (m).
const RAIL_H: f32 = 1.0;
const RAIL_T: f32 = 0.05;

const STAIR_FINISHES: &[Finish] = &[
    f("wooden", "wood", [0.5, 0.33, 0.18]),
    f("brown", "wood", [0.32, 0.2, 0.1]),
    f("white", "wood", [0.86, 0.86, 0.83]),
    f("grey", "stone", [0.55, 0.55, 0.56]),
];
const RAIL_FINISHES: &[Finish] = &[
    f("black", "metal", [0.06, 0.06, 0.06]),
    f("white", "wood", [0.9, 0.9, 0.88]),
    f("wooden", "wood", [0.45, 0.3, 0.16]),
];

/// Which side of the footprint the stair hall is added to.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Side {
    XMin,
    XMax,
    ZMin,
    ZMax,
}

impl Side {
    const ALL: [Side; 4] = [Side::XMin, Side::XMax, Side::ZMin, Side::ZMax];

    /// Whether the wall line of this side runs along z.
    fn along_z(self) -> bool {
        matches!(self, Side::XMin | Side::XMax)
    }

    /// The side's line and its extent along the side.
    fn line(self, f: &Rect) -> (f32, f32, f32) {
        match self {
            Side::XMin => (f.x0, f.z0, f.z1),
            Side::XMax => (f.x1, f.z0, f.z1),
            Side::ZMin => (f.z0, f.x0, f.x1),
            Side::ZMax => (f.z1, f.x0, f.x1),
        }
    }

    /// World `(x, z)` of a point `u` along the side and `v` outwards from its line.
    fn world(self, base: f32, u: f32, v: f32) -> (f32, f32) {
        match self {
            Side::XMin => (base - v, u),
            Side::XMax => (base + v, u),
            Side::ZMin => (u, base - v),
            Side::ZMax => (u, base + v),
        }
    }

    /// World rectangle of `u0..u1` along the side and `v0..v1` outwards.
    fn rect(self, base: f32, u: (f32, f32), v: (f32, f32)) -> Rect {
        let a = self.world(base, u.0, v.0);
        let b = self.world(base, u.1, v.1);
        Rect {
            x0: a.0.min(b.0),
            z0: a.1.min(b.1),
            x1: a.0.max(b.0),
            z1: a.1.max(b.1),
        }
    }
}

/// The staircase of a two-storey home, in world coordinates.
#[derive(Clone, Debug)]
pub(crate) struct Staircase {
    /// The flight's footprint, which is also the stairwell in the upper floor.
    pub flight: Rect,
    /// Whether the flight runs along z.
    pub along_z: bool,
    /// +1 when the flight rises towards larger x (or z), -1 otherwise.
    pub up: f32,
    /// The walkway side of the stairwell: the line where its railing stands and the sign
    /// pointing from the stairwell into the walkway (across the flight).
    pub inner_edge: (f32, f32),
    /// Foot and head points `(x, z)`.
    pub foot: (f32, f32),
    pub head: (f32, f32),
    /// Risers, their height, tread depth, width.
    pub steps: u32,
    pub rise: f32,
    pub run: f32,
    pub width: f32,
    /// Height of the upper floor.
    pub upper_height: f32,
}

/// The upper floor of a two-storey home: its plan (the landing last), the ground floor's
/// stair hall and the opening joining it to the house, and the staircase.
#[derive(Clone, Debug)]
pub(crate) struct UpperFloor {
    pub plan: Plan,
    pub ground_hall: PlanRoom,
    pub ground_opening: Opening,
    pub stairs: Staircase,
}

/// Whether the home of `seed` gets a second floor (no draw at all at share 0).
fn wants_two(cfg: &ProcgenConfig, rng: &mut ChaCha8Rng) -> bool {
    let share = cfg.floors.two_storey_share;
    share > 0.0 && rng.random::<f32>() < share
}

/// The upper floor of the home whose ground floor is `ground`, or None when the home stays on
/// one floor (not drawn, or no side of the footprint takes the stair hall, or no upper layout
/// was found).
pub(crate) fn plan_upper(cfg: &ProcgenConfig, seed: u64, ground: &Plan) -> Option<UpperFloor> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ SALT);
    if !wants_two(cfg, &mut rng) {
        return None;
    }
    let footprint = ground
        .rooms
        .iter()
        .fold(ground.rooms.first()?.rect, |a, r| Rect {
            x0: a.x0.min(r.rect.x0),
            z0: a.z0.min(r.rect.z0),
            x1: a.x1.max(r.rect.x1),
            z1: a.z1.max(r.rect.z1),
        });
    let (stairs, hall, shared_ground) = place_hall(cfg, ground, &footprint, &mut rng)?;
    let n = ground.rooms.len();
    let ground_hall = PlanRoom {
        kind: RoomType::Hallway,
        rect: hall,
        bare: true,
    };
    let mut with_hall = ground.rooms.clone();
    with_hall.push(ground_hall.clone());
    let shared = Shared {
        b: n,
        ..shared_ground
    };
    let ground_opening = floorplan::make_opening(cfg, &with_hall, &shared, &mut rng);
    let plan = upper_plan(cfg, &footprint, hall, &mut rng)?;
    Some(UpperFloor {
        plan,
        ground_hall,
        ground_opening,
        stairs,
    })
}

/// Risers, riser height and tread depth of a flight rising `height`.
fn flight_steps(cfg: &ProcgenConfig, height: f32) -> (u32, f32, f32) {
    let n = (height / cfg.floors.max_riser - 1e-4).ceil().max(2.0) as u32;
    (n, height / n as f32, cfg.floors.tread)
}

/// The stair hall: a side of the footprint where a public room can take a door to it, the hall
/// rectangle, the staircase and the shared wall (its `b` to be set to the hall's index).
fn place_hall(
    cfg: &ProcgenConfig,
    ground: &Plan,
    footprint: &Rect,
    rng: &mut ChaCha8Rng,
) -> Option<(Staircase, Rect, Shared)> {
    let t = cfg.walls.thickness;
    let fl = &cfg.floors;
    let upper_height = cfg.walls.height + fl.slab;
    let (steps, rise, run) = flight_steps(cfg, upper_height);
    let flight_len = (steps - 1) as f32 * run;
    let len = t + 2.0 * LANDING + flight_len;
    let depth = t + WALKWAY + fl.stair_width;
    let d = &cfg.doors;
    let min_len = d.width_min + 2.0 * (d.frame_width + d.corner_margin) + t;
    let mut sides = Side::ALL;
    sides.shuffle(rng);
    let rises_up = rng.random_bool(0.5);
    for side in sides {
        let (base, s0, s1) = side.line(footprint);
        if s1 - s0 < len {
            continue;
        }
        // Public rooms along this side, the widest edge first.
        let mut edges: Vec<(usize, f32, f32)> = ground
            .rooms
            .iter()
            .enumerate()
            .filter(|(_, r)| is_public(r.kind))
            .filter_map(|(i, r)| {
                let (line_a, line_b, a, b) = if side.along_z() {
                    (r.rect.x0, r.rect.x1, r.rect.z0, r.rect.z1)
                } else {
                    (r.rect.z0, r.rect.z1, r.rect.x0, r.rect.x1)
                };
                let on = [line_a, line_b].iter().any(|l| (l - base).abs() < 1e-3);
                on.then_some((i, a, b))
            })
            .collect();
        edges.sort_by(|p, q| (q.2 - q.1).total_cmp(&(p.2 - p.1)).then(p.0.cmp(&q.0)));
        for (room, a, b) in edges {
            let u0 = ((a + b) * 0.5 - len * 0.5).clamp(s0, s1 - len);
            let (lo, hi) = (a.max(u0), b.min(u0 + len));
            if hi - lo < min_len {
                continue;
            }
            let hall = side.rect(base, (u0, u0 + len), (0.0, depth));
            // Across (v): the walkway next to the house, the flight against the outer wall.
            let v_flight = (t * 0.5 + WALKWAY, depth - t * 0.5);
            // Along (u): landing, flight, landing.
            let (f0, f1) = (u0 + t * 0.5 + LANDING, u0 + t * 0.5 + LANDING + flight_len);
            let flight = side.rect(base, (f0, f1), v_flight);
            let v_mid = (v_flight.0 + v_flight.1) * 0.5;
            let (u_foot, u_head) = if rises_up {
                (f0 - APPROACH, f1 + APPROACH)
            } else {
                (f1 + APPROACH, f0 - APPROACH)
            };
            let foot = side.world(base, u_foot, v_mid);
            let head = side.world(base, u_head, v_mid);
            // u is z on the x sides and x on the z sides, running with the world axis.
            let world_up = if rises_up { 1.0 } else { -1.0 };
            // The walkway-side edge of the stairwell, and the direction into the walkway.
            let (edge_line, into_walkway) = {
                let (ex, ez) = side.world(base, 0.0, v_flight.0);
                let (ox, oz) = side.world(base, 0.0, v_flight.0 - 1.0);
                if side.along_z() {
                    (ex, (ox - ex).signum())
                } else {
                    (ez, (oz - ez).signum())
                }
            };
            let stairs = Staircase {
                flight,
                along_z: side.along_z(),
                up: world_up,
                inner_edge: (edge_line, into_walkway),
                foot,
                head,
                steps,
                rise,
                run,
                width: fl.stair_width,
                upper_height,
            };
            let shared = Shared {
                a: room,
                b: usize::MAX,
                along_z: side.along_z(),
                line: base,
                lo,
                hi,
            };
            return Some((stairs, hall, shared));
        }
    }
    None
}

/// The upper floor's room kinds and target areas: a bathroom, bedrooms, sometimes an office
/// and, in larger homes, a corridor; the areas fill the footprint.
fn upper_kinds(cfg: &ProcgenConfig, area: f32, rng: &mut ChaCha8Rng) -> Vec<(RoomType, f32)> {
    let n = ((area / 16.0).round() as usize).clamp(2, 6);
    let mut kinds = vec![RoomType::Bathroom, RoomType::Bedroom];
    if n >= 4 && rng.random_bool(0.6) {
        kinds.push(RoomType::Hallway);
    }
    if n >= 3 && rng.random_bool(0.5) {
        kinds.push(RoomType::Office);
    }
    while kinds.len() < n {
        let extra_bath = kinds.len() >= 5 && rng.random_bool(0.3);
        kinds.push(if extra_bath {
            RoomType::Bathroom
        } else {
            RoomType::Bedroom
        });
    }
    let range = |k: RoomType| {
        cfg.rooms
            .kinds
            .iter()
            .find(|c| c.kind == k)
            .map_or((8.0, 14.0), |c| (c.area_min, c.area_max))
    };
    let mut out: Vec<(RoomType, f32)> = kinds
        .into_iter()
        .map(|k| {
            let (lo, hi) = range(k);
            (k, rng.random_range(lo..=hi.max(lo)))
        })
        .collect();
    let total: f32 = out.iter().map(|r| r.1).sum();
    for r in &mut out {
        r.1 *= area / total.max(1e-6);
    }
    out
}

/// The upper floor plan over `footprint`, the landing (over the stair hall) last.
fn upper_plan(
    cfg: &ProcgenConfig,
    footprint: &Rect,
    hall: Rect,
    rng: &mut ChaCha8Rng,
) -> Option<Plan> {
    let rc = &cfg.rooms;
    let d = &cfg.doors;
    let min_len = d.width_min + 2.0 * (d.frame_width + d.corner_margin) + cfg.walls.thickness;
    for attempt in 0..UPPER_ATTEMPTS {
        let mut kinds = upper_kinds(cfg, footprint.area(), rng);
        if attempt % 2 == 1 {
            kinds.shuffle(rng);
        } else {
            // The corridor and the bathroom in the middle of the order, bedrooms outside.
            kinds.sort_by_key(|k| match k.0 {
                RoomType::Bedroom => 0u8,
                RoomType::Office => 1,
                RoomType::Hallway => 2,
                _ => 3,
            });
        }
        let mut rects = Vec::with_capacity(kinds.len() + 1);
        floorplan::split(*footprint, &kinds, rng, &mut rects);
        let ok = rects.iter().zip(&kinds).all(|(r, (k, _))| {
            let max_aspect = if *k == RoomType::Hallway {
                rc.max_aspect * 1.5
            } else {
                rc.max_aspect
            };
            r.w().min(r.d()) >= rc.min_side && r.aspect() <= max_aspect
        });
        if !ok {
            continue;
        }
        rects.push(hall);
        let mut rooms: Vec<PlanRoom> = rects
            .iter()
            .zip(&kinds)
            .map(|(&rect, &(kind, _))| PlanRoom {
                kind,
                rect,
                bare: false,
            })
            .collect();
        rooms.push(PlanRoom {
            kind: RoomType::Hallway,
            rect: hall,
            bare: true,
        });
        let mut shared = floorplan::shared_walls(&rects, min_len);
        shared.retain(|s| floorplan::may_join(rooms[s.a].kind, rooms[s.b].kind));
        let landing = rooms.len() - 1;
        if !shared.iter().any(|s| s.b == landing || s.a == landing) {
            continue;
        }
        if !floorplan::connected_without(&vec![false; rooms.len()], &shared) {
            continue;
        }
        let openings = floorplan::connect(cfg, &rooms, &shared, landing, rng)?;
        return Some(Plan { rooms, openings });
    }
    None
}

/// The flight: a solid block per tread, rising `rise` each, as one `stairs` object in
/// `room` (the ground floor's hall).
pub(crate) fn add_flight(
    s: &Staircase,
    room: RoomId,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) -> ObjectId {
    use rand::seq::IndexedRandom;
    let fin = *STAIR_FINISHES.choose(rng).unwrap_or(&STAIR_FINISHES[0]);
    let (cx, cz) = s.flight.center();
    let n_treads = s.steps - 1;
    let mut parts = Vec::with_capacity(n_treads as usize);
    for k in 1..=n_treads {
        // Tread k spans [start + (k-1) run, start + k run] along the rising direction.
        let along = -(n_treads as f32) * s.run * 0.5 + (k as f32 - 0.5) * s.run;
        let top = k as f32 * s.rise;
        let offset = along * s.up;
        let (center, size) = if s.along_z {
            (
                Vec3::new(0.0, top * 0.5, offset),
                Vec3::new(s.flight.w(), top, s.run),
            )
        } else {
            (
                Vec3::new(offset, top * 0.5, 0.0),
                Vec3::new(s.run, top, s.flight.d()),
            )
        };
        parts.push(box_part(center, size, fin.rgb));
    }
    let mass = s.flight.area() * 300.0;
    b.add_finish(
        C::Stairs,
        Some(room),
        Pose::from_yaw(Vec3::new(cx, 0.0, cz), 0.0),
        parts,
        fin,
        mass,
        None,
    )
}

/// Railings round the stairwell on the upper floor (level-local heights: the floor at 0):
/// along its walkway side and across its low end; the high end stays open where the flight
/// arrives. One `railing` object each: a top rail, posts and an infill panel.
pub(crate) fn add_railings(s: &Staircase, room: RoomId, rng: &mut ChaCha8Rng, b: &mut Builder) {
    use rand::seq::IndexedRandom;
    let fin = *RAIL_FINISHES.choose(rng).unwrap_or(&RAIL_FINISHES[0]);
    let (edge, into) = s.inner_edge;
    let line = edge + into * RAIL_T * 0.5;
    let f = s.flight;
    // (centre x, centre z, length, along_z)
    let mut runs: Vec<(f32, f32, f32, bool)> = Vec::with_capacity(2);
    if s.along_z {
        runs.push((line, (f.z0 + f.z1) * 0.5, f.d() + RAIL_T, true));
        // Low end: the foot side of the flight.
        let z = if s.up > 0.0 { f.z0 } else { f.z1 };
        let z = z - s.up * RAIL_T * 0.5;
        runs.push(((f.x0 + f.x1) * 0.5, z, f.w(), false));
    } else {
        runs.push(((f.x0 + f.x1) * 0.5, line, f.w() + RAIL_T, false));
        let x = if s.up > 0.0 { f.x0 } else { f.x1 };
        let x = x - s.up * RAIL_T * 0.5;
        runs.push((x, (f.z0 + f.z1) * 0.5, f.d(), true));
    }
    for (x, z, len, along_z) in runs {
        let sized = |l: f32, h: f32, t: f32| {
            if along_z {
                Vec3::new(t, h, l)
            } else {
                Vec3::new(l, h, t)
            }
        };
        let at = |u: f32, y: f32| {
            if along_z {
                Vec3::new(0.0, y, u)
            } else {
                Vec3::new(u, y, 0.0)
            }
        };
        let mut parts = vec![
            box_part(at(0.0, RAIL_H - 0.025), sized(len, 0.05, RAIL_T), fin.rgb),
            box_part(at(0.0, 0.5), sized(len - 0.1, 0.8, 0.02), fin.rgb),
        ];
        let posts = (len / 1.2).ceil().max(1.0) as usize;
        for p in 0..=posts {
            let u = -len * 0.5 + 0.025 + (len - 0.05) * p as f32 / posts as f32;
            parts.push(box_part(
                at(u, RAIL_H * 0.5),
                sized(0.05, RAIL_H, RAIL_T),
                fin.rgb,
            ));
        }
        b.add_finish(
            C::Railing,
            Some(room),
            Pose::from_yaw(Vec3::new(x, 0.0, z), 0.0),
            parts,
            fin,
            len * 8.0,
            None,
        );
    }
}

/// Cut the rectangle `hole` out of the one-box slabs of class `class` in room `room`: the slab
/// becomes up to four boxes round the hole.
pub(crate) fn cut_hole(objects: &mut [SceneObject], class: C, room: RoomId, hole: &Rect) {
    for o in objects
        .iter_mut()
        .filter(|o| o.class == class && o.room == Some(room))
    {
        let Some(part) = o.parts.first().cloned() else {
            continue;
        };
        let vlnverse_env::Shape::Cuboid { half_extents, .. } = part.shape else {
            continue;
        };
        let c = o.pose.translation() + Vec3::from_array(part.transform.position);
        let slab = Rect::centered(c.x, c.z, half_extents[0] * 2.0, half_extents[2] * 2.0);
        if !slab.overlaps(hole, 1e-4) {
            continue;
        }
        let h = Rect {
            x0: hole.x0.max(slab.x0),
            z0: hole.z0.max(slab.z0),
            x1: hole.x1.min(slab.x1),
            z1: hole.z1.min(slab.z1),
        };
        let pieces = [
            Rect { x1: h.x0, ..slab },
            Rect { x0: h.x1, ..slab },
            Rect {
                x0: h.x0,
                x1: h.x1,
                z1: h.z0,
                ..slab
            },
            Rect {
                x0: h.x0,
                x1: h.x1,
                z0: h.z1,
                ..slab
            },
        ];
        let mut parts: Vec<_> = pieces
            .iter()
            .filter(|r| r.w() > 1e-3 && r.d() > 1e-3)
            .map(|r| {
                let (px, pz) = r.center();
                box_part(
                    Vec3::new(px, c.y, pz) - o.pose.translation(),
                    Vec3::new(r.w(), half_extents[1] * 2.0, r.d()),
                    part.color,
                )
            })
            .collect();
        parts.extend(o.parts.iter().skip(1).cloned());
        o.parts = parts;
        o.bbox = o.compute_bbox();
    }
}

/// Append the objects of another builder (an upper floor built at height 0), lifted by `dy`,
/// their ids after the existing ones and their rooms after the first `room_offset`; returns the
/// id offset.
pub(crate) fn append_lifted(
    b: &mut Builder,
    upper: Vec<SceneObject>,
    dy: f32,
    room_offset: RoomId,
) -> ObjectId {
    let off = b.objects.len() as ObjectId;
    for mut o in upper {
        o.id += off;
        o.name = format!("{}_{}", o.class.name(), o.id);
        o.supported_by = o.supported_by.map(|s| s + off);
        o.room = o.room.map(|r| r + room_offset);
        o.pose.position[1] += dy;
        // From the lifted pose, as every other box is made (adding `dy` to the old box rounds
        // differently).
        o.bbox = o.compute_bbox();
        b.objects.push(o);
    }
    off
}
