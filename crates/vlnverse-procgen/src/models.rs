//! Primitive-built object models. Each model is built in its own frame: origin at the centre of
//! its footprint on the floor, width along x, depth along z, height along +y, its front facing
//! -Z (so a sofa's back, a bed's headboard or a wardrobe's back is at +Z and goes to the wall).
//! Cuboids are preferred (12 triangles each); cylinders and spheres only where the shape needs
//! them.

use crate::palette::{self, shade, tone, Finish};
use crate::rect::Rect;
use glam::{Quat, Vec3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{Part, Pose, SemanticClass as C, Shape};

/// An object model in its own frame.
#[derive(Clone, Debug)]
pub(crate) struct Model {
    pub class: C,
    pub parts: Vec<Part>,
    /// Footprint width (x), height (y), depth (z).
    pub w: f32,
    pub h: f32,
    pub d: f32,
    /// Flat top at height `h` where small objects may stand (rectangle in the model frame).
    pub top: Option<Rect>,
    pub finish: Finish,
    pub mass: f32,
    /// What tells this model from the other variants of its class ("footboard", "two
    /// drawers"), recorded on the object for language (`data/features` keys of
    /// vlnverse-instructions).
    pub features: Vec<&'static str>,
}

impl Model {
    /// Model from parts; the footprint and height are measured from the parts (`size` is only
    /// the nominal size) so that placement is exact even where handles stick out.
    pub(crate) fn new(
        class: C,
        finish: Finish,
        size: [f32; 3],
        mass: f32,
        parts: Vec<Part>,
    ) -> Model {
        let mut m = Model {
            class,
            parts,
            w: size[0],
            h: size[1],
            d: size[2],
            top: None,
            finish,
            mass,
            features: Vec::new(),
        };
        recentre(&mut m);
        m
    }

    /// The model with `features` recorded.
    pub(crate) fn with_features(mut self, features: &[&'static str]) -> Model {
        self.features = features.to_vec();
        self
    }

    /// Mark the whole top (inset by `m`) as a support surface.
    pub(crate) fn with_top(mut self, m: f32) -> Model {
        self.top = Some(Rect::centered(0.0, 0.0, self.w, self.d).inset(m));
        self
    }
}

/// Box with its bottom centre at `(x, y0, z)`.
pub(crate) fn cube(p: &mut Vec<Part>, x: f32, y0: f32, z: f32, size: [f32; 3], rgb: [f32; 3]) {
    bcube(p, x, y0, z, size, 0.0, rgb);
}

/// Box with its bottom centre at `(x, y0, z)` and its edges chamfered by `bevel` metres (only
/// the drawn mesh: physics and occupancy keep the full box).
pub(crate) fn bcube(
    p: &mut Vec<Part>,
    x: f32,
    y0: f32,
    z: f32,
    size: [f32; 3],
    bevel: f32,
    rgb: [f32; 3],
) {
    p.push(Part {
        shape: Shape::Cuboid {
            half_extents: [size[0] * 0.5, size[1] * 0.5, size[2] * 0.5],
            bevel,
        },
        transform: Pose {
            position: [x, y0 + size[1] * 0.5, z],
            rotation: [0.0, 0.0, 0.0, 1.0],
        },
        color: rgb,
    });
}

/// Thin panel on the front face (z = -d/2) of a body of depth `d`: door, drawer front, handle.
/// `at` is (x, bottom y, z offset from the front face).
pub(crate) fn front(p: &mut Vec<Part>, d: f32, at: [f32; 3], size: [f32; 3], rgb: [f32; 3]) {
    cube(p, at[0], at[1], -d * 0.5 + at[2], size, rgb);
}

/// Upright cylinder with its bottom centre at `(x, y0, z)`.
pub(crate) fn cyl(p: &mut Vec<Part>, x: f32, y0: f32, z: f32, r: f32, h: f32, rgb: [f32; 3]) {
    p.push(Part {
        shape: Shape::Cylinder {
            radius: r,
            half_height: h * 0.5,
        },
        transform: Pose {
            position: [x, y0 + h * 0.5, z],
            rotation: [0.0, 0.0, 0.0, 1.0],
        },
        color: rgb,
    });
}

/// Cylinder lying along z (a disc facing the front when short), centred at `c`.
pub(crate) fn disc_z(p: &mut Vec<Part>, c: [f32; 3], r: f32, len: f32, rgb: [f32; 3]) {
    p.push(Part {
        shape: Shape::Cylinder {
            radius: r,
            half_height: len * 0.5,
        },
        transform: Pose {
            position: c,
            rotation: Quat::from_rotation_x(std::f32::consts::FRAC_PI_2).to_array(),
        },
        color: rgb,
    });
}

/// Sphere centred at `c`.
pub(crate) fn ball(p: &mut Vec<Part>, c: [f32; 3], r: f32, rgb: [f32; 3]) {
    p.push(Part {
        shape: Shape::Sphere { radius: r },
        transform: Pose {
            position: c,
            rotation: [0.0, 0.0, 0.0, 1.0],
        },
        color: rgb,
    });
}

/// Four square legs at the corners of a `w` x `d` footprint.
pub(crate) fn legs(p: &mut Vec<Part>, w: f32, d: f32, h: f32, s: f32, rgb: [f32; 3]) {
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            cube(
                p,
                sx * (w - s) * 0.5,
                0.0,
                sz * (d - s) * 0.5,
                [s, h, s],
                rgb,
            );
        }
    }
}

/// A shape centred at `c`, turned by `rot`.
pub(crate) fn turned(p: &mut Vec<Part>, shape: Shape, c: [f32; 3], rot: Quat, rgb: [f32; 3]) {
    p.push(Part {
        shape,
        transform: Pose {
            position: c,
            rotation: rot.to_array(),
        },
        color: rgb,
    });
}

#[cfg(test)]
thread_local! {
    /// Tests force one variant of every model built on this thread.
    static FORCE_VARIANT: std::cell::Cell<Option<usize>> = const { std::cell::Cell::new(None) };
}

/// Which of `n` variants of a model to build, hashed from values the model already drew from
/// the rng. Drawing the choice instead would shift every later draw and so change the layout,
/// episodes and instructions of every home.
fn variant(n: usize, drawn: &[f32]) -> usize {
    #[cfg(test)]
    if let Some(v) = FORCE_VARIANT.with(|f| f.get()) {
        return v % n;
    }
    let mut z: u64 = 0x243F_6A88_85A3_08D3;
    for v in drawn {
        z = (z ^ u64::from(v.to_bits())).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        z ^= z >> 29;
    }
    (z % n as u64) as usize
}

pub(crate) fn r(rng: &mut ChaCha8Rng, lo: f32, hi: f32) -> f32 {
    rng.random_range(lo..=hi)
}

/// A double (or single) bed: frame, mattress, blanket, pillows, headboard. Variants: a panel
/// or a slatted headboard (posts, rails, slats), with or without a footboard; and its bedding
/// as it is ([`BedDressing`]).
pub(crate) fn bed(rng: &mut ChaCha8Rng, double: bool) -> Model {
    let fin = palette::pick(C::Bed, rng);
    let w = if double {
        r(rng, 1.45, 1.8)
    } else {
        r(rng, 0.95, 1.1)
    };
    let d = r(rng, 2.0, 2.15);
    let head_h = r(rng, 0.9, 1.15);
    let bedding = palette::fabric(rng);
    // Four headboards times four beddings: `v % 4` picks the headboard as it always did.
    let v = variant(16, &[w, d, head_h]);
    let dressing = BedDressing::of(v / 4);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, -0.04, [w, 0.3, d - 0.08], 0.02, fin.rgb);
    bcube(
        &mut p,
        0.0,
        0.3,
        -0.05,
        [w - 0.06, 0.2, d - 0.16],
        0.04,
        tone::LINEN,
    );
    if dressing == BedDressing::Quilt {
        quilt(&mut p, w - 0.04, d * 0.6, -0.3, bedding);
    } else {
        cube(&mut p, 0.0, 0.5, -0.3, [w - 0.04, 0.03, d * 0.6], bedding);
    }
    match dressing {
        BedDressing::FoldedBlanket => {
            // Folded across the foot, over the blanket: a thick band in another shade.
            let z = -d * 0.5 + 0.25;
            bcube(
                &mut p,
                0.0,
                0.53,
                z,
                [w - 0.03, 0.07, 0.38],
                0.012,
                contrast(bedding),
            );
        }
        BedDressing::ThrowPillows => {
            // Two small cushions in the blanket's colour (a darker shade of a pale one),
            // leaning on the white pillows.
            let cw = (w * 0.3).min(0.36);
            for s in [-1.0, 1.0] {
                let x = s * (w * 0.18).min(0.3);
                let c = d * 0.5 - 0.58;
                let rgb = if bedding.iter().sum::<f32>() > 1.35 {
                    contrast(bedding)
                } else {
                    bedding
                };
                bcube(&mut p, x, 0.5, c, [cw, 0.28, 0.1], 0.02, rgb);
            }
        }
        _ => {}
    }
    let pillows = if double { 2 } else { 1 };
    for i in 0..pillows {
        let x = if pillows == 1 {
            0.0
        } else {
            (i as f32 - 0.5) * w * 0.48
        };
        bcube(
            &mut p,
            x,
            0.5,
            d * 0.5 - 0.34,
            [0.5, 0.12, 0.34],
            0.0,
            tone::WHITE,
        );
    }
    let head_rgb = shade(fin.rgb, 0.85);
    // Every headboard keeps the panel's depth, height and footprint (a full-width rail), so the
    // bed's box and its occupancy stay those of the panel bed. Only parts with the panel's x
    // and z may touch its faces: once the bed is turned, a box face is rounded from the x and
    // z of the part that makes it, so other parts stay 0.5 mm inside.
    let hz = d * 0.5 - 0.04;
    if v & 1 == 0 {
        bcube(&mut p, 0.0, 0.0, hz, [w, head_h, 0.08], 0.015, head_rgb);
    } else {
        for s in [-1.0, 1.0] {
            bcube(
                &mut p,
                s * (w * 0.5 - 0.05),
                0.0,
                hz,
                [0.08, head_h, 0.079],
                0.015,
                head_rgb,
            );
        }
        cube(&mut p, 0.0, 0.01, hz, [w, 0.49, 0.08], head_rgb);
        bcube(
            &mut p,
            0.0,
            head_h - 0.12,
            hz,
            [w - 0.1, 0.09, 0.079],
            0.015,
            head_rgb,
        );
        let span = w - 0.18;
        let n = ((span / 0.14) as usize).max(2);
        for i in 0..n {
            let x = -span * 0.5 + span * (i as f32 + 0.5) / n as f32;
            cube(&mut p, x, 0.5, hz, [0.04, head_h - 0.62, 0.03], head_rgb);
        }
    }
    if v & 2 != 0 {
        // A footboard just in front of the mattress, inside the frame's footprint.
        cube(
            &mut p,
            0.0,
            0.01,
            -d * 0.5 + 0.016,
            [w - 0.02, 0.6, 0.028],
            head_rgb,
        );
    }
    let head = if v & 1 == 0 {
        "panel headboard"
    } else {
        "slatted headboard"
    };
    let mut features = vec![head];
    if v & 2 != 0 {
        features.push("footboard");
    }
    features.extend(dressing.feature());
    Model::new(C::Bed, fin, [w, head_h, d], 60.0 + 20.0 * w, p).with_features(&features)
}

/// A colour that stands out against `rgb`: a dark shade of a light colour, a pale one of a
/// dark colour (a black blanket has no darker shade).
fn contrast(rgb: [f32; 3]) -> [f32; 3] {
    if rgb.iter().sum::<f32>() > 1.35 {
        shade(rgb, 0.5)
    } else {
        rgb.map(|c| c + (tone::LINEN[0] - c) * 0.55)
    }
}

/// What lies on a bed besides its blanket and pillows.
#[derive(Clone, Copy, PartialEq, Eq)]
enum BedDressing {
    Plain,
    /// A blanket folded across the foot.
    FoldedBlanket,
    /// Two small cushions before the pillows.
    ThrowPillows,
    /// The blanket as a quilt of squares in two shades.
    Quilt,
}

impl BedDressing {
    fn of(k: usize) -> BedDressing {
        match k {
            1 => BedDressing::FoldedBlanket,
            2 => BedDressing::ThrowPillows,
            3 => BedDressing::Quilt,
            _ => BedDressing::Plain,
        }
    }

    fn feature(self) -> Option<&'static str> {
        match self {
            BedDressing::Plain => None,
            BedDressing::FoldedBlanket => Some("folded blanket"),
            BedDressing::ThrowPillows => Some("throw pillows"),
            BedDressing::Quilt => Some("quilt"),
        }
    }
}

/// A quilt of `w` x `d` centred at `z` on a mattress: squares of about 35 cm in `rgb` and its
/// [`contrast`], like a chessboard.
fn quilt(p: &mut Vec<Part>, w: f32, d: f32, z: f32, rgb: [f32; 3]) {
    let (nx, nz) = (
        ((w / 0.35).round() as usize).max(2),
        ((d / 0.35).round() as usize).max(2),
    );
    let (sw, sd) = (w / nx as f32, d / nz as f32);
    for i in 0..nx {
        for j in 0..nz {
            let c = if (i + j) % 2 == 0 { rgb } else { contrast(rgb) };
            let x = -w * 0.5 + sw * (i as f32 + 0.5);
            let zz = z - d * 0.5 + sd * (j as f32 + 0.5);
            cube(p, x, 0.5, zz, [sw, 0.03, sd], c);
        }
    }
}

