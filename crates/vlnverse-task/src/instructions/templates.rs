//! The default, template-based instruction generator.

use super::path::{
    classify_turn, direction_of_yaw, env_side, floor_points, footprint, rect_distance,
    segment_headings, side_word, visible, wall_rects, Turn, TurnConfig,
};
use super::phrases::{self as ph, capitalize, decapitalize, fill, pick};
use super::{InstructionGenerator, PathContext};
use crate::episode::{GroundedObject, Instruction, Role, Side, Style};
use crate::error::{Result, TaskError};
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use vlnverse_env::scene_graph::{
    is_landmark, rooms_along_path, side_of_heading, Mention, ReferringExpression, Relation,
    RoomMention,
};
use vlnverse_env::{ObjectId, RoomId, Scene, SceneObject};

/// Settings of the [`TemplateGenerator`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct TemplateConfig {
    /// Landmarks are objects whose footprint comes within this many metres of the path.
    pub landmark_distance: f32,
    /// At most this many landmarks are named per straight leg of the path.
    pub max_landmarks_per_leg: usize,
    /// The end point is described by the landmark-sized object closest to the goal within
    /// this many metres (else by its room).
    pub end_object_distance: f32,
    /// The last metres of a sight line that may cross non-navigable cells (the navigable map is
    /// dilated by the agent radius around the seen object itself).
    pub sight_slack: f32,
    /// Turn thresholds.
    pub turns: TurnConfig,
}

impl Default for TemplateConfig {
    fn default() -> Self {
        TemplateConfig {
            landmark_distance: 1.5,
            max_landmarks_per_leg: 2,
            end_object_distance: 1.5,
            sight_slack: 0.4,
            turns: TurnConfig::default(),
        }
    }
}

impl TemplateConfig {
    /// Check the values; the error names the field.
    pub fn validate(&self) -> Result<()> {
        let pos = |field: &str, v: f32| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(TaskError::invalid(
                    format!("instructions.{field}"),
                    v,
                    "must be a finite number >= 0",
                ))
            }
        };
        pos("landmark_distance", self.landmark_distance)?;
        pos("end_object_distance", self.end_object_distance)?;
        pos("sight_slack", self.sight_slack)?;
        let t = &self.turns;
        if !(0.0 < t.slight_deg && t.slight_deg <= t.turn_deg && t.turn_deg <= t.around_deg)
            || t.around_deg > 180.0
        {
            return Err(TaskError::invalid(
                "instructions.turns",
                format!("{}/{}/{}", t.slight_deg, t.turn_deg, t.around_deg),
                "need 0 < slight_deg <= turn_deg <= around_deg <= 180",
            ));
        }
        Ok(())
    }
}

/// Deterministic, template-based generator grounded in the scene graph (the default).
///
/// The same context, target, style and seed always give the same instruction; every mentioned
/// object is listed in [`Instruction::grounding`].
#[derive(Clone, Debug, Default)]
pub struct TemplateGenerator {
    /// Settings.
    pub config: TemplateConfig,
}

impl TemplateGenerator {
    /// A generator with the given settings (checked).
    pub fn new(config: TemplateConfig) -> Result<Self> {
        config.validate()?;
        Ok(TemplateGenerator { config })
    }
}

/// A straight stretch of the path: segments `first..=last`, entered with `turn`.
struct Leg {
    first: usize,
    last: usize,
    turn: Turn,
}

/// "the red sofa" or "the sofa": the colour is used when the class alone is ambiguous in the
/// scene, and now and then otherwise.
fn object_phrase(scene: &Scene, o: &SceneObject, rng: &mut ChaCha8Rng) -> String {
    let same_class = scene
        .objects
        .iter()
        .filter(|x| x.class == o.class)
        .take(2)
        .count();
    if !o.color.is_empty() && (same_class > 1 || rng.random_bool(0.35)) {
        format!("the {} {}", o.color, o.class.words())
    } else {
        format!("the {}", o.class.words())
    }
}

fn room_phrase(scene: &Scene, room: RoomId) -> Option<String> {
    scene.room(room).map(|r| format!("the {}", r.kind.words()))
}

