//! The dialogue task's oracle: questions an agent may ask while navigating, with a budget.
//!
//! [`ShortestPathOracle`] (the default) answers deterministically from the true remaining path
//! (the geodesic shortest path from the agent to the goal on the navigable map), the scene graph
//! and distance buckets. Once the budget is spent every answer says so and reveals nothing.
//! [`LlmOracle`] (optional) rephrases another oracle's answers through an OpenAI-compatible chat
//! endpoint ([`vlnverse_instructions::llm::ChatClient`]).
//!
//! ```no_run
//! # use std::sync::Arc;
//! # use vlnverse_eval::oracle::{Oracle, OracleConfig, OracleQuery, ShortestPathOracle};
//! # fn demo(scene: Arc<vlnverse_env::Scene>, graph: Arc<vlnverse_env::scene_graph::SceneGraph>,
//! #         map: Arc<vlnverse_env::occupancy::GridMap>) -> vlnverse_eval::Result<()> {
//! let mut oracle = ShortestPathOracle::new(scene, graph, map, [2.0, 0.0, -3.0], None,
//!                                          OracleConfig::default())?;
//! let a = oracle.ask(&OracleQuery::WhichWay, [0.0, 0.0, 0.0], 0.0)?;
//! println!("{} ({} questions left)", a.text, a.remaining);
//! # Ok(()) }
//! ```

use crate::error::{Result, TaskError};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use vlnverse_env::geodesic::{shortest_path, GeodesicPath, Guide, LevelField};
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::scene_graph::{direction_of_yaw, segment_headings};
use vlnverse_env::scene_graph::{rooms_along_path, side_of, SceneGraph};
use vlnverse_env::{ObjectId, Scene, SceneObject};
use vlnverse_score::episode::{Episode, Side};
use vlnverse_score::route::{classify_turn, env_side, side_word, Turn, TurnConfig};

/// Default number of questions per episode.
pub const DEFAULT_ORACLE_BUDGET: u32 = 5;

/// A question to the oracle.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OracleQuery {
    /// "Which way should I go?"
    WhichWay,
    /// "Where is the X?": an object class ("mug", "coffee table"), optionally with a colour
    /// ("red mug"), an object name, or a room type ("kitchen").
    WhereIs(String),
    /// "Am I close?"
    AmIClose,
}

impl OracleQuery {
    /// Read a free-text question: "am I close?" / "how far ..." -> [`OracleQuery::AmIClose`];
    /// "where is the red mug?" / "find the sofa" -> [`OracleQuery::WhereIs`]; anything else
    /// ("which way?") -> [`OracleQuery::WhichWay`].
    pub fn parse(question: &str) -> OracleQuery {
        let q = question
            .trim()
            .trim_end_matches(['?', '.', '!'])
            .to_lowercase();
        let words: Vec<&str> = q.split_whitespace().collect();
        if words
            .iter()
            .any(|w| matches!(*w, "close" | "near" | "far" | "arrived"))
        {
            return OracleQuery::AmIClose;
        }
        let object = ["where is ", "where's ", "where are ", "find "]
            .iter()
            .find_map(|p| q.strip_prefix(p));
        match object {
            Some(rest) => {
                let rest = rest.trim();
                let rest = ["the ", "a ", "an ", "my "]
                    .iter()
                    .find_map(|a| rest.strip_prefix(a))
                    .unwrap_or(rest);
                OracleQuery::WhereIs(rest.trim().to_string())
            }
            None => OracleQuery::WhichWay,
        }
    }
}

/// The oracle's reply.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct OracleAnswer {
    /// The reply in words.
    pub text: String,
    /// Whether the reply carries information (false once the budget is spent, or when the
    /// question could not be answered).
    pub answered: bool,
    /// Questions left after this one.
    pub remaining: u32,
    /// Which way: the turn to make before the first leg of the remaining path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub turn: Option<Turn>,
    /// Which way / am I close: geodesic distance to the goal (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance_m: Option<f32>,
    /// Where is: the object described.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub object_id: Option<u32>,
    /// Where is: its side as seen by the agent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<Side>,
}

impl OracleAnswer {
    fn silent(text: String, remaining: u32) -> Self {
        OracleAnswer {
            text,
            answered: false,
            remaining,
            turn: None,
            distance_m: None,
            object_id: None,
            side: None,
        }
    }
}

