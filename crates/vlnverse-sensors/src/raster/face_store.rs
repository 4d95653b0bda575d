//! The face textures of a prepared scene ([`super::faces`]), kept as they were stored: small
//! faces as they are, the others packed each on its own and unpacked the first time a view
//! draws them. A home switch then reads and holds the packed bytes and unpacks only the faces
//! its views show; the texels drawn are the baked ones, byte for byte.
//!
//! A face texel is the light there times a texel of its surface texture, shared by every home
//! ([`FaceOrigin`]). Packing predicts each texel from the row above it: the light of the three
//! texels above (their sum over the sum of their surface texels) times this texel's surface
//! texel, rounded. What is stored is the difference from the prediction (mostly 0 or +-1, as
//! the light varies slowly) in two bits a texel (0, +1, -1, or "the next of the other
//! differences", which follow), packed with zstd. Unpacking computes the same prediction from
//! the rows already unpacked, with the same float operations, so it gives back every texel
//! exactly.
//!
//! A face unpacked for drawing is kept in blocks of [`BLOCK`] x [`BLOCK`] texels (one cache
//! line each, [`blocked_index`]) rather than in rows: the pixels of a run sample a face along
//! a line that crosses its rows (a floor seen at a slant), and in rows every such pixel would
//! touch a line of its own. The small faces kept as they are fit in the cache whole.

use super::faces::{round_byte, FaceOrigin, FaceTexture};
use std::borrow::Cow;
use std::cell::RefCell;
use std::sync::OnceLock;
use vlnverse_env::material::TEX_SIZE;

/// Faces of fewer texels are stored as they are (packing them gains little).
const RAW_BELOW: usize = 4096;
/// zstd level of a face's differences.
const LEVEL: i32 = 3;

/// How a face's texels are stored: as they are, or as differences from the prediction, packed.
const RAW: u32 = 0;
const PREDICTED: u32 = 1;
/// Bytes per face in the stored table: length, how, surface, origin, other differences.
const TABLE: usize = 20;

/// Side in texels of the square blocks an unpacked face is kept in (64 bytes: a cache line).
pub(crate) const BLOCK: u32 = 8;

/// Where texel `(tu, tv)` of a face kept in blocks, `bw` blocks wide, is: its block's
/// `BLOCK * BLOCK` bytes in row-major order of blocks, and row-major inside the block.
#[inline(always)]
pub(crate) fn blocked_index(tu: u32, tv: u32, bw: u32) -> u32 {
    ((tv / BLOCK) * bw + tu / BLOCK) * (BLOCK * BLOCK) + (tv % BLOCK) * BLOCK + tu % BLOCK
}

/// Bytes of a `w x h` face kept in blocks (its sides rounded up to whole blocks).
fn blocked_len(w: usize, h: usize) -> usize {
    let b = BLOCK as usize;
    w.div_ceil(b) * h.div_ceil(b) * b * b
}

/// The rows of a `w x h` face kept in blocks ([`blocks_into`]).
fn from_blocks(blocks: &[u8], w: usize, h: usize) -> Vec<u8> {
    let bw = (w as u32).div_ceil(BLOCK);
    (0..h as u32)
        .flat_map(|tv| (0..w as u32).map(move |tu| blocked_index(tu, tv, bw) as usize))
        .map(|at| blocks[at])
        .collect()
}

/// The texels of a `w`-wide face (rows, one after the other) in blocks ([`blocked_index`]),
/// added to `out`; the texels past the face's sides are 0 and never drawn.
fn blocks_into(rows: &[u8], w: usize, out: &mut Vec<u8>) {
    let b = BLOCK as usize;
    let h = rows.len() / w.max(1);
    let bw = w.div_ceil(b);
    let start = out.len();
    out.resize(start + blocked_len(w, h), 0);
    let out = &mut out[start..];
    for (j, row) in rows.chunks_exact(w.max(1)).enumerate() {
        let first = (j / b * bw * b + j % b) * b;
        // Whole pieces of a block's row as fixed-size moves, then the face's ragged edge.
        let mut pieces = row.chunks_exact(b);
        for (bx, piece) in (&mut pieces).enumerate() {
            let at = first + bx * b * b;
            out[at..at + b].copy_from_slice(piece);
        }
        let rest = pieces.remainder();
        if !rest.is_empty() {
            let at = first + w / b * b * b;
            out[at..at + rest.len()].copy_from_slice(rest);
        }
    }
}

