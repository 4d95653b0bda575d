//! Door leaves: a hinged slab with a handle on both faces in every doorway that has a frame
//! (open-plan openings have none).
//!
//! Some doors are closed (`doors.closed_probability`), but only where every room stays
//! reachable from every other through open doors and open-plan openings, so episodes can always
//! be routed round a closed door. A closed leaf fills its doorway. An open leaf stands swung
//! 90 degrees into one room by its hinge jamb: its inner handle stops at the edge of the clear
//! width, so the doorway keeps its full width and its clearance box stays empty. Of the four
//! ways a leaf can swing (two rooms, two hinge jambs), those whose footprint stays inside the
//! room, clear of the furniture, of the other doorways' clearance boxes and of the other leaves,
//! and cuts no part of the room off from its doorways, are kept, and the one leaving the most of
//! its room reachable is taken. A doorway where none fits gets a closed leaf if the rooms stay
//! connected, else no leaf.
//!
//! Leaves are added after the furniture and ceilings, before the decoration (which keeps clear
//! of them), from their own random stream: turning them off changes no furniture.

use crate::config::ProcgenConfig;
use crate::floorplan::{Opening, Plan};
use crate::home::{box_part, clearance_rect, Builder};
use crate::navgrid::NavGrid;
use crate::palette::{f, tone, Finish};
use crate::rect::Rect;
use glam::Vec3;
use rand::seq::{IndexedRandom, SliceRandom};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f32::consts::FRAC_PI_2;
use vlnverse_env::{
    Aabb, DoorState, ObjectId, Part, Pose, RoomId, SceneObject, SemanticClass as C, Shape,
};

/// Salt of the doors' random stream.
const SALT: u64 = 0xd004_1ea5_5eed_0002;
/// Leaf thickness (m).
const LEAF_T: f32 = 0.04;
/// How far a handle stands out of the leaf's face (m).
const HANDLE_OUT: f32 = 0.05;
/// Gap between the leaf and its frame (m).
const FRAME_GAP: f32 = 0.005;
/// Gap under the leaf, above the floor and any rug (m).
const UNDERCUT: f32 = 0.02;
/// Height of the handle above the floor (m).
const HANDLE_Y: f32 = 1.0;
/// Distance of the handle from the leaf's free edge (m).
const HANDLE_INSET: f32 = 0.07;
/// Share of a room's floor an open leaf must leave reachable, unless it keeps
/// [`KEEP_IN_FULL_ROOM`] of what was reachable before it.
const MIN_REACHABLE: f32 = 0.2;
/// Part of a furnished room's reachable floor an open leaf must leave.
const KEEP_IN_FULL_ROOM: f32 = 0.8;
/// Cell of the in-room reachability check (m): the occupancy map's.
const CHECK_CELL: f32 = 0.05;
/// Radius of the in-room reachability check (m): the agent's radius plus one map cell.
const CHECK_RADIUS: f32 = 0.35;
/// Objects lower than this stand under the agent's height band (rugs, skirting; m).
const FLOOR_BAND: f32 = 0.05;
/// Chamfer of the slab's top edges (m).
const BEVEL: f32 = 0.006;
/// Kept between an open leaf and furniture, walls and other leaves (m).
const MARGIN: f32 = 0.02;

const FINISHES: &[Finish] = &[
    f("white", "wood", [0.86, 0.86, 0.83]),
    f("white", "wood", [0.92, 0.91, 0.88]),
    f("wooden", "wood", [0.5, 0.32, 0.17]),
    f("brown", "wood", [0.3, 0.18, 0.09]),
    f("grey", "wood", [0.45, 0.46, 0.48]),
    f("beige", "wood", [0.74, 0.64, 0.48]),
    f("black", "wood", [0.06, 0.06, 0.06]),
];

/// What a doorway got: its state and its leaf (both `None` for open-plan openings and doorways
/// without a leaf), one entry per opening of the plan.
pub(crate) type DoorLeaf = (Option<DoorState>, Option<ObjectId>);

