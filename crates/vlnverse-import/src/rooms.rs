//! Rooms of imported scenes: segmentation of the floor plan by walls and narrow passages, or a
//! room annotation file; doors between rooms; the room of each object.
//!
//! # Segmentation
//! 1. An occupancy map of the **structure only** (walls, door frames, windows; floors bound the
//!    home) is built with [`build_maps`], so furniture never splits a room.
//! 2. Exact distance transform of the free cells to the nearest wall (or outside) cell.
//! 3. Seeds: plateaus of regional maxima of that distance (the middle of each open space).
//! 4. Watershed: seeds grow over all free cells in order of decreasing wall distance, so two
//!    regions meet at the narrowest place between them (a door, a narrow passage).
//! 5. Merging: neighbouring regions whose shared opening is not a constriction (its clear width
//!    at least `door_ratio` times the narrower region's width) become one (open plan); regions
//!    nobody can stand in (narrower than the agent) are dropped; regions smaller than
//!    `min_room_area` join the neighbour they share the longest border with. Regions larger
//!    than `split_area` that hold anchors of several room types (bed; sofa/TV/coffee table;
//!    kitchen appliances; bathroom fixtures; fitness equipment names) are split between them,
//!    each cell going to the geodesically nearest anchor group (open-plan living room, kitchen
//!    and gym become three rooms joined by open-plan openings).
//! 6. Polygons: the outline of each region's cells (largest part, holes filled), traced along
//!    cell edges (axis-aligned, collinear points removed), counter-clockwise seen from above.
//! 7. Doors: each connected stretch of border between two regions; its position is the border
//!    cell farthest from walls, its width the clear width there (twice that distance), its normal
//!    points from the first room to the second; openings of 1.2 m or more are `open_plan`.
//! 8. Room types from what stands inside (a bed -> bedroom, a fridge or stove -> kitchen, a
//!    sofa or TV -> living room, fitness equipment names -> gym, ...), else `hallway` for
//!    small narrow regions and `room` otherwise.
//!
//! # Annotation file
//! ```toml
//! [[room]]
//! name = "master_bedroom"   # optional; default <kind>_<n>
//! kind = "bedroom"          # a RoomType name
//! polygon = [[-9.0, -5.0], [-3.0, -5.0], [-3.0, 0.5], [-9.0, 0.5]]  # [x, z], metres
//! ```
//! Coordinates are those of the imported scene (after axis, unit and floor conversion). Doors
//! are then found where annotated rooms meet in the free space, as above.

use glam::Vec2;
use serde::Deserialize;
use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};
use std::path::Path;
use vlnverse_env::occupancy::{
    build_maps, squared_distance_transform, CellState, GridMap, OccupancyConfig,
};
use vlnverse_env::{Door, EnvError, Result, Room, RoomId, RoomType, Scene, SemanticClass};

/// Room segmentation settings.
#[derive(Clone, Debug, PartialEq)]
pub struct RoomParams {
    /// Two regions stay separate rooms when the clear width of the opening between them is
    /// less than this share of the narrower region's width (both measured as twice the largest
    /// distance to a wall); wider openings merge them (open plan).
    pub door_ratio: f32,
    /// Regions at least this large (m^2) holding anchors of several room types (bed, sofa/TV,
    /// kitchen appliances, bathroom fixtures, fitness equipment) are split between them.
    pub split_area: f32,
    /// Smallest room (m^2); smaller regions join a neighbour.
    pub min_room_area: f32,
    /// Openings at least this wide (m) are marked `open_plan`.
    pub open_plan_width: f32,
    /// How far (m) from a region an object's centre may be and still count as in it.
    pub object_snap: f32,
}

/// Largest room annotation coordinate (m, either sign).
pub const MAX_COORD: f32 = 10_000.0;

impl RoomParams {
    /// Check every value: `door_ratio` in (0, 1], `split_area` in [0, 100000] m^2,
    /// `min_room_area` in [0, 10000] m^2, `open_plan_width` and `object_snap` in [0, 100] m.
    /// The error names the field (`room_params.NAME`) and the value.
    pub fn validate(&self) -> Result<()> {
        let fields = [
            ("door_ratio", self.door_ratio, 1e-6, 1.0),
            ("split_area", self.split_area, 0.0, 100_000.0),
            ("min_room_area", self.min_room_area, 0.0, 10_000.0),
            ("open_plan_width", self.open_plan_width, 0.0, 100.0),
            ("object_snap", self.object_snap, 0.0, 100.0),
        ];
        for (name, v, lo, hi) in fields {
            if !(v.is_finite() && (lo..=hi).contains(&v)) {
                return Err(EnvError::invalid(
                    format!("room_params.{name}"),
                    v,
                    if lo > 0.0 {
                        format!("must be in (0, {hi}]")
                    } else {
                        format!("must be in [{lo}, {hi}]")
                    },
                ));
            }
        }
        Ok(())
    }
}

