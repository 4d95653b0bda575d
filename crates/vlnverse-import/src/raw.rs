//! Reading glTF 2.0 and Wavefront OBJ files into world-space triangle soups per node, before any
//! labelling. Axis conversion and unit scale are applied here, so everything downstream is in
//! metres, Y up.

use crate::{ImportOptions, UpAxis};
use glam::{Mat4, Vec3};
use serde::Deserialize;
use std::path::Path;
use std::sync::Arc;
use vlnverse_env::scene::MeshTexture;
use vlnverse_env::{EnvError, Motion, Result, SemanticClass};

/// What a label source (glTF extras or a mapping rule) says about some geometry.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct RawLabel {
    /// Semantic class (None only for `drop` rules).
    pub class: Option<SemanticClass>,
    /// Static or dynamic override.
    pub motion: Option<Motion>,
    /// Mass override (kg).
    pub mass: Option<f32>,
    /// Friction override.
    pub friction: Option<f32>,
    /// Colour word override.
    pub color: Option<String>,
    /// Material word override.
    pub material: Option<String>,
    /// Leave the geometry out.
    pub drop: bool,
}

/// One primitive: world-space triangles and a colour.
#[derive(Clone, Debug, Default)]
pub struct RawPrim {
    /// Vertex positions (metres, Y up, world frame).
    pub positions: Vec<Vec3>,
    /// Triangles.
    pub indices: Vec<[u32; 3]>,
    /// Linear RGB flat colour (base colour factor times the texture's mean).
    pub color: [f32; 3],
    /// Base-colour texture coordinates per vertex (empty without `texture`).
    pub uvs: Vec<[f32; 2]>,
    /// Base-colour texture (factor and resampled image).
    pub texture: Option<MeshTexture>,
    /// Material name, if any.
    pub material: Option<String>,
}

/// A node of the source file that carries geometry.
#[derive(Clone, Debug, Default)]
pub struct RawNode {
    /// Index of the node in the file (glTF node index, OBJ model index).
    pub index: usize,
    /// Node name (`node_<i>` when unnamed).
    pub name: String,
    /// Mesh name, if any.
    pub mesh_name: Option<String>,
    /// Label from the node's own `extras`.
    pub extras: Option<RawLabel>,
    /// Ancestors, nearest first: (node index, name, label from extras).
    pub ancestors: Vec<(usize, String, Option<RawLabel>)>,
    /// Primitives.
    pub prims: Vec<RawPrim>,
}

/// Required glTF extensions whose data we can ignore without losing geometry.
const IGNORABLE_REQUIRED: &[&str] = &[
    "KHR_materials_unlit",
    "KHR_texture_transform",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_transmission",
    "KHR_lights_punctual",
];

fn axis_matrix(opts: &ImportOptions) -> Mat4 {
    let s = opts.unit.meters();
    let axis = match opts.up {
        UpAxis::Y => Mat4::IDENTITY,
        // (x, y, z)_zup -> (x, z, -y)_yup: a -90 degree turn about +X.
        UpAxis::Z => Mat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, -1.0, 0.0, //
            0.0, 1.0, 0.0, 0.0, //
            0.0, 0.0, 0.0, 1.0,
        ]),
    };
    Mat4::from_scale(Vec3::splat(s)) * axis
}

