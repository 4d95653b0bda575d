//! Models of the things issue 26 added so that instructions can name what people name in a
//! home (R2R's "walk past the grand piano", "stop on the doormat", "go past the room
//! divider"): mats and a hallway runner, a grand piano, a hot tub and a fountain, wall
//! hangings (a tapestry, a wreath, a deer head, a dartboard), gym machines, game machines, a
//! bar, children's things, garage things and a telescope.
//!
//! Like every model (`models.rs`), each is built in its own frame with its front at -Z and its
//! back (the side that goes to the wall) at +Z, and draws its colour from a finish list of its
//! own, so that the colour word instructions use is the colour of its largest part.

use crate::models::{ball, bcube, cube, cyl, disc_z, front, legs, r, turned, Model};
use crate::palette::{f, shade, tone, Finish};
use glam::Quat;
use rand::seq::IndexedRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, TAU};
use vlnverse_env::{SemanticClass as C, Shape};

/// Coir and rubber doormats.
const MAT: &[Finish] = &[
    f("brown", "fabric", [0.36, 0.22, 0.1]),
    f("brown", "fabric", [0.3, 0.18, 0.08]),
    f("black", "fabric", [0.05, 0.05, 0.05]),
    f("grey", "fabric", [0.3, 0.3, 0.32]),
    f("beige", "fabric", [0.66, 0.55, 0.38]),
];
/// Hallway runners: the colours of long rugs.
const RUNNER: &[Finish] = &[
    f("red", "fabric", [0.45, 0.06, 0.06]),
    f("blue", "fabric", [0.08, 0.15, 0.42]),
    f("beige", "fabric", [0.7, 0.6, 0.44]),
    f("grey", "fabric", [0.35, 0.35, 0.37]),
    f("green", "fabric", [0.1, 0.3, 0.15]),
    f("brown", "fabric", [0.3, 0.17, 0.08]),
];
/// Piano lacquer: mostly black.
const LACQUER: &[Finish] = &[
    f("black", "wood", [0.03, 0.03, 0.03]),
    f("black", "wood", [0.03, 0.03, 0.03]),
    f("white", "wood", [0.88, 0.88, 0.86]),
    f("brown", "wood", [0.25, 0.13, 0.06]),
];
/// Outdoor wood and plastic: hot tub cladding, barrels, outdoor frames.
const CLADDING: &[Finish] = &[
    f("brown", "wood", [0.3, 0.17, 0.08]),
    f("wooden", "wood", [0.5, 0.32, 0.16]),
    f("grey", "plastic", [0.35, 0.35, 0.37]),
    f("black", "plastic", [0.05, 0.05, 0.05]),
];
const STONE: &[Finish] = &[
    f("white", "stone", [0.8, 0.78, 0.74]),
    f("grey", "stone", [0.45, 0.45, 0.46]),
    f("beige", "stone", [0.68, 0.6, 0.46]),
];
/// Appliances and machines in plastic or painted steel.
const MACHINE: &[Finish] = &[
    f("white", "plastic", [0.88, 0.88, 0.88]),
    f("black", "plastic", [0.05, 0.05, 0.05]),
    f("grey", "plastic", [0.4, 0.4, 0.42]),
    f("silver", "metal", [0.6, 0.6, 0.62]),
];
/// Cloth hung on a wall or from a pole.
const CLOTH: &[Finish] = &[
    f("red", "fabric", [0.45, 0.06, 0.06]),
    f("blue", "fabric", [0.08, 0.15, 0.42]),
    f("green", "fabric", [0.1, 0.3, 0.15]),
    f("beige", "fabric", [0.7, 0.6, 0.44]),
    f("brown", "fabric", [0.32, 0.18, 0.08]),
];
/// Folding screens: wood frames, paper or cloth panels.
const SCREEN: &[Finish] = &[
    f("wooden", "wood", [0.5, 0.32, 0.16]),
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("white", "fabric", [0.86, 0.85, 0.8]),
    f("black", "wood", [0.05, 0.05, 0.05]),
];
const EVERGREEN: &[Finish] = &[
    f("green", "plastic", [0.05, 0.25, 0.08]),
    f("green", "plastic", [0.08, 0.3, 0.1]),
];
/// A deer's fur, a rocking horse's coat.
const FUR: &[Finish] = &[
    f("brown", "fabric", [0.35, 0.2, 0.09]),
    f("brown", "fabric", [0.28, 0.16, 0.07]),
];
/// Game and jukebox cabinets: black, wood or a loud colour.
const CABINET: &[Finish] = &[
    f("black", "wood", [0.04, 0.04, 0.05]),
    f("red", "wood", [0.55, 0.05, 0.05]),
    f("blue", "wood", [0.08, 0.16, 0.5]),
    f("wooden", "wood", [0.5, 0.32, 0.16]),
];
/// Gym machines.
const GYM: &[Finish] = &[
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("grey", "metal", [0.35, 0.35, 0.37]),
    f("silver", "metal", [0.6, 0.6, 0.62]),
];
/// Home bars: wood or painted panels.
const BAR: &[Finish] = &[
    f("wooden", "wood", [0.5, 0.32, 0.16]),
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("black", "wood", [0.05, 0.05, 0.05]),
    f("white", "wood", [0.86, 0.86, 0.84]),
];
/// Painted toys: dollhouses and rocking horses.
const TOY: &[Finish] = &[
    f("white", "wood", [0.88, 0.88, 0.86]),
    f("pink", "wood", [0.85, 0.45, 0.55]),
    f("yellow", "wood", [0.85, 0.7, 0.15]),
    f("blue", "wood", [0.15, 0.3, 0.65]),
    f("wooden", "wood", [0.55, 0.35, 0.17]),
];
/// Bunk bed blankets.
const BLANKET: &[Finish] = &[
    f("blue", "fabric", [0.1, 0.22, 0.55]),
    f("red", "fabric", [0.5, 0.07, 0.06]),
    f("green", "fabric", [0.12, 0.38, 0.14]),
    f("grey", "fabric", [0.35, 0.35, 0.37]),
    f("white", "fabric", [0.86, 0.86, 0.84]),
];
/// Carpet-covered cat trees.
const CARPET: &[Finish] = &[
    f("beige", "fabric", [0.7, 0.6, 0.44]),
    f("grey", "fabric", [0.4, 0.4, 0.42]),
    f("white", "fabric", [0.85, 0.84, 0.8]),
    f("brown", "fabric", [0.32, 0.2, 0.1]),
];
/// Bright plastic of vacuum cleaners, mowers and kayaks.
const BRIGHT: &[Finish] = &[
    f("red", "plastic", [0.6, 0.05, 0.04]),
    f("yellow", "plastic", [0.85, 0.68, 0.08]),
    f("orange", "plastic", [0.85, 0.35, 0.05]),
    f("blue", "plastic", [0.08, 0.2, 0.6]),
    f("green", "plastic", [0.1, 0.4, 0.12]),
];
/// Dartboards are black with coloured rings.
const DARTBOARD: &[Finish] = &[f("black", "fabric", [0.04, 0.04, 0.04])];