/// An oracle the agent may query during navigation.
pub trait Oracle: Send {
    /// Answer `query` for an agent standing at `position` (floor, world frame) facing `yaw`
    /// (radians, yaw 0 looks along -Z). Every call uses one question of the budget while any
    /// is left. Errors only for invalid input (non-finite position or yaw).
    fn ask(&mut self, query: &OracleQuery, position: [f32; 3], yaw: f32) -> Result<OracleAnswer>;

    /// Questions left.
    fn remaining(&self) -> u32;
}

/// Settings of the [`ShortestPathOracle`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct OracleConfig {
    /// Questions per episode.
    pub budget: u32,
    /// Within this geodesic distance (m) the agent is told it has arrived.
    pub arrived_m: f32,
    /// Upper bounds (m) of the distance buckets "very close", "close", "not far"; beyond the
    /// last, "still far".
    pub buckets_m: [f32; 3],
    /// How many legs of the remaining path "which way" describes.
    pub legs: usize,
    /// Turn thresholds.
    pub turns: TurnConfig,
}

impl Default for OracleConfig {
    fn default() -> Self {
        OracleConfig {
            budget: DEFAULT_ORACLE_BUDGET,
            arrived_m: 0.5,
            buckets_m: [1.5, 3.0, 6.0],
            legs: 2,
            turns: TurnConfig::default(),
        }
    }
}

impl OracleConfig {
    /// Check the values; the error names the field.
    pub fn validate(&self) -> Result<()> {
        let b = self.buckets_m;
        if !(self.arrived_m.is_finite() && self.arrived_m >= 0.0) {
            return Err(TaskError::invalid(
                "oracle.arrived_m",
                self.arrived_m,
                "must be a finite number >= 0",
            ));
        }
        if !(b.iter().all(|v| v.is_finite()) && 0.0 < b[0] && b[0] <= b[1] && b[1] <= b[2]) {
            return Err(TaskError::invalid(
                "oracle.buckets_m",
                format!("{b:?}"),
                "need 0 < b0 <= b1 <= b2",
            ));
        }
        if self.legs == 0 {
            return Err(TaskError::invalid("oracle.legs", 0, "must be at least 1"));
        }
        Ok(())
    }
}

/// The default oracle: answers from the geodesic shortest path to the goal, the scene graph and
/// distance buckets; deterministic.
#[derive(Clone, Debug)]
pub struct ShortestPathOracle {
    scene: Arc<Scene>,
    graph: Arc<SceneGraph>,
    navigable: Arc<GridMap>,
    goal: Vec2,
    target: Option<ObjectId>,
    config: OracleConfig,
    asked: u32,
    /// In a home on several floors, the goal's field across floors (see
    /// [`ShortestPathOracle::with_levels`]).
    levels: Option<Arc<LevelField>>,
}

fn check_finite(field: &str, v: &[f32]) -> Result<()> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(TaskError::invalid(
            field,
            format!("{v:?}"),
            "must be finite",
        ))
    }
}

fn metres(d: f32) -> String {
    if d < 1.5 {
        "about a metre".to_string()
    } else {
        format!("about {} metres", d.round() as u32)
    }
}

fn object_words(o: &SceneObject) -> String {
    if o.color.is_empty() {
        o.class.words()
    } else {
        format!("{} {}", o.color, o.class.words())
    }
}