/// Parse a label from a glTF `extras` object: `{"class": "bed", "motion": "dynamic", ...}`
/// (`semantic_class` is accepted as an alias of `class`).
fn label_from_extras(
    path: &Path,
    what: &str,
    extras: &gltf::json::Extras,
) -> Result<Option<RawLabel>> {
    let Some(raw) = extras else { return Ok(None) };
    let v: serde_json::Value = serde_json::from_str(raw.get())
        .map_err(|e| EnvError::parse(path, format!("{what}.extras: {e}")))?;
    let Some(obj) = v.as_object() else {
        return Ok(None);
    };
    let class_v = obj.get("class").or_else(|| obj.get("semantic_class"));
    let Some(class_s) = class_v.and_then(|c| c.as_str()) else {
        return Ok(None);
    };
    let class = SemanticClass::from_name(class_s).ok_or_else(|| {
        EnvError::parse(
            path,
            format!("{what}.extras.class = `{class_s}` is not a semantic class name"),
        )
    })?;
    let motion = match obj.get("motion").and_then(|m| m.as_str()) {
        None => None,
        Some("static") => Some(Motion::Static),
        Some("dynamic") => Some(Motion::Dynamic),
        Some(other) => {
            return Err(EnvError::parse(
                path,
                format!("{what}.extras.motion = `{other}`: expected `static` or `dynamic`"),
            ))
        }
    };
    let num = |k: &str| obj.get(k).and_then(|x| x.as_f64()).map(|x| x as f32);
    let text = |k: &str| obj.get(k).and_then(|x| x.as_str()).map(str::to_string);
    Ok(Some(RawLabel {
        class: Some(class),
        motion,
        mass: num("mass"),
        friction: num("friction"),
        color: text("color"),
        material: text("material"),
        drop: false,
    }))
}

fn gltf_err(path: &Path, e: gltf::Error) -> EnvError {
    let msg = match e {
        gltf::Error::Validation(errs) => {
            let list: Vec<String> = errs.iter().map(|(p, e)| format!("{p}: {e}")).collect();
            format!("invalid glTF: {}", list.join("; "))
        }
        other => format!("glTF: {other}"),
    };
    EnvError::parse(path, msg)
}

