//! Feature pieces (pool tables, grandfather clocks, kitchen islands...): placed from an rng of
//! their own, so turning them on adds objects and moves no furniture.

use std::collections::BTreeSet;
use vlnverse_env::{ClassKind, RoomType, Scene, SemanticClass as C};
use vlnverse_procgen::Preset;

const PIECES: [C; 34] = [
    C::Recliner,
    C::RockingChair,
    C::PoolTable,
    C::PingPongTable,
    C::FoosballTable,
    C::GrandfatherClock,
    C::Guitar,
    C::DrumKit,
    C::Statue,
    C::FireExtinguisher,
    C::Dryer,
    C::Easel,
    C::Birdcage,
    C::Grill,
    C::KitchenIsland,
    C::ConsoleTable,
    C::ChinaCabinet,
    C::Ladder,
    C::Column,
    C::Chandelier,
    C::MassageTable,
    C::Hammock,
    C::ChaiseLounge,
    C::Cactus,
    C::Urn,
    C::Lounger,
    C::PopcornMachine,
    C::WineRack,
    C::Lockers,
    C::ArcadeMachine,
    C::ChristmasTree,
    C::WallSconce,
    C::Poster,
    C::PorchSwing,
];

/// Whether `o` was placed by the pieces stage: a piece class, but not furniture of a room's own
/// recipe, there with pieces or without (a recliner of a home theater's row of seats, a spa's
/// massage table and hot tub, a wine cellar's racks and barrels, a playroom's dollhouse and rocking horse,
/// a mud room's lockers).
fn is_piece(s: &Scene, o: &vlnverse_env::SceneObject) -> bool {
    use RoomType as R;
    let room = o.room.and_then(|r| s.room(r)).map(|r| r.kind);
    let own = matches!(
        (o.class, room),
        (C::Recliner, Some(R::HomeTheater))
            | (C::MassageTable | C::HotTub, Some(R::Spa))
            | (C::WineRack | C::Barrel, Some(R::WineCellar))
            | (C::Dollhouse | C::RockingHorse, Some(R::Playroom))
            | (C::Lockers, Some(R::MudRoom))
    );
    // Classes from the doormat on (issue 26's things) are all placed by the pieces stage.
    (PIECES.contains(&o.class) || o.class.id() >= C::Doormat.id()) && !own
}

fn homes(pieces: f32, n: usize) -> Vec<Scene> {
    let mut cfg = Preset::Vlnverse.config().expect("vlnverse preset");
    cfg.furniture.pieces = pieces;
    // Sets come after the pieces and stand by some of them (stools at an island).
    cfg.furniture.sets = 0.0;
    crate::support::first_homes(cfg, n)
}

/// The furniture and small objects but the pieces, as (class, room, box) in scene order.
/// Door leaves, windows, curtains and paintings are placed after the furniture, where it
/// leaves room (a door is shut only where the home stays connected, a window goes on a wall
/// free of tall furniture), so a piece may change them.
fn others(s: &Scene) -> Vec<String> {
    s.objects
        .iter()
        .filter(|o| !is_piece(s, o) && !on_a_piece(s, o))
        .filter(|o| matches!(o.class.kind(), ClassKind::Furniture | ClassKind::Small))
        .filter(|o| !matches!(o.class, C::Door | C::Curtain | C::PictureFrame))
        .map(|o| format!("{:?} {:?} {:?}", o.class, o.room, o.bbox))
        .collect()
}

/// Whether `o` stands on a piece (a bowl on the island): it comes and goes with the piece.
fn on_a_piece(s: &Scene, o: &vlnverse_env::SceneObject) -> bool {
    o.supported_by
        .and_then(|id| s.object(id))
        .is_some_and(|sup| is_piece(s, sup))
}

#[test]
fn pieces_add_objects_and_move_no_furniture() {
    let without = homes(0.0, 16);
    let with = homes(1.0, 16);
    let mut added = 0;
    for (a, b) in without.iter().zip(&with) {
        assert!(
            a.objects.iter().all(|o| !is_piece(a, o)),
            "{}: a piece with pieces = 0",
            a.id
        );
        let (oa, ob) = (others(a), others(b));
        let first = oa.iter().zip(&ob).position(|(x, y)| x != y);
        assert!(
            first.is_none() && oa.len() == ob.len(),
            "{}: other objects moved, first {:?}: {:?} / {:?}",
            a.id,
            first,
            first.map(|i| &oa[i]),
            first.map(|i| &ob[i])
        );
        added += b.objects.iter().filter(|o| is_piece(b, o)).count();
    }
    assert!(added >= 16, "only {added} pieces in 16 homes");
}

#[test]
fn most_piece_kinds_turn_up_in_the_rooms_that_list_them() {
    let with = homes(1.0, 60);
    let mut seen = BTreeSet::new();
    for s in &with {
        for o in s.objects.iter().filter(|o| PIECES.contains(&o.class)) {
            seen.insert(o.class);
            let room = o
                .room
                .and_then(|r| s.room(r))
                .expect("a piece stands in a room");
            let (x, z) = (
                (o.bbox.min[0] + o.bbox.max[0]) * 0.5,
                (o.bbox.min[2] + o.bbox.max[2]) * 0.5,
            );
            assert!(room.contains(x, z), "{}: {} outside its room", s.id, o.name);
            if o.class == C::Chandelier {
                // Over the middle of a dining table of its room.
                let (cx, cz) = (
                    (o.bbox.min[0] + o.bbox.max[0]) * 0.5,
                    (o.bbox.min[2] + o.bbox.max[2]) * 0.5,
                );
                let table = s
                    .objects
                    .iter()
                    .filter(|t| t.class == C::DiningTable && t.room == o.room)
                    .find(|t| {
                        let (tx, tz) = (
                            (t.bbox.min[0] + t.bbox.max[0]) * 0.5,
                            (t.bbox.min[2] + t.bbox.max[2]) * 0.5,
                        );
                        (tx - cx).abs() < 0.02 && (tz - cz).abs() < 0.02
                    })
                    .expect("a chandelier hangs over the middle of a dining table");
                assert!(
                    table.bbox.max[1] < o.bbox.min[1] - 0.6,
                    "{}: {}",
                    s.id,
                    o.name
                );
                assert!(
                    o.bbox.min[1] > table.bbox.min[1] + 1.5,
                    "{}: low {}",
                    s.id,
                    o.name
                );
            }
        }
    }
    assert!(seen.len() >= 20, "{} kinds placed: {seen:?}", seen.len());
}
