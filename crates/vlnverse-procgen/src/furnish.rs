//! Furniture placement by room type.
//!
//! A room's recipe is a list of groups (a bed with its nightstands, a sofa with a coffee table
//! and a rug, a table with chairs, a kitchen run...). A group has its own frame (front -Z, back
//! +Z) and is placed as a unit: against a wall (back to the wall), in a corner, or free in the
//! room. A placement is kept only if its footprint stays inside the room, clear of the other
//! groups and of every doorway's clearance box, and the room's free space stays one connected
//! island reaching every doorway ([`NavGrid`]). Small objects then go on the flat tops.

use crate::config::ProcgenConfig;
use crate::floorplan::{Plan, PlanRoom};
use crate::home::{clearance_rect, Builder};
use crate::household;
use crate::models::{self, Model};
use crate::more_things;
use crate::navgrid::NavGrid;
use crate::pieces::{self, Spot};
use crate::rect::Rect;
use glam::{Quat, Vec3};
use rand::seq::IndexedRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f32::consts::{FRAC_PI_2, PI};
use vlnverse_env::{ObjectId, Pose, RoomId, RoomType, SemanticClass as C};

/// Grid cell of the in-room navigability check (m).
const NAV_CELL: f32 = 0.1;
/// How far past a framed doorway's gap, along the wall, floor and wall clutter stays away (m):
/// an open leaf (about a door width deep) stands there.
const CLUTTER_SWING: f32 = 0.7;
/// Share of a room's floor that stays free in the in-room grid (whose radius is more than the
/// agent's) when floor and wall clutter is placed.
const CLUTTER_MIN_FREE: f32 = 0.2;
/// The same share for furniture: a bed may not take the last of a bedroom's open floor and
/// leave the rest of the room behind a gap narrower than the agent.
const FURNITURE_MIN_FREE: f32 = 0.12;
/// Random spots tried for each small object on its surface.
const SMALL_TRIES: usize = 16;
/// Distance kept between furniture and walls (m).
pub(crate) const WALL_GAP: f32 = 0.01;

/// One object of a group, in the group frame.
#[derive(Clone, Debug)]
struct Item {
    model: Model,
    x: f32,
    z: f32,
    /// Height of its base (> 0 when standing on another item of the group).
    y: f32,
    /// Yaw relative to the group (a multiple of 90 degrees).
    yaw: f32,
    /// Index of the item it stands on.
    on: Option<usize>,
    /// Rugs: walkable, may lie under other items.
    flat: bool,
    /// No small objects on this one (its top is taken).
    bare: bool,
}

impl Item {
    fn at(model: Model, x: f32, z: f32, yaw: f32) -> Item {
        Item {
            // Rugs and mats: walkable (below the maps' floor clearance).
            flat: model.class == C::Rug || model.h < 0.02,
            model,
            x,
            z,
            y: 0.0,
            yaw,
            on: None,
            bare: false,
        }
    }

    /// Footprint in the group frame.
    fn rect(&self) -> Rect {
        let (w, d) = if quarter(self.yaw) % 2 == 1 {
            (self.model.d, self.model.w)
        } else {
            (self.model.w, self.model.d)
        };
        Rect::centered(self.x, self.z, w, d)
    }
}

/// Number of quarter turns of a yaw (0..4).
fn quarter(yaw: f32) -> i32 {
    ((yaw / FRAC_PI_2).round() as i32).rem_euclid(4)
}

/// How a group is placed.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    /// Back against a wall.
    Wall,
    /// Back against a wall, at one end of it.
    Corner,
    /// Free in the room, at least a walkway away from the walls.
    Center,
}

#[derive(Clone, Debug)]
struct Group {
    items: Vec<Item>,
    mode: Mode,
}

impl Group {
    fn one(model: Model, mode: Mode) -> Group {
        Group {
            items: vec![Item::at(model, 0.0, 0.0, 0.0)],
            mode,
        }
    }

    /// Union of the item footprints, and re-centre the items on it.
    fn normalise(&mut self) -> (f32, f32) {
        let mut r = self.items[0].rect();
        for it in &self.items[1..] {
            let q = it.rect();
            r = Rect {
                x0: r.x0.min(q.x0),
                z0: r.z0.min(q.z0),
                x1: r.x1.max(q.x1),
                z1: r.z1.max(q.z1),
            };
        }
        let (cx, cz) = r.center();
        for it in &mut self.items {
            it.x -= cx;
            it.z -= cz;
        }
        (r.w(), r.d())
    }
}

/// Rotate a group-frame offset by a yaw.
fn rotate(x: f32, z: f32, yaw: f32) -> (f32, f32) {
    let v = Quat::from_rotation_y(yaw) * Vec3::new(x, 0.0, z);
    (v.x, v.z)
}

pub(crate) struct RoomState<'a> {
    pub(crate) cfg: &'a ProcgenConfig,
    pub(crate) id: RoomId,
    pub(crate) interior: Rect,
    pub(crate) keepout: Vec<Rect>,
    pub(crate) placed: Vec<Rect>,
    pub(crate) grid: NavGrid,
    pub(crate) seeds: Vec<(f32, f32)>,
    /// Fewest free grid cells a placement must leave (the clutter stage keeps a share of the
    /// room walkable).
    pub(crate) min_free: usize,
}

/// A placed group item, ready to become a scene object.
struct Placed {
    model: Model,
    pose: Pose,
    on: Option<usize>,
    bare: bool,
}

impl RoomState<'_> {
    /// Candidate centres and yaws of a group of footprint `gw` x `gd`, in trial order: along
    /// walls every 15 cm (only the ends for corners), or random spots for free groups.
    fn candidates(
        &self,
        mode: Mode,
        gw: f32,
        gd: f32,
        rng: &mut ChaCha8Rng,
    ) -> Vec<(f32, f32, f32)> {
        use rand::seq::SliceRandom;
        let ir = self.interior.inset(WALL_GAP);
        let (mx, mz) = ir.center();
        let mut out = Vec::new();
        match mode {
            Mode::Wall | Mode::Corner => {
                // Inward normals of the four walls and the wall lengths.
                for (nx, nz, len) in [
                    (0.0f32, 1.0f32, ir.w()),
                    (0.0, -1.0, ir.w()),
                    (1.0, 0.0, ir.d()),
                    (-1.0, 0.0, ir.d()),
                ] {
                    if len < gw {
                        continue;
                    }
                    let yaw = (-nx).atan2(-nz);
                    let slack = len - gw;
                    let n = if mode == Mode::Corner {
                        1
                    } else {
                        ((slack / 0.15).floor() as usize).max(1)
                    };
                    for k in 0..=n {
                        let along = -len * 0.5 + gw * 0.5 + slack * k as f32 / n as f32;
                        let (cx, cz) = if nx != 0.0 {
                            let x = if nx > 0.0 { ir.x0 } else { ir.x1 };
                            (x + nx * gd * 0.5, mz + along)
                        } else {
                            let z = if nz > 0.0 { ir.z0 } else { ir.z1 };
                            (mx + along, z + nz * gd * 0.5)
                        };
                        out.push((cx, cz, yaw));
                    }
                }
                out.shuffle(rng);
            }
            Mode::Center => {
                let walk = 0.6;
                for _ in 0..self.cfg.furniture.attempts * 3 {
                    let q = rng.random_range(0..4);
                    let (ew, ed) = if q % 2 == 1 { (gd, gw) } else { (gw, gd) };
                    let free_x = ir.w() - ew - 2.0 * walk;
                    let free_z = ir.d() - ed - 2.0 * walk;
                    if free_x < 0.0 || free_z < 0.0 {
                        continue;
                    }
                    // Mostly near the middle: that is where tables and rugs go.
                    let fx = (rng.random::<f32>() + rng.random::<f32>()) * 0.5 - 0.5;
                    let fz = (rng.random::<f32>() + rng.random::<f32>()) * 0.5 - 0.5;
                    out.push((mx + fx * free_x, mz + fz * free_z, q as f32 * FRAC_PI_2));
                }
            }
        }
        out
    }

    /// Try to place a group; returns the world poses of its items.
    fn place(&mut self, g: &mut Group, rng: &mut ChaCha8Rng) -> Option<Vec<Placed>> {
        let (gw, gd) = g.normalise();
        let ir = self.interior.inset(WALL_GAP);
        let candidates = self.candidates(g.mode, gw, gd, rng);
        let mut checks = 0;
        for (cx, cz, yaw) in candidates {
            let q = quarter(yaw);
            let (ew, ed) = if q % 2 == 1 { (gd, gw) } else { (gw, gd) };
            let foot = Rect::centered(cx, cz, ew, ed);
            if !ir.contains_rect(&foot, 1e-4)
                || self.keepout.iter().any(|k| k.overlaps(&foot, 0.0))
                || self
                    .placed
                    .iter()
                    .any(|p| p.overlaps(&foot, -self.cfg.furniture.gap))
            {
                continue;
            }
            checks += 1;
            if checks > self.cfg.furniture.attempts {
                break;
            }
            // World footprints of the solid items.
            let solid: Vec<Rect> = g
                .items
                .iter()
                .filter(|it| !it.flat && it.on.is_none())
                .map(|it| {
                    let r = it.rect();
                    let (x, z) = rotate(r.center().0, r.center().1, yaw);
                    let (w, d) = if q % 2 == 1 {
                        (r.d(), r.w())
                    } else {
                        (r.w(), r.d())
                    };
                    Rect::centered(cx + x, cz + z, w, d)
                })
                .collect();
            for r in &solid {
                self.grid.stamp(r, true);
            }
            if !self.grid.connected(&self.seeds) || self.grid.free_cells() < self.min_free {
                for r in &solid {
                    self.grid.stamp(r, false);
                }
                continue;
            }
            self.placed.push(foot);
            let placed = g
                .items
                .iter()
                .map(|it| {
                    let (x, z) = rotate(it.x, it.z, yaw);
                    Placed {
                        model: it.model.clone(),
                        pose: Pose::from_yaw(Vec3::new(cx + x, it.y, cz + z), yaw + it.yaw),
                        on: it.on,
                        bare: it.bare,
                    }
                })
                .collect();
            return Some(placed);
        }
        None
    }
}

