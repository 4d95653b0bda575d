//! `semantic`: a non-learned baseline for the coarse-grained, visual-reference and dialogue
//! tasks. It reads the target class from the instruction text (words of the
//! [`SemanticClass`] vocabulary, plus a few synonyms) and never the ground-truth goal or target
//! id. It looks around once, builds its own top-down map from depth (0.1 m cells: unknown /
//! free / occupied, obstacles inflated by the agent radius), explores frontiers (the best one by
//! path length, turning and hints, kept until explored), groups what the semantic camera labels
//! as the target class into sightings (one per object, roughly), walks to the chosen sighting
//! and stops next to it.
//!
//! - Dialogue: it asks "where is the TARGET?" once at the start and keeps the answer (side and
//!   distance) as a hint that ranks frontiers and sightings; it asks "which way?" when the map
//!   stops growing, when nothing is left to explore or when a sighting turned out wrong, walks
//!   the legs of the answer and takes their end as the new hint; before stopping (and at the end
//!   of a complete answer) it asks "am I close?" and gives up a sighting the oracle calls far.
//!   One question is kept in reserve for that last check.
//! - Visual reference: it keeps the colour histogram of the middle of the reference image and
//!   compares it with the colours under each sighting's semantic mask (its own RGB camera at the
//!   semantic camera's pose); it looks all around before stopping, skips poorly matching
//!   sightings until most steps are spent, and prefers a clearly better match to the nearest.
//!
//! Everything is deterministic. In the continuous action space the same decisions are carried
//! out with velocity commands ([`super::control::VelocityController`]).

use std::collections::VecDeque;

use glam::Vec2;
use vlnverse_env::SemanticClass;
use vlnverse_sensors::{CameraSpec, Frame, Observation, SensorSpec};
use vlnverse_sim::{Action, AgentConfig};

use super::control::VelocityController;
use super::cues::{self, ColourHistogram};
use super::{floor_point, wrap_angle, yaw_towards};
use crate::agent::{Agent, EpisodeInputs, OracleHandle, StepInput};
use crate::error::Result;
use crate::protocol::ActionSpace;

/// Name of the semantic camera the agent attaches.
pub const SEMANTIC_SENSOR: &str = "semantic_agent_semantic";
/// Name of the depth camera the agent attaches (same pose, so both come from one view).
pub const DEPTH_SENSOR: &str = "semantic_agent_depth";
/// Name of the RGB camera the agent attaches (same pose; visual reference only reads it).
pub const RGB_SENSOR: &str = "semantic_agent_rgb";

const RES: f32 = 0.1;
const SIZE: i32 = 600;
const UNKNOWN: u8 = 0;
const FREE: u8 = 1;
const OCCUPIED: u8 = 2;
/// Stop this close (m) to the seen target.
const STOP_NEAR: f32 = 1.2;
/// Walk to a free cell within this distance (m) of a sighting's centre.
const APPROACH_RADIUS: f32 = 2.5;
/// Target pixels within this distance (m) of a sighting's centre belong to it.
const SIGHTING_RADIUS: f32 = 1.5;
/// Frontier score: metres of path one radian of turning is worth.
const TURN_COST: f32 = 1.0;
/// Frontier score: weight of the distance (m) between a frontier and the dialogue hint.
const HINT_WEIGHT: f32 = 1.0;
/// Steps a frontier is pursued before it is chosen afresh.
const COMMIT_STEPS: u32 = 40;
/// Dialogue: exploration has stalled when the map grew by fewer than `STALL_CELLS` cells in
/// `STALL_STEPS` steps.
const STALL_STEPS: u32 = 25;
const STALL_CELLS: u32 = 30;
/// Dialogue: with no plausible sighting by this share of the step limit, ask "which way".
const LATE_SHARE: f32 = 0.4;
/// Steps spent walking toward one point of a "which way" route.
const ROUTE_STEPS: u32 = 30;
/// Visual reference: a sighting is preferred to the nearest one when its colour match is this
/// much better.
const MATCH_MARGIN: f32 = 0.1;
/// Visual reference: the least colour match of a sighting worth walking to.
const MATCH_MIN: f32 = 0.25;
/// Visual reference: after this share of the step limit any sighting will do.
const MATCH_LATE_SHARE: f32 = 0.75;
/// Visual reference: target pixels a view needs before its colours count.
const MATCH_PIXELS: usize = 12;

/// Words that name a class differently from its vocabulary name.
const SYNONYMS: &[(&str, SemanticClass)] = &[
    ("couch", SemanticClass::Sofa),
    ("refrigerator", SemanticClass::Fridge),
    ("television", SemanticClass::Tv),
    ("plant", SemanticClass::PottedPlant),
    ("lamp", SemanticClass::FloorLamp),
    ("bookcase", SemanticClass::Bookshelf),
    ("oven", SemanticClass::Stove),
    ("bathtub", SemanticClass::Bathtub),
    ("tub", SemanticClass::Bathtub),
    ("nightstand", SemanticClass::Nightstand),
    ("night stand", SemanticClass::Nightstand),
    ("wardrobe", SemanticClass::Wardrobe),
    ("closet", SemanticClass::Wardrobe),
    ("bin", SemanticClass::TrashCan),
    ("painting", SemanticClass::PictureFrame),
    ("picture", SemanticClass::PictureFrame),
];

