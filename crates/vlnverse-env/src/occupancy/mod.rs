//! 2-D occupancy maps of a scene: raw obstacles in the agent's height band and the navigable map
//! (free cells dilated by the agent radius, largest island only), with ROS `map_server` I/O.
//!
//! # Grid and frames
//! A [`GridMap`] is a row-major grid of [`CellState`]s. Cell `(col, row)` covers world
//! `x in [origin.x + col*res, origin.x + (col+1)*res)` and
//! `z in [origin.y + row*res, origin.y + (row+1)*res)` (2-D points are `Vec2(x, z)`).
//!
//! The ROS map frame is `map x = world x`, `map y = -world z` (the top-down view seen from +Y with
//! -Z pointing up the screen). The top row of the PGM image is the largest map y, i.e. the
//! smallest world z, which is grid row 0: PGM pixel `(i, j)` is cell `(col = i, row = j)`, no flip.
//! The YAML `origin` is the map-frame position of the lower-left corner of the image:
//! `[origin.x, -(origin.y + height*res), 0.0]`.
//!
//! # How the maps are built ([`build_maps`])
//! - Every object except the classes `floor` and `ceiling` is cut to the height band
//!   `[floor_height + floor_clearance, floor_height + agent_height]` and its footprint is
//!   rasterised conservatively: a cell is occupied when the footprint overlaps it (touching an
//!   edge does not count). Cuboids and cylinders whose axis stays vertical (pure yaw) and spheres
//!   take an exact fast path; anything else (imported meshes, tilted primitives) is triangulated,
//!   each triangle clipped to the band and its convex footprint rasterised row by row.
//! - When the scene has objects of class `floor`, the cells that are neither occupied nor over a
//!   floor footprint and connect to the map border through such cells are
//!   [`CellState::Unknown`] (the outside of the home); small floor gaps enclosed by walls and
//!   floor (e.g. between two room slabs under a doorway) stay free. Without any floor object
//!   every non-occupied cell is free.
//! - Navigable: a free cell whose centre is at least `agent_radius + res/2` from the centre of the
//!   nearest occupied cell (exact Euclidean distance transform), restricted to one
//!   **4-connected** island (4-connectivity matches the geodesic search, which never cuts a
//!   corner between two blocked cells): the largest, or, when the scene has ceilings, the one
//!   with the most cells under a ceiling (the indoor floor of an imported house with a terrace
//!   around it). Unknown cells stay unknown; everything else is occupied.

mod edt;
mod raster;
mod ros;
pub mod synthetic;

use crate::error::{EnvError, Result};
use crate::scene::{LevelId, Scene};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

pub use edt::{dilate, keep_best_island, keep_largest_island, squared_distance_transform};

/// Largest grid accepted (cells), to fail clearly instead of allocating gigabytes.
pub const MAX_CELLS: u64 = 400_000_000;

/// Parameters of the occupancy maps.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OccupancyConfig {
    /// Cell size in metres.
    pub resolution: f32,
    /// Agent radius used to dilate obstacles for the navigable map (m).
    pub agent_radius: f32,
    /// Agent height: geometry above `floor_height + agent_height` is ignored (m).
    pub agent_height: f32,
    /// Geometry lower than `floor_height + floor_clearance` is ignored, e.g. rugs (m).
    pub floor_clearance: f32,
    /// Margin added around the scene bounds (m).
    pub padding: f32,
}

impl Default for OccupancyConfig {
    fn default() -> Self {
        OccupancyConfig {
            resolution: 0.05,
            agent_radius: 0.30,
            agent_height: 1.50,
            floor_clearance: 0.05,
            padding: 0.25,
        }
    }
}

