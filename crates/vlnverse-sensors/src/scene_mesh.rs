//! The scene prepared for rendering: every triangle in world space, grouped by object, with
//! per-object bounding boxes (for frustum culling), an id -> class table, and the look of each
//! triangle: its colour, the light baked by [`vlnverse_env::light`] at its corners and texture
//! coordinates into its surface's texture ([`vlnverse_env::material`]), the same data
//! `scene.glb` holds.
//!
//! Every backend computes a pixel the same way, in the encoded (gamma 2.2) space of the output:
//! `tone x light x texel`, clamped to 1, where `tone` is the triangle's encoded colour, `light`
//! the encoded light interpolated (perspective-correct) from the corners and `texel` the
//! encoded texture value ([`Surface::luma_encoded`]). With a pure 2.2 gamma this is the
//! encoded product of the linear values; only the interpolation of the light differs from a
//! viewer of `scene.glb`, which interpolates linear light (a few levels at most, in the
//! gradients). One interpolated value per pixel instead of three keeps the rasteriser fast.
//!
//! Imported mesh parts with a base-colour image ([`vlnverse_env::scene::MeshTexture`]) use it
//! instead of the surface texture: `tone` is then the encoded `baseColorFactor` times the
//! light's colour and `texel` the image's RGB bytes / 255 (nearest texel, repeating), see
//! [`TriLook::image`].

use crate::error::{Result, SensorError};
use glam::Vec3;
use std::path::PathBuf;
use vlnverse_env::geometry::triangulate_part_cells;
use vlnverse_env::light::{bake, cell_of, BakedLight};
use vlnverse_env::material::{box_uv, part_surfaces, picture_uv, Surface, TEX_SIZE};
use vlnverse_env::scene::MeshTexture;
use vlnverse_env::{Aabb, Scene, Shape};

/// Bytes a vector has allocated.
pub(crate) fn held<T>(v: &Vec<T>) -> usize {
    v.capacity() * std::mem::size_of::<T>()
}

/// Gamma of the encoded output (as [`crate::shading::encode`]).
const GAMMA: f32 = 1.0 / 2.2;

/// How one triangle looks (see the module docs for how a pixel is made of it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriLook {
    /// Encoded colour: part colour times the texture's tint times the light's colour, each
    /// linear value raised to `1 / 2.2` (may exceed 1 slightly).
    pub tone: [f32; 3],
    /// Encoded light intensity at each corner (linear intensity raised to `1 / 2.2`).
    pub light: [f32; 3],
    /// Texture coordinates of each corner in texels of a [`TEX_SIZE`] texture (repeating).
    pub uv: [[f32; 2]; 3],
    /// The surface whose texture applies.
    pub surface: Surface,
    /// When set, the texel comes from this image (RGB) instead of the surface texture, and
    /// `uv` are in texels of that image (repeating).
    pub image: Option<u32>,
}

/// An imported base-colour texture resampled to power-of-two sides (<= 1024), encoded RGB
/// bytes as in the file (sRGB), row-major, v down the rows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ImageTexture {
    /// Width in texels (a power of two).
    pub width: u32,
    /// Height in texels (a power of two).
    pub height: u32,
    /// `width * height` texels.
    pub texels: Vec<[u8; 3]>,
}

impl ImageTexture {
    /// The texel at texel coordinates `(u, v)`, repeating (floor, then modulo each side).
    pub fn texel(&self, u: f32, v: f32) -> [u8; 3] {
        let wrap = |x: f32, n: u32| (x.floor() as i64).rem_euclid(n.max(1) as i64) as usize;
        let (x, y) = (wrap(u, self.width), wrap(v, self.height));
        self.texels
            .get(y * self.width as usize + x)
            .copied()
            .unwrap_or([255; 3])
    }

    /// Mean of the texels per channel, as a fraction of 255 (encoded, like the texels).
    pub fn mean_encoded(&self) -> [f32; 3] {
        let mut sum = [0u64; 3];
        for t in &self.texels {
            for k in 0..3 {
                sum[k] += t[k] as u64;
            }
        }
        let n = self.texels.len().max(1) as f64 * 255.0;
        sum.map(|s| (s as f64 / n) as f32)
    }
}