/// Whether every room reaches room 0 through the openings not in `closed`.
fn connected(plan: &Plan, closed: &[bool]) -> bool {
    let n = plan.rooms.len();
    if n == 0 {
        return true;
    }
    let mut seen = vec![false; n];
    let mut stack = vec![0usize];
    seen[0] = true;
    while let Some(r) = stack.pop() {
        for (o, _) in plan
            .openings
            .iter()
            .zip(closed)
            .filter(|(o, &c)| !c && o.rooms.contains(&r))
        {
            let other = if o.rooms[0] == r {
                o.rooms[1]
            } else {
                o.rooms[0]
            };
            if !seen[other] {
                seen[other] = true;
                stack.push(other);
            }
        }
    }
    seen.iter().all(|&s| s)
}

/// A leaf of clear width `lw` and height `lh` in its own frame: local x across the leaf, local z
/// through it; the handles sit `HANDLE_INSET` from the edge on the `free` side of local x.
fn leaf_parts(lw: f32, lh: f32, free: f32, rgb: [f32; 3]) -> Vec<Part> {
    let mut slab = box_part(
        Vec3::new(0.0, UNDERCUT + lh * 0.5, 0.0),
        Vec3::new(lw, lh, LEAF_T),
        rgb,
    );
    if let Shape::Cuboid { bevel, .. } = &mut slab.shape {
        *bevel = BEVEL;
    }
    let mut parts = vec![slab];
    let x = free * (lw * 0.5 - HANDLE_INSET);
    for s in [-1.0f32, 1.0] {
        // A square rose and stem out of the face, and the lever along it towards the hinge.
        parts.push(box_part(
            Vec3::new(x, HANDLE_Y, s * (LEAF_T + HANDLE_OUT) * 0.5),
            Vec3::new(0.035, 0.035, HANDLE_OUT),
            tone::STEEL,
        ));
        parts.push(box_part(
            Vec3::new(
                x - free * 0.05,
                HANDLE_Y,
                s * (LEAF_T * 0.5 + HANDLE_OUT - 0.01),
            ),
            Vec3::new(0.13, 0.022, 0.02),
            tone::STEEL,
        ));
    }
    parts
}

/// A leaf object (id 0: not yet added) of the given centre on the floor, yaw and handle side.
fn leaf_object(center: Vec3, yaw: f32, parts: Vec<Part>) -> SceneObject {
    SceneObject::from_parts(0, C::Door, Pose::from_yaw(center, yaw), parts)
}

/// Along-wall and depth axes of an opening as world `(x, z)` unit vectors, and the yaw that turns
/// local x along the wall.
fn axes(o: &Opening) -> ((f32, f32), (f32, f32), f32) {
    if o.along_z {
        // Local x turns to -z at yaw 90 degrees.
        ((0.0, -1.0), (1.0, 0.0), FRAC_PI_2)
    } else {
        ((1.0, 0.0), (0.0, 1.0), 0.0)
    }
}

/// The closed leaf of an opening, hinged on side `hinge` (+1/-1 along local x).
fn closed_leaf(cfg: &ProcgenConfig, o: &Opening, hinge: f32, rgb: [f32; 3]) -> SceneObject {
    let (_, _, yaw) = axes(o);
    let lw = o.width - 2.0 * FRAME_GAP;
    let lh = cfg.doors.head_height - UNDERCUT - FRAME_GAP;
    let (x, z) = o.position();
    leaf_object(Vec3::new(x, 0.0, z), yaw, leaf_parts(lw, lh, -hinge, rgb))
}