/// Draw with probability `p` scaled by the furniture density.
fn maybe(cfg: &ProcgenConfig, rng: &mut ChaCha8Rng, p: f32) -> bool {
    rng.random_bool((p * cfg.furniture.density).clamp(0.0, 1.0) as f64)
}

/// Sofa facing a coffee table on a rug, maybe an armchair beside the table.
fn sofa_group(rng: &mut ChaCha8Rng, max_w: f32, armchair: bool) -> Group {
    let sw = rng.random_range(1.5f32..2.3).min(max_w);
    let sofa = models::sofa(rng, sw);
    let table = models::coffee_table(rng);
    let sofa_z = sofa.d * 0.5;
    let table_z = -0.4 - table.d * 0.5;
    let rw = (table.w + rng.random_range(0.8f32..1.2)).min(sofa.w + 0.4);
    let rd = table.d + rng.random_range(0.7f32..1.0);
    let rug = models::rug(rng, rw, rd);
    let mut items = vec![
        Item::at(sofa, 0.0, sofa_z, 0.0),
        Item::at(table.clone(), 0.0, table_z, 0.0),
    ];
    if rng.random_bool(0.6) {
        items.push(Item::at(rug, 0.0, table_z, 0.0));
    }
    if armchair {
        let a = models::armchair(rng);
        let side = if rng.random_bool(0.5) { -1.0 } else { 1.0 };
        let x = side * (table.w * 0.5 + 0.45 + a.d * 0.5);
        // Faces the table: front towards -side along x.
        items.push(Item::at(a, x, table_z, side * FRAC_PI_2));
    }
    Group {
        items,
        mode: Mode::Wall,
    }
}

/// TV on a stand.
fn tv_group(rng: &mut ChaCha8Rng) -> Group {
    let stand = models::tv_stand(rng);
    let tv = models::tv(rng, stand.w - 0.1);
    let h = stand.h;
    let mut st = Item::at(stand, 0.0, 0.0, 0.0);
    st.bare = true;
    let mut t = Item::at(tv, 0.0, 0.0, 0.0);
    t.y = h;
    t.on = Some(0);
    Group {
        items: vec![st, t],
        mode: Mode::Wall,
    }
}

/// Bed with nightstands, maybe a rug at its foot.
fn bed_group(rng: &mut ChaCha8Rng, double: bool, stands: usize) -> Group {
    let bed = models::bed(rng, double);
    let (bw, bd) = (bed.w, bed.d);
    let mut items = vec![Item::at(bed, 0.0, 0.0, 0.0)];
    let sides: &[f32] = match stands {
        0 => &[],
        1 => {
            if rng.random_bool(0.5) {
                &[-1.0]
            } else {
                &[1.0]
            }
        }
        _ => &[-1.0, 1.0],
    };
    for &s in sides {
        let ns = models::nightstand(rng);
        let x = s * (bw * 0.5 + 0.04 + ns.w * 0.5);
        let z = bd * 0.5 - ns.d * 0.5;
        items.push(Item::at(ns, x, z, 0.0));
    }
    if rng.random_bool(0.35) {
        let rd = rng.random_range(1.0f32..1.5);
        let rug = models::rug(rng, bw + 0.6, rd);
        let z = -bd * 0.5 + 0.3;
        items.push(Item::at(rug, 0.0, z, 0.0));
    }
    Group {
        items,
        mode: Mode::Wall,
    }
}

/// Table with chairs around it (`seats` per long side, maybe one at each end), maybe a rug.
/// With `wall`, the table stands against a wall with no chairs on that side.
fn dining_group(rng: &mut ChaCha8Rng, per_side: usize, ends: bool, rug: bool, wall: bool) -> Group {
    let w = 0.3 + 0.55 * per_side as f32 + rng.random_range(0.0f32..0.2);
    let d = rng.random_range(0.8f32..1.0);
    let table = models::dining_table(rng, w, d);
    let chair = models::chair(rng);
    let mut items = vec![Item::at(table.clone(), 0.0, 0.0, 0.0)];
    let off = 0.03;
    for i in 0..per_side {
        let x = -table.w * 0.5 + table.w * (i as f32 + 0.5) / per_side as f32;
        // Front side (z < 0) chairs face +Z (yaw pi); back side chairs face -Z.
        items.push(Item::at(
            chair.clone(),
            x,
            -table.d * 0.5 - off - chair.d * 0.5,
            PI,
        ));
        if !wall {
            items.push(Item::at(
                chair.clone(),
                x,
                table.d * 0.5 + off + chair.d * 0.5,
                0.0,
            ));
        }
    }
    if ends {
        for s in [-1.0f32, 1.0] {
            let x = s * (table.w * 0.5 + off + chair.d * 0.5);
            items.push(Item::at(chair.clone(), x, 0.0, -s * FRAC_PI_2));
        }
    }
    if rug && !wall {
        // The group is symmetric about the table, so the rug is centred on it.
        let mut g = Group {
            items: items.clone(),
            mode: Mode::Center,
        };
        let (gw, gd) = g.normalise();
        items.push(Item::at(
            models::rug(rng, gw + 0.3, gd + 0.3),
            0.0,
            0.0,
            0.0,
        ));
    }
    Group {
        items,
        mode: if wall { Mode::Wall } else { Mode::Center },
    }
}

/// Desk with a chair in front of it.
fn desk_group(rng: &mut ChaCha8Rng, office_chair: bool) -> Group {
    let desk = models::desk(rng);
    let chair = if office_chair {
        models::office_chair(rng)
    } else {
        models::chair(rng)
    };
    let dz = desk.d * 0.5;
    let cz = -0.05 - chair.d * 0.5;
    let x = rng.random_range(-0.15f32..0.15) * desk.w;
    // The chair faces the desk (+Z).
    Group {
        items: vec![Item::at(desk, 0.0, dz, 0.0), Item::at(chair, x, cz, PI)],
        mode: Mode::Wall,
    }
}

/// Kitchen run along one wall: fridge, counters, stove, maybe a dishwasher.
fn kitchen_run(rng: &mut ChaCha8Rng, target: f32) -> Group {
    let fridge = models::fridge(rng);
    let stove = models::stove(rng);
    let dish = if target > 3.0 && rng.random_bool(0.6) {
        Some(models::dishwasher(rng))
    } else {
        None
    };
    let fixed = fridge.w + stove.w + dish.as_ref().map_or(0.0, |d| d.w);
    let rest = (target - fixed).max(0.6);
    let (c1, c2) = if rest > 1.2 {
        let a = rng.random_range(0.4f32..0.6) * rest;
        (a, rest - a)
    } else {
        (rest, 0.0)
    };
    let mut seq = vec![fridge, models::counter(rng, c1), stove];
    if c2 > 0.3 {
        seq.push(models::counter(rng, c2));
    }
    if let Some(d) = dish {
        seq.push(d);
    }
    if rng.random_bool(0.5) {
        seq.reverse();
    }
    let mut items = Vec::with_capacity(seq.len());
    let mut x = 0.0;
    for m in seq {
        let (w, d) = (m.w, m.d);
        let mut it = Item::at(m, x + w * 0.5, -d * 0.5, 0.0);
        it.bare = it.model.class == C::Dishwasher;
        items.push(it);
        x += w + 0.005;
    }
    // Backs flush: align every item's back to z = 0.
    Group {
        items,
        mode: Mode::Wall,
    }
}

/// A bathroom sink with a mirror on the wall above it.
fn sink_group(rng: &mut ChaCha8Rng) -> Group {
    let sink = models::sink(rng);
    let mirror = models::clutter(C::Mirror, rng);
    let back = (sink.d - mirror.d) * 0.5;
    let mut items = vec![Item::at(sink, 0.0, 0.0, 0.0)];
    if mirror.w <= items[0].model.w {
        items.push(Item::at(mirror, 0.0, back, 0.0));
    }
    Group {
        items,
        mode: Mode::Wall,
    }
}

/// A vanity (dressing table) with a mirror above it and a stool in front.
fn vanity_group(rng: &mut ChaCha8Rng) -> Group {
    let vanity = models::clutter(C::Vanity, rng);
    let mirror = models::clutter(C::Mirror, rng);
    let stool = models::stool(rng);
    let (vd, md) = (vanity.d, mirror.d);
    let mut items = vec![Item::at(vanity, 0.0, 0.0, 0.0)];
    if mirror.w <= items[0].model.w {
        items.push(Item::at(mirror, 0.0, (vd - md) * 0.5, 0.0));
    }
    if rng.random_bool(0.6) {
        let z = -vd * 0.5 - 0.05 - stool.d * 0.5;
        items.push(Item::at(stool, 0.0, z, 0.0));
    }
    Group {
        items,
        mode: Mode::Wall,
    }
}

