//! The map history: a top-down grid of what the agent has seen, built from its own depth
//! camera (never from the scene's map), with the walked trajectory and the current heading.
//! Cells no depth ray has crossed stay unknown, so unexplored rooms and the goal never show.

use glam::Vec2;
use image::{Rgb, RgbImage};
use vlnverse_env::Pose;
use vlnverse_sensors::Frame;

const UNKNOWN: u8 = 0;
const FREE: u8 = 1;
const WALL: u8 = 2;

/// Colours of the map picture.
pub const UNKNOWN_RGB: [u8; 3] = [128, 128, 128];
/// Seen floor.
pub const FREE_RGB: [u8; 3] = [250, 250, 250];
/// Seen obstacle.
pub const WALL_RGB: [u8; 3] = [40, 40, 40];
/// The trajectory.
pub const PATH_RGB: [u8; 3] = [30, 90, 230];
/// The agent and its heading.
pub const AGENT_RGB: [u8; 3] = [220, 30, 30];

/// Cells on a side: the grid covers `SIDE * resolution` metres around the start.
const SIDE: usize = 512;

/// Explored space around the episode start.
#[derive(Clone, Debug)]
pub struct ExploredMap {
    res: f32,
    origin: Vec2,
    cells: Vec<u8>,
    /// Bounding box of the known cells: (min col, min row, max col, max row).
    known: Option<(usize, usize, usize, usize)>,
    path: Vec<Vec2>,
    heading: f32,
}

/// Pinhole parameters of the depth camera the map reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthCamera {
    /// Horizontal field of view (degrees).
    pub hfov_deg: f32,
    /// Depth beyond this is "nothing seen up to here" (the far plane).
    pub far: f32,
    /// Depth values are divided by `far` (normalised camera).
    pub normalized: bool,
}

impl ExploredMap {
    /// An empty map around `start`, `res` metres per cell.
    pub fn new(start: &Pose, res: f32) -> Self {
        ExploredMap {
            res,
            origin: Vec2::new(start.position[0], start.position[2]),
            cells: vec![UNKNOWN; SIDE * SIDE],
            known: None,
            path: vec![Vec2::new(start.position[0], start.position[2])],
            heading: start.yaw(),
        }
    }

    fn cell(&self, p: Vec2) -> Option<(usize, usize)> {
        let q = (p - self.origin) / self.res + Vec2::splat(SIDE as f32 / 2.0);
        (q.x >= 0.0 && q.y >= 0.0 && q.x < SIDE as f32 && q.y < SIDE as f32)
            .then_some((q.x as usize, q.y as usize))
    }

    fn mark(&mut self, c: (usize, usize), v: u8) {
        let i = c.1 * SIDE + c.0;
        // A wall seen once stays a wall; free space does not erase it.
        if self.cells[i] == WALL && v == FREE {
            return;
        }
        self.cells[i] = v;
        self.known = Some(match self.known {
            None => (c.0, c.1, c.0, c.1),
            Some((a, b, x, y)) => (a.min(c.0), b.min(c.1), x.max(c.0), y.max(c.1)),
        });
    }

