//! The third lot of things issue 26 added: what people name in a home when they give
//! directions ("stop by the light switch", "the thermostat on the wall", "past the futon", "the
//! record player on the cabinet"). Two kinds:
//!
//! - things that stand in a room like furniture (a futon, a daybed, a trophy case, an amp, a
//!   microphone, a violin, a tool chest, a wheelbarrow, a shovel, a hose reel, a suitcase, a mop
//!   and bucket, a broom, a bathroom scale, firewood, a spice rack) or on the top of a piece of
//!   furniture (a sewing machine, a typewriter, a record player, a radio, a knife block): placed
//!   last in their room, after the second lot (`furnish.rs`, `add_household`), from an rng of
//!   their own seeded by the home and room;
//! - fixtures on the walls and the ceiling (light switches beside doorways, outlets, thermostats,
//!   air vents, calendars, air conditioners, range hoods over stoves, smoke detectors): added by
//!   [`add_fixtures`] after the door leaves of a floor and before its decoration (windows,
//!   pictures keep clear of them; the decoration must come last, `decor.rs`), clear of
//!   everything, so that no furniture moves. Those below the agent's head stay within the
//!   occupancy cell their wall face reaches into, as the decoration does (`decor.rs`), so the
//!   navigable map is the same with and without them.
//!
//! Like every model (`models.rs`), each is built in its own frame with its front at -Z and its
//! back (the side that goes to the wall) at +Z, and takes its colour word from its largest part.

use crate::config::ProcgenConfig;
use crate::floorplan::Plan;
use crate::home::Builder;
use crate::models::{ball, bcube, cube, cyl, disc_z, front, r, turned, Model};
use crate::palette::{f, shade, tone, Finish};
use crate::room_things::Thing;
use glam::{Quat, Vec3};
use rand::seq::{IndexedRandom, SliceRandom};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f32::consts::FRAC_PI_2;
use vlnverse_env::{
    Aabb, ObjectId, Part, Pose, RoomId, RoomType, SceneObject, SemanticClass as C, Shape,
};

/// Salt of the standing things' rng, apart from the other lots' ones.
pub(crate) const SALT: u64 = 0x40A5_E401_D7A1_6E5D;
/// Salt of the fixtures' rng (one stream a floor, seeded by its seed).
const FIXTURE_SALT: u64 = 0xF1C7_0BE5_5A17_C4E5;

/// Chance of an amp, a microphone or a violin in a room that already has an instrument: they
/// stand where the music is.
pub(crate) const WITH_INSTRUMENTS: f32 = 0.35;
/// Instruments the music things keep company with.
pub(crate) const INSTRUMENTS: [C; 5] =
    [C::Guitar, C::DrumKit, C::GrandPiano, C::Piano, C::Saxophone];
/// Chance of firewood in a room with a fireplace.
pub(crate) const BY_THE_FIRE: f32 = 0.5;

/// The chance of `th` in a room, given what the room already holds: the music things where
/// the instruments are, firewood only by a fireplace (or on a porch).
pub(crate) fn chance(th: &Thing, kind: RoomType, has: impl Fn(&[C]) -> bool) -> f32 {
    match th.class {
        C::Amplifier | C::Microphone | C::Violin if has(&INSTRUMENTS) => WITH_INSTRUMENTS,
        C::Firewood if kind != RoomType::Porch => {
            if has(&[C::Fireplace]) {
                BY_THE_FIRE
            } else {
                0.0
            }
        }
        _ => th.chance,
    }
}

/// The pieces of furniture a thing that stands on a top may stand on, in order of preference.
pub(crate) fn supports(class: C) -> &'static [C] {
    match class {
        C::SewingMachine => &[C::Desk, C::DiningTable, C::ConsoleTable],
        C::Typewriter => &[C::Desk, C::ConsoleTable, C::SideTable],
        C::RecordPlayer => &[
            C::ConsoleTable,
            C::Cabinet,
            C::Buffet,
            C::TvStand,
            C::Dresser,
            C::SideTable,
            C::Desk,
        ],
        C::Radio => &[
            C::Counter,
            C::Nightstand,
            C::Dresser,
            C::Desk,
            C::KitchenIsland,
            C::Cabinet,
            C::ConsoleTable,
        ],
        C::KnifeBlock => &[C::Counter, C::KitchenIsland],
        _ => &[],
    }
}