/// A small outdoor table with one to three chairs around it.
fn patio_group(rng: &mut ChaCha8Rng, chairs: usize) -> Group {
    let table = models::clutter(C::PatioTable, rng);
    let chair = models::clutter(C::PatioChair, rng);
    let off = table.w * 0.5 + 0.05 + chair.d * 0.5;
    let mut items = vec![Item::at(table, 0.0, 0.0, 0.0)];
    // Chairs face the table: on the left, right and front sides.
    for (x, z, yaw) in [
        (-off, 0.0, -FRAC_PI_2),
        (off, 0.0, FRAC_PI_2),
        (0.0, -off, PI),
    ]
    .into_iter()
    .take(chairs)
    {
        items.push(Item::at(chair.clone(), x, z, yaw));
    }
    Group {
        items,
        mode: Mode::Wall,
    }
}

/// A projector screen on the wall and, `dist` metres in front of it, a row of `seats`
/// recliners facing it, with a side table between neighbours when `tables`. The gap between
/// the screen and the row stays part of the group's footprint, so nothing else stands in it.
fn theater_group(rng: &mut ChaCha8Rng, seats: usize, dist: f32, tables: bool) -> Group {
    let screen = models::clutter(C::ProjectorScreen, rng);
    let chair = pieces::model(C::Recliner, 0.0, rng);
    let table = models::side_table(rng);
    let z = -(screen.d * 0.5 + dist + chair.d * 0.5);
    let between = if tables { table.w + 0.1 } else { 0.1 };
    let row = seats as f32 * chair.w + (seats.max(1) - 1) as f32 * between;
    let mut items = vec![Item::at(screen, 0.0, 0.0, 0.0)];
    let mut x = -row * 0.5 + chair.w * 0.5;
    for k in 0..seats {
        // Turned round: the seat's front faces the screen at +Z.
        items.push(Item::at(chair.clone(), x, z, PI));
        if tables && k + 1 < seats {
            let tx = x + chair.w * 0.5 + between * 0.5;
            items.push(Item::at(table.clone(), tx, z, 0.0));
        }
        x += chair.w + between;
    }
    Group {
        items,
        mode: Mode::Wall,
    }
}

fn wall(m: Model) -> Group {
    Group::one(m, Mode::Wall)
}

fn corner(m: Model) -> Group {
    Group::one(m, Mode::Corner)
}