/// The target class an instruction names: the class phrase that occurs first in the text
/// (longest phrase on ties; plural `s` accepted). Structure classes are not targets.
pub fn parse_target_class(text: &str) -> Option<SemanticClass> {
    let words: Vec<String> = text
        .to_lowercase()
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_string)
        .collect();
    let mut phrases: Vec<(Vec<String>, SemanticClass)> = SemanticClass::ALL
        .iter()
        .filter(|c| !c.is_structure() && **c != SemanticClass::Unknown)
        .map(|c| (c.words().split(' ').map(str::to_string).collect(), *c))
        .collect();
    phrases.extend(
        SYNONYMS
            .iter()
            .map(|(w, c)| (w.split(' ').map(str::to_string).collect(), *c)),
    );
    let matches_at = |i: usize, p: &[String]| {
        p.len() <= words.len() - i
            && p.iter().enumerate().all(|(k, w)| {
                let t = &words[i + k];
                t == w || (k + 1 == p.len() && (*t == format!("{w}s") || *t == format!("{w}es")))
            })
    };
    for i in 0..words.len() {
        let best = phrases
            .iter()
            .filter(|(p, _)| matches_at(i, p))
            .max_by_key(|(p, c)| (p.len(), std::cmp::Reverse(c.id())));
        if let Some((_, c)) = best {
            return Some(*c);
        }
    }
    None
}

/// One object of the target class as the agent has seen it (target pixels grouped by place).
#[derive(Debug, Clone)]
struct Sighting {
    /// Mean of its target points.
    centre: Vec2,
    /// Points folded into the mean.
    points: u32,
    /// Its target point nearest to the agent in the latest view that saw it.
    near: Vec2,
    /// Visual reference: colour match of the view with the most target pixels, and that count.
    matched: Option<(f32, usize)>,
    /// Given up (the dialogue oracle said the goal is far from it).
    rejected: bool,
}

/// Cells reached from the agent's cell: path length (cells) and parent.
struct Flood {
    dist: Vec<u32>,
    parent: Vec<u32>,
    /// Whether the inflation around obstacles was ignored (only occupied cells block).
    relaxed: bool,
}

impl Flood {
    fn reached(&self, i: usize) -> bool {
        self.dist[i] != u32::MAX
    }
}

/// The frontier-exploring, semantic-camera agent.
pub struct SemanticAgent {
    agent: AgentConfig,
    space: ActionSpace,
    control: VelocityController,
    target: Option<SemanticClass>,
    grid: Vec<u8>,
    blocked: Vec<bool>,
    /// Bounding box of the mapped cells `(x0, y0, x1, y1)`.
    known_box: (i32, i32, i32, i32),
    /// Mapped cells.
    known: u32,
    origin: Vec2,
    /// Look-around still to turn (rad).
    spin: f32,
    last_yaw: f32,
    sightings: Vec<Sighting>,
    max_steps: u32,
    res_px: u32,
    /// Exploration goal being pursued and the step it was chosen.
    frontier: Option<(Vec2, u32)>,
    /// Dialogue: where the oracle said the target is.
    hint: Option<Vec2>,
    /// Dialogue: points of the latest "which way" answer still to walk, and the step the first
    /// one was started.
    route: VecDeque<Vec2>,
    route_since: u32,
    dialogue: bool,
    asked_where: bool,
    /// "Which way" questions asked.
    asked_way: u32,
    /// The latest "which way" answer said to ask again at its end.
    ask_again: bool,
    /// The latest "which way" answer described the whole way (no "ask again").
    route_complete: bool,
    /// The end of a complete route was reached.
    arrived: bool,
    /// Map size at the last stall check and its step.
    stall_mark: (u32, u32),
    /// Visual reference: the reference image's centre-weighted colours.
    reference: Option<ColourHistogram>,
}

impl Default for SemanticAgent {
    fn default() -> Self {
        SemanticAgent {
            agent: AgentConfig::default(),
            space: ActionSpace::Discrete,
            control: VelocityController::default(),
            target: None,
            grid: Vec::new(),
            blocked: Vec::new(),
            known_box: (SIZE, SIZE, -1, -1),
            known: 0,
            origin: Vec2::ZERO,
            spin: 0.0,
            last_yaw: 0.0,
            sightings: Vec::new(),
            max_steps: 200,
            res_px: 128,
            frontier: None,
            hint: None,
            route: VecDeque::new(),
            route_since: 0,
            dialogue: false,
            asked_where: false,
            asked_way: 0,
            ask_again: false,
            route_complete: false,
            arrived: false,
            stall_mark: (0, 0),
            reference: None,
        }
    }
}

const N4: [(i32, i32); 4] = [(1, 0), (-1, 0), (0, 1), (0, -1)];

impl SemanticAgent {
    fn cell(&self, p: Vec2) -> Option<(i32, i32)> {
        let c = ((p - self.origin) / RES).floor();
        let (x, y) = (c.x as i32 + SIZE / 2, c.y as i32 + SIZE / 2);
        ((0..SIZE).contains(&x) && (0..SIZE).contains(&y)).then_some((x, y))
    }

    fn center(&self, (x, y): (i32, i32)) -> Vec2 {
        self.origin + Vec2::new((x - SIZE / 2) as f32 + 0.5, (y - SIZE / 2) as f32 + 0.5) * RES
    }

