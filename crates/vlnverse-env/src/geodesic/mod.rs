//! Geodesic (shortest walkable) distances on a [`GridMap`], normally the navigable map.
//!
//! - [`shortest_path`] / [`geodesic_distance`]: one query, Lazy Theta* (A* whose vertices may
//!   link to any visible earlier vertex) with the Euclidean heuristic, which is admissible for
//!   any-angle lengths (octile would overestimate them). The path is then string-pulled with
//!   [`GridMap::line_of_sight`], so lengths are close to the true any-angle shortest distance
//!   (exactly the Euclidean distance when the ends see each other), not 8-connected lengths.
//! - [`DistanceField`]: the same search without a target, from one goal to every cell; a query
//!   is then O(1).
//! - [`GeodesicCache`]: distance fields keyed by goal cell (LRU), for many queries.
//! - [`MultiLevelMap`]: the same across the levels of a home on several floors, the stairs
//!   joining the levels' navigable maps as portals.
//!
//! Traversable cells are the free cells; moves never cut a corner between two blocked cells, so
//! reachability is 4-connectivity (as the navigable map's island selection).
//!
//! **Snapping**: a start or goal that is not in a free cell (e.g. an agent pressed against a
//! wall, inside the dilation margin) is moved to the nearest free cell centre within
//! [`snap_distance`] (`max(0.10 m, 1.5 cells)`); the short snap leg is included in the returned
//! length and path. Farther away, outside the map, or on another island:
//! [`GeodesicDistance::Unreachable`]. Non-finite coordinates are an error.

pub mod bench;
mod cache;
mod field;
mod level_field;
mod levels;
pub(crate) mod search;

pub use cache::GeodesicCache;
pub use field::DistanceField;
pub use level_field::{Guide, LevelField};
pub use levels::{LevelPoint, LevelRoute, MultiLevelMap, Portal, RouteLeg};

use crate::error::{EnvError, Result};
use crate::occupancy::GridMap;
use glam::Vec2;
use search::{lazy_theta, Grid, Scratch};
use std::cell::RefCell;

thread_local! {
    /// Search buffers reused by the point-to-point queries of this thread.
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::new());
}
use serde::{Deserialize, Serialize};

/// A geodesic distance: reachable with a length in metres, or explicitly unreachable.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GeodesicDistance {
    /// Reachable; the length in metres.
    Reachable(f32),
    /// No path (other island, blocked, or outside the map).
    Unreachable,
}

impl GeodesicDistance {
    /// The length in metres when reachable.
    pub fn meters(self) -> Option<f32> {
        match self {
            GeodesicDistance::Reachable(d) => Some(d),
            GeodesicDistance::Unreachable => None,
        }
    }

    /// Whether a path exists.
    pub fn is_reachable(self) -> bool {
        matches!(self, GeodesicDistance::Reachable(_))
    }
}

/// A shortest path: line-of-sight smoothed waypoints from start to goal, and its length.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeodesicPath {
    /// Waypoints `(x, z)`, the exact start first and the exact goal last.
    pub points: Vec<Vec2>,
    /// Length of the polyline in metres.
    pub length: f32,
}

impl GeodesicPath {
    fn from_points(points: Vec<Vec2>) -> GeodesicPath {
        let length = polyline_length(&points);
        GeodesicPath { points, length }
    }
}

/// Length of a polyline.
pub fn polyline_length(points: &[Vec2]) -> f32 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// How far a start or goal outside the free cells is snapped: `max(0.10 m, 1.5 cells)`.
pub fn snap_distance(map: &GridMap) -> f32 {
    (1.5 * map.resolution).max(0.10)
}

/// An endpoint resolved onto the grid.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Endpoint {
    /// The point as given.
    pub point: Vec2,
    /// The point itself if free, else the snapped cell centre.
    pub on_grid: Vec2,
    /// Its cell index.
    pub cell: usize,
}

impl Endpoint {
    pub fn snap_len(&self) -> f32 {
        self.point.distance(self.on_grid)
    }
}

