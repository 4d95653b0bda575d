//! Datasets on homes with two floors (issue 30, item 3): every task has episodes across floors,
//! every start and goal is navigable on its own level, reference paths climb the flight tread
//! by tread, the geodesic distance is the one across floors, the scene folders hold the upper
//! floor's maps, grounding is exact on the whole path, and the bytes do not depend on threads.

use std::path::Path;
use std::sync::OnceLock;

use glam::Vec2;
use vlnverse_env::geodesic::{LevelPoint, MultiLevelMap};
use vlnverse_env::io::load_scene;
use vlnverse_env::occupancy::{build_level_maps, OccupancyConfig};
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_generate::{run, GeneratePreset, RunOptions, StageTimes};
use vlnverse_instructions::{check_grounding, PathContext, TemplateGenerator};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_score::dataset::read_split;
use vlnverse_score::{Episode, Split, Task};

const HOMES: usize = 4;

fn generate(out: &Path, threads: usize) {
    let cfg = GeneratePreset::Tiny.config().unwrap().rescaled(HOMES);
    generate_with(out, threads, &cfg, &Task::ALL);
}

fn generate_with(
    out: &Path,
    threads: usize,
    cfg: &vlnverse_generate::GenerateConfig,
    tasks: &[Task],
) {
    let mut pc = Preset::Tiny.config().unwrap();
    pc.scenes.count = HOMES;
    pc.floors.two_storey_share = 1.0;
    let source = HomeGenerator::new(pc).unwrap();
    let opts = RunOptions {
        out: out.to_path_buf(),
        tasks: tasks.to_vec(),
        shard: (0, 1),
        occupancy: OccupancyConfig::default(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        run(
            &source,
            cfg,
            &opts,
            &TemplateGenerator::default(),
            &StageTimes::default(),
            &|_| {},
        )
    })
    .unwrap();
}

fn two_storey() -> &'static Path {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = tempfile::tempdir().unwrap();
        generate(d.path(), 2);
        d
    })
    .path()
}

fn episodes(task: Task) -> Vec<Episode> {
    Split::ALL
        .into_iter()
        .flat_map(|s| read_split(two_storey(), task, s).ok().unwrap_or_default())
        .collect()
}

fn levels_of(ep: &Episode) -> Vec<u32> {
    serde_json::from_value(ep.info.extra["levels"].clone()).unwrap()
}

#[test]
fn every_task_crosses_floors_with_navigable_ends_and_a_climbing_path() {
    let dir = two_storey();
    let occ = OccupancyConfig::default();
    let mut scenes = std::collections::BTreeMap::new();
    for task in Task::ALL {
        let eps = episodes(task);
        assert!(!eps.is_empty(), "{task}");
        let mut crossing = 0;
        for ep in &eps {
            let (scene, maps, multi) = scenes.entry(ep.scene_id.clone()).or_insert_with(|| {
                let sdir = dir.join("scenes").join(&ep.scene_id);
                assert!(sdir.join("navigable_level1.yaml").is_file());
                assert!(sdir.join("occupancy_level1.pgm").is_file());
                let scene = load_scene(&sdir).unwrap();
                assert!(scene.is_multi_level(), "{}", scene.id);
                let maps = build_level_maps(&scene, &occ).unwrap();
                let multi = MultiLevelMap::from_scene(&scene, &occ).unwrap();
                (scene, maps, multi)
            });
            let levels = levels_of(ep);
            let on_level = |p: [f32; 3], what: &str| {
                let l = scene.level_at_height(p[1]);
                assert_eq!(
                    Some(p[1]),
                    scene.level_height(l),
                    "{what} on a floor: {p:?}"
                );
                assert!(
                    maps[l as usize].navigable.is_free_at(Vec2::new(p[0], p[2])),
                    "episode {} {task}: {what} {p:?} not navigable on level {l}",
                    ep.episode_id
                );
                l
            };
            assert_eq!(on_level(ep.start_position, "start"), levels[0]);
            let goals = ep.goal_sequence();
            for (g, &l) in goals.iter().zip(&levels[1..]) {
                assert_eq!(on_level(g.position, "goal"), l);
            }
            let last = *levels.last().unwrap();
            if levels.iter().any(|&l| l != levels[0]) {
                crossing += 1;
                // The path climbs or descends the flight: y changes a riser at a time.
                let ys: Vec<f32> = ep.reference_path.iter().map(|p| p[1]).collect();
                assert!(ys.windows(2).all(|w| (w[1] - w[0]).abs() < 0.2), "{ys:?}");
                assert!(ys.iter().any(|&y| y > 0.1 && y < 2.0), "{ys:?}");
            }
            if task != Task::LongHorizon {
                let d = multi
                    .geodesic_distance(
                        LevelPoint::from_world(scene, ep.start_position),
                        LevelPoint::from_world(scene, goals[0].position),
                    )
                    .unwrap()
                    .meters()
                    .unwrap();
                let g = ep.info.geodesic_distance;
                assert!(
                    (d - g).abs() < 0.5,
                    "episode {} {task}: {g} vs {d}",
                    ep.episode_id
                );
                assert_eq!(last, levels[1]);
            }
        }
        let share = crossing as f64 / eps.len() as f64;
        assert!(
            share > 0.1 && share < 0.6,
            "{task}: {crossing}/{}",
            eps.len()
        );
    }
}

