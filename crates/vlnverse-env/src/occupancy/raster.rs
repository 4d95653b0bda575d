//! Conservative rasterisation of scene footprints in the agent's height band.

use super::{CellState, GridMap, OccupancyConfig};
use crate::error::{EnvError, Result};
use crate::geometry;
use crate::scene::{LevelId, Pose, Scene, SceneObject, Shape};
use crate::vocab::SemanticClass;
use glam::{Affine3A, DVec2, Quat, Vec2, Vec3};

/// Cells an edge must overlap by (in cell units) to count; also absorbs float noise so that a
/// wall face lying exactly on a cell boundary does not spill into the next cell.
const EPS: f64 = 1e-3;

/// A 2-D footprint in world `(x, z)`.
enum Footprint {
    /// Convex polygon (or degenerate segment/point): range into the point buffer.
    Poly { start: u32, len: u8 },
    /// Disc.
    Disc { center: Vec2, radius: f32 },
}

#[derive(Default)]
struct Footprints {
    points: Vec<Vec2>,
    items: Vec<Footprint>,
    min: Vec2,
    max: Vec2,
}

impl Footprints {
    fn new() -> Self {
        Footprints {
            min: Vec2::splat(f32::INFINITY),
            max: Vec2::splat(f32::NEG_INFINITY),
            ..Default::default()
        }
    }

    fn push_poly(&mut self, pts: &[Vec2]) {
        if pts.is_empty() {
            return;
        }
        let start = self.points.len() as u32;
        for &p in pts {
            self.min = self.min.min(p);
            self.max = self.max.max(p);
            self.points.push(p);
        }
        self.items.push(Footprint::Poly {
            start,
            len: pts.len() as u8,
        });
    }

    fn push_disc(&mut self, center: Vec2, radius: f32) {
        if radius <= 0.0 {
            return;
        }
        self.min = self.min.min(center - Vec2::splat(radius));
        self.max = self.max.max(center + Vec2::splat(radius));
        self.items.push(Footprint::Disc { center, radius });
    }

    fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
}

/// Height band: geometry counts when it overlaps `(lo, hi)` with positive thickness.
#[derive(Clone, Copy)]
struct Band {
    lo: f32,
    hi: f32,
}

impl Band {
    fn overlaps(&self, ymin: f32, ymax: f32) -> bool {
        ymax > self.lo && ymin < self.hi
    }
}

/// Whether the rotation keeps the local Y axis vertical (a pure yaw, possibly upside down).
fn keeps_vertical(q: Quat) -> bool {
    (q * Vec3::Y).y.abs() > 1.0 - 1e-6
}

fn xz(p: Vec3) -> Vec2 {
    Vec2::new(p.x, p.z)
}

/// Footprint of one part in the band (or unconditionally when `band` is None, for floors).
fn part_footprint(shape: &Shape, pose: &Pose, band: Option<Band>, out: &mut Footprints) {
    let q = pose.quat();
    let t = pose.translation();
    let in_band = |ymin: f32, ymax: f32| band.is_none_or(|b| b.overlaps(ymin, ymax));
    match shape {
        Shape::Cuboid { half_extents, .. } if keeps_vertical(q) => {
            let h = Vec3::from_array(*half_extents);
            if !in_band(t.y - h.y, t.y + h.y) {
                return;
            }
            let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .map(|(sx, sz)| xz(q * Vec3::new(sx * h.x, 0.0, sz * h.z) + t));
            out.push_poly(&corners);
        }
        Shape::Cylinder {
            radius,
            half_height,
        } if keeps_vertical(q) => {
            if in_band(t.y - half_height, t.y + half_height) {
                out.push_disc(xz(t), *radius);
            }
        }
        Shape::Sphere { radius } => {
            let r = *radius;
            if !in_band(t.y - r, t.y + r) {
                return;
            }
            let rr = match band {
                Some(b) if t.y < b.lo => (r * r - (b.lo - t.y).powi(2)).max(0.0).sqrt(),
                Some(b) if t.y > b.hi => (r * r - (t.y - b.hi).powi(2)).max(0.0).sqrt(),
                _ => r,
            };
            out.push_disc(xz(t), rr);
        }
        Shape::Mesh(m) => {
            let aff = Affine3A::from_rotation_translation(q, t);
            out.points.reserve(m.indices.len() * 3);
            out.items.reserve(m.indices.len());
            let world: Vec<Vec3> = m
                .positions
                .iter()
                .map(|p| aff.transform_point3(Vec3::from_array(*p)))
                .collect();
            for tri in &m.indices {
                let (Some(&a), Some(&b), Some(&c)) = (
                    world.get(tri[0] as usize),
                    world.get(tri[1] as usize),
                    world.get(tri[2] as usize),
                ) else {
                    continue; // Out-of-range indices are the importer's problem; skip them.
                };
                triangle_footprint([a, b, c], band, out);
            }
        }
        other => {
            // The full box, as for upright boxes: a bevel only shapes the drawn mesh.
            let sharp;
            let other = match other {
                Shape::Cuboid { half_extents, .. } => {
                    sharp = Shape::Cuboid {
                        half_extents: *half_extents,
                        bevel: 0.0,
                    };
                    &sharp
                }
                _ => other,
            };
            let local = geometry::triangulate(other);
            let aff = Affine3A::from_rotation_translation(q, t);
            for tri in &local.indices {
                let v = tri
                    .map(|i| aff.transform_point3(Vec3::from_array(local.positions[i as usize])));
                triangle_footprint(v, band, out);
            }
        }
    }
}