/// Draw a finish from `list`, in one of its colour word's tones or its own.
fn pick(list: &[Finish], rng: &mut ChaCha8Rng) -> Finish {
    let fin = *list.choose(rng).unwrap_or(&list[0]);
    crate::tones::toned(fin, rng)
}

/// A cuboid of half extents `h`, centred at `c` and turned by `rot`.
fn tilted(p: &mut Vec<vlnverse_env::Part>, c: [f32; 3], h: [f32; 3], rot: Quat, rgb: [f32; 3]) {
    let shape = Shape::Cuboid {
        half_extents: h,
        bevel: 0.0,
    };
    turned(p, shape, c, rot, rgb);
}

/// The model of one of this module's classes; `None` for any other class (the doormat and
/// the runner are sized by where they lie: [`doormat`], [`runner`]).
pub(crate) fn model(class: C, rng: &mut ChaCha8Rng) -> Option<Model> {
    Some(match class {
        C::Doormat => doormat(rng, 0.9),
        C::Runner => runner(rng, 3.0, 0.7),
        C::GrandPiano => grand_piano(rng),
        C::HotTub => hot_tub(rng),
        C::Fountain => fountain(rng),
        C::WaterCooler => water_cooler(rng),
        C::Tapestry => tapestry(rng),
        C::RoomDivider => room_divider(rng),
        C::Wreath => wreath(rng),
        C::DeerHead => deer_head(rng),
        C::Flag => flag(rng),
        C::Elliptical => elliptical(rng),
        C::RowingMachine => rowing_machine(rng),
        C::Bar => bar(rng),
        C::Dollhouse => dollhouse(rng),
        C::AirHockeyTable => air_hockey_table(rng),
        C::PinballMachine => pinball_machine(rng),
        C::Dartboard => dartboard(rng),
        C::Barrel => barrel(rng),
        C::BunkBed => bunk_bed(rng),
        C::RockingHorse => rocking_horse(rng),
        C::CatTree => cat_tree(rng),
        C::VacuumCleaner => vacuum_cleaner(rng),
        C::LawnMower => lawn_mower(rng),
        C::Kayak => kayak(rng),
        C::Telescope => telescope(rng),
        C::Jukebox => jukebox(rng),
        _ => return None,
    })
}

/// A doormat at most `max_w` wide: a flat mat with a darker border, low enough to walk on.
pub(crate) fn doormat(rng: &mut ChaCha8Rng, max_w: f32) -> Model {
    let fin = pick(MAT, rng);
    let w = r(rng, 0.7, 0.95).min(max_w);
    let d = r(rng, 0.45, 0.6);
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [w, 0.012, d], fin.rgb);
    let border = shade(fin.rgb, 0.6);
    for sz in [-1.0, 1.0] {
        cube(
            &mut p,
            0.0,
            0.0,
            sz * (d * 0.5 - 0.02),
            [w, 0.013, 0.04],
            border,
        );
    }
    Model::new(C::Doormat, fin, [w, 0.013, d], 1.5, p)
}

/// A hallway runner `len` long and `w` wide: a long flat rug with a border stripe near each
/// long edge and a band at each end.
pub(crate) fn runner(rng: &mut ChaCha8Rng, len: f32, w: f32) -> Model {
    let fin = pick(RUNNER, rng);
    let c = fin.rgb;
    let band = if fin.color == "beige" {
        shade(c, 0.6)
    } else {
        tone::LINEN
    };
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [len, 0.01, w], c);
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            0.0,
            0.0,
            s * (w * 0.5 - 0.07),
            [len - 0.1, 0.011, 0.03],
            band,
        );
        cube(
            &mut p,
            s * (len * 0.5 - 0.1),
            0.0,
            0.0,
            [0.04, 0.011, w - 0.1],
            band,
        );
    }
    Model::new(C::Runner, fin, [len, 0.011, w], 3.0, p)
}

