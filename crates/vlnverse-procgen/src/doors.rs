//! Door leaves: a hinged slab with a handle on both faces in every doorway that has a frame
//! (open-plan openings have none), or a sliding glass panel, or a pair of french doors; arched
//! doorways have none ([`kinds`]).
//!
//! A doorway's kind comes from a stream of its own, seeded by the home and the door, so a home's
//! other draws stay as they were. Sliding doors lead to porches and balconies (and some join a
//! living room to a dining room): open, the panel lies flat against the wall beside the opening,
//! in front of the wall face, where it fits clear of the furniture. French doors join living
//! rooms, dining rooms, offices and libraries: two glass-paned leaves of half the width, hinged
//! at the two jambs, both swung into one room when open. Arched doorways (between living rooms,
//! kitchens, dining rooms, hallways and entrance halls) have no leaf; their arch is part of the
//! door frame (`home.rs`), above the door head.
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
use vlnverse_env::scene::DoorKind;
use vlnverse_env::{
    Aabb, DoorState, ObjectId, Part, Pose, RoomId, RoomType, SceneObject, SemanticClass as C, Shape,
};

/// Salt of the doors' random stream.
const SALT: u64 = 0xd004_1ea5_5eed_0002;
/// Salt of the streams of the doorways' kinds (one per doorway).
const KIND_SALT: u64 = 0x6b1d_d00e_5a1e_0003;
/// Thickness of a glass pane (m): thinner than the frame, which tells panes from frames.
const PANE_T: f32 = 0.01;
/// Width of the stiles and rails of a glass door's frame (m).
const STILE: f32 = 0.06;
/// Height of a french door's bottom rail (m).
const FRENCH_RAIL: f32 = 0.18;
/// Tint of a glass door's pane: darker than a window's glowing pane, so it reads as glass.
const PANE_RGB: [f32; 3] = [0.42, 0.52, 0.58];
/// How far a sliding door's pull bar stands out of each face (m).
const PULL_OUT: f32 = 0.012;
/// Gap between the two leaves of french doors (m).
const MEETING_GAP: f32 = 0.006;
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

/// Frames of sliding doors (aluminium or painted); the panes are glass.
const SLIDING_FINISHES: &[Finish] = &[
    f("white", "glass", [0.88, 0.88, 0.86]),
    f("black", "glass", [0.05, 0.05, 0.05]),
    f("grey", "glass", [0.42, 0.43, 0.45]),
];
/// Frames of french doors (painted or stained wood); the panes are glass.
const FRENCH_FINISHES: &[Finish] = &[
    f("white", "glass", [0.9, 0.9, 0.87]),
    f("wooden", "glass", [0.5, 0.32, 0.17]),
    f("brown", "glass", [0.3, 0.18, 0.09]),
    f("black", "glass", [0.06, 0.06, 0.06]),
    f("grey", "glass", [0.45, 0.46, 0.48]),
];

/// What a doorway got: its kind, its state and its leaves (`None` for open-plan openings and
/// doorways without a leaf), one entry per opening of the plan.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct DoorLeaf {
    pub kind: DoorKind,
    pub state: Option<DoorState>,
    pub leaf: Option<ObjectId>,
    /// The second leaf of french doors.
    pub second: Option<ObjectId>,
}