impl OccupancyConfig {
    /// Check every value; the error names the offending field.
    pub fn validate(&self) -> Result<()> {
        let finite = |field: &str, v: f32| {
            if v.is_finite() {
                Ok(())
            } else {
                Err(EnvError::invalid(field, v, "must be a finite number"))
            }
        };
        finite("resolution", self.resolution)?;
        finite("agent_radius", self.agent_radius)?;
        finite("agent_height", self.agent_height)?;
        finite("floor_clearance", self.floor_clearance)?;
        finite("padding", self.padding)?;
        if self.resolution <= 0.0 {
            return Err(EnvError::invalid(
                "resolution",
                self.resolution,
                "must be > 0 (metres per cell)",
            ));
        }
        if self.agent_radius < 0.0 {
            return Err(EnvError::invalid(
                "agent_radius",
                self.agent_radius,
                "must be >= 0",
            ));
        }
        if self.floor_clearance < 0.0 {
            return Err(EnvError::invalid(
                "floor_clearance",
                self.floor_clearance,
                "must be >= 0",
            ));
        }
        if self.agent_height <= self.floor_clearance {
            return Err(EnvError::invalid(
                "agent_height",
                self.agent_height,
                format!("must be > floor_clearance ({})", self.floor_clearance),
            ));
        }
        if self.padding < 0.0 {
            return Err(EnvError::invalid("padding", self.padding, "must be >= 0"));
        }
        Ok(())
    }
}

/// State of one cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[repr(u8)]
pub enum CellState {
    /// Free (PGM 254).
    Free = 0,
    /// Occupied (PGM 0).
    Occupied = 1,
    /// Unknown, e.g. outside the floor (PGM 205).
    Unknown = 2,
}

impl CellState {
    /// The ROS map_server trinary pixel value (negate 0).
    pub fn pgm_value(self) -> u8 {
        match self {
            CellState::Free => 254,
            CellState::Occupied => 0,
            CellState::Unknown => 205,
        }
    }
}

/// A 2-D grid over the floor plane. See the [module docs](self) for the frame conventions.
///
/// Clones share their cells until one of them is changed (a distance field keeps the map it
/// was computed on; a home's dozens of fields then hold one copy of its cells, not dozens).
#[derive(Clone, Debug, PartialEq)]
pub struct GridMap {
    /// Number of columns (along +x).
    pub width: u32,
    /// Number of rows (along +z).
    pub height: u32,
    /// Cell size in metres.
    pub resolution: f32,
    /// World `(x, z)` of the min corner of cell `(0, 0)`.
    pub origin: Vec2,
    cells: Arc<Vec<CellState>>,
}

impl GridMap {
    /// A map with every cell set to `fill`.
    pub fn new(
        width: u32,
        height: u32,
        resolution: f32,
        origin: Vec2,
        fill: CellState,
    ) -> Result<GridMap> {
        check_geometry(width, height, resolution, origin)?;
        Ok(GridMap {
            width,
            height,
            resolution,
            origin,
            cells: Arc::new(vec![fill; width as usize * height as usize]),
        })
    }

    /// A map from row-major cells (`cells[row * width + col]`).
    pub fn from_cells(
        width: u32,
        height: u32,
        resolution: f32,
        origin: Vec2,
        cells: Vec<CellState>,
    ) -> Result<GridMap> {
        check_geometry(width, height, resolution, origin)?;
        let n = width as usize * height as usize;
        if cells.len() != n {
            return Err(EnvError::invalid(
                "cells",
                cells.len(),
                format!("expected width*height = {n} cells"),
            ));
        }
        Ok(GridMap {
            width,
            height,
            resolution,
            origin,
            cells: Arc::new(cells),
        })
    }

    /// Row-major cells (`cells()[row * width + col]`).
    pub fn cells(&self) -> &[CellState] {
        &self.cells
    }