/// A grand piano: a deep body on three legs with its lid propped open, the keyboard at the
/// front and the curved tail at the back.
fn grand_piano(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(LACQUER, rng);
    let c = fin.rgb;
    let (w, d) = (r(rng, 1.45, 1.55), r(rng, 1.55, 1.8));
    let mut p = Vec::new();
    let (y, body_h) = (0.62, 0.3);
    // The body: a straight front part and a narrower rounded tail (the piano's bent side).
    bcube(&mut p, 0.0, y, -d * 0.2, [w, body_h, d * 0.6], 0.02, c);
    cyl(&mut p, -w * 0.12, y, d * 0.15, w * 0.38, body_h, c);
    // Legs: two at the front corners, one under the tail.
    for sx in [-1.0, 1.0] {
        cube(
            &mut p,
            sx * (w * 0.5 - 0.08),
            0.0,
            -d * 0.5 + 0.12,
            [0.09, y, 0.09],
            c,
        );
    }
    cube(&mut p, -w * 0.12, 0.0, d * 0.3, [0.09, y, 0.09], c);
    // Keyboard jutting out at the front, white keys with black ones on them.
    let kz = -d * 0.5 - 0.04;
    cube(
        &mut p,
        0.0,
        y + 0.08,
        kz,
        [w - 0.2, 0.05, 0.16],
        tone::WHITE,
    );
    for k in 0..18 {
        let x = -w * 0.42 + k as f32 * (w * 0.84 / 17.0);
        cube(
            &mut p,
            x,
            y + 0.13,
            kz + 0.03,
            [0.02, 0.015, 0.09],
            tone::SOOT,
        );
    }
    // The lid, propped up on the right side by a stick.
    let lid = Quat::from_rotation_z(-0.5);
    tilted(
        &mut p,
        [w * 0.22, y + body_h + 0.3, 0.0],
        [w * 0.48, 0.012, d * 0.45],
        lid,
        c,
    );
    cube(&mut p, w * 0.4, y + body_h, 0.0, [0.02, 0.45, 0.02], c);
    // Music stand.
    cube(
        &mut p,
        0.0,
        y + body_h,
        -d * 0.42,
        [w * 0.5, 0.25, 0.02],
        shade(c, 0.9),
    );
    Model::new(C::GrandPiano, fin, [w, 1.3, d + 0.1], 400.0, p)
}

/// A square hot tub: clad sides, a rim, blue water inside and a folded cover at the back.
fn hot_tub(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CLADDING, rng);
    let c = fin.rgb;
    let s = r(rng, 1.5, 1.8);
    let h = 0.9;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [s, h - 0.08, s], 0.03, c);
    bcube(&mut p, 0.0, h - 0.08, 0.0, [s, 0.08, s], 0.015, tone::LINEN);
    cube(
        &mut p,
        0.0,
        h - 0.07,
        0.0,
        [s - 0.3, 0.08, s - 0.3],
        tone::WATER,
    );
    cube(
        &mut p,
        0.0,
        h,
        s * 0.5 - 0.25,
        [s - 0.1, 0.12, 0.5],
        tone::METAL,
    );
    Model::new(C::HotTub, fin, [s, h + 0.12, s], 300.0, p)
}

/// A garden fountain: a wide round basin with water, a pillar and a smaller bowl on top.
fn fountain(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(STONE, rng);
    let c = fin.rgb;
    let rad = r(rng, 0.35, 0.45);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, rad, 0.4, c);
    cyl(&mut p, 0.0, 0.4, 0.0, rad - 0.06, 0.01, tone::WATER);
    cyl(&mut p, 0.0, 0.0, 0.0, 0.1, 0.85, shade(c, 0.9));
    cyl(&mut p, 0.0, 0.85, 0.0, rad * 0.5, 0.12, c);
    cyl(&mut p, 0.0, 0.97, 0.0, rad * 0.5 - 0.04, 0.01, tone::WATER);
    cyl(&mut p, 0.0, 0.97, 0.0, 0.04, 0.2, c);
    ball(&mut p, [0.0, 1.2, 0.0], 0.06, c);
    Model::new(C::Fountain, fin, [rad * 2.0, 1.26, rad * 2.0], 120.0, p)
}

/// A water cooler: a cabinet with two taps and a blue bottle upside down on top.
fn water_cooler(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(MACHINE, rng);
    let c = fin.rgb;
    let h = r(rng, 0.95, 1.05);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [0.32, h, 0.32], 0.01, c);
    front(
        &mut p,
        0.32,
        [0.0, h * 0.62, -0.05],
        [0.2, 0.18, 0.1],
        shade(c, 0.7),
    );
    for (x, tap) in [(-0.05, [0.1, 0.2, 0.7]), (0.05, tone::FRUIT_RED)] {
        front(&mut p, 0.32, [x, h * 0.72, -0.04], [0.03, 0.04, 0.04], tap);
    }
    cyl(&mut p, 0.0, h, 0.0, 0.13, 0.4, [0.3, 0.5, 0.8]);
    cyl(&mut p, 0.0, h + 0.4, 0.0, 0.05, 0.05, [0.3, 0.5, 0.8]);
    Model::new(C::WaterCooler, fin, [0.32, h + 0.45, 0.32], 15.0, p)
}

/// A tapestry: a woven wall hanging on a rod, with bands of a second colour and a border. Its
/// footprint is a strip along the wall.
fn tapestry(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CLOTH, rng);
    let c = fin.rgb;
    let (w, h) = (r(rng, 1.1, 1.7), r(rng, 1.0, 1.3));
    let y = r(rng, 0.75, 0.9);
    let accent = [tone::FRUIT_YELLOW, tone::LINEN, [0.5, 0.1, 0.1]][rng.random_range(0..3)];
    let mut p = Vec::new();
    cube(&mut p, 0.0, y, 0.0, [w, h, 0.02], c);
    for k in 0..3 {
        let band = y + h * (0.25 + 0.25 * k as f32);
        cube(&mut p, 0.0, band, -0.012, [w - 0.16, 0.06, 0.004], accent);
    }
    let edge = shade(c, 0.6);
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * (w * 0.5 - 0.04),
            y,
            -0.012,
            [0.04, h, 0.004],
            edge,
        );
    }
    turned(
        &mut p,
        Shape::Cylinder {
            radius: 0.015,
            half_height: w * 0.5 + 0.06,
        },
        [0.0, y + h + 0.02, 0.0],
        Quat::from_rotation_z(FRAC_PI_2),
        tone::WOOD,
    );
    // The rod's brackets stand out from the wall.
    for sx in [-1.0, 1.0] {
        let at = [sx * (w * 0.5 + 0.03), y + h - 0.01, -0.01];
        cube(&mut p, at[0], at[1], at[2], [0.03, 0.06, 0.06], tone::WOOD);
    }
    Model::new(C::Tapestry, fin, [w + 0.12, y + h + 0.05, 0.06], 2.0, p)
}