/// A nightstand: body, drawer fronts with handles; small objects on top. Variants: one
/// drawer, two drawers, a drawer over an open niche.
pub(crate) fn nightstand(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Nightstand, rng);
    let (w, h, d) = (r(rng, 0.4, 0.5), r(rng, 0.5, 0.6), r(rng, 0.35, 0.42));
    let v = variant(3, &[w, h, d]);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, h, d], 0.012, fin.rgb);
    // Fronts and handles keep their x extent and depth in every variant (they stick out of
    // the body, so they are part of the footprint); only their heights change.
    let drawer = |p: &mut Vec<Part>, y: f32| {
        front(
            p,
            d,
            [0.0, y, -0.005],
            [w - 0.06, h * 0.3, 0.01],
            shade(fin.rgb, 0.8),
        );
        front(
            p,
            d,
            [0.0, y + h * 0.13, -0.02],
            [0.08, 0.02, 0.02],
            tone::METAL,
        );
    };
    drawer(&mut p, h * 0.55);
    match v {
        1 => drawer(&mut p, h * 0.2),
        2 => front(
            &mut p,
            d,
            [0.0, h * 0.1, -0.005],
            [w - 0.06, h * 0.38, 0.01],
            shade(fin.rgb, 0.35),
        ),
        _ => {}
    }
    let features = match v {
        1 => "two drawers",
        2 => "open shelf",
        _ => "one drawer",
    };
    Model::new(C::Nightstand, fin, [w, h, d + 0.02], 12.0, p)
        .with_top(0.04)
        .with_features(&[features])
}

/// A wardrobe: body, doors, handles. Variants: two doors; two doors over a row of drawers;
/// three doors with a mirror in the middle; two doors under a row of top cupboards.
pub(crate) fn wardrobe(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Wardrobe, rng);
    let (w, h, d) = (r(rng, 0.9, 1.6), r(rng, 1.9, 2.2), r(rng, 0.55, 0.62));
    let v = variant(4, &[w, h, d]);
    let door_rgb = shade(fin.rgb, 0.9);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.01, [w, h, d - 0.02], 0.015, fin.rgb);
    // Door fronts fill the same strip in front of the body in every variant (same outer edges,
    // 2 cm gaps at most, which no 5 cm map cell can fall into); the two handles, which stick
    // out further, keep their place.
    let pair = |p: &mut Vec<Part>, y0: f32, dh: f32, rgb: [f32; 3]| {
        for s in [-1.0, 1.0] {
            front(
                p,
                d,
                [s * w * 0.25, y0, 0.01],
                [w * 0.5 - 0.02, dh, 0.02],
                rgb,
            );
        }
    };
    match v {
        1 => {
            pair(&mut p, 0.45, h - 0.5, door_rgb);
            pair(&mut p, 0.05, 0.38, shade(fin.rgb, 0.8));
        }
        2 => {
            let dw = w / 3.0;
            for i in [-1.0, 0.0, 1.0] {
                let rgb = if i == 0.0 { tone::GLASS } else { door_rgb };
                front(
                    &mut p,
                    d,
                    [i * dw, 0.05, 0.01],
                    [dw - 0.02, h - 0.1, 0.02],
                    rgb,
                );
            }
        }
        3 => {
            pair(&mut p, 0.05, h * 0.74, door_rgb);
            pair(
                &mut p,
                h * 0.74 + 0.07,
                h * 0.26 - 0.12,
                shade(fin.rgb, 0.8),
            );
        }
        _ => pair(&mut p, 0.05, h - 0.1, door_rgb),
    }
    for s in [-1.0, 1.0] {
        front(
            &mut p,
            d,
            [s * 0.05, h * 0.5, -0.005],
            [0.02, 0.2, 0.01],
            tone::METAL,
        );
    }
    let features: &[&str] = match v {
        1 => &["two doors", "drawers below"],
        2 => &["three doors", "mirror door"],
        3 => &["two doors", "top cupboards"],
        _ => &["two doors"],
    };
    Model::new(C::Wardrobe, fin, [w, h, d], 70.0, p).with_features(features)
}

/// A dresser: body with drawer fronts; small objects on top. Variants: three full-width rows;
/// two columns of three; four rows with a split top row; two columns of two in a contrasting
/// colour; each with plain fronts, round knobs or bar handles.
pub(crate) fn dresser(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Dresser, rng);
    let (w, h, d) = (r(rng, 0.9, 1.4), r(rng, 0.75, 0.95), r(rng, 0.42, 0.52));
    // `k % 4` is the layout as it always was, `k / 4` the pulls (none, knobs, handles).
    let k = variant(12, &[w, h, d]);
    let (v, pulls) = (k % 4, k / 4);
    // Dark pulls on a light dresser, steel ones on a dark one.
    let pull_rgb = if fin.rgb.iter().sum::<f32>() > 1.2 {
        tone::METAL
    } else {
        tone::STEEL
    };
    // Pulls stick out of the fronts: the fronts stand 1 cm back against the body, and the
    // pulls end 0.5 mm inside the face the kick strip below makes.
    let back = if pulls > 0 { 0.01 } else { 0.0 };
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.01, [w, h, d - 0.02], 0.015, fin.rgb);
    // Drawer fronts stick out of the body: every layout covers the same strip (outer edges at
    // +-(w - 0.08) / 2, 1 cm gaps).
    let fw = w - 0.08;
    let rgb = if v == 3 {
        tone::LINEN
    } else {
        shade(fin.rgb, 0.85)
    };
    let (rows, split): (usize, &[usize]) = match v {
        1 => (3, &[0, 1, 2]),
        2 => (4, &[3]),
        3 => (2, &[0, 1]),
        _ => (3, &[]),
    };
    for i in 0..rows {
        let rh = (h - 0.1) / rows as f32;
        let y = 0.06 + i as f32 * rh;
        let pull_y = y + (rh - 0.03) * 0.5;
        if split.contains(&i) {
            for s in [-1.0, 1.0] {
                let x = s * (fw + 0.01) * 0.25;
                front(
                    &mut p,
                    d,
                    [x, y, 0.0055 + back],
                    [(fw - 0.01) * 0.5, rh - 0.03, 0.009],
                    rgb,
                );
                pull(&mut p, d, pulls, [x, pull_y], 0.1, pull_rgb);
            }
        } else {
            front(
                &mut p,
                d,
                [0.0, y, 0.005 + back],
                [fw, rh - 0.03, 0.01],
                rgb,
            );
            for s in [-1.0, 1.0] {
                pull(&mut p, d, pulls, [s * fw * 0.25, pull_y], 0.16, pull_rgb);
            }
        }
    }
    if !split.is_empty() || pulls > 0 {
        // Split fronts stand 0.5 mm back (their x would round the turned box's front face
        // differently); a kick strip with the full front's x and z makes that face.
        front(
            &mut p,
            d,
            [0.0, 0.02, 0.005],
            [fw, 0.035, 0.01],
            shade(rgb, 0.7),
        );
    }
    let drawers = match v {
        1 => "six drawers",
        2 => "five drawers",
        3 => "four drawers",
        _ => "three drawers",
    };
    let mut features = vec![drawers];
    features.extend(match pulls {
        1 => Some("knobs"),
        2 => Some("handles"),
        _ => None,
    });
    Model::new(C::Dresser, fin, [w, h, d], 45.0, p)
        .with_top(0.05)
        .with_features(&features)
}

/// A drawer's pull on the front face of a body of depth `d`, centred at `at` (x, y): none
/// (kind 0), a knob (1) or a bar handle `len` long (2), 9.5 mm deep, ending 0.5 mm
/// inside the face.
fn pull(p: &mut Vec<Part>, d: f32, kind: usize, at: [f32; 2], len: f32, rgb: [f32; 3]) {
    let [x, y] = at;
    let z = -d * 0.5 + 0.0005 + 0.00475;
    match kind {
        // Square: a box is 12 triangles, a disc 64.
        1 => cube(p, x, y - 0.02, z, [0.04, 0.04, 0.0095], rgb),
        2 => cube(p, x, y - 0.011, z, [len, 0.022, 0.0095], rgb),
        _ => {}
    }
}

/// A toilet: base, bowl, seat, tank.
pub(crate) fn toilet(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Toilet, rng);
    let (w, d) = (0.42, 0.7);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [0.26, 0.3, 0.4], 0.03, fin.rgb);
    cyl(&mut p, 0.0, 0.3, -0.08, 0.19, 0.1, fin.rgb);
    cyl(&mut p, 0.0, 0.4, -0.08, 0.2, 0.03, shade(fin.rgb, 0.9));
    bcube(&mut p, 0.0, 0.3, 0.26, [w, 0.5, 0.18], 0.03, fin.rgb);
    Model::new(C::Toilet, fin, [w, 0.8, d], 30.0, p).with_features(&["tank"])
}

/// A bathroom sink: vanity cabinet, basin, faucet.
pub(crate) fn sink(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Sink, rng);
    let wood = palette::pick(C::Cabinet, rng);
    let (w, h, d) = (r(rng, 0.6, 0.9), 0.85, 0.5);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, h - 0.04, d], 0.012, wood.rgb);
    cube(&mut p, 0.0, h - 0.04, 0.0, [w, 0.04, d], fin.rgb);
    cyl(
        &mut p,
        0.0,
        h - 0.02,
        -0.03,
        0.18,
        0.04,
        shade(fin.rgb, 0.8),
    );
    cyl(&mut p, 0.0, h, d * 0.5 - 0.08, 0.02, 0.2, tone::STEEL);
    cube(
        &mut p,
        0.0,
        h + 0.16,
        d * 0.5 - 0.14,
        [0.03, 0.03, 0.12],
        tone::STEEL,
    );
    Model::new(C::Sink, fin, [w, h + 0.2, d], 35.0, p).with_features(&["vanity cabinet"])
}

/// A bathtub: shell walls, floor, faucet.
pub(crate) fn bathtub(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Bathtub, rng);
    let (w, h, d) = (r(rng, 1.5, 1.75), 0.56, r(rng, 0.72, 0.8));
    let t = 0.08;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, 0.12, d], 0.02, fin.rgb);
    cube(
        &mut p,
        0.0,
        0.12,
        -d * 0.5 + t * 0.5,
        [w, h - 0.12, t],
        fin.rgb,
    );
    cube(
        &mut p,
        0.0,
        0.12,
        d * 0.5 - t * 0.5,
        [w, h - 0.12, t],
        fin.rgb,
    );
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * (w - t) * 0.5,
            0.12,
            0.0,
            [t, h - 0.12, d - 2.0 * t],
            fin.rgb,
        );
    }
    cube(
        &mut p,
        0.0,
        0.12,
        0.0,
        [w - 2.0 * t, 0.02, d - 2.0 * t],
        shade(fin.rgb, 0.85),
    );
    cyl(&mut p, -w * 0.5 + 0.04, h, 0.0, 0.02, 0.12, tone::STEEL);
    Model::new(C::Bathtub, fin, [w, h + 0.12, d], 60.0, p).with_features(&["faucet"])
}

/// A shower: tray, two glass panels, pole and head.
pub(crate) fn shower(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Shower, rng);
    let s = r(rng, 0.85, 1.0);
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [s, 0.08, s], fin.rgb);
    cube(
        &mut p,
        0.0,
        0.08,
        -s * 0.5 + 0.01,
        [s, 1.9, 0.02],
        tone::GLASS,
    );
    cube(
        &mut p,
        -s * 0.5 + 0.01,
        0.08,
        0.0,
        [0.02, 1.9, s - 0.04],
        tone::GLASS,
    );
    cube(
        &mut p,
        0.0,
        0.08,
        s * 0.5 - 0.04,
        [0.03, 1.9, 0.03],
        tone::STEEL,
    );
    cube(
        &mut p,
        0.0,
        1.93,
        s * 0.5 - 0.15,
        [0.15, 0.03, 0.2],
        tone::STEEL,
    );
    Model::new(C::Shower, fin, [s, 1.98, s], 40.0, p).with_features(&["glass panels"])
}

/// A fridge: body, freezer and fridge doors, handles.
pub(crate) fn fridge(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Fridge, rng);
    let (w, h, d) = (r(rng, 0.6, 0.8), r(rng, 1.7, 1.95), 0.68);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.02, [w, h, d - 0.04], 0.025, fin.rgb);
    front(
        &mut p,
        d,
        [0.0, 0.02, 0.01],
        [w - 0.02, h * 0.62, 0.02],
        shade(fin.rgb, 0.93),
    );
    front(
        &mut p,
        d,
        [0.0, h * 0.64 + 0.02, 0.01],
        [w - 0.02, h * 0.36 - 0.04, 0.02],
        shade(fin.rgb, 0.93),
    );
    front(
        &mut p,
        d,
        [w * 0.4, h * 0.35, -0.01],
        [0.025, 0.35, 0.02],
        tone::METAL,
    );
    front(
        &mut p,
        d,
        [w * 0.4, h * 0.7, -0.01],
        [0.025, 0.2, 0.02],
        tone::METAL,
    );
    Model::new(C::Fridge, fin, [w, h, d + 0.02], 80.0, p).with_features(&["freezer door"])
}

/// A kitchen counter of width `w`: plinth, cabinet body, door lines, worktop.
pub(crate) fn counter(rng: &mut ChaCha8Rng, w: f32) -> Model {
    let fin = palette::pick(C::Counter, rng);
    let (h, d) = (0.9, 0.62);
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.03, [w, 0.1, d - 0.08], tone::METAL);
    cube(&mut p, 0.0, 0.1, 0.01, [w, h - 0.14, d - 0.04], fin.rgb);
    let doors = (w / 0.5).round().max(1.0) as usize;
    for i in 0..doors {
        let dw = w / doors as f32;
        let x = -w * 0.5 + dw * (i as f32 + 0.5);
        front(
            &mut p,
            d,
            [x, 0.13, 0.02],
            [dw - 0.02, h - 0.2, 0.01],
            shade(fin.rgb, 0.9),
        );
        front(
            &mut p,
            d,
            [x, h - 0.14, 0.005],
            [0.12, 0.015, 0.015],
            tone::STEEL,
        );
    }
    bcube(
        &mut p,
        0.0,
        h - 0.04,
        0.0,
        [w, 0.04, d],
        0.008,
        [0.75, 0.74, 0.7],
    );
    Model::new(C::Counter, fin, [w, h, d], 40.0 * w, p).with_top(0.06)
}