fn normalize(s: &str) -> String {
    s.trim()
        .to_lowercase()
        .trim_start_matches("the ")
        .trim_start_matches("a ")
        .replace('_', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

impl ShortestPathOracle {
    /// An oracle for one episode: the scene, its graph, its navigable map, the goal position and
    /// the target object (when the task has one; "where is" prefers it among equal names).
    pub fn new(
        scene: Arc<Scene>,
        graph: Arc<SceneGraph>,
        navigable: Arc<GridMap>,
        goal: [f32; 3],
        target: Option<ObjectId>,
        config: OracleConfig,
    ) -> Result<Self> {
        check_finite("goal", &goal)?;
        config.validate()?;
        Ok(ShortestPathOracle {
            scene,
            graph,
            navigable,
            goal: Vec2::new(goal[0], goal[2]),
            target,
            config,
            asked: 0,
            levels: None,
        })
    }

    /// In a home on several floors: answer with the goal's field across floors (`navigable`
    /// is then the goal's floor's map). "Which way" from another floor leads to the stairs and
    /// says to take them; on a flight it says to keep going up or down; "am I close" counts
    /// the walk through the stairs; "where is" names the room of the asker's own floor.
    pub fn with_levels(self, levels: Arc<LevelField>) -> Self {
        ShortestPathOracle {
            levels: Some(levels),
            ..self
        }
    }

    /// The way from a 3-D point across floors: `(path on this floor, total distance, what to
    /// say after it)`; `None` when there is no field across floors or no way.
    fn across(&self, at: [f32; 3]) -> Option<(Option<GeodesicPath>, f32, Option<&'static str>)> {
        let lf = self.levels.as_ref()?;
        let d = lf.distance(at).meters()?;
        let p = Vec2::new(at[0], at[2]);
        Some(match lf.guide(at)? {
            Guide::Walk { field, rest } if rest > 0.0 => {
                let up = lf.goal_level() > lf.level_at(at[1]);
                let then = if up {
                    "go up the stairs; the goal is upstairs"
                } else {
                    "go down the stairs; the goal is downstairs"
                };
                (field.path(p), d, Some(then))
            }
            Guide::Walk { field, .. } => (field.path(p), d, None),
            Guide::Flight { up: true, .. } => (None, d, Some("go up the stairs")),
            Guide::Flight { up: false, .. } => (None, d, Some("go down the stairs")),
        })
    }

    /// An oracle for a dialogue episode: its final goal, its target object and its
    /// `oracle_budget` (else `config.budget`).
    pub fn for_episode(
        scene: Arc<Scene>,
        graph: Arc<SceneGraph>,
        navigable: Arc<GridMap>,
        episode: &Episode,
        config: OracleConfig,
    ) -> Result<Self> {
        let goal = episode.goal_sequence().last().ok_or_else(|| {
            TaskError::invalid(
                format!("episode {}.goals", episode.episode_id),
                "[]",
                "an oracle needs a goal",
            )
        })?;
        let config = OracleConfig {
            budget: episode.oracle_budget.unwrap_or(config.budget),
            ..config
        };
        Self::new(
            scene,
            graph,
            navigable,
            goal.position,
            episode.target_object_id.or(goal.object_id),
            config,
        )
    }

    /// The settings.
    pub fn config(&self) -> &OracleConfig {
        &self.config
    }

    fn which_way(&self, at: [f32; 3], yaw: f32, remaining: u32) -> Result<OracleAnswer> {
        let p = Vec2::new(at[0], at[2]);
        let (path, total, then) = match (self.levels.is_some(), self.across(at)) {
            (true, None) => (None, 0.0, None),
            (true, Some((path, d, then))) => (path, d, then),
            (false, _) => (shortest_path(&self.navigable, p, self.goal)?, 0.0, None),
        };
        if let (None, Some(then)) = (&path, then) {
            // On a flight (or at its end): keep going along it.
            return Ok(OracleAnswer {
                text: format!("{}.", crate_capitalize(then)),
                answered: true,
                remaining,
                turn: Some(Turn::Straight),
                distance_m: Some(total),
                object_id: None,
                side: None,
            });
        }
        let Some(path) = path else {
            return Ok(OracleAnswer::silent(
                "I cannot find a way to the goal from where you are.".into(),
                remaining,
            ));
        };
        let d = if self.levels.is_some() {
            total
        } else {
            path.length
        };
        if d <= self.config.arrived_m {
            return Ok(OracleAnswer {
                text: "You are already there; stop here.".into(),
                answered: true,
                remaining,
                turn: Some(Turn::Straight),
                distance_m: Some(d),
                object_id: None,
                side: None,
            });
        }
        // Drop waypoints closer than 0.3 m (snap legs) so the first heading is meaningful.
        let mut pts = vec![path.points[0]];
        for &q in &path.points[1..] {
            if q.distance(*pts.last().unwrap_or(&q)) >= 0.3 {
                pts.push(q);
            }
        }
        if pts.len() < 2 {
            pts.push(match self.levels {
                // Across floors the path may end at a flight's end, not at the goal.
                Some(_) => path.points.last().copied().unwrap_or(self.goal),
                None => self.goal,
            });
        }
        if self.levels.is_some() && pts[0] == pts[1] {
            pts[1] = p + direction_of_yaw(yaw) * 0.3;
        }
        let headings = segment_headings(&pts);
        // Legs: merge segments joined without a named turn.
        let mut legs: Vec<(Turn, f32, usize)> = vec![(
            classify_turn(direction_of_yaw(yaw), headings[0], &self.config.turns),
            pts[0].distance(pts[1]),
            1,
        )];
        for i in 1..headings.len() {
            let t = classify_turn(headings[i - 1], headings[i], &self.config.turns);
            let len = pts[i].distance(pts[i + 1]);
            match (t, legs.last_mut()) {
                (Turn::Straight, Some(l)) => {
                    l.1 += len;
                    l.2 = i + 1;
                }
                _ => legs.push((t, len, i + 1)),
            }
        }
        let path3: Vec<glam::Vec3> = pts
            .iter()
            .map(|q| glam::Vec3::new(q.x, at[1], q.y))
            .collect();
        let rooms = rooms_along_path(&self.scene, &path3);
        let mut parts = Vec::new();
        for (k, &(turn, len, end)) in legs.iter().take(self.config.legs).enumerate() {
            let first = k == 0;
            let mv = match turn {
                Turn::Straight if first => format!("go straight ahead {}", metres(len)),
                Turn::Straight => format!("keep going {}", metres(len)),
                Turn::Slight(s) => format!("bear {} and go {}", side_word(s), metres(len)),
                Turn::Turn(s) => format!("turn {} and go {}", side_word(s), metres(len)),
                Turn::Around => format!("turn around and go {}", metres(len)),
            };
            // A room entered on this leg.
            let start = if first { 0 } else { legs[k - 1].2 };
            let entered = rooms
                .iter()
                .skip(1)
                .find(|(i, _)| *i >= start && *i < end)
                .and_then(|&(_, r)| self.scene.room(r));
            let mv = match entered {
                Some(r) => format!("{mv} into the {}", r.kind.words()),
                None => mv,
            };
            parts.push(mv);
        }
        let mut text = parts.join(", then ");
        if legs.len() > self.config.legs {
            text.push_str(", and ask again from there");
            if let Some(then) = then {
                // The way goes on to the stairs: say so now.
                text.push_str(&format!(" (after that, {then})"));
            }
        } else if let Some(then) = then {
            text.push_str(&format!(", then {then}"));
        }
        Ok(OracleAnswer {
            text: format!("{}.", crate_capitalize(&text)),
            answered: true,
            remaining,
            turn: Some(legs[0].0),
            distance_m: Some(d),
            object_id: None,
            side: None,
        })
    }

    fn am_i_close(&self, at: [f32; 3], remaining: u32) -> Result<OracleAnswer> {
        let p = Vec2::new(at[0], at[2]);
        let d = match &self.levels {
            Some(lf) => lf.distance(at).meters(),
            None => shortest_path(&self.navigable, p, self.goal)?.map(|path| path.length),
        };
        let Some(d) = d else {
            return Ok(OracleAnswer::silent(
                "I cannot tell: there is no way to the goal from where you are.".into(),
                remaining,
            ));
        };
        let b = self.config.buckets_m;
        let text = if d <= self.config.arrived_m {
            "Yes, you are there. Stop here.".to_string()
        } else if d <= b[0] {
            "You are very close, just a step or two away.".to_string()
        } else if d <= b[1] {
            format!("You are close, {} away.", metres(d))
        } else if d <= b[2] {
            format!("Not far now, {} away.", metres(d))
        } else {
            format!("No, you are still far, {} away.", metres(d))
        };
        Ok(OracleAnswer {
            text,
            answered: true,
            remaining,
            turn: None,
            distance_m: Some(d),
            object_id: None,
            side: None,
        })
    }

    /// Objects whose name, class or colour + class is `what`.
    fn find(&self, what: &str) -> Vec<&SceneObject> {
        let q = normalize(what);
        self.scene
            .objects
            .iter()
            .filter(|o| !o.is_structure() && self.graph.object(o.id).is_some())
            .filter(|o| normalize(&o.name) == q || o.class.words() == q || object_words(o) == q)
            .collect()
    }

    fn where_is(&self, what: &str, at: [f32; 3], yaw: f32, remaining: u32) -> OracleAnswer {
        let p = Vec2::new(at[0], at[2]);
        let level = self.scene.level_at_height(at[1]);
        let found = self.find(what);
        let q = normalize(what);
        let pick = found
            .iter()
            .find(|o| Some(o.id) == self.target)
            .or_else(|| {
                found.iter().min_by(|a, b| {
                    let da = Vec2::new(a.bbox.center().x, a.bbox.center().z).distance(p);
                    let db = Vec2::new(b.bbox.center().x, b.bbox.center().z).distance(p);
                    da.total_cmp(&db).then(a.id.cmp(&b.id))
                })
            })
            .copied();
        let Some(o) = pick else {
            // A room?
            let room = self
                .scene
                .rooms
                .iter()
                .filter(|r| r.kind.words() == q || normalize(&r.name) == q)
                .min_by(|a, b| {
                    let ca = Vec2::from(a.center()).distance(p);
                    let cb = Vec2::from(b.center()).distance(p);
                    ca.total_cmp(&cb).then(a.id.cmp(&b.id))
                });
            return match room {
                Some(r)
                    if r.contains(p.x, p.y)
                        && self.scene.room_level(r.id).unwrap_or(0) == level =>
                {
                    OracleAnswer {
                        text: format!("You are in the {} now.", r.kind.words()),
                        answered: true,
                        ..OracleAnswer::silent(String::new(), remaining)
                    }
                }
                Some(r) => {
                    let c = Vec2::from(r.center());
                    let side = env_side(side_of(p, yaw, c));
                    OracleAnswer {
                        text: format!(
                            "The {} is {}, {} away.",
                            r.kind.words(),
                            side_phrase(side),
                            metres(c.distance(p))
                        ),
                        answered: true,
                        side: Some(side),
                        ..OracleAnswer::silent(String::new(), remaining)
                    }
                }
                None => OracleAnswer::silent(
                    format!("I don't know of any {q} in this home."),
                    remaining,
                ),
            };
        };
        let c = o.bbox.center();
        let c = Vec2::new(c.x, c.z);
        let side = env_side(side_of(p, yaw, c));
        let mut place = String::new();
        if let Some(s) = self
            .graph
            .supports_of(o.id)
            .first()
            .and_then(|&s| self.scene.object(s))
        {
            place.push_str(&format!(" on the {}", s.class.words()));
        }
        let here = self.scene.room_at_level(level, p.x, p.y).map(|r| r.id);
        if let Some(r) = self.graph.room_of(o.id).and_then(|r| self.scene.room(r)) {
            if Some(r.id) == here {
                place.push_str(" here in this room");
            } else {
                place.push_str(&format!(" in the {}", r.kind.words()));
            }
        }
        OracleAnswer {
            text: format!(
                "The {}{place} is {}, {} away.",
                object_words(o),
                side_phrase(side),
                metres(c.distance(p))
            ),
            answered: true,
            remaining,
            turn: None,
            distance_m: None,
            object_id: Some(o.id),
            side: Some(side),
        }
    }
}

fn side_phrase(side: Side) -> &'static str {
    match side {
        Side::Ahead => "ahead of you",
        Side::Left => "on your left",
        Side::Right => "on your right",
        Side::Behind => "behind you",
    }
}

fn crate_capitalize(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().collect::<String>() + c.as_str(),
        None => String::new(),
    }
}

