//! The agent on the ground of a multi-level scene ([`PhysicsScene::follows_ground`]): it steps
//! up onto what is at most `max_step_height` above its feet (a tread, the upper floor's slab),
//! steps down likewise, walks slopes up to `max_slope_deg` and falls where nothing is under it
//! (a stairwell). Nothing here knows about stairs: the ground is whatever the physics world's
//! floors and solids offer under the agent's footprint, so imported multi-level scenes climb
//! their own flights. Single-level scenes never come here (the planar agent, unchanged).

use super::{RapierSimulator, MIN_MOVE};
use crate::simulator::StepOutcome;
use crate::world::{standable, STAND_QUERY, STEP_QUERY};
use glam::Vec3;
use rapier3d::parry::query::ShapeCastOptions;
use rapier3d::prelude::*;
use std::sync::Arc;
use vlnverse_env::ObjectId;

/// Longest horizontal move between two looks at the ground (m): shorter than any tread, so
/// one sub-move meets at most one riser.
const CLIMB_STEP: f32 = 0.1;
/// Height differences below this are none (m); ground this close to a level's floor is that
/// floor, exactly.
const FLAT: f32 = 1e-3;
/// A contact whose normal is less upward than this (its y) is the side of something, not
/// ground, unless a ray finds ground under it.
const GRAZE: f32 = 0.05;
/// How far below the scene's lowest point a fall is looked for (m).
const FALL_MARGIN: f32 = 1.0;

/// How a piece of a move along the ground ended.
enum Piece {
    /// Nothing moved, or a riser too high, a slope too steep or a top it may not stand on
    /// stopped it.
    Stopped,
    /// It moved; `blocked` when something it slid along was in the way.
    Moved { blocked: bool },
}

/// A velocity command as both drives run it ([`RapierSimulator::accelerate`] each tick): the
/// target speed and turn rate (clamped), the physics ticks, their length and the largest change
/// of speed and turn rate per tick.
pub(super) struct Drive {
    pub v: f32,
    pub omega: f32,
    pub ticks: u32,
    pub dt: f32,
    pub lin_acc: f32,
    pub ang_acc: f32,
}

/// The surface the agent stands on.
struct Ground {
    /// Its height under the footprint (the agent's feet).
    y: f32,
    /// The collider it belongs to.
    handle: ColliderHandle,
    /// Whether the agent may stand on it: a floor or a step (not a wall's top, not furniture)
    /// whose slope at the contact is within its `max_slope_deg`.
    walkable: bool,
}

impl RapierSimulator {
    /// Whether the current world makes the agent follow the ground (a multi-level scene).
    pub(super) fn follows_ground(&self) -> bool {
        self.scene.as_ref().is_some_and(|s| s.follows_ground())
    }

    /// How far the shape is raised for a move that may step up: its bottom then clears
    /// everything lower than `max_step_height` above the feet.
    fn lift(&self) -> f32 {
        (self.cfg.agent.max_step_height - self.cfg.agent.ground_clearance).max(0.0)
    }

    /// The highest floor or solid under the agent's footprint, its feet at `base` raised by
    /// `lift` (a shape cast straight down, as deep as the scene goes).
    fn ground_under(&self, base: Vec3, lift: f32) -> Option<Ground> {
        let (s, w) = (self.scene.as_ref()?, self.world.as_ref()?);
        let qp = w.query(
            QueryFilter::default()
                .exclude_rigid_body(s.agent_body)
                .groups(STAND_QUERY),
        );
        let from = base + Vec3::Y * lift;
        let bottom = from.y + self.cfg.agent.ground_clearance;
        let depth = bottom - (s.min_y - FALL_MARGIN);
        if depth <= 0.0 {
            return None;
        }
        let (handle, hit) = qp.cast_shape(
            &self.shape_pose(from, self.quat()),
            Vec3::NEG_Y,
            s.agent_shape.as_ref(),
            ShapeCastOptions {
                target_distance: 0.0,
                stop_at_penetration: false,
                max_time_of_impact: depth,
                compute_impact_geometry_on_penetration: true,
            },
        )?;
        let mut y = bottom - hit.time_of_impact;
        if let Some(f) = s.levels.iter().find(|f| (y - **f).abs() < FLAT) {
            y = *f;
        }
        let cos_max = self.cfg.agent.max_slope_deg.to_radians().cos();
        // The surface under the contact point, by a ray: a shape touching a tread's edge
        // reports a slanted normal, and one grazing a wall's face a level one at any depth.
        let under = || {
            let p = hit.witness1;
            let ray = Ray::new(Vec3::new(p.x, y + 0.05, p.z), Vec3::NEG_Y);
            qp.cast_ray_and_get_normal(&ray, 0.1, true)
                .map(|(_, r)| r.normal.y)
        };
        if hit.normal1.y < GRAZE && under().is_none_or(|n| n < GRAZE) {
            return None;
        }
        let walkable = hit.normal1.y >= cos_max || under().is_some_and(|n| n >= cos_max);
        let standable = w
            .colliders
            .get(handle)
            .is_some_and(|c| standable(c.collision_groups()));
        Some(Ground {
            y,
            handle,
            walkable: walkable && standable,
        })
    }

