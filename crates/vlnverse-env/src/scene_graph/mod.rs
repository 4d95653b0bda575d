//! The scene graph: rooms and objects as nodes, spatial relations as edges.
//!
//! Built once per scene with [`SceneGraph::build`] (a petgraph [`DiGraph`] inside) and written as
//! `scene_graph.json` ([`SceneGraph::to_json_string`] / [`SceneGraph::from_json`]). Relations:
//!
//! | relation | from -> to | meaning |
//! |---|---|---|
//! | `in` | object -> room | the object stands in the room |
//! | `on` | object -> object | the source rests on the target (`supported_by` or geometry) |
//! | `near` | object -> object | footprints closer than 1.0 m, same room (symmetric, stored once) |
//! | `next_to` | object -> object | footprints closer than 0.3 m, same room (also `near`) |
//! | `connected` | room -> room | a door or open-plan opening joins the rooms (carries the door id and, for a doorway with a leaf, its `state`) |
//!
//! A door leaf is an object node of class `door` whose `door` field names its doorway, its
//! state (`open` / `closed`) and the two rooms it joins.
//!
//! Viewpoint relations (left / right / ahead / behind) depend on where the agent stands, so they
//! are computed on demand with [`side_of`]. The task layer's queries live here too:
//! [`SceneGraph::referring_expression`] (a description matching exactly one object) and
//! [`SceneGraph::landmarks_along_path`].
//!
//! ```
//! use vlnverse_env::scene_graph::{side_of, Side};
//! use glam::Vec2;
//!
//! // At yaw 0 the agent looks along -Z: +X is on its right.
//! assert_eq!(side_of(Vec2::ZERO, 0.0, Vec2::new(1.0, 0.0)), Side::Right);
//! assert_eq!(side_of(Vec2::ZERO, 0.0, Vec2::new(0.0, -1.0)), Side::Ahead);
//! ```

mod build;
mod json;
mod landmarks;
mod refer;
mod spatial;

pub use landmarks::{is_landmark, rooms_along_path, segment_headings, Landmark};
pub use refer::{unique_mention, Mention, ReferringExpression, RoomMention};
pub use spatial::{
    direction_of_yaw, footprint_distance, segment_enters_rect, side_of, side_of_heading,
    yaw_from_direction, Side,
};

use crate::scene::{Aabb, DoorState, LevelId, ObjectId, RoomId};
use crate::vocab::{RoomType, SemanticClass};
use petgraph::graph::{DiGraph, NodeIndex};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;

/// Version of the `scene_graph.json` format.
pub const SCENE_GRAPH_FORMAT_VERSION: u32 = 1;

/// File name of the exported graph inside a scene folder.
pub const SCENE_GRAPH_FILE: &str = "scene_graph.json";

/// Thresholds used when building the graph (metres).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneGraphConfig {
    /// `near` when the footprint distance is below this.
    pub near: f32,
    /// `next_to` when the footprint distance is below this.
    pub next_to: f32,
    /// `on` (geometric) when the bottom of one box is within this of the other's top.
    pub support_tolerance: f32,
}

impl Default for SceneGraphConfig {
    fn default() -> Self {
        SceneGraphConfig {
            near: 1.0,
            next_to: 0.3,
            support_tolerance: 0.03,
        }
    }
}

/// Reference to a node: a room or an object. Written as `"room:3"` / `"object:12"` in JSON.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum NodeRef {
    /// A room by id.
    Room(RoomId),
    /// An object by id.
    Object(ObjectId),
}

impl fmt::Display for NodeRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NodeRef::Room(id) => write!(f, "room:{id}"),
            NodeRef::Object(id) => write!(f, "object:{id}"),
        }
    }
}

impl std::str::FromStr for NodeRef {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("node id `{s}` is not `room:<n>` or `object:<n>`");
        let (kind, num) = s.split_once(':').ok_or_else(bad)?;
        let num: u32 = num.parse().map_err(|_| bad())?;
        match kind {
            "room" => Ok(NodeRef::Room(num)),
            "object" => Ok(NodeRef::Object(num)),
            _ => Err(bad()),
        }
    }
}