/// Clip a triangle to the band and push its projected (convex) footprint.
fn triangle_footprint(v: [Vec3; 3], band: Option<Band>, out: &mut Footprints) {
    if !v.iter().all(|p| p.is_finite()) {
        return;
    }
    let ymin = v[0].y.min(v[1].y).min(v[2].y);
    let ymax = v[0].y.max(v[1].y).max(v[2].y);
    let Some(b) = band else {
        out.push_poly(&v.map(xz));
        return;
    };
    if !b.overlaps(ymin, ymax) {
        // A horizontal triangle exactly in the band still has zero thickness: ignore it only
        // when it lies outside the open band.
        if !(ymin == ymax && ymin > b.lo && ymin < b.hi) {
            return;
        }
    }
    if ymin >= b.lo && ymax <= b.hi {
        out.push_poly(&v.map(xz));
        return;
    }
    // Sutherland-Hodgman against y >= lo then y <= hi.
    let mut a = [Vec3::ZERO; 5];
    let mut na = 0;
    clip(&v, &mut a, &mut na, |p| p.y - b.lo);
    let mut c = [Vec3::ZERO; 5];
    let mut nc = 0;
    clip(&a[..na], &mut c, &mut nc, |p| b.hi - p.y);
    if nc == 0 {
        return;
    }
    let mut pts = [Vec2::ZERO; 5];
    for i in 0..nc {
        pts[i] = xz(c[i]);
    }
    out.push_poly(&pts[..nc]);
}

/// Keep the part of a convex polygon where `side(p) >= 0`.
fn clip(input: &[Vec3], out: &mut [Vec3; 5], n: &mut usize, side: impl Fn(Vec3) -> f32) {
    *n = 0;
    let len = input.len();
    for i in 0..len {
        let p = input[i];
        let q = input[(i + 1) % len];
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 && *n < 5 {
            out[*n] = p;
            *n += 1;
        }
        if (sp >= 0.0) != (sq >= 0.0) && *n < 5 {
            let t = sp / (sp - sq);
            out[*n] = p + (q - p) * t;
            *n += 1;
        }
    }
}

/// Boolean grid being painted.
struct Canvas {
    width: u32,
    height: u32,
    origin: DVec2,
    inv_res: f64,
    cells: Vec<bool>,
}

/// `floor` without a libm call (values here are far inside the i64 range).
#[inline]
fn ffloor(x: f64) -> i64 {
    let t = x as i64;
    if (t as f64) > x {
        t - 1
    } else {
        t
    }
}

/// Inclusive cell range covered by `[lo, hi]` (cell units), or None when outside `[0, n)`.
#[inline]
fn cover(lo: f64, hi: f64, n: u32) -> Option<(u32, u32)> {
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let (mut a, mut b) = (ffloor(lo + EPS), ffloor(hi - EPS));
    if b < a {
        // Thinner than 2*EPS (e.g. a vertical wall triangle seen from above): its own cell.
        let m = ffloor(0.5 * (lo + hi));
        a = m;
        b = m;
    }
    if b < 0 || a >= n as i64 {
        return None;
    }
    Some((a.max(0) as u32, b.min(n as i64 - 1) as u32))
}

impl Canvas {
    fn fill_row(&mut self, row: u32, c0: u32, c1: u32) {
        let base = row as usize * self.width as usize;
        self.cells[base + c0 as usize..=base + c1 as usize].fill(true);
    }

