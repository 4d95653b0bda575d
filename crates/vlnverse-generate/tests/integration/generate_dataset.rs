//! End-to-end checks of the tiny preset: every episode is valid against an independent
//! recomputation (maps rebuilt from the written scene, A* instead of distance fields), and the
//! output is byte-identical on 1 and 2 threads, when sharded and merged, and when resumed.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use glam::Vec2;
use vlnverse_env::geodesic::{shortest_path, DistanceField};
use vlnverse_env::io::load_scene;
use vlnverse_env::occupancy::{build_maps, OccupancyConfig, OccupancyMaps};
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::Scene;
use vlnverse_generate::{merge, part_path, run, RunOptions};
use vlnverse_generate::{GeneratePreset, StageTimes};
use vlnverse_instructions::{check_grounding, PathContext, TemplateGenerator};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_score::dataset::read_split;
use vlnverse_score::{Episode, Role, Split, Task};

fn generate(out: &Path, threads: usize, shard: (usize, usize), tasks: &[Task]) {
    let cfg = GeneratePreset::Tiny.config().unwrap();
    let source = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let opts = RunOptions {
        out: out.to_path_buf(),
        tasks: tasks.to_vec(),
        shard,
        occupancy: OccupancyConfig::default(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        run(
            &source,
            &cfg,
            &opts,
            &TemplateGenerator::default(),
            &StageTimes::default(),
            &|_| {},
        )
    })
    .unwrap();
}

/// The tiny dataset, generated once per test binary on 2 threads.
fn tiny() -> &'static Path {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = tempfile::tempdir().unwrap();
        generate(d.path(), 2, (0, 1), &Task::ALL);
        d
    })
    .path()
}

struct SceneCheck {
    scene: Scene,
    maps: OccupancyMaps,
    graph: SceneGraph,
}

/// Scenes reloaded from the written folders, maps and graphs rebuilt independently.
fn scenes() -> &'static BTreeMap<String, SceneCheck> {
    static S: OnceLock<BTreeMap<String, SceneCheck>> = OnceLock::new();
    S.get_or_init(|| {
        let mut out = BTreeMap::new();
        for e in std::fs::read_dir(tiny().join("scenes")).unwrap() {
            let scene = load_scene(e.unwrap().path()).unwrap();
            let maps = build_maps(&scene, &OccupancyConfig::default()).unwrap();
            let graph = SceneGraph::build(&scene);
            out.insert(scene.id.clone(), SceneCheck { scene, maps, graph });
        }
        out
    })
}

fn all_episodes(task: Task) -> Vec<(Split, Episode)> {
    Split::ALL
        .into_iter()
        .flat_map(|s| {
            read_split(tiny(), task, s)
                .unwrap()
                .into_iter()
                .map(move |e| (s, e))
        })
        .collect()
}

fn start_yaw(q: [f32; 4]) -> f32 {
    let (axis, angle) = glam::Quat::from_array(q).to_axis_angle();
    angle * axis.y.signum()
}

fn xz(p: [f32; 3]) -> Vec2 {
    Vec2::new(p[0], p[2])
}

#[test]
fn counts_match_the_tiny_config() {
    let cfg = GeneratePreset::Tiny.config().unwrap();
    for task in Task::ALL {
        for split in Split::ALL {
            let eps = read_split(tiny(), task, split).unwrap();
            assert_eq!(
                eps.len(),
                cfg.tasks.get(task).episodes.get(split),
                "{task} {split}"
            );
            let ids: Vec<u64> = eps.iter().map(|e| e.episode_id).collect();
            assert_eq!(ids, (1..=eps.len() as u64).collect::<Vec<_>>());
            assert!(eps.iter().all(|e| e.task == task));
        }
    }
}

