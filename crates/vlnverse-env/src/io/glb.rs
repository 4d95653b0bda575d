//! `scene.glb`: a glTF 2.0 binary with one node per object.
//!
//! Layout (see `docs/formats.md`): node `i` (a root node) is object `i` of the scene, named after
//! the object, with the object pose as its translation/rotation and `extras` holding id, class
//! and physics. Its mesh holds the object's primitive parts (cuboids, cylinders, spheres) in
//! object-local coordinates, one glTF primitive per distinct (colour, surface material), with
//! the baked light ([`crate::light`]) as `COLOR_0` and box-projected texture coordinates
//! ([`crate::material`]) as `TEXCOORD_0`; materials are unlit (`KHR_materials_unlit`: the light
//! is in the vertices) and carry the surface's procedural texture. Mesh parts
//! ([`Shape::Mesh`]) each get a child node carrying the part transform and a mesh of their own;
//! the `k`-th mesh part of the scene (object order, then part order) is glTF mesh `k`, which is
//! what [`MeshData::glb_mesh`] names. A mesh part with its own base-colour image
//! ([`MeshData::texture`], imported homes) is written with its texture coordinates as
//! `TEXCOORD_0` and a material whose `baseColorTexture` is that image (an RGB PNG in the BIN
//! chunk); [`restore_mesh_parts`] reads both back.

use super::glb_light::GlbColours;
use crate::error::{EnvError, Result};
use crate::geometry::{
    mesh_with_normals, triangle_count_cells, triangulate_cells, vertex_count_cells, TriMesh,
};
use crate::light::{bake, cell_of, BakedLight};
use crate::material::{box_uv, part_surfaces, picture_uv, Surface, TEX_SIZE};
use crate::scene::{MeshData, MeshTexture, Motion, Pose, Scene, SceneObject, Shape};
use glam::Vec3;
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

const GLB_MAGIC: u32 = 0x4654_6C67; // "glTF"
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_BYTE: u32 = 5121;
const UNSIGNED_INT: u32 = 5125;

/// An `f32` as the `f64` with the same shortest decimal form, so the JSON reads `0.85` rather
/// than `0.8500000238418579` (and still parses back to the same `f32`).
fn short(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(x as f64)
}

fn short_all<const N: usize>(v: [f32; N]) -> [f64; N] {
    v.map(short)
}

/// Pad to a multiple of 4 bytes (GLB chunks and buffer views are 4-byte aligned).
fn pad4(v: &mut Vec<u8>, byte: u8) {
    let n = (4 - v.len() % 4) % 4;
    v.resize(v.len() + n, byte);
}

/// Give every mesh part of the scene its canonical glTF mesh index (`k` for the `k`-th mesh
/// part in object order, then part order), the index [`write_glb`] uses.
pub fn assign_glb_mesh_indices(scene: &mut Scene) {
    let mut k = 0u32;
    for o in &mut scene.objects {
        for p in &mut o.parts {
            if let Shape::Mesh(m) = &mut p.shape {
                m.glb_mesh = Some(k);
                k += 1;
            }
        }
    }
}

/// Accumulates the BIN chunk, buffer views and accessors.
#[derive(Default)]
struct Bin {
    data: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Bin {
    /// Append a buffer view of `n` bytes written by `fill` (4-byte aligned start).
    fn view(&mut self, n: usize, target: u32, fill: impl FnOnce(&mut Vec<u8>)) -> usize {
        pad4(&mut self.data, 0);
        let offset = self.data.len();
        self.data.reserve(n);
        fill(&mut self.data);
        debug_assert_eq!(self.data.len(), offset + n);
        self.views.push(json!({
            "buffer": 0, "byteOffset": offset, "byteLength": n, "target": target
        }));
        self.views.len() - 1
    }

    fn vec3(&mut self, v: &[[f32; 3]], with_bounds: bool) -> usize {
        let view = self.view(v.len() * 12, ARRAY_BUFFER, |d| {
            for x in v.iter().flatten() {
                d.extend_from_slice(&x.to_le_bytes());
            }
        });
        let mut acc = json!({
            "bufferView": view, "componentType": FLOAT, "count": v.len(), "type": "VEC3"
        });
        if with_bounds {
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for p in v {
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
            acc["min"] = json!(short_all(lo));
            acc["max"] = json!(short_all(hi));
        }
        self.accessors.push(acc);
        self.accessors.len() - 1
    }

    fn indices(&mut self, t: &[[u32; 3]]) -> usize {
        let view = self.view(t.len() * 12, ELEMENT_ARRAY_BUFFER, |d| {
            for x in t.iter().flatten() {
                d.extend_from_slice(&x.to_le_bytes());
            }
        });
        self.accessors.push(json!({
            "bufferView": view, "componentType": UNSIGNED_INT, "count": t.len() * 3, "type": "SCALAR"
        }));
        self.accessors.len() - 1
    }

    fn primitive(&mut self, m: &TriMesh, material: usize) -> Value {
        let pos = self.vec3(&m.positions, true);
        let nrm = self.vec3(&m.normals, false);
        let idx = self.indices(&m.indices);
        json!({
            "attributes": {"POSITION": pos, "NORMAL": nrm},
            "indices": idx,
            "material": material,
            "mode": 4
        })
    }

    /// A primitive with baked light (`COLOR_0`, RGBA8 normalised) and texture coordinates.
    fn lit_primitive(&mut self, m: &Lit, material: usize) -> Value {
        let mut p = self.primitive(&m.mesh, material);
        let view = self.view(m.light.len() * 4, ARRAY_BUFFER, |d| {
            for c in &m.light {
                d.extend_from_slice(&[c[0], c[1], c[2], 255]);
            }
        });
        self.accessors.push(json!({
            "bufferView": view, "componentType": UNSIGNED_BYTE, "normalized": true,
            "count": m.light.len(), "type": "VEC4"
        }));
        p["attributes"]["COLOR_0"] = json!(self.accessors.len() - 1);
        let view = self.view(m.uv.len() * 8, ARRAY_BUFFER, |d| {
            for x in m.uv.iter().flatten() {
                d.extend_from_slice(&x.to_le_bytes());
            }
        });
        self.accessors.push(json!({
            "bufferView": view, "componentType": FLOAT, "count": m.uv.len(), "type": "VEC2"
        }));
        p["attributes"]["TEXCOORD_0"] = json!(self.accessors.len() - 1);
        p
    }

    /// A buffer view holding raw bytes (an image), no target.
    fn blob(&mut self, bytes: &[u8]) -> usize {
        pad4(&mut self.data, 0);
        let offset = self.data.len();
        self.data.extend_from_slice(bytes);
        self.views
            .push(json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()}));
        self.views.len() - 1
    }
}