fn distance_phrase(d: f32, rng: &mut ChaCha8Rng) -> String {
    if d < 1.25 {
        pick(
            rng,
            &["a short way", "a step or two", "a little", "a few steps"],
        )
        .to_string()
    } else if d < 1.75 {
        pick(rng, &["about a metre and a half", "one or two metres"]).to_string()
    } else {
        let n = d.round() as u32;
        let about = pick(rng, &["about", "roughly", "around", "some"]);
        format!("{about} {n} metres")
    }
}

fn grounded(o: &SceneObject, role: Role, side: Option<Side>, idx: Option<usize>) -> GroundedObject {
    GroundedObject {
        object_id: o.id,
        class: o.class.name().to_string(),
        role,
        side,
        path_index: idx.map(|i| i as u32),
    }
}

fn check_path(path: &[[f32; 3]]) -> Result<()> {
    if path.len() < 2 {
        return Err(TaskError::invalid(
            "path",
            format!("{} points", path.len()),
            "a fine-grained instruction needs a path of at least two points",
        ));
    }
    if let Some((i, p)) = path
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|v| v.is_finite()))
    {
        return Err(TaskError::invalid(
            format!("path[{i}]"),
            format!("{p:?}"),
            "coordinates must be finite",
        ));
    }
    Ok(())
}

/// Join clauses into one sentence with varied connectors.
fn join_clauses(clauses: &[String], rng: &mut ChaCha8Rng) -> String {
    let mut s = String::new();
    for (i, c) in clauses.iter().enumerate() {
        if i > 0 {
            s.push_str(pick(rng, ph::AND));
        }
        s.push_str(c);
    }
    s
}

fn turn_clause(turn: Turn, start: bool, rng: &mut ChaCha8Rng) -> Option<String> {
    match turn {
        Turn::Straight => None,
        Turn::Around => Some(pick(rng, ph::TURN_AROUND).to_string()),
        Turn::Slight(s) => Some(fill(pick(rng, ph::SLIGHT_TURN), &[("dir", side_word(s))])),
        Turn::Turn(s) => {
            let bank = if start { ph::START_TURN } else { ph::TURN };
            Some(fill(pick(rng, bank), &[("dir", side_word(s))]))
        }
    }
}

/// Side of `center` seen from the end of the path, facing along the last segment.
fn end_side(pts: &[Vec2], headings: &[Vec2], center: Vec2) -> Option<Side> {
    let (p, h) = (pts.last()?, headings.last()?);
    Some(env_side(side_of_heading(*p, *h, center)))
}

impl TemplateGenerator {
    fn end_object<'s>(
        &self,
        ctx: &PathContext<'s>,
        end: Vec2,
        walls: &[(Vec2, Vec2)],
    ) -> Option<&'s SceneObject> {
        let mut best: Option<(f32, &SceneObject)> = None;
        for o in ctx.scene.objects.iter().filter(|o| is_landmark(o)) {
            let (lo, hi) = footprint(o);
            let d = rect_distance(end, lo, hi);
            if d > self.config.end_object_distance {
                continue;
            }
            let near = end.clamp(lo, hi);
            let aim = match (end - near).try_normalize() {
                Some(dir) if d > 0.15 => near + dir * 0.15,
                _ => end,
            };
            if !visible(ctx.navigable, walls, end, aim, self.config.sight_slack) {
                continue;
            }
            if best.is_none_or(|(bd, bo)| d < bd - 1e-6 || (d <= bd + 1e-6 && o.id < bo.id)) {
                best = Some((d, o));
            }
        }
        best.map(|(_, o)| o)
    }
}

impl InstructionGenerator for TemplateGenerator {
    fn fine(&self, ctx: &PathContext<'_>, seed: u64) -> Result<Instruction> {
        check_path(ctx.path)?;
        let cfg = &self.config;
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6669_6e65);
        let pts = floor_points(ctx.path);
        let n = pts.len();
        let headings = segment_headings(&pts);
        let path3: Vec<Vec3> = ctx.path.iter().map(|p| Vec3::from(*p)).collect();
        let walls = wall_rects(ctx.scene);