    /// Mutable row-major cells.
    pub fn cells_mut(&mut self) -> &mut [CellState] {
        Arc::make_mut(&mut self.cells).as_mut_slice()
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// Whether the map has no cells.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// Row-major index of a cell (no bounds check beyond debug asserts).
    #[inline]
    pub fn index(&self, col: u32, row: u32) -> usize {
        debug_assert!(col < self.width && row < self.height);
        row as usize * self.width as usize + col as usize
    }

    /// `(col, row)` of a row-major index.
    #[inline]
    pub fn cell_of_index(&self, i: usize) -> (u32, u32) {
        let w = self.width as usize;
        ((i % w) as u32, (i / w) as u32)
    }

    /// State of a cell; [`CellState::Unknown`] outside the map.
    #[inline]
    pub fn state(&self, col: u32, row: u32) -> CellState {
        if col < self.width && row < self.height {
            self.cells[self.index(col, row)]
        } else {
            CellState::Unknown
        }
    }

    /// Set a cell (ignored outside the map).
    pub fn set(&mut self, col: u32, row: u32, state: CellState) {
        if col < self.width && row < self.height {
            let i = self.index(col, row);
            Arc::make_mut(&mut self.cells)[i] = state;
        }
    }

    /// Whether a cell is free (false outside the map).
    #[inline]
    pub fn is_free(&self, col: u32, row: u32) -> bool {
        self.state(col, row) == CellState::Free
    }

    /// The cell containing a world point `(x, z)`, or None outside the map (or for NaN).
    pub fn world_to_cell(&self, p: Vec2) -> Option<(u32, u32)> {
        let u = ((p.x - self.origin.x) / self.resolution).floor();
        let v = ((p.y - self.origin.y) / self.resolution).floor();
        // The negated comparisons also reject NaN.
        if !(u >= 0.0 && v >= 0.0 && u < self.width as f32 && v < self.height as f32) {
            return None;
        }
        Some((u as u32, v as u32))
    }

    /// World `(x, z)` of a cell's centre.
    #[inline]
    pub fn cell_center(&self, col: u32, row: u32) -> Vec2 {
        self.origin + Vec2::new(col as f32 + 0.5, row as f32 + 0.5) * self.resolution
    }

    /// Whether the point lies in a free cell (false outside the map).
    pub fn is_free_at(&self, p: Vec2) -> bool {
        self.world_to_cell(p)
            .is_some_and(|(c, r)| self.is_free(c, r))
    }

    /// World `(x, z)` extent: `(min corner, max corner)`.
    pub fn bounds(&self) -> (Vec2, Vec2) {
        (
            self.origin,
            self.origin + Vec2::new(self.width as f32, self.height as f32) * self.resolution,
        )
    }

    /// Whether every cell the segment `a`-`b` passes through (corners included: a segment through
    /// a grid corner touches all four cells) is free. False when either end is outside the map.
    pub fn line_of_sight(&self, a: Vec2, b: Vec2) -> bool {
        let res = self.resolution;
        let ua = (a - self.origin) / res;
        let ub = (b - self.origin) / res;
        los_float(ua, ub, self.width, self.height, |c, r| self.is_free(c, r))
    }

    /// `p` itself when it is in a free cell, else the centre of the free cell nearest to `p`
    /// whose centre lies within `max_dist`; None when there is none.
    pub fn nearest_free(&self, p: Vec2, max_dist: f32) -> Option<Vec2> {
        if self.is_free_at(p) {
            return Some(p);
        }
        self.nearest_cell_where(p, max_dist, |i| self.cells[i] == CellState::Free)
            .map(|i| {
                let (c, r) = self.cell_of_index(i);
                self.cell_center(c, r)
            })
    }

    /// Index of the cell nearest to `p` (by centre distance, ties broken by index) within
    /// `max_dist` that satisfies `pred`.
    pub(crate) fn nearest_cell_where(
        &self,
        p: Vec2,
        max_dist: f32,
        pred: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        if !(p.is_finite() && max_dist >= 0.0) {
            return None;
        }
        let res = self.resolution;
        let u = (p.x - self.origin.x) / res;
        let v = (p.y - self.origin.y) / res;
        let rc = max_dist / res;
        let c0 = (u - rc - 0.5).floor().max(0.0);
        let c1 = (u + rc - 0.5).ceil().min(self.width as f32 - 1.0);
        let r0 = (v - rc - 0.5).floor().max(0.0);
        let r1 = (v + rc - 0.5).ceil().min(self.height as f32 - 1.0);
        if c0 > c1 || r0 > r1 {
            return None;
        }
        let mut best: Option<(f32, usize)> = None;
        for row in r0 as u32..=r1 as u32 {
            for col in c0 as u32..=c1 as u32 {
                let i = self.index(col, row);
                if !pred(i) {
                    continue;
                }
                let d = self.cell_center(col, row).distance(p);
                if d <= max_dist && best.is_none_or(|(bd, _)| d < bd) {
                    best = Some((d, i));
                }
            }
        }
        best.map(|(_, i)| i)
    }

    /// Number of free cells.
    pub fn free_count(&self) -> usize {
        self.cells.iter().filter(|&&c| c == CellState::Free).count()
    }

    /// Free area in square metres.
    pub fn free_area_m2(&self) -> f32 {
        self.free_count() as f32 * self.resolution * self.resolution
    }

    /// Every free cell as `(col, row)`, row-major.
    pub fn free_cells(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.cells
            .iter()
            .enumerate()
            .filter(|(_, &c)| c == CellState::Free)
            .map(|(i, _)| self.cell_of_index(i))
    }
}

fn check_geometry(width: u32, height: u32, resolution: f32, origin: Vec2) -> Result<()> {
    if !(resolution.is_finite() && resolution > 0.0) {
        return Err(EnvError::invalid(
            "resolution",
            resolution,
            "must be a finite number > 0",
        ));
    }
    if !origin.is_finite() {
        return Err(EnvError::invalid(
            "origin",
            format!("{origin:?}"),
            "must be finite",
        ));
    }
    if width == 0 || height == 0 {
        return Err(EnvError::invalid(
            "width/height",
            format!("{width}x{height}"),
            "a map needs at least one cell",
        ));
    }
    if width as u64 * height as u64 > MAX_CELLS {
        return Err(EnvError::invalid(
            "width/height",
            format!("{width}x{height}"),
            format!("more than {MAX_CELLS} cells; use a coarser resolution"),
        ));
    }
    Ok(())
}

/// Supercover traversal in cell units (`ua`, `ub` = position / resolution from the origin).
pub(crate) fn los_float(
    ua: Vec2,
    ub: Vec2,
    width: u32,
    height: u32,
    free: impl Fn(u32, u32) -> bool,
) -> bool {
    if !(ua.is_finite() && ub.is_finite()) {
        return false;
    }
    let inside = |u: Vec2| u.x >= 0.0 && u.y >= 0.0 && u.x < width as f32 && u.y < height as f32;
    if !inside(ua) || !inside(ub) {
        return false;
    }
    let (mut cx, mut cy) = (ua.x.floor() as i64, ua.y.floor() as i64);
    let (ex, ey) = (ub.x.floor() as i64, ub.y.floor() as i64);
    let ok = |x: i64, y: i64| {
        x >= 0 && y >= 0 && (x as u32) < width && (y as u32) < height && free(x as u32, y as u32)
    };
    if !ok(cx, cy) {
        return false;
    }
    let d = ub - ua;
    let sx: i64 = if d.x > 0.0 { 1 } else { -1 };
    let sy: i64 = if d.y > 0.0 { 1 } else { -1 };
    let inv = |v: f32| {
        if v != 0.0 {
            1.0 / v.abs()
        } else {
            f32::INFINITY
        }
    };
    let (tdx, tdy) = (inv(d.x), inv(d.y));
    let next_x = if d.x > 0.0 {
        (cx as f32 + 1.0 - ua.x) * tdx
    } else {
        (ua.x - cx as f32) * tdx
    };
    let next_y = if d.y > 0.0 {
        (cy as f32 + 1.0 - ua.y) * tdy
    } else {
        (ua.y - cy as f32) * tdy
    };
    let (mut tx, mut ty) = (next_x, next_y);
    let steps = (ex - cx).abs() + (ey - cy).abs();
    let mut taken = 0;
    const EPS: f32 = 1e-5;
    while (cx != ex || cy != ey) && taken <= steps {
        if (tx - ty).abs() < EPS {
            // Through a corner: both side cells must be free.
            if !ok(cx + sx, cy) || !ok(cx, cy + sy) {
                return false;
            }
            cx += sx;
            cy += sy;
            tx += tdx;
            ty += tdy;
            taken += 2;
        } else if tx < ty {
            cx += sx;
            tx += tdx;
            taken += 1;
        } else {
            cy += sy;
            ty += tdy;
            taken += 1;
        }
        if !ok(cx, cy) {
            return false;
        }
    }
    true
}

/// The two maps of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct OccupancyMaps {
    /// Raw obstacles in the agent's height band (free / occupied / unknown outside the floor).
    pub occupancy: GridMap,
    /// Free cells dilated by the agent radius, one 4-connected island only: the largest, or
    /// the one most under a ceiling when the scene has ceilings ([`keep_best_island`]).
    pub navigable: GridMap,
}

