//! The second lot of things issue 26 added so that instructions can name what people name in a
//! home (R2R's "walk past the sectional", "stop by the buffet", "under the ceiling fan", "the
//! water heater", "the teddy bear", "the bust"): a sectional, a buffet, a ceiling fan, a water
//! heater, a mini fridge, a teddy bear, a bust on its pedestal, a saxophone on its stand, a
//! basketball hoop, a whiteboard and a bulletin board, a chess table, a candelabra, an
//! exercise ball, a mounted sword and a pile of rocks.
//!
//! They are placed last in their room, after the sets (`furnish.rs`, `add_more_things`), from
//! an rng of their own seeded by the home and room, so that nothing placed before moves. Like
//! every model (`models.rs`), each is built in its own frame with its front at -Z and its back
//! (the side that goes to the wall) at +Z, and draws its colour from a finish list of its own,
//! so that the colour word instructions use is the colour of its largest part.

use crate::models::{ball, bcube, cube, cyl, disc_z, front, legs, r, turned, Model};
use crate::palette::{f, shade, tone, Finish};
use glam::Quat;
use rand::seq::IndexedRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, TAU};
use vlnverse_env::{SemanticClass as C, Shape};

/// Salt of these things' rng, apart from the pieces' and the sets' ones.
pub(crate) const SALT: u64 = 0x7A1E_5C0D_B0A7_5EED;

/// Chance of a saxophone in a room that already has an instrument (a guitar, a piano, a drum
/// kit): it stands where the music is.
pub(crate) const SAX_WITH_INSTRUMENTS: f32 = 0.6;
/// Instruments a saxophone keeps company with.
pub(crate) const INSTRUMENTS: [C; 4] = [C::Guitar, C::DrumKit, C::GrandPiano, C::Piano];

/// Supports a candelabra stands on, in order of preference.
pub(crate) const CANDELABRA_ON: [C; 5] = [
    C::DiningTable,
    C::Buffet,
    C::ConsoleTable,
    C::SideTable,
    C::CoffeeTable,
];

