//! Feature pieces: the furniture a home has one of, or none, and that people name when they
//! give directions ("walk past the pool table", "stop by the grandfather clock"): game tables,
//! instruments, a statue, a kitchen island, a console table in the hall, a dryer beside the
//! washer.
//!
//! They are placed after a room's furniture and clutter, with the same placement checks, but
//! from an rng of their own seeded by the home and room: every other object of a home stays
//! where it was, and `furniture.pieces = 0` gives the homes of before.

use crate::models::{ball, bcube, cube, cyl, disc_z, front, legs, r, turned, Model};
use crate::palette::{self, f, shade, tone, Finish};
use glam::Quat;
use rand::seq::IndexedRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{RoomType, SemanticClass as C, Shape};

/// Where a piece stands in its room.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Spot {
    /// Back to a wall.
    Wall,
    /// In a corner.
    Corner,
    /// Free in the room, away from the walls (game tables, an island).
    Centre,
}

/// One line of a room's list: the class, its chance (times `furniture.pieces`), where it goes
/// and the least room floor area (m²) it needs.
pub(crate) struct Piece {
    pub class: C,
    pub chance: f32,
    pub spot: Spot,
    pub min_area: f32,
}

const fn p(class: C, chance: f32, spot: Spot, min_area: f32) -> Piece {
    Piece {
        class,
        chance,
        spot,
        min_area,
    }
}