/// The open leaf of an opening swung into the room on side `side` of the wall (+1/-1 along the
/// depth axis), hinged on side `hinge` along the wall.
fn open_leaf(
    cfg: &ProcgenConfig,
    o: &Opening,
    side: f32,
    hinge: f32,
    rgb: [f32; 3],
) -> SceneObject {
    let ((ax, az), (nx, nz), yaw) = axes(o);
    let lw = o.width - 2.0 * FRAME_GAP;
    let lh = cfg.doors.head_height - UNDERCUT - FRAME_GAP;
    // The post stands (t + 0.02) / 2 out of the wall line (see `add_door_frame`).
    let depth0 = (cfg.walls.thickness + 0.02) * 0.5 + FRAME_GAP;
    // Leaf face towards the doorway just outside the inner handle, which ends at the clear width.
    let along = hinge * (o.width * 0.5 + FRAME_GAP + HANDLE_OUT + LEAF_T * 0.5);
    let depth = side * (depth0 + lw * 0.5);
    let (x, z) = o.position();
    let c = Vec3::new(
        x + ax * along + nx * depth,
        0.0,
        z + az * along + nz * depth,
    );
    // Rotated a quarter turn from the closed leaf: local x now runs along the depth axis.
    let yaw = yaw + FRAC_PI_2;
    // World direction of local +x at this yaw, dotted with the depth axis, tells which end of
    // local x is the free (far) edge.
    let (lx, lz) = (yaw.cos(), -yaw.sin());
    let free = (side * (lx * nx + lz * nz)).signum();
    leaf_object(c, yaw, leaf_parts(lw, lh, free, rgb))
}

/// Whether an open leaf may stand where `leaf` is: inside the room, clear of furniture, of the
/// other doorways' clearance boxes and of the leaves placed so far, closing off nothing. Returns
/// the share of the room's floor the agent can still reach, or `None`.
#[allow(clippy::too_many_arguments)]
fn fits(
    cfg: &ProcgenConfig,
    plan: &Plan,
    own: usize,
    room_index: usize,
    room: &Rect,
    leaf: &Aabb,
    objects: &[SceneObject],
    leaves: &[Aabb],
) -> Option<f32> {
    let foot = footprint(leaf);
    // The hinge end stands just off the wall face; the wall line is the room rectangle's edge.
    let inner = room.inset(cfg.walls.thickness * 0.5);
    if !inner.contains_rect(&foot, 0.0) {
        return None;
    }
    let grown = Aabb::new(
        leaf.min_v() - Vec3::splat(MARGIN),
        leaf.max_v() + Vec3::splat(MARGIN),
    );
    let blocked = objects.iter().any(|o| {
        !matches!(
            o.class,
            C::Floor | C::Wall | C::Ceiling | C::DoorFrame | C::Rug
        ) && o.bbox.intersects(&grown, 0.0)
    });
    if blocked || leaves.iter().any(|l| l.intersects(&grown, 0.0)) {
        return None;
    }
    let clear = plan
        .openings
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != own)
        .all(|(_, o)| !clearance_rect(o, cfg, cfg.doors.clearance, 0.0).overlaps(&foot, 0.0));
    if !clear {
        return None;
    }
    room_stays_connected(cfg, plan, room_index, objects, leaves, &foot)
}

/// Footprint of a box on the floor.
fn footprint(b: &Aabb) -> Rect {
    Rect {
        x0: b.min[0],
        x1: b.max[0],
        z0: b.min[2],
        z1: b.max[2],
    }
}

/// Whether the leaf leaves the rest of the room as reachable as it was: on a fine grid at the
/// agent's radius (plus a map cell, as the occupancy map rounds outwards), the cells reachable
/// from the doorways drop by no more than the cells the leaf itself covers. Furniture placement
/// checks its own connectivity at a larger radius, which misses corners the agent can still
/// reach and a leaf could close off. Returns the share of the room's floor still reachable.
fn room_stays_connected(
    cfg: &ProcgenConfig,
    plan: &Plan,
    room_index: usize,
    objects: &[SceneObject],
    leaves: &[Aabb],
    leaf: &Rect,
) -> Option<f32> {
    let t = cfg.walls.thickness;
    let room = &plan.rooms[room_index];
    let interior = room.rect.inset(t * 0.5);
    let mut grid = NavGrid::new(interior, CHECK_CELL, CHECK_RADIUS);
    let near = interior.inset(-CHECK_RADIUS);
    let obstacles = objects
        .iter()
        .filter(|o| !matches!(o.class, C::Floor | C::Wall | C::Ceiling | C::DoorFrame))
        .map(|o| &o.bbox)
        .chain(leaves)
        .filter(|b| b.max[1] > FLOOR_BAND)
        .map(footprint);
    for r in obstacles {
        if r.overlaps(&near, 0.0) {
            grid.stamp(&r, true);
        }
    }
    let (cx, cz) = room.rect.center();
    let inside = t * 0.5 + CHECK_RADIUS + 2.0 * CHECK_CELL;
    let seeds: Vec<(f32, f32)> = plan
        .openings
        .iter()
        .filter(|o| o.rooms.contains(&room_index))
        .map(|o| {
            let (x, z) = o.position();
            if o.along_z {
                (x + (cx - x).signum() * inside, z)
            } else {
                (x, z + (cz - z).signum() * inside)
            }
        })
        .collect();
    let (free, reach) = (grid.free_cells(), grid.reachable(&seeds));
    grid.stamp(leaf, true);
    let lost = free - grid.free_cells();
    let after = grid.reachable(&seeds);
    let share = after as f32 * CHECK_CELL * CHECK_CELL / interior.area().max(1e-6);
    // In a room furniture already fills, the leaf may take only a small part of what is left.
    let small = share >= MIN_REACHABLE || after as f32 >= KEEP_IN_FULL_ROOM * reach as f32;
    (after > 0 && after + lost >= reach && small).then_some(share)
}

