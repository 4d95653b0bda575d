//! Top-down trajectory plots: the scene from above (`vlnverse_env::topdown`), the reference
//! path in green, the agent's path in blue (red when the episode failed), start and goal marks;
//! one picture per floor the episode touches in a home on several floors.

use std::path::Path;

use glam::Vec2;
use image::RgbImage;
use vlnverse_env::geodesic::MultiLevelMap;
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::topdown::{
    draw_marker, draw_path, render_topdown, render_topdown_level, Topdown, TopdownOptions,
};
use vlnverse_env::{LevelId, Scene};

use crate::error::{Result, TaskError};
use vlnverse_score::episode::Episode;
use vlnverse_score::metrics::EpisodeMetrics;
use vlnverse_score::trajectory::Trajectory;

fn floor(p: &[f32; 3]) -> Vec2 {
    Vec2::new(p[0], p[2])
}

/// Draw one episode. A home on several floors gets one picture per floor the episode touches,
/// side by side, each with that floor's map (`levels`) and the parts of the paths on it.
pub fn plot_episode(
    scene: &Scene,
    navigable: Option<&GridMap>,
    levels: Option<&MultiLevelMap>,
    ep: &Episode,
    traj: &Trajectory,
    m: &EpisodeMetrics,
) -> RgbImage {
    let opts = plot_options(format!(
        "ep {} {} NE {}",
        ep.episode_id,
        if m.success { "success" } else { "failure" },
        m.ne.map_or_else(|| "-".into(), |v| format!("{v:.2} m"))
    ));
    let Some(levels) = levels.filter(|_| scene.is_multi_level()) else {
        let mut td = render_topdown(scene, navigable, &opts);
        draw_episode(&mut td, None, ep, traj, m.success);
        return td.image;
    };
    let level_of = |p: &[f32; 3]| scene.level_at_height(p[1]);
    let mut touched: Vec<LevelId> = ep
        .reference_path
        .iter()
        .chain(&traj.positions)
        .chain([&ep.start_position])
        .map(level_of)
        .collect();
    touched.sort_unstable();
    touched.dedup();
    let pictures: Vec<RgbImage> = touched
        .iter()
        .filter_map(|&k| {
            let mut td = render_topdown_level(scene, k, levels.level(k), &opts)?;
            draw_episode(&mut td, Some((scene, k)), ep, traj, m.success);
            Some(td.image)
        })
        .collect();
    side_by_side(&pictures)
}

/// The picture of an episode plot: 40 px a metre (at most 1,200 px), no class labels.
fn plot_options(title: String) -> TopdownOptions {
    TopdownOptions {
        px_per_m: 40.0,
        max_size: 1200,
        labels: false,
        title,
        ..Default::default()
    }
}

/// The reference path (green), the agent's path (blue, red on failure), the start (white) and
/// goal marks, and where the agent ended; with `on = Some((scene, level))` only what lies on
/// that level.
fn draw_episode(
    td: &mut Topdown,
    on: Option<(&Scene, LevelId)>,
    ep: &Episode,
    traj: &Trajectory,
    success: bool,
) {
    let here = |p: &[f32; 3]| on.is_none_or(|(s, k)| s.level_at_height(p[1]) == k);
    for run in runs_on(&ep.reference_path, &here) {
        draw_path(&mut td.image, &td.frame, &run, [40, 170, 60], 4.0);
    }
    let color = if success {
        [30, 90, 220]
    } else {
        [220, 40, 40]
    };
    for run in runs_on(&traj.positions, &here) {
        draw_path(&mut td.image, &td.frame, &run, color, 2.5);
    }
    if here(&ep.start_position) {
        let start = floor(&ep.start_position);
        draw_marker(&mut td.image, &td.frame, start, [255, 255, 255], 5.0);
    }
    for g in ep.goal_sequence().iter().filter(|g| here(&g.position)) {
        draw_marker(
            &mut td.image,
            &td.frame,
            floor(&g.position),
            [40, 170, 60],
            5.0,
        );
    }
    if let Some(last) = traj.positions.last().filter(|p| here(p)) {
        draw_marker(&mut td.image, &td.frame, floor(last), color, 4.0);
    }
}

