//! The CPU rasteriser backend: a plain software rasteriser for the few thousand triangles of a
//! home, several times faster than both the ray caster and wgpu on a software Vulkan driver.
//!
//! Per view: objects outside the frustum are skipped (bounding boxes), and so are runs of up to 32
//! consecutive triangles of an object (clusters, each with its own box) that are outside it or
//! whose projected box holds no pixel centre; the rest of the triangles go to camera space (a
//! cluster's triangles together, in lanes the compiler vectorises, which also reject those behind
//! the near plane, beside the view, too small to hold a pixel centre, or culled back faces:
//! `raster/lanes.rs`), are clipped against the near plane (and a wide guard band), projected with
//! vertices snapped to 1/4096 pixel, and filled with exact integer edge functions sampled at pixel
//! centres `(x + 0.5, y + 0.5)` under the top-left rule, so neighbouring triangles neither leave
//! cracks nor overlap. Depth is `1 / z` from the triangle's plane (linear in screen space) and is
//! kept in the depth buffer; a resolve pass turns it into metres along the optical axis and the
//! winning triangle into colour, class and object ids. Colour is the baked light of the triangle's
//! corners times its surface texture times its colour, in encoded space ([`SceneMesh::look`]): for
//! views with RGB, each visible triangle gets a slot with three attributes (light, texture u, v)
//! set up so that `attribute / depth` is linear in screen space; the resolve pass evaluates them at
//! the pixel from the depth buffer (perspective-correct, one division per pixel), fetches one byte
//! of texel and multiplies by the triangle's colour. The light is baked, so the per-pixel cost is
//! flat and small.
//!
//! Back faces are culled only where that cannot change the image: for objects whose triangles
//! form closed, outward-oriented surfaces, seen from outside their box (with room for the near
//! plane). Everything else is drawn two-sided, as the ray caster sees it.
//!
//! Objects are drawn nearest first (by distance from the eye to their box), each cluster filled
//! as soon as it is set up, and a coarse depth buffer (8x8 tiles, the farthest depth of each)
//! skips an object or cluster that cannot come nearer over its screen box: before set-up by
//! its box (projected rectangle, nearest corner), after set-up by its screen triangles. That
//! never changes the image. The fill of a view runs on one thread; its resolve (colour, depth,
//! ids) is split into bands of rows.
//! Span ends are walked down the rows with exact integer steps (no division per row).
//!
//! Views of a batch render in parallel (rayon); a batch smaller than twice the thread count
//! splits each view's resolve into bands of rows as well.
//!
//! The fill and the resolve are compiled twice on x86-64: for the baseline (SSE2) and with
//! AVX2, chosen at the first frame by what the CPU has (`raster/isa.rs`; [`ISA_VAR`] set
//! to `baseline` forces the first). Both give the same pixels, bit for bit.

use crate::camera::Camera;
use crate::error::{Result, SensorError};
use crate::frame::{Frame, View};
use crate::renderer::Renderer;
use crate::scene_mesh::SceneMesh;
use glam::{DVec3, Mat3, Vec3};
use rayon::prelude::*;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock, Weak};
use vlnverse_env::cache::{self, SharedLru};
use vlnverse_env::material::{Surface, TEX_SIZE};
use vlnverse_env::Aabb;

mod face_store;
mod faces;
mod isa;
mod lanes;
mod prepared;
mod unzstd;

use isa::Isa;
pub use isa::{copy_in_use, ISA_VAR};
use prepared::Prepared;
pub use prepared::{PREPARED_FILE, PREPARED_VERSION};

/// Every surface texture's grey part, encoded ([`Surface::luma_encoded`]), one after the other
/// ([`Surface::ALL`] order): made once and shared by every prepared scene.
fn surface_luma() -> &'static [u8] {
    static LUMA: OnceLock<Vec<u8>> = OnceLock::new();
    LUMA.get_or_init(|| {
        Surface::ALL
            .iter()
            .flat_map(|s| s.luma_encoded().iter().copied())
            .collect()
    })
}

/// Megabytes of prepared scenes kept by [`RasterScene::shared`] unless [`SCENE_CACHE_MB_VAR`]
/// says otherwise (a generated `vlnverse` home loaded from `raster.bin` holds about 3.5 MB, up
/// to about 12 MB once views have unpacked all its face textures: `cargo xtask bench --filter
/// home_switch`).
pub const SCENE_CACHE_MB: usize = 256;
/// Environment variable with the megabytes of prepared scenes kept by [`RasterScene::shared`]
/// (0: none).
pub const SCENE_CACHE_MB_VAR: &str = "VLNVERSE_RASTER_CACHE_MB";
/// The prepared scenes of [`RasterScene::shared_once`] by [`SceneMesh::content_key`]: weak
/// references, so a scene lives exactly while a renderer shows it.
type InUse = Vec<(u64, Weak<RasterScene>)>;

/// The scenes of [`RasterScene::shared_once`] in use, the dead ones dropped from the list.
fn scenes_in_use() -> std::sync::MutexGuard<'static, InUse> {
    static IN_USE: Mutex<InUse> = Mutex::new(Vec::new());
    let mut list = IN_USE
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    list.retain(|(_, w)| w.strong_count() > 0);
    list
}

/// Projected vertices stay within `[-guard, guard]` pixels (else they are clipped); `guard` is at
/// least this and twice the image size.
const MIN_GUARD: f32 = 8192.0;
/// Snapped coordinates `guard * sub` stay below `2^25` so that every edge function value is an
/// integer below `2^53`, exact in `f64`.
const MAX_FIXED: f64 = (1u64 << 25) as f64;
/// Fewest rows per band when a view is split between threads.
const MIN_BAND_ROWS: usize = 16;
/// Side in pixels of the square tiles of the coarse depth buffer used for occlusion culling.
const TILE: usize = 8;
/// Longest run of pixels of one triangle shaded at once by the RGB resolve.
const RUN: usize = 64;

/// Most triangles in a cluster: a run of consecutive triangles of one object with its own box,
/// culled as a whole against the view (frustum, and whether it can cover a pixel centre).
const CLUSTER: usize = 32;

/// Grid in metres on which [`closed_outward`] compares corners (2^-16 m, about 15 micrometres:
/// far below any edge of a home's meshes, far above the rounding error of a corner).
const WELD: f64 = 1.0 / 65536.0;

/// Pixels in the box of a triangle small enough that [`emit`] tests their centres before
/// setting it up for the fill.
const SMALL_BOX: i64 = 4;

/// Attributes interpolated over a triangle: encoded light, texture u, v.
const ATTRS: usize = 3;

/// How a triangle's look varies over it: corner 0 and the vectors giving the barycentric
/// weights of corners 1 and 2 of a point `q` on its plane (`(q - a) . wu`, `(q - a) . wv`),
/// and the attributes (encoded light, texture u, v) at corner 0 and their changes towards
/// corners 1 and 2.
#[derive(Clone, Copy, Debug)]
struct Look {
    a: Vec3,
    wu: Vec3,
    wv: Vec3,
    at: [f32; ATTRS],
    du: [f32; ATTRS],
    dv: [f32; ATTRS],
    /// First texel of the surface texture in [`RasterScene::texels`] (or the face texture's
    /// index in [`RasterScene::faces`], or the image's first texel).
    tex: u32,
    /// Encoded colour ([`crate::scene_mesh::TriLook::tone`]) scaled so that
    /// `tone x light x texel byte` is the output byte.
    tone: [f32; 3],
    /// How the texel is found.
    kind: Kind,
}

/// Where a triangle's pixels take their texel from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Light interpolated from the corners times a repeating surface texture.
    Tiled,
    /// A face texture of `w x h` texels holding light times texture (light attribute unused).
    Face { w: u32, h: u32 },
    /// Light interpolated from the corners times an imported RGB image of `w x h` texels
    /// (powers of two) in [`RasterScene::image_texels`], repeating.
    Image { w: u32, h: u32 },
}

/// A visible triangle of one view: attribute `k` times `1 / depth` at pixel `(x, y)` is
/// `k[k][0] x + k[k][1] y + k[k][2]`.
#[derive(Clone, Copy, Debug)]
struct Slot {
    k: [[f32; 3]; ATTRS],
    tex: u32,
    tone: [f32; 3],
    kind: Kind,
}

/// An object's triangle range and whether its back faces may be culled.
#[derive(Clone, Copy, Debug)]
struct ObjInfo {
    count: usize,
    bbox: Aabb,
    /// Closed, outward-oriented surfaces only.
    closed: bool,
    /// Its clusters: `clusters[c0..c1]` of [`RasterScene::clusters`].
    c0: u32,
    c1: u32,
}

/// Consecutive draw triangles `first..end` of one object and the box of their corners.
#[derive(Clone, Copy, Debug)]
struct Cluster {
    first: u32,
    end: u32,
    bbox: Aabb,
    /// Its corners and normals, one row per corner and coordinate:
    /// `RasterScene::lanes[b0..b1]` ([`lanes::pack`]).
    b0: u32,
    b1: u32,
}

/// A scene prepared for the rasteriser (built once per [`Renderer::set_scene`]).
#[derive(Debug)]
pub struct RasterScene {
    /// The mesh it was prepared from, not kept alive by it (drawing needs none of it): a kept
    /// scene holds only what it draws, and [`RasterScene::shared`] still finds it by its mesh
    /// while the mesh lives.
    mesh: Weak<SceneMesh>,
    /// Class and object id of each tag (`2 * triangle + back + 1`; 0 for tag 0).
    tag_class: Vec<u16>,
    tag_object: Vec<u32>,
    /// Look of each triangle.
    look: Vec<Look>,
    /// Every surface texture's grey part, encoded ([`Surface::luma_encoded`]), one after the
    /// other ([`Surface::ALL`] order); tints are in the triangle colours. Shared.
    texels: &'static [u8],
    /// The triangles drawn (the mesh's, with faces cut into cells merged back); their corners
    /// and faces are dropped once the clusters' blocks and the looks hold them, their face
    /// textures are in `faces`.
    draw: faces::DrawMesh,
    /// The merged faces' textures (kept as stored when loaded: unpacked when first drawn).
    faces: face_store::FaceTexels,
    /// Every imported image ([`SceneMesh::images`]), texels packed as `r | g << 8 | b << 16`.
    image_texels: Vec<u32>,
    /// Every cluster's corners and unit geometric normals (as [`SceneMesh::normal`]), one
    /// row per corner and coordinate ([`lanes::pack`]), as the lanes read them.
    lanes: Vec<f32>,
    objects: Vec<ObjInfo>,
    /// Every object's triangles in runs of at most [`CLUSTER`], object by object.
    clusters: Vec<Cluster>,
    /// Whether clusters are culled (off only in tests that compare against drawing them all).
    cull_clusters: bool,
}

/// Reused depth and id buffers of views that do not return them (saves page faults), shared
/// by every prepared scene so that scenes kept in the cache hold none.
static SPARE_Z: Mutex<Vec<Vec<f32>>> = Mutex::new(Vec::new());
static SPARE_IDS: Mutex<Vec<Vec<u32>>> = Mutex::new(Vec::new());
/// Reused set-up lists of finished views (a big home's lists take a fresh allocation, and so
/// page faults, in every view otherwise).
static SPARE_SETUP: Mutex<Vec<Setup>> = Mutex::new(Vec::new());

/// Take a buffer from a pool (or a new one) holding `n` copies of `v`.
fn take<T: Copy>(pool: &Mutex<Vec<Vec<T>>>, n: usize, v: T) -> Vec<T> {
    let mut b = pool
        .lock()
        .ok()
        .and_then(|mut p| p.pop())
        .unwrap_or_default();
    b.clear();
    b.resize(n, v);
    b
}

/// Return a buffer to a pool (a few per thread are plenty).
fn give<T>(pool: &Mutex<Vec<Vec<T>>>, b: Vec<T>) {
    if let Ok(mut p) = pool.lock() {
        if p.len() < 16 {
            p.push(b);
        }
    }
}

/// One edge function `e(x, y) = a x + b y + c` over pixel indices; a pixel is inside when
/// `e >= 0`. Values are integers in sub-pixel units (below `2^53`).
#[derive(Clone, Copy, Debug)]
struct Edge {
    a: i64,
    b: i64,
    c: i64,
}

/// A sloped edge's bound on the span of each row, walked down the rows with exact integer
/// steps instead of a division per row: `x` is the first (a left edge, `a > 0`) or last (a
/// right edge, `a < 0`) inside pixel of the current row, and `r = e(x, y)`, in `[0, |a|)`.
/// (A horizontal edge bounds the rows instead: [`raster`].)
#[derive(Clone, Copy, Debug)]
struct Walk {
    x: i64,
    r: i64,
    /// `|a|`, `b mod |a|` and `dir * floor(b / |a|)` (`dir`: -1 for a left edge, 1 for a
    /// right one).
    a: i64,
    br: i64,
    dq: i64,
}

impl Walk {
    /// A bound that never binds: its `x` stays at `x` and nothing carries.
    const NONE: Walk = Walk {
        x: 0,
        r: 0,
        a: i64::MAX,
        br: 0,
        dq: 0,
    };

    /// Start at row `y` (`e.a != 0`); with `steps`, ready to step down the rows (without, it
    /// stays on row `y`: one division instead of two).
    #[inline(always)]
    fn new(e: &Edge, y: i64, steps: bool) -> Walk {
        let er = e.b * y + e.c;
        let (a, dir) = if e.a > 0 { (e.a, -1) } else { (-e.a, 1) };
        // a > 0: first x with a x + er >= 0 is ceil(-er / a) = -floor(er / a);
        // a < 0: last x with er - |a| x >= 0 is floor(er / |a|). Either way r = er mod |a|.
        let f = er.div_euclid(a);
        let (br, dq) = if steps {
            (e.b.rem_euclid(a), dir * e.b.div_euclid(a))
        } else {
            (0, 0)
        };
        Walk {
            x: dir * f,
            r: er.rem_euclid(a),
            a,
            br,
            dq,
        }
    }