/// Sofa fabrics and leathers.
const UPHOLSTERY: &[Finish] = &[
    f("grey", "fabric", [0.35, 0.35, 0.37]),
    f("grey", "fabric", [0.5, 0.5, 0.52]),
    f("beige", "fabric", [0.68, 0.6, 0.46]),
    f("blue", "fabric", [0.1, 0.18, 0.42]),
    f("brown", "leather", [0.3, 0.16, 0.07]),
    f("black", "leather", [0.05, 0.05, 0.05]),
    f("white", "fabric", [0.85, 0.84, 0.8]),
    f("green", "fabric", [0.14, 0.3, 0.18]),
];
/// Cabinet woods and paints.
const CASEWORK: &[Finish] = &[
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("brown", "wood", [0.33, 0.19, 0.09]),
    f("white", "wood", [0.85, 0.85, 0.82]),
    f("black", "wood", [0.05, 0.05, 0.05]),
    f("grey", "wood", [0.35, 0.35, 0.36]),
];
/// Fan motors and candelabras.
const FITTING: &[Finish] = &[
    f("white", "metal", [0.88, 0.88, 0.87]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("silver", "metal", [0.62, 0.62, 0.64]),
    f("gold", "metal", [0.75, 0.58, 0.2]),
];
/// Water heaters and mini fridges.
const APPLIANCE: &[Finish] = &[
    f("white", "metal", [0.88, 0.88, 0.87]),
    f("white", "metal", [0.82, 0.82, 0.8]),
    f("grey", "metal", [0.45, 0.45, 0.47]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("silver", "metal", [0.62, 0.62, 0.64]),
];
/// Teddy bears' fur.
const PLUSH: &[Finish] = &[
    f("brown", "fabric", [0.42, 0.25, 0.12]),
    f("brown", "fabric", [0.32, 0.19, 0.09]),
    f("beige", "fabric", [0.72, 0.6, 0.42]),
    f("white", "fabric", [0.88, 0.87, 0.84]),
    f("pink", "fabric", [0.85, 0.55, 0.62]),
];
/// Marble and stone.
const MARBLE: &[Finish] = &[
    f("white", "stone", [0.86, 0.85, 0.82]),
    f("white", "stone", [0.8, 0.79, 0.76]),
    f("grey", "stone", [0.5, 0.5, 0.51]),
    f("black", "stone", [0.08, 0.08, 0.09]),
];
/// Brass, nickel and black lacquer saxophones.
const HORN: &[Finish] = &[
    f("gold", "metal", [0.78, 0.6, 0.2]),
    f("gold", "metal", [0.72, 0.55, 0.16]),
    f("silver", "metal", [0.68, 0.68, 0.7]),
    f("black", "metal", [0.05, 0.05, 0.05]),
];
/// Backboards.
const BACKBOARD: &[Finish] = &[
    f("white", "plastic", [0.9, 0.9, 0.9]),
    f("white", "plastic", [0.85, 0.86, 0.88]),
];
/// Whiteboards are white.
const WHITEBOARD: &[Finish] = &[f("white", "plastic", [0.95, 0.95, 0.95])];
/// Cork.
const CORK: &[Finish] = &[
    f("brown", "wood", [0.6, 0.43, 0.25]),
    f("beige", "wood", [0.7, 0.55, 0.36]),
];
/// Chess tables: wood.
const CHESS: &[Finish] = &[
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("black", "wood", [0.05, 0.05, 0.05]),
];
/// Exercise balls.
const RUBBER: &[Finish] = &[
    f("blue", "plastic", [0.1, 0.25, 0.65]),
    f("red", "plastic", [0.62, 0.06, 0.05]),
    f("grey", "plastic", [0.45, 0.45, 0.47]),
    f("green", "plastic", [0.15, 0.5, 0.2]),
    f("pink", "plastic", [0.85, 0.45, 0.6]),
    f("black", "plastic", [0.05, 0.05, 0.05]),
];
/// Sword blades.
const BLADE: &[Finish] = &[
    f("silver", "metal", [0.72, 0.72, 0.75]),
    f("silver", "metal", [0.62, 0.63, 0.66]),
];
/// Rocks and stones.
const ROCK: &[Finish] = &[
    f("grey", "stone", [0.45, 0.45, 0.46]),
    f("grey", "stone", [0.58, 0.57, 0.55]),
    f("grey", "stone", [0.36, 0.36, 0.37]),
    f("beige", "stone", [0.66, 0.6, 0.5]),
];
/// Brass for handles and fittings.
const BRASS: [f32; 3] = [0.75, 0.58, 0.2];
/// Copper pipes.
const COPPER: [f32; 3] = [0.72, 0.42, 0.2];
/// Basketball orange.
const ORANGE: [f32; 3] = [0.9, 0.38, 0.06];

/// Draw a finish from `list`, in one of its colour word's tones or its own.
fn pick(list: &[Finish], rng: &mut ChaCha8Rng) -> Finish {
    let fin = *list.choose(rng).unwrap_or(&list[0]);
    crate::tones::toned(fin, rng)
}

/// A cuboid of full size `s`, centred at `c` and turned by `rot`, its edges bevelled by `bevel`.
fn tilted(p: &mut Vec<vlnverse_env::Part>, c: [f32; 3], s: [f32; 3], rot: Quat, rgb: [f32; 3]) {
    let shape = Shape::Cuboid {
        half_extents: [s[0] * 0.5, s[1] * 0.5, s[2] * 0.5],
        bevel: 0.0,
    };
    turned(p, shape, c, rot, rgb);
}

/// A small bead (an eye, a key, a pin, a flame) of radius `rad` centred at `c`: a box, which
/// is 12 triangles where a sphere is 144, and reads the same at that size.
fn bead(p: &mut Vec<vlnverse_env::Part>, c: [f32; 3], rad: f32, rgb: [f32; 3]) {
    let d = rad * 1.7;
    cube(p, c[0], c[1] - d * 0.5, c[2], [d, d, d], rgb);
}

/// A cylinder of radius `rad` and length `len` centred at `c`, its axis turned from +Y by
/// `rot`.
fn rod(p: &mut Vec<vlnverse_env::Part>, c: [f32; 3], rad: f32, len: f32, rot: Quat, rgb: [f32; 3]) {
    let shape = Shape::Cylinder {
        radius: rad,
        half_height: len * 0.5,
    };
    turned(p, shape, c, rot, rgb);
}

/// The model of one of this module's classes; `None` for any other class.
pub(crate) fn model(class: C, rng: &mut ChaCha8Rng) -> Option<Model> {
    Some(match class {
        C::Sectional => sectional(rng),
        C::Buffet => buffet(rng),
        C::CeilingFan => ceiling_fan(rng),
        C::WaterHeater => water_heater(rng),
        C::MiniFridge => mini_fridge(rng),
        C::TeddyBear => teddy_bear(rng),
        C::Bust => bust(rng),
        C::Saxophone => saxophone(rng),
        C::BasketballHoop => basketball_hoop(rng),
        C::Whiteboard => whiteboard(rng),
        C::BulletinBoard => bulletin_board(rng),
        C::ChessTable => chess_table(rng),
        C::Candelabra => candelabra(rng),
        C::ExerciseBall => exercise_ball(rng),
        C::Sword => sword(rng),
        C::Rocks => rocks(rng),
        _ => return None,
    })
}

/// An L-shaped sectional: a long sofa with a back along its back and a return coming forward
/// at one end with a back along its outer side, seat cushions on both, an arm at each free end
/// and throw pillows. It goes in a corner, both backs to the walls.
fn sectional(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(UPHOLSTERY, rng);
    let c = fin.rgb;
    let (w, l) = (r(rng, 2.3, 2.7), r(rng, 1.6, 1.9));
    let (d, h, cw, arm) = (0.92, 0.84, 0.92, 0.2);
    // The return is on the right (+x) or the left.
    let s = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
    let rx = s * (w - cw) * 0.5;
    let mut p = Vec::new();
    // Feet, then the seat bases (the long one along the back, z in [-d, 0], and the return).
    for (x, z) in [
        (-w * 0.5 + 0.06, -0.06),
        (w * 0.5 - 0.06, -0.06),
        (-s * (w * 0.5 - 0.06), -d + 0.06),
        (s * (w * 0.5 - 0.06), -l + 0.06),
        (rx - s * (cw * 0.5 - 0.06), -l + 0.06),
    ] {
        cube(&mut p, x, 0.0, z, [0.05, 0.08, 0.05], tone::METAL);
    }
    let base = shade(c, 0.88);
    bcube(&mut p, 0.0, 0.08, -d * 0.5, [w, 0.25, d], 0.03, base);
    bcube(
        &mut p,
        rx,
        0.08,
        -(l + d) * 0.5,
        [cw, 0.25, l - d],
        0.03,
        base,
    );
    // Backs: along the back, and along the return's outer side.
    let back = h - 0.33;
    bcube(&mut p, 0.0, 0.33, -0.11, [w, back, 0.22], 0.04, c);
    let sx = s * (w * 0.5 - 0.11);
    bcube(
        &mut p,
        sx,
        0.33,
        -l * 0.5 - 0.11,
        [0.22, back, l - 0.22],
        0.04,
        c,
    );
    // Arms at the free ends: the far end of the long part and the front of the return.
    let ax = -s * (w - arm) * 0.5;
    bcube(
        &mut p,
        ax,
        0.08,
        -d * 0.5,
        [arm, 0.55, d],
        0.04,
        shade(c, 0.95),
    );
    bcube(
        &mut p,
        rx,
        0.08,
        -l + arm * 0.5,
        [cw, 0.55, arm],
        0.04,
        shade(c, 0.95),
    );
    // Seat cushions: three along the long part (the corner seat included), two on the return.
    let x0 = -s * (w * 0.5 - arm);
    let x1 = s * (w * 0.5 - 0.22);
    for k in 0..3 {
        let x = x0 + (x1 - x0) * (k as f32 + 0.5) / 3.0;
        let cwid = (x1 - x0).abs() / 3.0 - 0.02;
        bcube(
            &mut p,
            x,
            0.33,
            -d * 0.5 - 0.1,
            [cwid, 0.12, d - 0.24],
            0.025,
            c,
        );
    }
    let (z0, z1) = (-d - 0.02, -l + arm);
    let inner = cw - 0.24;
    for k in 0..2 {
        let z = z0 + (z1 - z0) * (k as f32 + 0.5) / 2.0;
        let len = (z1 - z0).abs() / 2.0 - 0.02;
        let x = rx - s * 0.11;
        bcube(&mut p, x, 0.33, z, [inner, 0.12, len], 0.025, c);
    }
    // Throw pillows against the backs, one in the corner.
    let pillow = [
        tone::LINEN,
        [0.75, 0.6, 0.2],
        [0.5, 0.1, 0.08],
        [0.2, 0.3, 0.5],
    ][rng.random_range(0..4)];
    for (x, z, yaw) in [
        (-s * (w * 0.5 - arm - 0.3), -0.3, 0.0),
        (s * (w * 0.5 - 0.5), -0.45, s * FRAC_PI_4),
        (s * (w * 0.5 - 0.3), -l + arm + 0.35, FRAC_PI_2),
    ] {
        tilted(
            &mut p,
            [x, 0.62, z],
            [0.42, 0.38, 0.12],
            Quat::from_rotation_y(yaw),
            pillow,
        );
    }
    Model::new(C::Sectional, fin, [w, h, l], 90.0, p)
}

/// A buffet: a long low cabinet on short legs, a row of drawers over three doors, brass pulls
/// and a top that overhangs a little; small things stand on it.
fn buffet(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CASEWORK, rng);
    let c = fin.rgb;
    let (w, d, h) = (r(rng, 1.5, 1.9), r(rng, 0.44, 0.5), r(rng, 0.82, 0.9));
    let foot = 0.14;
    let mut p = Vec::new();
    legs(&mut p, w - 0.06, d - 0.06, foot, 0.05, shade(c, 0.8));
    bcube(&mut p, 0.0, foot, 0.0, [w, h - foot - 0.03, d], 0.01, c);
    bcube(
        &mut p,
        0.0,
        h - 0.03,
        0.0,
        [w + 0.04, 0.03, d + 0.03],
        0.006,
        shade(c, 0.8),
    );
    let face = if fin.color == "white" {
        shade(c, 0.93)
    } else {
        shade(c, 1.15)
    };
    let body = h - foot - 0.03;
    let drawer_h = 0.14;
    let cols = 3;
    let cwid = (w - 0.06) / cols as f32;
    for k in 0..cols {
        let x = -w * 0.5 + 0.03 + cwid * (k as f32 + 0.5);
        // A drawer at the top, a door below it, each with a pull.
        let dy = foot + body - drawer_h - 0.03;
        front(
            &mut p,
            d,
            [x, dy, -0.005],
            [cwid - 0.03, drawer_h, 0.01],
            face,
        );
        front(
            &mut p,
            d,
            [x, dy + drawer_h * 0.45, -0.015],
            [0.1, 0.015, 0.012],
            BRASS,
        );
        let door_h = dy - foot - 0.05;
        front(
            &mut p,
            d,
            [x, foot + 0.03, -0.005],
            [cwid - 0.03, door_h, 0.01],
            face,
        );
        let hx = x + if k % 2 == 0 { 0.5 } else { -0.5 } * (cwid - 0.12);
        front(
            &mut p,
            d,
            [hx, foot + 0.03 + door_h * 0.55, -0.015],
            [0.015, 0.1, 0.012],
            BRASS,
        );
    }
    Model::new(C::Buffet, fin, [w + 0.04, h, d + 0.03], 60.0, p).with_top(0.06)
}

/// A ceiling fan, built from its bottom up to its top at the ceiling: a glass light bowl
/// under the motor housing, five blades out from it, and the downrod and canopy up to the
/// ceiling. It hangs with its top at the ceiling, its bottom above 2.1 m.
fn ceiling_fan(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(FITTING, rng);
    let c = fin.rgb;
    let blade = [
        [0.45, 0.27, 0.13],
        [0.26, 0.15, 0.07],
        tone::WHITE,
        [0.06, 0.06, 0.06],
        [0.62, 0.5, 0.32],
    ][rng.random_range(0..5)];
    let span = r(rng, 0.6, 0.66);
    let h = r(rng, 0.4, 0.48);
    let mut p = Vec::new();
    // The light bowl, its fitter, the motor housing.
    cyl(&mut p, 0.0, 0.0, 0.0, 0.09, 0.1, [0.95, 0.92, 0.82]);
    cyl(&mut p, 0.0, 0.1, 0.0, 0.16, 0.15, c);
    let y = 0.2;
    for k in 0..5 {
        let a = k as f32 * TAU / 5.0 + 0.3;
        let (ca, sa) = (a.cos(), a.sin());
        let rot = Quat::from_rotation_y(-a) * Quat::from_rotation_x(0.12);
        let mid = (0.14 + span) * 0.5;
        tilted(
            &mut p,
            [ca * mid, y, sa * mid],
            [span - 0.14, 0.01, 0.13],
            rot,
            blade,
        );
    }
    // Downrod and canopy.
    cyl(&mut p, 0.0, 0.25, 0.0, 0.016, h - 0.3, c);
    cyl(&mut p, 0.0, h - 0.06, 0.0, 0.08, 0.06, c);
    Model::new(C::CeilingFan, fin, [span * 2.0, h, span * 2.0], 7.0, p)
}

/// A tank water heater: a tall round tank on a base ring, a capped top with the cold and hot
/// pipes going up, the gas control box and a label at the front, and the relief pipe down its
/// side.
fn water_heater(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(APPLIANCE, rng);
    let c = fin.rgb;
    let (rad, h) = (r(rng, 0.26, 0.3), r(rng, 1.35, 1.55));
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, rad + 0.015, 0.06, shade(c, 0.6));
    cyl(&mut p, 0.0, 0.06, 0.0, rad, h - 0.1, c);
    cyl(&mut p, 0.0, h - 0.04, 0.0, rad - 0.03, 0.04, shade(c, 0.85));
    for x in [-0.1, 0.1] {
        cyl(&mut p, x, h, 0.02, 0.022, 0.28, COPPER);
        cube(
            &mut p,
            x,
            h + 0.22,
            0.02 + rad * 0.5,
            [0.045, 0.045, rad],
            COPPER,
        );
    }
    cyl(&mut p, 0.0, h, -0.06, 0.05, 0.08, tone::METAL);
    // The control box and the burner door at the bottom front, a label higher up.
    cube(
        &mut p,
        0.0,
        0.3,
        -rad - 0.02,
        [0.14, 0.16, 0.08],
        tone::METAL,
    );
    cyl(&mut p, 0.0, 0.44, -rad - 0.03, 0.025, 0.02, tone::FRUIT_RED);
    cube(&mut p, 0.0, 0.1, -rad + 0.02, [0.2, 0.14, 0.05], tone::SOOT);
    let label = if fin.color == "white" {
        [0.9, 0.75, 0.15]
    } else {
        tone::WHITE
    };
    cube(
        &mut p,
        0.0,
        h * 0.55,
        -rad + 0.035,
        [0.2, 0.26, 0.04],
        label,
    );
    // The relief valve and its pipe down to the floor.
    let px = rad * 0.75;
    cube(
        &mut p,
        px,
        h * 0.85,
        -rad * 0.66,
        [0.06, 0.06, 0.06],
        COPPER,
    );
    cyl(
        &mut p,
        px + 0.03,
        0.06,
        -rad * 0.66,
        0.016,
        h * 0.85 - 0.06,
        COPPER,
    );
    Model::new(
        C::WaterHeater,
        fin,
        [rad * 2.0, h + 0.28, rad * 2.0],
        60.0,
        p,
    )
}