/// One face texture: its stored bytes `data[at..at + len]`.
#[derive(Debug)]
struct Face {
    at: usize,
    len: usize,
    w: usize,
    h: usize,
    origin: FaceOrigin,
    held: Held,
}

/// How a face's texels are held.
#[derive(Debug)]
enum Held {
    /// In rows, as stored (a small face).
    Rows,
    /// In blocks ([`blocks_into`]): a larger face of a scene prepared here.
    Blocks,
    /// Packed as stored, and in blocks once unpacked for drawing.
    Packed(OnceLock<Box<[u8]>>),
}

/// Every face texture of a scene, face `i` being the `i`-th in the order of their first texel
/// in [`super::faces::DrawMesh::texels`].
#[derive(Debug, Default)]
pub(crate) struct FaceTexels {
    data: Vec<u8>,
    faces: Vec<Face>,
}

/// The surface texels under texel row `j` of a face: `out[i]` for texel `(i, j)`.
fn surface_row(luma: &[u8], o: FaceOrigin, j: usize, out: &mut [f32]) {
    const N: usize = TEX_SIZE * TEX_SIZE;
    let tex = luma.get(o.surface as usize * N..(o.surface as usize + 1) * N);
    let Some(tex) = tex else {
        out.fill(0.0);
        return;
    };
    let tv = (o.tv0 as usize + j) & (TEX_SIZE - 1);
    let row = &tex[tv * TEX_SIZE..(tv + 1) * TEX_SIZE];
    let mut i = 0;
    while i < out.len() {
        let tu = (o.tu0 as usize + i) & (TEX_SIZE - 1);
        let n = (TEX_SIZE - tu).min(out.len() - i);
        for (d, s) in out[i..i + n].iter_mut().zip(&row[tu..tu + n]) {
            *d = *s as f32;
        }
        i += n;
    }
}

/// The prediction of row `j > 0` from the row above: `prev` its texels, `tprev` and `t` the
/// surface texels of the row above and of this one. The sums run over the three texels above
/// (the edge ones counted twice at the ends), in one order, so every caller gets the same
/// bytes.
fn predict(prev: &[u8], tprev: &[f32], t: &[f32], out: &mut [u8]) {
    let w = prev.len();
    let at = |i: usize, k: isize| (i as isize + k).clamp(0, w as isize - 1) as usize;
    let one = |i: usize| {
        let (a, b, c) = (at(i, -1), i, at(i, 1));
        let sx = prev[a] as f32 + prev[b] as f32 + prev[c] as f32;
        let st = tprev[a] + tprev[b] + tprev[c];
        round_byte(sx * t[i] / st)
    };
    if w < 3 {
        for (i, o) in out.iter_mut().enumerate() {
            *o = one(i);
        }
        return;
    }
    out[0] = one(0);
    out[w - 1] = one(w - 1);
    // The inner texels branch-free, on vector lanes (the same operations as `one`).
    for (k, o) in out[1..w - 1].iter_mut().enumerate() {
        let sx = prev[k] as f32 + prev[k + 1] as f32 + prev[k + 2] as f32;
        let st = tprev[k] + tprev[k + 1] + tprev[k + 2];
        *o = round_byte(sx * t[k + 1] / st);
    }
}

