//! Triangulation of object parts, shared by the glTF writer, the renderers, the occupancy
//! rasteriser and the ray-cast backend so that they all see the same surfaces.

use crate::scene::{Part, Pose, Scene, Shape};
use glam::Vec3;

/// Segments around a cylinder.
pub const CYLINDER_SEGMENTS: u32 = 16;
/// Largest side in metres of the grid cells a box face is cut into by [`triangulate_cells`]
/// (walls, floors and ceilings of homes with baked light, see [`crate::light`]).
pub const MAX_CELL: f32 = 0.75;
/// Latitude bands of a sphere (longitude uses twice as many).
pub const SPHERE_BANDS: u32 = 6;
/// Triangles of a bevelled box: 6 faces and the 4 chamfer strips of its top edges, two
/// triangles each.
pub const BEVELLED_BOX_TRIANGLES: usize = 20;
/// Largest bevel as a fraction of the smallest half extent (keeps every face and strip of a
/// thin panel non-degenerate).
pub const MAX_BEVEL_FRACTION: f32 = 0.45;

/// An indexed triangle mesh with per-vertex normals.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Vertex normals (unit length; flat-shaded for boxes).
    pub normals: Vec<[f32; 3]>,
    /// Counter-clockwise triangles (front faces point outwards).
    pub indices: Vec<[u32; 3]>,
}

impl TriMesh {
    /// Append `other`, transformed by `pose`.
    pub fn append_transformed(&mut self, other: &TriMesh, pose: &Pose) {
        let base = self.positions.len() as u32;
        let q = pose.quat();
        self.positions.extend(
            other
                .positions
                .iter()
                .map(|p| pose.transform_point(Vec3::from_array(*p)).to_array()),
        );
        self.normals.extend(
            other
                .normals
                .iter()
                .map(|n| (q * Vec3::from_array(*n)).to_array()),
        );
        self.indices.extend(
            other
                .indices
                .iter()
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }
}

/// Number of triangles [`triangulate`] produces for a shape.
pub fn triangle_count(shape: &Shape) -> usize {
    triangle_count_cells(shape, None)
}

/// Number of triangles [`triangulate_cells`] produces for a shape.
pub fn triangle_count_cells(shape: &Shape, cell: Option<f32>) -> usize {
    match shape {
        Shape::Cuboid {
            half_extents: h,
            bevel,
        } => {
            if cut_bevel(*h, *bevel, cell) > 0.0 {
                return BEVELLED_BOX_TRIANGLES;
            }
            let [x, y, z] = h.map(|h| cells(h, cell));
            (4 * (x * y + y * z + x * z)) as usize
        }
        Shape::Cylinder { .. } => (CYLINDER_SEGMENTS * 4) as usize,
        Shape::Sphere { .. } => (SPHERE_BANDS * SPHERE_BANDS * 2 * 2) as usize,
        Shape::Mesh(m) => m.indices.len(),
    }
}

/// Number of vertices [`triangulate_cells`] produces for a shape (without building them: the
/// light read back from a file is matched part by part on these counts).
pub fn vertex_count_cells(shape: &Shape, cell: Option<f32>) -> usize {
    match shape {
        Shape::Cuboid {
            half_extents: h,
            bevel,
        } => {
            if cut_bevel(*h, *bevel, cell) > 0.0 {
                // Ten quads of their own four corners.
                return 2 * BEVELLED_BOX_TRIANGLES;
            }
            // Each face a grid of (cells + 1) x (cells + 1) corners along its two axes.
            let [x, y, z] = h.map(|h| cells(h, cell) + 1);
            (2 * (z * y + x * z + x * y)) as usize
        }
        Shape::Cylinder { .. } => {
            (2 * (CYLINDER_SEGMENTS + 1) + 2 * (CYLINDER_SEGMENTS + 2)) as usize
        }
        Shape::Sphere { .. } => ((SPHERE_BANDS + 1) * (2 * SPHERE_BANDS + 1)) as usize,
        Shape::Mesh(m) => m.positions.len(),
    }
}

/// Corners of a conservative local bounding box of a shape (8 points).
pub fn shape_corners(shape: &Shape) -> Vec<Vec3> {
    let h = match shape {
        Shape::Cuboid { half_extents, .. } => Vec3::from_array(*half_extents),
        Shape::Cylinder {
            radius,
            half_height,
        } => Vec3::new(*radius, *half_height, *radius),
        Shape::Sphere { radius } => Vec3::splat(*radius),
        Shape::Mesh(m) => {
            return m.positions.iter().map(|p| Vec3::from_array(*p)).collect();
        }
    };
    let mut v = Vec::with_capacity(8);
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                v.push(h * Vec3::new(sx, sy, sz));
            }
        }
    }
    v
}

