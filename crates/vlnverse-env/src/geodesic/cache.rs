//! LRU cache of distance fields keyed by goal cell.

use super::field::DistanceField;
use super::search::Grid;
use super::{check_finite, resolve, Endpoint, GeodesicDistance, GeodesicPath};
use crate::error::Result;
use crate::occupancy::GridMap;
use glam::Vec2;
use std::collections::HashMap;
use std::sync::Arc;

/// Many geodesic queries on one map: the first query to a goal builds a [`DistanceField`] for
/// the goal's cell (one Dijkstra-like sweep of the map), later queries to any goal point in the
/// same cell are O(1). At most `capacity` fields are kept (least recently used evicted first).
/// Goal points in the same cell share a field but each query uses its exact goal point.
#[derive(Debug)]
pub struct GeodesicCache {
    map: Arc<GridMap>,
    capacity: usize,
    fields: HashMap<usize, (Arc<DistanceField>, u64)>,
    tick: u64,
    hits: u64,
    misses: u64,
}

impl GeodesicCache {
    /// Cache over `map` keeping at most `capacity` fields (at least 1).
    pub fn new(map: impl Into<Arc<GridMap>>, capacity: usize) -> GeodesicCache {
        GeodesicCache {
            map: map.into(),
            capacity: capacity.max(1),
            fields: HashMap::new(),
            tick: 0,
            hits: 0,
            misses: 0,
        }
    }

    /// The map queried.
    pub fn map(&self) -> &GridMap {
        &self.map
    }

    /// Number of fields held.
    pub fn len(&self) -> usize {
        self.fields.len()
    }

    /// Whether no field is held.
    pub fn is_empty(&self) -> bool {
        self.fields.is_empty()
    }

    /// `(hits, misses)` of field look-ups so far.
    pub fn stats(&self) -> (u64, u64) {
        (self.hits, self.misses)
    }

    /// Drop every field.
    pub fn clear(&mut self) {
        self.fields.clear();
    }

    /// The field for the cell of `goal` (built on first use), or None when the goal cannot be
    /// placed on a free cell. Note the field's own `goal()` is the first goal point seen for
    /// that cell; prefer [`GeodesicCache::distance`] for exact goals.
    pub fn field(&mut self, goal: Vec2) -> Result<Option<Arc<DistanceField>>> {
        Ok(self
            .entry(goal)?
            .map(|(key, _)| self.fields[&key].0.clone()))
    }

    /// Make sure the field of `goal`'s cell exists; its key and the resolved goal.
    fn entry(&mut self, goal: Vec2) -> Result<Option<(usize, Endpoint)>> {
        check_finite("goal", goal)?;
        let grid = Grid::new(&self.map);
        let Some(g) = resolve(&self.map, goal, |i| grid.free_index(i)) else {
            return Ok(None);
        };
        self.tick += 1;
        let tick = self.tick;
        if let Some(entry) = self.fields.get_mut(&g.cell) {
            entry.1 = tick;
            self.hits += 1;
            return Ok(Some((g.cell, g)));
        }
        self.misses += 1;
        if self.fields.len() >= self.capacity {
            // Ticks are unique, so the evicted entry does not depend on hash order.
            if let Some(&oldest) = self
                .fields
                .iter()
                .min_by_key(|(_, (_, t))| *t)
                .map(|(k, _)| k)
            {
                self.fields.remove(&oldest);
            }
        }
        let field = Arc::new(DistanceField::new(&self.map, goal)?);
        debug_assert_eq!(field.root(), Some(g.cell));
        self.fields.insert(g.cell, (field, tick));
        Ok(Some((g.cell, g)))
    }

    /// Geodesic distance from `a` to `b` (builds or reuses the field of `b`'s cell).
    pub fn distance(&mut self, a: Vec2, b: Vec2) -> Result<GeodesicDistance> {
        check_finite("start", a)?;
        Ok(match self.entry(b)? {
            Some((key, goal)) => self.fields[&key].0.distance_to(a, &goal),
            None => GeodesicDistance::Unreachable,
        })
    }

    /// Shortest path from `a` to `b` along the cached field of `b`'s cell.
    pub fn shortest_path(&mut self, a: Vec2, b: Vec2) -> Result<Option<GeodesicPath>> {
        check_finite("start", a)?;
        Ok(match self.entry(b)? {
            Some((key, goal)) => self.fields[&key].0.path_to(a, &goal),
            None => None,
        })
    }
}