impl Serialize for NodeRef {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for NodeRef {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// A room node.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RoomNode {
    /// Room id.
    pub room: RoomId,
    /// Room type.
    pub kind: RoomType,
    /// Unique name, e.g. `bedroom_2`.
    pub name: String,
    /// Centroid of the floor polygon at the height of the room's floor.
    pub position: [f32; 3],
    /// The level (storey) the room is on, in a home on more than one floor; absent otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub level: Option<LevelId>,
}

/// An object node (furniture, small objects; never structure).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectNode {
    /// Object id.
    pub object: ObjectId,
    /// Semantic class.
    pub class: SemanticClass,
    /// Unique name, e.g. `mug_12`.
    pub name: String,
    /// Room the object is in (its own `room`, else the room containing its centre).
    pub room: Option<RoomId>,
    /// Centre of the bounding box.
    pub position: [f32; 3],
    /// Colour word ("red"); empty when unknown.
    pub color: String,
    /// World bounding box.
    pub bbox: Aabb,
    /// For a door leaf (class `door`): its doorway, state and the two rooms it joins.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub door: Option<DoorNode>,
}

/// What a door leaf object adds to its node: it stands in a doorway between two rooms, open or
/// closed ("go through the white door", "the closed door on your left").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct DoorNode {
    /// Id of the doorway in the scene's `doors`.
    pub id: u32,
    /// Open or closed.
    pub state: DoorState,
    /// The two rooms of the doorway.
    pub rooms: [RoomId; 2],
}

/// A node of the graph.
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    /// A room.
    Room(RoomNode),
    /// An object.
    Object(ObjectNode),
}

impl Node {
    /// The node's reference.
    pub fn key(&self) -> NodeRef {
        match self {
            Node::Room(r) => NodeRef::Room(r.room),
            Node::Object(o) => NodeRef::Object(o.object),
        }
    }
}

/// Kind of an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Relation {
    /// Object in room.
    In,
    /// Object resting on another object.
    On,
    /// Footprints closer than [`SceneGraphConfig::near`] (symmetric).
    Near,
    /// Footprints closer than [`SceneGraphConfig::next_to`] (symmetric; implies `near`).
    NextTo,
    /// Rooms joined by a door or opening (symmetric).
    Connected,
}

impl Relation {
    /// Whether `a R b` implies `b R a` (such edges are stored once, smaller node first).
    pub fn is_symmetric(self) -> bool {
        matches!(
            self,
            Relation::Near | Relation::NextTo | Relation::Connected
        )
    }

    /// Words used in text ("next to").
    pub fn words(self) -> &'static str {
        match self {
            Relation::In => "in",
            Relation::On => "on",
            Relation::Near => "near",
            Relation::NextTo => "next to",
            Relation::Connected => "connected to",
        }
    }
}

/// An edge: `source relation target`, with relation-specific data.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Edge {
    /// Source node.
    pub source: NodeRef,
    /// Target node.
    pub target: NodeRef,
    /// Relation.
    pub relation: Relation,
    /// Footprint distance (m) for `near` / `next_to`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance: Option<f32>,
    /// Door id for `connected`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub door: Option<u32>,
    /// Whether the `connected` opening is open plan (no door frame).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub open_plan: Option<bool>,
    /// State of the `connected` doorway's leaf, if it has one (a closed door does not let the
    /// agent through: the rooms are still connected, by other ways round).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state: Option<DoorState>,
}

impl Edge {
    fn sort_key(&self) -> (NodeRef, NodeRef, Relation, Option<u32>) {
        (self.source, self.target, self.relation, self.door)
    }
}

/// The scene graph of one scene.
#[derive(Clone, Debug)]
pub struct SceneGraph {
    scene_id: String,
    graph: DiGraph<Node, Edge>,
    rooms: BTreeMap<RoomId, NodeIndex>,
    objects: BTreeMap<ObjectId, NodeIndex>,
    by_class: BTreeMap<SemanticClass, Vec<ObjectId>>,
}

impl PartialEq for SceneGraph {
    fn eq(&self, other: &Self) -> bool {
        self.scene_id == other.scene_id
            && self.nodes().eq(other.nodes())
            && self.edges().eq(other.edges())
    }
}

