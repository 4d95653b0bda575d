//! Top-down pictures of a scene: rooms tinted by type, the navigable area shaded, walls dark,
//! doors marked, objects as filled footprints coloured by class with labels and a legend, room
//! names and a scale bar. [`Topdown::frame`] maps world points to pixels so other layers can
//! draw trajectories on top ([`draw_path`], [`draw_marker`]).
//!
//! Primitive parts (procedural homes) are drawn as their footprints. Mesh parts (imported homes)
//! are drawn by their triangles cut to the height band the occupancy map sees (floor clearance
//! to agent height, [`crate::occupancy::OccupancyConfig`]), so a whole-house wall mesh shows as
//! lines and the rooms stay visible; structure keeps only its upright faces, and an object with
//! nothing in the band (a chandelier) is drawn whole and faint.
//!
//! Image axes: pixel x grows with world x, pixel y grows with world z (so the picture is the
//! scene seen from above with -Z, the agent's yaw-0 heading, pointing up).

use crate::geometry::shape_corners;
use crate::occupancy::GridMap;
use crate::occupancy::OccupancyConfig;
use crate::scene::{DoorKind, MeshData, Pose, Scene, SceneObject, Shape};
use crate::vocab::{ClassKind, RoomType, SemanticClass};
use glam::{Vec2, Vec3};
use image::{Rgb, RgbImage};

/// Drawing options of [`render_topdown`].
#[derive(Clone, Debug, PartialEq)]
pub struct TopdownOptions {
    /// Pixels per metre (clamped so the image stays within `max_size` pixels).
    pub px_per_m: f32,
    /// Largest width or height of the map area in pixels.
    pub max_size: u32,
    /// Margin around the scene in pixels.
    pub margin_px: u32,
    /// Draw class-name labels on furniture.
    pub labels: bool,
    /// Draw a legend of the classes present on the right.
    pub legend: bool,
    /// Draw room names.
    pub room_names: bool,
    /// Title written in the top-left corner (e.g. the scene id); empty for none.
    pub title: String,
}

impl Default for TopdownOptions {
    fn default() -> Self {
        TopdownOptions {
            px_per_m: 50.0,
            max_size: 3000,
            margin_px: 36,
            labels: true,
            legend: true,
            room_names: true,
            title: String::new(),
        }
    }
}

/// The world -> pixel mapping of a top-down image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldToPixel {
    /// World `(x, z)` drawn at pixel `(origin_px.x, origin_px.y)`.
    pub world_min: Vec2,
    /// Pixel position of `world_min`.
    pub origin_px: Vec2,
    /// Pixels per metre.
    pub px_per_m: f32,
}

impl WorldToPixel {
    /// Pixel coordinates (continuous) of a world floor point `(x, z)`.
    pub fn to_pixel(&self, p: Vec2) -> Vec2 {
        self.origin_px + (p - self.world_min) * self.px_per_m
    }

    /// World floor point `(x, z)` under a pixel position.
    pub fn to_world(&self, px: Vec2) -> Vec2 {
        self.world_min + (px - self.origin_px) / self.px_per_m
    }
}

/// A rendered top-down image and its world -> pixel mapping.
#[derive(Clone, Debug)]
pub struct Topdown {
    /// The picture.
    pub image: RgbImage,
    /// Mapping from world `(x, z)` to pixels.
    pub frame: WorldToPixel,
}

impl Topdown {
    /// Draw a polyline of world points (see [`draw_path`]).
    pub fn draw_path(&mut self, points: &[Vec2], color: [u8; 3], width_px: f32) {
        draw_path(&mut self.image, &self.frame, points, color, width_px);
    }

    /// Draw a filled disc with a dark outline at a world point (see [`draw_marker`]).
    pub fn draw_marker(&mut self, p: Vec2, color: [u8; 3], radius_px: f32) {
        draw_marker(&mut self.image, &self.frame, p, color, radius_px);
    }
}

/// Pastel tint of a room type.
pub fn room_color(kind: RoomType) -> [u8; 3] {
    match kind {
        RoomType::LivingRoom => [246, 226, 196],
        RoomType::Kitchen => [252, 240, 178],
        RoomType::DiningRoom => [246, 212, 200],
        RoomType::Bedroom => [214, 226, 250],
        RoomType::Bathroom => [200, 238, 240],
        RoomType::Hallway => [228, 228, 222],
        RoomType::Office => [226, 240, 208],
        RoomType::LaundryRoom => [236, 222, 246],
        RoomType::Closet => [236, 232, 214],
        RoomType::Gym => [250, 214, 226],
        RoomType::Room => [234, 234, 234],
        RoomType::EntranceHall => [226, 220, 240],
        RoomType::Balcony => [214, 236, 240],
        RoomType::Pantry => [244, 232, 200],
        RoomType::HomeTheater => [218, 206, 236],
        RoomType::Library => [232, 222, 204],
        RoomType::Garage => [216, 216, 210],
        RoomType::Porch => [222, 238, 214],
        RoomType::Sauna => [240, 214, 190],
        RoomType::Spa => [210, 240, 226],
        RoomType::WineCellar => [230, 204, 212],
        RoomType::Playroom => [252, 226, 236],
        RoomType::MudRoom => [222, 214, 200],
        RoomType::Workshop => [224, 226, 200],
    }
}