/// A folding screen: four tall panels standing in a zigzag, each a frame round a lighter
/// panel.
fn room_divider(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(SCREEN, rng);
    let c = fin.rgb;
    let (pw, h) = (r(rng, 0.42, 0.5), r(rng, 1.7, 1.85));
    let n = 4;
    let a = 0.45f32;
    let step = pw * a.cos();
    let panel = if fin.color == "white" {
        tone::LINEN
    } else {
        shade(c, 1.6)
    };
    let mut p = Vec::new();
    for k in 0..n {
        let x = (k as f32 - (n - 1) as f32 * 0.5) * step;
        let yaw = if k % 2 == 0 { a } else { -a };
        let rot = Quat::from_rotation_y(yaw);
        tilted(&mut p, [x, h * 0.5, 0.0], [pw * 0.5, h * 0.5, 0.02], rot, c);
        let inner = [pw * 0.38, h * 0.4, 0.022];
        tilted(&mut p, [x, h * 0.52, 0.0], inner, rot, panel);
    }
    let w = n as f32 * step + 0.1;
    Model::new(C::RoomDivider, fin, [w, h, pw * a.sin() + 0.06], 10.0, p)
}

/// A wreath on the wall: a ring of evergreen with red berries and a red bow at the bottom.
fn wreath(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(EVERGREEN, rng);
    let rad = r(rng, 0.2, 0.26);
    let y = r(rng, 1.45, 1.6);
    let mut p = Vec::new();
    for k in 0..12 {
        let a = k as f32 / 12.0 * TAU;
        ball(
            &mut p,
            [a.sin() * rad, y + a.cos() * rad, 0.0],
            0.075,
            fin.rgb,
        );
        if k % 3 == 1 {
            let c = [a.sin() * rad * 1.05, y + a.cos() * rad * 1.05, -0.07];
            ball(&mut p, c, 0.022, tone::FRUIT_RED);
        }
    }
    let bow = [0.14, 0.08, 0.03];
    cube(&mut p, 0.0, y - rad - 0.05, -0.07, bow, [0.6, 0.04, 0.04]);
    Model::new(
        C::Wreath,
        fin,
        [rad * 2.0 + 0.15, y + rad + 0.08, 0.15],
        0.5,
        p,
    )
}

/// A mounted deer head: a wooden shield on the wall, the neck and head coming out of it and
/// branching antlers. It hangs high, so only a strip of floor along the wall is its own.
fn deer_head(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(FUR, rng);
    let c = fin.rgb;
    let y = r(rng, 1.6, 1.7);
    let mut p = Vec::new();
    bcube(
        &mut p,
        0.0,
        y - 0.2,
        0.18,
        [0.32, 0.42, 0.04],
        0.008,
        tone::WOOD,
    );
    // Neck out of the shield, the head pointing forward and a little down.
    bcube(&mut p, 0.0, y - 0.15, 0.05, [0.18, 0.26, 0.24], 0.04, c);
    tilted(
        &mut p,
        [0.0, y + 0.05, -0.12],
        [0.08, 0.08, 0.14],
        Quat::from_rotation_x(0.35),
        c,
    );
    for s in [-1.0f32, 1.0] {
        // Ears, then an antler: a beam up and out with two tines.
        tilted(
            &mut p,
            [s * 0.1, y + 0.14, -0.04],
            [0.05, 0.02, 0.02],
            Quat::from_rotation_z(s * 0.4),
            c,
        );
        let beam = Quat::from_rotation_z(-s * 0.5);
        tilted(
            &mut p,
            [s * 0.1, y + 0.3, -0.05],
            [0.015, 0.16, 0.015],
            beam,
            tone::LINEN,
        );
        for t in [0.25, 0.38] {
            let tine = Quat::from_rotation_z(s * 0.2);
            tilted(
                &mut p,
                [s * (0.08 + t * 0.3), y + t + 0.1, -0.05],
                [0.012, 0.07, 0.012],
                tine,
                tone::LINEN,
            );
        }
    }
    ball(&mut p, [0.0, y - 0.01, -0.25], 0.03, tone::SOOT);
    Model::new(C::DeerHead, fin, [0.5, y + 0.5, 0.45], 3.0, p)
}

/// A flag on a pole in a weighted stand: a striped cloth hanging from the top of the pole.
fn flag(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CLOTH, rng);
    let c = fin.rgb;
    let h = r(rng, 2.0, 2.15);
    let (fw, fh) = (r(rng, 0.8, 0.95), r(rng, 0.55, 0.65));
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.18, 0.06, tone::METAL);
    cyl(&mut p, 0.0, 0.0, 0.0, 0.018, h, tone::FRUIT_YELLOW);
    ball(&mut p, [0.0, h + 0.03, 0.0], 0.035, tone::FRUIT_YELLOW);
    // The cloth, hanging to one side of the pole, with a white stripe.
    let top = h - 0.1;
    cube(&mut p, fw * 0.5 + 0.02, top - fh, 0.0, [fw, fh, 0.015], c);
    cube(
        &mut p,
        fw * 0.5 + 0.02,
        top - fh * 0.6,
        -0.004,
        [fw, fh * 0.2, 0.012],
        tone::WHITE,
    );
    Model::new(C::Flag, fin, [fw + 0.4, h + 0.07, 0.36], 5.0, p)
}

