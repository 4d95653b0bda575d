//! The per-vertex colours (`COLOR_0`) of a `scene.glb`, read without the whole glTF document:
//! what [`super::glb::read_baked_light`] needs of a file, on every home a renderer loads.
//!
//! Only the nodes' meshes, the meshes' primitives and their `COLOR_0` accessors, buffer views
//! and buffers are deserialised (the rest of the JSON is skipped); the colours are read straight
//! from the BIN chunk. This covers the colours [`super::glb::write_glb_with`] writes (RGBA,
//! unsigned bytes, tightly packed, in the BIN chunk); a file with colours of any other kind, or
//! whose references do not fit, is not read here (`None`), and the caller reads it through the
//! `gltf` crate instead, so what is read never differs.

use serde::Deserialize;

/// `componentType` of unsigned bytes.
const UNSIGNED_BYTE: u32 = 5121;

#[derive(Deserialize)]
struct Doc<'a> {
    #[serde(default)]
    nodes: Vec<Node>,
    #[serde(default)]
    meshes: Vec<Mesh>,
    #[serde(default, borrow)]
    accessors: Vec<Accessor<'a>>,
    #[serde(default, rename = "bufferViews")]
    views: Vec<View>,
    #[serde(default)]
    buffers: Vec<Buffer>,
}

#[derive(Deserialize)]
struct Node {
    mesh: Option<usize>,
}

#[derive(Deserialize)]
struct Mesh {
    primitives: Vec<Primitive>,
}

#[derive(Deserialize)]
struct Primitive {
    attributes: Attributes,
}

#[derive(Deserialize)]
struct Attributes {
    #[serde(rename = "COLOR_0")]
    color: Option<usize>,
}

#[derive(Deserialize)]
struct Accessor<'a> {
    #[serde(rename = "bufferView")]
    view: Option<usize>,
    #[serde(default, rename = "byteOffset")]
    offset: usize,
    #[serde(rename = "componentType")]
    component: u32,
    count: usize,
    #[serde(rename = "type", borrow)]
    kind: std::borrow::Cow<'a, str>,
    sparse: Option<serde::de::IgnoredAny>,
}

#[derive(Deserialize)]
struct View {
    buffer: usize,
    #[serde(default, rename = "byteOffset")]
    offset: usize,
    #[serde(rename = "byteLength")]
    length: usize,
    #[serde(rename = "byteStride")]
    stride: Option<usize>,
}

#[derive(Deserialize)]
struct Buffer {
    uri: Option<serde::de::IgnoredAny>,
}

/// The colours of a `scene.glb`'s primitives, by node and mesh (see the module notes).
pub(crate) struct GlbColours {
    /// Per node, its mesh.
    node_mesh: Vec<Option<usize>>,
    /// Per mesh, per primitive, its colours (RGB; `None` without `COLOR_0`).
    colours: Vec<Vec<Option<Vec<[u8; 3]>>>>,
}

impl GlbColours {
    /// The colours of the glTF binary `bytes`; `None` when it is not one whose colours are all
    /// RGBA unsigned bytes, tightly packed, within its BIN chunk.
    pub(crate) fn read(bytes: &[u8]) -> Option<GlbColours> {
        let glb = gltf::binary::Glb::from_slice(bytes).ok()?;
        let doc: Doc<'_> = serde_json::from_slice(&glb.json).ok()?;
        let bin = glb.bin.as_deref();
        let colours = doc
            .meshes
            .iter()
            .map(|m| {
                m.primitives
                    .iter()
                    .map(|p| match p.attributes.color {
                        None => Some(None),
                        Some(a) => rgba_u8(&doc, a, bin?).map(Some),
                    })
                    .collect::<Option<Vec<_>>>()
            })
            .collect::<Option<Vec<_>>>()?;
        Some(GlbColours {
            node_mesh: doc.nodes.iter().map(|n| n.mesh).collect(),
            colours,
        })
    }

    /// Colours gathered otherwise: per node its mesh, per mesh per primitive its colours.
    pub(crate) fn new(
        node_mesh: Vec<Option<usize>>,
        colours: Vec<Vec<Option<Vec<[u8; 3]>>>>,
    ) -> GlbColours {
        GlbColours { node_mesh, colours }
    }

    /// Node `node`'s mesh (`Some(None)`: a node without one; `None`: no such node).
    pub(crate) fn node_mesh(&self, node: usize) -> Option<Option<usize>> {
        self.node_mesh.get(node).copied()
    }

