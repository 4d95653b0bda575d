//! Light baked into the vertices of a scene: ambient occlusion and direct light with shadows
//! from ceiling lamps, computed once with the ray caster ([`crate::bvh`]) so that renderers
//! only multiply per pixel.
//!
//! [`bake`] gives one light value per vertex of every part's triangulation
//! ([`crate::geometry::triangulate_part_cells`] with [`cell_of`]: the walls, floors and
//! ceilings of procedural homes are cut into cells of at most [`crate::geometry::MAX_CELL`] for
//! resolution, everything else keeps two triangles per box face, or 44 per bevelled box whose
//! chamfers get their own light, so the renderers draw few more triangles than without light). `scene.glb` stores it as `COLOR_0` (with
//! `KHR_materials_unlit`, so viewers show the baked look) and the renderers multiply it with the
//! part colour and texture ([`crate::material`]). It is a pure function of the scene: the same
//! scene gives the same bytes on any number of threads (each vertex draws its rays from a hash
//! of its own index, and parts are baked independently and collected in order).
//!
//! Procedural homes (`source = "procgen"`) get the full bake: a lamp under the ceiling of
//! every room (two in long rooms), 16 occlusion rays and two shadow rays per lamp per vertex.
//! Window panes ([`is_pane`]) glow at full light and are area lights: daylight from two points
//! on each pane, with cosine falloff at both ends and a shadow ray each, brightens the floor
//! and walls in front of windows.
//! Other scenes (imported houses, hand-made fixtures) get the old directional look per vertex,
//! which costs nothing.
//!
//! A scene is baked once, when its `scene.glb` is written; loading a scene folder reads the
//! light back from there ([`crate::io::load_scene`], [`remember`]) instead of baking again.
//! [`bake`] keeps results in a process-wide cache keyed by the scene's content
//! ([`crate::cache`], 256 MB unless `VLNVERSE_LIGHT_CACHE_MB` says otherwise); a hit returns
//! the same bytes as a fresh bake.

use crate::bvh::TriBvh;
use crate::cache;
use crate::scene::{Scene, SceneObject};
use crate::SemanticClass;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::{Arc, OnceLock};

/// Occlusion rays per vertex.
const AO_RAYS: usize = 16;
/// Reach of occlusion rays in metres (local occlusion: corners, under furniture).
const AO_REACH: f32 = 0.9;
/// Lamp power (light at 1 m straight below, before the `+ LAMP_SOFT` falloff).
const LAMP_POWER: f32 = 3.2;
/// Added to the squared distance so light near a lamp does not blow up.
const LAMP_SOFT: f32 = 0.6;
/// Lamps farther than this do not light a vertex.
const LAMP_REACH: f32 = 9.0;
/// Lamps hang this far below the top of the walls.
const LAMP_DROP: f32 = 0.35;
/// Directional look of unbaked scenes (as the renderers' flat shading was).
const FLAT_AMBIENT: f32 = 0.35;
const FLAT_DIFFUSE: f32 = 0.65;
const FLAT_LIGHT: [f32; 3] = [0.35, 1.0, 0.25];
/// Colour of the lamps (warm: a touch more red than blue), green = 1.
pub const LAMP_TINT: [f32; 3] = [1.04, 1.0, 0.92];
/// Cells of walls, in units of [`crate::geometry::MAX_CELL`].
const WALL_CELL: f32 = 2.0;
/// Light thrown back up by floors and walls onto faces looking down (a cheap bounce).
const BOUNCE: f32 = 0.24;
/// Megabytes of bakes kept by [`bake`] unless [`CACHE_MB_VAR`] says otherwise (a home's bake
/// takes 30 to 60 kB: every home of the `vlnverse` preset fits many times over).
pub const CACHE_MB: usize = 256;
/// Environment variable with the megabytes of bakes kept by [`bake`] (0: none).
pub const CACHE_MB_VAR: &str = "VLNVERSE_LIGHT_CACHE_MB";
/// Daylight through a window: light per square metre of pane at 1 m, straight in front.
const DAY_POWER: f32 = 1.6;
/// Added to the squared distance of daylight samples (the pane is large, not a point).
const DAY_SOFT: f32 = 0.5;
/// Windows farther than this do not light a vertex.
const DAY_REACH: f32 = 7.0;
/// Daylight is sampled this far in front of the pane (in front of frames and curtains, which
/// stay within 5 cm of the wall).
const DAY_LIFT: f32 = 0.06;
/// Objects of class `wall` lower than this (or floors taller than 6 cm) are skirting boards: no cells (a long thin board
/// would cost many triangles for a light that hardly changes along it).
const LOW_WALL: f32 = 0.5;