#[test]
fn grounding_is_exact_on_the_whole_path_and_the_stairs_are_named() {
    let dir = two_storey();
    let mut said = 0;
    for task in [Task::Fine, Task::Coarse] {
        for ep in episodes(task) {
            let scene = load_scene(dir.join("scenes").join(&ep.scene_id)).unwrap();
            let graph = SceneGraph::build(&scene);
            let maps = build_level_maps(&scene, &OccupancyConfig::default()).unwrap();
            let ctx = PathContext {
                scene: &scene,
                graph: &graph,
                navigable: &maps[0].navigable,
                path: &ep.reference_path,
                start_yaw: 0.0,
                whole_home: None,
            };
            let problems = check_grounding(&ctx, &ep.instruction, 3.0);
            assert!(
                problems.is_empty(),
                "{task} episode {}: {problems:?} {:?} {:?}",
                ep.episode_id,
                ep.instruction,
                ep.info.extra
            );
            let levels = levels_of(&ep);
            if levels[0] != levels[1] {
                let t = ep.instruction.instruction_text.to_lowercase();
                // "the stairs", "upstairs", "the staircase", "the sixteen steps", "the flight"
                assert!(
                    ["stair", "steps", "flight"].iter().any(|w| t.contains(w)),
                    "{t}"
                );
                said += 1;
            }
        }
    }
    assert!(said > 0);
}

#[test]
fn a_fine_walk_off_the_flight_does_not_name_the_stairs_it_left() {
    let dir = two_storey();
    let mut checked = 0;
    for ep in episodes(Task::Fine) {
        let levels = levels_of(&ep);
        if levels[0] == levels[1] {
            continue;
        }
        let scene = load_scene(dir.join("scenes").join(&ep.scene_id)).unwrap();
        let is_stairs = |id: u32| {
            scene
                .object(id)
                .is_some_and(|o| o.class == vlnverse_env::SemanticClass::Stairs)
        };
        // The first point on the goal's floor: where the flight ends.
        let end_y = ep.reference_path.last().unwrap()[1];
        let off = ep
            .reference_path
            .iter()
            .position(|p| (p[1] - end_y).abs() < 0.01)
            .unwrap();
        for g in &ep.instruction.grounding {
            assert!(
                !(is_stairs(g.object_id) && g.path_index.is_some_and(|i| i as usize >= off)),
                "episode {}: the stairs named at point {:?} after the flight (from {off}): {}",
                ep.episode_id,
                g.path_index,
                ep.instruction.instruction_text
            );
        }
        checked += 1;
    }
    assert!(checked > 5, "only {checked} fine episodes across floors");
}

#[test]
fn two_storey_datasets_are_byte_identical_on_one_thread() {
    let one = tempfile::tempdir().unwrap();
    generate(one.path(), 1);
    for task in Task::ALL {
        for split in Split::ALL {
            let p = vlnverse_score::dataset::split_path(two_storey(), task, split);
            let q = vlnverse_score::dataset::split_path(one.path(), task, split);
            assert_eq!(
                std::fs::read(&p).ok(),
                std::fs::read(&q).ok(),
                "{}",
                p.display()
            );
        }
    }
}

#[test]
fn a_task_may_have_its_own_share_across_floors() {
    let mut cfg = GeneratePreset::Tiny.config().unwrap().rescaled(HOMES);
    cfg.sampling.cross_floor_share = 0.0;
    cfg.tasks.get_mut(Task::Coarse).cross_floor_share = Some(1.0);
    let d = tempfile::tempdir().unwrap();
    generate_with(d.path(), 2, &cfg, &[Task::Fine, Task::Coarse]);
    let share = |task| {
        let eps: Vec<Episode> = Split::ALL
            .into_iter()
            .flat_map(|s| read_split(d.path(), task, s).ok().unwrap_or_default())
            .collect();
        let n = eps
            .iter()
            .filter(|e| levels_of(e).iter().any(|&l| l != levels_of(e)[0]))
            .count();
        n as f64 / eps.len() as f64
    };
    assert_eq!(share(Task::Fine), 0.0);
    assert!(share(Task::Coarse) > 0.7, "{}", share(Task::Coarse));
    cfg.tasks.get_mut(Task::Fine).cross_floor_share = Some(1.5);
    let e = cfg.validate().unwrap_err().to_string();
    assert!(
        e.contains("tasks.fine.cross_floor_share") && e.contains("1.5"),
        "{e}"
    );
}