/// Triangles with their per-vertex light and texture coordinates.
#[derive(Default)]
struct Lit {
    mesh: TriMesh,
    light: Vec<[u8; 3]>,
    uv: Vec<[f32; 2]>,
}

impl Lit {
    /// Append part `shape` placed by `local` (object frame), its light and texture coordinates
    /// from the world frame (`object` pose).
    fn append(
        &mut self,
        tri: &TriMesh,
        local: &Pose,
        object: &Pose,
        light: &[[u8; 3]],
        surface: Surface,
    ) {
        let start = self.mesh.positions.len();
        self.mesh.append_transformed(tri, local);
        let q = object.quat();
        let r = surface.repeat();
        let world: Vec<Vec3> = self.mesh.positions[start..]
            .iter()
            .map(|p| object.transform_point(Vec3::from_array(*p)))
            .collect();
        // A picture spans its canvas once (half a texel in from each edge): the part's box.
        let canvas = surface.is_picture().then(|| {
            world.iter().fold(
                (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
                |(lo, hi), p| (lo.min(*p), hi.max(*p)),
            )
        });
        let edge = 0.5 / TEX_SIZE as f32;
        for (i, w) in (start..self.mesh.positions.len()).zip(world) {
            let n = q * Vec3::from_array(self.mesh.normals[i]);
            self.uv.push(match canvas {
                Some((lo, hi)) => {
                    let [u, v] = picture_uv(w, n, lo, hi);
                    [edge + u * (1.0 - 2.0 * edge), edge + v * (1.0 - 2.0 * edge)]
                }
                None => {
                    let [u, v] = box_uv(w, n);
                    [u / r, v / r]
                }
            });
        }
        // Light is per vertex of the part's triangulation; grey if it does not fit.
        let n = self.mesh.positions.len() - start;
        if light.len() == n {
            self.light.extend_from_slice(light);
        } else {
            self.light.extend(std::iter::repeat_n([200u8; 3], n));
        }
    }
}

/// Where a glTF texture's image comes from.
#[derive(Clone, Copy, PartialEq)]
enum TexSource {
    /// A procedural surface texture.
    Surface(Surface),
    /// An imported image: index into [`Materials::images`].
    Image(usize),
}

/// Materials deduplicated by (colour, metallic, surface) in order of first use; textures
/// (one per surface or imported image used) likewise.
#[derive(Default)]
struct Materials {
    index: BTreeMap<([u32; 3], bool, Option<Surface>), usize>,
    /// Materials of imported images, by (factor, image).
    image_index: BTreeMap<([u32; 3], usize), usize>,
    list: Vec<Value>,
    textures: Vec<TexSource>,
    /// Distinct imported images, in order of first use.
    images: Vec<MeshTexture>,
}

impl Materials {
    /// A textured, unlit material for a part with baked light.
    fn lit(&mut self, color: [f32; 3], surface: Surface) -> usize {
        let key = (color.map(f32::to_bits), surface.metallic(), Some(surface));
        if let Some(&i) = self.index.get(&key) {
            return i;
        }
        let tex = self.texture(TexSource::Surface(surface));
        let srgb = color.map(|c| (linear_to_srgb(c) * 255.0).round() as u8);
        let name = format!(
            "{}_{:02x}{:02x}{:02x}",
            surface.name(),
            srgb[0],
            srgb[1],
            srgb[2]
        );
        let metal = surface.metallic();
        self.list.push(json!({
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": [short(color[0]), short(color[1]), short(color[2]), 1.0],
                "baseColorTexture": {"index": tex},
                "metallicFactor": if metal { 0.6 } else { 0.0 },
                "roughnessFactor": if metal { 0.35 } else { 0.8 }
            },
            "extensions": {"KHR_materials_unlit": {}},
            "doubleSided": false
        }));
        self.index.insert(key, self.list.len() - 1);
        self.list.len() - 1
    }