/// Whether an object is a window pane: class `window` of material `glass`. Panes glow at full
/// light and light the room (see the module docs).
pub fn is_pane(o: &SceneObject) -> bool {
    o.class == SemanticClass::Window && o.material == "glass"
}

/// A window pane as a light: two sample points in front of it and its normal into the room.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pane {
    samples: [Vec3; 2],
    normal: Vec3,
    /// Light of each sample: [`DAY_POWER`] times half the pane's area.
    power: f32,
}

/// The window panes of a lit scene as lights (a pane's box: its thinnest axis is the normal,
/// which points to the side of the object's local +z, into the room).
fn panes(scene: &Scene) -> Vec<Pane> {
    if !is_lit(scene) {
        return Vec::new();
    }
    let mut out = Vec::new();
    for o in scene.objects.iter().filter(|o| is_pane(o)) {
        for p in &o.parts {
            // The full box: a bevel narrows the pane's rim only.
            let crate::scene::Shape::Cuboid { half_extents, .. } = p.shape else {
                continue;
            };
            let pose = o.pose.mul(&p.transform);
            let q = pose.quat();
            let c = pose.translation();
            let h = Vec3::from_array(half_extents);
            let axes = [q * Vec3::X, q * Vec3::Y, q * Vec3::Z];
            let thin = if h.x <= h.y && h.x <= h.z {
                0
            } else if h.y <= h.z {
                1
            } else {
                2
            };
            let (a, b) = ((thin + 1) % 3, (thin + 2) % 3);
            let mut normal = axes[thin];
            // Into the room: towards the object's local +z.
            if normal.dot(o.pose.quat() * Vec3::Z) < 0.0 {
                normal = -normal;
            }
            let (ea, eb) = (axes[a] * h[a] * 0.5, axes[b] * h[b] * 0.5);
            let front = c + normal * (h[thin] + DAY_LIFT);
            out.push(Pane {
                samples: [front + ea + eb, front - ea - eb],
                normal,
                power: DAY_POWER * 2.0 * h[a] * h[b],
            });
        }
    }
    out
}

/// Light per vertex of every part: `parts[k][i]` is vertex `i` of
/// `triangulate_part_cells(part, pose, cell_of(scene, object))` of the `k`-th part of the scene
/// (object order, then part order), linear, 255 = full base colour. Every value is the light's
/// colour ([`BakedLight::tint`]) times one intensity, so renderers may interpolate the green
/// channel alone and multiply the tint into the part colour.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BakedLight {
    /// Per part, per vertex, RGB.
    pub parts: Vec<Vec<[u8; 3]>>,
    /// Colour of the light (green is 1): [`LAMP_TINT`] for lamp-lit homes, white otherwise.
    pub tint: [f32; 3],
}

impl BakedLight {
    /// Bytes held (allocated; for the cache's budget).
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self
                .parts
                .iter()
                .map(|p| p.capacity() * 3 + std::mem::size_of::<Vec<u8>>())
                .sum::<usize>()
    }
}

/// Whether a scene gets lamps and the full bake (procedural homes).
pub fn is_lit(scene: &Scene) -> bool {
    scene.source == "procgen"
}

