//! Lazy Theta* (any-angle A*) on the free cells of a grid, shared by point-to-point queries and
//! distance fields. Vertices are cell centres; moves are 8-connected without corner cutting
//! (a diagonal step needs both side cells free), and a vertex may take its grandparent as parent
//! when the two see each other (line of sight through free cells only), which makes lengths
//! any-angle instead of 8-connected.

use crate::occupancy::{CellState, GridMap};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Read-only view of the free cells.
pub(crate) struct Grid<'a> {
    pub w: i64,
    pub h: i64,
    cells: &'a [CellState],
    /// The non-free cells counted by box ([`Sat`]), for a grid that answers many
    /// line-of-sight checks (a sweep); `None`: every line is walked cell by cell.
    sat: Option<Sat>,
}

/// Summed-area table of the cells that are not free: `(w + 1) x (h + 1)` counts, entry
/// `(x, y)` the number of non-free cells in columns `< x` of rows `< y`. A line of sight whose
/// cells' bounding box holds none is clear without walking it.
pub(crate) struct Sat {
    w1: usize,
    counts: Vec<u32>,
}

impl Sat {
    fn new(w: usize, h: usize, cells: &[CellState]) -> Sat {
        let w1 = w + 1;
        let mut counts = vec![0u32; w1 * (h + 1)];
        for y in 0..h {
            let mut row = 0u32;
            for x in 0..w {
                row = row.wrapping_add(u32::from(cells[y * w + x] != CellState::Free));
                counts[(y + 1) * w1 + x + 1] = counts[y * w1 + x + 1].wrapping_add(row);
            }
        }
        Sat { w1, counts }
    }

    /// Whether the box of columns `x0..=x1` and rows `y0..=y1` holds only free cells.
    #[inline]
    fn all_free(&self, x0: usize, y0: usize, x1: usize, y1: usize) -> bool {
        let c = &self.counts;
        let (top, bottom) = (y0 * self.w1, (y1 + 1) * self.w1);
        // The box's count, modulo 2^32 (it is below that: at most `w * h`).
        c[bottom + x1 + 1].wrapping_add(c[top + x0]) == c[bottom + x0].wrapping_add(c[top + x1 + 1])
    }
}

/// Steps of a line-of-sight walk between two looks at the box left to walk ([`Sat`]).
const BOX_STRIDE: u32 = 8;

const DIRS: [(i64, i64); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (1, -1),
    (-1, 1),
    (-1, -1),
];

impl<'a> Grid<'a> {
    pub fn new(map: &'a GridMap) -> Self {
        Grid {
            w: map.width as i64,
            h: map.height as i64,
            cells: map.cells(),
            sat: None,
        }
    }

    /// A grid for many line-of-sight checks (a sweep over the whole map): the same answers as
    /// [`Grid::new`]'s, a line whose bounding box holds only free cells found clear at once
    /// ([`Sat`], built here, 4 bytes a cell).
    pub fn with_sat(map: &'a GridMap) -> Self {
        let mut g = Grid::new(map);
        g.sat = Some(Sat::new(g.w as usize, g.h as usize, g.cells));
        g
    }

    #[inline]
    pub fn free_index(&self, i: usize) -> bool {
        self.cells[i] == CellState::Free
    }

    #[inline]
    fn free_xy(&self, x: i64, y: i64) -> bool {
        x >= 0
            && y >= 0
            && x < self.w
            && y < self.h
            && self.cells[(y * self.w + x) as usize] == CellState::Free
    }

    #[inline]
    pub fn xy(&self, i: usize) -> (i64, i64) {
        ((i as i64) % self.w, (i as i64) / self.w)
    }

    /// Supercover line of sight between two free cell centres (exact integer arithmetic; a
    /// segment through a grid corner needs both cells beside the corner free).
    #[inline]
    pub fn los(&self, a: usize, b: usize) -> bool {
        match &self.sat {
            Some(sat) => self.walk(a, b, Some(sat)),
            None => self.walk(a, b, None),
        }
    }