    fn idx((x, y): (i32, i32)) -> usize {
        (y * SIZE + x) as usize
    }

    fn at(i: usize) -> (i32, i32) {
        ((i as i32) % SIZE, (i as i32) / SIZE)
    }

    fn grow_box(&mut self, (x, y): (i32, i32)) {
        let b = &mut self.known_box;
        *b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
    }

    fn mark(&mut self, p: Vec2, v: u8) {
        let Some(c) = self.cell(p) else { return };
        let i = Self::idx(c);
        if self.grid[i] == UNKNOWN {
            self.known += 1;
            self.grow_box(c);
        }
        if v == OCCUPIED {
            if self.grid[i] != OCCUPIED {
                self.grid[i] = OCCUPIED;
                let r = (self.agent.shape.bounding_radius() / RES).ceil() as i32;
                for (x, y) in square_around(c, r) {
                    let (dx, dy) = (x - c.0, y - c.1);
                    if dx * dx + dy * dy <= r * r {
                        self.blocked[Self::idx((x, y))] = true;
                    }
                }
            }
        } else if self.grid[i] == UNKNOWN {
            self.grid[i] = FREE;
        }
    }

    /// The sighting a target point belongs to (made when none is close).
    fn sighting_of(&mut self, p: Vec2) -> usize {
        let near = self
            .sightings
            .iter()
            .enumerate()
            .map(|(i, s)| (i, s.centre.distance(p)))
            .filter(|(_, d)| *d <= SIGHTING_RADIUS)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match near {
            Some((i, _)) => i,
            None => {
                self.sightings.push(Sighting {
                    centre: p,
                    points: 0,
                    near: p,
                    matched: None,
                    rejected: false,
                });
                self.sightings.len() - 1
            }
        }
    }

    /// Merge sightings whose centres drifted within [`SIGHTING_RADIUS`] of each other (one
    /// large object seen part by part); `hits` is renumbered.
    fn merge_sightings(&mut self, hits: &mut [(usize, f32, Vec2, usize)]) {
        let mut i = 0;
        while i < self.sightings.len() {
            let close = (i + 1..self.sightings.len()).find(|&j| {
                self.sightings[i].centre.distance(self.sightings[j].centre) <= SIGHTING_RADIUS
            });
            let Some(j) = close else {
                i += 1;
                continue;
            };
            let b = self.sightings.remove(j);
            let a = &mut self.sightings[i];
            let n = (a.points + b.points).max(1) as f32;
            a.centre = (a.centre * a.points as f32 + b.centre * b.points as f32) / n;
            a.points += b.points;
            a.rejected |= b.rejected;
            if b.matched.map_or(0, |m| m.1) > a.matched.map_or(0, |m| m.1) {
                a.matched = b.matched;
            }
            for h in hits.iter_mut() {
                if h.0 == j {
                    h.0 = i;
                } else if h.0 > j {
                    h.0 -= 1;
                }
            }
        }
    }

    /// Fold one depth (+ semantic, + RGB) frame taken at `pos`, `yaw` into the map and the
    /// sightings.
    fn integrate(&mut self, view: View, pos: Vec2, yaw: f32, far: f32) {
        let depth = view.depth;
        let (w, h) = (depth.width as usize, depth.height as usize);
        let f = w as f32 / 2.0; // HFOV 90: fx = w / 2 / tan(45 deg)
        let (cx, cy) = (w as f32 / 2.0, h as f32 / 2.0);
        let fwd = cues::heading(yaw);
        let right = Vec2::new(yaw.cos(), -yaw.sin());
        let cam_h = 1.25;
        let target_id = self.target.map(SemanticClass::id);
        // (sighting, range, point, pixel index) of this view's target pixels.
        let mut hits: Vec<(usize, f32, Vec2, usize)> = Vec::new();
        for u in (0..w).step_by(2) {
            let mut obstacle = f32::INFINITY;
            let mut floor = 0.0f32;
            for v in (0..h).step_by(2) {
                let i = v * w + u;
                let d = depth.depth[i];
                if !d.is_finite() || d >= far * 0.99 {
                    continue;
                }
                let xc = (u as f32 + 0.5 - cx) / f * d;
                let height = cam_h - (v as f32 + 0.5 - cy) / f * d;
                let p = pos + fwd * d + right * xc;
                let range = (d * d + xc * xc).sqrt();
                if height < 0.15 {
                    floor = floor.max(range);
                } else if height < 1.6 {
                    if range < obstacle {
                        obstacle = range;
                    }
                    self.mark(p, OCCUPIED);
                }
                if let (Some(t), Some(s)) = (target_id, view.semantic) {
                    if s.semantic.get(i) == Some(&t) {
                        let k = self.sighting_of(p);
                        let sg = &mut self.sightings[k];
                        sg.points += 1;
                        sg.centre += (p - sg.centre) / sg.points as f32;
                        hits.push((k, range, p, i));
                    }
                }
            }
            // Free space along the column up to the first obstacle (or the farthest floor seen).
            let xc = (u as f32 + 0.5 - cx) / f;
            let dir = (fwd + right * xc).normalize();
            let reach = obstacle.min(floor.max(0.5)).min(6.0) - 0.1;
            let mut t = 0.0;
            while t < reach {
                self.mark(pos + dir * t, FREE);
                t += RES * 0.7;
            }
        }
        self.merge_sightings(&mut hits);
        // Per sighting seen in this view: its nearest point, and (visual reference) the colours
        // under its mask.
        for k in 0..self.sightings.len() {
            let mine: Vec<&(usize, f32, Vec2, usize)> = hits.iter().filter(|h| h.0 == k).collect();
            let Some(nearest) = mine.iter().min_by(|a, b| a.1.total_cmp(&b.1)) else {
                continue;
            };
            self.sightings[k].near = nearest.2;
            if let (Some(reference), Some(rgb)) = (&self.reference, view.rgb) {
                if mine.len() >= MATCH_PIXELS
                    && mine.len() > self.sightings[k].matched.map_or(0, |m| m.1)
                {
                    let mut hist = ColourHistogram::default();
                    for h in &mine {
                        if let Some(px) = rgb.rgb.get(h.3 * 3..h.3 * 3 + 3) {
                            hist.add(px, 1.0);
                        }
                    }
                    let score = hist.normalised().similarity(reference);
                    self.sightings[k].matched = Some((score, mine.len()));
                }
            }
        }
    }