/// A mini fridge: a small box on the floor with a glass door onto shelves of cans and bottles
/// (a bar fridge) or a solid door, a long handle and a grille at the bottom.
fn mini_fridge(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(APPLIANCE, rng);
    let c = fin.rgb;
    let (w, h, d) = (r(rng, 0.46, 0.52), r(rng, 0.8, 0.88), r(rng, 0.48, 0.54));
    let glass = rng.random_bool(0.85);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.03, 0.0, [w, h - 0.03, d], 0.02, c);
    cube(
        &mut p,
        0.0,
        0.0,
        0.0,
        [w - 0.06, 0.03, d - 0.06],
        tone::SOOT,
    );
    front(
        &mut p,
        d,
        [0.0, 0.05, -0.004],
        [w - 0.06, 0.06, 0.01],
        tone::SOOT,
    );
    let (dy, dh) = (0.14, h - 0.19);
    if glass {
        front(
            &mut p,
            d,
            [-0.02, dy, -0.006],
            [w - 0.1, dh, 0.012],
            [0.1, 0.13, 0.16],
        );
        // Three shelves of cans and bottles seen through the glass, lit from inside.
        let fills = [
            tone::FRUIT_RED,
            tone::LEAF,
            [0.15, 0.3, 0.7],
            tone::FRUIT_YELLOW,
        ];
        for row in 0..3 {
            let y = dy + 0.04 + row as f32 * dh / 3.0;
            front(
                &mut p,
                d,
                [-0.02, y - 0.015, -0.013],
                [w - 0.14, 0.012, 0.004],
                tone::GLASS,
            );
            for k in 0..3 {
                let x = -0.02 - (w - 0.2) * 0.5 + k as f32 * (w - 0.2) / 2.0;
                let fill = fills[(row + k) % 4];
                front(
                    &mut p,
                    d,
                    [x, y, -0.014],
                    [0.05, dh / 3.0 - 0.08, 0.004],
                    fill,
                );
            }
        }
    } else {
        front(
            &mut p,
            d,
            [0.0, dy, -0.006],
            [w - 0.04, dh, 0.012],
            shade(c, 0.95),
        );
    }
    front(
        &mut p,
        d,
        [w * 0.5 - 0.05, dy + dh * 0.3, -0.03],
        [0.025, dh * 0.5, 0.025],
        tone::STEEL,
    );
    Model::new(C::MiniFridge, fin, [w, h, d + 0.03], 25.0, p)
}