    /// The primitives of mesh `mesh` (none for no such mesh), each with its colours when it
    /// has `COLOR_0`.
    pub(crate) fn primitives(&self, mesh: usize) -> &[Option<Vec<[u8; 3]>>] {
        self.colours.get(mesh).map_or(&[], Vec::as_slice)
    }
}

/// Accessor `a`'s colours as RGB, when they are RGBA unsigned bytes packed in `bin`.
fn rgba_u8(doc: &Doc<'_>, a: usize, bin: &[u8]) -> Option<Vec<[u8; 3]>> {
    let acc = doc.accessors.get(a)?;
    if acc.component != UNSIGNED_BYTE || acc.kind != "VEC4" || acc.sparse.is_some() {
        return None;
    }
    let view = doc.views.get(acc.view?)?;
    if !matches!(view.stride, None | Some(4)) || doc.buffers.get(view.buffer)?.uri.is_some() {
        return None;
    }
    let len = acc.count.checked_mul(4)?;
    if acc.offset.checked_add(len)? > view.length {
        return None;
    }
    let start = view.offset.checked_add(acc.offset)?;
    let data = bin.get(start..start.checked_add(len)?)?;
    Some(data.chunks_exact(4).map(|c| [c[0], c[1], c[2]]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::glb::{glb_container, gltf_colours};
    use serde_json::json;

    /// A glTF binary: node 0 with mesh 0 (a primitive with `colour` as `COLOR_0` over 3
    /// vertices, one without), node 1 without a mesh. The colour accessor reads `bin` at 4.
    fn file(colour: serde_json::Value, bin: &[u8]) -> Vec<u8> {
        let doc = json!({
            "asset": {"version": "2.0"},
            "scene": 0,
            "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"mesh": 0, "name": "a"}, {"name": "b"}],
            "meshes": [{"primitives": [
                {"attributes": {"POSITION": 0, "COLOR_0": 1}},
                {"attributes": {"POSITION": 0}}
            ]}],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
                colour
            ],
            "bufferViews": [
                {"buffer": 0, "byteOffset": 16, "byteLength": 36},
                {"buffer": 0, "byteOffset": 4, "byteLength": 12}
            ],
            "buffers": [{"byteLength": bin.len()}]
        });
        glb_container(&serde_json::to_vec(&doc).unwrap(), bin)
    }

    fn bin() -> Vec<u8> {
        let mut b = vec![0u8; 4];
        b.extend_from_slice(&[10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 128]);
        for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            p.iter().for_each(|x| b.extend_from_slice(&x.to_le_bytes()));
        }
        b
    }

    fn same(a: &GlbColours, b: &GlbColours) -> bool {
        a.node_mesh == b.node_mesh && a.colours == b.colours
    }

    #[test]
    fn rgba_bytes_are_read_without_the_document_as_the_gltf_crate_reads_them() {
        let rgba = json!({"bufferView": 1, "componentType": 5121, "normalized": true,
                          "count": 3, "type": "VEC4"});
        let glb = file(rgba, &bin());
        let lean = GlbColours::read(&glb).expect("the writer's kind of colours");
        assert_eq!(lean.node_mesh(0), Some(Some(0)));
        assert_eq!(lean.node_mesh(1), Some(None));
        assert_eq!(lean.node_mesh(2), None);
        let want = vec![[10, 20, 30], [40, 50, 60], [70, 80, 90]];
        assert_eq!(lean.primitives(0), &[Some(want), None]);
        assert!(lean.primitives(1).is_empty());
        let full = gltf_colours(&glb, "scene.glb".as_ref()).unwrap();
        assert!(same(&lean, &full));
    }

    #[test]
    fn colours_of_another_kind_or_out_of_their_view_are_left_to_the_gltf_crate() {
        // Three bytes a vertex: the gltf crate reads them, this reader does not.
        let rgb = json!({"bufferView": 1, "componentType": 5121, "normalized": true,
                         "count": 4, "type": "VEC3"});
        let glb = file(rgb, &bin());
        assert!(GlbColours::read(&glb).is_none());
        let full = gltf_colours(&glb, "scene.glb".as_ref()).unwrap();
        assert_eq!(full.primitives(0)[0].as_ref().map(Vec::len), Some(4));
        // Four vertices of RGBA do not fit the 12 bytes of their view.
        let long = json!({"bufferView": 1, "componentType": 5121, "normalized": true,
                          "count": 4, "type": "VEC4"});
        assert!(GlbColours::read(&file(long, &bin())).is_none());
        // Not a glTF binary at all.
        assert!(GlbColours::read(b"{\"asset\": {\"version\": \"2.0\"}}").is_none());
    }
}
