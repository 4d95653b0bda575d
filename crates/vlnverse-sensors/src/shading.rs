//! The lighting model shared by both backends (the WGSL shader mirrors these numbers).

use glam::Vec3;

/// Ambient light fraction.
pub const AMBIENT: f32 = 0.35;
/// Directional light fraction.
pub const DIFFUSE: f32 = 0.65;
/// Direction *towards* the light (normalised in [`light_dir`]).
pub const LIGHT: [f32; 3] = [0.35, 1.0, 0.25];

/// Unit direction towards the light.
pub fn light_dir() -> Vec3 {
    Vec3::from_array(LIGHT).normalize()
}

/// Lit linear colour of a surface with normal `n` facing the viewer.
pub fn shade(color: [f32; 3], n: Vec3) -> [f32; 3] {
    let k = AMBIENT + DIFFUSE * n.dot(light_dir()).max(0.0);
    color.map(|c| (c * k).clamp(0.0, 1.0))
}

/// Linear to sRGB-encoded byte (gamma 2.2 approximation, as the shader).
pub fn encode(c: f32) -> u8 {
    (c.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0 + 0.5) as u8
}