/// Fabrics of futon and daybed covers.
const COVER: &[Finish] = &[
    f("grey", "fabric", [0.35, 0.35, 0.37]),
    f("beige", "fabric", [0.68, 0.6, 0.46]),
    f("blue", "fabric", [0.1, 0.18, 0.42]),
    f("black", "fabric", [0.05, 0.05, 0.05]),
    f("red", "fabric", [0.5, 0.08, 0.07]),
    f("green", "fabric", [0.14, 0.3, 0.18]),
    f("white", "fabric", [0.85, 0.84, 0.8]),
];
/// Cabinet woods and paints.
const CASEWORK: &[Finish] = &[
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("white", "wood", [0.85, 0.85, 0.82]),
    f("black", "wood", [0.05, 0.05, 0.05]),
];
/// Wall plates, thermostats, vents, detectors.
const PLATE: &[Finish] = &[
    f("white", "plastic", [0.9, 0.9, 0.88]),
    f("white", "plastic", [0.86, 0.85, 0.8]),
    f("beige", "plastic", [0.78, 0.72, 0.6]),
];
/// Appliances: air conditioners and hoods.
const APPLIANCE: &[Finish] = &[
    f("white", "plastic", [0.9, 0.9, 0.9]),
    f("white", "plastic", [0.85, 0.86, 0.87]),
];
/// Range hoods.
const HOOD: &[Finish] = &[
    f("silver", "metal", [0.62, 0.62, 0.64]),
    f("silver", "metal", [0.7, 0.7, 0.72]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("white", "metal", [0.88, 0.88, 0.87]),
];
/// Amplifiers' covering.
const TOLEX: &[Finish] = &[
    f("black", "plastic", [0.04, 0.04, 0.04]),
    f("black", "plastic", [0.07, 0.07, 0.07]),
    f("brown", "plastic", [0.3, 0.18, 0.09]),
    f("beige", "plastic", [0.72, 0.62, 0.45]),
];
/// Stands and poles.
const STAND: &[Finish] = &[
    f("black", "metal", [0.04, 0.04, 0.04]),
    f("silver", "metal", [0.62, 0.62, 0.64]),
];
/// Violin varnish.
const VARNISH: &[Finish] = &[
    f("brown", "wood", [0.45, 0.2, 0.06]),
    f("brown", "wood", [0.35, 0.14, 0.04]),
    f("orange", "wood", [0.62, 0.3, 0.08]),
];
/// Tool chests and toolboxes.
const TOOL_RED: &[Finish] = &[
    f("red", "metal", [0.62, 0.06, 0.05]),
    f("red", "metal", [0.55, 0.05, 0.04]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("blue", "metal", [0.1, 0.22, 0.55]),
    f("grey", "metal", [0.4, 0.4, 0.42]),
];
/// Wheelbarrow tubs.
const TUB: &[Finish] = &[
    f("green", "metal", [0.12, 0.38, 0.15]),
    f("red", "metal", [0.6, 0.07, 0.05]),
    f("grey", "metal", [0.45, 0.45, 0.47]),
    f("black", "plastic", [0.05, 0.05, 0.05]),
    f("orange", "plastic", [0.85, 0.35, 0.05]),
];
/// Wooden handles.
const HANDLE: &[Finish] = &[
    f("wooden", "wood", [0.55, 0.36, 0.18]),
    f("wooden", "wood", [0.6, 0.42, 0.22]),
];
/// Hoses.
const HOSE: &[Finish] = &[
    f("green", "plastic", [0.1, 0.45, 0.12]),
    f("green", "plastic", [0.15, 0.55, 0.1]),
    f("black", "plastic", [0.05, 0.05, 0.05]),
    f("yellow", "plastic", [0.85, 0.7, 0.1]),
];
/// Suitcase shells.
const SHELL: &[Finish] = &[
    f("black", "plastic", [0.05, 0.05, 0.05]),
    f("blue", "plastic", [0.1, 0.2, 0.5]),
    f("red", "plastic", [0.6, 0.07, 0.06]),
    f("grey", "plastic", [0.45, 0.45, 0.47]),
    f("silver", "plastic", [0.68, 0.68, 0.7]),
    f("green", "plastic", [0.14, 0.3, 0.18]),
];
/// Buckets, broom heads, scales.
const CLEANING: &[Finish] = &[
    f("yellow", "plastic", [0.88, 0.72, 0.08]),
    f("blue", "plastic", [0.1, 0.3, 0.65]),
    f("red", "plastic", [0.62, 0.07, 0.05]),
    f("grey", "plastic", [0.45, 0.45, 0.47]),
    f("green", "plastic", [0.15, 0.5, 0.2]),
];
/// Bathroom scales.
const SCALE: &[Finish] = &[
    f("white", "plastic", [0.9, 0.9, 0.9]),
    f("black", "plastic", [0.05, 0.05, 0.05]),
    f("grey", "plastic", [0.5, 0.5, 0.52]),
];
/// Logs.
const LOG: &[Finish] = &[
    f("brown", "wood", [0.36, 0.22, 0.11]),
    f("brown", "wood", [0.3, 0.18, 0.09]),
];
/// Sewing machines.
const MACHINE: &[Finish] = &[
    f("white", "plastic", [0.9, 0.9, 0.88]),
    f("white", "plastic", [0.86, 0.86, 0.84]),
    f("black", "metal", [0.05, 0.05, 0.05]),
];
/// Typewriters.
const TYPEWRITER: &[Finish] = &[
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("green", "metal", [0.2, 0.35, 0.28]),
    f("red", "metal", [0.55, 0.08, 0.06]),
    f("beige", "metal", [0.72, 0.65, 0.5]),
    f("blue", "metal", [0.3, 0.5, 0.62]),
];
/// Record players' plinths.
const PLINTH: &[Finish] = &[
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("black", "wood", [0.05, 0.05, 0.05]),
    f("silver", "metal", [0.62, 0.62, 0.64]),
    f("white", "wood", [0.85, 0.85, 0.82]),
];
/// Radios.
const RADIO: &[Finish] = &[
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("red", "plastic", [0.6, 0.07, 0.06]),
    f("beige", "plastic", [0.75, 0.68, 0.52]),
    f("black", "plastic", [0.05, 0.05, 0.05]),
    f("silver", "metal", [0.62, 0.62, 0.64]),
    f("blue", "plastic", [0.3, 0.5, 0.62]),
];
/// Knife blocks.
const BLOCK: &[Finish] = &[
    f("wooden", "wood", [0.55, 0.36, 0.18]),
    f("brown", "wood", [0.3, 0.18, 0.09]),
    f("black", "wood", [0.05, 0.05, 0.05]),
];
/// Calendars' paper.
const PAPER: &[Finish] = &[f("white", "paper", [0.94, 0.94, 0.92])];
/// Gold for trophies.
const GOLD: [f32; 3] = [0.8, 0.62, 0.18];

/// Draw a finish from `list`, in one of its colour word's tones or its own.
fn pick(list: &[Finish], rng: &mut ChaCha8Rng) -> Finish {
    let fin = *list.choose(rng).unwrap_or(&list[0]);
    crate::tones::toned(fin, rng)
}

/// A cuboid of full size `s`, centred at `c` and turned by `rot`.
fn tilted(p: &mut Vec<Part>, c: [f32; 3], s: [f32; 3], rot: Quat, rgb: [f32; 3]) {
    let shape = Shape::Cuboid {
        half_extents: [s[0] * 0.5, s[1] * 0.5, s[2] * 0.5],
        bevel: 0.0,
    };
    turned(p, shape, c, rot, rgb);
}

/// A cylinder of radius `rad` and length `len` centred at `c`, its axis turned from +Y by
/// `rot`.
fn rod(p: &mut Vec<Part>, c: [f32; 3], rad: f32, len: f32, rot: Quat, rgb: [f32; 3]) {
    let shape = Shape::Cylinder {
        radius: rad,
        half_height: len * 0.5,
    };
    turned(p, shape, c, rot, rgb);
}

/// A rod from `a` to `b`.
fn strut(p: &mut Vec<Part>, a: Vec3, b: Vec3, rad: f32, rgb: [f32; 3]) {
    let v = b - a;
    let rot = Quat::from_rotation_arc(Vec3::Y, v.normalize_or(Vec3::Y));
    rod(p, ((a + b) * 0.5).to_array(), rad, v.length(), rot, rgb);
}

/// A small box (a knob, a key, a light) of side `s` centred at `c`.
fn dot(p: &mut Vec<Part>, c: [f32; 3], s: f32, rgb: [f32; 3]) {
    cube(p, c[0], c[1] - s * 0.5, c[2], [s, s, s], rgb);
}

/// The model of one of this module's classes; `None` for any other class. Fixtures on a wall
/// are built `depth` deep at most (their plate's distance out of the wall).
pub(crate) fn model(class: C, depth: f32, rng: &mut ChaCha8Rng) -> Option<Model> {
    Some(match class {
        C::LightSwitch => light_switch(depth, rng),
        C::Outlet => outlet(depth, rng),
        C::Thermostat => thermostat(depth, rng),
        C::AirVent => air_vent(depth, rng),
        C::SmokeDetector => smoke_detector(rng),
        C::Calendar => calendar(depth, rng),
        C::AirConditioner => air_conditioner(rng),
        C::RangeHood => range_hood(0.76, 0.8, rng),
        C::Futon => futon(rng),
        C::Daybed => daybed(rng),
        C::TrophyCase => trophy_case(rng),
        C::Amplifier => amplifier(rng),
        C::Microphone => microphone(rng),
        C::Violin => violin(rng),
        C::Toolbox => toolbox(rng),
        C::Wheelbarrow => wheelbarrow(rng),
        C::Shovel => shovel(rng),
        C::GardenHose => garden_hose(rng),
        C::Suitcase => suitcase(rng),
        C::MopBucket => mop_bucket(rng),
        C::Broom => broom(rng),
        C::BathroomScale => bathroom_scale(rng),
        C::Firewood => firewood(rng),
        C::SpiceRack => spice_rack(rng),
        C::SewingMachine => sewing_machine(rng),
        C::Typewriter => typewriter(rng),
        C::RecordPlayer => record_player(rng),
        C::Radio => radio(rng),
        C::KnifeBlock => knife_block(rng),
        _ => return None,
    })
}

/// Lowest and highest top (m above the support's foot) a thing stands on: a table, a
/// counter, a cabinet, not a tall unit (nor the pegboard of a workbench).
const TOP_RANGE: (f32, f32) = (0.4, 1.2);

/// Stand `m` on the top of a piece of furniture of room `room` of one of the classes `on` (in
/// that order, each piece in scene order), turned as the piece is, at the first spot along its
/// long side clear of what already stands on it; false when none has room.
pub(crate) fn stand_on(room: RoomId, m: &Model, on: &[C], b: &mut Builder) -> bool {
    for class in on {
        let sups: Vec<(ObjectId, Aabb, [f32; 4])> = b
            .objects
            .iter()
            .filter(|o| o.room == Some(room) && o.class == *class)
            .map(|o| (o.id, o.bbox, o.pose.rotation))
            .collect();
        for (id, bb, rot) in sups {
            let top = bb.max[1];
            if !(TOP_RANGE.0..=TOP_RANGE.1).contains(&(top - bb.min[1])) {
                continue;
            }
            // The model's width goes along the piece's own x axis.
            let ax = Quat::from_array(rot) * Vec3::X;
            let along_x = ax.x.abs() >= ax.z.abs();
            let (sx, sz) = (bb.max[0] - bb.min[0], bb.max[2] - bb.min[2]);
            let (fw, fd) = if along_x { (m.w, m.d) } else { (m.d, m.w) };
            if sx < fw + 0.06 || sz < fd + 0.06 {
                continue;
            }
            let (cx, cz) = ((bb.min[0] + bb.max[0]) * 0.5, (bb.min[2] + bb.max[2]) * 0.5);
            let long_x = sx >= sz;
            let slack = if long_x {
                sx - fw - 0.06
            } else {
                sz - fd - 0.06
            };
            // Towards the piece's back, away from the chairs pulled up to its front.
            let back = Quat::from_array(rot) * Vec3::Z;
            let spare = if long_x {
                sz - fd - 0.06
            } else {
                sx - fw - 0.06
            };
            let inward = spare.max(0.0) * 0.5;
            let (bx, bz) = if long_x {
                (0.0, back.z.signum() * inward)
            } else {
                (back.x.signum() * inward, 0.0)
            };
            for k in 0..9 {
                // The middle, then out towards both ends.
                let t = [0.0f32, -0.25, 0.25, -0.5, 0.5, -0.75, 0.75, -1.0, 1.0][k];
                let off = t * slack * 0.5;
                let (x, z) = if long_x {
                    (cx + off + bx, cz + bz)
                } else {
                    (cx + bx, cz + off + bz)
                };
                let lo = Vec3::new(x - fw * 0.5 - 0.03, top + 0.005, z - fd * 0.5 - 0.03);
                let hi = Vec3::new(x + fw * 0.5 + 0.03, top + m.h, z + fd * 0.5 + 0.03);
                let room_for = Aabb::new(lo, hi);
                let taken = b.objects.iter().any(|o| {
                    o.id != id && !o.class.is_structure() && o.bbox.intersects(&room_for, 0.0)
                });
                if taken {
                    continue;
                }
                let pose = Pose {
                    position: [x, top, z],
                    rotation: rot,
                };
                b.add_model(m, room, pose, Some(id));
                return true;
            }
        }
    }
    false
}

// ---------------------------------------------------------------------------------------
// Fixtures on the walls and the ceiling.

/// A light switch: a plate about 8 x 12 cm (or a double one) at 1.2 m, with one or two
/// rockers or toggles.
fn light_switch(depth: f32, rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PLATE, rng);
    let c = fin.rgb;
    let two = rng.random_bool(0.3);
    let (w, h) = (if two { 0.13 } else { 0.085 }, 0.125);
    let y = 1.15;
    let plate = (depth * 0.5).max(0.003);
    let mut p = Vec::new();
    // Plates have softened edges (a bevel of under half their thickness).
    bcube(&mut p, 0.0, y, -plate * 0.5, [w, h, plate], plate * 0.2, c);
    let n = if two { 2 } else { 1 };
    let rocker = shade(c, 0.93);
    for k in 0..n {
        let x = (k as f32 - (n - 1) as f32 * 0.5) * 0.05;
        let out = depth - plate;
        cube(
            &mut p,
            x,
            y + h * 0.5 - 0.03,
            -plate - out * 0.5,
            [0.03, 0.06, out],
            rocker,
        );
    }
    Model::new(C::LightSwitch, fin, [w, y + h, depth], 0.05, p)
}

/// An outlet low on the wall: a plate with two sockets, a shade darker.
fn outlet(depth: f32, rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PLATE, rng);
    let c = fin.rgb;
    let two = rng.random_bool(0.3);
    let (w, h) = (if two { 0.14 } else { 0.085 }, 0.125);
    let y = 0.28;
    let plate = (depth * 0.6).max(0.003);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, y, -plate * 0.5, [w, h, plate], plate * 0.2, c);
    let out = depth - plate;
    let cols = if two { 2 } else { 1 };
    for i in 0..cols {
        let x = (i as f32 - (cols - 1) as f32 * 0.5) * 0.06;
        for k in 0..2 {
            let yy = y + 0.025 + k as f32 * 0.045;
            let z = -plate - out * 0.5;
            cube(&mut p, x, yy, z, [0.045, 0.032, out], shade(c, 0.72));
        }
    }
    Model::new(C::Outlet, fin, [w, y + h, depth], 0.05, p)
}

/// A thermostat at eye height: a square box with a dark display and two buttons.
fn thermostat(depth: f32, rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PLATE, rng);
    let c = fin.rgb;
    let y = r(rng, 1.4, 1.5);
    let mut p = Vec::new();
    let (w, h) = (0.14, 0.1);
    bcube(
        &mut p,
        0.0,
        y,
        -depth * 0.4,
        [w, h, depth * 0.8],
        depth * 0.15,
        c,
    );
    let screen = [[0.05, 0.08, 0.1], [0.1, 0.3, 0.5], [0.15, 0.25, 0.15]][rng.random_range(0..3)];
    cube(
        &mut p,
        -0.015,
        y + 0.025,
        -depth * 0.85,
        [0.07, 0.045, depth * 0.1],
        screen,
    );
    for k in 0..2 {
        let yy = y + 0.03 + k as f32 * 0.025;
        cube(
            &mut p,
            0.045,
            yy,
            -depth * 0.85,
            [0.014, 0.014, depth * 0.1],
            shade(c, 0.8),
        );
    }
    Model::new(C::Thermostat, fin, [0.14, y + 0.1, depth], 0.2, p)
}

/// An air vent low on the wall: a frame round a dark opening with slats across it.
fn air_vent(depth: f32, rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PLATE, rng);
    let c = fin.rgb;
    let (w, h) = (r(rng, 0.3, 0.4), r(rng, 0.14, 0.18));
    let y = if rng.random_bool(0.7) {
        0.14
    } else {
        r(rng, 2.0, 2.15)
    };
    let back = (depth * 0.3).max(0.001);
    let mut p = Vec::new();
    cube(
        &mut p,
        0.0,
        y,
        -back * 0.5,
        [w, h, back],
        [0.05, 0.05, 0.05],
    );
    let out = depth - back;
    let f = 0.02;
    for (x, yy, sw, sh) in [
        (0.0, y, w, f),
        (0.0, y + h - f, w, f),
        (-(w - f) * 0.5, y, f, h),
        ((w - f) * 0.5, y, f, h),
    ] {
        bcube(
            &mut p,
            x,
            yy,
            -back - out * 0.5,
            [sw, sh, out],
            out * 0.2,
            c,
        );
    }
    let n = ((h - 2.0 * f) / 0.022) as usize;
    for k in 0..n {
        let yy = y + f + 0.004 + k as f32 * 0.022;
        cube(
            &mut p,
            0.0,
            yy,
            -back - out * 0.5,
            [w - 2.0 * f, 0.011, out],
            c,
        );
    }
    Model::new(C::AirVent, fin, [w, y + h, depth], 0.3, p)
}