/// The bevel a box is drawn with: `bevel` clamped to [`MAX_BEVEL_FRACTION`] of the smallest
/// half extent, 0 (sharp) when it is not positive and finite or the box has a side that is
/// not (a flat or broken box has no edges to bevel).
pub fn drawn_bevel(half_extents: [f32; 3], bevel: f32) -> f32 {
    let min = half_extents.into_iter().fold(f32::INFINITY, f32::min);
    if !(bevel > 0.0 && bevel.is_finite() && min > 0.0 && min.is_finite()) {
        return 0.0;
    }
    bevel.min(MAX_BEVEL_FRACTION * min)
}

/// Triangulate a shape in its own frame (two triangles per box face; a bevelled box gets
/// [`BEVELLED_BOX_TRIANGLES`]).
pub fn triangulate(shape: &Shape) -> TriMesh {
    triangulate_cells(shape, None)
}

/// Triangulate a shape in its own frame, box faces cut into a grid of cells of at most `cell`
/// metres (`None`: two triangles per face), so that light baked per vertex has resolution.
///
/// A box with a bevel ([`drawn_bevel`] > 0) and no cells is drawn with its four top edges
/// chamfered: a 45-degree strip along each, mitred at the corners, each face and strip with its
/// own flat normal (the light baked per vertex then differs on the chamfer, which is what shows
/// the edge). Only the top edges: the camera (1.25 m) sees furniture from above, where the top
/// edges are what reads as rounded, and a box stays at [`BEVELLED_BOX_TRIANGLES`] = 20
/// triangles (44 with every edge chamfered; triangle set-up is most of what a bevel costs the
/// rasteriser). A box whose faces `cell` cuts into more than one cell (walls and floors of lit
/// homes) keeps its cells and sharp edges: bevel and cells do not combine (a small box `cell`
/// leaves whole is bevelled as without it).
pub fn triangulate_cells(shape: &Shape, cell: Option<f32>) -> TriMesh {
    match shape {
        Shape::Cuboid {
            half_extents,
            bevel,
        } => {
            let b = cut_bevel(*half_extents, *bevel, cell);
            if b > 0.0 {
                chamfered_box(Vec3::from_array(*half_extents), b)
            } else {
                cuboid(Vec3::from_array(*half_extents), cell)
            }
        }
        Shape::Cylinder {
            radius,
            half_height,
        } => cylinder(*radius, *half_height),
        Shape::Sphere { radius } => sphere(*radius),
        Shape::Mesh(m) => mesh_with_normals(&m.positions, &m.indices),
    }
}

/// Triangulate a part placed by `object_pose` (world space).
pub fn triangulate_part(part: &Part, object_pose: &Pose) -> TriMesh {
    triangulate_part_cells(part, object_pose, None)
}

/// [`triangulate_part`] with box faces cut into cells (see [`triangulate_cells`]).
pub fn triangulate_part_cells(part: &Part, object_pose: &Pose, cell: Option<f32>) -> TriMesh {
    let mut out = TriMesh::default();
    out.append_transformed(
        &triangulate_cells(&part.shape, cell),
        &object_pose.mul(&part.transform),
    );
    out
}