impl Default for RoomParams {
    fn default() -> Self {
        RoomParams {
            door_ratio: 0.6,
            split_area: 40.0,
            min_room_area: 2.5,
            open_plan_width: 1.2,
            object_snap: 1.0,
        }
    }
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct AnnotatedRoomFile {
    name: Option<String>,
    kind: String,
    polygon: Vec<[f32; 2]>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct AnnotationFile {
    #[serde(default, rename = "room")]
    rooms: Vec<AnnotatedRoomFile>,
}

/// Rooms given by hand (see the [module docs](self) for the file format).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RoomAnnotation {
    /// Rooms with ids `0..n` in file order.
    pub rooms: Vec<Room>,
}

impl RoomAnnotation {
    /// Parse TOML text; `path` is used in error messages.
    pub fn from_toml(text: &str, path: &Path) -> Result<Self> {
        let f: AnnotationFile =
            toml::from_str(text).map_err(|e| EnvError::parse(path, e.to_string()))?;
        let mut rooms = Vec::new();
        let mut per_kind: BTreeMap<RoomType, u32> = BTreeMap::new();
        for (i, r) in f.rooms.into_iter().enumerate() {
            let kind = RoomType::from_name(&r.kind).ok_or_else(|| {
                EnvError::invalid(format!("room[{i}].kind"), &r.kind, "not a room type name")
                    .in_file(path)
            })?;
            let far = |v: &f32| !(v.is_finite() && v.abs() <= MAX_COORD);
            if r.polygon.len() < 3
                || r.polygon.len() > 10_000
                || r.polygon.iter().flatten().any(far)
            {
                return Err(EnvError::invalid(
                    format!("room[{i}].polygon"),
                    format!("{:?}", r.polygon),
                    format!("needs 3 to 10000 [x, z] points, each coordinate in [-{MAX_COORD}, {MAX_COORD}] m"),
                )
                .in_file(path));
            }
            let n = per_kind.entry(kind).or_insert(0);
            *n += 1;
            let mut room = Room {
                id: i as RoomId,
                kind,
                name: r.name.unwrap_or_else(|| format!("{}_{}", kind.name(), n)),
                polygon: r.polygon,
            };
            make_ccw_from_above(&mut room.polygon);
            rooms.push(room);
        }
        Ok(RoomAnnotation { rooms })
    }

    /// Load an annotation file.
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| EnvError::io(path, e))?;
        Self::from_toml(&text, path)
    }
}

/// Signed area in the (x, z) plane; negative means counter-clockwise seen from above (+Y), where
/// -Z points up the screen.
fn shoelace_xz(p: &[[f32; 2]]) -> f32 {
    let n = p.len();
    (0..n)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f32>()
        * 0.5
}

fn make_ccw_from_above(p: &mut [[f32; 2]]) {
    if shoelace_xz(p) > 0.0 {
        p.reverse();
    }
}

/// A label per cell of a grid (0 = none), with the wall distance of every cell.
struct Labels {
    w: usize,
    h: usize,
    res: f32,
    origin: Vec2,
    label: Vec<u32>,
    /// Distance (m) from the cell centre to the nearest blocked cell centre.
    dist: Vec<f32>,
    free: Vec<bool>,
}

impl Labels {
    fn center(&self, i: usize) -> Vec2 {
        let (c, r) = (i % self.w, i / self.w);
        self.origin + Vec2::new((c as f32 + 0.5) * self.res, (r as f32 + 0.5) * self.res)
    }

    #[allow(dead_code)]
    fn cell(&self, p: Vec2) -> Option<usize> {
        let u = (p - self.origin) / self.res;
        if !(u.x >= 0.0 && u.y >= 0.0) {
            return None;
        }
        let (c, r) = (u.x as usize, u.y as usize);
        (c < self.w && r < self.h).then_some(r * self.w + c)
    }

    fn neighbours(&self, i: usize) -> impl Iterator<Item = usize> {
        grid_neighbours(i, self.w, self.h)
    }

    /// The cell with label `l` nearest to `p` within `max` metres.
    fn label_cell_near(&self, p: Vec2, max: f32, l: u32) -> Option<usize> {
        self.cell_near(p, max, |i| self.label[i] == l)
    }

    /// Label of the cell at `p`, or of the nearest labelled cell within `max` metres.
    fn label_near(&self, p: Vec2, max: f32) -> Option<u32> {
        self.cell_near(p, max, |i| self.label[i] != 0)
            .map(|i| self.label[i])
    }

    /// The cell accepted by `keep` nearest to `p` within `max` metres (at least one cell);
    /// ties go to the first in row-major order of the search window.
    fn cell_near(&self, p: Vec2, max: f32, keep: impl Fn(usize) -> bool) -> Option<usize> {
        let u = (p - self.origin) / self.res;
        let reach = (max / self.res).ceil() as i64;
        let (c0, r0) = (u.x.floor() as i64, u.y.floor() as i64);
        let mut best: Option<(f32, usize)> = None;
        for dr in -reach..=reach {
            for dc in -reach..=reach {
                let (c, r) = (c0 + dc, r0 + dr);
                if c < 0 || r < 0 || c >= self.w as i64 || r >= self.h as i64 {
                    continue;
                }
                let i = r as usize * self.w + c as usize;
                if !keep(i) {
                    continue;
                }
                let d = self.center(i).distance(p);
                if d <= max.max(self.res) && best.is_none_or(|(bd, _)| d < bd) {
                    best = Some((d, i));
                }
            }
        }
        best.map(|(_, i)| i)
    }
}