        // Legs between named turns.
        let mut legs = vec![Leg {
            first: 0,
            last: 0,
            turn: classify_turn(direction_of_yaw(ctx.start_yaw), headings[0], &cfg.turns),
        }];
        for w in 1..n - 1 {
            let t = classify_turn(headings[w - 1], headings[w], &cfg.turns);
            if t == Turn::Straight {
                if let Some(l) = legs.last_mut() {
                    l.last = w;
                }
            } else {
                legs.push(Leg {
                    first: w,
                    last: w,
                    turn: t,
                });
            }
        }
        let leg_of = |seg: usize| {
            let seg = seg.min(n - 2);
            legs.iter()
                .position(|l| l.first <= seg && seg <= l.last)
                .unwrap_or(legs.len() - 1)
        };

        let end = pts[n - 1];
        let end_obj = self.end_object(ctx, end, &walls);
        let landmarks = ctx.graph.landmarks_along_path(
            ctx.scene,
            &path3,
            |a, b| visible(ctx.navigable, &walls, a, b, cfg.sight_slack),
            cfg.landmark_distance,
        );
        let rooms = rooms_along_path(ctx.scene, &path3);

        let mut grounding = Vec::new();
        let mut sentences: Vec<String> = Vec::new();
        let mut pending_prefix = String::new();
        if let Some(&(_, r0)) = rooms.first() {
            if let Some(room) = room_phrase(ctx.scene, r0) {
                let s = fill(pick(&mut rng, ph::START_ROOM), &[("room", &room)]);
                if s.ends_with(',') {
                    pending_prefix = format!("{s} ");
                } else if !s.is_empty() {
                    sentences.push(s);
                }
            }
        }

        for (li, leg) in legs.iter().enumerate() {
            let mut clauses: Vec<String> = Vec::new();
            if let Some(t) = turn_clause(leg.turn, li == 0, &mut rng) {
                clauses.push(t);
            }
            let len: f32 = (leg.first..=leg.last)
                .map(|s| pts[s].distance(pts[s + 1]))
                .sum();
            // Landmarks of this leg: left / right / ahead, closest first, distinct classes.
            let mut mine: Vec<_> = landmarks
                .iter()
                .filter(|l| leg_of(l.path_index) == li)
                .filter(|l| Some(l.object) != end_obj.map(|o| o.id))
                .filter(|l| !matches!(env_side(l.side), Side::Behind))
                .collect();
            mine.sort_by(|a, b| {
                a.distance
                    .total_cmp(&b.distance)
                    .then(a.object.cmp(&b.object))
            });
            let mut chosen: Vec<&vlnverse_env::scene_graph::Landmark> = Vec::new();
            for l in mine {
                if chosen.len() >= cfg.max_landmarks_per_leg {
                    break;
                }
                let Some(o) = ctx.scene.object(l.object) else {
                    continue;
                };
                if chosen.iter().any(|c| {
                    ctx.scene
                        .object(c.object)
                        .is_some_and(|x| x.class == o.class)
                }) {
                    continue;
                }
                chosen.push(l);
            }
            chosen.sort_by_key(|l| (l.path_index, l.object));

            let mut movement = if rng.random_bool(0.5) {
                let d = distance_phrase(len, &mut rng);
                fill(pick(&mut rng, ph::MOVE_DIST), &[("dist", &d)])
            } else {
                pick(&mut rng, ph::MOVE).to_string()
            };
            let mut lm_clauses = Vec::new();
            for l in &chosen {
                let Some(o) = ctx.scene.object(l.object) else {
                    continue;
                };
                let side = env_side(l.side);
                let obj = object_phrase(ctx.scene, o, &mut rng);
                let c = if side == Side::Ahead {
                    fill(pick(&mut rng, ph::TOWARDS), &[("obj", &obj)])
                } else {
                    let sp = fill(pick(&mut rng, ph::SIDE), &[("dir", side_word(side))]);
                    fill(
                        pick(&mut rng, ph::PASS_SIDE),
                        &[("obj", &obj), ("side", &sp)],
                    )
                };
                lm_clauses.push(c);
                grounding.push(grounded(o, Role::Landmark, Some(side), Some(l.path_index)));
            }
            if let Some(first) = lm_clauses.first() {
                let sep = if first.starts_with("towards")
                    || first.starts_with("in the direction")
                    || first.starts_with("heading")
                    || first.starts_with("aiming")
                    || first.starts_with("making")
                {
                    " "
                } else {
                    ", "
                };
                movement = format!("{movement}{sep}{first}");
            }
            clauses.push(movement);
            if let Some(second) = lm_clauses.get(1) {
                clauses.push(format!("continue {second}"));
            }
            // Room changes on this leg.
            for k in 1..rooms.len() {
                if leg_of(rooms[k].0) != li {
                    continue;
                }
                let (Some(from), Some(to)) = (
                    room_phrase(ctx.scene, rooms[k - 1].1),
                    room_phrase(ctx.scene, rooms[k].1),
                ) else {
                    continue;
                };
                let to = if from == to {
                    to.replacen("the ", "the next ", 1)
                } else {
                    to
                };
                let c = match rng.random_range(0..3) {
                    0 => fill(
                        pick(&mut rng, ph::ROOM_TO_ROOM),
                        &[("from", &from), ("room", &to)],
                    ),
                    1 => fill(pick(&mut rng, ph::ENTER_ROOM), &[("room", &to)]),
                    _ => format!(
                        "{} and {}",
                        fill(pick(&mut rng, ph::LEAVE_ROOM), &[("room", &from)]),
                        fill(pick(&mut rng, ph::ENTER_ROOM), &[("room", &to)])
                    ),
                };
                clauses.push(c);
            }
            let mut s = join_clauses(&clauses, &mut rng);
            if li > 0 {
                s = format!("{}{s}", pick(&mut rng, ph::NEXT));
            }
            if !pending_prefix.is_empty() {
                s = format!("{}{}", std::mem::take(&mut pending_prefix), s);
            }
            sentences.push(format!("{}.", capitalize(&s)));
        }

