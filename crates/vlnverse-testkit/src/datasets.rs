//! A small dataset for the evaluation tests: procgen `tiny` homes, their maps, and fine-grained
//! episodes whose reference path is the geodesic shortest path (until `cargo xtask generate`
//! output is available to tests).

use std::path::Path;

use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::geodesic::shortest_path;
use vlnverse_env::io::{write_scene_bundle, SceneBundle};
use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::Pose;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_score::{dataset, Episode, EpisodeInfo, Goal, Instruction, Split, Task};

/// Home `s` of a dataset made from `seed` (`tiny_<s>`), written under `dir/scenes`, with the
/// centres of its navigable cells.
fn tiny_home(dir: &Path, gen: &HomeGenerator, seed: u64, s: usize) -> (SceneBundle, Vec<Vec2>) {
    let id = format!("tiny_{s:03}");
    let scene = gen.generate(seed.wrapping_add(s as u64), &id).unwrap();
    let (bundle, _) =
        write_scene_bundle(dir.join("scenes"), scene, &OccupancyConfig::default()).unwrap();
    let nav = &bundle.maps.navigable;
    let free = nav
        .free_cells()
        .map(|(c, r)| nav.cell_center(c, r))
        .collect();
    (bundle, free)
}

/// Write `scenes` tiny homes and `per_scene` episodes each (test split of `task`) under `dir`.
pub fn make_dataset(
    dir: &Path,
    task: Task,
    scenes: usize,
    per_scene: usize,
    seed: u64,
) -> Vec<Episode> {
    let gen = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut episodes = Vec::new();
    for s in 0..scenes {
        let (bundle, free) = tiny_home(dir, &gen, seed, s);
        let nav = &bundle.maps.navigable;
        let y = bundle.scene.floor_height;
        let mut made = 0;
        let mut tries = 0;
        while made < per_scene && tries < 10_000 {
            tries += 1;
            let a = free[rng.random_range(0..free.len())];
            let b = free[rng.random_range(0..free.len())];
            let Ok(Some(path)) = shortest_path(nav, a, b) else {
                continue;
            };
            if !(4.0..=14.0).contains(&path.length) {
                continue;
            }
            let id = episodes.len() as u64 + 1;
            let text = "Walk to the goal.".to_string();
            let start = random_start(&mut rng, a, y);
            episodes.push(episode(
                id,
                &bundle.scene.id,
                task,
                start,
                &path,
                None,
                text,
            ));
            made += 1;
        }
    }
    dataset::write_split(dir, task, Split::Test, &episodes).unwrap();
    episodes
}

/// Coarse-style episodes: the goal is the navigable point nearest to a furniture object, the
/// instruction names its class.
pub fn make_object_dataset(dir: &Path, scenes: usize, per_scene: usize, seed: u64) -> Vec<Episode> {
    use vlnverse_env::vocab::ClassKind;
    let gen = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut episodes = Vec::new();
    for s in 0..scenes {
        let (bundle, free) = tiny_home(dir, &gen, seed, s);
        let nav = &bundle.maps.navigable;
        let y = bundle.scene.floor_height;
        let objects: Vec<_> = bundle
            .scene
            .objects
            .iter()
            .filter(|o| {
                o.class.kind() == ClassKind::Furniture
                    && o.class != vlnverse_env::SemanticClass::Rug
            })
            .collect();
        let mut made = 0;
        let mut tries = 0;
        while made < per_scene && tries < 10_000 && !objects.is_empty() {
            tries += 1;
            let o = objects[rng.random_range(0..objects.len())];
            // Only classes that occur once, so the instruction is unambiguous.
            if objects.iter().filter(|x| x.class == o.class).count() != 1 {
                continue;
            }
            let c = Vec2::new(o.pose.position[0], o.pose.position[2]);
            let Some(b) = nav.nearest_free(c, 2.0) else {
                continue;
            };
            let a = free[rng.random_range(0..free.len())];
            let Ok(Some(path)) = shortest_path(nav, a, b) else {
                continue;
            };
            if !(4.0..=14.0).contains(&path.length) {
                continue;
            }
            let id = episodes.len() as u64 + 1;
            let text = format!("Go to the {}.", o.class.words());
            let start = random_start(&mut rng, a, y);
            let e = episode(
                id,
                &bundle.scene.id,
                Task::Coarse,
                start,
                &path,
                Some(o.id),
                text,
            );
            episodes.push(e);
            made += 1;
        }
    }
    dataset::write_split(dir, Task::Coarse, Split::Test, &episodes).unwrap();
    episodes
}

/// A start pose at the floor point `a` with a random heading.
fn random_start(rng: &mut ChaCha8Rng, a: Vec2, y: f32) -> Pose {
    let yaw = rng.random_range(-std::f32::consts::PI..std::f32::consts::PI);
    Pose::from_yaw(Vec3::new(a.x, y, a.y), yaw)
}

/// One episode whose goal is the end of `path` and whose reference path is `path`.
fn episode(
    id: u64,
    scene_id: &str,
    task: Task,
    start: Pose,
    path: &vlnverse_env::geodesic::GeodesicPath,
    object_id: Option<vlnverse_env::ObjectId>,
    text: String,
) -> Episode {
    let y = start.position[1];
    let b = *path.points.last().expect("a path has an end");
    Episode {
        episode_id: id,
        trajectory_id: id,
        scene_id: scene_id.to_string(),
        start_position: start.position,
        start_rotation: start.rotation,
        goals: vec![Goal {
            position: [b.x, y, b.y],
            radius: 3.0,
            object_id,
        }],
        instruction: Instruction {
            instruction_text: text,
            ..Default::default()
        },
        reference_path: path.points.iter().map(|p| [p.x, y, p.y]).collect(),
        info: EpisodeInfo {
            geodesic_distance: path.length,
            ..Default::default()
        },
        task,
        target_object_id: object_id,
        ..Default::default()
    }
}