/// A smoke detector on the ceiling: a round white cap with a ring of slots and a red light.
/// Built from its bottom up; its top goes against the ceiling.
fn smoke_detector(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(&PLATE[..2], rng);
    let c = fin.rgb;
    let rad = r(rng, 0.065, 0.075);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.012, 0.0, rad, 0.03, c);
    cyl(&mut p, 0.0, 0.0, 0.0, rad * 0.7, 0.012, shade(c, 0.8));
    dot(&mut p, [rad * 0.35, 0.0, 0.0], 0.008, [0.9, 0.05, 0.03]);
    Model::new(C::SmokeDetector, fin, [rad * 2.0, 0.042, rad * 2.0], 0.2, p)
}

/// A wall calendar: a picture over a grid of the month's days, on a nail.
fn calendar(depth: f32, rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PAPER, rng);
    let c = fin.rgb;
    let (w, h) = (r(rng, 0.3, 0.36), r(rng, 0.46, 0.56));
    let y = r(rng, 1.25, 1.35);
    let sheet = (depth * 0.5).max(0.002);
    let ink = (depth - sheet).max(0.0005);
    let z = -sheet - ink * 0.5;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, y, -sheet * 0.5, [w, h, sheet], sheet * 0.2, c);
    let pic = [
        [0.2, 0.45, 0.7],
        [0.2, 0.5, 0.2],
        [0.75, 0.45, 0.15],
        [0.55, 0.2, 0.4],
    ][rng.random_range(0..4)];
    cube(
        &mut p,
        0.0,
        y + h * 0.5 + 0.01,
        z,
        [w - 0.03, h * 0.45, ink],
        pic,
    );
    cube(
        &mut p,
        0.0,
        y + h * 0.5 + 0.01,
        z,
        [w - 0.03, h * 0.12, ink * 1.01],
        shade(pic, 0.5),
    );
    // The month's name, then the grid of the days.
    cube(
        &mut p,
        0.0,
        y + h * 0.44,
        z,
        [w * 0.4, 0.018, ink],
        tone::FRUIT_RED,
    );
    let (gw, gh) = (w - 0.04, h * 0.38);
    for row in 0..4 {
        let yy = y + 0.02 + row as f32 * gh / 3.0;
        cube(&mut p, 0.0, yy, z, [gw, 0.003, ink], [0.35, 0.35, 0.35]);
    }
    for col in 0..4 {
        let x = -gw * 0.5 + col as f32 * gw / 3.0;
        cube(&mut p, x, y + 0.02, z, [0.003, gh, ink], [0.35, 0.35, 0.35]);
    }
    Model::new(C::Calendar, fin, [w, y + h, depth], 0.2, p)
}

/// A wall air conditioner, high on the wall: a long rounded white unit with a dark louvre
/// along its bottom front and a small display.
fn air_conditioner(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(APPLIANCE, rng);
    let c = fin.rgb;
    let (w, h, d) = (r(rng, 0.8, 0.95), r(rng, 0.27, 0.3), r(rng, 0.19, 0.22));
    let y = 2.02;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, y + 0.03, 0.0, [w, h - 0.03, d], 0.03, c);
    cube(
        &mut p,
        0.0,
        y,
        0.01,
        [w - 0.02, 0.03, d - 0.04],
        shade(c, 0.9),
    );
    front(
        &mut p,
        d,
        [0.0, y + 0.02, 0.01],
        [w - 0.1, 0.05, 0.02],
        [0.15, 0.15, 0.16],
    );
    front(
        &mut p,
        d,
        [0.0, y + h * 0.55, -0.002],
        [w - 0.02, 0.004, 0.004],
        shade(c, 0.8),
    );
    front(
        &mut p,
        d,
        [w * 0.32, y + 0.09, -0.002],
        [0.06, 0.02, 0.004],
        [0.1, 0.3, 0.6],
    );
    Model::new(C::AirConditioner, fin, [w, y + h, d], 9.0, p)
}

/// A chimney range hood `w` wide, built from its bottom up, with a chimney `chimney` tall:
/// a shallow canopy, a sloped middle, the chimney to the ceiling, and lights and a control
/// strip under the front edge.
fn range_hood(w: f32, chimney: f32, rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(HOOD, rng);
    let c = fin.rgb;
    let d = 0.5;
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [w, 0.08, d], c);
    cube(
        &mut p,
        0.0,
        0.0,
        -d * 0.5 + 0.02,
        [w * 0.3, 0.02, 0.005],
        tone::SOOT,
    );
    // The sloped middle: a box tipped back so its front leans to the wall.
    let mid = 0.22;
    let tip = Quat::from_rotation_x(0.45);
    tilted(
        &mut p,
        [0.0, 0.08 + mid * 0.5, 0.06],
        [w * 0.55, mid, d * 0.6],
        tip,
        c,
    );
    cube(&mut p, 0.0, 0.08, 0.1, [w * 0.55, mid, d * 0.3], c);
    cube(
        &mut p,
        0.0,
        0.08 + mid,
        d * 0.5 - 0.13,
        [0.3, chimney, 0.26],
        c,
    );
    for sx in [-1.0f32, 1.0] {
        cube(
            &mut p,
            sx * w * 0.25,
            -0.003,
            -0.05,
            [0.06, 0.004, 0.06],
            [1.0, 0.95, 0.8],
        );
    }
    Model::new(C::RangeHood, fin, [w, 0.08 + mid + chimney, d], 12.0, p)
}

// ---------------------------------------------------------------------------------------
// Standing things.

/// A futon: a thick mattress folded into a seat and a back on a low slatted wooden frame with
/// wooden arms.
fn futon(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(COVER, rng);
    let c = fin.rgb;
    let wood = [[0.55, 0.36, 0.18], [0.3, 0.18, 0.09], tone::SOOT][rng.random_range(0..3)];
    let (w, d) = (r(rng, 1.85, 2.0), 0.9);
    let mut p = Vec::new();
    // Frame: two side arms (posts and an arm rail) and the seat rails.
    for sx in [-1.0f32, 1.0] {
        let x = sx * (w * 0.5 - 0.04);
        for z in [-d * 0.5 + 0.04, d * 0.5 - 0.04] {
            cube(&mut p, x, 0.0, z, [0.06, 0.62, 0.06], wood);
        }
        cube(&mut p, x, 0.58, 0.0, [0.08, 0.04, d], wood);
        cube(&mut p, x, 0.15, 0.0, [0.04, 0.05, d], wood);
    }
    cube(
        &mut p,
        0.0,
        0.2,
        -d * 0.5 + 0.06,
        [w - 0.1, 0.08, 0.04],
        wood,
    );
    // The seat part of the mattress, and the back part leaning against the back rest.
    let mw = w - 0.16;
    bcube(&mut p, 0.0, 0.28, -0.05, [mw, 0.16, d - 0.2], 0.03, c);
    tilted(
        &mut p,
        [0.0, 0.68, d * 0.5 - 0.16],
        [mw, 0.62, 0.16],
        Quat::from_rotation_x(-0.22),
        c,
    );
    cube(
        &mut p,
        0.0,
        0.3,
        d * 0.5 - 0.05,
        [w - 0.1, 0.04, 0.04],
        wood,
    );
    // Tufts: buttons along the seat.
    for k in 0..5 {
        let x = (k as f32 - 2.0) * mw / 5.0;
        dot(&mut p, [x, 0.445, -0.05], 0.02, shade(c, 0.7));
    }
    Model::new(C::Futon, fin, [w, 1.0, d], 40.0, p)
}

/// A daybed: a single mattress under a cover, in a frame with a back along its long side and
/// arms at both ends like a sofa, bolsters and pillows against the back.
fn daybed(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(COVER, rng);
    let c = fin.rgb;
    let frame = [
        [0.85, 0.85, 0.82],
        tone::SOOT,
        [0.45, 0.27, 0.13],
        [0.26, 0.15, 0.07],
    ][rng.random_range(0..4)];
    let (w, d) = (r(rng, 1.98, 2.08), 0.98);
    let mut p = Vec::new();
    // Frame: base, back (a panel with spindles' posts), end arms.
    cube(&mut p, 0.0, 0.12, 0.0, [w, 0.12, d], frame);
    legs_at(&mut p, w - 0.06, d - 0.06, 0.12, frame);
    cube(&mut p, 0.0, 0.24, d * 0.5 - 0.03, [w, 0.72, 0.05], frame);
    for sx in [-1.0f32, 1.0] {
        cube(
            &mut p,
            sx * (w * 0.5 - 0.03),
            0.24,
            0.0,
            [0.05, 0.5, d],
            frame,
        );
        cyl(
            &mut p,
            sx * (w * 0.5 - 0.03),
            0.74,
            d * 0.5 - 0.03,
            0.035,
            0.24,
            frame,
        );
    }
    // Mattress and cover, pillows and two bolsters.
    bcube(&mut p, 0.0, 0.24, -0.02, [w - 0.1, 0.2, d - 0.1], 0.03, c);
    let pil = [tone::LINEN, shade(c, 1.3), [0.75, 0.6, 0.2]][rng.random_range(0..3)];
    for k in 0..3 {
        let x = (k as f32 - 1.0) * 0.55;
        tilted(
            &mut p,
            [x, 0.62, d * 0.5 - 0.15],
            [0.48, 0.36, 0.12],
            Quat::from_rotation_x(-0.2),
            pil,
        );
    }
    for sx in [-1.0f32, 1.0] {
        let rot = Quat::from_rotation_x(FRAC_PI_2);
        rod(
            &mut p,
            [sx * (w * 0.5 - 0.16), 0.53, -0.02],
            0.09,
            d - 0.16,
            rot,
            shade(c, 0.85),
        );
    }
    Model::new(C::Daybed, fin, [w, 0.98, d], 45.0, p)
}

/// Four square legs `h` tall at the corners of a `w` x `d` rectangle.
fn legs_at(p: &mut Vec<Part>, w: f32, d: f32, h: f32, rgb: [f32; 3]) {
    for sx in [-1.0f32, 1.0] {
        for sz in [-1.0f32, 1.0] {
            cube(p, sx * w * 0.5, 0.0, sz * d * 0.5, [0.05, h, 0.05], rgb);
        }
    }
}

/// One trophy: a base, a stem and a cup with two handles, `s` of full size, standing at
/// `(x, y, z)`.
fn trophy(p: &mut Vec<Part>, x: f32, y: f32, z: f32, s: f32, metal: [f32; 3]) {
    cube(
        p,
        x,
        y,
        z,
        [0.08 * s, 0.05 * s, 0.08 * s],
        [0.1, 0.07, 0.05],
    );
    cube(p, x, y + 0.05 * s, z, [0.02 * s, 0.08 * s, 0.02 * s], metal);
    cyl(p, x, y + 0.13 * s, z, 0.045 * s, 0.09 * s, metal);
    for sx in [-1.0f32, 1.0] {
        cube(
            p,
            x + sx * 0.055 * s,
            y + 0.15 * s,
            z,
            [0.015 * s, 0.05 * s, 0.01 * s],
            metal,
        );
    }
}