    /// Record the agent at `pose` and what its depth camera sees: each column of the middle
    /// row is a ray, free up to the depth and an obstacle there (nothing beyond the far plane).
    pub fn observe(&mut self, pose: &Pose, depth: Option<(&Frame, DepthCamera)>) {
        let here = Vec2::new(pose.position[0], pose.position[2]);
        if self.path.last() != Some(&here) {
            self.path.push(here);
        }
        self.heading = pose.yaw();
        if let Some(c) = self.cell(here) {
            self.mark(c, FREE);
        }
        let Some((frame, cam)) = depth else {
            return;
        };
        if frame.depth.len() != frame.pixels() || frame.width == 0 {
            return;
        }
        let yaw = pose.yaw();
        let fwd = Vec2::new(-yaw.sin(), -yaw.cos());
        let right = Vec2::new(yaw.cos(), -yaw.sin());
        let fx = frame.width as f32 / 2.0 / (cam.hfov_deg.to_radians() / 2.0).tan();
        let cx = frame.width as f32 / 2.0;
        let row = frame.height / 2;
        let stride = (frame.width / 64).max(1);
        for u in (0..frame.width).step_by(stride as usize) {
            let mut d = frame.depth[frame.index(u, row)];
            if cam.normalized {
                d *= cam.far;
            }
            if !d.is_finite() || d <= 0.0 {
                continue;
            }
            let hit = d < cam.far * 0.98;
            let d = d.min(cam.far);
            let x = (u as f32 + 0.5 - cx) / fx;
            let end = here + fwd * d + right * (x * d);
            let len = end.distance(here);
            let n = (len / (0.5 * self.res)).ceil() as usize;
            for k in 0..n {
                let p = here + (end - here) * (k as f32 / n.max(1) as f32);
                if let Some(c) = self.cell(p) {
                    self.mark(c, FREE);
                }
            }
            if hit {
                if let Some(c) = self.cell(end) {
                    self.mark(c, WALL);
                }
            }
        }
    }

    /// Cells seen so far (free or obstacle).
    pub fn known_cells(&self) -> usize {
        self.cells.iter().filter(|&&c| c != UNKNOWN).count()
    }

    /// Whether the world point `p` has been seen.
    pub fn is_known(&self, p: Vec2) -> bool {
        self.cell(p)
            .is_some_and(|(c, r)| self.cells[r * SIDE + c] != UNKNOWN)
    }

    /// Metres per pixel of the last [`ExploredMap::render`] of side `px` (for the prompt).
    pub fn metres_per_pixel(&self, px: u32) -> f32 {
        let (cols, rows) = self.window();
        (cols.max(rows) as f32 * self.res) / px as f32
    }

    /// The square window drawn: the known box with a margin, at least 8 m across.
    fn window(&self) -> (usize, usize) {
        let (a, b, x, y) = self.box_with_margin();
        (x - a + 1, y - b + 1)
    }

    fn box_with_margin(&self) -> (usize, usize, usize, usize) {
        let mut bx = self
            .known
            .unwrap_or((SIDE / 2, SIDE / 2, SIDE / 2, SIDE / 2));
        for p in &self.path {
            if let Some(c) = self.cell(*p) {
                bx = (bx.0.min(c.0), bx.1.min(c.1), bx.2.max(c.0), bx.3.max(c.1));
            }
        }
        let min_side = (8.0 / self.res) as usize;
        let side = (bx.2 - bx.0).max(bx.3 - bx.1) + 1;
        let side = (side + 2 * (side / 10 + 2)).max(min_side).min(SIDE);
        let cx = (bx.0 + bx.2) / 2;
        let cy = (bx.1 + bx.3) / 2;
        let a = cx.saturating_sub(side / 2).min(SIDE - side);
        let b = cy.saturating_sub(side / 2).min(SIDE - side);
        (a, b, a + side - 1, b + side - 1)
    }

    /// Draw the map `px` pixels square: world -Z up, +X right; seen floor light, obstacles
    /// dark, unknown grey, the trajectory blue, the agent a red dot with a heading line.
    pub fn render(&self, px: u32) -> RgbImage {
        let (a, b, x, _) = self.box_with_margin();
        let side = x - a + 1;
        let scale = px as f32 / side as f32;
        let mut img = RgbImage::from_fn(px, px, |i, j| {
            let c = a + ((i as f32 / scale) as usize).min(side - 1);
            let r = b + ((j as f32 / scale) as usize).min(side - 1);
            Rgb(match self.cells[r * SIDE + c] {
                FREE => FREE_RGB,
                WALL => WALL_RGB,
                _ => UNKNOWN_RGB,
            })
        });
        let to_px = |p: Vec2| {
            let q = (p - self.origin) / self.res + Vec2::splat(SIDE as f32 / 2.0);
            Vec2::new((q.x - a as f32) * scale, (q.y - b as f32) * scale)
        };
        for w in self.path.windows(2) {
            line(&mut img, to_px(w[0]), to_px(w[1]), PATH_RGB, 1.0);
        }
        let here = *self.path.last().unwrap_or(&self.origin);
        let p = to_px(here);
        let fwd = Vec2::new(-self.heading.sin(), -self.heading.cos());
        let r = (px as f32 / 40.0).max(2.0);
        line(&mut img, p, p + fwd * (3.0 * r), AGENT_RGB, 1.0);
        disk(&mut img, p, r, AGENT_RGB);
        img
    }
}

