#![doc = include_str!("../README.md")]

//! Instruction generation: the [`InstructionGenerator`] swap point.
//!
//! The default generator is deterministic and template-based, grounded in the scene graph; an
//! optional LLM-backed stage implements the same trait. See `docs/instructions.md`.
//!
//! - [`TemplateGenerator`] (`templates.rs`; phrase banks in `data/phrases.toml`, loaded and
//!   checked by `phrases.rs`): fine-grained
//!   instructions (`fine.rs`) follow the path's legs, turns, room changes and landmarks,
//!   written by one of several writers with varied sentence plans; objects, rooms and openings
//!   are described in `describe.rs` with the words of [`lexicon`] (class names and uses in
//!   `data/classes.toml`, kinds named as one group in `data/groups.toml`, colour shades in
//!   `data/colours.toml`); coarse ones render the scene
//!   graph's unique referring expression in three styles; [`chain_parts`] joins
//!   sub-instructions.
//! - [`check_grounding`]: mechanical check of an instruction's grounding metadata.
//! - `llm` (feature `llm`, on by default): the optional LLM stage (`llm::LlmGenerator`).
//!
//! ```
//! use glam::Vec2;
//! use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
//! use vlnverse_env::scene_graph::SceneGraph;
//! use vlnverse_env::{geodesic::shortest_path, SceneSource};
//! use vlnverse_procgen::{HomeGenerator, Preset};
//! use vlnverse_instructions::{check_grounding, InstructionGenerator, PathContext, TemplateGenerator};
//! use vlnverse_score::Style;
//!
//! let scene = HomeGenerator::from_preset(Preset::Tiny)?.scene(0)?;
//! let maps = build_maps(&scene, &OccupancyConfig::default())?;
//! let graph = SceneGraph::build(&scene);
//! // A path between two navigable points, and a target with a unique description.
//! let free: Vec<Vec2> = maps.navigable.free_cells().map(|(c, r)| maps.navigable.cell_center(c, r)).collect();
//! let p = shortest_path(&maps.navigable, free[0], free[free.len() - 1])?.expect("one island");
//! let path: Vec<[f32; 3]> = p.points.iter().map(|q| [q.x, 0.0, q.y]).collect();
//! let ctx = PathContext { scene: &scene, graph: &graph, navigable: &maps.navigable, path: &path, start_yaw: 0.0, whole_home: None };
//!
//! let g = TemplateGenerator::default();
//! let fine = g.fine(&ctx, 7)?;
//! assert_eq!(fine, g.fine(&ctx, 7)?); // deterministic from the seed
//! assert!(check_grounding(&ctx, &fine, 3.0).is_empty());
//! let target = scene.objects.iter().find(|o| graph.referring_expression(&scene, o.id).is_some()).unwrap();
//! let coarse = g.coarse(&ctx, target.id, Style::Natural, 7)?;
//! // The target goes by its class's name or, now and then, another name people use for it.
//! let names = vlnverse_instructions::lexicon::object_names(target);
//! assert!(names.iter().any(|n| coarse.instruction_text.contains(n)));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod data;
mod describe;
mod door_order;
mod fine;
mod groups;
pub mod lexicon;
#[cfg(feature = "llm")]
pub mod llm;
mod openings;
mod path;
mod phrases;
mod room_facts;
mod spatial;
mod stairwell;
pub mod storeys;
mod templates;

use path::{direction_of_yaw, env_side, floor_points, segment_headings};
pub use templates::{chain_parts, coarse_expression, TemplateConfig, TemplateGenerator};

use glam::Vec2;
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::{ObjectId, Scene};
use vlnverse_score::episode::{Instruction, Side, Style};
use vlnverse_score::Result;

/// Everything an instruction generator may look at for one trajectory.
#[derive(Clone, Copy)]
pub struct PathContext<'a> {
    /// The scene the path lies in.
    pub scene: &'a Scene,
    /// Its scene graph.
    pub graph: &'a SceneGraph,
    /// The navigable map (line of sight for landmark visibility).
    pub navigable: &'a GridMap,
    /// Reference path from the start to the goal (waypoints on the floor).
    pub path: &'a [[f32; 3]],
    /// Heading of the agent at the start (radians, yaw 0 looks along -Z).
    pub start_yaw: f32,
    /// The whole home when `scene` is one of its floors ([`Scene::level_view`]): what is said
    /// to be the only one "in the house" is counted there. `None` when `scene` is the home.
    pub whole_home: Option<&'a Scene>,
}

