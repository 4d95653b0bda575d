//! The default dialogue oracle on the tiny preset's homes: answers agree with the true remaining
//! path and the scene graph, and the budget is enforced.

use glam::Vec2;
use std::f32::consts::FRAC_PI_2;
use std::sync::Arc;
use vlnverse_env::geodesic::shortest_path;
use vlnverse_env::scene_graph::{side_of, yaw_from_direction};
use vlnverse_eval::oracle::{Oracle, OracleConfig, OracleQuery, ShortestPathOracle};
use vlnverse_score::route::{env_side, Turn};
use vlnverse_score::{Episode, Side};
use vlnverse_testkit::homes::{paths, worlds, World};

fn oracle(w: &World, goal: Vec2, budget: u32) -> ShortestPathOracle {
    ShortestPathOracle::new(
        Arc::new(w.scene.clone()),
        Arc::new(w.graph.clone()),
        Arc::new(w.maps.navigable.clone()),
        [goal.x, 0.0, goal.y],
        None,
        OracleConfig {
            budget,
            ..Default::default()
        },
    )
    .unwrap()
}

fn p3(p: Vec2) -> [f32; 3] {
    [p.x, 0.0, p.y]
}

/// The first waypoint of the true path at least 0.3 m from the start.
fn next_waypoint(w: &World, a: Vec2, b: Vec2) -> (Vec2, f32) {
    let path = shortest_path(&w.maps.navigable, a, b).unwrap().unwrap();
    let wp = *path
        .points
        .iter()
        .find(|q| q.distance(a) >= 0.3)
        .unwrap_or(&b);
    (wp, path.length)
}

#[test]
fn which_way_turns_towards_the_next_waypoint() {
    let mut checked = [0usize; 4];
    for (wi, w) in worlds(3).iter().enumerate() {
        for s in paths(w, 15, 200 + wi as u64) {
            let a = Vec2::new(s.path[0][0], s.path[0][2]);
            let b = Vec2::new(s.path.last().unwrap()[0], s.path.last().unwrap()[2]);
            let (wp, len) = next_waypoint(w, a, b);
            let facing = yaw_from_direction(wp - a);
            // Face the waypoint, then put it on the left, the right and behind.
            for (k, (yaw, want)) in [
                (facing, Side::Ahead),
                (facing - FRAC_PI_2, Side::Left),
                (facing + FRAC_PI_2, Side::Right),
                (facing + 2.0 * FRAC_PI_2, Side::Behind),
            ]
            .into_iter()
            .enumerate()
            {
                assert_eq!(env_side(side_of(a, yaw, wp)), want);
                let mut o = oracle(w, b, 5);
                let ans = o.ask(&OracleQuery::WhichWay, p3(a), yaw).unwrap();
                assert!(ans.answered, "{}", ans.text);
                assert!((ans.distance_m.unwrap() - len).abs() < 1e-3);
                let t = ans.text.to_lowercase();
                match want {
                    Side::Ahead => {
                        assert_eq!(ans.turn, Some(Turn::Straight), "{t}");
                        assert!(t.starts_with("go straight"), "{t}");
                    }
                    Side::Left => {
                        assert_eq!(ans.turn, Some(Turn::Turn(Side::Left)), "{t}");
                        assert!(t.starts_with("turn left"), "{t}");
                    }
                    Side::Right => {
                        assert_eq!(ans.turn, Some(Turn::Turn(Side::Right)), "{t}");
                        assert!(t.starts_with("turn right"), "{t}");
                    }
                    Side::Behind => {
                        assert_eq!(ans.turn, Some(Turn::Around), "{t}");
                        assert!(t.starts_with("turn around"), "{t}");
                    }
                }
                checked[k] += 1;
            }
        }
    }
    assert!(checked.iter().all(|&c| c >= 20), "{checked:?}");
}

#[test]
fn am_i_close_follows_the_geodesic_distance() {
    let w = &worlds(1)[0];
    let mut seen = [false; 5];
    for s in paths(w, 20, 300) {
        let b = Vec2::new(s.path.last().unwrap()[0], s.path.last().unwrap()[2]);
        // Points along the path: start, middle of each segment, the goal.
        let mut probes = vec![b];
        for seg in s.path.windows(2) {
            let (p, q) = (
                Vec2::new(seg[0][0], seg[0][2]),
                Vec2::new(seg[1][0], seg[1][2]),
            );
            probes.push(p);
            probes.push(p.lerp(q, 0.5));
        }
        for p in probes {
            let mut o = oracle(w, b, 5);
            let ans = o.ask(&OracleQuery::AmIClose, p3(p), 0.0).unwrap();
            let d = shortest_path(&w.maps.navigable, p, b)
                .unwrap()
                .unwrap()
                .length;
            assert!((ans.distance_m.unwrap() - d).abs() < 1e-3);
            let t = ans.text.to_lowercase();
            let bucket = if d <= 0.5 {
                assert!(t.contains("you are there"), "{d}: {t}");
                0
            } else if d <= 1.5 {
                assert!(t.contains("very close"), "{d}: {t}");
                1
            } else if d <= 3.0 {
                assert!(t.starts_with("you are close"), "{d}: {t}");
                2
            } else if d <= 6.0 {
                assert!(t.contains("not far"), "{d}: {t}");
                3
            } else {
                assert!(t.contains("still far"), "{d}: {t}");
                4
            };
            seen[bucket] = true;
            if bucket >= 2 {
                assert!(
                    t.contains(&format!("{} metres", d.round() as u32)),
                    "{d}: {t}"
                );
            }
        }
    }
    assert!(seen.iter().all(|&s| s), "{seen:?}");
}