    /// Move to the next row (`DIR`: -1 for a left edge, 1 for a right one; branch-free:
    /// whether `r` carries past `|a|` is data, not pattern).
    #[inline(always)]
    fn step<const DIR: i64>(&mut self) {
        self.r += self.br;
        let carry = i64::from(self.r >= self.a);
        self.x += self.dq + DIR * carry;
        self.r -= carry * self.a;
    }
}

/// A projected triangle ready to fill.
#[derive(Clone, Copy, Debug)]
struct ScreenTri {
    edges: [Edge; 3],
    /// Inclusive pixel bounds (clamped to the image).
    x0: i32,
    x1: i32,
    y0: i32,
    y1: i32,
    /// `1 / depth` at the centre of pixel `(x, y)` is `za x + zb y + zc`, clamped to
    /// `[zlo, zhi]` (the range over the corners) against snapping error.
    za: f32,
    zb: f32,
    zc: f32,
    zlo: f32,
    zhi: f32,
    /// `2 * triangle + back + 1` (0 is nothing).
    tag: u32,
}

/// The screen triangles of one cluster: their inclusive pixel bounds and the largest
/// `1 / depth` any of them can write (each clamps to its `zhi`).
#[derive(Clone, Copy, Debug)]
struct Group {
    x0: i32,
    x1: i32,
    y0: i32,
    y1: i32,
    zmax: f32,
}

/// What set-up leaves of one view once it has drawn it (see [`RasterScene::setup`]). Views with
/// RGB write slot numbers (`slot + 1`) instead of tags; `slot_tag` maps them back.
#[derive(Default)]
struct Setup {
    /// Scratch list of one cluster's screen triangles (kept for its allocation).
    tris: Vec<ScreenTri>,
    slots: Vec<Slot>,
    slot_tag: Vec<u32>,
    /// Class of each slot number (`slot_class[0]`: nothing), for the semantic image written
    /// run by run with the colour.
    slot_class: Vec<u16>,
    /// Clusters culled whole (what the tests check culling against).
    #[cfg_attr(not(test), allow(dead_code))]
    culled: usize,
    /// Of those, clusters culled as hidden behind what was drawn before them.
    #[cfg_attr(not(test), allow(dead_code))]
    occluded: usize,
}

/// Per-view constants.
struct ViewParams {
    w: usize,
    h: usize,
    fx: f32,
    fy: f32,
    cx: f32,
    cy: f32,
    near: f32,
    far: f32,
    /// Guard band half-width in pixels and sub-pixel steps per pixel (a power of two).
    guard: f32,
    sub: f64,
    /// World to camera rotation and the camera position.
    rot: Mat3,
    pos: Vec3,
}

impl ViewParams {
    fn new(c: &Camera) -> Self {
        let guard = MIN_GUARD.max(2.0 * c.width.max(c.height) as f32);
        ViewParams {
            w: c.width as usize,
            h: c.height as usize,
            fx: c.fx(),
            fy: c.fy(),
            cx: c.cx(),
            cy: c.cy(),
            near: c.near,
            far: c.far,
            guard,
            sub: (MAX_FIXED / guard as f64).log2().floor().exp2(),
            rot: Mat3::from_quat(c.rotation.normalize()).transpose(),
            pos: c.position,
        }
    }

    /// A world point in camera space (what the lanes and [`screen_box`] compute, written out).
    #[cfg(test)]
    fn to_camera(&self, p: Vec3) -> Vec3 {
        self.rot * (p - self.pos)
    }

    /// Pixel coordinates (continuous) of a camera-space point in front of the camera.
    #[inline(always)]
    fn project(&self, p: Vec3) -> (f32, f32, f32) {
        let iz = 1.0 / -p.z;
        (
            self.cx + self.fx * p.x * iz,
            self.cy - self.fy * p.y * iz,
            iz,
        )
    }

    /// Clip planes `f(p) >= 0` inside, in camera space: near, then the guard band.
    fn plane(&self, k: usize, p: Vec3) -> f32 {
        let (x, y, z) = (p.x, p.y, p.z);
        match k {
            0 => -z - self.near,
            1 => self.fx * x - (self.guard + self.cx) * z,
            2 => (self.guard - self.cx) * -z - self.fx * x,
            3 => (self.guard + self.cy) * -z - self.fy * y,
            _ => self.fy * y + (self.cy - self.guard) * z,
        }
    }
}

/// A convex polygon being clipped (a triangle cut by up to five planes).
#[derive(Clone, Copy)]
struct Poly {
    v: [Vec3; 9],
    n: usize,
}

impl RasterScene {
    /// Prepare a mesh: the triangles to draw (cut faces merged, with their face textures),
    /// per-triangle looks, ids, and which objects are closed surfaces.
    pub fn new(mesh: Arc<SceneMesh>) -> Self {
        let p = Self::prepare(&mesh);
        Self::from_parts(mesh, p)
    }

    /// The part of the preparation that costs, and that [`PREPARED_FILE`] stores: merged faces
    /// with their face textures, and which objects are closed surfaces.
    fn prepare(mesh: &SceneMesh) -> Prepared {
        let mut draw = faces::build(mesh, surface_luma());
        // `build` lays the faces out one after the other: they always tile the texels.
        let spans = prepared::face_spans(&draw).unwrap_or_default();
        let origin = std::mem::take(&mut draw.origin);
        let faces = face_store::FaceTexels::raw(std::mem::take(&mut draw.texels), &spans, &origin);
        // Closed surfaces are judged on the mesh's own triangles (merged faces meet their
        // neighbours' cells at T-junctions, but bound the same solid).
        let closed = mesh
            .objects
            .iter()
            .map(|o| {
                let (f, n) = (o.first as usize, o.count as usize);
                closed_outward(&mesh.positions[3 * f..3 * (f + n)])
            })
            .collect();
        Prepared {
            draw,
            closed,
            faces,
        }
    }

    /// [`RasterScene::new`], the merged faces and face textures read from a prepared file
    /// ([`RasterScene::write_prepared`]) instead of computed: the same scene, for a small part
    /// of the time. Refused, naming the file and what is wrong, when the file is not one,
    /// is damaged, or was prepared from another mesh or with other surface textures.
    pub fn load_prepared(mesh: Arc<SceneMesh>, file: &Path) -> Result<Self> {
        let key = mesh.content_key();
        Self::load_prepared_keyed(mesh, key, file)
    }

    /// [`RasterScene::load_prepared`] for a mesh whose [`SceneMesh::content_key`] is `key`
    /// (hashing a home's mesh costs about as much as triangulating it).
    fn load_prepared_keyed(mesh: Arc<SceneMesh>, key: u64, file: &Path) -> Result<Self> {
        let bytes = std::fs::read(file)
            .map_err(|e| SensorError::from(vlnverse_env::EnvError::io(file, e)))?;
        let p = prepared::decode(&bytes, &mesh, key, surface_luma()).map_err(|message| {
            SensorError::Scene {
                scene: mesh.scene_id.clone(),
                message: format!("prepared scene {}: {message}", file.display()),
            }
        })?;
        Ok(Self::from_parts(mesh, p))
    }

    /// The scene for `mesh`: loaded from [`SceneMesh::prepared_file`] when it names a file
    /// that exists, else prepared afresh ([`RasterScene::new`]). A file that cannot be used
    /// (damaged, or stale: made from another mesh) is reported as a warning and the scene
    /// prepared afresh, so the images never depend on the file.
    pub fn load_or_new(mesh: Arc<SceneMesh>) -> Self {
        Self::load_or_new_keyed(mesh, None)
    }

    /// [`RasterScene::load_or_new`], with the mesh's [`SceneMesh::content_key`] when known.
    fn load_or_new_keyed(mesh: Arc<SceneMesh>, key: Option<u64>) -> Self {
        if let Some(file) = mesh.prepared_file.as_ref().filter(|f| f.is_file()) {
            let key = key.unwrap_or_else(|| mesh.content_key());
            match Self::load_prepared_keyed(mesh.clone(), key, file) {
                Ok(s) => return s,
                Err(e) => tracing::warn!("{e}; preparing the scene afresh"),
            }
        }
        Self::new(mesh)
    }

    /// Prepare `mesh` and write what [`RasterScene::load_prepared`] reads back: the merged
    /// faces, their face textures and which objects are closed, keyed to the mesh and the
    /// surface textures (written to a temporary file first, then renamed).
    pub fn write_prepared(mesh: &SceneMesh, file: &Path) -> Result<()> {
        let err = |message: String| SensorError::Write {
            path: file.to_path_buf(),
            message,
        };
        let p = Self::prepare(mesh);
        let bytes =
            prepared::encode(&p.draw, &p.faces, &p.closed, mesh, surface_luma()).map_err(err)?;
        let tmp = file.with_extension("bin.tmp");
        let err = |e: std::io::Error| err(e.to_string());
        std::fs::write(&tmp, &bytes).map_err(err)?;
        std::fs::rename(&tmp, file).map_err(err)
    }

    /// Prepare `scene` (its mesh with the light it was baked with) and write it to
    /// [`PREPARED_FILE`] in `scene_dir`, the scene's folder; returns the file. Generation
    /// calls it after writing the folder, so that loading the home costs no preparation.
    pub fn write_prepared_scene(
        scene: &vlnverse_env::Scene,
        scene_dir: &Path,
    ) -> Result<std::path::PathBuf> {
        let file = scene_dir.join(PREPARED_FILE);
        RasterScene::write_prepared(&SceneMesh::new(scene)?, &file)?;
        Ok(file)
    }

    /// The rest of the preparation, from the merged faces: looks, clusters, ids.
    fn from_parts(mesh: Arc<SceneMesh>, p: Prepared) -> Self {
        let Prepared {
            mut draw,
            closed,
            faces: face_texels,
        } = p;
        // Face texture `i` of `face_texels` by its first texel.
        let face_base: Vec<u32> = prepared::face_spans(&draw)
            .unwrap_or_default()
            .into_iter()
            .map(|f| f.base)
            .collect();
        let texels = surface_luma();
        let n_tri = mesh.triangle_count();
        let mut image_texels = Vec::new();
        let image_base: Vec<u32> = mesh
            .images
            .iter()
            .map(|im| {
                let base = image_texels.len() as u32;
                image_texels.extend(
                    im.texels
                        .iter()
                        .map(|[r, g, b]| *r as u32 | (*g as u32) << 8 | (*b as u32) << 16),
                );
                base
            })
            .collect();
        let n_draw = draw.src.len();
        let mut normal = Vec::with_capacity(n_draw);
        let mut look = Vec::with_capacity(n_draw);
        for d in 0..n_draw {
            let t = draw.src[d] as usize;
            let [a, b, c] = [0, 1, 2].map(|k| draw.pos[3 * d + k]);
            normal.push((b - a).cross(c - a).normalize_or(Vec3::Y));
            let (e1, e2) = (b - a, c - a);
            let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
            let den = d00 * d11 - d01 * d01;
            let (wu, wv) = if den.abs() > 1e-20 {
                ((e1 * d11 - e2 * d01) / den, (e2 * d00 - e1 * d01) / den)
            } else {
                (Vec3::ZERO, Vec3::ZERO)
            };
            let l = mesh.look.get(t);
            let face = draw.face[d];
            let attr = |k: usize| -> [f32; ATTRS] {
                match (face, l) {
                    (Some((_, uv)), _) => [1.0, uv[k][0], uv[k][1]],
                    (None, Some(l)) => [l.light[k], l.uv[k][0], l.uv[k][1]],
                    (None, None) => [1.0, 0.0, 0.0],
                }
            };
            // Bytes: tone x light x texel byte (255 = 1) is the output byte.
            let tone = match l {
                Some(l) => l.tone,
                None => mesh.color[t].map(|c| c.clamp(0.0, 1.0).powf(1.0 / 2.2)),
            };
            let (a0, a1, a2) = (attr(0), attr(1), attr(2));
            let image = l
                .and_then(|l| l.image)
                .and_then(|i| Some((*image_base.get(i as usize)?, mesh.images.get(i as usize)?)))
                .filter(|(_, im)| im.width.is_power_of_two() && im.height.is_power_of_two());
            let (tex, kind) = match (face, image) {
                (Some((f, _)), _) => (
                    face_base.binary_search(&f.base).unwrap_or(usize::MAX) as u32,
                    Kind::Face { w: f.w, h: f.h },
                ),
                (None, Some((base, im))) => (
                    base,
                    Kind::Image {
                        w: im.width,
                        h: im.height,
                    },
                ),
                (None, None) => (
                    (l.map_or(Surface::Plain, |l| l.surface).index() * TEX_SIZE * TEX_SIZE) as u32,
                    Kind::Tiled,
                ),
            };
            look.push(Look {
                a,
                wu,
                wv,
                at: a0,
                du: [0, 1, 2].map(|k| a1[k] - a0[k]),
                dv: [0, 1, 2].map(|k| a2[k] - a0[k]),
                tex,
                tone,
                kind,
            });
        }
        let mut clusters = Vec::new();
        // Exactly the blocks' length.
        let mut packed = Vec::with_capacity(
            draw.objects
                .iter()
                .map(|&(_, count, _)| {
                    (count / CLUSTER) * lanes::block_len(CLUSTER)
                        + lanes::block_len(count % CLUSTER)
                })
                .sum(),
        );
        let objects = closed
            .iter()
            .zip(&draw.objects)
            .map(|(&closed, &(first, count, bbox))| {
                let c0 = clusters.len() as u32;
                for s in (first..first + count).step_by(CLUSTER) {
                    let end = (s + CLUSTER).min(first + count);
                    let mut b = Aabb::EMPTY;
                    draw.pos[3 * s..3 * end].iter().for_each(|p| b.extend(*p));
                    let b0 = packed.len() as u32;
                    lanes::pack(&draw.pos[3 * s..3 * end], &normal[s..end], &mut packed);
                    clusters.push(Cluster {
                        first: s as u32,
                        end: end as u32,
                        bbox: b,
                        b0,
                        b1: packed.len() as u32,
                    });
                }
                ObjInfo {
                    count,
                    bbox,
                    closed,
                    c0,
                    c1: clusters.len() as u32,
                }
            })
            .collect();
        // The looks hold what the merged faces gave (face texture and its coordinates), the
        // clusters' blocks the corners.
        draw.face = Vec::new();
        draw.pos = Vec::new();
        let class = |t: usize| mesh.class(mesh.object[t]);
        let mut tag_class = Vec::with_capacity(2 * n_tri + 1);
        tag_class.push(0);
        tag_class.extend((0..n_tri).flat_map(|t| [class(t); 2]));
        let mut tag_object = Vec::with_capacity(2 * n_tri + 1);
        tag_object.push(0);
        tag_object.extend((0..n_tri).flat_map(|t| [mesh.object[t]; 2]));
        RasterScene {
            tag_class,
            tag_object,
            look,
            texels,
            draw,
            faces: face_texels,
            image_texels,
            mesh: Arc::downgrade(&mesh),
            lanes: packed,
            objects,
            clusters,
            cull_clusters: true,
        }
    }