/// A teddy bear sitting on the floor, legs out in front: a round body with a lighter belly,
/// a head with round ears, a muzzle, a black nose and eyes, paws and a bow at the neck. Some
/// are giant ones.
fn teddy_bear(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PLUSH, rng);
    let c = fin.rgb;
    let k = if rng.random_bool(0.35) {
        r(rng, 1.6, 2.0)
    } else {
        r(rng, 0.9, 1.2)
    };
    let light = if fin.color == "white" {
        [0.95, 0.9, 0.8]
    } else {
        shade(c, 1.6)
    };
    let bow = [tone::FRUIT_RED, [0.15, 0.3, 0.7], [0.85, 0.45, 0.6]][rng.random_range(0..3)];
    let s = |v: [f32; 3]| v.map(|x| x * k);
    let mut p = Vec::new();
    ball(&mut p, s([0.0, 0.16, 0.02]), 0.16 * k, c);
    ball(&mut p, s([0.0, 0.15, -0.06]), 0.11 * k, light);
    ball(&mut p, s([0.0, 0.4, 0.0]), 0.115 * k, c);
    ball(&mut p, s([0.0, 0.38, -0.095]), 0.05 * k, light);
    bead(&mut p, s([0.0, 0.395, -0.14]), 0.018 * k, tone::SOOT);
    for sx in [-1.0f32, 1.0] {
        bead(
            &mut p,
            s([sx * 0.045, 0.435, -0.097]),
            0.014 * k,
            tone::SOOT,
        );
        ball(&mut p, s([sx * 0.085, 0.5, 0.0]), 0.045 * k, c);
        // Arms down the sides, legs out in front.
        rod(
            &mut p,
            s([sx * 0.15, 0.2, -0.04]),
            0.045 * k,
            0.12 * k,
            Quat::from_rotation_z(sx * 0.5) * Quat::from_rotation_x(-0.4),
            c,
        );
        disc_z(
            &mut p,
            s([sx * 0.085, 0.055, -0.14]),
            0.055 * k,
            0.14 * k,
            c,
        );
    }
    tilted(
        &mut p,
        s([0.0, 0.29, -0.1]),
        s([0.12, 0.04, 0.03]),
        Quat::IDENTITY,
        bow,
    );
    Model::new(C::TeddyBear, fin, s([0.36, 0.55, 0.4]), 0.8 * k, p)
}