/// A trophy case: a tall open cabinet with four shelves of gold and silver cups, a lit back
/// and a glass door frame.
fn trophy_case(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CASEWORK, rng);
    let c = fin.rgb;
    let (w, h, d) = (r(rng, 0.85, 1.05), r(rng, 1.75, 1.9), 0.4);
    let back = [[0.1, 0.12, 0.25], [0.35, 0.06, 0.06], [0.12, 0.12, 0.12]][rng.random_range(0..3)];
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [w, 0.1, d], c);
    cube(&mut p, 0.0, h - 0.05, 0.0, [w, 0.05, d], c);
    for sx in [-1.0f32, 1.0] {
        cube(
            &mut p,
            sx * (w - 0.04) * 0.5,
            0.1,
            0.0,
            [0.04, h - 0.15, d],
            c,
        );
    }
    cube(
        &mut p,
        0.0,
        0.1,
        d * 0.5 - 0.01,
        [w - 0.08, h - 0.15, 0.02],
        back,
    );
    let n = 4;
    let step = (h - 0.15) / n as f32;
    for k in 0..n {
        let y = 0.1 + k as f32 * step;
        if k > 0 {
            cube(&mut p, 0.0, y - 0.02, 0.0, [w - 0.08, 0.02, d - 0.03], c);
        }
        let m = 2 + rng.random_range(0..2);
        for i in 0..m {
            let x = -w * 0.35 + i as f32 * (w * 0.7) / (m - 1) as f32;
            let s = r(rng, 1.0, 1.7).min(step / 0.2 - 0.3);
            let metal = if rng.random_bool(0.75) {
                GOLD
            } else {
                tone::STEEL
            };
            trophy(&mut p, x, y, -0.02, s, metal);
        }
    }
    // The door's frame (its glass would hide the cups from the renderer, so only the frame).
    for (x, y, sw, sh) in [
        (0.0, 0.1, w - 0.08, 0.03),
        (0.0, h - 0.08, w - 0.08, 0.03),
        (0.0, 0.1, 0.03, h - 0.15),
    ] {
        front(&mut p, d, [x, y, -0.01], [sw, sh, 0.02], c);
    }
    Model::new(C::TrophyCase, fin, [w, h, d], 50.0, p)
}

/// A guitar amplifier on the floor: a box covered in black (or brown, or cream) with a grille
/// cloth front over the speaker, a control strip with knobs along the top and a handle.
fn amplifier(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(TOLEX, rng);
    let c = fin.rgb;
    let (w, h, d) = (r(rng, 0.5, 0.65), r(rng, 0.45, 0.6), r(rng, 0.25, 0.3));
    let cloth = [[0.2, 0.2, 0.2], [0.6, 0.55, 0.45], [0.35, 0.3, 0.25]][rng.random_range(0..3)];
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.02, 0.0, [w, h - 0.02, d], 0.015, c);
    for sx in [-1.0f32, 1.0] {
        for sz in [-1.0f32, 1.0] {
            cube(
                &mut p,
                sx * (w * 0.5 - 0.04),
                0.0,
                sz * (d * 0.5 - 0.04),
                [0.04, 0.02, 0.04],
                tone::SOOT,
            );
        }
    }
    front(
        &mut p,
        d,
        [0.0, 0.05, -0.003],
        [w - 0.06, h - 0.18, 0.006],
        cloth,
    );
    disc_z(
        &mut p,
        [0.0, 0.05 + (h - 0.18) * 0.5, -d * 0.5 - 0.005],
        (h - 0.25) * 0.45,
        0.004,
        shade(cloth, 0.8),
    );
    front(
        &mut p,
        d,
        [0.0, h - 0.12, -0.003],
        [w - 0.06, 0.08, 0.006],
        [0.75, 0.72, 0.65],
    );
    for k in 0..6 {
        let x = -w * 0.35 + k as f32 * w * 0.12;
        dot(&mut p, [x, h - 0.07, -d * 0.5 - 0.012], 0.022, tone::SOOT);
    }
    cube(&mut p, 0.0, h, 0.0, [0.2, 0.025, 0.04], tone::SOOT);
    Model::new(C::Amplifier, fin, [w, h + 0.03, d], 15.0, p)
}

/// A microphone on a stand: a round weighted base, a pole about head high, a boom out in
/// front and the microphone at its end with a cable down the pole.
fn microphone(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(STAND, rng);
    let c = fin.rgb;
    let h = r(rng, 1.35, 1.5);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.15, 0.025, c);
    cyl(&mut p, 0.0, 0.025, 0.0, 0.012, h, c);
    cyl(&mut p, 0.0, h * 0.6, 0.0, 0.02, 0.05, c);
    let top = Vec3::new(0.0, h + 0.02, 0.0);
    let end = Vec3::new(0.0, h + 0.16, -0.32);
    strut(&mut p, top, end, 0.009, c);
    // The microphone: a black handle and a silver mesh head, pointing forward and up.
    let dir = Vec3::new(0.0, 0.3, -1.0).normalize();
    let body = end + dir * 0.08;
    strut(&mut p, end, body + dir * 0.04, 0.018, tone::SOOT);
    let head = body + dir * 0.08;
    ball(&mut p, head.to_array(), 0.03, tone::STEEL);
    Model::new(C::Microphone, fin, [0.3, h + 0.25, 0.5], 3.0, p)
}

