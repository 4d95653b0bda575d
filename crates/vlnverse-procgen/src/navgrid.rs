//! A coarse per-room free-space grid used while placing furniture: a cell is blocked when its
//! centre is closer than the check radius to a wall or a piece of furniture. A placement is kept
//! only if the free cells stay one connected island that contains every doorway's approach
//! point, so the agent can still reach every part of the room and pass through it.

use crate::rect::Rect;
use std::collections::VecDeque;

/// Free-space grid of one room.
#[derive(Clone, Debug)]
pub(crate) struct NavGrid {
    x0: f32,
    z0: f32,
    cell: f32,
    cols: usize,
    rows: usize,
    radius: f32,
    blocked: Vec<u16>,
    /// Scratch buffer for the flood fill.
    seen: Vec<bool>,
    queue: VecDeque<usize>,
}

impl NavGrid {
    /// Grid over a room interior; cells near the walls start blocked.
    pub fn new(interior: Rect, cell: f32, radius: f32) -> NavGrid {
        let cols = ((interior.w() / cell).ceil() as usize).max(1);
        let rows = ((interior.d() / cell).ceil() as usize).max(1);
        let inner = interior.inset(radius);
        let mut blocked = vec![0u16; cols * rows];
        for r in 0..rows {
            for c in 0..cols {
                let x = interior.x0 + (c as f32 + 0.5) * cell;
                let z = interior.z0 + (r as f32 + 0.5) * cell;
                if !(x > inner.x0 && x < inner.x1 && z > inner.z0 && z < inner.z1) {
                    blocked[r * cols + c] = 1;
                }
            }
        }
        NavGrid {
            x0: interior.x0,
            z0: interior.z0,
            cell,
            cols,
            rows,
            radius,
            blocked,
            seen: vec![false; cols * rows],
            queue: VecDeque::new(),
        }
    }

    fn cell_of(&self, x: f32, z: f32) -> Option<usize> {
        let c = ((x - self.x0) / self.cell).floor();
        let r = ((z - self.z0) / self.cell).floor();
        if c < 0.0 || r < 0.0 || c as usize >= self.cols || r as usize >= self.rows {
            return None;
        }
        Some(r as usize * self.cols + c as usize)
    }

    /// Add (`add = true`) or remove an obstacle footprint.
    pub fn stamp(&mut self, rect: &Rect, add: bool) {
        let grown = rect.inset(-self.radius);
        let c0 = (((grown.x0 - self.x0) / self.cell).floor().max(0.0)) as usize;
        let r0 = (((grown.z0 - self.z0) / self.cell).floor().max(0.0)) as usize;
        let c1 = (((grown.x1 - self.x0) / self.cell).ceil().max(0.0) as usize).min(self.cols);
        let r1 = (((grown.z1 - self.z0) / self.cell).ceil().max(0.0) as usize).min(self.rows);
        for r in r0..r1 {
            for c in c0..c1 {
                let x = self.x0 + (c as f32 + 0.5) * self.cell;
                let z = self.z0 + (r as f32 + 0.5) * self.cell;
                if rect.distance(x, z) < self.radius {
                    let b = &mut self.blocked[r * self.cols + c];
                    if add {
                        *b += 1;
                    } else {
                        *b -= 1;
                    }
                }
            }
        }
    }

    /// Whether the free cells form one island containing every seed point.
    pub fn connected(&mut self, seeds: &[(f32, f32)]) -> bool {
        let total = self.blocked.iter().filter(|&&b| b == 0).count();
        match self.seed_cells(seeds) {
            Some(cells) if cells.is_empty() => total > 0,
            Some(cells) => self.flood(&cells) == Some(total),
            None => false,
        }
    }

    /// Number of free cells reachable from the first seed point, or 0 when a seed is blocked or
    /// not reachable from the first.
    pub fn reachable(&mut self, seeds: &[(f32, f32)]) -> usize {
        match self.seed_cells(seeds) {
            Some(cells) if !cells.is_empty() => self.flood(&cells).unwrap_or(0),
            _ => 0,
        }
    }

    /// The cells of the seed points, or `None` when one is outside the grid or blocked.
    fn seed_cells(&self, seeds: &[(f32, f32)]) -> Option<Vec<usize>> {
        seeds
            .iter()
            .map(|&(x, z)| self.cell_of(x, z).filter(|&i| self.blocked[i] == 0))
            .collect()
    }

    /// Flood the free cells from `cells[0]`: the number reached, or `None` when another of
    /// `cells` is not among them.
    fn flood(&mut self, cells: &[usize]) -> Option<usize> {
        let first = cells[0];
        self.seen.iter_mut().for_each(|s| *s = false);
        self.queue.clear();
        self.seen[first] = true;
        self.queue.push_back(first);
        let mut reached = 0;
        while let Some(i) = self.queue.pop_front() {
            reached += 1;
            let (r, c) = (i / self.cols, i % self.cols);
            let mut next = [None; 4];
            if c > 0 {
                next[0] = Some(i - 1);
            }
            if c + 1 < self.cols {
                next[1] = Some(i + 1);
            }
            if r > 0 {
                next[2] = Some(i - self.cols);
            }
            if r + 1 < self.rows {
                next[3] = Some(i + self.cols);
            }
            for j in next.into_iter().flatten() {
                if !self.seen[j] && self.blocked[j] == 0 {
                    self.seen[j] = true;
                    self.queue.push_back(j);
                }
            }
        }
        cells.iter().all(|&i| self.seen[i]).then_some(reached)
    }

    /// Number of free cells.
    pub fn free_cells(&self) -> usize {
        self.blocked.iter().filter(|&&b| b == 0).count()
    }
}