/// Cell size of an object's triangulation for baking (see the module docs): floors of lamp-lit
/// homes get [`crate::geometry::MAX_CELL`] (shadows of furniture), walls cells twice as
/// large (smooth falloff, corner occlusion), other objects `None` (two triangles per box face).
pub fn cell_of(scene: &Scene, o: &SceneObject) -> Option<f32> {
    if !is_lit(scene) {
        return None;
    }
    let m = crate::geometry::MAX_CELL;
    match o.class {
        // Skirting boards (low walls or raised floors): two triangles per face.
        SemanticClass::Wall if o.bbox.max[1] - o.bbox.min[1] < LOW_WALL => None,
        SemanticClass::Floor if o.bbox.max[1] > o.bbox.min[1] + 0.06 => None,
        // Shadows of furniture on the floor need the finest cells; walls and ceilings carry
        // smooth falloff and corner occlusion.
        SemanticClass::Floor => Some(m),
        // Walls and ceilings carry smooth falloff, the lamps' pools of light and corner
        // occlusion. The rasteriser draws cut faces whole, so cells cost it no triangles.
        SemanticClass::Wall | SemanticClass::Ceiling => Some(m * WALL_CELL),
        _ => None,
    }
}

/// World-space triangulation of every part as baked (object order, then part order).
pub fn bake_meshes(scene: &Scene) -> Vec<crate::geometry::TriMesh> {
    scene
        .objects
        .iter()
        .flat_map(|o| {
            let cell = cell_of(scene, o);
            o.parts.iter().map(move |p| (o, p, cell))
        })
        .map(|(o, p, cell)| crate::geometry::triangulate_part_cells(p, &o.pose, cell))
        .collect()
}

/// Where the lamps of a scene hang: under the ceiling of every room, at the centre of its
/// outline's box, two along the long side of rooms longer than 4.5 m. Empty for scenes that are
/// not procedural homes. In a home on several floors each room's lamps hang under the walls of
/// its own floor.
pub fn lamps(scene: &Scene) -> Vec<Vec3> {
    if !is_lit(scene) {
        return Vec::new();
    }
    // The top of the walls standing on a floor at height `floor` (all walls when `None`).
    let wall_top = |floor: Option<f32>| {
        scene
            .objects
            .iter()
            .filter(|o| o.class == crate::SemanticClass::Wall)
            .filter(|o| floor.is_none_or(|f| (o.bbox.min[1] - f).abs() < 0.3))
            .map(|o| o.bbox.max[1])
            .fold(f32::NEG_INFINITY, f32::max)
    };
    let top = wall_top(None);
    let y = if top.is_finite() {
        top - LAMP_DROP
    } else {
        scene.floor_height + 2.3
    };
    // A room's lamp height: the scene's for one floor (as it always was), else its floor's.
    let height_of = |r: &crate::scene::Room| {
        if !scene.is_multi_level() {
            return y;
        }
        let floor = scene
            .room_level(r.id)
            .and_then(|l| scene.level_height(l))
            .unwrap_or(scene.floor_height);
        let top = wall_top(Some(floor));
        if top.is_finite() {
            top - LAMP_DROP
        } else {
            floor + 2.3
        }
    };
    let mut out = Vec::new();
    for r in &scene.rooms {
        let y = height_of(r);
        if r.polygon.is_empty() {
            continue;
        }
        let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
        for p in &r.polygon {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let c = [(lo[0] + hi[0]) * 0.5, (lo[1] + hi[1]) * 0.5];
        let (w, d) = (hi[0] - lo[0], hi[1] - lo[1]);
        if w.max(d) > 4.5 {
            let (dx, dz) = if w >= d {
                (w * 0.25, 0.0)
            } else {
                (0.0, d * 0.25)
            };
            out.push(Vec3::new(c[0] - dx, y, c[1] - dz));
            out.push(Vec3::new(c[0] + dx, y, c[1] + dz));
        } else {
            out.push(Vec3::new(c[0], y, c[1]));
        }
    }
    out
}

/// Bakes kept by [`bake`]: up to [`CACHE_MB_VAR`] megabytes (default [`CACHE_MB`]).
fn cache() -> &'static cache::SharedLru<BakedLight> {
    static C: OnceLock<cache::SharedLru<BakedLight>> = OnceLock::new();
    C.get_or_init(|| cache::shared_lru(cache::budget_from_env(CACHE_MB_VAR, CACHE_MB)))
}

