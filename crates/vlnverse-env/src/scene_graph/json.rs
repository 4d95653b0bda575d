//! `scene_graph.json`: export and import.

use super::{
    Edge, Node, NodeRef, ObjectNode, Relation, RoomNode, SceneGraph, SCENE_GRAPH_FILE,
    SCENE_GRAPH_FORMAT_VERSION,
};
use crate::error::{EnvError, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::path::Path;

/// One node as written in the file: `type` says room or object.
#[derive(Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
enum FileNode {
    Room {
        id: NodeRef,
        #[serde(flatten)]
        node: RoomNode,
    },
    Object {
        id: NodeRef,
        #[serde(flatten)]
        node: ObjectNode,
    },
}

#[derive(Serialize, Deserialize)]
struct FileGraph {
    format_version: u32,
    scene_id: String,
    nodes: Vec<FileNode>,
    edges: Vec<Edge>,
}

fn err(message: String) -> EnvError {
    EnvError::parse(SCENE_GRAPH_FILE, message)
}

impl SceneGraph {
    fn to_file(&self) -> FileGraph {
        FileGraph {
            format_version: SCENE_GRAPH_FORMAT_VERSION,
            scene_id: self.scene_id.clone(),
            nodes: self
                .nodes()
                .map(|n| match n {
                    Node::Room(r) => FileNode::Room {
                        id: n.key(),
                        node: r.clone(),
                    },
                    Node::Object(o) => FileNode::Object {
                        id: n.key(),
                        node: o.clone(),
                    },
                })
                .collect(),
            edges: self.edges().cloned().collect(),
        }
    }

    /// The graph as a JSON value (the content of `scene_graph.json`).
    pub fn to_json(&self) -> serde_json::Value {
        // Plain data with string keys: serialisation cannot fail.
        serde_json::to_value(self.to_file()).unwrap_or(serde_json::Value::Null)
    }

    /// The graph as pretty-printed JSON text, byte-identical for identical graphs.
    pub fn to_json_string(&self) -> String {
        serde_json::to_string_pretty(&self.to_file()).unwrap_or_default()
    }

    /// Parse `scene_graph.json` text. Errors name the offending field and value.
    pub fn from_json(text: &str) -> Result<SceneGraph> {
        let file: FileGraph = serde_json::from_str(text).map_err(|e| {
            match crate::io::json::offending_line(text.as_bytes(), &e) {
                Some(l) => err(format!("invalid scene graph: {e}: `{l}`")),
                None => err(format!("invalid scene graph: {e}")),
            }
        })?;
        if file.format_version != SCENE_GRAPH_FORMAT_VERSION {
            return Err(err(format!(
                "format_version = {}: expected {SCENE_GRAPH_FORMAT_VERSION}",
                file.format_version
            )));
        }
        let mut keys = BTreeSet::new();
        let mut nodes = Vec::with_capacity(file.nodes.len());
        for (i, n) in file.nodes.into_iter().enumerate() {
            let node = match n {
                FileNode::Room { id, node } => {
                    if id != NodeRef::Room(node.room) {
                        return Err(err(format!(
                            "nodes[{i}].id = `{id}` disagrees with room = {}",
                            node.room
                        )));
                    }
                    Node::Room(node)
                }
                FileNode::Object { id, node } => {
                    if id != NodeRef::Object(node.object) {
                        return Err(err(format!(
                            "nodes[{i}].id = `{id}` disagrees with object = {}",
                            node.object
                        )));
                    }
                    Node::Object(node)
                }
            };
            if !keys.insert(node.key()) {
                return Err(err(format!(
                    "nodes[{i}].id = `{}` is a duplicate",
                    node.key()
                )));
            }
            nodes.push(node);
        }
        for (i, n) in nodes.iter().enumerate() {
            if let Node::Object(o) = n {
                if let Some(r) = o.room {
                    if !keys.contains(&NodeRef::Room(r)) {
                        return Err(err(format!("nodes[{i}].room = {r}: no such room node")));
                    }
                }
            }
        }
        for (i, e) in file.edges.iter().enumerate() {
            for (field, key) in [("source", e.source), ("target", e.target)] {
                if !keys.contains(&key) {
                    return Err(err(format!("edges[{i}].{field} = `{key}`: no such node")));
                }
            }
            let objects = matches!(
                (e.source, e.target),
                (NodeRef::Object(_), NodeRef::Object(_))
            );
            let ok = match e.relation {
                Relation::In => {
                    matches!((e.source, e.target), (NodeRef::Object(_), NodeRef::Room(_)))
                }
                Relation::On => objects,
                Relation::Near | Relation::NextTo => objects && e.distance.is_some(),
                Relation::Connected => {
                    matches!((e.source, e.target), (NodeRef::Room(_), NodeRef::Room(_)))
                        && e.door.is_some()
                }
            };
            if !ok {
                return Err(err(format!(
                    "edges[{i}]: relation `{}` from `{}` to `{}` is malformed (in: object->room; \
                     on/near/next_to: object->object, near/next_to with distance; connected: \
                     room->room with door)",
                    serde_json::to_value(e.relation)
                        .ok()
                        .and_then(|v| v.as_str().map(str::to_owned))
                        .unwrap_or_default(),
                    e.source,
                    e.target
                )));
            }
        }
        Ok(SceneGraph::assemble(file.scene_id, nodes, file.edges))
    }

    /// Write `scene_graph.json` into `dir`.
    pub fn save(&self, dir: &Path) -> Result<()> {
        let path = dir.join(SCENE_GRAPH_FILE);
        std::fs::write(&path, self.to_json_string()).map_err(|e| EnvError::io(&path, e))
    }

    /// Read `scene_graph.json` from `dir`; parse errors name the file.
    pub fn load(dir: &Path) -> Result<SceneGraph> {
        let path = dir.join(SCENE_GRAPH_FILE);
        let text = std::fs::read_to_string(&path).map_err(|e| EnvError::io(&path, e))?;
        Self::from_json(&text).map_err(|e| match e {
            EnvError::Parse { message, .. } => EnvError::parse(&path, message),
            other => other,
        })
    }
}