    /// Feet height for an agent put at `p`: the ground under it if that is within a step of
    /// `p.y` (so a start on a tread or a hair off the floor stands on it), else `p.y`.
    pub(super) fn stand_height(&self, p: Vec3) -> f32 {
        let step = self.cfg.agent.max_step_height;
        match self.ground_under(p, self.lift()) {
            Some(g) if g.walkable && (g.y - p.y).abs() <= step + FLAT => g.y,
            _ => p.y,
        }
    }

    /// [`Self::slide_move`] following the ground: the move is cut into sub-moves of at most
    /// [`CLIMB_STEP`]; each slides with the shape raised by [`Self::lift`] (so a low step does
    /// not stop it) and then drops onto the ground under it. A step higher than
    /// `max_step_height`, a slope steeper than `max_slope_deg` or a top that is not a floor or
    /// a step (a wall's, a piece of furniture's) stops the move there (hit, as a wall would); a
    /// drop of any depth onto a floor or a step is a fall.
    pub(super) fn climb_move(&mut self, desired: Vec3) -> (Vec3, Vec<ObjectId>) {
        let flat = Vec3::new(desired.x, 0.0, desired.z);
        let n = (flat.length() / CLIMB_STEP).ceil().max(1.0);
        let part = flat / n;
        let start = self.state.base;
        let mut handles = Vec::new();
        for _ in 0..n as usize {
            match self.ground_piece(part, &mut handles) {
                Piece::Stopped => break,
                Piece::Moved { blocked } if blocked && !self.cfg.agent.allow_sliding => break,
                Piece::Moved { .. } => {}
            }
        }
        let hits = self.ids(handles);
        self.state.speed = 0.0;
        self.state.omega = 0.0;
        self.sync_body(Vec3::ZERO);
        (self.state.base - start, hits)
    }

    /// One piece (at most [`CLIMB_STEP`]) of a move along the ground: slide with the shape
    /// raised by [`Self::lift`], then stand on the ground under it. What stopped or touched the
    /// agent goes to `handles`.
    fn ground_piece(&mut self, part: Vec3, handles: &mut Vec<ColliderHandle>) -> Piece {
        let base = self.state.base;
        let max_step = self.cfg.agent.max_step_height;
        let mut lift = self.lift();
        // No room overhead to raise the shape: no step up from here.
        if lift > 0.0 && !self.overlaps(base + Vec3::Y * lift).is_empty() {
            lift = 0.0;
        }
        let (moved, hits) = self.slide_cast(base + Vec3::Y * lift, part, STAND_QUERY);
        let blocked = !hits.is_empty();
        handles.extend(hits);
        if moved.length() < MIN_MOVE {
            return Piece::Stopped;
        }
        let Some(g) = self.ground_under(base + moved, lift) else {
            // Nothing under it at all (off the scene): keep the height.
            self.state.base = base + moved;
            return Piece::Moved { blocked: false };
        };
        let up = g.y - base.y;
        if !g.walkable || up > max_step + FLAT {
            handles.push(g.handle);
            return Piece::Stopped;
        }
        let next = Vec3::new(base.x + moved.x, g.y, base.z + moved.z);
        // Standing up on the step may put the head into what hangs over it (a slab's edge
        // over a flight): no room, no step.
        if up > FLAT && !self.overlaps(next).is_empty() {
            handles.push(g.handle);
            return Piece::Stopped;
        }
        self.state.base = next;
        Piece::Moved { blocked }
    }

    /// One physics tick of a velocity command: turn rate and speed move towards the command
    /// by at most the tick's change, and the heading turns by the new rate.
    pub(super) fn accelerate(&mut self, cmd: &Drive) {
        self.state.omega += (cmd.omega - self.state.omega).clamp(-cmd.ang_acc, cmd.ang_acc);
        self.state.yaw = super::wrap(self.state.yaw + (self.state.omega * cmd.dt) as f64);
        self.state.speed += (cmd.v - self.state.speed).clamp(-cmd.lin_acc, cmd.lin_acc);
    }

