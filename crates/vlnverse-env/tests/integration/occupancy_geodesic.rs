//! Geodesic distances on navigable maps of hand-made scenes.

use crate::occupancy_fixtures;

use glam::Vec2;
use occupancy_fixtures::*;
use vlnverse_env::geodesic::{
    geodesic_distance, shortest_path, DistanceField, GeodesicCache, GeodesicDistance,
};
use vlnverse_env::occupancy::{build_maps, GridMap, OccupancyConfig};
use vlnverse_env::EnvError;

fn navigable(scene: &vlnverse_env::Scene) -> GridMap {
    build_maps(scene, &OccupancyConfig::default())
        .expect("maps")
        .navigable
}

fn meters(d: GeodesicDistance) -> f32 {
    d.meters().expect("reachable")
}

/// Deterministic navigable points on a lattice.
fn lattice(map: &GridMap, step: f32) -> Vec<Vec2> {
    let (lo, hi) = map.bounds();
    let mut out = Vec::new();
    let mut z = lo.y + 0.013;
    while z < hi.y {
        let mut x = lo.x + 0.027;
        while x < hi.x {
            let p = Vec2::new(x, z);
            if map.is_free_at(p) {
                out.push(p);
            }
            x += step;
        }
        z += step;
    }
    out
}

#[test]
fn open_space_geodesic_is_euclidean() {
    let map = navigable(&open_room(10.0));
    let pts = lattice(&map, 0.77);
    assert!(pts.len() > 100);
    let goal = pts[pts.len() / 3];
    let field = DistanceField::new(&map, goal).expect("field");
    for &p in &pts {
        let e = p.distance(goal);
        let a = meters(geodesic_distance(&map, p, goal).expect("query"));
        let f = meters(field.distance(p));
        assert!(
            (a - e).abs() <= 0.01 * e + 1e-4,
            "A* {a} vs euclid {e} from {p}"
        );
        assert!(
            (f - e).abs() <= 0.01 * e + 1e-4,
            "field {f} vs euclid {e} from {p}"
        );
    }
}

/// Length of the shortest path from `s` to `g` (on either side of the wall x = 5, below its
/// tip) around the tip of the wall, an obstacle [4.95, 5.05] x [.., 7.05] grown by `r`.
fn around_wall_tip(s: Vec2, g: Vec2, r: f32) -> f32 {
    let half = |p: Vec2, c: Vec2| {
        let v = p - c;
        let d = v.length();
        let tangent = (d * d - r * r).sqrt();
        // Angle from `v` to straight up (+z), minus the angle the tangent line already covers.
        let alpha = (v.y / d).acos();
        let arc = alpha - (r / d).acos();
        tangent + r * arc
    };
    half(s, Vec2::new(4.95, 7.05)) + half(g, Vec2::new(5.05, 7.05)) + 0.1
}

#[test]
fn path_around_a_wall_matches_the_hand_computed_length() {
    let map = navigable(&room_with_long_wall());
    let (s, g) = (Vec2::new(3.0, 2.0), Vec2::new(7.0, 2.0));
    // Continuous agent of radius 0.3; the grid adds up to 1.5 cells of margin.
    let lo = around_wall_tip(s, g, 0.3);
    let hi = around_wall_tip(s, g, 0.3 + 1.5 * map.resolution);
    assert!(lo > 11.0 && lo < 12.0, "hand computation {lo}");
    let path = shortest_path(&map, s, g)
        .expect("query")
        .expect("reachable");
    assert!(
        path.length >= lo * 0.999 && path.length <= hi * 1.005,
        "A* {} not in [{lo}, {hi}]",
        path.length
    );
    // An 8-connected grid path would be several percent longer than the any-angle length.
    assert!(path.length < lo * 1.02);
    assert_eq!(path.points.first(), Some(&s));
    assert_eq!(path.points.last(), Some(&g));
    for w in path.points.windows(2) {
        assert!(
            map.line_of_sight(w[0], w[1]),
            "segment {} -> {} blocked",
            w[0],
            w[1]
        );
    }
    // The path passes above the tip of the wall.
    assert!(path.points.iter().any(|p| p.y > 7.3));
    let field = DistanceField::new(&map, g).expect("field");
    let f = meters(field.distance(s));
    assert!(
        (f - path.length).abs() <= 0.01 * path.length,
        "field {f} vs A* {}",
        path.length
    );
}