/// Candidate groups of a room, most important first; each entry lists fall-back variants.
fn recipe(
    cfg: &ProcgenConfig,
    kind: RoomType,
    interior: Rect,
    has_kitchen: bool,
    rng: &mut ChaCha8Rng,
) -> Vec<Vec<Group>> {
    let long = interior.w().max(interior.d());
    let area = interior.area();
    let mut out: Vec<Vec<Group>> = Vec::new();
    match kind {
        RoomType::LivingRoom => {
            let arm = maybe(cfg, rng, 0.5);
            out.push(vec![
                sofa_group(rng, long - 0.4, arm),
                sofa_group(rng, long - 0.4, false),
                wall(models::sofa(rng, 1.5)),
            ]);
            if !has_kitchen {
                // A home without a kitchen gets a kitchenette in the living room.
                let mut compact = kitchen_run(rng, 1.9);
                compact.items.retain(|it| it.model.class != C::Fridge);
                out.push(vec![kitchen_run(rng, 2.4), kitchen_run(rng, 1.9), compact]);
            }
            if maybe(cfg, rng, 0.9) {
                out.push(vec![tv_group(rng)]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(models::bookshelf(rng))]);
            }
            if maybe(cfg, rng, 0.1) {
                out.push(vec![wall(models::piano(rng))]);
            }
            if maybe(cfg, rng, 0.2) {
                out.push(vec![wall(models::clutter(C::Fireplace, rng))]);
            }
            if maybe(cfg, rng, 0.08) {
                out.push(vec![wall(models::clutter(C::Aquarium, rng))]);
            }
            for (p, f) in [
                (0.6, models::potted_plant as fn(&mut ChaCha8Rng) -> Model),
                (0.5, models::floor_lamp),
                (0.4, models::side_table),
                (0.3, models::cabinet),
            ] {
                if maybe(cfg, rng, p) {
                    let m = f(rng);
                    out.push(vec![corner(m)]);
                }
            }
        }
        RoomType::Kitchen => {
            let target = (long - 0.3).min(rng.random_range(2.4f32..4.2));
            let mut compact = kitchen_run(rng, 1.9);
            compact.items.retain(|it| it.model.class != C::Fridge);
            out.push(vec![
                kitchen_run(rng, target),
                kitchen_run(rng, target * 0.75),
                kitchen_run(rng, 1.9),
                compact,
            ]);
            // Only used when the kitchen run above had to leave its fridge out.
            out.push(vec![corner(models::fridge(rng))]);
            if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(models::kitchen_cabinet(rng))]);
            }
            if area > 11.0 && maybe(cfg, rng, 0.5) {
                out.push(vec![dining_group(rng, 1, false, false, false)]);
            } else if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(models::stool(rng))]);
            }
            if maybe(cfg, rng, 0.3) {
                let w = rng.random_range(0.8f32..1.4);
                out.push(vec![wall(models::counter(rng, w))]);
            }
            if maybe(cfg, rng, 0.6) {
                out.push(vec![corner(models::trash_can(rng))]);
            }
            if maybe(cfg, rng, 0.3) {
                out.push(vec![corner(models::potted_plant(rng))]);
            }
        }
        RoomType::DiningRoom => {
            let rug = maybe(cfg, rng, 0.35);
            let (e3, e2) = (rng.random_bool(0.4), rng.random_bool(0.5));
            out.push(vec![
                dining_group(rng, 3, e3, rug, false),
                dining_group(rng, 2, e2, false, false),
                dining_group(rng, 2, false, false, false),
                dining_group(rng, 1, false, false, false),
                dining_group(rng, 2, true, false, true),
                dining_group(rng, 1, false, false, true),
            ]);
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::cabinet(rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![corner(models::potted_plant(rng))]);
            }
            if maybe(cfg, rng, 0.25) {
                out.push(vec![corner(models::floor_lamp(rng))]);
            }
        }
        RoomType::Bedroom => {
            let double = area > 11.0 && rng.random_bool(0.75);
            out.push(vec![
                bed_group(rng, double, 2),
                bed_group(rng, double, 1),
                bed_group(rng, false, 1),
                bed_group(rng, false, 0),
                Group {
                    mode: Mode::Center,
                    ..bed_group(rng, false, 0)
                },
            ]);
            if maybe(cfg, rng, 0.8) {
                out.push(vec![wall(models::wardrobe(rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(models::dresser(rng))]);
            }
            if maybe(cfg, rng, 0.25) {
                let office = rng.random_bool(0.5);
                out.push(vec![desk_group(rng, office)]);
            }
            if maybe(cfg, rng, 0.2) {
                out.push(vec![vanity_group(rng)]);
            }
            if maybe(cfg, rng, 0.25) {
                out.push(vec![wall(models::clutter(C::Chest, rng))]);
            }
            if maybe(cfg, rng, 0.06) {
                out.push(vec![wall(models::clutter(C::Crib, rng))]);
            }
            for (p, f) in [
                (0.3, models::potted_plant as fn(&mut ChaCha8Rng) -> Model),
                (0.25, models::floor_lamp),
                (0.15, models::armchair),
            ] {
                if maybe(cfg, rng, p) {
                    let m = f(rng);
                    out.push(vec![corner(m)]);
                }
            }
        }
        RoomType::Bathroom => {
            out.push(vec![wall(models::toilet(rng))]);
            out.push(vec![sink_group(rng), wall(models::sink(rng))]);
            if maybe(cfg, rng, 0.55) {
                out.push(vec![
                    corner(models::bathtub(rng)),
                    corner(models::shower(rng)),
                ]);
            } else if maybe(cfg, rng, 0.6) {
                out.push(vec![corner(models::shower(rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::cabinet(rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![corner(models::trash_can(rng))]);
            }
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::clutter(C::TowelRack, rng))]);
            }
        }
        RoomType::Office => {
            out.push(vec![desk_group(rng, true), desk_group(rng, false)]);
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::clutter(C::FilingCabinet, rng))]);
            }
            if maybe(cfg, rng, 0.8) {
                out.push(vec![wall(models::bookshelf(rng))]);
            }
            if maybe(cfg, rng, 0.35) {
                out.push(vec![wall(models::bookshelf(rng))]);
            }
            for (p, f) in [
                (0.4, models::potted_plant as fn(&mut ChaCha8Rng) -> Model),
                (0.3, models::floor_lamp),
                (0.35, models::cabinet),
                (0.2, models::armchair),
                (0.5, models::trash_can),
            ] {
                if maybe(cfg, rng, p) {
                    let m = f(rng);
                    out.push(vec![corner(m)]);
                }
            }
        }
        RoomType::Hallway => {
            for (p, f) in [
                (0.6, models::shoe_rack as fn(&mut ChaCha8Rng) -> Model),
                (0.45, models::coat_rack),
                (0.35, models::bench),
                (0.35, models::potted_plant),
                (0.3, models::side_table),
            ] {
                if maybe(cfg, rng, p) {
                    let m = f(rng);
                    out.push(vec![wall(m)]);
                }
            }
            if maybe(cfg, rng, 0.4) {
                let (w, d) = (rng.random_range(0.7f32..1.0), rng.random_range(1.4f32..2.2));
                let r = models::rug(rng, w, d);
                out.push(vec![Group::one(r, Mode::Center)]);
            }
        }
        RoomType::LaundryRoom => {
            out.push(vec![wall(models::washing_machine(rng))]);
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::clutter(C::IroningBoard, rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::clutter(C::DryingRack, rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(models::clutter(C::ShelvingUnit, rng))]);
            }
            if maybe(cfg, rng, 0.45) {
                out.push(vec![wall(models::washing_machine(rng))]);
            }
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::cabinet(rng))]);
            }
            if maybe(cfg, rng, 0.3) {
                out.push(vec![corner(models::trash_can(rng))]);
            }
        }
        RoomType::Closet => {
            out.push(vec![
                wall(models::clutter(C::ClothesRail, rng)),
                wall(models::wardrobe(rng)),
            ]);
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::shoe_rack(rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::clutter(C::ShelvingUnit, rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(models::clutter(C::Chest, rng))]);
            }
            if maybe(cfg, rng, 0.3) {
                out.push(vec![wall(models::dresser(rng))]);
            }
        }
        RoomType::EntranceHall => {
            out.push(vec![wall(models::shoe_rack(rng)), wall(models::bench(rng))]);
            if maybe(cfg, rng, 0.7) {
                out.push(vec![corner(models::coat_rack(rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::side_table(rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(models::clutter(C::Mirror, rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![corner(models::potted_plant(rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                let (w, d) = (rng.random_range(0.8f32..1.2), rng.random_range(1.0f32..1.6));
                let r = models::rug(rng, w, d);
                out.push(vec![Group::one(r, Mode::Center)]);
            }
        }
        RoomType::Balcony => {
            // A narrow balcony keeps a walkway: a third chair only on a large one.
            let chairs = rng.random_range(1..=if area > 8.0 { 3 } else { 2 });
            out.push(vec![
                patio_group(rng, chairs),
                patio_group(rng, 1),
                wall(models::clutter(C::PatioChair, rng)),
            ]);
            out.push(vec![wall(models::clutter(C::Planter, rng))]);
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::clutter(C::Planter, rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![corner(models::potted_plant(rng))]);
            }
        }
        RoomType::Gym => {
            out.push(vec![
                wall(models::clutter(C::Treadmill, rng)),
                wall(models::clutter(C::ExerciseBike, rng)),
            ]);
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::clutter(C::ExerciseBike, rng))]);
            }
            if maybe(cfg, rng, 0.8) {
                let bench = models::clutter(C::WeightBench, rng);
                out.push(vec![wall(bench.clone()), Group::one(bench, Mode::Center)]);
            }
            if maybe(cfg, rng, 0.6) {
                out.push(vec![corner(models::clutter(C::PunchingBag, rng))]);
            }
            for (p, class) in [
                (0.7, C::YogaMat),
                (0.6, C::Dumbbells),
                (0.5, C::Mirror),
                (0.3, C::YogaMat),
            ] {
                if maybe(cfg, rng, p) {
                    out.push(vec![wall(models::clutter(class, rng))]);
                }
            }
            for (p, f) in [
                (0.3, models::potted_plant as fn(&mut ChaCha8Rng) -> Model),
                (0.3, models::trash_can),
            ] {
                if maybe(cfg, rng, p) {
                    let m = f(rng);
                    out.push(vec![corner(m)]);
                }
            }
        }
        RoomType::Pantry => {
            out.push(vec![
                wall(models::clutter(C::ShelvingUnit, rng)),
                wall(models::kitchen_cabinet(rng)),
            ]);
            if maybe(cfg, rng, 0.8) {
                out.push(vec![wall(models::clutter(C::ShelvingUnit, rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(models::clutter(C::ShelvingUnit, rng))]);
            }
            if maybe(cfg, rng, 0.3) {
                out.push(vec![wall(models::kitchen_cabinet(rng))]);
            }
            if maybe(cfg, rng, 0.3) {
                out.push(vec![corner(models::stool(rng))]);
            }
        }
        RoomType::HomeTheater => {
            let seats = if area > 16.0 { 3 } else { 2 };
            out.push(vec![
                theater_group(rng, seats, 2.4, true),
                theater_group(rng, 2, 2.2, true),
                theater_group(rng, 2, 1.8, false),
                theater_group(rng, 1, 1.6, false),
                wall(models::clutter(C::ProjectorScreen, rng)),
            ]);
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::cabinet(rng))]);
            }
            if maybe(cfg, rng, 0.2) {
                out.push(vec![wall(models::bookshelf(rng))]);
            }
            for (p, f) in [
                (0.3, models::floor_lamp as fn(&mut ChaCha8Rng) -> Model),
                (0.3, models::potted_plant),
            ] {
                if maybe(cfg, rng, p) {
                    let m = f(rng);
                    out.push(vec![corner(m)]);
                }
            }
        }
        RoomType::Library => {
            out.push(vec![wall(models::bookshelf(rng))]);
            for p in [0.9, 0.8, 0.6, 0.4] {
                if maybe(cfg, rng, p) {
                    out.push(vec![wall(models::bookshelf(rng))]);
                }
            }
            out.push(vec![corner(models::armchair(rng))]);
            if maybe(cfg, rng, 0.7) {
                out.push(vec![corner(models::floor_lamp(rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::side_table(rng))]);
            }
            if maybe(cfg, rng, 0.3) {
                out.push(vec![corner(models::armchair(rng))]);
            }
            if maybe(cfg, rng, 0.35) {
                out.push(vec![desk_group(rng, false)]);
            }
            if maybe(cfg, rng, 0.4) {
                let (w, d) = (rng.random_range(1.2f32..2.0), rng.random_range(1.0f32..1.6));
                let r = models::rug(rng, w, d);
                out.push(vec![Group::one(r, Mode::Center)]);
            }
        }
        RoomType::Porch => {
            // A small table and a chair; the swing or hammock comes with the pieces.
            out.push(vec![
                patio_group(rng, 1),
                wall(models::clutter(C::PatioChair, rng)),
            ]);
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::clutter(C::Planter, rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![corner(models::potted_plant(rng))]);
            }
        }
        RoomType::Sauna => {
            // Wooden benches along two walls and the heater in a corner.
            out.push(vec![wall(models::bench(rng))]);
            out.push(vec![corner(models::clutter(C::Heater, rng))]);
            out.push(vec![wall(models::bench(rng))]);
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::clutter(C::TowelRack, rng))]);
            }
        }
        RoomType::Spa => {
            // A hot tub first in a large spa (it needs a wall of its own), then the massage
            // table, free in the room when there is room to walk round it.
            if area >= 10.0 && maybe(cfg, rng, 0.6) {
                let tub = pieces::model(C::HotTub, 0.0, rng);
                out.push(vec![corner(tub.clone()), wall(tub)]);
            }
            let table = pieces::model(C::MassageTable, 0.0, rng);
            out.push(vec![Group::one(table.clone(), Mode::Center), wall(table)]);
            out.push(vec![wall(models::clutter(C::TowelRack, rng))]);
            if maybe(cfg, rng, 0.7) {
                out.push(vec![wall(models::cabinet(rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![corner(models::stool(rng))]);
            }
            if maybe(cfg, rng, 0.6) {
                out.push(vec![corner(models::potted_plant(rng))]);
            }
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::side_table(rng))]);
            }
        }
        RoomType::WineCellar => {
            // Racks of bottles along the walls and barrels in the corners; a bar with stools
            // comes with the pieces and sets.
            out.push(vec![wall(pieces::model(C::WineRack, 0.0, rng))]);
            out.push(vec![wall(pieces::model(C::WineRack, 0.0, rng))]);
            if maybe(cfg, rng, 0.4) {
                out.push(vec![wall(pieces::model(C::WineRack, 0.0, rng))]);
            }
            out.push(vec![corner(pieces::model(C::Barrel, 0.0, rng))]);
            if maybe(cfg, rng, 0.5) {
                out.push(vec![corner(pieces::model(C::Barrel, 0.0, rng))]);
            }
            if maybe(cfg, rng, 0.7) {
                out.push(vec![wall(models::side_table(rng))]);
            }
        }
        RoomType::Playroom => {
            out.push(vec![corner(pieces::model(C::Dollhouse, 0.0, rng))]);
            out.push(vec![corner(pieces::model(C::RockingHorse, 0.0, rng))]);
            // A small desk to draw at.
            out.push(vec![desk_group(rng, false)]);
            out.push(vec![corner(models::clutter(C::BeanBag, rng))]);
            if maybe(cfg, rng, 0.5) {
                out.push(vec![corner(models::clutter(C::BeanBag, rng))]);
            }
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::clutter(C::Chest, rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::clutter(C::ShelvingUnit, rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                let (w, d) = (rng.random_range(1.2f32..2.0), rng.random_range(1.0f32..1.6));
                let r = models::rug(rng, w, d);
                out.push(vec![Group::one(r, Mode::Center)]);
            }
        }
        RoomType::MudRoom => {
            // Where coats, bags and boots come off: lockers or hooks, a bench, shoes.
            out.push(vec![
                wall(pieces::model(C::Lockers, 0.0, rng)),
                wall(models::coat_rack(rng)),
            ]);
            out.push(vec![wall(models::bench(rng))]);
            // A small room: the rest only now and then, so a door still swings in it.
            if maybe(cfg, rng, 0.6) {
                out.push(vec![wall(models::shoe_rack(rng))]);
            }
            if maybe(cfg, rng, 0.3) {
                out.push(vec![corner(models::coat_rack(rng))]);
            }
        }
        RoomType::Workshop => {
            out.push(vec![wall(models::clutter(C::Workbench, rng))]);
            out.push(vec![wall(models::clutter(C::ShelvingUnit, rng))]);
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::clutter(C::Workbench, rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![wall(models::clutter(C::ShelvingUnit, rng))]);
            }
            if maybe(cfg, rng, 0.6) {
                out.push(vec![corner(models::stool(rng))]);
            }
            if maybe(cfg, rng, 0.4) {
                out.push(vec![corner(models::trash_can(rng))]);
            }
        }
        RoomType::Garage => {
            let car = models::clutter(C::Car, rng);
            out.push(vec![wall(car.clone()), Group::one(car, Mode::Center)]);
            if maybe(cfg, rng, 0.8) {
                out.push(vec![wall(models::clutter(C::Workbench, rng))]);
            }
            if maybe(cfg, rng, 0.7) {
                out.push(vec![wall(models::clutter(C::ShelvingUnit, rng))]);
            }
            if maybe(cfg, rng, 0.5) {
                out.push(vec![corner(models::trash_can(rng))]);
            }
        }
        _ => {
            for (p, f) in [
                (0.6, models::cabinet as fn(&mut ChaCha8Rng) -> Model),
                (0.5, models::potted_plant),
                (0.4, models::bookshelf),
                (0.3, models::floor_lamp),
            ] {
                if maybe(cfg, rng, p) {
                    let m = f(rng);
                    out.push(vec![wall(m)]);
                }
            }
        }
    }
    out
}