    /// Breadth-first search over unblocked (`relaxed`: any), not-occupied cells (unknown ones
    /// too) inside the mapped box (plus a margin) from `start`.
    fn flood(&self, start: (i32, i32), relaxed: bool) -> Flood {
        let n = (SIZE * SIZE) as usize;
        let mut dist = vec![u32::MAX; n];
        let mut parent = vec![u32::MAX; n];
        let (b, m) = (self.known_box, 10);
        let (x0, y0, x1, y1) = (
            (b.0.min(start.0) - m).max(0),
            (b.1.min(start.1) - m).max(0),
            (b.2.max(start.0) + m).min(SIZE - 1),
            (b.3.max(start.1) + m).min(SIZE - 1),
        );
        let s = Self::idx(start);
        dist[s] = 0;
        parent[s] = s as u32;
        let mut q = VecDeque::from([start]);
        while let Some(c) = q.pop_front() {
            let ci = Self::idx(c);
            for (dx, dy) in N4 {
                let (x, y) = (c.0 + dx, c.1 + dy);
                if x < x0 || x > x1 || y < y0 || y > y1 {
                    continue;
                }
                let i = Self::idx((x, y));
                // The start cell may be inside the inflation (we are standing there).
                if dist[i] != u32::MAX
                    || self.grid[i] == OCCUPIED
                    || (!relaxed && self.blocked[i] && !self.blocked[ci])
                {
                    continue;
                }
                dist[i] = dist[ci] + 1;
                parent[i] = ci as u32;
                q.push_back((x, y));
            }
        }
        Flood {
            dist,
            parent,
            relaxed,
        }
    }

    /// The path (start excluded) to cell index `goal`.
    fn path_to(flood: &Flood, goal: usize) -> Vec<(i32, i32)> {
        let mut path = Vec::new();
        let mut i = goal;
        while flood.parent[i] as usize != i {
            path.push(Self::at(i));
            i = flood.parent[i] as usize;
        }
        path.reverse();
        path
    }

    /// The reached cell nearest (by path) among those within `radius` of `p`; failing that,
    /// the reached cell nearest to `p`.
    fn cell_near(&self, flood: &Flood, p: Vec2, radius: f32) -> Option<usize> {
        let c = self.cell(p)?;
        let r = (radius / RES).ceil() as i32;
        let mut best: Option<(u32, usize)> = None;
        for (x, y) in square_around(c, r) {
            let i = Self::idx((x, y));
            if flood.dist[i] != u32::MAX
                && self.center((x, y)).distance(p) <= radius
                && best.is_none_or(|b| flood.dist[i] < b.0)
            {
                best = Some((flood.dist[i], i));
            }
        }
        best.map(|b| b.1)
    }

    /// The reached cell nearest to `p` (within [`APPROACH_RADIUS`]; a shorter path breaks
    /// near ties).
    fn cell_facing(&self, flood: &Flood, p: Vec2) -> Option<usize> {
        let c = self.cell(p)?;
        let r = (APPROACH_RADIUS / RES).ceil() as i32;
        let mut best: Option<(f32, usize)> = None;
        for (x, y) in square_around(c, r) {
            let i = Self::idx((x, y));
            let d = self.center((x, y)).distance(p);
            if !flood.reached(i) || (!flood.relaxed && self.blocked[i]) || d > APPROACH_RADIUS {
                continue;
            }
            let cost = d + 0.05 * RES * flood.dist[i] as f32;
            if best.is_none_or(|b| cost < b.0) {
                best = Some((cost, i));
            }
        }
        best.map(|b| b.1)
    }

    fn is_frontier(&self, c: (i32, i32)) -> bool {
        self.grid[Self::idx(c)] == FREE
            && N4.iter().any(|(dx, dy)| {
                let (x, y) = (c.0 + dx, c.1 + dy);
                (0..SIZE).contains(&x)
                    && (0..SIZE).contains(&y)
                    && self.grid[Self::idx((x, y))] == UNKNOWN
            })
    }