impl Oracle for ShortestPathOracle {
    fn ask(&mut self, query: &OracleQuery, position: [f32; 3], yaw: f32) -> Result<OracleAnswer> {
        check_finite("position", &position)?;
        check_finite("yaw", &[yaw])?;
        if self.asked >= self.config.budget {
            return Ok(OracleAnswer::silent(
                format!(
                    "You have used all {} of your questions; I cannot help any more.",
                    self.config.budget
                ),
                0,
            ));
        }
        self.asked += 1;
        let remaining = self.config.budget - self.asked;
        match query {
            OracleQuery::WhichWay => self.which_way(position, yaw, remaining),
            OracleQuery::AmIClose => self.am_i_close(position, remaining),
            OracleQuery::WhereIs(what) => Ok(self.where_is(what, position, yaw, remaining)),
        }
    }

    fn remaining(&self) -> u32 {
        self.config.budget.saturating_sub(self.asked)
    }
}

/// System prompt of the `LlmOracle` (feature `llm`).
pub const ORACLE_PROMPT: &str = "You are the guide of a robot that navigates a home and may \
ask you a few questions. You get the robot's question and the true answer, computed from the \
map. Reply to the robot as a helpful person would, in one or two short sentences, keeping every \
direction (left, right, ahead, behind, turn around), every distance, every object, colour and \
room of the true answer. Add nothing that is not in the true answer and never mention maps, \
coordinates or ids.";