/// A violin standing upright on a small stand: the body (a wide lower bout, a narrow waist
/// and an upper bout), the black fingerboard and neck up to the scroll, the strings, the
/// bridge and the two f-holes, with its bow leaning beside it.
fn violin(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(VARNISH, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    // The stand: a foot, a post, a cradle under the body.
    let st = tone::SOOT;
    cyl(&mut p, 0.0, 0.0, 0.0, 0.12, 0.02, st);
    cyl(&mut p, 0.0, 0.02, 0.02, 0.012, 0.2, st);
    cube(&mut p, 0.0, 0.2, 0.0, [0.2, 0.02, 0.06], st);
    // The body stands on its bottom edge at y0, its face to the front.
    let y0 = 0.22;
    let (thick, z) = (0.045, 0.0);
    disc_z(&mut p, [0.0, y0 + 0.1, z], 0.1, thick, c);
    disc_z(&mut p, [0.0, y0 + 0.27, z], 0.085, thick, c);
    cube(&mut p, 0.0, y0 + 0.12, z, [0.12, 0.14, thick], c);
    let dark = shade(c, 0.55);
    let face = -thick * 0.5 - 0.003;
    // The fingerboard along the upper half, the neck and the scroll above.
    cube(
        &mut p,
        0.0,
        y0 + 0.14,
        z + face - 0.004,
        [0.04, 0.27, 0.008],
        tone::SOOT,
    );
    cube(&mut p, 0.0, y0 + 0.35, z, [0.028, 0.14, 0.03], c);
    cube(&mut p, 0.0, y0 + 0.47, z, [0.03, 0.06, 0.035], dark);
    ball(&mut p, [0.0, y0 + 0.55, z], 0.025, c);
    // The bridge, the strings, the tailpiece, the f-holes.
    cube(
        &mut p,
        0.0,
        y0 + 0.1,
        z + face,
        [0.05, 0.015, 0.006],
        [0.85, 0.75, 0.55],
    );
    cube(
        &mut p,
        0.0,
        y0 + 0.02,
        z + face,
        [0.03, 0.08, 0.006],
        tone::SOOT,
    );
    for k in 0..4 {
        let x = (k as f32 - 1.5) * 0.006;
        cube(
            &mut p,
            x,
            y0 + 0.06,
            z + face - 0.009,
            [0.0015, 0.42, 0.0015],
            [0.85, 0.85, 0.82],
        );
    }
    for sx in [-1.0f32, 1.0] {
        let rot = Quat::from_rotation_z(sx * 0.15);
        tilted(
            &mut p,
            [sx * 0.045, y0 + 0.13, z + face],
            [0.006, 0.07, 0.002],
            rot,
            tone::SOOT,
        );
    }
    // The bow, leaning beside the body.
    let rot = Quat::from_rotation_z(-0.12);
    rod(
        &mut p,
        [0.14, 0.37, 0.0],
        0.004,
        0.72,
        rot,
        [0.3, 0.15, 0.05],
    );
    Model::new(C::Violin, fin, [0.36, 0.8, 0.24], 1.0, p)
}

/// A rolling tool chest: a bottom cabinet of wide drawers on casters, a top chest of narrow
/// drawers with a lid, steel pulls, and a portable toolbox on top of it all.
fn toolbox(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(TOOL_RED, rng);
    let c = fin.rgb;
    let (w, d) = (r(rng, 0.68, 0.8), 0.46);
    let (h0, h1) = (0.78, 0.42);
    let mut p = Vec::new();
    for sx in [-1.0f32, 1.0] {
        for sz in [-1.0f32, 1.0] {
            cyl(
                &mut p,
                sx * (w * 0.5 - 0.06),
                0.0,
                sz * (d * 0.5 - 0.06),
                0.04,
                0.08,
                tone::SOOT,
            );
        }
    }
    bcube(&mut p, 0.0, 0.08, 0.0, [w, h0, d], 0.01, c);
    bcube(
        &mut p,
        0.0,
        0.08 + h0 + 0.01,
        0.02,
        [w - 0.02, h1, d - 0.04],
        0.01,
        c,
    );
    let rows: [(f32, f32, usize); 2] = [(0.1, h0 - 0.05, 4), (0.08 + h0 + 0.03, h1 - 0.1, 5)];
    for (y, span, n) in rows {
        for k in 0..n {
            let yy = y + k as f32 * span / n as f32;
            front(
                &mut p,
                d,
                [0.0, yy + span / n as f32 - 0.014, -0.002],
                [w - 0.04, 0.006, 0.006],
                tone::SOOT,
            );
            front(
                &mut p,
                d,
                [0.0, yy + span / n as f32 * 0.5, -0.012],
                [w * 0.7, 0.018, 0.02],
                tone::STEEL,
            );
        }
    }
    // A portable toolbox on top: a box, a lid, a handle.
    let top = 0.08 + h0 + 0.01 + h1;
    let tb = [tone::FRUIT_RED, tone::SOOT, [0.1, 0.3, 0.6]][rng.random_range(0..3)];
    cube(&mut p, -w * 0.15, top, 0.0, [0.42, 0.16, 0.2], tb);
    cube(
        &mut p,
        -w * 0.15,
        top + 0.16,
        0.0,
        [0.43, 0.03, 0.21],
        shade(tb, 0.7),
    );
    cube(
        &mut p,
        -w * 0.15,
        top + 0.19,
        0.0,
        [0.2, 0.02, 0.03],
        tone::SOOT,
    );
    for sx in [-1.0f32, 1.0] {
        cube(
            &mut p,
            -w * 0.15 + sx * 0.1,
            top + 0.19,
            0.0,
            [0.02, 0.04, 0.03],
            tone::SOOT,
        );
    }
    Model::new(C::Toolbox, fin, [w, top + 0.23, d], 60.0, p)
}

/// A wheelbarrow, its length along the wall: a deep tray, one wheel at the front, two long
/// handles out the back and two legs under them.
fn wheelbarrow(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(TUB, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    let frame = tone::SOOT;
    // The wheel at -x, the handles to +x.
    let wheel = Vec3::new(-0.62, 0.2, 0.0);
    let rot = Quat::from_rotation_x(FRAC_PI_2);
    rod(&mut p, wheel.to_array(), 0.2, 0.08, rot, tone::SOOT);
    rod(&mut p, wheel.to_array(), 0.1, 0.09, rot, tone::STEEL);
    for sz in [-1.0f32, 1.0] {
        let z = sz * 0.25;
        strut(
            &mut p,
            Vec3::new(-0.62, 0.2, sz * 0.05),
            Vec3::new(0.72, 0.6, z),
            0.016,
            frame,
        );
        strut(
            &mut p,
            Vec3::new(0.3, 0.45, z),
            Vec3::new(0.35, 0.0, z),
            0.014,
            frame,
        );
        cube(&mut p, 0.76, 0.57, z, [0.14, 0.06, 0.045], tone::SOOT);
    }
    // The tray: a bottom, a sloped front and back, and two sides.
    cube(&mut p, 0.0, 0.38, 0.0, [0.55, 0.03, 0.56], c);
    let tip = 0.7;
    tilted(
        &mut p,
        [-0.38, 0.56, 0.0],
        [0.03, 0.42, 0.66],
        Quat::from_rotation_z(-tip),
        c,
    );
    tilted(
        &mut p,
        [0.3, 0.56, 0.0],
        [0.03, 0.36, 0.66],
        Quat::from_rotation_z(0.35),
        c,
    );
    for sz in [-1.0f32, 1.0] {
        let rot = Quat::from_rotation_x(sz * 0.25);
        tilted(&mut p, [-0.05, 0.56, sz * 0.3], [0.82, 0.36, 0.03], rot, c);
    }
    Model::new(C::Wheelbarrow, fin, [1.5, 0.75, 0.72], 20.0, p)
}

/// A shovel leaning against the wall: a wooden handle with a grip at the top and a steel
/// blade on the floor a little out from the wall.
fn shovel(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(HANDLE, rng);
    let c = fin.rgb;
    let blade = [tone::STEEL, tone::SOOT, [0.6, 0.1, 0.06]][rng.random_range(0..3)];
    let len = r(rng, 1.2, 1.35);
    let lean = 0.22f32;
    let mut p = Vec::new();
    // In the model frame the wall is at +z: the handle goes from the blade (front, low) up
    // and back to the wall.
    let foot = Vec3::new(0.0, 0.3, -0.12);
    let top = foot + Vec3::new(0.0, lean.cos(), lean.sin()) * len;
    strut(&mut p, foot, top, 0.018, c);
    cube(
        &mut p,
        0.0,
        top.y - 0.02,
        top.z - 0.02,
        [0.13, 0.035, 0.035],
        shade(c, 0.8),
    );
    cube(
        &mut p,
        0.0,
        top.y - 0.1,
        top.z - 0.03,
        [0.025, 0.1, 0.02],
        shade(c, 0.8),
    );
    // The blade: a rounded plate tipped like the handle, a socket into the handle.
    let rot = Quat::from_rotation_x(-lean);
    tilted(&mut p, [0.0, 0.16, -0.16], [0.24, 0.3, 0.012], rot, blade);
    ball(&mut p, [0.0, 0.03, -0.2], 0.05, blade);
    rod(&mut p, [0.0, 0.32, -0.12], 0.025, 0.1, rot, blade);
    Model::new(C::Shovel, fin, [0.26, top.y + 0.02, 0.5], 2.0, p)
}

/// A garden hose on a wall reel: a bracket plate, the drum wound with coils of hose, a crank,
/// and the end of the hose with its nozzle hanging down.
fn garden_hose(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(HOSE, rng);
    let c = fin.rgb;
    let y = r(rng, 0.75, 0.9);
    let reel = [tone::SOOT, [0.2, 0.3, 0.6], [0.45, 0.45, 0.47]][rng.random_range(0..3)];
    let mut p = Vec::new();
    cube(&mut p, 0.0, y - 0.25, -0.01, [0.2, 0.5, 0.02], reel);
    for side in [-0.02f32, -0.27] {
        disc_z(&mut p, [0.0, y, side - 0.01], 0.25, 0.015, reel);
    }
    disc_z(&mut p, [0.0, y, -0.145], 0.2, 0.23, c);
    // The coils: thin darker rings round the wound hose.
    for k in 0..3 {
        let z = -0.06 - k as f32 * 0.07;
        disc_z(&mut p, [0.0, y, z], 0.205, 0.006, shade(c, 0.7));
    }
    disc_z(&mut p, [0.0, y, -0.3], 0.03, 0.04, reel);
    cube(&mut p, 0.1, y - 0.02, -0.33, [0.2, 0.03, 0.03], reel);
    cube(&mut p, 0.2, y - 0.04, -0.38, [0.03, 0.05, 0.08], tone::SOOT);
    // The free end down the front and its nozzle.
    let a = Vec3::new(0.12, y - 0.16, -0.2);
    let b = Vec3::new(0.22, 0.2, -0.22);
    strut(&mut p, a, b, 0.012, c);
    strut(
        &mut p,
        b,
        Vec3::new(0.22, 0.06, -0.22),
        0.014,
        [0.9, 0.55, 0.05],
    );
    Model::new(C::GardenHose, fin, [0.52, y + 0.26, 0.4], 8.0, p)
}

/// A hard-shell suitcase standing on its wheels, its pull-up handle out, with ribs down its
/// front, and (some) a smaller one beside it.
fn suitcase(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(SHELL, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    let two = rng.random_bool(0.4);
    let cases: &[(f32, f32, f32, f32)] = if two {
        &[(-0.15, 0.46, 0.7, 0.28), (0.2, 0.36, 0.55, 0.22)]
    } else {
        &[(0.0, 0.46, 0.7, 0.28)]
    };
    for &(x, w, h, d) in cases {
        let z = 0.14 - d * 0.5;
        for sx in [-1.0f32, 1.0] {
            for sz in [-1.0f32, 1.0] {
                cube(
                    &mut p,
                    x + sx * (w * 0.5 - 0.04),
                    0.0,
                    z + sz * (d * 0.5 - 0.04),
                    [0.05, 0.05, 0.03],
                    tone::SOOT,
                );
            }
        }
        bcube(&mut p, x, 0.05, z, [w, h, d], 0.03, c);
        cube(
            &mut p,
            x,
            0.05 + h * 0.5 - 0.01,
            z,
            [w + 0.005, 0.02, d + 0.005],
            shade(c, 0.6),
        );
        for k in 0..4 {
            let xx = x + (k as f32 - 1.5) * w * 0.2;
            cube(
                &mut p,
                xx,
                0.1,
                z - d * 0.5 - 0.005,
                [0.02, h - 0.1, 0.01],
                shade(c, 0.85),
            );
        }
        // The telescopic handle from the top.
        for sx in [-1.0f32, 1.0] {
            cube(
                &mut p,
                x + sx * 0.1,
                0.05 + h,
                z + d * 0.3,
                [0.015, 0.3, 0.015],
                tone::STEEL,
            );
        }
        cube(
            &mut p,
            x,
            0.35 + h,
            z + d * 0.3,
            [0.24, 0.03, 0.03],
            tone::SOOT,
        );
    }
    Model::new(C::Suitcase, fin, [0.8, 1.1, 0.28], 5.0, p)
}

/// A mop and bucket: a wide bucket on casters with a wringer on its rim, and a mop standing
/// in it, its handle up against the wall.
fn mop_bucket(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CLEANING, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    for (x, z) in [(-0.17, -0.12), (0.17, -0.12), (-0.17, 0.12), (0.17, 0.12)] {
        cyl(&mut p, x, 0.0, z, 0.025, 0.05, tone::SOOT);
    }
    bcube(&mut p, 0.0, 0.05, 0.0, [0.44, 0.34, 0.34], 0.04, c);
    cube(&mut p, 0.0, 0.36, 0.0, [0.4, 0.02, 0.3], [0.35, 0.5, 0.55]);
    // The wringer on one half, its lever up.
    cube(&mut p, 0.1, 0.38, 0.0, [0.2, 0.14, 0.26], shade(c, 0.8));
    strut(
        &mut p,
        Vec3::new(0.18, 0.5, 0.0),
        Vec3::new(0.24, 0.95, 0.08),
        0.012,
        tone::STEEL,
    );
    // The mop: a grey tangle in the bucket, the handle to the wall.
    ball(&mut p, [-0.1, 0.37, 0.0], 0.1, [0.75, 0.75, 0.72]);
    let handle = [[0.55, 0.36, 0.18], tone::STEEL, [0.2, 0.3, 0.6]][rng.random_range(0..3)];
    strut(
        &mut p,
        Vec3::new(-0.1, 0.35, 0.0),
        Vec3::new(-0.12, 1.35, 0.14),
        0.014,
        handle,
    );
    Model::new(C::MopBucket, fin, [0.46, 1.36, 0.34], 6.0, p)
}

/// A broom leaning in a corner: a wide brush head of stiff bristles on the floor, its long
/// handle up to the wall, and a dustpan beside it.
fn broom(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CLEANING, rng);
    let c = fin.rgb;
    let handle = [[0.55, 0.36, 0.18], tone::STEEL, tone::SOOT][rng.random_range(0..3)];
    let bristles = [[0.75, 0.62, 0.3], tone::SOOT, shade(c, 0.7)][rng.random_range(0..3)];
    let mut p = Vec::new();
    let lean = 0.2f32;
    let rot = Quat::from_rotation_x(-lean);
    tilted(
        &mut p,
        [0.0, 0.06, -0.1],
        [0.32, 0.11, 0.06],
        Quat::IDENTITY,
        bristles,
    );
    tilted(
        &mut p,
        [0.0, 0.14, -0.1],
        [0.34, 0.06, 0.07],
        Quat::IDENTITY,
        c,
    );
    let foot = Vec3::new(0.0, 0.17, -0.1);
    let top = foot + Vec3::new(0.0, lean.cos(), lean.sin()) * 1.25;
    strut(&mut p, foot, top, 0.013, handle);
    tilted(
        &mut p,
        [0.0, top.y - 0.04, top.z],
        [0.03, 0.08, 0.03],
        rot,
        c,
    );
    // The dustpan, standing on its lip against the wall beside the broom.
    let pan = shade(c, 0.9);
    tilted(
        &mut p,
        [0.3, 0.14, 0.0],
        [0.26, 0.26, 0.015],
        Quat::from_rotation_x(-0.12),
        pan,
    );
    cube(&mut p, 0.3, 0.26, 0.02, [0.04, 0.14, 0.03], pan);
    Model::new(C::Broom, fin, [0.62, top.y + 0.02, 0.3], 1.0, p)
}

/// A bathroom scale on the floor: a flat square with a round dial or a display.
fn bathroom_scale(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(SCALE, rng);
    let c = fin.rgb;
    let s = r(rng, 0.28, 0.32);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.005, 0.0, [s, 0.04, s], 0.008, c);
    for (x, z) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        cube(
            &mut p,
            x * (s * 0.5 - 0.03),
            0.0,
            z * (s * 0.5 - 0.03),
            [0.03, 0.005, 0.03],
            tone::SOOT,
        );
    }
    if rng.random_bool(0.5) {
        cyl(&mut p, 0.0, 0.045, -s * 0.28, 0.05, 0.004, tone::WHITE);
        cube(
            &mut p,
            0.0,
            0.049,
            -s * 0.28 + 0.02,
            [0.004, 0.002, 0.04],
            tone::FRUIT_RED,
        );
    } else {
        cube(
            &mut p,
            0.0,
            0.045,
            -s * 0.32,
            [0.08, 0.003, 0.035],
            [0.08, 0.1, 0.12],
        );
    }
    // Two pads where the feet go.
    for sx in [-1.0f32, 1.0] {
        cube(
            &mut p,
            sx * s * 0.2,
            0.045,
            s * 0.08,
            [0.08, 0.003, 0.14],
            shade(c, 0.85),
        );
    }
    Model::new(C::BathroomScale, fin, [s, 0.05, s], 2.0, p)
}