/// A contiguous run of triangles belonging to one object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectRange {
    /// Object id.
    pub id: u32,
    /// First triangle index.
    pub first: u32,
    /// Number of triangles.
    pub count: u32,
    /// World bounding box of the triangles.
    pub bbox: Aabb,
}

/// Triangles of a scene ready for the backends.
#[derive(Clone, Debug, Default)]
pub struct SceneMesh {
    /// Scene id.
    pub scene_id: String,
    /// Corners of triangle `i` are `positions[3i..3i+3]`.
    pub positions: Vec<Vec3>,
    /// Object id of each triangle.
    pub object: Vec<u32>,
    /// Linear base colour of each triangle.
    pub color: Vec<[f32; 3]>,
    /// Objects in triangle order.
    pub objects: Vec<ObjectRange>,
    /// Semantic class id indexed by object id (0 for unknown ids).
    pub class_of: Vec<u16>,
    /// Look of each triangle (baked light, texture).
    pub look: Vec<TriLook>,
    /// Imported textures, indexed by [`TriLook::image`].
    pub images: Vec<ImageTexture>,
    /// Where the rasteriser may find this mesh prepared ([`crate::raster::PREPARED_FILE`] in
    /// the scene's folder, written at generation) instead of preparing it; the file is checked
    /// against the mesh before use ([`crate::RasterScene::load_or_new`]). Not part of
    /// [`SceneMesh::content_key`].
    pub prepared_file: Option<PathBuf>,
}

impl SceneMesh {
    /// A 64-bit hash of everything in the mesh (id included): equal meshes give equal keys,
    /// so prepared scenes can be cached by it ([`vlnverse_env::cache`]).
    pub fn content_key(&self) -> u64 {
        let mut k = vlnverse_env::cache::ContentKey::new();
        k.bytes(self.scene_id.as_bytes());
        k.u32(self.positions.len() as u32);
        self.positions.iter().for_each(|p| k.f32s(&p.to_array()));
        self.object.iter().for_each(|o| k.u32(*o));
        self.color.iter().for_each(|c| k.f32s(c));
        for o in &self.objects {
            [o.id, o.first, o.count].iter().for_each(|v| k.u32(*v));
            k.f32s(&o.bbox.min);
            k.f32s(&o.bbox.max);
        }
        self.class_of.iter().for_each(|c| k.u32(u32::from(*c)));
        k.u32(self.look.len() as u32);
        for l in &self.look {
            k.f32s(&l.tone);
            k.f32s(&l.light);
            l.uv.iter().for_each(|uv| k.f32s(uv));
            k.u32(l.surface.index() as u32);
            k.u32(l.image.map_or(u32::MAX, |i| i));
        }
        for im in &self.images {
            k.u32(im.width);
            k.u32(im.height);
            k.bytes(im.texels.as_flattened());
        }
        k.finish()
    }

