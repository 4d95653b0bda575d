//! Axis-aligned rectangles on the floor plane (`x`, `z`).

/// An axis-aligned rectangle on the floor: `x` in `[x0, x1]`, `z` in `[z0, z1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// Smallest x.
    pub x0: f32,
    /// Smallest z.
    pub z0: f32,
    /// Largest x.
    pub x1: f32,
    /// Largest z.
    pub z1: f32,
}

impl Rect {
    /// Rectangle from its centre and full sizes.
    pub fn centered(cx: f32, cz: f32, w: f32, d: f32) -> Rect {
        Rect {
            x0: cx - w * 0.5,
            z0: cz - d * 0.5,
            x1: cx + w * 0.5,
            z1: cz + d * 0.5,
        }
    }

    /// Size along x.
    pub fn w(&self) -> f32 {
        self.x1 - self.x0
    }

    /// Size along z.
    pub fn d(&self) -> f32 {
        self.z1 - self.z0
    }

    /// Area.
    pub fn area(&self) -> f32 {
        self.w() * self.d()
    }

    /// Centre `(x, z)`.
    pub fn center(&self) -> (f32, f32) {
        ((self.x0 + self.x1) * 0.5, (self.z0 + self.z1) * 0.5)
    }

    /// Shrunk by `m` on every side (grown for negative `m`).
    pub fn inset(&self, m: f32) -> Rect {
        Rect {
            x0: self.x0 + m,
            z0: self.z0 + m,
            x1: self.x1 - m,
            z1: self.z1 - m,
        }
    }

    /// Whether the interiors overlap by more than `eps`.
    pub fn overlaps(&self, o: &Rect, eps: f32) -> bool {
        self.x0 + eps < o.x1 && o.x0 + eps < self.x1 && self.z0 + eps < o.z1 && o.z0 + eps < self.z1
    }

    /// Whether `o` lies inside `self` (with tolerance `eps`).
    pub fn contains_rect(&self, o: &Rect, eps: f32) -> bool {
        o.x0 >= self.x0 - eps
            && o.x1 <= self.x1 + eps
            && o.z0 >= self.z0 - eps
            && o.z1 <= self.z1 + eps
    }

    /// Distance from a point to the rectangle (0 inside).
    pub fn distance(&self, x: f32, z: f32) -> f32 {
        let dx = (self.x0 - x).max(x - self.x1).max(0.0);
        let dz = (self.z0 - z).max(z - self.z1).max(0.0);
        (dx * dx + dz * dz).sqrt()
    }

    /// Longest side over shortest side.
    pub fn aspect(&self) -> f32 {
        let (a, b) = (self.w(), self.d());
        a.max(b) / a.min(b).max(1e-6)
    }
}
