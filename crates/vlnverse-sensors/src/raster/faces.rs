//! Faces drawn whole: the floors and walls of lit homes are cut into cells so that the bake can
//! give them shadows and falloff ([`vlnverse_env::light::cell_of`]), but every cell costs the
//! rasteriser a triangle in every view and breaks the resolve's runs of one triangle. Here the
//! cells of each rectangular face are merged back into two triangles, and the face's light
//! times its texture is written once into a face texture (one byte per texel, texels of the
//! surface texture) that the resolve samples directly: the per-pixel work of a wall or floor is
//! one texel fetch, whatever the light does across it.
//!
//! A group of coplanar triangles of one object (same surface and colour) merges only when their
//! areas add up to the rectangle that bounds them (so they tile it exactly); the texel for a
//! point is the one the cells would have fetched (same texture coordinates), times the light
//! the cells interpolate there, rounded to a byte.
//!
//! What this builds is stored at generation ([`super::prepared`]): a change to it must raise
//! [`super::PREPARED_VERSION`] (a test holds a checksum of what it builds for a small mesh).

use crate::scene_mesh::SceneMesh;
use glam::{Vec2, Vec3};
use vlnverse_env::material::TEX_SIZE;
use vlnverse_env::Aabb;

/// Largest face texture (texels); bigger faces keep their cells.
const MAX_TEXELS: usize = 1 << 22;

/// A merged face's texture: `w x h` bytes at `base` of [`DrawMesh::texels`], row-major; texel
/// `(i, j)` covers texture coordinates `[u0 + i, u0 + i + 1) x [v0 + j, v0 + j + 1)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FaceTexture {
    pub base: u32,
    pub w: u32,
    pub h: u32,
}

/// Where a face texture's texels take the surface texture from: texel `(i, j)` is the light
/// there times texel `((tu0 + i) mod TEX_SIZE, (tv0 + j) mod TEX_SIZE)` of surface `surface`
/// ([`vlnverse_env::material::Surface::ALL`] order).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct FaceOrigin {
    pub surface: u32,
    pub tu0: u32,
    pub tv0: u32,
}

/// The triangles the rasteriser draws: the mesh's, with cut faces merged.
#[derive(Debug, Default)]
pub(crate) struct DrawMesh {
    /// Corners of draw triangle `i` are `pos[3i..3i+3]`.
    pub pos: Vec<Vec3>,
    /// The mesh triangle each draw triangle stands for (ids, class, look).
    pub src: Vec<u32>,
    /// For merged triangles: the face texture and the face-texture coordinates of the corners.
    pub face: Vec<Option<(FaceTexture, [[f32; 2]; 3])>>,
    /// Draw triangle range and box of each mesh object (same order).
    pub objects: Vec<(usize, usize, Aabb)>,
    /// Every face texture, one after the other (at least one byte).
    pub texels: Vec<u8>,
    /// Each face texture's surface texture and offset in it, in the order of `texels`.
    pub origin: Vec<FaceOrigin>,
}

/// Texture coordinates as an affine function of a point on a triangle's plane.
struct UvMap {
    a: Vec3,
    wu: Vec3,
    wv: Vec3,
    uv: [Vec2; 3],
}

impl UvMap {
    fn new(p: [Vec3; 3], uv: [[f32; 2]; 3]) -> Option<UvMap> {
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let den = d00 * d11 - d01 * d01;
        (den.abs() > 1e-20).then(|| UvMap {
            a: p[0],
            wu: (e1 * d11 - e2 * d01) / den,
            wv: (e2 * d00 - e1 * d01) / den,
            uv: uv.map(Vec2::from_array),
        })
    }

    fn at(&self, q: Vec3) -> Vec2 {
        let (s, t) = ((q - self.a).dot(self.wu), (q - self.a).dot(self.wv));
        self.uv[0] + s * (self.uv[1] - self.uv[0]) + t * (self.uv[2] - self.uv[0])
    }
}

