//! Models of the classes the gym, the pantry, the home theater and the garage brought (issue
//! 26): a weight bench, a punching bag, a projector screen, a popcorn machine, a projector, a
//! jar, a wine rack, lockers, an arcade machine, a car, a workbench, a Christmas tree and a
//! wall sconce, a poster and a porch swing.
//!
//! Like every model (`models.rs`), each is built in its own frame with its front at -Z and its
//! back (the side that goes to the wall) at +Z, and draws its colour from a finish list of its
//! own, so that the colour word instructions use is the colour of its largest part.

use crate::models::{bcube, cube, cyl, disc_z, front, r, turned, Model};
use crate::palette::{f, shade, tone, Finish};
use glam::Quat;
use rand::seq::IndexedRandom;
use rand_chacha::ChaCha8Rng;
use std::f32::consts::FRAC_PI_2;
use vlnverse_env::{SemanticClass as C, Shape};

/// Gym padding and punching bags: the colours sports gear comes in.
const PADDING: &[Finish] = &[
    f("black", "leather", [0.04, 0.04, 0.04]),
    f("red", "leather", [0.5, 0.05, 0.05]),
    f("blue", "leather", [0.08, 0.16, 0.5]),
    f("grey", "fabric", [0.3, 0.3, 0.32]),
];
/// A projector screen's surface: matt white or light grey.
const SCREEN_CLOTH: &[Finish] = &[
    f("white", "fabric", [0.9, 0.9, 0.88]),
    f("white", "fabric", [0.86, 0.86, 0.86]),
    f("grey", "fabric", [0.62, 0.62, 0.64]),
];
/// Popcorn machines are fairground red, now and then black or silver.
const CART: &[Finish] = &[
    f("red", "metal", [0.6, 0.05, 0.04]),
    f("red", "metal", [0.6, 0.05, 0.04]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("silver", "metal", [0.6, 0.6, 0.62]),
];
const PROJECTOR: &[Finish] = &[
    f("white", "plastic", [0.88, 0.88, 0.88]),
    f("black", "plastic", [0.04, 0.04, 0.04]),
    f("grey", "plastic", [0.4, 0.4, 0.42]),
];
/// A jar's glass, named by what shows through it.
const JAR: &[Finish] = &[
    f("white", "glass", [0.8, 0.85, 0.85]),
    f("brown", "glass", [0.3, 0.15, 0.05]),
    f("green", "glass", [0.1, 0.4, 0.15]),
    f("orange", "glass", [0.75, 0.32, 0.08]),
    f("red", "glass", [0.55, 0.08, 0.06]),
];
/// Wood of wine racks and workbench tops.
const RACK_WOOD: &[Finish] = &[
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("black", "wood", [0.05, 0.05, 0.05]),
    f("white", "wood", [0.85, 0.85, 0.82]),
];
/// Painted steel of lockers.
const LOCKER: &[Finish] = &[
    f("grey", "metal", [0.4, 0.42, 0.44]),
    f("blue", "metal", [0.1, 0.22, 0.5]),
    f("red", "metal", [0.55, 0.07, 0.05]),
    f("green", "metal", [0.14, 0.36, 0.18]),
    f("white", "metal", [0.86, 0.86, 0.86]),
];
/// Arcade cabinets: black, or a loud colour.
const ARCADE: &[Finish] = &[
    f("black", "wood", [0.04, 0.04, 0.05]),
    f("red", "wood", [0.55, 0.05, 0.05]),
    f("blue", "wood", [0.08, 0.16, 0.5]),
    f("yellow", "wood", [0.85, 0.68, 0.08]),
];
/// Car paint.
const PAINT: &[Finish] = &[
    f("red", "metal", [0.55, 0.04, 0.03]),
    f("blue", "metal", [0.06, 0.16, 0.45]),
    f("silver", "metal", [0.6, 0.6, 0.62]),
    f("black", "metal", [0.04, 0.04, 0.04]),
    f("white", "metal", [0.88, 0.88, 0.88]),
    f("grey", "metal", [0.32, 0.33, 0.35]),
];
/// Wine bottles seen end on.
const BOTTLE_ENDS: [[f32; 3]; 3] = [[0.06, 0.2, 0.08], [0.25, 0.05, 0.06], [0.04, 0.1, 0.05]];
/// Tools hanging on a workbench's board.
const TOOLS: [[f32; 3]; 4] = [
    [0.6, 0.06, 0.04],
    [0.85, 0.6, 0.05],
    [0.1, 0.25, 0.6],
    [0.12, 0.12, 0.13],
];
/// Baubles on a Christmas tree.
const BAUBLES: [[f32; 3]; 3] = [[0.7, 0.05, 0.05], [0.8, 0.6, 0.12], [0.1, 0.2, 0.7]];
/// Fir green.
const FIR: &[Finish] = &[
    f("green", "plastic", [0.05, 0.28, 0.08]),
    f("green", "plastic", [0.08, 0.34, 0.12]),
];
/// Wall sconce shades.
const SHADE: &[Finish] = &[
    f("white", "fabric", [0.9, 0.88, 0.82]),
    f("gold", "metal", [0.75, 0.58, 0.2]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("beige", "fabric", [0.72, 0.62, 0.45]),
];
/// A poster's background colour, the one people name it by.
const PRINT: &[Finish] = &[
    f("black", "paper", [0.04, 0.04, 0.05]),
    f("white", "paper", [0.88, 0.88, 0.85]),
    f("red", "paper", [0.55, 0.07, 0.07]),
    f("blue", "paper", [0.08, 0.18, 0.5]),
    f("yellow", "paper", [0.85, 0.7, 0.12]),
];
/// Popcorn behind the machine's glass.
const POPCORN: [f32; 3] = [0.92, 0.82, 0.45];

/// Draw a finish from `list`, in one of its colour word's tones or its own.
fn pick(list: &[Finish], rng: &mut ChaCha8Rng) -> Finish {
    let fin = *list.choose(rng).unwrap_or(&list[0]);
    crate::tones::toned(fin, rng)
}

/// The model of one of this module's classes; `None` for any other class.
pub(crate) fn model(class: C, rng: &mut ChaCha8Rng) -> Option<Model> {
    Some(match class {
        C::WeightBench => weight_bench(rng),
        C::PunchingBag => punching_bag(rng),
        C::ProjectorScreen => projector_screen(rng),
        C::PopcornMachine => popcorn_machine(rng),
        C::Projector => projector(rng),
        C::Jar => jar(rng),
        C::WineRack => wine_rack(rng),
        C::Lockers => lockers(rng),
        C::ArcadeMachine => arcade_machine(rng),
        C::Car => car(rng),
        C::Workbench => workbench(rng),
        C::ChristmasTree => christmas_tree(rng),
        C::WallSconce => wall_sconce(rng),
        C::Poster => poster(rng),
        C::PorchSwing => porch_swing(rng),
        _ => return None,
    })
}

/// A padded bench on a steel frame, its head at the back under a rack with a loaded barbell.
fn weight_bench(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PADDING, rng);
    let c = fin.rgb;
    let len = r(rng, 1.15, 1.3);
    let bar = r(rng, 1.5, 1.7);
    let mut p = Vec::new();
    // Frame: a foot at each end and a spine under the pad.
    cube(
        &mut p,
        0.0,
        0.0,
        -len * 0.5 + 0.05,
        [0.5, 0.05, 0.08],
        tone::METAL,
    );
    cube(
        &mut p,
        0.0,
        0.0,
        len * 0.5 - 0.05,
        [0.6, 0.05, 0.08],
        tone::METAL,
    );
    cube(&mut p, 0.0, 0.05, 0.0, [0.06, 0.32, len - 0.1], tone::METAL);
    bcube(&mut p, 0.0, 0.37, -0.05, [0.3, 0.08, len - 0.15], 0.015, c);
    // Two uprights with hooks at the head, and the bar across them.
    let z = len * 0.5 - 0.1;
    for sx in [-1.0, 1.0] {
        cube(&mut p, sx * 0.27, 0.05, z, [0.05, 1.0, 0.05], tone::METAL);
    }
    let rod = Quat::from_rotation_z(FRAC_PI_2);
    turned(
        &mut p,
        Shape::Cylinder {
            radius: 0.015,
            half_height: bar * 0.5,
        },
        [0.0, 1.0, z - 0.05],
        rod,
        tone::STEEL,
    );
    for sx in [-1.0, 1.0] {
        turned(
            &mut p,
            Shape::Cylinder {
                radius: 0.2,
                half_height: 0.03,
            },
            [sx * (bar * 0.5 - 0.12), 1.0, z - 0.05],
            rod,
            tone::SOOT,
        );
    }
    Model::new(C::WeightBench, fin, [bar, 1.2, len], 60.0, p)
}

/// A standing punching bag: a weighted round base and the bag on a short post.
fn punching_bag(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PADDING, rng);
    let c = fin.rgb;
    let h = r(rng, 1.45, 1.7);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.3, 0.22, tone::SOOT);
    cyl(&mut p, 0.0, 0.22, 0.0, 0.05, 0.2, tone::METAL);
    cyl(&mut p, 0.0, 0.42, 0.0, 0.18, h - 0.46, c);
    cyl(&mut p, 0.0, h - 0.04, 0.0, 0.15, 0.04, shade(c, 0.7));
    Model::new(C::PunchingBag, fin, [0.6, h, 0.6], 35.0, p)
}

