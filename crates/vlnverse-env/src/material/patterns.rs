//! Tileable patterned fabrics (stripes, checks, plaid, flowers, dots) and stone worktops
//! (marble, granite): grey textures of period [`TEX_SIZE`] that repeat every
//! [`Surface::repeat`] metres, tinted by the part colour like every surface.

use super::{fbm, hash01, Surface, TEX_SIZE};
use std::f32::consts::TAU;

/// The grey value (0 black, 1 white) of pattern `s` at texel `(x, y)`; `None` for a surface
/// that is not one of these patterns.
pub(super) fn texel(s: Surface, seed: u32, x: usize, y: usize) -> Option<f32> {
    let (fx, fy) = (x as f32, y as f32);
    // The weave under every fabric.
    let weave = if (x + y).is_multiple_of(2) {
        0.02
    } else {
        -0.02
    };
    Some(match s {
        Surface::Striped => {
            // Four stripes a repeat: wide light, dark edge, wide mid, dark edge.
            let v = match x % 32 {
                0..14 => 0.96,
                14..16 | 30..32 => 0.38,
                _ => 0.6,
            };
            v + weave + 0.03 * fbm(seed, fx, fy, 8.0)
        }
        Surface::Checkered => {
            let light = ((x / 32) + (y / 32)).is_multiple_of(2);
            (if light { 0.95 } else { 0.42 }) + weave + 0.03 * fbm(seed, fx, fy, 8.0)
        }
        Surface::Plaid => {
            // Dark bands both ways, darker where they cross, thin light lines between.
            let band = |v: usize| match v % 64 {
                0..16 => 0.22,
                36..38 => -0.18,
                _ => 0.0,
            };
            let twill = if (x + 2 * y) % 4 < 2 { 0.03 } else { -0.03 };
            0.88 - band(x) - band(y) + twill
        }
        Surface::Floral => {
            // A flower every 32 texels, rows offset by half a cell, leaves below each.
            let row = y / 32;
            let shift = if row.is_multiple_of(2) { 0 } else { 16 };
            let (u, v) = (((x + shift) % 32) as f32 - 16.0, (y % 32) as f32 - 14.0);
            let r = (u * u + v * v).sqrt();
            let edge = 6.5 * (0.55 + 0.45 * (5.0 * v.atan2(u)).cos().abs());
            let leaf = |cx: f32| {
                let (a, b) = ((u - cx) / 5.0, (v - 10.0) / 2.2);
                a * a + b * b <= 1.0
            };
            if r < 2.2 {
                0.3
            } else if r < edge {
                0.97
            } else if leaf(-6.0) || leaf(6.0) {
                0.36
            } else {
                0.62 + weave
            }
        }
        Surface::PolkaDot => {
            let row = y / 32;
            let shift = if row.is_multiple_of(2) { 0 } else { 16 };
            let (u, v) = (((x + shift) % 32) as f32 - 16.0, (y % 32) as f32 - 16.0);
            (if u * u + v * v < 49.0 { 0.97 } else { 0.5 }) + weave
        }
        Surface::Marble => {
            // Pale stone with a few dark veins that wander across the tile.
            let warp = 5.0 * fbm(seed, fx, fy, 64.0);
            let main = (TAU * (fx + fy) / TEX_SIZE as f32 + warp).sin().abs();
            let fine = (TAU * 2.0 * (fx - fy) / TEX_SIZE as f32
                + 6.0 * fbm(seed ^ 9, fx, fy, 16.0))
            .sin()
            .abs();
            let vein = if main < 0.07 {
                -0.42
            } else if fine < 0.03 {
                -0.16
            } else {
                0.0
            };
            0.92 + 0.05 * fbm(seed ^ 3, fx, fy, 16.0) + vein
        }
        Surface::Granite => {
            // Speckles of dark and light grains, two texels across, on a mid grey.
            let h = hash01(seed, x / 2, y / 2);
            if h < 0.2 {
                0.18
            } else if h > 0.86 {
                0.96
            } else {
                0.62 + 0.08 * fbm(seed, fx, fy, 8.0) + 0.06 * hash01(seed ^ 1, x, y)
            }
        }
        _ => return None,
    })
}
