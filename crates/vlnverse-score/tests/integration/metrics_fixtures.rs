//! Metrics on hand-computed fixtures.

use std::sync::Arc;

use vlnverse_score::metrics::{
    aggregate, dtw, is_stuck, ndtw, path_length, resample, score_episode, spl, GoalDistance,
    GoalDistances, MetricsConfig,
};
use vlnverse_score::{Episode, EpisodeInfo, Goal, Task, Trajectory};

fn episode(start: [f32; 3], goal: [f32; 3], geodesic: f32) -> Episode {
    Episode {
        episode_id: 1,
        trajectory_id: 1,
        scene_id: "s".into(),
        start_position: start,
        goals: vec![Goal {
            position: goal,
            radius: 3.0,
            object_id: None,
        }],
        reference_path: vec![start, goal],
        info: EpisodeInfo {
            geodesic_distance: geodesic,
            ..Default::default()
        },
        ..Default::default()
    }
}

fn walk(points: &[[f32; 3]], step: f32) -> Vec<[f32; 3]> {
    // Positions every `step` metres along the polyline, as a discrete agent would record them.
    resample(points, step)
}

fn score(ep: &Episode, t: &Trajectory) -> vlnverse_score::EpisodeMetrics {
    score_episode(
        ep,
        t,
        &GoalDistances::euclidean(ep),
        &MetricsConfig::default(),
    )
}

const O: [f32; 3] = [0.0, 0.0, 0.0];

#[test]
fn spl_zero_length_reference() {
    // Start on the goal, L = 0.
    let ep = episode(O, O, 0.0);
    // Never moves and stops: the optimal behaviour, SPL = 1 (0/0 is defined as S).
    let m = score(&ep, &Trajectory::from_positions(1, vec![O], true));
    assert!(m.success);
    assert_eq!(m.spl, 1.0);
    // Walks 2 m out and back, stops on the goal: S = 1 but L / max(P, L) = 0 / 4.
    let out_back = vec![O, [2.0, 0.0, 0.0], O];
    let m = score(&ep, &Trajectory::from_positions(1, out_back, true));
    assert!(m.success);
    assert_eq!(m.tl, 4.0);
    assert_eq!(m.spl, 0.0);
    assert!(m.ndtw.is_finite() && m.ndtw > 0.0);
}

#[test]
fn spl_agent_that_never_moves() {
    // Goal 2 m away (inside the 3 m threshold): stopping at once succeeds with SPL = L / L = 1.
    let near = episode(O, [2.0, 0.0, 0.0], 2.0);
    let m = score(&near, &Trajectory::from_positions(1, vec![O], true));
    assert!(m.success);
    assert_eq!((m.tl, m.spl), (0.0, 1.0));
    // Goal 5 m away: a failure, SPL 0, NE 5, steps 0, CR 0 (no division by zero).
    let far = episode(O, [5.0, 0.0, 0.0], 5.0);
    let m = score(&far, &Trajectory::from_positions(1, vec![O], true));
    assert!(!m.success);
    assert_eq!((m.spl, m.ne, m.steps, m.cr), (0.0, Some(5.0), 0, 0.0));
    // Empty position list: scored as standing at the start.
    let m = score(&far, &Trajectory::from_positions(1, vec![], false));
    assert_eq!((m.tl, m.ne, m.success), (0.0, Some(5.0), false));
}

#[test]
fn spl_longer_path() {
    // L = 4; the agent takes a detour of length 8 (4 up, 4 across... ) and stops on the goal.
    let goal = [4.0, 0.0, 0.0];
    let ep = episode(O, goal, 4.0);
    let detour = walk(&[O, [0.0, 0.0, 2.0], [4.0, 0.0, 2.0], goal], 0.25);
    let t = Trajectory::from_positions(1, detour, true);
    let m = score(&ep, &t);
    assert!((m.tl - 8.0).abs() < 1e-4, "tl {}", m.tl);
    assert!(m.success);
    assert!((m.spl - 0.5).abs() < 1e-4, "spl {}", m.spl);
    assert_eq!(spl(true, 4.0, 8.0), 0.5);
    assert_eq!(spl(false, 4.0, 8.0), 0.0);
    assert_eq!(spl(true, f32::NAN, 8.0), 0.0);
}

#[test]
fn dtw_matches_hand_worked_3x4_example() {
    // R = r1 (0,0,0), r2 (3,0,0), r3 (6,0,0); Q = q1 (0,0,0), q2 (0,0,4), q3 (3,0,4), q4 (6,0,0).
    // Point costs d(ri, qj):      q1   q2      q3   q4
    //                        r1   0    4       5    6
    //                        r2   3    5       4    3
    //                        r3   6    7.2111  5    0
    // Accumulated D(i,j) = d + min(D(i-1,j), D(i,j-1), D(i-1,j-1)):
    //                        r1   0    4       9    15
    //                        r2   3    5       8    11
    //                        r3   9    10.2111 10   8
    // DTW = D(3,4) = 8; nDTW = exp(-8 / (3 * 3)) = 0.41111.
    let r = [O, [3.0, 0.0, 0.0], [6.0, 0.0, 0.0]];
    let q = [O, [0.0, 0.0, 4.0], [3.0, 0.0, 4.0], [6.0, 0.0, 0.0]];
    assert!((dtw(&r, &q) - 8.0).abs() < 1e-9);
    assert!((dtw(&q, &r) - 8.0).abs() < 1e-9, "DTW is symmetric");
    let expected = (-8.0f64 / 9.0).exp() as f32;
    assert!((ndtw(&r, &q, 3.0) - expected).abs() < 1e-6);
    assert!((expected - 0.41111).abs() < 1e-4);
    // Identical paths: DTW 0, nDTW 1.
    assert_eq!(dtw(&r, &r), 0.0);
    assert_eq!(ndtw(&r, &r, 3.0), 1.0);
}