/// A stove: body, oven door with window, hob with four burners.
pub(crate) fn stove(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Stove, rng);
    let (w, h, d) = (0.6, 0.9, 0.62);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, h - 0.02, d], 0.012, fin.rgb);
    front(
        &mut p,
        d,
        [0.0, 0.15, -0.005],
        [w - 0.06, 0.45, 0.01],
        tone::SCREEN,
    );
    front(
        &mut p,
        d,
        [0.0, 0.7, -0.015],
        [w - 0.1, 0.02, 0.02],
        tone::STEEL,
    );
    cube(&mut p, 0.0, h - 0.02, 0.0, [w, 0.02, d], tone::SCREEN);
    for sx in [-1.0, 1.0] {
        for sz in [-1.0, 1.0] {
            cyl(&mut p, sx * 0.14, h, sz * 0.14, 0.08, 0.01, tone::METAL);
        }
    }
    Model::new(C::Stove, fin, [w, h + 0.01, d + 0.02], 50.0, p)
        .with_features(&["four burners", "oven door"])
}

/// A dishwasher: body, door, handle.
pub(crate) fn dishwasher(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Dishwasher, rng);
    let (w, h, d) = (0.6, 0.88, 0.62);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, h, d], 0.015, fin.rgb);
    front(
        &mut p,
        d,
        [0.0, 0.1, -0.005],
        [w - 0.02, h - 0.15, 0.01],
        shade(fin.rgb, 0.9),
    );
    front(
        &mut p,
        d,
        [0.0, h - 0.1, -0.02],
        [w - 0.15, 0.02, 0.02],
        tone::STEEL,
    );
    Model::new(C::Dishwasher, fin, [w, h, d + 0.04], 45.0, p).with_top(0.05)
}

/// A tall kitchen cabinet (pantry): body, two doors, handles. Variants: a solid top door; a
/// top door of glass panes in a frame.
pub(crate) fn kitchen_cabinet(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::KitchenCabinet, rng);
    let (w, h, d) = (r(rng, 0.5, 0.8), r(rng, 1.9, 2.1), 0.6);
    let glass = variant(2, &[w, h]) == 1;
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.01, [w, h, d - 0.02], 0.015, fin.rgb);
    front(
        &mut p,
        d,
        [0.0, 0.05, 0.005],
        [w - 0.03, h * 0.6, 0.01],
        shade(fin.rgb, 0.9),
    );
    let (top_y, top_w, top_h) = (h * 0.62 + 0.05, w - 0.03, h * 0.36);
    let door_rgb = shade(fin.rgb, 0.9);
    front(
        &mut p,
        d,
        [0.0, top_y, 0.005],
        [top_w, top_h, 0.01],
        if glass { tone::GLASS } else { door_rgb },
    );
    if glass {
        // The door's frame and the bars between four panes, on the glass, no further out
        // than the handle.
        let bar = 0.05;
        for s in [-1.0, 1.0] {
            let x = s * (top_w - bar) * 0.5;
            front(&mut p, d, [x, top_y, -0.003], [bar, top_h, 0.006], door_rgb);
            // The top bar ends 0.5 mm under the door's top, which makes the cabinet's height.
            let y = top_y + (top_h - bar - 0.0005) * (0.5 + 0.5 * s);
            front(&mut p, d, [0.0, y, -0.003], [top_w, bar, 0.006], door_rgb);
        }
        let y = top_y + (top_h - 0.03) * 0.5;
        front(&mut p, d, [0.0, y, -0.003], [top_w, 0.03, 0.006], door_rgb);
        front(
            &mut p,
            d,
            [0.0, top_y, -0.003],
            [0.03, top_h, 0.006],
            door_rgb,
        );
    }
    front(
        &mut p,
        d,
        [w * 0.35, h * 0.5, -0.01],
        [0.02, 0.15, 0.02],
        tone::STEEL,
    );
    let features: &[&str] = if glass {
        &["two doors", "glass panes"]
    } else {
        &["two doors"]
    };
    Model::new(C::KitchenCabinet, fin, [w, h, d], 50.0, p).with_features(features)
}

/// Sofa and armchair variants, from three bits of a hash: a plinth instead of legs; low arms
/// (an armless look: the arm parts keep their footprint but end at the base's top); one long
/// seat cushion instead of one per seat.
#[derive(Clone, Copy)]
struct Seating {
    plinth: bool,
    low_arms: bool,
    bench: bool,
}

impl Seating {
    /// The features of a seat in this variant whose legs are `legs`.
    fn features(self, legs: &'static str) -> Vec<&'static str> {
        let mut out = Vec::new();
        if !self.plinth {
            out.push(legs);
        }
        if self.low_arms {
            out.push("low arms");
        }
        if self.bench {
            out.push("one long cushion");
        }
        out
    }

    fn of(v: usize) -> Seating {
        Seating {
            plinth: v & 1 != 0,
            low_arms: v & 2 != 0,
            bench: v & 4 != 0,
        }
    }
}

/// Feet of a sofa or armchair: four legs at the corners of `(w, d)`, or a recessed plinth that
/// covers them (so the footprint under the base is the same).
fn seat_feet(p: &mut Vec<Part>, v: Seating, w: f32, d: f32, h: f32, s: f32, rgb: [f32; 3]) {
    if v.plinth {
        cube(p, 0.0, 0.0, 0.0, [w, h, d], shade(rgb, 0.6));
    } else {
        legs(p, w, d, h, s, rgb);
    }
}

/// A sofa of width `w`: feet, base, seat cushions, back, arms, back cushions. See [`Seating`]
/// for its variants.
pub(crate) fn sofa(rng: &mut ChaCha8Rng, w: f32) -> Model {
    let fin = palette::pick(C::Sofa, rng);
    let (h, d) = (r(rng, 0.8, 0.9), r(rng, 0.85, 0.95));
    // `k % 8` is the seat as it always was; `k / 8` what lies on it (none, a blanket over an
    // arm or folded on the seat, two more cushions).
    let k = variant(24, &[w, h, d]);
    let v = Seating::of(k % 8);
    let arm = 0.2;
    let mut p = Vec::new();
    seat_feet(&mut p, v, w - 0.1, d - 0.1, 0.08, 0.05, tone::METAL);
    bcube(
        &mut p,
        0.0,
        0.08,
        0.0,
        [w, 0.25, d],
        0.03,
        shade(fin.rgb, 0.9),
    );
    // Without arms the seat cushions reach almost to the sides.
    let inner = if v.low_arms { 0.04 } else { arm };
    let seats = if v.bench {
        1
    } else if w > 1.7 {
        3
    } else {
        2
    };
    let sw = (w - 2.0 * inner) / seats as f32;
    for i in 0..seats {
        let x = -w * 0.5 + inner + sw * (i as f32 + 0.5);
        bcube(
            &mut p,
            x,
            0.33,
            -0.08,
            [sw - 0.02, 0.12, d - 0.3],
            0.025,
            fin.rgb,
        );
    }
    bcube(
        &mut p,
        0.0,
        0.33,
        d * 0.5 - 0.11,
        [w, h - 0.33, 0.22],
        0.04,
        fin.rgb,
    );
    let arm_h = if v.low_arms { 0.25 } else { 0.55 };
    for s in [-1.0, 1.0] {
        bcube(
            &mut p,
            s * (w - arm) * 0.5,
            0.08,
            0.0,
            [arm, arm_h, d],
            0.04,
            shade(fin.rgb, 0.95),
        );
    }
    let cushion = palette::fabric(rng);
    for s in [-1.0, 1.0] {
        bcube(
            &mut p,
            s * (w * 0.5 - arm - 0.25),
            0.45,
            d * 0.5 - 0.3,
            [0.4, 0.35, 0.12],
            0.025,
            cushion,
        );
    }
    let mut features = vec![if w > 1.7 { "three seats" } else { "two seats" }];
    features.extend(v.features("metal legs"));
    match k / 8 {
        1 => {
            let x = -(w - arm) * 0.5;
            let rgb = contrast(fin.rgb);
            if v.low_arms {
                // Low arms are under the seat cushions: folded on the left end of the seat.
                bcube(&mut p, x + 0.11, 0.45, -0.04, [0.38, 0.05, 0.5], 0.01, rgb);
                features.push("blanket on seat");
            } else {
                // Over the left arm (seen from the front), down its inside to the seat.
                let top = 0.08 + arm_h;
                bcube(&mut p, x, top, -0.04, [arm - 0.01, 0.03, 0.5], 0.006, rgb);
                let (xi, hi) = (x + arm * 0.5 + 0.012, top + 0.02 - 0.45);
                cube(&mut p, xi, 0.45, -0.04, [0.024, hi, 0.5], rgb);
                features.push("blanket over arm");
            }
        }
        2 => {
            // Two smaller cushions in another colour in front of the first two.
            for s in [-1.0, 1.0] {
                let x = s * (w * 0.5 - arm - 0.42).max(0.19);
                let c = contrast(cushion);
                bcube(&mut p, x, 0.45, d * 0.5 - 0.4, [0.34, 0.3, 0.1], 0.02, c);
            }
            features.push("four cushions");
        }
        _ => {}
    }
    Model::new(C::Sofa, fin, [w, h, d], 30.0 + 25.0 * w, p).with_features(&features)
}

/// An armchair: a one-seat sofa (plinth or legs, high or low arms).
pub(crate) fn armchair(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Armchair, rng);
    let (w, h, d) = (r(rng, 0.75, 0.9), r(rng, 0.8, 0.95), r(rng, 0.75, 0.85));
    // `k % 4` is the seat as it always was (an armchair has no bench variant); `k / 4` a
    // blanket over the back.
    let k = variant(8, &[w, h, d]);
    let v = Seating::of(k % 4);
    let arm = 0.15;
    let mut p = Vec::new();
    seat_feet(&mut p, v, w - 0.1, d - 0.1, 0.1, 0.04, tone::WOOD);
    bcube(
        &mut p,
        0.0,
        0.1,
        0.0,
        [w, 0.22, d],
        0.03,
        shade(fin.rgb, 0.9),
    );
    let inner = if v.low_arms { 0.04 } else { arm };
    bcube(
        &mut p,
        0.0,
        0.32,
        -0.06,
        [w - 2.0 * inner, 0.1, d - 0.22],
        0.02,
        fin.rgb,
    );
    bcube(
        &mut p,
        0.0,
        0.32,
        d * 0.5 - 0.09,
        [w, h - 0.32, 0.18],
        0.04,
        fin.rgb,
    );
    let arm_h = if v.low_arms { 0.22 } else { 0.5 };
    for s in [-1.0, 1.0] {
        bcube(
            &mut p,
            s * (w - arm) * 0.5,
            0.1,
            0.0,
            [arm, arm_h, d],
            0.03,
            shade(fin.rgb, 0.95),
        );
    }
    let mut features = v.features("wooden legs");
    if k / 4 == 1 {
        // Over the top of the back (just under it, so the chair's height stays) and down its
        // front to the seat cushion.
        let rgb = contrast(fin.rgb);
        let bw = (w - 2.0 * arm) * 0.7;
        let zb = d * 0.5 - 0.09;
        cube(&mut p, -0.05, h - 0.0205, zb, [bw, 0.02, 0.178], rgb);
        let front = d * 0.5 - 0.18 - 0.011;
        cube(
            &mut p,
            -0.05,
            0.42,
            front,
            [bw, h - 0.0205 - 0.42 + 0.02, 0.022],
            rgb,
        );
        features.push("blanket over back");
    }
    Model::new(C::Armchair, fin, [w, h, d], 25.0, p).with_features(&features)
}

/// A flat-screen TV on a foot: panel, screen, neck, foot.
pub(crate) fn tv(rng: &mut ChaCha8Rng, max_w: f32) -> Model {
    let fin = palette::pick(C::Tv, rng);
    let w = r(rng, 0.9, 1.45).min(max_w);
    let h = w * 0.58;
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [w * 0.4, 0.02, 0.22], tone::METAL);
    cube(&mut p, 0.0, 0.02, 0.02, [0.06, 0.08, 0.04], tone::METAL);
    cube(&mut p, 0.0, 0.08, 0.02, [w, h, 0.05], fin.rgb);
    cube(
        &mut p,
        0.0,
        0.1,
        -0.005,
        [w - 0.04, h - 0.04, 0.01],
        tone::SCREEN,
    );
    Model::new(C::Tv, fin, [w, h + 0.08, 0.22], 8.0 + 6.0 * w, p)
}

/// A TV stand: body, two compartments, legs.
pub(crate) fn tv_stand(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::TvStand, rng);
    let (w, h, d) = (r(rng, 1.2, 1.8), r(rng, 0.45, 0.55), r(rng, 0.4, 0.48));
    let mut p = Vec::new();
    legs(&mut p, w - 0.05, d - 0.05, 0.08, 0.04, tone::METAL);
    bcube(&mut p, 0.0, 0.08, 0.0, [w, h - 0.08, d], 0.012, fin.rgb);
    for s in [-1.0, 1.0] {
        front(
            &mut p,
            d,
            [s * w * 0.25, 0.12, -0.005],
            [w * 0.5 - 0.06, h - 0.16, 0.01],
            shade(fin.rgb, 0.75),
        );
    }
    Model::new(C::TvStand, fin, [w, h, d + 0.01], 30.0, p)
        .with_top(0.02)
        .with_features(&["two compartments"])
}

/// Height of the feet of table variants. Parts standing on the floor set the bottom of an
/// object's box, which is rounded differently for parts of different heights once the object
/// is turned: variants stand only on parts as tall as the four legs they replace; their feet
/// float 2 mm above the floor.
const LIFT: f32 = 0.002;

/// Table variants: four legs; a pedestal (two for long tables) on crossed feet; two trestle
/// ends joined by a stretcher; four legs braced by an apron and low rails.
const TABLE_VARIANTS: usize = 4;

