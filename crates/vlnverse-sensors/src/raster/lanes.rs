//! The first tests of a cluster's triangles in one view, all of them at once in lanes the
//! compiler vectorises (one array per corner and coordinate): corners to camera space and
//! projected, and which triangles cannot cover a pixel centre by their corners alone (behind
//! the near plane or beyond the far one, beside the view, or in front of the near plane and
//! too small to hold a pixel centre). The values are those the scalar set-up computes
//! ([`ViewParams::to_camera`], [`ViewParams::project`]: the same operations in the same order),
//! so what is kept is set up exactly as before.

use super::{ViewParams, CLUSTER};
use glam::Vec3;

/// One coordinate of corner `k` of triangle `i` at `[k][i]`.
type Coords = [[f32; CLUSTER]; 3];

/// Up to [`CLUSTER`] triangles of one view: corners in camera space, projected, and tested.
pub(super) struct Lanes {
    x: Coords,
    y: Coords,
    z: Coords,
    sx: Coords,
    sy: Coords,
    /// Whether triangle `i` may cover a pixel centre (it is not rejected by its corners).
    keep: [bool; CLUSTER],
    /// Whether every corner of triangle `i` is in front of the near plane.
    front: [bool; CLUSTER],
    /// Whether triangle `i` faces away from the eye (its normal and the eye on opposite sides
    /// of its plane, as `RasterScene::setup` tests it).
    back: [bool; CLUSTER],
}

impl Lanes {
    /// Lanes for a view (zeros until [`Lanes::load`]).
    #[inline(always)]
    pub(super) fn new() -> Self {
        let zero = [[0.0; CLUSTER]; 3];
        Lanes {
            x: zero,
            y: zero,
            z: zero,
            sx: zero,
            sy: zero,
            keep: [false; CLUSTER],
            front: [false; CLUSTER],
            back: [false; CLUSTER],
        }
    }

    /// Transform, project and test the triangles whose corners are `pos` (three a triangle,
    /// at most [`CLUSTER`] triangles; any further ones are ignored) and unit normals
    /// `normals`; with `cull`, back faces are not kept.
    #[cfg(test)]
    pub(super) fn load(&mut self, p: &ViewParams, pos: &[Vec3], normals: &[Vec3], cull: bool) {
        let n = (pos.len() / 3).min(normals.len()).min(CLUSTER);
        let mut block = Vec::new();
        pack(&pos[..3 * n], &normals[..n], &mut block);
        self.load_packed(p, &block, cull);
    }