#[test]
fn starts_and_goals_are_navigable_and_connected() {
    for task in Task::ALL {
        for (_, ep) in all_episodes(task) {
            let sc = &scenes()[&ep.scene_id];
            let nav = &sc.maps.navigable;
            let start = xz(ep.start_position);
            assert!(nav.is_free_at(start), "{task} {}: start", ep.episode_id);
            for g in ep.goal_sequence() {
                let goal = xz(g.position);
                assert!(nav.is_free_at(goal), "{task} {}: goal", ep.episode_id);
                let field = DistanceField::new(nav, goal).unwrap();
                assert!(
                    field.distance(start).is_reachable(),
                    "{task} {}",
                    ep.episode_id
                );
            }
        }
    }
}

#[test]
fn reference_paths_are_free_for_the_agent_and_end_at_the_goal() {
    for task in Task::ALL {
        for (_, ep) in all_episodes(task) {
            let nav = &scenes()[&ep.scene_id].maps.navigable;
            let path = &ep.reference_path;
            assert!(path.len() >= 2);
            assert_eq!(path[0], ep.start_position);
            assert_eq!(*path.last().unwrap(), ep.goals[0].position);
            for w in path.windows(2) {
                assert!(
                    nav.line_of_sight(xz(w[0]), xz(w[1])),
                    "{task} {}: segment {:?} -> {:?} blocked",
                    ep.episode_id,
                    w[0],
                    w[1]
                );
            }
            let len: f32 = path.windows(2).map(|w| xz(w[0]).distance(xz(w[1]))).sum();
            assert!(
                (len - ep.info.geodesic_distance).abs() < 1e-3,
                "{task} {}",
                ep.episode_id
            );
        }
    }
}

#[test]
fn geodesic_distances_match_an_independent_astar() {
    let cfg = GeneratePreset::Tiny.config().unwrap();
    for task in Task::ALL {
        let limits = cfg.tasks.get(task);
        for (_, ep) in all_episodes(task) {
            let nav = &scenes()[&ep.scene_id].maps.navigable;
            let mut at = xz(ep.start_position);
            let mut total = 0.0;
            for g in ep.goal_sequence() {
                let leg = shortest_path(nav, at, xz(g.position)).unwrap().unwrap();
                assert!(
                    leg.length >= limits.min_length * 0.97
                        && leg.length <= limits.max_length * 1.03
                );
                total += leg.length;
                at = xz(g.position);
            }
            let d = ep.info.geodesic_distance;
            assert!(
                (d - total).abs() <= 0.03 * total + 0.1,
                "{task} {}: stored {d}, A* {total}",
                ep.episode_id
            );
        }
    }
}

#[test]
fn grounded_objects_exist_with_their_class() {
    for task in Task::ALL {
        for (_, ep) in all_episodes(task) {
            let scene = &scenes()[&ep.scene_id].scene;
            for g in &ep.instruction.grounding {
                let o = scene.object(g.object_id).unwrap_or_else(|| {
                    panic!("{task} {}: object {} missing", ep.episode_id, g.object_id)
                });
                assert_eq!(o.class.name(), g.class);
                if let Some(i) = g.path_index {
                    assert!((i as usize) < ep.reference_path.len());
                }
            }
            // Near the path and on the stated side (the instruction layer's mechanical check).
            let sc = &scenes()[&ep.scene_id];
            let ctx = PathContext {
                scene: &sc.scene,
                graph: &sc.graph,
                navigable: &sc.maps.navigable,
                path: &ep.reference_path,
                start_yaw: start_yaw(ep.start_rotation),
                whole_home: None,
            };
            if task != Task::LongHorizon {
                let problems = check_grounding(&ctx, &ep.instruction, 2.5);
                assert!(
                    problems.is_empty(),
                    "{task} {}: {problems:?}",
                    ep.episode_id
                );
                continue;
            }
            // Long-horizon: each mention is checked on its own leg, which ends at a sub-goal.
            let ends: Vec<usize> = ep
                .sub_goals
                .iter()
                .map(|g| {
                    ep.reference_path
                        .iter()
                        .position(|p| *p == g.position)
                        .unwrap()
                })
                .collect();
            for g in &ep.instruction.grounding {
                let i = g.path_index.unwrap_or(0) as usize;
                let end = *ends.iter().find(|&&e| e >= i).unwrap();
                let leg = PathContext {
                    path: &ep.reference_path[..=end],
                    ..ctx
                };
                let one = vlnverse_score::Instruction {
                    grounding: vec![g.clone()],
                    ..Default::default()
                };
                let problems = check_grounding(&leg, &one, 2.5);
                assert!(
                    problems.is_empty(),
                    "{task} {}: {problems:?}",
                    ep.episode_id
                );
            }
        }
    }
}