/// The variant of a table, from its drawn size and colours (a dining table's size is chosen by
/// the room, its colours are its own draws).
fn table_variant(fin: Finish, w: f32, h: f32, d: f32, leg_rgb: [f32; 3]) -> usize {
    variant(
        TABLE_VARIANTS,
        &[w, h, d, fin.rgb[0], fin.rgb[2], leg_rgb[1]],
    )
}

/// A table top on one of the [`TABLE_VARIANTS`] supports (coffee, dining, side tables). The
/// top covers the whole footprint and is the largest part in every variant.
fn table(class: C, fin: Finish, w: f32, h: f32, d: f32, leg_rgb: [f32; 3], mass: f32) -> Model {
    let mut p = Vec::new();
    let top = 0.04;
    let under = h - top;
    bcube(&mut p, 0.0, under, 0.0, [w, top, d], 0.008, fin.rgb);
    let v = table_variant(fin, w, h, d, leg_rgb);
    match v {
        1 => {
            let r = (w.min(d) * 0.1).clamp(0.03, 0.05);
            let xs: &[f32] = if w > 1.3 { &[-0.3, 0.3] } else { &[0.0] };
            for &f in xs {
                let x = f * w;
                cyl(&mut p, x, 0.0, 0.0, r, under, leg_rgb);
                cube(&mut p, x, LIFT, 0.0, [0.08, 0.04, d * 0.7], leg_rgb);
                if xs.len() == 1 {
                    cube(&mut p, x, LIFT, 0.0, [w * 0.7, 0.04, 0.08], leg_rgb);
                }
            }
            if xs.len() == 2 {
                cube(&mut p, 0.0, 0.25, 0.0, [w * 0.6, 0.05, 0.05], leg_rgb);
            }
        }
        2 => {
            for s in [-1.0, 1.0] {
                let x = s * (w * 0.5 - 0.1);
                cube(&mut p, x, 0.0, 0.0, [0.035, under, d * 0.45], leg_rgb);
                cube(&mut p, x, LIFT, 0.0, [0.07, 0.03, d - 0.1], leg_rgb);
            }
            cube(
                &mut p,
                0.0,
                under * 0.3,
                0.0,
                [w - 0.2, 0.05, 0.03],
                leg_rgb,
            );
        }
        3 => {
            legs(&mut p, w - 0.06, d - 0.06, under, 0.05, leg_rgb);
            for s in [-1.0, 1.0] {
                cube(
                    &mut p,
                    0.0,
                    under - 0.07,
                    s * (d * 0.5 - 0.05),
                    [w - 0.12, 0.07, 0.02],
                    leg_rgb,
                );
                cube(
                    &mut p,
                    s * (w * 0.5 - 0.055),
                    0.12,
                    0.0,
                    [0.025, 0.03, d - 0.12],
                    leg_rgb,
                );
            }
            cube(&mut p, 0.0, 0.12, 0.0, [w - 0.12, 0.03, 0.025], leg_rgb);
        }
        _ => legs(&mut p, w - 0.06, d - 0.06, under, 0.05, leg_rgb),
    }
    let support = match v {
        // Long tables stand on two (see the pedestal variant above).
        1 if w > 1.3 => "two pedestals",
        1 => "pedestal",
        2 => "trestle legs",
        3 => "braced legs",
        _ => "four legs",
    };
    Model::new(class, fin, [w, h, d], mass, p)
        .with_top(0.05)
        .with_features(&[support])
}

/// A coffee table (with a lower shelf when it stands on legs).
pub(crate) fn coffee_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::CoffeeTable, rng);
    let (w, h, d) = (r(rng, 0.9, 1.2), r(rng, 0.38, 0.46), r(rng, 0.5, 0.65));
    let mut m = table(C::CoffeeTable, fin, w, h, d, shade(fin.rgb, 0.8), 15.0);
    if matches!(table_variant(fin, w, h, d, shade(fin.rgb, 0.8)), 0 | 3) {
        // A lower shelf makes it read as a coffee table rather than a bench.
        cube(
            &mut m.parts,
            0.0,
            0.08,
            0.0,
            [w - 0.1, 0.02, d - 0.1],
            shade(fin.rgb, 0.8),
        );
        m.features.push("lower shelf");
    }
    m
}

/// A dining table of the given size.
pub(crate) fn dining_table(rng: &mut ChaCha8Rng, w: f32, d: f32) -> Model {
    let fin = palette::pick(C::DiningTable, rng);
    let legs_rgb = if rng.random_bool(0.5) {
        tone::METAL
    } else {
        shade(fin.rgb, 0.85)
    };
    table(
        C::DiningTable,
        fin,
        w,
        0.75,
        d,
        legs_rgb,
        20.0 + 10.0 * w * d,
    )
}

/// A side table.
pub(crate) fn side_table(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::SideTable, rng);
    let s = r(rng, 0.4, 0.55);
    table(
        C::SideTable,
        fin,
        s,
        r(rng, 0.5, 0.62),
        s,
        shade(fin.rgb, 0.8),
        6.0,
    )
}

/// A desk: top, two side panels, a drawer block.
pub(crate) fn desk(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Desk, rng);
    let (w, h, d) = (r(rng, 1.1, 1.5), 0.75, r(rng, 0.6, 0.7));
    let mut p = Vec::new();
    bcube(&mut p, 0.0, h - 0.04, 0.0, [w, 0.04, d], 0.008, fin.rgb);
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * (w * 0.5 - 0.02),
            0.0,
            0.0,
            [0.04, h - 0.04, d - 0.04],
            shade(fin.rgb, 0.85),
        );
    }
    cube(
        &mut p,
        0.0,
        h * 0.35,
        d * 0.5 - 0.03,
        [w - 0.08, h * 0.4, 0.02],
        shade(fin.rgb, 0.85),
    );
    cube(
        &mut p,
        w * 0.5 - 0.25,
        h - 0.2,
        -0.02,
        [0.4, 0.16, d - 0.1],
        shade(fin.rgb, 0.9),
    );
    Model::new(C::Desk, fin, [w, h, d], 30.0, p)
        .with_top(0.05)
        .with_features(&["drawer block"])
}

/// A chair: four legs, seat, backrest on two posts. Variants: a top panel; spindles under
/// the panel; a solid back down to the seat; arms. The panel, seat and legs keep their place
/// in every variant (they make the chair's box), the rest stays inside it.
pub(crate) fn chair(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Chair, rng);
    let (w, d) = (r(rng, 0.42, 0.5), r(rng, 0.44, 0.52));
    let seat = r(rng, 0.44, 0.48);
    let h = r(rng, 0.85, 0.98);
    // `v % 4` is the back as it always was; `v / 4` a cushion on the seat.
    let v = variant(8, &[w, d, seat, h]);
    let leg_rgb = if fin.material == "wood" {
        shade(fin.rgb, 0.8)
    } else {
        tone::METAL
    };
    let mut p = Vec::new();
    legs(&mut p, w, d, seat - 0.04, 0.035, leg_rgb);
    // Chairs come in sets: their thin seat and back stay sharp (a bevel costs 32 triangles).
    cube(&mut p, 0.0, seat - 0.04, 0.0, [w, 0.04, d], fin.rgb);
    let back_z = d * 0.5 - 0.02;
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * (w - 0.035) * 0.5,
            seat,
            d * 0.5 - 0.0175,
            [0.035, h - seat - 0.16, 0.035],
            leg_rgb,
        );
    }
    bcube(&mut p, 0.0, h - 0.18, back_z, [w, 0.18, 0.04], 0.0, fin.rgb);
    let below = h - seat - 0.18;
    if v / 4 == 1 {
        // Sharp like the seat: a set of chairs shares it.
        let rgb = contrast(fin.rgb);
        cube(&mut p, 0.0, seat, -0.015, [w - 0.08, 0.035, d - 0.1], rgb);
    }
    match v % 4 {
        1 => {
            for x in [-0.25, 0.0, 0.25] {
                cube(&mut p, x * w, seat, back_z, [0.02, below, 0.02], leg_rgb);
            }
        }
        2 => cube(
            &mut p,
            0.0,
            seat,
            back_z,
            [w - 0.07, below, 0.03],
            shade(fin.rgb, 0.95),
        ),
        3 => {
            for s in [-1.0, 1.0] {
                let x = s * (w * 0.5 - 0.025);
                cube(&mut p, x, seat + 0.2, 0.0, [0.04, 0.03, d * 0.8], fin.rgb);
                cube(
                    &mut p,
                    x,
                    seat,
                    -d * 0.5 + 0.06,
                    [0.025, 0.2, 0.025],
                    leg_rgb,
                );
            }
        }
        _ => {}
    }
    let mut features: Vec<&str> = match v % 4 {
        1 => vec!["spindle back"],
        2 => vec!["solid back"],
        3 => vec!["arms"],
        _ => vec![],
    };
    if v / 4 == 1 {
        features.push("seat cushion");
    }
    Model::new(C::Chair, fin, [w, h, d], 5.0, p).with_features(&features)
}

/// An office chair: five-star base (two crossed bars), column, seat, backrest.
pub(crate) fn office_chair(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::OfficeChair, rng);
    let s = 0.6;
    let h = r(rng, 0.95, 1.1);
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.02, 0.0, [s, 0.04, 0.06], tone::METAL);
    cube(&mut p, 0.0, 0.02, 0.0, [0.06, 0.04, s], tone::METAL);
    for (x, z) in [
        (s * 0.45, 0.0),
        (-s * 0.45, 0.0),
        (0.0, s * 0.45),
        (0.0, -s * 0.45),
    ] {
        cube(&mut p, x, 0.0, z, [0.05, 0.03, 0.05], tone::METAL);
    }
    cyl(&mut p, 0.0, 0.06, 0.0, 0.03, 0.36, tone::STEEL);
    bcube(&mut p, 0.0, 0.42, 0.0, [0.5, 0.08, 0.5], 0.015, fin.rgb);
    cube(&mut p, 0.0, 0.45, 0.24, [0.06, 0.15, 0.04], tone::METAL);
    bcube(
        &mut p,
        0.0,
        0.6,
        0.25,
        [0.46, h - 0.6, 0.06],
        0.012,
        fin.rgb,
    );
    Model::new(C::OfficeChair, fin, [s, h, s], 12.0, p)
}

/// A bookshelf: sides, back, shelves, rows of books.
pub(crate) fn bookshelf(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Bookshelf, rng);
    let (w, h, d) = (r(rng, 0.7, 1.2), r(rng, 1.5, 2.0), r(rng, 0.3, 0.38));
    let t = 0.03;
    let mut p = Vec::new();
    for s in [-1.0, 1.0] {
        cube(&mut p, s * (w - t) * 0.5, 0.0, 0.0, [t, h, d], fin.rgb);
    }
    cube(
        &mut p,
        0.0,
        0.0,
        d * 0.5 - 0.01,
        [w - 2.0 * t, h, 0.02],
        shade(fin.rgb, 0.8),
    );
    let shelves = (h / 0.38) as usize;
    let gap = (h - t) / shelves as f32;
    for i in 0..=shelves {
        cube(
            &mut p,
            0.0,
            i as f32 * gap,
            0.0,
            [w - 2.0 * t, t, d],
            fin.rgb,
        );
    }
    for i in 0..shelves {
        // One block of books per shelf, in a varying colour and fill.
        let fill = r(rng, 0.4, 0.9);
        let bw = (w - 2.0 * t - 0.04) * fill;
        let x = -w * 0.5 + t + 0.02 + bw * 0.5;
        let rgb = palette::pick(C::Book, rng).rgb;
        cube(
            &mut p,
            x,
            i as f32 * gap + t,
            0.0,
            [bw, gap * 0.65, d - 0.08],
            rgb,
        );
    }
    let count = match shelves {
        0..=3 => "three shelves",
        4 => "four shelves",
        _ => "five shelves",
    };
    Model::new(C::Bookshelf, fin, [w, h, d], 35.0, p)
        .with_top(0.03)
        .with_features(&[count])
}

/// A potted plant: pot, soil, stem, foliage. Variants: one round bush; a bush with smaller
/// clumps around its base; a bush with broad leaves sticking out; each with or without
/// flowers. The main ball (the largest part) is in every variant and the rest stays inside
/// its outline seen from above.
pub(crate) fn potted_plant(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::PottedPlant, rng);
    let pot_r = r(rng, 0.14, 0.2);
    let h = r(rng, 0.8, 1.4);
    let fol = (pot_r * 1.6).min(0.3);
    // `k % 3` is the bush as it always was, `k / 3` flowers.
    let k = variant(6, &[pot_r, h]);
    let v = k % 3;
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, pot_r, 0.35, fin.rgb);
    cyl(&mut p, 0.0, 0.35, 0.0, pot_r - 0.02, 0.01, tone::SOIL);
    cyl(&mut p, 0.0, 0.35, 0.0, 0.025, h - 0.35 - fol, tone::WOOD);
    ball(&mut p, [0.0, h - fol, 0.0], fol, tone::LEAF);
    let dark = shade(tone::LEAF, 0.75);
    match v {
        1 => {
            for k in 0..3 {
                let a = k as f32 * std::f32::consts::TAU / 3.0 + 0.5;
                let c = [a.cos() * fol * 0.4, h - fol * 1.25, a.sin() * fol * 0.4];
                ball(&mut p, c, fol * 0.55, dark);
            }
        }
        2 => {
            for k in 0..5 {
                let a = k as f32 * std::f32::consts::TAU / 5.0;
                let rot = Quat::from_rotation_y(-a) * Quat::from_rotation_z(0.6);
                let len = fol * 0.85;
                let c = [a.cos() * fol * 0.5, h - fol * 1.1, a.sin() * fol * 0.5];
                let blade = Shape::Cuboid {
                    half_extents: [len * 0.5, 0.005, 0.04],
                    bevel: 0.0,
                };
                turned(&mut p, blade, c, rot, dark);
            }
        }
        _ => {}
    }
    let mut features = if v == 2 { vec!["broad leaves"] } else { vec![] };
    if k / 3 == 1 {
        // Blossoms in three colours half out of the bush, all inside its box (the ball's top
        // and sides make the plant's box) and its outline seen from above.
        let centre = Vec3::new(0.0, h - fol, 0.0);
        for (i, (lat, lon)) in BLOSSOMS.iter().enumerate() {
            let (lat, lon) = (lat.to_radians(), lon.to_radians());
            let dir = Vec3::new(lat.cos() * lon.cos(), lat.sin(), lat.cos() * lon.sin());
            // Small boxes, not balls: a ball is 144 triangles, a box 12.
            let c = centre + dir * (fol - 0.01);
            let rgb = BLOSSOM_RGB[i % BLOSSOM_RGB.len()];
            cube(&mut p, c.x, c.y - 0.0225, c.z, [0.045; 3], rgb);
        }
        features.push("flowers");
    }
    let s = 2.0 * fol.max(pot_r);
    Model::new(C::PottedPlant, fin, [s, h, s], 10.0, p).with_features(&features)
}