/// The differences of a `w`-wide face's texels from their predictions (the first row as it
/// is).
fn differences(texels: &[u8], w: usize, o: FaceOrigin, luma: &[u8]) -> Vec<u8> {
    let mut out = texels.to_vec();
    let (mut tprev, mut t, mut p) = (vec![0.0; w], vec![0.0; w], vec![0u8; w]);
    surface_row(luma, o, 0, &mut tprev);
    for (j, (prev, row)) in texels
        .chunks_exact(w)
        .zip(texels.chunks_exact(w).skip(1))
        .enumerate()
    {
        surface_row(luma, o, j + 1, &mut t);
        predict(prev, &tprev, &t, &mut p);
        for ((d, x), q) in out[(j + 1) * w..(j + 2) * w].iter_mut().zip(row).zip(&p) {
            *d = x.wrapping_sub(*q);
        }
        std::mem::swap(&mut tprev, &mut t);
    }
    out
}

/// Difference of each two-bit code: 0, +1, -1, or 0 for "the next of the other differences".
const CODE: [u8; 4] = [0, 1, 255, 0];

/// The four differences of a byte of codes.
const QUADS: [[u8; 4]; 256] = {
    let mut t = [[0u8; 4]; 256];
    let mut b = 0;
    while b < 256 {
        let mut k = 0;
        while k < 4 {
            t[b][k] = CODE[(b >> (2 * k)) & 3];
            k += 1;
        }
        b += 1;
    }
    t
};

/// Differences in two bits each (four to a byte, the first in the low bits), then those that
/// are not 0, +1 or -1, in order.
fn two_bits(d: &[u8]) -> Vec<u8> {
    let mut codes = vec![0u8; d.len().div_ceil(4)];
    let mut other = Vec::new();
    for (i, &v) in d.iter().enumerate() {
        let c = match v {
            0 => 0,
            1 => 1,
            255 => 2,
            _ => {
                other.push(v);
                3
            }
        };
        codes[i / 4] |= c << (2 * (i % 4));
    }
    codes.extend_from_slice(&other);
    codes
}

/// The `n` differences of [`two_bits`]'s bytes, into `out`; `None` when they do not fit `n`.
fn from_two_bits_into(b: &[u8], n: usize, out: &mut Vec<u8>) -> Option<()> {
    let (codes, other) = b.split_at_checked(n.div_ceil(4))?;
    out.clear();
    out.resize(4 * codes.len(), 0);
    for (o, c) in out.chunks_exact_mut(4).zip(codes) {
        o.copy_from_slice(&QUADS[*c as usize]);
    }
    let mut other = other.iter();
    for (q, c) in codes.iter().enumerate() {
        // Codes 3 ("another difference"): both bits set.
        let m = c & (c >> 1) & 0x55;
        if m == 0 {
            continue;
        }
        for k in 0..4 {
            if m >> (2 * k) & 1 != 0 {
                out[4 * q + k] = *other.next()?;
            }
        }
    }
    if other.next().is_some() || out[n..].iter().any(|&v| v != 0) {
        return None;
    }
    out.truncate(n);
    Some(())
}

/// The `n` differences of [`two_bits`]'s bytes; `None` when they do not fit `n`.
#[cfg(test)]
fn from_two_bits(b: &[u8], n: usize) -> Option<Vec<u8>> {
    let mut out = Vec::new();
    from_two_bits_into(b, n, &mut out).map(|()| out)
}