    /// Index of the glTF texture for `src`, added on first use.
    fn texture(&mut self, src: TexSource) -> usize {
        match self.textures.iter().position(|t| *t == src) {
            Some(t) => t,
            None => {
                self.textures.push(src);
                self.textures.len() - 1
            }
        }
    }

    /// An unlit material showing an imported image times `factor` (the part has baked light).
    fn image(&mut self, t: &MeshTexture) -> usize {
        let img = match self
            .images
            .iter()
            .position(|i| Arc::ptr_eq(&i.texels, &t.texels) || i == t)
        {
            Some(i) => i,
            None => {
                self.images.push(t.clone());
                self.images.len() - 1
            }
        };
        let key = (t.factor.map(f32::to_bits), img);
        if let Some(&i) = self.image_index.get(&key) {
            return i;
        }
        let tex = self.texture(TexSource::Image(img));
        let f = t.factor;
        self.list.push(json!({
            "name": format!("image{img}_{}", self.list.len()),
            "pbrMetallicRoughness": {
                "baseColorFactor": [short(f[0]), short(f[1]), short(f[2]), 1.0],
                "baseColorTexture": {"index": tex},
                "metallicFactor": 0.0,
                "roughnessFactor": 0.8
            },
            "extensions": {"KHR_materials_unlit": {}},
            "doubleSided": false
        }));
        self.image_index.insert(key, self.list.len() - 1);
        self.list.len() - 1
    }

    fn get(&mut self, color: [f32; 3], metal: bool) -> usize {
        let key = (color.map(f32::to_bits), metal, None);
        if let Some(&i) = self.index.get(&key) {
            return i;
        }
        let srgb = color.map(|c| (linear_to_srgb(c) * 255.0).round() as u8);
        let name = format!(
            "{}{:02x}{:02x}{:02x}",
            if metal { "metal_" } else { "color_" },
            srgb[0],
            srgb[1],
            srgb[2]
        );
        self.list.push(json!({
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": [short(color[0]), short(color[1]), short(color[2]), 1.0],
                "metallicFactor": if metal { 0.6 } else { 0.0 },
                "roughnessFactor": if metal { 0.35 } else { 0.8 }
            },
            "doubleSided": false
        }));
        self.index.insert(key, self.list.len() - 1);
        self.list.len() - 1
    }
}

/// Linear -> sRGB transfer function for one channel in `[0, 1]`.
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// The `extras` object of an object's node.
pub fn node_extras(o: &SceneObject) -> Value {
    json!({
        "id": o.id,
        "class": o.class.name(),
        "class_id": o.class.id(),
        "room": o.room,
        "color": o.color,
        "material": o.material,
        "mass": short(o.physics.mass),
        "friction": short(o.physics.friction),
        "motion": match o.physics.motion { Motion::Static => "static", Motion::Dynamic => "dynamic" },
        "supported_by": o.supported_by,
    })
}

fn set_pose(node: &mut Value, pose: &Pose) {
    if pose.position != [0.0; 3] {
        node["translation"] = json!(short_all(pose.position));
    }
    if pose.rotation != [0.0, 0.0, 0.0, 1.0] {
        node["rotation"] = json!(short_all(pose.quat().normalize().to_array()));
    }
}

/// Encode a scene as a glTF 2.0 binary (`scene.glb`). Deterministic: the same scene gives the
/// same bytes.
pub fn write_glb(scene: &Scene) -> Vec<u8> {
    write_glb_with(scene, &bake(scene))
}

