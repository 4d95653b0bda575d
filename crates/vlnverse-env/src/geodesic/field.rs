//! Distance field from one goal to every reachable cell.

use super::search::{sweep, Grid, Reached};
use super::{check_finite, resolve, Endpoint, GeodesicDistance, GeodesicPath};
use crate::error::Result;
use crate::occupancy::GridMap;
use glam::Vec2;

/// Geodesic distance from every cell of a map to one goal (any-angle Lazy Theta* run without a
/// target from the goal's cell). Each reachable cell stores its distance and its *anchor*, the
/// visible vertex it walks to in a straight line, so a query is O(1) and exact (Euclidean) when
/// the goal is in sight. Only reachable cells hold a distance and an anchor (about a third of
/// a home's map), found by their rank among them.
#[derive(Clone, Debug)]
pub struct DistanceField {
    map: GridMap,
    root: Option<usize>,
    goal: Option<Endpoint>,
    /// The reachable cells.
    reached: Reached,
    /// Per reachable cell, in cell order: distance (cells) from the root cell centre along
    /// anchors.
    g: Vec<f32>,
    /// Per reachable cell, in cell order: its anchor's cell index (the root's is the root).
    parent: Vec<u32>,
}

impl DistanceField {
    /// Field from `goal` `(x, z)` over the free cells of `map` (a goal outside the free cells is
    /// snapped like [`super::shortest_path`] does; if it cannot be, every query is
    /// unreachable). Errors only for non-finite coordinates.
    pub fn new(map: &GridMap, goal: Vec2) -> Result<DistanceField> {
        check_finite("goal", goal)?;
        let grid = Grid::new(map);
        let goal = resolve(map, goal, |i| grid.free_index(i));
        let mut f = DistanceField::from_root(map, goal.map(|e| e.cell));
        f.goal = goal;
        Ok(f)
    }

    /// Field rooted at the centre of cell `root` (a free cell), without a goal point.
    pub(crate) fn from_root(map: &GridMap, root: Option<usize>) -> DistanceField {
        let Some(root) = root else {
            return DistanceField {
                map: map.clone(),
                root: None,
                goal: None,
                reached: Reached::default(),
                g: Vec::new(),
                parent: Vec::new(),
            };
        };
        let grid = Grid::with_sat(map);
        let res = sweep(&grid, root);
        DistanceField {
            map: map.clone(),
            root: Some(root),
            goal: None,
            reached: res.reached,
            g: res.g,
            parent: res.parent,
        }
    }

    /// The root cell index (None when the goal was unreachable / off the map).
    pub(crate) fn root(&self) -> Option<usize> {
        self.root
    }

    /// The map the field was computed on.
    pub fn map(&self) -> &GridMap {
        &self.map
    }

    /// The goal as given to [`DistanceField::new`] (None for an unusable goal).
    pub fn goal(&self) -> Option<Vec2> {
        self.goal.map(|e| e.point)
    }

    /// Bytes the field holds: its per-cell arrays, by capacity. Its map's cells are not
    /// counted: they are shared with the map the field was computed on ([`GridMap`]'s clones
    /// share them).
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.reached.bytes()
            + self.g.capacity() * 4
            + self.parent.capacity() * 4
    }

    /// Distance (cells) of cell `i` from the root along anchors; infinite when unreachable.
    #[inline]
    fn g(&self, i: usize) -> f32 {
        self.reached.slot(i).map_or(f32::INFINITY, |k| self.g[k])
    }

    /// The anchor of reachable cell `i`.
    #[inline]
    fn parent(&self, i: usize) -> usize {
        self.reached
            .slot(i)
            .map_or(u32::MAX as usize, |k| self.parent[k] as usize)
    }

    /// Number of cells with a finite distance.
    pub fn reachable_cells(&self) -> usize {
        self.g.len()
    }

    /// The first vertex after the root on the anchor chain of `a` (reachable, not the root): a
    /// walk of a few vertices, kept per cell it cost 4 bytes a cell of every field.
    fn first_vertex(&self, a: usize, root: usize) -> usize {
        let mut v = a;
        loop {
            let p = self.parent(v);
            if p == root || p == v {
                return v;
            }
            v = p;
        }
    }

    fn center(&self, i: usize) -> Vec2 {
        let (c, r) = self.map.cell_of_index(i);
        self.map.cell_center(c, r)
    }

    fn start_endpoint(&self, p: Vec2) -> Option<Endpoint> {
        if !p.is_finite() {
            return None;
        }
        resolve(&self.map, p, |i| self.reached.slot(i).is_some())
    }

    /// Geodesic distance from `p` to the field's goal (O(1)).
    pub fn distance(&self, p: Vec2) -> GeodesicDistance {
        match self.goal {
            Some(goal) => self.distance_to(p, &goal),
            None => GeodesicDistance::Unreachable,
        }
    }

    /// Distance from `p` to a goal point lying in the root cell.
    pub(crate) fn distance_to(&self, p: Vec2, goal: &Endpoint) -> GeodesicDistance {
        let (Some(root), Some(s)) = (self.root, self.start_endpoint(p)) else {
            return GeodesicDistance::Unreachable;
        };
        let a = self.parent(s.cell);
        let res = self.map.resolution;
        let core = if a == root {
            s.on_grid.distance(goal.on_grid)
        } else {
            let v1 = self.first_vertex(a, root);
            s.on_grid.distance(self.center(a))
                + (self.g(a) - self.g(v1)) * res
                + self.center(v1).distance(goal.on_grid)
        };
        GeodesicDistance::Reachable(core + s.snap_len() + goal.snap_len())
    }

    /// The point to walk to in a straight line from `p` towards the goal (the goal itself when
    /// it is in sight); None when unreachable.
    pub fn next_waypoint(&self, p: Vec2) -> Option<Vec2> {
        let goal = self.goal?;
        let root = self.root?;
        let s = self.start_endpoint(p)?;
        if s.snap_len() > 0.0 {
            return Some(s.on_grid);
        }
        let a = self.parent(s.cell);
        Some(if a == root {
            goal.on_grid
        } else {
            self.center(a)
        })
    }

    /// The whole path from `p` to the goal along the field's anchors; None when unreachable.
    pub fn path(&self, p: Vec2) -> Option<GeodesicPath> {
        let goal = self.goal?;
        self.path_to(p, &goal)
    }

    pub(crate) fn path_to(&self, p: Vec2, goal: &Endpoint) -> Option<GeodesicPath> {
        let root = self.root?;
        let s = self.start_endpoint(p)?;
        let mut pts = vec![s.point];
        if s.snap_len() > 0.0 {
            pts.push(s.on_grid);
        }
        let mut c = self.parent(s.cell);
        while c != root {
            pts.push(self.center(c));
            c = self.parent(c);
        }
        pts.push(goal.on_grid);
        if goal.snap_len() > 0.0 {
            pts.push(goal.point);
        }
        pts.dedup();
        Some(GeodesicPath::from_points(pts))
    }
}