/// Colour of a semantic class: structure in greys, other classes spread around the hue circle
/// (golden-angle steps over the class id, so neighbouring ids differ clearly).
pub fn class_color(class: SemanticClass) -> [u8; 3] {
    match class {
        SemanticClass::Wall => [52, 52, 58],
        SemanticClass::DoorFrame => [120, 86, 60],
        SemanticClass::Door => [176, 120, 70],
        SemanticClass::Window => [120, 180, 230],
        SemanticClass::Floor | SemanticClass::Ceiling => [200, 200, 200],
        SemanticClass::Unknown => [150, 150, 150],
        _ => {
            let hue = (class.id() as f32 * 137.508) % 360.0;
            let (s, v) = match class.kind() {
                ClassKind::Small => (0.75, 0.85),
                _ => (0.55, 0.78),
            };
            hsv(hue, s, v)
        }
    }
}

fn hsv(h: f32, s: f32, v: f32) -> [u8; 3] {
    let c = v * s;
    let hp = h / 60.0;
    let x = c * (1.0 - (hp % 2.0 - 1.0).abs());
    let (r, g, b) = match hp as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = v - c;
    [r, g, b].map(|u| ((u + m) * 255.0).round() as u8)
}

fn darker(c: [u8; 3], f: f32) -> [u8; 3] {
    c.map(|u| (u as f32 * f) as u8)
}

/// Blend `color` into a pixel with opacity `alpha` (ignored outside the image).
fn blend(img: &mut RgbImage, x: i64, y: i64, color: [u8; 3], alpha: f32) {
    if x < 0 || y < 0 || x >= img.width() as i64 || y >= img.height() as i64 {
        return;
    }
    let p = img.get_pixel_mut(x as u32, y as u32);
    for (c, t) in p.0.iter_mut().zip(color) {
        *c = (*c as f32 * (1.0 - alpha) + t as f32 * alpha).round() as u8;
    }
}

/// Fill a polygon given in pixel coordinates (even-odd rule, pixel centres sampled).
fn fill_polygon(img: &mut RgbImage, pts: &[Vec2], color: [u8; 3], alpha: f32) {
    if pts.len() < 3 {
        return;
    }
    let (mut y0, mut y1) = (f32::INFINITY, f32::NEG_INFINITY);
    for p in pts {
        y0 = y0.min(p.y);
        y1 = y1.max(p.y);
    }
    let ys = (y0 - 0.5).ceil().max(0.0) as i64;
    let ye = ((y1 - 0.5).floor() as i64).min(img.height() as i64 - 1);
    let mut xs = Vec::new();
    for y in ys..=ye {
        let sy = y as f32 + 0.5;
        xs.clear();
        for i in 0..pts.len() {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            if (a.y > sy) != (b.y > sy) {
                xs.push(a.x + (sy - a.y) / (b.y - a.y) * (b.x - a.x));
            }
        }
        xs.sort_by(f32::total_cmp);
        for pair in xs.chunks_exact(2) {
            let xa = (pair[0] - 0.5).ceil().max(0.0) as i64;
            let xb = ((pair[1] - 0.5).floor() as i64).min(img.width() as i64 - 1);
            for x in xa..=xb {
                blend(img, x, y, color, alpha);
            }
        }
    }
}

fn fill_disc(img: &mut RgbImage, c: Vec2, r: f32, color: [u8; 3], alpha: f32) {
    let (x0, x1) = ((c.x - r).floor() as i64, (c.x + r).ceil() as i64);
    let (y0, y1) = ((c.y - r).floor() as i64, (c.y + r).ceil() as i64);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let d = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) - c;
            if d.length_squared() <= r * r {
                blend(img, x, y, color, alpha);
            }
        }
    }
}

/// A thick segment in pixel coordinates with round caps.
fn thick_line(img: &mut RgbImage, a: Vec2, b: Vec2, width: f32, color: [u8; 3]) {
    let d = b - a;
    let r = width * 0.5;
    if d.length() > 1e-3 {
        let n = d.perp().normalize() * r;
        fill_polygon(img, &[a + n, b + n, b - n, a - n], color, 1.0);
    }
    fill_disc(img, a, r, color, 1.0);
    fill_disc(img, b, r, color, 1.0);
}