#[test]
fn ndtw_of_an_agent_on_the_reference_path_is_one() {
    // A discrete agent walking exactly along a sparse reference path: resampling both every
    // 0.25 m makes nDTW 1 (on the raw points it would be penalised for its density).
    let goal = [4.0, 0.0, 3.0];
    let mut ep = episode(O, goal, 7.0);
    ep.reference_path = vec![O, [4.0, 0.0, 0.0], goal];
    let t = Trajectory::from_positions(1, walk(&ep.reference_path, 0.25), true);
    let m = score(&ep, &t);
    assert!((m.ndtw - 1.0).abs() < 1e-5, "ndtw {}", m.ndtw);
    assert_eq!(m.sdtw, m.ndtw);
    let raw = MetricsConfig {
        ndtw_spacing: None,
        ..Default::default()
    };
    let m_raw = score_episode(&ep, &t, &GoalDistances::euclidean(&ep), &raw);
    assert!(m_raw.ndtw < 0.5, "raw nDTW {}", m_raw.ndtw);
}

#[test]
fn resample_keeps_ends_and_drops_turns_in_place() {
    let pts = [O, O, [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.6]];
    let r = resample(&pts, 0.5);
    assert_eq!(
        r,
        vec![
            O,
            [0.5, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.5],
            [1.0, 0.0, 0.6]
        ]
    );
    assert!((path_length(&r) - 1.6).abs() < 1e-6);
    assert_eq!(resample(&[O, O], 0.25), vec![O]);
    assert!(resample(&[], 0.25).is_empty());
}

#[test]
fn osr_counts_passing_the_goal_sr_needs_the_stop() {
    let goal = [6.0, 0.0, 0.0];
    let ep = episode(O, goal, 6.0);
    // Passes 1 m from the goal, walks on and stops 5 m from it.
    let past = walk(&[O, [5.0, 0.0, 0.0], [11.0, 0.0, 0.0]], 0.25);
    let m = score(&ep, &Trajectory::from_positions(1, past, true));
    assert!(m.oracle_success && !m.success);
    assert!((m.ne.unwrap() - 5.0).abs() < 1e-4);
    assert!(m.oracle_ne.unwrap() < 1e-4, "passes through the goal");
    // Reaches the goal but never stops (step limit): OSR 1, SR 0, SPL 0.
    let there = walk(&[O, goal], 0.25);
    let m = score(&ep, &Trajectory::from_positions(1, there.clone(), false));
    assert!(m.oracle_success && !m.success);
    assert_eq!((m.spl, m.sdtw), (0.0, 0.0));
    // Stops exactly 3 m away: success (<= threshold).
    let edge = walk(&[O, [3.0, 0.0, 0.0]], 0.25);
    let m = score(&ep, &Trajectory::from_positions(1, edge, true));
    assert_eq!(m.ne, Some(3.0));
    assert!(m.success);
    // With a collision under fail_on_collision (Strict applied after the fact): failure.
    let mut t = Trajectory::from_positions(1, there, true);
    t.collisions = 2;
    let strict = MetricsConfig {
        fail_on_collision: true,
        ..Default::default()
    };
    let m = score_episode(&ep, &t, &GoalDistances::euclidean(&ep), &strict);
    assert!(!m.success && m.oracle_success);
    assert!((m.cr - 2.0 / 24.0).abs() < 1e-6);
}

