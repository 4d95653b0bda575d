//! Building the graph from a [`Scene`].

use super::spatial::footprint_distance;
use super::{
    DoorNode, Edge, Node, NodeRef, ObjectNode, Relation, RoomNode, SceneGraph, SceneGraphConfig,
};
use crate::scene::{Aabb, ObjectId, RoomId, Scene};
use std::collections::{BTreeMap, BTreeSet};

impl SceneGraph {
    /// Build the graph of a scene with the default thresholds.
    pub fn build(scene: &Scene) -> SceneGraph {
        Self::build_with(scene, &SceneGraphConfig::default())
    }

    /// Build the graph of a scene with explicit thresholds.
    ///
    /// Pairwise relations are only tested between objects of the same room, after a sweep
    /// along x, so the cost stays close to linear for furnished homes.
    pub fn build_with(scene: &Scene, cfg: &SceneGraphConfig) -> SceneGraph {
        let mut nodes = Vec::with_capacity(scene.rooms.len() + scene.objects.len());
        let mut edges = Vec::new();
        let multi = scene.is_multi_level();
        for room in &scene.rooms {
            let c = room.center();
            let level = scene.room_level(room.id).unwrap_or(0);
            let y = scene.level_height(level).unwrap_or(scene.floor_height);
            nodes.push(Node::Room(RoomNode {
                room: room.id,
                kind: room.kind,
                name: room.name.clone(),
                position: [c[0], y, c[1]],
                level: multi.then_some(level),
            }));
        }

        // Objects bucketed by room (None: outside every room).
        let mut buckets: BTreeMap<Option<RoomId>, Vec<(ObjectId, Aabb)>> = BTreeMap::new();
        let mut is_node: BTreeSet<ObjectId> = BTreeSet::new();
        for obj in scene.items() {
            let center = obj.bbox.center();
            let room = obj.room.filter(|&r| scene.room(r).is_some()).or_else(|| {
                let level = scene.level_at_height(obj.bbox.min[1]);
                scene.room_at_level(level, center.x, center.z).map(|r| r.id)
            });
            let door = scene
                .doors
                .iter()
                .find(|d| d.leaves().any(|l| l == obj.id))
                .and_then(|d| {
                    Some(DoorNode {
                        id: d.id,
                        state: d.state?,
                        rooms: d.rooms,
                    })
                });
            nodes.push(Node::Object(ObjectNode {
                object: obj.id,
                class: obj.class,
                name: obj.name.clone(),
                room,
                position: center.to_array(),
                color: obj.color.clone(),
                bbox: obj.bbox,
                door,
            }));
            is_node.insert(obj.id);
            if let Some(r) = room {
                edges.push(Edge::plain(
                    NodeRef::Object(obj.id),
                    NodeRef::Room(r),
                    Relation::In,
                ));
            }
            buckets.entry(room).or_default().push((obj.id, obj.bbox));
        }

        // Declared support.
        let mut declared: Vec<(ObjectId, ObjectId)> = scene
            .items()
            .filter_map(|o| Some((o.id, o.supported_by?)))
            .filter(|&(a, s)| a != s && is_node.contains(&s))
            .collect();
        declared.sort_unstable();
        for &(a, s) in &declared {
            edges.push(Edge::plain(
                NodeRef::Object(a),
                NodeRef::Object(s),
                Relation::On,
            ));
        }

        // `on` across rooms too: a vase may overhang the room its cabinet stands in.
        let mut all: Vec<(ObjectId, Aabb)> = buckets.values().flatten().copied().collect();
        let mut on_pairs = supports(&mut all, cfg);
        for &(top, bottom) in &on_pairs {
            edges.push(Edge::plain(
                NodeRef::Object(top),
                NodeRef::Object(bottom),
                Relation::On,
            ));
        }
        on_pairs.extend_from_slice(&declared);
        on_pairs.sort_unstable();
        for bucket in buckets.values_mut() {
            proximity(bucket, cfg, &on_pairs, &mut edges);
        }

        for door in &scene.doors {
            let [a, b] = door.rooms;
            if a == b || scene.room(a).is_none() || scene.room(b).is_none() {
                continue;
            }
            let (a, b) = (a.min(b), a.max(b));
            edges.push(Edge {
                source: NodeRef::Room(a),
                target: NodeRef::Room(b),
                relation: Relation::Connected,
                distance: None,
                door: Some(door.id),
                open_plan: Some(door.open_plan),
                state: door.state,
            });
        }

        SceneGraph::assemble(scene.id.clone(), nodes, edges)
    }
}

impl Edge {
    fn plain(source: NodeRef, target: NodeRef, relation: Relation) -> Edge {
        Edge {
            source,
            target,
            relation,
            distance: None,
            door: None,
            open_plan: None,
            state: None,
        }
    }
}

/// Sort by min x: a sweep then only visits pairs whose x ranges come within `reach`.
fn sort_for_sweep(items: &mut [(ObjectId, Aabb)]) {
    items.sort_by(|a, b| a.1.min[0].total_cmp(&b.1.min[0]).then(a.0.cmp(&b.0)));
}

/// Geometric `on` pairs `(top, bottom)`, sorted.
fn supports(items: &mut [(ObjectId, Aabb)], cfg: &SceneGraphConfig) -> Vec<(ObjectId, ObjectId)> {
    sort_for_sweep(items);
    let mut out = Vec::new();
    for i in 0..items.len() {
        let (ia, a) = items[i];
        for &(ib, b) in &items[i + 1..] {
            if b.min[0] > a.max[0] {
                break;
            }
            if !a.intersects_xz(&b, 0.0) {
                continue;
            }
            if rests_on(&a, &b, cfg.support_tolerance) {
                out.push((ia, ib));
            } else if rests_on(&b, &a, cfg.support_tolerance) {
                out.push((ib, ia));
            }
        }
    }
    out.sort_unstable();
    out
}

/// `near` and `next_to` inside one room bucket, skipping pairs where one rests on the other
/// (`on_pairs`, sorted): a thing on a table is described by `on`, not by `near`.
fn proximity(
    bucket: &mut [(ObjectId, Aabb)],
    cfg: &SceneGraphConfig,
    on_pairs: &[(ObjectId, ObjectId)],
    edges: &mut Vec<Edge>,
) {
    sort_for_sweep(bucket);
    let reach = cfg.near.max(0.0);
    for i in 0..bucket.len() {
        let (ia, a) = bucket[i];
        for &(ib, b) in &bucket[i + 1..] {
            // Sorted by min x: everything further on starts beyond reach.
            if b.min[0] > a.max[0] + reach {
                break;
            }
            let d = footprint_distance(&a, &b);
            if d >= reach
                || on_pairs.binary_search(&(ia, ib)).is_ok()
                || on_pairs.binary_search(&(ib, ia)).is_ok()
            {
                continue;
            }
            let (lo, hi) = (ia.min(ib), ia.max(ib));
            let mut e = Edge::plain(NodeRef::Object(lo), NodeRef::Object(hi), Relation::Near);
            e.distance = Some(d);
            if d < cfg.next_to {
                let mut n = e.clone();
                n.relation = Relation::NextTo;
                edges.push(n);
            }
            edges.push(e);
        }
    }
}

/// Whether `top` rests on `bottom`: its base is within `tol` of the other's top, and the
/// supporter has real height below that base (so things standing beside each other on a rug
/// are not "on" one another).
fn rests_on(top: &Aabb, bottom: &Aabb, tol: f32) -> bool {
    (top.min[1] - bottom.max[1]).abs() <= tol && top.min[1] > bottom.min[1] + tol
}