/// Firewood: split logs stacked in a black iron rack.
fn firewood(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(LOG, rng);
    let c = fin.rgb;
    let w = r(rng, 0.7, 0.9);
    let d = 0.38;
    let mut p = Vec::new();
    // The rack: two hoops (as four posts and a bottom rail each) and rails along.
    for sx in [-1.0f32, 1.0] {
        let x = sx * (w * 0.5 - 0.02);
        for sz in [-1.0f32, 1.0] {
            cube(
                &mut p,
                x,
                0.0,
                sz * (d * 0.5 - 0.02),
                [0.025, 0.62, 0.025],
                tone::SOOT,
            );
        }
        cube(&mut p, x, 0.05, 0.0, [0.025, 0.025, d], tone::SOOT);
    }
    for sz in [-1.0f32, 1.0] {
        cube(
            &mut p,
            0.0,
            0.05,
            sz * (d * 0.5 - 0.02),
            [w, 0.025, 0.025],
            tone::SOOT,
        );
    }
    // Logs along the rack, rows of three or four.
    let rot = Quat::from_rotation_z(FRAC_PI_2);
    for row in 0..4 {
        let n = 4 - row % 2;
        for k in 0..n {
            let rad = r(rng, 0.045, 0.055);
            let z = -d * 0.5 + 0.07 + k as f32 * (d - 0.14) / 3.0 + (row % 2) as f32 * 0.04;
            let y = 0.12 + row as f32 * 0.1;
            let len = w - 0.06 - r(rng, 0.0, 0.06);
            rod(&mut p, [0.0, y, z], rad, len, rot, c);
        }
    }
    Model::new(C::Firewood, fin, [w, 0.62, d], 30.0, p)
}

/// A spice rack on the wall above the floor: a wooden frame of three shelves, each with a
/// rail and a row of small jars with coloured spices and lids.
fn spice_rack(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BLOCK, rng);
    let c = fin.rgb;
    let w = r(rng, 0.45, 0.6);
    let (y, h, d) = (1.2, 0.5, 0.11);
    let mut p = Vec::new();
    for sx in [-1.0f32, 1.0] {
        cube(&mut p, sx * (w * 0.5 - 0.01), y, 0.0, [0.02, h, d], c);
    }
    cube(&mut p, 0.0, y, d * 0.5 - 0.005, [w, h, 0.01], shade(c, 0.8));
    let spices = [
        [0.6, 0.15, 0.05],
        [0.75, 0.55, 0.1],
        [0.25, 0.35, 0.1],
        [0.45, 0.25, 0.12],
        [0.85, 0.8, 0.6],
        [0.7, 0.3, 0.05],
    ];
    for row in 0..3 {
        let yy = y + row as f32 * h / 3.0;
        bcube(&mut p, 0.0, yy, 0.0, [w - 0.02, 0.015, d], 0.003, c);
        cube(
            &mut p,
            0.0,
            yy + 0.06,
            -d * 0.5 + 0.005,
            [w - 0.02, 0.01, 0.01],
            c,
        );
        let n = ((w - 0.04) / 0.06) as usize;
        for k in 0..n {
            let x = -w * 0.5 + 0.05 + k as f32 * (w - 0.08) / (n.max(2) - 1) as f32;
            let s = spices[(row * 3 + k) % spices.len()];
            // Jars as boxes: at this size they read the same for a fraction of the triangles.
            cube(&mut p, x, yy + 0.015, 0.0, [0.04, 0.09, 0.04], s);
            cube(&mut p, x, yy + 0.105, 0.0, [0.042, 0.02, 0.042], tone::SOOT);
        }
    }
    Model::new(C::SpiceRack, fin, [w, y + h, d], 3.0, p)
}

/// A sewing machine: a base, the pillar on its right, the arm across the top and the head on
/// the left with the needle down to the plate, a hand wheel and a spool of thread on top.
fn sewing_machine(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(MACHINE, rng);
    let c = fin.rgb;
    let accent = [
        [0.2, 0.4, 0.7],
        tone::FRUIT_RED,
        [0.5, 0.3, 0.6],
        tone::STEEL,
    ][rng.random_range(0..4)];
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [0.42, 0.08, 0.19], 0.01, c);
    bcube(&mut p, 0.14, 0.08, 0.0, [0.13, 0.16, 0.16], 0.01, c);
    bcube(&mut p, 0.0, 0.24, 0.0, [0.42, 0.08, 0.16], 0.015, c);
    bcube(&mut p, -0.17, 0.14, 0.0, [0.08, 0.1, 0.15], 0.01, c);
    front(
        &mut p,
        0.16,
        [0.0, 0.255, -0.002],
        [0.28, 0.05, 0.004],
        accent,
    );
    cube(
        &mut p,
        -0.17,
        0.09,
        -0.02,
        [0.004, 0.05, 0.004],
        tone::STEEL,
    );
    cube(&mut p, -0.17, 0.08, -0.02, [0.06, 0.004, 0.08], tone::STEEL);
    disc_z(&mut p, [0.22, 0.22, 0.0], 0.05, 0.03, shade(c, 0.8));
    cyl(&mut p, 0.05, 0.32, 0.0, 0.015, 0.04, accent);
    Model::new(C::SewingMachine, fin, [0.45, 0.36, 0.19], 8.0, p)
}

/// A typewriter: a low body with a sloped keyboard of round keys at the front, the roller
/// across the back with a sheet of paper in it, and the carriage return lever.
fn typewriter(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(TYPEWRITER, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.03, [0.34, 0.09, 0.2], 0.015, c);
    tilted(
        &mut p,
        [0.0, 0.05, -0.1],
        [0.32, 0.04, 0.12],
        Quat::from_rotation_x(0.25),
        c,
    );
    for row in 0..4 {
        let z = -0.145 + row as f32 * 0.025;
        let y = 0.068 + row as f32 * 0.007;
        for k in 0..10 {
            let x = (k as f32 - 4.5) * 0.026 + (row % 2) as f32 * 0.008;
            cube(&mut p, x, y, z, [0.015, 0.01, 0.015], tone::SOOT);
            cube(&mut p, x, y + 0.01, z, [0.012, 0.002, 0.012], tone::WHITE);
        }
    }
    let rot = Quat::from_rotation_z(FRAC_PI_2);
    rod(&mut p, [0.0, 0.12, 0.07], 0.025, 0.4, rot, tone::SOOT);
    cube(&mut p, 0.0, 0.1, 0.09, [0.4, 0.03, 0.05], c);
    tilted(
        &mut p,
        [0.0, 0.2, 0.085],
        [0.21, 0.16, 0.002],
        Quat::from_rotation_x(-0.15),
        tone::WHITE,
    );
    cube(&mut p, -0.22, 0.13, 0.06, [0.06, 0.01, 0.01], tone::STEEL);
    Model::new(C::Typewriter, fin, [0.44, 0.28, 0.3], 6.0, p)
}

/// A record player: a plinth with a black record on the platter, its label, the tone arm
/// resting beside it, and two knobs at the front.
fn record_player(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PLINTH, rng);
    let c = fin.rgb;
    let (w, d) = (0.4, 0.3);
    let mut p = Vec::new();
    for (x, z) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        cyl(
            &mut p,
            x * (w * 0.5 - 0.04),
            0.0,
            z * (d * 0.5 - 0.04),
            0.022,
            0.015,
            tone::SOOT,
        );
    }
    bcube(&mut p, 0.0, 0.015, 0.0, [w, 0.08, d], 0.006, c);
    let py = 0.095;
    cyl(&mut p, -0.05, py, 0.0, 0.155, 0.01, tone::STEEL);
    cyl(
        &mut p,
        -0.05,
        py + 0.01,
        0.0,
        0.15,
        0.004,
        [0.02, 0.02, 0.02],
    );
    let label = [tone::FRUIT_RED, [0.9, 0.8, 0.3], [0.2, 0.4, 0.75]][rng.random_range(0..3)];
    cyl(&mut p, -0.05, py + 0.014, 0.0, 0.045, 0.001, label);
    cyl(&mut p, -0.05, py + 0.015, 0.0, 0.004, 0.012, tone::STEEL);
    // The tone arm, from its pivot at the back right to the record's edge.
    cyl(&mut p, 0.17, py, 0.11, 0.022, 0.03, tone::STEEL);
    strut(
        &mut p,
        Vec3::new(0.17, py + 0.04, 0.11),
        Vec3::new(0.1, py + 0.035, -0.1),
        0.005,
        tone::STEEL,
    );
    cube(
        &mut p,
        0.1,
        py + 0.02,
        -0.1,
        [0.02, 0.02, 0.035],
        tone::SOOT,
    );
    for x in [0.12, 0.18] {
        disc_z(
            &mut p,
            [x, 0.05, -d * 0.5 - 0.006],
            0.012,
            0.012,
            tone::STEEL,
        );
    }
    Model::new(C::RecordPlayer, fin, [w, 0.15, d], 6.0, p)
}

/// A radio: a box with a round speaker grille on one side, a tuning dial, two knobs, a handle
/// and an antenna.
fn radio(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(RADIO, rng);
    let c = fin.rgb;
    let (w, h, d) = (r(rng, 0.28, 0.34), r(rng, 0.16, 0.2), 0.11);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, h, d], 0.012, c);
    let grille = [[0.75, 0.7, 0.6], tone::SOOT, [0.4, 0.4, 0.42]][rng.random_range(0..3)];
    disc_z(
        &mut p,
        [-w * 0.2, h * 0.5, -d * 0.5 - 0.002],
        h * 0.36,
        0.006,
        grille,
    );
    for k in 0..4 {
        let y = h * 0.5 + (k as f32 - 1.5) * h * 0.14;
        cube(
            &mut p,
            -w * 0.2,
            y,
            -d * 0.5 - 0.006,
            [h * 0.55, 0.004, 0.002],
            shade(grille, 0.6),
        );
    }
    front(
        &mut p,
        d,
        [w * 0.22, h * 0.55, -0.002],
        [w * 0.38, h * 0.25, 0.004],
        [0.85, 0.8, 0.6],
    );
    cube(
        &mut p,
        w * 0.22,
        h * 0.55,
        -d * 0.5 - 0.005,
        [0.003, h * 0.22, 0.002],
        tone::FRUIT_RED,
    );
    for x in [w * 0.12, w * 0.32] {
        disc_z(
            &mut p,
            [x, h * 0.25, -d * 0.5 - 0.008],
            0.016,
            0.016,
            tone::SOOT,
        );
    }
    cube(&mut p, 0.0, h, 0.0, [w * 0.6, 0.012, 0.02], tone::SOOT);
    let rot = Quat::from_rotation_z(-0.3);
    rod(
        &mut p,
        [w * 0.5 + 0.007, h + 0.12, 0.03],
        0.003,
        0.25,
        rot,
        tone::STEEL,
    );
    Model::new(C::Radio, fin, [w, h, d], 2.0, p)
}