/// The 4-neighbours of cell `i` of a row-major `w` x `h` grid.
fn grid_neighbours(i: usize, w: usize, h: usize) -> impl Iterator<Item = usize> {
    let (c, r) = (i % w, i / w);
    [
        (c > 0).then(|| i - 1),
        (c + 1 < w).then(|| i + 1),
        (r > 0).then(|| i - w),
        (r + 1 < h).then(|| i + w),
    ]
    .into_iter()
    .flatten()
}

/// Free cells of the structure-only map and their distance to walls / outside.
fn structure_grid(scene: &Scene, occ: &OccupancyConfig) -> Result<Labels> {
    let mut s = scene.clone();
    s.objects.retain(|o| {
        matches!(
            o.class,
            SemanticClass::Wall
                | SemanticClass::DoorFrame
                | SemanticClass::Window
                | SemanticClass::Floor
        )
    });
    let has_floor = s.objects.iter().any(|o| o.class == SemanticClass::Floor);
    if s.objects.is_empty() {
        // Nothing bounds the home: use the whole scene footprint.
        s.objects = scene.objects.clone();
    }
    let map: GridMap = build_maps(&s, occ)?.occupancy;
    let (w, h) = (map.width as usize, map.height as usize);
    let cells = map.cells();
    let mut free: Vec<bool> = cells.iter().map(|c| *c == CellState::Free).collect();
    if !has_floor {
        // Without a floor the padding around the scene is free too: drop what the map border
        // reaches, unless that is everything (a scene without enclosing walls).
        let mut outside = vec![false; w * h];
        let mut stack: Vec<usize> = (0..w * h)
            .filter(|&i| {
                let (c, r) = (i % w, i / w);
                free[i] && (c == 0 || r == 0 || c + 1 == w || r + 1 == h)
            })
            .collect();
        for &i in &stack {
            outside[i] = true;
        }
        while let Some(i) = stack.pop() {
            for j in grid_neighbours(i, w, h) {
                if free[j] && !outside[j] {
                    outside[j] = true;
                    stack.push(j);
                }
            }
        }
        let inside = free
            .iter()
            .zip(&outside)
            .filter(|(f, o)| **f && !**o)
            .count();
        if inside as f32 * map.resolution * map.resolution > 2.0 {
            for (f, o) in free.iter_mut().zip(&outside) {
                *f &= !o;
            }
        }
    }
    let d2 = squared_distance_transform(map.width, map.height, |i| !free[i]);
    let dist = d2
        .iter()
        .map(|d| (d.sqrt() as f32) * map.resolution)
        .collect();
    Ok(Labels {
        w,
        h,
        res: map.resolution,
        origin: map.origin,
        label: vec![0; w * h],
        dist,
        free,
    })
}

/// Seeds: plateaus (8-connected) of regional maxima of the wall distance.
fn seed_maxima(g: &mut Labels) {
    let (w, h) = (g.w as i64, g.h as i64);
    let is_max = |i: usize| {
        if !g.free[i] {
            return false;
        }
        let (c, r) = ((i % g.w) as i64, (i / g.w) as i64);
        for dr in -1..=1 {
            for dc in -1..=1 {
                let (x, y) = (c + dc, r + dr);
                if (dc, dr) != (0, 0) && x >= 0 && y >= 0 && x < w && y < h {
                    let j = y as usize * g.w + x as usize;
                    if g.dist[j] > g.dist[i] + 1e-6 {
                        return false;
                    }
                }
            }
        }
        true
    };
    let maxima: Vec<bool> = (0..g.w * g.h).map(is_max).collect();
    let mut next = 0u32;
    let mut stack = Vec::new();
    for s in 0..g.w * g.h {
        if !maxima[s] || g.label[s] != 0 {
            continue;
        }
        next += 1;
        g.label[s] = next;
        stack.push(s);
        while let Some(i) = stack.pop() {
            let (c, r) = ((i % g.w) as i64, (i / g.w) as i64);
            for dr in -1..=1 {
                for dc in -1..=1 {
                    let (x, y) = (c + dc, r + dr);
                    if x >= 0 && y >= 0 && x < w && y < h {
                        let j = y as usize * g.w + x as usize;
                        if maxima[j] && g.label[j] == 0 {
                            g.label[j] = next;
                            stack.push(j);
                        }
                    }
                }
            }
        }
    }
}