/// A wide screen on the wall: a black frame round a matt surface, its roller case on top. It
/// hangs from the wall above a low piece of furniture, so its bottom edge is 0.6 to 0.8 m up.
fn projector_screen(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(SCREEN_CLOTH, rng);
    let (w, h) = (r(rng, 1.8, 2.6), r(rng, 1.05, 1.35));
    let y = r(rng, 0.6, 0.8);
    let mut p = Vec::new();
    // A thin black backing shows as a border round the surface (the surface is the largest
    // part, so its colour is the one instructions name).
    cube(&mut p, 0.0, y, 0.03, [w + 0.08, h + 0.08, 0.01], tone::SOOT);
    cube(&mut p, 0.0, y + 0.04, 0.0, [w, h, 0.05], fin.rgb);
    cube(
        &mut p,
        0.0,
        y + h + 0.08,
        0.0,
        [w + 0.2, 0.09, 0.07],
        tone::METAL,
    );
    Model::new(
        C::ProjectorScreen,
        fin,
        [w + 0.2, y + h + 0.17, 0.09],
        12.0,
        p,
    )
}

/// A popcorn cart: a cabinet on four wheels, a glass case full of popcorn and a roof.
fn popcorn_machine(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(CART, rng);
    let c = fin.rgb;
    let (w, d) = (r(rng, 0.5, 0.6), r(rng, 0.45, 0.5));
    let mut p = Vec::new();
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            cyl(
                &mut p,
                sx * (w * 0.5 - 0.06),
                0.0,
                sz * (d * 0.5 - 0.06),
                0.05,
                0.1,
                tone::SOOT,
            );
        }
    }
    bcube(&mut p, 0.0, 0.1, 0.0, [w, 0.7, d], 0.015, c);
    front(
        &mut p,
        d,
        [0.0, 0.3, -0.004],
        [w * 0.6, 0.3, 0.008],
        shade(c, 0.75),
    );
    // The glass case: corner posts, popcorn heaped in it, and a roof.
    let case = 0.5;
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            cube(
                &mut p,
                sx * (w * 0.5 - 0.02),
                0.8,
                sz * (d * 0.5 - 0.02),
                [0.03, case, 0.03],
                c,
            );
        }
    }
    cube(&mut p, 0.0, 0.8, 0.0, [w - 0.04, 0.22, d - 0.04], POPCORN);
    cube(
        &mut p,
        0.0,
        1.02,
        0.0,
        [w - 0.04, case - 0.22, d - 0.04],
        tone::GLASS,
    );
    bcube(
        &mut p,
        0.0,
        0.8 + case,
        0.0,
        [w + 0.04, 0.1, d + 0.04],
        0.02,
        c,
    );
    Model::new(C::PopcornMachine, fin, [w + 0.04, 1.4, d + 0.04], 30.0, p)
}