    /// Velocity control following the ground: the speed and turn rate change within the
    /// agent's accelerations as in the rigid-body drive, and each physics tick's displacement
    /// is moved along the ground ([`Self::ground_piece`]), so the agent walks up a flight, steps
    /// onto what is within a step and falls where the floor ends. Something in the way takes
    /// the speed down to what was achieved.
    pub(super) fn drive_on_ground(&mut self, cmd: Drive, out: &mut StepOutcome) {
        let start = self.state.base;
        let (mut commanded, mut handles) = (Vec3::ZERO, Vec::new());
        for _ in 0..cmd.ticks {
            self.accelerate(&cmd);
            let desired = self.forward() * self.state.speed * cmd.dt;
            commanded += desired;
            if desired.length() < MIN_MOVE {
                continue;
            }
            let before = self.state.base;
            let piece = self.ground_piece(desired, &mut handles);
            if !matches!(piece, Piece::Moved { blocked: false }) {
                let moved = self.state.base - before;
                let along = Vec3::new(moved.x, 0.0, moved.z).dot(self.forward());
                self.state.speed = along / cmd.dt;
            }
            if matches!(piece, Piece::Moved { blocked: true }) && !self.cfg.agent.allow_sliding {
                self.state.speed = 0.0;
            }
        }
        self.sync_body(self.forward() * self.state.speed);
        out.commanded = [commanded.x, commanded.z];
        out.achieved = [self.state.base.x - start.x, self.state.base.z - start.z];
        out.hit = self.ids(handles);
        out.collided = !out.hit.is_empty();
    }

    /// The feet height a walk straight from `start` to `(target.x, target.z)` would reach,
    /// obstacles aside: the ground under the line, looked at every [`CLIMB_STEP`] with a ray
    /// down, followed where it is within a step of the height so far (up a flight, down a
    /// flight, over rugs and thresholds) and ignored elsewhere (walls, holes). This is how a
    /// Tel-Hop waypoint, which names a floor point `(x, z)`, picks its level.
    fn walk_height(&self, start: Vec3, target: Vec3) -> f32 {
        let (Some(s), Some(w)) = (self.scene.as_ref(), self.world.as_ref()) else {
            return start.y;
        };
        let qp = w.query(
            QueryFilter::default()
                .exclude_rigid_body(s.agent_body)
                .groups(STEP_QUERY),
        );
        let step = self.cfg.agent.max_step_height;
        let d = Vec3::new(target.x - start.x, 0.0, target.z - start.z);
        let n = (d.length() / CLIMB_STEP).ceil().max(1.0);
        let mut y = start.y;
        for i in 1..=n as usize {
            let p = start + d * (i as f32 / n);
            let top = y + step + FLAT;
            let ray = Ray::new(Vec3::new(p.x, top, p.z), Vec3::NEG_Y);
            if let Some((_, toi)) = qp.cast_ray(&ray, 2.0 * step + 2.0 * FLAT, true) {
                if toi > 0.0 {
                    y = top - toi;
                }
            }
        }
        s.levels
            .iter()
            .find(|f| (y - **f).abs() < FLAT)
            .copied()
            .unwrap_or(y)
    }

    /// [`Self::hop`] following the ground: the landing height is [`Self::walk_height`]'s;
    /// each candidate spot of the search stands on the ground under its footprint, within a
    /// step of that height (no landing in a stairwell); closed doors on the start's level and
    /// the landing's bound the hop.
    pub(super) fn hop_on_ground(&mut self, target: Vec3, out: &mut StepOutcome) {
        let start = self.state.base;
        out.commanded = [target.x - start.x, target.z - start.z];
        let y = self.walk_height(start, target);
        let step = self.cfg.agent.max_step_height;
        let lift = self.lift();
        let stand = |p: Vec3| -> Option<Vec3> {
            let g = self.ground_under(Vec3::new(p.x, y, p.z), lift)?;
            (g.walkable && (g.y - y).abs() <= step + FLAT).then(|| Vec3::new(p.x, g.y, p.z))
        };
        let at_target = stand(target).map(|p| self.overlaps(p)).unwrap_or_default();
        out.collided = !at_target.is_empty();
        out.hit = at_target;
        let offsets = Arc::clone(&self.hop_offsets);
        let Some(scene) = self.scene.clone() else {
            return;
        };
        let from_level = scene.level_at(start.y);
        let mut behind = None;
        let landed = offsets
            .iter()
            .map(|o| target + Vec3::new(o.x, 0.0, o.y))
            .filter_map(&stand)
            .find(|p| {
                if !self.overlaps(*p).is_empty() {
                    return false;
                }
                let on = [from_level, scene.level_at(p.y)];
                match scene.closed_door_between_on([start.x, start.z], [p.x, p.z], &on) {
                    Some(d) => {
                        behind.get_or_insert(d);
                        false
                    }
                    None => true,
                }
            });
        // The shift is measured across the floor: landing on a step is no shift.
        let landed = landed.map(|p| (p, Vec3::new(p.x - target.x, 0.0, p.z - target.z).length()));
        self.settle_hop(landed, behind, start, out);
    }
}