/// A marble bust on a square pedestal: the plinth, shaft and cap, then the bust's socle,
/// shoulders, neck and head.
fn bust(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(&MARBLE[..3], rng);
    let c = fin.rgb;
    let ph = r(rng, 1.0, 1.15);
    let stand = if rng.random_bool(0.5) {
        shade(c, 0.85)
    } else {
        pick(&MARBLE[3..], rng).rgb
    };
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [0.44, 0.08, 0.44], 0.01, stand);
    bcube(&mut p, 0.0, 0.08, 0.0, [0.32, ph - 0.16, 0.32], 0.01, stand);
    bcube(&mut p, 0.0, ph - 0.08, 0.0, [0.42, 0.08, 0.42], 0.01, stand);
    cyl(&mut p, 0.0, ph, 0.0, 0.09, 0.06, c);
    bcube(&mut p, 0.0, ph + 0.06, 0.0, [0.4, 0.2, 0.2], 0.04, c);
    cyl(&mut p, 0.0, ph + 0.24, 0.0, 0.055, 0.1, c);
    let hy = ph + 0.4;
    ball(&mut p, [0.0, hy, 0.0], 0.115, c);
    // Brow, nose and chin stand out of the face; a knot of hair at the back.
    cube(&mut p, 0.0, hy - 0.02, -0.11, [0.035, 0.05, 0.04], c);
    cube(&mut p, 0.0, hy - 0.12, -0.07, [0.07, 0.07, 0.07], c);
    ball(&mut p, [0.0, hy + 0.04, 0.04], 0.1, shade(c, 0.97));
    Model::new(C::Bust, fin, [0.44, hy + 0.14, 0.44], 60.0, p)
}

/// A saxophone on its stand: three splayed legs and a post, the body curving down into the
/// U-bend and up into the flared bell, keys down its front, the neck and mouthpiece at the
/// top.
fn saxophone(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(HORN, rng);
    let c = fin.rgb;
    let keys = if fin.color == "gold" {
        [0.92, 0.88, 0.78]
    } else {
        shade(c, 1.3)
    };
    let mut p = Vec::new();
    for k in 0..3 {
        let a = k as f32 * TAU / 3.0 + 0.5;
        let (sx, sz) = (a.sin(), a.cos());
        let rot = Quat::from_rotation_arc(
            glam::Vec3::Y,
            glam::Vec3::new(-sx * 0.6, 1.0, -sz * 0.6).normalize(),
        );
        rod(
            &mut p,
            [sx * 0.1, 0.1, sz * 0.1],
            0.01,
            0.22,
            rot,
            tone::SOOT,
        );
    }
    cyl(&mut p, 0.0, 0.0, 0.04, 0.012, 0.5, tone::SOOT);
    cube(&mut p, 0.0, 0.2, 0.02, [0.14, 0.02, 0.1], tone::SOOT);
    // The body, leaning back a little, from the bend at 0.28 m up to 0.82 m.
    let lean = Quat::from_rotation_x(0.12);
    rod(&mut p, [0.0, 0.55, 0.04], 0.035, 0.55, lean, c);
    ball(&mut p, [0.0, 0.27, 0.0], 0.052, c);
    // The bell section up from the bend in front of the body, and the flared bell.
    let up = Quat::from_rotation_x(-0.35);
    rod(&mut p, [0.0, 0.4, -0.08], 0.048, 0.28, up, c);
    rod(&mut p, [0.0, 0.55, -0.135], 0.085, 0.05, up, c);
    rod(&mut p, [0.0, 0.556, -0.137], 0.065, 0.05, up, tone::SOOT);
    // Keys down the front of the body.
    for k in 0..6 {
        let y = 0.4 + k as f32 * 0.065;
        bead(&mut p, [0.0, y, 0.0 - (y - 0.55) * 0.12], 0.016, keys);
    }
    // The neck bending forward from the top, and the black mouthpiece.
    let neck = Quat::from_rotation_x(-1.1);
    rod(&mut p, [0.0, 0.86, 0.02], 0.016, 0.16, neck, c);
    rod(&mut p, [0.0, 0.9, -0.07], 0.014, 0.06, neck, tone::SOOT);
    Model::new(C::Saxophone, fin, [0.3, 0.95, 0.35], 3.0, p)
}

