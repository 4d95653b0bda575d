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

/// One row of a vertical distance pass: 0 on occupied cells, else one more than the row before
/// (capped).
fn column_step(last: &mut [u16], row: &[CellState], cap: u16) {
    for (l, &c) in last.iter_mut().zip(row) {
        *l = if c == CellState::Occupied {
            0
        } else {
            (*l + 1).min(cap)
        };
    }
}

/// Free cells of `map` whose centre is at least `radius + resolution/2` from the centre of every
/// occupied cell stay free; other free cells become occupied; unknown cells stay unknown.
/// (Measured to occupied cells only: the edge of the known floor does not push the agent away.)
///
/// Exact Euclidean test in O(cells): the vertical distance to the nearest occupied cell of each
/// column (capped at the radius), then per row every column with a small vertical distance blocks
/// the interval of cells within the radius (a difference array), which is the row pass of the
/// separable distance transform specialised to one threshold.
pub fn dilate(map: &GridMap, radius: f32) -> GridMap {
    let (w, h) = (map.width as usize, map.height as usize);
    let need = (radius.max(0.0) / map.resolution) as f64 + 0.5;
    let need2 = need * need;
    // Vertical distances >= `cap` never block.
    let cap = need.ceil().min(u16::MAX as f64 - 1.0) as u16;
    // Half-width of the blocked interval for each vertical distance (-1: blocks nothing).
    let hw: Vec<i64> = (0..=cap as i64)
        .map(|g| {
            let g2 = (g * g) as f64;
            if g2 >= need2 {
                return -1;
            }
            let mut dx = (need2 - g2).sqrt().floor() as i64;
            while dx > 0 && (dx * dx) as f64 + g2 >= need2 {
                dx -= 1;
            }
            dx
        })
        .collect();
    let cells = map.cells();
    let mut gv = vec![cap; w * h];
    let mut last = vec![cap; w];
    // Down, then up: each pass carries the distance to the last occupied cell in each column.
    for y in 0..h {
        column_step(&mut last, &cells[y * w..(y + 1) * w], cap);
        gv[y * w..(y + 1) * w].copy_from_slice(&last);
    }
    last.fill(cap);
    for y in (0..h).rev() {
        column_step(&mut last, &cells[y * w..(y + 1) * w], cap);
        for (o, &l) in gv[y * w..(y + 1) * w].iter_mut().zip(&last) {
            *o = (*o).min(l);
        }
    }
    let mut out = map.clone();
    let mut diff = vec![0i32; w + 1];
    let dst = out.cells_mut();
    for y in 0..h {
        diff.fill(0);
        let g = &gv[y * w..(y + 1) * w];
        for (x, &gx) in g.iter().enumerate() {
            let r = hw[gx as usize];
            if r >= 0 {
                let a = (x as i64 - r).max(0) as usize;
                let b = (x as i64 + r + 1).min(w as i64) as usize;
                diff[a] += 1;
                diff[b] -= 1;
            }
        }
        let mut acc = 0;
        let row = &mut dst[y * w..(y + 1) * w];
        for x in 0..w {
            acc += diff[x];
            if acc > 0 && row[x] == CellState::Free {
                row[x] = CellState::Occupied;
            }
        }
    }
    out
}

/// Keep only the largest 4-connected island of free cells (ties: the island with the smallest
/// first cell in row-major order); other free cells become occupied. Returns the island size.
///
/// Union-find over horizontal runs of free cells, so the cost is one pass over the cells plus a
/// little per run.
pub fn keep_largest_island(map: &mut GridMap) -> usize {
    keep_best_island(map, None)
}