thread_local! {
    /// The buffer packed differences unpack into, per thread: unpacking a face allocates only
    /// the texels it keeps, not a buffer freed at once (short-lived blocks between kept ones
    /// leave holes in the heap).
    static UNPACKED: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    /// The rows a face unpacks into before they go into blocks, per thread (as above).
    static ROWS: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// The differences of a face of `n` texels from its stored bytes, into `out` (None when they
/// do not unpack to exactly that: the frame is larger than its codes and other differences,
/// or corrupt).
fn unpack_differences(stored: &[u8], n: usize, out: &mut Vec<u8>) -> Option<()> {
    UNPACKED.with(|cell| {
        let buf = &mut *cell.borrow_mut();
        // At most the codes and a difference a texel, as before: a larger frame is refused.
        buf.resize(n.div_ceil(4) + n, 0);
        let len =
            super::unzstd::with_decompressor(|z| z.decompress_to_buffer(stored, &mut buf[..]))?
                .ok()?;
        from_two_bits_into(&buf[..len], n, out)
    })
}

/// The texels of a `w`-wide face from their differences (in place).
fn undo_differences(d: &mut [u8], w: usize, o: FaceOrigin, luma: &[u8]) {
    let (mut tprev, mut t, mut p) = (vec![0.0; w], vec![0.0; w], vec![0u8; w]);
    surface_row(luma, o, 0, &mut tprev);
    for j in 1..d.len() / w {
        surface_row(luma, o, j, &mut t);
        let (done, rest) = d.split_at_mut(j * w);
        predict(&done[(j - 1) * w..], &tprev, &t, &mut p);
        for (x, q) in rest[..w].iter_mut().zip(&p) {
            *x = x.wrapping_add(*q);
        }
        std::mem::swap(&mut tprev, &mut t);
    }
}

impl Face {
    /// The texels of this packed face (face `i`, stored as `stored`) in rows, into `rows`;
    /// black, with a warning, when they do not unpack (the frame's size was checked when
    /// read: [`FaceTexels::read`]).
    fn unpack_rows(&self, i: usize, stored: &[u8], rows: &mut Vec<u8>) {
        let n = self.w * self.h;
        if unpack_differences(stored, n, rows).is_none() {
            tracing::warn!("face texture {i} does not unpack; drawn black");
            rows.clear();
            rows.resize(n, 0);
        }
        undo_differences(rows, self.w, self.origin, super::surface_luma());
    }
}

impl FaceTexels {
    /// The baked texels as they are: `texels` of `faces` (one after the other, in order of
    /// `base`) with their surface textures `origin`; faces of [`RAW_BELOW`] texels or more
    /// go into blocks.
    pub(crate) fn raw(texels: Vec<u8>, faces: &[FaceTexture], origin: &[FaceOrigin]) -> FaceTexels {
        let rows_of = |f: &FaceTexture| {
            let (w, h, base) = (f.w as usize, f.h as usize, f.base as usize);
            texels.get(base..base + w * h).unwrap_or(&[])
        };
        // Allocated once, to the byte: the blocks' padding would otherwise grow the buffer
        // (a copy) and `shrink_to_fit` copy it again.
        let size = faces
            .iter()
            .map(|f| match rows_of(f).len() {
                n if n >= RAW_BELOW => blocked_len(f.w as usize, f.h as usize),
                n => n,
            })
            .sum();
        let mut data = Vec::with_capacity(size);
        let faces: Vec<Face> = faces
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let (w, h) = (f.w as usize, f.h as usize);
                let rows = rows_of(f);
                let at = data.len();
                let held = if rows.len() >= RAW_BELOW {
                    blocks_into(rows, w, &mut data);
                    Held::Blocks
                } else {
                    data.extend_from_slice(rows);
                    Held::Rows
                };
                Face {
                    at,
                    len: data.len() - at,
                    w,
                    h,
                    origin: origin.get(i).copied().unwrap_or_default(),
                    held,
                }
            })
            .collect();
        debug_assert_eq!(data.len(), data.capacity());
        FaceTexels { data, faces }
    }

    /// Number of faces.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.faces.len()
    }

    /// The texels of face `i` in rows (empty for an index out of range); made again for
    /// every call unless the face is held in rows.
    pub(crate) fn texels(&self, i: usize) -> Cow<'_, [u8]> {
        let Some(f) = self.faces.get(i) else {
            return Cow::Borrowed(&[]);
        };
        let stored = &self.data[f.at..f.at + f.len];
        match &f.held {
            Held::Rows => Cow::Borrowed(stored),
            Held::Blocks => Cow::Owned(from_blocks(stored, f.w, f.h)),
            Held::Packed(_) => {
                let mut rows = Vec::new();
                f.unpack_rows(i, stored, &mut rows);
                Cow::Owned(rows)
            }
        }
    }

    /// The texels of face `i` as drawn, and whether they are in blocks ([`blocked_index`]) or
    /// in rows (a small face); a packed face is unpacked the first time it is asked for.
    /// Empty for an index out of range.
    pub(crate) fn drawn(&self, i: usize) -> (&[u8], bool) {
        let Some(f) = self.faces.get(i) else {
            return (&[], false);
        };
        let stored = &self.data[f.at..f.at + f.len];
        match &f.held {
            Held::Rows => (stored, false),
            Held::Blocks => (stored, true),
            Held::Packed(cell) => {
                let blocks = cell.get_or_init(|| {
                    ROWS.with(|rows| {
                        let rows = &mut *rows.borrow_mut();
                        f.unpack_rows(i, stored, rows);
                        let mut blocks = Vec::with_capacity(blocked_len(f.w, f.h));
                        blocks_into(rows, f.w, &mut blocks);
                        blocks.into_boxed_slice()
                    })
                });
                (blocks, true)
            }
        }
    }

    /// Bytes held now: the stored bytes and the faces unpacked so far.
    pub(crate) fn held(&self) -> usize {
        self.data.capacity()
            + self.faces.capacity() * std::mem::size_of::<Face>()
            + self
                .faces
                .iter()
                .filter_map(|f| match &f.held {
                    Held::Packed(cell) => cell.get().map(|t| t.len()),
                    _ => None,
                })
                .sum::<usize>()
    }

    /// Bytes held once every face is unpacked.
    pub(crate) fn held_at_most(&self) -> usize {
        self.data.capacity()
            + self.faces.capacity() * std::mem::size_of::<Face>()
            + self
                .faces
                .iter()
                .filter(|f| matches!(f.held, Held::Packed(_)))
                .map(|f| blocked_len(f.w, f.h))
                .sum::<usize>()
    }

    /// Texels of every face.
    pub(crate) fn texel_count(&self) -> usize {
        self.faces.iter().map(|f| f.w * f.h).sum()
    }

    /// The stored form: per face its stored length, how it is stored, its surface, its origin
    /// in it (`tu0 | tv0 << 16`) and the number of its differences that two bits do not hold
    /// (u32 each), then every face's stored bytes; faces of [`RAW_BELOW`] texels or more stored
    /// as packed differences from their prediction.
    pub(crate) fn write(&self) -> Result<Vec<u8>, String> {
        let luma = super::surface_luma();
        let mut table = Vec::with_capacity(TABLE * self.faces.len());
        let mut data = Vec::new();
        for (i, f) in self.faces.iter().enumerate() {
            let t = self.texels(i);
            let (how, stored, other) = if t.len() >= RAW_BELOW {
                let d = two_bits(&differences(&t, f.w, f.origin, luma));
                let other = d.len() - t.len().div_ceil(4);
                let p = zstd::bulk::compress(&d, LEVEL).map_err(|e| e.to_string())?;
                (PREDICTED, p, other as u32)
            } else {
                (RAW, t.to_vec(), 0)
            };
            let o = f.origin;
            for v in [
                stored.len() as u32,
                how,
                o.surface,
                o.tu0 | o.tv0 << 16,
                other,
            ] {
                table.extend_from_slice(&v.to_le_bytes());
            }
            data.extend_from_slice(&stored);
        }
        table.extend_from_slice(&data);
        Ok(table)
    }

    /// The faces stored in `b` ([`FaceTexels::write`]) for `faces` (in order of `base`); what
    /// is wrong otherwise (the face and the values found).
    pub(crate) fn read(b: &[u8], faces: &[FaceTexture]) -> Result<FaceTexels, String> {
        let surfaces = (super::surface_luma().len() / (TEX_SIZE * TEX_SIZE)) as u32;
        let table = faces
            .len()
            .checked_mul(TABLE)
            .filter(|&n| n <= b.len())
            .ok_or_else(|| {
                format!(
                    "{} bytes of face textures for {} faces",
                    b.len(),
                    faces.len()
                )
            })?;
        let (head, data) = b.split_at(table);
        let mut out = Vec::with_capacity(faces.len());
        let mut at = 0usize;
        for (i, (row, f)) in head.chunks_exact(TABLE).zip(faces).enumerate() {
            let word = |k: usize| u32::from_le_bytes(row[4 * k..4 * k + 4].try_into().expect("4"));
            let (len, how, surface, origin) = (word(0) as usize, word(1), word(2), word(3));
            let other = word(4) as u64;
            let (w, h) = (f.w as usize, f.h as usize);
            let n = w * h;
            if data.get(at..at + len).is_none() {
                return Err(format!(
                    "face texture {i}: {len} bytes at {at}, past the end (truncated)"
                ));
            }
            let (tu0, tv0) = (origin & 0xffff, origin >> 16);
            if surface >= surfaces || tu0 as usize >= TEX_SIZE || tv0 as usize >= TEX_SIZE {
                return Err(format!(
                    "face texture {i}: surface {surface} at ({tu0}, {tv0}) (there are \
                     {surfaces} surfaces of {TEX_SIZE}x{TEX_SIZE} texels)"
                ));
            }
            let held = match how {
                RAW if len == n => Held::Rows,
                PREDICTED => {
                    let size = zstd::zstd_safe::get_frame_content_size(&data[at..at + len])
                        .ok()
                        .flatten();
                    // Two bits a texel, and the differences those do not hold.
                    if other > n as u64 || size != Some(n.div_ceil(4) as u64 + other) {
                        return Err(format!(
                            "face texture {i}: packed size {size:?} for {n} texels and {other} \
                             other differences"
                        ));
                    }
                    Held::Packed(OnceLock::new())
                }
                _ => {
                    return Err(format!(
                        "face texture {i}: stored as {how} in {len} bytes, {n} texels expected"
                    ))
                }
            };
            out.push(Face {
                at,
                len,
                w,
                h,
                origin: FaceOrigin { surface, tu0, tv0 },
                held,
            });
            at += len;
        }
        if at != data.len() {
            return Err(format!(
                "face textures of {at} bytes, {} stored",
                data.len()
            ));
        }
        Ok(FaceTexels {
            data: data.to_vec(),
            faces: out,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Faces of `(w, h)` one after the other, their texels a light varying across them times
    /// their surface texture, with a few texels off (a shadow's edge).
    fn faces(dims: &[(u32, u32)]) -> (Vec<u8>, Vec<FaceTexture>, Vec<FaceOrigin>) {
        let luma = super::super::surface_luma();
        let (mut texels, mut f, mut o) = (Vec::new(), Vec::new(), Vec::new());
        for (k, &(w, h)) in dims.iter().enumerate() {
            let origin = FaceOrigin {
                surface: k as u32 % 3,
                tu0: (17 * k as u32) % 128,
                tv0: (5 + 31 * k as u32) % 128,
            };
            f.push(FaceTexture {
                base: texels.len() as u32,
                w,
                h,
            });
            let mut t = vec![0.0; w as usize];
            for j in 0..h as usize {
                surface_row(luma, origin, j, &mut t);
                for (i, s) in t.iter().enumerate() {
                    let light = 0.3 + 0.5 * (i as f32 / w as f32) + 0.2 * (j as f32 / h as f32);
                    let shadow = if (i + j) % 97 < 3 { 0.4 } else { 1.0 };
                    texels.push(round_byte(light * shadow * s));
                }
            }
            o.push(origin);
        }
        (texels, f, o)
    }

    #[test]
    fn stored_faces_read_back_the_same_texels_unpacked_into_blocks_when_first_drawn() {
        let dims = [
            (2, 5),
            (100, 50),
            (1, 1),
            (64, 63),
            (300, 240),
            (128, 40),
            (1, 5000),
            (5000, 1),
        ];
        let (t, f, o) = faces(&dims);
        let raw = FaceTexels::raw(t.clone(), &f, &o);
        let stored = raw.write().unwrap();
        assert!(
            stored.len() < t.len() / 3,
            "{} bytes stored for {} texels",
            stored.len(),
            t.len()
        );
        let read = FaceTexels::read(&stored, &f).unwrap();
        assert_eq!(read.len(), dims.len());
        assert!(read.held() < raw.held(), "packed faces held packed");
        let packed: usize = dims
            .iter()
            .filter(|&&(w, h)| (w * h) as usize >= RAW_BELOW)
            .map(|&(w, h)| blocked_len(w as usize, h as usize))
            .sum();
        assert_eq!(read.held_at_most(), read.held() + packed);
        for (i, face) in f.iter().enumerate() {
            let want = &t[face.base as usize..(face.base + face.w * face.h) as usize];
            for faces in [&read, &raw] {
                assert_eq!(faces.texels(i), want, "face {i}");
                // As drawn: every texel where the resolve looks for it.
                let (drawn, blocked) = faces.drawn(i);
                assert_eq!(blocked, want.len() >= RAW_BELOW, "face {i}");
                let bw = face.w.div_ceil(BLOCK);
                for (k, texel) in want.iter().enumerate() {
                    let (tu, tv) = (k as u32 % face.w, k as u32 / face.w);
                    let at = if blocked {
                        blocked_index(tu, tv, bw)
                    } else {
                        tv * face.w + tu
                    };
                    assert_eq!(drawn[at as usize], *texel, "face {i}, ({tu}, {tv})");
                }
            }
        }
        assert_eq!(read.held(), read.held_at_most(), "every face unpacked");
        assert!(read.texels(dims.len()).is_empty());
        assert!(read.drawn(dims.len()).0.is_empty());
    }

    #[test]
    fn any_texels_come_back_exactly_whatever_the_surface_under_them() {
        // Texels that are not light times the surface (the prediction is off everywhere).
        let (_, f, o) = faces(&[(70, 90)]);
        let t: Vec<u8> = (0..70 * 90)
            .map(|i| ((i * 7 + i / 300) % 256) as u8)
            .collect();
        let stored = FaceTexels::raw(t.clone(), &f, &o).write().unwrap();
        assert_eq!(FaceTexels::read(&stored, &f).unwrap().texels(0), &t[..]);
    }

    #[test]
    fn differences_in_two_bits_come_back_and_misfits_are_refused() {
        let d: Vec<u8> = (0..1001u32)
            .map(|i| match i % 7 {
                0..=2 => 0,
                3 => 1,
                4 => 255,
                _ => (i % 251) as u8,
            })
            .collect();
        let b = two_bits(&d);
        assert_eq!(from_two_bits(&b, d.len()), Some(d.clone()));
        assert!(
            from_two_bits(&b[..b.len() - 1], d.len()).is_none(),
            "one missing"
        );
        let mut more = b.clone();
        more.push(9);
        assert!(from_two_bits(&more, d.len()).is_none(), "one too many");
        assert!(from_two_bits(&b[..10], d.len()).is_none());
        assert_eq!(from_two_bits(&two_bits(&[]), 0), Some(vec![]));
    }

    #[test]
    fn damaged_stored_faces_are_refused_naming_the_face() {
        let (t, f, o) = faces(&[(2, 5), (100, 50)]);
        let stored = FaceTexels::raw(t, &f, &o).write().unwrap();
        let mut other = f.clone();
        other[1].h = 49;
        let e = FaceTexels::read(&stored, &other).unwrap_err();
        assert!(e.contains("face texture 1") && e.contains("4900"), "{e}");
        let e = FaceTexels::read(&stored[..stored.len() - 1], &f).unwrap_err();
        assert!(
            e.contains("face texture 1") && e.contains("truncated"),
            "{e}"
        );
        let e = FaceTexels::read(&stored[..7], &f).unwrap_err();
        assert!(e.contains("2 faces"), "{e}");
        let mut longer = stored.clone();
        longer.push(0);
        let e = FaceTexels::read(&longer, &f).unwrap_err();
        assert!(e.contains("stored"), "{e}");
        let mut surface = stored.clone();
        surface[8..12].copy_from_slice(&999u32.to_le_bytes());
        let e = FaceTexels::read(&surface, &f).unwrap_err();
        assert!(
            e.contains("face texture 0") && e.contains("surface 999"),
            "{e}"
        );
    }
}