/// An elliptical trainer: a long base, two pedal arms, tall swinging handles and a console.
fn elliptical(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(GYM, rng);
    let c = fin.rgb;
    let (w, d) = (0.65, r(rng, 1.6, 1.8));
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [0.2, 0.12, d], 0.02, c);
    cube(&mut p, 0.0, 0.0, d * 0.5 - 0.08, [w, 0.08, 0.12], c);
    cube(&mut p, 0.0, 0.0, -d * 0.5 + 0.08, [w, 0.08, 0.12], c);
    // The flywheel housing at the back and the pedals.
    disc_z(
        &mut p,
        [0.0, 0.35, d * 0.5 - 0.25],
        0.25,
        0.22,
        shade(c, 0.8),
    );
    for s in [-1.0, 1.0] {
        cube(&mut p, s * 0.15, 0.25, 0.0, [0.14, 0.04, 0.36], tone::SOOT);
        // Handles swinging up from the front post.
        tilted(
            &mut p,
            [s * 0.24, 1.05, -d * 0.5 + 0.28],
            [0.02, 0.5, 0.02],
            Quat::from_rotation_x(0.12),
            tone::STEEL,
        );
    }
    cube(&mut p, 0.0, 0.08, -d * 0.5 + 0.2, [0.1, 1.3, 0.1], c);
    tilted(
        &mut p,
        [0.0, 1.42, -d * 0.5 + 0.2],
        [0.17, 0.12, 0.03],
        Quat::from_rotation_x(-0.5),
        tone::SCREEN,
    );
    Model::new(C::Elliptical, fin, [w, 1.62, d], 60.0, p)
}

/// A rowing machine: a long rail on the floor, a sliding seat, foot plates and the round fan
/// housing at the front.
fn rowing_machine(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(GYM, rng);
    let c = fin.rgb;
    let d = r(rng, 1.8, 1.95);
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, d * 0.5 - 0.05, [0.5, 0.06, 0.1], c);
    tilted(
        &mut p,
        [0.0, 0.2, 0.1],
        [0.05, 0.03, d * 0.42],
        Quat::from_rotation_x(-0.12),
        c,
    );
    disc_z(&mut p, [0.0, 0.35, -d * 0.5 + 0.25], 0.27, 0.18, c);
    cube(&mut p, 0.0, 0.0, -d * 0.5 + 0.2, [0.5, 0.06, 0.1], c);
    bcube(&mut p, 0.0, 0.26, 0.1, [0.3, 0.06, 0.3], 0.012, tone::SOOT);
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * 0.1,
            0.15,
            -d * 0.5 + 0.55,
            [0.12, 0.2, 0.26],
            tone::SOOT,
        );
    }
    cube(
        &mut p,
        0.0,
        0.55,
        -d * 0.5 + 0.45,
        [0.45, 0.03, 0.03],
        tone::SOOT,
    );
    Model::new(C::RowingMachine, fin, [0.55, 0.62, d], 35.0, p)
}

/// A home bar: a counter higher than a kitchen's with an overhanging top and a foot rail at
/// the front, and a shelf of bottles on the wall behind it.
fn bar(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BAR, rng);
    let c = fin.rgb;
    let w = r(rng, 1.6, 2.2);
    let (d, h) = (0.6, 1.08);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.05, [w, h - 0.05, d - 0.1], 0.01, c);
    bcube(
        &mut p,
        0.0,
        h - 0.05,
        0.0,
        [w + 0.06, 0.05, d],
        0.01,
        shade(c, 0.7),
    );
    for k in 0..3 {
        let x = (k as f32 - 1.0) * w / 3.0;
        front(
            &mut p,
            d - 0.1,
            [x, 0.15, 0.04],
            [w / 3.0 - 0.06, h - 0.35, 0.01],
            shade(c, 0.85),
        );
    }
    turned(
        &mut p,
        Shape::Cylinder {
            radius: 0.02,
            half_height: w * 0.5 - 0.05,
        },
        [0.0, 0.2, -d * 0.5 + 0.03],
        Quat::from_rotation_z(FRAC_PI_2),
        tone::STEEL,
    );
    // A shelf of bottles on the wall, above the back of the counter.
    let sy = h + 0.45;
    cube(
        &mut p,
        0.0,
        sy,
        d * 0.5 - 0.1,
        [w * 0.8, 0.03, 0.2],
        shade(c, 0.7),
    );
    for k in 0..7 {
        let x = -w * 0.35 + k as f32 * w * 0.7 / 6.0;
        let glass = [tone::LEAF, [0.35, 0.2, 0.05], tone::GLASS][k % 3];
        cyl(&mut p, x, sy + 0.03, d * 0.5 - 0.1, 0.035, 0.28, glass);
    }
    Model::new(C::Bar, fin, [w + 0.06, sy + 0.31, d], 150.0, p)
}

/// A dollhouse on a low stand: a painted house with a pitched roof, open windows and a door.
fn dollhouse(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(TOY, rng);
    let c = fin.rgb;
    let (w, h, d) = (r(rng, 0.7, 0.85), r(rng, 0.55, 0.65), 0.4);
    let y = 0.3;
    let roof = [[0.55, 0.12, 0.1], [0.2, 0.2, 0.22], [0.15, 0.3, 0.6]][rng.random_range(0..3)];
    let mut p = Vec::new();
    legs(&mut p, w, d, y, 0.04, tone::WOOD);
    cube(
        &mut p,
        0.0,
        y - 0.03,
        0.0,
        [w + 0.04, 0.03, d + 0.04],
        tone::WOOD,
    );
    cube(&mut p, 0.0, y, 0.0, [w, h, d], c);
    for s in [-1.0, 1.0] {
        let rot = Quat::from_rotation_z(s * FRAC_PI_4);
        let half = [w * 0.38, 0.015, d * 0.5 + 0.02];
        tilted(
            &mut p,
            [-s * w * 0.25, y + h + w * 0.22, 0.0],
            half,
            rot,
            roof,
        );
        for row in [0.3, 0.65] {
            front(
                &mut p,
                d,
                [s * w * 0.25, y + h * row, -0.004],
                [0.12, 0.12, 0.008],
                tone::SCREEN,
            );
        }
    }
    front(
        &mut p,
        d,
        [0.0, y, -0.004],
        [0.1, 0.2, 0.008],
        shade(c, 0.5),
    );
    Model::new(
        C::Dollhouse,
        fin,
        [w + 0.08, y + h + w * 0.45, d + 0.04],
        10.0,
        p,
    )
}