/// The pieces a room of kind `kind` may get, in the order they are tried.
pub(crate) fn pieces(kind: RoomType) -> &'static [Piece] {
    use Spot::{Centre, Corner, Wall};
    match kind {
        RoomType::LivingRoom => {
            const L: &[Piece] = &[
                p(C::PoolTable, 0.18, Centre, 30.0),
                p(C::Recliner, 0.3, Wall, 0.0),
                p(C::GrandfatherClock, 0.12, Wall, 0.0),
                p(C::Guitar, 0.15, Corner, 0.0),
                p(C::Statue, 0.12, Corner, 20.0),
                p(C::RockingChair, 0.12, Corner, 0.0),
                p(C::FoosballTable, 0.06, Wall, 24.0),
                p(C::Birdcage, 0.06, Corner, 0.0),
                p(C::DrumKit, 0.04, Corner, 24.0),
                p(C::PingPongTable, 0.06, Centre, 32.0),
                p(C::Column, 0.1, Centre, 32.0),
                p(C::ChaiseLounge, 0.06, Wall, 0.0),
                p(C::Cactus, 0.08, Corner, 0.0),
                p(C::Urn, 0.05, Corner, 0.0),
                p(C::WineRack, 0.06, Wall, 0.0),
                p(C::ArcadeMachine, 0.04, Wall, 24.0),
                p(C::ChristmasTree, 0.2, Wall, 0.0),
                p(C::WallSconce, 0.3, Wall, 0.0),
                p(C::GrandPiano, 0.15, Centre, 28.0),
                p(C::Tapestry, 0.12, Wall, 0.0),
                p(C::CatTree, 0.15, Corner, 0.0),
                p(C::RoomDivider, 0.06, Wall, 20.0),
                p(C::Telescope, 0.05, Corner, 0.0),
                p(C::DeerHead, 0.05, Wall, 0.0),
                p(C::Bar, 0.05, Wall, 28.0),
                p(C::Jukebox, 0.03, Wall, 24.0),
                p(C::AirHockeyTable, 0.04, Centre, 32.0),
            ];
            L
        }
        RoomType::Kitchen => {
            const L: &[Piece] = &[
                p(C::KitchenIsland, 0.55, Centre, 11.0),
                p(C::FireExtinguisher, 0.2, Wall, 0.0),
                p(C::WineRack, 0.15, Wall, 0.0),
                p(C::WaterCooler, 0.05, Wall, 0.0),
            ];
            L
        }
        RoomType::DiningRoom => {
            const L: &[Piece] = &[
                p(C::ChinaCabinet, 0.4, Wall, 0.0),
                p(C::GrandfatherClock, 0.1, Wall, 0.0),
                p(C::Statue, 0.06, Corner, 14.0),
                p(C::Chandelier, 0.45, Centre, 0.0),
                p(C::Column, 0.05, Centre, 18.0),
                p(C::WineRack, 0.3, Wall, 0.0),
                p(C::WallSconce, 0.3, Wall, 0.0),
                p(C::ChristmasTree, 0.1, Wall, 0.0),
                p(C::Tapestry, 0.1, Wall, 0.0),
                p(C::Bar, 0.1, Wall, 16.0),
                p(C::Barrel, 0.05, Corner, 0.0),
                p(C::GrandPiano, 0.05, Centre, 24.0),
            ];
            L
        }
        RoomType::Bedroom => {
            const L: &[Piece] = &[
                p(C::RockingChair, 0.08, Corner, 0.0),
                p(C::Guitar, 0.1, Corner, 0.0),
                p(C::Easel, 0.05, Corner, 0.0),
                p(C::DrumKit, 0.03, Corner, 14.0),
                p(C::ChaiseLounge, 0.06, Wall, 12.0),
                p(C::WallSconce, 0.2, Wall, 0.0),
                p(C::Poster, 0.1, Wall, 0.0),
                p(C::BunkBed, 0.1, Wall, 13.0),
                p(C::RockingHorse, 0.06, Corner, 0.0),
                p(C::Dollhouse, 0.06, Corner, 0.0),
                p(C::RoomDivider, 0.05, Wall, 14.0),
                p(C::Tapestry, 0.08, Wall, 0.0),
                p(C::CatTree, 0.03, Corner, 0.0),
            ];
            L
        }
        RoomType::Office => {
            const L: &[Piece] = &[
                p(C::PingPongTable, 0.12, Centre, 11.0),
                p(C::Easel, 0.12, Corner, 0.0),
                p(C::Guitar, 0.1, Corner, 0.0),
                p(C::Recliner, 0.1, Corner, 0.0),
                p(C::FoosballTable, 0.08, Wall, 9.0),
                p(C::MassageTable, 0.05, Wall, 9.0),
                p(C::Cactus, 0.1, Corner, 0.0),
                p(C::ArcadeMachine, 0.04, Wall, 0.0),
                p(C::Flag, 0.15, Wall, 0.0),
                p(C::WaterCooler, 0.1, Wall, 0.0),
                p(C::Telescope, 0.08, Corner, 0.0),
                p(C::DeerHead, 0.06, Wall, 0.0),
                p(C::Dartboard, 0.08, Wall, 0.0),
                p(C::RoomDivider, 0.04, Wall, 12.0),
            ];
            L
        }
        RoomType::Gym => {
            // The machines before the rest: a gym full of lockers and posters has no wall
            // left for an elliptical.
            const L: &[Piece] = &[
                p(C::Elliptical, 0.5, Wall, 0.0),
                p(C::MassageTable, 0.25, Wall, 10.0),
                p(C::FireExtinguisher, 0.1, Wall, 0.0),
                p(C::Lockers, 0.4, Wall, 0.0),
                p(C::Poster, 0.3, Wall, 0.0),
                p(C::RowingMachine, 0.6, Wall, 0.0),
                p(C::WaterCooler, 0.3, Wall, 0.0),
            ];
            L
        }
        RoomType::Pantry => {
            const L: &[Piece] = &[
                p(C::Ladder, 0.25, Wall, 0.0),
                p(C::FireExtinguisher, 0.05, Wall, 0.0),
                p(C::WineRack, 0.4, Wall, 0.0),
                p(C::Barrel, 0.25, Corner, 0.0),
                p(C::VacuumCleaner, 0.15, Corner, 0.0),
            ];
            L
        }
        RoomType::HomeTheater => {
            const L: &[Piece] = &[
                p(C::PopcornMachine, 0.6, Corner, 0.0),
                p(C::FoosballTable, 0.1, Wall, 16.0),
                p(C::Guitar, 0.08, Corner, 0.0),
                p(C::DrumKit, 0.25, Corner, 0.0),
                p(C::ArcadeMachine, 0.35, Wall, 0.0),
                p(C::WineRack, 0.1, Wall, 0.0),
                p(C::WallSconce, 0.5, Wall, 0.0),
                p(C::Poster, 0.6, Wall, 0.0),
                p(C::Poster, 0.3, Wall, 0.0),
                p(C::Jukebox, 0.2, Wall, 0.0),
                p(C::PinballMachine, 0.3, Wall, 0.0),
                p(C::AirHockeyTable, 0.3, Wall, 16.0),
                p(C::Bar, 0.2, Wall, 16.0),
                p(C::Dartboard, 0.2, Wall, 0.0),
            ];
            L
        }
        RoomType::Library => {
            const L: &[Piece] = &[
                p(C::Ladder, 0.5, Wall, 0.0),
                p(C::GrandfatherClock, 0.2, Wall, 0.0),
                p(C::RockingChair, 0.15, Corner, 0.0),
                p(C::Statue, 0.1, Corner, 12.0),
                p(C::ChaiseLounge, 0.1, Wall, 12.0),
                p(C::WallSconce, 0.35, Wall, 0.0),
                p(C::DeerHead, 0.15, Wall, 0.0),
                p(C::Telescope, 0.12, Corner, 0.0),
                p(C::Tapestry, 0.15, Wall, 0.0),
                p(C::GrandPiano, 0.15, Centre, 20.0),
                p(C::Flag, 0.1, Wall, 0.0),
            ];
            L
        }
        RoomType::Garage => {
            const L: &[Piece] = &[
                p(C::Ladder, 0.4, Wall, 0.0),
                p(C::Lockers, 0.3, Wall, 0.0),
                p(C::FireExtinguisher, 0.3, Wall, 0.0),
                p(C::Grill, 0.15, Wall, 0.0),
                p(C::Poster, 0.15, Wall, 0.0),
                p(C::LawnMower, 0.6, Wall, 0.0),
                p(C::Kayak, 0.4, Wall, 0.0),
                p(C::Dartboard, 0.25, Wall, 0.0),
                p(C::WaterCooler, 0.1, Wall, 0.0),
                p(C::Flag, 0.15, Wall, 0.0),
                p(C::Barrel, 0.1, Corner, 0.0),
                p(C::AirHockeyTable, 0.3, Wall, 0.0),
            ];
            L
        }
        RoomType::Porch => {
            const L: &[Piece] = &[
                p(C::Hammock, 0.3, Wall, 0.0),
                p(C::PorchSwing, 0.9, Wall, 0.0),
                p(C::RockingChair, 0.4, Corner, 0.0),
                p(C::Lounger, 0.1, Wall, 0.0),
                p(C::Wreath, 0.3, Wall, 0.0),
                p(C::Fountain, 0.5, Wall, 0.0),
                p(C::Flag, 0.3, Wall, 0.0),
                p(C::HotTub, 0.4, Wall, 0.0),
            ];
            L
        }
        RoomType::Room => {
            const L: &[Piece] = &[
                p(C::PingPongTable, 0.35, Centre, 0.0),
                p(C::PoolTable, 0.3, Centre, 0.0),
                p(C::FoosballTable, 0.25, Wall, 0.0),
                p(C::DrumKit, 0.15, Corner, 0.0),
                p(C::Easel, 0.15, Corner, 0.0),
                p(C::MassageTable, 0.15, Wall, 0.0),
                p(C::ArcadeMachine, 0.3, Wall, 0.0),
                p(C::AirHockeyTable, 0.3, Wall, 0.0),
                p(C::PinballMachine, 0.3, Wall, 0.0),
                p(C::Jukebox, 0.2, Wall, 0.0),
                p(C::Dartboard, 0.3, Wall, 0.0),
                p(C::Bar, 0.2, Wall, 0.0),
            ];
            L
        }
        RoomType::Hallway => {
            const L: &[Piece] = &[
                p(C::ConsoleTable, 0.35, Wall, 0.0),
                p(C::GrandfatherClock, 0.1, Wall, 0.0),
                p(C::Statue, 0.08, Corner, 0.0),
                p(C::FireExtinguisher, 0.1, Wall, 0.0),
                p(C::Urn, 0.06, Corner, 0.0),
                p(C::WallSconce, 0.3, Wall, 0.0),
                p(C::Tapestry, 0.08, Wall, 0.0),
                p(C::DeerHead, 0.05, Wall, 0.0),
                p(C::WaterCooler, 0.03, Wall, 0.0),
            ];
            L
        }
        RoomType::EntranceHall => {
            const L: &[Piece] = &[
                p(C::ConsoleTable, 0.5, Wall, 0.0),
                p(C::Statue, 0.15, Corner, 0.0),
                p(C::GrandfatherClock, 0.1, Wall, 0.0),
                p(C::Urn, 0.15, Corner, 0.0),
                p(C::Cactus, 0.06, Corner, 0.0),
                p(C::Lockers, 0.12, Wall, 0.0),
                p(C::WallSconce, 0.35, Wall, 0.0),
                p(C::ChristmasTree, 0.05, Wall, 0.0),
                p(C::Wreath, 0.25, Wall, 0.0),
                p(C::DeerHead, 0.08, Wall, 0.0),
                p(C::Flag, 0.08, Wall, 0.0),
                p(C::Tapestry, 0.06, Wall, 0.0),
                p(C::Fountain, 0.2, Centre, 10.0),
            ];
            L
        }
        RoomType::LaundryRoom => {
            const L: &[Piece] = &[
                p(C::Dryer, 0.7, Wall, 0.0),
                p(C::Ladder, 0.3, Wall, 0.0),
                p(C::FireExtinguisher, 0.1, Wall, 0.0),
                p(C::Lockers, 0.12, Wall, 0.0),
                p(C::VacuumCleaner, 0.35, Corner, 0.0),
            ];
            L
        }
        RoomType::Closet => {
            const L: &[Piece] = &[
                p(C::Ladder, 0.2, Wall, 0.0),
                p(C::VacuumCleaner, 0.2, Wall, 0.0),
            ];
            L
        }
        RoomType::Balcony => {
            const L: &[Piece] = &[
                p(C::Hammock, 0.2, Wall, 0.0),
                p(C::Grill, 0.35, Wall, 0.0),
                p(C::Lounger, 0.25, Wall, 0.0),
                p(C::HotTub, 0.25, Wall, 6.0),
                p(C::Fountain, 0.35, Wall, 0.0),
                p(C::Telescope, 0.15, Corner, 0.0),
            ];
            L
        }
        RoomType::Bathroom => {
            const L: &[Piece] = &[p(C::HotTub, 0.1, Corner, 8.0)];
            L
        }
        RoomType::Sauna => &[],
        RoomType::Spa => {
            const L: &[Piece] = &[
                p(C::WallSconce, 0.4, Wall, 0.0),
                p(C::Fountain, 0.15, Wall, 0.0),
                p(C::RoomDivider, 0.1, Wall, 10.0),
            ];
            L
        }
        RoomType::WineCellar => {
            const L: &[Piece] = &[p(C::Bar, 0.4, Wall, 6.0), p(C::WallSconce, 0.4, Wall, 0.0)];
            L
        }
        RoomType::Playroom => {
            const L: &[Piece] = &[
                p(C::Easel, 0.35, Corner, 0.0),
                p(C::Telescope, 0.2, Corner, 0.0),
                p(C::Poster, 0.3, Wall, 0.0),
                p(C::FoosballTable, 0.12, Wall, 11.0),
                p(C::AirHockeyTable, 0.08, Wall, 12.0),
                p(C::CatTree, 0.05, Corner, 0.0),
            ];
            L
        }
        RoomType::MudRoom => {
            const L: &[Piece] = &[
                p(C::VacuumCleaner, 0.2, Corner, 0.0),
                p(C::FireExtinguisher, 0.1, Wall, 0.0),
            ];
            L
        }
        RoomType::Workshop => {
            const L: &[Piece] = &[
                p(C::Ladder, 0.5, Wall, 0.0),
                p(C::FireExtinguisher, 0.3, Wall, 0.0),
                p(C::VacuumCleaner, 0.2, Corner, 0.0),
                p(C::Poster, 0.1, Wall, 0.0),
                p(C::Lockers, 0.1, Wall, 0.0),
                p(C::Kayak, 0.3, Wall, 0.0),
            ];
            L
        }
    }
}

