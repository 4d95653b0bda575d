//! The scoring layer alone (no physics, no graphics): an episode, two trajectories (one that
//! reaches the goal and stops, one that wanders off), their metrics and the summary.
//! Distances here are straight lines; `score_on_maps` uses geodesics on a dataset's maps.
//!
//! `cargo run -p vlnverse-score --example score_trajectory`

use std::sync::Arc;

use vlnverse_score::metrics::{aggregate, score_episode, Euclidean, GoalDistances, MetricsConfig};
use vlnverse_score::{Episode, EpisodeInfo, Goal, Trajectory};

/// Score both trajectories; return the success rate of the two.
pub fn run() -> Result<f64, Box<dyn std::error::Error>> {
    let goal = [6.0, 0.0, 0.0];
    let episode = Episode {
        episode_id: 1,
        scene_id: "example".into(),
        start_position: [0.0, 0.0, 0.0],
        start_rotation: [0.0, 0.0, 0.0, 1.0],
        goals: vec![Goal {
            position: goal,
            radius: 3.0,
            object_id: None,
        }],
        reference_path: (0..=6).map(|x| [x as f32, 0.0, 0.0]).collect(),
        info: EpisodeInfo {
            geodesic_distance: 6.0,
            ..Default::default()
        },
        ..Default::default()
    };
    let straight = Trajectory::from_positions(
        1,
        (0..=24).map(|i| [i as f32 * 0.25, 0.0, 0.0]).collect(),
        true,
    );
    let astray = Trajectory::from_positions(
        1,
        (0..=24).map(|i| [0.0, 0.0, i as f32 * 0.25]).collect(),
        true,
    );
    let distances = GoalDistances {
        goal: Arc::new(Euclidean(goal)),
        sub_goals: vec![],
    };
    let cfg = MetricsConfig::default();
    let metrics: Vec<_> = [&straight, &astray]
        .iter()
        .map(|t| score_episode(&episode, t, &distances, &cfg))
        .collect();
    for (name, m) in ["straight", "astray"].iter().zip(&metrics) {
        println!(
            "{name:<9} success {}  SPL {:.2}  NE {:?}  nDTW {:.2}",
            m.success, m.spl, m.ne, m.ndtw
        );
    }
    let summary = aggregate(&metrics);
    println!(
        "summary over {} episodes: SR {:.2}  SPL {:.2}",
        summary.episodes, summary.sr, summary.spl
    );
    Ok(summary.sr)
}

#[allow(dead_code)] // the tests call `run` through `#[path]`
fn main() -> Result<(), Box<dyn std::error::Error>> {
    run().map(|_| ())
}
