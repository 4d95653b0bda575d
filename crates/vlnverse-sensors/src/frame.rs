//! Rendered images as tightly packed arrays.
//!
//! Layout of every image: row-major, top row first, no padding between rows; pixel `(u, v)` is
//! element `v * width + u`.
//! - `rgb`: `u8` x 3 per pixel (sRGB-encoded R, G, B), `3 * width * height` bytes.
//! - `depth`: `f32` metres along the optical axis, clipped at the camera's `far`; a pixel that
//!   sees nothing within `far` holds `far`.
//! - `semantic`: `u16` class id ([`vlnverse_env::SemanticClass::id`]), 0 = nothing.
//! - `instance`: `u32` object id ([`vlnverse_env::SceneObject::id`]), 0 = nothing.

use crate::camera::Camera;

/// Which images a view asks for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Channels {
    /// Lit colour.
    pub rgb: bool,
    /// Linear depth.
    pub depth: bool,
    /// Class id per pixel.
    pub semantic: bool,
    /// Object id per pixel.
    pub instance: bool,
}

impl Channels {
    /// Every channel.
    pub const ALL: Channels = Channels {
        rgb: true,
        depth: true,
        semantic: true,
        instance: true,
    };
    /// Colour only.
    pub const RGB: Channels = Channels {
        rgb: true,
        depth: false,
        semantic: false,
        instance: false,
    };
    /// Depth only.
    pub const DEPTH: Channels = Channels {
        rgb: false,
        depth: true,
        semantic: false,
        instance: false,
    };

    /// Union of two requests.
    pub fn union(self, o: Channels) -> Channels {
        Channels {
            rgb: self.rgb || o.rgb,
            depth: self.depth || o.depth,
            semantic: self.semantic || o.semantic,
            instance: self.instance || o.instance,
        }
    }

    /// Whether per-pixel ids are needed (semantic or instance).
    pub fn ids(&self) -> bool {
        self.semantic || self.instance
    }
}

/// One camera view to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The camera.
    pub camera: Camera,
    /// The images wanted.
    pub channels: Channels,
}

/// The images of one view; a channel that was not asked for is an empty vector.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// sRGB colour, 3 bytes per pixel.
    pub rgb: Vec<u8>,
    /// Depth in metres along the optical axis.
    pub depth: Vec<f32>,
    /// Semantic class id per pixel.
    pub semantic: Vec<u16>,
    /// Object id per pixel.
    pub instance: Vec<u32>,
}

impl Frame {
    /// Number of pixels.
    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Index of pixel `(u, v)` in the per-pixel arrays.
    pub fn index(&self, u: u32, v: u32) -> usize {
        v as usize * self.width as usize + u as usize
    }
}

/// Distance-free pinhole parameters of a camera, as written to `camera.json`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Intrinsics {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Focal length x in pixels.
    pub fx: f32,
    /// Focal length y in pixels.
    pub fy: f32,
    /// Principal point x.
    pub cx: f32,
    /// Principal point y.
    pub cy: f32,
}

impl From<&Camera> for Intrinsics {
    fn from(c: &Camera) -> Self {
        Intrinsics {
            width: c.width,
            height: c.height,
            fx: c.fx(),
            fy: c.fy(),
            cx: c.cx(),
            cy: c.cy(),
        }
    }
}

/// Fixed 256-entry colour palette for id images (0 is black; the rest well spread hues).
pub fn palette_color(id: u32) -> [u8; 3] {
    if id == 0 {
        return [0, 0, 0];
    }
    // Golden-ratio hue steps with alternating value/saturation keep neighbours distinct.
    let h = (id as f32 * 0.618_034).fract();
    let s = if id.is_multiple_of(2) { 0.65 } else { 0.9 };
    let v = if (id / 2).is_multiple_of(2) {
        0.95
    } else {
        0.75
    };
    let i = (h * 6.0).floor();
    let f = h * 6.0 - i;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - f * s), v * (1.0 - (1.0 - f) * s));
    let (r, g, b) = match i as u32 % 6 {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    [(r * 255.0) as u8, (g * 255.0) as u8, (b * 255.0) as u8]
}

/// Colourise an id image with [`palette_color`] (3 bytes per pixel).
pub fn colorize_ids(ids: impl IntoIterator<Item = u32>) -> Vec<u8> {
    ids.into_iter().flat_map(palette_color).collect()
}
