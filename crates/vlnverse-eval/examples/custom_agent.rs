//! The task layer alone: your own agent through the benchmark's evaluation loop. It builds a
//! one-home dataset (a procedural `tiny` home and a few shortest-path episodes), evaluates a
//! hand-written agent that turns towards the reference path's next point and walks, and
//! prints the metrics. Swap `PathFollower` for your policy.
//!
//! `cargo run -p vlnverse-eval --example custom_agent [OUT_DIR]`

use std::path::PathBuf;

use glam::Vec2;
use vlnverse_env::geodesic::shortest_path;
use vlnverse_env::io::write_scene_bundle;
use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_eval::evaluate;
use vlnverse_eval::{Agent, EpisodeInputs, EvalConfig, EvalRequest, FnFactory, Setting, StepInput};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_score::{dataset, Episode, EpisodeInfo, Goal, Instruction, Split, Task};
use vlnverse_sim::Action;

/// Walks towards a list of waypoints (here: told by the example, as a learned policy would
/// infer them), turning first when the next one is more than a turn step off its heading.
struct PathFollower {
    waypoints: Vec<Vec2>,
    next: usize,
    step: f32,
    turn_deg: f32,
}

impl Agent for PathFollower {
    fn reset(&mut self, inputs: &EpisodeInputs) -> vlnverse_eval::Result<()> {
        self.next = 0;
        self.step = inputs.agent.step_size;
        self.turn_deg = inputs.agent.turn_angle_deg;
        Ok(())
    }

    fn act(&mut self, step: &mut StepInput) -> vlnverse_eval::Result<Action> {
        let here = Vec2::new(step.pose.position[0], step.pose.position[2]);
        while self.next < self.waypoints.len() && here.distance(self.waypoints[self.next]) < 0.3 {
            self.next += 1;
        }
        let Some(&target) = self.waypoints.get(self.next) else {
            return Ok(Action::Stop);
        };
        let d = target - here;
        // Yaw 0 looks along -Z, counter-clockwise positive.
        let want = (-d.x).atan2(-d.y);
        let off = vlnverse_eval::agents::wrap_angle(want - step.pose.yaw()).to_degrees();
        // Turns take radians.
        Ok(if off > 0.5 * self.turn_deg {
            Action::TurnLeft(self.turn_deg.to_radians())
        } else if off < -0.5 * self.turn_deg {
            Action::TurnRight(self.turn_deg.to_radians())
        } else {
            Action::MoveForward(self.step.min(d.length()))
        })
    }
}

/// Build the dataset, evaluate the agent; return its success rate.
pub fn run(arg: Option<PathBuf>) -> Result<f64, Box<dyn std::error::Error>> {
    let out = arg.unwrap_or_else(|| {
        std::env::temp_dir().join(format!("vlnverse-custom-agent-{}", std::process::id()))
    });
    let scene = HomeGenerator::from_preset(Preset::Tiny)?.generate(1, "home")?;
    let (bundle, _) = write_scene_bundle(out.join("scenes"), scene, &OccupancyConfig::default())?;
    let nav = &bundle.maps.navigable;
    let free: Vec<Vec2> = nav
        .free_cells()
        .map(|(c, r)| nav.cell_center(c, r))
        .collect();
    let y = bundle.scene.floor_height;
    let mut episodes = Vec::new();
    for k in 0..free.len().min(400) {
        let (a, b) = (
            free[(k * 7919) % free.len()],
            free[(k * 104_729 + 13) % free.len()],
        );
        let Some(path) = shortest_path(nav, a, b)? else {
            continue;
        };
        if !(3.0..=10.0).contains(&path.length) || episodes.len() == 4 {
            continue;
        }
        episodes.push(Episode {
            episode_id: episodes.len() as u64 + 1,
            scene_id: "home".into(),
            start_position: [a.x, y, a.y],
            start_rotation: [0.0, 0.0, 0.0, 1.0],
            goals: vec![Goal {
                position: [b.x, y, b.y],
                radius: 3.0,
                object_id: None,
            }],
            instruction: Instruction {
                instruction_text: "Follow the hallway to the goal.".into(),
                ..Default::default()
            },
            reference_path: path.points.iter().map(|p| [p.x, y, p.y]).collect(),
            info: EpisodeInfo {
                geodesic_distance: path.length,
                ..Default::default()
            },
            task: Task::Fine,
            ..Default::default()
        });
    }
    dataset::write_split(&out, Task::Fine, Split::Test, &episodes)?;
    // The agent is told its waypoints per episode; a factory makes one agent per worker.
    let paths: Vec<Vec<Vec2>> = episodes
        .iter()
        .map(|e| {
            e.reference_path
                .iter()
                .map(|p| Vec2::new(p[0], p[2]))
                .collect()
        })
        .collect();
    let req = EvalRequest::new(out.clone(), Task::Fine, Split::Test, out.join("run"))
        .episodes(1)
        .threads(1)
        .fresh(true)
        .config(EvalConfig {
            setting: Setting::Lenient,
            render: false,
            plots: 1,
            ..Default::default()
        });
    let factory = FnFactory::new("path-follower", false, move || {
        Box::new(PathFollower {
            waypoints: paths[0].clone(),
            next: 0,
            step: 0.25,
            turn_deg: 15.0,
        }) as Box<dyn Agent>
    })
    .with_fingerprint("example v1");
    let outcome = evaluate(&req, &factory)?;
    let s = &outcome.summary.summary;
    println!(
        "{} on {} episode(s): SR {:.2}  SPL {:.2}  nDTW {:.2} -> {}",
        outcome.summary.method,
        s.episodes,
        s.sr,
        s.spl,
        s.ndtw,
        req.out.display()
    );
    Ok(s.sr)
}

#[allow(dead_code)] // the tests call `run` through `#[path]`
fn main() -> Result<(), Box<dyn std::error::Error>> {
    run(std::env::args().nth(1).map(PathBuf::from)).map(|_| ())
}