    fn to_cell_units(&self, p: Vec2) -> DVec2 {
        (p.as_dvec2() - self.origin) * self.inv_res
    }

    fn poly(&mut self, world: &[Vec2]) {
        let mut pts = [DVec2::ZERO; 8];
        let n = world.len().min(8);
        for i in 0..n {
            pts[i] = self.to_cell_units(world[i]);
        }
        let pts = &pts[..n];
        let (mut umin, mut umax, mut vmin, mut vmax) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in pts {
            umin = umin.min(p.x);
            umax = umax.max(p.x);
            vmin = vmin.min(p.y);
            vmax = vmax.max(p.y);
        }
        let Some((r0, r1)) = cover(vmin, vmax, self.height) else {
            return;
        };
        let Some((c0, c1)) = cover(umin, umax, self.width) else {
            return;
        };
        if r0 == r1 || c0 == c1 {
            // Bounding box is exact when one side spans a single cell.
            for r in r0..=r1 {
                self.fill_row(r, c0, c1);
            }
            return;
        }
        for r in r0..=r1 {
            // The strip of this row, widened so that a degenerate polygon still hits it.
            let s0 = (r as f64).max(vmin);
            let s1 = (r as f64 + 1.0).min(vmax);
            let (s0, s1) = if s1 < s0 { (s1, s0) } else { (s0, s1) };
            let (mut lo, mut hi) = (f64::MAX, f64::MIN);
            for i in 0..n {
                let a = pts[i];
                let b = pts[(i + 1) % n];
                let dv = b.y - a.y;
                if dv.abs() < 1e-12 {
                    if a.y >= s0 - EPS && a.y <= s1 + EPS {
                        lo = lo.min(a.x.min(b.x));
                        hi = hi.max(a.x.max(b.x));
                    }
                    continue;
                }
                let ta = (s0 - a.y) / dv;
                let tb = (s1 - a.y) / dv;
                let t0 = ta.min(tb).max(0.0);
                let t1 = ta.max(tb).min(1.0);
                if t0 <= t1 {
                    let x0 = a.x + (b.x - a.x) * t0;
                    let x1 = a.x + (b.x - a.x) * t1;
                    lo = lo.min(x0.min(x1));
                    hi = hi.max(x0.max(x1));
                }
            }
            if lo > hi {
                continue;
            }
            if let Some((a, b)) = cover(lo, hi, self.width) {
                self.fill_row(r, a, b);
            }
        }
    }

    fn disc(&mut self, center: Vec2, radius: f32) {
        let c = self.to_cell_units(center);
        let r = radius as f64 * self.inv_res;
        let Some((r0, r1)) = cover(c.y - r, c.y + r, self.height) else {
            return;
        };
        for row in r0..=r1 {
            let (s0, s1) = (row as f64, row as f64 + 1.0);
            let dv = if c.y < s0 {
                s0 - c.y
            } else if c.y > s1 {
                c.y - s1
            } else {
                0.0
            };
            let hw2 = r * r - dv * dv;
            if hw2 < 0.0 {
                continue;
            }
            let hw = hw2.sqrt();
            if let Some((a, b)) = cover(c.x - hw, c.x + hw, self.width) {
                self.fill_row(row, a, b);
            }
        }
    }

    fn paint(&mut self, f: &Footprints) {
        for item in &f.items {
            match *item {
                Footprint::Poly { start, len } => {
                    let s = start as usize;
                    self.poly(&f.points[s..s + len as usize]);
                }
                Footprint::Disc { center, radius } => self.disc(center, radius),
            }
        }
    }
}

/// Cells that are neither occupied nor on the floor and connect (4-neighbours) to the map border
/// through such cells: the outside of the home. Floor gaps enclosed by walls and floor (e.g.
/// between two room slabs under a doorway) are not outside.
fn outside_floor(occupied: &[bool], floor: &[bool], w: usize, h: usize) -> Vec<bool> {
    let open = |i: usize| !occupied[i] && !floor[i];
    let mut out = vec![false; w * h];
    let mut stack: Vec<usize> = Vec::new();
    let seed = |i: usize, out: &mut Vec<bool>, stack: &mut Vec<usize>| {
        if open(i) && !out[i] {
            out[i] = true;
            stack.push(i);
        }
    };
    for x in 0..w {
        seed(x, &mut out, &mut stack);
        seed((h - 1) * w + x, &mut out, &mut stack);
    }
    for y in 0..h {
        seed(y * w, &mut out, &mut stack);
        seed(y * w + w - 1, &mut out, &mut stack);
    }
    while let Some(i) = stack.pop() {
        let (x, y) = (i % w, i / w);
        if x > 0 {
            seed(i - 1, &mut out, &mut stack);
        }
        if x + 1 < w {
            seed(i + 1, &mut out, &mut stack);
        }
        if y > 0 {
            seed(i - w, &mut out, &mut stack);
        }
        if y + 1 < h {
            seed(i + w, &mut out, &mut stack);
        }
    }
    out
}