impl SceneGraph {
    /// Assemble from nodes and edges (any order; sorted here so output is deterministic).
    fn assemble(scene_id: String, mut nodes: Vec<Node>, mut edges: Vec<Edge>) -> SceneGraph {
        nodes.sort_by_key(Node::key);
        // Declared and geometric support may both give `a on b`: keep one.
        edges.sort_unstable_by(|a, b| {
            a.sort_key()
                .cmp(&b.sort_key())
                .then(a.distance.total_cmp_opt(&b.distance))
        });
        edges.dedup_by(|a, b| a.sort_key() == b.sort_key());
        let mut graph = DiGraph::with_capacity(nodes.len(), edges.len());
        let mut rooms = BTreeMap::new();
        let mut objects = BTreeMap::new();
        for node in nodes {
            let key = node.key();
            let ix = graph.add_node(node);
            match key {
                NodeRef::Room(id) => rooms.insert(id, ix),
                NodeRef::Object(id) => objects.insert(id, ix),
            };
        }
        for edge in edges {
            let (Some(a), Some(b)) = (
                Self::index_in(&rooms, &objects, edge.source),
                Self::index_in(&rooms, &objects, edge.target),
            ) else {
                continue;
            };
            graph.add_edge(a, b, edge);
        }
        let mut by_class: BTreeMap<SemanticClass, Vec<ObjectId>> = BTreeMap::new();
        for n in graph.node_weights() {
            if let Node::Object(o) = n {
                by_class.entry(o.class).or_default().push(o.object);
            }
        }
        SceneGraph {
            scene_id,
            graph,
            rooms,
            objects,
            by_class,
        }
    }

    fn index_in(
        rooms: &BTreeMap<RoomId, NodeIndex>,
        objects: &BTreeMap<ObjectId, NodeIndex>,
        key: NodeRef,
    ) -> Option<NodeIndex> {
        match key {
            NodeRef::Room(id) => rooms.get(&id).copied(),
            NodeRef::Object(id) => objects.get(&id).copied(),
        }
    }

    /// Id of the scene the graph was built from.
    pub fn scene_id(&self) -> &str {
        &self.scene_id
    }

    /// The petgraph graph, for graph algorithms (node order: rooms by id, then objects by id).
    pub fn graph(&self) -> &DiGraph<Node, Edge> {
        &self.graph
    }

    /// Petgraph index of a node.
    pub fn index(&self, key: NodeRef) -> Option<NodeIndex> {
        Self::index_in(&self.rooms, &self.objects, key)
    }