/// A box projector with its round lens at the front.
fn projector(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PROJECTOR, rng);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [0.3, 0.1, 0.24], 0.01, fin.rgb);
    disc_z(&mut p, [0.08, 0.05, -0.125], 0.035, 0.02, tone::SCREEN);
    Model::new(C::Projector, fin, [0.3, 0.1, 0.26], 3.0, p)
}

/// A glass storage jar with a lid.
fn jar(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(JAR, rng);
    let (rad, h) = (r(rng, 0.045, 0.07), r(rng, 0.12, 0.22));
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, rad, h, fin.rgb);
    cyl(&mut p, 0.0, h, 0.0, rad * 0.85, 0.03, tone::METAL);
    Model::new(C::Jar, fin, [rad * 2.0, h + 0.03, rad * 2.0], 0.5, p)
}

/// A wooden rack of square cells, most holding a bottle seen end on.
fn wine_rack(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(RACK_WOOD, rng);
    let c = fin.rgb;
    let (cols, rows) = (if r(rng, 0.0, 1.0) < 0.5 { 4 } else { 5 }, 4);
    let cell = 0.16;
    let (w, h, d) = (cols as f32 * cell + 0.04, rows as f32 * cell + 0.14, 0.32);
    let mut p = Vec::new();
    // Back panel and frame: the largest part is the wood the rack is named by.
    cube(&mut p, 0.0, 0.0, d * 0.5 - 0.02, [w, h, 0.04], c);
    for sx in [-1.0, 1.0] {
        cube(&mut p, sx * (w - 0.02) * 0.5, 0.0, 0.0, [0.02, h, d], c);
    }
    for k in 0..=rows {
        let y = 0.1 + k as f32 * cell;
        cube(&mut p, 0.0, y - 0.02, 0.0, [w, 0.02, d], c);
    }
    for row in 0..rows {
        for col in 0..cols {
            if (row * 7 + col * 3) % 5 == 4 {
                continue;
            }
            let x = -w * 0.5 + 0.02 + (col as f32 + 0.5) * cell;
            let y = 0.1 + row as f32 * cell + 0.03;
            let glass = BOTTLE_ENDS[(row + col) % BOTTLE_ENDS.len()];
            cube(&mut p, x, y, -0.02, [0.08, 0.08, d - 0.1], glass);
        }
    }
    Model::new(C::WineRack, fin, [w, h, d], 15.0, p)
}