/// [`write_glb`] with light already baked ([`crate::light::bake`] of this scene).
pub fn write_glb_with(scene: &Scene, light: &BakedLight) -> Vec<u8> {
    let mut bin = Bin::default();
    let mut mats = Materials::default();
    let mut meshes: Vec<Value> = Vec::new();
    let mut nodes: Vec<Value> = Vec::new();
    let no_light: Vec<[u8; 3]> = Vec::new();
    let light_of = |k: usize| light.parts.get(k).unwrap_or(&no_light);
    // Mesh parts first so their glTF mesh index is their canonical index.
    let mut part_index = 0usize;
    for o in &scene.objects {
        let surfaces = part_surfaces(scene, o);
        for (k, p) in o.parts.iter().enumerate() {
            let surface = surfaces[k];
            if let Shape::Mesh(m) = &p.shape {
                // An imported image replaces the surface texture when it fits the vertices.
                let image = m
                    .texture
                    .as_ref()
                    .filter(|t| t.is_valid() && m.uvs.len() == m.positions.len());
                let mat = match image {
                    Some(t) => mats.image(t),
                    None => mats.lit(p.color, surface),
                };
                let tri = mesh_with_normals(&m.positions, &m.indices);
                let prims = if tri.indices.is_empty() {
                    vec![]
                } else {
                    let mut lit = Lit::default();
                    lit.append(
                        &tri,
                        &Pose::IDENTITY,
                        &o.pose.mul(&p.transform),
                        light_of(part_index),
                        surface,
                    );
                    if image.is_some() {
                        lit.uv.clone_from(&m.uvs);
                    }
                    vec![bin.lit_primitive(&lit, mat)]
                };
                meshes.push(json!({"name": format!("{}/part{k}", o.name), "primitives": prims}));
            }
            part_index += 1;
        }
    }
    let n_objects = scene.objects.len();
    let mut children_nodes: Vec<Value> = Vec::new();
    let mut mesh_part = 0usize;
    let mut part_index = 0usize;
    for o in &scene.objects {
        let surfaces = part_surfaces(scene, o);
        // Group primitive parts by material, in order of first appearance.
        let mut groups: Vec<(usize, Lit)> = Vec::new();
        let mut children = Vec::new();
        for (k, p) in o.parts.iter().enumerate() {
            let surface = surfaces[k];
            let part_light = light_of(part_index);
            part_index += 1;
            let mat = mats.lit(p.color, surface);
            if let Shape::Mesh(_) = p.shape {
                let mut child = json!({"name": format!("{}/part{k}", o.name), "mesh": mesh_part});
                set_pose(&mut child, &p.transform);
                if meshes[mesh_part]["primitives"]
                    .as_array()
                    .is_none_or(|a| a.is_empty())
                {
                    child.as_object_mut().map(|c| c.remove("mesh"));
                }
                children.push(n_objects + children_nodes.len());
                children_nodes.push(child);
                mesh_part += 1;
                continue;
            }
            let tri = triangulate_cells(&p.shape, cell_of(scene, o));
            let gi = match groups.iter().position(|(m, _)| *m == mat) {
                Some(gi) => gi,
                None => {
                    groups.push((mat, Lit::default()));
                    groups.len() - 1
                }
            };
            groups[gi]
                .1
                .append(&tri, &p.transform, &o.pose, part_light, surface);
        }
        let mut node = json!({"name": o.name, "extras": node_extras(o)});
        set_pose(&mut node, &o.pose);
        let prims: Vec<Value> = groups
            .iter()
            .filter(|(_, m)| !m.mesh.indices.is_empty())
            .map(|(mat, m)| bin.lit_primitive(m, *mat))
            .collect();
        if !prims.is_empty() {
            meshes.push(json!({"name": o.name, "primitives": prims}));
            node["mesh"] = json!(meshes.len() - 1);
        }
        if !children.is_empty() {
            node["children"] = json!(children);
        }
        nodes.push(node);
    }
    // A mesh without primitives is invalid glTF; empty mesh parts (whose nodes dropped the
    // reference) keep their index with one degenerate triangle, flagged so readers skip it.
    for m in &mut meshes {
        if m["primitives"].as_array().is_some_and(|a| a.is_empty()) {
            let tri = TriMesh {
                positions: vec![[0.0; 3]; 3],
                normals: vec![[0.0, 1.0, 0.0]; 3],
                indices: vec![[0, 1, 2]],
            };
            let mat = mats.get([0.5; 3], false);
            m["primitives"] = json!([bin.primitive(&tri, mat)]);
            m["extras"] = json!({"empty": true});
        }
    }
    nodes.extend(children_nodes);
    let roots: Vec<usize> = (0..n_objects).collect();
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": concat!("vlnverse-rs ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
        "scenes": [{
            "name": scene.id,
            "nodes": roots,
            "extras": {"scene_id": scene.id, "source": scene.source, "format_version": scene.format_version}
        }],
        "nodes": nodes,
    });
    if !mats.textures.is_empty() {
        let mut images = Vec::new();
        for t in &mats.textures {
            let (name, png) = match *t {
                TexSource::Surface(s) => (s.name().to_string(), texture_png(s)),
                TexSource::Image(i) => (format!("image{i}"), image_png(&mats.images[i])),
            };
            let view = bin.blob(&png);
            images.push(json!({"name": name, "bufferView": view, "mimeType": "image/png"}));
        }
        doc["images"] = json!(images);
        doc["samplers"] =
            json!([{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}]);
        doc["textures"] = json!((0..images.len())
            .map(|i| json!({"sampler": 0, "source": i}))
            .collect::<Vec<_>>());
        doc["extensionsUsed"] = json!(["KHR_materials_unlit"]);
    }
    if !meshes.is_empty() {
        doc["meshes"] = json!(meshes);
        doc["materials"] = json!(mats.list);
        doc["accessors"] = json!(bin.accessors);
        doc["bufferViews"] = json!(bin.views);
    }
    pad4(&mut bin.data, 0);
    if !bin.data.is_empty() {
        doc["buffers"] = json!([{"byteLength": bin.data.len()}]);
    }
    let json_bytes = serde_json::to_vec(&doc).expect("glTF JSON is always serialisable");
    glb_container(&json_bytes, &bin.data)
}

/// The baked light a `scene.glb` written by [`write_glb_with`] holds as `COLOR_0`, back in the
/// per-part form of [`crate::light::bake`] (object order, then part order; the light colour
/// from [`crate::light::is_lit`]), so that loading a scene does not bake it again. `Ok(None)`
/// when the file's primitives do not fit the scene's parts (a file of another scene, or not
/// written by this writer): the caller then bakes. Errors only for a file that is not glTF.
pub fn read_baked_light(scene: &Scene, bytes: &[u8], path: &Path) -> Result<Option<BakedLight>> {
    // The colours read without the whole document where they are of the kind this writer
    // writes; through the `gltf` crate otherwise (the same colours either way).
    let colours = match GlbColours::read(bytes) {
        Some(c) => c,
        None => gltf_colours(bytes, path)?,
    };
    Ok(light_from(scene, &colours))
}