    /// The best frontier cell: path length + turning + distance to the hint.
    fn pick_frontier(&self, flood: &Flood, pos: Vec2, yaw: f32) -> Option<usize> {
        let (b, mut best) = (self.known_box, None::<(f32, usize)>);
        for y in b.1.max(0)..=b.3.min(SIZE - 1) {
            for x in b.0.max(0)..=b.2.min(SIZE - 1) {
                let i = Self::idx((x, y));
                if !flood.reached(i)
                    || (!flood.relaxed && self.blocked[i])
                    || !self.is_frontier((x, y))
                {
                    continue;
                }
                let c = self.center((x, y));
                if c.distance(pos) < 1.0 {
                    continue;
                }
                let turn = wrap_angle(yaw_towards(c - pos) - yaw).abs();
                let mut score = flood.dist[i] as f32 * RES + TURN_COST * turn;
                if let Some(h) = self.hint {
                    score += HINT_WEIGHT * c.distance(h);
                }
                if best.is_none_or(|(s, _)| score < s) {
                    best = Some((score, i));
                }
            }
        }
        best.map(|b| b.1)
    }

    /// The sighting to walk to, if any is plausible; `late` (most steps spent) drops the
    /// visual-reference colour test.
    fn choose(&self, pos: Vec2, late: bool) -> Option<usize> {
        let live = || {
            self.sightings
                .iter()
                .enumerate()
                .filter(|(_, s)| !s.rejected)
        };
        if let Some(h) = self.hint {
            // The oracle's hint picks among objects of the class ("am I close?" checks it).
            return live()
                .min_by(|a, b| {
                    a.1.centre
                        .distance(h)
                        .total_cmp(&b.1.centre.distance(h))
                        .then(a.0.cmp(&b.0))
                })
                .map(|(i, _)| i);
        }
        // Visual reference: only sightings whose colours may match (or not yet compared).
        let visual = self.reference.is_some() && !late;
        let fits = |s: &Sighting| !visual || s.matched.is_none_or(|m| m.0 >= MATCH_MIN);
        let nearest = live().filter(|(_, s)| fits(s)).min_by(|a, b| {
            a.1.near
                .distance(pos)
                .total_cmp(&b.1.near.distance(pos))
                .then(a.0.cmp(&b.0))
        });
        if visual {
            let best = live()
                .filter_map(|(i, s)| s.matched.map(|m| (i, m.0)))
                .filter(|m| m.1 >= MATCH_MIN)
                .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)));
            if let (Some((bi, bs)), Some((ni, _))) = (best, nearest) {
                let ns = self.sightings[ni].matched.map_or(0.0, |m| m.0);
                if bi != ni && bs >= ns + MATCH_MARGIN {
                    return Some(bi);
                }
            }
        }
        nearest.map(|(i, _)| i)
    }

    fn ask(oracle: &mut Option<&mut dyn OracleHandle>, keep: u32, q: &str) -> Option<String> {
        let o = oracle.as_mut()?;
        if o.remaining() <= keep {
            return None;
        }
        o.ask(q)
    }

    /// One step toward `to` (discrete: turn or move forward; continuous: a velocity command);
    /// `left` is the path length still to go (m).
    fn steer(&mut self, pos: Vec2, yaw: f32, to: Vec2, left: f32) -> Action {
        let diff = wrap_angle(yaw_towards(to - pos) - yaw);
        if self.space == ActionSpace::Continuous {
            return self.control.follow(diff, left, 0.0);
        }
        let turn = self.agent.turn_angle();
        if diff.abs() > 0.5 * turn + 1e-4 {
            if diff > 0.0 {
                Action::left(&self.agent)
            } else {
                Action::right(&self.agent)
            }
        } else {
            Action::forward(&self.agent)
        }
    }

    /// Follow `path` (cells, start excluded) a few cells ahead.
    fn walk(&mut self, pos: Vec2, yaw: f32, path: &[(i32, i32)]) -> Action {
        let k = path.len().min(6) - 1;
        let to = self.center(path[k]);
        self.steer(pos, yaw, to, path.len() as f32 * RES)
    }

    /// Turn on the spot toward `to` (stop once facing it).
    fn face(&mut self, pos: Vec2, yaw: f32, to: Vec2) -> Action {
        let diff = wrap_angle(yaw_towards(to - pos) - yaw);
        if self.space == ActionSpace::Continuous {
            return self.control.turn(diff);
        }
        let turn = self.agent.turn_angle();
        if diff.abs() <= 0.5 * turn + 1e-4 {
            Action::Stop
        } else if diff > 0.0 {
            Action::left(&self.agent)
        } else {
            Action::right(&self.agent)
        }
    }

    /// Turn on the spot (look around) by up to `angle` (rad, counter-clockwise).
    fn look_around(&mut self, angle: f32) -> Action {
        if self.space == ActionSpace::Continuous {
            return self.control.turn(angle.min(std::f32::consts::PI));
        }
        Action::left(&self.agent)
    }
}

/// The frames of one view of the agent's own cameras.
struct View<'a> {
    depth: &'a Frame,
    semantic: Option<&'a Frame>,
    rgb: Option<&'a Frame>,
}

