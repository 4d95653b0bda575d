//! The scene prepared for rendering: every triangle in world space, grouped by object, with
//! per-object bounding boxes (for frustum culling) and an id -> class table.

use crate::error::{Result, SensorError};
use glam::Vec3;
use vlnverse_env::geometry::scene_triangles;
use vlnverse_env::{Aabb, Scene};

/// A contiguous run of triangles belonging to one object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectRange {
    /// Object id.
    pub id: u32,
    /// First triangle index.
    pub first: u32,
    /// Number of triangles.
    pub count: u32,
    /// World bounding box of the triangles.
    pub bbox: Aabb,
}

/// Triangles of a scene ready for the backends.
#[derive(Clone, Debug, Default)]
pub struct SceneMesh {
    /// Scene id.
    pub scene_id: String,
    /// Corners of triangle `i` are `positions[3i..3i+3]`.
    pub positions: Vec<Vec3>,
    /// Object id of each triangle.
    pub object: Vec<u32>,
    /// Linear base colour of each triangle.
    pub color: Vec<[f32; 3]>,
    /// Objects in triangle order.
    pub objects: Vec<ObjectRange>,
    /// Semantic class id indexed by object id (0 for unknown ids).
    pub class_of: Vec<u16>,
}

impl SceneMesh {
    /// Triangulate a scene (with the shared [`vlnverse_env::geometry`] code).
    pub fn new(scene: &Scene) -> Result<Self> {
        let tris = scene_triangles(scene);
        if tris.is_empty() {
            return Err(SensorError::Scene {
                scene: scene.id.clone(),
                message: "no triangles to render (every object has no parts)".into(),
            });
        }
        let max_id = scene.objects.iter().map(|o| o.id).max().unwrap_or(0) as usize;
        let mut class_of = vec![0u16; max_id + 1];
        for o in &scene.objects {
            class_of[o.id as usize] = o.class.id();
        }
        let mut m = SceneMesh {
            scene_id: scene.id.clone(),
            positions: Vec::with_capacity(tris.len() * 3),
            object: Vec::with_capacity(tris.len()),
            color: Vec::with_capacity(tris.len()),
            objects: Vec::new(),
            class_of,
        };
        for (i, t) in tris.iter().enumerate() {
            m.positions.extend_from_slice(&t.v);
            m.object.push(t.object);
            m.color.push(t.color);
            match m.objects.last_mut() {
                Some(r) if r.id == t.object => {
                    r.count += 1;
                    t.v.iter().for_each(|p| r.bbox.extend(*p));
                }
                _ => {
                    let mut bbox = Aabb::EMPTY;
                    t.v.iter().for_each(|p| bbox.extend(*p));
                    m.objects.push(ObjectRange {
                        id: t.object,
                        first: i as u32,
                        count: 1,
                        bbox,
                    });
                }
            }
        }
        Ok(m)
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.object.len()
    }

    /// Class id of an object id (0 for 0 or unknown).
    pub fn class(&self, id: u32) -> u16 {
        self.class_of.get(id as usize).copied().unwrap_or(0)
    }

    /// Geometric unit normal of triangle `i`.
    pub fn normal(&self, i: usize) -> Vec3 {
        let [a, b, c] = [0, 1, 2].map(|k| self.positions[3 * i + k]);
        (b - a).cross(c - a).normalize_or(Vec3::Y)
    }
}