        // The end point.
        let last_room = rooms.last().and_then(|&(_, r)| room_phrase(ctx.scene, r));
        let stop = if let Some(o) = end_obj {
            let (lo, hi) = footprint(o);
            let side = end_side(&pts, &headings, (lo + hi) * 0.5);
            let obj = object_phrase(ctx.scene, o, &mut rng);
            grounding.push(grounded(o, Role::Target, side, Some(n - 1)));
            let mut s = fill(pick(&mut rng, ph::STOP_AT), &[("obj", &obj)]);
            if let Some(sd @ (Side::Left | Side::Right)) = side {
                if rng.random_bool(0.5) {
                    let sp = fill(pick(&mut rng, ph::SIDE), &[("dir", side_word(sd))]);
                    s = format!("{s}, which is {sp}");
                }
            }
            s
        } else if let Some(room) = last_room {
            fill(pick(&mut rng, ph::STOP_ROOM), &[("room", &room)])
        } else {
            pick(&mut rng, ph::STOP).to_string()
        };
        let s = format!("{}{stop}", pick(&mut rng, ph::LAST));
        sentences.push(format!("{}.", capitalize(&s)));

        Ok(Instruction {
            instruction_text: sentences.join(" "),
            instruction_tokens: None,
            style: None,
            grounding,
            sub_instructions: Vec::new(),
        })
    }

    fn coarse(
        &self,
        ctx: &PathContext<'_>,
        target: ObjectId,
        style: Style,
        seed: u64,
    ) -> Result<Instruction> {
        let expr = coarse_expression(ctx, target, style)?;
        let salt = match style {
            Style::Formal => 0x666f_726d,
            Style::Natural => 0x6e61_7475,
            Style::Casual => 0x6361_7375,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(
            seed ^ salt ^ u64::from(target).wrapping_mul(0x9E37_79B9_7F4A_7C15),
        );
        let words = |m: &Mention| format!("the {}", m.words());
        let desc = match &expr.color {
            Some(c) => format!("the {c} {}", expr.class.words()),
            None => format!("the {}", expr.class.words()),
        };
        let (sup_bank, next_bank, near_bank) = match style {
            Style::Formal => (ph::FORMAL_SUP, ph::FORMAL_NEXT, ph::FORMAL_NEAR),
            Style::Natural => (ph::NATURAL_SUP, ph::NATURAL_NEXT, ph::NATURAL_NEAR),
            Style::Casual => (ph::CASUAL_SUP, ph::CASUAL_NEXT, ph::CASUAL_NEAR),
        };
        let sup = expr
            .support
            .as_ref()
            .map(|m| fill(pick(&mut rng, sup_bank), &[("obj", &words(m))]))
            .unwrap_or_default();
        let rel = match (&expr.reference, expr.relation) {
            (Some(m), Some(r)) => {
                let bank = if r == Relation::NextTo {
                    next_bank
                } else {
                    near_bank
                };
                fill(pick(&mut rng, bank), &[("obj", &words(m))])
            }
            _ => String::new(),
        };
        let room = expr.room.map(|r| format!("the {}", r.kind.words()));
        let text = match style {
            Style::Formal => {
                let rc = room
                    .as_ref()
                    .map(|r| fill(pick(&mut rng, ph::FORMAL_ROOM), &[("room", r)]))
                    .unwrap_or_default();
                fill(
                    pick(&mut rng, ph::FORMAL),
                    &[("desc", &desc), ("sup", &sup), ("rel", &rel), ("room", &rc)],
                )
            }
            Style::Natural => match &room {
                Some(r) => fill(
                    pick(&mut rng, ph::NATURAL_ROOM),
                    &[("desc", &desc), ("sup", &sup), ("rel", &rel), ("room", r)],
                ),
                None => fill(
                    pick(&mut rng, ph::NATURAL),
                    &[("desc", &desc), ("sup", &sup), ("rel", &rel)],
                ),
            },
            Style::Casual => {
                let rc = room
                    .as_ref()
                    .map(|r| fill(pick(&mut rng, ph::CASUAL_ROOM), &[("room", r)]))
                    .unwrap_or_default();
                fill(
                    pick(&mut rng, ph::CASUAL),
                    &[("desc", &desc), ("sup", &sup), ("rel", &rel), ("room", &rc)],
                )
            }
        };
        let text = capitalize_sentence(&text, style);

        // Grounding: seen from the end of the path, facing along its last segment.
        let pts = floor_points(ctx.path);
        let headings = segment_headings(&pts);
        let idx = pts.len().checked_sub(1);
        let mut grounding = Vec::new();
        let mut push = |id: ObjectId, role: Role| {
            if let Some(o) = ctx.scene.object(id) {
                let (lo, hi) = footprint(o);
                let side = if pts.len() >= 2 {
                    end_side(&pts, &headings, (lo + hi) * 0.5)
                } else {
                    None
                };
                grounding.push(grounded(o, role, side, idx));
            }
        };
        push(expr.target, Role::Target);
        if let Some(m) = &expr.support {
            push(m.object, Role::Reference);
        }
        if let Some(m) = &expr.reference {
            push(m.object, Role::Reference);
        }
        Ok(Instruction {
            instruction_text: text,
            instruction_tokens: None,
            style: Some(style),
            grounding,
            sub_instructions: Vec::new(),
        })
    }

    fn chain(&self, parts: &[Instruction], seed: u64) -> Result<Instruction> {
        chain_parts(parts, seed)
    }
}