/// A 64-bit key of everything the bake reads: what every part is triangulated from (shape,
/// pose, cell size) and the lights. Made from the scene's few numbers per part, not from the
/// triangulation, so a cache hit costs next to nothing.
fn content_key(scene: &Scene, lights: &Lights) -> u64 {
    let mut k = cache::ContentKey::new();
    k.u32(scene.objects.len() as u32);
    for o in &scene.objects {
        k.f32(cell_of(scene, o).unwrap_or(-1.0));
        k.f32s(&o.pose.position);
        k.f32s(&o.pose.rotation);
        k.u32(o.parts.len() as u32);
        for p in &o.parts {
            k.f32s(&p.transform.position);
            k.f32s(&p.transform.rotation);
            match &p.shape {
                crate::Shape::Cuboid {
                    half_extents,
                    bevel,
                } => {
                    k.u32(0);
                    k.f32s(half_extents);
                    k.f32(*bevel);
                }
                crate::Shape::Cylinder {
                    radius,
                    half_height,
                } => {
                    k.u32(1);
                    k.f32s(&[*radius, *half_height]);
                }
                crate::Shape::Sphere { radius } => {
                    k.u32(2);
                    k.f32(*radius);
                }
                crate::Shape::Mesh(m) => {
                    k.u32(3);
                    k.u32(m.positions.len() as u32);
                    m.positions.iter().for_each(|v| k.f32s(v));
                    k.u32(m.indices.len() as u32);
                    m.indices.iter().flatten().for_each(|i| k.u32(*i));
                }
            }
        }
    }
    for l in &lights.lamps {
        k.f32s(&l.to_array());
    }
    for p in &lights.panes {
        for v in p.samples.iter().chain([&p.normal]) {
            k.f32s(&v.to_array());
        }
        k.f32(p.power);
    }
    for e in &lights.glowing {
        k.u32(u32::from(*e));
    }
    k.finish()
}

/// Everything that lights a scene.
struct Lights {
    lamps: Vec<Vec3>,
    panes: Vec<Pane>,
    /// Per part (as [`bake_meshes`]): whether it glows at full light (window panes).
    glowing: Vec<bool>,
}

fn lights(scene: &Scene) -> Lights {
    let lit = is_lit(scene);
    Lights {
        lamps: lamps(scene),
        panes: panes(scene),
        glowing: scene
            .objects
            .iter()
            .flat_map(|o| o.parts.iter().map(move |_| lit && is_pane(o)))
            .collect(),
    }
}

/// Bake the light of a scene (see the module docs); the same result as a fresh bake, taken
/// from the cache when this scene was baked (or its light loaded, [`remember`]) a moment ago.
pub fn bake(scene: &Scene) -> Arc<BakedLight> {
    let lights = lights(scene);
    let key = content_key(scene, &lights);
    cache::get_or_insert(
        cache(),
        key,
        || bake_uncached(bake_meshes(scene), &lights),
        BakedLight::bytes,
    )
}

/// Keep light already baked for `scene` (e.g. read back from its `scene.glb`,
/// [`crate::io::glb::read_baked_light`]) so that [`bake`] returns it instead of baking again.
/// The given light replaces what the cache held for this scene.
pub fn remember(scene: &Scene, light: BakedLight) -> Arc<BakedLight> {
    let key = content_key(scene, &lights(scene));
    let (bytes, light) = (light.bytes(), Arc::new(light));
    if let Ok(mut c) = cache().lock() {
        c.insert(key, light.clone(), bytes);
    }
    light
}