/// An oracle that rephrases the answers of another one (usually the [`ShortestPathOracle`])
/// with an LLM. The inner oracle keeps the budget; answers without information (budget spent,
/// unknown object) are passed on as they are, so nothing is revealed once the budget is spent. A
/// failed call keeps the inner answer ([`vlnverse_instructions::llm::OnReject::Fallback`]) or is
/// an error ([`vlnverse_instructions::llm::OnReject::Error`]).
#[cfg(feature = "llm-oracle")]
#[derive(Debug)]
pub struct LlmOracle<O> {
    inner: O,
    client: vlnverse_instructions::llm::ChatClient,
    seed: u64,
}

#[cfg(feature = "llm-oracle")]
impl<O: Oracle> LlmOracle<O> {
    /// Wrap `inner`; `seed` is sent with every request.
    pub fn new(inner: O, config: vlnverse_instructions::llm::LlmConfig, seed: u64) -> Result<Self> {
        Ok(LlmOracle {
            inner,
            client: vlnverse_instructions::llm::ChatClient::new(config)?,
            seed,
        })
    }

    /// The wrapped oracle.
    pub fn inner(&self) -> &O {
        &self.inner
    }
}

#[cfg(feature = "llm-oracle")]
fn query_words(q: &OracleQuery) -> String {
    match q {
        OracleQuery::WhichWay => "Which way should I go?".into(),
        OracleQuery::WhereIs(x) => format!("Where is the {}?", normalize(x)),
        OracleQuery::AmIClose => "Am I close?".into(),
    }
}