/// Where a flowering plant's blossoms sit on its bush: latitude and longitude in degrees, none
/// so near the top that it would stick out of the bush's box, nor so low that it would stick
/// out of its outline seen from above (the maps).
const BLOSSOMS: [(f32, f32); 10] = [
    (65.0, 200.0),
    (55.0, 0.0),
    (55.0, 120.0),
    (55.0, 240.0),
    (45.0, 60.0),
    (45.0, 180.0),
    (45.0, 300.0),
    (35.0, 0.0),
    (35.0, 120.0),
    (35.0, 240.0),
];

/// Blossom colours: red, yellow, pink.
const BLOSSOM_RGB: [[f32; 3]; 3] = [[0.8, 0.08, 0.1], [0.95, 0.8, 0.15], [0.95, 0.5, 0.7]];

/// A floor lamp: base, pole, shade. Variants: a drum shade; a tapered shade (a narrow drum over
/// a wide rim); a drum on a tripod.
pub(crate) fn floor_lamp(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::FloorLamp, rng);
    let h = r(rng, 1.5, 1.8);
    let v = variant(3, &[h]);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.15, 0.03, tone::METAL);
    cyl(&mut p, 0.0, 0.03, 0.0, 0.015, h - 0.33, tone::METAL);
    // The widest shade part keeps the drum's radius and stays in the agent's height band, so
    // the footprint is the drum's disc in every variant.
    if v == 1 {
        cyl(&mut p, 0.0, h - 0.32, 0.0, 0.12, 0.32, fin.rgb);
        cyl(&mut p, 0.0, h - 0.32, 0.0, 0.17, 0.1, fin.rgb);
        cyl(&mut p, 0.0, h - 0.23, 0.0, 0.145, 0.1, fin.rgb);
    } else {
        cyl(&mut p, 0.0, h - 0.32, 0.0, 0.17, 0.32, fin.rgb);
    }
    if v == 2 {
        // Three legs from the pole down to the rim of the base.
        let (top, foot, r): (f32, f32, f32) = (0.5, 0.13, 0.012);
        let len = (foot * foot + (top - 0.01) * (top - 0.01)).sqrt();
        let tilt = (foot / (top - 0.01)).atan();
        for k in 0..3 {
            let a = k as f32 * std::f32::consts::TAU / 3.0;
            let rot = Quat::from_rotation_y(-a) * Quat::from_rotation_z(tilt);
            let c = [
                a.cos() * foot * 0.5,
                (top + 0.01) * 0.5,
                a.sin() * foot * 0.5,
            ];
            let leg = Shape::Cylinder {
                radius: r,
                half_height: len * 0.5,
            };
            turned(&mut p, leg, c, rot, tone::METAL);
        }
    }
    let features = match v {
        1 => "tapered shade",
        2 => "tripod",
        _ => "drum shade",
    };
    Model::new(C::FloorLamp, fin, [0.34, h, 0.34], 5.0, p).with_features(&[features])
}

/// A flat rug of the given size (under 2 cm high).
pub(crate) fn rug(rng: &mut ChaCha8Rng, w: f32, d: f32) -> Model {
    let fin = palette::pick(C::Rug, rng);
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [w, 0.01, d], fin.rgb);
    cube(
        &mut p,
        0.0,
        0.0,
        0.0,
        [w * 0.7, 0.012, d * 0.6],
        shade(fin.rgb, 1.4),
    );
    // The renderer weaves every rug's diamond lattice (vlnverse_env::material, `Surface::Rug`).
    Model::new(C::Rug, fin, [w, 0.012, d], 3.0 * w * d, p).with_features(&["diamond pattern"])
}

/// A low cabinet: body, two doors, handles; small objects on top.
pub(crate) fn cabinet(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Cabinet, rng);
    let (w, h, d) = (r(rng, 0.6, 1.0), r(rng, 0.75, 0.95), r(rng, 0.38, 0.48));
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.01, [w, h, d - 0.02], 0.015, fin.rgb);
    for s in [-1.0, 1.0] {
        front(
            &mut p,
            d,
            [s * w * 0.25, 0.04, 0.005],
            [w * 0.5 - 0.03, h - 0.08, 0.01],
            shade(fin.rgb, 0.85),
        );
        front(
            &mut p,
            d,
            [s * 0.04, h * 0.6, -0.005],
            [0.015, 0.1, 0.01],
            tone::STEEL,
        );
    }
    Model::new(C::Cabinet, fin, [w, h, d], 25.0, p)
        .with_top(0.04)
        .with_features(&["two doors"])
}

/// A shoe rack: sides and three shelves with shoes.
pub(crate) fn shoe_rack(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::ShoeRack, rng);
    let (w, h, d) = (r(rng, 0.6, 1.0), r(rng, 0.45, 0.6), 0.32);
    let mut p = Vec::new();
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * (w - 0.03) * 0.5,
            0.0,
            0.0,
            [0.03, h, d],
            fin.rgb,
        );
    }
    for i in 0..3 {
        cube(
            &mut p,
            0.0,
            i as f32 * (h - 0.03) / 2.0,
            0.0,
            [w - 0.06, 0.03, d],
            fin.rgb,
        );
    }
    for i in 0..2 {
        let y = 0.03 + i as f32 * (h - 0.03) / 2.0;
        cube(
            &mut p,
            -w * 0.2,
            y,
            0.0,
            [0.1, 0.08, 0.26],
            palette::fabric(rng),
        );
        cube(
            &mut p,
            w * 0.15,
            y,
            0.0,
            [0.1, 0.08, 0.26],
            palette::fabric(rng),
        );
    }
    Model::new(C::ShoeRack, fin, [w, h, d], 8.0, p)
        .with_top(0.04)
        .with_features(&["three shelves with shoes"])
}

/// A coat rack: base, pole, hooks, a coat.
pub(crate) fn coat_rack(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::CoatRack, rng);
    let h = r(rng, 1.7, 1.85);
    let mut p = Vec::new();
    cube(&mut p, 0.0, 0.0, 0.0, [0.45, 0.03, 0.06], fin.rgb);
    cube(&mut p, 0.0, 0.0, 0.0, [0.06, 0.03, 0.45], fin.rgb);
    cyl(&mut p, 0.0, 0.03, 0.0, 0.02, h - 0.03, fin.rgb);
    cube(&mut p, 0.0, h - 0.12, 0.0, [0.36, 0.02, 0.02], fin.rgb);
    cube(&mut p, 0.0, h - 0.12, 0.0, [0.02, 0.02, 0.36], fin.rgb);
    cube(
        &mut p,
        0.12,
        h - 0.95,
        0.0,
        [0.08, 0.8, 0.3],
        palette::fabric(rng),
    );
    Model::new(C::CoatRack, fin, [0.45, h, 0.45], 6.0, p).with_features(&["coat"])
}

/// A washing machine: body, round door, control strip.
pub(crate) fn washing_machine(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::WashingMachine, rng);
    let (w, h, d) = (0.6, 0.85, 0.6);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.0, [w, h, d], 0.015, fin.rgb);
    disc_z(
        &mut p,
        [0.0, h * 0.45, -d * 0.5 - 0.015],
        0.19,
        0.03,
        tone::SCREEN,
    );
    disc_z(
        &mut p,
        [0.0, h * 0.45, -d * 0.5 - 0.03],
        0.14,
        0.01,
        tone::GLASS,
    );
    front(
        &mut p,
        d,
        [0.0, h - 0.12, -0.005],
        [w - 0.04, 0.1, 0.01],
        shade(fin.rgb, 0.8),
    );
    Model::new(C::WashingMachine, fin, [w, h, d + 0.07], 65.0, p)
        .with_top(0.05)
        .with_features(&["round door"])
}

/// An upright piano: body, keyboard shelf, keys, legs.
pub(crate) fn piano(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Piano, rng);
    let (w, h, d) = (1.45, r(rng, 1.1, 1.3), 0.6);
    let mut p = Vec::new();
    bcube(&mut p, 0.0, 0.0, 0.1, [w, h, 0.4], 0.015, fin.rgb);
    bcube(&mut p, 0.0, 0.7, -0.15, [w, 0.06, 0.3], 0.012, fin.rgb);
    cube(&mut p, 0.0, 0.76, -0.2, [w - 0.2, 0.02, 0.16], tone::WHITE);
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * (w * 0.5 - 0.05),
            0.0,
            -0.2,
            [0.06, 0.7, 0.06],
            fin.rgb,
        );
    }
    Model::new(C::Piano, fin, [w, h, d], 200.0, p).with_features(&["keys"])
}

/// A bench: seat on two solid sides.
pub(crate) fn bench(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Bench, rng);
    let wood = palette::pick(C::SideTable, rng);
    let (w, h, d) = (r(rng, 0.9, 1.3), 0.46, 0.38);
    let mut p = Vec::new();
    for s in [-1.0, 1.0] {
        cube(
            &mut p,
            s * (w * 0.5 - 0.03),
            0.0,
            0.0,
            [0.05, h - 0.06, d],
            wood.rgb,
        );
    }
    bcube(&mut p, 0.0, h - 0.06, 0.0, [w, 0.06, d], 0.012, fin.rgb);
    Model::new(C::Bench, fin, [w, h, d], 12.0, p).with_features(&["solid sides"])
}

/// A stool: round seat on four legs.
pub(crate) fn stool(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::Stool, rng);
    let h = r(rng, 0.45, 0.7);
    let mut p = Vec::new();
    legs(&mut p, 0.3, 0.3, h - 0.04, 0.03, tone::METAL);
    cyl(&mut p, 0.0, h - 0.04, 0.0, 0.17, 0.04, fin.rgb);
    Model::new(C::Stool, fin, [0.34, h, 0.34], 3.0, p).with_features(&["round seat"])
}

/// A trash can: bin and lid.
pub(crate) fn trash_can(rng: &mut ChaCha8Rng) -> Model {
    let fin = palette::pick(C::TrashCan, rng);
    let h = r(rng, 0.35, 0.55);
    let mut p = Vec::new();
    cyl(&mut p, 0.0, 0.0, 0.0, 0.14, h - 0.02, fin.rgb);
    cyl(&mut p, 0.0, h - 0.02, 0.0, 0.15, 0.02, shade(fin.rgb, 0.7));
    Model::new(C::TrashCan, fin, [0.3, h, 0.3], 2.0, p).with_features(&["lid"])
}

