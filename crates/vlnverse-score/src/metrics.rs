//! Navigation metrics: per episode ([`score_episode`]) and aggregated ([`aggregate`]).
//!
//! Definitions (docs/metrics.md has the long version and the differences to the paper's appendix
//! and to VLN-CE):
//! - TL: length of the polyline through the trajectory's positions.
//! - NE: geodesic distance from the final position to the goal.
//! - SR: the agent stopped with NE <= success distance (3 m).
//! - OSR: some position of the trajectory had geodesic distance <= 3 m to the goal.
//! - SPL: S * L / max(P, L), L = `info.geodesic_distance`, P = TL; 1 * S when both are 0.
//! - nDTW: exp(-DTW(R, Q) / (|R| * 3 m)), exact DTW, Euclidean point distance, R the reference
//!   path and Q the positions, both resampled every 0.25 m of arc length by default.
//! - SDTW = S * nDTW; CR = collisions / steps (per episode; the run's CR pools all episodes);
//!   oracle NE = min distance to the goal over positions.
//! - Long-horizon: the k-th STOP is judged against the k-th goal; sub-goal k is reached when it and
//!   all earlier ones are. SR_n = P(reached n | reached n-1), SR_all = all reached (= SR).
//!
//! Distances to a goal come from a [`GoalDistance`], so metrics do not depend on how the geodesic
//! is computed (a distance field on the navigable map in practice, [`Euclidean`] in tests).
//! `None` means unreachable: the episode is flagged, counts as a failure, and is left out of the
//! distance means (NE, oracle NE), which therefore never become inf or NaN.

use std::collections::BTreeMap;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::episode::{Episode, Split, Style, Task};
use crate::error::{DataError, Result};
use crate::trajectory::Trajectory;

/// Settings of the metrics; defaults follow the paper and VLN-CE.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MetricsConfig {
    /// Success threshold in metres (3.0). A distance equal to it counts as success.
    pub success_distance: f32,
    /// Resample R and Q every this many metres of arc length before DTW (0.25, the forward
    /// step); `None` uses the points as given.
    pub ndtw_spacing: Option<f32>,
    /// Stuck detection window in steps (20).
    pub stuck_window: u32,
    /// Stuck when the agent moved less than this over the window (0.2 m).
    pub stuck_distance: f32,
    /// ... and turned less than this in total over the window (15 degrees).
    pub stuck_angle_deg: f32,
    /// Any noticeable collision fails the episode (Strict setting applied after the fact).
    pub fail_on_collision: bool,
}

impl Default for MetricsConfig {
    fn default() -> Self {
        MetricsConfig {
            success_distance: 3.0,
            ndtw_spacing: Some(0.25),
            stuck_window: 20,
            stuck_distance: 0.2,
            stuck_angle_deg: 15.0,
            fail_on_collision: false,
        }
    }
}

impl MetricsConfig {
    /// Check ranges; errors name the field.
    pub fn validate(&self) -> Result<()> {
        if !(self.success_distance.is_finite() && self.success_distance > 0.0) {
            return Err(DataError::invalid(
                "success_distance",
                self.success_distance,
                "must be a positive number of metres",
            ));
        }
        if let Some(s) = self.ndtw_spacing {
            if !(s.is_finite() && s > 0.0) {
                return Err(DataError::invalid("ndtw_spacing", s, "must be positive"));
            }
        }
        if self.stuck_window == 0 {
            return Err(DataError::invalid(
                "stuck_window",
                0,
                "must be at least 1 step",
            ));
        }
        if !(self.stuck_distance >= 0.0 && self.stuck_angle_deg >= 0.0) {
            return Err(DataError::invalid(
                "stuck_distance/stuck_angle_deg",
                format!("{}/{}", self.stuck_distance, self.stuck_angle_deg),
                "must not be negative",
            ));
        }
        Ok(())
    }
}

/// Distance from a point to one goal; `None` when the goal cannot be reached from there.
pub trait GoalDistance: Send + Sync {
    /// Distance in metres from `p` (a floor point) to the goal.
    fn distance(&self, p: [f32; 3]) -> Option<f32>;
}