/// Merge the cut faces of `mesh` and bake their face textures from `luma` (each surface's
/// encoded grey texture, [`vlnverse_env::material::Surface::ALL`] order).
pub(crate) fn build(mesh: &SceneMesh, luma: &[u8]) -> DrawMesh {
    let mut d = DrawMesh::default();
    for o in &mesh.objects {
        let first = d.src.len();
        let (lo, hi) = (o.first as usize, (o.first + o.count) as usize);
        // Group the object's triangles by plane and look, then into pieces that share corners
        // (coplanar faces of separate parts, such as wall pieces beside a door, stay apart).
        let mut keyed: Vec<([i64; 8], usize)> = (lo..hi)
            .filter(|&t| !degenerate(mesh, t))
            .filter_map(|t| {
                // Imported images keep their own texture coordinates.
                let l = mesh.look.get(t).filter(|l| l.image.is_none())?;
                let n = mesh.normal(t);
                let q = |v: f32| (v as f64 * 1e4).round() as i64;
                Some((
                    [
                        q(n.x),
                        q(n.y),
                        q(n.z),
                        q(n.dot(mesh.positions[3 * t])),
                        l.tone[0].to_bits() as i64,
                        l.tone[1].to_bits() as i64,
                        l.tone[2].to_bits() as i64,
                        l.surface.index() as i64,
                    ],
                    t,
                ))
            })
            .collect();
        keyed.sort_unstable();
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for run in keyed.chunk_by(|a, b| a.0 == b.0) {
            let tris: Vec<usize> = run.iter().map(|k| k.1).collect();
            groups.extend(pieces(mesh, &tris));
        }
        // In order of first triangle, so the draw order follows the mesh.
        groups.sort_unstable_by_key(|g| g[0]);
        let mut group_of = vec![usize::MAX; hi - lo];
        for (g, tris) in groups.iter().enumerate() {
            for &t in tris {
                group_of[t - lo] = g;
            }
        }
        let mut done = vec![false; groups.len()];
        for t in lo..hi {
            if degenerate(mesh, t) {
                continue;
            }
            let g = group_of[t - lo];
            if g == usize::MAX || groups[g].len() <= 2 {
                push_plain(&mut d, mesh, t);
                continue;
            }
            if done[g] {
                continue;
            }
            done[g] = true;
            if !merge(&mut d, mesh, &groups[g], luma) {
                for &s in &groups[g] {
                    push_plain(&mut d, mesh, s);
                }
            }
        }
        d.objects.push((first, d.src.len() - first, o.bbox));
    }
    // Never empty, so the resolve can clamp its indices to the last texel.
    if d.texels.is_empty() {
        d.texels.push(0);
    }
    d.texels.shrink_to_fit();
    d.pos.shrink_to_fit();
    d.src.shrink_to_fit();
    d.face.shrink_to_fit();
    d
}

/// Give empty texels (NaN) the value of the nearest filled one before (else after) them in
/// their row, then rows left empty the values of the nearest filled row before (else after).
fn fill_gaps(t: &mut [f32], w: usize, h: usize) {
    let mut empty_rows = false;
    for row in t.chunks_exact_mut(w) {
        // Gaps are few and mostly at the ends of a row: find each run of them and fill it
        // with the value before it (a leading run: the first value of the row).
        let Some(mut i) = row.iter().position(|v| v.is_nan()) else {
            continue;
        };
        while i < row.len() {
            let end = row[i..]
                .iter()
                .position(|v| !v.is_nan())
                .map_or(row.len(), |n| i + n);
            let fill = if i > 0 {
                row[i - 1]
            } else if end < row.len() {
                row[end]
            } else {
                empty_rows = true;
                break;
            };
            row[i..end].fill(fill);
            i = match row[end..].iter().position(|v| v.is_nan()) {
                Some(n) => end + n,
                None => break,
            };
        }
    }
    if !empty_rows {
        return;
    }
    let Some(mut from) = (0..h).find(|&j| !t[j * w].is_nan()) else {
        return;
    };
    for j in 0..h {
        if !t[j * w].is_nan() {
            from = j;
        } else {
            t.copy_within(from * w..(from + 1) * w, j * w);
        }
    }
}