/// Merge neighbouring regions whose shared opening is not a constriction: its clear width
/// (twice the largest wall distance on the border) is at least `ratio` times the width of the
/// narrower region (twice its largest wall distance). Widest openings first.
fn merge_open(g: &mut Labels, ratio: f32) {
    let n = g.label.iter().copied().max().unwrap_or(0) as usize;
    // Union-find over labels.
    let mut parent: Vec<usize> = (0..=n).collect();
    fn find(p: &mut [usize], x: usize) -> usize {
        let mut r = x;
        while p[r] != r {
            r = p[r];
        }
        let mut y = x;
        while p[y] != r {
            let nx = p[y];
            p[y] = r;
            y = nx;
        }
        r
    }
    let mut width = vec![0.0f32; n + 1];
    for i in 0..g.w * g.h {
        let l = g.label[i] as usize;
        if l != 0 {
            width[l] = width[l].max(g.dist[i]);
        }
    }
    // Border clear width per pair: max over border cells of their wall distance.
    let mut border: BTreeMap<(usize, usize), f32> = BTreeMap::new();
    for i in 0..g.w * g.h {
        let a = g.label[i] as usize;
        if a == 0 {
            continue;
        }
        for j in g.neighbours(i) {
            let b = g.label[j] as usize;
            if b != 0 && b != a {
                let e = border.entry((a.min(b), a.max(b))).or_insert(0.0);
                *e = e.max(g.dist[i].min(g.dist[j]));
            }
        }
    }
    loop {
        let mut best: Option<(f32, usize, usize)> = None;
        for (&(a, b), &bw) in &border {
            let r = bw / width[a].min(width[b]).max(1e-6);
            if r >= ratio && best.is_none_or(|(br, _, _)| r > br) {
                best = Some((r, a, b));
            }
        }
        let Some((_, a, b)) = best else { break };
        parent[b] = a;
        width[a] = width[a].max(width[b]);
        let old = std::mem::take(&mut border);
        for ((x, y), bw) in old {
            let (x, y) = (find(&mut parent, x), find(&mut parent, y));
            if x != y {
                let e = border.entry((x.min(y), x.max(y))).or_insert(0.0);
                *e = e.max(bw);
            }
        }
    }
    for l in g.label.iter_mut() {
        if *l != 0 {
            *l = find(&mut parent, *l as usize) as u32;
        }
    }
}

/// Regions nobody can stand in (no cell farther than `radius` from a wall, e.g. the strip
/// between an outer wall and the edge of the floor) are not rooms.
fn drop_thin(g: &mut Labels, radius: f32) {
    let mut width: BTreeMap<u32, f32> = BTreeMap::new();
    for i in 0..g.w * g.h {
        if g.label[i] != 0 {
            let e = width.entry(g.label[i]).or_insert(0.0);
            *e = e.max(g.dist[i]);
        }
    }
    for l in g.label.iter_mut() {
        if *l != 0 && width[l] < radius {
            *l = 0;
        }
    }
}

/// Room type an object anchors, for splitting open-plan regions.
fn anchor_type(o: &vlnverse_env::SceneObject) -> Option<RoomType> {
    use SemanticClass as C;
    match o.class {
        C::Bed => Some(RoomType::Bedroom),
        C::Sofa | C::Tv | C::CoffeeTable => Some(RoomType::LivingRoom),
        C::Fridge | C::Stove | C::Counter | C::KitchenCabinet | C::Dishwasher => {
            Some(RoomType::Kitchen)
        }
        C::Toilet | C::Bathtub | C::Shower => Some(RoomType::Bathroom),
        C::WashingMachine => Some(RoomType::LaundryRoom),
        _ if name_has(o, GYM_WORDS) => Some(RoomType::Gym),
        _ => None,
    }
}

const GYM_WORDS: &[&str] = &["fitness", "dumbbell", "treadmill", "gym", "weights"];

/// Split regions larger than `min_area` that hold anchors of several room types (an open-plan
/// living room, kitchen and gym): every cell goes to the nearest group of anchors (geodesic,
/// inside the region).
fn split_open_plan(g: &mut Labels, scene: &Scene, min_area: f32) {
    let n = g.label.iter().copied().max().unwrap_or(0);
    let mut next = n;
    for l in 1..=n {
        let area = g.label.iter().filter(|&&x| x == l).count() as f32 * g.res * g.res;
        if area < min_area {
            continue;
        }
        let mut groups: BTreeMap<RoomType, Vec<usize>> = BTreeMap::new();
        for o in scene.objects.iter().filter(|o| !o.is_structure()) {
            let Some(t) = anchor_type(o) else { continue };
            let c = o.bbox.center();
            let Some(cell) = g.label_cell_near(Vec2::new(c.x, c.z), 1.0, l) else {
                continue;
            };
            groups.entry(t).or_default().push(cell);
        }
        if groups.len() < 2 {
            continue;
        }
        let mut lab: Vec<u32> = vec![0; g.w * g.h];
        let mut queue = std::collections::VecDeque::new();
        let mut ids = Vec::new();
        for (k, cells) in groups.values().enumerate() {
            let id = if k == 0 { l } else { next + k as u32 };
            ids.push(id);
            for &c in cells {
                if lab[c] == 0 {
                    lab[c] = id;
                    queue.push_back(c);
                }
            }
        }
        next += groups.len() as u32 - 1;
        while let Some(i) = queue.pop_front() {
            let next_cells: Vec<usize> = g.neighbours(i).collect();
            for j in next_cells {
                if g.label[j] == l && lab[j] == 0 {
                    lab[j] = lab[i];
                    queue.push_back(j);
                }
            }
        }
        for (x, &y) in g.label.iter_mut().zip(&lab) {
            if *x == l && y != 0 {
                *x = y;
            }
        }
    }
}