/// Straight-line distance to a goal point (tests, and scenes without a map).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Euclidean(pub [f32; 3]);

impl GoalDistance for Euclidean {
    fn distance(&self, p: [f32; 3]) -> Option<f32> {
        Some(dist(p, self.0))
    }
}

/// The nearest of several goals (VLN-CE measures distance to the closest entry of `goals`).
pub struct Nearest(pub Vec<Arc<dyn GoalDistance>>);

impl GoalDistance for Nearest {
    fn distance(&self, p: [f32; 3]) -> Option<f32> {
        self.0
            .iter()
            .filter_map(|g| g.distance(p))
            .min_by(f32::total_cmp)
    }
}

impl<F: Fn([f32; 3]) -> Option<f32> + Send + Sync> GoalDistance for F {
    fn distance(&self, p: [f32; 3]) -> Option<f32> {
        self(p)
    }
}

impl<T: GoalDistance + ?Sized> GoalDistance for Arc<T> {
    fn distance(&self, p: [f32; 3]) -> Option<f32> {
        (**self).distance(p)
    }
}

/// Geodesic distance on the field's map (the floor point's `(x, z)`); off-map or other-island
/// points are unreachable (the field snaps points just outside the free cells).
impl GoalDistance for vlnverse_env::geodesic::DistanceField {
    fn distance(&self, p: [f32; 3]) -> Option<f32> {
        vlnverse_env::geodesic::DistanceField::distance(self, glam::Vec2::new(p[0], p[2])).meters()
    }
}

/// Geodesic distance across the floors of a home (the 3-D point's level from its height): a
/// point on another floor than the goal is as far as the walk through the stairs, so a success
/// radius counts on the goal's floor only.
impl GoalDistance for vlnverse_env::geodesic::LevelField {
    fn distance(&self, p: [f32; 3]) -> Option<f32> {
        vlnverse_env::geodesic::LevelField::distance(self, p).meters()
    }
}

/// The distances an episode is scored with: to its goal (nearest of `goals`), and to each of its
/// `sub_goals` in order (long-horizon only; empty otherwise).
#[derive(Clone)]
pub struct GoalDistances {
    /// Distance to the episode's goal.
    pub goal: Arc<dyn GoalDistance>,
    /// Distance to each sub-goal, in order.
    pub sub_goals: Vec<Arc<dyn GoalDistance>>,
}

impl GoalDistances {
    /// Straight-line distances to the episode's goals.
    pub fn euclidean(ep: &Episode) -> Self {
        let goals: Vec<Arc<dyn GoalDistance>> = ep
            .goals
            .iter()
            .map(|g| Arc::new(Euclidean(g.position)) as Arc<dyn GoalDistance>)
            .collect();
        let goal: Arc<dyn GoalDistance> = if goals.len() == 1 {
            goals[0].clone()
        } else {
            Arc::new(Nearest(goals))
        };
        GoalDistances {
            goal,
            sub_goals: ep
                .sub_goals
                .iter()
                .map(|g| Arc::new(Euclidean(g.position)) as Arc<dyn GoalDistance>)
                .collect(),
        }
    }
}