/// An air hockey table: a cabinet on legs, its white playing surface with rails, a centre line,
/// a goal at each end and two mallets.
fn air_hockey_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CABINET, rng);
    let c = fin.rgb;
    let (w, d) = (r(rng, 1.9, 2.2), r(rng, 1.0, 1.15));
    let h = 0.8;
    let mut p = Vec::new();
    legs(&mut p, w - 0.1, d - 0.1, h - 0.3, 0.1, tone::SOOT);
    bcube(&mut p, 0.0, h - 0.3, 0.0, [w, 0.26, d], 0.01, c);
    cube(
        &mut p,
        0.0,
        h - 0.04,
        0.0,
        [w - 0.1, 0.02, d - 0.1],
        tone::WHITE,
    );
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            0.0,
            h - 0.04,
            s * (d * 0.5 - 0.03),
            [w, 0.06, 0.06],
            c,
        );
        cube(
            &mut p,
            s * (w * 0.5 - 0.03),
            h - 0.04,
            0.0,
            [0.06, 0.06, d],
            c,
        );
        cube(
            &mut p,
            s * (w * 0.5 - 0.03),
            h - 0.039,
            0.0,
            [0.065, 0.02, 0.3],
            tone::SOOT,
        );
        cyl(
            &mut p,
            s * w * 0.3,
            h - 0.02,
            0.0,
            0.05,
            0.04,
            tone::FRUIT_RED,
        );
    }
    cube(
        &mut p,
        0.0,
        h - 0.039,
        0.0,
        [0.02, 0.021, d - 0.1],
        tone::FRUIT_RED,
    );
    Model::new(C::AirHockeyTable, fin, [w, h + 0.02, d], 80.0, p)
}

/// A pinball machine: a long cabinet on four legs, its glass playfield sloping up to the back,
/// and an upright backbox with a lit display.
fn pinball_machine(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CABINET, rng);
    let c = fin.rgb;
    let (w, d) = (0.7, r(rng, 1.3, 1.4));
    let mut p = Vec::new();
    legs(&mut p, w, d - 0.1, 0.75, 0.06, tone::STEEL);
    tilted(
        &mut p,
        [0.0, 0.92, 0.0],
        [w * 0.5, 0.14, d * 0.5],
        Quat::from_rotation_x(-0.1),
        c,
    );
    tilted(
        &mut p,
        [0.0, 1.07, -0.02],
        [w * 0.45, 0.005, d * 0.46],
        Quat::from_rotation_x(-0.1),
        [0.15, 0.25, 0.6],
    );
    bcube(&mut p, 0.0, 1.0, d * 0.5 - 0.12, [w, 0.85, 0.22], 0.01, c);
    cube(
        &mut p,
        0.0,
        1.2,
        d * 0.5 - 0.235,
        [w * 0.8, 0.55, 0.01],
        tone::FRUIT_YELLOW,
    );
    Model::new(C::PinballMachine, fin, [w, 1.85, d], 110.0, p)
}

/// A dartboard on the wall: a black bristle disc with red and green rings and a bull, on a
/// square backboard.
fn dartboard(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(DARTBOARD, rng);
    let y = 1.73;
    let mut p = Vec::new();
    cube(&mut p, 0.0, y - 0.33, 0.03, [0.66, 0.66, 0.02], tone::WOOD);
    disc_z(&mut p, [0.0, y, 0.0], 0.23, 0.04, fin.rgb);
    disc_z(&mut p, [0.0, y, -0.021], 0.2, 0.003, tone::FRUIT_RED);
    disc_z(&mut p, [0.0, y, -0.023], 0.18, 0.003, tone::LINEN);
    disc_z(&mut p, [0.0, y, -0.025], 0.12, 0.003, tone::LEAF);
    disc_z(&mut p, [0.0, y, -0.027], 0.1, 0.003, tone::SOOT);
    disc_z(&mut p, [0.0, y, -0.029], 0.02, 0.003, tone::FRUIT_RED);
    Model::new(C::Dartboard, fin, [0.66, y + 0.33, 0.08], 3.0, p)
}

/// A wooden barrel standing on end, with dark metal hoops.
fn barrel(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(&CLADDING[..2], rng);
    let c = fin.rgb;
    let (rad, h) = (r(rng, 0.28, 0.33), r(rng, 0.8, 0.95));
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, rad * 0.9, h, c);
    cyl(&mut p, 0.0, h * 0.2, 0.0, rad, h * 0.6, c);
    for y in [0.08, h * 0.3, h * 0.7 - 0.04, h - 0.12] {
        cyl(&mut p, 0.0, y, 0.0, rad * 0.93 + 0.01, 0.04, tone::METAL);
    }
    Model::new(C::Barrel, fin, [rad * 2.0, h, rad * 2.0], 40.0, p)
}

/// A bunk bed: two beds one above the other on four tall posts, its long side to the wall, a
/// guard rail along the top bunk and a ladder at one end.
fn bunk_bed(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BLANKET, rng);
    let wood = pick(BAR, rng).rgb;
    let (w, d, h) = (r(rng, 2.0, 2.1), 1.0, r(rng, 1.65, 1.8));
    let mut p = Vec::new();
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            cube(
                &mut p,
                sx * (w * 0.5 - 0.04),
                0.0,
                sz * (d * 0.5 - 0.04),
                [0.07, h, 0.07],
                wood,
            );
        }
        cube(
            &mut p,
            sx * (w * 0.5 - 0.04),
            0.2,
            0.0,
            [0.05, 0.25, d],
            wood,
        );
        cube(
            &mut p,
            sx * (w * 0.5 - 0.04),
            h - 0.6,
            0.0,
            [0.05, 0.25, d],
            wood,
        );
    }
    for y in [0.2, h - 0.6] {
        cube(&mut p, 0.0, y, 0.0, [w - 0.1, 0.12, d - 0.08], wood);
        cube(
            &mut p,
            0.0,
            y + 0.12,
            0.0,
            [w - 0.12, 0.16, d - 0.1],
            tone::LINEN,
        );
        cube(
            &mut p,
            -0.2,
            y + 0.28,
            0.0,
            [w - 0.5, 0.03, d - 0.08],
            fin.rgb,
        );
        bcube(
            &mut p,
            w * 0.5 - 0.3,
            y + 0.28,
            0.0,
            [0.35, 0.1, d * 0.6],
            0.02,
            tone::WHITE,
        );
    }
    // Guard rail on the open side of the top bunk, and the ladder at the foot.
    cube(
        &mut p,
        0.1,
        h - 0.22,
        -d * 0.5 + 0.04,
        [w - 0.4, 0.05, 0.04],
        wood,
    );
    for x in [-w * 0.5 + 0.15, -w * 0.5 + 0.5] {
        cube(&mut p, x, 0.0, -d * 0.5 - 0.02, [0.04, h - 0.2, 0.04], wood);
    }
    for k in 1..5 {
        let y = k as f32 * (h - 0.3) / 5.0;
        cube(
            &mut p,
            -w * 0.5 + 0.325,
            y,
            -d * 0.5 - 0.02,
            [0.35, 0.03, 0.04],
            wood,
        );
    }
    Model::new(C::BunkBed, fin, [w, h, d + 0.04], 80.0, p)
}