/// The runs of consecutive points of `points` for which `keep` holds, on the floor.
fn runs_on(points: &[[f32; 3]], keep: &dyn Fn(&[f32; 3]) -> bool) -> Vec<Vec<Vec2>> {
    let mut runs: Vec<Vec<Vec2>> = Vec::new();
    let mut open = false;
    for p in points {
        if !keep(p) {
            open = false;
            continue;
        }
        if !open {
            runs.push(Vec::new());
            open = true;
        }
        if let Some(run) = runs.last_mut() {
            run.push(floor(p));
        }
    }
    runs
}

/// Pictures placed left to right on a white ground, tops aligned.
fn side_by_side(pictures: &[RgbImage]) -> RgbImage {
    let w = pictures.iter().map(|p| p.width()).sum::<u32>().max(1);
    let h = pictures.iter().map(|p| p.height()).max().unwrap_or(1);
    let mut out = RgbImage::from_pixel(w, h, image::Rgb([255, 255, 255]));
    let mut x = 0;
    for p in pictures {
        image::imageops::replace(&mut out, p, i64::from(x), 0);
        x += p.width();
    }
    out
}

/// Indices of `n` episodes spread evenly over `len` (deterministic).
pub fn sample_indices(len: usize, n: usize) -> Vec<usize> {
    if len == 0 || n == 0 {
        return Vec::new();
    }
    let n = n.min(len);
    let mut v: Vec<usize> = (0..n).map(|i| i * len / n).collect();
    v.dedup();
    v
}

/// Save a plot as PNG (atomically).
pub fn save_png(path: &Path, img: &RgbImage) -> Result<()> {
    let mut bytes = Vec::new();
    img.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    )
    .map_err(|e| TaskError::invalid("plot", path.display(), e.to_string()))?;
    Ok(vlnverse_score::dataset::write_atomic(path, &bytes)?)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use vlnverse_env::occupancy::OccupancyConfig;
    use vlnverse_env::SceneSource;

    fn episode(start: [f32; 3], goal: [f32; 3]) -> Episode {
        serde_json::from_value(serde_json::json!({
            "episode_id": 1, "scene_id": "s", "start_position": start,
            "start_rotation": [0.0, 0.0, 0.0, 1.0], "goals": [{"position": goal}],
            "instruction": {"instruction_text": "go"}, "reference_path": [start, goal],
        }))
        .unwrap()
    }

    /// One episode's metrics, for tests that need some (also `runner`'s).
    pub(crate) fn metrics() -> EpisodeMetrics {
        serde_json::from_value(serde_json::json!({
            "episode_id": 1, "trajectory_id": 1, "scene_id": "s", "task": "fine",
            "split": null, "style": null, "geodesic_distance": 1.0, "tl": 1.0, "ne": 0.5,
            "oracle_ne": 0.5, "success": true, "oracle_success": true, "spl": 1.0, "ndtw": 1.0,
            "sdtw": 1.0, "collisions": 0, "steps": 2, "cr": 0.0, "stuck": null,
            "unreachable": false, "sub_goals": 0, "sub_goals_reached": 0,
        }))
        .unwrap()
    }

    #[test]
    fn an_episode_across_floors_gets_a_picture_of_each_floor() {
        let mut pc = vlnverse_procgen::Preset::Tiny.config().unwrap();
        pc.scenes.count = 1;
        pc.floors.two_storey_share = 1.0;
        let scene = vlnverse_procgen::HomeGenerator::new(pc)
            .unwrap()
            .scene(0)
            .unwrap();
        let levels = MultiLevelMap::from_scene(&scene, &OccupancyConfig::default()).unwrap();
        let st = &scene.storeys.stairs[0];
        let m = metrics();
        let traj = Trajectory {
            positions: vec![st.foot, st.head],
            ..Default::default()
        };
        let nav = levels.level(0);
        let across = plot_episode(
            &scene,
            nav,
            Some(&levels),
            &episode(st.foot, st.head),
            &traj,
            &m,
        );
        let down = traj.positions[..1].to_vec();
        let one = Trajectory {
            positions: down,
            ..Default::default()
        };
        let below = plot_episode(
            &scene,
            nav,
            Some(&levels),
            &episode(st.foot, st.foot),
            &one,
            &m,
        );
        let ground = render_topdown_level(&scene, 0, nav, &plot_options(String::new())).unwrap();
        let upper =
            render_topdown_level(&scene, 1, levels.level(1), &plot_options(String::new())).unwrap();
        assert_eq!(below.width(), ground.image.width());
        assert_eq!(across.width(), ground.image.width() + upper.image.width());
    }
}