/// A bank of two or three tall steel lockers, each door with vent slits and a handle.
fn lockers(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(LOCKER, rng);
    let c = fin.rgb;
    let n = if r(rng, 0.0, 1.0) < 0.5 { 3 } else { 2 };
    let (lw, h, d) = (0.38, r(rng, 1.7, 1.85), 0.45);
    let w = n as f32 * lw;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, h, d], 0.01, c);
    let dark = shade(c, 0.6);
    for k in 0..n {
        let x = -w * 0.5 + (k as f32 + 0.5) * lw;
        if k + 1 < n {
            // The seam between this door and the next.
            let seam = [x + lw * 0.5, 0.08, -0.003];
            front(&mut p, d, seam, [0.012, h - 0.12, 0.006], dark);
        }
        for v in 0..3 {
            let y = h - 0.25 + v as f32 * 0.05;
            front(&mut p, d, [x, y, -0.004], [lw * 0.5, 0.015, 0.008], dark);
        }
        front(
            &mut p,
            d,
            [x + lw * 0.3, h * 0.5, -0.012],
            [0.03, 0.1, 0.02],
            tone::STEEL,
        );
    }
    Model::new(C::Lockers, fin, [w, h, d], 40.0, p)
}

/// An upright arcade cabinet: a screen tilted back in the top, a control panel with a stick
/// and buttons, a lit marquee.
fn arcade_machine(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(ARCADE, rng);
    let c = fin.rgb;
    let (w, h, d) = (r(rng, 0.6, 0.7), r(rng, 1.7, 1.85), 0.75);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.1, [w, h, d - 0.2], 0.015, c);
    // Control panel sticking out at the front.
    bcube(&mut p, 0.0, 0.85, -0.3, [w, 0.12, 0.2], 0.01, shade(c, 0.8));
    cyl(&mut p, -0.12, 0.97, -0.3, 0.015, 0.08, tone::SOOT);
    for (k, col) in [tone::FRUIT_RED, tone::FRUIT_YELLOW, [0.1, 0.3, 0.8]]
        .into_iter()
        .enumerate()
    {
        cyl(&mut p, 0.02 + k as f32 * 0.07, 0.97, -0.3, 0.02, 0.015, col);
    }
    // Screen and marquee on the body's front face.
    let face = 0.1 - (d - 0.2) * 0.5 - 0.006;
    cube(
        &mut p,
        0.0,
        1.03,
        face,
        [w * 0.8, 0.45, 0.012],
        tone::SCREEN,
    );
    cube(
        &mut p,
        0.0,
        h - 0.2,
        face,
        [w * 0.85, 0.14, 0.012],
        tone::FRUIT_YELLOW,
    );
    Model::new(C::ArcadeMachine, fin, [w, h, d], 90.0, p)
}