    /// [`Grid::los`] cell by cell, never ended early (the tests' reference).
    #[cfg(test)]
    pub fn los_walk(&self, a: usize, b: usize) -> bool {
        self.walk(a, b, None)
    }

    /// The supercover walk from `a` to `b`. With `sat` it ends early once the box between the
    /// cell it has reached and `b` holds only free cells (looked at first, then every
    /// [`BOX_STRIDE`] steps): the walk is monotone, so every cell it would still look at (those
    /// it enters and those beside a corner it passes) lies in that box. The same answer, often
    /// without walking the line. Inlined into both callers, each with `sat` known.
    #[inline(always)]
    fn walk(&self, a: usize, b: usize, sat: Option<&Sat>) -> bool {
        let (x0, y0) = self.xy(a);
        let (x1, y1) = self.xy(b);
        let (dx, dy) = ((x1 - x0).abs(), (y1 - y0).abs());
        let (sx, ux): (isize, i64) = if x1 > x0 { (1, 1) } else { (-1, -1) };
        let (sy, uy): (isize, i64) = if y1 > y0 {
            (self.w as isize, 1)
        } else {
            (-(self.w as isize), -1)
        };
        // The box from the cell `nx`, `ny` steps before `b` to `b`.
        let clear_to_b = |sat: &Sat, nx: i64, ny: i64| {
            let (cx, cy) = (x1 - ux * nx, y1 - uy * ny);
            sat.all_free(
                cx.min(x1) as usize,
                cy.min(y1) as usize,
                cx.max(x1) as usize,
                cy.max(y1) as usize,
            )
        };
        let cells = self.cells;
        let mut i = a as isize;
        // decision = (1 + 2 ix) dy - (1 + 2 iy) dx, kept incrementally.
        let mut decision = dy - dx;
        let (mut nx, mut ny) = (dx, dy);
        let mut until_box = 0u32;
        while nx > 0 || ny > 0 {
            if let Some(sat) = sat {
                if until_box == 0 {
                    if clear_to_b(sat, nx, ny) {
                        return true;
                    }
                    until_box = BOX_STRIDE;
                }
                until_box -= 1;
            }
            if decision == 0 {
                if cells[(i + sx) as usize] != CellState::Free
                    || cells[(i + sy) as usize] != CellState::Free
                {
                    return false;
                }
                i += sx + sy;
                decision += 2 * dy - 2 * dx;
                nx -= 1;
                ny -= 1;
            } else if decision < 0 {
                i += sx;
                decision += 2 * dy;
                nx -= 1;
            } else {
                i += sy;
                decision -= 2 * dx;
                ny -= 1;
            }
            if cells[i as usize] != CellState::Free {
                return false;
            }
        }
        true
    }

    /// Calls `f(neighbour, nx, ny, step_cost)` for every allowed move from free cell `(x, y)`.
    #[inline]
    fn neighbours(&self, x: i64, y: i64, mut f: impl FnMut(usize, i64, i64, f32)) {
        for (k, &(dx, dy)) in DIRS.iter().enumerate() {
            let (nx, ny) = (x + dx, y + dy);
            if !self.free_xy(nx, ny) {
                continue;
            }
            if k >= 4 && !(self.free_xy(x + dx, y) && self.free_xy(x, y + dy)) {
                continue;
            }
            let cost = if k >= 4 {
                std::f32::consts::SQRT_2
            } else {
                1.0
            };
            f((ny * self.w + nx) as usize, nx, ny, cost);
        }
    }
}

#[inline]
fn hypot(dx: i64, dy: i64) -> f32 {
    ((dx * dx + dy * dy) as f32).sqrt()
}