/// Connected components (4-connected) of cells where `member` holds; returns labels 1..=n.
fn components(g: &Labels, member: impl Fn(usize) -> bool) -> (Vec<u32>, Vec<usize>) {
    let mut lab = vec![0u32; g.w * g.h];
    let mut sizes = vec![0usize];
    let mut stack = Vec::new();
    for s in 0..g.w * g.h {
        if lab[s] != 0 || !member(s) {
            continue;
        }
        let id = sizes.len() as u32;
        sizes.push(0);
        lab[s] = id;
        stack.push(s);
        while let Some(i) = stack.pop() {
            sizes[id as usize] += 1;
            for j in g.neighbours(i) {
                if lab[j] == 0 && member(j) {
                    lab[j] = id;
                    stack.push(j);
                }
            }
        }
    }
    (lab, sizes)
}

/// Watershed from the labelled cells over free cells, highest wall distance first.
fn flood(g: &mut Labels) {
    // (distance in 1/1000 cell, Reverse(index)) for a deterministic order.
    let key = |g: &Labels, i: usize| ((g.dist[i] / g.res * 1000.0) as u64, Reverse(i));
    let mut heap = BinaryHeap::new();
    for i in 0..g.w * g.h {
        if g.label[i] != 0 {
            for j in g.neighbours(i) {
                if g.free[j] && g.label[j] == 0 {
                    heap.push((key(g, j), g.label[i], j));
                }
            }
        }
    }
    while let Some((_, l, i)) = heap.pop() {
        if g.label[i] != 0 {
            continue;
        }
        g.label[i] = l;
        let next: Vec<usize> = g.neighbours(i).collect();
        for j in next {
            if g.free[j] && g.label[j] == 0 {
                heap.push((key(g, j), l, j));
            }
        }
    }
}