const LEATHER: &[Finish] = &[
    f("brown", "leather", [0.28, 0.14, 0.06]),
    f("black", "leather", [0.04, 0.04, 0.04]),
    f("grey", "fabric", [0.3, 0.3, 0.32]),
    f("beige", "fabric", [0.7, 0.6, 0.45]),
    f("blue", "fabric", [0.08, 0.16, 0.5]),
];
/// The furniture's wood finishes without the painted colours: wooden, brown, white, black.
const WOOD: &[Finish] = palette::WOOD.split_at(4).0;
const DARK_WOOD: &[Finish] = &[
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("black", "wood", [0.05, 0.05, 0.05]),
];
/// A game table's cloth or top, which people name it by ("the green pool table").
const FELT: &[Finish] = &[
    f("green", "wood", [0.05, 0.32, 0.12]),
    f("green", "wood", [0.05, 0.32, 0.12]),
    f("blue", "wood", [0.06, 0.18, 0.45]),
    f("red", "wood", [0.45, 0.05, 0.05]),
];
const TABLE_TOP: &[Finish] = &[
    f("blue", "wood", [0.06, 0.18, 0.45]),
    f("green", "wood", [0.05, 0.3, 0.15]),
    f("black", "wood", [0.04, 0.04, 0.05]),
];
const INSTRUMENT: &[Finish] = &[
    f("wooden", "wood", [0.55, 0.33, 0.14]),
    f("black", "wood", [0.04, 0.04, 0.04]),
    f("red", "wood", [0.5, 0.06, 0.05]),
    f("white", "wood", [0.86, 0.86, 0.84]),
    f("blue", "wood", [0.08, 0.18, 0.5]),
];
const STONE: &[Finish] = &[
    f("white", "stone", [0.82, 0.8, 0.76]),
    f("grey", "stone", [0.42, 0.42, 0.43]),
    f("black", "metal", [0.06, 0.06, 0.06]),
];
const APPLIANCE: &[Finish] = &[
    f("white", "metal", [0.88, 0.88, 0.88]),
    f("silver", "metal", [0.6, 0.6, 0.62]),
    f("grey", "metal", [0.35, 0.35, 0.37]),
];
const CAGE: &[Finish] = &[
    f("white", "metal", [0.88, 0.88, 0.88]),
    f("gold", "metal", [0.75, 0.58, 0.2]),
    f("black", "metal", [0.06, 0.06, 0.06]),
];
const GRILL: &[Finish] = &[
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("silver", "metal", [0.6, 0.6, 0.62]),
    f("red", "metal", [0.55, 0.06, 0.05]),
];
const LADDER: &[Finish] = &[
    f("silver", "metal", [0.62, 0.62, 0.64]),
    f("wooden", "wood", [0.5, 0.32, 0.16]),
];
const RED: &[Finish] = &[f("red", "metal", [0.6, 0.04, 0.04])];
const PLASTER: &[Finish] = &[
    f("white", "stone", [0.86, 0.85, 0.82]),
    f("grey", "stone", [0.55, 0.55, 0.56]),
    f("beige", "stone", [0.72, 0.64, 0.5]),
];
const BRASS: &[Finish] = &[
    f("gold", "metal", [0.75, 0.58, 0.2]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("silver", "metal", [0.62, 0.62, 0.64]),
];
const CUSHION: &[Finish] = &[
    f("white", "fabric", [0.85, 0.85, 0.85]),
    f("beige", "fabric", [0.7, 0.6, 0.45]),
    f("blue", "fabric", [0.08, 0.16, 0.5]),
    f("green", "fabric", [0.12, 0.38, 0.14]),
    f("red", "fabric", [0.55, 0.06, 0.06]),
    f("grey", "fabric", [0.3, 0.3, 0.32]),
];
const POT: &[Finish] = &[
    f("terracotta", "ceramic", [0.55, 0.25, 0.12]),
    f("white", "ceramic", [0.9, 0.9, 0.9]),
    f("blue", "ceramic", [0.1, 0.2, 0.5]),
    f("black", "ceramic", [0.05, 0.05, 0.05]),
];

/// Draw a finish from `list`, in one of its colour word's tones or its own.
fn pick(list: &[Finish], rng: &mut ChaCha8Rng) -> Finish {
    let fin = *list.choose(rng).unwrap_or(&list[0]);
    crate::tones::toned(fin, rng)
}

/// The model of a piece of class `class`, in a room whose ceiling is `ceiling` metres above
/// its floor.
pub(crate) fn model(class: C, ceiling: f32, rng: &mut ChaCha8Rng) -> Model {
    match class {
        C::Recliner => recliner(rng),
        C::RockingChair => rocking_chair(rng),
        C::PoolTable => pool_table(rng),
        C::PingPongTable => ping_pong_table(rng),
        C::FoosballTable => foosball_table(rng),
        C::GrandfatherClock => grandfather_clock(rng),
        C::Guitar => guitar(rng),
        C::DrumKit => drum_kit(rng),
        C::Statue => statue(rng),
        C::FireExtinguisher => fire_extinguisher(rng),
        C::Dryer => dryer(rng),
        C::Easel => easel(rng),
        C::Birdcage => birdcage(rng),
        C::Grill => grill(rng),
        C::KitchenIsland => kitchen_island(rng),
        C::ConsoleTable => console_table(rng),
        C::ChinaCabinet => china_cabinet(rng),
        C::Ladder => ladder(rng),
        C::Column => column(ceiling, rng),
        C::Chandelier => chandelier(rng),
        C::MassageTable => massage_table(rng),
        C::Hammock => hammock(rng),
        C::ChaiseLounge => chaise_lounge(rng),
        C::Cactus => cactus(rng),
        C::Urn => urn(rng),
        C::Lounger => lounger(rng),
        // Every class of `pieces` is above or in `things`; anything else gets the clutter
        // model.
        _ => crate::things::model(class, rng).unwrap_or_else(|| crate::models::clutter(class, rng)),
    }
}

/// A bulky padded chair with a high back and a footrest folded under the seat.
fn recliner(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(LEATHER, rng);
    let c = fin.rgb;
    let dark = shade(c, 0.8);
    let (w, d) = (r(rng, 0.85, 0.95), r(rng, 0.9, 1.0));
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.05, 0.0, [w, 0.4, d], 0.04, c);
    bcube(
        &mut p,
        0.0,
        0.45,
        -0.02,
        [w - 0.3, 0.14, d - 0.25],
        0.03,
        dark,
    );
    bcube(&mut p, 0.0, 0.45, d * 0.5 - 0.14, [w, 0.62, 0.28], 0.06, c);
    for sx in [-1.0, 1.0] {
        bcube(
            &mut p,
            sx * (w * 0.5 - 0.08),
            0.45,
            -0.05,
            [0.16, 0.22, d - 0.3],
            0.03,
            c,
        );
    }
    front(&mut p, d, [0.0, 0.08, -0.01], [w - 0.3, 0.3, 0.03], dark);
    cube(&mut p, 0.0, 0.0, 0.0, [w - 0.1, 0.05, d - 0.1], tone::METAL);
    Model::new(C::Recliner, fin, [w, 1.07, d], 45.0, p)
}