/// A small object that stands on furniture. The footprint is its local bounding box.
pub(crate) fn small(class: C, rng: &mut ChaCha8Rng) -> Model {
    if let Some(m) = crate::gear::model(class, rng) {
        return m;
    }
    let fin = palette::pick(class, rng);
    let c = fin.rgb;
    let mut p = Vec::new();
    let mut features = Vec::new();
    let (size, mass) = match class {
        C::Cup => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.04, 0.1, c);
            ([0.08, 0.1, 0.08], 0.2)
        }
        C::Mug => {
            cyl(&mut p, -0.015, 0.0, 0.0, 0.045, 0.1, c);
            cube(&mut p, 0.045, 0.02, 0.0, [0.03, 0.06, 0.015], c);
            ([0.12, 0.1, 0.09], 0.3)
        }
        C::Book => {
            let (w, d, t) = (r(rng, 0.13, 0.18), r(rng, 0.19, 0.25), r(rng, 0.02, 0.05));
            cube(&mut p, 0.0, 0.0, 0.0, [w, t, d], c);
            cube(
                &mut p,
                0.005,
                0.003,
                0.0,
                [w - 0.005, t - 0.006, d - 0.01],
                tone::LINEN,
            );
            ([w, t, d], 0.4)
        }
        C::Laptop => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.33, 0.02, 0.23], c);
            cube(&mut p, 0.0, 0.02, 0.11, [0.33, 0.22, 0.01], c);
            cube(&mut p, 0.0, 0.03, 0.104, [0.3, 0.19, 0.003], tone::SCREEN);
            ([0.33, 0.24, 0.24], 1.5)
        }
        C::Vase => {
            let h = r(rng, 0.18, 0.32);
            cyl(&mut p, 0.0, 0.0, 0.0, 0.07, h * 0.75, c);
            if variant(2, &[h]) == 1 {
                // Flowers in place of the neck: a bunch of stems as tall as the neck (so the
                // vase's box stays), blossoms round their tops inside the body's outline.
                cyl(&mut p, 0.0, h * 0.75, 0.0, 0.04, h * 0.25, tone::LEAF);
                for (i, (x, z, y)) in [(-0.03, 0.0, 0.0), (0.03, 0.012, 0.015), (0.0, -0.03, 0.008)]
                    .into_iter()
                    .enumerate()
                {
                    let rgb = BLOSSOM_RGB[i % BLOSSOM_RGB.len()];
                    cube(&mut p, x, h - 0.0505 - y, z, [0.05; 3], rgb);
                }
                features.push("flowers in vase");
            } else {
                cyl(&mut p, 0.0, h * 0.75, 0.0, 0.04, h * 0.25, c);
            }
            ([0.14, h, 0.14], 0.8)
        }
        C::Bowl => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.05, 0.02, c);
            cyl(&mut p, 0.0, 0.02, 0.0, 0.09, 0.05, c);
            ([0.18, 0.07, 0.18], 0.4)
        }
        C::Plate => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.12, 0.015, c);
            ([0.24, 0.015, 0.24], 0.4)
        }
        C::Bottle => {
            let h = r(rng, 0.25, 0.32);
            cyl(&mut p, 0.0, 0.0, 0.0, 0.035, h * 0.7, c);
            cyl(&mut p, 0.0, h * 0.7, 0.0, 0.014, h * 0.3, c);
            ([0.07, h, 0.07], 0.8)
        }
        C::Clock => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.16, 0.03, 0.07], c);
            disc_z(&mut p, [0.0, 0.1, 0.0], 0.08, 0.05, c);
            disc_z(&mut p, [0.0, 0.1, -0.026], 0.065, 0.004, tone::WHITE);
            ([0.16, 0.18, 0.07], 0.5)
        }
        C::TableLamp => {
            let h = r(rng, 0.35, 0.5);
            cyl(&mut p, 0.0, 0.0, 0.0, 0.08, 0.03, tone::METAL);
            cyl(&mut p, 0.0, 0.03, 0.0, 0.012, h - 0.2, tone::METAL);
            cyl(&mut p, 0.0, h - 0.18, 0.0, 0.12, 0.18, c);
            ([0.24, h, 0.24], 1.5)
        }
        C::SmallPlant => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.06, 0.1, c);
            ball(&mut p, [0.0, 0.18, 0.0], 0.08, tone::LEAF);
            ([0.16, 0.26, 0.16], 0.8)
        }
        C::Monitor => {
            let w = r(rng, 0.48, 0.62);
            cube(&mut p, 0.0, 0.0, 0.0, [0.22, 0.02, 0.16], tone::METAL);
            cube(&mut p, 0.0, 0.02, 0.02, [0.04, 0.12, 0.03], tone::METAL);
            cube(&mut p, 0.0, 0.1, 0.0, [w, w * 0.6, 0.03], c);
            cube(
                &mut p,
                0.0,
                0.115,
                -0.016,
                [w - 0.03, w * 0.6 - 0.03, 0.003],
                tone::SCREEN,
            );
            ([w, 0.1 + w * 0.6, 0.16], 4.0)
        }
        C::Keyboard => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.44, 0.02, 0.14], c);
            cube(&mut p, 0.0, 0.02, 0.0, [0.4, 0.008, 0.11], shade(c, 0.6));
            ([0.44, 0.028, 0.14], 0.7)
        }
        C::Remote => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.05, 0.02, 0.18], c);
            ([0.05, 0.02, 0.18], 0.15)
        }
        C::Toaster => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.28, 0.19, 0.17], c);
            cube(&mut p, 0.0, 0.19, -0.035, [0.2, 0.005, 0.03], tone::SCREEN);
            cube(&mut p, 0.0, 0.19, 0.035, [0.2, 0.005, 0.03], tone::SCREEN);
            ([0.28, 0.195, 0.17], 1.5)
        }
        C::Kettle => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.09, 0.2, c);
            cube(&mut p, 0.09, 0.05, 0.0, [0.03, 0.13, 0.02], tone::METAL);
            cube(&mut p, -0.1, 0.12, 0.0, [0.04, 0.02, 0.02], c);
            ([0.24, 0.2, 0.18], 1.0)
        }
        C::Microwave => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.48, 0.28, 0.36], c);
            cube(&mut p, -0.06, 0.04, -0.181, [0.3, 0.2, 0.002], tone::SCREEN);
            ([0.48, 0.28, 0.362], 12.0)
        }
        C::Candle => {
            let h = r(rng, 0.08, 0.2);
            cyl(&mut p, 0.0, 0.0, 0.0, 0.035, h, c);
            ([0.07, h, 0.07], 0.2)
        }
        C::PictureFrame => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.2, 0.26, 0.02], c);
            cube(
                &mut p,
                0.0,
                0.03,
                -0.011,
                [0.16, 0.2, 0.002],
                palette::fabric(rng),
            );
            cube(&mut p, 0.0, 0.0, 0.05, [0.03, 0.18, 0.08], c);
            ([0.2, 0.26, 0.12], 0.4)
        }
        C::Towel => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.3, 0.06, 0.2], c);
            ([0.3, 0.06, 0.2], 0.4)
        }
        C::SoapDispenser => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.035, 0.13, c);
            cyl(&mut p, 0.0, 0.13, 0.0, 0.01, 0.04, tone::STEEL);
            ([0.07, 0.17, 0.07], 0.3)
        }
        C::FruitBowl => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.12, 0.06, c);
            let fruit = [tone::FRUIT_RED, tone::FRUIT_YELLOW, tone::FRUIT_ORANGE];
            for (i, rgb) in fruit.into_iter().enumerate() {
                let a = i as f32 * 2.1;
                cube(
                    &mut p,
                    a.cos() * 0.05,
                    0.05,
                    a.sin() * 0.05,
                    [0.07, 0.06, 0.07],
                    rgb,
                );
            }
            ([0.24, 0.11, 0.24], 1.2)
        }
        C::Teapot => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.08, 0.13, c);
            cube(&mut p, 0.1, 0.04, 0.0, [0.06, 0.025, 0.025], c);
            cube(&mut p, -0.095, 0.03, 0.0, [0.03, 0.08, 0.02], c);
            ([0.26, 0.13, 0.16], 0.9)
        }
        C::Pot => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.11, 0.14, c);
            cube(&mut p, 0.0, 0.1, 0.0, [0.3, 0.025, 0.03], tone::METAL);
            ([0.3, 0.14, 0.22], 1.6)
        }
        C::Pan => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.13, 0.045, c);
            cube(&mut p, 0.21, 0.03, 0.0, [0.18, 0.02, 0.03], tone::METAL);
            ([0.44, 0.05, 0.26], 1.2)
        }
        C::CuttingBoard => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.38, 0.02, 0.26], c);
            ([0.38, 0.02, 0.26], 1.0)
        }
        C::CoffeeMachine => {
            cube(&mut p, 0.0, 0.0, 0.02, [0.24, 0.36, 0.26], c);
            cube(&mut p, 0.0, 0.0, -0.13, [0.2, 0.03, 0.06], shade(c, 0.6));
            cube(&mut p, 0.0, 0.28, -0.13, [0.24, 0.08, 0.06], c);
            ([0.24, 0.36, 0.32], 5.0)
        }
        C::Blender => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.16, 0.12, 0.16], c);
            cyl(&mut p, 0.0, 0.12, 0.0, 0.065, 0.24, tone::GLASS);
            ([0.16, 0.36, 0.16], 2.5)
        }
        C::DishRack => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.42, 0.03, 0.3], c);
            for i in 0..4 {
                let x = -0.15 + 0.1 * i as f32;
                cube(&mut p, x, 0.03, 0.02, [0.015, 0.2, 0.22], tone::WHITE);
            }
            ([0.42, 0.23, 0.3], 1.5)
        }
        C::TissueBox => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.23, 0.09, 0.12], c);
            cube(&mut p, 0.0, 0.09, 0.0, [0.08, 0.03, 0.04], tone::WHITE);
            ([0.23, 0.12, 0.12], 0.2)
        }
        C::Basket => {
            let (w, d) = (r(rng, 0.25, 0.4), r(rng, 0.18, 0.28));
            bcube(&mut p, 0.0, 0.0, 0.0, [w, 0.16, d], 0.01, c);
            ([w, 0.16, d], 0.6)
        }
        C::Speaker => {
            let h = r(rng, 0.18, 0.32);
            cube(&mut p, 0.0, 0.0, 0.0, [0.14, h, 0.16], c);
            // The cone as a square grille: a box is 12 triangles, a disc 64.
            cube(
                &mut p,
                0.0,
                h * 0.4 - 0.045,
                -0.081,
                [0.09, 0.09, 0.004],
                tone::METAL,
            );
            ([0.14, h, 0.164], 2.0)
        }
        C::Phone => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.075, 0.01, 0.15], c);
            cube(&mut p, 0.0, 0.01, 0.0, [0.065, 0.002, 0.135], tone::SCREEN);
            ([0.075, 0.012, 0.15], 0.2)
        }
        C::Tablet => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.25, 0.01, 0.17], c);
            cube(&mut p, 0.0, 0.01, 0.0, [0.23, 0.002, 0.15], tone::SCREEN);
            ([0.25, 0.012, 0.17], 0.5)
        }
        C::Printer => {
            bcube(&mut p, 0.0, 0.0, 0.0, [0.42, 0.2, 0.34], 0.01, c);
            cube(&mut p, 0.0, 0.2, 0.08, [0.3, 0.06, 0.08], tone::LINEN);
            cube(&mut p, 0.0, 0.08, -0.2, [0.3, 0.015, 0.06], shade(c, 0.7));
            ([0.42, 0.26, 0.4], 6.0)
        }
        C::PenHolder => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.04, 0.1, c);
            cube(&mut p, 0.0, 0.1, 0.0, [0.02, 0.05, 0.02], tone::FRUIT_RED);
            ([0.08, 0.15, 0.08], 0.2)
        }
        C::Globe => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.14, 0.02, 0.14], tone::WOOD);
            cube(&mut p, 0.0, 0.02, 0.0, [0.02, 0.08, 0.02], tone::METAL);
            cyl(&mut p, 0.0, 0.1, 0.0, 0.13, 0.22, c);
            ([0.26, 0.32, 0.26], 1.0)
        }
        C::BoardGame => {
            let t = r(rng, 0.04, 0.07);
            cube(&mut p, 0.0, 0.0, 0.0, [0.4, t, 0.27], c);
            cube(&mut p, 0.0, t, 0.0, [0.3, 0.002, 0.18], tone::LINEN);
            ([0.4, t + 0.002, 0.27], 1.0)
        }
        C::Toy => {
            // A toy truck: body, cab, wheels.
            cube(&mut p, 0.0, 0.03, 0.0, [0.24, 0.08, 0.12], c);
            cube(
                &mut p,
                -0.08,
                0.11,
                0.0,
                [0.08, 0.07, 0.11],
                tone::FRUIT_YELLOW,
            );
            for sx in [-1.0, 1.0] {
                cube(&mut p, sx * 0.07, 0.0, 0.0, [0.05, 0.05, 0.14], tone::METAL);
            }
            ([0.24, 0.18, 0.14], 0.4)
        }
        C::JewelryBox => {
            bcube(&mut p, 0.0, 0.0, 0.0, [0.2, 0.09, 0.13], 0.008, c);
            cube(&mut p, 0.0, 0.09, 0.0, [0.2, 0.02, 0.13], shade(c, 0.8));
            ([0.2, 0.11, 0.13], 0.5)
        }
        C::ToiletPaper => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.055, 0.1, c);
            ([0.11, 0.1, 0.11], 0.1)
        }
        C::Shampoo => {
            let h = r(rng, 0.18, 0.24);
            cube(&mut p, 0.0, 0.0, 0.0, [0.08, h, 0.045], c);
            cube(&mut p, 0.0, h, 0.0, [0.03, 0.03, 0.03], tone::WHITE);
            ([0.08, h + 0.03, 0.045], 0.4)
        }
        C::ToothbrushHolder => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.035, 0.1, c);
            cube(
                &mut p,
                -0.01,
                0.1,
                0.0,
                [0.012, 0.08, 0.012],
                tone::FRUIT_RED,
            );
            cube(&mut p, 0.012, 0.1, 0.0, [0.012, 0.07, 0.012], tone::WHITE);
            ([0.07, 0.18, 0.07], 0.3)
        }
        C::Hairdryer => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.05, 0.14, 0.05], c);
            cube(&mut p, 0.03, 0.12, 0.0, [0.2, 0.08, 0.08], c);
            ([0.23, 0.2, 0.08], 0.6)
        }
        C::Magazine => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.21, 0.008, 0.28], c);
            ([0.21, 0.008, 0.28], 0.2)
        }
        C::Headphones => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.16, 0.03, 0.18], c);
            cube(&mut p, 0.0, 0.03, 0.0, [0.03, 0.05, 0.03], c);
            ([0.16, 0.08, 0.18], 0.3)
        }
        // Anything else becomes a plain box, so a caller can never get an empty model.
        _ => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.15, 0.15, 0.15], c);
            ([0.15, 0.15, 0.15], 0.5)
        }
    };
    Model::new(class, fin, size, mass, p).with_features(&features)
}