    /// All nodes: rooms by id, then objects by id.
    pub fn nodes(&self) -> impl Iterator<Item = &Node> + '_ {
        self.graph.node_weights()
    }

    /// All edges, sorted by (source, target, relation, door).
    pub fn edges(&self) -> impl Iterator<Item = &Edge> + '_ {
        self.graph.edge_weights()
    }

    /// Number of room nodes.
    pub fn room_count(&self) -> usize {
        self.rooms.len()
    }

    /// Number of object nodes.
    pub fn object_count(&self) -> usize {
        self.objects.len()
    }

    /// A room node.
    pub fn room(&self, id: RoomId) -> Option<&RoomNode> {
        match self.graph.node_weight(*self.rooms.get(&id)?)? {
            Node::Room(r) => Some(r),
            Node::Object(_) => None,
        }
    }

    /// An object node.
    pub fn object(&self, id: ObjectId) -> Option<&ObjectNode> {
        match self.graph.node_weight(*self.objects.get(&id)?)? {
            Node::Object(o) => Some(o),
            Node::Room(_) => None,
        }
    }

    /// Every object node, by id.
    pub fn objects(&self) -> impl Iterator<Item = &ObjectNode> + '_ {
        self.objects
            .values()
            .filter_map(|&ix| match &self.graph[ix] {
                Node::Object(o) => Some(o),
                Node::Room(_) => None,
            })
    }

    /// Every room node, by id.
    pub fn rooms(&self) -> impl Iterator<Item = &RoomNode> + '_ {
        self.rooms.values().filter_map(|&ix| match &self.graph[ix] {
            Node::Room(r) => Some(r),
            Node::Object(_) => None,
        })
    }

    /// Edges touching `key` (either direction) with the given relation, as (other node, edge),
    /// sorted by the other node.
    pub fn related(&self, key: NodeRef, relation: Relation) -> Vec<(NodeRef, &Edge)> {
        let Some(ix) = self.index(key) else {
            return Vec::new();
        };
        let mut out: Vec<(NodeRef, &Edge)> = self
            .graph
            .edges_directed(ix, petgraph::Direction::Outgoing)
            .chain(self.graph.edges_directed(ix, petgraph::Direction::Incoming))
            .map(|e| e.weight())
            .filter(|e| e.relation == relation)
            .map(|e| (if e.source == key { e.target } else { e.source }, e))
            .collect();
        out.sort_by_key(|a| (a.0, a.1.door));
        out
    }

    fn outgoing(&self, key: NodeRef, relation: Relation) -> Vec<NodeRef> {
        let Some(ix) = self.index(key) else {
            return Vec::new();
        };
        let mut out: Vec<NodeRef> = self
            .graph
            .edges_directed(ix, petgraph::Direction::Outgoing)
            .filter(|e| e.weight().relation == relation)
            .map(|e| e.weight().target)
            .collect();
        out.sort();
        out.dedup();
        out
    }

    fn incoming(&self, key: NodeRef, relation: Relation) -> Vec<NodeRef> {
        let Some(ix) = self.index(key) else {
            return Vec::new();
        };
        let mut out: Vec<NodeRef> = self
            .graph
            .edges_directed(ix, petgraph::Direction::Incoming)
            .filter(|e| e.weight().relation == relation)
            .map(|e| e.weight().source)
            .collect();
        out.sort();
        out.dedup();
        out
    }

    /// Ids of the object nodes of a class, sorted.
    pub fn objects_of_class(&self, class: SemanticClass) -> &[ObjectId] {
        self.by_class.get(&class).map_or(&[], Vec::as_slice)
    }

    /// Room of an object (its `in` edge).
    pub fn room_of(&self, object: ObjectId) -> Option<RoomId> {
        self.object(object)?.room
    }

    /// Objects in a room, sorted by id.
    pub fn objects_in_room(&self, room: RoomId) -> Vec<ObjectId> {
        self.incoming(NodeRef::Room(room), Relation::In)
            .into_iter()
            .filter_map(object_id)
            .collect()
    }

    /// What the object rests on (`object on X`), sorted by id.
    pub fn supports_of(&self, object: ObjectId) -> Vec<ObjectId> {
        self.outgoing(NodeRef::Object(object), Relation::On)
            .into_iter()
            .filter_map(object_id)
            .collect()
    }

    /// What rests on the object (`X on object`), sorted by id.
    pub fn supported(&self, object: ObjectId) -> Vec<ObjectId> {
        self.incoming(NodeRef::Object(object), Relation::On)
            .into_iter()
            .filter_map(object_id)
            .collect()
    }

    /// Objects `near` (or, with [`Relation::NextTo`], `next_to`) the object, closest first, with
    /// their footprint distance.
    pub fn neighbours(&self, object: ObjectId, relation: Relation) -> Vec<(ObjectId, f32)> {
        let mut out: Vec<(ObjectId, f32)> = self
            .related(NodeRef::Object(object), relation)
            .into_iter()
            .filter_map(|(n, e)| Some((object_id(n)?, e.distance.unwrap_or(0.0))))
            .collect();
        out.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        out
    }

    /// Rooms connected to `room`, as (other room, door id, open plan), sorted.
    pub fn connected_rooms(&self, room: RoomId) -> Vec<(RoomId, u32, bool)> {
        self.related(NodeRef::Room(room), Relation::Connected)
            .into_iter()
            .filter_map(|(n, e)| match n {
                NodeRef::Room(r) => Some((r, e.door.unwrap_or(0), e.open_plan.unwrap_or(false))),
                NodeRef::Object(_) => None,
            })
            .collect()
    }

    /// Whether `a relation b` holds (either direction for symmetric relations).
    pub fn has_relation(&self, a: NodeRef, relation: Relation, b: NodeRef) -> bool {
        let (Some(ia), Some(ib)) = (self.index(a), self.index(b)) else {
            return false;
        };
        let forward = self
            .graph
            .edges_connecting(ia, ib)
            .any(|e| e.weight().relation == relation);
        forward
            || (relation.is_symmetric()
                && self
                    .graph
                    .edges_connecting(ib, ia)
                    .any(|e| e.weight().relation == relation))
    }
}

fn object_id(n: NodeRef) -> Option<ObjectId> {
    match n {
        NodeRef::Object(id) => Some(id),
        NodeRef::Room(_) => None,
    }
}

trait TotalCmpOpt {
    fn total_cmp_opt(&self, o: &Self) -> std::cmp::Ordering;
}

impl TotalCmpOpt for Option<f32> {
    fn total_cmp_opt(&self, o: &Self) -> std::cmp::Ordering {
        match (self, o) {
            (Some(a), Some(b)) => a.total_cmp(b),
            _ => self.is_some().cmp(&o.is_some()),
        }
    }
}