    /// Transform, project and test the triangles of one block made by [`pack`] (up to
    /// [`CLUSTER`] triangles); with `cull`, back faces are not kept. Lanes past the block's
    /// triangles hold what an earlier block left or padding: ask only for the block's own.
    #[inline(always)]
    pub(super) fn load_packed(&mut self, p: &ViewParams, block: &[f32], cull: bool) {
        let m = (block.len() / ROWS).min(CLUSTER);
        let row = |r: usize| &block[r * m..r * m + m];
        let (ex, ey, ez) = (p.pos.x, p.pos.y, p.pos.z);
        // `normal.dot(corner 0 - eye) > 0` as glam's `Vec3::dot`.
        let (px, py, pz) = (row(0), row(3), row(6));
        let (nx, ny, nz_) = (row(9), row(10), row(11));
        for i in 0..m {
            let (a, b, c) = (px[i] - ex, py[i] - ey, pz[i] - ez);
            self.back[i] = nx[i] * a + ny[i] * b + nz_[i] * c > 0.0;
        }
        // `rot * d` as glam's `Mat3 * Vec3`: x axis times d.x, plus y axis times d.y, plus
        // z axis times d.z.
        let (ra, rb, rc) = (p.rot.x_axis, p.rot.y_axis, p.rot.z_axis);
        let (nz, far) = (-p.near, p.far);
        let (fx, fy, cx, cy) = (p.fx, p.fy, p.cx, p.cy);
        let (right, bottom) = (p.w as f32 - cx, -(p.h as f32 - cy));
        for k in 0..3 {
            let (px, py, pz) = (row(k), row(3 + k), row(6 + k));
            let (ox, oy, oz) = (&mut self.x[k], &mut self.y[k], &mut self.z[k]);
            let (osx, osy) = (&mut self.sx[k], &mut self.sy[k]);
            for i in 0..m {
                let (a, b, c) = (px[i] - ex, py[i] - ey, pz[i] - ez);
                let x = ra.x * a + rb.x * b + rc.x * c;
                let y = ra.y * a + rb.y * b + rc.y * c;
                let z = ra.z * a + rb.z * b + rc.z * c;
                let iz = 1.0 / -z;
                ox[i] = x;
                oy[i] = y;
                oz[i] = z;
                osx[i] = cx + fx * x * iz;
                osy[i] = cy - fy * y * iz;
            }
        }
        // Margin in pixels far above snapping and rounding.
        const M: f32 = 0.01;
        let (x, y, z, sx, sy) = (&self.x, &self.y, &self.z, &self.sx, &self.sy);
        for i in 0..m {
            // A test passed by all three corners.
            let all = |f: &dyn Fn(usize) -> bool| f(0) & f(1) & f(2);
            let out = all(&|k| z[k][i] > nz)
                | all(&|k| z[k][i] < -far)
                | (all(&|k| z[k][i] < 0.0)
                    & (all(&|k| fx * x[k][i] < -cx * -z[k][i])
                        | all(&|k| fx * x[k][i] > right * -z[k][i])
                        | all(&|k| fy * y[k][i] > cy * -z[k][i])
                        | all(&|k| fy * y[k][i] < bottom * -z[k][i])));
            let front = all(&|k| z[k][i] <= nz);
            let (x0, x1) = (
                min3(sx[0][i], sx[1][i], sx[2][i]),
                max3(sx[0][i], sx[1][i], sx[2][i]),
            );
            let (y0, y1) = (
                min3(sy[0][i], sy[1][i], sy[2][i]),
                max3(sy[0][i], sy[1][i], sy[2][i]),
            );
            let small = none(x0 - 0.5 - M, x1 - 0.5 + M) | none(y0 - 0.5 - M, y1 - 0.5 + M);
            self.keep[i] = !(out | (front & small) | (cull & self.back[i]));
            self.front[i] = front;
        }
    }

    /// Whether triangle `i` of the last [`Lanes::load`] may cover a pixel centre.
    #[cfg(test)]
    pub(super) fn keep(&self, i: usize) -> bool {
        self.keep.get(i).copied().unwrap_or(false)
    }

    /// Which of the first `n` triangles of the last [`Lanes::load_packed`] may cover a pixel
    /// centre, as bits (bit `i` for triangle `i`).
    #[inline(always)]
    pub(super) fn kept(&self, n: usize) -> u32 {
        const _: () = assert!(CLUSTER <= 32);
        self.keep
            .iter()
            .take(n)
            .enumerate()
            .fold(0, |m, (i, &k)| m | (k as u32) << i)
    }

    /// Whether triangle `i` faces away from the eye.
    #[inline(always)]
    pub(super) fn back(&self, i: usize) -> bool {
        self.back.get(i).copied().unwrap_or(false)
    }

    /// Triangle `i`'s corners in camera space, and projected when they are all in front of
    /// the near plane.
    #[inline(always)]
    pub(super) fn triangle(&self, i: usize) -> ([Vec3; 3], Option<[(f32, f32); 3]>) {
        let i = i.min(CLUSTER - 1);
        // Written out rather than `map` closures, which the AVX2 copy would call out of line.
        let (x, y, z) = (&self.x, &self.y, &self.z);
        let v = [
            Vec3::new(x[0][i], y[0][i], z[0][i]),
            Vec3::new(x[1][i], y[1][i], z[1][i]),
            Vec3::new(x[2][i], y[2][i], z[2][i]),
        ];
        let s = if self.front[i] {
            let (sx, sy) = (&self.sx, &self.sy);
            Some([
                (sx[0][i], sy[0][i]),
                (sx[1][i], sy[1][i]),
                (sx[2][i], sy[2][i]),
            ])
        } else {
            None
        };
        (v, s)
    }
}