/// A wooden chair with a spindle back on two curved rockers.
fn rocking_chair(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(WOOD, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    for sx in [-1.0, 1.0] {
        let x = sx * 0.24;
        // Each rocker as three flat segments, tipped up at both ends.
        turned(
            &mut p,
            Shape::Cuboid {
                half_extents: [0.02, 0.025, 0.3],
                bevel: 0.0,
            },
            [x, 0.03, 0.0],
            Quat::IDENTITY,
            c,
        );
        for (z, a) in [(-0.4f32, 0.35f32), (0.4, -0.35)] {
            turned(
                &mut p,
                Shape::Cuboid {
                    half_extents: [0.02, 0.025, 0.12],
                    bevel: 0.0,
                },
                [x, 0.06, z],
                Quat::from_rotation_x(a),
                c,
            );
        }
        for z in [-0.2, 0.2] {
            cube(&mut p, x, 0.05, z, [0.04, 0.4, 0.04], c);
        }
        cube(&mut p, x, 0.6, 0.0, [0.04, 0.04, 0.42], c);
        cube(&mut p, x, 0.45, 0.22, [0.04, 0.7, 0.04], c);
    }
    bcube(&mut p, 0.0, 0.45, 0.0, [0.52, 0.04, 0.46], 0.008, c);
    cube(&mut p, 0.0, 1.08, 0.22, [0.52, 0.07, 0.04], c);
    for i in 0..5 {
        let x = -0.16 + i as f32 * 0.08;
        cube(&mut p, x, 0.49, 0.22, [0.025, 0.6, 0.025], c);
    }
    Model::new(C::RockingChair, fin, [0.52, 1.15, 1.0], 9.0, p)
}

/// A billiard table: cloth bed, cushioned rails, six pockets, heavy legs.
fn pool_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(FELT, rng);
    let wood = pick(DARK_WOOD, rng).rgb;
    let (w, d) = (r(rng, 2.2, 2.5), r(rng, 1.25, 1.4));
    let mut p = Vec::new();
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            cube(
                &mut p,
                sx * (w * 0.5 - 0.2),
                0.0,
                sz * (d * 0.5 - 0.18),
                [0.14, 0.62, 0.14],
                wood,
            );
        }
    }
    cube(&mut p, 0.0, 0.58, 0.0, [w - 0.08, 0.16, d - 0.08], wood);
    cube(&mut p, 0.0, 0.74, 0.0, [w - 0.24, 0.03, d - 0.24], fin.rgb);
    for sz in [-1.0, 1.0] {
        cube(
            &mut p,
            0.0,
            0.74,
            sz * (d * 0.5 - 0.07),
            [w, 0.07, 0.14],
            wood,
        );
    }
    for sx in [-1.0, 1.0] {
        cube(
            &mut p,
            sx * (w * 0.5 - 0.07),
            0.74,
            0.0,
            [0.14, 0.07, d - 0.28],
            wood,
        );
    }
    for x in [-0.5, 0.0, 0.5] {
        for sz in [-1.0, 1.0] {
            cyl(
                &mut p,
                x * (w - 0.2),
                0.775,
                sz * (d * 0.5 - 0.12),
                0.045,
                0.04,
                tone::SOOT,
            );
        }
    }
    Model::new(C::PoolTable, fin, [w, 0.81, d], 300.0, p)
}

