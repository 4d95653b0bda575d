//! `semantic`: a non-learned baseline for the coarse-grained, visual-reference and dialogue
//! tasks. It reads the target class from the instruction text (words of the
//! [`SemanticClass`] vocabulary, plus a few synonyms) and never the ground-truth goal or target
//! id. It looks around once, builds its own top-down map from depth (0.1 m cells: unknown /
//! free / occupied, obstacles inflated by the agent radius), explores the nearest frontier,
//! walks to the target once the semantic camera sees it, and stops next to it.

use std::collections::VecDeque;

use glam::Vec2;
use vlnverse_env::SemanticClass;
use vlnverse_sensors::{CameraSpec, Frame, Observation, SensorSpec};
use vlnverse_sim::{Action, AgentConfig};

use super::{floor_point, wrap_angle, yaw_towards};
use crate::error::Result;
use crate::eval::agent::{Agent, EpisodeInputs, StepInput};

/// Name of the semantic camera the agent attaches.
pub const SEMANTIC_SENSOR: &str = "semantic_agent_semantic";
/// Name of the depth camera the agent attaches (same pose, so both come from one view).
pub const DEPTH_SENSOR: &str = "semantic_agent_depth";

const RES: f32 = 0.1;
const SIZE: i32 = 600;
const UNKNOWN: u8 = 0;
const FREE: u8 = 1;
const OCCUPIED: u8 = 2;
/// Stop this close (m) to the seen target.
const STOP_NEAR: f32 = 1.2;

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

/// The frontier-exploring, semantic-camera agent.
pub struct SemanticAgent {
    agent: AgentConfig,
    target: Option<SemanticClass>,
    grid: Vec<u8>,
    blocked: Vec<bool>,
    origin: Vec2,
    spin_left: u32,
    seen: Option<Vec2>,
    max_steps: u32,
    res_px: u32,
}