/// Turns a trajectory into natural-language instructions with grounding metadata.
///
/// Implementations are deterministic: the same context and seed give the same text.
pub trait InstructionGenerator: Send + Sync {
    /// A fine-grained, step-by-step instruction following `ctx.path` (landmarks, their side,
    /// action verbs, the end point).
    fn fine(&self, ctx: &PathContext<'_>, seed: u64) -> Result<Instruction>;

    /// A coarse-grained goal description of `target` (class, attribute, relation to a reference
    /// object or room, unique within the scene) in one style.
    fn coarse(
        &self,
        ctx: &PathContext<'_>,
        target: ObjectId,
        style: Style,
        seed: u64,
    ) -> Result<Instruction>;

    /// One long-horizon instruction chaining coarse sub-instructions in order.
    fn chain(&self, parts: &[Instruction], seed: u64) -> Result<Instruction>;
}

/// Add `offset` to every grounded path index of `ins` (for a part whose path is appended to a
/// longer reference path at index `offset`).
pub fn offset_grounding(ins: &mut Instruction, offset: u32) {
    for g in &mut ins.grounding {
        if let Some(i) = g.path_index.as_mut() {
            *i += offset;
        }
    }
}

/// Problems with the grounding metadata of `ins` for the path of `ctx`, empty when it is sound:
/// every grounded object exists in the scene with the stated class; its path index lies on the
/// path; its footprint lies within `max_distance` metres of the path point (the segment
/// `path[i] -> path[i + 1]`, or the point itself for the last index); and its stated side is
/// the side of the footprint's centre seen from a closest point of that segment (any point
/// within 2 cm of the closest distance), facing along the segment (along the last segment for
/// the last index).
pub fn check_grounding(ctx: &PathContext<'_>, ins: &Instruction, max_distance: f32) -> Vec<String> {
    let pts = floor_points(ctx.path);
    let headings = segment_headings(&pts);
    let mut problems = Vec::new();
    for (k, g) in ins.grounding.iter().enumerate() {
        let what = format!("grounding[{k}] (object {})", g.object_id);
        let Some(o) = ctx.scene.object(g.object_id) else {
            problems.push(format!("{what}: not in scene `{}`", ctx.scene.id));
            continue;
        };
        if o.class.name() != g.class {
            problems.push(format!(
                "{what}: class `{}` but the scene says `{}`",
                g.class,
                o.class.name()
            ));
        }
        let Some(idx) = g.path_index else { continue };
        let idx = idx as usize;
        if idx >= pts.len() {
            problems.push(format!(
                "{what}: path index {idx} beyond the path ({} points)",
                pts.len()
            ));
            continue;
        }
        let (lo, hi) = path::footprint(o);
        let center = (lo + hi) * 0.5;
        // Candidate viewpoints: the segment sampled every ~2 cm, or the last point.
        let (a, b, heading) = if idx + 1 < pts.len() {
            (pts[idx], pts[idx + 1], headings[idx])
        } else if let Some(h) = headings.last() {
            (pts[idx], pts[idx], *h)
        } else {
            (pts[idx], pts[idx], direction_of_yaw(ctx.start_yaw))
        };
        let steps = ((b - a).length() / 0.02).ceil().max(1.0) as usize;
        let samples: Vec<(Vec2, f32)> = (0..=steps)
            .map(|s| {
                let p = a.lerp(b, s as f32 / steps as f32);
                (p, path::rect_distance(p, lo, hi))
            })
            .collect();
        let dmin = samples.iter().map(|s| s.1).fold(f32::INFINITY, f32::min);
        if dmin > max_distance {
            problems.push(format!(
                "{what}: {dmin:.2} m from path point {idx}, more than {max_distance} m"
            ));
        }
        if let Some(side) = g.side {
            let ok = samples.iter().filter(|s| s.1 <= dmin + 0.02).any(|s| {
                env_side(vlnverse_env::scene_graph::side_of_heading(
                    s.0, heading, center,
                )) == side
            });
            if !ok {
                let seen = env_side(vlnverse_env::scene_graph::side_of_heading(
                    a, heading, center,
                ));
                problems.push(format!(
                    "{what}: stated {side:?} but it is {seen:?} from path point {idx}"
                ));
            }
        }
    }
    problems
}

/// Whether a side is left or right (the sides a landmark is passed on).
pub fn is_lateral(side: Side) -> bool {
    matches!(side, Side::Left | Side::Right)
}