/// Rows of a block made by [`pack`]: x of corners 0, 1, 2, then y, then z, then the normal's
/// x, y, z.
const ROWS: usize = 12;

/// Lanes a block is padded to (a multiple of the SSE2 width).
const PAD: usize = 4;

/// Length of the block of a cluster of `n` triangles ([`pack`]).
pub(super) fn block_len(n: usize) -> usize {
    ROWS * n.min(CLUSTER).div_ceil(PAD) * PAD
}

/// Append the block of one cluster (its triangles' corners `pos`, three a triangle, and unit
/// normals, at most [`CLUSTER`] triangles) that [`Lanes::load_packed`] reads: [`ROWS`] rows,
/// each of the triangle count rounded up to [`PAD`] values (padding zero). Its length.
pub(super) fn pack(pos: &[Vec3], normals: &[Vec3], out: &mut Vec<f32>) -> usize {
    let n = (pos.len() / 3).min(normals.len()).min(CLUSTER);
    let m = block_len(n) / ROWS;
    let start = out.len();
    out.resize(start + ROWS * m, 0.0);
    let block = &mut out[start..];
    for (i, (t, nrm)) in pos.chunks_exact(3).zip(normals).take(n).enumerate() {
        for k in 0..3 {
            block[k * m + i] = t[k].x;
            block[(3 + k) * m + i] = t[k].y;
            block[(6 + k) * m + i] = t[k].z;
        }
        block[9 * m + i] = nrm.x;
        block[10 * m + i] = nrm.y;
        block[11 * m + i] = nrm.z;
    }
    ROWS * m
}

#[inline(always)]
fn min3(a: f32, b: f32, c: f32) -> f32 {
    let m = if b < a { b } else { a };
    if c < m {
        c
    } else {
        m
    }
}

#[inline(always)]
fn max3(a: f32, b: f32, c: f32) -> f32 {
    let m = if b > a { b } else { a };
    if c > m {
        c
    } else {
        m
    }
}

/// No integer in `[lo, hi]` (no pixel centre in a box): `floor(hi) < lo`, branch-free, for
/// `|hi|` below 2^22 (where adding and taking away 1.5 x 2^23 rounds to an integer exactly);
/// "not sure" (false) beyond, which only sends a triangle on to the exact set-up.
#[inline(always)]
fn none(lo: f32, hi: f32) -> bool {
    const MAGIC: f32 = 12_582_912.0;
    const LIMIT: f32 = 4_194_304.0;
    let r = (hi + MAGIC) - MAGIC;
    let f = if r > hi { r - 1.0 } else { r };
    let small = (if hi < 0.0 { -hi } else { hi }) < LIMIT;
    small & (f < lo)
}

#[cfg(test)]
mod tests {
    use super::super::{emit, raster, ScreenTri, ViewParams, CLUSTER};
    use super::Lanes;
    use glam::Vec3;
    use rand::{Rng, SeedableRng};

    fn view() -> ViewParams {
        let pose = vlnverse_env::Pose::from_yaw(Vec3::new(1.0, 0.0, 2.0), 0.7);
        ViewParams::new(&crate::CameraSpec::default().camera(&pose))
    }