/// Build the raw occupancy map and the navigable map of a scene. For a scene on several levels
/// these are the maps of level 0 (the ground floor); [`build_level_maps`] gives every level's.
pub fn build_maps(scene: &Scene, cfg: &OccupancyConfig) -> Result<OccupancyMaps> {
    if scene.is_multi_level() {
        return build_one_level(scene, cfg, 0);
    }
    cfg.validate()?;
    let (occupancy, covered) = raster::rasterize_scene(scene, cfg)?;
    let mut navigable = dilate(&occupancy, cfg.agent_radius);
    let kept = keep_best_island(&mut navigable, covered.as_deref());
    tracing::debug!(
        scene = %scene.id,
        width = occupancy.width,
        height = occupancy.height,
        navigable_cells = kept,
        "occupancy maps built"
    );
    Ok(OccupancyMaps {
        occupancy,
        navigable,
    })
}

/// The maps of every level of a scene, the lowest first: for a single-storey scene exactly
/// `vec![build_maps(scene, cfg)?]`. On a level the height band starts at that level's floor,
/// only the floors and ceilings of that level count (a floor by the height of its top, a ceiling
/// by the height below its underside), and the footprint of every flight of stairs reaching
/// the level is occupied: a solid block on the lower level, the stairwell on the upper one. The
/// stairs join the levels as portals ([`crate::geodesic::MultiLevelMap`]).
pub fn build_level_maps(scene: &Scene, cfg: &OccupancyConfig) -> Result<Vec<OccupancyMaps>> {
    if !scene.is_multi_level() {
        return Ok(vec![build_maps(scene, cfg)?]);
    }
    (0..scene.level_count() as LevelId)
        .map(|l| build_one_level(scene, cfg, l))
        .collect()
}