/// A table tennis table: a painted top with white edge and centre lines, a net, folding legs.
fn ping_pong_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(TABLE_TOP, rng);
    let (w, d) = (2.74, 1.52);
    let mut p = Vec::new();
    legs(&mut p, w - 0.5, d - 0.2, 0.72, 0.05, tone::METAL);
    cube(&mut p, 0.0, 0.72, 0.0, [w, 0.04, d], fin.rgb);
    for sz in [-1.0, 1.0] {
        cube(
            &mut p,
            0.0,
            0.76,
            sz * (d * 0.5 - 0.01),
            [w, 0.002, 0.02],
            tone::WHITE,
        );
    }
    for sx in [-1.0, 1.0] {
        cube(
            &mut p,
            sx * (w * 0.5 - 0.01),
            0.76,
            0.0,
            [0.02, 0.002, d],
            tone::WHITE,
        );
    }
    cube(&mut p, 0.0, 0.76, 0.0, [w, 0.002, 0.006], tone::WHITE);
    cube(&mut p, 0.0, 0.76, 0.0, [0.01, 0.15, d + 0.1], tone::SOOT);
    Model::new(C::PingPongTable, fin, [w, 0.91, d + 0.1], 70.0, p)
}

/// A table football cabinet on four legs, its rods sticking out of both long sides.
fn foosball_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(INSTRUMENT, rng);
    let (w, d) = (r(rng, 1.2, 1.4), 0.72);
    let mut p = Vec::new();
    legs(&mut p, w - 0.1, d - 0.1, 0.7, 0.08, fin.rgb);
    bcube(&mut p, 0.0, 0.62, 0.0, [w, 0.26, d], 0.01, fin.rgb);
    cube(
        &mut p,
        0.0,
        0.8,
        0.0,
        [w - 0.1, 0.01, d - 0.06],
        [0.05, 0.32, 0.12],
    );
    for i in 0..8 {
        let x = -w * 0.5 + 0.15 + i as f32 * (w - 0.3) / 7.0;
        disc_z(&mut p, [x, 0.83, 0.0], 0.008, d + 0.3, tone::STEEL);
        for sz in [-1.0, 1.0] {
            disc_z(
                &mut p,
                [x, 0.83, sz * (d * 0.5 + 0.15)],
                0.02,
                0.08,
                tone::SOOT,
            );
        }
    }
    Model::new(C::FoosballTable, fin, [w, 0.88, d + 0.38], 60.0, p)
}

/// A tall case clock: plinth, a long trunk with a glass door over the pendulum, a round face.
fn grandfather_clock(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(DARK_WOOD, rng);
    let c = fin.rgb;
    let (w, d) = (r(rng, 0.45, 0.55), 0.3);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, 0.35, d], 0.01, c);
    cube(&mut p, 0.0, 0.35, 0.02, [w - 0.1, 1.15, d - 0.04], c);
    bcube(&mut p, 0.0, 1.5, 0.0, [w, 0.5, d], 0.02, c);
    front(
        &mut p,
        d - 0.04,
        [0.0, 0.5, -0.005],
        [w - 0.22, 0.85, 0.01],
        tone::GLASS,
    );
    cube(
        &mut p,
        0.0,
        0.7,
        -d * 0.5 + 0.05,
        [0.008, 0.45, 0.008],
        [0.75, 0.58, 0.2],
    );
    disc_z(
        &mut p,
        [0.0, 0.72, -d * 0.5 + 0.05],
        0.06,
        0.01,
        [0.75, 0.58, 0.2],
    );
    disc_z(
        &mut p,
        [0.0, 1.75, -d * 0.5],
        (w * 0.5 - 0.07).min(0.2),
        0.02,
        tone::WHITE,
    );
    cube(&mut p, 0.0, 2.0, 0.0, [w + 0.04, 0.06, d + 0.02], c);
    Model::new(
        C::GrandfatherClock,
        fin,
        [w + 0.04, 2.06, d + 0.02],
        60.0,
        p,
    )
}