/// A car seen as people draw one: a body on four wheels, a cabin with dark windows, lights
/// at both ends. Its front faces -Z.
fn car(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PAINT, rng);
    let c = fin.rgb;
    let (w, len) = (r(rng, 1.7, 1.85), r(rng, 3.9, 4.5));
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.25, 0.0, [w, 0.6, len], 0.08, c);
    let cabin = len * 0.5;
    bcube(
        &mut p,
        0.0,
        0.85,
        0.1,
        [w - 0.16, 0.55, cabin],
        0.08,
        shade(c, 0.95),
    );
    // Windows: a band along both sides, the windscreen and the rear window.
    cube(
        &mut p,
        0.0,
        0.9,
        0.1,
        [w - 0.12, 0.4, cabin - 0.3],
        tone::SCREEN,
    );
    cube(
        &mut p,
        0.0,
        0.9,
        0.1,
        [w - 0.3, 0.4, cabin + 0.02],
        tone::SCREEN,
    );
    let wheel = Quat::from_rotation_z(FRAC_PI_2);
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            turned(
                &mut p,
                Shape::Cylinder {
                    radius: 0.31,
                    half_height: 0.1,
                },
                [sx * (w * 0.5 - 0.08), 0.31, sz * (len * 0.5 - 0.75)],
                wheel,
                tone::SOOT,
            );
        }
        front(
            &mut p,
            len,
            [sx * (w * 0.5 - 0.25), 0.6, -0.005],
            [0.3, 0.1, 0.01],
            tone::WHITE,
        );
        cube(
            &mut p,
            sx * (w * 0.5 - 0.25),
            0.6,
            len * 0.5 - 0.005,
            [0.3, 0.1, 0.01],
            tone::FRUIT_RED,
        );
    }
    Model::new(C::Car, fin, [w, 1.4, len], 1300.0, p)
}