/// Every primitive's `COLOR_0` of a glTF file, read with the `gltf` crate.
pub(crate) fn gltf_colours(bytes: &[u8], path: &Path) -> Result<GlbColours> {
    let (gltf, blob) = parse_gltf(bytes, path)?;
    let blob = blob.as_deref();
    let get = |b: gltf::Buffer<'_>| match b.source() {
        gltf::buffer::Source::Bin => blob,
        gltf::buffer::Source::Uri(_) => None,
    };
    let colours = |p: &gltf::Primitive<'_>| -> Option<Vec<[u8; 3]>> {
        let c = p.reader(get).read_colors(0)?.into_rgba_u8();
        Some(c.map(|[r, g, b, _]| [r, g, b]).collect())
    };
    Ok(GlbColours::new(
        gltf.nodes().map(|n| n.mesh().map(|m| m.index())).collect(),
        gltf.meshes()
            .map(|m| m.primitives().map(|p| colours(&p)).collect())
            .collect(),
    ))
}

/// The baked light of `scene` from its file's colours; `None` when they do not fit its parts.
fn light_from(scene: &Scene, colours: &GlbColours) -> Option<BakedLight> {
    let n_parts: usize = scene.objects.iter().map(|o| o.parts.len()).sum();
    let mut parts: Vec<Vec<[u8; 3]>> = Vec::with_capacity(n_parts);
    for (i, o) in scene.objects.iter().enumerate() {
        // Node `i` is object `i`.
        let mesh = colours.node_mesh(i)?;
        let cell = cell_of(scene, o);
        // Parts grouped by material (colour and surface), in order of first appearance, as the
        // writer groups them (a sink's or a counter's worktop has a surface of its own, maybe
        // in the same colour as the rest); each group is one primitive unless it has no
        // triangles.
        let surfaces = part_surfaces(scene, o);
        let first = parts.len();
        let mut groups: Vec<(([u32; 3], Surface), Vec<(usize, usize, bool)>)> = Vec::new();
        for (p, &surface) in o.parts.iter().zip(&surfaces) {
            let k = parts.len();
            if let Shape::Mesh(m) = &p.shape {
                // A mesh part's light: the first primitive of its own glTF mesh.
                let light = m
                    .glb_mesh
                    .and_then(|g| colours.primitives(g as usize).first())
                    .and_then(Option::as_ref);
                match light {
                    Some(l) if l.len() == m.positions.len() => parts.push(l.clone()),
                    _ if m.indices.is_empty() => parts.push(Vec::new()),
                    _ => return None,
                }
                continue;
            }
            // What `triangulate_cells` gives the part, counted (the writer's vertices).
            let vertices = vertex_count_cells(&p.shape, cell);
            let drawn = triangle_count_cells(&p.shape, cell) > 0;
            let key = (p.color.map(f32::to_bits), surface);
            let g = match groups.iter().position(|g| g.0 == key) {
                Some(g) => g,
                None => {
                    groups.push((key, Vec::new()));
                    groups.len() - 1
                }
            };
            groups[g].1.push((k, vertices, drawn));
            parts.push(Vec::new());
        }
        let mut prims = mesh.map_or(&[][..], |m| colours.primitives(m)).iter();
        for (_, members) in groups.iter().filter(|g| g.1.iter().any(|m| m.2)) {
            let light = prims.next()?.as_ref()?;
            if light.len() != members.iter().map(|m| m.1).sum::<usize>() {
                return None;
            }
            let mut at = 0;
            for &(k, n, _) in members {
                parts[k] = light[at..at + n].to_vec();
                at += n;
            }
        }
        if prims.next().is_some() {
            return None;
        }
        debug_assert_eq!(parts.len() - first, o.parts.len());
    }
    Some(BakedLight {
        parts,
        tint: crate::light::tint_of(scene),
    })
}

/// A binary glTF container: the header, the JSON chunk (padded with spaces) and, when `bin`
/// is not empty, the BIN chunk (padded with zeros).
pub fn glb_container(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let (mut json, mut bin) = (json.to_vec(), bin.to_vec());
    pad4(&mut json, b' ');
    pad4(&mut bin, 0);
    let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(&GLB_MAGIC.to_le_bytes());
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        out.extend_from_slice(&bin);
    }
    out
}

/// A surface texture as PNG bytes (8-bit sRGB-encoded, as glTF base colour textures are).
fn texture_png(s: Surface) -> Vec<u8> {
    let data: Vec<u8> = s
        .texture()
        .iter()
        .flat_map(|c| c.map(|v| (linear_to_srgb(v as f32 / 255.0) * 255.0).round() as u8))
        .collect();
    let mut out = Vec::new();
    let enc = image::codecs::png::PngEncoder::new(&mut out);
    image::ImageEncoder::write_image(
        enc,
        &data,
        TEX_SIZE as u32,
        TEX_SIZE as u32,
        image::ExtendedColorType::Rgb8,
    )
    .expect("encoding a PNG into memory does not fail");
    out
}