#[cfg(feature = "llm-oracle")]
impl<O: Oracle> Oracle for LlmOracle<O> {
    fn ask(&mut self, query: &OracleQuery, position: [f32; 3], yaw: f32) -> Result<OracleAnswer> {
        use vlnverse_instructions::llm::{ChatMessage, OnReject};
        let ans = self.inner.ask(query, position, yaw)?;
        if !ans.answered {
            return Ok(ans);
        }
        let reply = self.client.chat(
            &[
                ChatMessage::system(ORACLE_PROMPT),
                ChatMessage::user(format!(
                    "Question: {}\nTrue answer: {}\nYour reply:",
                    query_words(query),
                    ans.text
                )),
            ],
            self.seed,
        );
        match (reply, self.client.config().on_reject) {
            (Ok(text), _) => Ok(OracleAnswer { text, ..ans }),
            (Err(e), OnReject::Fallback) => {
                tracing::warn!(error = %e, "LLM oracle call failed; keeping the plain answer");
                Ok(ans)
            }
            (Err(e), OnReject::Error) => Err(e.into()),
        }
    }

    fn remaining(&self) -> u32 {
        self.inner.remaining()
    }
}

#[cfg(test)]
mod tests {
    use super::OracleQuery;

    #[test]
    fn free_text_questions_map_to_queries() {
        assert_eq!(OracleQuery::parse("Which way?"), OracleQuery::WhichWay);
        assert_eq!(
            OracleQuery::parse("where should I go now"),
            OracleQuery::WhichWay
        );
        assert_eq!(OracleQuery::parse("Am I close?"), OracleQuery::AmIClose);
        assert_eq!(OracleQuery::parse("how far is it"), OracleQuery::AmIClose);
        assert_eq!(
            OracleQuery::parse("Where is the red mug?"),
            OracleQuery::WhereIs("red mug".into())
        );
        assert_eq!(
            OracleQuery::parse("find a coffee table"),
            OracleQuery::WhereIs("coffee table".into())
        );
    }
}