/// A rocking horse: a painted wooden horse on two curved rockers, with a mane and a saddle.
fn rocking_horse(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(TOY, rng);
    let c = fin.rgb;
    let len = r(rng, 0.85, 1.0);
    let mut p = Vec::new();
    // Each rocker: three pieces on an arc, lowest in the middle.
    for s in [-1.0, 1.0] {
        for (k, a) in [-0.35f32, 0.0, 0.35].into_iter().enumerate() {
            let x = (k as f32 - 1.0) * len * 0.32;
            let y = 0.03 + a.abs() * 0.12;
            tilted(
                &mut p,
                [x, y, s * 0.12],
                [len * 0.17, 0.02, 0.02],
                Quat::from_rotation_z(a),
                tone::WOOD,
            );
        }
    }
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            tilted(
                &mut p,
                [sx * 0.2, 0.22, sz * 0.08],
                [0.025, 0.17, 0.025],
                Quat::from_rotation_z(sx * 0.15),
                c,
            );
        }
    }
    bcube(&mut p, 0.0, 0.37, 0.0, [len * 0.55, 0.2, 0.2], 0.04, c);
    tilted(
        &mut p,
        [len * 0.3, 0.65, 0.0],
        [0.06, 0.16, 0.07],
        Quat::from_rotation_z(-0.4),
        c,
    );
    tilted(
        &mut p,
        [len * 0.38, 0.77, 0.0],
        [0.12, 0.06, 0.06],
        Quat::from_rotation_z(-0.3),
        c,
    );
    tilted(
        &mut p,
        [len * 0.27, 0.7, 0.0],
        [0.02, 0.16, 0.075],
        Quat::from_rotation_z(-0.4),
        tone::SOOT,
    );
    cube(&mut p, 0.0, 0.56, 0.0, [0.2, 0.03, 0.22], tone::FRUIT_RED);
    cube(&mut p, -len * 0.3, 0.4, 0.0, [0.04, 0.16, 0.05], tone::SOOT);
    Model::new(C::RockingHorse, fin, [len, 0.86, 0.3], 10.0, p)
}

/// A cat tree: carpeted platforms at three heights on sisal posts, a cube den at the bottom
/// and a bed on top.
fn cat_tree(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CARPET, rng);
    let c = fin.rgb;
    let h = r(rng, 1.3, 1.6);
    let sisal = [0.6, 0.5, 0.32];
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [0.6, 0.06, 0.55], c);
    bcube(&mut p, -0.14, 0.06, 0.1, [0.32, 0.32, 0.32], 0.02, c);
    front(
        &mut p,
        0.55,
        [-0.14, 0.12, 0.1 - 0.001],
        [0.16, 0.18, 0.01],
        tone::SOOT,
    );
    cyl(&mut p, 0.17, 0.06, 0.12, 0.05, h - 0.1, sisal);
    cyl(&mut p, -0.14, 0.38, 0.1, 0.05, h * 0.4, sisal);
    cube(&mut p, -0.1, 0.38 + h * 0.4, 0.05, [0.4, 0.04, 0.36], c);
    cube(&mut p, 0.14, h * 0.6, 0.05, [0.34, 0.04, 0.36], c);
    cyl(&mut p, 0.15, h - 0.04, 0.1, 0.2, 0.08, c);
    cyl(&mut p, 0.15, h + 0.04, 0.1, 0.16, 0.01, shade(c, 0.8));
    Model::new(C::CatTree, fin, [0.6, h + 0.05, 0.55], 12.0, p)
}

/// An upright vacuum cleaner: a wide floor head, the body with its dust bin and a tall handle.
fn vacuum_cleaner(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BRIGHT, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, -0.06, [0.32, 0.1, 0.24], 0.02, tone::SOOT);
    bcube(&mut p, 0.0, 0.08, 0.06, [0.24, 0.6, 0.2], 0.04, c);
    cyl(&mut p, 0.0, 0.25, -0.03, 0.07, 0.3, tone::GLASS);
    cube(&mut p, 0.0, 0.68, 0.08, [0.04, 0.4, 0.04], tone::SOOT);
    cube(&mut p, 0.0, 1.05, 0.08, [0.12, 0.04, 0.04], tone::SOOT);
    Model::new(C::VacuumCleaner, fin, [0.32, 1.09, 0.36], 6.0, p)
}