fn outline(img: &mut RgbImage, pts: &[Vec2], color: [u8; 3]) {
    for i in 0..pts.len() {
        let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
        let n = ((b - a).length().ceil() as usize).max(1);
        for k in 0..=n {
            let p = a + (b - a) * (k as f32 / n as f32);
            blend(img, p.x.floor() as i64, p.y.floor() as i64, color, 0.9);
        }
    }
}

/// Draw a polyline of world floor points `(x, z)` onto a top-down image.
pub fn draw_path(
    img: &mut RgbImage,
    frame: &WorldToPixel,
    points: &[Vec2],
    color: [u8; 3],
    width_px: f32,
) {
    let px: Vec<Vec2> = points.iter().map(|p| frame.to_pixel(*p)).collect();
    for w in px.windows(2) {
        thick_line(img, w[0], w[1], width_px, color);
    }
    if let [p] = px.as_slice() {
        fill_disc(img, *p, width_px * 0.5, color, 1.0);
    }
}

/// Draw a filled disc with a dark outline at a world floor point `(x, z)` (start/goal marks).
pub fn draw_marker(
    img: &mut RgbImage,
    frame: &WorldToPixel,
    p: Vec2,
    color: [u8; 3],
    radius_px: f32,
) {
    let c = frame.to_pixel(p);
    fill_disc(img, c, radius_px + 1.5, [20, 20, 20], 1.0);
    fill_disc(img, c, radius_px, color, 1.0);
}

/// Width in pixels of `text` drawn with [`draw_text`] at `scale`.
pub fn text_width(text: &str, scale: u32) -> u32 {
    text.chars().count() as u32 * 8 * scale
}

/// Draw ASCII text (8x8 font, `scale` times enlarged) with its top-left corner at `(x, y)`;
/// `halo` draws a 1-pixel light outline first for readability on busy backgrounds.
pub fn draw_text(
    img: &mut RgbImage,
    x: i64,
    y: i64,
    text: &str,
    scale: u32,
    color: [u8; 3],
    halo: bool,
) {
    let s = scale.max(1) as i64;
    let glyph_pass = |img: &mut RgbImage, dx: i64, dy: i64, c: [u8; 3]| {
        for (i, ch) in text.chars().enumerate() {
            let code = ch as usize;
            let glyph = font8x8::legacy::BASIC_LEGACY
                .get(code)
                .copied()
                .unwrap_or(font8x8::legacy::BASIC_LEGACY[b'?' as usize]);
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    if bits >> col & 1 == 1 {
                        for yy in 0..s {
                            for xx in 0..s {
                                blend(
                                    img,
                                    x + dx + (i as i64 * 8 + col) * s + xx,
                                    y + dy + row as i64 * s + yy,
                                    c,
                                    1.0,
                                );
                            }
                        }
                    }
                }
            }
        }
    };
    if halo {
        for (dx, dy) in [
            (-1, 0),
            (1, 0),
            (0, -1),
            (0, 1),
            (-1, -1),
            (1, 1),
            (-1, 1),
            (1, -1),
        ] {
            glyph_pass(img, dx, dy, [255, 255, 255]);
        }
    }
    glyph_pass(img, 0, 0, color);
}

/// Footprint of one part in world `(x, z)`: a disc `(centre, radius)` for upright cylinders and
/// spheres, else the convex hull of its projected corners.
enum Footprint {
    Disc(Vec2, f32),
    Polygon(Vec<Vec2>),
}

fn part_footprint(shape: &Shape, pose: &Pose) -> Footprint {
    let up = pose.quat() * Vec3::Y;
    let c = pose.translation();
    match shape {
        Shape::Sphere { radius } => return Footprint::Disc(Vec2::new(c.x, c.z), *radius),
        Shape::Cylinder { radius, .. } if up.y.abs() > 0.999 => {
            return Footprint::Disc(Vec2::new(c.x, c.z), *radius)
        }
        _ => {}
    }
    let pts: Vec<Vec2> = shape_corners(shape)
        .into_iter()
        .map(|p| {
            let w = pose.transform_point(p);
            Vec2::new(w.x, w.z)
        })
        .collect();
    Footprint::Polygon(convex_hull(pts))
}