/// Raw occupancy map of a scene (see the module docs for the rules), and which of its cells lie
/// under a ceiling (None when the scene has no ceiling).
pub(super) fn rasterize_scene(
    scene: &Scene,
    cfg: &OccupancyConfig,
) -> Result<(GridMap, Option<Vec<bool>>)> {
    rasterize(scene, cfg, None)
}

/// Raw occupancy map of one level of a multi-level scene (see `build_level_maps`): the band
/// from that level's floor, only the floors and ceilings of that level, and the footprints of
/// the stairs that reach it occupied.
pub(super) fn rasterize_level(
    scene: &Scene,
    cfg: &OccupancyConfig,
    level: LevelId,
) -> Result<(GridMap, Option<Vec<bool>>)> {
    rasterize(scene, cfg, Some(level))
}

/// Whether a floor or ceiling object belongs to `level` (always for single-level maps): a floor
/// by the height of its top, a ceiling by the height just below its underside.
fn on_level(scene: &Scene, o: &SceneObject, level: Option<LevelId>) -> bool {
    let Some(level) = level else {
        return true;
    };
    let y = if o.class == SemanticClass::Ceiling {
        o.bbox.min[1] - 0.5
    } else {
        o.bbox.max[1]
    };
    scene.level_at_height(y) == level
}