/// One world-space triangle with the id and class of the object it belongs to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldTriangle {
    /// The three corners.
    pub v: [Vec3; 3],
    /// Object id (instance id).
    pub object: u32,
    /// Semantic class id.
    pub class: u16,
    /// Linear RGB colour of the part.
    pub color: [f32; 3],
}

/// Every triangle of a scene in world space, tagged with its object.
pub fn scene_triangles(scene: &Scene) -> Vec<WorldTriangle> {
    let mut out = Vec::with_capacity(scene.triangle_count());
    for o in &scene.objects {
        for part in &o.parts {
            let m = triangulate_part(part, &o.pose);
            for t in &m.indices {
                out.push(WorldTriangle {
                    v: t.map(|i| Vec3::from_array(m.positions[i as usize])),
                    object: o.id,
                    class: o.class.id(),
                    color: part.color,
                });
            }
        }
    }
    out
}

/// The bevel a box is drawn with when its faces are cut by `cell`: [`drawn_bevel`] when every
/// face stays one cell (small boxes of lit classes, such as ceiling fixtures), else 0.
fn cut_bevel(h: [f32; 3], bevel: f32, cell: Option<f32>) -> f32 {
    if h.iter().any(|h| cells(*h, cell) > 1) {
        return 0.0;
    }
    drawn_bevel(h, bevel)
}

/// Segments along one box edge of half length `h`: cells of at most `cell` metres (one segment
/// for `None`).
fn cells(h: f32, cell: Option<f32>) -> u32 {
    match cell {
        Some(c) if c > 0.0 => ((2.0 * h.abs() / c).ceil() as u32).clamp(1, 64),
        _ => 1,
    }
}

/// Coordinate `k` of `n` along an axis of half length `h`, from `-h` (the same arithmetic for
/// every face sharing the edge, so shared edge vertices are bit-identical: no cracks).
fn grid(h: f32, k: u32, n: u32) -> f32 {
    if k == n {
        h
    } else {
        -h + 2.0 * h * (k as f32 / n as f32)
    }
}