/// The kind of each opening of a plan (`hinged` for open-plan openings), each drawn from a
/// stream seeded by the home's `seed` and the opening's index, so that choosing kinds moves
/// nothing else and a kind depends only on its own doorway.
pub(crate) fn kinds(plan: &Plan, seed: u64) -> Vec<DoorKind> {
    use RoomType as R;
    plan.openings
        .iter()
        .enumerate()
        .map(|(i, o)| {
            if o.open_plan {
                return DoorKind::Hinged;
            }
            let mut rng = ChaCha8Rng::seed_from_u64(
                (seed ^ KIND_SALT).wrapping_add((i as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15)),
            );
            let [a, b] = o.rooms.map(|r| plan.rooms[r].kind);
            let either = |k: &[R]| k.contains(&a) || k.contains(&b);
            let both = |k: &[R]| k.contains(&a) && k.contains(&b);
            let x: f32 = rng.random();
            // (kind, probability) tried in order on one draw.
            let table: &[(DoorKind, f32)] = if either(&[R::Porch, R::Balcony]) {
                &[(DoorKind::Sliding, 0.8)]
            } else if both(&[R::LivingRoom, R::DiningRoom]) && a != b {
                &[
                    (DoorKind::French, 0.35),
                    (DoorKind::Sliding, 0.15),
                    (DoorKind::Arched, 0.25),
                ]
            } else if both(&[R::LivingRoom, R::DiningRoom, R::Office, R::Library]) {
                &[(DoorKind::French, 0.4)]
            } else if both(&[
                R::LivingRoom,
                R::DiningRoom,
                R::Kitchen,
                R::Hallway,
                R::EntranceHall,
            ]) {
                &[(DoorKind::Arched, 0.25)]
            } else {
                &[]
            };
            let mut acc = 0.0;
            for &(kind, p) in table {
                acc += p;
                if x < acc {
                    return kind;
                }
            }
            DoorKind::Hinged
        })
        .collect()
}

/// The frame finish of a glass door of `kind`, drawn from the kind's own list with `rng`.
fn glass_finish(kind: DoorKind, rng: &mut ChaCha8Rng) -> Finish {
    let list = if kind == DoorKind::French {
        FRENCH_FINISHES
    } else {
        SLIDING_FINISHES
    };
    *list.choose(rng).unwrap_or(&list[0])
}

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
    add_levers(&mut parts, lw, free);
    parts
}

/// A rose and a lever on each face, `HANDLE_INSET` from the `free` edge of a leaf `lw` wide.
fn add_levers(parts: &mut Vec<Part>, lw: f32, free: f32) {
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
}

/// A glass leaf of `kind` (sliding or french), `lw` wide and `lh` high, in the same frame as
/// [`leaf_parts`]: a frame of stiles and rails in `rgb` round a pane of glass thinner
/// than the frame (french doors have two glazing bars across it and a deeper bottom rail), and
/// a pull bar (sliding) or levers (french) near the `free` edge.
fn glass_leaf_parts(kind: DoorKind, lw: f32, lh: f32, free: f32, rgb: [f32; 3]) -> Vec<Part> {
    let bottom = if kind == DoorKind::French {
        FRENCH_RAIL
    } else {
        STILE
    };
    let y0 = UNDERCUT;
    let y1 = UNDERCUT + lh;
    let inner_w = lw - 2.0 * STILE;
    let (p0, p1) = (y0 + bottom, y1 - STILE);
    let mut parts = vec![
        // The pane first: the largest part, the one a view through the doorway meets.
        box_part(
            Vec3::new(0.0, (p0 + p1) * 0.5, 0.0),
            Vec3::new(inner_w, p1 - p0, PANE_T),
            PANE_RGB,
        ),
    ];
    for s in [-1.0f32, 1.0] {
        parts.push(box_part(
            Vec3::new(s * (lw - STILE) * 0.5, (y0 + y1) * 0.5, 0.0),
            Vec3::new(STILE, lh, LEAF_T),
            rgb,
        ));
    }
    parts.push(box_part(
        Vec3::new(0.0, y0 + bottom * 0.5, 0.0),
        Vec3::new(inner_w, bottom, LEAF_T),
        rgb,
    ));
    parts.push(box_part(
        Vec3::new(0.0, y1 - STILE * 0.5, 0.0),
        Vec3::new(inner_w, STILE, LEAF_T),
        rgb,
    ));
    if kind == DoorKind::French {
        for k in 1..3 {
            let y = p0 + (p1 - p0) * k as f32 / 3.0;
            parts.push(box_part(
                Vec3::new(0.0, y, 0.0),
                Vec3::new(inner_w, 0.03, 0.03),
                rgb,
            ));
        }
        add_levers(&mut parts, lw, free);
    } else {
        // A flat pull bar through the stile at the free edge, a little proud of both faces
        // (the open panel lies close to the wall).
        parts.push(box_part(
            Vec3::new(free * (lw - STILE) * 0.5, HANDLE_Y, 0.0),
            Vec3::new(0.025, 0.35, LEAF_T + 2.0 * PULL_OUT),
            tone::STEEL,
        ));
    }
    parts
}