#[test]
fn unreachable_goals_are_flagged_and_aggregates_stay_finite() {
    // A wall at x = 5: the goal cannot be reached from points beyond it.
    let goal = [2.0, 0.0, 0.0];
    let walled: Arc<dyn GoalDistance> =
        Arc::new(move |p: [f32; 3]| (p[0] < 5.0).then(|| (p[0] - goal[0]).abs()));
    let ep = episode(O, goal, 2.0);
    let d = GoalDistances {
        goal: walled,
        sub_goals: vec![],
    };
    let cfg = MetricsConfig::default();
    let beyond = Trajectory::from_positions(1, vec![[6.0, 0.0, 0.0], [7.0, 0.0, 0.0]], true);
    let bad = score_episode(&ep, &beyond, &d, &cfg);
    assert!(bad.unreachable && bad.ne.is_none() && bad.oracle_ne.is_none());
    assert!(!bad.success && !bad.oracle_success);
    let good = score_episode(&ep, &Trajectory::from_positions(1, vec![O], true), &d, &cfg);
    assert!(!good.unreachable && good.success);

    let s = aggregate(&[bad.clone(), good]);
    assert_eq!((s.episodes, s.unreachable), (2, 1));
    assert_eq!(s.ne, Some(2.0), "NE averages the reachable episode only");
    assert_eq!(s.sr, 0.5, "the unreachable episode counts as a failure");
    let only_bad = aggregate(&[bad]);
    assert_eq!(only_bad.ne, None);
    for v in [
        only_bad.tl,
        only_bad.sr,
        only_bad.spl,
        only_bad.ndtw,
        only_bad.cr,
    ] {
        assert!(v.is_finite());
    }
    let json = serde_json::to_string(&only_bad).unwrap();
    assert!(json.contains("\"ne\":null"), "{json}");
    assert_eq!(aggregate(&[]).episodes, 0);
}

fn long_horizon(goals: &[[f32; 3]]) -> Episode {
    let mut ep = episode(O, *goals.last().unwrap(), 20.0);
    ep.task = Task::LongHorizon;
    ep.sub_goals = goals
        .iter()
        .map(|&position| Goal {
            position,
            radius: 3.0,
            object_id: None,
        })
        .collect();
    ep
}

fn chain(stops: &[[f32; 3]]) -> Trajectory {
    // Walks from the origin through each stop point, issuing STOP there.
    let mut positions = vec![O];
    let mut idx = Vec::new();
    for &s in stops {
        positions.push(s);
        idx.push((positions.len() - 1) as u32);
    }
    let mut t = Trajectory::from_positions(1, positions, true);
    t.stops = idx;
    t
}

#[test]
fn conditional_sr_n_follows_the_order_of_goals() {
    let (g1, g2, g3) = ([4.0, 0.0, 0.0], [4.0, 0.0, 8.0], [12.0, 0.0, 8.0]);
    let far = [30.0, 0.0, 30.0];
    let three = long_horizon(&[g1, g2, g3]);
    let two = long_horizon(&[g1, g2]);
    let ms = [
        score(&three, &chain(&[g1, g2, g3])),  // A: all three
        score(&three, &chain(&[g1, far, g3])), // B: first only
        score(&three, &chain(&[far, g2, g3])), // C: misses the first, later ones do not count
        score(&two, &chain(&[g1, g2])),        // D: both of two
    ];
    let reached: Vec<u32> = ms.iter().map(|m| m.sub_goals_reached).collect();
    assert_eq!(reached, [3, 1, 0, 2]);
    let success: Vec<bool> = ms.iter().map(|m| m.success).collect();
    assert_eq!(success, [true, false, false, true]);
    let s = aggregate(&ms);
    assert_eq!(s.sr_1, Some(0.75)); // A, B, D of 4
    assert!((s.sr_2.unwrap() - 2.0 / 3.0).abs() < 1e-12); // A, D of those that reached 1: A, B, D
    assert_eq!(s.sr_3, Some(1.0)); // A of the three-goal chains that reached 2: A
    assert_eq!(s.sr_all, Some(0.5));
    assert_eq!(s.sr, 0.5);
    // Without the stop list only the final STOP exists: it is judged against goal 1.
    let mut t = chain(&[g1, g2, g3]);
    t.stops.clear();
    assert_eq!(score(&three, &t).sub_goals_reached, 0);
    // Tasks without sub-goals have no SR_n keys.
    let plain = aggregate(&[score(&episode(O, g1, 4.0), &chain(&[g1]))]);
    assert_eq!((plain.sr_1, plain.sr_all), (None, None));
}

#[test]
fn stuck_needs_a_still_window_and_headings() {
    let still = vec![O; 25];
    let turning: Vec<f32> = (0..25).map(|i| (i as f32 * 15.0).to_radians()).collect();
    let fixed = vec![0.3f32; 25];
    assert!(is_stuck(&still, &fixed, 20, 0.2, 15.0));
    assert!(
        !is_stuck(&still, &turning, 20, 0.2, 15.0),
        "turning in place is not stuck"
    );
    let moving: Vec<[f32; 3]> = (0..25).map(|i| [0.25 * i as f32, 0.0, 0.0]).collect();
    assert!(!is_stuck(&moving, &fixed, 20, 0.2, 15.0));
    assert!(
        !is_stuck(&still[..20], &fixed[..20], 20, 0.2, 15.0),
        "shorter than the window"
    );
    // Headings wrap: oscillating across +-pi is a small turn.
    let wrap: Vec<f32> = (0..25)
        .map(|i| (std::f32::consts::PI - 0.001) * if i % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    assert!(is_stuck(&still, &wrap, 20, 0.2, 15.0));

    let ep = episode(O, [5.0, 0.0, 0.0], 5.0);
    let mut t = Trajectory::from_positions(1, still, false);
    assert_eq!(score(&ep, &t).stuck, None);
    t.headings = Some(fixed);
    assert_eq!(score(&ep, &t).stuck, Some(true));
}