    /// The mesh it was prepared from, while something else keeps it alive (a prepared scene
    /// does not).
    pub fn mesh(&self) -> Option<Arc<SceneMesh>> {
        self.mesh.upgrade()
    }

    /// Number of triangles drawn (the mesh's, with faces cut into cells merged back).
    pub fn drawn_triangles(&self) -> usize {
        self.draw.src.len()
    }

    /// Bytes of the face textures of the merged faces, unpacked (one per texel).
    pub fn face_texture_bytes(&self) -> usize {
        self.faces.texel_count()
    }

    /// Bytes held now (allocated, not only used): drawn triangles, looks, face textures as
    /// held (a loaded scene keeps the larger ones packed until a view draws them) and images
    /// (not the mesh, which it does not keep: [`SceneMesh::bytes`]).
    pub fn bytes(&self) -> usize {
        self.bytes_besides_faces() + self.faces.held()
    }

    /// Bytes held once every face texture is unpacked.
    pub fn bytes_at_most(&self) -> usize {
        self.bytes_besides_faces() + self.faces.held_at_most()
    }

    fn bytes_besides_faces(&self) -> usize {
        use crate::scene_mesh::held;
        let d = &self.draw;
        // The mesh's own block stays allocated while a weak reference to it lives.
        std::mem::size_of::<Self>()
            + std::mem::size_of::<SceneMesh>()
            + held(&d.pos)
            + held(&d.src)
            + held(&d.face)
            + held(&d.objects)
            + held(&d.texels)
            + held(&self.image_texels)
            + held(&self.look)
            + held(&self.lanes)
            + held(&self.objects)
            + held(&self.clusters)
            + held(&self.tag_class)
            + held(&self.tag_object)
    }

    /// [`RasterScene::load_or_new`], shared: a mesh prepared a moment ago (same
    /// [`SceneMesh::content_key`]) is taken from a process-wide cache of up to
    /// [`SCENE_CACHE_MB_VAR`] megabytes (default [`SCENE_CACHE_MB`]), so environments that keep
    /// loading the same homes prepare each once.
    pub fn shared(mesh: Arc<SceneMesh>) -> Arc<Self> {
        static CACHE: OnceLock<SharedLru<RasterScene>> = OnceLock::new();
        let cache = CACHE.get_or_init(|| {
            cache::shared_lru(cache::budget_from_env(SCENE_CACHE_MB_VAR, SCENE_CACHE_MB))
        });
        Self::shared_in(cache, mesh)
    }

    /// [`RasterScene::load_or_new`] for users that do not come back to a home once they left
    /// it (an evaluation runs a split in scene order): renderers in one home share one
    /// prepared scene, and a scene no renderer shows any more is dropped, not kept for later.
    /// What is held is the homes in use, however many homes pass. The same scene as
    /// [`RasterScene::shared`] gives.
    pub fn shared_once(mesh: Arc<SceneMesh>) -> Arc<Self> {
        /// The first scene of `list` still alive for which `hit` holds.
        fn live(list: &InUse, hit: impl Fn(u64, &RasterScene) -> bool) -> Option<Arc<RasterScene>> {
            list.iter()
                .filter_map(|(k, w)| w.upgrade().map(|s| (*k, s)))
                .find(|(k, s)| hit(*k, s))
                .map(|(_, s)| s)
        }
        if let Some(s) = live(&scenes_in_use(), |_, s| s.is_of(&mesh)) {
            return s;
        }
        // One scene made at a time, outside the in-use list's lock: renderers entering a home
        // together (an evaluation's workers) wait for the first one's instead of each making
        // and holding a copy.
        static MAKING: Mutex<()> = Mutex::new(());
        let _making = MAKING
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let key = mesh.content_key();
        if let Some(s) = live(&scenes_in_use(), |k, _| k == key) {
            return s;
        }
        let made = Arc::new(RasterScene::load_or_new_keyed(mesh, Some(key)));
        scenes_in_use().push((key, Arc::downgrade(&made)));
        made
    }

    /// Prepared scenes of [`RasterScene::shared_once`] alive now.
    #[cfg(test)]
    fn in_use_count() -> usize {
        scenes_in_use().len()
    }

    /// Whether this scene was prepared from this very mesh (environments sharing one loaded
    /// home): no need to hash it. A scene's weak reference keeps its mesh's block allocated
    /// even after the mesh is dropped, so no other mesh can be at that address while the scene
    /// lives.
    fn is_of(&self, mesh: &Arc<SceneMesh>) -> bool {
        std::ptr::eq(self.mesh.as_ptr(), Arc::as_ptr(mesh))
    }

    /// A prepared scene of `mesh` from `cache`, prepared (or loaded) and kept there if missing.
    fn shared_in(cache: &SharedLru<RasterScene>, mesh: Arc<SceneMesh>) -> Arc<Self> {
        let same = |s: &RasterScene| s.is_of(&mesh);
        // Kept scenes grow as views unpack their face textures: accounted by what they hold
        // now on every visit, a hit too (a working set of hits alone would outgrow the budget).
        if let Some(hit) = cache.lock().ok().and_then(|mut c| {
            let hit = c.find(same);
            c.remeasure(RasterScene::bytes);
            hit
        }) {
            return hit;
        }
        let key = mesh.content_key();
        cache::get_or_insert(
            cache,
            key,
            || RasterScene::load_or_new_keyed(mesh, Some(key)),
            RasterScene::bytes,
        )
    }

    /// Number of objects whose back faces may be culled (closed, outward-oriented surfaces).
    pub fn closed_objects(&self) -> usize {
        self.objects.iter().filter(|o| o.closed).count()
    }

    /// Render one view on the calling thread's rayon pool, split into `bands` bands of rows
    /// (1 = no split).
    pub fn render_view(&self, view: &View, bands: usize) -> Frame {
        self.render_view_on(Isa::detect(), view, bands)
    }

    /// [`Self::render_view`] with the copy `isa` of the fill and resolve (`raster/isa.rs`);
    /// the buffers are set up in that copy too.
    #[allow(unsafe_code)] // a function built for CPU features; see the SAFETY note
    fn render_view_on(&self, isa: Isa, view: &View, bands: usize) -> Frame {
        match isa {
            Isa::Baseline => self.render_view_in(isa, view, bands),
            // SAFETY: as in `setup_on`.
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2(_) => unsafe { self.render_view_avx2(isa, view, bands) },
        }
    }