/// A workbench: a thick wooden top on steel legs with a shelf below, and a board of tools on
/// the wall behind it.
fn workbench(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(RACK_WOOD, rng);
    let c = fin.rgb;
    let (w, d) = (r(rng, 1.4, 2.0), r(rng, 0.6, 0.75));
    let h = 0.9;
    let mut p = Vec::new();
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            cube(
                &mut p,
                sx * (w * 0.5 - 0.05),
                0.0,
                sz * (d * 0.5 - 0.05),
                [0.05, h - 0.06, 0.05],
                tone::METAL,
            );
        }
    }
    bcube(&mut p, 0.0, h - 0.06, 0.0, [w, 0.06, d], 0.01, c);
    cube(
        &mut p,
        0.0,
        0.15,
        0.0,
        [w - 0.1, 0.03, d - 0.1],
        shade(c, 0.8),
    );
    // The tool board, standing on the back edge of the top.
    let board = [w - 0.1, 0.7, 0.02];
    cube(&mut p, 0.0, h, d * 0.5 - 0.02, board, tone::LINEN);
    for (k, col) in TOOLS.into_iter().enumerate() {
        let x = -w * 0.35 + k as f32 * w * 0.22;
        cube(&mut p, x, h + 0.3, d * 0.5 - 0.045, [0.06, 0.3, 0.03], col);
    }
    Model::new(C::Workbench, fin, [w, h + 0.8, d], 45.0, p)
}

/// A Christmas tree: four green tiers narrowing to the top on a red skirt, coloured baubles
/// and a gold star.
fn christmas_tree(rng: &mut ChaCha8Rng) -> Model {
    // Fir green as it is: no tone (an olive or mint tree reads as another thing).
    let fin = *FIR.choose(rng).unwrap_or(&FIR[0]);
    let h = r(rng, 1.6, 2.0);
    let rad = r(rng, 0.5, 0.6);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, rad * 0.7, 0.08, [0.6, 0.05, 0.05]);
    cyl(&mut p, 0.0, 0.08, 0.0, 0.05, 0.2, tone::WOOD);
    let tier = (h - 0.4) / 4.0;
    for k in 0..4 {
        let t = k as f32;
        let rk = rad * (1.0 - t * 0.22);
        let y = 0.25 + t * tier * 0.9;
        cyl(&mut p, 0.0, y, 0.0, rk, tier * 1.1, fin.rgb);
        // Two baubles on each tier's rim, turned a quarter further each tier.
        for side in [-1.0f32, 1.0] {
            let a = t * 0.8 + if side > 0.0 { 0.0 } else { 3.1 };
            let c = [a.sin() * rk, y + tier * 0.3, -a.cos() * rk];
            crate::models::ball(&mut p, c, 0.045, BAUBLES[k % BAUBLES.len()]);
        }
    }
    let top = 0.25 + 3.0 * tier * 0.9 + tier * 1.1;
    crate::models::ball(&mut p, [0.0, top + 0.06, 0.0], 0.07, [0.9, 0.72, 0.15]);
    Model::new(
        C::ChristmasTree,
        fin,
        [rad * 2.0, top + 0.13, rad * 2.0],
        15.0,
        p,
    )
}

/// A wall light at about head height: a back plate, a short arm and a shade. Only the
/// hanging parts are up there; its footprint is a strip along the wall.
fn wall_sconce(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(SHADE, rng);
    let y = r(rng, 1.65, 1.8);
    let mut p = Vec::new();
    cube(&mut p, 0.0, y, 0.07, [0.1, 0.18, 0.02], tone::METAL);
    cube(&mut p, 0.0, y + 0.07, 0.02, [0.02, 0.02, 0.08], tone::METAL);
    cyl(&mut p, 0.0, y + 0.02, -0.04, 0.08, 0.16, fin.rgb);
    Model::new(C::WallSconce, fin, [0.16, y + 0.18, 0.16], 1.5, p)
}