/// Metrics of one episode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EpisodeMetrics {
    /// Episode id.
    pub episode_id: u64,
    /// Trajectory (path) id of the episode.
    pub trajectory_id: u64,
    /// Scene.
    pub scene_id: String,
    /// Task.
    pub task: Task,
    /// Split, when the caller knows it.
    pub split: Option<Split>,
    /// Instruction style, when it has one.
    pub style: Option<Style>,
    /// Shortest-path length start -> goal from the dataset (L of SPL).
    pub geodesic_distance: f32,
    /// Trajectory length (P of SPL).
    pub tl: f32,
    /// Navigation error; `None` when the goal is unreachable from the final position.
    pub ne: Option<f32>,
    /// Minimum distance to the goal over the positions; `None` when none could reach it.
    pub oracle_ne: Option<f32>,
    /// Stopped within the success distance (and the long-horizon chain complete).
    pub success: bool,
    /// Some position within the success distance.
    pub oracle_success: bool,
    /// Success weighted by path length.
    pub spl: f32,
    /// Normalized dynamic time warping.
    pub ndtw: f32,
    /// Success weighted by nDTW.
    pub sdtw: f32,
    /// Noticeable collisions.
    pub collisions: u32,
    /// Actions taken.
    pub steps: u32,
    /// Collisions per action.
    pub cr: f32,
    /// Whether the agent got stuck; `None` without headings.
    pub stuck: Option<bool>,
    /// The goal is unreachable from the final position (NE left out of means).
    pub unreachable: bool,
    /// Long-horizon: number of goals in the chain (0 for other tasks).
    pub sub_goals: u32,
    /// Long-horizon: how many goals were reached in order (a prefix of the chain).
    pub sub_goals_reached: u32,
}