/// Convex hull (monotone chain), counter-clockwise in (x, z).
fn convex_hull(mut pts: Vec<Vec2>) -> Vec<Vec2> {
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut lower: Vec<Vec2> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0.0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<Vec2> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0.0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

fn draw_object(
    img: &mut RgbImage,
    frame: &WorldToPixel,
    o: &SceneObject,
    fill: [u8; 3],
    alpha: f32,
    band: [f32; 2],
) {
    let edge = darker(fill, 0.55);
    // Mesh parts (imported scenes) are drawn by their triangles cut to the agent's height band;
    // an object with no geometry in the band (a chandelier) is drawn whole but faint, so that it
    // does not vanish. Structure (walls, frames) shows only its upright faces: a floor or
    // platform that shares the walls' mesh or material must not paint the room dark.
    let mesh_parts: Vec<(&MeshData, Pose)> = o
        .parts
        .iter()
        .filter_map(|part| match &part.shape {
            Shape::Mesh(m) => Some((m, o.pose.mul(&part.transform))),
            _ => None,
        })
        .collect();
    if !mesh_parts.is_empty() {
        let structure = o.class.kind() == ClassKind::Structure;
        let mut pieces: Vec<Vec<Vec2>> = Vec::new();
        for (m, pose) in &mesh_parts {
            mesh_footprint(m, pose, band, structure, &mut pieces);
        }
        let mut alpha = alpha;
        if pieces.is_empty() && !structure {
            alpha *= 0.35;
            for (m, pose) in &mesh_parts {
                let all = [f32::NEG_INFINITY, f32::INFINITY];
                mesh_footprint(m, pose, all, false, &mut pieces);
            }
        }
        for poly in &pieces {
            let px: Vec<Vec2> = poly.iter().map(|p| frame.to_pixel(*p)).collect();
            fill_polygon(img, &px, fill, alpha);
            // Upright triangles (walls) project to slivers that cover no pixel centre: draw
            // their edges as thin lines.
            let area = polygon_area(&px);
            let perimeter: f32 = (0..px.len())
                .map(|i| (px[(i + 1) % px.len()] - px[i]).length())
                .sum();
            if area < perimeter {
                for i in 0..px.len() {
                    thin_line(img, px[i], px[(i + 1) % px.len()], fill, alpha);
                }
            }
        }
    }
    for part in &o.parts {
        if matches!(part.shape, Shape::Mesh(_)) {
            continue;
        }
        let pose = o.pose.mul(&part.transform);
        match part_footprint(&part.shape, &pose) {
            Footprint::Disc(c, r) => {
                let (c, r) = (frame.to_pixel(c), r * frame.px_per_m);
                fill_disc(img, c, r + 0.7, edge, alpha);
                fill_disc(img, c, (r - 0.7).max(0.5), fill, alpha);
            }
            Footprint::Polygon(pts) => {
                let px: Vec<Vec2> = pts.iter().map(|p| frame.to_pixel(*p)).collect();
                fill_polygon(img, &px, fill, alpha);
                outline(img, &px, edge);
            }
        }
    }
}

/// Absolute area of a polygon (shoelace).
fn polygon_area(pts: &[Vec2]) -> f32 {
    let mut a = 0.0;
    for i in 0..pts.len() {
        a += pts[i].perp_dot(pts[(i + 1) % pts.len()]);
    }
    (a * 0.5).abs()
}

/// A line about 1.5 pixels wide (a square brush stepped along the segment).
fn thin_line(img: &mut RgbImage, a: Vec2, b: Vec2, color: [u8; 3], alpha: f32) {
    let n = ((b - a).length().ceil() as usize).max(1);
    let mut last = (i64::MIN, i64::MIN);
    for k in 0..=n {
        let p = a + (b - a) * (k as f32 / n as f32);
        let (x, y) = ((p.x - 0.25).floor() as i64, (p.y - 0.25).floor() as i64);
        if (x, y) == last {
            continue;
        }
        last = (x, y);
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            blend(img, x + dx, y + dy, color, alpha);
        }
    }
}

/// The floor-plan pieces of a mesh: each triangle (in world space) clipped to the height band
/// `[lo, hi]` and projected to `(x, z)`; with `upright_only`, nearly horizontal triangles are
/// left out. Pieces with fewer than two points are dropped.
fn mesh_footprint(
    m: &MeshData,
    pose: &Pose,
    band: [f32; 2],
    upright_only: bool,
    out: &mut Vec<Vec<Vec2>>,
) {
    let world: Vec<Vec3> = m
        .positions
        .iter()
        .map(|p| pose.transform_point(Vec3::from_array(*p)))
        .collect();
    let mut poly: Vec<Vec3> = Vec::with_capacity(6);
    let mut tmp: Vec<Vec3> = Vec::with_capacity(6);
    for tri in &m.indices {
        let Some(v) = tri
            .map(|i| world.get(i as usize).copied())
            .into_iter()
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let (y0, y1) = (
            v.iter().map(|p| p.y).fold(f32::INFINITY, f32::min),
            v.iter().map(|p| p.y).fold(f32::NEG_INFINITY, f32::max),
        );
        if y1 < band[0] || y0 > band[1] {
            continue;
        }
        if upright_only {
            let n = (v[1] - v[0]).cross(v[2] - v[0]);
            if n.y.abs() > 0.9 * n.length() {
                continue;
            }
        }
        poly.clear();
        poly.extend_from_slice(&v);
        if y0 < band[0] {
            clip_y(&poly, band[0], true, &mut tmp);
            std::mem::swap(&mut poly, &mut tmp);
        }
        if y1 > band[1] {
            clip_y(&poly, band[1], false, &mut tmp);
            std::mem::swap(&mut poly, &mut tmp);
        }
        if poly.len() >= 2 {
            out.push(poly.iter().map(|p| Vec2::new(p.x, p.z)).collect());
        }
    }
}