fn capitalize_sentence(s: &str, style: Style) -> String {
    match style {
        Style::Casual => s.to_string(),
        _ => capitalize(s),
    }
}

/// A short description of `o` alone in the scene: its class, else colour + class; `None` when
/// neither is unique.
fn unique_mention(ctx: &PathContext<'_>, o: &SceneObject) -> Option<Mention> {
    vlnverse_env::scene_graph::unique_mention(ctx.scene, ctx.graph, o)
}

/// The description a coarse instruction of `target` renders, unique within the scene: the scene
/// graph's shortest referring expression, enriched per style so that it names the class, the
/// colour and a relation to a reference object or room (formal: colour, support or reference
/// object, room; natural: colour, room, support or reference; casual: colour, support or
/// reference, else room). Every addition is checked with
/// [`vlnverse_env::scene_graph::ReferringExpression::matches`]; the result always matches
/// exactly `[target]`.
pub fn coarse_expression(
    ctx: &PathContext<'_>,
    target: ObjectId,
    style: Style,
) -> Result<ReferringExpression> {
    let expr = ctx
        .graph
        .referring_expression(ctx.scene, target)
        .ok_or_else(|| {
            TaskError::invalid(
                "target",
                target,
                format!(
                    "scene `{}`: no description picks out this object alone (it is structure, \
                     missing from the scene graph, or indistinguishable from another object)",
                    ctx.scene.id
                ),
            )
        })?;
    let Some(obj) = ctx.scene.object(target) else {
        return Ok(expr);
    };
    let unique = |e: &ReferringExpression| e.matches(ctx.scene, ctx.graph) == [target];
    let mut e = expr;
    let mut try_add = |e: &mut ReferringExpression, f: &dyn Fn(&mut ReferringExpression)| {
        let mut c = e.clone();
        f(&mut c);
        if c != *e && unique(&c) {
            *e = c;
            true
        } else {
            false
        }
    };
    if !obj.color.is_empty() {
        try_add(&mut e, &|c| c.color = Some(obj.color.clone()));
    }
    let add_room = |c: &mut ReferringExpression| {
        if let Some(r) = ctx.graph.room_of(target) {
            if let Some(room) = ctx.scene.room(r) {
                c.room = Some(RoomMention {
                    room: r,
                    kind: room.kind,
                });
            }
        }
    };
    let add_support = |c: &mut ReferringExpression| {
        if c.support.is_some() {
            return;
        }
        let mut supports = ctx.graph.supports_of(target);
        if let Some(s) = obj.supported_by {
            supports.sort_by_key(|&x| x != s);
        }
        if let Some(s) = supports.first().and_then(|&s| ctx.scene.object(s)) {
            c.support = Some(Mention {
                object: s.id,
                class: s.class,
                color: None,
            });
        }
    };
    let add_reference = |c: &mut ReferringExpression| {
        if c.reference.is_some() {
            return;
        }
        let support = c.support.as_ref().map(|m| m.object);
        for rel in [Relation::NextTo, Relation::Near] {
            let mut ns = ctx.graph.neighbours(target, rel);
            ns.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
            for (n, _) in ns {
                let Some(o) = ctx.scene.object(n) else {
                    continue;
                };
                if o.class == obj.class || o.is_structure() || Some(n) == support {
                    continue;
                }
                if let Some(m) = unique_mention(ctx, o) {
                    c.relation = Some(rel);
                    c.reference = Some(m);
                    return;
                }
            }
        }
    };
    let relation = |e: &mut ReferringExpression,
                    try_add: &mut dyn FnMut(
        &mut ReferringExpression,
        &dyn Fn(&mut ReferringExpression),
    ) -> bool| {
        if e.support.is_none() && e.reference.is_none() && !try_add(e, &add_support) {
            try_add(e, &add_reference);
        }
    };
    match style {
        Style::Formal => {
            relation(&mut e, &mut try_add);
            try_add(&mut e, &add_room);
        }
        Style::Natural => {
            try_add(&mut e, &add_room);
            relation(&mut e, &mut try_add);
        }
        Style::Casual => {
            relation(&mut e, &mut try_add);
            if e.support.is_none() && e.reference.is_none() {
                try_add(&mut e, &add_room);
            }
        }
    }
    Ok(e)
}