impl Agent for SemanticAgent {
    fn required_sensors(&self) -> Vec<SensorSpec> {
        let cam = |name: &str| CameraSpec {
            name: name.into(),
            width: self.res_px,
            height: self.res_px,
            ..CameraSpec::default()
        };
        vec![
            SensorSpec::Semantic(cam(SEMANTIC_SENSOR)),
            SensorSpec::Depth(cam(DEPTH_SENSOR)),
            SensorSpec::Rgb(cam(RGB_SENSOR)),
        ]
    }

    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.agent = inputs.agent.clone();
        self.space = inputs.action_space;
        self.control = VelocityController::new(&inputs.agent);
        self.target = parse_target_class(&inputs.instruction);
        self.grid = vec![UNKNOWN; (SIZE * SIZE) as usize];
        self.blocked = vec![false; (SIZE * SIZE) as usize];
        self.known_box = (SIZE, SIZE, -1, -1);
        self.known = 0;
        self.origin = floor_point(&inputs.start);
        self.spin = std::f32::consts::TAU - 0.5 * self.agent.turn_angle();
        self.last_yaw = inputs.start.yaw();
        self.sightings.clear();
        self.max_steps = inputs.max_steps;
        self.frontier = None;
        self.hint = None;
        self.route.clear();
        self.route_since = 0;
        self.dialogue = inputs.oracle_budget.is_some_and(|b| b > 0);
        self.asked_where = false;
        self.asked_way = 0;
        self.ask_again = false;
        self.route_complete = false;
        self.arrived = false;
        self.stall_mark = (0, 0);
        self.reference = match &inputs.reference_image {
            Some(p) => Some(ColourHistogram::of_reference(p)?),
            None => None,
        };
        Ok(())
    }

    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        self.decide(step)
    }
}

impl SemanticAgent {
    /// One step: map, ask, choose, move.
    fn decide(&mut self, step: &mut StepInput) -> Result<Action> {
        let pos = floor_point(&step.pose);
        let yaw = step.pose.yaw();
        let turned = wrap_angle(yaw - self.last_yaw);
        self.last_yaw = yaw;
        if turned > 0.0 {
            self.spin -= turned;
        }
        if self.target.is_none() || step.step + 1 >= self.max_steps {
            return Ok(Action::Stop);
        }
        let frame = |name: &str| match step.observations.get(name) {
            Some(Observation::Depth(f) | Observation::Semantic(f) | Observation::Rgb(f)) => Some(f),
            _ => None,
        };
        if let Some(depth) = frame(DEPTH_SENSOR) {
            let view = View {
                depth,
                semantic: frame(SEMANTIC_SENSOR),
                rgb: frame(RGB_SENSOR),
            };
            self.integrate(view, pos, yaw, 10.0);
        }
        // A blocked move: the obstacle is right ahead.
        if let Some(last) = step.last {
            let cmd = Vec2::from_array(last.commanded).length();
            let got = Vec2::from_array(last.achieved).length();
            if cmd > 0.0 && got < 0.5 * cmd {
                let ahead = pos + cues::heading(yaw) * (self.agent.shape.bounding_radius() + 0.1);
                self.mark(ahead, OCCUPIED);
            }
        }
        let mut oracle = step.oracle.take();
        if self.dialogue && !self.asked_where {
            self.asked_where = true;
            let what = self.target.map(SemanticClass::words).unwrap_or_default();
            if let Some(a) = Self::ask(&mut oracle, 0, &format!("where is the {what}?")) {
                if let Some((bearing, d)) = cues::parse_where(&a) {
                    self.hint = Some(pos + cues::heading(yaw + bearing) * d);
                }
            }
        }
        let late = step.step as f32 >= MATCH_LATE_SHARE * self.max_steps as f32;
        let chosen = self.choose(pos, late);
        // Visual reference: look around first, so every object of the class gets compared.
        let settled = self.reference.is_none() || self.spin <= 0.0;
        if let Some(k) = chosen.filter(|_| settled) {
            let s = &self.sightings[k];
            if pos.distance(s.near) <= STOP_NEAR && pos.distance(s.centre) <= STOP_NEAR + 0.5 {
                if self.reference.is_some() && s.matched.is_none() && !late {
                    // Not compared yet: face it.
                    let to = s.centre;
                    return Ok(self.face(pos, yaw, to));
                }
                // Dialogue: check with the oracle while a question is left.
                match Self::ask(&mut oracle, 0, "am I close?")
                    .as_deref()
                    .map(cues::parse_close)
                {
                    Some(Some(false)) => {
                        // Another object of the class: ask the way from here.
                        self.sightings[k].rejected = true;
                        self.ask_again = true;
                    }
                    _ => return Ok(Action::Stop),
                }
            }
        }
        if std::mem::take(&mut self.arrived) {
            // At the end of the way the oracle described: the goal should be here.
            match Self::ask(&mut oracle, 0, "am I close?")
                .as_deref()
                .map(cues::parse_close)
            {
                Some(Some(false)) => self.ask_again = true,
                _ => return Ok(Action::Stop),
            }
        }
        let chosen = self.choose(pos, late);
        if chosen.is_none() && self.hint.is_some_and(|h| h.distance(pos) < 1.0) {
            // Reached the hint without seeing the target: explore freely.
            self.hint = None;
        }
        // Look around once (visual reference: before walking to anything, so every object of the
        // class in sight gets compared).
        if self.spin > 0.0 && (chosen.is_none() || self.reference.is_some()) {
            return Ok(self.look_around(self.spin));
        }
        let Some(start) = self.cell(pos) else {
            return Ok(Action::Stop);
        };
        let strict = self.flood(start, false);
        if let Some(k) = chosen {
            // The reachable cell nearest the middle of what was seen (the goal may lie on any
            // side of a large object); through the obstacles' inflation when that gets closer.
            let centre = self.sightings[k].centre;
            let best = self.cell_facing(&strict, centre);
            let far = |g: usize| self.center(Self::at(g)).distance(centre) > STOP_NEAR + 0.5;
            if best.is_none_or(far) {
                let relaxed = self.flood(start, true);
                if let Some(g) = self.cell_facing(&relaxed, centre) {
                    let closer = |h: usize| {
                        self.center(Self::at(g)).distance(centre) + 0.3
                            < self.center(Self::at(h)).distance(centre)
                    };
                    if best.is_none_or(closer) {
                        let path = Self::path_to(&relaxed, g);
                        return Ok(self.approach(pos, yaw, &path));
                    }
                }
            }
            if let Some(g) = best {
                let path = Self::path_to(&strict, g);
                return Ok(self.approach(pos, yaw, &path));
            }
        }
        // Dialogue: ask the way when exploration stalls (keeping one question for the stop).
        let asking = self.dialogue && chosen.is_none() && self.route.is_empty();
        if asking {
            let again = std::mem::take(&mut self.ask_again);
            let (cells, since) = self.stall_mark;
            let stalled =
                again || (step.step >= since + STALL_STEPS && self.known < cells + STALL_CELLS);
            let late =
                step.step as f32 >= LATE_SHARE * self.max_steps as f32 && self.asked_way == 0;
            if (stalled || late) && self.ask_way(&mut oracle, pos, yaw, step.step) {
                return Ok(Action::Stop);
            }
            if step.step >= since + STALL_STEPS {
                self.stall_mark = (self.known, step.step);
            }
        }
        if let Some(a) = self.explore(&strict, pos, yaw, step.step) {
            return Ok(a);
        }
        // Boxed in by the inflation (a narrow door, a noisy wall): squeeze through.
        let relaxed = self.flood(start, true);
        if let Some(a) = self.explore(&relaxed, pos, yaw, step.step) {
            return Ok(a);
        }
        // Nothing left to explore: ask the way before giving up.
        if asking && self.route.is_empty() && !self.ask_way(&mut oracle, pos, yaw, step.step) {
            if let Some(a) = self.explore(&relaxed, pos, yaw, step.step) {
                return Ok(a);
            }
        }
        Ok(Action::Stop)
    }

