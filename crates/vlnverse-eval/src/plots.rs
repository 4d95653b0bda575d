//! Top-down trajectory plots: the scene from above (`vlnverse_env::topdown`), the reference
//! path in green, the agent's path in blue (red when the episode failed), start and goal marks.

use std::path::Path;

use glam::Vec2;
use image::RgbImage;
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::topdown::{draw_marker, draw_path, render_topdown, TopdownOptions};
use vlnverse_env::Scene;

use crate::error::{Result, TaskError};
use vlnverse_score::episode::Episode;
use vlnverse_score::metrics::EpisodeMetrics;
use vlnverse_score::trajectory::Trajectory;

fn floor(p: &[f32; 3]) -> Vec2 {
    Vec2::new(p[0], p[2])
}

/// Draw one episode.
pub fn plot_episode(
    scene: &Scene,
    navigable: Option<&GridMap>,
    ep: &Episode,
    traj: &Trajectory,
    m: &EpisodeMetrics,
) -> RgbImage {
    let opts = TopdownOptions {
        px_per_m: 40.0,
        max_size: 1200,
        labels: false,
        title: format!(
            "ep {} {} NE {}",
            ep.episode_id,
            if m.success { "success" } else { "failure" },
            m.ne.map_or_else(|| "-".into(), |v| format!("{v:.2} m"))
        ),
        ..Default::default()
    };
    let mut td = render_topdown(scene, navigable, &opts);
    let reference: Vec<Vec2> = ep.reference_path.iter().map(floor).collect();
    draw_path(&mut td.image, &td.frame, &reference, [40, 170, 60], 4.0);
    let path: Vec<Vec2> = traj.positions.iter().map(floor).collect();
    let color = if m.success {
        [30, 90, 220]
    } else {
        [220, 40, 40]
    };
    draw_path(&mut td.image, &td.frame, &path, color, 2.5);
    draw_marker(
        &mut td.image,
        &td.frame,
        floor(&ep.start_position),
        [255, 255, 255],
        5.0,
    );
    for g in ep.goal_sequence() {
        draw_marker(
            &mut td.image,
            &td.frame,
            floor(&g.position),
            [40, 170, 60],
            5.0,
        );
    }
    if let Some(last) = traj.positions.last() {
        draw_marker(&mut td.image, &td.frame, floor(last), color, 4.0);
    }
    td.image
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
