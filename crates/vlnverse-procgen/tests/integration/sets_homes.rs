//! Furniture in sets (a matching second armchair, stools along an island, a double vanity,
//! twin beds, bedside sconces, two desks): placed from an rng of their own, so turning them on
//! adds objects and moves nothing placed before; the second of a pair is the same model.

use std::collections::BTreeMap;
use vlnverse_env::{ClassKind, RoomType, Scene, SceneObject, SemanticClass as C};
use vlnverse_procgen::Preset;

/// The classes a set adds (a new nightstand comes between twin beds, a desk with its chair).
const SET_CLASSES: [C; 11] = [
    C::Armchair,
    C::Sofa,
    C::Stool,
    C::Sink,
    C::Mirror,
    C::Bed,
    C::Nightstand,
    C::WallSconce,
    C::Desk,
    C::Chair,
    C::OfficeChair,
];

fn homes(sets: f32, n: usize) -> Vec<Scene> {
    let mut cfg = Preset::Vlnverse.config().expect("vlnverse preset");
    cfg.furniture.sets = sets;
    crate::support::first_homes(cfg, n)
}

/// The furniture and small objects, as (class, "class room box") in scene order. Door leaves,
/// windows, curtains and paintings are placed after the furniture, where it leaves room, so a
/// set may change them; so may the things placed after the sets (classes from the sectional
/// on, `more_things.rs`) and what stands on them.
fn furniture(s: &Scene) -> Vec<(C, String)> {
    let late = |c: C| c.id() >= C::Sectional.id();
    s.objects
        .iter()
        .filter(|o| matches!(o.class.kind(), ClassKind::Furniture | ClassKind::Small))
        .filter(|o| !matches!(o.class, C::Door | C::Curtain | C::PictureFrame))
        .filter(|o| !late(o.class))
        .filter(|o| {
            !o.supported_by
                .and_then(|id| s.object(id))
                .is_some_and(|sup| late(sup.class))
        })
        .map(|o| (o.class, format!("{:?} {:?} {:?}", o.class, o.room, o.bbox)))
        .collect()
}

/// What `with` holds beyond `without`, when `without` is `with` less some of its objects, in
/// the same order; `None` when an object of `without` is missing from `with` or moved.
fn added(without: &[(C, String)], with: &[(C, String)]) -> Option<Vec<C>> {
    let mut extra = Vec::new();
    let mut it = without.iter().peekable();
    for o in with {
        if it.peek() == Some(&o) {
            it.next();
        } else {
            extra.push(o.0);
        }
    }
    it.peek().is_none().then_some(extra)
}

#[test]
fn sets_add_objects_and_move_nothing() {
    let without = homes(0.0, 16);
    let with = homes(1.0, 16);
    let mut total = 0;
    for (a, b) in without.iter().zip(&with) {
        let extra = added(&furniture(a), &furniture(b))
            .unwrap_or_else(|| panic!("{}: an object placed before sets moved", a.id));
        for c in &extra {
            assert!(SET_CLASSES.contains(c), "{}: a set added a {c:?}", a.id);
        }
        total += extra.len();
    }
    assert!(total >= 16, "only {total} set objects in 16 homes");
}

/// Whether two objects are the same model in the same finish.
fn alike(a: &SceneObject, b: &SceneObject) -> bool {
    a.color == b.color && a.material == b.material && a.parts.len() == b.parts.len() && {
        let size = |o: &SceneObject| {
            let mut s = [
                o.bbox.max[0] - o.bbox.min[0],
                o.bbox.max[1] - o.bbox.min[1],
                o.bbox.max[2] - o.bbox.min[2],
            ];
            s.sort_by(f32::total_cmp);
            s
        };
        size(a)
            .iter()
            .zip(size(b))
            .all(|(x, y)| (x - y).abs() < 1e-3)
    }
}

#[test]
fn sets_turn_up_in_the_preset_and_match() {
    let with = homes(1.0, 60);
    // Rooms holding two or more alike of a class, by (room kind, class).
    let mut pairs: BTreeMap<(RoomType, C), usize> = BTreeMap::new();
    for s in &with {
        let mut by_room: BTreeMap<(u32, C), Vec<&SceneObject>> = BTreeMap::new();
        for o in s.objects.iter().filter(|o| o.supported_by.is_none()) {
            if let Some(r) = o.room {
                by_room.entry((r, o.class)).or_default().push(o);
            }
        }
        for ((r, c), objs) in by_room {
            let alike_pair = objs
                .iter()
                .enumerate()
                .any(|(i, a)| objs[i + 1..].iter().any(|b| alike(a, b)));
            if alike_pair {
                let kind = s.room(r).expect("room").kind;
                *pairs.entry((kind, c)).or_default() += 1;
            }
        }
        for o in &s.objects {
            if let Some(room) = o.room.and_then(|r| s.room(r)) {
                if SET_CLASSES.contains(&o.class) {
                    let (x, z) = (
                        (o.bbox.min[0] + o.bbox.max[0]) * 0.5,
                        (o.bbox.min[2] + o.bbox.max[2]) * 0.5,
                    );
                    assert!(room.contains(x, z), "{}: {} outside its room", s.id, o.name);
                }
            }
        }
    }
    let count = |k: RoomType, c: C| pairs.get(&(k, c)).copied().unwrap_or(0);
    for (k, c, least) in [
        (RoomType::LivingRoom, C::Armchair, 5),
        (RoomType::Kitchen, C::Stool, 5),
        (RoomType::Bathroom, C::Sink, 5),
        (RoomType::Bathroom, C::Mirror, 3),
        (RoomType::Bedroom, C::Bed, 3),
        (RoomType::Bedroom, C::WallSconce, 3),
        (RoomType::Office, C::Desk, 2),
    ] {
        assert!(
            count(k, c) >= least,
            "{k:?} with two alike {c:?}: {} in 60 homes ({pairs:?})",
            count(k, c)
        );
    }
}