    /// Ask "which way?" (keeping one question in reserve) and take the answer's legs as the
    /// route; true when the oracle says the agent is already there.
    fn ask_way(
        &mut self,
        oracle: &mut Option<&mut dyn OracleHandle>,
        pos: Vec2,
        yaw: f32,
        step: u32,
    ) -> bool {
        self.asked_way += 1;
        let Some(a) = Self::ask(oracle, 1, "which way?") else {
            return false;
        };
        match cues::parse_which_way(&a) {
            Some(legs) if legs.is_empty() => true,
            Some(legs) => {
                // The goal lies at the end of the legs, or beyond it when the answer says to
                // ask again there.
                let pts = cues::route_points(pos, yaw, &legs);
                let end = pts.last().copied().unwrap_or(pos);
                let h = yaw + legs.iter().map(|l| l.0).sum::<f32>();
                self.ask_again = a.to_lowercase().contains("ask again");
                self.route_complete = !self.ask_again;
                self.hint = Some(if self.ask_again {
                    end + cues::heading(h) * 2.0
                } else {
                    end
                });
                self.route = pts.into();
                self.route_since = step;
                self.frontier = None;
                false
            }
            None => false,
        }
    }

    /// Walk `path` to a sighting; stop at its end.
    fn approach(&mut self, pos: Vec2, yaw: f32, path: &[(i32, i32)]) -> Action {
        if path.len() <= 2 {
            return Action::Stop;
        }
        self.walk(pos, yaw, path)
    }

    /// Walk the "which way" route, else toward a frontier (kept while it is one); `None` when
    /// no frontier is reached.
    fn explore(&mut self, flood: &Flood, pos: Vec2, yaw: f32, step: u32) -> Option<Action> {
        while let Some(&p) = self.route.front() {
            let goal = self.cell_near(flood, p, 0.7);
            let path = goal.map(|g| Self::path_to(flood, g)).unwrap_or_default();
            if path.len() < 3 || step >= self.route_since + ROUTE_STEPS {
                if path.len() < 3 && self.route.len() == 1 && self.route_complete {
                    self.arrived = true;
                }
                self.route.pop_front();
                self.route_since = step;
                continue;
            }
            return Some(self.walk(pos, yaw, &path));
        }
        let keep = self.frontier.and_then(|(f, since)| {
            let c = self.cell(f)?;
            let i = Self::idx(c);
            (self.is_frontier(c)
                && flood.reached(i)
                && f.distance(pos) > 0.5
                && step < since + COMMIT_STEPS)
                .then_some(i)
        });
        let goal = match keep {
            Some(i) => i,
            None => {
                let g = self.pick_frontier(flood, pos, yaw);
                self.frontier = g.map(|i| (self.center(Self::at(i)), step));
                g?
            }
        };
        let path = Self::path_to(flood, goal);
        (!path.is_empty()).then(|| self.walk(pos, yaw, &path))
    }
}