/// A knife block: a wooden block tipped back, with the black handles of five knives in its
/// slots.
fn knife_block(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BLOCK, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    let tip = Quat::from_rotation_x(0.35);
    // Its lowest edge on the base, which stands on the counter.
    tilted(&mut p, [0.0, 0.17, 0.02], [0.12, 0.24, 0.15], tip, c);
    bcube(&mut p, 0.0, 0.0, 0.03, [0.12, 0.03, 0.2], 0.005, c);
    let handle = [tone::SOOT, tone::STEEL, [0.4, 0.22, 0.1]][rng.random_range(0..3)];
    for (k, &(x, dz)) in [
        (-0.03f32, -0.04f32),
        (0.0, -0.04),
        (0.03, -0.04),
        (-0.02, 0.02),
        (0.02, 0.02),
    ]
    .iter()
    .enumerate()
    {
        let base = Vec3::new(x, 0.29, 0.02 + dz);
        let len = 0.1 + (k % 2) as f32 * 0.02;
        let dir = tip * Vec3::Y;
        let mid = base + dir * len * 0.5;
        tilted(&mut p, mid.to_array(), [0.02, len, 0.022], tip, handle);
        cube(
            &mut p,
            base.x,
            base.y - 0.005,
            base.z,
            [0.006, 0.012, 0.03],
            tone::STEEL,
        );
    }
    Model::new(C::KnifeBlock, fin, [0.12, 0.42, 0.2], 2.0, p)
}

// ---------------------------------------------------------------------------------------
// Fixtures: placement.

/// Occupancy cell fixtures below the agent's head keep within, and the margin to a cell
/// boundary (the decoration's, `decor.rs`).
const GRID: f64 = 0.05;
const GRID_MARGIN: f64 = 3e-4;
/// Deepest a fixture below the agent's head is built (m out of the wall).
const FLUSH: f32 = 0.02;
/// Thinnest it may be: where the wall face leaves less of its cell, the wall is skipped.
const THINNEST: f32 = 0.004;
/// Distance (m) of a light switch's centre from its doorway's gap.
const SWITCH_OFF: f32 = 0.18;
/// Gap (m) a fixture keeps to everything else on its wall.
const GAP: f32 = 0.05;

/// The fixtures a room of kind `kind` may get, with their chances (times `furniture.pieces`).
fn fixtures(kind: RoomType) -> &'static [(C, f32)] {
    use RoomType as R;
    // Fewer of the small ones than homes have: each is a landmark instructions may name, and
    // people name a switch or an outlet far less often than a door or a sofa.
    match kind {
        R::LivingRoom => &[
            (C::LightSwitch, 0.35),
            (C::Outlet, 0.25),
            (C::Thermostat, 0.25),
            (C::AirVent, 0.1),
            (C::AirConditioner, 0.05),
            (C::SmokeDetector, 0.08),
        ],
        R::Kitchen => &[
            (C::LightSwitch, 0.3),
            (C::RangeHood, 0.3),
            (C::Calendar, 0.25),
            (C::Outlet, 0.15),
            (C::SmokeDetector, 0.15),
            (C::AirVent, 0.05),
        ],
        R::DiningRoom => &[
            (C::LightSwitch, 0.3),
            (C::Thermostat, 0.1),
            (C::Outlet, 0.15),
            (C::AirVent, 0.05),
        ],
        R::Bedroom => &[
            (C::LightSwitch, 0.3),
            (C::Outlet, 0.2),
            (C::AirVent, 0.08),
            (C::SmokeDetector, 0.12),
            (C::AirConditioner, 0.06),
        ],
        R::Office => &[
            (C::LightSwitch, 0.3),
            (C::Outlet, 0.25),
            (C::Calendar, 0.25),
            (C::AirVent, 0.1),
            (C::AirConditioner, 0.06),
        ],
        R::Gym => &[
            (C::LightSwitch, 0.3),
            (C::AirConditioner, 0.15),
            (C::Outlet, 0.2),
        ],
        R::HomeTheater => &[(C::LightSwitch, 0.3), (C::AirVent, 0.15), (C::Outlet, 0.2)],
        R::Library => &[
            (C::LightSwitch, 0.3),
            (C::Thermostat, 0.1),
            (C::Outlet, 0.2),
        ],
        R::Garage => &[(C::LightSwitch, 0.4), (C::Outlet, 0.4), (C::Calendar, 0.1)],
        R::Porch | R::Balcony => &[(C::Outlet, 0.1)],
        R::Room => &[
            (C::LightSwitch, 0.3),
            (C::Outlet, 0.2),
            (C::AirConditioner, 0.06),
            (C::AirVent, 0.1),
        ],
        R::Hallway => &[
            (C::LightSwitch, 0.3),
            (C::Thermostat, 0.3),
            (C::SmokeDetector, 0.3),
        ],
        R::EntranceHall => &[
            (C::LightSwitch, 0.4),
            (C::Thermostat, 0.3),
            (C::SmokeDetector, 0.15),
        ],
        R::LaundryRoom => &[
            (C::LightSwitch, 0.3),
            (C::Outlet, 0.3),
            (C::AirVent, 0.15),
            (C::Calendar, 0.1),
        ],
        R::Closet | R::Pantry => &[(C::LightSwitch, 0.2)],
        R::Bathroom => &[(C::LightSwitch, 0.3), (C::AirVent, 0.15)],
        R::Sauna => &[(C::LightSwitch, 0.3)],
        R::Spa => &[(C::LightSwitch, 0.3), (C::AirVent, 0.15)],
        // A cellar keeps the wine at one temperature.
        R::WineCellar => &[(C::LightSwitch, 0.3), (C::Thermostat, 0.3)],
        R::Playroom => &[(C::LightSwitch, 0.3), (C::Outlet, 0.15)],
        R::MudRoom => &[(C::LightSwitch, 0.3), (C::Outlet, 0.15)],
        R::Workshop => &[(C::LightSwitch, 0.4), (C::Outlet, 0.4)],
    }
}

/// One wall face of a room: its line, the inward normal and its extent along the wall.
struct Face {
    along_z: bool,
    /// Coordinate of the face (the wall line moved half a wall in).
    at: f32,
    /// Inward normal, +1 or -1 along the axis across the wall.
    sign: f32,
    span: (f32, f32),
}

impl Face {
    /// World (x, z) of a point `along` the wall and `out` from the face.
    fn point(&self, along: f32, out: f32) -> (f32, f32) {
        let n = self.at + self.sign * out;
        if self.along_z {
            (n, along)
        } else {
            (along, n)
        }
    }

    /// Yaw that turns a model's front (-Z) to face into the room.
    fn yaw(&self) -> f32 {
        let (nx, nz) = if self.along_z {
            (self.sign, 0.0)
        } else {
            (0.0, self.sign)
        };
        (-nx).atan2(-nz)
    }

    /// The box `(along0, along1) x (0, out) x (y0, y1)` in world coordinates.
    fn volume(&self, (a, b): (f32, f32), out: f32, (y0, y1): (f32, f32)) -> [Vec3; 2] {
        let (n0, n1) = if self.sign > 0.0 {
            (self.at, self.at + out)
        } else {
            (self.at - out, self.at)
        };
        if self.along_z {
            [Vec3::new(n0, y0, a), Vec3::new(n1, y1, b)]
        } else {
            [Vec3::new(a, y0, n0), Vec3::new(b, y1, n1)]
        }
    }

    /// How far out of the face a fixture may stand and stay within the face's occupancy cell.
    fn free_depth(&self) -> f32 {
        let q = f64::from(self.at) * f64::from(self.sign);
        let lo = (q / GRID).floor() * GRID;
        let d = lo + GRID - q - GRID_MARGIN;
        if q - lo < GRID_MARGIN {
            0.0
        } else {
            (d as f32).max(0.0)
        }
    }
}

/// The four wall faces of room `i`.
fn faces(cfg: &ProcgenConfig, plan: &Plan, i: usize) -> [Face; 4] {
    let r = plan.rooms[i].rect;
    let h = cfg.walls.thickness * 0.5;
    [
        Face {
            along_z: true,
            at: r.x0 + h,
            sign: 1.0,
            span: (r.z0 + h, r.z1 - h),
        },
        Face {
            along_z: true,
            at: r.x1 - h,
            sign: -1.0,
            span: (r.z0 + h, r.z1 - h),
        },
        Face {
            along_z: false,
            at: r.z0 + h,
            sign: 1.0,
            span: (r.x0 + h, r.x1 - h),
        },
        Face {
            along_z: false,
            at: r.z1 - h,
            sign: -1.0,
            span: (r.x0 + h, r.x1 - h),
        },
    ]
}

/// The gaps (along the wall, widened by `clear`) the doorways of room `i` cut in `face`.
fn doorways(
    cfg: &ProcgenConfig,
    plan: &Plan,
    i: usize,
    face: &Face,
    clear: f32,
) -> Vec<(f32, f32)> {
    let t = cfg.walls.thickness * 0.5;
    plan.openings
        .iter()
        .filter(|o| o.rooms.contains(&i) && o.along_z == face.along_z)
        .filter(|o| (o.line - (face.at - face.sign * t)).abs() < 1e-3)
        .map(|o| {
            let g = o.gap(cfg) * 0.5 + clear;
            (o.center - g, o.center + g)
        })
        .collect()
}

/// Whether the box `v` meets an object other than the floors, walls and ceilings.
fn blocked(objects: &[SceneObject], v: [Vec3; 2]) -> bool {
    let v = Aabb::new(v[0], v[1]);
    objects
        .iter()
        .any(|o| !matches!(o.class, C::Floor | C::Wall | C::Ceiling) && o.bbox.intersects(&v, 0.0))
}

/// Add the wall and ceiling fixtures of every room of a floor, after its furniture and door
/// leaves and before its decoration, from a stream of its own seeded by the floor's seed.
pub(crate) fn add_fixtures(cfg: &ProcgenConfig, plan: &Plan, seed: u64, b: &mut Builder) {
    if cfg.furniture.pieces <= 0.0 {
        return;
    }
    let ceiling = cfg.walls.height - 0.03;
    for (i, room) in plan.rooms.iter().enumerate() {
        if room.bare {
            continue;
        }
        let salt = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ FIXTURE_SALT ^ salt);
        for &(class, chance) in fixtures(room.kind) {
            let chance = (chance * cfg.furniture.pieces).clamp(0.0, 1.0);
            if !rng.random_bool(f64::from(chance)) {
                continue;
            }
            match class {
                C::SmokeDetector if cfg.walls.ceiling => {
                    on_ceiling(cfg, plan, i, ceiling, &mut rng, b);
                }
                C::RangeHood => over_stove(cfg, plan, i, ceiling, &mut rng, b),
                C::LightSwitch => by_doorway(cfg, plan, i, &mut rng, b),
                C::SmokeDetector => {}
                _ => on_wall(cfg, plan, i, class, &mut rng, b),
            }
        }
    }
}

