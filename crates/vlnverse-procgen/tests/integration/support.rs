//! Helpers for checking homes that may stand on two floors: each floor's view, the rooms a
//! flight of stairs joins, and reachability through doors and stairs.

use rayon::prelude::*;
use std::collections::VecDeque;
use vlnverse_env::{Door, LevelId, RoomId, Scene, SceneObject, SemanticClass as C};
use vlnverse_procgen::{door_clearance, scene_seed, HomeGenerator, ProcgenConfig};

/// Each floor of a home as a scene of its own (`Scene::level_view`), the ground floor first.
pub fn floors(s: &Scene) -> Vec<Scene> {
    (0..s.level_count() as LevelId)
        .map(|k| s.level_view(k).expect("a level the scene has"))
        .collect()
}

/// The level a door stands on (both its rooms are on it).
pub fn door_level(s: &Scene, d: &Door) -> LevelId {
    s.room_level(d.rooms[0]).expect("a door's room has a level")
}

/// The two rooms each flight joins: the one at its foot and the one at its head.
pub fn stair_links(s: &Scene) -> Vec<[RoomId; 2]> {
    s.storeys
        .stairs
        .iter()
        .map(|st| {
            let at = |level, p: [f32; 3]| {
                s.room_at_level(level, p[0], p[2])
                    .unwrap_or_else(|| panic!("{}: stairs {} end in no room", s.id, st.id))
                    .id
            };
            [at(st.levels[0], st.foot), at(st.levels[1], st.head)]
        })
        .collect()
}

/// Whether every room reaches every other through doorways (closed doors too when
/// `through_closed`) and flights of stairs. Room ids are indices into `s.rooms`.
pub fn rooms_connected(s: &Scene, through_closed: bool) -> bool {
    let mut links: Vec<[RoomId; 2]> = s
        .doors
        .iter()
        .filter(|d| through_closed || !d.is_closed())
        .map(|d| d.rooms)
        .collect();
    links.extend(stair_links(s));
    let n = s.rooms.len();
    let mut seen = vec![false; n];
    let mut q = VecDeque::from([0usize]);
    seen[0] = true;
    while let Some(r) = q.pop_front() {
        for [a, b] in links.iter().map(|l| l.map(|x| x as usize)) {
            for (p, o) in [(a, b), (b, a)] {
                if p == r && !seen[o] {
                    seen[o] = true;
                    q.push_back(o);
                }
            }
        }
    }
    seen.iter().all(|&x| x)
}

/// The ground floor's stair hall (the room at the foot of the first flight), if any.
pub fn stair_hall(s: &Scene) -> Option<RoomId> {
    stair_links(s).first().map(|l| l[0])
}

/// Rooms drawn by the floorplan on the ground floor: its rooms but the stair hall.
pub fn ground_plan_rooms(s: &Scene) -> Vec<&vlnverse_env::Room> {
    let hall = stair_hall(s);
    s.rooms
        .iter()
        .filter(|r| s.room_level(r.id) == Some(0) && Some(r.id) != hall)
        .collect()
}

/// The first `n` homes of `cfg` (as the preset's own scenes with that config: `home_0000`, ...,
/// each from the config's base seed), generated in parallel.
pub fn first_homes(cfg: ProcgenConfig, n: usize) -> Vec<Scene> {
    let base = cfg.scenes.seed;
    let g = HomeGenerator::new(cfg).expect("config");
    (0..n)
        .into_par_iter()
        .map(|i| {
            g.generate(scene_seed(base, i), &format!("home_{i:04}"))
                .expect("scene")
        })
        .collect()
}

/// Asserts that the open door leaf `o` stands in no doorway's clearance box (`clearance` deep,
/// as `door_clearance` draws it): not in its own doorway's passage nor in front of another.
pub fn assert_leaf_clear_of_doorways(s: &Scene, o: &SceneObject, clearance: f32) {
    for e in &s.doors {
        let zone = door_clearance(e, clearance, 2.0);
        assert!(
            !o.bbox.intersects(&zone, 1e-3),
            "{}: open leaf {} in the clearance of door {}",
            s.id,
            o.name,
            e.id
        );
    }
}

/// Asserts that the door leaf `o` overlaps no other object but rugs.
pub fn assert_leaf_touches_nothing(s: &Scene, o: &SceneObject) {
    for other in s.items().filter(|x| x.id != o.id && x.class != C::Rug) {
        assert!(
            !o.bbox.intersects(&other.bbox, 1e-3),
            "{}: {} intersects {}",
            s.id,
            o.name,
            other.name
        );
    }
}