impl Default for SemanticAgent {
    fn default() -> Self {
        SemanticAgent {
            agent: AgentConfig::default(),
            target: None,
            grid: Vec::new(),
            blocked: Vec::new(),
            origin: Vec2::ZERO,
            spin_left: 0,
            seen: None,
            max_steps: 200,
            res_px: 128,
        }
    }
}

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

    fn mark(&mut self, p: Vec2, v: u8) {
        let Some(c) = self.cell(p) else { return };
        let i = Self::idx(c);
        if v == OCCUPIED {
            if self.grid[i] != OCCUPIED {
                self.grid[i] = OCCUPIED;
                let r = (self.agent.shape.bounding_radius() / RES).ceil() as i32;
                for dy in -r..=r {
                    for dx in -r..=r {
                        let (x, y) = (c.0 + dx, c.1 + dy);
                        if dx * dx + dy * dy <= r * r
                            && (0..SIZE).contains(&x)
                            && (0..SIZE).contains(&y)
                        {
                            self.blocked[Self::idx((x, y))] = true;
                        }
                    }
                }
            }
        } else if self.grid[i] == UNKNOWN {
            self.grid[i] = FREE;
        }
    }

    /// Fold one depth (+ semantic) frame taken at `pos`, `yaw` into the map.
    fn integrate(
        &mut self,
        depth: &Frame,
        semantic: Option<&Frame>,
        pos: Vec2,
        yaw: f32,
        far: f32,
    ) {
        let (w, h) = (depth.width as usize, depth.height as usize);
        let f = w as f32 / 2.0; // HFOV 90: fx = w / 2 / tan(45 deg)
        let (cx, cy) = (w as f32 / 2.0, h as f32 / 2.0);
        let fwd = Vec2::new(-yaw.sin(), -yaw.cos());
        let right = Vec2::new(yaw.cos(), -yaw.sin());
        let cam_h = 1.25;
        let target_id = self.target.map(SemanticClass::id);
        let mut best_target: Option<(f32, Vec2)> = None;
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
                if let (Some(t), Some(s)) = (target_id, semantic) {
                    if s.semantic.get(i) == Some(&t) && best_target.is_none_or(|(r, _)| range < r) {
                        best_target = Some((range, p));
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
        if let Some((_, p)) = best_target {
            self.seen = Some(p);
        }
    }

    /// Breadth-first search over unblocked, not-occupied cells (unknown ones too) from `start`
    /// to the first cell accepted by `goal`; returns the path (start excluded).
    fn bfs(&self, start: (i32, i32), goal: impl Fn((i32, i32)) -> bool) -> Option<Vec<(i32, i32)>> {
        let n = (SIZE * SIZE) as usize;
        let mut parent = vec![u32::MAX; n];
        let s = Self::idx(start);
        parent[s] = s as u32;
        let mut q = VecDeque::from([start]);
        while let Some(c) = q.pop_front() {
            if c != start && goal(c) {
                let mut path = vec![c];
                let mut i = Self::idx(c);
                while parent[i] as usize != s {
                    i = parent[i] as usize;
                    path.push(((i as i32) % SIZE, (i as i32) / SIZE));
                }
                path.reverse();
                return Some(path);
            }
            for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                let (x, y) = (c.0 + dx, c.1 + dy);
                if !(0..SIZE).contains(&x) || !(0..SIZE).contains(&y) {
                    continue;
                }
                let i = Self::idx((x, y));
                // The start cell may be inside the inflation (we are standing there).
                if parent[i] != u32::MAX
                    || self.grid[i] == OCCUPIED
                    || (self.blocked[i] && c != start && !self.blocked[Self::idx(c)])
                {
                    continue;
                }
                parent[i] = Self::idx(c) as u32;
                q.push_back((x, y));
            }
        }
        None
    }

    fn steer(&self, pos: Vec2, yaw: f32, to: Vec2) -> Action {
        let diff = wrap_angle(yaw_towards(to - pos) - yaw);
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
        ]
    }

    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.agent = inputs.agent.clone();
        self.target = parse_target_class(&inputs.instruction);
        self.grid = vec![UNKNOWN; (SIZE * SIZE) as usize];
        self.blocked = vec![false; (SIZE * SIZE) as usize];
        self.origin = floor_point(&inputs.start);
        self.spin_left = (std::f32::consts::TAU / self.agent.turn_angle()).round() as u32;
        self.seen = None;
        self.max_steps = inputs.max_steps;
        Ok(())
    }

    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        let pos = floor_point(&step.pose);
        let yaw = step.pose.yaw();
        if self.target.is_none() || step.step + 1 >= self.max_steps {
            return Ok(Action::Stop);
        }
        let depth = match step.observations.get(DEPTH_SENSOR) {
            Some(Observation::Depth(f)) => Some(f),
            _ => None,
        };
        let sem = match step.observations.get(SEMANTIC_SENSOR) {
            Some(Observation::Semantic(f)) => Some(f),
            _ => None,
        };
        if let Some(d) = depth {
            self.integrate(d, sem, pos, yaw, 10.0);
        }
        // A blocked move: the obstacle is right ahead.
        if let Some(last) = step.last {
            let cmd = Vec2::from_array(last.commanded).length();
            let got = Vec2::from_array(last.achieved).length();
            if cmd > 0.0 && got < 0.5 * cmd {
                let ahead = pos
                    + Vec2::new(-yaw.sin(), -yaw.cos())
                        * (self.agent.shape.bounding_radius() + 0.1);
                self.mark(ahead, OCCUPIED);
            }
        }
        if let Some(t) = self.seen {
            if pos.distance(t) <= STOP_NEAR {
                return Ok(Action::Stop);
            }
        }
        if self.spin_left > 0 && self.seen.is_none() {
            self.spin_left -= 1;
            return Ok(Action::left(&self.agent));
        }
        let Some(start) = self.cell(pos) else {
            return Ok(Action::Stop);
        };
        let path = match self.seen {
            Some(t) => {
                let near = STOP_NEAR - 0.2;
                self.bfs(start, |c| self.center(c).distance(t) <= near)
            }
            None => None,
        };
        let path = path.or_else(|| {
            self.bfs(start, |c| {
                let i = Self::idx(c);
                self.grid[i] == FREE
                    && self.center(c).distance(pos) >= 1.0
                    && [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|(dx, dy)| {
                        let (x, y) = (c.0 + dx, c.1 + dy);
                        (0..SIZE).contains(&x)
                            && (0..SIZE).contains(&y)
                            && self.grid[Self::idx((x, y))] == UNKNOWN
                    })
            })
        });
        let Some(path) = path else {
            // Nothing left to explore and no target in sight.
            return Ok(Action::Stop);
        };
        let k = path.len().min(6) - 1;
        Ok(self.steer(pos, yaw, self.center(path[k])))
    }
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
}