/// Floor and wall clutter of a room, placed after its furniture (ProcTHOR's separate floor
/// and wall stages): each entry is a class, its chance (times `furniture.clutter`) and where it
/// goes. Pieces stand against a wall or in a corner, so they keep the room's free space one
/// island and the doorways clear like any furniture (the same placement checks).
fn clutter_recipe(cfg: &ProcgenConfig, kind: RoomType, rng: &mut ChaCha8Rng) -> Vec<Vec<Group>> {
    use RoomType as R;
    const W: Mode = Mode::Wall;
    const K: Mode = Mode::Corner;
    let list: &[(C, f32, Mode)] = match kind {
        R::LivingRoom => &[
            (C::WallShelf, 0.6, W),
            (C::Radiator, 0.35, W),
            (C::Ottoman, 0.4, W),
            (C::BeanBag, 0.2, K),
            (C::DogBed, 0.2, K),
            (C::Fan, 0.12, K),
            (C::Heater, 0.1, K),
            (C::Box, 0.25, K),
            (C::Treadmill, 0.05, W),
            (C::ShelvingUnit, 0.15, W),
            (C::WallShelf, 0.4, W),
            (C::WallShelf, 0.3, W),
        ],
        R::Kitchen => &[
            (C::WallShelf, 0.5, W),
            (C::WallShelf, 0.3, W),
            (C::HighChair, 0.12, W),
            (C::Radiator, 0.25, W),
            (C::DogBed, 0.1, K),
            (C::ShelvingUnit, 0.2, W),
        ],
        R::DiningRoom => &[
            (C::WallShelf, 0.4, W),
            (C::WallShelf, 0.3, W),
            (C::Radiator, 0.35, W),
            (C::HighChair, 0.15, W),
            (C::Aquarium, 0.05, W),
            (C::ShelvingUnit, 0.15, W),
        ],
        R::Bedroom => &[
            (C::WallShelf, 0.5, W),
            (C::WallShelf, 0.3, W),
            (C::LaundryBasket, 0.5, K),
            (C::Slippers, 0.45, W),
            (C::Shoes, 0.25, W),
            (C::Backpack, 0.3, W),
            (C::Radiator, 0.3, W),
            (C::Ottoman, 0.1, W),
            (C::BeanBag, 0.1, K),
            (C::YogaMat, 0.1, W),
            (C::Dumbbells, 0.1, W),
            (C::ExerciseBike, 0.05, W),
            (C::Fan, 0.1, K),
            (C::Heater, 0.08, K),
            (C::ClothesRail, 0.08, W),
            (C::Box, 0.25, K),
            (C::Ottoman, 0.15, W),
            (C::ShelvingUnit, 0.1, W),
        ],
        R::Bathroom => &[
            (C::WallShelf, 0.55, W),
            (C::LaundryBasket, 0.3, K),
            (C::Radiator, 0.25, W),
            (C::Slippers, 0.15, W),
        ],
        R::Office => &[
            (C::WallShelf, 0.6, W),
            (C::WallShelf, 0.4, W),
            (C::Backpack, 0.3, W),
            (C::Box, 0.35, K),
            (C::Radiator, 0.3, W),
            (C::ShelvingUnit, 0.2, W),
            (C::Fan, 0.15, K),
            (C::Heater, 0.1, K),
            (C::ExerciseBike, 0.06, W),
            (C::Treadmill, 0.04, W),
            (C::YogaMat, 0.08, W),
        ],
        R::Hallway => &[
            (C::Shoes, 0.5, W),
            (C::UmbrellaStand, 0.35, K),
            (C::Mirror, 0.3, W),
            (C::Radiator, 0.2, W),
            (C::Backpack, 0.2, W),
            (C::WallShelf, 0.25, W),
            (C::Bicycle, 0.06, W),
            (C::Box, 0.2, K),
        ],
        R::EntranceHall => &[
            (C::Shoes, 0.7, W),
            (C::Shoes, 0.4, W),
            (C::UmbrellaStand, 0.5, K),
            (C::Backpack, 0.3, W),
            (C::Slippers, 0.3, W),
            (C::WallShelf, 0.35, W),
            (C::Radiator, 0.25, W),
            (C::Bicycle, 0.1, W),
        ],
        R::LaundryRoom => &[
            (C::LaundryBasket, 0.7, K),
            (C::Box, 0.3, K),
            (C::WallShelf, 0.4, W),
            (C::LaundryBasket, 0.25, K),
        ],
        R::Closet => &[
            (C::Shoes, 0.6, W),
            (C::Box, 0.5, K),
            (C::LaundryBasket, 0.4, K),
            (C::WallShelf, 0.4, W),
            (C::Mirror, 0.3, W),
            (C::Slippers, 0.3, W),
        ],
        R::Balcony => &[(C::DryingRack, 0.3, W), (C::Bicycle, 0.1, W)],
        R::Gym => &[
            (C::WallShelf, 0.3, W),
            (C::Dumbbells, 0.4, W),
            (C::Fan, 0.3, K),
            (C::Backpack, 0.2, W),
            (C::Radiator, 0.2, W),
        ],
        R::Pantry => &[
            (C::WallShelf, 0.5, W),
            (C::WallShelf, 0.3, W),
            (C::Box, 0.4, K),
            (C::Box, 0.3, K),
        ],
        R::HomeTheater => &[
            (C::WallShelf, 0.3, W),
            (C::BeanBag, 0.3, K),
            (C::Ottoman, 0.2, W),
            (C::Radiator, 0.2, W),
            (C::Box, 0.1, K),
        ],
        R::Porch => &[(C::Shoes, 0.3, W), (C::UmbrellaStand, 0.3, K)],
        R::Sauna => &[],
        R::Spa => &[(C::LaundryBasket, 0.3, K), (C::WallShelf, 0.4, W)],
        R::WineCellar => &[(C::Box, 0.3, K), (C::WallShelf, 0.3, W)],
        R::Playroom => &[
            (C::Box, 0.4, K),
            (C::BeanBag, 0.2, K),
            (C::Backpack, 0.2, W),
            (C::WallShelf, 0.3, W),
        ],
        R::MudRoom => &[
            (C::Shoes, 0.8, W),
            (C::Shoes, 0.5, W),
            (C::UmbrellaStand, 0.5, K),
            (C::Backpack, 0.4, W),
            (C::Slippers, 0.2, W),
            (C::WallShelf, 0.3, W),
        ],
        R::Workshop => &[
            (C::Box, 0.5, K),
            (C::Box, 0.3, K),
            (C::WallShelf, 0.4, W),
            (C::Bicycle, 0.1, W),
        ],
        R::Garage => &[
            (C::Box, 0.5, K),
            (C::Box, 0.3, K),
            (C::Bicycle, 0.3, W),
            (C::WallShelf, 0.3, W),
        ],
        R::Library => &[
            (C::WallShelf, 0.4, W),
            (C::Ottoman, 0.3, W),
            (C::Radiator, 0.25, W),
            (C::Box, 0.2, K),
        ],
        _ => &[(C::WallShelf, 0.3, W), (C::Box, 0.2, K)],
    };
    let mut out = Vec::new();
    for &(class, p, mode) in list {
        let p = (p * cfg.furniture.clutter).clamp(0.0, 1.0);
        if rng.random_bool(p as f64) {
            out.push(vec![Group::one(models::clutter(class, rng), mode)]);
        }
    }
    out
}