/// `v.round().clamp(0.0, 255.0) as u8` (0 for NaN) for the light times a texel, branch-free,
/// without the libm call (`round` is one without SSE4.1) or a saturating conversion, so that a
/// loop of it runs on vector lanes: adding 1.5 * 2^23 rounds to the nearest integer `n`, ties
/// to even, in the low mantissa bits; `v - n` is exact, and a tie below `v` goes up.
#[inline]
pub(super) fn round_byte(v: f32) -> u8 {
    const MAGIC: f32 = 12_582_912.0;
    let v = if v > 0.0 { v.min(255.0) } else { 0.0 };
    let r = v + MAGIC;
    let n = r.to_bits() & 0xff;
    (n + u32::from(v - (r - MAGIC) >= 0.5)) as u8
}

/// Split triangles into pieces connected through shared corners (exact positions), each in
/// triangle order.
fn pieces(mesh: &SceneMesh, tris: &[usize]) -> Vec<Vec<usize>> {
    if tris.len() <= 2 {
        return vec![tris.to_vec()];
    }
    let mut parent: Vec<usize> = (0..tris.len()).collect();
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut corner: Vec<([u32; 3], usize)> = tris
        .iter()
        .enumerate()
        .flat_map(|(i, &t)| {
            (0..3).map(move |k| {
                (
                    mesh.positions[3 * t + k]
                        .to_array()
                        .map(|c| (c + 0.0).to_bits()),
                    i,
                )
            })
        })
        .collect();
    corner.sort_unstable();
    for run in corner.chunk_by(|a, b| a.0 == b.0) {
        for w in run.windows(2) {
            let (a, b) = (find(&mut parent, w[0].1), find(&mut parent, w[1].1));
            parent[a] = b;
        }
    }
    let mut out: Vec<Vec<usize>> = Vec::new();
    let mut slot: Vec<usize> = vec![usize::MAX; tris.len()];
    for (i, &t) in tris.iter().enumerate() {
        let r = find(&mut parent, i);
        if slot[r] == usize::MAX {
            slot[r] = out.len();
            out.push(Vec::new());
        }
        out[slot[r]].push(t);
    }
    out
}

/// Whether two corners of mesh triangle `t` are the same point (the poles of a sphere): it
/// covers no pixel in any view, so it is not drawn (its corners snap to the same pixel
/// position, an empty triangle, in every view).
fn degenerate(mesh: &SceneMesh, t: usize) -> bool {
    let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[3 * t + k]);
    a == b || b == c || c == a
}

fn push_plain(d: &mut DrawMesh, mesh: &SceneMesh, t: usize) {
    d.pos.extend_from_slice(&mesh.positions[3 * t..3 * t + 3]);
    d.src.push(t as u32);
    d.face.push(None);
}