/// An imported image as PNG bytes (its sRGB texels as they are).
fn image_png(t: &MeshTexture) -> Vec<u8> {
    let mut data: Vec<u8> = t.texels.iter().flatten().copied().collect();
    // A texture whose texels do not fill its sides (hand-built scenes) is padded white rather
    // than failing the whole file; the importer always fills them.
    let (w, h) = (t.width.max(1), t.height.max(1));
    data.resize(3 * w as usize * h as usize, 255);
    let mut out = Vec::new();
    let enc = image::codecs::png::PngEncoder::new(&mut out);
    image::ImageEncoder::write_image(enc, &data, w, h, image::ExtendedColorType::Rgb8)
        .expect("encoding a PNG of whole rows into memory does not fail");
    out
}

/// A node read back from a `.glb`.
#[derive(Clone, Debug, PartialEq)]
pub struct GlbNode {
    /// Node name.
    pub name: Option<String>,
    /// Local translation.
    pub translation: [f32; 3],
    /// Local rotation `[x, y, z, w]`.
    pub rotation: [f32; 4],
    /// The node's mesh index.
    pub mesh: Option<u32>,
    /// Child node indices.
    pub children: Vec<u32>,
    /// The `extras` JSON, if any.
    pub extras: Option<Value>,
}

/// A mesh read back from a `.glb`: the triangles of all its primitives, concatenated.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GlbMesh {
    /// Mesh name.
    pub name: Option<String>,
    /// Vertex positions in the mesh's frame.
    pub positions: Vec<[f32; 3]>,
    /// Triangles (indices into `positions`).
    pub indices: Vec<[u32; 3]>,
    /// Number of glTF primitives.
    pub primitives: usize,
    /// `TEXCOORD_0` of every vertex, when every primitive has it (else empty).
    pub uvs: Vec<[f32; 2]>,
    /// The image of the first primitive's `baseColorTexture`, if any.
    pub image: Option<u32>,
}

/// An image of a `.glb` stored in its binary chunk, still encoded.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GlbImage {
    /// `mimeType` (empty when not given).
    pub mime: String,
    /// The encoded bytes (empty when the image is not in the binary chunk).
    pub bytes: Vec<u8>,
}

/// The content of a `.glb` as far as scenes need it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GlbContents {
    /// Every node, in file order.
    pub nodes: Vec<GlbNode>,
    /// Root nodes of the default scene.
    pub roots: Vec<u32>,
    /// Every mesh, in file order.
    pub meshes: Vec<GlbMesh>,
    /// Every image, in file order.
    pub images: Vec<GlbImage>,
}

/// Why the data of accessor `acc` cannot be read, for errors: no bufferView, no buffer data
/// (`data_len` is `None`: an external buffer that was not loaded), or its last element lying
/// beyond its bufferView or buffer. `data_len` is the length of the loaded buffer data.
pub fn accessor_problem(acc: &gltf::Accessor<'_>, data_len: Option<usize>) -> String {
    let i = acc.index();
    let Some(view) = acc.view() else {
        return format!("accessor {i} has no bufferView (and no readable sparse data)");
    };
    let b = view.buffer().index();
    let Some(len) = data_len else {
        return format!(
            "accessor {i}: bufferView {} refers to buffer {b}, whose data is not in the file",
            view.index()
        );
    };
    let size = acc.size();
    let stride = view.stride().unwrap_or(size);
    let in_view = acc.offset() + stride * acc.count().saturating_sub(1) + size;
    format!(
        "accessor {i} is out of range: {} elements of {size} bytes from byteOffset {} end at \
         byte {in_view} of bufferView {} (byteLength {}), byte {} of buffer {b}, which holds \
         {len} bytes",
        acc.count(),
        acc.offset(),
        view.index(),
        view.length(),
        view.offset() + in_view
    )
}

/// Parse glTF (binary or JSON) as `gltf::Gltf::from_slice` does, with the same validation,
/// but with the BIN chunk borrowed from `bytes` rather than copied (~1.7 MB per generated
/// home, on every scene load). `path` only names the source in errors.
fn parse_gltf<'a>(
    bytes: &'a [u8],
    path: &Path,
) -> Result<(gltf::Document, Option<std::borrow::Cow<'a, [u8]>>)> {
    let invalid =
        |e: gltf::Error| EnvError::parse(path, format!("not a valid glTF 2.0 binary: {e}"));
    let (json, bin) = if bytes.starts_with(b"glTF") {
        let glb = gltf::binary::Glb::from_slice(bytes).map_err(invalid)?;
        (glb.json, glb.bin)
    } else {
        (std::borrow::Cow::Borrowed(bytes), None)
    };
    let root = gltf::json::deserialize::from_slice(&json)
        .map_err(|e| invalid(gltf::Error::Deserialize(e)))?;
    let document = gltf::Document::from_json(root).map_err(invalid)?;
    Ok((document, bin))
}

/// Read a `.glb` file (with the `gltf` crate).
pub fn read_glb(path: impl AsRef<Path>) -> Result<GlbContents> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|e| EnvError::io(path, e))?;
    read_glb_bytes(&bytes, path)
}

