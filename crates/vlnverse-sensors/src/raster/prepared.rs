//! A scene prepared for the rasteriser, stored: the merged faces and their face textures
//! ([`super::faces`]) and which objects are closed surfaces, the part of
//! [`super::RasterScene::new`] that costs (nearly all of a home switch: merging faces and
//! baking their textures takes ~25 ms a `vlnverse` home, reading them back ~2 ms). Written at
//! generation beside `scene.glb` ([`PREPARED_FILE`]) and read back when a home is loaded.
//!
//! The file is keyed to what it was made from: the mesh ([`SceneMesh::content_key`]) and the
//! surface textures (a hash of their bytes), with a format version and a checksum of every
//! byte before it, so a stale or damaged file is refused rather than drawn.
//!
//! Layout, little-endian: magic `VLNRAST\0`, version (u32), 0 (u32), the lengths of the body
//! and of the face textures' texels (u64 each), the length of the packed body (u64), then the
//! body packed with zstd (level 1), then the face textures as [`super::face_store`] stores them:
//! per face (in the order of their `base`) its stored length, how it is stored (0 as it is, 1
//! as two-bit differences from a prediction packed with zstd), its surface, its origin and the
//! count of its other differences (five u32), then every face's stored bytes. Faces are packed
//! one by one so that a loaded scene keeps them packed and unpacks a face when a view first
//! draws it. The body: mesh key (u64), texture key (u64), mesh triangles, draw triangles,
//! objects, face-texture texels (u32 each); per draw triangle its 9 corner coordinates (f32);
//! per draw triangle its mesh triangle (u32); per draw triangle its face texture (`base, w, h`
//! as u32, `w = 0` for none, then 6 f32 of face-texture coordinates; the faces tile the texels
//! one after the other in the order of their `base`); per object its first draw triangle and
//! count (u32), box (6 f32) and whether it is closed (u32); the checksum of the body before it
//! and of the stored face textures (u64).

use super::face_store::FaceTexels;
use super::faces::{DrawMesh, FaceTexture};
use crate::scene_mesh::SceneMesh;
use glam::Vec3;
use vlnverse_env::Aabb;

/// Name of the prepared-scene file in a scene's folder.
pub const PREPARED_FILE: &str = "raster.bin";
/// Format of [`PREPARED_FILE`]; raise it whenever what the rasteriser prepares changes (how
/// faces merge, how face textures are baked), so files of the old kind are refused.
/// (3: triangles with two equal corners are left out, and the seams of round shapes no longer
/// keep them from counting as closed surfaces. 4: face textures stored face by face, the larger
/// ones packed each on its own; the same texels.)
pub const PREPARED_VERSION: u32 = 4;

const MAGIC: &[u8; 8] = b"VLNRAST\0";
/// Bytes before the packed body: magic, version, 0, three lengths.
const FILE_HEADER: usize = 8 + 4 + 4 + 3 * 8;
/// Bytes of the body's header: two keys, four counts.
const HEADER: usize = 8 + 8 + 4 * 4;
/// zstd level of the body.
const LEVEL: i32 = 1;
/// Longest body or face textures read back (a home's are a few megabytes).
const MAX_BODY: u64 = 1 << 31;

/// The checksum of the body (before its checksum) and the face textures.
fn body_checksum(body: &[u8], texels: &[u8]) -> u64 {
    checksum(body) ^ checksum(texels).rotate_left(17)
}
/// Bytes per draw triangle: corners, mesh triangle, face texture and its coordinates.
const PER_TRIANGLE: usize = 9 * 4 + 4 + 3 * 4 + 6 * 4;
/// Bytes per object: range, box, closed.
const PER_OBJECT: usize = 2 * 4 + 6 * 4 + 4;

/// What is stored: the triangles drawn (their face textures in `faces`, not in
/// `draw.texels`) and whether each object is a closed surface.
pub(crate) struct Prepared {
    pub draw: DrawMesh,
    pub closed: Vec<bool>,
    pub faces: FaceTexels,
}

