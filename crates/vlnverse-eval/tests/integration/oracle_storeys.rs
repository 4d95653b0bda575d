//! The dialogue oracle and the teacher's field in a home on two floors: from the ground floor
//! "which way" leads to the stairs and says to go up; "am I close" counts the walk through the
//! stairs; upstairs the answers are those of one floor.

use std::sync::Arc;

use glam::Vec2;
use vlnverse_env::geodesic::{LevelField, LevelPoint, MultiLevelMap};
use vlnverse_env::occupancy::{build_level_maps, OccupancyConfig};
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::SceneSource;
use vlnverse_eval::oracle::{Oracle, OracleAnswer, OracleConfig, OracleQuery, ShortestPathOracle};
use vlnverse_procgen::{HomeGenerator, Preset};

#[test]
fn the_dialogue_oracle_sends_an_agent_downstairs_up_the_stairs() {
    let mut pc = Preset::Tiny.config().unwrap();
    pc.scenes.count = 1;
    pc.floors.two_storey_share = 1.0;
    let scene = HomeGenerator::new(pc).unwrap().scene(0).unwrap();
    assert!(scene.is_multi_level());
    let cfg = OccupancyConfig::default();
    let maps = build_level_maps(&scene, &cfg).unwrap();
    let multi = MultiLevelMap::from_scene(&scene, &cfg).unwrap();
    let free = |l: usize| -> Vec<Vec2> {
        let n = &maps[l].navigable;
        n.free_cells().map(|(c, r)| n.cell_center(c, r)).collect()
    };
    let (down, up) = (free(0), free(1));
    let h1 = scene.level_height(1).unwrap();
    let goal = up[up.len() / 2];
    let heights = [scene.floor_height, h1];
    let half: Vec<f32> = scene.storeys.stairs.iter().map(|s| 0.5 * s.width).collect();
    let lf = Arc::new(
        LevelField::new(&multi, &heights, &half, LevelPoint::new(1, goal.x, goal.y)).unwrap(),
    );
    let mut o = ShortestPathOracle::new(
        Arc::new(scene.clone()),
        Arc::new(SceneGraph::build(&scene)),
        Arc::new(maps[1].navigable.clone()),
        [goal.x, h1, goal.y],
        None,
        OracleConfig {
            budget: 10,
            ..Default::default()
        },
    )
    .unwrap()
    .with_levels(lf.clone());
    let start = down[down.len() / 3];
    let at = [start.x, scene.floor_height, start.y];
    let ans: OracleAnswer = o.ask(&OracleQuery::WhichWay, at, 0.0).unwrap();
    assert!(ans.text.contains("up the stairs"), "{}", ans.text);
    let close = o.ask(&OracleQuery::AmIClose, at, 0.0).unwrap();
    let want = multi
        .geodesic_distance(
            LevelPoint::new(0, start.x, start.y),
            LevelPoint::new(1, goal.x, goal.y),
        )
        .unwrap()
        .meters()
        .unwrap();
    let got = close.distance_m.unwrap();
    assert!((got - want).abs() < 0.3, "{got} vs {want}");
    // On the goal's floor, a step or so from the goal (by the walk, not through a wall): no
    // stairs.
    let walk_to_goal = |p: Vec2| {
        multi
            .geodesic_distance(
                LevelPoint::new(1, p.x, p.y),
                LevelPoint::new(1, goal.x, goal.y),
            )
            .ok()
            .and_then(|d| d.meters())
    };
    let near = *up
        .iter()
        .find(|p| walk_to_goal(**p).is_some_and(|d| (0.3..1.5).contains(&d)))
        .expect("a free cell a step from the goal");
    let ans = o
        .ask(&OracleQuery::WhichWay, [near.x, h1, near.y], 0.0)
        .unwrap();
    assert!(!ans.text.contains("stairs"), "{}", ans.text);
    assert!(ans.distance_m.unwrap() < 2.0);
}