    /// [`Self::render_view_in`] built with AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    fn render_view_avx2(&self, isa: Isa, view: &View, bands: usize) -> Frame {
        self.render_view_in(isa, view, bands)
    }

    /// The body of [`Self::render_view_on`]: buffers, fill, resolve in bands.
    #[inline(always)]
    fn render_view_in(&self, isa: Isa, view: &View, bands: usize) -> Frame {
        let c = &view.camera;
        let p = ViewParams::new(c);
        let (w, h) = (p.w, p.h);
        let n = w * h;
        let ch = view.channels;
        let ids_needed = ch.rgb || ch.ids();
        let inv_far = 1.0 / p.far;
        let mut zbuf = if ch.depth {
            vec![inv_far; n]
        } else {
            take(&SPARE_Z, n, inv_far)
        };
        let mut ids = match (ids_needed, ch.instance) {
            (false, _) => Vec::new(),
            (true, true) => vec![0u32; n],
            (true, false) => take(&SPARE_IDS, n, 0),
        };
        let ids_out = ids_needed.then_some(&mut ids[..]);
        let tris = self.setup_on(isa, c, &p, ch.rgb, &mut zbuf, ids_out);
        let mut rgb = if ch.rgb { vec![0u8; 3 * n] } else { Vec::new() };
        let mut sem = if ch.semantic {
            vec![0u16; n]
        } else {
            Vec::new()
        };
        let rows = h.div_ceil(bands.clamp(1, h.div_ceil(MIN_BAND_ROWS).max(1)));
        let mut work: Vec<Band<'_>> = Vec::with_capacity(h.div_ceil(rows));
        {
            let mut z = zbuf.chunks_mut(rows * w);
            let mut i = ids.chunks_mut(rows * w);
            let mut r = rgb.chunks_mut(3 * rows * w);
            let mut s = sem.chunks_mut(rows * w);
            for y0 in (0..h).step_by(rows) {
                work.push(Band {
                    y0,
                    zbuf: z.next().unwrap_or_default(),
                    ids: i.next(),
                    rgb: r.next(),
                    semantic: s.next(),
                });
            }
        }
        let run = |b: Band<'_>| self.resolve_band_on(isa, &p, &tris, b, ch.depth, ch.instance);
        if work.len() == 1 {
            work.into_iter().for_each(run);
        } else {
            work.into_par_iter().for_each(run);
        }
        if let Ok(mut pool) = SPARE_SETUP.lock() {
            if pool.len() < 16 {
                pool.push(tris);
            }
        }
        let depth = if ch.depth {
            zbuf
        } else {
            give(&SPARE_Z, zbuf);
            Vec::new()
        };
        let instance = if ch.instance {
            ids
        } else {
            if ids_needed {
                give(&SPARE_IDS, ids);
            }
            Vec::new()
        };
        Frame {
            width: c.width,
            height: c.height,
            rgb,
            depth,
            semantic: sem,
            instance,
        }
    }

    /// [`Self::setup`] in the copy `isa`. Called from the view's body, which may already run in
    /// that copy: inlining the fill there instead drew ~8 % fewer frames (one pose, generated
    /// home), so it keeps an entry point of its own.
    #[allow(unsafe_code)] // a function built for CPU features; see the SAFETY note
    fn setup_on(
        &self,
        isa: Isa,
        c: &Camera,
        p: &ViewParams,
        shade: bool,
        zbuf: &mut [f32],
        ids: Option<&mut [u32]>,
    ) -> Setup {
        match isa {
            Isa::Baseline => self.setup(c, p, shade, zbuf, ids),
            // SAFETY: an `Isa::Avx2` exists only on a CPU with every feature `setup_avx2` is built
            // for (`Isa::widest`).
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2(_) => unsafe { self.setup_avx2(c, p, shade, zbuf, ids) },
        }
    }

    /// [`Self::setup`] built with AVX2 (the same pixels, 8-wide lanes).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    fn setup_avx2(
        &self,
        c: &Camera,
        p: &ViewParams,
        shade: bool,
        zbuf: &mut [f32],
        ids: Option<&mut [u32]>,
    ) -> Setup {
        self.setup(c, p, shade, zbuf, ids)
    }

    /// Cull, clip, project and fill every triangle that may be seen into `zbuf` (and `ids`),
    /// object by object, nearest objects (by distance from the eye to their box) first; each
    /// cluster is filled as soon as it is set up, so that an object or cluster whose box, at
    /// its nearest depth, lies behind the coarse depth of what was drawn so far is skipped
    /// before any of its triangles is transformed (occlusion culling; exact: the depth test
    /// would have let none of its pixels through).
    #[inline(always)]
    fn setup(
        &self,
        c: &Camera,
        p: &ViewParams,
        shade: bool,
        zbuf: &mut [f32],
        mut ids: Option<&mut [u32]>,
    ) -> Setup {
        let frustum = c.frustum();
        // Distance from the eye to the near plane's corners: a back face may be culled only
        // when no part of the near plane can be inside the object.
        let reach =
            p.near * (1.0 + (p.cx / p.fx).powi(2) + (p.cy / p.fy).powi(2)).sqrt() * 1.001 + 1e-4;
        // A loop rather than `filter` and `map` closures, which the AVX2 copy would call out
        // of line (`raster/isa.rs`).
        let mut order: Vec<(f32, usize)> = Vec::with_capacity(self.objects.len());
        for (i, o) in self.objects.iter().enumerate() {
            if o.count > 0 && frustum.intersects_aabb(&o.bbox) {
                let q = p.pos.clamp(o.bbox.min_v(), o.bbox.max_v());
                order.push((q.distance_squared(p.pos), i));
            }
        }
        // Ties (and NaN-free keys) broken by object index: the order is deterministic.
        order.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let spare = SPARE_SETUP
            .lock()
            .ok()
            .and_then(|mut p| p.pop())
            .unwrap_or_default();
        let (mut out, mut slots, mut slot_tag) = (spare.tris, spare.slots, spare.slot_tag);
        out.clear();
        slots.clear();
        slot_tag.clear();
        let (mut culled, mut occluded) = (0, 0);
        if shade {
            slot_tag.push(0);
        }
        let mut coarse = Coarse::new(p.w, p.h, 1.0 / p.far);
        let mut lanes = lanes::Lanes::new();
        for &(_, oi) in &order {
            let o = &self.objects[oi];
            let cull = o.closed && {
                let (lo, hi) = (o.bbox.min_v() - reach, o.bbox.max_v() + reach);
                !(p.pos.cmpge(lo).all() && p.pos.cmple(hi).all())
            };
            let several = o.c1 > o.c0 + 1;
            // The whole object hidden behind what was drawn so far.
            if self.cull_clusters && several {
                if let Reach::Box {
                    x0,
                    x1,
                    y0,
                    y1,
                    zmax,
                } = screen_box(p, &o.bbox)
                {
                    if coarse.hidden(zbuf, x0, x1, y0, y1, zmax) {
                        culled += (o.c1 - o.c0) as usize;
                        occluded += (o.c1 - o.c0) as usize;
                        continue;
                    }
                }
            }
            for c in &self.clusters[o.c0 as usize..o.c1 as usize] {
                if self.cull_clusters {
                    // The box's screen rectangle first: when the box is in front of the near
                    // plane, it also tells whether the box is beside the view.
                    let hidden = match screen_box(p, &c.bbox) {
                        Reach::Near => several && !frustum.intersects_aabb(&c.bbox),
                        Reach::Nothing => true,
                        Reach::Box {
                            x0,
                            x1,
                            y0,
                            y1,
                            zmax,
                        } => {
                            let h = coarse.hidden(zbuf, x0, x1, y0, y1, zmax);
                            occluded += h as usize;
                            h
                        }
                    };
                    if hidden {
                        culled += 1;
                        continue;
                    }
                }
                let first = out.len();
                let tris = c.first as usize..c.end as usize;
                // Transformed, projected and tested (back faces where they may be culled)
                // all at once.
                lanes.load_packed(p, &self.lanes[c.b0 as usize..c.b1 as usize], cull);
                // The kept ones, in order, without a branch per left-out triangle.
                let mut kept = lanes.kept(tris.len());
                while kept != 0 {
                    let i = kept.trailing_zeros() as usize;
                    kept &= kept - 1;
                    let t = tris.start + i;
                    let back = lanes.back(i);
                    let (v, projected) = lanes.triangle(i);
                    let tag = 2 * self.draw.src[t] + back as u32 + 1;
                    if shade {
                        let n = out.len();
                        let slot = slots.len() as u32 + 1;
                        if let Some(plane) = self.setup_triangle(p, v, projected, slot, &mut out) {
                            if out.len() > n {
                                slots.push(self.slot(p, t, plane));
                                slot_tag.push(tag);
                            }
                        }
                    } else {
                        self.setup_triangle(p, v, projected, tag, &mut out);
                    }
                }
                if out.len() > first {
                    let mut g = Group {
                        x0: i32::MAX,
                        x1: i32::MIN,
                        y0: i32::MAX,
                        y1: i32::MIN,
                        zmax: 0.0,
                    };
                    for t in &out[first..] {
                        g.x0 = g.x0.min(t.x0);
                        g.x1 = g.x1.max(t.x1);
                        g.y0 = g.y0.min(t.y0);
                        g.y1 = g.y1.max(t.y1);
                        g.zmax = g.zmax.max(t.zhi);
                    }
                    // Drawn now, so that what follows is tested against it; the triangles
                    // are not kept.
                    let (x0, x1, y0, y1) =
                        (g.x0 as usize, g.x1 as usize, g.y0 as usize, g.y1 as usize);
                    if !coarse.hidden(zbuf, x0, x1, y0, y1, g.zmax) {
                        let tris = &out[first..];
                        match ids.as_deref_mut() {
                            Some(ids) => raster::<true>(p.w, 0, p.h, tris, zbuf, ids),
                            None => raster::<false>(p.w, 0, p.h, tris, zbuf, &mut []),
                        }
                        coarse.touch(x0, x1, y0, y1);
                    }
                    out.truncate(first);
                }
            }
        }
        let mut slot_class = spare.slot_class;
        slot_class.clear();
        slot_class.extend(slot_tag.iter().map(|&t| self.tag_class[t as usize]));
        Setup {
            tris: out,
            slots,
            slot_tag,
            slot_class,
            culled,
            occluded,
        }
    }

    /// The attribute planes of triangle `t` in this view (see [`Slot`]); `plane` is its
    /// `1 / depth` plane.
    #[inline(always)]
    fn slot(&self, p: &ViewParams, t: usize, plane: [f64; 3]) -> Slot {
        let l = &self.look[t];
        let (fx, fy, cx, cy) = (p.fx as f64, p.fy as f64, p.cx as f64, p.cy as f64);
        // A barycentric weight w = (q - a) . g_w with q = pos + rot^T c (camera point c) is
        // c . (rot g_w) + (pos - a) . g_w; with c = depth * ((x + 0.5 - cx) / fx,
        // -(y + 0.5 - cy) / fy, -1), w / depth is linear in the pixel (x, y).
        let lin = |g: Vec3| -> [f64; 3] {
            let r = (p.rot * g).as_dvec3();
            let h = (p.pos - l.a).dot(g) as f64;
            [
                r.x / fx + h * plane[0],
                -r.y / fy + h * plane[1],
                r.x * (0.5 - cx) / fx + r.y * (cy - 0.5) / fy - r.z + h * plane[2],
            ]
        };
        let (u, v) = (lin(l.wu), lin(l.wv));
        // Loops rather than `map` closures, which the AVX2 copy would call out of line.
        let mut k = [[0.0f32; 3]; ATTRS];
        for (i, ki) in k.iter_mut().enumerate() {
            let (a0, a1, a2) = (l.at[i] as f64, l.du[i] as f64, l.dv[i] as f64);
            for (j, kij) in ki.iter_mut().enumerate() {
                *kij = (a0 * plane[j] + a1 * u[j] + a2 * v[j]) as f32;
            }
        }
        Slot {
            k,
            tex: l.tex,
            tone: l.tone,
            kind: l.kind,
        }
    }

    /// Clip, project and emit one triangle (corners `v` in camera space) that the tests of
    /// its corners kept ([`lanes::Lanes`]); `projected`: its corners projected, when all are
    /// in front of the near plane. Its `1 / depth` plane when it may be visible.
    #[inline(always)]
    fn setup_triangle(
        &self,
        p: &ViewParams,
        v: [Vec3; 3],
        projected: Option<[(f32, f32); 3]>,
        tag: u32,
        out: &mut Vec<ScreenTri>,
    ) -> Option<[f64; 3]> {
        // The plane of the whole triangle gives 1/depth at every pixel (exact under clipping).
        let plane_of = || {
            let [a, b, c] = v.map(|q| q.as_dvec3());
            let nrm: DVec3 = (b - a).cross(c - a);
            let d = nrm.dot(a);
            if d.abs() <= 1e-7 * nrm.length() {
                return None; // Edge-on: the plane passes through the eye.
            }
            let (fx, fy, cx, cy) = (p.fx as f64, p.fy as f64, p.cx as f64, p.cy as f64);
            let za = nrm.x / (fx * d);
            let zb = -nrm.y / (fy * d);
            let zc = (-nrm.x * cx / fx + nrm.y * cy / fy - nrm.z) / d + 0.5 * (za + zb);
            Some([za, zb, zc])
        };
        let in_guard = |q: &Vec3| {
            let (sx, sy, _) = p.project(*q);
            sx.abs() < p.guard && sy.abs() < p.guard
        };
        if let Some(s) = projected {
            if s.iter()
                .all(|(sx, sy)| sx.abs() < p.guard && sy.abs() < p.guard)
            {
                // The plane only for a triangle that covers a pixel centre (a third of those
                // projected here cover none).
                let mut plane64 = None;
                emit_with(p, v, tag, out, SMALL_BOX, || {
                    plane64 = plane_of();
                    plane64.map(|q| q.map(|z| z as f32))
                });
                return plane64;
            }
        }
        let plane64 = plane_of()?;
        let plane = plane64.map(|z| z as f32);
        let plane64 = Some(plane64);
        let mut poly = Poly {
            v: [Vec3::ZERO; 9],
            n: 3,
        };
        poly.v[..3].copy_from_slice(&v);
        poly = clip(p, &poly, 0);
        if poly.n < 3 {
            return None;
        }
        if !poly.v[..poly.n].iter().all(in_guard) {
            for k in 1..5 {
                poly = clip(p, &poly, k);
                if poly.n < 3 {
                    return None;
                }
            }
        }
        for i in 1..poly.n - 1 {
            emit(p, [poly.v[0], poly.v[i], poly.v[i + 1]], plane, tag, out);
        }
        plane64
    }

    /// [`Self::resolve_band`] in the copy `isa`.
    #[allow(unsafe_code)] // a function built for CPU features; see the SAFETY note
    fn resolve_band_on(
        &self,
        isa: Isa,
        p: &ViewParams,
        setup: &Setup,
        b: Band<'_>,
        want_depth: bool,
        want_instance: bool,
    ) {
        match isa {
            Isa::Baseline => self.resolve_band(p, setup, b, want_depth, want_instance),
            // SAFETY: as in `setup_on`.
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2(_) => unsafe {
                self.resolve_band_avx2(p, setup, b, want_depth, want_instance)
            },
        }
    }

    /// [`Self::resolve_band`] built with AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    fn resolve_band_avx2(
        &self,
        p: &ViewParams,
        setup: &Setup,
        b: Band<'_>,
        want_depth: bool,
        want_instance: bool,
    ) {
        self.resolve_band(p, setup, b, want_depth, want_instance)
    }

    /// Resolve one band of rows (filled by [`Self::setup`]) into the outputs. Inlined into
    /// each copy (`raster/isa.rs`), as are the functions it calls in its loops.
    #[inline(always)]
    fn resolve_band(
        &self,
        p: &ViewParams,
        setup: &Setup,
        b: Band<'_>,
        want_depth: bool,
        want_instance: bool,
    ) {
        let Band {
            y0,
            zbuf,
            ids,
            rgb,
            semantic,
        } = b;
        let w = p.w;
        // Resolve: slots to colour (from 1/depth), then 1/depth to metres, tags to class and
        // object.
        let Some(ids) = ids else {
            self.resolve_depth(p, zbuf, want_depth);
            return;
        };
        let mut semantic = semantic;
        if let Some(rgb) = rgb {
            // Without instance ids, the classes are written with the colour, run by run.
            let sem = if want_instance { None } else { semantic.take() };
            self.resolve_rgb(setup, w, y0, zbuf, ids, rgb, sem);
            if want_instance {
                for id in ids.iter_mut() {
                    *id = setup.slot_tag[*id as usize];
                }
            }
        }
        self.resolve_depth(p, zbuf, want_depth);
        if let Some(sem) = semantic {
            for (s, id) in sem.iter_mut().zip(ids.iter()) {
                *s = self.tag_class[*id as usize];
            }
        }
        if want_instance {
            for id in ids.iter_mut() {
                *id = self.tag_object[*id as usize];
            }
        }
    }

    #[inline(always)]
    fn resolve_depth(&self, p: &ViewParams, zbuf: &mut [f32], want_depth: bool) {
        let (inv_far, far) = (1.0 / p.far, p.far);
        if want_depth {
            for z in zbuf.iter_mut() {
                // A select, not `f32::min` (NaN-aware, more instructions): the same value, as
                // `1 / z` is never NaN (z > 0).
                let d = 1.0 / *z;
                let d = if d < far { d } else { far };
                *z = if *z > inv_far { d } else { far };
            }
        }
    }

    /// Colour of every pixel of a band from its slot and `1 / depth`, and with `sem` its
    /// class.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn resolve_rgb(
        &self,
        setup: &Setup,
        w: usize,
        y0: usize,
        zbuf: &[f32],
        ids: &[u32],
        rgb: &mut [u8],
        mut sem: Option<&mut [u16]>,
    ) {
        const TEXELS: usize = TEX_SIZE * TEX_SIZE;
        let slots = &setup.slots[..];
        // `v` in [0, 255]: its rounded value.
        let byte = |v: f32| -> u32 { (v + MAGIC).to_bits() & 0xff };
        // A run of pixels of one slot is shaded in passes: attributes and texel indices
        // (branch-free, vectorised), texel fetch, colour packed in a word (vectorised), bytes.
        let mut light = [0.0f32; RUN];
        let mut index = [0u32; RUN];
        let mut packed = [0u32; RUN];
        let mut lanes = [0.0f32; RUN];
        for (j, l) in lanes.iter_mut().enumerate() {
            *l = j as f32;
        }
        for (row, ((zr, ir), out)) in zbuf
            .chunks_exact(w)
            .zip(ids.chunks_exact(w))
            .zip(rgb.chunks_exact_mut(3 * w))
            .enumerate()
        {
            let y = (y0 + row) as f32;
            let mut x = 0;
            while x < w {
                let id = ir[x];
                let end = (x + RUN).min(w);
                // Whole blocks of 8 equal ids first (branch-free compare), then one by one.
                let mut e = x + 1;
                while e + 8 <= end && ir[e..e + 8].iter().fold(true, |all, &v| all & (v == id)) {
                    e += 8;
                }
                while e < end && ir[e] == id {
                    e += 1;
                }
                let n = e - x;
                if let Some(s) = sem.as_deref_mut() {
                    let class = setup.slot_class.get(id as usize).copied().unwrap_or(0);
                    if let Some(run) = s.get_mut(row * w + x..row * w + e) {
                        run.fill(class);
                    }
                }
                let px = &mut out[3 * x..3 * e];
                let Some(s) = (id as usize).checked_sub(1).and_then(|i| slots.get(i)) else {
                    px.fill(0);
                    x = e;
                    continue;
                };
                let xf = x as f32;
                let k = &s.k;
                // Attribute / depth at pixel x + j is a x_j + b.
                let (a0, a1, a2) = (k[0][0], k[1][0], k[2][0]);
                let b0 = k[0][0] * xf + k[0][1] * y + k[0][2];
                let b1 = k[1][0] * xf + k[1][1] * y + k[1][2];
                let b2 = k[2][0] * xf + k[2][1] * y + k[2][2];
                // Light, and the index (from `base`) of the texel of a repeating `w x h`
                // texture (sides powers of two): floor(t) as round(t - 0.5), the mask wraps
                // negative coordinates.
                let mut repeating = |w: u32, h: u32, base: u32| {
                    for (((l, i), iz), j) in light[..n]
                        .iter_mut()
                        .zip(index[..n].iter_mut())
                        .zip(&zr[x..e])
                        .zip(&lanes[..n])
                    {
                        let inv = 1.0 / *iz;
                        *l = (a0 * j + b0) * inv;
                        let tu = ((a1 * j + b1) * inv - 0.5 + MAGIC).to_bits() & (w - 1);
                        let tv = ((a2 * j + b2) * inv - 0.5 + MAGIC).to_bits() & (h - 1);
                        *i = base + tv * w + tu;
                    }
                };
                match s.kind {
                    Kind::Tiled => {
                        let Some(tex) = self
                            .texels
                            .get(s.tex as usize..s.tex as usize + TEXELS)
                            .and_then(|t| <&[u8; TEXELS]>::try_from(t).ok())
                        else {
                            px.fill(0);
                            x = e;
                            continue;
                        };
                        repeating(TEX_SIZE as u32, TEX_SIZE as u32, 0);
                        for (l, i) in light[..n].iter_mut().zip(&index[..n]) {
                            *l *= tex[*i as usize & (TEXELS - 1)] as f32;
                        }
                    }
                    Kind::Image { w: iw, h: ih } => repeating(iw, ih, s.tex),
                    Kind::Face { w: fw, h: fh } => {
                        // A clamped index needs no bounds check (the face's texels are all
                        // inside, so the clamp never changes one).
                        let (all, blocked) = self.faces.drawn(s.tex as usize);
                        let Some(last) = all.len().checked_sub(1) else {
                            px.fill(0);
                            x = e;
                            continue;
                        };
                        let run = FaceRun {
                            zr: &zr[x..e],
                            lanes: &lanes[..n],
                            u: (a1, b1),
                            v: (a2, b2),
                            // Coordinates clamped into the face texture (rounding at its edges).
                            max: (fw as f32 - 0.5, fh as f32 - 0.5),
                        };
                        if blocked {
                            let bw = fw.div_ceil(face_store::BLOCK);
                            run.indices(&mut index[..n], |tu, tv| {
                                face_store::blocked_index(tu, tv, bw)
                            });
                        } else {
                            run.indices(&mut index[..n], |tu, tv| tv * fw + tu);
                        }
                        for (l, i) in light[..n].iter_mut().zip(&index[..n]) {
                            *l = all[(*i as usize).min(last)] as f32;
                        }
                    }
                }
                let [tr, tg, tb] = s.tone;
                if let Kind::Image { .. } = s.kind {
                    // RGB texels: each channel clamped on its own.
                    let f = |v: f32| byte(v.clamp_range(0.0, 255.0));
                    for ((c, l), i) in packed[..n].iter_mut().zip(&light[..n]).zip(&index[..n]) {
                        let t = self.image_texels.get(*i as usize).copied().unwrap_or(0);
                        let [r, g, b, _] = t.to_le_bytes();
                        *c = f(tr * l * r as f32)
                            | f(tg * l * g as f32) << 8
                            | f(tb * l * b as f32) << 16;
                    }
                } else {
                    // Clamping the product once keeps every channel in [0, 255].
                    let top = 255.0 / tr.max(tg).max(tb).max(1e-6);
                    for (c, l) in packed[..n].iter_mut().zip(&light[..n]) {
                        let m = if *l < top { *l } else { top };
                        let m = if m > 0.0 { m } else { 0.0 };
                        *c = byte(tr * m) | byte(tg * m) << 8 | byte(tb * m) << 16;
                    }
                }
                // Four pixels (twelve bytes) in three words, then the rest three bytes each
                // (`packed` holds a pixel's bytes in its low 24 bits).
                let mut out4 = px.chunks_exact_mut(12);
                let mut in4 = packed[..n].chunks_exact(4);
                for (o, c) in (&mut out4).zip(&mut in4) {
                    let words = [
                        c[0] | c[1] << 24,
                        c[1] >> 8 | c[2] << 16,
                        c[2] >> 16 | c[3] << 8,
                    ];
                    for (o, w) in o.chunks_exact_mut(4).zip(words) {
                        o.copy_from_slice(&w.to_le_bytes());
                    }
                }
                for (o, c) in out4
                    .into_remainder()
                    .chunks_exact_mut(3)
                    .zip(in4.remainder())
                {
                    o.copy_from_slice(&c.to_le_bytes()[..3]);
                }
                x = e;
            }
        }
    }
}