#[test]
fn coarse_targets_are_described_uniquely() {
    for task in [
        Task::Coarse,
        Task::VisualReference,
        Task::Dialogue,
        Task::LongHorizon,
    ] {
        for (_, ep) in all_episodes(task) {
            let sc = &scenes()[&ep.scene_id];
            for goal in ep.goal_sequence() {
                let target = goal.object_id.expect("object goal");
                let expr = sc.graph.referring_expression(&sc.scene, target).unwrap();
                assert_eq!(expr.matches(&sc.scene, &sc.graph), vec![target]);
                assert!(
                    ep.instruction
                        .grounding
                        .iter()
                        .any(|g| g.object_id == target && g.role == Role::Target),
                    "{task} {}: target {target} not grounded",
                    ep.episode_id
                );
                // The goal point is near the target.
                let o = sc.scene.object(target).unwrap();
                let p = xz(goal.position);
                let lo = Vec2::new(o.bbox.min[0], o.bbox.min[2]);
                let hi = Vec2::new(o.bbox.max[0], o.bbox.max[2]);
                assert!(p.distance(p.clamp(lo, hi)) <= 1.0 + 1e-4);
            }
            assert_eq!(ep.target_object_id, ep.goals[0].object_id);
        }
    }
}

#[test]
fn coarse_trajectories_have_three_styles() {
    for task in [Task::Coarse, Task::VisualReference, Task::Dialogue] {
        let mut by_traj: BTreeMap<(Split, u64), Vec<Episode>> = BTreeMap::new();
        for (s, ep) in all_episodes(task) {
            by_traj.entry((s, ep.trajectory_id)).or_default().push(ep);
        }
        for eps in by_traj.values() {
            assert_eq!(eps.len(), 3);
            let styles: Vec<_> = eps.iter().map(|e| e.style().unwrap()).collect();
            assert_eq!(styles, vlnverse_score::Style::ALL.to_vec());
            assert!(eps
                .iter()
                .all(|e| e.reference_path == eps[0].reference_path));
        }
    }
}

#[test]
fn long_horizon_goals_are_distinct_and_chained() {
    for (_, ep) in all_episodes(Task::LongHorizon) {
        let n = ep.sub_goals.len();
        assert!((2..=3).contains(&n), "{n}");
        assert_eq!(ep.sub_goals[n - 1], ep.goals[0]);
        assert_eq!(ep.instruction.sub_instructions.len(), n);
        for i in 0..n {
            for j in 0..i {
                assert_ne!(ep.sub_goals[i].object_id, ep.sub_goals[j].object_id);
                assert_ne!(ep.sub_goals[i].position, ep.sub_goals[j].position);
            }
        }
        // The reference path passes through every sub-goal.
        for g in &ep.sub_goals {
            assert!(ep.reference_path.contains(&g.position));
        }
    }
}

#[test]
fn visual_reference_images_and_dialogue_budgets_exist() {
    for (split, ep) in all_episodes(Task::VisualReference) {
        let rel = ep.reference_image.as_ref().unwrap();
        assert_eq!(rel, &format!("images/{}.png", ep.episode_id));
        let file = tiny().join("visual_reference").join(split.name()).join(rel);
        let img = image::open(&file).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (224, 224));
        // Something is in view (not a uniform image).
        let first = img.get_pixel(0, 0);
        assert!(img.pixels().any(|p| p != first));
    }
    for (_, ep) in all_episodes(Task::Dialogue) {
        assert_eq!(ep.oracle_budget, Some(5));
    }
}