/// Small objects that fit on a support, by support class and room.
fn small_choices(support: C, room: RoomType) -> &'static [C] {
    match (support, room) {
        (C::WallShelf | C::Cabinet | C::SideTable, RoomType::Spa) => &[
            C::Towel,
            C::Towel,
            C::Candle,
            C::Bottle,
            C::SoapDispenser,
            C::SmallPlant,
        ],
        (C::WallShelf | C::SideTable | C::Box, RoomType::WineCellar) => {
            &[C::Bottle, C::Bottle, C::Cup, C::Candle, C::Bowl]
        }
        (C::WallShelf | C::ShelvingUnit | C::Chest | C::Box, RoomType::Playroom) => {
            &[C::Toy, C::Toy, C::BoardGame, C::Book, C::Basket]
        }
        (C::WallShelf | C::ShelvingUnit, RoomType::Workshop) => &[C::Basket, C::Bottle, C::Pot],
        (C::Nightstand, _) => &[
            C::TableLamp,
            C::Book,
            C::Clock,
            C::Cup,
            C::SmallPlant,
            C::Candle,
            C::Phone,
            C::TissueBox,
            C::Tablet,
        ],
        (C::Dresser, _) => &[
            C::Vase,
            C::PictureFrame,
            C::Candle,
            C::Clock,
            C::TableLamp,
            C::Book,
            C::SmallPlant,
            C::JewelryBox,
            C::Basket,
        ],
        (C::Counter, _) => &[
            C::Toaster,
            C::Kettle,
            C::Microwave,
            C::Bowl,
            C::Plate,
            C::Cup,
            C::Mug,
            C::Bottle,
            C::FruitBowl,
            C::Teapot,
            C::Pot,
            C::Pan,
            C::CuttingBoard,
            C::CoffeeMachine,
            C::Blender,
            C::DishRack,
            C::Jar,
        ],
        (C::CoffeeTable, _) => &[
            C::Remote,
            C::Book,
            C::Vase,
            C::Bowl,
            C::Candle,
            C::Cup,
            C::Mug,
            C::SmallPlant,
            C::Magazine,
            C::TissueBox,
            C::BoardGame,
            C::FruitBowl,
            C::Phone,
            C::Tablet,
            C::Toy,
        ],
        (C::DiningTable, _) => &[
            C::Plate,
            C::Bowl,
            C::Vase,
            C::Cup,
            C::Bottle,
            C::Candle,
            C::FruitBowl,
            C::Teapot,
        ],
        (C::ShelvingUnit | C::WallShelf, RoomType::Garage) => &[C::Basket, C::Bottle, C::Pot],
        (C::SideTable | C::Cabinet, RoomType::HomeTheater) => &[
            C::Projector,
            C::Remote,
            C::Speaker,
            C::Bowl,
            C::Cup,
            C::Bottle,
        ],
        (C::ShelvingUnit | C::WallShelf | C::KitchenCabinet | C::Box, RoomType::Pantry) => &[
            C::Jar,
            C::Jar,
            C::Jar,
            C::Bottle,
            C::Basket,
            C::Bowl,
            C::Pot,
        ],
        (C::SideTable, _) => &[
            C::TableLamp,
            C::Vase,
            C::Book,
            C::SmallPlant,
            C::Clock,
            C::Phone,
            C::Magazine,
            C::TissueBox,
        ],
        (C::Desk, _) => &[
            C::Laptop,
            C::Mug,
            C::Book,
            C::TableLamp,
            C::Cup,
            C::Phone,
            C::PenHolder,
            C::Printer,
            C::Headphones,
            C::Globe,
            C::Speaker,
            C::Tablet,
        ],
        (C::Cabinet, RoomType::Bathroom | RoomType::LaundryRoom) => &[
            C::Towel,
            C::SoapDispenser,
            C::Bottle,
            C::ToiletPaper,
            C::Shampoo,
            C::ToothbrushHolder,
            C::Hairdryer,
            C::Basket,
        ],
        (C::Cabinet, _) => &[
            C::Vase,
            C::Book,
            C::Bowl,
            C::SmallPlant,
            C::PictureFrame,
            C::Clock,
            C::Speaker,
            C::Basket,
            C::BoardGame,
            C::Globe,
            C::Toy,
        ],
        (C::WashingMachine | C::Dryer, _) => &[C::Towel, C::Bottle, C::Basket],
        (C::KitchenIsland, _) => &[
            C::FruitBowl,
            C::Bowl,
            C::CuttingBoard,
            C::Mug,
            C::Plate,
            C::Bottle,
            C::SmallPlant,
        ],
        (C::Buffet, _) => &[
            C::Vase,
            C::TableLamp,
            C::FruitBowl,
            C::Candle,
            C::Bowl,
            C::SmallPlant,
            C::Bottle,
        ],
        (C::ConsoleTable, _) => &[
            C::Vase,
            C::TableLamp,
            C::Bowl,
            C::PictureFrame,
            C::Clock,
            C::SmallPlant,
            C::Basket,
            C::Candle,
        ],
        (C::ShoeRack, _) => &[C::SmallPlant, C::Vase, C::Basket],
        (C::Vanity, _) => &[
            C::JewelryBox,
            C::Hairdryer,
            C::TissueBox,
            C::Candle,
            C::PictureFrame,
            C::Vase,
            C::Bottle,
        ],
        (C::Chest, _) => &[C::Basket, C::Book, C::Toy, C::BoardGame, C::Pillow],
        (C::FilingCabinet, _) => &[C::Printer, C::PenHolder, C::Globe, C::Book, C::SmallPlant],
        (C::WallShelf, RoomType::Bathroom) => &[
            C::Towel,
            C::Shampoo,
            C::ToiletPaper,
            C::SoapDispenser,
            C::Candle,
        ],
        (C::WallShelf, RoomType::Kitchen) => {
            &[C::Bowl, C::Plate, C::Mug, C::Teapot, C::Bottle, C::Jar]
        }
        (C::WallShelf, _) => &[
            C::Book,
            C::Vase,
            C::SmallPlant,
            C::PictureFrame,
            C::Clock,
            C::Candle,
            C::Toy,
            C::Speaker,
            C::Globe,
        ],
        (C::Fireplace, _) => &[C::Candle, C::Clock, C::PictureFrame, C::Vase],
        (C::Ottoman, _) => &[C::Magazine, C::Book, C::Tablet],
        (C::PatioTable, _) => &[
            C::Cup,
            C::Mug,
            C::Bottle,
            C::Candle,
            C::SmallPlant,
            C::Phone,
        ],
        (C::ShelvingUnit, RoomType::LaundryRoom | RoomType::Closet) => {
            &[C::Basket, C::Towel, C::Bottle]
        }
        (C::ShelvingUnit, RoomType::Kitchen | RoomType::DiningRoom) => &[
            C::Bowl,
            C::Plate,
            C::Teapot,
            C::Bottle,
            C::Basket,
            C::FruitBowl,
        ],
        (C::ShelvingUnit, _) => &[C::Basket, C::Book, C::Toy, C::BoardGame, C::Speaker],
        (C::Box, _) => &[C::Book, C::Magazine, C::Toy],
        (C::Bookshelf, _) => &[
            C::Basket,
            C::Vase,
            C::SmallPlant,
            C::Globe,
            C::Clock,
            C::Speaker,
            C::Toy,
            C::BoardGame,
            C::PictureFrame,
        ],
        _ => &[],
    }
}

/// Put up to `n` small objects on the top of `support`.
fn add_smalls(
    cfg: &ProcgenConfig,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
    room: RoomId,
    kind: RoomType,
    support: &Model,
    pose: &Pose,
    support_id: ObjectId,
) {
    let Some(top) = support.top else {
        return;
    };
    let fc = &cfg.furniture;
    if fc.small_objects_max == 0 || !rng.random_bool(fc.small_object_probability as f64) {
        return;
    }
    let choices = small_choices(support.class, kind);
    if choices.is_empty() {
        return;
    }
    let mut taken: Vec<Rect> = Vec::new();
    let mut want: Vec<C> = Vec::new();
    if support.class == C::Desk && rng.random_bool(0.5) {
        want.extend([C::Monitor, C::Keyboard]);
    }
    // At least half the most: a surface that has things on it rarely has just one.
    let lo = (fc.small_objects_max / 2).max(1);
    let n = rng.random_range(lo..=fc.small_objects_max);
    while want.len() < n.max(want.len()) {
        if let Some(&c) = choices.choose(rng) {
            want.push(c);
        }
    }
    for class in want {
        let m = models::small(class, rng);
        let q = rng.random_range(0..4);
        // Screens and lamps face the front of the support.
        let q = if matches!(
            class,
            C::Monitor | C::Keyboard | C::Laptop | C::PictureFrame | C::Clock
        ) {
            0
        } else {
            q
        };
        let (w, d) = if q % 2 == 1 { (m.d, m.w) } else { (m.w, m.d) };
        if w > top.w() || d > top.d() {
            continue;
        }
        for _ in 0..SMALL_TRIES {
            let x = rng.random_range(top.x0 + w * 0.5..=top.x1 - w * 0.5);
            let z = rng.random_range(top.z0 + d * 0.5..=top.z1 - d * 0.5);
            let r = Rect::centered(x, z, w, d);
            if taken.iter().any(|t| t.overlaps(&r, -0.02)) {
                continue;
            }
            taken.push(r);
            let local = Pose::from_yaw(Vec3::new(x, support.h, z), q as f32 * FRAC_PI_2);
            let world = pose.mul(&local);
            // Keep the pose yaw-only and exactly on the support top.
            let mut p = world.translation();
            p.y = pose.position[1] + support.h;
            let pose = Pose::from_yaw(p, world.yaw());
            b.add_model(&m, room, pose, Some(support_id));
            break;
        }
    }
}

