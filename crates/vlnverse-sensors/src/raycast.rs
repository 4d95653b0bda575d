//! The CPU ray-cast backend: one ray per pixel centre against the scene's triangles (the same
//! triangulation the rasteriser draws), rows in parallel with rayon. Single queries and LiDAR go
//! through parry's BVH ([`SceneRaycaster::cast`]); images through a flat [`TriBvh`].

use crate::bvh::TriBvh;
use crate::camera::Camera;
use crate::error::{Result, SensorError};
use crate::frame::{Frame, View};
use crate::renderer::Renderer;
use crate::scene_mesh::SceneMesh;
use glam::Vec3;
use parry3d::query::Ray;
use parry3d::shape::{CompositeShapeRef, TriMesh};
use rayon::prelude::*;
use std::sync::Arc;

/// A ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance from the ray origin along the (unit) direction, metres.
    pub distance: f32,
    /// Index of the triangle in the [`SceneMesh`].
    pub triangle: u32,
    /// Object id of the triangle.
    pub object: u32,
}

/// Ray queries against a scene's triangles.
pub struct SceneRaycaster {
    mesh: Arc<SceneMesh>,
    bvh: TriMesh,
    fast: TriBvh,
}

impl SceneRaycaster {
    /// Build the BVH.
    pub fn new(mesh: Arc<SceneMesh>) -> Result<Self> {
        let vertices = mesh.positions.clone();
        let indices = (0..mesh.triangle_count() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        let bvh = TriMesh::new(vertices, indices).map_err(|e| SensorError::Scene {
            scene: mesh.scene_id.clone(),
            message: format!("cannot build the ray-cast BVH: {e:?}"),
        })?;
        let fast = TriBvh::new(&mesh.positions);
        Ok(SceneRaycaster { mesh, bvh, fast })
    }

    /// The triangles cast against.
    pub fn mesh(&self) -> &Arc<SceneMesh> {
        &self.mesh
    }

    /// First hit of the ray `origin + t * dir` (`dir` unit length) with `t < max_distance`.
    /// Triangles are two-sided.
    pub fn cast(&self, origin: Vec3, dir: Vec3, max_distance: f32) -> Option<Hit> {
        let ray = Ray::new(origin, dir);
        CompositeShapeRef(&self.bvh)
            .cast_local_ray(&ray, max_distance, true)
            .map(|(tri, t)| Hit {
                distance: t,
                triangle: tri,
                object: self.mesh.object[tri as usize],
            })
    }

    /// [`SceneRaycaster::cast`] on the image BVH ([`TriBvh`]): same triangles, faster.
    pub fn cast_fast(&self, origin: Vec3, dir: Vec3, max_distance: f32) -> Option<Hit> {
        self.fast
            .cast(origin, dir, max_distance)
            .map(|(t, tri)| Hit {
                distance: t,
                triangle: tri,
                object: self.mesh.object[tri as usize],
            })
    }

    /// Render one view (rows in parallel).
    pub fn render_view(&self, view: &View) -> Frame {
        let c = &view.camera;
        let (w, h) = (c.width as usize, c.height as usize);
        let ch = view.channels;
        let mut f = Frame {
            width: c.width,
            height: c.height,
            rgb: if ch.rgb { vec![0; 3 * w * h] } else { vec![] },
            depth: if ch.depth { vec![0.0; w * h] } else { vec![] },
            semantic: if ch.semantic { vec![0; w * h] } else { vec![] },
            instance: if ch.instance { vec![0; w * h] } else { vec![] },
        };
        // Split every requested image into rows and walk them together.
        let mut rows: Vec<Row<'_>> = Vec::with_capacity(h);
        {
            let mut rgb = f.rgb.chunks_mut(3 * w);
            let mut depth = f.depth.chunks_mut(w);
            let mut sem = f.semantic.chunks_mut(w);
            let mut inst = f.instance.chunks_mut(w);
            for v in 0..h {
                rows.push(Row {
                    v: v as u32,
                    rgb: rgb.next(),
                    depth: depth.next(),
                    semantic: sem.next(),
                    instance: inst.next(),
                });
            }
        }
        rows.into_par_iter().for_each(|row| self.render_row(c, row));
        f
    }

    fn render_row(&self, c: &Camera, mut row: Row<'_>) {
        let fwd = c.forward();
        let (fx, cx, cy) = (c.fx(), c.cx(), c.cy());
        let y = -(row.v as f32 + 0.5 - cy) / fx;
        for u in 0..c.width {
            // Same as `c.pixel_ray(u, v)` with the intrinsics hoisted out of the loop.
            let dir = (c.rotation * Vec3::new((u as f32 + 0.5 - cx) / fx, y, -1.0)).normalize();
            let cos = dir.dot(fwd);
            // Start at the near plane and stop at the far plane, as the rasteriser clips.
            let t0 = c.near / cos;
            let hit = self.cast_fast(c.position + dir * t0, dir, (c.far - c.near) / cos);
            let i = u as usize;
            let (depth, id) = match hit {
                Some(h) => ((t0 + h.distance) * cos, h.object),
                None => (c.far, 0),
            };
            if let Some(d) = row.depth.as_deref_mut() {
                d[i] = depth.min(c.far);
            }
            if let Some(s) = row.instance.as_deref_mut() {
                s[i] = id;
            }
            if let Some(s) = row.semantic.as_deref_mut() {
                s[i] = self.mesh.class(id);
            }
            if let Some(rgb) = row.rgb.as_deref_mut() {
                let px = match hit {
                    Some(h) => self
                        .mesh
                        .shade(h.triangle as usize, c.position + dir * (t0 + h.distance)),
                    None => [0, 0, 0],
                };
                rgb[3 * i..3 * i + 3].copy_from_slice(&px);
            }
        }
    }
}

struct Row<'a> {
    v: u32,
    rgb: Option<&'a mut [u8]>,
    depth: Option<&'a mut [f32]>,
    semantic: Option<&'a mut [u16]>,
    instance: Option<&'a mut [u32]>,
}

/// The CPU ray-cast backend of [`Renderer`]; needs no GPU, Vulkan or GL.
#[derive(Default)]
pub struct RaycastRenderer {
    raycaster: Option<Arc<SceneRaycaster>>,
}

impl RaycastRenderer {
    /// A renderer with no scene yet.
    pub fn new() -> Self {
        RaycastRenderer::default()
    }

    /// The ray caster of the current scene.
    pub fn raycaster(&self) -> Option<&Arc<SceneRaycaster>> {
        self.raycaster.as_ref()
    }
}

impl Renderer for RaycastRenderer {
    fn name(&self) -> String {
        "raycast".into()
    }

    fn set_scene(&mut self, mesh: Arc<SceneMesh>) -> Result<()> {
        self.raycaster = Some(Arc::new(SceneRaycaster::new(mesh)?));
        Ok(())
    }

    fn render(&mut self, views: &[View]) -> Result<Vec<Frame>> {
        let rc = self.raycaster.as_ref().ok_or(SensorError::NoScene)?;
        Ok(views.iter().map(|v| rc.render_view(v)).collect())
    }
}