/// A basketball hoop on the wall: a white backboard with its target square, standing off the
/// wall on two arms, the orange rim out in front and the white net hanging from it. It hangs
/// above the agent's height; only a strip of floor along the wall is its own.
fn basketball_hoop(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BACKBOARD, rng);
    let c = fin.rgb;
    let (bw, bh) = (r(rng, 1.0, 1.15), r(rng, 0.66, 0.72));
    let y = r(rng, 1.8, 1.85);
    let line = [tone::FRUIT_RED, tone::SOOT, [0.1, 0.2, 0.6]][rng.random_range(0..3)];
    let mut p = Vec::new();
    // Arms from the wall (z = 0.28) to the board's back.
    for sx in [-1.0, 1.0] {
        cube(
            &mut p,
            sx * bw * 0.3,
            y + bh * 0.5,
            0.16,
            [0.05, 0.05, 0.24],
            tone::METAL,
        );
    }
    cube(&mut p, 0.0, y, 0.0, [bw, bh, 0.04], c);
    // The target square over the rim.
    for (x, yy, sw, sh) in [
        (0.0, y + 0.08, 0.46, 0.025),
        (0.0, y + 0.38, 0.46, 0.025),
        (-0.22, y + 0.08, 0.025, 0.32),
        (0.22, y + 0.08, 0.025, 0.32),
    ] {
        cube(&mut p, x, yy, -0.022, [sw, sh, 0.005], line);
    }
    // The rim: a ring of short bars, on a bracket from the board.
    let (ry, rr, rz) = (y + 0.12, 0.23, -0.02 - 0.06 - 0.23);
    cube(&mut p, 0.0, ry - 0.04, -0.05, [0.14, 0.06, 0.08], ORANGE);
    let n = 10;
    for k in 0..n {
        let a = k as f32 * TAU / n as f32;
        let (x, z) = (a.cos() * rr, rz + a.sin() * rr);
        let len = TAU * rr / n as f32 + 0.01;
        tilted(
            &mut p,
            [x, ry, z],
            [0.02, 0.02, len],
            Quat::from_rotation_y(-a),
            ORANGE,
        );
    }
    // The net: strings down and in from the rim, and a ring round their lower ends.
    for k in 0..6 {
        let a = (k as f32 + 0.5) * TAU / 6.0;
        let (ca, sa) = (a.cos(), a.sin());
        let mid = [ca * rr * 0.8, ry - 0.16, rz + sa * rr * 0.8];
        let rot = Quat::from_rotation_arc(
            glam::Vec3::Y,
            glam::Vec3::new(ca * 0.08, 0.3, sa * 0.08).normalize(),
        );
        rod(&mut p, mid, 0.006, 0.33, rot, tone::WHITE);
    }
    for k in 0..6 {
        let a = k as f32 * TAU / 6.0;
        let (x, z) = (a.cos() * rr * 0.62, rz + a.sin() * rr * 0.62);
        tilted(
            &mut p,
            [x, ry - 0.3, z],
            [0.008, 0.008, 0.16],
            Quat::from_rotation_y(-a),
            tone::WHITE,
        );
    }
    Model::new(C::BasketballHoop, fin, [bw, y + bh, 0.8], 15.0, p)
}

/// A whiteboard on the wall: a white board in a silver frame with a marker tray under it,
/// markers on the tray and a few lines of writing.
fn whiteboard(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(WHITEBOARD, rng);
    let (w, h) = (r(rng, 1.2, 1.8), r(rng, 0.9, 1.2));
    let y = r(rng, 0.85, 0.95);
    let mut p = Vec::new();
    cube(&mut p, 0.0, y, 0.0, [w, h, 0.025], fin.rgb);
    for (x, yy, sw, sh) in [
        (0.0, y + h - 0.025, w + 0.03, 0.03),
        (0.0, y - 0.005, w + 0.03, 0.03),
        (-w * 0.5, y, 0.03, h),
        (w * 0.5, y, 0.03, h),
    ] {
        cube(&mut p, x, yy, -0.004, [sw, sh, 0.03], tone::STEEL);
    }
    cube(
        &mut p,
        0.0,
        y - 0.02,
        -0.05,
        [w * 0.6, 0.025, 0.08],
        tone::STEEL,
    );
    let inks = [
        tone::SOOT,
        [0.1, 0.2, 0.7],
        tone::FRUIT_RED,
        [0.1, 0.45, 0.15],
    ];
    for (k, ink) in inks.iter().take(2).enumerate() {
        let x = -w * 0.15 + k as f32 * 0.1;
        let rot = Quat::from_rotation_z(FRAC_PI_2);
        rod(&mut p, [x, y + 0.01, -0.05], 0.01, 0.12, rot, *ink);
    }
    // Writing: lines of strokes in one or two inks, a box and an arrow.
    let ink = inks[rng.random_range(0..3)];
    let lines = 3 + rng.random_range(0..3);
    for l in 0..lines {
        let yy = y + h - 0.15 - l as f32 * (h - 0.3) / lines as f32;
        let mut x = -w * 0.5 + 0.12;
        let end = w * r(rng, -0.1, 0.1);
        while x < end {
            let sw = r(rng, 0.15, 0.35);
            cube(&mut p, x + sw * 0.5, yy, -0.014, [sw, 0.018, 0.004], ink);
            x += sw + 0.05;
        }
    }
    let bx = w * 0.32;
    for (x, yy, sw, sh) in [
        (bx, y + h * 0.35, 0.28, 0.012),
        (bx, y + h * 0.65, 0.28, 0.012),
        (bx - 0.14, y + h * 0.35, 0.012, h * 0.3),
        (bx + 0.14, y + h * 0.35, 0.012, h * 0.3),
    ] {
        cube(&mut p, x, yy, -0.014, [sw, sh, 0.004], inks[3]);
    }
    Model::new(C::Whiteboard, fin, [w + 0.03, y + h + 0.01, 0.09], 6.0, p)
}

