//! Referring expressions: the shortest description that picks out exactly one object.

use super::{Relation, SceneGraph};
use crate::scene::{ObjectId, RoomId, Scene, SceneObject};
use crate::vocab::{RoomType, SemanticClass};
use serde::{Deserialize, Serialize};

/// An object named inside a description ("the nightstand", "the red sofa").
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Mention {
    /// The object meant.
    pub object: ObjectId,
    /// Its class.
    pub class: SemanticClass,
    /// Its colour, when the description uses it.
    pub color: Option<String>,
}

impl Mention {
    /// Whether an object fits this mention's words (class, and colour when given).
    pub fn fits(&self, o: &SceneObject) -> bool {
        o.class == self.class && self.color.as_ref().is_none_or(|c| *c == o.color)
    }

    /// "red sofa", "nightstand".
    pub fn words(&self) -> String {
        match &self.color {
            Some(c) => format!("{c} {}", self.class.words()),
            None => self.class.words(),
        }
    }
}

/// A room named inside a description ("in the kitchen"); it matches every room of that type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct RoomMention {
    /// The room meant.
    pub room: RoomId,
    /// Its type (the words used).
    pub kind: RoomType,
}

/// A description of a target object in parts, e.g. "the red mug on the nightstand in the
/// bedroom": class, optional colour, optional support, optional room, optional relation to a
/// reference object. [`ReferringExpression::matches`] evaluates the words (not the ids) against a
/// scene, so uniqueness can be checked mechanically.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ReferringExpression {
    /// The object described.
    pub target: ObjectId,
    /// Its class.
    pub class: SemanticClass,
    /// Its colour, when used.
    pub color: Option<String>,
    /// What it rests on ("on the nightstand"), when used.
    pub support: Option<Mention>,
    /// Its room ("in the bedroom"), when used.
    pub room: Option<RoomMention>,
    /// Relation to the reference object ([`Relation::Near`] or [`Relation::NextTo`]).
    pub relation: Option<Relation>,
    /// A reference object the target is near / next to, itself described uniquely.
    pub reference: Option<Mention>,
}

impl ReferringExpression {
    fn bare(target: &SceneObject) -> Self {
        ReferringExpression {
            target: target.id,
            class: target.class,
            color: None,
            support: None,
            room: None,
            relation: None,
            reference: None,
        }
    }

    /// English rendering: "the red mug on the nightstand next to the lamp in the bedroom".
    pub fn text(&self) -> String {
        let mut s = String::from("the ");
        if let Some(c) = &self.color {
            s.push_str(c);
            s.push(' ');
        }
        s.push_str(&self.class.words());
        if let Some(m) = &self.support {
            s.push_str(" on the ");
            s.push_str(&m.words());
        }
        if let (Some(rel), Some(m)) = (self.relation, &self.reference) {
            s.push(' ');
            s.push_str(rel.words());
            s.push_str(" the ");
            s.push_str(&m.words());
        }
        if let Some(r) = &self.room {
            s.push_str(" in the ");
            s.push_str(&r.kind.words());
        }
        s
    }

    /// Number of parts besides the class (0 for "the sofa").
    pub fn parts(&self) -> usize {
        usize::from(self.color.is_some())
            + usize::from(self.support.is_some())
            + usize::from(self.room.is_some())
            + usize::from(self.reference.is_some())
    }