/// Sutherland-Hodgman against the plane `y = h`, keeping `y >= h` (`above`) or `y <= h`.
fn clip_y(poly: &[Vec3], h: f32, above: bool, out: &mut Vec<Vec3>) {
    out.clear();
    let inside = |p: &Vec3| if above { p.y >= h } else { p.y <= h };
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (ia, ib) = (inside(&a), inside(&b));
        if ia {
            out.push(a);
        }
        if ia != ib {
            let t = (h - a.y) / (b.y - a.y);
            out.push(a + (b - a) * t);
        }
    }
}

/// Pixel centre for a room name of `w` x `h` pixels: among candidate spots inside the room, the
/// one overlapping the fewest furniture footprints (ties: nearest the room's centre).
fn room_label_spot(
    room: &crate::scene::Room,
    frame: &WorldToPixel,
    w: f32,
    h: f32,
    boxes: &[[f32; 4]],
) -> Vec2 {
    let centre = Vec2::from_array(room.center());
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for p in &room.polygon {
        lo = lo.min(Vec2::from_array(*p));
        hi = hi.max(Vec2::from_array(*p));
    }
    let mut best = (f32::INFINITY, f32::INFINITY, frame.to_pixel(centre));
    for i in 0..=6 {
        for j in 0..=6 {
            let f = Vec2::new(0.2 + 0.6 * i as f32 / 6.0, 0.2 + 0.6 * j as f32 / 6.0);
            let p = lo + (hi - lo) * f;
            if !room.contains(p.x, p.y) {
                continue;
            }
            let c = frame.to_pixel(p);
            let r = [c.x - w * 0.5, c.y - h * 0.5, c.x + w * 0.5, c.y + h * 0.5];
            let overlap: f32 = boxes
                .iter()
                .map(|b| {
                    let ox = (r[2].min(b[2]) - r[0].max(b[0])).max(0.0);
                    let oy = (r[3].min(b[3]) - r[1].max(b[1])).max(0.0);
                    ox * oy
                })
                .sum();
            let d = (p - centre).length();
            if (overlap, d) < (best.0, best.1) {
                best = (overlap, d, c);
            }
        }
    }
    best.2
}

fn draw_order(o: &SceneObject) -> u8 {
    match (o.class, o.class.kind()) {
        (SemanticClass::Rug, _) => 0,
        (_, ClassKind::Furniture | ClassKind::Unknown) => 1,
        (SemanticClass::Window, _) => 2,
        (SemanticClass::Wall, _) => 3,
        (SemanticClass::DoorFrame, _) => 4,
        (_, ClassKind::Small) => 5,
        _ => 6,
    }
}

/// The pixels per metre [`render_topdown`] draws a scene of `extent` (metres, x and z) with:
/// `requested`, lowered so the map area stays within `max_size` pixels, and at least 1. The
/// value used is in [`Topdown::frame`]; callers compare it with what they asked for.
pub fn clamped_px_per_m(requested: f32, max_size: u32, extent: Vec2) -> f32 {
    requested
        .min(max_size as f32 / extent.max_element().max(1e-6))
        .max(1.0)
}