/// Euclidean distance of two 3-D points.
#[inline]
pub fn dist(a: [f32; 3], b: [f32; 3]) -> f32 {
    let (dx, dy, dz) = (a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    (dx * dx + dy * dy + dz * dz).sqrt()
}

/// Length of the polyline through `points` (TL).
pub fn path_length(points: &[[f32; 3]]) -> f32 {
    points
        .windows(2)
        .map(|w| f64::from(dist(w[0], w[1])))
        .sum::<f64>() as f32
}

/// SPL of one episode: `S * L / max(P, L)`; when both `L` and `P` are 0 the agent did the
/// optimal thing (nothing), so SPL = S. A non-finite or negative `L` gives 0.
pub fn spl(success: bool, shortest: f32, travelled: f32) -> f32 {
    if !success || !shortest.is_finite() || shortest < 0.0 {
        return 0.0;
    }
    let denom = travelled.max(shortest);
    if denom <= 0.0 {
        1.0
    } else {
        shortest / denom
    }
}

/// Exact dynamic time warping distance (Euclidean point cost), O(|r| |q|) time, O(|q|) memory.
/// `0` when both are empty, `inf` when exactly one is.
pub fn dtw(r: &[[f32; 3]], q: &[[f32; 3]]) -> f64 {
    if r.is_empty() || q.is_empty() {
        return if r.is_empty() && q.is_empty() {
            0.0
        } else {
            f64::INFINITY
        };
    }
    let m = q.len();
    let mut prev = vec![f64::INFINITY; m + 1];
    let mut cur = vec![f64::INFINITY; m + 1];
    prev[0] = 0.0;
    for &ri in r {
        cur[0] = f64::INFINITY;
        for j in 0..m {
            let best = prev[j].min(prev[j + 1]).min(cur[j]);
            cur[j + 1] = f64::from(dist(ri, q[j])) + best;
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[m]
}

/// nDTW = exp(-DTW(R, Q) / (|R| * d)) of already prepared point lists; 0 when either is empty.
pub fn ndtw(reference: &[[f32; 3]], query: &[[f32; 3]], success_distance: f32) -> f32 {
    if reference.is_empty() || query.is_empty() {
        return 0.0;
    }
    let d = dtw(reference, query);
    (-d / (reference.len() as f64 * f64::from(success_distance))).exp() as f32
}

/// Most points [`resample`] returns; a longer polyline is sampled more coarsely, so memory and
/// DTW time stay bounded whatever the input.
pub const MAX_RESAMPLED_POINTS: usize = 100_000;

/// Points every `spacing` metres of arc length along the polyline, both ends included;
/// repeated points (turns in place) vanish. A polyline of length 0 gives its first point.
/// Arc length is accumulated in `f64`, and a polyline longer than
/// `spacing * MAX_RESAMPLED_POINTS` is sampled at `length / MAX_RESAMPLED_POINTS` instead, so the
/// output never has more than about [`MAX_RESAMPLED_POINTS`] points. Non-finite input gives the
/// points as they are.
pub fn resample(points: &[[f32; 3]], spacing: f32) -> Vec<[f32; 3]> {
    let Some(&first) = points.first() else {
        return Vec::new();
    };
    let seg_len = |a: [f32; 3], b: [f32; 3]| -> f64 {
        let d = |i: usize| f64::from(b[i]) - f64::from(a[i]);
        (d(0) * d(0) + d(1) * d(1) + d(2) * d(2)).sqrt()
    };
    let total: f64 = points.windows(2).map(|w| seg_len(w[0], w[1])).sum();
    if !total.is_finite() || !spacing.is_finite() {
        return points.to_vec();
    }
    let mut out = vec![first];
    if total <= 0.0 || spacing <= 0.0 {
        return out;
    }
    let spacing = f64::from(spacing).max(total / MAX_RESAMPLED_POINTS as f64);
    let mut k = 1u64; // index of the next sample, at arc length k * spacing
    let mut walked = 0.0f64; // arc length at the start of the current segment
    for w in points.windows(2) {
        let seg = seg_len(w[0], w[1]);
        loop {
            let next = k as f64 * spacing;
            if !(seg > 0.0 && next <= walked + seg && next < total - 1e-4) {
                break;
            }
            let t = (next - walked) / seg;
            let lerp = |i: usize| {
                (f64::from(w[0][i]) + (f64::from(w[1][i]) - f64::from(w[0][i])) * t) as f32
            };
            out.push([lerp(0), lerp(1), lerp(2)]);
            k += 1;
        }
        walked += seg;
    }
    if let Some(&last) = points.last() {
        out.push(last);
    }
    out
}

/// Horizontal (floor-plane `x`, `z`) distance of two points.
pub fn horizontal_dist(a: [f32; 3], b: [f32; 3]) -> f32 {
    let (dx, dz) = (
        f64::from(a[0]) - f64::from(b[0]),
        f64::from(a[2]) - f64::from(b[2]),
    );
    (dx * dx + dz * dz).sqrt() as f32
}

/// Default of [`check_starts`]' tolerance (m): a trajectory must begin this close to the
/// episode's start position.
pub const DEFAULT_START_TOLERANCE: f32 = 0.5;

/// Check that every non-empty trajectory begins at its episode's start: the horizontal distance
/// from its first position to `start_position` must be at most `tolerance` metres.
/// `trajectories[i]` belongs to `episodes[i]` (see [`match_trajectories`]). The error names the
/// episode, the first position and the start.
pub fn check_starts(
    episodes: &[Episode],
    trajectories: &[Trajectory],
    tolerance: f32,
) -> Result<()> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(DataError::invalid(
            "start_tolerance",
            tolerance,
            "must be a non-negative number of metres",
        ));
    }
    for (ep, t) in episodes.iter().zip(trajectories) {
        let Some(&p) = t.positions.first() else {
            continue;
        };
        let d = horizontal_dist(p, ep.start_position);
        if d.is_nan() || d > tolerance {
            return Err(DataError::invalid(
                format!("episode {}: positions[0]", ep.episode_id),
                format!("{p:?}"),
                format!(
                    "the trajectory must begin at the episode's start_position {:?}, but its \
                     first position is {d:.2} m away (horizontally; tolerance {tolerance} m, \
                     --start-tolerance to relax it)",
                    ep.start_position
                ),
            ));
        }
    }
    Ok(())
}

/// Whether the agent got stuck: over some window of `window` steps it moved less than
/// `max_dist` away from where the window began and turned less than `max_angle_deg` in total.
pub fn is_stuck(
    positions: &[[f32; 3]],
    headings: &[f32],
    window: usize,
    max_dist: f32,
    max_angle_deg: f32,
) -> bool {
    let n = positions.len().min(headings.len());
    if window == 0 || n <= window {
        return false;
    }
    let max_angle = max_angle_deg.to_radians();
    (0..n - window).any(|s| {
        let moved = positions[s + 1..=s + window]
            .iter()
            .all(|&p| dist(p, positions[s]) < max_dist);
        moved
            && headings[s..=s + window]
                .windows(2)
                .map(|w| wrap_angle(w[1] - w[0]).abs())
                .sum::<f32>()
                < max_angle
    })
}

/// An angle wrapped into [-pi, pi].
fn wrap_angle(a: f32) -> f32 {
    let t = std::f32::consts::TAU;
    let r = a.rem_euclid(t);
    if r > std::f32::consts::PI {
        r - t
    } else {
        r
    }
}

/// Score one episode. `distances.sub_goals` must list the episode's `sub_goals` in order (a
/// missing entry falls back to the straight-line distance).
pub fn score_episode(
    ep: &Episode,
    traj: &Trajectory,
    distances: &GoalDistances,
    cfg: &MetricsConfig,
) -> EpisodeMetrics {
    let d_ok = |d: Option<f32>| d.is_some_and(|d| d <= cfg.success_distance);
    let start = [ep.start_position];
    let positions: &[[f32; 3]] = if traj.positions.is_empty() {
        &start
    } else {
        &traj.positions
    };
    let last = positions[positions.len() - 1];
    let tl = path_length(positions);
    let ne = distances.goal.distance(last).filter(|d| d.is_finite());
    let oracle_ne = positions
        .iter()
        .filter_map(|&p| distances.goal.distance(p))
        .filter(|d| d.is_finite())
        .min_by(f32::total_cmp);
    let collision_ok = !cfg.fail_on_collision || traj.collisions == 0;

    // Long-horizon chain: the k-th STOP is judged against the k-th goal.
    let n_sub = ep.sub_goals.len();
    let mut reached = 0usize;
    if n_sub > 0 {
        let stops = traj.stop_indices();
        for (k, goal) in ep.sub_goals.iter().enumerate() {
            let Some(&idx) = stops.get(k) else { break };
            let p = positions[idx.min(positions.len() - 1)];
            let d = match distances.sub_goals.get(k) {
                Some(g) => g.distance(p),
                None => Some(dist(p, goal.position)),
            };
            if !d_ok(d) {
                break;
            }
            reached += 1;
        }
    }
    let success = collision_ok
        && if n_sub > 0 {
            reached == n_sub && traj.stopped
        } else {
            traj.stopped && d_ok(ne)
        };
    let oracle_success = oracle_ne.is_some_and(|d| d <= cfg.success_distance);

    let goal_point = ep.goals.first().map_or(ep.start_position, |g| g.position);
    let fallback_ref = [ep.start_position, goal_point];
    let reference: &[[f32; 3]] = if ep.reference_path.is_empty() {
        &fallback_ref
    } else {
        &ep.reference_path
    };
    let ndtw_value = match cfg.ndtw_spacing {
        Some(s) => ndtw(
            &resample(reference, s),
            &resample(positions, s),
            cfg.success_distance,
        ),
        None => ndtw(reference, positions, cfg.success_distance),
    };
    let spl_value = spl(success, ep.info.geodesic_distance, tl);
    let stuck = traj.headings.as_ref().map(|h| {
        is_stuck(
            positions,
            h,
            cfg.stuck_window as usize,
            cfg.stuck_distance,
            cfg.stuck_angle_deg,
        )
    });
    EpisodeMetrics {
        episode_id: ep.episode_id,
        trajectory_id: ep.trajectory_id,
        scene_id: ep.scene_id.clone(),
        task: ep.task,
        split: None,
        style: ep.instruction.style,
        geodesic_distance: ep.info.geodesic_distance,
        tl,
        ne,
        oracle_ne,
        success,
        oracle_success,
        spl: spl_value,
        ndtw: ndtw_value,
        sdtw: if success { ndtw_value } else { 0.0 },
        collisions: traj.collisions,
        steps: traj.steps,
        cr: if traj.steps == 0 {
            0.0
        } else {
            traj.collisions as f32 / traj.steps as f32
        },
        stuck,
        unreachable: ne.is_none(),
        sub_goals: n_sub as u32,
        sub_goals_reached: reached as u32,
    }
}

/// Pair trajectories with episodes by id. Errors on a trajectory of an unknown episode, a
/// duplicate, or (unless `allow_missing`) an episode without a trajectory; with `allow_missing`
/// such an episode gets an empty trajectory (it never moved nor stopped: a failure).
pub fn match_trajectories(
    episodes: &[Episode],
    trajectories: Vec<Trajectory>,
    allow_missing: bool,
) -> Result<Vec<Trajectory>> {
    let index: BTreeMap<u64, usize> = episodes
        .iter()
        .enumerate()
        .map(|(i, e)| (e.episode_id, i))
        .collect();
    let mut slots: Vec<Option<Trajectory>> = vec![None; episodes.len()];
    for t in trajectories {
        let Some(&i) = index.get(&t.episode_id) else {
            return Err(DataError::invalid(
                "episode_id",
                t.episode_id,
                "no episode with this id in the split",
            ));
        };
        if slots[i].is_some() {
            return Err(DataError::invalid(
                "episode_id",
                t.episode_id,
                "more than one trajectory for this episode",
            ));
        }
        slots[i] = Some(t);
    }
    let missing: Vec<u64> = slots
        .iter()
        .zip(episodes)
        .filter(|(s, _)| s.is_none())
        .map(|(_, e)| e.episode_id)
        .collect();
    if !missing.is_empty() && !allow_missing {
        let shown: Vec<String> = missing.iter().take(5).map(u64::to_string).collect();
        return Err(DataError::invalid(
            "episode_id",
            shown.join(", "),
            format!(
                "{} episode(s) of the split have no trajectory (pass --allow-missing to score them as failures)",
                missing.len()
            ),
        ));
    }
    Ok(slots
        .into_iter()
        .zip(episodes)
        .map(|(s, e)| {
            s.unwrap_or_else(|| Trajectory::from_positions(e.episode_id, Vec::new(), false))
        })
        .collect())
}

/// Score many episodes in parallel (rayon); `trajectories[i]` belongs to `episodes[i]` and
/// `distances(ep)` gives the distances of an episode. Output order is input order.
pub fn score_all(
    episodes: &[Episode],
    trajectories: &[Trajectory],
    distances: &(dyn Fn(&Episode) -> GoalDistances + Sync),
    cfg: &MetricsConfig,
) -> Vec<EpisodeMetrics> {
    use rayon::prelude::*;
    episodes
        .par_iter()
        .zip(trajectories.par_iter())
        .map(|(ep, t)| score_episode(ep, t, &distances(ep), cfg))
        .collect()
}

/// Aggregated metrics: plain means over episodes (CR excepted: the paper's pooled ratio),
/// rates as fractions in [0, 1].
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Summary {
    /// Number of episodes.
    pub episodes: usize,
    /// Mean trajectory length (m).
    pub tl: f64,
    /// Mean navigation error (m) over episodes whose goal is reachable from the final position;
    /// `null` when there is none.
    pub ne: Option<f64>,
    /// Success rate.
    pub sr: f64,
    /// Oracle success rate.
    pub osr: f64,
    /// Mean SPL.
    pub spl: f64,
    /// Mean nDTW.
    pub ndtw: f64,
    /// Mean SDTW.
    pub sdtw: f64,
    /// Collision rate as the paper defines it: all noticeable collisions over all actions of
    /// the run (pooled over episodes).
    pub cr: f64,
    /// The mean over episodes of each episode's collisions per action (weights short and long
    /// episodes alike).
    #[serde(default)]
    pub cr_episode_mean: f64,
    /// Long-horizon: success rate of the first goal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sr_1: Option<f64>,
    /// Long-horizon: success rate of the second goal given the first.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sr_2: Option<f64>,
    /// Long-horizon: success rate of the third goal given the first two.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sr_3: Option<f64>,
    /// Long-horizon: every goal reached in order.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sr_all: Option<f64>,
    /// Mean oracle navigation error (m), like `ne`.
    pub oracle_ne: Option<f64>,
    /// Mean actions per episode.
    pub steps: f64,
    /// Mean noticeable collisions per episode.
    pub collisions: f64,
    /// Fraction of episodes with headings in which the agent got stuck.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stuck: Option<f64>,
    /// Episodes whose goal is unreachable from the final position.
    pub unreachable: usize,
}

fn mean(it: impl Iterator<Item = f64>) -> Option<f64> {
    let (mut s, mut n) = (0.0f64, 0usize);
    for v in it {
        if v.is_finite() {
            s += v;
            n += 1;
        }
    }
    (n > 0).then(|| s / n as f64)
}

/// Conditional success rate of goal `n` (1-based) over the chains that have one.
fn sr_n(ms: &[EpisodeMetrics], n: u32) -> Option<f64> {
    let eligible: Vec<&EpisodeMetrics> = ms.iter().filter(|m| m.sub_goals >= n).collect();
    if eligible.is_empty() {
        return None;
    }
    let given = eligible
        .iter()
        .filter(|m| m.sub_goals_reached + 1 >= n)
        .count();
    let hit = eligible.iter().filter(|m| m.sub_goals_reached >= n).count();
    Some(if given == 0 {
        0.0
    } else {
        hit as f64 / given as f64
    })
}

/// Aggregate episode metrics (plain means; see [`Summary`]).
pub fn aggregate(ms: &[EpisodeMetrics]) -> Summary {
    let f = |x: f32| f64::from(x);
    let b = |x: bool| if x { 1.0 } else { 0.0 };
    let zero = |o: Option<f64>| o.unwrap_or(0.0);
    let lh: Vec<EpisodeMetrics> = ms.iter().filter(|m| m.sub_goals > 0).cloned().collect();
    let steps: u64 = ms.iter().map(|m| u64::from(m.steps)).sum();
    let collisions: u64 = ms.iter().map(|m| u64::from(m.collisions)).sum();
    Summary {
        episodes: ms.len(),
        tl: zero(mean(ms.iter().map(|m| f(m.tl)))),
        ne: mean(ms.iter().filter_map(|m| m.ne).map(f)),
        sr: zero(mean(ms.iter().map(|m| b(m.success)))),
        osr: zero(mean(ms.iter().map(|m| b(m.oracle_success)))),
        spl: zero(mean(ms.iter().map(|m| f(m.spl)))),
        ndtw: zero(mean(ms.iter().map(|m| f(m.ndtw)))),
        sdtw: zero(mean(ms.iter().map(|m| f(m.sdtw)))),
        cr: if steps == 0 {
            0.0
        } else {
            collisions as f64 / steps as f64
        },
        cr_episode_mean: zero(mean(ms.iter().map(|m| f(m.cr)))),
        sr_1: sr_n(&lh, 1),
        sr_2: sr_n(&lh, 2),
        sr_3: sr_n(&lh, 3),
        sr_all: mean(lh.iter().map(|m| b(m.sub_goals_reached == m.sub_goals))),
        oracle_ne: mean(ms.iter().filter_map(|m| m.oracle_ne).map(f)),
        steps: zero(mean(ms.iter().map(|m| f64::from(m.steps)))),
        collisions: zero(mean(ms.iter().map(|m| f64::from(m.collisions)))),
        stuck: mean(ms.iter().filter_map(|m| m.stuck).map(b)),
        unreachable: ms.iter().filter(|m| m.unreachable).count(),
    }
}

/// Aggregate per group, e.g. per style: `aggregate_by(&ms, |m| m.style.map(|s| s.to_string()))`.
/// Episodes whose key is `None` are left out. Groups come out sorted by key.
pub fn aggregate_by(
    ms: &[EpisodeMetrics],
    key: impl Fn(&EpisodeMetrics) -> Option<String>,
) -> BTreeMap<String, Summary> {
    let mut groups: BTreeMap<String, Vec<EpisodeMetrics>> = BTreeMap::new();
    for m in ms {
        if let Some(k) = key(m) {
            groups.entry(k).or_default().push(m.clone());
        }
    }
    groups
        .into_iter()
        .map(|(k, v)| (k, aggregate(&v)))
        .collect()
}