/// Furnish every room of a plan.
pub(crate) fn furnish(cfg: &ProcgenConfig, plan: &Plan, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let t = cfg.walls.thickness;
    let has_kitchen = plan.rooms.iter().any(|r| r.kind == RoomType::Kitchen);
    for (i, room) in plan.rooms.iter().enumerate() {
        furnish_room(cfg, plan, i, room, t, has_kitchen, rng, b);
    }
}

fn furnish_room(
    cfg: &ProcgenConfig,
    plan: &Plan,
    i: usize,
    room: &PlanRoom,
    t: f32,
    has_kitchen: bool,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) {
    if room.bare {
        return;
    }
    let interior = room.rect.inset(t * 0.5);
    let mut keepout = Vec::new();
    let mut seeds = Vec::new();
    for o in plan.openings.iter().filter(|o| o.rooms.contains(&i)) {
        keepout.push(clearance_rect(o, cfg, cfg.doors.clearance + 0.05, 0.1));
        let (x, z) = o.position();
        let (cx, cz) = room.rect.center();
        // Approach point inside this room, far enough from the wall (and from furniture kept
        // out of the clearance box) that its grid cell is free whatever the cell rounding.
        let inside = t * 0.5 + cfg.furniture.nav_radius + NAV_CELL;
        let (sx, sz) = if o.along_z {
            (x + (cx - x).signum() * inside, z)
        } else {
            (x, z + (cz - z).signum() * inside)
        };
        seeds.push((sx, sz));
    }
    let mut st = RoomState {
        cfg,
        id: i as RoomId,
        interior,
        keepout,
        placed: Vec::new(),
        grid: NavGrid::new(interior, NAV_CELL, cfg.furniture.nav_radius),
        seeds,
        min_free: (FURNITURE_MIN_FREE * interior.area() / (NAV_CELL * NAV_CELL)) as usize,
    };
    if !st.grid.connected(&st.seeds) {
        tracing::debug!(
            room = i,
            "room free space is not connected before furnishing"
        );
        return;
    }
    let mut has_fridge = false;
    let groups = recipe(cfg, room.kind, interior, has_kitchen, rng);
    let main = groups.len();
    let mut groups = groups;
    groups.extend(clutter_recipe(cfg, room.kind, rng));
    for (g, variants) in groups.into_iter().enumerate() {
        if g == main {
            // Clutter also keeps off the wall beside each framed doorway, where its door leaf
            // swings open (`doors.rs`), so that the leaf does not close a pocket off.
            for o in plan
                .openings
                .iter()
                .filter(|o| o.rooms.contains(&i) && !o.open_plan)
            {
                let swing = clearance_rect(o, cfg, cfg.doors.clearance + 0.05, CLUTTER_SWING);
                st.keepout.push(swing);
            }
            st.min_free = (CLUTTER_MIN_FREE * interior.area() / (NAV_CELL * NAV_CELL)) as usize;
        }
        for mut g in variants {
            let fridge = g.items.iter().any(|it| it.model.class == C::Fridge);
            if fridge && has_fridge {
                break;
            }
            if !add_group(&mut st, &mut g, room.kind, rng, b) {
                continue;
            }
            has_fridge |= fridge;
            break;
        }
    }
    if cfg.furniture.pieces > 0.0 {
        add_pieces(&mut st, plan, room.kind, rng, b);
    }
    if cfg.furniture.sets > 0.0 {
        crate::sets::add_sets(&mut st, room.kind, rng, b);
    }
    if cfg.furniture.pieces > 0.0 {
        add_more_things(&mut st, room.kind, rng, b);
        add_household(&mut st, room.kind, rng, b);
    }
    tracing::trace!(room = i, free = st.grid.free_cells(), "room furnished");
}

/// Place group `g` in the room and add it and the small objects on its tops to the home;
/// false when it found no place.
fn add_group(
    st: &mut RoomState,
    g: &mut Group,
    kind: RoomType,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) -> bool {
    let Some(placed) = st.place(g, rng) else {
        return false;
    };
    let mut ids: Vec<ObjectId> = Vec::with_capacity(placed.len());
    for p in &placed {
        let support = p.on.map(|k| ids[k]);
        let id = b.add_model(&p.model, st.id, p.pose, support);
        ids.push(id);
    }
    for (p, &id) in placed.iter().zip(&ids) {
        if !p.bare {
            add_smalls(st.cfg, rng, b, st.id, kind, &p.model, &p.pose, id);
        }
    }
    true
}

/// The room's feature pieces ([`pieces`]), drawn from an rng of their own seeded by the home's
/// stream and the room, so that the main stream, and every room furnished after this one, is
/// the same with or without them.
fn add_pieces(st: &mut RoomState, plan: &Plan, kind: RoomType, rng: &ChaCha8Rng, b: &mut Builder) {
    let salt = u64::from(st.id).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    let mut own = ChaCha8Rng::seed_from_u64(crate::tones::stream_hash(rng) ^ salt);
    let area = st.interior.area();
    // The underside of the ceiling slab (`decor.rs` hangs it from the top of the walls).
    let ceiling = st.cfg.walls.height - 0.03;
    for piece in pieces::pieces(kind) {
        let chance = (piece.chance * st.cfg.furniture.pieces).clamp(0.0, 1.0);
        if area < piece.min_area || !own.random_bool(f64::from(chance)) {
            continue;
        }
        let m = pieces::model(piece.class, ceiling, &mut own);
        if piece.class == C::Chandelier {
            hang_over_table(st, m, ceiling, b);
            continue;
        }
        let mode = match piece.spot {
            Spot::Wall => Mode::Wall,
            Spot::Corner => Mode::Corner,
            Spot::Centre => Mode::Center,
        };
        add_group(st, &mut Group::one(m, mode), kind, &mut own, b);
    }
    lay_doormats(st, plan, &mut own, b);
    if kind == RoomType::Hallway {
        lay_runner(st, &mut own, b);
    }
}

/// The room's second lot of things ([`more_things`]), placed last (after the sets) from an rng
/// of their own seeded by the home's stream and the room, so that nothing placed before moves.
fn add_more_things(st: &mut RoomState, kind: RoomType, rng: &ChaCha8Rng, b: &mut Builder) {
    use crate::room_things::{things, Lot, Spot as S};
    let salt = u64::from(st.id).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ more_things::SALT;
    let mut own = ChaCha8Rng::seed_from_u64(crate::tones::stream_hash(rng) ^ salt);
    let area = st.interior.area();
    let ceiling = st.cfg.walls.height - 0.03;
    for thing in things(Lot::Second, kind) {
        let mut chance = thing.chance;
        if thing.class == C::Saxophone && room_has(st, b, &more_things::INSTRUMENTS) {
            chance = more_things::SAX_WITH_INSTRUMENTS;
        }
        let chance = (chance * st.cfg.furniture.pieces).clamp(0.0, 1.0);
        if area < thing.min_area || !own.random_bool(f64::from(chance)) {
            continue;
        }
        let Some(m) = more_things::model(thing.class, &mut own) else {
            continue;
        };
        let mode = match thing.spot {
            S::Wall => Mode::Wall,
            S::Corner => Mode::Corner,
            S::Centre => Mode::Center,
            S::Ceiling => {
                if st.cfg.walls.ceiling {
                    hang_fan(st, m, ceiling, &mut own, b);
                }
                continue;
            }
            S::OnTop => {
                stand_on_top(st, m, &more_things::CANDELABRA_ON, b);
                continue;
            }
        };
        add_group(st, &mut Group::one(m, mode), kind, &mut own, b);
    }
}

/// The room's third lot of standing things ([`household`]), placed after the second from an
/// rng of their own, so that nothing placed before moves.
fn add_household(st: &mut RoomState, kind: RoomType, rng: &ChaCha8Rng, b: &mut Builder) {
    use crate::room_things::{things, Lot, Spot as S};
    let salt = u64::from(st.id).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ household::SALT;
    let mut own = ChaCha8Rng::seed_from_u64(crate::tones::stream_hash(rng) ^ salt);
    let area = st.interior.area();
    for thing in things(Lot::Third, kind) {
        let chance = household::chance(thing, kind, |c| room_has(st, b, c));
        let chance = (chance * st.cfg.furniture.pieces).clamp(0.0, 1.0);
        if area < thing.min_area || !own.random_bool(f64::from(chance)) {
            continue;
        }
        let Some(m) = household::model(thing.class, 0.0, &mut own) else {
            continue;
        };
        let mode = match thing.spot {
            S::Wall => Mode::Wall,
            S::Corner => Mode::Corner,
            S::OnTop => {
                household::stand_on(st.id, &m, household::supports(thing.class), b);
                continue;
            }
            // The file's check keeps the third lot off the ceiling and out of the room's middle.
            S::Centre | S::Ceiling => continue,
        };
        add_group(st, &mut Group::one(m, mode), kind, &mut own, b);
    }
}

/// Whether the room already holds an object of one of `classes`.
fn room_has(st: &RoomState, b: &Builder, classes: &[C]) -> bool {
    b.objects
        .iter()
        .any(|o| o.room == Some(st.id) && classes.contains(&o.class))
}