pub(crate) fn check_finite(field: &str, p: Vec2) -> Result<()> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(EnvError::invalid(
            field,
            format!("({}, {})", p.x, p.y),
            "coordinates must be finite",
        ))
    }
}

/// Resolve a point onto a free cell (snapping within [`snap_distance`]) with `ok(cell)`.
pub(crate) fn resolve(map: &GridMap, p: Vec2, ok: impl Fn(usize) -> bool) -> Option<Endpoint> {
    if let Some((c, r)) = map.world_to_cell(p) {
        let i = map.index(c, r);
        if ok(i) {
            return Some(Endpoint {
                point: p,
                on_grid: p,
                cell: i,
            });
        }
    }
    let i = map.nearest_cell_where(p, snap_distance(map), ok)?;
    let (c, r) = map.cell_of_index(i);
    Some(Endpoint {
        point: p,
        on_grid: map.cell_center(c, r),
        cell: i,
    })
}

/// Greedy string pulling: from each kept point, jump to the farthest later point in sight
/// (scanning forward, so it is linear in the number of points).
pub fn string_pull(map: &GridMap, pts: &[Vec2]) -> Vec<Vec2> {
    if pts.len() <= 2 {
        return pts.to_vec();
    }
    let mut out = vec![pts[0]];
    let mut i = 0;
    while i + 1 < pts.len() {
        let mut k = i + 1;
        while k + 1 < pts.len() && map.line_of_sight(pts[i], pts[k + 1]) {
            k += 1;
        }
        out.push(pts[k]);
        i = k;
    }
    out
}

/// Shortest path between two world points `(x, z)` on the free cells of `map` (see the module
/// docs for the search, smoothing and snapping rules). `Ok(None)` when unreachable; an error
/// only for non-finite coordinates.
pub fn shortest_path(map: &GridMap, start: Vec2, goal: Vec2) -> Result<Option<GeodesicPath>> {
    check_finite("start", start)?;
    check_finite("goal", goal)?;
    let grid = Grid::new(map);
    let free = |i: usize| grid.free_index(i);
    let (Some(a), Some(b)) = (resolve(map, start, free), resolve(map, goal, free)) else {
        return Ok(None);
    };
    let mut pts = vec![a.point];
    if a.snap_len() > 0.0 {
        pts.push(a.on_grid);
    }
    if a.cell != b.cell && !map.line_of_sight(a.on_grid, b.on_grid) {
        let chain = SCRATCH.with(|sc| {
            let sc = &mut *sc.borrow_mut();
            if !lazy_theta(&grid, a.cell, Some(b.cell), sc) {
                return None;
            }
            let mut chain = vec![b.cell];
            let mut c = b.cell;
            while sc.parent(c) != c {
                c = sc.parent(c);
                chain.push(c);
            }
            Some(chain)
        });
        let Some(chain) = chain else {
            return Ok(None);
        };
        pts.extend(chain.iter().rev().map(|&i| {
            let (col, row) = map.cell_of_index(i);
            map.cell_center(col, row)
        }));
    }
    if b.snap_len() > 0.0 {
        pts.push(b.on_grid);
    }
    pts.push(b.point);
    pts.dedup();
    // Keep the snap legs (their ends are not in free cells), pull the middle.
    let lo = usize::from(a.snap_len() > 0.0);
    let hi = pts.len() - usize::from(b.snap_len() > 0.0);
    let mut out = pts[..lo].to_vec();
    out.extend(string_pull(map, &pts[lo..hi]));
    out.extend_from_slice(&pts[hi..]);
    Ok(Some(GeodesicPath::from_points(out)))
}

/// Geodesic distance between two world points `(x, z)` (one A* query; use
/// [`GeodesicCache`] for many queries).
pub fn geodesic_distance(map: &GridMap, a: Vec2, b: Vec2) -> Result<GeodesicDistance> {
    Ok(match shortest_path(map, a, b)? {
        Some(p) => GeodesicDistance::Reachable(p.length),
        None => GeodesicDistance::Unreachable,
    })
}