/// Reusable search buffers; cells are valid for the current generation only, so a new search
/// does not clear them.
pub(crate) struct Scratch {
    g: Vec<f32>,
    parent: Vec<u32>,
    /// `2*gen` seen this search, `2*gen + 1` closed; older values mean untouched.
    mark: Vec<u32>,
    gen: u32,
    heap: BinaryHeap<Reverse<(u64, u32)>>,
    order: Vec<u32>,
}

impl Scratch {
    pub fn new() -> Scratch {
        Scratch {
            g: Vec::new(),
            parent: Vec::new(),
            mark: Vec::new(),
            gen: 0,
            heap: BinaryHeap::new(),
            order: Vec::new(),
        }
    }

    fn reset(&mut self, n: usize) {
        if self.mark.len() != n || self.gen >= u32::MAX / 2 - 1 {
            self.g = vec![f32::INFINITY; n];
            self.parent = vec![u32::MAX; n];
            self.mark = vec![0; n];
            self.gen = 0;
        }
        self.gen += 1;
        self.heap.clear();
        self.order.clear();
    }

    #[inline]
    fn closed(&self, i: usize) -> bool {
        self.mark[i] == 2 * self.gen + 1
    }

    /// Parent of a cell reached by the last search.
    #[inline]
    pub fn parent(&self, i: usize) -> usize {
        self.parent[i] as usize
    }
}

/// Cells a sweep reached: a bit a cell and, per word of 64, the count of set bits before it,
/// so a reached cell's slot in per-reached-cell arrays is a popcount away. The default reaches
/// no cell.
#[derive(Clone, Debug, Default)]
pub(crate) struct Reached {
    bits: Vec<u64>,
    before: Vec<u32>,
}

impl Reached {
    /// The slot of cell `i` among the reached cells (in cell order), None when not reached.
    #[inline]
    pub fn slot(&self, i: usize) -> Option<usize> {
        let w = *self.bits.get(i / 64)?;
        let bit = 1u64 << (i % 64);
        (w & bit != 0).then(|| self.before[i / 64] as usize + (w & (bit - 1)).count_ones() as usize)
    }

    /// Bytes held, by capacity.
    pub fn bytes(&self) -> usize {
        self.bits.capacity() * 8 + self.before.capacity() * 4
    }
}

/// Result of a full sweep: distance (cells) and parent of every reachable cell, in cell order.
pub(crate) struct SearchResult {
    pub reached: Reached,
    pub g: Vec<f32>,
    pub parent: Vec<u32>,
    /// Cells in the order they were closed (parents always come before children).
    #[cfg(test)]
    pub order: Vec<u32>,
}

/// Heap key: f first, then larger g first (ties broken towards the target), then index.
#[inline]
fn key(f: f32, g: f32) -> u64 {
    ((f.to_bits() as u64) << 32) | (!g.to_bits()) as u64
}