fn cuboid(h: Vec3, cell: Option<f32>) -> TriMesh {
    let mut m = TriMesh::default();
    // Each face: normal axis, and two tangent axes chosen so (u x v) = n (CCW from outside).
    let faces: [(Vec3, Vec3, Vec3); 6] = [
        (Vec3::X, Vec3::NEG_Z, Vec3::Y),
        (Vec3::NEG_X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::X, Vec3::NEG_Z),
        (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
    ];
    let axis = |v: Vec3| -> (usize, bool) {
        let i = if v.x != 0.0 {
            0
        } else if v.y != 0.0 {
            1
        } else {
            2
        };
        (i, v[i] > 0.0)
    };
    for (n, u, v) in faces {
        let base = m.positions.len() as u32;
        let ((an, pn), (au, pu), (av, pv)) = (axis(n), axis(u), axis(v));
        let (nu, nv) = (cells(h[au], cell), cells(h[av], cell));
        for j in 0..=nv {
            for i in 0..=nu {
                let mut p = [0.0f32; 3];
                p[an] = if pn { h[an] } else { -h[an] };
                p[au] = grid(h[au], if pu { i } else { nu - i }, nu);
                p[av] = grid(h[av], if pv { j } else { nv - j }, nv);
                m.positions.push(p);
                m.normals.push(n.to_array());
            }
        }
        for j in 0..nv {
            for i in 0..nu {
                let a = base + j * (nu + 1) + i;
                let (b, c, d) = (a + 1, a + nu + 2, a + nu + 1);
                m.indices.push([a, b, c]);
                m.indices.push([a, c, d]);
            }
        }
    }
    m
}

/// A box of half extents `h` whose four top edges are chamfered at 45 degrees by `b`
/// (`0 < b < min h`), the strips meeting in mitres at the corners; the vertical and bottom
/// edges stay sharp. Every vertex coordinate is `+-h` or `+-(h - b)` on its axis, computed
/// once, so the faces and strips that share a corner share it bit for bit (a closed surface,
/// no cracks).
fn chamfered_box(h: Vec3, b: f32) -> TriMesh {
    let i = h - Vec3::splat(b);
    let mut m = TriMesh::default();
    // One flat quad (corners in order around it), wound to face along `n`.
    let mut quad = |c: [Vec3; 4], n: Vec3| {
        let base = m.positions.len() as u32;
        let n = n.normalize();
        for p in c {
            m.positions.push(p.to_array());
            m.normals.push(n.to_array());
        }
        let flip = (c[1] - c[0]).cross(c[2] - c[0]).dot(n) < 0.0;
        for k in 1..3 {
            let (i, j) = (base + k, base + k + 1);
            m.indices
                .push(if flip { [base, j, i] } else { [base, i, j] });
        }
    };
    let v = Vec3::new;
    // Top face inset on both sides, bottom face whole.
    quad(
        [
            v(-i.x, h.y, -i.z),
            v(i.x, h.y, -i.z),
            v(i.x, h.y, i.z),
            v(-i.x, h.y, i.z),
        ],
        Vec3::Y,
    );
    quad(
        [
            v(-h.x, -h.y, -h.z),
            v(h.x, -h.y, -h.z),
            v(h.x, -h.y, h.z),
            v(-h.x, -h.y, h.z),
        ],
        Vec3::NEG_Y,
    );
    let top = h.y - b;
    for s in [1.0f32, -1.0] {
        // Sides facing +-x and +-z, up to where the chamfer starts.
        quad(
            [
                v(s * h.x, -h.y, -h.z),
                v(s * h.x, -h.y, h.z),
                v(s * h.x, top, h.z),
                v(s * h.x, top, -h.z),
            ],
            v(s, 0.0, 0.0),
        );
        quad(
            [
                v(-h.x, -h.y, s * h.z),
                v(h.x, -h.y, s * h.z),
                v(h.x, top, s * h.z),
                v(-h.x, top, s * h.z),
            ],
            v(0.0, 0.0, s),
        );
        // Chamfer strips: trapezoids from the side's top edge to the top face's edge.
        quad(
            [
                v(s * h.x, top, -h.z),
                v(s * h.x, top, h.z),
                v(s * i.x, h.y, i.z),
                v(s * i.x, h.y, -i.z),
            ],
            v(s, 1.0, 0.0),
        );
        quad(
            [
                v(-h.x, top, s * h.z),
                v(h.x, top, s * h.z),
                v(i.x, h.y, s * i.z),
                v(-i.x, h.y, s * i.z),
            ],
            v(0.0, 1.0, s),
        );
    }
    m
}

fn cylinder(r: f32, hh: f32) -> TriMesh {
    let mut m = TriMesh::default();
    let n = CYLINDER_SEGMENTS;
    let ang = |i: u32| std::f32::consts::TAU * i as f32 / n as f32;
    // Side: two vertices per segment boundary.
    for i in 0..=n {
        let (s, c) = ang(i).sin_cos();
        let dir = Vec3::new(c, 0.0, -s);
        m.positions.push((dir * r + Vec3::Y * hh).to_array());
        m.normals.push(dir.to_array());
        m.positions.push((dir * r - Vec3::Y * hh).to_array());
        m.normals.push(dir.to_array());
    }
    for i in 0..n {
        let (t0, b0, t1, b1) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
        m.indices.push([t0, b0, b1]);
        m.indices.push([t0, b1, t1]);
    }
    // Caps as fans.
    for (y, ny) in [(hh, 1.0f32), (-hh, -1.0)] {
        let center = m.positions.len() as u32;
        m.positions.push([0.0, y, 0.0]);
        m.normals.push([0.0, ny, 0.0]);
        for i in 0..=n {
            let (s, c) = ang(i).sin_cos();
            m.positions.push([c * r, y, -s * r]);
            m.normals.push([0.0, ny, 0.0]);
        }
        for i in 0..n {
            let (a, b) = (center + 1 + i, center + 2 + i);
            if ny > 0.0 {
                m.indices.push([center, a, b]);
            } else {
                m.indices.push([center, b, a]);
            }
        }
    }
    m
}

fn sphere(r: f32) -> TriMesh {
    let mut m = TriMesh::default();
    let lat = SPHERE_BANDS;
    let lon = SPHERE_BANDS * 2;
    for i in 0..=lat {
        let theta = std::f32::consts::PI * i as f32 / lat as f32;
        for j in 0..=lon {
            let phi = std::f32::consts::TAU * j as f32 / lon as f32;
            let d = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            );
            m.positions.push((d * r).to_array());
            m.normals.push(d.to_array());
        }
    }
    let row = lon + 1;
    for i in 0..lat {
        for j in 0..lon {
            let a = i * row + j;
            let b = a + row;
            m.indices.push([a, b, b + 1]);
            m.indices.push([a, b + 1, a + 1]);
        }
    }
    m
}

