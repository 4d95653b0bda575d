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
}

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
        }
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

    /// Euclidean distance between two cell centres, in cells.
    #[inline]
    pub fn dist(&self, a: usize, b: usize) -> f32 {
        let (ax, ay) = self.xy(a);
        let (bx, by) = self.xy(b);
        (((ax - bx) * (ax - bx) + (ay - by) * (ay - by)) as f32).sqrt()
    }

    /// Supercover line of sight between two free cell centres (exact integer arithmetic; a
    /// segment through a grid corner needs both cells beside the corner free).
    pub fn los(&self, a: usize, b: usize) -> bool {
        let (mut x, mut y) = self.xy(a);
        let (x1, y1) = self.xy(b);
        let (dx, dy) = ((x1 - x).abs(), (y1 - y).abs());
        let (sx, sy) = ((x1 - x).signum(), (y1 - y).signum());
        let w = self.w;
        let cells = self.cells;
        let free = |x: i64, y: i64| cells[(y * w + x) as usize] == CellState::Free;
        let (mut ix, mut iy) = (0i64, 0i64);
        while ix < dx || iy < dy {
            let decision = (1 + 2 * ix) * dy - (1 + 2 * iy) * dx;
            if decision == 0 {
                if !free(x + sx, y) || !free(x, y + sy) {
                    return false;
                }
                x += sx;
                y += sy;
                ix += 1;
                iy += 1;
            } else if decision < 0 {
                x += sx;
                ix += 1;
            } else {
                y += sy;
                iy += 1;
            }
            if !free(x, y) {
                return false;
            }
        }
        true
    }

    /// Calls `f(neighbour, step_cost)` for every allowed move from free cell `i`.
    #[inline]
    fn neighbours(&self, i: usize, mut f: impl FnMut(usize, f32)) {
        let (x, y) = self.xy(i);
        for (k, &(dx, dy)) in DIRS.iter().enumerate() {
            let (nx, ny) = (x + dx, y + dy);
            if !self.free_xy(nx, ny) {
                continue;
            }
            if k >= 4 && !(self.free_xy(x + dx, y) && self.free_xy(x, y + dy)) {
                continue;
            }
            let cost = if k >= 4 { std::f32::consts::SQRT_2 } else { 1.0 };
            f((ny * self.w + nx) as usize, cost);
        }
    }
}

/// Result of a search: distance (cells) and parent of every closed cell.
pub(crate) struct SearchResult {
    pub g: Vec<f32>,
    pub parent: Vec<u32>,
    /// Cells in the order they were closed (parents always come before children).
    pub order: Vec<u32>,
    /// Whether the target (if any) was reached.
    pub reached: bool,
}

/// Lazy Theta* from `root`; stops when `target` is closed (A* with the Euclidean heuristic,
/// admissible and consistent for any-angle lengths) or, with no target, when every reachable
/// cell is closed (a distance field). `root` must be a free cell.
pub(crate) fn lazy_theta(grid: &Grid<'_>, root: usize, target: Option<usize>) -> SearchResult {
    let n = (grid.w * grid.h) as usize;
    let mut g = vec![f32::INFINITY; n];
    let mut parent = vec![u32::MAX; n];
    let mut closed = vec![false; n];
    let mut order = Vec::new();
    let mut heap: BinaryHeap<Reverse<(u32, u32)>> = BinaryHeap::new();
    let h = |i: usize| target.map_or(0.0, |t| grid.dist(i, t));
    g[root] = 0.0;
    parent[root] = root as u32;
    heap.push(Reverse((h(root).to_bits(), root as u32)));
    let mut reached = false;
    while let Some(Reverse((_, s))) = heap.pop() {
        let s = s as usize;
        if closed[s] {
            continue;
        }
        // Lazy line-of-sight check of the optimistic parent.
        let p = parent[s] as usize;
        if p != s && !grid.los(p, s) {
            // Fall back to the best closed neighbour, or to a neighbour's parent when it is in
            // sight (plain Lazy Theta* only takes the neighbour, which leaves staircase bends).
            let mut cands: [(f32, u32, bool); 16] = [(f32::INFINITY, u32::MAX, false); 16];
            let mut n = 0;
            grid.neighbours(s, |nb, cost| {
                if closed[nb] {
                    cands[n] = (g[nb] + cost, nb as u32, false);
                    n += 1;
                    let pn = parent[nb] as usize;
                    if pn != nb && pn != p {
                        cands[n] = (g[pn] + grid.dist(pn, s), pn as u32, true);
                        n += 1;
                    }
                }
            });
            let cands = &mut cands[..n];
            cands.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            for &(cost, via, needs_los) in cands.iter() {
                if !needs_los || grid.los(via as usize, s) {
                    g[s] = cost;
                    parent[s] = via;
                    break;
                }
            }
        }
        closed[s] = true;
        order.push(s as u32);
        if Some(s) == target {
            reached = true;
            break;
        }
        let ps = parent[s] as usize;
        let gps = g[ps];
        grid.neighbours(s, |nb, _| {
            if closed[nb] {
                return;
            }
            let cand = gps + grid.dist(ps, nb);
            if cand < g[nb] {
                g[nb] = cand;
                parent[nb] = ps as u32;
                heap.push(Reverse(((cand + h(nb)).to_bits(), nb as u32)));
            }
        });
    }
    SearchResult {
        g,
        parent,
        order,
        reached,
    }
}