/// Float -> int by the magic-number trick (adding 1.5 * 2^23 leaves the rounded value in the low
/// mantissa bits): no saturating conversions, no branches in the resolve's hot loops.
const MAGIC: f32 = 12_582_912.0;

/// A run of pixels of one face-textured slot in a row: their `1 / depth` and offsets from the
/// run's first pixel, and each texture coordinate over depth as `a * offset + b`.
struct FaceRun<'a> {
    zr: &'a [f32],
    lanes: &'a [f32],
    u: (f32, f32),
    v: (f32, f32),
    max: (f32, f32),
}

impl FaceRun<'_> {
    /// The index of each pixel's texel, `at(tu, tv)` of its texel coordinates (branch-free,
    /// on vector lanes once inlined).
    #[inline(always)]
    fn indices(&self, index: &mut [u32], at: impl Fn(u32, u32) -> u32) {
        let ((a1, b1), (a2, b2), (umax, vmax)) = (self.u, self.v, self.max);
        for ((i, iz), j) in index.iter_mut().zip(self.zr).zip(self.lanes) {
            let inv = 1.0 / *iz;
            let u = ((a1 * j + b1) * inv).clamp_range(0.0, umax);
            let v = ((a2 * j + b2) * inv).clamp_range(0.0, vmax);
            let tu = (u - 0.5 + MAGIC).to_bits() & 0x3f_ffff;
            let tv = (v - 0.5 + MAGIC).to_bits() & 0x3f_ffff;
            *i = at(tu, tv);
        }
    }
}

/// A band of rows of one view's buffers.
struct Band<'a> {
    y0: usize,
    zbuf: &'a mut [f32],
    ids: Option<&'a mut [u32]>,
    rgb: Option<&'a mut [u8]>,
    semantic: Option<&'a mut [u16]>,
}

/// Where a box can write in a view (see [`screen_box`]).
#[derive(Clone, Copy, Debug)]
enum Reach {
    /// Part of the box is not in front of the near plane: anything may be covered.
    Near,
    /// No pixel of the image can be covered.
    Nothing,
    /// Pixels `x0..=x1`, `y0..=y1` (inclusive, within the image) hold every pixel a triangle
    /// inside the box can cover, and no triangle inside it writes a `1 / depth` above `zmax`.
    Box {
        x0: usize,
        x1: usize,
        y0: usize,
        y1: usize,
        zmax: f32,
    },
}

/// The pixels a box can cover and the largest `1 / depth` a triangle inside it can write
/// (with margins far above the rounding of a triangle's own projection: a pixel on every side,
/// 0.1 % on `1 / depth`), for occlusion culling before set-up.
#[inline(always)]
fn screen_box(p: &ViewParams, b: &Aabb) -> Reach {
    let (lo, hi) = (b.min_v(), b.max_v());
    // The eight corners (corner `k` takes the high side on axis `j` when bit `j` of `k` is
    // set) to camera space and projected, in lanes: the operations of
    // [`ViewParams::to_camera`] and [`ViewParams::project`] (as `lanes::Lanes` does them).
    let cx = [lo.x, hi.x, lo.x, hi.x, lo.x, hi.x, lo.x, hi.x];
    let cy = [lo.y, lo.y, hi.y, hi.y, lo.y, lo.y, hi.y, hi.y];
    let cz = [lo.z, lo.z, lo.z, lo.z, hi.z, hi.z, hi.z, hi.z];
    let (ex, ey, ez) = (p.pos.x, p.pos.y, p.pos.z);
    let (ra, rb, rc) = (p.rot.x_axis, p.rot.y_axis, p.rot.z_axis);
    let (mut sx, mut sy, mut d) = ([0.0f32; 8], [0.0f32; 8], [0.0f32; 8]);
    let mut near = false;
    for k in 0..8 {
        let (a, b, c) = (cx[k] - ex, cy[k] - ey, cz[k] - ez);
        let x = ra.x * a + rb.x * b + rc.x * c;
        let y = ra.y * a + rb.y * b + rc.y * c;
        let z = ra.z * a + rb.z * b + rc.z * c;
        near |= z > -p.near;
        let iz = 1.0 / -z;
        sx[k] = p.cx + p.fx * x * iz;
        sy[k] = p.cy - p.fy * y * iz;
        d[k] = -z;
    }
    if near {
        return Reach::Near;
    }
    let lowest = |v: &[f32; 8]| v.iter().fold(f32::MAX, |m, &q| if q < m { q } else { m });
    let highest = |v: &[f32; 8]| v.iter().fold(f32::MIN, |m, &q| if q > m { q } else { m });
    let (x0, x1, y0, y1) = (lowest(&sx), highest(&sx), lowest(&sy), highest(&sy));
    let dmin = lowest(&d);
    // No pixel centre in the projection's rectangle, even with twice the margin
    // [`RasterScene::setup_triangle`] gives a triangle (so every triangle inside the box would be
    // rejected there; projection is convex in front of the eye): an integer in [lo, hi] when
    // floor(hi) >= lo.
    const M: f32 = 0.02;
    let some = |lo: f32, hi: f32| fast_floor(hi as f64) >= lo as f64;
    if !(some(x0 - 0.5 - M, x1 - 0.5 + M) && some(y0 - 0.5 - M, y1 - 0.5 + M)) {
        return Reach::Nothing;
    }
    // A pixel's centre `x + 0.5` inside the triangle: `x` in [x0 - 0.5, x1 - 0.5], widened.
    let (fx0, fx1) = (fast_floor(x0 as f64 - 1.5), fast_ceil(x1 as f64 + 0.5));
    let (fy0, fy1) = (fast_floor(y0 as f64 - 1.5), fast_ceil(y1 as f64 + 0.5));
    let (w, h) = (p.w as f64 - 1.0, p.h as f64 - 1.0);
    if fx1 < 0.0 || fy1 < 0.0 || fx0 > w || fy0 > h {
        return Reach::Nothing;
    }
    Reach::Box {
        x0: fx0.max(0.0) as usize,
        x1: fx1.min(w) as usize,
        y0: fy0.max(0.0) as usize,
        y1: fy1.min(h) as usize,
        zmax: (1.0 / dmin) * 1.001,
    }
}

/// A view's coarse depth buffer: the smallest `1 / depth` of each [`TILE`] x [`TILE`] tile of
/// the depth buffer, refreshed lazily. Anything that writes at most that over its tiles is
/// hidden (the depth test is strict: a tie keeps what was drawn first).
struct Coarse {
    /// Tiles across.
    tw: usize,
    w: usize,
    h: usize,
    hiz: Vec<f32>,
    /// Tiles drawn into since their minimum was taken: recomputed only when a test reads them
    /// (most are drawn into again, or never read, before that).
    dirty: Vec<bool>,
}

impl Coarse {
    #[inline(always)]
    fn new(w: usize, h: usize, inv_far: f32) -> Self {
        let (tw, th) = (w.div_ceil(TILE), h.div_ceil(TILE));
        Coarse {
            tw,
            w,
            h,
            hiz: vec![inv_far; tw * th],
            dirty: vec![false; tw * th],
        }
    }

    /// Whether nothing writing at most `zmax` over pixels `x0..=x1`, `y0..=y1` can pass the
    /// depth test of `zbuf`.
    #[inline(always)]
    fn hidden(
        &mut self,
        zbuf: &[f32],
        x0: usize,
        x1: usize,
        y0: usize,
        y1: usize,
        zmax: f32,
    ) -> bool {
        let (tx0, tx1, ty0, ty1) = (x0 / TILE, x1 / TILE, y0 / TILE, y1 / TILE);
        // Plain loops, not `all` with closures: a closure is compiled on its own and would run
        // the baseline copy inside the AVX2 one (`raster/isa.rs`).
        for ty in ty0..=ty1 {
            for tx in tx0..=tx1 {
                // A stale minimum is a lower bound of the true one.
                let i = ty * self.tw + tx;
                if zmax <= self.hiz[i] {
                    continue;
                }
                if !self.dirty[i] {
                    return false;
                }
                self.dirty[i] = false;
                let r1 = ((ty + 1) * TILE).min(self.h);
                self.hiz[i] = tile_min(zbuf, self.w, ty * TILE, r1, tx * TILE);
                // As `all` did: a NaN `zmax` is never hidden.
                let covered = zmax <= self.hiz[i];
                if !covered {
                    return false;
                }
            }
        }
        true
    }

    /// Mark the tiles over pixels `x0..=x1`, `y0..=y1` as drawn into.
    #[inline(always)]
    fn touch(&mut self, x0: usize, x1: usize, y0: usize, y1: usize) {
        let (tx0, tx1) = (x0 / TILE, x1 / TILE);
        for ty in y0 / TILE..=y1 / TILE {
            self.dirty[ty * self.tw + tx0..=ty * self.tw + tx1].fill(true);
        }
    }
}

/// Clip a polygon against plane `k` of [`ViewParams::plane`] (Sutherland-Hodgman). New points
/// are always interpolated from the inside vertex, so an edge shared by two triangles is cut at
/// bit-identical points and the fill stays watertight.
#[inline(always)]
fn clip(p: &ViewParams, poly: &Poly, k: usize) -> Poly {
    let mut out = Poly {
        v: [Vec3::ZERO; 9],
        n: 0,
    };
    for i in 0..poly.n {
        let (a, b) = (poly.v[i], poly.v[(i + 1) % poly.n]);
        let (fa, fb) = (p.plane(k, a), p.plane(k, b));
        if fa >= 0.0 {
            out.v[out.n] = a;
            out.n += 1;
        }
        if (fa >= 0.0) != (fb >= 0.0) && out.n < out.v.len() {
            let (i_in, f_in, o, f_o) = if fa >= 0.0 {
                (a, fa, b, fb)
            } else {
                (b, fb, a, fa)
            };
            let mut q = i_in + (o - i_in) * (f_in / (f_in - f_o));
            if k == 0 {
                q.z = q.z.min(-p.near); // Exactly on or in front of the near plane.
            }
            out.v[out.n] = q;
            out.n += 1;
        }
    }
    out
}