/// Lazy Theta* from `root` in `sc`; stops when `target` is closed (A* with the Euclidean
/// heuristic, admissible and consistent for any-angle lengths) or, with no target, when every
/// reachable cell is closed. Returns whether the target was reached. `root` must be free.
pub(crate) fn lazy_theta(
    grid: &Grid<'_>,
    root: usize,
    target: Option<usize>,
    sc: &mut Scratch,
) -> bool {
    let n = (grid.w * grid.h) as usize;
    sc.reset(n);
    let seen = 2 * sc.gen;
    let closed_mark = seen + 1;
    let (tx, ty) = target.map_or((0, 0), |t| grid.xy(t));
    let h = |x: i64, y: i64| {
        if target.is_some() {
            hypot(x - tx, y - ty)
        } else {
            0.0
        }
    };
    sc.g[root] = 0.0;
    sc.parent[root] = root as u32;
    sc.mark[root] = seen;
    let (rx, ry) = grid.xy(root);
    sc.heap.push(Reverse((key(h(rx, ry), 0.0), root as u32)));
    while let Some(Reverse((_, s))) = sc.heap.pop() {
        let s = s as usize;
        if sc.mark[s] == closed_mark {
            continue;
        }
        let (x, y) = grid.xy(s);
        // Lazy line-of-sight check of the optimistic parent.
        let p = sc.parent[s] as usize;
        if p != s && !grid.los(p, s) {
            // Fall back to the best closed neighbour, or to a neighbour's parent when it is in
            // sight (plain Lazy Theta* only takes the neighbour, which leaves staircase bends).
            let mut cands: [(f32, u32, bool); 16] = [(f32::INFINITY, u32::MAX, false); 16];
            let mut k = 0;
            grid.neighbours(x, y, |nb, _, _, cost| {
                if sc.closed(nb) {
                    cands[k] = (sc.g[nb] + cost, nb as u32, false);
                    k += 1;
                    let pn = sc.parent[nb] as usize;
                    if pn != nb && pn != p {
                        let (px, py) = grid.xy(pn);
                        cands[k] = (sc.g[pn] + hypot(px - x, py - y), pn as u32, true);
                        k += 1;
                    }
                }
            });
            let cands = &mut cands[..k];
            cands.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            for &(cost, via, needs_los) in cands.iter() {
                if !needs_los || grid.los(via as usize, s) {
                    sc.g[s] = cost;
                    sc.parent[s] = via;
                    break;
                }
            }
        }
        sc.mark[s] = closed_mark;
        sc.order.push(s as u32);
        if Some(s) == target {
            return true;
        }
        let ps = sc.parent[s] as usize;
        let gps = sc.g[ps];
        let (px, py) = grid.xy(ps);
        let Scratch {
            g,
            parent,
            mark,
            heap,
            ..
        } = sc;
        grid.neighbours(x, y, |nb, nx, ny, _| {
            let m = mark[nb];
            if m == closed_mark {
                return;
            }
            let cand = gps + hypot(nx - px, ny - py);
            if m != seen || cand < g[nb] {
                g[nb] = cand;
                parent[nb] = ps as u32;
                mark[nb] = seen;
                heap.push(Reverse((key(cand + h(nx, ny), cand), nb as u32)));
            }
        });
    }
    false
}

/// Lazy Theta* sweep from `root` over every reachable cell (a distance field); `grid` best
/// made with [`Grid::with_sat`] (a sweep checks a line of sight from every cell it closes).
pub(crate) fn sweep(grid: &Grid<'_>, root: usize) -> SearchResult {
    SWEEP.with(|sc| {
        let sc = &mut *sc.borrow_mut();
        lazy_theta(grid, root, None, sc);
        // Marked this sweep (every cell seen is closed once the heap is empty); the others hold
        // older sweeps' values.
        let seen = 2 * sc.gen;
        let words = sc.mark.len().div_ceil(64);
        let (mut bits, mut before) = (Vec::with_capacity(words), Vec::with_capacity(words));
        let mut g = Vec::with_capacity(sc.order.len());
        let mut parent = Vec::with_capacity(sc.order.len());
        for (w, marks) in sc.mark.chunks(64).enumerate() {
            before.push(g.len() as u32);
            let mut word = 0u64;
            for (j, &m) in marks.iter().enumerate() {
                if m >= seen {
                    word |= 1 << j;
                    g.push(sc.g[w * 64 + j]);
                    parent.push(sc.parent[w * 64 + j]);
                }
            }
            bits.push(word);
        }
        SearchResult {
            reached: Reached { bits, before },
            g,
            parent,
            #[cfg(test)]
            order: sc.order.clone(),
        }
    })
}