/// The file name of a map of floor `level` in a scene folder: `{stem}.{ext}` on the ground
/// floor (`navigable.yaml`), `{stem}_level{level}.{ext}` above it (`navigable_level1.yaml`);
/// `stem` is `occupancy` or `navigable`, `ext` `yaml` or `pgm`.
pub fn level_map_file(stem: &str, level: LevelId, ext: &str) -> String {
    if level == 0 {
        format!("{stem}.{ext}")
    } else {
        format!("{stem}_level{level}.{ext}")
    }
}

/// The ROS map files of the levels above the ground floor of a multi-level scene:
/// `occupancy_level<k>.{pgm,yaml}` and `navigable_level<k>.{pgm,yaml}` for `k >= 1` (the
/// ground floor's are the scene folder's `occupancy.*` / `navigable.*`); none for a
/// single-storey scene.
pub fn upper_level_files(scene: &Scene, cfg: &OccupancyConfig) -> Result<Vec<(String, Vec<u8>)>> {
    let mut out = Vec::new();
    if !scene.is_multi_level() {
        return Ok(out);
    }
    for level in 1..scene.level_count() as LevelId {
        let maps = build_one_level(scene, cfg, level)?;
        for (stem, map) in [
            ("occupancy", &maps.occupancy),
            ("navigable", &maps.navigable),
        ] {
            let pgm = level_map_file(stem, level, "pgm");
            out.push((
                level_map_file(stem, level, "yaml"),
                map.to_yaml(&pgm).into_bytes(),
            ));
            out.push((pgm, map.to_pgm_bytes()));
        }
    }
    Ok(out)
}