#[test]
fn where_is_names_the_object_its_place_and_side() {
    let mut asked = 0;
    for (wi, w) in worlds(3).iter().enumerate() {
        let s = &paths(w, 1, 400 + wi as u64)[0];
        let a = Vec2::new(s.path[0][0], s.path[0][2]);
        let b = Vec2::new(s.path.last().unwrap()[0], s.path.last().unwrap()[2]);
        for o in w.scene.objects.iter().filter(|o| !o.is_structure()) {
            let mut orc = oracle(w, b, 100);
            let yaw = 0.7 * asked as f32;
            let ans = orc
                .ask(
                    &OracleQuery::WhereIs(format!("the {}", o.class.words())),
                    p3(a),
                    yaw,
                )
                .unwrap();
            assert!(ans.answered, "{}", ans.text);
            let id = ans.object_id.unwrap();
            let found = w.scene.object(id).unwrap();
            assert_eq!(found.class, o.class);
            let c = found.bbox.center();
            assert_eq!(
                ans.side,
                Some(env_side(side_of(a, yaw, Vec2::new(c.x, c.z))))
            );
            assert!(ans.text.contains(&found.class.words()), "{}", ans.text);
            let side_words = match ans.side.unwrap() {
                Side::Ahead => "ahead",
                Side::Left => "left",
                Side::Right => "right",
                Side::Behind => "behind",
            };
            assert!(ans.text.contains(side_words), "{}", ans.text);
            if let Some(r) = w.graph.room_of(id) {
                let here = w.scene.room_at(a.x, a.y).map(|r| r.id);
                if here != Some(r) {
                    assert!(
                        ans.text.contains(&w.scene.room(r).unwrap().kind.words()),
                        "{}",
                        ans.text
                    );
                }
            }
            // Of several objects with that class, the nearest one is described.
            let dist = |x: &vlnverse_env::SceneObject| {
                let c = x.bbox.center();
                Vec2::new(c.x, c.z).distance(a)
            };
            let nearest = w
                .scene
                .objects
                .iter()
                .filter(|x| x.class == o.class && w.graph.object(x.id).is_some())
                .map(dist)
                .fold(f32::INFINITY, f32::min);
            assert!((dist(found) - nearest).abs() < 1e-4);
            asked += 1;
        }
        // Unknown things and rooms.
        let mut orc = oracle(w, b, 100);
        let ans = orc
            .ask(&OracleQuery::WhereIs("spaceship".into()), p3(a), 0.0)
            .unwrap();
        assert!(
            !ans.answered && ans.text.contains("spaceship"),
            "{}",
            ans.text
        );
        let room = &w.scene.rooms[0];
        let ans = orc
            .ask(&OracleQuery::WhereIs(room.kind.words()), p3(a), 0.0)
            .unwrap();
        assert!(
            ans.answered && ans.text.contains(&room.kind.words()),
            "{}",
            ans.text
        );
    }
    assert!(asked >= 50, "{asked}");
}

#[test]
fn where_is_prefers_the_episode_target() {
    let w = &worlds(1)[0];
    // A class with at least two objects: the target is described even when farther away.
    let mut classes = std::collections::BTreeMap::new();
    for o in w
        .scene
        .objects
        .iter()
        .filter(|o| !o.is_structure() && w.graph.object(o.id).is_some())
    {
        classes.entry(o.class).or_insert_with(Vec::new).push(o.id);
    }
    let (class, ids) = classes
        .iter()
        .find(|(_, v)| v.len() >= 2)
        .expect("a repeated class");
    let s = &paths(w, 1, 5)[0];
    let a = Vec2::new(s.path[0][0], s.path[0][2]);
    for &target in ids {
        let mut o = ShortestPathOracle::new(
            Arc::new(w.scene.clone()),
            Arc::new(w.graph.clone()),
            Arc::new(w.maps.navigable.clone()),
            s.path[s.path.len() - 1],
            Some(target),
            OracleConfig::default(),
        )
        .unwrap();
        let ans = o
            .ask(&OracleQuery::WhereIs(class.words()), p3(a), 0.0)
            .unwrap();
        assert_eq!(ans.object_id, Some(target));
    }
}