/// Map cells of the square of half-width `r` around `c`, row by row, clipped to the map.
fn square_around(c: (i32, i32), r: i32) -> impl Iterator<Item = (i32, i32)> {
    let ys = (c.1 - r).max(0)..=(c.1 + r).min(SIZE - 1);
    ys.flat_map(move |y| ((c.0 - r).max(0)..=(c.0 + r).min(SIZE - 1)).map(move |x| (x, y)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn target_class_is_the_first_class_named() {
        assert_eq!(
            parse_target_class("Find the floor lamp next to the sofa."),
            Some(SemanticClass::FloorLamp)
        );
        assert_eq!(
            parse_target_class("go to the Coffee Table in the living room"),
            Some(SemanticClass::CoffeeTable)
        );
        assert_eq!(
            parse_target_class("walk to the couches"),
            Some(SemanticClass::Sofa)
        );
        assert_eq!(
            parse_target_class("the office chair by the desk"),
            Some(SemanticClass::OfficeChair)
        );
        assert_eq!(parse_target_class("walk past the wall"), None);
    }

    /// A scripted oracle that answers by the kind of question, within a budget.
    struct Scripted {
        asked: Vec<String>,
        budget: u32,
    }

    impl OracleHandle for Scripted {
        fn ask(&mut self, question: &str) -> Option<String> {
            if self.remaining() == 0 {
                return None;
            }
            self.asked.push(question.to_string());
            Some(if question.starts_with("where") {
                "The grey sofa in the living room is on your left, about 4 metres away.".into()
            } else if question.contains("close") {
                "Not far now, about 5 metres away.".into()
            } else {
                "Turn right and go about 2 metres, then keep going about 3 metres, and ask \
                 again from there."
                    .into()
            })
        }
        fn remaining(&self) -> u32 {
            self.budget - self.asked.len() as u32
        }
    }

    #[test]
    fn dialogue_asks_where_first_and_stays_within_the_budget() {
        use crate::agents::test_support::{inputs, step_input};
        for space in [ActionSpace::Discrete, ActionSpace::Continuous] {
            let mut a = SemanticAgent::default();
            let mut ep = inputs(space);
            ep.oracle_budget = Some(3);
            a.reset(&ep).unwrap();
            // The pose below never turns: skip the look-around.
            a.spin = 0.0;
            let mut oracle = Scripted {
                asked: Vec::new(),
                budget: 3,
            };
            let obs = vlnverse_sensors::Observations::new();
            for k in 0..120 {
                let mut step = step_input(k, &obs, None);
                step.oracle = Some(&mut oracle);
                let act = a.act(&mut step).unwrap();
                assert!(space.allows(&act), "{act:?} in {space:?}");
                if k == 0 {
                    // Nothing is mapped (no cameras), so there is nothing to explore: it asks
                    // the way at once. Facing -Z, "turn right, 2 m, keep going 3 m, ask again"
                    // leads along +X; the hint lies 2 m past the end.
                    assert_eq!(oracle.asked, ["where is the sofa?", "which way?"]);
                    let h = a.hint.unwrap();
                    assert!(h.distance(Vec2::new(7.0, 0.0)) < 1e-3, "{h:?}");
                }
                if act == Action::Stop {
                    break;
                }
            }
            assert_eq!(oracle.asked[0], "where is the sofa?");
            // The last question is kept for "am I close?".
            let ways = oracle.asked.iter().filter(|q| *q == "which way?").count();
            assert_eq!(ways, 1, "{:?}", oracle.asked);
            assert!(oracle.asked.len() <= 3);
        }
    }

    fn sighting(centre: Vec2, matched: Option<f32>) -> Sighting {
        Sighting {
            centre,
            points: 10,
            near: centre,
            matched: matched.map(|m| (m, 50)),
            rejected: false,
        }
    }

    #[test]
    fn sightings_of_one_large_object_merge() {
        let mut a = SemanticAgent {
            sightings: vec![
                sighting(Vec2::new(0.0, 0.0), Some(0.3)),
                sighting(Vec2::new(5.0, 0.0), None),
                sighting(Vec2::new(1.2, 0.0), Some(0.6)),
            ],
            ..Default::default()
        };
        let mut hits = vec![(2, 1.0, Vec2::ZERO, 0), (1, 1.0, Vec2::ZERO, 0)];
        a.merge_sightings(&mut hits);
        assert_eq!(a.sightings.len(), 2);
        assert!((a.sightings[0].centre.x - 0.6).abs() < 1e-5);
        assert_eq!(a.sightings[0].points, 20);
        assert_eq!(hits[0].0, 0);
        assert_eq!(hits[1].0, 1);
    }

    #[test]
    fn visual_reference_prefers_the_matching_object() {
        let mut a = SemanticAgent {
            reference: Some(ColourHistogram::default()),
            ..Default::default()
        };
        let pos = Vec2::ZERO;
        // Nearest first when the colours do not tell them apart.
        a.sightings = vec![
            sighting(Vec2::new(2.0, 0.0), Some(0.5)),
            sighting(Vec2::new(6.0, 0.0), Some(0.55)),
        ];
        assert_eq!(a.choose(pos, false), Some(0));
        // A clearly better match wins over distance; a poor match is not walked to.
        a.sightings[1].matched = Some((0.9, 50));
        assert_eq!(a.choose(pos, false), Some(1));
        a.sightings = vec![sighting(Vec2::new(2.0, 0.0), Some(0.1))];
        assert_eq!(a.choose(pos, false), None);
        // ... unless time is running out.
        assert_eq!(a.choose(pos, true), Some(0));
    }
}
