//! Scene-graph costs on a synthetic home of ~300 objects (10 rooms of 5 x 5 m, 18 pieces of
//! furniture and 12 small objects on them per room).
//!
//! `cargo bench -p vlnverse-env --bench scene_graph -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::{
    Aabb, Motion, Physics, Pose, Room, RoomType, Scene, SceneObject, SemanticClass,
    SCENE_FORMAT_VERSION,
};

const FURNITURE: [SemanticClass; 6] = [
    SemanticClass::Sofa,
    SemanticClass::Cabinet,
    SemanticClass::Chair,
    SemanticClass::Desk,
    SemanticClass::Bookshelf,
    SemanticClass::SideTable,
];
const SMALL: [SemanticClass; 4] = [
    SemanticClass::Mug,
    SemanticClass::Book,
    SemanticClass::Vase,
    SemanticClass::Laptop,
];
const COLORS: [&str; 5] = ["red", "blue", "white", "black", "green"];

fn object(
    id: u32,
    class: SemanticClass,
    room: u32,
    lo: Vec3,
    hi: Vec3,
    rng: &mut ChaCha8Rng,
) -> SceneObject {
    SceneObject {
        id,
        name: format!("{}_{id}", class.name()),
        class,
        room: Some(room),
        pose: Pose::from_yaw((lo + hi) * 0.5, 0.0),
        bbox: Aabb::new(lo, hi),
        color: COLORS[rng.random_range(0..COLORS.len())].into(),
        material: "wood".into(),
        shade: None,
        features: Vec::new(),
        physics: Physics {
            mass: 10.0,
            friction: 0.5,
            motion: Motion::Static,
        },
        supported_by: None,
        parts: Vec::new(),
    }
}

fn synthetic_home(seed: u64) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut rooms = Vec::new();
    let mut objects = Vec::new();
    let mut id = 1;
    for r in 0..10u32 {
        let (x0, z0) = ((r % 5) as f32 * 5.0, (r / 5) as f32 * 5.0);
        rooms.push(Room {
            id: r + 1,
            kind: RoomType::ALL[r as usize % RoomType::ALL.len()],
            name: format!("room_{r}"),
            polygon: vec![
                [x0, z0],
                [x0 + 5.0, z0],
                [x0 + 5.0, z0 + 5.0],
                [x0, z0 + 5.0],
            ],
        });
        let mut tops = Vec::new();
        for _ in 0..18 {
            let (w, d) = (rng.random_range(0.4..1.5), rng.random_range(0.4..1.0));
            let x = x0 + rng.random_range(0.1..4.9 - w);
            let z = z0 + rng.random_range(0.1..4.9 - d);
            let h = rng.random_range(0.4..1.2);
            let class = FURNITURE[rng.random_range(0..FURNITURE.len())];
            let lo = Vec3::new(x, 0.0, z);
            let hi = Vec3::new(x + w, h, z + d);
            objects.push(object(id, class, r + 1, lo, hi, &mut rng));
            tops.push((id, lo, hi));
            id += 1;
        }
        for _ in 0..12 {
            let (sid, lo, hi) = tops[rng.random_range(0..tops.len())];
            let x = rng.random_range(lo.x..hi.x - 0.1);
            let z = rng.random_range(lo.z..hi.z - 0.1);
            let class = SMALL[rng.random_range(0..SMALL.len())];
            let mut o = object(
                id,
                class,
                r + 1,
                Vec3::new(x, hi.y, z),
                Vec3::new(x + 0.1, hi.y + 0.15, z + 0.1),
                &mut rng,
            );
            o.supported_by = Some(sid);
            objects.push(o);
            id += 1;
        }
    }
    Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: "bench_home".into(),
        source: "bench".into(),
        seed: Some(seed),
        floor_height: 0.0,
        rooms,
        doors: Vec::new(),
        objects,
        storeys: Default::default(),
    }
}

fn bench(c: &mut Criterion) {
    let scene = synthetic_home(7);
    assert_eq!(scene.objects.len(), 300);
    let graph = SceneGraph::build(&scene);
    c.bench_function("scene_graph/build_300_objects", |b| {
        b.iter(|| SceneGraph::build(black_box(&scene)))
    });
    c.bench_function("scene_graph/to_json_string", |b| {
        b.iter(|| black_box(&graph).to_json_string())
    });
    let text = graph.to_json_string();
    c.bench_function("scene_graph/from_json", |b| {
        b.iter(|| SceneGraph::from_json(black_box(&text)))
    });
    c.bench_function("scene_graph/referring_expression_all_300", |b| {
        b.iter(|| {
            scene
                .objects
                .iter()
                .filter(|o| graph.referring_expression(&scene, o.id).is_some())
                .count()
        })
    });
    let path: Vec<Vec3> = [(0.5, 0.5), (24.5, 0.5), (24.5, 9.5), (0.5, 9.5)]
        .iter()
        .map(|&(x, z)| Vec3::new(x, 0.0, z))
        .collect();
    c.bench_function("scene_graph/landmarks_along_path", |b| {
        b.iter(|| graph.landmarks_along_path(&scene, black_box(&path), |_, _| true, 1.5))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