/// Project, snap and set up one triangle in front of the near plane.
#[inline(always)]
fn emit(p: &ViewParams, v: [Vec3; 3], plane: [f32; 3], tag: u32, out: &mut Vec<ScreenTri>) {
    emit_tested(p, v, plane, tag, out, SMALL_BOX)
}

/// [`emit`], testing the pixel centres of boxes of at most `small` pixels.
#[inline(always)]
fn emit_tested(
    p: &ViewParams,
    v: [Vec3; 3],
    plane: [f32; 3],
    tag: u32,
    out: &mut Vec<ScreenTri>,
    small: i64,
) {
    emit_with(p, v, tag, out, small, || Some(plane));
}

/// [`emit_tested`] with the `1 / depth` plane asked for only once the triangle is found to
/// cover a pixel centre it may hold (none: nothing is emitted).
#[inline(always)]
fn emit_with(
    p: &ViewParams,
    v: [Vec3; 3],
    tag: u32,
    out: &mut Vec<ScreenTri>,
    small: i64,
    plane: impl FnOnce() -> Option<[f32; 3]>,
) {
    // Snapped coordinates are integers below 2^25 (`MAX_FIXED`) and every value below is an
    // integer below 2^53: exact in i64 as it was in f64, without f64 -> i64 conversions.
    // `sub` is a power of two, at least 1 for any image under 2^24 pixels a side (a wider
    // one draws nothing).
    let sub = p.sub;
    let si = sub as i64;
    if si < 1 {
        return;
    }
    // Floor and ceiling of `n / (2 sub)` by an arithmetic shift.
    let shift = (2 * si).trailing_zeros();
    let mut s = [(0i64, 0i64); 3];
    let (mut zlo, mut zhi) = (f32::INFINITY, 0.0f32);
    for (k, q) in v.iter().enumerate() {
        let iz = 1.0 / -(q.z as f64);
        let sx = p.cx as f64 + p.fx as f64 * q.x as f64 * iz;
        let sy = p.cy as f64 - p.fy as f64 * q.y as f64 * iz;
        s[k] = (floor_i64(sx * sub + 0.5), floor_i64(sy * sub + 0.5));
        zlo = zlo.min(iz as f32);
        zhi = zhi.max(iz as f32);
    }
    let area = (s[1].0 - s[0].0) * (s[2].1 - s[0].1) - (s[1].1 - s[0].1) * (s[2].0 - s[0].0);
    if area == 0 {
        return;
    }
    if area < 0 {
        s.swap(1, 2);
    }
    let (xmin, xmax) = (
        s[0].0.min(s[1].0).min(s[2].0),
        s[0].0.max(s[1].0).max(s[2].0),
    );
    let (ymin, ymax) = (
        s[0].1.min(s[1].1).min(s[2].1),
        s[0].1.max(s[1].1).max(s[2].1),
    );
    // Pixels whose centres can be inside: ceil and floor of (coordinate - sub / 2) / sub, in
    // units of half a sub-pixel step.
    let ceil = |n: i64| -((-n) >> shift);
    let floor = |n: i64| n >> shift;
    let x0 = ceil(2 * xmin - si).max(0);
    let x1 = floor(2 * xmax - si).min(p.w as i64 - 1);
    let y0 = ceil(2 * ymin - si).max(0);
    let y1 = floor(2 * ymax - si).min(p.h as i64 - 1);
    if x0 > x1 || y0 > y1 {
        return;
    }
    let edge = |i: usize, j: usize| {
        let (dx, dy) = (s[j].0 - s[i].0, s[j].1 - s[i].1);
        // Top-left rule (y down, inside on the right of i -> j): left edges go up, top edges
        // run right; pixels exactly on other edges belong to the neighbour.
        let top_left = dy < 0 || (dy == 0 && dx > 0);
        // c = dx (sub / 2 - y_i) - dy (sub / 2 - x_i) - (0 or 1), truncated as the f64 value
        // was (an integer for sub >= 2).
        let c2 = dx * (si - 2 * s[i].1) - dy * (si - 2 * s[i].0) - if top_left { 0 } else { 2 };
        Edge {
            a: -si * dy,
            b: si * dx,
            c: c2 / 2,
        }
    };
    let edges = [edge(0, 1), edge(1, 2), edge(2, 0)];
    // A triangle of a few pixels' box (most of a small object's far away) often holds none of
    // their centres: test them here, as the fill would, and leave out one that would fill
    // nothing (no slot, no fill, no group for it).
    let (px0, px1, py0, py1) = (x0, x1, y0, y1);
    if (px1 - px0 + 1) * (py1 - py0 + 1) <= small && !covers_a_centre(&edges, px0, px1, py0, py1) {
        return;
    }
    let Some(plane) = plane() else {
        return;
    };
    out.push(ScreenTri {
        edges,
        x0: x0 as i32,
        x1: x1 as i32,
        y0: y0 as i32,
        y1: y1 as i32,
        za: plane[0],
        zb: plane[1],
        zc: plane[2],
        zlo,
        zhi,
        tag,
    });
}

/// Fill rows `y0..y1` (the buffers hold exactly those rows) with the nearest triangle per pixel.
#[inline(always)]
fn raster<const IDS: bool>(
    w: usize,
    y0: usize,
    y1: usize,
    tris: &[ScreenTri],
    zbuf: &mut [f32],
    ids: &mut [u32],
) {
    let (by0, by1) = (y0 as i64, y1 as i64 - 1);
    for t in tris {
        let (mut ya, mut yb) = ((t.y0 as i64).max(by0), (t.y1 as i64).min(by1));
        // A horizontal edge (`a = 0`) holds the rows where `b y + c >= 0`: it bounds the rows
        // (exactly those a per-row test would keep); the others bound each row's span, a left
        // edge (`a > 0`) from below, a right one (`a < 0`) from above.
        let mut left = 0;
        let mut right = 0;
        for (i, e) in t.edges.iter().enumerate() {
            left |= u8::from(e.a > 0) << i;
            right |= u8::from(e.a < 0) << i;
            if e.a != 0 {
                continue;
            }
            if e.b > 0 {
                ya = ya.max(-e.c.div_euclid(e.b));
            } else if e.b < 0 {
                yb = yb.min(e.c.div_euclid(-e.b));
            } else if e.c < 0 {
                yb = ya - 1;
            }
        }
        if ya > yb {
            continue;
        }
        let k = |i: usize| Walk::new(&t.edges[i], ya, yb > ya);
        let b = Bounds { t, ya, yb, w, y0 };
        // A triangle with area has at least one left and one right edge.
        match (left, right) {
            (0b001, 0b110) => rows::<IDS, 1, 2>(b, [k(0)], [k(1), k(2)], zbuf, ids),
            (0b010, 0b101) => rows::<IDS, 1, 2>(b, [k(1)], [k(0), k(2)], zbuf, ids),
            (0b100, 0b011) => rows::<IDS, 1, 2>(b, [k(2)], [k(0), k(1)], zbuf, ids),
            (0b110, 0b001) => rows::<IDS, 2, 1>(b, [k(1), k(2)], [k(0)], zbuf, ids),
            (0b101, 0b010) => rows::<IDS, 2, 1>(b, [k(0), k(2)], [k(1)], zbuf, ids),
            (0b011, 0b100) => rows::<IDS, 2, 1>(b, [k(0), k(1)], [k(2)], zbuf, ids),
            _ => {
                // One left and one right edge (the third horizontal), or (not reached) none.
                let pick = |m: u8, none: i64| {
                    if m != 0 {
                        k(m.trailing_zeros() as usize)
                    } else {
                        Walk {
                            x: none,
                            ..Walk::NONE
                        }
                    }
                };
                let (l, r) = (pick(left, i64::MIN), pick(right, i64::MAX));
                rows::<IDS, 1, 1>(b, [l], [r], zbuf, ids)
            }
        }
    }
}

/// The rows of one triangle [`rows`] fills, and its buffers' width and first row.
#[derive(Clone, Copy)]
struct Bounds<'a> {
    t: &'a ScreenTri,
    ya: i64,
    yb: i64,
    w: usize,
    y0: usize,
}

/// Fill rows `ya..=yb` of a triangle bounded by `NL` left and `NR` right edges, walked from row
/// `ya`.
#[inline(always)]
fn rows<const IDS: bool, const NL: usize, const NR: usize>(
    b: Bounds<'_>,
    mut left: [Walk; NL],
    mut right: [Walk; NR],
    zbuf: &mut [f32],
    ids: &mut [u32],
) {
    let Bounds { t, ya, yb, w, y0 } = b;
    for y in ya..=yb {
        let (mut lo, mut hi) = (t.x0 as i64, t.x1 as i64);
        for k in &mut left {
            lo = if k.x > lo { k.x } else { lo };
            k.step::<-1>();
        }
        for k in &mut right {
            hi = if k.x < hi { k.x } else { hi };
            k.step::<1>();
        }
        if lo > hi {
            continue;
        }
        let (lo, hi) = (lo as usize, hi as usize);
        let row = (y as usize - y0) * w;
        let z0 = t.zb * y as f32 + t.zc + t.za * lo as f32;
        let n = hi + 1 - lo;
        let zs = &mut zbuf[row + lo..row + lo + n];
        if IDS {
            span_ids(zs, &mut ids[row + lo..row + lo + n], z0, t);
        } else {
            span_depth(zs, z0, t);
        }
    }
}

/// Whether a pixel centre of columns `x0..=x1`, rows `y0..=y1` is inside all three `edges`
/// (plain loops: see [`Coarse::hidden`]).
#[inline(always)]
fn covers_a_centre(edges: &[Edge; 3], x0: i64, x1: i64, y0: i64, y1: i64) -> bool {
    for y in y0..=y1 {
        for x in x0..=x1 {
            let inside = (edges[0].a * x + edges[0].b * y + edges[0].c >= 0)
                & (edges[1].a * x + edges[1].b * y + edges[1].c >= 0)
                & (edges[2].a * x + edges[2].b * y + edges[2].c >= 0);
            if inside {
                return true;
            }
        }
    }
    false
}

/// The smallest value of rows `r0..r1`, columns `c0..c0 + TILE` (clipped to the row) of a
/// buffer `w` wide: eight independent lanes with branch-free selects, which vectorise.
#[inline(always)]
fn tile_min(z: &[f32], w: usize, r0: usize, r1: usize, c0: usize) -> f32 {
    let mut m = [f32::INFINITY; TILE];
    if c0 + TILE <= w {
        for r in r0..r1 {
            let Ok(row) = <&[f32; TILE]>::try_from(&z[r * w + c0..r * w + c0 + TILE]) else {
                continue;
            };
            for j in 0..TILE {
                m[j] = if row[j] < m[j] { row[j] } else { m[j] };
            }
        }
    } else {
        for r in r0..r1 {
            for (j, v) in z[r * w + c0..(r + 1) * w].iter().enumerate() {
                m[j] = if *v < m[j] { *v } else { m[j] };
            }
        }
    }
    m.iter()
        .fold(f32::INFINITY, |a, b| if *b < a { *b } else { a })
}

/// Lane offsets of an 8-pixel block.
const LANES: [f32; 8] = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];

/// Depth-test a span and write depth and tag: blocks of 8 pixels with branch-free selects (no
/// NaN-aware `max`) that the compiler turns into SIMD, then the rest one by one.
#[inline(always)]
fn span_ids(zs: &mut [f32], ids: &mut [u32], z0: f32, t: &ScreenTri) {
    let (za, lo, hi, tag) = (t.za, t.zlo, t.zhi, t.tag);
    let ids = &mut ids[..zs.len()];
    let mut zc = zs.chunks_exact_mut(8);
    let mut ic = ids.chunks_exact_mut(8);
    let mut base = z0;
    for (zb, ib) in (&mut zc).zip(&mut ic) {
        // Work on array copies: the SLP vectoriser handles these, not the slices.
        let (Ok(zb), Ok(ib)) = (<&mut [f32; 8]>::try_from(zb), <&mut [u32; 8]>::try_from(ib))
        else {
            continue;
        };
        let (mut z, mut id) = (*zb, *ib);
        for j in 0..8 {
            let v = base + za * LANES[j];
            let v = if v < lo { lo } else { v };
            let v = if v > hi { hi } else { v };
            let m = v > z[j];
            id[j] = if m { tag } else { id[j] };
            z[j] = if m { v } else { z[j] };
        }
        *zb = z;
        *ib = id;
        base += 8.0 * za;
    }
    for (k, (z, id)) in zc
        .into_remainder()
        .iter_mut()
        .zip(ic.into_remainder())
        .enumerate()
    {
        // Stores of selected values, not branches (which pixel wins is data).
        let v = (base + za * k as f32).clamp_range(lo, hi);
        let m = v > *z;
        *id = if m { tag } else { *id };
        *z = if m { v } else { *z };
    }
}

/// [`span_ids`] without ids.
#[inline(always)]
fn span_depth(zs: &mut [f32], z0: f32, t: &ScreenTri) {
    let (za, lo, hi) = (t.za, t.zlo, t.zhi);
    let mut zc = zs.chunks_exact_mut(8);
    let mut base = z0;
    for zb in &mut zc {
        let Ok(zb) = <&mut [f32; 8]>::try_from(zb) else {
            continue;
        };
        let mut z = *zb;
        for j in 0..8 {
            let v = base + za * LANES[j];
            let v = if v < lo { lo } else { v };
            let v = if v > hi { hi } else { v };
            z[j] = if v > z[j] { v } else { z[j] };
        }
        *zb = z;
        base += 8.0 * za;
    }
    for (k, z) in zc.into_remainder().iter_mut().enumerate() {
        let v = (base + za * k as f32).clamp_range(lo, hi);
        *z = if v > *z { v } else { *z };
    }
}

/// Clamp without `f32::clamp`'s panic on an empty range.
trait ClampRange {
    fn clamp_range(self, lo: Self, hi: Self) -> Self;
}

impl ClampRange for f32 {
    #[inline(always)]
    fn clamp_range(self, lo: f32, hi: f32) -> f32 {
        let v = if self < lo { lo } else { self };
        if v > hi {
            hi
        } else {
            v
        }
    }
}