/// An acoustic guitar upright on a floor stand, its strings to the front.
fn guitar(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(INSTRUMENT, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    for sx in [-1.0, 1.0] {
        cube(&mut p, sx * 0.15, 0.0, 0.0, [0.03, 0.03, 0.35], tone::METAL);
    }
    cube(&mut p, 0.0, 0.0, 0.12, [0.03, 0.7, 0.03], tone::METAL);
    disc_z(&mut p, [0.0, 0.3, 0.0], 0.19, 0.1, c);
    disc_z(&mut p, [0.0, 0.55, 0.0], 0.14, 0.1, c);
    disc_z(&mut p, [0.0, 0.52, -0.05], 0.045, 0.005, tone::SOOT);
    cube(&mut p, 0.0, 0.66, -0.01, [0.05, 0.42, 0.03], tone::SOOT);
    cube(&mut p, 0.0, 1.08, -0.01, [0.08, 0.14, 0.03], tone::SOOT);
    Model::new(C::Guitar, fin, [0.4, 1.22, 0.35], 3.0, p)
}

/// A drum set: bass drum on its side, snare and toms on stands, two cymbals, a stool.
fn drum_kit(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(INSTRUMENT, rng);
    let c = fin.rgb;
    let brass = [0.75, 0.58, 0.2];
    let mut p = Vec::new();
    disc_z(&mut p, [0.0, 0.28, -0.15], 0.28, 0.4, c);
    disc_z(&mut p, [0.0, 0.28, -0.36], 0.26, 0.01, tone::WHITE);
    for (x, z, h, rad) in [(-0.35, 0.05, 0.55, 0.17), (0.35, 0.0, 0.45, 0.2)] {
        cube(&mut p, x, 0.0, z, [0.03, h, 0.03], tone::STEEL);
        cyl(&mut p, x, h, z, rad, 0.18, c);
    }
    for sx in [-1.0, 1.0] {
        cyl(&mut p, sx * 0.12, 0.6, -0.1, 0.11, 0.14, c);
    }
    for (x, z, h) in [(-0.55, -0.2, 0.95), (0.55, -0.15, 1.05)] {
        cube(&mut p, x, 0.0, z, [0.025, h, 0.025], tone::STEEL);
        cyl(&mut p, x, h, z, 0.2, 0.01, brass);
    }
    cyl(&mut p, 0.0, 0.0, 0.4, 0.16, 0.5, tone::SOOT);
    Model::new(C::DrumKit, fin, [1.3, 1.06, 1.1], 25.0, p)
}

/// A statue on a plinth: a standing figure, or a bust of head and shoulders.
fn statue(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(STONE, rng);
    let c = fin.rgb;
    let plinth = if fin.material == "stone" {
        shade(c, 0.85)
    } else {
        [0.82, 0.8, 0.76]
    };
    let bust = rng.random_bool(0.4);
    let mut p = Vec::new();
    if bust {
        bcube(&mut p, 0.0, 0.0, 0.0, [0.4, 1.05, 0.4], 0.01, plinth);
        bcube(&mut p, 0.0, 1.05, 0.0, [0.34, 0.16, 0.2], 0.03, c);
        cyl(&mut p, 0.0, 1.21, 0.0, 0.05, 0.08, c);
        ball(&mut p, [0.0, 1.38, 0.0], 0.11, c);
        Model::new(C::Statue, fin, [0.4, 1.49, 0.4], 70.0, p)
    } else {
        bcube(&mut p, 0.0, 0.0, 0.0, [0.45, 0.5, 0.45], 0.01, plinth);
        cube(&mut p, 0.0, 0.5, 0.0, [0.35, 0.04, 0.3], c);
        for sx in [-1.0, 1.0] {
            cube(&mut p, sx * 0.06, 0.54, 0.0, [0.09, 0.7, 0.12], c);
        }
        bcube(&mut p, 0.0, 1.24, 0.0, [0.3, 0.5, 0.16], 0.03, c);
        for sx in [-1.0, 1.0] {
            cube(&mut p, sx * 0.19, 1.12, 0.0, [0.07, 0.58, 0.08], c);
        }
        cyl(&mut p, 0.0, 1.74, 0.0, 0.04, 0.06, c);
        ball(&mut p, [0.0, 1.89, 0.0], 0.1, c);
        Model::new(C::Statue, fin, [0.45, 1.99, 0.45], 90.0, p)
    }
}

/// A red extinguisher standing by the wall: cylinder, valve, hose.
fn fire_extinguisher(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(RED, rng);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.08, 0.45, fin.rgb);
    ball(&mut p, [0.0, 0.45, 0.0], 0.06, fin.rgb);
    cube(&mut p, 0.0, 0.5, 0.0, [0.04, 0.06, 0.04], tone::SOOT);
    cube(&mut p, 0.0, 0.56, -0.03, [0.03, 0.02, 0.12], tone::SOOT);
    cube(&mut p, 0.07, 0.2, -0.02, [0.02, 0.32, 0.02], tone::SOOT);
    Model::new(C::FireExtinguisher, fin, [0.18, 0.58, 0.18], 5.0, p)
}

/// A front-loading clothes dryer: cabinet, a round door without a window, a control strip.
fn dryer(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(APPLIANCE, rng);
    let c = fin.rgb;
    let d = 0.62;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [0.6, 0.85, d], 0.02, c);
    front(
        &mut p,
        d,
        [0.0, 0.72, -0.005],
        [0.56, 0.1, 0.01],
        shade(c, 0.8),
    );
    disc_z(
        &mut p,
        [0.0, 0.4, -d * 0.5 - 0.01],
        0.2,
        0.02,
        shade(c, 0.9),
    );
    disc_z(
        &mut p,
        [0.18, 0.77, -d * 0.5 - 0.015],
        0.025,
        0.02,
        tone::METAL,
    );
    Model::new(C::Dryer, fin, [0.6, 0.85, d + 0.04], 40.0, p)
        .with_top(0.04)
        .with_features(&["round door"])
}

/// A painter's easel: three legs and a blank canvas on its ledge.
fn easel(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(WOOD, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    let leg = Shape::Cuboid {
        half_extents: [0.02, 0.85, 0.02],
        bevel: 0.0,
    };
    for sx in [-1.0, 1.0] {
        turned(
            &mut p,
            leg.clone(),
            [sx * 0.2, 0.84, -0.05],
            Quat::from_rotation_z(sx * 0.22),
            c,
        );
    }
    turned(
        &mut p,
        leg,
        [0.0, 0.8, 0.25],
        Quat::from_rotation_x(-0.35),
        c,
    );
    cube(&mut p, 0.0, 0.75, -0.1, [0.6, 0.03, 0.08], c);
    cube(&mut p, 0.0, 0.78, -0.12, [0.55, 0.7, 0.025], tone::LINEN);
    Model::new(C::Easel, fin, [0.62, 1.7, 0.6], 4.0, p)
}

/// A round birdcage of thin bars on a tall stand.
fn birdcage(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CAGE, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.2, 0.03, c);
    cyl(&mut p, 0.0, 0.03, 0.0, 0.02, 0.9, c);
    cyl(&mut p, 0.0, 0.93, 0.0, 0.22, 0.02, c);
    for i in 0..10 {
        let a = i as f32 * std::f32::consts::TAU / 10.0;
        cyl(&mut p, 0.21 * a.cos(), 0.95, 0.21 * a.sin(), 0.012, 0.42, c);
    }
    cyl(&mut p, 0.0, 1.37, 0.0, 0.22, 0.02, c);
    ball(&mut p, [0.0, 1.43, 0.0], 0.07, c);
    cube(&mut p, 0.0, 1.05, 0.0, [0.3, 0.015, 0.015], tone::WOOD);
    Model::new(C::Birdcage, fin, [0.44, 1.5, 0.44], 6.0, p)
}