/// The face textures of `draw`'s triangles, once each, in the order of their first texel. An
/// error when they do not tile the texels one after the other (as [`super::faces::build`] lays
/// them out) or two triangles give one base different sizes.
pub(crate) fn face_spans(draw: &DrawMesh) -> Result<Vec<FaceTexture>, String> {
    let mut f: Vec<FaceTexture> = draw.face.iter().flatten().map(|(t, _)| *t).collect();
    f.sort_unstable_by_key(|t| t.base);
    f.dedup_by(|a, b| a.base == b.base && (a.w, a.h) == (b.w, b.h));
    let mut next = 0u64;
    f.iter()
        .map(|t| {
            if u64::from(t.base) != next {
                return Err(format!(
                    "face texture {}x{} at {}: expected at {next} (faces must tile the texels)",
                    t.w, t.h, t.base
                ));
            }
            next += u64::from(t.w) * u64::from(t.h);
            Ok(*t)
        })
        .collect()
}

/// A hash of bytes, eight at a time on four independent lanes (a few megabytes of face
/// textures hash in well under a millisecond).
fn checksum(b: &[u8]) -> u64 {
    const K: [u64; 4] = [
        0x9e37_79b9_7f4a_7c15,
        0xc2b2_ae3d_27d4_eb4f,
        0x1656_67b1_9e37_79f9,
        0x85eb_ca77_c2b2_ae63,
    ];
    let mut h = K;
    let blocks = b.chunks_exact(32);
    let tail = blocks.remainder();
    for block in blocks {
        for (k, w) in block.chunks_exact(8).enumerate() {
            let w = u64::from_le_bytes(w.try_into().expect("8 bytes"));
            h[k] = (h[k] ^ w).wrapping_mul(K[k]).rotate_left(29);
        }
    }
    let mut out = b.len() as u64;
    for (k, v) in h.iter().enumerate() {
        out = (out ^ v).wrapping_mul(K[k]).rotate_left(31);
    }
    for &c in tail {
        out = (out ^ u64::from(c)).wrapping_mul(K[0]);
    }
    out ^ (out >> 32)
}

/// Key of the surface textures the face textures were baked from.
fn texture_key(luma: &[u8]) -> u64 {
    checksum(luma)
}

/// The file's bytes for `draw`, its face textures `faces` and `closed`, prepared from `mesh`
/// with the surface textures `luma`.
pub(crate) fn encode(
    draw: &DrawMesh,
    faces: &FaceTexels,
    closed: &[bool],
    mesh: &SceneMesh,
    luma: &[u8],
) -> Result<Vec<u8>, String> {
    let n = draw.src.len();
    let mut b = Vec::with_capacity(HEADER + n * PER_TRIANGLE + closed.len() * PER_OBJECT + 8);
    let u32s = |b: &mut Vec<u8>, v: u32| b.extend_from_slice(&v.to_le_bytes());
    let f32s = |b: &mut Vec<u8>, v: &[f32]| v.iter().for_each(|x| u32s(b, x.to_bits()));
    b.extend_from_slice(&mesh.content_key().to_le_bytes());
    b.extend_from_slice(&texture_key(luma).to_le_bytes());
    for c in [
        mesh.triangle_count(),
        n,
        draw.objects.len(),
        faces.texel_count(),
    ] {
        u32s(&mut b, c as u32);
    }
    draw.pos.iter().for_each(|p| f32s(&mut b, &p.to_array()));
    draw.src.iter().for_each(|s| u32s(&mut b, *s));
    for f in &draw.face {
        let (t, uv) = f.unwrap_or((
            FaceTexture {
                base: 0,
                w: 0,
                h: 0,
            },
            [[0.0; 2]; 3],
        ));
        [t.base, t.w, t.h].iter().for_each(|v| u32s(&mut b, *v));
        f32s(&mut b, uv.as_flattened());
    }
    for (&(first, count, bbox), &c) in draw.objects.iter().zip(closed) {
        u32s(&mut b, first as u32);
        u32s(&mut b, count as u32);
        f32s(&mut b, &bbox.min);
        f32s(&mut b, &bbox.max);
        u32s(&mut b, u32::from(c));
    }
    let texels = faces.write()?;
    let sum = body_checksum(&b, &texels);
    b.extend_from_slice(&sum.to_le_bytes());
    let body = zstd::bulk::compress(&b, LEVEL).map_err(|e| e.to_string())?;
    let mut file = Vec::with_capacity(FILE_HEADER + body.len() + texels.len());
    file.extend_from_slice(MAGIC);
    file.extend_from_slice(&PREPARED_VERSION.to_le_bytes());
    file.extend_from_slice(&0u32.to_le_bytes());
    for len in [b.len(), faces.texel_count(), body.len()] {
        file.extend_from_slice(&(len as u64).to_le_bytes());
    }
    file.extend_from_slice(&body);
    file.extend_from_slice(&texels);
    Ok(file)
}

