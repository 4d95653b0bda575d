//! What a room's openings and fixtures say about it, as people put it: how many doorways lead
//! out of a room just entered ("The room has three doors, two of them closed."), the rooms
//! they lead to ("two bedrooms and a bathroom"), and whether a bathroom is a half bath (a toilet and a sink, no bathtub or shower: "the powder
//! room").

use super::lexicon::{number_word, plural};
use glam::Vec2;
use vlnverse_env::{Door, RoomId, RoomType, Scene, SemanticClass as C};

/// How the openings of a room are counted in a remark.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OpeningCount {
    /// Every opening has a door leaf: `total` doors, `closed` of them shut.
    Doors { total: usize, closed: usize },
    /// No leaf in some, but none is an open-plan connection: doorways.
    Doorways(usize),
    /// Some are open-plan connections: openings.
    Openings(usize),
}

/// The openings of `room` (doors, doorways, open-plan connections), in the scene's order.
pub(crate) fn openings_of(scene: &Scene, room: RoomId) -> impl Iterator<Item = &Door> {
    scene.doors.iter().filter(move |d| d.rooms.contains(&room))
}

/// The openings of `room` as a remark counts them, when there are two to five (one goes
/// without saying, more is a list nobody reads); `None` otherwise.
pub(crate) fn opening_count(scene: &Scene, room: RoomId) -> Option<OpeningCount> {
    let doors: Vec<&Door> = openings_of(scene, room).collect();
    if !(2..=5).contains(&doors.len()) {
        return None;
    }
    let n = doors.len();
    Some(if doors.iter().all(|d| d.leaf.is_some()) {
        OpeningCount::Doors {
            total: n,
            closed: doors.iter().filter(|d| d.is_closed()).count(),
        }
    } else if doors.iter().any(|d| d.open_plan) {
        OpeningCount::Openings(n)
    } else {
        OpeningCount::Doorways(n)
    })
}

/// The rooms the openings of `room` lead to, said as people list them ("two bedrooms, a
/// bathroom and a closet"): by type in the order of the openings, a number and the plural
/// for several of one type. `None` unless two to five other rooms open off it.
pub(crate) fn rooms_off(scene: &Scene, room: RoomId) -> Option<String> {
    let mut others: Vec<RoomId> = Vec::new();
    for d in openings_of(scene, room) {
        for &r in &d.rooms {
            if r != room && !others.contains(&r) {
                others.push(r);
            }
        }
    }
    if !(2..=5).contains(&others.len()) {
        return None;
    }
    let mut kinds: Vec<(RoomType, u32)> = Vec::new();
    for r in others {
        let kind = scene.room(r)?.kind;
        match kinds.iter_mut().find(|(k, _)| *k == kind) {
            Some((_, n)) => *n += 1,
            None => kinds.push((kind, 1)),
        }
    }
    let items: Vec<String> = kinds
        .iter()
        .map(|&(k, n)| {
            let w = k.words();
            if n == 1 {
                let an = if w.starts_with(['a', 'e', 'i', 'o', 'u']) {
                    "an"
                } else {
                    "a"
                };
                format!("{an} {w}")
            } else {
                format!("{} {}", number_word(n), plural(&w))
            }
        })
        .collect();
    Some(match items.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => return None,
    })
}

/// How the opening `door` of `room` stands among the room's openings seen from `p` (a point
/// in the room): the only one, or the nearest by at least a metre.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Nearest {
    /// The room's only opening.
    Only,
    /// The nearest to `p`, every other at least a metre further.
    Nearest,
}

/// Whether `door` is the only opening of `room` or the clearly nearest one to `p`.
pub(crate) fn nearest_opening(
    scene: &Scene,
    room: RoomId,
    door: &Door,
    p: Vec2,
) -> Option<Nearest> {
    let dist = |d: &Door| Vec2::new(d.position[0], d.position[2]).distance(p);
    let mut others = openings_of(scene, room)
        .filter(|d| d.id != door.id)
        .peekable();
    if others.peek().is_none() {
        return Some(Nearest::Only);
    }
    let own = dist(door);
    others
        .all(|d| dist(d) >= own + 1.0)
        .then_some(Nearest::Nearest)
}

