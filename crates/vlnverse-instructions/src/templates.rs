//! The default, template-based instruction generator.

use super::describe::{content_name, places, Place};
use super::lexicon::{
    color_phrases, distinct_uses, material_noun, material_words, number_word, object_names, plural,
    shape_words,
};
use super::path::{env_side, floor_points, footprint, rect_distance, segment_headings, TurnConfig};
use super::phrases::{self as ph, capitalize, decapitalize, fill, pick};
use super::{InstructionGenerator, PathContext};
use glam::Vec2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use vlnverse_env::scene_graph::{
    side_of_heading, Mention, ReferringExpression, Relation, RoomMention,
};
use vlnverse_env::{ObjectId, Scene, SceneObject};
use vlnverse_score::episode::{GroundedObject, Instruction, Role, Side, Style};
use vlnverse_score::{DataError, Result};

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
                Err(DataError::invalid(
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
            return Err(DataError::invalid(
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

/// Side of `center` seen from the end of the path, facing along the last segment.
fn end_side(pts: &[Vec2], headings: &[Vec2], center: Vec2) -> Option<Side> {
    let (p, h) = (pts.last()?, headings.last()?);
    Some(env_side(side_of_heading(*p, *h, center)))
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

impl InstructionGenerator for TemplateGenerator {
    fn fine(&self, ctx: &PathContext<'_>, seed: u64) -> Result<Instruction> {
        let mut ins = super::fine::fine(&self.config, ctx, seed)?;
        let american = writes_american(seed);
        ins.instruction_text = spelled(&outdoor_prepositions(&ins.instruction_text), american);
        for s in &mut ins.sub_instructions {
            *s = spelled(&outdoor_prepositions(s), american);
        }
        Ok(ins)
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
        let name = match ctx.scene.object(target) {
            Some(o) => other_name(o, coarse_synonym(style), &mut rng),
            None => expr.class.words(),
        };
        let desc = coarse_description(ctx, target, &expr, &name, &mut rng);
        let (sup, rel) = coarse_relations(ctx, &expr, style, &mut rng);
        let room = coarse_room(ctx, &expr, &mut rng);
        // Now and then a remark on the target from what the scene model holds: its material,
        // the shade of its colour, what its class is for, or where it stands in its room.
        let mut grounding = coarse_grounding(ctx, &expr);
        let remark = ctx
            .scene
            .object(target)
            .filter(|_| rng.random_bool(0.2))
            .and_then(|o| target_remark(ctx, o, &name, style, &mut rng, &mut grounding))
            .unwrap_or_default();
        let parts = CoarseParts {
            desc,
            sup,
            rel,
            room,
            remark,
        };
        let text = capitalize_sentence(&coarse_sentence(style, &parts, &mut rng), style);
        let text = spelled(&outdoor_prepositions(&text), writes_american(seed ^ salt));
        let ins = Instruction {
            instruction_text: text,
            instruction_tokens: None,
            style: Some(style),
            grounding,
            sub_instructions: Vec::new(),
        };
        // On a path that leads to the target, a reference out of reach of its end (a
        // nightstand beyond the far end of the long bed it describes) is no help there: an
        // error, so the pipeline samples again.
        let problems = super::check_grounding(ctx, &ins, COARSE_REACH);
        // Checked on the target alone only when something is out of reach (rarely).
        let leads_there = || {
            let target_only = Instruction {
                grounding: ins.grounding.iter().take(1).cloned().collect(),
                ..Instruction::default()
            };
            super::check_grounding(ctx, &target_only, COARSE_REACH).is_empty()
        };
        if let Some(p) = problems.first().filter(|_| leads_there()) {
            return Err(DataError::invalid(
                "target",
                target,
                format!("scene `{}`: {p}", ctx.scene.id),
            ));
        }
        Ok(ins)
    }

    fn chain(&self, parts: &[Instruction], seed: u64) -> Result<Instruction> {
        chain_parts(parts, seed)
    }
}

/// A balcony is not a room one is "in": "in the balcony" becomes "on the balcony", "into" becomes
/// "out onto", "inside" becomes "out on".
fn outdoor_prepositions(text: &str) -> String {
    if !text.contains("balcony") {
        return text.to_string();
    }
    let mut out = text.to_string();
    for size in ["", "small ", "little ", "large ", "big "] {
        let place = format!("the {size}balcony");
        for (from, to) in [
            ("into", "out onto"),
            ("inside", "out on"),
            ("over in", "out on"),
            ("in", "on"),
            ("Into", "Out onto"),
            ("Inside", "Out on"),
            ("In", "On"),
        ] {
            out = replace_words(&out, &format!("{from} {place}"), &format!("{to} {place}"));
        }
    }
    out
}

/// Whether the writer of the instruction seeded `seed` spells the American way ("gray"), as
/// some of the people who wrote R2R's directions did (a third of its greys are grays).
fn writes_american(seed: u64) -> bool {
    ChaCha8Rng::seed_from_u64(seed ^ 0x7370_656c).random_bool(0.25)
}

/// `text` in the writer's spelling.
fn spelled(text: &str, american: bool) -> String {
    if american {
        replace_words(text, "grey", "gray")
    } else {
        text.to_string()
    }
}

/// `text` with every `from` that starts a word replaced by `to`.
fn replace_words(text: &str, from: &str, to: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find(from) {
        let starts_word = rest[..i]
            .chars()
            .next_back()
            .is_none_or(|c| !c.is_alphanumeric());
        out.push_str(&rest[..i]);
        out.push_str(if starts_word { to } else { from });
        rest = &rest[i + from.len()..];
    }
    out.push_str(rest);
    out
}

/// The pieces of a coarse instruction before they are put in a sentence.
struct CoarseParts {
    /// The target: "the tall dark red sofa".
    desc: String,
    /// What it stands on (" on the rug"), or "".
    sup: String,
    /// Its relation to a reference object (" next to the lamp"), or "".
    rel: String,
    /// Its room ("the spacious kitchen").
    room: Option<String>,
    /// A remark on the target (". It is made of wood"), or "".
    remark: String,
}

/// "the " and a mention's words: its colour, if any, and its class's vocabulary name or, now and
/// then, another name of the object ("the shelf" for the wall shelf), as for the target.
fn mention_words(ctx: &PathContext<'_>, m: &Mention, rng: &mut ChaCha8Rng) -> String {
    let name = match ctx.scene.object(m.object) {
        Some(o) => other_name(o, 0.2, rng),
        None => m.class.words(),
    };
    match &m.color {
        Some(c) => format!("the {c} {name}"),
        None => format!("the {name}"),
    }
}

/// How far from the path's end every object a coarse instruction names may stand (m, to its
/// footprint).
pub(crate) const COARSE_REACH: f32 = 2.5;

/// How often a coarse target goes by another of its names ("the couch", "the refrigerator")
/// rather than its class's vocabulary name, by style: a formal request keeps to the plainest.
fn coarse_synonym(style: Style) -> f64 {
    match style {
        Style::Formal => 0.15,
        Style::Natural | Style::Casual => 0.3,
    }
}

/// The class's vocabulary name of `o`, or with probability `p` another of the object's names
/// (one true of this object: "loveseat" only for a sofa for two).
fn other_name(o: &SceneObject, p: f64, rng: &mut ChaCha8Rng) -> String {
    let plain = o.class.words();
    let others: Vec<&str> = object_names(o)
        .into_iter()
        .filter(|n| *n != plain)
        .collect();
    if !others.is_empty() && rng.random_bool(p) {
        pick(rng, &others).to_string()
    } else {
        plain
    }
}

/// The target described: size and shape words the geometry supports may precede the colour,
/// which stays next to the noun `name` (see [`other_name`]).
fn coarse_description(
    ctx: &PathContext<'_>,
    target: ObjectId,
    expr: &ReferringExpression,
    name: &str,
    rng: &mut ChaCha8Rng,
) -> String {
    let shape = ctx.scene.object(target).and_then(|o| {
        let peers: Vec<&SceneObject> = ctx
            .graph
            .objects_of_class(o.class)
            .iter()
            .filter_map(|&id| ctx.scene.object(id))
            .collect();
        // Never an adjective the name already says ("the low coffee table" stays, "the
        // low-slung low table" does not).
        let w: Vec<&str> = shape_words(o, &peers)
            .into_iter()
            .filter(|a| !name.split(' ').any(|n| a.contains(n) || n.contains(a)))
            .collect();
        (!w.is_empty() && rng.random_bool(0.3)).then(|| pick(rng, &w).to_string())
    });
    let mut desc = String::from("the ");
    if let Some(a) = &shape {
        desc.push_str(a);
        desc.push(' ');
    }
    if let Some(c) = &expr.color {
        desc.push_str(c);
        desc.push(' ');
    }
    desc.push_str(name);
    desc
}

/// What the target stands on, and its relation to the reference object, in the style's
/// phrases (each "" when the expression has none).
fn coarse_relations(
    ctx: &PathContext<'_>,
    expr: &ReferringExpression,
    style: Style,
    rng: &mut ChaCha8Rng,
) -> (String, String) {
    let (sup_bank, next_bank, near_bank) = match style {
        Style::Formal => (ph::FORMAL_SUP, ph::FORMAL_NEXT, ph::FORMAL_NEAR),
        Style::Natural => (ph::NATURAL_SUP, ph::NATURAL_NEXT, ph::NATURAL_NEAR),
        Style::Casual => (ph::CASUAL_SUP, ph::CASUAL_NEXT, ph::CASUAL_NEAR),
    };
    let sup = expr
        .support
        .as_ref()
        .map(|m| {
            let obj = mention_words(ctx, m, rng);
            fill(pick(rng, &sup_bank), &[("obj", &obj)])
        })
        .unwrap_or_default();
    let rel = match (&expr.reference, expr.relation) {
        (Some(m), Some(r)) => {
            let bank = if closest_of_its_class(ctx, expr.target, m.object) && rng.random_bool(0.3) {
                ph::CLOSEST
            } else if r == Relation::NextTo {
                next_bank
            } else {
                near_bank
            };
            let obj = mention_words(ctx, m, rng);
            fill(pick(rng, &bank), &[("obj", &obj)])
        }
        _ => String::new(),
    };
    (sup, rel)
}

/// Whether `target` is clearly the closest of its class to `reference` (by 30 cm or more,
/// footprint to footprint), so "the cup closest to the lamp" names it.
fn closest_of_its_class(ctx: &PathContext<'_>, target: ObjectId, reference: ObjectId) -> bool {
    let (Some(t), Some(r)) = (ctx.scene.object(target), ctx.scene.object(reference)) else {
        return false;
    };
    let (rlo, rhi) = footprint(r);
    let gap = |o: &SceneObject| {
        let (lo, hi) = footprint(o);
        rect_distance((lo + hi) * 0.5, rlo, rhi)
    };
    let mine = gap(t);
    ctx.scene
        .objects
        .iter()
        .filter(|o| o.class == t.class && o.id != t.id)
        .all(|o| gap(o) > mine + 0.3)
}

/// The target's room, now and then with its size from the floor area ("the spacious kitchen").
fn coarse_room(
    ctx: &PathContext<'_>,
    expr: &ReferringExpression,
    rng: &mut ChaCha8Rng,
) -> Option<String> {
    expr.room.map(|r| {
        // Named with its type's words (readers and agents look for "bedroom").
        if let Some(name) = content_name(ctx.scene, r.room, 0.3, true, rng) {
            return name;
        }
        let area = ctx.scene.room(r.room).map_or(15.0, |x| x.area());
        let size: &[&str] = if area > 24.0 {
            &["large", "big"]
        } else if area < 8.0 {
            &["small", "little"]
        } else {
            &[]
        };
        if !size.is_empty() && rng.random_bool(0.25) {
            format!("the {} {}", pick(rng, size), r.kind.words())
        } else {
            format!("the {}", r.kind.words())
        }
    })
}

/// The coarse sentence in the style's register: an opener, the core sentence (with the room
/// where the style's core has one), the remark and a closer.
fn coarse_sentence(style: Style, p: &CoarseParts, rng: &mut ChaCha8Rng) -> String {
    let (desc, sup, rel, remark) = (&p.desc, &p.sup, &p.rel, &p.remark);
    match style {
        Style::Formal => {
            let rc = p
                .room
                .as_ref()
                .map(|r| fill(pick(rng, &ph::FORMAL_ROOM), &[("room", r)]))
                .unwrap_or_default();
            let core = fill(
                pick(rng, &ph::FORMAL),
                &[("desc", desc), ("sup", sup), ("rel", rel), ("room", &rc)],
            );
            let open = pick(rng, &ph::FORMAL_OPEN);
            // "In this house, proceed to ...", not "In this house, Proceed".
            let core = if open.ends_with(", ") {
                decapitalize(&core)
            } else {
                core
            };
            let close = closer(&core, pick(rng, &ph::FORMAL_CLOSE), ".");
            format!("{open}{core}{remark}{close}")
        }
        Style::Natural => {
            let core = match &p.room {
                Some(r) => fill(
                    pick(rng, &ph::NATURAL_ROOM),
                    &[("desc", desc), ("sup", sup), ("rel", rel), ("room", r)],
                ),
                None => fill(
                    pick(rng, &ph::NATURAL),
                    &[("desc", desc), ("sup", sup), ("rel", rel)],
                ),
            };
            let open = pick(rng, &ph::NATURAL_OPEN);
            let core = if open.ends_with(", ") || open.ends_with(": ") {
                decapitalize(&core)
            } else {
                core
            };
            let close = closer(&core, pick(rng, &ph::NATURAL_CLOSE), ".");
            let close = if !remark.is_empty() && close.starts_with(',') {
                "."
            } else {
                close
            };
            format!("{open}{core}{remark}{close}")
        }
        Style::Casual => {
            let rc = p
                .room
                .as_ref()
                .map(|r| fill(pick(rng, &ph::CASUAL_ROOM), &[("room", r)]))
                .unwrap_or_default();
            let core = fill(
                pick(rng, &ph::CASUAL),
                &[("desc", desc), ("sup", sup), ("rel", rel), ("room", &rc)],
            );
            let open = pick(rng, &ph::CASUAL_OPEN);
            let close = closer(&core, pick(rng, &ph::CASUAL_CLOSE), "");
            format!("{open}{core}{remark}{close}")
        }
    }
}

/// `close`, or `plain` when both it and the core sentence say to stop or wait ("Find the desk
/// and stop there. Stop when you get there.").
fn closer<'a>(core: &str, close: &'a str, plain: &'a str) -> &'a str {
    let halts = |s: &str| {
        let s = s.to_lowercase();
        ["stop", "wait", "remain"].iter().any(|w| s.contains(w))
    };
    if halts(core) && halts(close) {
        plain
    } else {
        close
    }
}

/// The grounding of a coarse instruction: the target, what it stands on and its reference
/// object, seen from the end of the path, facing along its last segment.
fn coarse_grounding(ctx: &PathContext<'_>, expr: &ReferringExpression) -> Vec<GroundedObject> {
    let mut grounding = Vec::new();
    let mut push = |id: ObjectId, role: Role| {
        if let Some(o) = ctx.scene.object(id) {
            grounding.push(grounded_at_end(ctx, o, role));
        }
    };
    push(expr.target, Role::Target);
    if let Some(m) = &expr.support {
        push(m.object, Role::Reference);
    }
    if let Some(m) = &expr.reference {
        push(m.object, Role::Reference);
    }
    grounding
}

/// The grounding of `o` seen from the end of the path, facing along its last segment.
fn grounded_at_end(ctx: &PathContext<'_>, o: &SceneObject, role: Role) -> GroundedObject {
    let pts = floor_points(ctx.path);
    let headings = segment_headings(&pts);
    let (lo, hi) = footprint(o);
    let side = if pts.len() >= 2 {
        end_side(&pts, &headings, (lo + hi) * 0.5)
    } else {
        None
    };
    grounded(o, role, side, pts.len().checked_sub(1))
}

/// A remark on `o` in the style's register ("It is made of wood", " - kinda navy"), from its
/// material, the shade of its colour, its class's use or its place in the room; `None` when the
/// scene model holds none of these.
fn target_remark(
    ctx: &PathContext<'_>,
    o: &SceneObject,
    name: &str,
    style: Style,
    rng: &mut ChaCha8Rng,
    grounding: &mut Vec<GroundedObject>,
) -> Option<String> {
    let (mat_b, shade_b, use_b, place_b, count_b) = match style {
        Style::Formal => (
            ph::FORMAL_MATERIAL,
            ph::FORMAL_SHADE,
            ph::FORMAL_USE,
            ph::FORMAL_PLACE,
            ph::FORMAL_COUNT,
        ),
        Style::Natural => (
            ph::NATURAL_MATERIAL,
            ph::NATURAL_SHADE,
            ph::NATURAL_USE,
            ph::NATURAL_PLACE,
            ph::NATURAL_COUNT,
        ),
        Style::Casual => (
            ph::CASUAL_MATERIAL,
            ph::CASUAL_SHADE,
            ph::CASUAL_USE,
            ph::CASUAL_PLACE,
            ph::CASUAL_COUNT,
        ),
    };
    let mats = material_words(o);
    // Shades only: the plain colour word is already in the description when it is needed.
    let shades: Vec<String> = color_phrases(o).into_iter().skip(1).collect();
    let peers = class_in_room(ctx.scene, o);
    let uses = distinct_uses(o, &peers);
    let place = super::describe::room_feature(ctx.scene, o);
    // Places the goal can be seen from: the path ends within reach of the target, and the
    // pieces a place names stand within a few metres of it.
    let end = floor_points(ctx.path).last().copied();
    let spatial: Vec<Place<'_>> = places(ctx, o)
        .into_iter()
        .filter(|p| {
            p.objects().iter().all(|x| {
                let (lo, hi) = footprint(x);
                end.is_some_and(|e| rect_distance(e, lo, hi) <= 2.5)
            })
        })
        .collect();
    // Counted by a name true of each of them ("two loveseats" only when both are for two).
    let count_name = if peers.iter().all(|p| object_names(p).contains(&name)) {
        name.to_string()
    } else {
        o.class.words()
    };
    let count = count_phrase(peers.len(), &count_name);
    let mut kinds: Vec<u8> = Vec::new();
    for (k, ok) in [
        (0u8, !mats.is_empty()),
        (1, !shades.is_empty()),
        (2, !uses.is_empty()),
        (3, place.is_some()),
        (4, !spatial.is_empty()),
        (5, count.is_some()),
    ] {
        if ok {
            kinds.push(k);
        }
    }
    if kinds.is_empty() {
        return None;
    }
    Some(match kinds[rng.random_range(0..kinds.len())] {
        0 => {
            let a = pick(rng, mats);
            fill(pick(rng, &mat_b), &[("a", a), ("m", material_noun(a))])
        }
        1 => {
            let c = &shades[rng.random_range(0..shades.len())];
            fill(pick(rng, &shade_b), &[("c", c)])
        }
        2 => fill(
            pick(rng, &use_b),
            &[("use", pick(rng, &uses)), ("name", name)],
        ),
        3 => fill(
            pick(rng, &place_b),
            &[("f", pick(rng, place.unwrap_or(&[])))],
        ),
        5 => {
            let (n, names) = count.unwrap_or_default();
            fill(pick(rng, &count_b), &[("n", &n), ("names", &names)])
        }
        _ => {
            let p = &spatial[rng.random_range(0..spatial.len())];
            for x in p.objects() {
                grounding.push(grounded_at_end(ctx, x, Role::Reference));
            }
            fill(pick(rng, &place_b), &[("f", &p.phrase(rng))])
        }
    })
}

/// How many objects of `o`'s class its room holds, as a number word, and the class name
/// `name` in the plural: `None` for one alone, for more than six (nobody counts those), and for
/// names with no plural ("shoes", "shampoo").
pub(crate) fn same_class_in_room(
    ctx: &PathContext<'_>,
    o: &SceneObject,
    name: &str,
) -> Option<(String, String)> {
    count_phrase(class_in_room(ctx.scene, o).len(), name)
}

/// The objects of `o`'s class in its room, `o` among them (none when it is in no room).
fn class_in_room<'a>(scene: &'a Scene, o: &SceneObject) -> Vec<&'a SceneObject> {
    let Some(room) = o.room else {
        return Vec::new();
    };
    scene
        .objects
        .iter()
        .filter(|x| x.class == o.class && x.room == Some(room))
        .collect()
}

/// [`same_class_in_room`] for `n` objects of the class in the room.
fn count_phrase(n: usize, name: &str) -> Option<(String, String)> {
    if name.ends_with('s') || NO_PLURAL.contains(&name) {
        return None;
    }
    (2..=6)
        .contains(&n)
        .then(|| (number_word(n as u32), plural(name)))
}

/// Class names that take no plural.
const NO_PLURAL: [&str; 2] = ["shampoo", "toilet paper"];

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
            DataError::invalid(
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

/// Join coarse sub-instructions in order: "First, go to ... Then ... Finally, ...", one sentence
/// per part (casual parts: one lower-case line, "first go to ..., then ..."). A part's opener
/// ("Okay, ", "Your task is as follows. ") is left out, as the chain opens each part itself.
/// The grounding of every part is kept as given (shift path indices with
/// [`super::offset_grounding`] first when the parts' paths are concatenated);
/// `sub_instructions` lists the parts' texts as they stand in the chain (without openers); the
/// style is the parts' common style, if any.
pub fn chain_parts(parts: &[Instruction], seed: u64) -> Result<Instruction> {
    if parts.is_empty() {
        return Err(DataError::invalid(
            "parts",
            0,
            "a chained instruction needs at least one part",
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6368_6169);
    let style = parts[0]
        .style
        .filter(|s| parts.iter().all(|p| p.style == Some(*s)));
    let casual = style == Some(Style::Casual);
    let subs: Vec<String> = if parts.len() == 1 {
        vec![parts[0].instruction_text.clone()]
    } else {
        parts
            .iter()
            .map(|p| {
                let t = without_openers(p.instruction_text.trim());
                if p.style == Some(Style::Casual) {
                    t
                } else {
                    capitalize(&t)
                }
            })
            .collect()
    };
    let text = if parts.len() == 1 {
        subs[0].clone()
    } else {
        let mut pieces = Vec::new();
        for (i, t) in subs.iter().enumerate() {
            let t = t.trim_end_matches(['.', '!']);
            // "I" stays a capital.
            let body = if t.starts_with("I ") || t.starts_with("I'") {
                t.to_string()
            } else {
                decapitalize(t)
            };
            if casual {
                // One line: "go to ..., then ... and then ..."; a "please" closes the line,
                // not a part in the middle of it.
                let join = if i == 0 {
                    String::new()
                } else {
                    let j = pick(&mut rng, &ph::CHAIN_CASUAL);
                    // After a part with a clause of its own ("..., it's against the wall"),
                    // the next one is set off by a comma too.
                    let clause = subs[i - 1].contains(", ");
                    if clause && !j.starts_with(',') {
                        format!(",{j}")
                    } else {
                        j.to_string()
                    }
                };
                let body = if i + 1 < subs.len() {
                    body.strip_suffix(" please").unwrap_or(&body).to_string()
                } else {
                    body
                };
                // "..., then can you go to ..." reads as two requests run together: a later
                // part drops its "can you".
                let body = match body.strip_prefix("can you ") {
                    Some(rest) if i > 0 => rest.to_string(),
                    _ => body,
                };
                pieces.push(format!("{join}{body}"));
                continue;
            }
            // One "please" to a request: a later part drops its own ("Then, navigate to ...",
            // not "Then, please navigate to ..."), a part before the last its closing one.
            let body = match body.strip_prefix("please ") {
                Some(rest) if i > 0 => rest.to_string(),
                _ => body,
            };
            let body = if i + 1 < subs.len() {
                body.replace(", please", "")
            } else {
                body
            };
            let opener = if i == 0 {
                // No "First, take the stairs up first."
                let first = pick(&mut rng, &ph::CHAIN_FIRST);
                if body
                    .split(|c: char| !c.is_alphanumeric())
                    .any(|w| w == "first")
                {
                    ""
                } else {
                    first
                }
            } else if i + 1 == subs.len() {
                pick(&mut rng, &ph::CHAIN_LAST)
            } else {
                pick(&mut rng, &ph::CHAIN_MID)
            };
            pieces.push(format!("{}.", capitalize(&format!("{opener}{body}"))));
        }
        pieces.join(if casual { "" } else { " " })
    };
    Ok(Instruction {
        instruction_text: text,
        instruction_tokens: None,
        style,
        grounding: parts.iter().flat_map(|p| p.grounding.clone()).collect(),
        sub_instructions: subs,
    })
}

/// `t` without the coarse opener it starts with, if any (and if something follows it).
fn without_opener(t: &str) -> &str {
    [ph::FORMAL_OPEN, ph::NATURAL_OPEN, ph::CASUAL_OPEN]
        .iter()
        .flat_map(|b| b.iter())
        .filter(|o| !o.trim().is_empty())
        .find_map(|o| t.strip_prefix(o).filter(|r| !r.trim().is_empty()))
        .unwrap_or(t)
}

/// `t` without a coarse opener at the start of any of its sentences: a part led by "Go
/// upstairs." opens its second sentence ("Go upstairs. In this house, find ..."), and the
/// chain opens each part itself.
fn without_openers(t: &str) -> String {
    let mut out: Vec<String> = Vec::new();
    for (k, sentence) in t.split(". ").enumerate() {
        let bare = without_opener(sentence);
        out.push(if k > 0 && bare.len() < sentence.len() {
            capitalize(bare)
        } else {
            bare.to_string()
        });
    }
    out.join(". ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain part: text `t` in `style`, grounding nothing.
    fn part(t: &str, style: Style) -> Instruction {
        Instruction {
            instruction_text: t.into(),
            style: Some(style),
            ..Instruction::default()
        }
    }

    #[test]
    fn a_closer_does_not_repeat_the_stop() {
        let core = "Find the desk and stop there";
        assert_eq!(closer(core, ". Stop when you get there.", "."), ".");
        assert_eq!(closer(core, ". Thanks.", "."), ". Thanks.");
        assert_eq!(
            closer("Go to the desk", ". Wait there.", "."),
            ". Wait there."
        );
        assert_eq!(closer("wait by the desk", " and wait there", ""), "");
    }

    #[test]
    fn one_stands_on_a_balcony_not_in_it() {
        assert_eq!(
            outdoor_prepositions("Go into the balcony and stop by the chair in the small balcony."),
            "Go out onto the balcony and stop by the chair on the small balcony."
        );
        assert_eq!(
            outdoor_prepositions("In the balcony, find the plant inside the balcony"),
            "On the balcony, find the plant out on the balcony"
        );
        assert_eq!(
            outdoor_prepositions("Go again the balcony, then in the balcony"),
            "Go again the balcony, then on the balcony"
        );
        // Other rooms and words that merely contain "in" are left alone.
        assert_eq!(
            outdoor_prepositions("Walk in the kitchen, then into the balcony"),
            "Walk in the kitchen, then out onto the balcony"
        );
    }

    #[test]
    fn a_chain_says_first_once_and_opens_its_parts_itself() {
        for seed in 0..30 {
            let c = chain_parts(
                &[
                    part(
                        "Take the stairs to the upper level first. In this house, please go to \
                         the bed.",
                        Style::Formal,
                    ),
                    part("Please go to the sofa.", Style::Formal),
                ],
                seed,
            )
            .unwrap();
            let t = &c.instruction_text;
            assert!(
                t.starts_with("Take the stairs to the upper level first. Please go"),
                "{t}"
            );
            assert!(!t.contains("In this house"), "{t}");
            assert_eq!(t.to_lowercase().matches("please").count(), 1, "{t}");
            let natural = chain_parts(
                &[
                    part("Go to the kitchen, please.", Style::Natural),
                    part("Go to the sofa, please.", Style::Natural),
                ],
                seed,
            )
            .unwrap();
            let t = &natural.instruction_text;
            assert!(t.contains("o to the kitchen. "), "{t}");
            assert!(t.ends_with("go to the sofa, please."), "{t}");
            let casual = chain_parts(
                &[
                    part("go to the shelf, it's against the wall", Style::Casual),
                    part("go to the bed", Style::Casual),
                ],
                seed,
            )
            .unwrap();
            let t = &casual.instruction_text;
            assert!(
                t.starts_with("go to the shelf, it's against the wall, "),
                "{t}"
            );
        }
    }

    #[test]
    fn a_casual_chain_asks_once() {
        let part = |t: &str| part(t, Style::Casual);
        for seed in 0..20 {
            let c = chain_parts(
                &[
                    part("can you go to the sofa"),
                    part("can you go to the bed"),
                ],
                seed,
            )
            .unwrap();
            let t = &c.instruction_text;
            assert!(t.starts_with("can you go to the sofa"), "{t}");
            assert_eq!(t.matches("can you").count(), 1, "{t}");
            assert!(t.ends_with("go to the bed"), "{t}");
        }
    }

    #[test]
    fn a_casual_chain_says_please_once_at_the_end() {
        let part = |t: &str| part(t, Style::Casual);
        let parts = [
            part("go to the desk please"),
            part("find the red mug please"),
            part("stop by the sofa please"),
        ];
        for seed in 0..20 {
            let text = chain_parts(&parts, seed).unwrap().instruction_text;
            assert_eq!(text.matches("please").count(), 1, "{text}");
            assert!(text.ends_with("the sofa please"), "{text}");
            assert!(text.starts_with("go to the desk"), "{text}");
        }
    }
}