/// Border lengths (in cell edges) between pairs of labels.
fn borders(g: &Labels) -> BTreeMap<(u32, u32), usize> {
    let mut out = BTreeMap::new();
    for i in 0..g.w * g.h {
        let a = g.label[i];
        if a == 0 {
            continue;
        }
        for j in g.neighbours(i).filter(|&j| j > i) {
            let b = g.label[j];
            if b != 0 && b != a {
                *out.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
    }
    out
}

/// Merge small regions into the neighbour with the longest shared border, then renumber labels
/// 1..=n in order of first cell.
fn merge_small(g: &mut Labels, min_cells: usize) {
    loop {
        let mut sizes: BTreeMap<u32, usize> = BTreeMap::new();
        for &l in &g.label {
            if l != 0 {
                *sizes.entry(l).or_insert(0) += 1;
            }
        }
        let b = borders(g);
        let small = sizes
            .iter()
            .filter(|(_, &s)| s < min_cells)
            .min_by_key(|(l, s)| (**s, **l))
            .map(|(l, _)| *l);
        let Some(l) = small else { break };
        let target = b
            .iter()
            .filter(|((a, c), _)| *a == l || *c == l)
            .max_by_key(|((a, c), n)| (**n, Reverse((*a).max(*c))))
            .map(|((a, c), _)| if *a == l { *c } else { *a });
        let to = target.unwrap_or(0);
        if to == 0 && sizes.len() == 1 {
            break;
        }
        for x in g.label.iter_mut() {
            if *x == l {
                *x = to;
            }
        }
    }
    let mut map: BTreeMap<u32, u32> = BTreeMap::new();
    for x in g.label.iter_mut() {
        if *x != 0 {
            let n = map.len() as u32 + 1;
            *x = *map.entry(*x).or_insert(n);
        }
    }
}

/// Outline of the largest 4-connected part of a label's cells, holes filled, as `[x, z]`
/// points counter-clockwise seen from above.
fn outline(g: &Labels, l: u32) -> Vec<[f32; 2]> {
    let (parts, sizes) = components(g, |i| g.label[i] == l);
    let Some((best, _)) = sizes.iter().enumerate().skip(1).max_by_key(|(_, s)| **s) else {
        return Vec::new();
    };
    let best = best as u32;
    // Fill holes: cells not reachable from the grid border through non-member cells.
    let member = |i: usize| parts[i] == best;
    let (outside, _) = {
        let (lab, _) = components(g, |i| !member(i));
        let mut border_labels = std::collections::BTreeSet::new();
        for (i, &x) in lab.iter().enumerate() {
            let (c, r) = (i % g.w, i / g.w);
            if (c == 0 || r == 0 || c + 1 == g.w || r + 1 == g.h) && x != 0 {
                border_labels.insert(x);
            }
        }
        (
            lab.iter()
                .map(|x| *x != 0 && border_labels.contains(x))
                .collect::<Vec<bool>>(),
            (),
        )
    };
    let inside = |c: i64, r: i64| {
        if c < 0 || r < 0 || c >= g.w as i64 || r >= g.h as i64 {
            return false;
        }
        !outside[r as usize * g.w + c as usize]
    };
    // Directed boundary edges with the region on the left, in (col, row) corner coordinates.
    let mut out_edges: BTreeMap<(i64, i64), Vec<(i64, i64)>> = BTreeMap::new();
    let mut n_edges = 0usize;
    for r in 0..g.h as i64 {
        for c in 0..g.w as i64 {
            if !inside(c, r) {
                continue;
            }
            let mut e = |a: (i64, i64), b: (i64, i64)| {
                out_edges.entry(a).or_default().push(b);
                n_edges += 1;
            };
            if !inside(c, r - 1) {
                e((c, r), (c + 1, r));
            }
            if !inside(c + 1, r) {
                e((c + 1, r), (c + 1, r + 1));
            }
            if !inside(c, r + 1) {
                e((c + 1, r + 1), (c, r + 1));
            }
            if !inside(c - 1, r) {
                e((c, r + 1), (c, r));
            }
        }
    }
    let Some((&start, _)) = out_edges.iter().next() else {
        return Vec::new();
    };
    let mut pts = vec![start];
    let mut cur = start;
    let mut dir = (1i64, 0i64);
    for _ in 0..=n_edges {
        let Some(outs) = out_edges.get_mut(&cur) else {
            break;
        };
        if outs.is_empty() {
            break;
        }
        // At a pinch point prefer the right turn, which keeps to the outside of the region.
        let k = if outs.len() == 1 {
            0
        } else {
            let right = (dir.1, -dir.0);
            outs.iter()
                .position(|&(x, y)| (x - cur.0, y - cur.1) == right)
                .unwrap_or(0)
        };
        let next = outs.swap_remove(k);
        dir = (next.0 - cur.0, next.1 - cur.1);
        cur = next;
        if cur == start {
            break;
        }
        pts.push(cur);
    }
    // Remove collinear points.
    let n = pts.len();
    let mut simple = Vec::with_capacity(n);
    for i in 0..n {
        let (a, b, c) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
        let cross = (b.0 - a.0) * (c.1 - b.1) - (b.1 - a.1) * (c.0 - b.0);
        if cross != 0 {
            simple.push(b);
        }
    }
    let mut poly: Vec<[f32; 2]> = simple
        .into_iter()
        .map(|(c, r)| [g.origin.x + c as f32 * g.res, g.origin.y + r as f32 * g.res])
        .collect();
    make_ccw_from_above(&mut poly);
    poly
}

/// Doors: each connected stretch of border between two labels (labels are room index + 1).
fn find_doors(g: &Labels, room_ids: &[RoomId], floor: f32, open_plan_width: f32) -> Vec<Door> {
    // Border cell pairs (i in label a, j in label b, a < b): clear half-width there (the
    // smaller wall distance of the two) and the direction a -> b.
    let mut pairs: BTreeMap<(u32, u32), Vec<(usize, usize)>> = BTreeMap::new();
    for i in 0..g.w * g.h {
        let a = g.label[i];
        if a == 0 {
            continue;
        }
        for j in g.neighbours(i) {
            let b = g.label[j];
            if b != 0 && a < b {
                pairs.entry((a, b)).or_default().push((i, j));
            }
        }
    }
    let mut doors = Vec::new();
    for ((a, b), list) in pairs {
        let by_cell: BTreeMap<usize, Vec<usize>> =
            list.iter().fold(BTreeMap::new(), |mut m, &(i, j)| {
                m.entry(i).or_insert_with(Vec::new).push(j);
                m
            });
        // Cluster the a-side border cells 8-connected: one opening per cluster.
        let mut seen = std::collections::BTreeSet::new();
        for &s in by_cell.keys() {
            if !seen.insert(s) {
                continue;
            }
            let mut stack = vec![s];
            let mut cluster = Vec::new();
            while let Some(i) = stack.pop() {
                cluster.push(i);
                let (c, r) = ((i % g.w) as i64, (i / g.w) as i64);
                for dr in -1..=1 {
                    for dc in -1..=1 {
                        let (x, y) = (c + dc, r + dr);
                        if x < 0 || y < 0 || x >= g.w as i64 || y >= g.h as i64 {
                            continue;
                        }
                        let j = y as usize * g.w + x as usize;
                        if by_cell.contains_key(&j) && seen.insert(j) {
                            stack.push(j);
                        }
                    }
                }
            }
            if cluster.len() < 2 {
                continue;
            }
            cluster.sort_unstable();
            let mut best: Option<(f32, usize, usize)> = None;
            let mut normal = Vec2::ZERO;
            for &i in &cluster {
                for &j in &by_cell[&i] {
                    normal += (g.center(j) - g.center(i)).normalize_or_zero();
                    let d = g.dist[i].min(g.dist[j]);
                    if best.is_none_or(|(bd, _, _)| d > bd) {
                        best = Some((d, i, j));
                    }
                }
            }
            let Some((d, i, j)) = best else { continue };
            let normal = normal.normalize_or_zero();
            let p = (g.center(i) + g.center(j)) * 0.5;
            // Wall distances are between cell centres: the clear gap is one cell less.
            let width = (2.0 * d - g.res).max(g.res);
            doors.push(Door {
                id: doors.len() as u32,
                position: [p.x, floor, p.y],
                width,
                normal: [normal.x, normal.y],
                rooms: [room_ids[a as usize - 1], room_ids[b as usize - 1]],
                open_plan: width >= open_plan_width,
                state: None,
                leaf: None,
                second_leaf: None,
                kind: Default::default(),
            });
        }
    }
    doors
}

/// Give each non-structure object the room its bounding-box centre is in (or the nearest room
/// region within `object_snap`).
fn assign_objects(scene: &mut Scene, g: &Labels, room_ids: &[RoomId], snap: f32) {
    for o in scene.objects.iter_mut() {
        if o.is_structure() {
            o.room = None;
            continue;
        }
        let c = o.bbox.center();
        let p = Vec2::new(c.x, c.z);
        o.room = g.label_near(p, snap).map(|l| room_ids[l as usize - 1]);
    }
}

fn name_has(o: &vlnverse_env::SceneObject, words: &[&str]) -> bool {
    let n = o.name.to_ascii_lowercase();
    words.iter().any(|w| n.contains(w))
}

/// Room type from the objects inside.
fn classify_room(scene: &Scene, room: RoomId, area: f32, polygon: &[[f32; 2]]) -> RoomType {
    use SemanticClass as C;
    let mut score: BTreeMap<RoomType, f32> = BTreeMap::new();
    for o in scene.objects.iter().filter(|o| o.room == Some(room)) {
        let (t, s) = match o.class {
            C::Bed => (RoomType::Bedroom, 3.0),
            C::Nightstand | C::Wardrobe | C::Dresser => (RoomType::Bedroom, 1.0),
            C::Toilet | C::Bathtub | C::Shower => (RoomType::Bathroom, 3.0),
            C::Fridge | C::Stove | C::Dishwasher => (RoomType::Kitchen, 3.0),
            C::Counter | C::KitchenCabinet | C::Microwave | C::Toaster | C::Kettle => {
                (RoomType::Kitchen, 1.5)
            }
            C::Sofa => (RoomType::LivingRoom, 3.0),
            C::Tv | C::TvStand | C::CoffeeTable | C::Armchair => (RoomType::LivingRoom, 1.0),
            C::DiningTable => (RoomType::DiningRoom, 1.5),
            C::Desk | C::OfficeChair => (RoomType::Office, 1.5),
            C::WashingMachine => (RoomType::LaundryRoom, 3.0),
            _ if name_has(o, GYM_WORDS) => (RoomType::Gym, 3.0),
            _ => continue,
        };
        *score.entry(t).or_insert(0.0) += s;
    }
    if let Some((t, _)) = score
        .iter()
        .max_by(|a, b| a.1.total_cmp(b.1).then(b.0.cmp(a.0)))
    {
        return *t;
    }
    let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
    for p in polygon {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let (a, b) = (hi[0] - lo[0], hi[1] - lo[1]);
    if area < 8.0 && a.min(b) < 1.6 {
        RoomType::Hallway
    } else {
        RoomType::Room
    }
}

/// Segment rooms (see the [module docs](self)) and fill `scene.rooms`, `scene.doors` and the
/// objects' `room`.
pub fn segment_into(scene: &mut Scene, occ: &OccupancyConfig, params: &RoomParams) -> Result<()> {
    let mut g = structure_grid(scene, occ)?;
    let cell_area = g.res * g.res;
    seed_maxima(&mut g);
    if g.label.iter().all(|&l| l == 0) {
        // No free space at all: one room over everything the map covers.
        for (l, f) in g.label.iter_mut().zip(&g.free) {
            *l = u32::from(*f);
        }
    }
    flood(&mut g);
    merge_open(&mut g, params.door_ratio);
    drop_thin(&mut g, occ.agent_radius);
    merge_small(&mut g, (params.min_room_area / cell_area).ceil() as usize);
    split_open_plan(&mut g, scene, params.split_area);
    let n = g.label.iter().copied().max().unwrap_or(0);
    let room_ids: Vec<RoomId> = (0..n).collect();
    let mut rooms = Vec::new();
    for l in 1..=n {
        let polygon = outline(&g, l);
        rooms.push(Room {
            id: l - 1,
            kind: RoomType::Room,
            name: String::new(),
            polygon,
        });
    }
    assign_objects(scene, &g, &room_ids, params.object_snap);
    let mut per_kind: BTreeMap<RoomType, u32> = BTreeMap::new();
    for r in rooms.iter_mut() {
        r.kind = classify_room(scene, r.id, r.area(), &r.polygon);
        let k = per_kind.entry(r.kind).or_insert(0);
        *k += 1;
        r.name = format!("{}_{}", r.kind.name(), k);
    }
    scene.doors = find_doors(&g, &room_ids, scene.floor_height, params.open_plan_width);
    scene.rooms = rooms;
    Ok(())
}

/// Use annotated rooms: free cells take the room whose polygon contains them, doors are found
/// where rooms meet, objects get the room containing their centre (or the nearest one within
/// `object_snap`).
pub fn apply_annotation(
    scene: &mut Scene,
    ann: &RoomAnnotation,
    occ: &OccupancyConfig,
    params: &RoomParams,
) -> Result<()> {
    let mut g = structure_grid(scene, occ)?;
    for i in 0..g.w * g.h {
        if !g.free[i] {
            continue;
        }
        let p = g.center(i);
        if let Some(k) = ann.rooms.iter().position(|r| r.contains(p.x, p.y)) {
            g.label[i] = k as u32 + 1;
        }
    }
    let room_ids: Vec<RoomId> = ann.rooms.iter().map(|r| r.id).collect();
    assign_objects(scene, &g, &room_ids, params.object_snap);
    for o in scene.objects.iter_mut().filter(|o| !o.is_structure()) {
        let c = o.bbox.center();
        if let Some(r) = ann.rooms.iter().find(|r| r.contains(c.x, c.z)) {
            o.room = Some(r.id);
        }
    }
    scene.doors = find_doors(&g, &room_ids, scene.floor_height, params.open_plan_width);
    scene.rooms = ann.rooms.clone();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn room_params_and_annotations_out_of_range_are_refused_by_name() {
        assert!(RoomParams::default().validate().is_ok());
        for (p, field) in [
            (
                RoomParams {
                    door_ratio: 0.0,
                    ..Default::default()
                },
                "room_params.door_ratio",
            ),
            (
                RoomParams {
                    split_area: f32::NAN,
                    ..Default::default()
                },
                "room_params.split_area",
            ),
            (
                RoomParams {
                    min_room_area: -1.0,
                    ..Default::default()
                },
                "room_params.min_room_area",
            ),
            (
                RoomParams {
                    open_plan_width: 1e9,
                    ..Default::default()
                },
                "room_params.open_plan_width",
            ),
            (
                RoomParams {
                    object_snap: f32::INFINITY,
                    ..Default::default()
                },
                "room_params.object_snap",
            ),
        ] {
            let e = p.validate().expect_err(field).to_string();
            assert!(e.contains(field), "{e}");
        }
        let far = "[[room]]\nkind = \"bedroom\"\npolygon = [[0.0, 0.0], [1e9, 0.0], [1.0, 1.0]]\n";
        let e = RoomAnnotation::from_toml(far, Path::new("rooms.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("rooms.toml") && e.contains("room[0].polygon") && e.contains("1000000000"),
            "{e}"
        );
    }

    #[test]
    fn annotation_parses_and_orients_polygons() {
        let t = "[[room]]\nkind = \"bedroom\"\npolygon = [[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]\n";
        let a = RoomAnnotation::from_toml(t, Path::new("r.toml")).unwrap();
        assert_eq!(a.rooms[0].name, "bedroom_1");
        assert!(shoelace_xz(&a.rooms[0].polygon) < 0.0);
        assert!((a.rooms[0].area() - 12.0).abs() < 1e-5);
        let bad = "[[room]]\nkind = \"ballroom\"\npolygon = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]\n";
        let e = RoomAnnotation::from_toml(bad, Path::new("r.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("r.toml") && e.contains("room[0].kind") && e.contains("ballroom"),
            "{e}"
        );
    }

    fn grid_from(rows: &[&str]) -> Labels {
        let h = rows.len();
        let w = rows[0].len();
        let free: Vec<bool> = rows
            .iter()
            .flat_map(|r| r.bytes().map(|b| b != b'#'))
            .collect();
        let d2 = squared_distance_transform(w as u32, h as u32, |i| !free[i]);
        Labels {
            w,
            h,
            res: 1.0,
            origin: Vec2::ZERO,
            label: vec![0; w * h],
            dist: d2.iter().map(|d| d.sqrt() as f32).collect(),
            free,
        }
    }

    #[test]
    fn two_rooms_meet_at_the_door_and_outline_is_their_cells() {
        // Two 7x7 rooms joined by a 3-cell door in the middle wall.
        let rows = [
            "#################",
            "#.......#.......#",
            "#.......#.......#",
            "#...............#",
            "#...............#",
            "#...............#",
            "#.......#.......#",
            "#.......#.......#",
            "#################",
        ];
        let mut g = grid_from(&rows);
        seed_maxima(&mut g);
        flood(&mut g);
        merge_open(&mut g, 0.6);
        merge_small(&mut g, 4);
        assert_eq!(g.label.iter().copied().max(), Some(2), "two rooms");
        // Every free cell is in a room; the left room holds column 1, the right column 15.
        assert!(g.free.iter().zip(&g.label).all(|(f, l)| !f || *l != 0));
        assert_ne!(g.label[4 * 17 + 1], g.label[4 * 17 + 15]);
        let doors = find_doors(&g, &[0, 1], 0.0, 5.0);
        assert_eq!(doors.len(), 1, "{doors:?}");
        let d = &doors[0];
        assert!((d.width - 3.0).abs() < 1e-4, "{d:?}");
        assert!(
            (d.position[2] - 4.5).abs() < 1e-4 && (7.0..=10.0).contains(&d.position[0]),
            "{d:?}"
        );
        assert!((d.normal[0].abs() - 1.0).abs() < 1e-4, "{d:?}");
        assert!(!d.open_plan);
        for l in 1..=2 {
            let room = Room {
                id: 0,
                kind: RoomType::Room,
                name: String::new(),
                polygon: outline(&g, l),
            };
            assert!(shoelace_xz(&room.polygon) < 0.0);
            let cells = g.label.iter().filter(|&&x| x == l).count() as f32;
            assert!(
                (room.area() - cells).abs() < 1e-3,
                "{} vs {cells}",
                room.area()
            );
        }
        // A lower door ratio treats the same door as an open-plan opening.
        let mut g = grid_from(&rows);
        seed_maxima(&mut g);
        flood(&mut g);
        merge_open(&mut g, 0.4);
        merge_small(&mut g, 4);
        assert_eq!(g.label.iter().copied().max(), Some(1));
    }
}