#[test]
fn distance_field_agrees_with_astar() {
    for scene in [room_with_long_wall(), two_rooms(0.9)] {
        let map = navigable(&scene);
        let pts = lattice(&map, 0.61);
        let goals: Vec<Vec2> = pts.iter().step_by(pts.len() / 6).copied().collect();
        for goal in goals {
            let field = DistanceField::new(&map, goal).expect("field");
            for &p in pts.iter().step_by(3) {
                let a = meters(geodesic_distance(&map, p, goal).expect("query"));
                let f = meters(field.distance(p));
                let e = p.distance(goal);
                assert!(a >= e * 0.9999 - 1e-4 && f >= e * 0.9999 - 1e-4);
                assert!(
                    (a - f).abs() <= 0.01 * a.max(f) + 1e-3,
                    "{}: A* {a} vs field {f} from {p} to {goal}",
                    scene.id
                );
            }
        }
    }
}

#[test]
fn following_the_field_reaches_the_goal() {
    let map = navigable(&room_with_long_wall());
    let (s, g) = (Vec2::new(2.0, 1.0), Vec2::new(8.5, 1.5));
    let field = DistanceField::new(&map, g).expect("field");
    let total = meters(field.distance(s));
    let path = field.path(s).expect("path");
    assert!((path.length - total).abs() < 1e-3 * total);
    assert_eq!(path.points.first(), Some(&s));
    assert_eq!(path.points.last(), Some(&g));
    let mut p = s;
    let mut walked = 0.0;
    for _ in 0..50 {
        if p == g {
            break;
        }
        let next = field.next_waypoint(p).expect("waypoint");
        assert!(map.line_of_sight(p, next));
        // Each waypoint gets closer to the goal geodesically.
        assert!(meters(field.distance(next)) < meters(field.distance(p)));
        walked += p.distance(next);
        p = next;
    }
    assert_eq!(p, g);
    assert!(
        (walked - total).abs() < 0.01 * total,
        "walked {walked} vs {total}"
    );
}

#[test]
fn unreachable_is_explicit() {
    let map = navigable(&room_and_closed_room());
    let inside = Vec2::new(3.0, 2.5);
    let cases = [
        (CLOSED_ROOM, "other island"),
        (Vec2::new(100.0, 2.0), "outside the map"),
        (
            Vec2::new(0.0, 2.5),
            "inside a wall, beyond the snap distance",
        ),
        (Vec2::new(7.8, 3.5), "outside the floor"),
    ];
    for (p, what) in cases {
        assert_eq!(
            geodesic_distance(&map, inside, p).expect("query"),
            GeodesicDistance::Unreachable,
            "{what}"
        );
        assert_eq!(
            geodesic_distance(&map, p, inside).expect("query"),
            GeodesicDistance::Unreachable,
            "{what} (as start)"
        );
        assert!(shortest_path(&map, inside, p).expect("query").is_none());
        let field = DistanceField::new(&map, inside).expect("field");
        assert_eq!(field.distance(p), GeodesicDistance::Unreachable, "{what}");
        assert_eq!(field.next_waypoint(p), None);
        let unreachable_goal = DistanceField::new(&map, p).expect("field");
        assert_eq!(
            unreachable_goal.distance(inside),
            GeodesicDistance::Unreachable
        );
        assert_eq!(unreachable_goal.reachable_cells(), 0);
        let mut cache = GeodesicCache::new(map.clone(), 4);
        assert_eq!(
            cache.distance(inside, p).expect("query"),
            GeodesicDistance::Unreachable
        );
        assert_eq!(
            cache.distance(p, inside).expect("query"),
            GeodesicDistance::Unreachable
        );
    }
    assert!(!GeodesicDistance::Unreachable.is_reachable());
    assert_eq!(GeodesicDistance::Unreachable.meters(), None);
    // Same point: reachable with length 0, not "unreachable".
    assert_eq!(
        geodesic_distance(&map, inside, inside).expect("query"),
        GeodesicDistance::Reachable(0.0)
    );
}