/// `ceil` and `floor` of snapped coordinates (|v| < 2^53) without a libm call on baseline x86-64.
#[inline(always)]
fn fast_ceil(v: f64) -> f64 {
    let t = v as i64 as f64;
    t + f64::from(u8::from(t < v))
}

/// `floor` of a snapped coordinate (|v| < 2^53) as an integer.
#[inline(always)]
fn floor_i64(v: f64) -> i64 {
    let t = v as i64;
    t - i64::from(t as f64 > v)
}

#[inline(always)]
fn fast_floor(v: f64) -> f64 {
    let t = v as i64 as f64;
    t - f64::from(u8::from(t > v))
}

/// Whether triangles (corner triples) form closed surfaces with outward winding: every
/// directed edge is matched by its reverse, and each connected piece encloses positive volume.
/// Corners are compared on a grid of [`WELD`] metres: the seam of a cylinder or sphere, where
/// the last segment's corners (at an angle of 2 pi) stand a rounding error away from the first
/// one's, is closed (that gap, under a micrometre, is a few thousandths of a pixel even a few
/// centimetres from the camera: a pixel centre falls in it about never).
fn closed_outward(pos: &[Vec3]) -> bool {
    if pos.is_empty() {
        return false;
    }
    // Corner ids by sorting the corners (no hashing). Two corners on either side of a grid
    // line stay apart: the surface is then judged open, which only costs speed.
    let mut keyed: Vec<([i64; 3], u32)> = pos
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let k = p.to_array().map(|c| (c as f64 / WELD).round() as i64);
            (k, i as u32)
        })
        .collect();
    keyed.sort_unstable();
    let mut vid = vec![0usize; pos.len()];
    let mut n_ids = 0;
    for run in keyed.chunk_by(|a, b| a.0 == b.0) {
        for &(_, i) in run {
            vid[i as usize] = n_ids;
        }
        n_ids += 1;
    }
    // Balance of directed edges: +1 for (a, b) with a < b, -1 for (b, a); sorted, each
    // undirected edge's signs must add up to zero.
    let mut edges: Vec<(usize, usize, i64)> = Vec::with_capacity(pos.len());
    for t in vid.chunks_exact(3) {
        // Two equal corners: a triangle of no area (a sphere's pole), seen from nowhere; its
        // two other edges are the same edge both ways.
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            continue;
        }
        for (i, j) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            edges.push(if i < j { (i, j, 1) } else { (j, i, -1) });
        }
    }
    edges.sort_unstable();
    if edges
        .chunk_by(|a, b| (a.0, a.1) == (b.0, b.1))
        .any(|run| run.iter().map(|e| e.2).sum::<i64>() != 0)
    {
        return false;
    }
    // Connected pieces (union-find over shared corners) and their signed volumes.
    let mut parent: Vec<usize> = (0..n_ids).collect();
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for t in vid.chunks_exact(3) {
        for k in 1..3 {
            let (a, b) = (find(&mut parent, t[0]), find(&mut parent, t[k]));
            parent[a] = b;
        }
    }
    let mut volume = vec![0.0f64; n_ids];
    let origin = pos[0].as_dvec3();
    for (t, c) in vid.chunks_exact(3).zip(pos.chunks_exact(3)) {
        let [a, b, cc] = [0, 1, 2].map(|k| c[k].as_dvec3() - origin);
        volume[find(&mut parent, t[0])] += a.dot(b.cross(cc));
    }
    (0..n_ids)
        .filter(|&i| find(&mut parent, i) == i)
        .all(|r| volume[r] > 0.0)
}

/// The CPU rasteriser backend of [`Renderer`] (see the [module docs](self)): exact against the
/// ray caster up to silhouette pixels, and the fastest backend on machines without a GPU.
#[derive(Default)]
pub struct RasterRenderer {
    scene: Option<Arc<RasterScene>>,
    /// Prepared scenes from [`RasterScene::shared_once`] instead of [`RasterScene::shared`].
    once: bool,
}

impl RasterRenderer {
    /// A renderer with no scene yet.
    pub fn new() -> Self {
        RasterRenderer::default()
    }

    /// A renderer with no scene yet whose prepared scenes come from
    /// [`RasterScene::shared_once`], which keeps only the homes renderers show: for users that
    /// finish with a home before the next (an evaluation in scene order). The same images as
    /// [`RasterRenderer::new`]'s.
    pub fn visiting_once() -> Self {
        RasterRenderer {
            scene: None,
            once: true,
        }
    }

    /// The prepared scene, once set.
    pub fn scene(&self) -> Option<&Arc<RasterScene>> {
        self.scene.as_ref()
    }
}

impl Renderer for RasterRenderer {
    fn name(&self) -> String {
        "raster".into()
    }

    fn set_scene(&mut self, mesh: Arc<SceneMesh>) -> Result<()> {
        // The home shown so far is let go first, so that a renderer moving on never holds two
        // (visiting once, that frees it unless another renderer shows it).
        if self.scene.as_ref().is_some_and(|s| !s.is_of(&mesh)) {
            self.scene = None;
        }
        self.scene = Some(if self.once {
            RasterScene::shared_once(mesh)
        } else {
            RasterScene::shared(mesh)
        });
        Ok(())
    }

    fn scene_preparer(&self) -> Option<fn(Arc<SceneMesh>)> {
        // A scene prepared ahead for a visiting-once renderer would be dropped at once.
        (!self.once).then_some(|mesh| drop(RasterScene::shared(mesh)))
    }