/// A framed poster on the wall: a thin frame, the print and two blocks of colour on it (a
/// title and a picture). Its footprint is a strip along the wall.
fn poster(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(PRINT, rng);
    let (w, h) = (r(rng, 0.5, 0.7), r(rng, 0.7, 1.0));
    let y = r(rng, 1.0, 1.15);
    let mut p = Vec::new();
    // A box frame round a print mounted on a board (the largest part: its colour names it).
    let frame = [w + 0.03, h + 0.03, 0.04];
    cube(&mut p, 0.0, y, 0.01, frame, tone::SOOT);
    cube(&mut p, 0.0, y + 0.015, 0.0, [w, h, 0.05], fin.rgb);
    let ink = if fin.color == "yellow" || fin.color == "white" {
        [BOTTLE_ENDS[1], tone::SOOT]
    } else {
        [tone::FRUIT_YELLOW, tone::WHITE]
    };
    let (title, picture) = ([w * 0.7, h * 0.12, 0.003], [w * 0.6, h * 0.4, 0.003]);
    cube(&mut p, 0.0, y + h * 0.72, -0.026, title, ink[0]);
    cube(&mut p, 0.0, y + h * 0.2, -0.026, picture, ink[1]);
    Model::new(C::Poster, fin, [w + 0.03, y + h + 0.03, 0.058], 0.5, p)
}

/// A porch swing: a slatted bench seat with a back, hanging on two chains from the beam of a
/// frame that stands on A-shaped legs at both ends.
fn porch_swing(rng: &mut ChaCha8Rng) -> Model {
    let fin = pick(RACK_WOOD, rng);
    let c = fin.rgb;
    let (w, d, h) = (r(rng, 1.7, 2.0), 1.1, r(rng, 1.9, 2.05));
    let mut p = Vec::new();
    for sx in [-1.0, 1.0] {
        let x = sx * (w * 0.5 - 0.04);
        // Each end: two legs leaning in to meet under the beam.
        for sz in [-1.0, 1.0] {
            turned(
                &mut p,
                Shape::Cuboid {
                    half_extents: [0.035, h * 0.5, 0.035],
                    bevel: 0.0,
                },
                [x, h * 0.5, sz * d * 0.2],
                Quat::from_rotation_x(-sz * 0.23),
                c,
            );
        }
    }
    cube(&mut p, 0.0, h - 0.08, 0.0, [w, 0.08, 0.08], c);
    let seat = w - 0.45;
    for sx in [-1.0, 1.0] {
        cube(
            &mut p,
            sx * seat * 0.45,
            0.5,
            0.0,
            [0.015, h - 0.58, 0.015],
            tone::METAL,
        );
    }
    bcube(&mut p, 0.0, 0.42, 0.0, [seat, 0.08, 0.5], 0.01, c);
    cube(&mut p, 0.0, 0.5, 0.22, [seat, 0.45, 0.05], c);
    Model::new(C::PorchSwing, fin, [w, h, d], 30.0, p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn every_class_builds_its_own_model_and_others_none() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for class in [
            C::WeightBench,
            C::PunchingBag,
            C::ProjectorScreen,
            C::PopcornMachine,
            C::Projector,
            C::Jar,
            C::WineRack,
            C::Lockers,
            C::ArcadeMachine,
            C::Car,
            C::Workbench,
            C::ChristmasTree,
            C::WallSconce,
            C::Poster,
            C::PorchSwing,
        ] {
            let m = model(class, &mut rng).expect("a model");
            assert_eq!(m.class, class);
            assert!(m.w > 0.05 && m.d > 0.05 && m.h > 0.05, "{class:?}");
            assert!(
                m.h < 2.3 && m.w < 2.9 && m.d < 4.8,
                "{class:?} {} {} {}",
                m.w,
                m.h,
                m.d
            );
        }
        assert!(model(C::Sofa, &mut rng).is_none());
    }
}