/// Floor clutter, wall objects and the larger pieces of the rooms issue 30 added (shoes,
/// laundry baskets, wall shelves, radiators, a fireplace, balcony furniture...). Mostly plain
/// boxes: a home holds many of them, and each box is 12 triangles (20 bevelled).
pub(crate) fn clutter(class: C, rng: &mut ChaCha8Rng) -> Model {
    if let Some(m) = crate::gear::model(class, rng) {
        return m;
    }
    let fin = palette::pick(class, rng);
    let c = fin.rgb;
    let dark = shade(c, 0.7);
    let mut p = Vec::new();
    let mut top = None;
    let (size, mass) = match class {
        C::Shoes => {
            for sx in [-1.0, 1.0] {
                cube(&mut p, sx * 0.06, 0.0, 0.0, [0.1, 0.1, 0.28], c);
            }
            ([0.22, 0.1, 0.28], 1.0)
        }
        C::Slippers => {
            for sx in [-1.0, 1.0] {
                cube(&mut p, sx * 0.06, 0.0, 0.0, [0.1, 0.06, 0.27], c);
            }
            ([0.22, 0.06, 0.27], 0.4)
        }
        C::LaundryBasket => {
            let h = r(rng, 0.4, 0.55);
            bcube(&mut p, 0.0, 0.0, 0.0, [0.5, h, 0.36], 0.02, c);
            cube(&mut p, 0.0, h, 0.0, [0.4, 0.05, 0.26], palette::fabric(rng));
            ([0.5, h + 0.05, 0.36], 2.0)
        }
        C::Box => {
            let (w, h, d) = (r(rng, 0.3, 0.6), r(rng, 0.25, 0.45), r(rng, 0.3, 0.45));
            cube(&mut p, 0.0, 0.0, 0.0, [w, h, d], c);
            cube(&mut p, 0.0, h, 0.0, [w, 0.004, 0.05], shade(c, 0.8));
            top = Some(0.03);
            ([w, h + 0.004, d], 3.0)
        }
        C::Backpack => {
            bcube(&mut p, 0.0, 0.0, 0.0, [0.3, 0.42, 0.18], 0.03, c);
            cube(&mut p, 0.0, 0.05, -0.11, [0.22, 0.18, 0.04], dark);
            ([0.3, 0.42, 0.22], 2.5)
        }
        C::UmbrellaStand => {
            cyl(&mut p, 0.0, 0.0, 0.0, 0.12, 0.5, c);
            cube(&mut p, 0.03, 0.5, 0.0, [0.03, 0.35, 0.03], tone::METAL);
            ([0.24, 0.85, 0.24], 3.0)
        }
        C::DogBed => {
            let (w, d) = (r(rng, 0.6, 0.9), r(rng, 0.5, 0.7));
            bcube(&mut p, 0.0, 0.0, 0.0, [w, 0.08, d], 0.015, c);
            cube(&mut p, 0.0, 0.08, d * 0.5 - 0.06, [w, 0.12, 0.12], dark);
            for sx in [-1.0, 1.0] {
                cube(
                    &mut p,
                    sx * (w * 0.5 - 0.06),
                    0.08,
                    0.0,
                    [0.12, 0.1, d - 0.12],
                    dark,
                );
            }
            ([w, 0.2, d], 2.0)
        }
        C::YogaMat => {
            let d = r(rng, 1.7, 1.85);
            cube(&mut p, 0.0, 0.0, 0.0, [0.61, 0.006, d], c);
            ([0.61, 0.006, d], 1.2)
        }
        C::Dumbbells => {
            for sx in [-1.0, 1.0] {
                cube(&mut p, sx * 0.07, 0.0, 0.0, [0.09, 0.09, 0.3], tone::METAL);
            }
            ([0.23, 0.09, 0.3], 10.0)
        }
        C::Ottoman => {
            let (w, h) = (r(rng, 0.5, 0.8), r(rng, 0.38, 0.45));
            bcube(&mut p, 0.0, 0.0, 0.0, [w, h, w * 0.8], 0.03, c);
            top = Some(0.06);
            ([w, h, w * 0.8], 10.0)
        }
        C::BeanBag => {
            let s = r(rng, 0.7, 0.9);
            bcube(&mut p, 0.0, 0.0, 0.0, [s, 0.45, s], 0.1, c);
            bcube(&mut p, 0.0, 0.3, s * 0.25, [s * 0.8, 0.3, s * 0.4], 0.06, c);
            ([s, 0.6, s], 4.0)
        }
        C::Chest => {
            let (w, h, d) = (r(rng, 0.8, 1.1), r(rng, 0.45, 0.55), r(rng, 0.42, 0.5));
            bcube(&mut p, 0.0, 0.0, 0.0, [w, h - 0.06, d], 0.015, c);
            bcube(
                &mut p,
                0.0,
                h - 0.06,
                0.0,
                [w + 0.02, 0.06, d + 0.02],
                0.012,
                dark,
            );
            front(
                &mut p,
                d,
                [0.0, h - 0.16, -0.006],
                [0.08, 0.06, 0.012],
                tone::STEEL,
            );
            top = Some(0.05);
            ([w + 0.02, h, d + 0.02], 25.0)
        }
        C::Vanity => {
            let (w, d) = (r(rng, 0.8, 1.1), 0.45);
            let h = 0.76;
            bcube(&mut p, 0.0, h - 0.04, 0.0, [w, 0.04, d], 0.008, c);
            for sx in [-1.0, 1.0] {
                cube(
                    &mut p,
                    sx * (w * 0.5 - 0.18),
                    0.0,
                    0.0,
                    [0.34, h - 0.04, d - 0.02],
                    c,
                );
                front(
                    &mut p,
                    d,
                    [sx * (w * 0.5 - 0.18), h * 0.5, -0.005],
                    [0.1, 0.02, 0.01],
                    tone::STEEL,
                );
            }
            top = Some(0.04);
            ([w, h, d], 25.0)
        }
        C::FilingCabinet => {
            let (w, h, d) = (0.45, r(rng, 0.7, 1.3), 0.6);
            bcube(&mut p, 0.0, 0.0, 0.0, [w, h, d], 0.01, c);
            let n = (h / 0.32) as usize;
            for i in 0..n {
                let y = 0.05 + i as f32 * (h - 0.05) / n as f32;
                front(
                    &mut p,
                    d,
                    [0.0, y + 0.08, -0.004],
                    [0.14, 0.025, 0.012],
                    tone::STEEL,
                );
            }
            top = Some(0.04);
            ([w, h, d], 30.0)
        }
        C::WallShelf => {
            let w = r(rng, 0.6, 1.1);
            let y = r(rng, 1.1, 1.4);
            bcube(&mut p, 0.0, y, 0.0, [w, 0.03, 0.22], 0.005, c);
            for sx in [-1.0, 1.0] {
                cube(
                    &mut p,
                    sx * (w * 0.5 - 0.08),
                    y - 0.12,
                    0.09,
                    [0.02, 0.12, 0.04],
                    tone::METAL,
                );
            }
            top = Some(0.02);
            ([w, y + 0.03, 0.22], 3.0)
        }
        C::Mirror => {
            let (w, h) = (r(rng, 0.45, 0.8), r(rng, 0.55, 0.8));
            let y = 1.05;
            cube(&mut p, 0.0, y, 0.0, [w, h, 0.025], c);
            cube(
                &mut p,
                0.0,
                y + 0.03,
                -0.013,
                [w - 0.06, h - 0.06, 0.002],
                tone::GLASS,
            );
            ([w, y + h, 0.027], 4.0)
        }
        C::TowelRack => {
            let w = r(rng, 0.5, 0.7);
            let y = r(rng, 0.9, 1.1);
            for sx in [-1.0, 1.0] {
                cube(
                    &mut p,
                    sx * w * 0.5,
                    y,
                    0.06,
                    [0.03, 0.04, 0.06],
                    tone::STEEL,
                );
            }
            cube(&mut p, 0.0, y + 0.01, 0.02, [w, 0.02, 0.02], tone::STEEL);
            cube(
                &mut p,
                0.0,
                y - 0.35,
                0.0,
                [w * 0.8, 0.38, 0.05],
                palette::pick(C::Towel, rng).rgb,
            );
            ([w + 0.03, y + 0.04, 0.09], 2.0)
        }
        C::Radiator => {
            let w = r(rng, 0.6, 1.2);
            // One block for the fins: a radiator in most rooms would otherwise cost 12
            // triangles a fin.
            cube(&mut p, 0.0, 0.12, 0.05, [w, 0.06, 0.06], c);
            cube(&mut p, 0.0, 0.12, 0.0, [w - 0.05, 0.5, 0.08], c);
            ([w, 0.62, 0.1], 15.0)
        }
        C::Fan => {
            let h = r(rng, 1.0, 1.3);
            cube(&mut p, 0.0, 0.0, 0.0, [0.36, 0.03, 0.36], c);
            cube(&mut p, 0.0, 0.03, 0.0, [0.04, h - 0.4, 0.04], c);
            disc_z(&mut p, [0.0, h - 0.2, 0.0], 0.2, 0.12, c);
            ([0.4, h, 0.36], 5.0)
        }
        C::Heater => {
            bcube(&mut p, 0.0, 0.0, 0.0, [0.45, 0.6, 0.2], 0.02, c);
            front(
                &mut p,
                0.2,
                [0.0, 0.35, -0.003],
                [0.3, 0.18, 0.006],
                tone::METAL,
            );
            ([0.45, 0.6, 0.2], 6.0)
        }
        C::Fireplace => {
            let w = r(rng, 1.2, 1.6);
            bcube(&mut p, 0.0, 0.0, 0.0, [w, 1.05, 0.4], 0.02, c);
            front(
                &mut p,
                0.4,
                [0.0, 0.12, -0.002],
                [w * 0.55, 0.6, 0.004],
                tone::SOOT,
            );
            front(
                &mut p,
                0.4,
                [0.0, 0.14, -0.004],
                [w * 0.35, 0.14, 0.004],
                tone::FRUIT_ORANGE,
            );
            bcube(&mut p, 0.0, 1.05, 0.0, [w + 0.1, 0.05, 0.45], 0.01, dark);
            top = Some(0.04);
            ([w + 0.1, 1.1, 0.45], 150.0)
        }
        C::Aquarium => {
            let w = r(rng, 0.8, 1.2);
            bcube(&mut p, 0.0, 0.0, 0.0, [w, 0.75, 0.4], 0.015, c);
            cube(&mut p, 0.0, 0.75, 0.0, [w, 0.45, 0.38], tone::WATER);
            cube(&mut p, 0.0, 1.2, 0.0, [w, 0.04, 0.4], tone::METAL);
            ([w, 1.24, 0.4], 120.0)
        }
        C::Treadmill => {
            bcube(&mut p, 0.0, 0.0, 0.0, [0.75, 0.18, 1.8], 0.03, c);
            cube(&mut p, 0.0, 0.18, 0.0, [0.5, 0.01, 1.5], tone::SCREEN);
            for sx in [-1.0, 1.0] {
                cube(
                    &mut p,
                    sx * 0.34,
                    0.18,
                    -0.75,
                    [0.05, 1.1, 0.06],
                    tone::METAL,
                );
            }
            cube(&mut p, 0.0, 1.2, -0.78, [0.75, 0.12, 0.2], c);
            ([0.75, 1.32, 1.8], 80.0)
        }
        C::ExerciseBike => {
            bcube(&mut p, 0.0, 0.0, 0.0, [0.5, 0.06, 1.0], 0.012, tone::METAL);
            cube(&mut p, 0.0, 0.06, -0.25, [0.06, 0.9, 0.06], c);
            cube(&mut p, 0.0, 0.06, 0.2, [0.06, 0.8, 0.06], c);
            cube(&mut p, 0.0, 0.2, -0.2, [0.08, 0.45, 0.45], c);
            cube(&mut p, 0.0, 0.86, 0.2, [0.22, 0.06, 0.3], tone::METAL);
            cube(&mut p, 0.0, 0.96, -0.3, [0.45, 0.04, 0.08], tone::METAL);
            ([0.5, 1.0, 1.0], 35.0)
        }
        C::Bicycle => {
            // Seen side on from the front: frame along z, wheels as thin discs.
            for z in [-0.55, 0.55] {
                turned(
                    &mut p,
                    Shape::Cylinder {
                        radius: 0.34,
                        half_height: 0.02,
                    },
                    [0.0, 0.34, z],
                    Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
                    tone::SOOT,
                );
            }
            cube(&mut p, 0.0, 0.55, 0.0, [0.04, 0.04, 1.0], c);
            cube(&mut p, 0.0, 0.34, 0.2, [0.04, 0.45, 0.04], c);
            cube(&mut p, 0.0, 0.8, 0.2, [0.1, 0.05, 0.22], tone::SOOT);
            cube(&mut p, 0.0, 0.9, -0.5, [0.5, 0.03, 0.03], tone::METAL);
            ([0.5, 0.93, 1.78], 12.0)
        }
        C::IroningBoard => {
            bcube(&mut p, 0.0, 0.85, 0.0, [1.2, 0.03, 0.36], 0.006, c);
            for sx in [-1.0, 1.0] {
                cube(&mut p, sx * 0.3, 0.0, 0.0, [0.03, 0.85, 0.3], tone::METAL);
            }
            top = Some(0.05);
            ([1.2, 0.88, 0.36], 6.0)
        }
        C::DryingRack => {
            for sx in [-1.0, 1.0] {
                cube(&mut p, sx * 0.42, 0.0, 0.0, [0.03, 0.95, 0.5], tone::STEEL);
            }
            for i in 0..5 {
                let z = -0.2 + 0.1 * i as f32;
                cube(&mut p, 0.0, 0.9, z, [0.84, 0.015, 0.015], tone::STEEL);
            }
            cube(
                &mut p,
                -0.1,
                0.45,
                0.0,
                [0.35, 0.45, 0.02],
                palette::fabric(rng),
            );
            ([0.87, 0.95, 0.5], 3.0)
        }
        C::Crib => {
            let (w, d, h) = (1.25, 0.68, 0.95);
            bcube(
                &mut p,
                0.0,
                0.3,
                0.0,
                [w - 0.06, 0.12, d - 0.06],
                0.02,
                tone::LINEN,
            );
            for sx in [-1.0, 1.0] {
                cube(&mut p, sx * (w - 0.04) * 0.5, 0.0, 0.0, [0.04, h, d], c);
            }
            for sz in [-1.0, 1.0] {
                cube(
                    &mut p,
                    0.0,
                    0.25,
                    sz * (d - 0.03) * 0.5,
                    [w - 0.08, 0.04, 0.03],
                    c,
                );
                cube(
                    &mut p,
                    0.0,
                    h - 0.04,
                    sz * (d - 0.03) * 0.5,
                    [w - 0.08, 0.04, 0.03],
                    c,
                );
            }
            ([w, h, d], 20.0)
        }
        C::HighChair => {
            legs(&mut p, 0.5, 0.55, 0.55, 0.04, c);
            bcube(&mut p, 0.0, 0.55, 0.0, [0.4, 0.05, 0.4], 0.01, c);
            cube(&mut p, 0.0, 0.6, 0.18, [0.38, 0.45, 0.04], c);
            cube(&mut p, 0.0, 0.78, -0.2, [0.42, 0.03, 0.18], tone::WHITE);
            ([0.5, 1.05, 0.55], 7.0)
        }
        C::PatioChair => {
            legs(&mut p, 0.5, 0.5, 0.42, 0.04, c);
            bcube(&mut p, 0.0, 0.42, 0.0, [0.5, 0.04, 0.5], 0.008, c);
            cube(&mut p, 0.0, 0.46, 0.23, [0.5, 0.45, 0.04], c);
            ([0.5, 0.91, 0.5], 4.0)
        }
        C::PatioTable => {
            let w = r(rng, 0.6, 0.9);
            legs(&mut p, w - 0.1, w - 0.1, 0.7, 0.04, c);
            bcube(&mut p, 0.0, 0.7, 0.0, [w, 0.03, w], 0.006, c);
            top = Some(0.04);
            ([w, 0.73, w], 8.0)
        }
        C::Planter => {
            let w = r(rng, 0.6, 1.0);
            bcube(&mut p, 0.0, 0.0, 0.0, [w, 0.4, 0.3], 0.02, c);
            cube(&mut p, 0.0, 0.4, 0.0, [w - 0.08, 0.25, 0.22], tone::LEAF);
            ([w, 0.65, 0.3], 25.0)
        }
        C::ClothesRail => {
            let w = r(rng, 0.9, 1.3);
            for sx in [-1.0, 1.0] {
                cube(
                    &mut p,
                    sx * w * 0.5,
                    0.0,
                    0.0,
                    [0.03, 1.6, 0.45],
                    tone::STEEL,
                );
            }
            cube(&mut p, 0.0, 1.55, 0.0, [w, 0.025, 0.025], tone::STEEL);
            let n = 4 + (w / 0.3) as usize;
            for i in 0..n {
                let x = -w * 0.5 + 0.1 + i as f32 * (w - 0.2) / (n - 1) as f32;
                cube(
                    &mut p,
                    x,
                    0.75,
                    0.0,
                    [0.04, 0.78, 0.4],
                    palette::fabric(rng),
                );
            }
            ([w + 0.03, 1.6, 0.45], 12.0)
        }
        C::ShelvingUnit => {
            let (w, h, d) = (r(rng, 0.8, 1.2), r(rng, 1.4, 1.8), 0.4);
            for sx in [-1.0, 1.0] {
                cube(
                    &mut p,
                    sx * (w - 0.03) * 0.5,
                    0.0,
                    0.0,
                    [0.03, h, d],
                    tone::STEEL,
                );
            }
            for i in 0..4 {
                let y = 0.1 + i as f32 * (h - 0.13) / 3.0;
                bcube(&mut p, 0.0, y, 0.0, [w - 0.06, 0.03, d], 0.005, c);
            }
            top = Some(0.03);
            ([w, h + 0.03, d], 20.0)
        }
        // Anything else becomes a plain box, so a caller can never get an empty model.
        _ => {
            cube(&mut p, 0.0, 0.0, 0.0, [0.4, 0.4, 0.4], c);
            ([0.4, 0.4, 0.4], 5.0)
        }
    };
    let m = Model::new(class, fin, size, mass, p);
    match top {
        Some(inset) => m.with_top(inset),
        None => m,
    }
}