thread_local! {
    /// Sweep buffers reused by this thread's sweeps (a sweep allocates only what it returns).
    static SWEEP: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::new());
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// A `w` x `h` map whose cells are occupied with probability `p` (splitmix64 on `seed`).
    fn random_map(w: u32, h: u32, p: f64, seed: u64) -> GridMap {
        let mut state = seed;
        let cells = (0..w * h)
            .map(|_| {
                state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
                let mut z = state;
                z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                z ^= z >> 31;
                if ((z >> 11) as f64) < p * (1u64 << 53) as f64 {
                    CellState::Occupied
                } else {
                    CellState::Free
                }
            })
            .collect();
        GridMap::from_cells(w, h, 0.05, Vec2::ZERO, cells).unwrap()
    }

    #[test]
    fn lines_of_sight_by_boxes_are_those_of_the_walk() {
        for (k, p) in [0.0, 0.05, 0.2, 0.45].into_iter().enumerate() {
            let map = random_map(41, 23, p, k as u64);
            let (walk, sat) = (Grid::new(&map), Grid::with_sat(&map));
            let free: Vec<usize> = (0..map.len()).filter(|&i| walk.free_index(i)).collect();
            let mut seen = [0usize; 2];
            for &a in &free {
                for &b in &free {
                    let want = walk.los_walk(a, b);
                    assert_eq!(
                        sat.los(a, b),
                        want,
                        "p {p}: {:?} -> {:?}",
                        walk.xy(a),
                        walk.xy(b)
                    );
                    assert_eq!(walk.los(a, b), want);
                    seen[usize::from(want)] += 1;
                }
            }
            if p > 0.0 {
                assert!(seen[0] > 0 && seen[1] > 0, "p {p}: {seen:?}");
            }
        }
    }

    #[test]
    fn a_line_beside_an_obstacle_in_its_box_is_still_clear() {
        // 9 x 9 free but for the corner cell (8, 0): the diagonal from (0, 0) to (8, 8) does
        // not reach it, though its box holds it; the line along row 0 does.
        let mut map = GridMap::new(9, 9, 0.05, Vec2::ZERO, CellState::Free).unwrap();
        map.set(8, 0, CellState::Occupied);
        let g = Grid::with_sat(&map);
        assert!(g.los(0, 80) && g.los(80, 0));
        assert!(!g.los(0, 8) && g.los(0, 7));
        assert!(g.los(9, 8 * 9 + 8) && !g.los(9 * 8, 8));
    }

    #[test]
    fn reached_cells_are_ranked_in_cell_order() {
        // Two rooms, the right one walled off: its free cells are never reached.
        let mut map = GridMap::new(130, 7, 0.05, Vec2::ZERO, CellState::Free).unwrap();
        for y in 0..7 {
            map.set(70, y, CellState::Occupied);
        }
        map.set(3, 3, CellState::Occupied);
        let res = sweep(&Grid::with_sat(&map), 0);
        let mut next = 0;
        for i in 0..map.len() {
            let (x, y) = (i % 130, i / 130);
            let reachable = x < 70 && (x, y) != (3, 3);
            match res.reached.slot(i) {
                Some(k) => {
                    assert!(reachable, "cell ({x}, {y}) reached");
                    assert_eq!(k, next, "cell ({x}, {y})");
                    assert!(res.g[k].is_finite());
                    next += 1;
                }
                None => assert!(!reachable, "cell ({x}, {y}) not reached"),
            }
        }
        assert_eq!(next, res.g.len());
        assert_eq!(res.reached.slot(map.len() + 64), None);
    }

    #[test]
    fn a_sweep_with_boxes_is_the_sweep_without() {
        for (k, p) in [0.05, 0.25].into_iter().enumerate() {
            let map = random_map(57, 38, p, 10 + k as u64);
            let (walk, sat) = (Grid::new(&map), Grid::with_sat(&map));
            for root in (0..map.len()).filter(|&i| walk.free_index(i)).step_by(97) {
                let (a, b) = (sweep(&walk, root), sweep(&sat, root));
                let bits = |r: &SearchResult| r.g.iter().map(|g| g.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&a), bits(&b));
                assert_eq!(a.parent, b.parent);
                assert_eq!(a.order, b.order);
            }
        }
    }
}