/// The parts of a leaf of `kind`.
fn parts_of(kind: DoorKind, lw: f32, lh: f32, free: f32, rgb: [f32; 3]) -> Vec<Part> {
    if kind.is_glass() {
        glass_leaf_parts(kind, lw, lh, free, rgb)
    } else {
        leaf_parts(lw, lh, free, rgb)
    }
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

/// Clear height of a leaf under the door head.
fn leaf_height(cfg: &ProcgenConfig) -> f32 {
    cfg.doors.head_height - UNDERCUT - FRAME_GAP
}

/// A leaf `lw` wide standing in the plane of the wall, its centre `along` the wall from the
/// opening's centre, its handles on side `free` (+1/-1 along local x).
fn leaf_in_wall(
    cfg: &ProcgenConfig,
    o: &Opening,
    kind: DoorKind,
    lw: f32,
    along: f32,
    free: f32,
    rgb: [f32; 3],
) -> SceneObject {
    let ((ax, az), _, yaw) = axes(o);
    let (x, z) = o.position();
    let c = Vec3::new(x + ax * along, 0.0, z + az * along);
    leaf_object(c, yaw, parts_of(kind, lw, leaf_height(cfg), free, rgb))
}

/// The closed leaves of an opening (two for french doors, hinged at the jambs), hinged on side
/// `hinge` (+1/-1 along local x).
fn closed_leaves(
    cfg: &ProcgenConfig,
    o: &Opening,
    kind: DoorKind,
    hinge: f32,
    rgb: [f32; 3],
) -> Vec<SceneObject> {
    let lw = o.width - 2.0 * FRAME_GAP;
    if kind == DoorKind::French {
        let half = (lw - MEETING_GAP) * 0.5;
        let off = (half + MEETING_GAP) * 0.5;
        return [-1.0f32, 1.0]
            .map(|h| leaf_in_wall(cfg, o, kind, half, h * off, -h, rgb))
            .to_vec();
    }
    vec![leaf_in_wall(cfg, o, kind, lw, 0.0, -hinge, rgb)]
}

/// The open leaves of an opening on side `side` of the wall (+1/-1 along the depth axis): a
/// hinged leaf swung into that room on its hinge jamb `hinge`, french doors both swung in, a
/// sliding panel slid along the wall towards `hinge`, flat in front of the wall face.
fn open_leaves(
    cfg: &ProcgenConfig,
    o: &Opening,
    kind: DoorKind,
    side: f32,
    hinge: f32,
    rgb: [f32; 3],
) -> Vec<SceneObject> {
    let lw = o.width - 2.0 * FRAME_GAP;
    match kind {
        DoorKind::French => {
            let half = (lw - MEETING_GAP) * 0.5;
            [-1.0f32, 1.0]
                .map(|h| swung_leaf(cfg, o, kind, half, side, h, rgb))
                .to_vec()
        }
        DoorKind::Sliding => {
            let ((ax, az), (nx, nz), yaw) = axes(o);
            // In front of the frame's post (which stands 1 cm proud of the wall face), beside
            // the opening, so the doorway keeps its full clear width.
            let depth =
                side * ((cfg.walls.thickness + 0.02) * 0.5 + FRAME_GAP + PULL_OUT + LEAF_T * 0.5);
            let along = hinge * (o.width * 0.5 + cfg.doors.frame_width + FRAME_GAP + lw * 0.5);
            let (x, z) = o.position();
            let c = Vec3::new(
                x + ax * along + nx * depth,
                0.0,
                z + az * along + nz * depth,
            );
            vec![leaf_object(
                c,
                yaw,
                parts_of(kind, lw, leaf_height(cfg), -hinge, rgb),
            )]
        }
        _ => vec![swung_leaf(cfg, o, kind, lw, side, hinge, rgb)],
    }
}

/// A leaf `lw` wide swung open into the room on side `side` of the wall (+1/-1 along the depth
/// axis), hinged on side `hinge` along the wall.
fn swung_leaf(
    cfg: &ProcgenConfig,
    o: &Opening,
    kind: DoorKind,
    lw: f32,
    side: f32,
    hinge: f32,
    rgb: [f32; 3],
) -> SceneObject {
    let ((ax, az), (nx, nz), yaw) = axes(o);
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
    leaf_object(c, yaw, parts_of(kind, lw, leaf_height(cfg), free, rgb))
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

/// The open leaves of opening `i` of `kind` in the way that fits leaving the most of its room
/// reachable, trying `options` (room side, hinge or slide side) in order; with the room they
/// stand in.
#[allow(clippy::too_many_arguments)]
fn open_placement(
    cfg: &ProcgenConfig,
    plan: &Plan,
    i: usize,
    kind: DoorKind,
    options: &[(usize, f32)],
    rgb: [f32; 3],
    objects: &[SceneObject],
    leaves: &[Aabb],
) -> Option<(Vec<SceneObject>, usize, DoorState)> {
    let o = &plan.openings[i];
    let (_, (nx, nz), _) = axes(o);
    let (px, pz) = o.position();
    let mut best: Option<(f32, Vec<SceneObject>, usize)> = None;
    for &(k, h) in options {
        let r = o.rooms[k];
        let (cx, cz) = plan.rooms[r].rect.center();
        // Side of the wall the room lies on, along the depth axis.
        let side = ((cx - px) * nx + (cz - pz) * nz).signum();
        let cands = open_leaves(cfg, o, kind, side, h, rgb);
        let room = &plan.rooms[r].rect;
        // Every leaf must fit, each clear of the others.
        let mut taken = leaves.to_vec();
        let mut share = Some(1.0f32);
        for c in &cands {
            let s = fits(cfg, plan, i, r, room, &c.bbox, objects, &taken);
            share = share.zip(s).map(|(a, s)| a.min(s));
            taken.push(c.bbox);
        }
        if let Some(share) = share {
            if best.as_ref().is_none_or(|b| share > b.0) {
                best = Some((share, cands, r));
            }
        }
    }
    best.map(|(_, cands, r)| (cands, r, DoorState::Open))
}

/// Add the leaves of every doorway of the given kinds ([`kinds`]); returns each opening's kind,
/// state and leaves.
pub(crate) fn add_leaves(
    cfg: &ProcgenConfig,
    plan: &Plan,
    kinds: &[DoorKind],
    seed: u64,
    b: &mut Builder,
) -> Vec<DoorLeaf> {
    let n = plan.openings.len();
    let kind_of = |i: usize| kinds.get(i).copied().unwrap_or_default();
    // Without leaves a doorway is bare (`hinged`) unless it is an arch.
    let mut out: Vec<DoorLeaf> = (0..n)
        .map(|i| DoorLeaf {
            kind: match kind_of(i) {
                DoorKind::Arched => DoorKind::Arched,
                _ => DoorKind::Hinged,
            },
            ..DoorLeaf::default()
        })
        .collect();
    if !cfg.doors.leaves {
        return out;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ SALT);
    // Which doors close: drawn in a random order, each kept only if the rooms stay connected.
    // An arch has nothing to close (its draw is still made, so the other doors keep theirs).
    let mut closed = vec![false; n];
    let mut order: Vec<usize> = (0..n).filter(|&i| !plan.openings[i].open_plan).collect();
    order.shuffle(&mut rng);
    for &i in &order {
        let draw = rng.random::<f32>() < cfg.doors.closed_probability;
        closed[i] = draw && kind_of(i) != DoorKind::Arched;
        if closed[i] && !connected(plan, &closed) {
            closed[i] = false;
        }
    }

    let mut leaves: Vec<Aabb> = Vec::new();
    for (i, o) in plan.openings.iter().enumerate() {
        if o.open_plan {
            continue;
        }
        let mut kind = kind_of(i);
        // The same draws for every kind, so the doors after this one keep theirs.
        let drawn = *FINISHES.choose(&mut rng).unwrap_or(&FINISHES[0]);
        let mut fin = drawn;
        let hinge = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
        let mut options = [(0usize, 1.0f32), (0, -1.0), (1, 1.0), (1, -1.0)];
        options.shuffle(&mut rng);
        if kind == DoorKind::Arched {
            continue;
        }
        if kind.is_glass() {
            let mut krng = ChaCha8Rng::seed_from_u64(
                (seed ^ KIND_SALT ^ SALT).wrapping_add((i as u64 + 1).wrapping_mul(0x2545_f491)),
            );
            fin = glass_finish(kind, &mut krng);
        }
        let mut placed = None;
        if !closed[i] {
            placed = open_placement(cfg, plan, i, kind, &options, fin.rgb, &b.objects, &leaves);
            if placed.is_none() {
                closed[i] = true;
                if !connected(plan, &closed) {
                    closed[i] = false;
                    // A glass door that neither opens nor closes here becomes a hinged door
                    // if one fits, with the finish drawn for it.
                    if kind.is_glass() {
                        fin = drawn;
                        kind = DoorKind::Hinged;
                        placed = open_placement(
                            cfg, plan, i, kind, &options, fin.rgb, &b.objects, &leaves,
                        );
                    }
                    if placed.is_none() {
                        tracing::debug!(door = i, "no room for the open leaf: doorway left bare");
                        continue;
                    }
                }
            }
        }
        let (objs, room, state) = match placed {
            Some(l) => l,
            None => (
                closed_leaves(cfg, o, kind, hinge, fin.rgb),
                o.rooms[0],
                DoorState::Closed,
            ),
        };
        let mut ids = Vec::with_capacity(2);
        for obj in objs {
            leaves.push(obj.bbox);
            ids.push(b.add_finish(
                C::Door,
                Some(room as RoomId),
                obj.pose,
                obj.parts,
                fin,
                if kind == DoorKind::French { 18.0 } else { 28.0 },
                None,
            ));
        }
        out[i] = DoorLeaf {
            kind,
            state: Some(state),
            leaf: ids.first().copied(),
            second: ids.get(1).copied(),
        };
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::PlanRoom;
    use glam::Vec2;
    use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
    use vlnverse_env::{Door, Room, RoomType, Scene};

    /// Three empty rooms joined in a ring (so one door may close), every doorway of `kind`,
    /// with leaves added at `closed_probability` 1: the scene and its doors.
    fn ring(kind: DoorKind) -> Scene {
        let mut cfg = ProcgenConfig::default();
        cfg.doors.closed_probability = 1.0;
        let r = |x0, z0, x1, z1| PlanRoom {
            kind: RoomType::LivingRoom,
            rect: Rect { x0, z0, x1, z1 },
            bare: true,
        };
        let door = |rooms, along_z, line, center| Opening {
            rooms,
            along_z,
            line,
            center,
            width: 1.0,
            open_plan: false,
        };
        let plan = Plan {
            rooms: vec![
                r(0.0, 0.0, 4.0, 4.0),
                r(4.0, 0.0, 8.0, 4.0),
                r(0.0, 4.0, 8.0, 8.0),
            ],
            openings: vec![
                door([0, 1], true, 4.0, 2.0),
                door([0, 2], false, 4.0, 2.0),
                door([1, 2], false, 4.0, 6.0),
            ],
        };
        let mut b = Builder {
            objects: Vec::new(),
        };
        for (i, room) in plan.rooms.iter().enumerate() {
            let q = room.rect;
            let mut floor = SceneObject::cuboid(
                0,
                C::Floor,
                Vec3::new(q.x0, -0.05, q.z0),
                Vec3::new(q.x1, 0.0, q.z1),
            );
            floor.id = b.objects.len() as ObjectId + 1;
            floor.room = Some(i as RoomId);
            b.objects.push(floor);
        }
        let kinds = vec![kind; 3];
        let leaves = add_leaves(&cfg, &plan, &kinds, 7, &mut b);
        let rooms = plan
            .rooms
            .iter()
            .enumerate()
            .map(|(i, p)| Room {
                id: i as RoomId,
                kind: p.kind,
                name: format!("living_room_{i}"),
                polygon: vec![
                    [p.rect.x0, p.rect.z0],
                    [p.rect.x0, p.rect.z1],
                    [p.rect.x1, p.rect.z1],
                    [p.rect.x1, p.rect.z0],
                ],
            })
            .collect();
        // (Every opening here is framed, so the home's own doors_of gives them as built.)
        let doors = crate::home::doors_of(&plan, leaves, 0.0, 0, 0, 0);
        Scene {
            format_version: vlnverse_env::SCENE_FORMAT_VERSION,
            id: "ring".into(),
            source: "test".into(),
            seed: Some(7),
            floor_height: 0.0,
            rooms,
            doors,
            objects: b.objects,
            storeys: Default::default(),
        }
    }

    #[test]
    fn a_closed_glass_door_fills_its_doorway_and_an_open_one_leaves_it_free() {
        let occ = OccupancyConfig::default();
        for kind in [DoorKind::Sliding, DoorKind::French] {
            let s = ring(kind);
            let maps = build_maps(&s, &occ).unwrap();
            let closed: Vec<&Door> = s.doors.iter().filter(|d| d.is_closed()).collect();
            assert_eq!(closed.len(), 1, "{kind:?}: one door of the ring closes");
            for d in &s.doors {
                assert_eq!(d.kind, kind);
                let ids: Vec<ObjectId> = d.leaves().collect();
                assert_eq!(ids.len(), if kind == DoorKind::French { 2 } else { 1 });
                let c = Vec2::new(d.position[0], d.position[2]);
                let across = Vec2::from_array(d.normal).perp();
                // Jamb to jamb, the clear width is blocked when closed and free when open.
                for k in 0..=20 {
                    let p = c + across * d.width * (k as f32 / 20.0 - 0.5) * 0.98;
                    assert_eq!(
                        maps.occupancy.is_free_at(p),
                        !d.is_closed(),
                        "{kind:?}: door {} at {p}",
                        d.id
                    );
                }
                for id in ids {
                    let o = s.object(id).unwrap();
                    assert_eq!(o.material, "glass");
                    if kind == DoorKind::Sliding && !d.is_closed() {
                        // Open, the panel lies against the wall beside the opening: within
                        // 14 cm of the wall line and beside the clear width, not across it.
                        let lc = Vec2::new(o.bbox.center().x, o.bbox.center().z);
                        let n = Vec2::from_array(d.normal);
                        assert!((lc - c).dot(n).abs() < 0.14, "{:?}", o.bbox);
                        assert!((lc - c).dot(across).abs() > d.width, "{:?}", o.bbox);
                        let thin = o.bbox.size().x.min(o.bbox.size().z);
                        assert!(thin < 0.07, "{:?}", o.bbox);
                    }
                }
            }
        }
    }
}