/// A bulletin board on the wall: a cork board in a wooden frame with notes, cards and photos
/// pinned to it.
fn bulletin_board(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CORK, rng);
    let (w, h) = (r(rng, 0.8, 1.2), r(rng, 0.6, 0.9));
    let y = r(rng, 1.05, 1.2);
    let frame = [tone::WOOD, [0.2, 0.12, 0.05], tone::WHITE][rng.random_range(0..3)];
    let mut p = Vec::new();
    cube(&mut p, 0.0, y, 0.0, [w, h, 0.02], fin.rgb);
    for (x, yy, sw, sh) in [
        (0.0, y + h - 0.02, w + 0.04, 0.04),
        (0.0, y - 0.02, w + 0.04, 0.04),
        (-w * 0.5, y, 0.04, h),
        (w * 0.5, y, 0.04, h),
    ] {
        cube(&mut p, x, yy, -0.005, [sw, sh, 0.03], frame);
    }
    let papers = [
        tone::WHITE,
        [0.95, 0.88, 0.35],
        [0.9, 0.6, 0.7],
        [0.55, 0.75, 0.9],
        [0.7, 0.88, 0.6],
    ];
    let pins = [
        tone::FRUIT_RED,
        [0.1, 0.3, 0.8],
        tone::FRUIT_YELLOW,
        tone::LEAF,
    ];
    let n = 4 + rng.random_range(0..3);
    for k in 0..n {
        let (pw, ph) = (r(rng, 0.1, 0.2), r(rng, 0.1, 0.2));
        let x = r(rng, -w * 0.5 + 0.06 + pw * 0.5, w * 0.5 - 0.06 - pw * 0.5);
        let yy = r(rng, y + 0.06, y + h - 0.06 - ph);
        let paper = papers[k % papers.len()];
        let rot = Quat::from_rotation_z(r(rng, -0.15, 0.15));
        tilted(
            &mut p,
            [x, yy + ph * 0.5, -0.012],
            [pw, ph, 0.003],
            rot,
            paper,
        );
        bead(
            &mut p,
            [x, yy + ph - 0.02, -0.016],
            0.009,
            pins[k % pins.len()],
        );
    }
    Model::new(
        C::BulletinBoard,
        fin,
        [w + 0.04, y + h + 0.02, 0.06],
        4.0,
        p,
    )
}

/// A chess table: a square table on a turned pedestal, its top a chessboard of light and dark
/// squares with the pieces set up, pawns in front of the back rows.
fn chess_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CHESS, rng);
    let c = fin.rgb;
    let s = r(rng, 0.62, 0.72);
    let h = 0.72;
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [0.44, 0.05, 0.44], c);
    cyl(&mut p, 0.0, 0.05, 0.0, 0.06, h - 0.1, c);
    cyl(&mut p, 0.0, 0.3, 0.0, 0.09, 0.12, shade(c, 0.9));
    bcube(&mut p, 0.0, h - 0.05, 0.0, [s, 0.05, s], 0.008, c);
    // The board: light squares under dark ones, a square an eighth of it.
    let b = s - 0.12;
    let q = b / 8.0;
    let top = h;
    cube(&mut p, 0.0, top, 0.0, [b, 0.004, b], [0.85, 0.76, 0.58]);
    for i in 0..8 {
        for j in 0..8 {
            if (i + j) % 2 == 1 {
                let (x, z) = ((i as f32 - 3.5) * q, (j as f32 - 3.5) * q);
                cube(&mut p, x, top + 0.004, z, [q, 0.002, q], [0.25, 0.13, 0.06]);
            }
        }
    }
    // The pieces in their back rows: white on the near side (-z), black on the far side.
    for (side, col) in [(-1.0f32, [0.93, 0.92, 0.88]), (1.0, tone::SOOT)] {
        for i in 0..8 {
            let x = (i as f32 - 3.5) * q;
            let tall = [0.05, 0.055, 0.06, 0.08, 0.085, 0.06, 0.055, 0.05][i];
            cyl(&mut p, x, top + 0.006, side * 3.5 * q, q * 0.3, tall, col);
        }
    }
    Model::new(C::ChessTable, fin, [s, h + 0.1, s], 15.0, p)
}

/// A candelabra: a round foot, a stem with a knot, arms out to both sides and candle cups with
/// white candles, three or (less often) five.
fn candelabra(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(FITTING, rng);
    let c = fin.rgb;
    let five = rng.random_bool(0.3);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.07, 0.02, c);
    cyl(&mut p, 0.0, 0.02, 0.0, 0.04, 0.03, c);
    cyl(&mut p, 0.0, 0.05, 0.0, 0.012, 0.22, c);
    cube(&mut p, 0.0, 0.12, 0.0, [0.045, 0.045, 0.045], c);
    let arm_y = 0.26;
    let spans: &[f32] = if five { &[0.07, 0.14] } else { &[0.13] };
    let mut cups = vec![(0.0f32, arm_y + 0.06)];
    for &sx in spans {
        cube(&mut p, 0.0, arm_y, 0.0, [sx * 2.0 + 0.02, 0.014, 0.014], c);
        for s in [-1.0, 1.0] {
            cyl(&mut p, s * sx, arm_y, 0.0, 0.008, 0.04, c);
            cups.push((s * sx, arm_y + 0.04));
        }
    }
    cyl(&mut p, 0.0, arm_y, 0.0, 0.012, 0.06, c);
    for (x, y) in cups {
        cyl(&mut p, x, y, 0.0, 0.024, 0.025, c);
        cyl(&mut p, x, y + 0.025, 0.0, 0.012, 0.12, [0.96, 0.94, 0.88]);
        bead(&mut p, [x, y + 0.16, 0.0], 0.01, [1.0, 0.75, 0.25]);
    }
    let w = spans.iter().fold(0.0f32, |a, &s| a.max(s)) * 2.0 + 0.05;
    Model::new(C::Candelabra, fin, [w, arm_y + 0.24, 0.14], 2.0, p)
}

/// An exercise ball on the floor.
fn exercise_ball(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(RUBBER, rng);
    let rad = r(rng, 0.28, 0.36);
    let mut p = Vec::new();
    ball(&mut p, [0.0, rad, 0.0], rad, fin.rgb);
    // The valve plug.
    bead(
        &mut p,
        [0.0, rad * 1.3, -rad * 0.96],
        0.012,
        shade(fin.rgb, 0.7),
    );
    Model::new(
        C::ExerciseBall,
        fin,
        [rad * 2.0, rad * 2.0, rad * 2.0],
        1.2,
        p,
    )
}

