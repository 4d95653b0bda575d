//! How object goals are drawn: small objects a third as often as furniture.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use vlnverse_env::ClassKind;
use vlnverse_generate::{SamplingConfig, SceneSampler};

#[test]
fn small_objects_are_drawn_a_third_as_often_as_furniture() {
    let w = &vlnverse_testkit::homes::worlds(1)[0];
    let cfg = SamplingConfig {
        max_attempts: 50,
        goal_max_distance: 1.0,
        goal_min_distance: 0.2,
        max_targets: 0,
        cross_floor_share: 0.3,
    };
    let sampler = SceneSampler::new(&w.scene, &w.maps, &w.graph, &cfg, 7);
    let kind = |id| w.scene.object(id).map(|o| o.class.kind());
    let small = |t: &&vlnverse_generate::TargetSpot| kind(t.object) == Some(ClassKind::Small);
    let n_small = sampler.targets().iter().filter(small).count() as f64;
    let n_all = sampler.targets().len() as f64;
    assert!(
        n_small > 0.0 && n_small < n_all,
        "home needs both kinds of target"
    );
    // Expected share of small objects among draws: s/3 / (s/3 + f).
    let expected = (n_small / 3.0) / (n_small / 3.0 + (n_all - n_small));
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let draws = 6000;
    let mut hits = 0usize;
    for _ in 0..draws {
        let t = sampler.draw_target(&mut rng).expect("targets exist");
        assert!(sampler.targets().iter().any(|x| x.object == t.object));
        hits += usize::from(kind(t.object) == Some(ClassKind::Small));
    }
    let share = hits as f64 / draws as f64;
    assert!(
        (share - expected).abs() < 0.04,
        "small share {share:.3}, expected {expected:.3}"
    );
}