    /// `n` random triangles (corners, world space) of every size from 0.1 mm to 3 m, all around
    /// the camera, and their unit normals.
    fn triangles(seed: u64, n: usize) -> (Vec<Vec3>, Vec<Vec3>) {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut r = |a: f32, b: f32| rng.random_range(a..b);
        let mut pos = Vec::with_capacity(3 * n);
        for _ in 0..n {
            let c = Vec3::new(r(-6.0, 8.0), r(-1.0, 3.0), r(-4.0, 8.0));
            let size = 10f32.powf(r(-4.0, 0.5));
            for _ in 0..3 {
                pos.push(c + Vec3::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0)) * size);
            }
        }
        let normals = pos
            .chunks_exact(3)
            .map(|t| (t[1] - t[0]).cross(t[2] - t[0]).normalize_or(Vec3::Y))
            .collect();
        (pos, normals)
    }

    #[test]
    fn a_block_holds_twelve_rows_padded_to_four_lanes() {
        let (pos, normals) = triangles(3, 5);
        let mut block = vec![7.0];
        assert_eq!(super::pack(&pos, &normals, &mut block), 12 * 8);
        assert_eq!(block.len(), 1 + 12 * 8);
        assert_eq!(super::block_len(5), 12 * 8);
        assert_eq!(super::block_len(CLUSTER), 12 * CLUSTER);
        // Row 4 is y of corner 1; lanes 5..8 are padding.
        assert_eq!(block[1 + 4 * 8 + 2], pos[3 * 2 + 1].y);
        assert_eq!(block[1 + 11 * 8 + 4], normals[4].z);
        assert!(block[1 + 8 * 8 + 5..1 + 9 * 8].iter().all(|&v| v == 0.0));
    }

    #[test]
    fn corners_and_projections_are_those_of_the_scalar_set_up() {
        let p = view();
        let (pos, normals) = triangles(1, 40 * CLUSTER + 7);
        let mut lanes = Lanes::new();
        let mut front = 0;
        for (c, n) in pos.chunks(3 * CLUSTER).zip(normals.chunks(CLUSTER)) {
            lanes.load(&p, c, n, false);
            for (i, t) in c.chunks_exact(3).enumerate() {
                let (v, s) = lanes.triangle(i);
                for k in 0..3 {
                    let q = p.to_camera(t[k]);
                    assert_eq!(
                        v[k].to_array().map(f32::to_bits),
                        q.to_array().map(f32::to_bits)
                    );
                    if let Some(s) = s {
                        let (sx, sy, _) = p.project(q);
                        assert_eq!(
                            (s[k].0.to_bits(), s[k].1.to_bits()),
                            (sx.to_bits(), sy.to_bits())
                        );
                    }
                }
                front += s.is_some() as usize;
                assert_eq!(lanes.back(i), n[i].dot(t[0] - p.pos) > 0.0);
            }
        }
        assert!(front > 100, "only {front} triangles in front");
    }

    #[test]
    fn a_triangle_left_out_in_front_of_the_near_plane_writes_no_pixel() {
        let p = view();
        let (pos, normals) = triangles(2, 400 * CLUSTER);
        let mut lanes = Lanes::new();
        let (mut left_out, mut kept) = (0, 0);
        let (mut z, mut ids) = (vec![0.0f32; p.w * p.h], vec![0u32; p.w * p.h]);
        for (c, n) in pos.chunks(3 * CLUSTER).zip(normals.chunks(CLUSTER)) {
            lanes.load(&p, c, n, false);
            for i in 0..c.len() / 3 {
                let (v, s) = lanes.triangle(i);
                // In front and inside the guard band: what the set-up would emit unclipped.
                let Some(s) = s.filter(|s| {
                    s.iter()
                        .all(|(x, y)| x.abs() < p.guard && y.abs() < p.guard)
                }) else {
                    continue;
                };
                if lanes.keep(i) {
                    kept += 1;
                    continue;
                }
                left_out += 1;
                let mut out: Vec<ScreenTri> = Vec::new();
                emit(&p, v, [0.0, 0.0, 0.5], 1, &mut out);
                z.fill(0.0);
                ids.fill(0);
                raster::<true>(p.w, 0, p.h, &out, &mut z, &mut ids);
                assert!(
                    ids.iter().all(|&t| t == 0),
                    "left out, but covers a pixel: {s:?}"
                );
            }
        }
        assert!(
            left_out > 1000 && kept > 100,
            "left out {left_out}, kept {kept}"
        );
    }
}