/// [`bake`] without the cache: always computes (tests compare the two, and thread counts).
pub fn bake_fresh(scene: &Scene) -> BakedLight {
    bake_uncached(bake_meshes(scene), &lights(scene))
}

/// The light colour [`bake`] gives a scene ([`BakedLight::tint`]).
pub(crate) fn tint_of(scene: &Scene) -> [f32; 3] {
    if lamps(scene).is_empty() && panes(scene).is_empty() {
        [1.0; 3]
    } else {
        LAMP_TINT
    }
}

fn bake_uncached(parts: Vec<crate::geometry::TriMesh>, lights: &Lights) -> BakedLight {
    if lights.lamps.is_empty() && lights.panes.is_empty() {
        let l = Vec3::from_array(FLAT_LIGHT).normalize();
        return BakedLight {
            parts: parts
                .iter()
                .map(|m| {
                    m.normals
                        .iter()
                        .map(|n| {
                            let k =
                                FLAT_AMBIENT + FLAT_DIFFUSE * Vec3::from_array(*n).dot(l).max(0.0);
                            [to_u8(k); 3]
                        })
                        .collect()
                })
                .collect(),
            tint: [1.0; 3],
        };
    }
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for m in &parts {
        for t in &m.indices {
            let v = t.map(|i| Vec3::from_array(m.positions[i as usize]));
            positions.extend_from_slice(&v);
            normals.push((v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero());
        }
    }
    let bvh = TriBvh::new(&positions);
    let ctx = Ctx {
        bvh: &bvh,
        normals: &normals,
        lamps: &lights.lamps,
        panes: &lights.panes,
        dirs: hemisphere(),
    };
    BakedLight {
        parts: parts
            .par_iter()
            .enumerate()
            .map(|(k, m)| {
                if lights.glowing.get(k).copied().unwrap_or(false) {
                    vec![LAMP_TINT.map(to_u8); m.positions.len()]
                } else {
                    ctx.bake_part(k, m)
                }
            })
            .collect(),
        tint: LAMP_TINT,
    }
}

fn to_u8(k: f32) -> u8 {
    (k.clamp(0.0, 1.0) * 255.0).round() as u8
}

struct Ctx<'a> {
    bvh: &'a TriBvh,
    normals: &'a [Vec3],
    lamps: &'a [Vec3],
    panes: &'a [Pane],
    /// Cosine-weighted directions around +Z.
    dirs: Vec<Vec3>,
}

/// Fixed cosine-weighted hemisphere directions around +Z (a Hammersley set).
fn hemisphere() -> Vec<Vec3> {
    (0..AO_RAYS)
        .map(|i| {
            let u = (i as f32 + 0.5) / AO_RAYS as f32;
            let v = (i as u32).reverse_bits() as f32 / 4_294_967_296.0;
            let r = u.sqrt();
            let phi = std::f32::consts::TAU * v;
            Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u).max(0.0).sqrt())
        })
        .collect()
}

