//! Property tests of the metrics.

use proptest::prelude::*;
use vlnverse_score::metrics::{
    aggregate, ndtw, resample, score_episode, GoalDistances, MetricsConfig,
};
use vlnverse_score::{Episode, EpisodeInfo, Goal, Trajectory};

fn point() -> impl Strategy<Value = [f32; 3]> {
    (-3.0f32..3.0, -0.1f32..0.1, -3.0f32..3.0).prop_map(|(x, y, z)| [x, y, z])
}

fn path(max: usize) -> impl Strategy<Value = Vec<[f32; 3]>> {
    prop::collection::vec(point(), 1..max)
}

fn episode(reference: Vec<[f32; 3]>, geodesic: f32) -> Episode {
    Episode {
        episode_id: 0,
        trajectory_id: 0,
        scene_id: "p".into(),
        start_position: reference[0],
        goals: vec![Goal {
            position: *reference.last().unwrap(),
            radius: 3.0,
            object_id: None,
        }],
        reference_path: reference,
        info: EpisodeInfo {
            geodesic_distance: geodesic,
            ..Default::default()
        },
        ..Default::default()
    }
}

proptest! {
    #[test]
    fn ndtw_is_in_unit_interval_and_one_on_the_reference(r in path(7), q in path(7)) {
        let v = ndtw(&r, &q, 3.0);
        prop_assert!(v > 0.0 && v <= 1.0, "ndtw {v}");
        prop_assert_eq!(ndtw(&r, &r, 3.0), 1.0);
        let (rr, rq) = (resample(&r, 0.25), resample(&q, 0.25));
        let w = ndtw(&rr, &rq, 3.0);
        prop_assert!((0.0..=1.0).contains(&w), "resampled ndtw {w}");
        prop_assert_eq!(ndtw(&rr, &rr, 3.0), 1.0);
    }

    #[test]
    fn spl_never_exceeds_success(
        r in path(6),
        q in path(12),
        geodesic in 0.0f32..12.0,
        stopped in any::<bool>(),
    ) {
        let ep = episode(r, geodesic);
        let t = Trajectory::from_positions(0, q.clone(), stopped);
        let m = score_episode(&ep, &t, &GoalDistances::euclidean(&ep), &MetricsConfig::default());
        let s = if m.success { 1.0 } else { 0.0 };
        prop_assert!(m.spl >= 0.0 && m.spl <= s, "spl {} success {}", m.spl, m.success);
        // >= 0: a long detour from a one-point reference may underflow exp() to 0 in f32.
        prop_assert!(m.sdtw <= m.ndtw && m.ndtw >= 0.0 && m.ndtw <= 1.0);
        prop_assert!(!m.success || m.oracle_success, "SR implies OSR");
        // Following the reference exactly scores nDTW 1.
        let exact = Trajectory::from_positions(0, ep.reference_path.clone(), true);
        let e = score_episode(&ep, &exact, &GoalDistances::euclidean(&ep), &MetricsConfig::default());
        prop_assert!((e.ndtw - 1.0).abs() < 1e-6, "ndtw on the reference {}", e.ndtw);
        let agg = aggregate(&[m, e]);
        prop_assert!(agg.spl <= agg.sr && agg.osr >= agg.sr);
    }
}
