//! The teacher trajectory of one episode, driven through the same [`EpisodeState`] as the
//! vector environment (`vlnverse_task::eval::vec_env`): reset, then at every state the rig's
//! observations and the shortest-path follower's next action, applied until the episode ends.
//!
//! Frame `t` is the state after `t` actions. The last frame's action is STOP: the teacher's
//! own STOP when it reaches the goal, or STOP given for the final state when the episode ended
//! otherwise (the step limit, or a Strict collision failure).

use glam::{Quat, Vec3};
use vlnverse_env::Pose;
use vlnverse_sensors::{Observations, SensorRig};
use vlnverse_sim::{Action, RapierSimulator};
use vlnverse_task::eval::agents::wrap_angle;
use vlnverse_task::eval::agents::OracleAgent;
use vlnverse_task::eval::check_episode;
use vlnverse_task::eval::Agent;
use vlnverse_task::eval::{EpisodeSettings, EpisodeState, SceneContext};
use vlnverse_task::Episode;

use crate::error::{ExportError, Result};

/// The discrete action ids of the `vlnverse` Python package (VLN-CE order).
pub fn action_id(a: &Action) -> Option<i64> {
    match a {
        Action::Stop => Some(0),
        Action::MoveForward(_) => Some(1),
        Action::TurnLeft(_) => Some(2),
        Action::TurnRight(_) => Some(3),
        Action::LookUp => Some(4),
        Action::LookDown => Some(5),
        _ => None,
    }
}

/// A simulator, an optional rig and a teacher: what one thread drives episodes with.
pub struct Worker {
    /// The physics.
    pub sim: RapierSimulator,
    /// The sensors (none when only planning).
    pub rig: Option<SensorRig>,
    teacher: OracleAgent,
}

impl Worker {
    /// A worker over a simulator and an optional rig.
    pub fn new(sim: RapierSimulator, rig: Option<SensorRig>) -> Self {
        Worker {
            sim,
            rig,
            teacher: OracleAgent::default(),
        }
    }
}

/// One state along the teacher trajectory.
pub struct Step<'a> {
    /// Actions taken before this state.
    pub index: u32,
    /// The base pose.
    pub pose: Pose,
    /// The episode's start pose.
    pub start: Pose,
    /// The rig's readings (empty without a rig).
    pub observations: &'a Observations,
    /// The teacher's action here (id of [`action_id`]).
    pub action: i64,
}

impl Step<'_> {
    /// `[x, y, z, yaw]`, as the Python env's `pose`.
    pub fn pose4(&self) -> [f32; 4] {
        let p = self.pose.position;
        [p[0], p[1], p[2], self.pose.yaw()]
    }

    /// Heading relative to the start, as the Python env's `compass`.
    pub fn compass(&self) -> f32 {
        wrap_angle(self.pose.yaw() - self.start.yaw())
    }

    /// Position in the start frame, `[forward, right]`, as the Python env's `gps`.
    pub fn gps(&self) -> [f32; 2] {
        let rel = Quat::from_array(self.start.rotation).inverse()
            * (Vec3::from_array(self.pose.position) - Vec3::from_array(self.start.position));
        [-rel.z, rel.x]
    }
}

/// Drive `ep` with the teacher, calling `on_step` at every state; returns the action ids.
pub fn run(
    w: &mut Worker,
    ep: &Episode,
    scene: &SceneContext,
    settings: &EpisodeSettings,
    mut on_step: impl FnMut(&Step<'_>) -> Result<()>,
) -> Result<Vec<i64>> {
    if let Err(e) = check_episode(ep, scene) {
        return Err(ExportError::invalid(
            &format!("episode {}.{}", ep.episode_id, e.field),
            e.value,
            e.reason.to_string(),
        ));
    }
    let mut state = EpisodeState::begin(&mut w.sim, w.rig.as_mut(), ep, scene, settings)?;
    w.teacher.set_truth(&state.privileged(ep));
    w.teacher.reset(&state.inputs)?;
    let mut actions = Vec::new();
    loop {
        let observations = match w.rig.as_mut() {
            Some(rig) => state.observe(rig)?,
            None => Observations::new(),
        };
        let over = state.is_over();
        let action = if over {
            Action::Stop
        } else {
            w.teacher.act(&mut state.step_input(&observations))?
        };
        let id = action_id(&action).ok_or_else(|| {
            ExportError::invalid(
                &format!("episode {}: teacher action", ep.episode_id),
                format!("{action:?}"),
                "not a discrete action",
            )
        })?;
        on_step(&Step {
            index: actions.len() as u32,
            pose: state.pose(),
            start: state.inputs.start,
            observations: &observations,
            action: id,
        })?;
        actions.push(id);
        if over {
            break;
        }
        state.apply(&mut w.sim, action, &settings.config)?;
        if action == Action::Stop && state.is_over() {
            break;
        }
    }
    Ok(actions)
}