#[test]
fn every_scene_folder_holds_its_prepared_raster_scene_and_it_draws_as_one_prepared_afresh() {
    use std::sync::Arc;
    use vlnverse_env::Pose;
    use vlnverse_sensors::raster::PREPARED_FILE;
    use vlnverse_sensors::{CameraSpec, Channels, RasterScene, SceneMesh, View};
    for (id, check) in scenes() {
        let file = tiny().join("scenes").join(id).join(PREPARED_FILE);
        let mesh = Arc::new(SceneMesh::new(&check.scene).unwrap());
        // Strict: the file fits the mesh of the scene loaded back from its folder.
        let loaded = RasterScene::load_prepared(mesh.clone(), &file).unwrap();
        let fresh = RasterScene::new(mesh);
        assert_eq!(loaded.drawn_triangles(), fresh.drawn_triangles(), "{id}");
        assert_eq!(
            loaded.face_texture_bytes(),
            fresh.face_texture_bytes(),
            "{id}"
        );
        assert!(
            fresh.face_texture_bytes() > 1,
            "{id}: a lit home has face textures"
        );
        let b = check.scene.bounds();
        let centre = glam::Vec3::new(
            (b.min[0] + b.max[0]) / 2.0,
            check.scene.floor_height,
            (b.min[2] + b.max[2]) / 2.0,
        );
        for k in 0..4 {
            let view = View {
                camera: CameraSpec::default().camera(&Pose::from_yaw(centre, k as f32 * 1.6)),
                channels: Channels::ALL,
            };
            let (a, f) = (loaded.render_view(&view, 1), fresh.render_view(&view, 1));
            assert!(a.rgb == f.rgb && a.depth == f.depth, "{id}: view {k}");
            assert!(
                a.semantic == f.semantic && a.instance == f.instance,
                "{id}: view {k}"
            );
        }
    }
}

#[test]
fn visual_reference_and_dialogue_reuse_the_coarse_episodes() {
    // The paper: the same trajectories and instructions as the coarse-grained dataset, so the
    // three tasks compare episode by episode.
    let coarse = all_episodes(Task::Coarse);
    assert!(!coarse.is_empty());
    for task in [Task::VisualReference, Task::Dialogue] {
        let other = all_episodes(task);
        assert_eq!(other.len(), coarse.len(), "{task}");
        for ((sa, a), (sb, b)) in coarse.iter().zip(&other) {
            let what = format!("{task} {sb} episode {}", b.episode_id);
            assert_eq!(sa, sb, "{what}");
            assert_eq!(
                (a.episode_id, a.trajectory_id, &a.scene_id),
                (b.episode_id, b.trajectory_id, &b.scene_id),
                "{what}"
            );
            assert_eq!(a.start_position, b.start_position, "{what}");
            assert_eq!(a.start_rotation, b.start_rotation, "{what}");
            assert_eq!(a.reference_path, b.reference_path, "{what}");
            assert_eq!(a.goals, b.goals, "{what}");
            assert_eq!(a.instruction, b.instruction, "{what}");
            assert_eq!(a.target_object_id, b.target_object_id, "{what}");
            assert_eq!(b.task, task);
        }
    }
}