/// Place `m` (built `depth` deep, its back at +z) on `face` at `along`, its feet at the floor.
fn put(b: &mut Builder, m: &Model, room: usize, face: &Face, along: f32) {
    let (x, z) = face.point(along, m.d * 0.5);
    let pose = Pose::from_yaw(Vec3::new(x, 0.0, z), face.yaw());
    b.add_model(m, room as RoomId, pose, None);
}

/// The vertical extent of a model's parts.
fn heights(m: &Model) -> (f32, f32) {
    let mut lo = f32::INFINITY;
    for part in &m.parts {
        for c in vlnverse_env::geometry::shape_corners(&part.shape) {
            lo = lo.min(part.transform.transform_point(c).y);
        }
    }
    (lo, m.h)
}

/// The depth a fixture may have on `face`: all it wants for an air conditioner (above the
/// agent's head), else what the face's occupancy cell leaves (`None` when that is too thin).
fn depth_on(face: &Face, class: C, want: f32) -> Option<f32> {
    if matches!(class, C::AirConditioner) {
        return Some(want);
    }
    let d = face.free_depth().min(want);
    (d >= THINNEST).then_some(d)
}

/// A light switch on the wall beside one of the room's doorways, on either side, at the
/// first spot clear of everything.
fn by_doorway(cfg: &ProcgenConfig, plan: &Plan, i: usize, rng: &mut ChaCha8Rng, b: &mut Builder) {
    let faces = faces(cfg, plan, i);
    let mut spots = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        for (g0, g1) in doorways(cfg, plan, i, face, 0.0) {
            spots.push((f, g0 - SWITCH_OFF));
            spots.push((f, g1 + SWITCH_OFF));
        }
    }
    spots.shuffle(rng);
    for (f, along) in spots {
        let face = &faces[f];
        let Some(depth) = depth_on(face, C::LightSwitch, FLUSH) else {
            continue;
        };
        let m = light_switch(depth, rng);
        if fits(cfg, plan, i, face, &m, along, depth, b) {
            put(b, &m, i, face, along);
            return;
        }
    }
}

/// Whether `m`, `depth` deep, fits on `face` at `along`: on the wall's own stretch, off the
/// doorways and the corners, clear of every other object.
#[allow(clippy::too_many_arguments)]
fn fits(
    cfg: &ProcgenConfig,
    plan: &Plan,
    i: usize,
    face: &Face,
    m: &Model,
    along: f32,
    depth: f32,
    b: &Builder,
) -> bool {
    let (a0, a1) = (along - m.w * 0.5, along + m.w * 0.5);
    // Built no deeper than asked (its back on the wall, its front within the cell).
    if m.d > depth + 1e-4 || a0 < face.span.0 + 0.1 || a1 > face.span.1 - 0.1 {
        return false;
    }
    if doorways(cfg, plan, i, face, 0.05)
        .iter()
        .any(|&(g0, g1)| a0 < g1 && a1 > g0)
    {
        return false;
    }
    let (y0, y1) = heights(m);
    let v = face.volume((a0 - GAP, a1 + GAP), depth + GAP, (y0 - GAP, y1 + GAP));
    !blocked(&b.objects, v)
}

/// A fixture at a free spot of one of the room's walls.
fn on_wall(
    cfg: &ProcgenConfig,
    plan: &Plan,
    i: usize,
    class: C,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) {
    let faces = faces(cfg, plan, i);
    let mut order: Vec<usize> = (0..4).collect();
    order.shuffle(rng);
    for f in order {
        let face = &faces[f];
        let want = if class == C::AirConditioner {
            0.22
        } else {
            FLUSH
        };
        let Some(depth) = depth_on(face, class, want) else {
            continue;
        };
        let Some(m) = model(class, depth, rng) else {
            return;
        };
        if m.h > cfg.walls.height - 0.1 {
            return;
        }
        let len = face.span.1 - face.span.0;
        let steps = (len / 0.2).floor() as usize;
        let mut tries: Vec<usize> = (1..steps.max(1)).collect();
        tries.shuffle(rng);
        for k in tries {
            let along = face.span.0 + k as f32 * 0.2;
            if fits(cfg, plan, i, face, &m, along, depth, b) {
                put(b, &m, i, face, along);
                return;
            }
        }
    }
}

/// A smoke detector on the ceiling of room `i`, near the middle of one of its short walls
/// (clear of the light panels at the middle and quarter points of the long axis) and of
/// anything reaching up to it.
fn on_ceiling(
    cfg: &ProcgenConfig,
    plan: &Plan,
    i: usize,
    ceiling: f32,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) {
    let ir = plan.rooms[i].rect.inset(cfg.walls.thickness * 0.5);
    let m = smoke_detector(rng);
    let (cx, cz) = ir.center();
    let off = 0.35;
    let mut ends = [1.0f32, -1.0];
    ends.shuffle(rng);
    for s in ends {
        let (x, z) = if ir.w() >= ir.d() {
            (cx + s * (ir.w() * 0.5 - off), cz)
        } else {
            (cx, cz + s * (ir.d() * 0.5 - off))
        };
        let lo = Vec3::new(x - 0.2, ceiling - m.h - 0.3, z - 0.2);
        let hi = Vec3::new(x + 0.2, ceiling - 0.005, z + 0.2);
        if blocked(&b.objects, [lo, hi]) {
            continue;
        }
        let pose = Pose::from_yaw(Vec3::new(x, ceiling - m.h, z), 0.0);
        b.add_model(&m, i as RoomId, pose, None);
        return;
    }
}

/// A range hood over the room's stove, its back on the stove's back where that is against a
/// wall, its canopy 65 cm above the cooktop and its chimney up towards the ceiling, where
/// nothing else hangs.
fn over_stove(
    cfg: &ProcgenConfig,
    plan: &Plan,
    i: usize,
    ceiling: f32,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) {
    let Some(stove) = b
        .objects
        .iter()
        .find(|o| o.room == Some(i as RoomId) && o.class == C::Stove)
    else {
        return;
    };
    let bb = stove.bbox;
    // Models have their back at +z: the stove's yaw says which way its back faces.
    let rot = stove.pose.rotation;
    let back = Quat::from_array(rot) * Vec3::Z;
    let across_x = back.x.abs() > back.z.abs();
    let (cx, cz) = ((bb.min[0] + bb.max[0]) * 0.5, (bb.min[2] + bb.max[2]) * 0.5);
    let (sw, sd) = if across_x {
        (bb.max[2] - bb.min[2], bb.max[0] - bb.min[0])
    } else {
        (bb.max[0] - bb.min[0], bb.max[2] - bb.min[2])
    };
    // The wall behind it: the stove's back within a few centimetres of the room's inside.
    let ir = plan.rooms[i].rect.inset(cfg.walls.thickness * 0.5);
    let gap = match (across_x, back.x > 0.0, back.z > 0.0) {
        (true, true, _) => ir.x1 - bb.max[0],
        (true, false, _) => bb.min[0] - ir.x0,
        (false, _, true) => ir.z1 - bb.max[2],
        (false, _, false) => bb.min[2] - ir.z0,
    };
    let bottom = bb.max[1] + 0.65;
    let chimney = ceiling - bottom - 0.3;
    if gap > 0.05 || chimney < 0.1 {
        return;
    }
    let m = range_hood(sw.clamp(0.6, 0.9), chimney, rng);
    let shift = (sd - m.d) * 0.5;
    let (bx, bz) = if across_x {
        (cx + back.x.signum() * shift, cz)
    } else {
        (cx, cz + back.z.signum() * shift)
    };
    let pose = Pose {
        position: [bx, bottom, bz],
        rotation: rot,
    };
    // Clear of everything but the stove itself, above it.
    let (hw, hd) = if across_x { (m.d, m.w) } else { (m.w, m.d) };
    let lo = Vec3::new(bx - hw * 0.5, bottom - 0.02, bz - hd * 0.5);
    let hi = Vec3::new(bx + hw * 0.5, ceiling - 0.01, bz + hd * 0.5);
    let hood = Aabb::new(lo, hi);
    let clash = b.objects.iter().any(|o| {
        o.id != stove.id
            && !matches!(o.class, C::Floor | C::Wall | C::Ceiling)
            && o.bbox.intersects(&hood, 0.0)
    });
    if !clash {
        b.add_model(&m, i as RoomId, pose, None);
    }
}

/// A model's floor footprint, centred (for tests).
#[cfg(test)]
fn footprint(m: &Model) -> crate::rect::Rect {
    crate::rect::Rect::centered(0.0, 0.0, m.w, m.d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::room_things::{things, Lot, Spot};

    #[test]
    fn every_class_builds_its_own_model_and_others_none() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for &class in C::ALL.iter().filter(|c| c.id() >= C::LightSwitch.id()) {
            for _ in 0..8 {
                let m = model(class, FLUSH, &mut rng).expect("a model");
                assert_eq!(m.class, class);
                assert!(m.w > 0.05 && m.d > 0.003 && m.h > 0.005, "{class:?}");
                assert!(footprint(&m).area() < 2.5, "{class:?}");
                assert!(m.h < 2.6, "{class:?} {}", m.h);
                for part in &m.parts {
                    assert!(
                        part.transform.position[1] > -0.05,
                        "{class:?} below the floor"
                    );
                }
            }
        }
        assert!(model(C::Sofa, FLUSH, &mut rng).is_none());
    }

    #[test]
    fn every_room_lists_only_this_module_classes() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for &kind in RoomType::ALL {
            for th in things(Lot::Third, kind) {
                assert!(model(th.class, FLUSH, &mut rng).is_some(), "{:?}", th.class);
                assert!((0.0..=1.0).contains(&th.chance));
                assert_eq!(th.spot == Spot::OnTop, !supports(th.class).is_empty());
            }
            for &(class, chance) in fixtures(kind) {
                assert!(model(class, FLUSH, &mut rng).is_some(), "{class:?}");
                assert!((0.0..=1.0).contains(&chance));
            }
        }
    }

    #[test]
    fn a_flush_fixture_stays_within_the_cell_its_wall_face_reaches() {
        for at in [0.0f32, 0.013, 0.049, 1.2345, -2.51] {
            for sign in [1.0f32, -1.0] {
                let face = Face {
                    along_z: true,
                    at,
                    sign,
                    span: (0.0, 1.0),
                };
                let d = face.free_depth();
                let q = f64::from(at) * f64::from(sign);
                let cell = (q / GRID).floor();
                let out = q + f64::from(d);
                assert!(d == 0.0 || (out / GRID).floor() == cell, "{at} {sign} {d}");
            }
        }
    }
}