/// Add the leaves of every doorway; returns each opening's state and leaf.
pub(crate) fn add_leaves(
    cfg: &ProcgenConfig,
    plan: &Plan,
    seed: u64,
    b: &mut Builder,
) -> Vec<DoorLeaf> {
    let n = plan.openings.len();
    let mut out: Vec<DoorLeaf> = vec![(None, None); n];
    if !cfg.doors.leaves {
        return out;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ SALT);
    // Which doors close: drawn in a random order, each kept only if the rooms stay connected.
    let mut closed = vec![false; n];
    let mut order: Vec<usize> = (0..n).filter(|&i| !plan.openings[i].open_plan).collect();
    order.shuffle(&mut rng);
    for &i in &order {
        let draw = rng.random::<f32>() < cfg.doors.closed_probability;
        closed[i] = draw;
        if draw && !connected(plan, &closed) {
            closed[i] = false;
        }
    }

    let mut leaves: Vec<Aabb> = Vec::new();
    for (i, o) in plan.openings.iter().enumerate() {
        if o.open_plan {
            continue;
        }
        let fin = *FINISHES.choose(&mut rng).unwrap_or(&FINISHES[0]);
        let hinge = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
        let mut options = [(0usize, 1.0f32), (0, -1.0), (1, 1.0), (1, -1.0)];
        options.shuffle(&mut rng);
        let mut leaf = None;
        if !closed[i] {
            let (_, (nx, nz), _) = axes(o);
            let (px, pz) = o.position();
            // Of the ways that fit, the one leaving the most of its room reachable.
            let mut best: Option<(f32, SceneObject, usize)> = None;
            for (k, h) in options {
                let r = o.rooms[k];
                let (cx, cz) = plan.rooms[r].rect.center();
                // Side of the wall the room lies on, along the depth axis.
                let side = ((cx - px) * nx + (cz - pz) * nz).signum();
                let cand = open_leaf(cfg, o, side, h, fin.rgb);
                let room = &plan.rooms[r].rect;
                let share = fits(cfg, plan, i, r, room, &cand.bbox, &b.objects, &leaves);
                if let Some(share) = share {
                    if best.as_ref().is_none_or(|b| share > b.0) {
                        best = Some((share, cand, r));
                    }
                }
            }
            leaf = best.map(|(_, cand, r)| (cand, r, DoorState::Open));
            if leaf.is_none() {
                closed[i] = true;
                if !connected(plan, &closed) {
                    closed[i] = false;
                    tracing::debug!(door = i, "no room for the open leaf: doorway left bare");
                    continue;
                }
            }
        }
        let (obj, room, state) = match leaf {
            Some(l) => l,
            None => (
                closed_leaf(cfg, o, hinge, fin.rgb),
                o.rooms[0],
                DoorState::Closed,
            ),
        };
        leaves.push(obj.bbox);
        let id = b.add_finish(
            C::Door,
            Some(room as RoomId),
            obj.pose,
            obj.parts,
            fin,
            28.0,
            None,
        );
        out[i] = (Some(state), Some(id));
    }
    out
}