impl Ctx<'_> {
    /// First hit along a ray: distance and whether it is a back face (the ray leaves a solid).
    fn hit(&self, o: Vec3, d: Vec3, t_max: f32) -> Option<(f32, bool)> {
        self.bvh
            .cast(o, d, t_max)
            .map(|(t, id)| (t, self.normals[id as usize].dot(d) > 0.0))
    }

    fn bake_part(&self, part: usize, m: &crate::geometry::TriMesh) -> Vec<[u8; 3]> {
        // A neighbour point inside the surface for every vertex: the centroid of the first
        // triangle using it (vertices of boxes that overlap, such as a floor under a wall or
        // the corner of two walls, lie inside the other solid and are moved out along it).
        let mut inward: Vec<Option<Vec3>> = vec![None; m.positions.len()];
        for t in &m.indices {
            let c = t
                .iter()
                .map(|&i| Vec3::from_array(m.positions[i as usize]))
                .sum::<Vec3>()
                / 3.0;
            for &i in t {
                inward[i as usize].get_or_insert(c);
            }
        }
        (0..m.positions.len())
            .map(|i| {
                let p = Vec3::from_array(m.positions[i]);
                let n = Vec3::from_array(m.normals[i]).normalize_or(Vec3::Y);
                let c = inward[i].unwrap_or(p);
                self.vertex(part, i, p, n, c)
            })
            .collect()
    }

    fn vertex(&self, part: usize, index: usize, p: Vec3, n: Vec3, inward: Vec3) -> [u8; 3] {
        let lift = n * 0.004;
        let mut s = p + lift;
        for f in [0.15, 0.35, 0.7, 0.98] {
            match self.hit(s, n, 1.0) {
                Some((_, true)) => s = p + (inward - p) * f + lift,
                _ => break,
            }
        }
        // Occlusion: cosine-weighted rays in a frame turned by a per-vertex hash.
        let h = hash(part as u32, index as u32);
        let (sin, cos) = (h as f32 / 4_294_967_296.0 * std::f32::consts::TAU).sin_cos();
        let t = n.any_orthonormal_vector();
        let b = n.cross(t);
        let (t, b) = (t * cos + b * sin, b * cos - t * sin);
        let occluded = |s: Vec3| {
            self.dirs
                .iter()
                .filter(|d| {
                    let dir = t * d.x + b * d.y + n * d.z;
                    self.bvh.occluded(s, dir, AO_REACH)
                })
                .count()
        };
        let mut blocked = occluded(s);
        // A corner buried in a neighbouring solid (a ceiling's corner inside the walls) sees
        // nothing: sample its face a little inwards instead.
        for f in [0.1, 0.25, 0.5] {
            if blocked < AO_RAYS {
                break;
            }
            s = p + (inward - p) * f + lift;
            blocked = occluded(s);
        }
        let ao = 1.0 - blocked as f32 / AO_RAYS as f32;
        // Direct light from every lamp in reach, two shadow rays each (a lamp is a small disc).
        let mut direct = 0.0;
        for lamp in self.lamps {
            let to = *lamp - s;
            let d2 = to.length_squared();
            if d2 > LAMP_REACH * LAMP_REACH {
                continue;
            }
            let cos_n = n.dot(to) / d2.sqrt();
            if cos_n <= 0.0 {
                continue;
            }
            let mut seen = 0.0;
            for off in [Vec3::new(0.12, 0.0, 0.05), Vec3::new(-0.12, 0.0, -0.05)] {
                let q = *lamp + off - s;
                let dist = q.length();
                if !self.bvh.occluded(s, q / dist, dist - 0.02) {
                    seen += 0.5;
                }
            }
            direct += seen * LAMP_POWER * cos_n / (d2 + LAMP_SOFT);
        }
        // Daylight: each pane in front of the vertex and facing it, two samples.
        for pane in self.panes {
            for q in pane.samples {
                let to = q - s;
                let d2 = to.length_squared();
                if d2 > DAY_REACH * DAY_REACH {
                    continue;
                }
                let dist = d2.sqrt();
                let dir = to / dist;
                let (cos_n, cos_p) = (n.dot(dir), -pane.normal.dot(dir));
                if cos_n <= 0.0 || cos_p <= 0.0 {
                    continue;
                }
                if !self.bvh.occluded(s, dir, dist - 0.02) {
                    direct += pane.power * cos_n * cos_p / (d2 + DAY_SOFT);
                }
            }
        }
        // Sky-ish ambient from above; faces looking down (ceilings, undersides) get the light
        // the lit floor and walls throw back up instead.
        let ambient = 0.17 + 0.06 * n.y + BOUNCE * (-n.y).max(0.0);
        let k = ao * ambient + (0.25 + 0.75 * ao) * direct;
        LAMP_TINT.map(|c| to_u8(k * c))
    }
}

fn hash(a: u32, b: u32) -> u32 {
    let mut h = a.wrapping_mul(0x9e37_79b1) ^ b.wrapping_mul(0x85eb_ca77);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^ (h >> 16)
}