/// Shift the parts so that their x/z extent is centred on the origin and record the exact
/// footprint (small objects are built by eye, this keeps their placement exact).
fn recentre(m: &mut Model) {
    let mut lo = Vec3::splat(f32::INFINITY);
    let mut hi = Vec3::splat(f32::NEG_INFINITY);
    for part in &m.parts {
        for c in vlnverse_env::geometry::shape_corners(&part.shape) {
            let q = part.transform.transform_point(c);
            lo = lo.min(q);
            hi = hi.max(q);
        }
    }
    let shift = Vec3::new((lo.x + hi.x) * 0.5, 0.0, (lo.z + hi.z) * 0.5);
    for part in &mut m.parts {
        let p = Vec3::from_array(part.transform.position) - shift;
        part.transform.position = p.to_array();
    }
    m.w = hi.x - lo.x;
    m.h = hi.y.max(0.0);
    m.d = hi.z - lo.z;
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngCore, SeedableRng};
    use vlnverse_env::occupancy::{build_maps, OccupancyConfig, OccupancyMaps};
    use vlnverse_env::{Scene, SceneObject, SCENE_FORMAT_VERSION};

    type Build = (&'static str, fn(&mut ChaCha8Rng) -> Model);

    /// Every furniture builder (small objects have no variants).
    const BUILDERS: &[Build] = &[
        ("double bed", |g| bed(g, true)),
        ("single bed", |g| bed(g, false)),
        ("nightstand", nightstand),
        ("wardrobe", wardrobe),
        ("dresser", dresser),
        ("toilet", toilet),
        ("sink", sink),
        ("bathtub", bathtub),
        ("shower", shower),
        ("fridge", fridge),
        ("counter", |g| counter(g, 1.3)),
        ("stove", stove),
        ("dishwasher", dishwasher),
        ("kitchen cabinet", kitchen_cabinet),
        ("sofa 2", |g| sofa(g, 1.5)),
        ("sofa 3", |g| sofa(g, 2.2)),
        ("armchair", armchair),
        ("tv", |g| tv(g, 1.2)),
        ("tv stand", tv_stand),
        ("coffee table", coffee_table),
        // The room chooses a dining table's size.
        ("dining table", |g| {
            let (w, d) = (r(g, 1.2, 1.8), r(g, 0.8, 1.0));
            dining_table(g, w, d)
        }),
        ("small dining table", |g| dining_table(g, 0.9, 0.8)),
        ("side table", side_table),
        ("desk", desk),
        ("chair", chair),
        ("office chair", office_chair),
        ("bookshelf", bookshelf),
        ("potted plant", potted_plant),
        ("floor lamp", floor_lamp),
        ("cabinet", cabinet),
        ("shoe rack", shoe_rack),
        ("coat rack", coat_rack),
        ("washing machine", washing_machine),
        ("piano", piano),
        ("bench", bench),
        ("stool", stool),
        ("trash can", trash_can),
    ];

    /// Build with variant `force` (None: the hashed one); also the rng's next draw.
    fn build(b: fn(&mut ChaCha8Rng) -> Model, seed: u64, force: Option<usize>) -> (Model, u64) {
        FORCE_VARIANT.with(|f| f.set(force));
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let m = b(&mut rng);
        FORCE_VARIANT.with(|f| f.set(None));
        (m, rng.next_u64())
    }

    /// What instructions read of a model: its largest part's shape kind and colour.
    fn largest(m: &Model) -> (std::mem::Discriminant<Shape>, [u32; 3]) {
        let p = m
            .parts
            .iter()
            .max_by(|a, b| {
                a.shape
                    .nominal_volume()
                    .total_cmp(&b.shape.nominal_volume())
            })
            .expect("a model has parts");
        (std::mem::discriminant(&p.shape), p.color.map(f32::to_bits))
    }

    /// The model on a floor at the four quarter turns homes use (a box is rounded from the parts
    /// that make its faces, differently at each turn), and the maps of that scene.
    fn placed(m: &Model) -> Vec<(Vec<[u32; 3]>, OccupancyMaps)> {
        let poses = [
            Pose::from_yaw(Vec3::new(0.013, 0.0, 0.027), 0.0),
            Pose::from_yaw(Vec3::new(0.31, 0.0, -0.44), std::f32::consts::FRAC_PI_2),
            Pose::from_yaw(Vec3::new(5.68, 0.0, -1.87), std::f32::consts::PI),
            Pose::from_yaw(Vec3::new(-3.1, 0.0, 2.2), -std::f32::consts::FRAC_PI_2),
        ];
        poses
            .iter()
            .map(|pose| {
                let mut floor = Vec::new();
                cube(&mut floor, 0.0, -0.05, 0.0, [6.0, 0.05, 6.0], tone::WHITE);
                let objects = vec![
                    SceneObject::from_parts(0, C::Floor, Pose::IDENTITY, floor),
                    SceneObject::from_parts(1, m.class, *pose, m.parts.clone()),
                ];
                let bbox = objects[1].bbox;
                let bits = vec![bbox.min.map(f32::to_bits), bbox.max.map(f32::to_bits)];
                let scene = Scene {
                    format_version: SCENE_FORMAT_VERSION,
                    id: "variant".into(),
                    source: "test".into(),
                    seed: None,
                    floor_height: 0.0,
                    rooms: Vec::new(),
                    doors: Vec::new(),
                    objects,
                    storeys: Default::default(),
                };
                let maps = build_maps(&scene, &OccupancyConfig::default()).expect("maps");
                (bits, maps)
            })
            .collect()
    }

    #[test]
    fn variants_keep_everything_episodes_read() {
        for &(name, b) in BUILDERS {
            for seed in 0..24 {
                let (base, base_next) = build(b, seed, Some(0));
                let base_maps = placed(&base);
                let (hashed, _) = build(b, seed, None);
                let mut hashed_is_a_variant = false;
                for k in 0..variants(name) {
                    let (m, next) = build(b, seed, Some(k));
                    let what = format!("{name}, seed {seed}, variant {k}");
                    hashed_is_a_variant |= m.parts == hashed.parts;
                    assert_eq!(next, base_next, "{what}: rng draws");
                    assert_eq!(m.class, base.class, "{what}");
                    assert_eq!(m.finish, base.finish, "{what}");
                    assert_eq!(m.mass.to_bits(), base.mass.to_bits(), "{what}");
                    let size = |m: &Model| [m.w, m.h, m.d].map(f32::to_bits);
                    assert_eq!(size(&m), size(&base), "{what}: measured size");
                    assert_eq!(m.top, base.top, "{what}: top");
                    assert_eq!(largest(&m), largest(&base), "{what}: largest part");
                    let maps = placed(&m);
                    for (i, (got, want)) in maps.iter().zip(&base_maps).enumerate() {
                        assert_eq!(got.0, want.0, "{what}, pose {i}: bbox");
                        assert!(got.1 == want.1, "{what}, pose {i}: occupancy maps differ");
                    }
                    for p in &m.parts {
                        if let Shape::Cuboid {
                            half_extents: h,
                            bevel,
                        } = p.shape
                        {
                            let min = h[0].min(h[1]).min(h[2]);
                            assert!(bevel <= 0.45 * min, "{what}: bevel {bevel} on {h:?}");
                        }
                    }
                }
                assert!(hashed_is_a_variant, "{name}, seed {seed}");
            }
        }
    }

    /// The builders with variants and how many each has (the others have one).
    const VARIANTS: &[(&str, usize)] = &[
        ("double bed", 16),
        ("single bed", 16),
        ("nightstand", 3),
        ("wardrobe", 4),
        ("dresser", 12),
        ("sofa 2", 24),
        ("sofa 3", 24),
        ("armchair", 8),
        ("coffee table", 4),
        ("dining table", 4),
        ("small dining table", 4),
        ("kitchen cabinet", 2),
        ("side table", 4),
        ("chair", 8),
        ("potted plant", 6),
        ("floor lamp", 3),
    ];

    fn variants(name: &str) -> usize {
        VARIANTS.iter().find(|v| v.0 == name).map_or(1, |v| v.1)
    }

    #[test]
    fn furniture_classes_have_visibly_different_variants() {
        // Two of each size are alike: the double bed and sofa stand for the single ones.
        for &(name, n) in VARIANTS
            .iter()
            .filter(|v| !matches!(v.0, "single bed" | "sofa 2" | "small dining table"))
        {
            let b = BUILDERS.iter().find(|x| x.0 == name).expect(name).1;
            let mut layouts: Vec<Vec<Part>> = Vec::new();
            for k in 0..n {
                let parts = build(b, 7, Some(k)).0.parts;
                assert!(!layouts.contains(&parts), "{name}: variant {k} repeats one");
                layouts.push(parts);
            }
            // The hash spreads real models over the variants.
            let mut seen = vec![0; n];
            for seed in 0..200 {
                let parts = build(b, seed, None).0.parts;
                let k = (0..n).find(|&k| build(b, seed, Some(k)).0.parts == parts);
                seen[k.expect("the hashed model is one of the variants")] += 1;
            }
            assert!(seen.iter().all(|c| *c > 200 / n / 3), "{name}: {seen:?}");
        }
    }

    /// A whole home with variants against the same seed built with the first variant of every
    /// model: same objects (class, box, colour, material, mass, support), same maps.
    #[test]
    fn homes_with_variants_match_homes_without() {
        let cfg = crate::Preset::Tiny.config().expect("tiny preset");
        for seed in 0..3 {
            FORCE_VARIANT.with(|f| f.set(Some(0)));
            let plain = crate::home::generate(&cfg, seed, "plain");
            FORCE_VARIANT.with(|f| f.set(None));
            let plain = plain.expect("home");
            let varied = crate::home::generate(&cfg, seed, "plain").expect("home");
            assert_eq!(plain.objects.len(), varied.objects.len(), "seed {seed}");
            let mut differ = 0;
            for (a, b) in plain.objects.iter().zip(&varied.objects) {
                let what = format!("seed {seed}, object {} ({:?})", a.id, a.class);
                assert_eq!(a.class, b.class, "{what}");
                assert_eq!(a.bbox, b.bbox, "{what}");
                assert_eq!(a.pose, b.pose, "{what}");
                assert_eq!((&a.color, &a.material), (&b.color, &b.material), "{what}");
                assert_eq!(a.physics, b.physics, "{what}");
                assert_eq!(a.supported_by, b.supported_by, "{what}");
                differ += usize::from(a.parts != b.parts);
            }
            assert!(differ > 0, "seed {seed}: no object got another variant");
            let cfg = OccupancyConfig::default();
            let (pm, vm) = (build_maps(&plain, &cfg), build_maps(&varied, &cfg));
            assert!(pm.expect("maps") == vm.expect("maps"), "seed {seed}: maps");
        }
    }
}
