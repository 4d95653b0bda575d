//! Occupancy-map build times: a 20 x 20 m synthetic home (primitive fast path) and the
//! 148k-triangle AWS small house (mesh path), both at 5 cm.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::{Mat4, Vec3};
use std::hint::black_box;
use std::path::Path;
use vlnverse_env::occupancy::{
    build_maps, dilate, keep_largest_island, synthetic::grid_home, OccupancyConfig,
};
use vlnverse_env::{
    Aabb, MeshData, Motion, Part, Physics, Pose, Scene, SceneObject, SemanticClass, Shape,
    SCENE_FORMAT_VERSION,
};

/// Every mesh primitive of a glTF file as one world-space mesh object (transforms baked in).
fn load_glb_as_meshes(path: &Path) -> Option<Scene> {
    let (doc, buffers, _) = gltf::import(path).ok()?;
    let mut objects = Vec::new();
    let mut stack: Vec<(gltf::Node, Mat4)> = doc
        .default_scene()
        .or_else(|| doc.scenes().next())?
        .nodes()
        .map(|n| (n, Mat4::IDENTITY))
        .collect();
    while let Some((node, parent)) = stack.pop() {
        let m = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            for prim in mesh.primitives() {
                let reader = prim.reader(|b| Some(&buffers[b.index()]));
                let Some(pos) = reader.read_positions() else {
                    continue;
                };
                let positions: Vec<[f32; 3]> = pos
                    .map(|p| m.transform_point3(Vec3::from_array(p)).to_array())
                    .collect();
                let flat: Vec<u32> = match reader.read_indices() {
                    Some(ix) => ix.into_u32().collect(),
                    None => (0..positions.len() as u32).collect(),
                };
                let indices = flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
                let id = objects.len() as u32 + 1;
                objects.push(SceneObject {
                    id,
                    name: format!("mesh_{id}"),
                    class: SemanticClass::Unknown,
                    room: None,
                    pose: Pose::IDENTITY,
                    bbox: Aabb::EMPTY,
                    color: String::new(),
                    material: String::new(),
                    shade: None,
                    features: Vec::new(),
                    physics: Physics {
                        mass: 1.0,
                        friction: 0.5,
                        motion: Motion::Static,
                    },
                    supported_by: None,
                    parts: vec![Part {
                        shape: Shape::Mesh(MeshData {
                            positions,
                            indices,
                            glb_mesh: None,
                            ..Default::default()
                        }),
                        transform: Pose::IDENTITY,
                        color: [0.5; 3],
                    }],
                });
            }
        }
        stack.extend(node.children().map(|c| (c, m)));
    }
    Some(Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: "aws_small_house".into(),
        source: "bench".into(),
        seed: None,
        floor_height: 0.0,
        rooms: Vec::new(),
        doors: Vec::new(),
        objects,
        storeys: Default::default(),
    })
}

fn bench(c: &mut Criterion) {
    let cfg = OccupancyConfig::default();
    let home = grid_home(4, 4, 5.0, 7);
    c.bench_function("build_maps/grid_home_20x20m_5cm", |b| {
        b.iter(|| black_box(build_maps(black_box(&home), &cfg).expect("maps")))
    });
    // Stages, to see where the time goes.
    let maps = build_maps(&home, &cfg).expect("maps");
    c.bench_function("stage/dilate_grid_home", |b| {
        b.iter(|| black_box(dilate(black_box(&maps.occupancy), cfg.agent_radius)))
    });
    let dilated = dilate(&maps.occupancy, cfg.agent_radius);
    c.bench_function("stage/largest_island_grid_home", |b| {
        b.iter(|| {
            let mut m = dilated.clone();
            black_box(keep_largest_island(&mut m))
        })
    });
    let aws = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/scenes/aws_small_house/aws_small_house_yup.glb");
    if let Some(scene) = load_glb_as_meshes(&aws) {
        eprintln!(
            "aws_small_house: {} triangles in {} mesh objects",
            scene.triangle_count(),
            scene.objects.len()
        );
        c.bench_function("build_maps/aws_small_house_148k_tris_5cm", |b| {
            b.iter(|| black_box(build_maps(black_box(&scene), &cfg).expect("maps")))
        });
    } else {
        eprintln!("skipping the AWS house: {} not readable", aws.display());
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