    fn render(&mut self, views: &[View]) -> Result<Vec<Frame>> {
        let scene = self.scene.as_ref().ok_or(SensorError::NoScene)?;
        // Enough pieces of work to keep every thread busy: whole views for batches of at least
        // two views a thread, bands of rows for smaller ones (sixteen per thread, at least 16
        // rows each: a view's fill runs on one thread, and the others take its resolve in small
        // pieces as soon as it is done; one RGB-D pose on two threads drew ~15 % more frames
        // than with four bands a thread).
        let threads = rayon::current_num_threads();
        let bands = if views.len() >= 2 * threads {
            1
        } else {
            (16 * threads).div_ceil(views.len().max(1))
        };
        if views.len() == 1 {
            return Ok(vec![scene.render_view(&views[0], bands)]);
        }
        Ok(views
            .par_iter()
            .map(|v| scene.render_view(v, bands))
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> Vec<Vec3> {
        corners(&vlnverse_env::Shape::Cuboid {
            half_extents: [0.5, 1.0, 0.25],
            bevel: 0.0,
        })
    }

    /// The corners of a shape's triangles, as the mesh holds them.
    fn corners(s: &vlnverse_env::Shape) -> Vec<Vec3> {
        let m = vlnverse_env::geometry::triangulate(s);
        m.indices
            .iter()
            .flat_map(|t| t.map(|i| Vec3::from_array(m.positions[i as usize])))
            .collect()
    }

    #[test]
    fn small_triangles_that_hold_no_pixel_centre_are_left_out_and_the_fill_is_the_same() {
        use rand::{Rng, SeedableRng};
        let cam = crate::CameraSpec::default().camera(&vlnverse_env::Pose::default());
        let p = ViewParams::new(&cam);
        // A camera-space point at depth `z` seen at pixel coordinates (x, y).
        let at =
            |x: f32, y: f32, z: f32| Vec3::new((x - p.cx) / p.fx * z, -(y - p.cy) / p.fy * z, -z);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let (mut all, mut tested) = (Vec::new(), Vec::new());
        for k in 0..4000u32 {
            // Triangles of up to two pixels a side around pixel (40 + k % 100, 60 + k / 100).
            let (cx, cy) = ((40 + k % 100) as f32, (60 + k / 100) as f32);
            let mut corner = || {
                let (dx, dy) = (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
                at(cx + dx, cy + dy, 2.0)
            };
            let v = [corner(), corner(), corner()];
            emit_tested(&p, v, [0.0, 0.0, 0.5], k + 1, &mut all, 0);
            emit_tested(&p, v, [0.0, 0.0, 0.5], k + 1, &mut tested, SMALL_BOX);
        }
        assert!(tested.len() < all.len(), "some are left out");
        let fill = |tris: &[ScreenTri]| {
            let (mut z, mut ids) = (vec![0.0f32; p.w * p.h], vec![0u32; p.w * p.h]);
            // Each on its own buffer (they overlap): every pixel it writes.
            let mut written = Vec::new();
            for t in tris {
                z.fill(0.0);
                ids.fill(0);
                raster::<true>(p.w, 0, p.h, std::slice::from_ref(t), &mut z, &mut ids);
                let px: Vec<usize> = (0..ids.len()).filter(|&i| ids[i] != 0).collect();
                if !px.is_empty() {
                    written.push((t.tag, px));
                }
            }
            written
        };
        assert_eq!(fill(&tested), fill(&all));
    }

    #[test]
    fn the_span_walk_fills_exactly_the_pixels_inside_every_edge() {
        use rand::{Rng, SeedableRng};
        let cam = crate::CameraSpec::default().camera(&vlnverse_env::Pose::default());
        let p = ViewParams::new(&cam);
        let at =
            |x: f32, y: f32, z: f32| Vec3::new((x - p.cx) / p.fx * z, -(y - p.cy) / p.fy * z, -z);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let mut tris = Vec::new();
        for k in 0..6000u32 {
            // Corners on pixel centres, edges and anywhere; every third triangle with a
            // horizontal edge (two corners on one row), sizes from a pixel to past the image.
            let size = [1.5f32, 6.0, 40.0, 400.0][k as usize % 4];
            let (cx, cy) = (
                rng.random_range(-20.0..250.0),
                rng.random_range(-20.0..250.0),
            );
            let mut coord = |c: f32| {
                let v: f32 = c + rng.random_range(-size..size);
                match rng.random_range(0..3) {
                    0 => v.round(),
                    1 => v.round() + 0.5,
                    _ => v,
                }
            };
            let mut c = [0; 3].map(|_| (coord(cx), coord(cy)));
            if k % 3 == 0 {
                c[1].1 = c[0].1;
            }
            let v = c.map(|(x, y)| at(x, y, 2.0));
            emit_tested(&p, v, [0.0, 0.0, 0.5], k + 1, &mut tris, 0);
        }
        let horizontal = tris
            .iter()
            .filter(|t| t.edges.iter().any(|e| e.a == 0))
            .count();
        assert!(
            horizontal > 1000 && tris.len() > 4000,
            "{horizontal} {}",
            tris.len()
        );
        let (mut z, mut ids) = (vec![0.0f32; p.w * p.h], vec![0u32; p.w * p.h]);
        for t in &tris {
            z.fill(0.0);
            ids.fill(0);
            raster::<true>(p.w, 0, p.h, std::slice::from_ref(t), &mut z, &mut ids);
            for y in 0..p.h {
                for x in 0..p.w {
                    let (xi, yi) = (x as i64, y as i64);
                    let inside = (t.x0..=t.x1).contains(&(x as i32))
                        && (t.y0..=t.y1).contains(&(y as i32))
                        && t.edges.iter().all(|e| e.a * xi + e.b * yi + e.c >= 0);
                    assert_eq!(ids[y * p.w + x] != 0, inside, "pixel ({x}, {y}) of {t:?}");
                }
            }
        }
    }

    #[test]
    fn round_shapes_are_closed_surfaces() {
        // Cups, bottles, vases, fruit and plants: their back faces may be culled. A sphere's
        // poles hold triangles with two equal corners (drawn as nothing), which do not open it.
        let cylinder = corners(&vlnverse_env::Shape::Cylinder {
            radius: 0.04,
            half_height: 0.06,
        });
        assert!(closed_outward(&cylinder));
        let sphere = corners(&vlnverse_env::Shape::Sphere { radius: 0.05 });
        assert!(sphere
            .chunks(3)
            .any(|t| t[0] == t[1] || t[1] == t[2] || t[2] == t[0]));
        assert!(closed_outward(&sphere));
        let flipped: Vec<Vec3> = sphere.chunks(3).flat_map(|t| [t[0], t[2], t[1]]).collect();
        assert!(!closed_outward(&flipped));
    }

    #[test]
    fn closed_outward_accepts_boxes_and_rejects_open_or_inverted_ones() {
        let c = cube();
        assert!(closed_outward(&c));
        // Two boxes side by side (two pieces) are still closed.
        let two: Vec<Vec3> = c
            .iter()
            .copied()
            .chain(c.iter().map(|p| *p + Vec3::X * 3.0))
            .collect();
        assert!(closed_outward(&two));
        // A missing triangle opens it; flipped winding turns it inside out.
        assert!(!closed_outward(&c[3..]));
        let flipped: Vec<Vec3> = c.chunks(3).flat_map(|t| [t[0], t[2], t[1]]).collect();
        assert!(!closed_outward(&flipped));
    }

    /// A tiny home's mesh (lit: merged faces with face textures).
    fn home_mesh(i: usize) -> (vlnverse_env::Scene, Arc<SceneMesh>) {
        use vlnverse_env::SceneSource;
        let homes = vlnverse_procgen::HomeGenerator::from_preset(vlnverse_procgen::Preset::Tiny)
            .expect("preset");
        let scene = homes.scene(i).expect("home");
        let mesh = Arc::new(SceneMesh::new(&scene).expect("mesh"));
        (scene, mesh)
    }

    /// `n` poses on the floor along a diagonal of the home's box, turning `turn` radians more
    /// at each.
    fn diagonal_poses(scene: &vlnverse_env::Scene, n: usize, turn: f32) -> Vec<vlnverse_env::Pose> {
        let b = scene.bounds();
        (0..n)
            .map(|k| {
                let t = (k as f32 + 0.5) / n as f32;
                let at = Vec3::new(
                    b.min[0] + (b.max[0] - b.min[0]) * t,
                    scene.floor_height,
                    b.min[2] + (b.max[2] - b.min[2]) * (1.0 - t),
                );
                vlnverse_env::Pose::from_yaw(at, k as f32 * turn)
            })
            .collect()
    }

    fn temp_file(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("vlnverse-raster-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        dir.join(name)
    }

    /// Visiting once: renderers in one home share one prepared scene, it draws what the main
    /// cache's scene draws, and only the homes shown are kept however many homes pass.
    #[test]
    fn visiting_once_shares_a_home_and_keeps_only_the_homes_shown() {
        use crate::{CameraSpec, Channels};
        use vlnverse_env::Pose;
        let (scene, mesh) = home_mesh(0);
        let (mut a, mut b) = (
            RasterRenderer::visiting_once(),
            RasterRenderer::visiting_once(),
        );
        a.set_scene(mesh.clone()).expect("scene");
        b.set_scene(mesh.clone()).expect("scene");
        let (sa, sb) = (a.scene().expect("set"), b.scene().expect("set"));
        assert!(Arc::ptr_eq(sa, sb), "one prepared scene for the home");
        let main = RasterScene::shared(mesh.clone());
        assert!(!Arc::ptr_eq(sa, &main), "a cache of its own");
        let at = Vec3::new(0.0, scene.floor_height, 0.0);
        let view = View {
            camera: CameraSpec::default().camera(&Pose::from_yaw(at, 0.7)),
            channels: Channels::ALL,
        };
        let (got, want) = (sa.render_view(&view, 1), main.render_view(&view, 1));
        assert_eq!(got.rgb, want.rgb);
        assert_eq!(got.depth, want.depth);
        assert_eq!(got.instance, want.instance);
        // Homes passing through: each lives while shown, and only then.
        let alone = Arc::downgrade(sa);
        for i in 1..4 {
            let (_, m) = home_mesh(i);
            let s = RasterScene::shared_once(m.clone());
            assert!(
                Arc::ptr_eq(&s, &RasterScene::shared_once(m)),
                "home {i} shared"
            );
            assert_eq!(RasterScene::in_use_count(), 2, "home 0 and home {i}");
        }
        assert_eq!(RasterScene::in_use_count(), 1, "home 0 alone");
        let (_, m) = home_mesh(4);
        a.set_scene(m.clone()).expect("scene");
        assert!(
            alone.upgrade().is_some(),
            "still shown by the other renderer"
        );
        b.set_scene(m).expect("scene");
        assert!(
            alone.upgrade().is_none(),
            "dropped once no renderer shows it"
        );
        assert_eq!(RasterScene::in_use_count(), 1, "home 4 alone");
        assert!(
            a.scene_preparer().is_none(),
            "nothing is prepared ahead to be dropped"
        );
    }

    /// Every face texture's texels, one after the other.
    fn face_texels(s: &RasterScene) -> Vec<u8> {
        (0..s.faces.len())
            .flat_map(|i| s.faces.texels(i).to_vec())
            .collect()
    }

    #[test]
    fn a_prepared_file_loads_the_same_scene_and_the_same_pixels() {
        use crate::{CameraSpec, Channels};
        let (scene, mesh) = home_mesh(0);
        let made = RasterScene::new(mesh.clone());
        assert!(made.face_texture_bytes() > 1, "the home has face textures");
        let file = temp_file("same.bin");
        RasterScene::write_prepared(&mesh, &file).expect("written");
        let loaded = RasterScene::load_prepared(mesh.clone(), &file).expect("loaded");
        let bits = |v: &[f32]| v.iter().map(|c| c.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&loaded.lanes), bits(&made.lanes));
        assert!(!made.lanes.is_empty());
        // Allocated exactly (the cache accounts what is held).
        assert_eq!(made.lanes.capacity(), made.lanes.len());
        assert_eq!(loaded.draw.src, made.draw.src);
        assert_eq!(format!("{:?}", loaded.look), format!("{:?}", made.look));
        assert_eq!(loaded.draw.objects, made.draw.objects);
        // A loaded scene holds its larger faces packed until they are drawn.
        assert!(loaded.bytes() < made.bytes());
        assert_eq!(made.bytes(), made.bytes_at_most());
        assert_eq!(face_texels(&loaded), face_texels(&made));
        assert!(
            loaded.bytes() < loaded.bytes_at_most(),
            "reading keeps none"
        );
        for i in 0..loaded.faces.len() {
            let _ = loaded.faces.drawn(i);
        }
        assert_eq!(
            loaded.bytes(),
            loaded.bytes_at_most(),
            "every face unpacked"
        );
        let closed = |s: &RasterScene| s.objects.iter().map(|o| o.closed).collect::<Vec<_>>();
        assert_eq!(closed(&loaded), closed(&made));
        assert!(made.closed_objects() > 0);
        // load_or_new takes the file the mesh names.
        let mut named = (*mesh).clone();
        named.prepared_file = Some(file.clone());
        let via = RasterScene::load_or_new(Arc::new(named));
        for (k, pose) in diagonal_poses(&scene, 8, 0.8).iter().enumerate() {
            let view = View {
                camera: CameraSpec::default().camera(pose),
                channels: Channels::ALL,
            };
            let want = made.render_view(&view, 1);
            for got in [loaded.render_view(&view, 1), via.render_view(&view, 2)] {
                assert_eq!(got.rgb, want.rgb, "view {k}");
                assert_eq!(got.depth, want.depth, "view {k}");
                assert_eq!(got.semantic, want.semantic, "view {k}");
                assert_eq!(got.instance, want.instance, "view {k}");
            }
        }
        let _ = std::fs::remove_file(&file);
    }

    /// The coarse depth hides a box only when every tile it covers is nearer than the box's
    /// nearest depth, after bringing a tile drawn into up to date; a NaN depth is never hidden.
    #[test]
    fn the_coarse_depth_hides_only_what_is_behind_and_never_a_nan_depth() {
        let (w, h) = (16, 16);
        let mut c = Coarse::new(w, h, 0.1);
        let zbuf = vec![0.5f32; w * h];
        assert!(!c.hidden(&zbuf, 0, 15, 0, 15, 0.2), "nothing drawn yet");
        c.touch(0, 15, 0, 15);
        assert!(c.hidden(&zbuf, 0, 15, 0, 15, 0.2), "behind what was drawn");
        assert!(!c.hidden(&zbuf, 0, 15, 0, 15, 0.6), "in front of it");
        c.touch(0, 15, 0, 15);
        assert!(!c.hidden(&zbuf, 0, 15, 0, 15, f32::NAN));
    }

    /// The wider copy of the fill and resolve (`raster/isa.rs`) draws exactly the baseline's
    /// pixels: colour, depth, classes and objects, with and without instance ids, RGB and
    /// depth-only views, one band or several.
    #[test]
    fn both_copies_of_the_fill_and_resolve_draw_the_same_pixels() {
        use crate::{CameraSpec, Channels};
        let Some(wide) = Isa::widest() else {
            eprintln!("this CPU runs only the baseline copy: nothing to compare");
            return;
        };
        let rgb_and_classes = Channels {
            rgb: true,
            semantic: true,
            ..Default::default()
        };
        let mut compared = 0;
        for home in 0..2 {
            let (scene, mesh) = home_mesh(home);
            let s = RasterScene::new(mesh);
            for (k, pose) in diagonal_poses(&scene, 12, 1.3).iter().enumerate() {
                for (spec, channels) in [
                    (CameraSpec::default(), Channels::ALL),
                    (CameraSpec::default(), rgb_and_classes),
                    (CameraSpec::depth(), Channels::DEPTH),
                ] {
                    let view = View {
                        camera: spec.camera(pose),
                        channels,
                    };
                    for bands in [1, 4] {
                        let want = s.render_view_on(Isa::Baseline, &view, bands);
                        let got = s.render_view_on(wide, &view, bands);
                        let at = format!("home {home}, view {k}, {channels:?}, {bands} bands");
                        assert_eq!(got.rgb, want.rgb, "{at}");
                        let bits = |v: &[f32]| v.iter().map(|d| d.to_bits()).collect::<Vec<_>>();
                        assert_eq!(bits(&got.depth), bits(&want.depth), "{at}");
                        assert_eq!(got.semantic, want.semantic, "{at}");
                        assert_eq!(got.instance, want.instance, "{at}");
                        compared += 1;
                    }
                }
            }
        }
        assert_eq!(compared, 2 * 12 * 3 * 2);
    }

    #[test]
    fn a_damaged_or_stale_prepared_file_is_refused_by_name_and_load_or_new_prepares_afresh() {
        let (_, mesh) = home_mesh(0);
        let file = temp_file("refused.bin");
        RasterScene::write_prepared(&mesh, &file).expect("written");
        let good = std::fs::read(&file).expect("read");
        let refused = |bytes: &[u8]| -> String {
            std::fs::write(&file, bytes).expect("written");
            let e = RasterScene::load_prepared(mesh.clone(), &file).expect_err("refused");
            let e = e.to_string();
            assert!(e.contains(&file.display().to_string()), "{e}");
            e
        };
        let mut flipped = good.clone();
        let mid = flipped.len() / 2;
        flipped[mid] ^= 0x10;
        assert!(refused(&flipped).contains("damaged"));
        assert!(refused(&good[..good.len() - 100]).contains("damaged"));
        assert!(refused(b"not a prepared scene at all").contains("VLNRAST"));
        let mut old = good.clone();
        old[8..12].copy_from_slice(&(PREPARED_VERSION + 1).to_le_bytes());
        assert!(refused(&old).contains("format version"));
        // Another home's file is stale for this mesh.
        let (_, other) = home_mesh(1);
        std::fs::write(&file, &good).expect("written");
        let e = RasterScene::load_prepared(other.clone(), &file).expect_err("stale");
        assert!(e.to_string().contains("mesh key"), "{e}");
        // load_or_new falls back to preparing: the same scene as new().
        let mut named = (*other).clone();
        named.prepared_file = Some(file.clone());
        let fresh = RasterScene::load_or_new(Arc::new(named));
        assert_eq!(face_texels(&fresh), face_texels(&RasterScene::new(other)));
        let _ = std::fs::remove_file(&file);
    }

    #[test]
    fn culling_clusters_changes_no_pixel() {
        use crate::{CameraSpec, Channels};
        use vlnverse_env::{Pose, SceneSource};
        let homes = vlnverse_procgen::HomeGenerator::from_preset(vlnverse_procgen::Preset::Tiny)
            .expect("preset");
        let scene = homes.scene(1).expect("home");
        let mesh = Arc::new(SceneMesh::new(&scene).expect("mesh"));
        let culled = RasterScene::new(mesh.clone());
        assert!(culled.clusters.len() > culled.objects.len());
        let mut all = RasterScene::new(mesh);
        all.cull_clusters = false;
        // Standing and looking across the home at varied headings and pitches, from a grid of
        // spots (some inside furniture: near-plane cuts), RGB with ids and depth.
        let b = scene.bounds();
        let (mut views, mut skipped, mut occluded) = (0, 0, 0);
        for i in 0..6 {
            for j in 0..6 {
                let x = b.min[0] + (b.max[0] - b.min[0]) * (i as f32 + 0.5) / 6.0;
                let z = b.min[2] + (b.max[2] - b.min[2]) * (j as f32 + 0.5) / 6.0;
                let yaw = (i * 6 + j) as f32 * 0.7;
                let mut pose = Pose::from_yaw(Vec3::new(x, scene.floor_height, z), yaw);
                let pitch = [0.0f32, -0.6, 0.4][(i + j) % 3];
                pose.rotation = (pose.quat() * glam::Quat::from_rotation_x(pitch)).to_array();
                for (spec, ch) in [
                    (CameraSpec::default(), Channels::ALL),
                    (CameraSpec::depth(), Channels::DEPTH),
                ] {
                    let view = View {
                        camera: spec.camera(&pose),
                        channels: ch,
                    };
                    let (p, c) = (ViewParams::new(&view.camera), &view.camera);
                    let mut z = vec![1.0 / p.far; p.w * p.h];
                    let s = culled.setup(c, &p, false, &mut z, None);
                    (skipped, occluded) = (skipped + s.culled, occluded + s.occluded);
                    z.fill(1.0 / p.far);
                    assert_eq!(all.setup(c, &p, false, &mut z, None).culled, 0);
                    for bands in [1, 3] {
                        let (x, y) = (
                            culled.render_view(&view, bands),
                            all.render_view(&view, bands),
                        );
                        assert_eq!(x.rgb, y.rgb, "view {views}");
                        assert_eq!(x.depth, y.depth, "view {views}");
                        assert_eq!(x.semantic, y.semantic, "view {views}");
                        assert_eq!(x.instance, y.instance, "view {views}");
                    }
                    views += 1;
                }
            }
        }
        assert!(skipped > occluded && occluded > 0, "{skipped} {occluded}");
    }

    #[test]
    fn adjacent_triangles_cover_each_pixel_exactly_once() {
        // A fan of triangles around a centre that falls on pixel centres and edges: with the
        // top-left rule every covered pixel is written by exactly one triangle.
        let cam = Camera::new(&vlnverse_env::Pose::IDENTITY, 32, 32, 1.2, 0.05, 10.0);
        let p = ViewParams::new(&cam);
        let ring: Vec<Vec3> = (0..7)
            .map(|i| {
                let a = i as f32 * std::f32::consts::TAU / 7.0;
                Vec3::new(a.cos() * 2.0, a.sin() * 2.0, -3.0)
            })
            .collect();
        let centre = Vec3::new(0.0, 0.0, -3.0);
        let mut tris = Vec::new();
        for i in 0..7 {
            let tri = [centre, ring[i], ring[(i + 1) % 7]];
            emit(&p, tri, [0.0, 0.0, 0.5], i as u32 + 1, &mut tris);
        }
        let mut count = vec![0u32; 32 * 32];
        for t in &tris {
            let mut z = vec![0.0f32; 32 * 32];
            let mut ids = vec![0u32; 32 * 32];
            raster::<true>(32, 0, 32, std::slice::from_ref(t), &mut z, &mut ids);
            for (c, id) in count.iter_mut().zip(&ids) {
                *c += (*id != 0) as u32;
            }
        }
        assert!(count.iter().all(|c| *c <= 1), "a pixel was filled twice");
        // The heptagon covers the whole centre of the image.
        for v in 8..24 {
            for u in 8..24 {
                assert_eq!(count[v * 32 + u], 1, "pixel ({u}, {v})");
            }
        }
    }
}