fn build_one_level(scene: &Scene, cfg: &OccupancyConfig, level: LevelId) -> Result<OccupancyMaps> {
    cfg.validate()?;
    let (occupancy, covered) = raster::rasterize_level(scene, cfg, level)?;
    let mut navigable = dilate(&occupancy, cfg.agent_radius);
    let kept = keep_best_island(&mut navigable, covered.as_deref());
    tracing::debug!(
        scene = %scene.id,
        level,
        width = occupancy.width,
        height = occupancy.height,
        navigable_cells = kept,
        "level maps built"
    );
    Ok(OccupancyMaps {
        occupancy,
        navigable,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn open(w: u32, h: u32) -> GridMap {
        GridMap::new(w, h, 0.1, Vec2::new(-1.0, -2.0), CellState::Free).unwrap()
    }

    /// Clones share their cells until one is changed, which then changes only itself.
    #[test]
    fn clones_share_cells_until_one_changes() {
        let mut a = open(4, 3);
        let b = a.clone();
        assert!(std::ptr::eq(a.cells(), b.cells()));
        a.set(1, 2, CellState::Occupied);
        assert_eq!(a.state(1, 2), CellState::Occupied);
        assert_eq!(b.state(1, 2), CellState::Free);
        let mut c = b.clone();
        c.cells_mut()[0] = CellState::Unknown;
        assert_eq!(
            (b.cells()[0], c.cells()[0]),
            (CellState::Free, CellState::Unknown)
        );
        assert!(!std::ptr::eq(b.cells(), c.cells()));
        assert_ne!(a, b);
    }

    #[test]
    fn cell_round_trip() {
        let m = open(20, 30);
        for (c, r) in [(0, 0), (19, 29), (5, 7)] {
            assert_eq!(m.world_to_cell(m.cell_center(c, r)), Some((c, r)));
        }
        assert_eq!(m.world_to_cell(Vec2::new(-1.01, 0.0)), None);
        assert_eq!(m.world_to_cell(Vec2::new(f32::NAN, 0.0)), None);
        assert_eq!(
            m.world_to_cell(Vec2::new(1.0 - 1e-4, 1.0 - 1e-4)),
            Some((19, 29))
        );
    }

    #[test]
    fn los_blocked_by_single_cell_and_by_corner() {
        let mut m = open(10, 10);
        let c = |col: u32, row: u32| m.cell_center(col, row);
        assert!(m.line_of_sight(c(0, 0), c(9, 9)));
        m.set(5, 5, CellState::Occupied);
        let m2 = m.clone();
        let c2 = |col: u32, row: u32| m2.cell_center(col, row);
        assert!(!m2.line_of_sight(c2(0, 0), c2(9, 9)));
        assert!(m2.line_of_sight(c2(0, 1), c2(9, 1)));
        // A diagonal through the corner shared by (5,5) and (4,4) touches (5,4) and (4,5).
        let mut m3 = open(10, 10);
        m3.set(5, 4, CellState::Occupied);
        assert!(!m3.line_of_sight(m3.cell_center(4, 4), m3.cell_center(5, 5)));
        assert!(m3.line_of_sight(m3.cell_center(4, 5), m3.cell_center(6, 5)));
    }

    #[test]
    fn nearest_free_finds_closest() {
        let mut m = GridMap::new(10, 10, 0.1, Vec2::ZERO, CellState::Occupied).unwrap();
        m.set(7, 2, CellState::Free);
        let p = Vec2::new(0.55, 0.25);
        assert_eq!(m.nearest_free(p, 0.1), None);
        let q = m.nearest_free(p, 0.3).unwrap();
        assert!(q.distance(m.cell_center(7, 2)) < 1e-6);
    }
}