/// Parse `.glb` bytes; `path` only names the source in errors.
pub fn read_glb_bytes(bytes: &[u8], path: &Path) -> Result<GlbContents> {
    let (gltf, blob) = parse_gltf(bytes, path)?;
    let blob = blob.as_deref();
    let get = |b: gltf::Buffer<'_>| match b.source() {
        gltf::buffer::Source::Bin => blob,
        gltf::buffer::Source::Uri(_) => None,
    };
    let mut out = GlbContents::default();
    for n in gltf.nodes() {
        let (t, r, _) = n.transform().decomposed();
        let extras = match n.extras() {
            Some(raw) => Some(serde_json::from_str(raw.get()).map_err(|e| {
                EnvError::parse(
                    path,
                    format!("node {} `extras`: invalid JSON: {e}", n.index()),
                )
            })?),
            None => None,
        };
        out.nodes.push(GlbNode {
            name: n.name().map(str::to_string),
            translation: t,
            rotation: r,
            mesh: n.mesh().map(|m| m.index() as u32),
            children: n.children().map(|c| c.index() as u32).collect(),
            extras,
        });
    }
    if let Some(s) = gltf.default_scene().or_else(|| gltf.scenes().next()) {
        out.roots = s.nodes().map(|n| n.index() as u32).collect();
    }
    for m in gltf.meshes() {
        let mut mesh = GlbMesh {
            name: m.name().map(str::to_string),
            ..Default::default()
        };
        let empty = m
            .extras()
            .as_ref()
            .and_then(|raw| serde_json::from_str::<Value>(raw.get()).ok())
            .is_some_and(|v| v["empty"] == json!(true));
        for p in m.primitives().filter(|_| !empty) {
            let what = |x: &str| format!("mesh {} primitive {}: {x}", m.index(), p.index());
            if p.mode() != gltf::mesh::Mode::Triangles {
                return Err(EnvError::parse(path, what("mode is not TRIANGLES")));
            }
            let r = p.reader(get);
            let data_len =
                |a: &gltf::Accessor<'_>| a.view().and_then(|v| get(v.buffer())).map(<[u8]>::len);
            let base = mesh.positions.len() as u32;
            let pos: Vec<[f32; 3]> = match r.read_positions() {
                Some(it) => it.collect(),
                None => {
                    let why = match p.get(&gltf::Semantic::Positions) {
                        Some(a) => format!("POSITION: {}", accessor_problem(&a, data_len(&a))),
                        None => "no POSITION attribute".to_string(),
                    };
                    return Err(EnvError::parse(path, what(&why)));
                }
            };
            let n = pos.len() as u32;
            let idx: Vec<u32> = match (r.read_indices(), p.indices()) {
                (Some(i), _) => i.into_u32().collect(),
                (None, Some(a)) => {
                    let why = format!("indices: {}", accessor_problem(&a, data_len(&a)));
                    return Err(EnvError::parse(path, what(&why)));
                }
                (None, None) => (0..n).collect(),
            };
            if !idx.chunks_exact(3).remainder().is_empty() {
                return Err(EnvError::parse(
                    path,
                    what("index count is not a multiple of 3"),
                ));
            }
            if let Some(bad) = idx.iter().find(|&&i| i >= n) {
                return Err(EnvError::parse(
                    path,
                    what(&format!("index {bad} >= vertex count {n}")),
                ));
            }
            let uvs: Option<Vec<[f32; 2]>> = r
                .read_tex_coords(0)
                .map(|t| t.into_f32().collect())
                .filter(|t: &Vec<[f32; 2]>| t.len() == pos.len());
            match uvs {
                Some(t) if mesh.uvs.len() == mesh.positions.len() => mesh.uvs.extend(t),
                _ => mesh.uvs.clear(),
            }
            if mesh.primitives == 0 {
                mesh.image = p
                    .material()
                    .pbr_metallic_roughness()
                    .base_color_texture()
                    .map(|i| i.texture().source().index() as u32);
            }
            mesh.positions.extend(pos);
            mesh.indices.extend(
                idx.chunks_exact(3)
                    .map(|c| [c[0] + base, c[1] + base, c[2] + base]),
            );
            mesh.primitives += 1;
        }
        if mesh.uvs.len() != mesh.positions.len() {
            mesh.uvs.clear();
        }
        out.meshes.push(mesh);
    }
    for img in gltf.images() {
        out.images.push(match img.source() {
            gltf::image::Source::View { view, mime_type } => {
                let bytes = blob
                    .filter(|_| matches!(view.buffer().source(), gltf::buffer::Source::Bin))
                    .and_then(|b| b.get(view.offset()..view.offset() + view.length()))
                    .unwrap_or_default();
                GlbImage {
                    mime: mime_type.to_string(),
                    bytes: bytes.to_vec(),
                }
            }
            gltf::image::Source::Uri { mime_type, .. } => GlbImage {
                mime: mime_type.unwrap_or_default().to_string(),
                bytes: Vec::new(),
            },
        });
    }
    Ok(out)
}