#[test]
fn a_task_config_unlike_coarse_draws_its_own_trajectories() {
    let mut cfg = vlnverse_generate::GeneratePreset::Tiny.config().unwrap();
    assert_eq!(cfg.tasks.sampled_as(Task::VisualReference), Task::Coarse);
    assert_eq!(cfg.tasks.sampled_as(Task::Dialogue), Task::Coarse);
    assert_eq!(cfg.tasks.sampled_as(Task::Fine), Task::Fine);
    assert_eq!(cfg.tasks.sampled_as(Task::LongHorizon), Task::LongHorizon);
    cfg.tasks.dialogue.max_length -= 1.0;
    assert_eq!(cfg.tasks.sampled_as(Task::Dialogue), Task::Dialogue);
    assert_eq!(cfg.tasks.sampled_as(Task::VisualReference), Task::Coarse);
}

/// Every file under `dir` (relative path -> bytes).
fn tree(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                out.insert(
                    p.strip_prefix(root).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

fn assert_same_tree(a: &Path, b: &Path) {
    let (ta, tb) = (tree(a), tree(b));
    assert_eq!(
        ta.keys().collect::<Vec<_>>(),
        tb.keys().collect::<Vec<_>>(),
        "file lists differ"
    );
    for (k, v) in &ta {
        assert!(v == &tb[k], "{} differs", k.display());
    }
}

#[test]
fn one_thread_gives_the_same_bytes_as_two() {
    let d = tempfile::tempdir().unwrap();
    generate(d.path(), 1, (0, 1), &Task::ALL);
    assert_same_tree(d.path(), tiny());
}

#[test]
fn shards_merge_into_the_bytes_of_a_single_run() {
    let d = tempfile::tempdir().unwrap();
    let (a, b) = (d.path().join("a"), d.path().join("b"));
    generate(&a, 1, (0, 2), &Task::ALL);
    generate(&b, 2, (1, 2), &Task::ALL);
    // A shard writes no split files.
    assert!(!a.join("fine/train/train.json.gz").exists());
    let merged = d.path().join("merged");
    merge(&merged, &[a, b]).unwrap();
    assert_same_tree(&merged, tiny());
}

#[test]
fn a_resumed_run_gives_the_same_bytes() {
    let d = tempfile::tempdir().unwrap();
    generate(d.path(), 2, (0, 1), &Task::ALL);
    // Simulate an interruption: a part and a scene folder lost, split files gone.
    std::fs::remove_file(part_path(d.path(), "tiny_0002", Task::Coarse)).unwrap();
    std::fs::remove_dir_all(d.path().join("scenes/tiny_0003")).unwrap();
    std::fs::remove_dir_all(d.path().join("fine")).unwrap();
    generate(d.path(), 2, (0, 1), &Task::ALL);
    assert_same_tree(d.path(), tiny());
}

#[test]
fn merge_refuses_parts_of_another_config() {
    let d = tempfile::tempdir().unwrap();
    let (a, b) = (d.path().join("a"), d.path().join("b"));
    generate(&a, 1, (0, 2), &[Task::Fine]);
    generate(&b, 1, (1, 2), &[Task::Coarse]);
    let e = merge(&d.path().join("m"), &[a, b.clone()])
        .unwrap_err()
        .to_string();
    assert!(e.contains(&b.display().to_string()), "{e}");
}

#[test]
fn stats_write_plots_and_a_summary_with_the_counts() {
    let d = tempfile::tempdir().unwrap();
    generate(d.path(), 2, (0, 1), &[Task::Fine, Task::Coarse]);
    let md = vlnverse_generate::stats::write_stats(d.path()).unwrap();
    for f in [
        "navigable_area.png",
        "rooms.png",
        "path_length.png",
        "instruction_length.png",
    ] {
        let img = image::open(d.path().join("stats").join(f)).unwrap();
        assert!(img.width() >= 400, "{f}");
    }
    let st = vlnverse_generate::stats::collect(d.path()).unwrap();
    assert_eq!(st.rooms.len(), 5);
    assert_eq!(st.path_length["fine"].len(), 46);
    assert_eq!(st.instruction_words["coarse"]["formal"].len(), 23);
    assert!(md.contains("| fine | 24 | 6 | 8 | 8 |"), "{md}");
}
