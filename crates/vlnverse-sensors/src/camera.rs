//! Pinhole cameras: intrinsics, placement on the agent, rays and frustum planes.
//!
//! Camera frame: looks along -Z, +Y up, +X right (as glTF and Habitat). Pixel `(u, v)` has its
//! centre at `(u + 0.5, v + 0.5)`, `v = 0` is the top row.

use glam::{Mat4, Quat, Vec3, Vec4};
use serde::{Deserialize, Serialize};
use vlnverse_env::{Aabb, Pose};

/// Where a sensor sits on the agent: an offset in the agent frame (x right, y up, z back; `y` is
/// the height above the agent's base on the floor) and a pitch (positive looks up).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Mount {
    /// Offset from the agent base in the agent frame, metres.
    pub offset: [f32; 3],
    /// Pitch in degrees (positive tilts the sensor up).
    pub pitch_deg: f32,
}

impl Default for Mount {
    /// 1.25 m above the base, level (the VLN-CE camera height).
    fn default() -> Self {
        Mount {
            offset: [0.0, 1.25, 0.0],
            pitch_deg: 0.0,
        }
    }
}

impl Mount {
    /// World pose of the sensor for an agent whose base is at `base` (position on the floor and
    /// yaw; any roll/pitch of `base` is kept).
    pub fn world_pose(&self, base: &Pose) -> Pose {
        base.mul(&Pose {
            position: self.offset,
            rotation: Quat::from_rotation_x(self.pitch_deg.to_radians()).to_array(),
        })
    }
}

/// A pinhole camera placed in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Optical centre in world coordinates.
    pub position: Vec3,
    /// Orientation (camera looks along its local -Z).
    pub rotation: Quat,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Horizontal field of view in radians (the vertical one follows from the aspect ratio).
    pub hfov: f32,
    /// Near clipping distance along the optical axis, metres.
    pub near: f32,
    /// Far clipping distance along the optical axis, metres (depth is clipped here).
    pub far: f32,
}

impl Camera {
    /// Camera at a world pose.
    pub fn new(pose: &Pose, width: u32, height: u32, hfov: f32, near: f32, far: f32) -> Self {
        Camera {
            position: pose.translation(),
            rotation: pose.quat().normalize(),
            width,
            height,
            hfov,
            near,
            far,
        }
    }

    /// The same camera turned by `yaw` radians about world +Y (counter-clockwise from above).
    pub fn yawed(&self, yaw: f32) -> Self {
        Camera {
            rotation: (Quat::from_rotation_y(yaw) * self.rotation).normalize(),
            ..*self
        }
    }

    /// Focal length in pixels along x: `width / 2 / tan(hfov / 2)`.
    pub fn fx(&self) -> f32 {
        self.width as f32 * 0.5 / (self.hfov * 0.5).tan()
    }

    /// Focal length in pixels along y (square pixels: equal to [`Camera::fx`]).
    pub fn fy(&self) -> f32 {
        self.fx()
    }

    /// Principal point x (`width / 2`).
    pub fn cx(&self) -> f32 {
        self.width as f32 * 0.5
    }

    /// Principal point y (`height / 2`).
    pub fn cy(&self) -> f32 {
        self.height as f32 * 0.5
    }

    /// Vertical field of view in radians, from the aspect ratio.
    pub fn vfov(&self) -> f32 {
        2.0 * (self.height as f32 * 0.5 / self.fy()).atan()
    }

    /// Viewing direction (world).
    pub fn forward(&self) -> Vec3 {
        self.rotation * Vec3::NEG_Z
    }

    /// The camera's world pose.
    pub fn pose(&self) -> Pose {
        Pose {
            position: self.position.to_array(),
            rotation: self.rotation.to_array(),
        }
    }

    /// Direction (camera frame, z = -1) through the image point `(x, y)` in pixels.
    pub fn local_dir(&self, x: f32, y: f32) -> Vec3 {
        Vec3::new(
            (x - self.cx()) / self.fx(),
            -(y - self.cy()) / self.fy(),
            -1.0,
        )
    }

    /// Unit world direction through the centre of pixel `(u, v)`.
    pub fn pixel_ray(&self, u: u32, v: u32) -> Vec3 {
        (self.rotation * self.local_dir(u as f32 + 0.5, v as f32 + 0.5)).normalize()
    }

    /// World-to-camera matrix.
    pub fn view_matrix(&self) -> Mat4 {
        Mat4::from_rotation_translation(self.rotation, self.position).inverse()
    }