/// A push lawn mower: a painted deck on four wheels, the engine on top, a grass bag behind and
/// the handle rising back over it.
fn lawn_mower(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BRIGHT, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.07, -0.2, [0.5, 0.16, 0.55], 0.03, c);
    cyl(&mut p, 0.0, 0.23, -0.22, 0.12, 0.15, tone::METAL);
    let wheel = Quat::from_rotation_z(FRAC_PI_2);
    for sx in [-1.0, 1.0] {
        for z in [-0.42, 0.03] {
            let shape = Shape::Cylinder {
                radius: 0.1,
                half_height: 0.025,
            };
            turned(&mut p, shape, [sx * 0.27, 0.1, z], wheel, tone::SOOT);
        }
        let arm = Quat::from_rotation_x(-0.6);
        tilted(
            &mut p,
            [sx * 0.2, 0.55, 0.4],
            [0.012, 0.5, 0.012],
            arm,
            tone::SOOT,
        );
    }
    bcube(
        &mut p,
        0.0,
        0.1,
        0.22,
        [0.38, 0.3, 0.3],
        0.04,
        [0.15, 0.15, 0.16],
    );
    cube(&mut p, 0.0, 0.95, 0.68, [0.44, 0.03, 0.03], tone::SOOT);
    Model::new(C::LawnMower, fin, [0.6, 1.0, 1.25], 30.0, p)
}

/// A kayak hanging on the wall on two brackets: a long hull with pointed ends and an open
/// cockpit.
fn kayak(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(BRIGHT, rng);
    let c = fin.rgb;
    let len = r(rng, 2.5, 2.8);
    let y = 1.0;
    let mut p = Vec::new();
    // Two brackets out of the wall under the hull (nothing stands on the floor).
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * len * 0.25,
            y - 0.1,
            0.2,
            [0.05, 0.3, 0.04],
            tone::METAL,
        );
        cube(
            &mut p,
            s * len * 0.25,
            y - 0.04,
            0.0,
            [0.05, 0.04, 0.42],
            tone::METAL,
        );
    }
    let body = len - 0.6;
    bcube(&mut p, 0.0, y, 0.0, [body, 0.28, 0.42], 0.06, c);
    for s in [-1.0, 1.0] {
        // The bow and stern: a box turned 45 degrees on end, tapering the hull to a point,
        // and a thinner one beyond it.
        let tip = Quat::from_rotation_y(FRAC_PI_4);
        tilted(
            &mut p,
            [s * body * 0.5, y + 0.13, 0.0],
            [0.14, 0.12, 0.14],
            tip,
            c,
        );
        tilted(
            &mut p,
            [s * (body * 0.5 + 0.17), y + 0.14, 0.0],
            [0.07, 0.08, 0.07],
            tip,
            c,
        );
    }
    bcube(
        &mut p,
        0.0,
        y + 0.26,
        -0.01,
        [0.7, 0.04, 0.3],
        0.008,
        tone::SOOT,
    );
    Model::new(C::Kayak, fin, [len, y + 0.3, 0.44], 20.0, p)
}

/// A telescope on a tripod, its tube tilted up towards a window.
fn telescope(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(MACHINE, rng);
    let c = fin.rgb;
    let len = r(rng, 0.9, 1.1);
    let mut p = Vec::new();
    for k in 0..3 {
        let a = k as f32 * TAU / 3.0;
        let (sx, sz) = (a.sin(), a.cos());
        // A leg from the head (1.1 m up) out to the floor 0.35 m away.
        let rot = Quat::from_rotation_arc(
            glam::Vec3::Y,
            glam::Vec3::new(-sx * 0.3, 1.0, -sz * 0.3).normalize(),
        );
        tilted(
            &mut p,
            [sx * 0.17, 0.55, sz * 0.17],
            [0.015, 0.57, 0.015],
            rot,
            tone::METAL,
        );
    }
    cyl(&mut p, 0.0, 1.08, 0.0, 0.05, 0.08, tone::METAL);
    let tube = Quat::from_rotation_x(FRAC_PI_2 - 0.5);
    let shape = Shape::Cylinder {
        radius: 0.07,
        half_height: len * 0.5,
    };
    turned(&mut p, shape, [0.0, 1.25, -0.05], tube, c);
    Model::new(
        C::Telescope,
        fin,
        [0.75, 1.25 + len * 0.25 + 0.1, 0.75],
        6.0,
        p,
    )
}

/// A jukebox: a wide cabinet with a rounded top, a glass window onto the records, coloured
/// light strips and a speaker grille.
fn jukebox(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CABINET, rng);
    let c = fin.rgb;
    let (w, h, d) = (r(rng, 0.8, 0.9), 1.2, 0.6);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, h, d], 0.02, c);
    disc_z(&mut p, [0.0, h, 0.0], w * 0.5, d, c);
    front(
        &mut p,
        d,
        [0.0, h * 0.6, -0.005],
        [w * 0.6, 0.35, 0.01],
        tone::GLASS,
    );
    front(
        &mut p,
        d,
        [0.0, h * 0.12, -0.005],
        [w * 0.55, 0.3, 0.01],
        tone::SOOT,
    );
    for (k, glow) in [tone::FRUIT_ORANGE, tone::FRUIT_YELLOW, tone::FRUIT_RED]
        .into_iter()
        .enumerate()
    {
        let x = (k as f32 - 1.0) * w * 0.38;
        front(&mut p, d, [x, h * 0.1, -0.01], [0.04, h * 0.8, 0.012], glow);
    }
    Model::new(C::Jukebox, fin, [w, h + w * 0.5, d], 100.0, p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn every_class_builds_its_own_model_and_others_none() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for &class in vlnverse_env::SemanticClass::ALL
            .iter()
            .filter(|c| c.id() >= C::Doormat.id() && c.id() < C::Sectional.id())
        {
            for _ in 0..8 {
                let m = model(class, &mut rng).expect("a model");
                assert_eq!(m.class, class);
                assert!(m.w > 0.05 && m.d > 0.02 && m.h > 0.005, "{class:?}");
                assert!(
                    m.h < 2.3 && m.w < 3.1 && m.d < 3.1,
                    "{class:?} {} {} {}",
                    m.w,
                    m.h,
                    m.d
                );
            }
        }
        assert!(model(C::Sofa, &mut rng).is_none());
    }

    #[test]
    fn mats_are_flat_enough_to_walk_on() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..20 {
            assert!(doormat(&mut rng, 0.8).h < 0.02);
            assert!(runner(&mut rng, 4.0, 0.7).h < 0.02);
            assert!(doormat(&mut rng, 0.8).w <= 0.8 + 1e-4);
        }
    }
}