    /// Every object of `scene` (among the graph's nodes) the words fit, sorted by id: the class and colour, resting on
    /// something that fits the support, in a room of the named type, near / next to something
    /// that fits the reference. A good expression matches exactly `[target]`.
    pub fn matches(&self, scene: &Scene, graph: &SceneGraph) -> Vec<ObjectId> {
        let fits_id = |id: ObjectId, m: &Mention| scene.object(id).is_some_and(|o| m.fits(o));
        // Objects of the class: the graph's index, checked against the scene.
        let mut out: Vec<ObjectId> = graph
            .objects_of_class(self.class)
            .iter()
            .filter_map(|&id| scene.object(id))
            .filter(|o| o.class == self.class && !o.is_structure())
            .filter(|o| self.color.as_ref().is_none_or(|c| *c == o.color))
            .filter(|o| {
                self.support
                    .as_ref()
                    .is_none_or(|m| graph.supports_of(o.id).into_iter().any(|s| fits_id(s, m)))
            })
            .filter(|o| {
                self.room.is_none_or(|rm| {
                    graph
                        .room_of(o.id)
                        .and_then(|r| scene.room(r))
                        .is_some_and(|r| r.kind == rm.kind)
                })
            })
            .filter(|o| match (&self.reference, self.relation) {
                (Some(m), Some(rel)) => graph
                    .neighbours(o.id, rel)
                    .into_iter()
                    .any(|(n, _)| fits_id(n, m)),
                (Some(_), None) | (None, Some(_)) => false,
                (None, None) => true,
            })
            .map(|o| o.id)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// A unique short description of `o` on its own (class, else colour + class), for use as a
/// reference object.
pub fn unique_mention(scene: &Scene, graph: &SceneGraph, o: &SceneObject) -> Option<Mention> {
    let mut m = Mention {
        object: o.id,
        class: o.class,
        color: None,
    };
    let count = |m: &Mention| {
        graph
            .objects_of_class(m.class)
            .iter()
            .filter_map(|&id| scene.object(id))
            .filter(|x| m.fits(x))
            .count()
    };
    if count(&m) == 1 {
        return Some(m);
    }
    if o.color.is_empty() {
        return None;
    }
    m.color = Some(o.color.clone());
    (count(&m) == 1).then_some(m)
}

impl SceneGraph {
    /// The shortest description of `target` that fits exactly one object of the scene, trying
    /// in order: class ("the sofa"); colour + class ("the red mug"); class + support ("the mug
    /// on the nightstand"); class + room ("the mug in the kitchen"); their combinations ("the
    /// red mug on the nightstand in the bedroom"); then class (+ colour, + room) near / next to
    /// a reference object that is itself unique by class or colour + class. `None` when the
    /// target is structure, unknown, or cannot be told apart from another object.
    pub fn referring_expression(
        &self,
        scene: &Scene,
        target: ObjectId,
    ) -> Option<ReferringExpression> {
        let obj = scene.object(target)?;
        if obj.is_structure() || self.object(target).is_none() {
            return None;
        }
        let bare = ReferringExpression::bare(obj);
        let color = (!obj.color.is_empty()).then(|| obj.color.clone());
        let room = self.room_of(target).and_then(|r| {
            Some(RoomMention {
                room: r,
                kind: scene.room(r)?.kind,
            })
        });
        // Declared support first, then geometric ones by id.
        let mut supports = self.supports_of(target);
        if let Some(s) = obj.supported_by {
            if let Some(i) = supports.iter().position(|&x| x == s) {
                supports[..=i].rotate_right(1);
            }
        }
        let support_mentions: Vec<Mention> = supports
            .iter()
            .filter_map(|&s| scene.object(s))
            .flat_map(|s| {
                let plain = Mention {
                    object: s.id,
                    class: s.class,
                    color: None,
                };
                let colored = (!s.color.is_empty()).then(|| Mention {
                    color: Some(s.color.clone()),
                    ..plain.clone()
                });
                [Some(plain), colored]
            })
            .flatten()
            .collect();

        let unique = |e: &ReferringExpression| e.matches(scene, self) == [target];
        // None when the description needs a colour or room the target does not have.
        let with = |use_color: bool, support: Option<&Mention>, in_room: bool| {
            let mut e = bare.clone();
            if use_color {
                e.color = Some(color.clone()?);
            }
            if in_room {
                e.room = Some(room?);
            }
            e.support = support.cloned();
            Some(e)
        };
        let plain: Vec<&Mention> = support_mentions
            .iter()
            .filter(|m| m.color.is_none())
            .collect();
        let colored: Vec<&Mention> = support_mentions
            .iter()
            .filter(|m| m.color.is_some())
            .collect();

        let mut candidates: Vec<Option<ReferringExpression>> =
            vec![with(false, None, false), with(true, None, false)];
        candidates.extend(plain.iter().map(|m| with(false, Some(m), false)));
        candidates.push(with(false, None, true));
        candidates.extend(plain.iter().map(|m| with(true, Some(m), false)));
        candidates.push(with(true, None, true));
        candidates.extend(plain.iter().map(|m| with(false, Some(m), true)));
        candidates.extend(plain.iter().map(|m| with(true, Some(m), true)));
        for (c, r) in [(false, false), (true, false), (false, true), (true, true)] {
            candidates.extend(colored.iter().map(|m| with(c, Some(m), r)));
        }
        if let Some(e) = candidates.into_iter().flatten().find(|e| unique(e)) {
            return Some(e);
        }

        // Reference objects: next_to first, then near, closest first.
        let mut refs: Vec<(Relation, Mention)> = Vec::new();
        let next_to: Vec<ObjectId> = self
            .neighbours(target, Relation::NextTo)
            .into_iter()
            .map(|(n, _)| n)
            .collect();
        for (rel, list) in [
            (Relation::NextTo, next_to.clone()),
            (
                Relation::Near,
                self.neighbours(target, Relation::Near)
                    .into_iter()
                    .map(|(n, _)| n)
                    .filter(|n| !next_to.contains(n))
                    .collect(),
            ),
        ] {
            for n in list {
                let Some(o) = scene.object(n) else { continue };
                if o.class == obj.class {
                    continue;
                }
                if let Some(m) = unique_mention(scene, self, o) {
                    refs.push((rel, m));
                }
            }
        }
        for (c, r) in [(false, false), (true, false), (false, true), (true, true)] {
            for (rel, m) in &refs {
                let Some(mut e) = with(c, None, r) else {
                    continue;
                };
                e.relation = Some(*rel);
                e.reference = Some(m.clone());
                if unique(&e) {
                    return Some(e);
                }
            }
        }
        None
    }
}