/// A gas barbecue: a hooded firebox on a cart, with side shelves.
fn grill(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(GRILL, rng);
    let c = fin.rgb;
    let w = r(rng, 0.9, 1.2);
    let mut p = Vec::new();
    legs(&mut p, w - 0.4, 0.45, 0.55, 0.04, tone::METAL);
    cube(&mut p, 0.0, 0.15, 0.0, [w - 0.4, 0.02, 0.45], tone::METAL);
    bcube(&mut p, 0.0, 0.55, 0.0, [w - 0.4, 0.25, 0.5], 0.02, c);
    bcube(&mut p, 0.0, 0.8, 0.03, [w - 0.4, 0.22, 0.44], 0.04, c);
    for sx in [-1.0, 1.0] {
        cube(
            &mut p,
            sx * (w * 0.5 - 0.1),
            0.76,
            0.0,
            [0.2, 0.03, 0.42],
            tone::METAL,
        );
    }
    front(
        &mut p,
        0.5,
        [0.0, 0.95, -0.04],
        [0.3, 0.03, 0.03],
        tone::STEEL,
    );
    Model::new(C::Grill, fin, [w, 1.02, 0.5], 30.0, p)
}

/// A free-standing run of kitchen units with a worktop, in the middle of a large kitchen.
fn kitchen_island(rng: &mut ChaCha8Rng) -> Model {
    let w = r(rng, 1.4, 2.0);
    let mut m = crate::models::counter(rng, w);
    m.class = C::KitchenIsland;
    m
}

/// A narrow hall table on slim legs, with a lower shelf.
fn console_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(WOOD, rng);
    let c = fin.rgb;
    let (w, d, h) = (r(rng, 0.9, 1.3), r(rng, 0.3, 0.38), r(rng, 0.76, 0.82));
    let mut p = Vec::new();
    legs(&mut p, w, d, h - 0.03, 0.04, c);
    bcube(&mut p, 0.0, h - 0.03, 0.0, [w, 0.03, d], 0.005, c);
    cube(&mut p, 0.0, 0.15, 0.0, [w - 0.06, 0.02, d - 0.04], c);
    Model::new(C::ConsoleTable, fin, [w, h, d], 14.0, p)
        .with_top(0.03)
        .with_features(&["lower shelf"])
}

/// A dining-room cupboard: closed doors below, a glass-fronted display of shelves above.
fn china_cabinet(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(DARK_WOOD, rng);
    let c = fin.rgb;
    let (w, d, h) = (r(rng, 0.9, 1.3), 0.45, r(rng, 1.8, 2.0));
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, 0.85, d], 0.01, c);
    cube(&mut p, 0.0, 0.85, 0.06, [w - 0.06, h - 0.9, d - 0.12], c);
    cube(&mut p, 0.0, h - 0.05, 0.0, [w, 0.05, d], c);
    for sx in [-1.0, 1.0] {
        front(
            &mut p,
            d,
            [sx * w * 0.25, 0.08, -0.005],
            [w * 0.5 - 0.03, 0.7, 0.01],
            shade(c, 0.85),
        );
        front(
            &mut p,
            d - 0.12,
            [sx * w * 0.25, 0.9, -0.005],
            [w * 0.5 - 0.05, h - 1.0, 0.01],
            tone::GLASS,
        );
    }
    for i in 0..3 {
        let y = 0.85 + (i as f32 + 1.0) * (h - 0.9) / 4.0;
        cube(&mut p, 0.0, y, 0.04, [w - 0.1, 0.02, d - 0.2], c);
        cube(
            &mut p,
            0.0,
            y + 0.02,
            0.06,
            [w * 0.6, 0.2, 0.02],
            tone::WHITE,
        );
    }
    Model::new(C::ChinaCabinet, fin, [w, h, d], 70.0, p)
}

/// A folded step ladder leaning on the wall.
fn ladder(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(LADDER, rng);
    let c = fin.rgb;
    let h = r(rng, 1.4, 1.8);
    let mut p = Vec::new();
    for sx in [-1.0, 1.0] {
        cube(&mut p, sx * 0.21, 0.0, 0.0, [0.04, h, 0.08], c);
    }
    let steps = 4 + (h > 1.6) as usize;
    for i in 0..steps {
        let y = 0.25 + i as f32 * (h - 0.4) / steps as f32;
        cube(&mut p, 0.0, y, 0.0, [0.42, 0.03, 0.1], c);
    }
    cube(&mut p, 0.0, h - 0.05, 0.0, [0.46, 0.05, 0.12], tone::METAL);
    Model::new(C::Ladder, fin, [0.46, h, 0.12], 6.0, p)
}

/// A round column from floor to ceiling, with a square base and capital.
fn column(h: f32, rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PLASTER, rng);
    let c = fin.rgb;
    let rad = r(rng, 0.13, 0.18);
    let mut p = Vec::new();
    cube(
        &mut p,
        0.0,
        0.0,
        0.0,
        [rad * 2.6, 0.12, rad * 2.6],
        shade(c, 0.9),
    );
    cyl(&mut p, 0.0, 0.12, 0.0, rad, h - 0.27, c);
    cube(
        &mut p,
        0.0,
        h - 0.15,
        0.0,
        [rad * 2.6, 0.15, rad * 2.6],
        shade(c, 0.9),
    );
    Model::new(C::Column, fin, [rad * 2.6, h, rad * 2.6], 200.0, p)
}

/// A chandelier: a stem from the ceiling, a hub and a ring of arms with candle bulbs. Built
/// from its top down to `h`; it hangs with its top at the ceiling.
fn chandelier(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BRASS, rng);
    let c = fin.rgb;
    let (arms, span) = (5 + rng.random_range(0..3usize), r(rng, 0.3, 0.42));
    let h = 0.75;
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.3, 0.0, 0.012, h - 0.3, c);
    cyl(&mut p, 0.0, h - 0.02, 0.0, 0.06, 0.02, c);
    ball(&mut p, [0.0, 0.22, 0.0], 0.07, c);
    for i in 0..arms {
        let a = i as f32 * std::f32::consts::TAU / arms as f32;
        let (x, z) = (span * 0.5 * a.cos(), span * 0.5 * a.sin());
        turned(
            &mut p,
            Shape::Cuboid {
                half_extents: [span * 0.25, 0.008, 0.008],
                bevel: 0.0,
            },
            [x * 0.5, 0.2, z * 0.5],
            Quat::from_rotation_y(-a),
            c,
        );
        cyl(&mut p, x, 0.16, z, 0.03, 0.04, c);
        cyl(&mut p, x, 0.2, z, 0.012, 0.07, tone::WHITE);
        ball(&mut p, [x, 0.29, z], 0.02, [1.0, 0.93, 0.75]);
    }
    Model::new(C::Chandelier, fin, [span, h, span], 10.0, p)
}