/// Build a mesh with flat-ish normals (area-weighted vertex normals) from raw data.
pub fn mesh_with_normals(positions: &[[f32; 3]], indices: &[[u32; 3]]) -> TriMesh {
    let mut normals = vec![Vec3::ZERO; positions.len()];
    for t in indices {
        let [a, b, c] = t.map(|i| Vec3::from_array(positions[i as usize]));
        let n = (b - a).cross(c - a);
        for &i in t {
            normals[i as usize] += n;
        }
    }
    TriMesh {
        positions: positions.to_vec(),
        normals: normals
            .into_iter()
            .map(|n| n.try_normalize().unwrap_or(Vec3::Y).to_array())
            .collect(),
        indices: indices.to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_closed_outward(m: &TriMesh) {
        // Outward winding: every triangle's geometric normal points away from the origin.
        for t in &m.indices {
            let [a, b, c] = t.map(|i| Vec3::from_array(m.positions[i as usize]));
            let n = (b - a).cross(c - a);
            let centroid = (a + b + c) / 3.0;
            if n.length() < 1e-5 {
                continue; // degenerate pole triangles of a sphere
            }
            assert!(n.dot(centroid) > 0.0, "inward triangle {t:?}");
        }
    }

    #[test]
    fn primitives_wind_outwards_and_counts_match() {
        for s in [
            Shape::Cuboid {
                half_extents: [1.0, 2.0, 0.5],
                bevel: 0.0,
            },
            Shape::Cuboid {
                half_extents: [1.0, 2.0, 0.5],
                bevel: 0.1,
            },
            Shape::Cylinder {
                radius: 0.5,
                half_height: 1.0,
            },
            Shape::Sphere { radius: 1.0 },
        ] {
            let m = triangulate(&s);
            check_closed_outward(&m);
            assert_eq!(m.triangle_count(), triangle_count(&s), "{s:?}");
            let fine = triangulate_cells(&s, Some(0.3));
            check_closed_outward(&fine);
            assert_eq!(
                fine.triangle_count(),
                triangle_count_cells(&s, Some(0.3)),
                "{s:?}"
            );
            for (mesh, cell) in [(&m, None), (&fine, Some(0.3))] {
                assert_eq!(mesh.positions.len(), vertex_count_cells(&s, cell), "{s:?}");
            }
            if let Shape::Cuboid { bevel, .. } = s {
                let want = if bevel > 0.0 {
                    BEVELLED_BOX_TRIANGLES
                } else {
                    12
                };
                assert_eq!(m.triangle_count(), want);
                assert!(fine.triangle_count() > 12);
            }
        }
    }
}