    /// Bytes held by the mesh (allocated, for cache budgets).
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.scene_id.capacity()
            + held(&self.positions)
            + held(&self.object)
            + held(&self.color)
            + held(&self.objects)
            + held(&self.class_of)
            + held(&self.look)
            + held(&self.images)
            + self.images.iter().map(|im| held(&im.texels)).sum::<usize>()
    }

    /// Triangulate a scene (with the shared [`vlnverse_env::geometry`] code) and bake its light
    /// ([`vlnverse_env::light::bake`], the light `scene.glb` holds).
    pub fn new(scene: &Scene) -> Result<Self> {
        Self::with_light(scene, &bake(scene))
    }

    /// [`SceneMesh::new`] with light already baked for this scene.
    pub fn with_light(scene: &Scene, light: &BakedLight) -> Result<Self> {
        let n_tri = scene.triangle_count();
        let max_id = scene.objects.iter().map(|o| o.id).max().unwrap_or(0) as usize;
        let mut class_of = vec![0u16; max_id + 1];
        for o in &scene.objects {
            class_of[o.id as usize] = o.class.id();
        }
        let mut m = SceneMesh {
            scene_id: scene.id.clone(),
            positions: Vec::with_capacity(n_tri * 3),
            object: Vec::with_capacity(n_tri),
            color: Vec::with_capacity(n_tri),
            objects: Vec::new(),
            class_of,
            look: Vec::with_capacity(n_tri),
            images: Vec::new(),
            prepared_file: None,
        };
        // The scene's textures, deduplicated, with the index each got in `images`.
        let mut seen: Vec<&MeshTexture> = Vec::new();
        let mut part_index = 0;
        // Encoded intensity of an 8-bit light value.
        let encoded: Vec<f32> = (0..256).map(|i| (i as f32 / 255.0).powf(GAMMA)).collect();
        let light_tint = if light.tint == [0.0; 3] {
            [1.0; 3]
        } else {
            light.tint
        };
        for o in &scene.objects {
            let surfaces = part_surfaces(scene, o);
            let cell = cell_of(scene, o);
            for (part, &surface) in o.parts.iter().zip(&surfaces) {
                let texels = TEX_SIZE as f32 / surface.repeat();
                let tint = surface.tint();
                let tm = triangulate_part_cells(part, &o.pose, cell);
                // A picture spans its canvas once: the part's world box.
                let canvas = surface.is_picture().then(|| {
                    tm.positions.iter().fold(
                        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
                        |(lo, hi), p| {
                            let p = Vec3::from_array(*p);
                            (lo.min(p), hi.max(p))
                        },
                    )
                });
                let lights = light
                    .parts
                    .get(part_index)
                    .filter(|l| l.len() == tm.positions.len());
                part_index += 1;
                // 8-bit base colour, as the GPU's vertices.
                let base = part
                    .color
                    .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() / 255.0);
                let tone = [0, 1, 2].map(|k| (base[k] * tint[k] * light_tint[k]).powf(GAMMA));
                // An imported image replaces the surface texture when it fits the vertices.
                let image = match &part.shape {
                    Shape::Mesh(md)
                        if md.uvs.len() == tm.positions.len()
                            && md.texture.as_ref().is_some_and(MeshTexture::is_valid) =>
                    {
                        md.texture.as_ref().map(|t| (t, &md.uvs))
                    }
                    _ => None,
                };
                let image = image.map(|(t, uvs)| {
                    let same = |s: &&MeshTexture| {
                        std::sync::Arc::ptr_eq(&s.texels, &t.texels)
                            || (s.width, s.height, &s.texels) == (t.width, t.height, &t.texels)
                    };
                    let idx = match seen.iter().position(same) {
                        Some(i) => i,
                        None => {
                            seen.push(t);
                            m.images.push(ImageTexture {
                                width: t.width,
                                height: t.height,
                                texels: t.texels.to_vec(),
                            });
                            seen.len() - 1
                        }
                    };
                    let f = t
                        .factor
                        .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() / 255.0);
                    let tone = [0, 1, 2].map(|k| (f[k] * light_tint[k]).powf(GAMMA));
                    (idx as u32, tone, uvs, [t.width as f32, t.height as f32])
                });
                for t in &tm.indices {
                    let v = t.map(|i| Vec3::from_array(tm.positions[i as usize]));
                    // The green channel carries the intensity (the light's tint is in `tone`).
                    let corner_light =
                        t.map(|i| encoded[lights.map_or(200, |l| l[i as usize][1]) as usize]);
                    let uv = t.map(|i| {
                        let i = i as usize;
                        let (p, n) = (
                            Vec3::from_array(tm.positions[i]),
                            Vec3::from_array(tm.normals[i]),
                        );
                        if let Some((lo, hi)) = canvas {
                            // Half a texel in from each edge, so no edge wraps round.
                            let span = TEX_SIZE as f32 - 1.0;
                            let [u, v] = picture_uv(p, n, lo, hi);
                            return [0.5 + u * span, 0.5 + v * span];
                        }
                        let [u, v] = box_uv(p, n);
                        [u * texels, v * texels]
                    });
                    m.push(v, o.id, part.color);
                    m.look.push(match image {
                        Some((idx, tone, uvs, [w, h])) => TriLook {
                            tone,
                            light: corner_light,
                            uv: t.map(|i| {
                                let [u, v] = uvs[i as usize];
                                [u * w, v * h]
                            }),
                            surface: Surface::Plain,
                            image: Some(idx),
                        },
                        None => TriLook {
                            tone,
                            light: corner_light,
                            uv,
                            surface,
                            image: None,
                        },
                    });
                }
            }
        }
        // Cut faces made more triangles than the scene's count: give back the spare room.
        m.positions.shrink_to_fit();
        m.object.shrink_to_fit();
        m.color.shrink_to_fit();
        m.objects.shrink_to_fit();
        m.look.shrink_to_fit();
        if m.object.is_empty() {
            return Err(SensorError::Scene {
                scene: scene.id.clone(),
                message: "no triangles to render (every object has no parts)".into(),
            });
        }
        Ok(m)
    }

    fn push(&mut self, v: [Vec3; 3], object: u32, color: [f32; 3]) {
        let i = self.object.len();
        self.positions.extend_from_slice(&v);
        self.object.push(object);
        self.color.push(color);
        match self.objects.last_mut() {
            Some(r) if r.id == object => {
                r.count += 1;
                v.iter().for_each(|p| r.bbox.extend(*p));
            }
            _ => {
                let mut bbox = Aabb::EMPTY;
                v.iter().for_each(|p| bbox.extend(*p));
                self.objects.push(ObjectRange {
                    id: object,
                    first: i as u32,
                    count: 1,
                    bbox,
                });
            }
        }
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.object.len()
    }

    /// Class id of an object id (0 for 0 or unknown).
    pub fn class(&self, id: u32) -> u16 {
        self.class_of.get(id as usize).copied().unwrap_or(0)
    }

    /// sRGB colour of triangle `t` at the world point `q` on it: baked light and texture, the
    /// reference for the rasteriser's per-pixel resolve (the ray caster uses it).
    pub fn shade(&self, t: usize, q: Vec3) -> [u8; 3] {
        let [a, b, c] = [0, 1, 2].map(|k| self.positions[3 * t + k]);
        let (e1, e2, d) = (b - a, c - a, q - a);
        let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let den = d00 * d11 - d01 * d01;
        let (u, v) = if den.abs() > 1e-20 {
            let (d20, d21) = (d.dot(e1), d.dot(e2));
            ((d11 * d20 - d01 * d21) / den, (d00 * d21 - d01 * d20) / den)
        } else {
            (0.0, 0.0)
        };
        let Some(l) = self.look.get(t) else {
            return self.color[t].map(crate::shading::encode);
        };
        let at = |x: [f32; 3]| x[0] + u * (x[1] - x[0]) + v * (x[2] - x[0]);
        if let Some(img) = l.image.and_then(|i| self.images.get(i as usize)) {
            let texel = img.texel(at(l.uv.map(|p| p[0])), at(l.uv.map(|p| p[1])));
            let k = at(l.light);
            return [0, 1, 2].map(|c| {
                (l.tone[c] * k * texel[c] as f32)
                    .clamp(0.0, 255.0)
                    .round_ties_even() as u8
            });
        }
        let bias = (TEX_SIZE * 256) as f32;
        let mask = TEX_SIZE as i32 - 1;
        let tu = ((at(l.uv.map(|p| p[0])) + bias) as i32) & mask;
        let tv = ((at(l.uv.map(|p| p[1])) + bias) as i32) & mask;
        let texel = l.surface.luma_encoded()[(tv * TEX_SIZE as i32 + tu) as usize] as f32;
        let k = at(l.light) * texel;
        l.tone
            .map(|c| (c * k).clamp(0.0, 255.0).round_ties_even() as u8)
    }

    /// Geometric unit normal of triangle `i`.
    pub fn normal(&self, i: usize) -> Vec3 {
        let [a, b, c] = [0, 1, 2].map(|k| self.positions[3 * i + k]);
        (b - a).cross(c - a).normalize_or(Vec3::Y)
    }
}