/// Read a `.gltf` or `.glb` file.
pub fn load_gltf(path: &Path, opts: &ImportOptions) -> Result<Vec<RawNode>> {
    let bytes = std::fs::read(path).map_err(|e| EnvError::io(path, e))?;
    if bytes.starts_with(b"glTF") && bytes.len() >= 12 {
        let declared = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize;
        if declared > bytes.len() {
            return Err(EnvError::parse(
                path,
                format!(
                    "truncated GLB: the header says {declared} bytes, the file has {}",
                    bytes.len()
                ),
            ));
        }
    }
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(&bytes).map_err(|e| gltf_err(path, e))?;
    let unsupported: Vec<&str> = document
        .extensions_required()
        .filter(|e| !IGNORABLE_REQUIRED.contains(e))
        .collect();
    if !unsupported.is_empty() {
        return Err(EnvError::parse(
            path,
            format!(
                "extensionsRequired = [{}]: not supported (decompress the file first, e.g. with \
                 `gltf-transform copy` or Blender)",
                unsupported.join(", ")
            ),
        ));
    }
    // Full validation now that we know the extensions are fine.
    gltf::Gltf::from_slice(&bytes).map_err(|e| gltf_err(path, e))?;
    let base = path.parent();
    for b in document.buffers() {
        if let gltf::buffer::Source::Uri(uri) = b.source() {
            if !uri.starts_with("data:") {
                let file = base.unwrap_or(Path::new(".")).join(uri);
                if !file.is_file() {
                    return Err(EnvError::parse(
                        path,
                        format!(
                            "buffers[{}].uri = `{uri}`: buffer file {} not found",
                            b.index(),
                            file.display()
                        ),
                    ));
                }
            }
        }
    }
    let buffers = gltf::import_buffers(&document, base, blob).map_err(|e| gltf_err(path, e))?;
    // Textures are optional: a missing or undecodable image leaves the parts that use it with
    // their base colour factor (and a warning), never an error.
    let images: Vec<Option<MeshTexture>> = document
        .images()
        .map(|img| {
            let decoded = gltf::image::Data::from_source(img.source(), base, &buffers)
                .map_err(|e| e.to_string())
                .and_then(|d| texture_of(&d));
            decoded
                .map_err(|e| {
                    tracing::warn!(
                        file = %path.display(),
                        image = img.index(),
                        "images[{}] not loaded ({e}); its parts keep their base colour factor",
                        img.index()
                    )
                })
                .ok()
        })
        .collect();
    let means: Vec<Option<[f32; 3]>> = images
        .iter()
        .map(|t| t.as_ref().map(MeshTexture::mean_linear))
        .collect();

    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or_else(|| EnvError::parse(path, "scenes: the file has no scene"))?;
    let root = axis_matrix(opts);
    let mut out = Vec::new();
    let mut stack: Vec<(gltf::Node, Mat4, Vec<(usize, String, Option<RawLabel>)>)> =
        scene.nodes().map(|n| (n, root, Vec::new())).collect();
    stack.reverse();
    let mut visited = 0usize;
    while let Some((node, parent, ancestors)) = stack.pop() {
        visited += 1;
        if visited > 1_000_000 {
            return Err(EnvError::parse(path, "nodes: hierarchy too deep or cyclic"));
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        let world = parent * local;
        let name = node
            .name()
            .map(str::to_string)
            .unwrap_or_else(|| format!("node_{}", node.index()));
        let what = format!("nodes[{}]", node.index());
        let extras = label_from_extras(path, &what, node.extras())?;
        if let Some(mesh) = node.mesh() {
            let flip = world.determinant() < 0.0;
            let mut prims = Vec::new();
            for prim in mesh.primitives() {
                if prim.mode() != gltf::mesh::Mode::Triangles {
                    tracing::debug!(node = %name, "skipping a non-triangle primitive");
                    continue;
                }
                let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
                let data_len = |a: &gltf::Accessor<'_>| {
                    a.view()
                        .and_then(|v| buffers.get(v.buffer().index()))
                        .map(|d| d.0.len())
                };
                let here = format!(
                    "meshes[{}].primitives[{}] (node `{name}`)",
                    mesh.index(),
                    prim.index()
                );
                let Some(pos) = reader.read_positions() else {
                    if let Some(a) = prim.get(&gltf::Semantic::Positions) {
                        return Err(EnvError::parse(
                            path,
                            format!(
                                "{here}.attributes.POSITION: {}",
                                vlnverse_env::io::glb::accessor_problem(&a, data_len(&a))
                            ),
                        ));
                    }
                    tracing::debug!(node = %name, "skipping a primitive without POSITION");
                    continue;
                };
                let positions: Vec<Vec3> = pos
                    .map(|p| world.transform_point3(Vec3::from_array(p)))
                    .collect();
                let n = positions.len() as u32;
                let flat: Vec<u32> = match (reader.read_indices(), prim.indices()) {
                    (Some(ix), _) => ix.into_u32().collect(),
                    (None, Some(a)) => {
                        return Err(EnvError::parse(
                            path,
                            format!(
                                "{here}.indices: {}",
                                vlnverse_env::io::glb::accessor_problem(&a, data_len(&a))
                            ),
                        ))
                    }
                    (None, None) => (0..n).collect(),
                };
                let mut indices = Vec::with_capacity(flat.len() / 3);
                for t in flat.chunks_exact(3) {
                    if t.iter().any(|&i| i >= n) {
                        return Err(EnvError::parse(
                            path,
                            format!(
                                "meshes[{}].primitives[{}].indices: index out of range ({} vertices)",
                                mesh.index(),
                                prim.index(),
                                n
                            ),
                        ));
                    }
                    indices.push(if flip {
                        [t[0], t[2], t[1]]
                    } else {
                        [t[0], t[1], t[2]]
                    });
                }
                let mat = prim.material();
                let pbr = mat.pbr_metallic_roughness();
                let f = pbr.base_color_factor();
                let factor = [f[0], f[1], f[2]].map(|c| c.clamp(0.0, 1.0));
                let mut color = factor;
                let mut texture = None;
                let mut uvs = Vec::new();
                if let Some(info) = pbr.base_color_texture() {
                    let img = info.texture().source().index();
                    let coords: Option<Vec<[f32; 2]>> = reader
                        .read_tex_coords(info.tex_coord())
                        .map(|t| t.into_f32().collect())
                        .filter(|t: &Vec<[f32; 2]>| {
                            t.len() == positions.len() && t.iter().flatten().all(|x| x.is_finite())
                        });
                    if let (Some(Some(t)), Some(Some(avg)), Some(c)) =
                        (images.get(img), means.get(img), coords)
                    {
                        color = [0, 1, 2].map(|k| factor[k] * avg[k]);
                        texture = Some(MeshTexture {
                            factor,
                            ..t.clone()
                        });
                        uvs = c;
                    } else if images.get(img).is_some_and(Option::is_some) {
                        tracing::warn!(
                            node = %name,
                            "{here}: baseColorTexture without usable TEXCOORD_{}; base colour factor only",
                            info.tex_coord()
                        );
                    }
                }
                if mat.index().is_none() {
                    color = crate::classify::DEFAULT_COLOR;
                }
                prims.push(RawPrim {
                    positions,
                    indices,
                    color,
                    uvs,
                    texture,
                    material: mat.name().map(str::to_string),
                });
            }
            out.push(RawNode {
                index: node.index(),
                name: name.clone(),
                mesh_name: mesh.name().map(str::to_string),
                extras: extras.clone(),
                ancestors: ancestors.clone(),
                prims,
            });
        }
        let mut chain = Vec::with_capacity(ancestors.len() + 1);
        chain.push((node.index(), name, extras));
        chain.extend(ancestors);
        let children: Vec<_> = node.children().collect();
        for c in children.into_iter().rev() {
            stack.push((c, world, chain.clone()));
        }
    }
    Ok(out)
}