/// Render a top-down picture of `scene`; `navigable` (the agent-dilated map) shades the area an
/// agent can reach.
pub fn render_topdown(
    scene: &Scene,
    navigable: Option<&GridMap>,
    opts: &TopdownOptions,
) -> Topdown {
    let (lo, hi) = scene_extent(scene);
    let extent = (hi - lo).max(Vec2::splat(0.5));
    let ppm = clamped_px_per_m(opts.px_per_m, opts.max_size, extent);
    let margin = opts.margin_px as f32;
    let title_h = if opts.title.is_empty() { 0.0 } else { 22.0 };
    let map_w = (extent.x * ppm).ceil() as u32 + 2 * opts.margin_px;
    let map_h = (extent.y * ppm).ceil() as u32 + 2 * opts.margin_px + title_h as u32 + 26;
    let frame = WorldToPixel {
        world_min: lo,
        origin_px: Vec2::new(margin, margin + title_h),
        px_per_m: ppm,
    };
    let present = legend_classes(scene);
    let legend_w = if opts.legend {
        present
            .iter()
            .map(|c| text_width(c.name(), 1))
            .max()
            .unwrap_or(0)
            + 40
    } else {
        0
    };
    let legend_h = if opts.legend {
        present.len() as u32 * 14 + 4 * 14 + 22 + title_h as u32 + 2 * opts.margin_px
    } else {
        0
    };
    let mut img = RgbImage::from_pixel(map_w + legend_w, map_h.max(legend_h), Rgb([250, 250, 248]));

    for r in &scene.rooms {
        let px: Vec<Vec2> = r
            .polygon
            .iter()
            .map(|p| frame.to_pixel(Vec2::from_array(*p)))
            .collect();
        fill_polygon(&mut img, &px, room_color(r.kind), 1.0);
    }
    if let Some(nav) = navigable {
        shade_navigable(&mut img, &frame, nav);
    }
    // Objects, in layers: rugs, furniture, walls and frames, small objects.
    let mut objs: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| !matches!(o.class, SemanticClass::Floor | SemanticClass::Ceiling))
        .collect();
    objs.sort_by_key(|o| (draw_order(o), o.id));
    draw_objects(&mut img, &frame, scene, &objs);
    draw_doors(&mut img, &frame, scene);
    // Labels skip places an earlier label took.
    let mut placed: Vec<[i64; 4]> = Vec::new();
    if opts.room_names {
        draw_room_names(&mut img, &frame, scene, &objs, &mut placed);
    }
    if opts.labels {
        draw_furniture_labels(&mut img, &frame, &objs, map_w, &mut placed);
    }
    if !opts.title.is_empty() {
        draw_text(
            &mut img,
            margin as i64,
            8,
            &opts.title,
            2,
            [20, 20, 20],
            false,
        );
    }
    draw_scale_bar(&mut img, ppm, margin, map_w, map_h);
    if opts.legend {
        let origin = (map_w as i64 + 4, margin as i64 + title_h as i64);
        draw_legend(&mut img, origin, &present, navigable.is_some());
    }
    Topdown { image: img, frame }
}

/// Render a top-down picture of one level of a scene ([`Scene::level_view`]: its rooms, doors
/// and objects, the stairs reaching it) with that level's navigable map; the title gets the
/// level's name. For a single-storey scene level 0 is [`render_topdown`]; None for a level the
/// scene does not have.
pub fn render_topdown_level(
    scene: &Scene,
    level: crate::scene::LevelId,
    navigable: Option<&GridMap>,
    opts: &TopdownOptions,
) -> Option<Topdown> {
    let view = scene.level_view(level)?;
    let mut opts = opts.clone();
    if let Some(l) = scene.storeys.levels.get(level as usize) {
        if !opts.title.is_empty() {
            opts.title = format!("{} - {}", opts.title, l.name);
        }
    }
    Some(render_topdown(&view, navigable, &opts))
}

/// The floor extent `(min, max)` of rooms and objects (ceilings excluded, they cover
/// everything anyway); a unit square for an empty scene.
fn scene_extent(scene: &Scene) -> (Vec2, Vec2) {
    let mut lo = Vec2::splat(f32::INFINITY);
    let mut hi = Vec2::splat(f32::NEG_INFINITY);
    for o in scene
        .objects
        .iter()
        .filter(|o| o.class != SemanticClass::Ceiling)
    {
        if !o.bbox.is_empty() {
            lo = lo.min(Vec2::new(o.bbox.min[0], o.bbox.min[2]));
            hi = hi.max(Vec2::new(o.bbox.max[0], o.bbox.max[2]));
        }
    }
    for p in scene.rooms.iter().flat_map(|r| &r.polygon) {
        lo = lo.min(Vec2::from_array(*p));
        hi = hi.max(Vec2::from_array(*p));
    }
    if !(lo.x <= hi.x && lo.y <= hi.y) {
        return (Vec2::ZERO, Vec2::ONE);
    }
    (lo, hi)
}

/// Classes present in the scene (the legend's rows), in vocabulary order.
fn legend_classes(scene: &Scene) -> Vec<SemanticClass> {
    let mut present: Vec<SemanticClass> = scene
        .objects
        .iter()
        .map(|o| o.class)
        .filter(|c| !matches!(c, SemanticClass::Floor | SemanticClass::Ceiling))
        .collect();
    present.sort_by_key(|c| c.id());
    present.dedup();
    present
}