/// Decode image `i` of `glb` as the texels of a `width x height` texture (errors without the
/// file name, which the caller adds).
fn decode_image(
    glb: &GlbContents,
    i: u32,
    size: (u32, u32),
) -> std::result::Result<Vec<[u8; 3]>, String> {
    let what = format!("images[{i}]");
    let img = glb
        .images
        .get(i as usize)
        .ok_or_else(|| format!("{what}: the file has {} images", glb.images.len()))?;
    if img.bytes.is_empty() {
        return Err(format!("{what}: no image data in the binary chunk"));
    }
    let dec = image::load_from_memory_with_format(&img.bytes, image::ImageFormat::Png)
        .map_err(|e| format!("{what} (mimeType `{}`): not a readable PNG: {e}", img.mime))?
        .into_rgb8();
    if dec.dimensions() != size {
        return Err(format!(
            "{what} is {}x{}, scene.json says {}x{}",
            dec.width(),
            dec.height(),
            size.0,
            size.1
        ));
    }
    Ok(dec.pixels().map(|p| p.0).collect())
}

/// Fill the vertex data of every mesh part of `scene` from `glb` (by [`MeshData::glb_mesh`]),
/// and the texture coordinates and image of parts with a [`MeshTexture`].
pub fn restore_mesh_parts(scene: &mut Scene, glb: &GlbContents, path: &Path) -> Result<()> {
    // Decoded images by glTF image index, shared between the parts that use them.
    let mut decoded: BTreeMap<u32, Arc<Vec<[u8; 3]>>> = BTreeMap::new();
    for o in &mut scene.objects {
        for (k, p) in o.parts.iter_mut().enumerate() {
            if let Shape::Mesh(MeshData {
                positions,
                indices,
                glb_mesh,
                uvs,
                texture,
            }) = &mut p.shape
            {
                let i = glb_mesh.ok_or_else(|| {
                    EnvError::parse(
                        path,
                        format!("object {} part {k}: mesh part without `glb_mesh`", o.id),
                    )
                })?;
                let m = glb.meshes.get(i as usize).ok_or_else(|| {
                    EnvError::parse(
                        path,
                        format!(
                            "object {} part {k}: `glb_mesh` = {i} but the file has {} meshes",
                            o.id,
                            glb.meshes.len()
                        ),
                    )
                })?;
                positions.clone_from(&m.positions);
                indices.clone_from(&m.indices);
                let Some(t) = texture else {
                    uvs.clear();
                    continue;
                };
                let here = |x: String| {
                    EnvError::parse(path, format!("object {} part {k} (mesh {i}): {x}", o.id))
                };
                if m.uvs.len() != m.positions.len() {
                    return Err(here(
                        "the part has a `texture` but the mesh has no TEXCOORD_0".into(),
                    ));
                }
                let img = m.image.ok_or_else(|| {
                    here("the part has a `texture` but the mesh has no baseColorTexture".into())
                })?;
                let texels = match decoded.get(&img) {
                    Some(d) => d.clone(),
                    None => {
                        let d =
                            Arc::new(decode_image(glb, img, (t.width, t.height)).map_err(here)?);
                        decoded.insert(img, d.clone());
                        d
                    }
                };
                t.texels = texels;
                if !t.is_valid() {
                    return Err(here(format!(
                        "texture {}x{}: sides must be powers of two <= {}",
                        t.width,
                        t.height,
                        MeshTexture::MAX_SIDE
                    )));
                }
                uvs.clone_from(&m.uvs);
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::occupancy::synthetic::grid_home;
    use crate::scene::Part;
    use crate::vocab::SemanticClass;

    /// A sink whose worktop is stone ("marble top") in the cabinet's colour: the writer gives
    /// the two parts a primitive each (one material per colour and surface), and the light
    /// read back must split them the same way (reading them as one primitive found no light
    /// there, and the home was baked again on every load; `home_0160` of the preset was such
    /// a home).
    #[test]
    fn parts_of_one_colour_on_two_surfaces_get_their_light_back() {
        let mut scene = grid_home(1, 1, 4.0, 3);
        scene.source = "procgen".into();
        let colour = [0.55, 0.5, 0.45];
        let cuboid = |h: [f32; 3], y: f32| Part {
            shape: Shape::Cuboid {
                half_extents: h,
                bevel: 0.0,
            },
            transform: Pose::from_yaw(Vec3::new(0.0, y, 0.0), 0.0),
            color: colour,
        };
        let id = scene.objects.iter().map(|o| o.id).max().unwrap_or(0) + 1;
        let mut sink = SceneObject::from_parts(
            id,
            SemanticClass::Sink,
            Pose::from_yaw(Vec3::new(1.0, 0.0, 1.0), 0.0),
            vec![
                cuboid([0.4, 0.4, 0.3], 0.4),
                cuboid([0.42, 0.02, 0.32], 0.82),
            ],
        );
        sink.features = vec!["marble top".into()];
        let surfaces = part_surfaces(&scene, &sink);
        assert_ne!(
            surfaces[0], surfaces[1],
            "the worktop has a surface of its own"
        );
        scene.objects.push(sink);
        let glb = write_glb(&scene);
        let read = read_baked_light(&scene, &glb, "scene.glb".as_ref()).unwrap();
        assert_eq!(read.as_ref(), Some(&*bake(&scene)));
    }
}