/// Side a texture is resampled to: the power of two nearest to `n` (in ratio), at most
/// [`MeshTexture::MAX_SIDE`].
fn pow2_side(n: u32) -> u32 {
    let lo = if n.is_power_of_two() {
        n
    } else {
        n.next_power_of_two() / 2
    };
    // Between lo and 2 lo the geometric middle is lo * sqrt(2).
    let side = if (n as f64) > lo as f64 * std::f64::consts::SQRT_2 {
        lo * 2
    } else {
        lo
    };
    side.clamp(1, MeshTexture::MAX_SIDE)
}

/// An imported image as a texture: RGB bytes as encoded in the file (alpha dropped, grey
/// spread to RGB, 16-bit and float channels reduced to 8 bits), resampled to power-of-two
/// sides (box filter when shrinking, nearest texel when growing).
pub(crate) fn texture_of(img: &gltf::image::Data) -> std::result::Result<MeshTexture, String> {
    use gltf::image::Format;
    let (w, h) = (img.width as usize, img.height as usize);
    if w == 0 || h == 0 {
        return Err(format!("empty image ({w}x{h})"));
    }
    let (ch, bytes_per) = match img.format {
        Format::R8 => (1, 1),
        Format::R8G8 => (2, 1),
        Format::R8G8B8 => (3, 1),
        Format::R8G8B8A8 => (4, 1),
        Format::R16 => (1, 2),
        Format::R16G16 => (2, 2),
        Format::R16G16B16 => (3, 2),
        Format::R16G16B16A16 => (4, 2),
        Format::R32G32B32FLOAT => (3, 4),
        Format::R32G32B32A32FLOAT => (4, 4),
    };
    let px = ch * bytes_per;
    if img.pixels.len() < w * h * px {
        return Err(format!(
            "{w}x{h} image with {} bytes of pixels",
            img.pixels.len()
        ));
    }
    let channel = |p: &[u8], k: usize| -> u8 {
        let k = if ch < 3 { 0 } else { k };
        let b = &p[k * bytes_per..(k + 1) * bytes_per];
        match bytes_per {
            1 => b[0],
            // 16-bit channels are stored in native (little-endian) order by the decoder.
            2 => (u16::from_ne_bytes([b[0], b[1]]) >> 8) as u8,
            _ => {
                let f = f32::from_ne_bytes([b[0], b[1], b[2], b[3]]);
                (f.clamp(0.0, 1.0) * 255.0).round() as u8
            }
        }
    };
    let src: Vec<[u8; 3]> = img.pixels[..w * h * px]
        .chunks_exact(px)
        .map(|p| [0, 1, 2].map(|k| channel(p, k)))
        .collect();
    let (tw, th) = (pow2_side(w as u32) as usize, pow2_side(h as u32) as usize);
    let span = |t: usize, n: usize, s: usize| {
        let a = t * s / n;
        (a, ((t + 1) * s / n).max(a + 1))
    };
    let mut texels = Vec::with_capacity(tw * th);
    for ty in 0..th {
        let (y0, y1) = span(ty, th, h);
        for tx in 0..tw {
            let (x0, x1) = span(tx, tw, w);
            let mut sum = [0u64; 3];
            for row in src[y0 * w..y1 * w].chunks_exact(w) {
                for t in &row[x0..x1] {
                    for k in 0..3 {
                        sum[k] += t[k] as u64;
                    }
                }
            }
            let n = ((y1 - y0) * (x1 - x0)) as u64;
            texels.push(sum.map(|s| ((s + n / 2) / n) as u8));
        }
    }
    Ok(MeshTexture {
        factor: [1.0; 3],
        width: tw as u32,
        height: th as u32,
        texels: Arc::new(texels),
    })
}