/// A padded treatment table with a face cradle at one end.
fn massage_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CUSHION, rng);
    let mut p = Vec::new();
    legs(&mut p, 1.7, 0.6, 0.62, 0.05, tone::WOOD);
    bcube(&mut p, 0.0, 0.62, 0.0, [1.85, 0.08, 0.7], 0.015, fin.rgb);
    cube(&mut p, 1.0, 0.6, 0.0, [0.16, 0.04, 0.05], tone::METAL);
    bcube(&mut p, 1.2, 0.62, 0.0, [0.28, 0.07, 0.3], 0.015, fin.rgb);
    Model::new(C::MassageTable, fin, [2.34, 0.7, 0.7], 25.0, p)
}

/// A hammock slung between the two outward-leaning posts of its stand.
fn hammock(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CUSHION, rng);
    let wood = pick(WOOD, rng).rgb;
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [1.5, 0.05, 0.08], wood);
    for sx in [-1.0f32, 1.0] {
        cube(&mut p, sx * 0.72, 0.0, 0.0, [0.08, 0.05, 0.8], wood);
        // From the foot at x = 0.72 up to the top at x = 0.97, 1.1 m high.
        turned(
            &mut p,
            Shape::Cuboid {
                half_extents: [0.035, 0.565, 0.035],
                bevel: 0.0,
            },
            [sx * 0.845, 0.55, 0.0],
            Quat::from_rotation_z(-sx * 0.223),
            wood,
        );
    }
    // The bed of the hammock: two sloping ends and a flat middle.
    for (x, y, len, a) in [
        (-0.65f32, 0.8f32, 0.78f32, -0.695f32),
        (0.0, 0.55, 0.7, 0.0),
        (0.65, 0.8, 0.78, 0.695),
    ] {
        turned(
            &mut p,
            Shape::Cuboid {
                half_extents: [len * 0.5, 0.015, 0.36],
                bevel: 0.0,
            },
            [x, y, 0.0],
            Quat::from_rotation_z(a),
            fin.rgb,
        );
    }
    Model::new(C::Hammock, fin, [2.0, 1.1, 0.8], 12.0, p)
}

/// A long upholstered seat with a raised, sloping back at one end.
fn chaise_lounge(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(LEATHER, rng);
    let c = fin.rgb;
    let (w, d) = (r(rng, 1.5, 1.75), r(rng, 0.6, 0.7));
    let mut p = Vec::new();
    legs(&mut p, w - 0.1, d - 0.1, 0.12, 0.05, tone::WOOD);
    bcube(&mut p, 0.0, 0.12, 0.0, [w, 0.3, d], 0.04, c);
    turned(
        &mut p,
        Shape::Cuboid {
            half_extents: [0.1, 0.3, d * 0.5],
            bevel: 0.0,
        },
        [w * 0.5 - 0.18, 0.62, 0.0],
        Quat::from_rotation_z(0.45),
        c,
    );
    Model::new(C::ChaiseLounge, fin, [w, 0.9, d], 30.0, p)
}

/// A tall cactus with two arms in a pot.
fn cactus(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(POT, rng);
    let green = [0.12, 0.36, 0.14];
    let h = r(rng, 0.9, 1.4);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.17, 0.3, fin.rgb);
    cyl(&mut p, 0.0, 0.27, 0.0, 0.15, 0.03, tone::SOIL);
    cyl(&mut p, 0.0, 0.3, 0.0, 0.07, h - 0.37, green);
    ball(&mut p, [0.0, h - 0.07, 0.0], 0.07, green);
    for (sx, y0, up) in [(-1.0f32, 0.55f32, 0.3f32), (1.0, 0.75, 0.22)] {
        let x = sx * 0.14;
        cube(&mut p, sx * 0.09, y0, 0.0, [0.1, 0.07, 0.07], green);
        cyl(&mut p, x, y0, 0.0, 0.045, up, green);
        ball(&mut p, [x, y0 + up, 0.0], 0.045, green);
    }
    Model::new(C::Cactus, fin, [0.34, h, 0.34], 8.0, p)
}

/// A tall floor vase, wide in the middle, with a narrow neck.
fn urn(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(POT, rng);
    let c = fin.rgb;
    let h = r(rng, 0.6, 0.85);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.11, 0.06, c);
    cyl(&mut p, 0.0, 0.06, 0.0, 0.16, h * 0.45, c);
    ball(&mut p, [0.0, 0.06 + h * 0.45, 0.0], 0.16, c);
    cyl(&mut p, 0.0, h * 0.6, 0.0, 0.07, h * 0.4, c);
    cyl(&mut p, 0.0, h - 0.03, 0.0, 0.1, 0.03, shade(c, 0.85));
    Model::new(C::Urn, fin, [0.32, h, 0.32], 8.0, p)
}

/// A reclining outdoor sun lounger on a low frame.
fn lounger(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(WOOD, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    legs(&mut p, 0.6, 1.8, 0.25, 0.05, c);
    cube(&mut p, 0.0, 0.25, 0.15, [0.6, 0.04, 1.5], c);
    cube(
        &mut p,
        0.0,
        0.29,
        0.15,
        [0.56, 0.05, 1.45],
        pick(CUSHION, rng).rgb,
    );
    turned(
        &mut p,
        Shape::Cuboid {
            half_extents: [0.3, 0.03, 0.3],
            bevel: 0.0,
        },
        [0.0, 0.45, -0.72],
        Quat::from_rotation_x(-0.9),
        c,
    );
    Model::new(C::Lounger, fin, [0.6, 0.75, 1.9], 10.0, p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn every_listed_piece_builds_its_own_class_with_parts() {
        let kinds = RoomType::ALL;
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for &k in kinds {
            for piece in pieces(k) {
                let m = model(piece.class, 2.67, &mut rng);
                assert_eq!(m.class, piece.class, "{:?}", piece.class);
                assert!(!m.parts.is_empty());
                assert!(
                    m.w > 0.1 && m.d > 0.05 && m.h > 0.3,
                    "{:?}: {} {} {}",
                    m.class,
                    m.w,
                    m.h,
                    m.d
                );
                assert!(m.w < 3.0 && m.d < 2.0 && m.h <= 2.67, "{:?}", m.class);
            }
        }
    }
}