/// Join coarse sub-instructions in order: "First, ...; then ...; finally ...". The grounding of
/// every part is kept as given (shift path indices with [`super::offset_grounding`] first when
/// the parts' paths are concatenated); `sub_instructions` lists the parts' texts; the style is
/// the parts' common style, if any.
pub fn chain_parts(parts: &[Instruction], seed: u64) -> Result<Instruction> {
    if parts.is_empty() {
        return Err(TaskError::invalid(
            "parts",
            0,
            "a chained instruction needs at least one part",
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6368_6169);
    let subs: Vec<String> = parts.iter().map(|p| p.instruction_text.clone()).collect();
    let style = parts[0]
        .style
        .filter(|s| parts.iter().all(|p| p.style == Some(*s)));
    let text = if parts.len() == 1 {
        subs[0].clone()
    } else {
        let mut pieces = Vec::new();
        for (i, t) in subs.iter().enumerate() {
            let body = decapitalize(t.trim().trim_end_matches(['.', '!']));
            let opener = if i == 0 {
                pick(&mut rng, ph::CHAIN_FIRST)
            } else if i + 1 == subs.len() {
                pick(&mut rng, ph::CHAIN_LAST)
            } else {
                pick(&mut rng, ph::CHAIN_MID)
            };
            pieces.push(format!("{opener}{body}"));
        }
        format!("{}.", pieces.join("; "))
    };
    Ok(Instruction {
        instruction_text: text,
        instruction_tokens: None,
        style,
        grounding: parts.iter().flat_map(|p| p.grounding.clone()).collect(),
        sub_instructions: subs,
    })
}