/// A sword mounted on the wall: a long steel blade with a ridge and its point, a wide gold
/// crossguard, a wrapped grip and a pommel, held on two brackets over a narrow dark plaque that
/// sets it off from the wall.
fn sword(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BLADE, rng);
    let c = fin.rgb;
    let len = r(rng, 1.0, 1.1);
    let y = r(rng, 1.45, 1.6);
    let guard = [BRASS, BRASS, tone::STEEL][rng.random_range(0..3)];
    let grip = [[0.25, 0.13, 0.06], tone::SOOT, [0.45, 0.08, 0.06]][rng.random_range(0..3)];
    let plaque =
        [[0.2, 0.11, 0.05], [0.12, 0.07, 0.04], [0.35, 0.05, 0.05]][rng.random_range(0..3)];
    let mut p = Vec::new();
    bcube(
        &mut p,
        0.0,
        y - 0.07,
        -0.006,
        [len + 0.1, 0.14, 0.012],
        0.002,
        plaque,
    );
    // From the point at x0 to the guard at gx, then the grip and the pommel.
    let (x0, gx) = (-len * 0.5, len * 0.5 - 0.26);
    let blade = gx - x0 - 0.05;
    let (z, bh) = (-0.05, 0.065);
    cube(
        &mut p,
        x0 + 0.05 + blade * 0.5,
        y - bh * 0.5,
        z,
        [blade, bh, 0.008],
        c,
    );
    cube(
        &mut p,
        x0 + 0.05 + blade * 0.5,
        y - 0.005,
        z - 0.005,
        [blade - 0.05, 0.01, 0.004],
        shade(c, 0.75),
    );
    let tip = Quat::from_rotation_z(FRAC_PI_4);
    tilted(&mut p, [x0 + 0.05, y, z], [0.046, 0.046, 0.008], tip, c);
    cube(&mut p, gx + 0.02, y - 0.13, z, [0.04, 0.26, 0.03], guard);
    let along = Quat::from_rotation_z(FRAC_PI_2);
    rod(&mut p, [gx + 0.13, y, z], 0.02, 0.18, along, grip);
    bead(&mut p, [gx + 0.245, y, z], 0.033, guard);
    // Two brackets out of the plaque, under the blade and under the grip.
    for x in [x0 + 0.25, gx + 0.13] {
        cube(
            &mut p,
            x,
            y - 0.065,
            z * 0.5 - 0.01,
            [0.03, 0.03, -z + 0.02],
            tone::METAL,
        );
    }
    Model::new(C::Sword, fin, [len + 0.1, y + 0.13, 0.09], 2.0, p)
}

/// A pile of rocks: a few lumpy boulders of different sizes (each a big stone with smaller
/// ones grown into it, sunk a little into the ground) and pebbles round them.
fn rocks(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(ROCK, rng);
    let c = fin.rgb;
    let n = 3 + rng.random_range(0..3);
    let mut p = Vec::new();
    for k in 0..n {
        let size = if k == 0 {
            r(rng, 0.2, 0.26)
        } else {
            r(rng, 0.1, 0.17)
        };
        let a = k as f32 * TAU / n as f32 + r(rng, 0.0, 0.8);
        let dist = if k == 0 { 0.0 } else { r(rng, 0.24, 0.36) };
        let (x, z) = (a.cos() * dist, a.sin() * dist);
        let rgb = shade(c, r(rng, 0.8, 1.1));
        let sink = (size * 0.25).min(0.04);
        ball(&mut p, [x, size - sink, z], size, rgb);
        // Lumps: smaller stones lower down either side, so that it is wider than tall.
        for _ in 0..1 {
            let b = r(rng, 0.0, TAU);
            let rad = size * r(rng, 0.6, 0.75);
            let off = size * 0.55;
            let lump = [
                x + b.cos() * off,
                rad - sink.min(rad * 0.25),
                z + b.sin() * off,
            ];
            ball(&mut p, lump, rad, shade(rgb, r(rng, 0.85, 1.1)));
        }
    }
    for _ in 0..3 {
        let a = r(rng, 0.0, TAU);
        let dist = r(rng, 0.35, 0.55);
        let rad = r(rng, 0.03, 0.05);
        let at = [a.cos() * dist, rad * 0.8, a.sin() * dist];
        ball(&mut p, at, rad, shade(c, r(rng, 0.7, 1.2)));
    }
    Model::new(C::Rocks, fin, [1.1, 0.5, 1.1], 80.0, p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::room_things::{things, Lot};
    use rand::SeedableRng;
    use vlnverse_env::RoomType;

    #[test]
    fn every_class_builds_its_own_model_and_others_none() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for &class in C::ALL
            .iter()
            .filter(|c| (C::Sectional.id()..=C::Rocks.id()).contains(&c.id()))
        {
            for _ in 0..8 {
                let m = model(class, &mut rng).expect("a model");
                assert_eq!(m.class, class);
                assert!(m.w > 0.05 && m.d > 0.02 && m.h > 0.005, "{class:?}");
                assert!(
                    m.h < 2.6 && m.w < 3.1 && m.d < 3.1,
                    "{class:?} {} {} {}",
                    m.w,
                    m.h,
                    m.d
                );
                for part in &m.parts {
                    let lo = part.transform.position[1];
                    assert!(lo > -0.2, "{class:?} below the floor");
                }
            }
        }
        assert!(model(C::Sofa, &mut rng).is_none());
    }

    #[test]
    fn every_room_lists_only_this_module_classes() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for &kind in RoomType::ALL {
            for th in things(Lot::Second, kind) {
                assert!(model(th.class, &mut rng).is_some(), "{:?}", th.class);
                assert!((0.0..=1.0).contains(&th.chance));
            }
        }
    }

    #[test]
    fn a_ceiling_fan_hangs_low_enough_to_clear_the_agent() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for _ in 0..20 {
            let m = ceiling_fan(&mut rng);
            // Hung with its top at a 2.67 m ceiling, its lowest point is above 2.1 m.
            assert!(2.67 - m.h > 2.1, "{}", m.h);
            assert!(m.w > 0.9 && m.w < 1.4, "{}", m.w);
        }
    }
}