#[test]
fn points_just_inside_the_margin_are_snapped() {
    let map = navigable(&open_room(5.0));
    // x = 0.32 lies in the dilation margin (navigable from x = 0.35); it snaps by ~5 cm.
    let p = Vec2::new(0.32, 2.5);
    assert!(!map.is_free_at(p));
    let goal = Vec2::new(4.0, 2.5);
    let d = meters(geodesic_distance(&map, p, goal).expect("query"));
    assert!(
        d >= p.distance(goal) - 1e-4 && d < p.distance(goal) + 0.05,
        "{d}"
    );
    let path = shortest_path(&map, p, goal).expect("query").expect("path");
    assert_eq!(path.points.first(), Some(&p));
    let f = meters(DistanceField::new(&map, goal).expect("field").distance(p));
    assert!((f - d).abs() < 0.01 * d);
    let back = meters(geodesic_distance(&map, goal, p).expect("query"));
    assert!((back - d).abs() < 0.01 * d);
}

#[test]
fn cache_reuses_fields_and_evicts_least_recently_used() {
    let map = navigable(&two_rooms(0.9));
    let mut cache = GeodesicCache::new(map.clone(), 2);
    let s = Vec2::new(1.0, 1.0);
    let (c, r) = map.world_to_cell(ROOM_B).expect("cell");
    let center = map.cell_center(c, r);
    let (g1, g2, g3) = (center - 0.01, Vec2::new(3.0, 3.0), Vec2::new(6.0, 3.5));
    let d1 = meters(cache.distance(s, g1).expect("query"));
    cache.distance(s, g2).expect("query");
    // Another goal point in the same cell as g1 reuses its field with its exact position.
    let g1b = center + 0.01;
    let d1b = meters(cache.distance(s, g1b).expect("query"));
    assert!((d1b - d1).abs() < 0.03);
    assert_eq!(cache.stats(), (1, 2));
    cache.distance(s, g3).expect("query"); // evicts g2, the least recently used
    assert_eq!(cache.len(), 2);
    cache.distance(s, g1).expect("query");
    assert_eq!(cache.stats(), (2, 3));
    cache.distance(s, g2).expect("query");
    assert_eq!(cache.stats(), (2, 4));
    let a = meters(geodesic_distance(&map, s, g1).expect("query"));
    assert!((a - d1).abs() <= 0.01 * a, "A* {a} vs cache {d1}");
    let p = cache.shortest_path(s, g1).expect("query").expect("path");
    assert!((p.length - d1).abs() < 1e-3 * d1);
}

#[test]
fn non_finite_points_are_errors_naming_the_argument() {
    let map = navigable(&open_room(3.0));
    let nan = Vec2::new(f32::NAN, 1.0);
    for (e, field) in [
        (
            geodesic_distance(&map, nan, Vec2::ONE).unwrap_err(),
            "start",
        ),
        (shortest_path(&map, Vec2::ONE, nan).unwrap_err(), "goal"),
        (DistanceField::new(&map, nan).unwrap_err(), "goal"),
        (
            GeodesicCache::new(map.clone(), 1)
                .distance(nan, Vec2::ONE)
                .unwrap_err(),
            "start",
        ),
    ] {
        match e {
            EnvError::InvalidConfig { field: f, .. } => assert_eq!(f, field),
            other => panic!("unexpected {other}"),
        }
    }
}