/// Longest room side (m) above which the light bake hangs two lamps, at the quarter points of
/// the long axis, instead of one in the middle (`vlnverse_env::light::lamps`); a margin either
/// side of it where a fan is left out rather than risk a panel under its blades.
const TWO_LAMPS: f32 = 4.5;
const TWO_LAMPS_MARGIN: f32 = 0.1;
/// Least gap (m) between a fan's blades and the walls, and between them and the approach
/// point inside each doorway.
const FAN_WALL_GAP: f32 = 0.3;
const FAN_DOOR_GAP: f32 = 1.3;
/// Half the side of a lamp's ceiling panel (`decor.rs`) and a gap, kept clear of fan blades.
const PANEL_CLEAR: f32 = 0.25;

/// Hang a ceiling fan `m` (built from its bottom up) with its top at the ceiling: in the
/// middle of a room with two lamps, else along the long axis clear of the one lamp's panel;
/// left out where its blades would reach a wall or anything tall stands under them.
fn hang_fan(st: &RoomState, m: Model, ceiling: f32, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let ir = st.interior;
    let (cx, cz) = ir.center();
    let long = ir.w().max(ir.d());
    let reach = m.w.max(m.d) * 0.5;
    let off = if long > TWO_LAMPS + TWO_LAMPS_MARGIN {
        0.0
    } else if long < TWO_LAMPS - TWO_LAMPS_MARGIN {
        reach + PANEL_CLEAR
    } else {
        return;
    };
    let side = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
    let bottom = ceiling - m.h;
    let spot = [side, -side].into_iter().find_map(|sd| {
        let (x, z) = if ir.w() >= ir.d() {
            (cx + sd * off, cz)
        } else {
            (cx, cz + sd * off)
        };
        let foot = Rect::centered(x, z, reach * 2.0, reach * 2.0);
        // Clear of the walls by more than curtains and sconces stand out from them, and of
        // the doorways by more than a door leaf swings (the leaves' checks count what
        // hangs above them as standing on the floor).
        let clear = ir.inset(FAN_WALL_GAP).contains_rect(&foot, 0.0)
            && st
                .seeds
                .iter()
                .all(|&(sx, sz)| foot.distance(sx, sz) >= FAN_DOOR_GAP);
        let under = b.objects.iter().any(|o| {
            o.room == Some(st.id)
                && o.bbox.max[1] > bottom - 0.1
                && foot.overlaps(&bbox_rect(&o.bbox), 0.0)
                && !o.class.is_structure()
        });
        (clear && !under).then_some((x, z))
    });
    let Some((x, z)) = spot else {
        return;
    };
    let pose = Pose {
        position: [x, bottom, z],
        rotation: Quat::from_rotation_y(rng.random_range(0.0..FRAC_PI_2)).to_array(),
    };
    b.add_model(&m, st.id, pose, None);
}

/// An object's floor footprint.
fn bbox_rect(bb: &vlnverse_env::Aabb) -> Rect {
    Rect {
        x0: bb.min[0],
        x1: bb.max[0],
        z0: bb.min[2],
        z1: bb.max[2],
    }
}

/// Stand `m` on the top of the first object of the room of one of `on` (in that order) that
/// has a clear spot for it: its middle, or most of the way to either end; turned along its
/// long side.
fn stand_on_top(st: &RoomState, m: Model, on: &[C], b: &mut Builder) {
    for class in on {
        let Some(sup) = b
            .objects
            .iter()
            .find(|o| o.room == Some(st.id) && o.class == *class)
        else {
            continue;
        };
        let top = sup.bbox.max[1];
        let r = bbox_rect(&sup.bbox);
        let (cx, cz) = r.center();
        let along_x = r.w() >= r.d();
        let (long, across) = if along_x {
            (r.w(), r.d())
        } else {
            (r.d(), r.w())
        };
        if long < m.w + 0.1 || across < m.d + 0.1 {
            continue;
        }
        for t in [0.0, -0.6, 0.6] {
            let off = t * (long - m.w - 0.06) * 0.5;
            let (x, z) = if along_x {
                (cx + off, cz)
            } else {
                (cx, cz + off)
            };
            let (fw, fd) = if along_x { (m.w, m.d) } else { (m.d, m.w) };
            let foot = Rect::centered(x, z, fw + 0.06, fd + 0.06);
            if !r.contains_rect(&foot, 0.0) {
                continue;
            }
            let taken = b.objects.iter().any(|o| {
                o.id != sup.id
                    && !o.class.is_structure()
                    && o.bbox.max[1] > top + 0.005
                    && o.bbox.min[1] < top + m.h
                    && foot.overlaps(&bbox_rect(&o.bbox), 0.0)
            });
            if taken {
                continue;
            }
            let yaw = if along_x { 0.0 } else { FRAC_PI_2 };
            let pose = Pose::from_yaw(Vec3::new(x, top, z), yaw);
            let id = sup.id;
            b.add_model(&m, st.id, pose, Some(id));
            return;
        }
    }
}

/// Chance that a doorway from the house to a porch or a garage has a doormat on the house side.
const DOORMAT_CHANCE: f64 = 0.85;
/// Chance that a long hallway has a runner down its middle.
const RUNNER_CHANCE: f64 = 0.7;
/// Least length (m) of a hallway's floor that gets a runner.
const RUNNER_MIN_HALL: f32 = 3.2;

/// A doormat on this room's side of each framed doorway to a porch or a garage (the doors
/// people come in by), across the doorway against the wall. It is flat, so it blocks nothing.
fn lay_doormats(st: &RoomState, plan: &Plan, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let me = st.id as usize;
    let outdoorsy = |k: RoomType| matches!(k, RoomType::Porch | RoomType::Garage);
    if outdoorsy(plan.rooms[me].kind) {
        return;
    }
    for o in plan.openings.iter().filter(|o| o.rooms.contains(&me)) {
        let other = if o.rooms[0] == me {
            o.rooms[1]
        } else {
            o.rooms[0]
        };
        if o.open_plan || !outdoorsy(plan.rooms[other].kind) || !rng.random_bool(DOORMAT_CHANCE) {
            continue;
        }
        let m = crate::things::doormat(rng, o.width);
        let (x, z) = o.position();
        let (cx, cz) = st.interior.center();
        let off = m.d * 0.5 + 0.03;
        let (px, pz, yaw) = if o.along_z {
            let face = if cx > x {
                st.interior.x0
            } else {
                st.interior.x1
            };
            (face + (cx - x).signum() * off, z, FRAC_PI_2)
        } else {
            let face = if cz > z {
                st.interior.z0
            } else {
                st.interior.z1
            };
            (x, face + (cz - z).signum() * off, 0.0)
        };
        let pose = Pose {
            position: [px, 0.0, pz],
            rotation: Quat::from_rotation_y(yaw).to_array(),
        };
        b.add_model(&m, st.id, pose, None);
    }
}

/// A runner down the middle of a long hallway, clear of everything already on its floor
/// (narrowed where a piece of furniture stands out from a wall, left out where even a narrow
/// one would run under something). It is flat, so it blocks nothing; what is placed after it
/// (the second lot of things) keeps off it.
fn lay_runner(st: &mut RoomState, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let (w, d) = (st.interior.w(), st.interior.d());
    let (len, across) = (w.max(d), w.min(d));
    if len < RUNNER_MIN_HALL || !rng.random_bool(RUNNER_CHANCE) {
        return;
    }
    let (cx, cz) = st.interior.center();
    let length = len - 0.8;
    let taken: Vec<Rect> = b
        .objects
        .iter()
        .filter(|o| o.room == Some(st.id) && !o.class.is_structure())
        .map(|o| Rect {
            x0: o.bbox.min[0],
            x1: o.bbox.max[0],
            z0: o.bbox.min[2],
            z1: o.bbox.max[2],
        })
        .collect();
    let along_x = w >= d;
    let widest = (across * 0.5).clamp(0.6, 0.9);
    for width in [widest, 0.6] {
        let foot = if along_x {
            Rect::centered(cx, cz, length, width)
        } else {
            Rect::centered(cx, cz, width, length)
        };
        if width > across - 0.3 || taken.iter().any(|t| t.overlaps(&foot, 0.0)) {
            continue;
        }
        let m = crate::things::runner(rng, length, width);
        let yaw = if along_x { 0.0 } else { FRAC_PI_2 };
        let pose = Pose {
            position: [cx, 0.0, cz],
            rotation: Quat::from_rotation_y(yaw).to_array(),
        };
        b.add_model(&m, st.id, pose, None);
        st.keepout.push(foot);
        return;
    }
}

/// Hang `m` from the ceiling over the middle of the room's dining table, if it has one. It
/// hangs above the agent's height, so it takes no floor.
fn hang_over_table(st: &RoomState, m: Model, ceiling: f32, b: &mut Builder) {
    let Some(table) = b
        .objects
        .iter()
        .rev()
        .find(|o| o.class == C::DiningTable && o.room == Some(st.id))
    else {
        return;
    };
    let (x, z) = (
        (table.bbox.min[0] + table.bbox.max[0]) * 0.5,
        (table.bbox.min[2] + table.bbox.max[2]) * 0.5,
    );
    let pose = Pose {
        position: [x, ceiling - m.h, z],
        rotation: [0.0, 0.0, 0.0, 1.0],
    };
    b.add_model(&m, st.id, pose, None);
}