/// Reads little-endian words, refusing to run past the end.
struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let s = self
            .b
            .get(self.at..self.at + n)
            .ok_or_else(|| format!("ends at byte {} (truncated)", self.b.len()))?;
        self.at += n;
        Ok(s)
    }

    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(
            self.take(4)?.try_into().expect("4 bytes"),
        ))
    }

    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }

    fn f32(&mut self) -> Result<f32, String> {
        Ok(f32::from_bits(self.u32()?))
    }

    fn f32s<const N: usize>(&mut self) -> Result<[f32; N], String> {
        let mut v = [0.0; N];
        for x in &mut v {
            *x = self.f32()?;
        }
        Ok(v)
    }
}

/// The prepared scene in `file`, checked against `mesh` (whose
/// [`SceneMesh::content_key`] is `mesh_key`) and the surface textures `luma`; what is wrong
/// otherwise (the field and the values found and expected).
pub(crate) fn decode(
    file: &[u8],
    mesh: &SceneMesh,
    mesh_key: u64,
    luma: &[u8],
) -> Result<Prepared, String> {
    if file.len() < FILE_HEADER || &file[..8] != MAGIC {
        return Err("not a prepared raster scene (no VLNRAST header)".into());
    }
    let mut r = Reader { b: file, at: 8 };
    let version = r.u32()?;
    if version != PREPARED_VERSION {
        return Err(format!(
            "format version {version}, this build reads {PREPARED_VERSION} (stale: generate the \
             dataset again, or delete the file to prepare the scene on load)"
        ));
    }
    r.u32()?;
    let (len, tex_len, packed) = (r.u64()?, r.u64()?, r.u64()?);
    if !(HEADER as u64 + 8..=MAX_BODY).contains(&len) || tex_len > MAX_BODY {
        return Err(format!(
            "body of {len} bytes, face textures of {tex_len} (damaged)"
        ));
    }
    let rest = &file[FILE_HEADER..];
    let split = usize::try_from(packed)
        .ok()
        .filter(|&p| p <= rest.len())
        .ok_or_else(|| format!("packed body of {packed} bytes past the end (truncated)"))?;
    let unpack = |what: &str, v: &[u8], len: u64| {
        let out = super::unzstd::decompress(v, len as usize)
            .map_err(|e| format!("cannot unpack the {what} (damaged): {e}"))?;
        if out.len() as u64 != len {
            return Err(format!(
                "{what} of {} bytes, {len} written (damaged)",
                out.len()
            ));
        }
        Ok(out)
    };
    let b = unpack("body", &rest[..split], len)?;
    let texels = &rest[split..];
    let (body, sum) = b.split_at(b.len() - 8);
    let mut r = Reader { b: body, at: 0 };
    let want = u64::from_le_bytes(sum.try_into().expect("8 bytes"));
    if body_checksum(body, texels) != want {
        return Err("checksum does not match (the file is damaged)".into());
    }
    let (found, tex_key) = (r.u64()?, r.u64()?);
    if found != mesh_key {
        return Err(format!(
            "mesh key {found:016x}, the scene's mesh is {mesh_key:016x} (stale: prepared from \
             another version of the scene)"
        ));
    }
    if tex_key != texture_key(luma) {
        return Err("prepared with other surface textures (stale)".into());
    }
    let (n_tri, n, n_obj, n_tex) = (
        r.u32()? as usize,
        r.u32()? as usize,
        r.u32()? as usize,
        r.u32()? as usize,
    );
    if n_tri != mesh.triangle_count() || n_obj != mesh.objects.len() {
        return Err(format!(
            "{n_tri} triangles and {n_obj} objects, the mesh has {} and {}",
            mesh.triangle_count(),
            mesh.objects.len()
        ));
    }
    let need = HEADER + n * PER_TRIANGLE + n_obj * PER_OBJECT;
    if body.len() != need || n_tex as u64 != tex_len {
        return Err(format!(
            "{} bytes before the checksum and {tex_len} face-texture texels, {need} and {n_tex} \
             expected for {n} triangles and {n_obj} objects",
            body.len(),
        ));
    }
    let mut d = DrawMesh {
        pos: Vec::with_capacity(3 * n),
        src: Vec::with_capacity(n),
        face: Vec::with_capacity(n),
        objects: Vec::with_capacity(n_obj),
        texels: Vec::new(),
        origin: Vec::new(),
    };
    // The corners in one read (the body's length is checked above), three floats each.
    let word = |c: &[u8]| f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
    d.pos.extend(
        r.take(3 * n * 12)?
            .chunks_exact(12)
            .map(|c| Vec3::new(word(&c[..4]), word(&c[4..8]), word(&c[8..]))),
    );
    for i in 0..n {
        let s = r.u32()?;
        if s as usize >= n_tri {
            return Err(format!("draw triangle {i}: mesh triangle {s} of {n_tri}"));
        }
        d.src.push(s);
    }
    for i in 0..n {
        let t = FaceTexture {
            base: r.u32()?,
            w: r.u32()?,
            h: r.u32()?,
        };
        let uv = r.f32s::<6>()?;
        if t.w == 0 {
            d.face.push(None);
            continue;
        }
        let end = t.base as u64 + t.w as u64 * t.h as u64;
        if t.h == 0 || end > n_tex as u64 {
            return Err(format!(
                "draw triangle {i}: face texture {}x{} at {} past the {n_tex} texel bytes",
                t.w, t.h, t.base
            ));
        }
        d.face
            .push(Some((t, [[uv[0], uv[1]], [uv[2], uv[3]], [uv[4], uv[5]]])));
    }
    let mut closed = Vec::with_capacity(n_obj);
    let mut next = 0;
    for k in 0..n_obj {
        let (first, count) = (r.u32()? as usize, r.u32()? as usize);
        let (min, max) = (r.f32s::<3>()?, r.f32s::<3>()?);
        if first != next || first + count > n {
            return Err(format!(
                "object {k}: draw triangles {first}..{} (expected from {next}, of {n})",
                first + count
            ));
        }
        next = first + count;
        d.objects.push((first, count, Aabb { min, max }));
        closed.push(r.u32()? != 0);
    }
    if next != n {
        return Err(format!("objects cover {next} of {n} draw triangles"));
    }
    let faces = FaceTexels::read(texels, &face_spans(&d)?)?;
    if faces.texel_count() != n_tex {
        return Err(format!(
            "faces of {} texels, {n_tex} written",
            faces.texel_count()
        ));
    }
    Ok(Prepared {
        draw: d,
        closed,
        faces,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_mesh::{ObjectRange, TriLook};
    use vlnverse_env::material::Surface;

    /// A floor of unit cells (two triangles each) with a light that is not linear, texture
    /// coordinates 64 texels per metre shifted off the texel grid (gaps to fill), and a wall
    /// piece on another surface.
    fn cells() -> SceneMesh {
        let mut m = SceneMesh::default();
        let light = |p: Vec3| 0.3 + 0.2 * p.x + 0.05 * p.z * p.z + 0.1 * p.y;
        let mut push = |tri: [Vec3; 3], uv: [[f32; 2]; 3], surface: Surface| {
            m.positions.extend_from_slice(&tri);
            m.object.push(1);
            m.color.push([0.7; 3]);
            m.look.push(TriLook {
                tone: [0.8, 0.7, 0.6],
                light: tri.map(light),
                uv,
                surface,
                image: None,
            });
        };
        for x in 0..3 {
            for z in 0..2 {
                let c = |dx: i32, dz: i32| Vec3::new((x + dx) as f32, 0.0, (z + dz) as f32);
                for tri in [[c(0, 0), c(0, 1), c(1, 1)], [c(0, 0), c(1, 1), c(1, 0)]] {
                    push(
                        tri,
                        tri.map(|p| [p.x * 64.0 + 0.3, p.z * 64.0 + 0.7]),
                        Surface::WoodFloor,
                    );
                }
            }
        }
        for y in 0..2 {
            let c = |dx: i32, dy: i32| Vec3::new((dx) as f32, (y + dy) as f32, 0.0);
            for tri in [[c(0, 0), c(1, 1), c(0, 1)], [c(0, 0), c(1, 0), c(1, 1)]] {
                push(tri, tri.map(|p| [p.x * 64.0, p.y * 64.0]), Surface::Plaster);
            }
        }
        let mut bbox = Aabb::EMPTY;
        m.positions.iter().for_each(|p| bbox.extend(*p));
        m.objects.push(ObjectRange {
            id: 1,
            first: 0,
            count: m.object.len() as u32,
            bbox,
        });
        m
    }

    #[test]
    fn what_is_prepared_is_what_files_of_this_version_hold() {
        // A file keeps what faces::build made when it was written; the mesh and texture keys
        // cannot tell that the building changed. If this fails, how faces are merged or face
        // textures baked has changed: raise PREPARED_VERSION (files of the old version are then
        // refused and scenes prepared on load until the dataset is generated again) and put
        // the new checksum here.
        let m = cells();
        let luma = super::super::surface_luma();
        let d = super::super::faces::build(&m, luma);
        assert!(d.face.iter().all(|f| f.is_some()), "the cells merge");
        let faces = FaceTexels::raw(d.texels.clone(), &face_spans(&d).unwrap(), &d.origin);
        let body = encode(&d, &faces, &[false], &m, luma).expect("encoded");
        let mut b = Vec::new();
        let r = decode(&body, &m, m.content_key(), luma).expect("decoded");
        (0..r.faces.len()).for_each(|i| b.extend_from_slice(&r.faces.texels(i)));
        r.draw.pos.iter().for_each(|p| {
            p.to_array()
                .iter()
                .for_each(|c| b.extend_from_slice(&c.to_bits().to_le_bytes()))
        });
        b.extend_from_slice(format!("{:?}{:?}", r.draw.face, r.draw.src).as_bytes());
        assert_eq!(
            (PREPARED_VERSION, checksum(&b)),
            (4, 14_747_998_955_599_738_887),
            "faces::build changed: raise PREPARED_VERSION"
        );
    }

    #[test]
    fn checksum_sees_every_byte_and_the_length() {
        let b: Vec<u8> = (0..1000u32).map(|i| (i * 7 % 251) as u8).collect();
        let h = checksum(&b);
        for i in [0, 31, 32, 500, 999] {
            let mut c = b.clone();
            c[i] ^= 1;
            assert_ne!(checksum(&c), h, "byte {i}");
        }
        assert_ne!(checksum(&b[..999]), h);
        let mut z = b.clone();
        z.push(0);
        assert_ne!(checksum(&z), h);
    }
}