    /// Perspective projection (clip depth 0..1, as wgpu).
    pub fn projection(&self) -> Mat4 {
        glam::camera::rh::proj::directx::perspective(
            self.vfov(),
            self.width as f32 / self.height as f32,
            self.near,
            self.far,
        )
    }

    /// `projection * view`.
    pub fn view_projection(&self) -> Mat4 {
        self.projection() * self.view_matrix()
    }

    /// The frustum of this camera.
    pub fn frustum(&self) -> Frustum {
        Frustum::from_view_projection(&self.view_projection())
    }
}

/// Six inward-facing planes `(n, d)` with `n . p + d >= 0` inside.
#[derive(Clone, Copy, Debug)]
pub struct Frustum {
    planes: [Vec4; 6],
}

impl Frustum {
    /// Planes of a `projection * view` matrix with clip depth 0..1.
    pub fn from_view_projection(m: &Mat4) -> Self {
        let r = |i: usize| m.row(i);
        let planes = [
            r(3) + r(0),
            r(3) - r(0),
            r(3) + r(1),
            r(3) - r(1),
            r(2),
            r(3) - r(2),
        ];
        Frustum { planes }
    }

    /// Whether a box may be visible (conservative: false only when surely outside).
    /// (Always inlined, with a plain loop: the rasteriser's AVX2 copy calls it per object.)
    #[inline(always)]
    pub fn intersects_aabb(&self, b: &Aabb) -> bool {
        let (lo, hi) = (b.min_v(), b.max_v());
        for p in &self.planes {
            let n = p.truncate();
            let v = Vec3::select(n.cmpge(Vec3::ZERO), hi, lo);
            // Written as `!(a >= b)` would be: a NaN box is outside.
            let inside = n.dot(v) + p.w >= -1e-4 * n.length();
            if !inside {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intrinsics_follow_resolution_and_fov() {
        let c = Camera::new(&Pose::IDENTITY, 224, 224, 90f32.to_radians(), 0.05, 10.0);
        assert!((c.fx() - 112.0).abs() < 1e-3);
        let c = Camera::new(&Pose::IDENTITY, 320, 240, 60f32.to_radians(), 0.05, 10.0);
        assert!((c.fx() - 160.0 / 30f32.to_radians().tan()).abs() < 1e-3);
        assert!((c.vfov() - 2.0 * (120.0 / c.fx()).atan()).abs() < 1e-6);
        // Pixel rays at the left edge make hfov/2 with the axis.
        let d = c.rotation * c.local_dir(0.0, 120.0);
        assert!((d.angle_between(Vec3::NEG_Z) - 30f32.to_radians()).abs() < 1e-5);
    }

    #[test]
    fn mount_height_and_pitch() {
        let m = Mount {
            offset: [0.0, 1.5, 0.0],
            pitch_deg: 30.0,
        };
        let base = Pose::from_yaw(Vec3::new(1.0, 0.0, 2.0), std::f32::consts::FRAC_PI_2);
        let p = m.world_pose(&base);
        assert!((p.translation() - Vec3::new(1.0, 1.5, 2.0)).length() < 1e-5);
        let fwd = p.quat() * Vec3::NEG_Z;
        // Yaw 90 deg looks along -X; pitched 30 deg up.
        assert!((fwd - Vec3::new(-30f32.to_radians().cos(), 0.5, 0.0)).length() < 1e-5);
    }

    #[test]
    fn frustum_culls_boxes_behind() {
        let c = Camera::new(&Pose::IDENTITY, 64, 64, 90f32.to_radians(), 0.05, 10.0);
        let f = c.frustum();
        let front = Aabb::new(Vec3::new(-0.5, -0.5, -3.0), Vec3::new(0.5, 0.5, -2.0));
        let behind = Aabb::new(Vec3::new(-0.5, -0.5, 2.0), Vec3::new(0.5, 0.5, 3.0));
        let far = Aabb::new(Vec3::new(-0.5, -0.5, -13.0), Vec3::new(0.5, 0.5, -12.0));
        assert!(f.intersects_aabb(&front));
        assert!(!f.intersects_aabb(&behind));
        assert!(!f.intersects_aabb(&far));
        let nan = Aabb {
            min: [f32::NAN; 3],
            max: [f32::NAN; 3],
        };
        assert!(!f.intersects_aabb(&nan), "a NaN box is outside");
    }
}