/// Tint the pixels whose centre is navigable.
fn shade_navigable(img: &mut RgbImage, frame: &WorldToPixel, nav: &GridMap) {
    let (w, h) = (img.width(), img.height());
    for y in 0..h {
        for x in 0..w {
            let p = frame.to_world(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            if nav.is_free_at(p) {
                blend(img, x as i64, y as i64, [96, 180, 110], 0.28);
            }
        }
    }
}

/// Objects in draw order; mesh geometry is cut to the band the occupancy map looks at (rugs:
/// from the floor).
fn draw_objects(img: &mut RgbImage, frame: &WorldToPixel, scene: &Scene, objs: &[&SceneObject]) {
    let occ = OccupancyConfig::default();
    let band = [
        scene.floor_height + occ.floor_clearance,
        scene.floor_height + occ.agent_height,
    ];
    for o in objs {
        let (alpha, band) = if o.class == SemanticClass::Rug {
            (0.45, [scene.floor_height - 0.05, band[1]])
        } else {
            (1.0, band)
        };
        draw_object(img, frame, o, class_color(o.class), alpha, band);
    }
}

/// Colour of an open doorway's bar.
const DOOR_OPEN: [u8; 3] = [230, 130, 30];
/// Colour of a closed door's bar.
const DOOR_CLOSED: [u8; 3] = [200, 30, 40];
/// Colour of an open-plan opening's dashes.
const OPEN_PLAN: [u8; 3] = [90, 150, 220];

/// Doors: a bar across the opening, orange when open (with the leaf's swing arc), red and
/// thicker when closed, dashed blue for open-plan connections. The leaves themselves are drawn
/// with the objects.
fn draw_doors(img: &mut RgbImage, frame: &WorldToPixel, scene: &Scene) {
    for d in &scene.doors {
        let n = Vec2::from_array(d.normal).normalize_or(Vec2::X);
        let t = n.perp();
        let c = Vec2::new(d.position[0], d.position[2]);
        let (a, b) = (c - t * d.width * 0.5, c + t * d.width * 0.5);
        if d.open_plan {
            let segs = 6;
            for k in (0..segs).step_by(2) {
                let p0 = a + (b - a) * (k as f32 / segs as f32);
                let p1 = a + (b - a) * ((k + 1) as f32 / segs as f32);
                thick_line(img, frame.to_pixel(p0), frame.to_pixel(p1), 3.0, OPEN_PLAN);
            }
        } else if d.is_closed() {
            thick_line(img, frame.to_pixel(a), frame.to_pixel(b), 6.0, DOOR_CLOSED);
        } else {
            thick_line(img, frame.to_pixel(a), frame.to_pixel(b), 4.0, DOOR_OPEN);
            // A sliding leaf moves along the wall and sweeps nothing; each leaf of a pair
            // sweeps its own half of the opening.
            if d.kind != DoorKind::Sliding {
                let reach = d.width / d.leaves().count().max(1) as f32;
                for leaf in d.leaves().filter_map(|id| scene.object(id)) {
                    draw_swing(img, frame, (c, t, n), d.width, reach, leaf);
                }
            }
        }
    }
}

/// The quarter circle of radius `reach` (the leaf's width) an open leaf sweeps about its
/// hinge, the jamb of the opening (centre `c`, along `t`, normal `n`) on the leaf's side.
fn draw_swing(
    img: &mut RgbImage,
    frame: &WorldToPixel,
    (c, t, n): (Vec2, Vec2, Vec2),
    width: f32,
    reach: f32,
    leaf: &SceneObject,
) {
    let lc = Vec2::new(leaf.bbox.center().x, leaf.bbox.center().z);
    let along = (lc - c).dot(t);
    let side = (lc - c).dot(n).signum();
    // The hinge: the leaf's jamb, on the wall line.
    let hinge = c + t * along.signum() * width * 0.5;
    let start = -t * along.signum();
    let end = n * side;
    let steps = 12;
    let point = |k: usize| {
        let u = k as f32 / steps as f32 * std::f32::consts::FRAC_PI_2;
        hinge + (start * u.cos() + end * u.sin()) * reach
    };
    for k in 0..steps {
        thin_line(
            img,
            frame.to_pixel(point(k)),
            frame.to_pixel(point(k + 1)),
            DOOR_OPEN,
            0.8,
        );
    }
}

/// Room names, kept off the furniture where possible; their boxes go to `placed`.
fn draw_room_names(
    img: &mut RgbImage,
    frame: &WorldToPixel,
    scene: &Scene,
    objs: &[&SceneObject],
    placed: &mut Vec<[i64; 4]>,
) {
    let ppm = frame.px_per_m;
    // Furniture footprints in pixels.
    let boxes: Vec<[f32; 4]> = objs
        .iter()
        .filter(|o| matches!(o.class.kind(), ClassKind::Furniture | ClassKind::Small))
        .map(|o| {
            let a = frame.to_pixel(Vec2::new(o.bbox.min[0], o.bbox.min[2]));
            let b = frame.to_pixel(Vec2::new(o.bbox.max[0], o.bbox.max[2]));
            [a.x, a.y, b.x, b.y]
        })
        .collect();
    for r in &scene.rooms {
        let name = r.kind.words();
        let room_w = r
            .polygon
            .iter()
            .map(|p| p[0])
            .fold(f32::NEG_INFINITY, f32::max)
            - r.polygon.iter().map(|p| p[0]).fold(f32::INFINITY, f32::min);
        // Large text unless it would spill out of a narrow room.
        let scale = if text_width(&name, 2) as f32 <= room_w * ppm * 0.9 {
            2
        } else {
            1
        };
        let (w, h) = (text_width(&name, scale) as i64, 8 * scale as i64);
        let c = room_label_spot(r, frame, w as f32, h as f32, &boxes);
        let (x, y) = (c.x as i64 - w / 2, c.y as i64 - h / 2);
        draw_text(img, x, y, &name, scale, [30, 30, 30], true);
        placed.push([x - 2, y - 2, x + w + 2, y + h + 2]);
    }
}

/// Furniture labels, big objects first (they have room for theirs), skipping any that would
/// overlap a label in `placed`.
fn draw_furniture_labels(
    img: &mut RgbImage,
    frame: &WorldToPixel,
    objs: &[&SceneObject],
    map_w: u32,
    placed: &mut Vec<[i64; 4]>,
) {
    let mut furniture: Vec<&&SceneObject> = objs
        .iter()
        .filter(|o| o.class.kind() == ClassKind::Furniture && o.class != SemanticClass::Rug)
        .collect();
    furniture.sort_by(|a, b| {
        let area = |o: &SceneObject| o.bbox.size().x * o.bbox.size().z;
        area(b).total_cmp(&area(a)).then(a.id.cmp(&b.id))
    });
    for o in furniture {
        let c = frame.to_pixel(Vec2::new(o.bbox.center().x, o.bbox.center().z));
        let name = o.class.words();
        let w = text_width(&name, 1) as i64;
        let x = (c.x as i64 - w / 2).clamp(2, (map_w as i64 - w - 2).max(2));
        let y = c.y as i64 - 4;
        let rect = [x - 1, y - 1, x + w + 1, y + 9];
        let overlaps = placed
            .iter()
            .any(|p| rect[0] < p[2] && p[0] < rect[2] && rect[1] < p[3] && p[1] < rect[3]);
        if !overlaps {
            draw_text(img, x, y, &name, 1, [20, 20, 20], true);
            placed.push(rect);
        }
    }
}

/// The scale bar and the axes note along the bottom of the map.
fn draw_scale_bar(img: &mut RgbImage, ppm: f32, margin: f32, map_w: u32, map_h: u32) {
    let bar_m = [0.5f32, 1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .find(|m| m * ppm >= 60.0)
        .unwrap_or(10.0);
    let y = (map_h - 16) as f32;
    let x0 = margin;
    let x1 = margin + bar_m * ppm;
    thick_line(img, Vec2::new(x0, y), Vec2::new(x1, y), 3.0, [20, 20, 20]);
    for x in [x0, x1] {
        thick_line(
            img,
            Vec2::new(x, y - 5.0),
            Vec2::new(x, y + 5.0),
            2.0,
            [20, 20, 20],
        );
    }
    draw_text(
        img,
        x1 as i64 + 8,
        y as i64 - 4,
        &format!("{bar_m} m"),
        1,
        [20, 20, 20],
        false,
    );
    let axes = "+x right, +z down";
    draw_text(
        img,
        (map_w as i64 - margin as i64 - text_width(axes, 1) as i64).max(x1 as i64 + 60),
        y as i64 - 4,
        axes,
        1,
        [90, 90, 90],
        false,
    );
}

/// The legend at `(lx, ly)`: one swatch per class, the navigable tint, doors.
fn draw_legend(
    img: &mut RgbImage,
    (lx, mut ly): (i64, i64),
    present: &[SemanticClass],
    navigable: bool,
) {
    draw_text(img, lx, ly, "classes", 1, [20, 20, 20], false);
    ly += 16;
    for c in present {
        let col = class_color(*c);
        for yy in 0..10 {
            for xx in 0..14 {
                let edge = yy == 0 || yy == 9 || xx == 0 || xx == 13;
                blend(
                    img,
                    lx + xx,
                    ly + yy,
                    if edge { darker(col, 0.55) } else { col },
                    1.0,
                );
            }
        }
        draw_text(img, lx + 20, ly + 1, c.name(), 1, [30, 30, 30], false);
        ly += 14;
    }
    ly += 6;
    if navigable {
        for yy in 0..10 {
            for xx in 0..14 {
                blend(img, lx + xx, ly + yy, [170, 210, 170], 1.0);
            }
        }
        draw_text(img, lx + 20, ly + 1, "navigable", 1, [30, 30, 30], false);
        ly += 14;
    }
    for (label, col, dashed) in [
        ("open door", DOOR_OPEN, false),
        ("closed door", DOOR_CLOSED, false),
        ("open plan", OPEN_PLAN, true),
    ] {
        for xx in 0..14 {
            if !dashed || (xx / 4) % 2 == 0 {
                for yy in 3..7 {
                    blend(img, lx + xx, ly + yy, col, 1.0);
                }
            }
        }
        draw_text(img, lx + 20, ly + 1, label, 1, [30, 30, 30], false);
        ly += 14;
    }
}