/// Whether `room` is a bathroom with a toilet and a sink but neither a bathtub nor a shower:
/// what people call a half bath or a powder room.
pub(crate) fn is_half_bath(scene: &Scene, room: RoomId) -> bool {
    if scene.room(room).map(|r| r.kind) != Some(RoomType::Bathroom) {
        return false;
    }
    let holds = |c: C| {
        scene
            .objects
            .iter()
            .any(|o| o.room == Some(room) && o.class == c)
    };
    holds(C::Toilet) && holds(C::Sink) && !holds(C::Bathtub) && !holds(C::Shower)
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_env::SceneSource;
    use vlnverse_procgen::{HomeGenerator, Preset};

    fn scenes() -> Vec<Scene> {
        let g = HomeGenerator::from_preset(Preset::Tiny).unwrap();
        (0..g.len()).map(|i| g.scene(i).unwrap()).collect()
    }

    #[test]
    fn a_count_names_every_opening_of_the_room_and_its_closed_doors() {
        let mut seen = 0;
        for scene in scenes() {
            for r in &scene.rooms {
                let all: Vec<&Door> = openings_of(&scene, r.id).collect();
                assert!(all.iter().all(|d| d.rooms.contains(&r.id)));
                match opening_count(&scene, r.id) {
                    None => assert!(!(2..=5).contains(&all.len())),
                    Some(OpeningCount::Doors { total, closed }) => {
                        seen += 1;
                        assert_eq!(total, all.len());
                        assert!(all.iter().all(|d| d.leaf.is_some()));
                        assert_eq!(closed, all.iter().filter(|d| d.is_closed()).count());
                    }
                    Some(OpeningCount::Doorways(n)) => {
                        seen += 1;
                        assert_eq!(n, all.len());
                        assert!(all.iter().all(|d| !d.open_plan));
                        assert!(all.iter().any(|d| d.leaf.is_none()));
                    }
                    Some(OpeningCount::Openings(n)) => {
                        seen += 1;
                        assert_eq!(n, all.len());
                        assert!(all.iter().any(|d| d.open_plan));
                    }
                }
            }
        }
        assert!(
            seen > 0,
            "no room with two to five openings in the tiny homes"
        );
    }

    #[test]
    fn the_rooms_off_a_room_are_listed_by_type_with_their_numbers() {
        let g = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
        let mut listed = 0;
        for i in 0..6 {
            let scene = g.scene(i).unwrap();
            for r in &scene.rooms {
                let Some(list) = rooms_off(&scene, r.id) else {
                    continue;
                };
                listed += 1;
                let mut others: Vec<RoomId> = openings_of(&scene, r.id)
                    .flat_map(|d| d.rooms)
                    .filter(|&x| x != r.id)
                    .collect();
                others.sort_unstable();
                others.dedup();
                assert!((2..=5).contains(&others.len()), "{list}");
                for x in others {
                    let w = scene.room(x).unwrap().kind.words();
                    assert!(list.contains(&w), "{list} lacks {w}");
                }
            }
        }
        assert!(listed > 0);
    }

    #[test]
    fn the_nearest_opening_is_a_metre_nearer_than_every_other() {
        for scene in scenes() {
            for r in &scene.rooms {
                let all: Vec<&Door> = openings_of(&scene, r.id).collect();
                let Some(first) = all.first() else { continue };
                let c = Vec2::new(first.position[0], first.position[2]);
                // Standing in its doorway, an opening is the nearest unless another is close.
                let got = nearest_opening(&scene, r.id, first, c);
                if all.len() == 1 {
                    assert_eq!(got, Some(Nearest::Only));
                    continue;
                }
                let clear = all[1..]
                    .iter()
                    .all(|d| Vec2::new(d.position[0], d.position[2]).distance(c) >= 1.0);
                assert_eq!(got == Some(Nearest::Nearest), clear);
            }
        }
    }

    #[test]
    fn a_half_bath_is_a_bathroom_without_a_tub_or_a_shower() {
        for scene in scenes() {
            for r in &scene.rooms {
                let has = |c: C| {
                    scene
                        .objects
                        .iter()
                        .any(|o| o.room == Some(r.id) && o.class == c)
                };
                let half = is_half_bath(&scene, r.id);
                if half {
                    assert_eq!(r.kind, RoomType::Bathroom);
                    assert!(has(C::Toilet) && has(C::Sink));
                }
                if has(C::Bathtub) || has(C::Shower) || r.kind != RoomType::Bathroom {
                    assert!(!half);
                }
            }
        }
    }
}