/// Like [`keep_largest_island`], but when `covered` (one flag per cell, row-major) marks any
/// cell of any island, keep the island with the most covered cells (ties: the larger, then the
/// first): an imported house with a terrace or garden around it keeps its indoor floor, the
/// one under its ceiling, even when the outdoor area is larger.
pub fn keep_best_island(map: &mut GridMap, covered: Option<&[bool]>) -> usize {
    let (w, h) = (map.width as usize, map.height as usize);
    let cells = map.cells_mut();
    // Runs as (row start index, x0, x1 exclusive); row_start[y] = first run of row y.
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut run_row: Vec<usize> = Vec::new();
    let mut row_start = vec![0usize; h + 1];
    let mut parent: Vec<u32> = Vec::new();
    fn find(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            let p = parent[i as usize];
            parent[i as usize] = parent[p as usize];
            i = p;
        }
        i
    }
    for y in 0..h {
        row_start[y] = runs.len();
        let row = &cells[y * w..(y + 1) * w];
        let mut x = 0;
        while x < w {
            if row[x] != CellState::Free {
                x += 1;
                continue;
            }
            let x0 = x;
            while x < w && row[x] == CellState::Free {
                x += 1;
            }
            let id = runs.len() as u32;
            runs.push((x0, x));
            run_row.push(y);
            parent.push(id);
        }
        if y > 0 {
            // Merge with overlapping runs of the previous row (two pointers).
            let (mut i, mut j) = (row_start[y - 1], row_start[y]);
            let (end_prev, end_cur) = (row_start[y], runs.len());
            while i < end_prev && j < end_cur {
                let (a0, a1) = runs[i];
                let (b0, b1) = runs[j];
                if a0 < b1 && b0 < a1 {
                    let (ra, rb) = (find(&mut parent, i as u32), find(&mut parent, j as u32));
                    if ra != rb {
                        // The smaller index stays root: roots order components by first cell.
                        let (lo, hi) = (ra.min(rb), ra.max(rb));
                        parent[hi as usize] = lo;
                    }
                }
                if a1 < b1 {
                    i += 1;
                } else {
                    j += 1;
                }
            }
        }
    }
    row_start[h] = runs.len();
    debug_assert!(
        covered.is_none_or(|c| c.len() == cells.len()),
        "one flag per cell"
    );
    let covered = covered.filter(|c| c.len() == cells.len());
    let mut size = vec![0usize; runs.len()];
    let mut under = vec![0usize; runs.len()];
    let mut root = vec![0u32; runs.len()];
    for r in 0..runs.len() {
        let rt = find(&mut parent, r as u32);
        root[r] = rt;
        let (x0, x1) = runs[r];
        size[rt as usize] += x1 - x0;
        if let Some(c) = covered {
            let base = run_row[r] * w;
            under[rt as usize] += c[base + x0..base + x1].iter().filter(|&&f| f).count();
        }
    }
    // (covered cells, size, root); the first root wins ties.
    let mut best = (0usize, 0usize, u32::MAX);
    for (r, (&s, &u)) in size.iter().zip(&under).enumerate() {
        if (u, s) > (best.0, best.1) {
            best = (u, s, r as u32);
        }
    }
    let best = (best.1, best.2);
    for (r, &(x0, x1)) in runs.iter().enumerate() {
        if root[r] != best.1 {
            let base = run_row[r] * w;
            cells[base + x0..base + x1].fill(CellState::Occupied);
        }
    }
    best.0
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
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

    fn pseudo_random_map(w: u32, h: u32, seed: u64) -> GridMap {
        let mut state = seed;
        let cells = (0..w * h)
            .map(|_| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                match (state >> 33) % 23 {
                    0 => CellState::Occupied,
                    1 => CellState::Unknown,
                    _ => CellState::Free,
                }
            })
            .collect();
        GridMap::from_cells(w, h, 0.05, glam::Vec2::ZERO, cells).unwrap()
    }

    #[test]
    fn dilation_matches_the_full_distance_transform() {
        for (seed, radius) in [(1, 0.3f32), (2, 0.12), (3, 0.0), (4, 0.51)] {
            let m = pseudo_random_map(61, 47, seed);
            let d2 = squared_distance_transform(m.width, m.height, |i| {
                m.cells()[i] == CellState::Occupied
            });
            let need = (radius / m.resolution) as f64 + 0.5;
            let fast = dilate(&m, radius);
            for i in 0..m.len() {
                let expect = match m.cells()[i] {
                    CellState::Free if d2[i] < need * need => CellState::Occupied,
                    c => c,
                };
                assert_eq!(fast.cells()[i], expect, "seed {seed} cell {i}");
            }
        }
    }

    #[test]
    fn covered_island_wins_over_a_larger_open_one() {
        // Two islands split by a wall column: 6 columns on the left, 3 on the right (covered).
        let mut m = GridMap::new(10, 4, 0.1, glam::Vec2::ZERO, CellState::Free).unwrap();
        for y in 0..4 {
            let i = m.index(6, y);
            m.cells_mut()[i] = CellState::Occupied;
        }
        let covered: Vec<bool> = (0..40).map(|i| i % 10 >= 7).collect();
        let mut a = m.clone();
        assert_eq!(keep_best_island(&mut a, Some(&covered)), 12);
        assert_eq!(a.cells()[a.index(8, 0)], CellState::Free);
        assert_eq!(a.cells()[a.index(0, 0)], CellState::Occupied);
        // Without coverage (or with none marked) the largest stays.
        let mut b = m.clone();
        assert_eq!(keep_best_island(&mut b, Some(&[false; 40])), 24);
        assert_eq!(keep_largest_island(&mut m), 24);
        assert_eq!(m.cells(), b.cells());
    }

    #[test]
    fn largest_island_matches_flood_fill() {
        for seed in 0..6 {
            let mut m = pseudo_random_map(40, 30, seed);
            // Sparse free space so that there are many islands.
            for (i, c) in m.cells_mut().iter_mut().enumerate() {
                if *c == CellState::Free && (i * 7 + seed as usize).is_multiple_of(3) {
                    *c = CellState::Occupied;
                }
            }
            let orig = m.clone();
            let kept = keep_largest_island(&mut m);
            // Reference: BFS labelling.
            let (w, h) = (40usize, 30usize);
            let mut label = vec![usize::MAX; w * h];
            let mut best = (0usize, usize::MAX);
            for s in 0..w * h {
                if orig.cells()[s] != CellState::Free || label[s] != usize::MAX {
                    continue;
                }
                let mut stack = vec![s];
                label[s] = s;
                let mut n = 0;
                while let Some(i) = stack.pop() {
                    n += 1;
                    let (x, y) = (i % w, i / w);
                    let mut nb = Vec::new();
                    if x > 0 {
                        nb.push(i - 1);
                    }
                    if x + 1 < w {
                        nb.push(i + 1);
                    }
                    if y > 0 {
                        nb.push(i - w);
                    }
                    if y + 1 < h {
                        nb.push(i + w);
                    }
                    for j in nb {
                        if orig.cells()[j] == CellState::Free && label[j] == usize::MAX {
                            label[j] = s;
                            stack.push(j);
                        }
                    }
                }
                if n > best.0 {
                    best = (n, s);
                }
            }
            assert_eq!(kept, best.0);
            for i in 0..w * h {
                let expect = match orig.cells()[i] {
                    CellState::Free if label[i] != best.1 => CellState::Occupied,
                    c => c,
                };
                assert_eq!(m.cells()[i], expect, "seed {seed} cell {i}");
            }
        }
    }
}