#[test]
fn budget_is_enforced_and_reveals_nothing_after() {
    let w = &worlds(1)[0];
    let s = &paths(w, 1, 6)[0];
    let a = Vec2::new(s.path[0][0], s.path[0][2]);
    let b = Vec2::new(s.path.last().unwrap()[0], s.path.last().unwrap()[2]);
    let mut o = oracle(w, b, 3);
    assert_eq!(o.remaining(), 3);
    let queries = [
        OracleQuery::WhichWay,
        OracleQuery::AmIClose,
        OracleQuery::WhereIs(
            w.scene
                .objects
                .iter()
                .find(|o| !o.is_structure())
                .unwrap()
                .class
                .words(),
        ),
    ];
    for (k, q) in queries.iter().enumerate() {
        let ans = o.ask(q, p3(a), 0.0).unwrap();
        assert!(ans.answered, "{}", ans.text);
        assert_eq!(ans.remaining, 2 - k as u32);
        assert_eq!(o.remaining(), 2 - k as u32);
    }
    for q in &queries {
        let ans = o.ask(q, p3(a), 0.0).unwrap();
        assert!(!ans.answered);
        assert_eq!(ans.remaining, 0);
        assert!(
            ans.turn.is_none()
                && ans.distance_m.is_none()
                && ans.object_id.is_none()
                && ans.side.is_none()
        );
        assert!(ans.text.contains("all 3"), "{}", ans.text);
        // No number (a distance) leaks into the text besides the budget.
        assert!(!ans.text.contains("metre"));
    }
    // The default budget is 5, and an episode's own budget wins.
    let mut d = oracle(w, b, OracleConfig::default().budget);
    for _ in 0..5 {
        assert!(d.ask(&OracleQuery::AmIClose, p3(a), 0.0).unwrap().answered);
    }
    assert!(!d.ask(&OracleQuery::AmIClose, p3(a), 0.0).unwrap().answered);
    let json = format!(
        r#"{{"episode_id": 1, "scene_id": "x", "start_position": [{}, 0.0, {}],
        "start_rotation": [0,0,0,1], "goals": [{{"position": [{}, 0.0, {}], "radius": 3.0}}],
        "instruction": {{"instruction_text": "go"}}, "task": "dialogue", "oracle_budget": 2}}"#,
        a.x, a.y, b.x, b.y
    );
    let ep: Episode = serde_json::from_str(&json).unwrap();
    let mut e = ShortestPathOracle::for_episode(
        Arc::new(w.scene.clone()),
        Arc::new(w.graph.clone()),
        Arc::new(w.maps.navigable.clone()),
        &ep,
        OracleConfig::default(),
    )
    .unwrap();
    assert_eq!(e.remaining(), 2);
    let first = e
        .ask(&OracleQuery::AmIClose, ep.start_position, 0.0)
        .unwrap();
    assert!(first.answered);
}

#[test]
fn answers_are_deterministic_and_the_oracle_moves_across_threads() {
    let w = &worlds(1)[0];
    let s = &paths(w, 1, 8)[0];
    let a = Vec2::new(s.path[0][0], s.path[0][2]);
    let b = Vec2::new(s.path.last().unwrap()[0], s.path.last().unwrap()[2]);
    let mut o1: Box<dyn Oracle> = Box::new(oracle(w, b, 5));
    let mut o2 = oracle(w, b, 5);
    let local = o2.ask(&OracleQuery::WhichWay, p3(a), 0.4).unwrap();
    let remote = std::thread::spawn(move || o1.ask(&OracleQuery::WhichWay, p3(a), 0.4).unwrap())
        .join()
        .unwrap();
    assert_eq!(local, remote);
}

#[test]
fn bad_input_is_an_error_that_names_the_field() {
    let w = &worlds(1)[0];
    let mut o = oracle(w, Vec2::ZERO, 5);
    let e = o
        .ask(&OracleQuery::AmIClose, [f32::NAN, 0.0, 0.0], 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("position"), "{e}");
    let e = o
        .ask(&OracleQuery::AmIClose, [0.0, 0.0, 0.0], f32::INFINITY)
        .unwrap_err()
        .to_string();
    assert!(e.contains("yaw"), "{e}");
    assert_eq!(o.remaining(), 5, "invalid questions use no budget");
    let e = ShortestPathOracle::new(
        Arc::new(w.scene.clone()),
        Arc::new(w.graph.clone()),
        Arc::new(w.maps.navigable.clone()),
        [0.0, 0.0, 0.0],
        None,
        OracleConfig {
            buckets_m: [3.0, 1.0, 6.0],
            ..Default::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("oracle.buckets_m"), "{e}");
}