/// Replace a group of coplanar triangles tiling a rectangle by two triangles and a face
/// texture; false (nothing added) when they do not tile a rectangle.
fn merge(d: &mut DrawMesh, mesh: &SceneMesh, tris: &[usize], luma: &[u8]) -> bool {
    let t0 = tris[0];
    let p0: [Vec3; 3] = [0, 1, 2].map(|k| mesh.positions[3 * t0 + k]);
    let n = mesh.normal(t0);
    let area: f32 = tris
        .iter()
        .map(|&t| {
            let p = &mesh.positions[3 * t..3 * t + 3];
            0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
        })
        .sum();
    // The rectangle's axes: one of the first triangle's edges (cells have two along the face).
    let rect = (0..3).find_map(|k| {
        let e1 = (p0[(k + 1) % 3] - p0[k]).normalize_or_zero();
        if e1 == Vec3::ZERO {
            return None;
        }
        let e2 = n.cross(e1);
        let (mut s0, mut s1, mut r0, mut r1) = (f32::MAX, f32::MIN, f32::MAX, f32::MIN);
        for &t in tris {
            for p in &mesh.positions[3 * t..3 * t + 3] {
                let (s, r) = ((*p - p0[0]).dot(e1), (*p - p0[0]).dot(e2));
                (s0, s1, r0, r1) = (s0.min(s), s1.max(s), r0.min(r), r1.max(r));
            }
        }
        let rect = (s1 - s0) * (r1 - r0);
        ((rect - area).abs() <= 1e-4 * rect.max(1e-6)).then(|| {
            let c = |s: f32, r: f32| p0[0] + s * e1 + r * e2;
            [c(s0, r0), c(s1, r0), c(s1, r1), c(s0, r1)]
        })
    });
    let Some(corner) = rect else { return false };
    let look = &mesh.look[t0];
    let Some(map) = UvMap::new(p0, look.uv) else {
        return false;
    };
    let cuv = corner.map(|c| map.at(c));
    let (mut umin, mut vmin) = (f32::MAX, f32::MAX);
    let (mut umax, mut vmax) = (f32::MIN, f32::MIN);
    for c in &cuv {
        (umin, umax, vmin, vmax) = (umin.min(c.x), umax.max(c.x), vmin.min(c.y), vmax.max(c.y));
    }
    let (u0, v0) = (umin.floor(), vmin.floor());
    let (w, h) = (
        ((umax.ceil() - u0) as usize).max(1),
        ((vmax.ceil() - v0) as usize).max(1),
    );
    if !(u0.is_finite() && v0.is_finite()) || w * h > MAX_TEXELS {
        return false;
    }
    let tex = &luma[look.surface.index() * TEX_SIZE * TEX_SIZE..][..TEX_SIZE * TEX_SIZE];
    let base = d.texels.len();
    // Light at each texel centre (NaN: none yet); the texture comes in at the end.
    let mut texels = vec![f32::NAN; w * h];
    for &t in tris {
        let l = &mesh.look[t];
        let uv = l.uv.map(|p| Vec2::new(p[0] - u0, p[1] - v0));
        let (e1, e2) = (uv[1] - uv[0], uv[2] - uv[0]);
        let den = e1.perp_dot(e2);
        if den.abs() < 1e-12 {
            continue;
        }
        let lo = uv[0].min(uv[1]).min(uv[2]);
        let hi = uv[0].max(uv[1]).max(uv[2]);
        let (i0, i1) = (
            (lo.x - 0.5).floor().max(0.0) as usize,
            (hi.x.ceil() as usize).min(w),
        );
        let (j0, j1) = (
            (lo.y - 0.5).floor().max(0.0) as usize,
            (hi.y.ceil() as usize).min(h),
        );
        let (l0, l1, l2) = (l.light[0], l.light[1] - l.light[0], l.light[2] - l.light[0]);
        // Each condition of the test below is linear along a row, `slope * qx + c >= 0`: its
        // root, widened by two texels, bounds the columns where a centre can pass (far beyond
        // the test's rounding; a nearly flat condition bounds nothing). The test itself is
        // unchanged, so no texel changes: only columns that cannot pass are skipped.
        let (d, ux) = (den as f64, uv[0].x as f64);
        let (s1, s2) = (e2.y as f64 / d, -(e1.y as f64) / d);
        for j in j0..j1 {
            let qy = j as f32 + 0.5 - uv[0].y;
            let (c1, c2) = (-(qy as f64) * e2.x as f64 / d, qy as f64 * e1.x as f64 / d);
            let (mut lo, mut hi) = (i0 as f64, i1 as f64 - 1.0);
            for (s, c) in [
                (s1, c1 + 1e-4),
                (s2, c2 + 1e-4),
                (-(s1 + s2), 1.0 + 1e-4 - c1 - c2),
            ] {
                if s.abs() < 1e-3 {
                    continue;
                }
                let root = -c / s + ux - 0.5;
                if s > 0.0 {
                    lo = lo.max((root - 2.0).floor());
                } else {
                    hi = hi.min((root + 2.0).ceil());
                }
            }
            // (`max` and `min` pass over a NaN root: the bounds stay numbers.)
            if lo > hi {
                continue;
            }
            let (a, b) = (lo as usize, hi as usize + 1);
            let row = &mut texels[j * w + a..j * w + b];
            // Branch-free so that it runs on vector lanes (IEEE division and products give
            // the same bits there). The first triangle (in order) that covers a texel centre
            // gives its light.
            for (k, cell) in row.iter_mut().enumerate() {
                // Through i32: exact below 2^24, and one instruction (usize is not).
                let qx = (a + k) as i32 as f32 + 0.5 - uv[0].x;
                let b1 = (qx * e2.y - qy * e2.x) / den;
                let b2 = (e1.x * qy - e1.y * qx) / den;
                let inside = b1 >= -1e-4 && b2 >= -1e-4 && b1 + b2 <= 1.0 + 1e-4;
                let v = l0 + b1 * l1 + b2 * l2;
                *cell = if inside && cell.is_nan() { v } else { *cell };
            }
        }
    }
    // Texels whose centre lies outside the face (its outline is not on texel boundaries):
    // the light of the nearest texel inside, along the row, else along the column.
    fill_gaps(&mut texels, w, h);
    d.texels.resize(base + w * h, 0);
    let u0i = u0 as i64 as usize;
    for (j, (row, out)) in texels
        .chunks_exact(w)
        .zip(d.texels[base..].chunks_exact_mut(w))
        .enumerate()
    {
        let tv = (v0 as i64 + j as i64) as usize & (TEX_SIZE - 1);
        let tex_row = &tex[tv * TEX_SIZE..(tv + 1) * TEX_SIZE];
        // Runs of the row over which the texture row does not wrap (slices of equal length, so
        // the loop runs on vector lanes).
        let mut i = 0;
        while i < w {
            let tu = u0i.wrapping_add(i) & (TEX_SIZE - 1);
            let n = (TEX_SIZE - tu).min(w - i);
            for ((o, light), t) in out[i..i + n]
                .iter_mut()
                .zip(&row[i..i + n])
                .zip(&tex_row[tu..tu + n])
            {
                *o = round_byte(*light * *t as f32);
            }
            i += n;
        }
    }
    let face = FaceTexture {
        base: base as u32,
        w: w as u32,
        h: h as u32,
    };
    d.origin.push(FaceOrigin {
        surface: look.surface.index() as u32,
        tu0: (u0i & (TEX_SIZE - 1)) as u32,
        tv0: ((v0 as i64) as usize & (TEX_SIZE - 1)) as u32,
    });
    let local = cuv.map(|c| [c.x - u0, c.y - v0]);
    for (a, b, c) in [(0, 1, 2), (0, 2, 3)] {
        d.pos.extend_from_slice(&[corner[a], corner[b], corner[c]]);
        d.src.push(t0 as u32);
        d.face.push(Some((face, [local[a], local[b], local[c]])));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_mesh::{ObjectRange, TriLook};
    use vlnverse_env::material::Surface;

    /// Light of the test floors: linear, so every triangulation interpolates it exactly.
    fn light(p: Vec3) -> f32 {
        0.2 + 0.3 * p.x + 0.1 * p.z
    }

    /// A floor object of unit cells at y = 0 (two triangles each, upward), texture coordinates
    /// 64 texels per metre.
    fn floor(cells: &[(i32, i32)]) -> SceneMesh {
        floor_uv(cells, 0.0)
    }

    /// [`floor`] with texture coordinates shifted by `shift` texels.
    fn floor_uv(cells: &[(i32, i32)], shift: f32) -> SceneMesh {
        let mut m = SceneMesh::default();
        for &(x, z) in cells {
            let c = |dx: i32, dz: i32| Vec3::new((x + dx) as f32, 0.0, (z + dz) as f32);
            for tri in [[c(0, 0), c(0, 1), c(1, 1)], [c(0, 0), c(1, 1), c(1, 0)]] {
                m.positions.extend_from_slice(&tri);
                m.object.push(1);
                m.color.push([0.8; 3]);
                m.look.push(TriLook {
                    tone: [0.9; 3],
                    light: tri.map(light),
                    uv: tri.map(|p| [p.x * 64.0 + shift, p.z * 64.0 + shift]),
                    surface: Surface::Plain,
                    image: None,
                });
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

    fn luma() -> Vec<u8> {
        Surface::ALL
            .iter()
            .flat_map(|s| s.luma_encoded().iter().copied())
            .collect()
    }

    #[test]
    fn cells_of_a_rectangle_become_two_triangles_and_a_face_texture_of_their_light() {
        let m = floor(&[(0, 0), (0, 1), (1, 0), (1, 1)]);
        let luma = luma();
        let d = build(&m, &luma);
        assert_eq!(d.src.len(), 2, "8 cell triangles drawn as 2");
        let (f, _) = d.face[0].expect("merged");
        assert_eq!((f.w, f.h), (128, 128));
        // The same normal as the cells (upward), so back faces stay back faces.
        let p = &d.pos[0..3];
        assert!((p[1] - p[0]).cross(p[2] - p[0]).y > 0.0);
        let plain = Surface::Plain.luma_encoded()[0] as f32;
        for (i, j) in [(0, 0), (5, 100), (127, 127), (64, 3)] {
            let q = Vec3::new((i as f32 + 0.5) / 64.0, 0.0, (j as f32 + 0.5) / 64.0);
            let want = (light(q) * plain).round();
            let got = d.texels[(f.base + j * f.w + i) as usize] as f32;
            assert!(
                (got - want).abs() <= 1.0,
                "texel ({i}, {j}): {got} vs {want}"
            );
        }
    }

    #[test]
    fn texels_past_the_outline_take_the_light_inside() {
        // The outline falls inside texels: the last row and column have centres past it.
        let m = floor_uv(&[(0, 0), (0, 1), (1, 0), (1, 1)], 0.4);
        let d = build(&m, &luma());
        let (f, _) = d.face[0].expect("merged");
        assert_eq!((f.w, f.h), (129, 129));
        let plain = Surface::Plain.luma_encoded()[0] as f32;
        for j in 0..f.h {
            for i in 0..f.w {
                // The texel centre, clamped onto the floor.
                let at = |k: u32| ((k as f32 + 0.5 - 0.4) / 64.0).clamp(0.0, 2.0);
                let want = light(Vec3::new(at(i), 0.0, at(j))) * plain;
                let got = d.texels[(f.base + j * f.w + i) as usize] as f32;
                assert!(
                    (got - want).abs() <= 3.0,
                    "texel ({i}, {j}): {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn gaps_take_the_nearest_value_before_else_after_in_rows_then_columns() {
        let n = f32::NAN;
        #[rustfmt::skip]
        let mut t = vec![
            n, n, n, n,
            n, 1.0, n, 2.0,
            n, n, n, n,
            3.0, n, n, n,
            n, n, n, n,
        ];
        fill_gaps(&mut t, 4, 5);
        #[rustfmt::skip]
        let want = vec![
            1.0, 1.0, 1.0, 2.0,
            1.0, 1.0, 1.0, 2.0,
            1.0, 1.0, 1.0, 2.0,
            3.0, 3.0, 3.0, 3.0,
            3.0, 3.0, 3.0, 3.0,
        ];
        assert_eq!(t, want);
        let mut none = vec![n; 6];
        fill_gaps(&mut none, 3, 2);
        assert!(none.iter().all(|v| v.is_nan()));
    }

    #[test]
    fn round_byte_rounds_like_round_then_clamp() {
        let mut v = -3.0f32;
        while v < 260.0 {
            for x in [v, v + 0.5, v + 0.49999997, v + 0.50000006] {
                assert_eq!(round_byte(x), x.round().clamp(0.0, 255.0) as u8, "{x}");
            }
            v += 0.03125;
        }
        assert_eq!(round_byte(f32::NAN), 0);
        assert_eq!(round_byte(f32::INFINITY), 255);
        assert_eq!(round_byte(f32::NEG_INFINITY), 0);
    }

    #[test]
    fn cells_that_do_not_tile_a_rectangle_stay_cells() {
        // An L of three cells, and two squares apart on one plane (merged one by one).
        let l = floor(&[(0, 0), (0, 1), (1, 0)]);
        assert_eq!(build(&l, &luma()).src.len(), 6);
        let apart = floor(&[
            (0, 0),
            (0, 1),
            (1, 0),
            (1, 1),
            (5, 0),
            (5, 1),
            (6, 0),
            (6, 1),
        ]);
        let d = build(&apart, &luma());
        assert_eq!(d.src.len(), 4);
        assert!(d.face.iter().all(|f| f.is_some()));
        assert_eq!(d.objects, vec![(0, 4, apart.objects[0].bbox)]);
    }
}