fn put(img: &mut RgbImage, x: i64, y: i64, c: [u8; 3]) {
    if x >= 0 && y >= 0 && (x as u32) < img.width() && (y as u32) < img.height() {
        img.put_pixel(x as u32, y as u32, Rgb(c));
    }
}

fn line(img: &mut RgbImage, a: Vec2, b: Vec2, c: [u8; 3], half_width: f32) {
    let n = (a.distance(b).ceil() as usize).max(1);
    let w = half_width.ceil() as i64;
    for k in 0..=n {
        let p = a + (b - a) * (k as f32 / n as f32);
        for dx in -w..=w {
            for dy in -w..=w {
                put(img, p.x as i64 + dx, p.y as i64 + dy, c);
            }
        }
    }
}

fn disk(img: &mut RgbImage, p: Vec2, r: f32, c: [u8; 3]) {
    let ri = r.ceil() as i64;
    for dx in -ri..=ri {
        for dy in -ri..=ri {
            if ((dx * dx + dy * dy) as f32) <= r * r {
                put(img, p.x as i64 + dx, p.y as i64 + dy, c);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn wall_at(d: f32) -> Frame {
        Frame {
            width: 64,
            height: 48,
            depth: vec![d; 64 * 48],
            ..Default::default()
        }
    }

    const CAM: DepthCamera = DepthCamera {
        hfov_deg: 90.0,
        far: 10.0,
        normalized: false,
    };

    #[test]
    fn only_the_cone_in_view_becomes_known() {
        let start = Pose::from_yaw(Vec3::ZERO, 0.0);
        let mut m = ExploredMap::new(&start, 0.1);
        m.observe(&start, Some((&wall_at(2.0), CAM)));
        // Facing -Z: the floor 1 m ahead is seen, 1 m behind and 3 m ahead (past the wall)
        // are not, nor is a point 1.5 m to the side (outside the 90 degree cone at 1 m).
        assert!(m.is_known(Vec2::new(0.0, -1.0)));
        assert!(!m.is_known(Vec2::new(0.0, 1.0)));
        assert!(!m.is_known(Vec2::new(0.0, -3.0)));
        assert!(!m.is_known(Vec2::new(1.5, -1.0)));
        let before = m.known_cells();
        // Turning around shows what is behind.
        let back = Pose::from_yaw(Vec3::ZERO, std::f32::consts::PI);
        m.observe(&back, Some((&wall_at(2.0), CAM)));
        assert!(m.is_known(Vec2::new(0.0, 1.0)));
        assert!(m.known_cells() > before);
    }

    #[test]
    fn the_picture_shows_unknown_seen_path_and_agent() {
        let start = Pose::from_yaw(Vec3::ZERO, 0.0);
        let mut m = ExploredMap::new(&start, 0.1);
        m.observe(&start, Some((&wall_at(3.0), CAM)));
        m.observe(
            &Pose::from_yaw(Vec3::new(0.0, 0.0, -1.0), 0.0),
            Some((&wall_at(2.0), CAM)),
        );
        let img = m.render(128);
        let has = |c: [u8; 3]| img.pixels().any(|p| p.0 == c);
        for c in [UNKNOWN_RGB, FREE_RGB, WALL_RGB, PATH_RGB, AGENT_RGB] {
            assert!(has(c), "{c:?} missing");
        }
        // The half behind the start (bottom rows) was never seen: no floor is drawn there.
        let bottom_free = (0..128)
            .flat_map(|x| (120..128).map(move |y| (x, y)))
            .filter(|&(x, y)| img.get_pixel(x, y).0 == FREE_RGB)
            .count();
        assert_eq!(bottom_free, 0);
    }
}