/// Read a Wavefront `.obj` (and its `.mtl` files): one node per object/group, one primitive per
/// material, colours from `Kd`.
pub fn load_obj(path: &Path, opts: &ImportOptions) -> Result<Vec<RawNode>> {
    let load = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, materials) =
        tobj::load_obj(path, &load).map_err(|e| EnvError::parse(path, format!("OBJ: {e}")))?;
    let materials = match materials {
        Ok(m) => m,
        Err(e) => {
            tracing::warn!(file = %path.display(), "materials not loaded ({e}); using grey");
            Vec::new()
        }
    };
    let m = axis_matrix(opts);
    let mut by_name: Vec<RawNode> = Vec::new();
    for (i, model) in models.iter().enumerate() {
        let mesh = &model.mesh;
        let positions: Vec<Vec3> = mesh
            .positions
            .chunks_exact(3)
            .map(|p| m.transform_point3(Vec3::new(p[0], p[1], p[2])))
            .collect();
        let n = positions.len() as u32;
        let mut indices = Vec::with_capacity(mesh.indices.len() / 3);
        for t in mesh.indices.chunks_exact(3) {
            if t.iter().any(|&k| k >= n) {
                return Err(EnvError::parse(
                    path,
                    format!("object `{}`: face index out of range", model.name),
                ));
            }
            indices.push([t[0], t[1], t[2]]);
        }
        let mat = mesh.material_id.and_then(|k| materials.get(k));
        let color = mat
            .and_then(|m| m.diffuse)
            .unwrap_or(crate::classify::DEFAULT_COLOR);
        let prim = RawPrim {
            positions,
            indices,
            color,
            material: mat.map(|m| m.name.clone()),
            ..Default::default()
        };
        let name = if model.name.is_empty() {
            format!("object_{i}")
        } else {
            model.name.clone()
        };
        // tobj splits an object at each material change: put the pieces back together.
        match by_name.iter_mut().find(|n| n.name == name) {
            Some(node) => node.prims.push(prim),
            None => by_name.push(RawNode {
                index: i,
                name,
                prims: vec![prim],
                ..Default::default()
            }),
        }
    }
    Ok(by_name)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A GLB with one triangle mesh whose POSITION accessor claims 30 vertices of a 36-byte
    /// buffer (3 vertices).
    fn glb_out_of_range() -> Vec<u8> {
        let json = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"name":"sofa"}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"buffers":[{"byteLength":36}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":30,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}]}"#;
        vlnverse_env::io::glb::glb_container(json.as_bytes(), &[0u8; 36])
    }

    #[test]
    fn an_out_of_range_accessor_names_mesh_primitive_and_accessor() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("house.glb");
        std::fs::write(&path, glb_out_of_range()).unwrap();
        let e = load_gltf(&path, &ImportOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("house.glb")
                && e.contains("meshes[0].primitives[0]")
                && e.contains("POSITION")
                && e.contains("accessor 0 is out of range"),
            "{e}"
        );
        assert!(!e.contains("no triangle geometry"), "{e}");
    }
}
