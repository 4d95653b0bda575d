//! Exact Euclidean distance transform (Felzenszwalb & Huttenlocher, O(cells)), dilation and
//! island selection.

use super::{CellState, GridMap};

/// Squared distance, in cells, from each cell centre to the centre of the nearest cell for which
/// `is_source` holds (`f64::INFINITY` when there is none). Exact, linear in the number of cells.
pub fn squared_distance_transform(
    width: u32,
    height: u32,
    is_source: impl Fn(usize) -> bool,
) -> Vec<f64> {
    let (w, h) = (width as usize, height as usize);
    // Larger than any real squared distance, finite so that the envelope arithmetic stays exact.
    let big = ((w + h) * (w + h)) as f64 * 4.0 + 1.0;
    let mut d: Vec<f64> = (0..w * h)
        .map(|i| if is_source(i) { 0.0 } else { big })
        .collect();
    let n = w.max(h);
    let mut f = vec![0.0; n];
    let mut out = vec![0.0; n];
    let mut v = vec![0usize; n];
    let mut z = vec![0.0; n + 1];
    // Columns.
    for x in 0..w {
        for y in 0..h {
            f[y] = d[y * w + x];
        }
        dt_1d(&f[..h], &mut out[..h], &mut v, &mut z);
        for y in 0..h {
            d[y * w + x] = out[y];
        }
    }
    // Rows.
    for y in 0..h {
        let row = &mut d[y * w..(y + 1) * w];
        f[..w].copy_from_slice(row);
        dt_1d(&f[..w], &mut out[..w], &mut v, &mut z);
        row.copy_from_slice(&out[..w]);
    }
    for x in d.iter_mut() {
        if *x >= big {
            *x = f64::INFINITY;
        }
    }
    d
}

/// 1-D squared distance transform of a sampled function (lower envelope of parabolas).
fn dt_1d(f: &[f64], d: &mut [f64], v: &mut [usize], z: &mut [f64]) {
    let n = f.len();
    if n == 0 {
        return;
    }
    let mut k = 0usize;
    v[0] = 0;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in 1..n {
        let qf = q as f64;
        let parabola = |p: usize| {
            let pf = p as f64;
            ((f[q] + qf * qf) - (f[p] + pf * pf)) / (2.0 * qf - 2.0 * pf)
        };
        let mut s = parabola(v[k]);
        // z[0] = -inf, so k never goes below 0.
        while s <= z[k] {
            k -= 1;
            s = parabola(v[k]);
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f64::INFINITY;
    }
    k = 0;
    for (q, dq) in d.iter_mut().enumerate() {
        let qf = q as f64;
        while z[k + 1] < qf {
            k += 1;
        }
        let p = v[k] as f64;
        *dq = (qf - p) * (qf - p) + f[v[k]];
    }
}

/// Free cells of `map` whose centre is at least `radius + resolution/2` from the centre of every
/// occupied cell stay free; other free cells become occupied; unknown cells stay unknown.
/// (Measured to occupied cells only: the edge of the known floor does not push the agent away.)
pub fn dilate(map: &GridMap, radius: f32) -> GridMap {
    let cells = map.cells();
    let d2 = squared_distance_transform(map.width, map.height, |i| {
        cells[i] == CellState::Occupied
    });
    let need = (radius.max(0.0) / map.resolution) as f64 + 0.5;
    let need2 = need * need;
    let mut out = map.clone();
    for (i, c) in out.cells_mut().iter_mut().enumerate() {
        if *c == CellState::Free && d2[i] < need2 {
            *c = CellState::Occupied;
        }
    }
    out
}

/// Keep only the largest 4-connected island of free cells (ties: the island with the smallest
/// first cell in row-major order); other free cells become occupied. Returns the island size.
pub fn keep_largest_island(map: &mut GridMap) -> usize {
    let (w, h) = (map.width as usize, map.height as usize);
    let cells = map.cells_mut();
    let mut label = vec![0u32; w * h];
    let mut stack = Vec::new();
    let mut best = (0usize, 0u32);
    let mut next = 0u32;
    for start in 0..w * h {
        if cells[start] != CellState::Free || label[start] != 0 {
            continue;
        }
        next += 1;
        label[start] = next;
        stack.push(start);
        let mut size = 0usize;
        while let Some(i) = stack.pop() {
            size += 1;
            let (x, y) = (i % w, i / w);
            let mut visit = |j: usize| {
                if cells[j] == CellState::Free && label[j] == 0 {
                    label[j] = next;
                    stack.push(j);
                }
            };
            if x > 0 {
                visit(i - 1);
            }
            if x + 1 < w {
                visit(i + 1);
            }
            if y > 0 {
                visit(i - w);
            }
            if y + 1 < h {
                visit(i + w);
            }
        }
        if size > best.0 {
            best = (size, next);
        }
    }
    for (c, &l) in cells.iter_mut().zip(&label) {
        if *c == CellState::Free && l != best.1 {
            *c = CellState::Occupied;
        }
    }
    best.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edt_matches_brute_force() {
        let (w, h) = (23u32, 17u32);
        let src: Vec<bool> = (0..w * h)
            .map(|i| (i * 7919 + 13) % 37 == 0 || i == 5)
            .collect();
        let d = squared_distance_transform(w, h, |i| src[i]);
        for i in 0..(w * h) as usize {
            let (x, y) = ((i % w as usize) as f64, (i / w as usize) as f64);
            let mut best = f64::INFINITY;
            for j in 0..(w * h) as usize {
                if src[j] {
                    let (a, b) = ((j % w as usize) as f64, (j / w as usize) as f64);
                    best = best.min((x - a).powi(2) + (y - b).powi(2));
                }
            }
            assert_eq!(d[i], best, "cell {i}");
        }
        let none = squared_distance_transform(4, 3, |_| false);
        assert!(none.iter().all(|x| x.is_infinite()));
    }
}