fn rasterize(
    scene: &Scene,
    cfg: &OccupancyConfig,
    level: Option<LevelId>,
) -> Result<(GridMap, Option<Vec<bool>>)> {
    let floor_height = match level {
        None => scene.floor_height,
        Some(l) => scene.level_height(l).ok_or_else(|| {
            EnvError::invalid("level", l, format!("scene {} has no such level", scene.id))
        })?,
    };
    if !floor_height.is_finite() {
        return Err(EnvError::InvalidScene {
            scene: scene.id.clone(),
            message: format!("floor_height = {floor_height} is not finite"),
        });
    }
    let band = Band {
        lo: floor_height + cfg.floor_clearance,
        hi: floor_height + cfg.agent_height,
    };
    let mut obstacles = Footprints::new();
    let mut floors = Footprints::new();
    let mut ceilings = Footprints::new();
    if let Some(l) = level {
        // A flight is a solid block on its lower level and a hole in the floor of its upper one.
        for s in scene
            .storeys
            .stairs
            .iter()
            .filter(|s| s.levels.contains(&l))
        {
            let pts: Vec<Vec2> = s.footprint.iter().map(|p| Vec2::new(p[0], p[1])).collect();
            obstacles.push_poly(&pts);
        }
    }
    for o in &scene.objects {
        if matches!(o.class, SemanticClass::Ceiling | SemanticClass::Floor)
            && !on_level(scene, o, level)
        {
            continue;
        }
        match o.class {
            SemanticClass::Ceiling => {
                for part in &o.parts {
                    part_footprint(
                        &part.shape,
                        &o.pose.mul(&part.transform),
                        None,
                        &mut ceilings,
                    )
                }
            }
            SemanticClass::Floor => {
                for part in &o.parts {
                    part_footprint(&part.shape, &o.pose.mul(&part.transform), None, &mut floors)
                }
            }
            _ => {
                for part in &o.parts {
                    part_footprint(
                        &part.shape,
                        &o.pose.mul(&part.transform),
                        Some(band),
                        &mut obstacles,
                    )
                }
            }
        }
    }
    if obstacles.is_empty() && floors.is_empty() {
        return Err(EnvError::InvalidScene {
            scene: scene.id.clone(),
            message: "no floor and no geometry in the agent's height band: nothing to map".into(),
        });
    }
    let lo = obstacles.min.min(floors.min);
    let hi = obstacles.max.max(floors.max);
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(EnvError::InvalidScene {
            scene: scene.id.clone(),
            message: "geometry has non-finite coordinates".into(),
        });
    }
    let res = cfg.resolution as f64;
    let pad = cfg.padding as f64;
    // Snap the origin to a multiple of the resolution so grid-aligned walls align with cells.
    let ox = ((lo.x as f64 - pad) / res).floor() * res;
    let oz = ((lo.y as f64 - pad) / res).floor() * res;
    let w = (((hi.x as f64 + pad) - ox) / res).ceil().max(1.0);
    let h = (((hi.y as f64 + pad) - oz) / res).ceil().max(1.0);
    if w * h > super::MAX_CELLS as f64 {
        return Err(EnvError::invalid(
            "resolution",
            cfg.resolution,
            format!(
                "scene {} would need {w}x{h} cells (more than {}); use a coarser resolution",
                scene.id,
                super::MAX_CELLS
            ),
        ));
    }
    let (w, h) = (w as u32, h as u32);
    let mut canvas = Canvas {
        width: w,
        height: h,
        origin: DVec2::new(ox, oz),
        inv_res: 1.0 / res,
        cells: vec![false; w as usize * h as usize],
    };
    canvas.paint(&obstacles);
    let occupied = std::mem::take(&mut canvas.cells);
    let outside = if floors.is_empty() {
        Vec::new()
    } else {
        canvas.cells = vec![false; w as usize * h as usize];
        canvas.paint(&floors);
        outside_floor(&occupied, &canvas.cells, w as usize, h as usize)
    };
    let covered = (!ceilings.is_empty()).then(|| {
        canvas.cells = vec![false; w as usize * h as usize];
        canvas.paint(&ceilings);
        std::mem::take(&mut canvas.cells)
    });
    let cells = occupied
        .iter()
        .enumerate()
        .map(|(i, &occ)| {
            if occ {
                CellState::Occupied
            } else if outside.get(i).copied().unwrap_or(false) {
                CellState::Unknown
            } else {
                CellState::Free
            }
        })
        .collect();
    let map = GridMap::from_cells(w, h, cfg.resolution, Vec2::new(ox as f32, oz as f32), cells)?;
    Ok((map, covered))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn canvas(w: u32, h: u32) -> Canvas {
        Canvas {
            width: w,
            height: h,
            origin: DVec2::ZERO,
            inv_res: 1.0,
            cells: vec![false; (w * h) as usize],
        }
    }

    fn count(c: &Canvas) -> usize {
        c.cells.iter().filter(|&&b| b).count()
    }

    #[test]
    fn aligned_square_covers_exact_cells() {
        let mut c = canvas(10, 10);
        c.poly(&[
            Vec2::new(2.0, 3.0),
            Vec2::new(5.0, 3.0),
            Vec2::new(5.0, 5.0),
            Vec2::new(2.0, 5.0),
        ]);
        assert_eq!(count(&c), 6);
        assert!(c.cells[3 * 10 + 2] && c.cells[4 * 10 + 4] && !c.cells[5 * 10 + 2]);
    }

    #[test]
    fn thin_segment_marks_cells_and_diagonal_is_conservative() {
        let mut c = canvas(10, 10);
        // A vertical wall triangle seen from above: a segment along z at x = 3.5.
        c.poly(&[
            Vec2::new(3.5, 1.2),
            Vec2::new(3.5, 6.7),
            Vec2::new(3.5, 1.2),
        ]);
        assert_eq!(count(&c), 6);
        let mut d = canvas(10, 10);
        d.poly(&[
            Vec2::new(0.5, 0.5),
            Vec2::new(4.5, 2.5),
            Vec2::new(0.5, 0.5),
        ]);
        // Every cell the segment crosses is marked.
        for k in 0..=40 {
            let p = Vec2::new(0.5, 0.5) + Vec2::new(4.0, 2.0) * (k as f32 / 40.0);
            assert!(d.cells[p.y as usize * 10 + p.x as usize], "{p}");
        }
    }

    #[test]
    fn disc_is_conservative() {
        let mut c = canvas(20, 20);
        c.disc(Vec2::new(10.0, 10.0), 3.0);
        for row in 0..20 {
            for col in 0..20 {
                // Closest point of the cell to the centre.
                let px = (10.0f32).clamp(col as f32, col as f32 + 1.0);
                let pz = (10.0f32).clamp(row as f32, row as f32 + 1.0);
                let inside = Vec2::new(px, pz).distance(Vec2::splat(10.0)) < 3.0 - 1e-3;
                if inside {
                    assert!(c.cells[row * 20 + col], "{col},{row}");
                }
            }
        }
    }
}
