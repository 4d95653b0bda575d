//! What framed canvases show: one procedural picture per subject ([`Surface::is_picture`]),
//! drawn once over the whole canvas (not tiled) in grey tones that the canvas colour tints.
//! Each is built from a few simple shapes so that the subject reads at the size a painting
//! has in a camera frame: a sailboat is a hull, a mast and two white sails over the sea.
//!
//! Coordinates are texels, `x` to the right and `y` down, over a [`TEX_SIZE`] square.

use super::{fbm, hash01, Surface, TEX_SIZE};

/// A point in texel coordinates.
type P = (f32, f32);

/// The grey value (0 black, 1 white) of picture `s` at texel `(x, y)`; `None` for a surface
/// that is not a picture.
pub(super) fn texel(s: Surface, seed: u32, x: usize, y: usize) -> Option<f32> {
    let p = (x as f32 + 0.5, y as f32 + 0.5);
    let v = match s {
        Surface::PaintingSailboat => sailboat(p),
        Surface::PaintingBeach => beach(p),
        Surface::PaintingLake => lake(p),
        Surface::PaintingFlowers => flowers(p),
        Surface::PaintingTree => tree(seed, p),
        Surface::PaintingCircles => circles(p),
        Surface::PaintingSquares => squares(p),
        Surface::PaintingPortrait => portrait(p),
        Surface::PaintingHorse => horse(p),
        Surface::PaintingZebra => zebra(p),
        Surface::PaintingHouse => house(p),
        Surface::PaintingGiraffe => giraffe(p),
        Surface::PaintingElephant => elephant(p),
        Surface::PaintingMountains => mountains(p),
        Surface::PaintingOcean => ocean(p),
        Surface::PaintingWaterfall => waterfall(p),
        Surface::PaintingCity => city(p),
        Surface::PaintingLighthouse => lighthouse(p),
        Surface::PaintingWindmill => windmill(p),
        Surface::PaintingBarn => barn(p),
        Surface::PaintingNightSky => night_sky(p),
        Surface::PaintingFruit => fruit(p),
        Surface::PaintingLion => lion(p),
        Surface::PaintingCow => cow(p),
        Surface::PaintingBirds => birds(p),
        Surface::PaintingFish => fish(p),
        Surface::PaintingCat => cat(p),
        Surface::PaintingDog => dog(p),
        Surface::PaintingButterfly => butterfly(p),
        Surface::PaintingSunflowers => sunflowers(p),
        Surface::PaintingBridge => bridge(p),
        Surface::PaintingShip => ship(p),
        Surface::PaintingWoman => woman(p),
        Surface::PaintingMan => man(p),
        Surface::PaintingCheetah => cheetah(p),
        _ => return None,
    };
    // Brush strokes: faint, horizontal-ish.
    Some(v + 0.04 * fbm(seed ^ 0x51, p.0, p.1 * 0.3, 8.0))
}

/// Whether `p` lies in the ellipse centred at `c` with radii `r`.
fn ellipse(p: P, c: P, r: P) -> bool {
    let (dx, dy) = ((p.0 - c.0) / r.0, (p.1 - c.1) / r.1);
    dx * dx + dy * dy <= 1.0
}

/// Whether `p` lies in the circle centred at `c` of radius `r`.
fn circle(p: P, c: P, r: f32) -> bool {
    ellipse(p, c, (r, r))
}

/// Whether `p` lies in the axis-aligned rectangle from `a` to `b`.
fn rect(p: P, a: P, b: P) -> bool {
    (a.0..b.0).contains(&p.0) && (a.1..b.1).contains(&p.1)
}

/// Whether `p` lies in the triangle `a b c` (either winding).
fn tri(p: P, a: P, b: P, c: P) -> bool {
    let side = |u: P, v: P| (v.0 - u.0) * (p.1 - u.1) - (v.1 - u.1) * (p.0 - u.0);
    let (d1, d2, d3) = (side(a, b), side(b, c), side(c, a));
    let neg = d1 < 0.0 || d2 < 0.0 || d3 < 0.0;
    let pos = d1 > 0.0 || d2 > 0.0 || d3 > 0.0;
    !(neg && pos)
}

/// Whether `p` lies within `r` of the segment `a b` (a stroke of width `2 r`).
fn stroke(p: P, a: P, b: P, r: f32) -> bool {
    let (vx, vy) = (b.0 - a.0, b.1 - a.1);
    let len2 = (vx * vx + vy * vy).max(1e-6);
    let t = (((p.0 - a.0) * vx + (p.1 - a.1) * vy) / len2).clamp(0.0, 1.0);
    let (dx, dy) = (p.0 - a.0 - t * vx, p.1 - a.1 - t * vy);
    dx * dx + dy * dy <= r * r
}

/// The triangle `a b c` shrunk by `k` (0..1) towards its centroid.
fn shrink(a: P, b: P, c: P, k: f32) -> (P, P, P) {
    let m = ((a.0 + b.0 + c.0) / 3.0, (a.1 + b.1 + c.1) / 3.0);
    let s = |v: P| (m.0 + (v.0 - m.0) * k, m.1 + (v.1 - m.1) * k);
    (s(a), s(b), s(c))
}

/// A white triangular sail with a dark edge.
fn sail(p: P, a: P, b: P, c: P) -> Option<f32> {
    if !tri(p, a, b, c) {
        return None;
    }
    let (i, j, k) = shrink(a, b, c, 0.88);
    Some(if tri(p, i, j, k) { 1.0 } else { 0.3 })
}

/// A sailboat on the sea under a sun: a dark hull, a mast, a white mainsail and jib.
fn sailboat(p: P) -> f32 {
    let (x, y) = p;
    let horizon = 80.0;
    if let Some(v) = sail(p, (66.0, 16.0), (66.0, 70.0), (98.0, 70.0)) {
        return v;
    }
    if let Some(v) = sail(p, (61.0, 24.0), (61.0, 70.0), (36.0, 70.0)) {
        return v;
    }
    if rect(p, (62.0, 12.0), (65.0, 72.0)) {
        return 0.18;
    }
    // The hull: a trapezoid narrowing to the keel.
    if (70.0..82.0).contains(&y) {
        let k = (y - 70.0) * 0.9;
        if (30.0 + k..104.0 - k).contains(&x) {
            return if y < 73.0 { 0.55 } else { 0.15 };
        }
    }
    if circle(p, (104.0, 26.0), 9.0) {
        return 1.0;
    }
    if y >= horizon {
        // Waves: bright crests on darker water, the hull's shadow below it.
        let crest =
            ((x * 0.35 + (y * 0.9).sin() * 3.0).sin() * 0.5 + 0.5) * ((y * 1.7).sin() * 0.5 + 0.5);
        let shadow = if (34.0..100.0).contains(&x) && y < 90.0 {
            -0.12
        } else {
            0.0
        };
        return 0.42 + 0.16 * crest - 0.08 * (y - horizon) / 48.0 + shadow;
    }
    0.9 - 0.2 * (y / horizon)
}

/// A beach at sunset: a half sun on the horizon, its path on the sea, sand and a palm tree.
fn beach(p: P) -> f32 {
    let (x, y) = p;
    let horizon = 62.0;
    // The palm: a leaning trunk and drooping fronds, dark against the light.
    let crown = (30.0, 40.0);
    let trunk = stroke(p, (18.0, 124.0), (24.0, 84.0), 3.0) || stroke(p, (24.0, 84.0), crown, 2.5);
    let fronds = [
        (8.0, 50.0),
        (12.0, 36.0),
        (26.0, 28.0),
        (46.0, 32.0),
        (52.0, 46.0),
        (44.0, 54.0),
    ];
    if trunk || fronds.iter().any(|&f| stroke(p, crown, f, 2.2)) {
        return 0.12;
    }
    let shore = 96.0 + 4.0 * (x * 0.06).sin();
    if y >= shore {
        return 0.8 - 0.1 * ((y - shore) / 32.0);
    }
    if y >= horizon {
        // The sun's path: bright dashes narrowing towards the shore.
        let half = 16.0 * (1.0 - (y - horizon) / 40.0).max(0.1);
        let dash = (y as i32) % 4 < 2 && (x - 64.0).abs() < half;
        let foam = y > shore - 3.0;
        return if dash || foam {
            0.95
        } else {
            0.38 + 0.04 * (x * 0.5 + y).sin()
        };
    }
    if circle(p, (64.0, horizon), 20.0) {
        return 1.0;
    }
    // A glowing sky, brightest at the horizon, with two bands of cloud.
    let cloud = (y - 22.0).abs() < 2.5 || ((y - 36.0).abs() < 2.0 && x > 70.0);
    (if cloud { 0.45 } else { 0.55 }) + 0.4 * (y / horizon)
}

/// A lake under snow-capped mountains, the mountains mirrored in the water.
fn lake(p: P) -> f32 {
    let (x, y) = p;
    let shore = 74.0;
    if y > 112.0 {
        return 0.5;
    }
    if y >= shore {
        let mirrored = (x, 2.0 * shore - y);
        let ripple = if (y as i32) % 5 == 0 { 0.08 } else { 0.0 };
        return 0.85 * land(mirrored) + ripple;
    }
    land(p)
}

/// Sky, two mountains with snow on their peaks and a dark tree line (the lake's upper half).
fn land(p: P) -> f32 {
    let (x, y) = p;
    let shore = 74.0;
    if y > shore - 6.0 + 2.0 * (x * 0.7).sin().abs() {
        return 0.25;
    }
    for (peak, half, base) in [((40.0, 18.0), 46.0, shore), ((92.0, 28.0), 40.0, shore)] {
        let (px, py) = peak;
        if y >= py {
            let w = half * (y - py) / (base - py);
            if (x - px).abs() <= w {
                if y < py + 12.0 + 3.0 * (x * 0.5).sin() {
                    return 0.96;
                }
                return if x < px { 0.5 } else { 0.34 };
            }
        }
    }
    0.92 - 0.2 * (y / shore)
}

/// Flowers in a vase on a table: petalled heads on stems, a dark round vase.
fn flowers(p: P) -> f32 {
    let (x, y) = p;
    let heads: [P; 6] = [
        (64.0, 26.0),
        (42.0, 38.0),
        (86.0, 36.0),
        (50.0, 56.0),
        (80.0, 56.0),
        (65.0, 45.0),
    ];
    for (i, &c) in heads.iter().enumerate() {
        let (dx, dy) = (x - c.0, y - c.1);
        let r = (dx * dx + dy * dy).sqrt();
        let petals = 5.0 + (i % 2) as f32;
        let edge = 9.0 * (0.6 + 0.4 * (petals * dy.atan2(dx)).cos().abs());
        if r < 3.2 {
            return 0.2;
        }
        if r < edge {
            return 0.98;
        }
    }
    if ellipse(p, (64.0, 94.0), (17.0, 16.0)) || rect(p, (57.0, 70.0), (71.0, 82.0)) {
        // A highlight down the vase's left side.
        return if (51.0..54.0).contains(&x) && y > 86.0 {
            0.55
        } else {
            0.22
        };
    }
    let stem = heads.iter().any(|&c| stroke(p, (64.0, 72.0), c, 1.3));
    let leaf = ellipse(p, (54.0, 66.0), (7.0, 3.0)) || ellipse(p, (75.0, 64.0), (7.0, 3.0));
    if stem || leaf {
        return 0.32;
    }
    if y > 108.0 {
        return 0.45;
    }
    0.74
}

/// A tree in a field: a round leafy crown on a trunk, the horizon low behind it.
fn tree(seed: u32, p: P) -> f32 {
    let (x, y) = p;
    let crown = [
        ((64.0, 40.0), 26.0),
        ((42.0, 52.0), 18.0),
        ((86.0, 52.0), 18.0),
        ((64.0, 22.0), 17.0),
    ];
    if crown.iter().any(|&(c, r)| circle(p, c, r)) {
        let dark = crown.iter().any(|&(c, r)| circle(p, c, r - 2.0));
        return if dark {
            0.36 + 0.2 * fbm(seed ^ 0x7ee, x, y, 4.0)
        } else {
            0.2
        };
    }
    let trunk_half = 4.0 + (y - 60.0).max(0.0) * 0.08;
    if y > 55.0 && y < 104.0 && (x - 64.0).abs() < trunk_half {
        return 0.2;
    }
    if y > 98.0 {
        return 0.55 + 0.08 * ((x * 0.9).sin() * (y * 1.3).cos());
    }
    0.93 - 0.2 * (y / 98.0)
}

/// Abstract art: overlapping discs and a ring in flat tones.
fn circles(p: P) -> f32 {
    let (dx, dy) = (p.0 - 92.0, p.1 - 30.0);
    let r = (dx * dx + dy * dy).sqrt();
    if (r - 15.0).abs() < 2.5 {
        return 0.12;
    }
    if circle(p, (58.0, 96.0), 16.0) {
        return 1.0;
    }
    if circle(p, (30.0, 104.0), 10.0) {
        return 0.45;
    }
    if circle(p, (82.0, 74.0), 30.0) {
        return 0.62;
    }
    if circle(p, (42.0, 48.0), 28.0) {
        return 0.24;
    }
    0.88
}

/// Abstract art: blocks of flat tone between thick black lines.
fn squares(p: P) -> f32 {
    let (x, y) = p;
    let line = |v: f32, at: f32| (v - at).abs() < 2.5;
    if line(x, 40.0)
        || line(y, 86.0)
        || (line(x, 92.0) && y > 34.0)
        || (line(y, 34.0) && x > 40.0)
        || (line(y, 60.0) && x < 40.0)
    {
        return 0.08;
    }
    match (x < 40.0, x > 92.0, y < 34.0, y > 86.0) {
        (true, _, _, false) if y < 60.0 => 0.3,
        (true, _, _, false) => 0.92,
        (_, true, _, true) => 0.55,
        (false, false, false, false) => 0.97,
        (true, _, _, true) => 0.72,
        (_, _, true, _) => 0.85,
        _ => 0.4,
    }
}

/// A portrait: head and shoulders against a dark ground, hair, eyes, nose and mouth.
fn portrait(p: P) -> f32 {
    let (x, y) = p;
    if ellipse(p, (56.0, 54.0), (3.2, 2.0)) || ellipse(p, (72.0, 54.0), (3.2, 2.0)) {
        return 0.12;
    }
    if stroke(p, (52.0, 49.0), (60.0, 48.5), 0.9) || stroke(p, (68.0, 48.5), (76.0, 49.0), 0.9) {
        return 0.2;
    }
    if ellipse(p, (64.0, 69.0), (6.5, 1.7)) {
        return 0.42;
    }
    if stroke(p, (64.0, 56.0), (62.0, 63.0), 0.9) {
        return 0.62;
    }
    let head = ellipse(p, (64.0, 54.0), (18.0, 24.0));
    if head && y > 40.0 {
        return 0.86;
    }
    if ellipse(p, (64.0, 48.0), (22.0, 28.0)) && y < 66.0 {
        return 0.18;
    }
    if head {
        return 0.86;
    }
    if rect(p, (57.0, 74.0), (71.0, 94.0)) {
        return 0.8;
    }
    if ellipse(p, (64.0, 134.0), (46.0, 42.0)) {
        // A collar's V.
        return if (x - 64.0).abs() < (y - 90.0) * 0.4 && y < 106.0 {
            0.8
        } else {
            0.3
        };
    }
    0.45 + 0.2 * (1.0 - y / TEX_SIZE as f32)
}

/// A horse's silhouette, facing right, standing on the ground line at `y` = 106.
fn horse_shape(p: P) -> bool {
    ellipse(p, (60.0, 66.0), (30.0, 14.0))
        || stroke(p, (80.0, 62.0), (93.0, 38.0), 7.5)
        || stroke(p, (94.0, 36.0), (107.0, 49.0), 5.5)
        || tri(p, (90.0, 32.0), (94.0, 22.0), (97.0, 33.0))
        || stroke(p, (82.0, 72.0), (85.0, 105.0), 3.0)
        || stroke(p, (75.0, 72.0), (72.0, 105.0), 3.0)
        || stroke(p, (40.0, 72.0), (37.0, 105.0), 3.3)
        || stroke(p, (47.0, 72.0), (51.0, 105.0), 3.0)
        || stroke(p, (32.0, 60.0), (22.0, 88.0), 2.6)
}

/// Sky and a grassy ground line behind an animal.
fn field(p: P) -> f32 {
    let (x, y) = p;
    if y > 104.0 {
        return 0.6 + 0.08 * ((x * 1.1).sin() * (y * 0.8).cos());
    }
    0.92 - 0.2 * (y / 104.0)
}

/// A dark horse standing in a field.
fn horse(p: P) -> f32 {
    if horse_shape(p) {
        // A lighter blaze down the face.
        return if stroke(p, (97.0, 39.0), (105.0, 47.0), 1.2) {
            0.6
        } else {
            0.16
        };
    }
    field(p)
}

/// A zebra standing in a field: the horse's shape, outlined, in black and white stripes.
fn zebra(p: P) -> f32 {
    let (x, y) = p;
    if !horse_shape(p) {
        return field(p);
    }
    let edge = [(-1.6, 0.0), (1.6, 0.0), (0.0, -1.6), (0.0, 1.6)]
        .iter()
        .any(|&(dx, dy)| !horse_shape((x + dx, y + dy)));
    if edge {
        return 0.08;
    }
    // Stripes across the body, bending on the neck and legs.
    let phase = if x > 78.0 {
        y * 0.45 + x * 0.2
    } else {
        x * 0.5 + 3.0 * (y * 0.12).sin()
    };
    if phase.rem_euclid(std::f32::consts::TAU) < 2.6 {
        0.08
    } else {
        0.97
    }
}

/// A house on a lawn: light walls under a dark pitched roof, a chimney, a door and two
/// windows with crossed bars.
fn house(p: P) -> f32 {
    let (x, y) = p;
    if rect(p, (80.0, 36.0), (88.0, 56.0)) {
        return 0.3;
    }
    if tri(p, (26.0, 64.0), (64.0, 32.0), (102.0, 64.0)) {
        return 0.24;
    }
    if rect(p, (34.0, 64.0), (94.0, 104.0)) {
        if rect(p, (58.0, 80.0), (70.0, 104.0)) {
            return if (66.0..68.0).contains(&x) && (91.0..93.0).contains(&y) {
                0.85
            } else {
                0.3
            };
        }
        for wx in [40.0, 76.0] {
            if rect(p, (wx, 72.0), (wx + 12.0, 84.0)) {
                let bar = (x - wx - 6.0).abs() < 0.8 || (y - 78.0).abs() < 0.8;
                return if bar { 0.85 } else { 0.35 };
            }
        }
        return 0.86;
    }
    if y > 102.0 {
        // A path from the door.
        let half = 6.0 + (y - 104.0) * 0.4;
        return if (x - 64.0).abs() < half {
            0.78
        } else {
            0.52 + 0.06 * (x * 1.3).sin() * (y * 0.9).cos()
        };
    }
    0.93 - 0.2 * (y / 102.0)
}

/// A giraffe's silhouette, facing right: a long neck rising from a short body on long legs.
fn giraffe_shape(p: P) -> bool {
    ellipse(p, (56.0, 68.0), (22.0, 11.0))
        || stroke(p, (70.0, 64.0), (90.0, 24.0), 5.0)
        || ellipse(p, (97.0, 21.0), (9.0, 4.5))
        || stroke(p, (90.0, 17.0), (89.0, 10.0), 1.2)
        || stroke(p, (94.0, 17.0), (94.0, 10.0), 1.2)
        || stroke(p, (40.0, 74.0), (37.0, 110.0), 2.6)
        || stroke(p, (47.0, 76.0), (50.0, 110.0), 2.6)
        || stroke(p, (66.0, 76.0), (64.0, 110.0), 2.6)
        || stroke(p, (72.0, 74.0), (76.0, 110.0), 2.6)
        || stroke(p, (35.0, 64.0), (29.0, 84.0), 1.3)
}

/// A giraffe on the savanna: its coat dark patches between light lines.
fn giraffe(p: P) -> f32 {
    let (x, y) = p;
    if giraffe_shape(p) {
        let row = (y / 9.0).floor();
        let shift = if row as i32 % 2 == 0 { 0.0 } else { 4.5 };
        let (u, v) = ((x + shift).rem_euclid(9.0), y.rem_euclid(9.0));
        let line = u < 1.8 || v < 1.8;
        return if line { 0.88 } else { 0.34 };
    }
    if y > 108.0 {
        return 0.66 + 0.06 * ((x * 1.1).sin() * (y * 0.8).cos());
    }
    // A flat-topped tree far off on the left.
    if ellipse(p, (18.0, 60.0), (14.0, 4.0)) || rect(p, (16.5, 60.0), (19.5, 108.0)) {
        return 0.3;
    }
    0.92 - 0.18 * (y / 108.0)
}

/// An elephant facing right: a big grey body, a dark-edged ear, a trunk and a white tusk.
fn elephant(p: P) -> f32 {
    if stroke(p, (97.0, 71.0), (108.0, 77.0), 1.6) {
        return 0.95;
    }
    if ellipse(p, (84.0, 58.0), (10.0, 14.0)) {
        return if ellipse(p, (84.0, 58.0), (8.0, 12.0)) {
            0.36
        } else {
            0.16
        };
    }
    if circle(p, (97.0, 52.0), 1.8) {
        return 0.1;
    }
    let body = ellipse(p, (58.0, 66.0), (31.0, 21.0))
        || circle(p, (92.0, 58.0), 14.0)
        || stroke(p, (102.0, 62.0), (106.0, 88.0), 4.0)
        || stroke(p, (106.0, 88.0), (100.0, 98.0), 3.0)
        || rect(p, (34.0, 76.0), (45.0, 106.0))
        || rect(p, (49.0, 78.0), (60.0, 106.0))
        || rect(p, (68.0, 78.0), (79.0, 106.0))
        || rect(p, (81.0, 74.0), (90.0, 106.0))
        || stroke(p, (28.0, 60.0), (24.0, 80.0), 1.3);
    if body {
        return 0.46;
    }
    field(p)
}

/// A sky brightening from the top towards a horizon at `h` (texels down).
fn sky(y: f32, h: f32) -> f32 {
    0.92 - 0.2 * (y / h).min(1.0)
}

/// Snowy mountains: a tall peak in front of two lower, hazier ones, snow on their tops, one
/// side in shadow, a dark pine forest along their foot.
fn mountains(p: P) -> f32 {
    let (x, y) = p;
    for k in 0..10 {
        let cx = 2.0 + k as f32 * 14.0;
        let top = 90.0 + ((k * 7) % 5) as f32 * 3.0;
        if tri(p, (cx, top), (cx - 8.0, 118.0), (cx + 8.0, 118.0))
            || rect(p, (cx - 1.0, 116.0), (cx + 1.0, 122.0))
        {
            return 0.14;
        }
    }
    if y > 112.0 {
        return 0.3;
    }
    // (apex, half width at the foot, haze): the front peak first.
    for (apex, half, haze) in [
        ((62.0, 12.0), 60.0, 0.0),
        ((22.0, 40.0), 42.0, 0.14),
        ((108.0, 32.0), 44.0, 0.14),
    ] {
        let (px, py) = apex;
        if y < py || (x - px).abs() > half * (y - py) / (112.0 - py) {
            continue;
        }
        let snow = y - py < 18.0 + 5.0 * (x * 0.55).sin() + 3.0 * (x * 1.3).cos();
        let lit = x < px + 2.0 * (y * 0.4).sin();
        return haze
            + match (snow, lit) {
                (true, true) => 0.97,
                (true, false) => 0.8,
                (false, true) => 0.48,
                (false, false) => 0.3,
            };
    }
    sky(y, 112.0)
}

/// Ocean waves: rows of breaking waves under a pale sky, taller towards the viewer, each a
/// dark swell under a white crest of foam.
fn ocean(p: P) -> f32 {
    let (x, y) = p;
    let horizon = 34.0;
    if y < horizon {
        // Two gulls.
        let gull = |c: P| {
            stroke(p, (c.0 - 6.0, c.1 - 2.0), c, 0.8) || stroke(p, c, (c.0 + 6.0, c.1 - 2.0), 0.8)
        };
        if gull((30.0, 14.0)) || gull((48.0, 22.0)) {
            return 0.25;
        }
        return 0.94 - 0.12 * y / horizon;
    }
    // (crest line at rest, height, wavelength factor); a texel belongs to the last row whose
    // crest is above it.
    let rows = [
        (38.0, 1.5, 0.3),
        (46.0, 2.5, 0.24),
        (58.0, 4.0, 0.17),
        (74.0, 6.5, 0.12),
        (96.0, 10.0, 0.085),
    ];
    let mut tone = 0.5 - 0.1 * (y - horizon) / 94.0;
    for (k, &(base, height, f)) in rows.iter().enumerate() {
        let s = (x * f + k as f32 * 1.9).sin();
        // Peaked crests: the swell rises slowly and drops sharply.
        let crest = base - height * (0.5 + 0.5 * s).powf(2.0);
        if y >= crest {
            let d = y - crest;
            let foam = 1.0 + 0.35 * height;
            tone = if d < foam {
                0.96
            } else if d < foam + 1.5 && (x * 0.9 + y).sin() > 0.2 {
                0.8
            } else {
                0.48 - 0.02 * d.min(12.0) + 0.04 * (x * 0.7 + d).sin()
            };
        }
    }
    tone
}

/// A waterfall: white water falling between dark cliffs into a pool of foam, trees on the
/// cliff tops.
fn waterfall(p: P) -> f32 {
    let (x, y) = p;
    let (left, right) = (
        46.0 + 3.0 * (y * 0.2).sin(),
        80.0 + 3.0 * (y * 0.17 + 1.0).sin(),
    );
    let top = 24.0;
    // Mist and foam at the foot of the falls, the pool below.
    if ellipse(p, (63.0, 100.0), (30.0, 7.0)) {
        return 0.95 - 0.1 * ((x * 0.8).sin() * 0.5 + 0.5);
    }
    if y > 100.0 {
        if y > 118.0 {
            return 0.26;
        }
        let ripple = if (x * 0.3 + y * 1.7).sin() > 0.7 {
            0.15
        } else {
            0.0
        };
        return 0.45 + ripple;
    }
    if y > top && (left..right).contains(&x) {
        // Falling water: bright vertical streaks.
        let streak = ((x * 1.1).sin() * 0.5 + 0.5) * ((x * 0.37 + 2.0).sin() * 0.5 + 0.5);
        return 0.8 + 0.18 * streak;
    }
    // The river above the lip, seen running towards the edge.
    if (top - 6.0..=top).contains(&y) && (left - 2.0..right + 2.0).contains(&x) {
        return 0.75;
    }
    // Trees on the cliff tops: round dark crowns.
    let crowns = [
        (8.0, 20.0),
        (20.0, 16.0),
        (34.0, 19.0),
        (94.0, 18.0),
        (108.0, 14.0),
        (122.0, 19.0),
    ];
    if crowns.iter().any(|&c| circle(p, c, 8.0)) {
        return 0.18;
    }
    if y > 20.0 {
        // Rock: ledges of two tones.
        let ledge = ((y + 4.0 * (x * 0.15).sin()) * 0.25).sin() > 0.6;
        return if ledge { 0.4 } else { 0.28 };
    }
    sky(y, 24.0)
}

/// A city skyline: towers of different heights with lit windows against an evening sky.
fn city(p: P) -> f32 {
    let (x, y) = p;
    // (left, right, top) of each building.
    let buildings: [(f32, f32, f32); 10] = [
        (0.0, 14.0, 62.0),
        (14.0, 30.0, 42.0),
        (30.0, 40.0, 70.0),
        (40.0, 56.0, 24.0),
        (56.0, 68.0, 52.0),
        (68.0, 84.0, 34.0),
        (84.0, 94.0, 64.0),
        (94.0, 110.0, 30.0),
        (110.0, 120.0, 56.0),
        (120.0, 128.0, 46.0),
    ];
    // A spire on the tallest.
    if rect(p, (47.0, 6.0), (49.0, 24.0)) || tri(p, (43.0, 24.0), (48.0, 14.0), (53.0, 24.0)) {
        return 0.18;
    }
    if y > 112.0 {
        // The street.
        return 0.3;
    }
    for (i, &(l, r, t)) in buildings.iter().enumerate() {
        if (l..r).contains(&x) && y >= t {
            let (u, v) = (x - l, y - t);
            let window = u > 2.0
                && r - x > 2.0
                && u.rem_euclid(5.0) < 2.5
                && v > 3.0
                && v.rem_euclid(6.0) < 3.0;
            if window {
                let lit = hash01(0xc17, (u / 5.0) as usize + i * 31, (v / 6.0) as usize) < 0.6;
                return if lit { 0.9 } else { 0.32 };
            }
            return if i % 2 == 0 { 0.16 } else { 0.24 };
        }
    }
    0.55 + 0.35 * (y / 112.0)
}

/// A lighthouse: a tapering striped tower with a lantern throwing two beams, on rocks by the sea.
fn lighthouse(p: P) -> f32 {
    let (x, y) = p;
    if tri(p, (52.0, 20.0), (64.0, 8.0), (76.0, 20.0)) || rect(p, (50.0, 30.0), (78.0, 34.0)) {
        return 0.15;
    }
    if rect(p, (56.0, 20.0), (72.0, 30.0)) {
        return if (x - 64.0).abs() < 1.0 { 0.3 } else { 1.0 };
    }
    if (34.0..100.0).contains(&y) {
        let half = 7.0 + (y - 34.0) * 0.12;
        if (x - 64.0).abs() < half {
            let band = ((y - 34.0) / 11.0) as i32 % 2 == 0;
            let door = rect(p, (61.0, 88.0), (67.0, 100.0));
            return if door {
                0.12
            } else if band {
                0.95
            } else {
                0.2
            };
        }
    }
    if ellipse(p, (64.0, 104.0), (36.0, 9.0)) || ellipse(p, (30.0, 106.0), (16.0, 6.0)) {
        return 0.26;
    }
    if y > 100.0 {
        let crest = (x * 0.4 + (y * 1.3).sin() * 2.0).sin() > 0.75;
        return if crest { 0.75 } else { 0.42 };
    }
    // Beams from the lantern, lighter than the dusk sky.
    if tri(p, (64.0, 25.0), (0.0, 12.0), (0.0, 38.0))
        || tri(p, (64.0, 25.0), (128.0, 14.0), (128.0, 36.0))
    {
        return 0.9;
    }
    0.42 + 0.22 * (y / 100.0)
}

/// A windmill in a field: a tapering body with a door, a cap and four latticed sails.
fn windmill(p: P) -> f32 {
    let (x, y) = p;
    let hub = (64.0, 42.0);
    let (qx, qy) = (x - hub.0, y - hub.1);
    for k in 0..4 {
        let a = 0.4 + k as f32 * std::f32::consts::FRAC_PI_2;
        let (c, s) = (a.cos(), a.sin());
        let along = qx * c + qy * s;
        let across = -qx * s + qy * c;
        if (4.0..50.0).contains(&along) && across.abs() < 1.3 {
            return 0.12;
        }
        if (10.0..48.0).contains(&along) && (0.0..11.0).contains(&across) {
            let bar = along.rem_euclid(6.0) < 1.2 || across.rem_euclid(5.5) < 1.1;
            return if bar { 0.22 } else { 0.93 };
        }
    }
    if circle(p, hub, 3.5) {
        return 0.1;
    }
    if ellipse(p, (64.0, 44.0), (13.0, 9.0)) && y < 46.0 {
        return 0.24;
    }
    if (44.0..104.0).contains(&y) {
        let half = 10.0 + (y - 44.0) * 0.22;
        if (x - 64.0).abs() < half {
            if rect(p, (59.0, 90.0), (69.0, 104.0)) || circle(p, (64.0, 66.0), 3.5) {
                return 0.12;
            }
            return 0.62;
        }
    }
    if y > 100.0 {
        // Rows of a field running away from the viewer.
        let row = ((x - 64.0) / (y - 90.0) * 6.0).sin() > 0.3;
        return if row { 0.45 } else { 0.6 };
    }
    sky(y, 100.0)
}

/// A barn on a farm: a gambrel roof over board walls, a big door braced with an X, a hay-loft
/// door, a silo beside it and a fence in front.
fn barn(p: P) -> f32 {
    let (x, y) = p;
    let fence_rail = (101.0..103.0).contains(&y) || (107.0..109.0).contains(&y);
    let fence_post = (98.0..114.0).contains(&y) && x.rem_euclid(16.0) < 2.5;
    if fence_post || (fence_rail && !(44.0..84.0).contains(&x)) {
        return 0.95;
    }
    // The silo: a banded cylinder under a dome.
    if rect(p, (100.0, 40.0), (120.0, 110.0)) {
        return if (y as i32) % 10 < 1 {
            0.4
        } else {
            0.72 - 0.1 * ((x - 110.0) / 10.0).abs()
        };
    }
    if circle(p, (110.0, 40.0), 10.0) {
        return 0.5;
    }
    let roof = tri(p, (34.0, 42.0), (64.0, 28.0), (94.0, 42.0))
        || tri(p, (22.0, 64.0), (34.0, 42.0), (106.0, 64.0))
        || tri(p, (34.0, 42.0), (94.0, 42.0), (106.0, 64.0));
    if roof {
        return 0.18;
    }
    if rect(p, (28.0, 62.0), (100.0, 110.0)) {
        // The big door: a white frame and an X.
        if rect(p, (50.0, 76.0), (78.0, 110.0)) {
            let frame = !rect(p, (52.0, 78.0), (76.0, 110.0));
            let brace = stroke(p, (52.0, 78.0), (76.0, 110.0), 1.4)
                || stroke(p, (76.0, 78.0), (52.0, 110.0), 1.4);
            return if frame || brace { 0.95 } else { 0.3 };
        }
        if rect(p, (58.0, 62.0), (70.0, 72.0)) {
            return if rect(p, (60.0, 64.0), (68.0, 72.0)) {
                0.12
            } else {
                0.95
            };
        }
        let corner = !(30.0..98.0).contains(&x);
        return if corner {
            0.95
        } else if x.rem_euclid(6.0) < 0.8 {
            0.28
        } else {
            0.4
        };
    }
    if y > 108.0 {
        return 0.58 + 0.06 * ((x * 1.1).sin() * (y * 0.8).cos());
    }
    sky(y, 108.0)
}

/// A night sky: a crescent moon and stars over dark hills.
fn night_sky(p: P) -> f32 {
    let (x, y) = p;
    let hill = 98.0 + 7.0 * (x * 0.05).sin() + 3.0 * (x * 0.13 + 1.0).sin();
    if y > hill {
        return 0.08;
    }
    if circle(p, (88.0, 32.0), 16.0) && !circle(p, (96.0, 26.0), 14.0) {
        return 0.97;
    }
    let stars: [(f32, f32, f32); 16] = [
        (14.0, 14.0, 3.5),
        (34.0, 30.0, 2.0),
        (52.0, 12.0, 3.0),
        (22.0, 52.0, 2.5),
        (46.0, 46.0, 4.0),
        (66.0, 60.0, 2.0),
        (112.0, 12.0, 2.5),
        (116.0, 58.0, 3.0),
        (92.0, 70.0, 2.0),
        (8.0, 80.0, 2.0),
        (36.0, 76.0, 2.5),
        (72.0, 24.0, 1.8),
        (60.0, 84.0, 1.8),
        (104.0, 86.0, 2.0),
        (124.0, 36.0, 1.8),
        (84.0, 6.0, 2.0),
    ];
    for &(sx, sy, r) in &stars {
        let (dx, dy) = ((x - sx).abs(), (y - sy).abs());
        if (dx < 0.7 && dy < r) || (dy < 0.7 && dx < r) || dx + dy < r * 0.45 {
            return 0.95;
        }
    }
    0.16 + 0.16 * (y / 100.0)
}

/// A bowl of fruit on a table: apples with stems and shine, a bunch of bananas, a dark bowl.
fn fruit(p: P) -> f32 {
    let (x, y) = p;
    if y >= 84.0 && ellipse(p, (64.0, 84.0), (42.0, 22.0)) {
        return if y < 88.0 {
            0.55
        } else {
            0.26 + 0.08 * ((x - 40.0) / 50.0).clamp(0.0, 1.0)
        };
    }
    if rect(p, (52.0, 104.0), (76.0, 110.0)) {
        return 0.22;
    }
    // Two bananas lying across the front, curved like smiles, tapering to dark tips.
    for (k, c) in [(54.0, 54.0), (66.0, 50.0)].into_iter().enumerate() {
        let (dx, dy) = (x - c.0, y - c.1);
        let (r, a) = ((dx * dx + dy * dy).sqrt(), dx.atan2(dy));
        let t = 9.0 * (1.0 - (a / 1.15).powi(2));
        if dy > 0.0 && t > 0.0 && (28.0 - t..28.0).contains(&r) {
            let edge = r < 28.0 - t + 1.0 || r > 27.0 || a.abs() > 1.0;
            return if edge { 0.25 } else { 0.95 - 0.08 * k as f32 };
        }
    }
    let apples = [
        ((44.0, 74.0), 14.0),
        ((72.0, 70.0), 15.0),
        ((96.0, 80.0), 11.0),
    ];
    for &(c, r) in &apples {
        if stroke(p, (c.0, c.1 - r + 2.0), (c.0 + 2.0, c.1 - r - 5.0), 1.0) {
            return 0.15;
        }
        if ellipse(p, (c.0 + 6.0, c.1 - r - 2.0), (4.0, 1.8)) {
            return 0.35;
        }
        if circle(p, c, r) {
            return if circle(p, (c.0 - r * 0.4, c.1 - r * 0.4), r * 0.22) {
                0.97
            } else if circle(p, (c.0 - 1.0, c.1 - 1.0), r - 2.0) {
                0.62
            } else {
                0.42
            };
        }
    }
    if y > 96.0 {
        return if y < 99.0 { 0.62 } else { 0.5 };
    }
    0.78 - 0.1 * (y / 96.0)
}

/// A lion's head, seen from the front: a big shaggy mane round a light face, ears, eyes, a
/// dark nose over a white muzzle.
fn lion(p: P) -> f32 {
    let (x, y) = p;
    let c = (64.0, 62.0);
    if ellipse(p, (54.0, 56.0), (4.5, 2.8)) || ellipse(p, (74.0, 56.0), (4.5, 2.8)) {
        return if circle(p, (55.0, 55.5), 1.0) || circle(p, (75.0, 55.5), 1.0) {
            0.9
        } else {
            0.1
        };
    }
    if tri(p, (57.0, 70.0), (71.0, 70.0), (64.0, 79.0))
        || stroke(p, (64.0, 79.0), (64.0, 84.0), 0.8)
    {
        return 0.12;
    }
    if stroke(p, (46.0, 50.0), (58.0, 51.0), 1.0) || stroke(p, (70.0, 51.0), (82.0, 50.0), 1.0) {
        return 0.35;
    }
    if circle(p, (58.0, 85.0), 7.0) || circle(p, (70.0, 85.0), 7.0) {
        let dot = [(55.0, 84.0), (58.0, 88.0), (73.0, 84.0), (70.0, 88.0)]
            .iter()
            .any(|&d| circle(p, d, 0.9));
        return if dot { 0.3 } else { 0.95 };
    }
    if ellipse(p, (64.0, 95.0), (7.0, 4.0)) {
        return 0.85;
    }
    if ellipse(p, c, (25.0, 32.0)) {
        return 0.72;
    }
    for ear in [(40.0, 34.0), (88.0, 34.0)] {
        if circle(p, ear, 9.0) {
            return if circle(p, ear, 5.0) { 0.3 } else { 0.66 };
        }
    }
    let (dx, dy) = (x - c.0, y - c.1);
    let a = dy.atan2(dx);
    let r = (dx * dx + dy * dy).sqrt();
    if r < 50.0 + 6.0 * (a * 13.0).cos() {
        // Locks of the mane: light and dark strands.
        return 0.32 + 0.1 * (a * 31.0 + r * 0.15).sin();
    }
    if y > 112.0 {
        return 0.62;
    }
    sky(y, 112.0)
}

/// A cow grazing on a hill, facing left: white with black patches, horns, an udder and a tail.
fn cow(p: P) -> f32 {
    let (x, y) = p;
    let body = ellipse(p, (62.0, 64.0), (32.0, 15.0)) || rect(p, (36.0, 52.0), (88.0, 78.0));
    let head = ellipse(p, (22.0, 60.0), (9.0, 12.0));
    let muzzle = ellipse(p, (19.0, 71.0), (8.0, 5.5));
    let legs = [(36.0, 74.0), (46.0, 74.0), (76.0, 74.0), (84.0, 74.0)]
        .iter()
        .any(|&(lx, ly)| rect(p, (lx, ly), (lx + 6.0, 104.0)));
    let neck =
        tri(p, (26.0, 50.0), (40.0, 52.0), (30.0, 70.0)) || rect(p, (28.0, 52.0), (40.0, 66.0));
    if stroke(p, (17.0, 50.0), (9.0, 42.0), 1.5) || stroke(p, (27.0, 50.0), (35.0, 42.0), 1.5) {
        return 0.9;
    }
    if ellipse(p, (34.0, 54.0), (5.0, 2.5)) || ellipse(p, (9.0, 54.0), (5.0, 2.5)) {
        return 0.2;
    }
    if stroke(p, (92.0, 56.0), (98.0, 90.0), 1.3) || ellipse(p, (98.0, 92.0), (3.0, 4.0)) {
        return 0.15;
    }
    if ellipse(p, (66.0, 80.0), (7.0, 4.0)) {
        return 0.78;
    }
    if muzzle {
        return if circle(p, (15.0, 72.0), 1.3) || circle(p, (22.0, 72.0), 1.3) {
            0.2
        } else {
            0.7
        };
    }
    if head && (circle(p, (18.0, 58.0), 1.8) || circle(p, (27.0, 58.0), 1.8)) {
        return 0.08;
    }
    if body || head || legs || neck {
        if legs && y > 100.0 {
            return 0.15;
        }
        let patches = [
            ((50.0, 60.0), (12.0, 9.0)),
            ((76.0, 70.0), (9.0, 8.0)),
            ((70.0, 52.0), (7.0, 5.0)),
            ((88.0, 60.0), (5.0, 7.0)),
            ((38.0, 74.0), (6.0, 6.0)),
            ((24.0, 56.0), (5.0, 6.0)),
            ((82.0, 90.0), (5.0, 6.0)),
        ];
        return if patches.iter().any(|&(c, r)| ellipse(p, c, r)) {
            0.1
        } else {
            0.95
        };
    }
    let hill = 86.0 + 10.0 * (x * 0.02 + 0.5).sin();
    if y > hill {
        return 0.5 + 0.06 * ((x * 1.3).sin() * (y * 0.9).cos());
    }
    sky(y, hill)
}

/// A bird perched on a branch at `c`, facing right (`dir` 1) or left (-1): a round body with a
/// pale breast, a dark wing, a head with a beak and an eye, a tail.
fn bird(p: P, c: P, dir: f32) -> Option<f32> {
    let q = ((p.0 - c.0) * dir, p.1 - c.1);
    let o = (0.0, 0.0);
    if circle(q, (9.0, -13.0), 1.4) {
        return Some(0.98);
    }
    if tri(q, (13.0, -14.0), (22.0, -11.0), (13.0, -9.0)) {
        return Some(0.12);
    }
    if circle(q, (8.0, -12.0), 7.0) {
        return Some(0.32);
    }
    if ellipse(q, (-3.0, -2.0), (9.0, 5.5)) {
        return Some(0.18);
    }
    if ellipse(q, (4.0, 2.0), (7.0, 6.0)) {
        return Some(0.85);
    }
    if ellipse(q, o, (12.0, 9.0)) || tri(q, (-8.0, 2.0), (-24.0, 12.0), (-18.0, 16.0)) {
        return Some(0.32);
    }
    if stroke(q, (0.0, 8.0), (1.0, 13.0), 0.7) || stroke(q, (4.0, 8.0), (5.0, 13.0), 0.7) {
        return Some(0.15);
    }
    None
}

/// Two birds perched on a branch against the sky.
fn birds(p: P) -> f32 {
    let (x, y) = p;
    if let Some(v) = bird(p, (40.0, 68.0), 1.0).or_else(|| bird(p, (90.0, 60.0), -1.0)) {
        return v;
    }
    let branch_y = 82.0 - x * 0.1;
    if (y - branch_y).abs() < 3.0 || stroke(p, (96.0, 73.0), (124.0, 98.0), 1.8) {
        return 0.22;
    }
    let leaves = [
        (16.0, 90.0),
        (60.0, 88.0),
        (112.0, 90.0),
        (120.0, 100.0),
        (74.0, 70.0),
    ];
    if leaves.iter().any(|&c| ellipse(p, c, (6.0, 3.0))) {
        return 0.4;
    }
    0.9 - 0.15 * (y / 128.0)
}

/// A fish under water: a scaled body, a forked tail, fins, a big eye, bubbles and weed.
fn fish(p: P) -> f32 {
    let (x, y) = p;
    let c = (58.0, 62.0);
    for (b, r) in [
        ((20.0, 40.0), 3.0),
        ((16.0, 28.0), 2.4),
        ((22.0, 16.0), 2.0),
        ((104.0, 24.0), 2.4),
    ] {
        let (dx, dy) = (x - b.0, y - b.1);
        if ((dx * dx + dy * dy).sqrt() - r).abs() < 0.8 {
            return 0.95;
        }
    }
    if circle(p, (36.0, 57.0), 5.0) {
        return if circle(p, (37.0, 57.0), 2.6) {
            0.08
        } else {
            0.98
        };
    }
    let body = ellipse(p, c, (34.0, 19.0));
    if body {
        if !ellipse(p, c, (32.0, 17.0)) || stroke(p, (24.0, 67.0), (30.0, 66.0), 0.8) {
            return 0.15;
        }
        let (dx, dy) = (x - 45.0, y - c.1);
        if ((dx * dx + dy * dy).sqrt() - 15.0).abs() < 1.0 && x < 47.0 {
            return 0.35;
        }
        if x > 50.0 {
            // Scales: rows of arcs.
            let (u, v) = (
                (x + if ((y / 5.0) as i32) % 2 == 0 {
                    0.0
                } else {
                    3.0
                })
                .rem_euclid(6.0),
                y.rem_euclid(5.0),
            );
            if ((u - 3.0).powi(2) + (v - 1.0).powi(2)).sqrt() > 2.8 && v > 1.0 {
                return 0.6;
            }
        }
        return if y > c.1 + 6.0 { 0.95 } else { 0.82 };
    }
    let tail = tri(p, (88.0, 62.0), (114.0, 40.0), (114.0, 84.0))
        && !tri(p, (114.0, 52.0), (100.0, 62.0), (114.0, 72.0));
    let fins = tri(p, (46.0, 46.0), (72.0, 46.0), (64.0, 30.0))
        || tri(p, (56.0, 78.0), (70.0, 78.0), (66.0, 90.0));
    if tail || fins {
        return if ((x + y) * 0.8).sin() > 0.6 {
            0.45
        } else {
            0.7
        };
    }
    if y > 114.0 {
        return 0.66 + 0.06 * (x * 1.7).sin();
    }
    let weed = |bx: f32, h: f32| y > h && (x - bx - 4.0 * (y * 0.2).sin()).abs() < 2.0;
    if weed(10.0, 76.0) || weed(22.0, 90.0) || weed(116.0, 92.0) {
        return 0.22;
    }
    0.62 - 0.28 * (y / 128.0)
}

/// A black cat sitting, facing the viewer: pointed ears, light eyes with slit pupils,
/// whiskers, front paws and a curled tail.
fn cat(p: P) -> f32 {
    let (x, y) = p;
    for e in [(57.0, 46.0), (71.0, 46.0)] {
        if ellipse(p, e, (4.2, 3.0)) {
            return if ellipse(p, e, (1.0, 2.8)) { 0.1 } else { 0.88 };
        }
    }
    if tri(p, (61.0, 53.0), (67.0, 53.0), (64.0, 56.0)) {
        return 0.55;
    }
    let whisker = [(38.0, 50.0), (38.0, 57.0), (90.0, 50.0), (90.0, 57.0)]
        .iter()
        .any(|&(wx, wy)| {
            stroke(
                p,
                (if wx < 64.0 { 58.0 } else { 70.0 }, 56.0),
                (wx, wy),
                0.45,
            )
        });
    if whisker {
        return 0.85;
    }
    let ears = tri(p, (46.0, 42.0), (49.0, 18.0), (62.0, 32.0))
        || tri(p, (82.0, 42.0), (79.0, 18.0), (66.0, 32.0));
    if tri(p, (50.0, 36.0), (51.0, 24.0), (58.0, 32.0))
        || tri(p, (78.0, 36.0), (77.0, 24.0), (70.0, 32.0))
    {
        return 0.38;
    }
    let body = circle(p, (64.0, 46.0), 17.0)
        || ears
        || ellipse(p, (64.0, 86.0), (24.0, 27.0))
        || ellipse(p, (55.0, 110.0), (7.0, 4.0))
        || ellipse(p, (73.0, 110.0), (7.0, 4.0))
        || stroke(p, (84.0, 106.0), (102.0, 98.0), 3.5)
        || stroke(p, (102.0, 98.0), (104.0, 80.0), 3.5);
    if body {
        return 0.14;
    }
    if y > 108.0 {
        return 0.55;
    }
    // A window behind: light panes and a dark frame.
    if rect(p, (14.0, 14.0), (44.0, 60.0)) {
        let bar = (x - 29.0).abs() < 1.2
            || (y - 37.0).abs() < 1.2
            || !rect(p, (16.0, 16.0), (42.0, 58.0));
        return if bar { 0.4 } else { 0.95 };
    }
    0.72
}

/// A dog's head and shoulders, from the front: long floppy ears, a white muzzle, a big black
/// nose, a collar with a tag.
fn dog(p: P) -> f32 {
    let (x, y) = p;
    if circle(p, (54.0, 50.0), 3.6) || circle(p, (74.0, 50.0), 3.6) {
        return if circle(p, (55.0, 49.0), 1.1) || circle(p, (75.0, 49.0), 1.1) {
            0.95
        } else {
            0.08
        };
    }
    if ellipse(p, (64.0, 64.0), (6.5, 4.5)) {
        return if circle(p, (62.0, 62.5), 1.2) {
            0.6
        } else {
            0.06
        };
    }
    if stroke(p, (64.0, 68.0), (64.0, 74.0), 0.8)
        || stroke(p, (64.0, 74.0), (57.0, 77.0), 0.8)
        || stroke(p, (64.0, 74.0), (71.0, 77.0), 0.8)
    {
        return 0.2;
    }
    if ellipse(p, (64.0, 81.0), (4.0, 4.5)) && y > 77.0 {
        return 0.5;
    }
    if ellipse(p, (38.0, 64.0), (10.0, 24.0)) || ellipse(p, (90.0, 64.0), (10.0, 24.0)) {
        return 0.28;
    }
    if ellipse(p, (64.0, 72.0), (15.0, 11.0)) {
        return 0.92;
    }
    if ellipse(p, (64.0, 54.0), (24.0, 27.0)) {
        return 0.62;
    }
    if ellipse(p, (64.0, 122.0), (38.0, 34.0)) {
        if circle(p, (64.0, 101.0), 3.2) {
            return 0.95;
        }
        let collar = (y - 94.0 - 0.002 * (x - 64.0).powi(2)).abs() < 2.5;
        return if collar { 0.18 } else { 0.62 };
    }
    0.9 - 0.12 * (y / 128.0)
}

/// A butterfly with open wings: dark-edged wings with white spots and eye spots, a thin body
/// and two antennae.
fn butterfly(p: P) -> f32 {
    let (x, y) = p;
    if ellipse(p, (64.0, 66.0), (3.0, 24.0)) || circle(p, (64.0, 40.0), 4.5) {
        return 0.1;
    }
    if stroke(p, (63.0, 37.0), (52.0, 16.0), 0.7)
        || stroke(p, (65.0, 37.0), (76.0, 16.0), 0.7)
        || circle(p, (52.0, 16.0), 2.0)
        || circle(p, (76.0, 16.0), 2.0)
    {
        return 0.1;
    }
    let q = ((x - 64.0).abs(), y);
    let upper = ((26.0, 44.0), (27.0, 23.0));
    let lower = ((20.0, 84.0), (18.0, 19.0));
    for (c, r) in [upper, lower] {
        if !ellipse(q, c, r) || q.0 < 3.0 {
            continue;
        }
        let inner = ellipse(q, c, (r.0 - 5.0, r.1 - 5.0));
        if !inner {
            // White spots along the dark edge.
            let (dx, dy) = ((q.0 - c.0) / r.0, (q.1 - c.1) / r.1);
            let spot = (dy.atan2(dx) * 7.0).sin() > 0.7;
            return if spot { 0.95 } else { 0.1 };
        }
        let eye = (c.0 + 3.0, c.1 - 2.0);
        if circle(q, eye, 6.0) {
            return if circle(q, eye, 3.5) { 0.1 } else { 0.95 };
        }
        // Veins from the body.
        let ang = (q.1 - 64.0).atan2(q.0);
        if (ang * 9.0).sin().abs() < 0.08 {
            return 0.2;
        }
        return 0.58;
    }
    0.88 - 0.1 * (y / 128.0)
}

/// Three sunflowers: wide dark seed heads ringed by many petals, on tall stems with big leaves.
fn sunflowers(p: P) -> f32 {
    let (x, y) = p;
    let heads = [
        ((36.0, 44.0), 11.0),
        ((90.0, 32.0), 12.0),
        ((72.0, 82.0), 9.0),
    ];
    for &(c, r) in &heads {
        let (dx, dy) = (x - c.0, y - c.1);
        let d = (dx * dx + dy * dy).sqrt();
        if d < r {
            let seed = (x as i32 + y as i32) % 3 == 0;
            return if seed { 0.3 } else { 0.14 };
        }
        let petal = r * (1.45 + 0.55 * (dy.atan2(dx) * 8.0).cos().abs());
        if d < petal {
            return if d > petal - 1.5 { 0.6 } else { 0.95 };
        }
    }
    for &(c, r) in &heads {
        if (y > c.1 + r) && (x - c.0 - (y - c.1) * 0.05).abs() < 2.0 {
            return 0.3;
        }
    }
    let leaves = [
        ((26.0, 84.0), (12.0, 5.0)),
        ((48.0, 74.0), (10.0, 4.5)),
        ((104.0, 70.0), (12.0, 5.0)),
        ((82.0, 110.0), (10.0, 4.5)),
    ];
    for &(c, r) in &leaves {
        if ellipse(p, c, r) {
            return if (y - c.1).abs() < 0.7 { 0.5 } else { 0.34 };
        }
    }
    0.82 - 0.12 * (y / 128.0)
}

/// A suspension bridge over water: two towers, a sagging main cable with hangers, the deck,
/// and their reflection.
fn bridge(p: P) -> f32 {
    let (x, y) = p;
    let deck = 78.0;
    let water = 86.0;
    let tower = |x: f32| (26.0..34.0).contains(&x) || (94.0..102.0).contains(&x);
    if y >= water {
        // The towers' reflections, broken by ripples.
        let ripple = (y * 1.3 + (x * 0.2).sin()).sin() > 0.5;
        if tower(x) && y < 118.0 && !ripple {
            return 0.26;
        }
        return if ripple { 0.55 } else { 0.44 };
    }
    if tower(x) && y >= 14.0 {
        let gap = (36.0..42.0).contains(&y) || (58.0..64.0).contains(&y);
        return if gap && (29.0..31.0).contains(&x.rem_euclid(68.0)) {
            0.85
        } else {
            0.2
        };
    }
    if (deck..deck + 5.0).contains(&y) {
        return 0.16;
    }
    // The main cable sags between the towers' tops and runs down to the shores outside them.
    let cable = if (30.0..=98.0).contains(&x) {
        deck - 6.0 - (deck - 22.0) * ((x - 64.0) / 34.0).powi(2)
    } else {
        16.0 + ((x - 64.0).abs() - 34.0) / 30.0 * (deck - 16.0)
    };
    if (y - cable).abs() < 1.3 {
        return 0.12;
    }
    if y > cable && y < deck && x.rem_euclid(6.0) < 0.9 {
        return 0.35;
    }
    if y > 70.0 && !(18.0..=112.0).contains(&x) {
        // Hills at the two shores.
        return 0.36;
    }
    sky(y, water)
}

/// A big ship at sea: a long dark hull with portholes, white decks, two funnels with smoke.
fn ship(p: P) -> f32 {
    let (x, y) = p;
    let sea = 88.0;
    if (68.0..92.0).contains(&y) {
        let l = 14.0 + (y - 68.0) * 0.3;
        let r = 118.0 - (y - 68.0) * 0.8;
        if (l..r).contains(&x) {
            if (71.0..73.0).contains(&y) {
                return 0.92;
            }
            if (y - 78.0).abs() < 1.4 && x.rem_euclid(7.0) < 2.5 && x > 20.0 && x < 104.0 {
                return 0.85;
            }
            return 0.14;
        }
    }
    if rect(p, (30.0, 54.0), (94.0, 68.0)) || rect(p, (42.0, 44.0), (84.0, 54.0)) {
        let window =
            ((57.0..60.0).contains(&y) || (47.0..50.0).contains(&y)) && x.rem_euclid(5.0) < 2.5;
        return if window { 0.25 } else { 0.94 };
    }
    for fx in [50.0, 68.0] {
        if rect(p, (fx, 24.0), (fx + 10.0, 44.0)) {
            return if y < 30.0 { 0.1 } else { 0.5 };
        }
    }
    if stroke(p, (104.0, 68.0), (104.0, 38.0), 0.8) || stroke(p, (22.0, 68.0), (22.0, 46.0), 0.8) {
        return 0.2;
    }
    let smoke = [
        ((50.0, 17.0), 6.0),
        ((40.0, 12.0), 7.0),
        ((27.0, 10.0), 6.5),
        ((68.0, 18.0), 5.0),
        ((58.0, 12.0), 5.5),
    ];
    if smoke.iter().any(|&(c, r)| circle(p, c, r)) {
        return 0.62;
    }
    if y >= sea {
        let crest =
            ((x * 0.35 + (y * 0.9).sin() * 3.0).sin() * 0.5 + 0.5) * ((y * 1.7).sin() * 0.5 + 0.5);
        let shadow = if (20.0..110.0).contains(&x) && y < 98.0 {
            -0.12
        } else {
            0.0
        };
        return 0.46 + 0.18 * crest + shadow;
    }
    sky(y, sea)
}

/// A portrait of a woman: long dark hair falling past her shoulders, earrings, a necklace, a
/// dress, against a light ground.
fn woman(p: P) -> f32 {
    let (x, y) = p;
    if ellipse(p, (57.0, 54.0), (3.2, 1.9)) || ellipse(p, (71.0, 54.0), (3.2, 1.9)) {
        return 0.1;
    }
    if stroke(p, (53.0, 49.5), (60.0, 49.0), 0.7) || stroke(p, (68.0, 49.0), (75.0, 49.5), 0.7) {
        return 0.2;
    }
    if ellipse(p, (64.0, 68.0), (5.0, 2.0)) {
        return 0.35;
    }
    if stroke(p, (64.0, 56.0), (63.0, 62.0), 0.7) {
        return 0.62;
    }
    if circle(p, (47.5, 62.0), 1.8) || circle(p, (80.5, 62.0), 1.8) {
        return 0.98;
    }
    let face = ellipse(p, (64.0, 56.0), (16.0, 21.0));
    // The hair's parting and fringe over the forehead.
    if face && y > 42.0 - 4.0 * ((x - 64.0) / 16.0).abs() {
        return 0.86;
    }
    if ellipse(p, (64.0, 52.0), (26.0, 30.0))
        || (rect(p, (38.0, 52.0), (90.0, 100.0))
            && !rect(p, (52.0, 74.0), (76.0, 100.0))
            && ellipse(p, (64.0, 76.0), (26.0, 30.0)))
    {
        return 0.18 + 0.05 * (x * 0.9).sin();
    }
    if rect(p, (57.0, 72.0), (71.0, 90.0)) {
        return 0.84;
    }
    let (dx, dy) = (x - 64.0, y - 80.0);
    if ((dx * dx + dy * dy).sqrt() - 12.0).abs() < 1.0 && y > 84.0 && (x.rem_euclid(3.0) < 2.0) {
        return 0.98;
    }
    if ellipse(p, (64.0, 132.0), (44.0, 40.0)) {
        return if y < 96.0 { 0.84 } else { 0.46 };
    }
    0.85 - 0.1 * (y / 128.0)
}

/// A portrait of a man: short dark hair, a full beard and moustache, a dark suit with a white
/// shirt and a tie, against a dark ground.
fn man(p: P) -> f32 {
    let y = p.1;
    if ellipse(p, (57.0, 52.0), (3.0, 1.9)) || ellipse(p, (71.0, 52.0), (3.0, 1.9)) {
        return 0.1;
    }
    if stroke(p, (52.0, 47.0), (61.0, 46.0), 1.3) || stroke(p, (67.0, 46.0), (76.0, 47.0), 1.3) {
        return 0.14;
    }
    if stroke(p, (64.0, 54.0), (62.0, 61.0), 0.8) {
        return 0.6;
    }
    if ellipse(p, (64.0, 70.0), (5.0, 1.6)) {
        return 0.5;
    }
    if ellipse(p, (64.0, 66.0), (9.0, 2.8)) {
        return 0.14;
    }
    let head = ellipse(p, (64.0, 56.0), (17.0, 23.0));
    if head && y > 64.0 && ellipse(p, (64.0, 62.0), (18.0, 20.0)) {
        return 0.2;
    }
    if head && y > 38.0 {
        return 0.82;
    }
    if ellipse(p, (64.0, 44.0), (19.0, 14.0)) && y < 46.0 {
        return 0.12;
    }
    if head {
        return 0.82;
    }
    if tri(p, (61.0, 96.0), (67.0, 96.0), (64.0, 124.0)) {
        return 0.3;
    }
    if tri(p, (50.0, 92.0), (78.0, 92.0), (64.0, 126.0)) {
        return 0.95;
    }
    if rect(p, (57.0, 76.0), (71.0, 94.0)) {
        return 0.8;
    }
    if ellipse(p, (64.0, 136.0), (50.0, 42.0)) {
        let lapel = stroke(p, (52.0, 96.0), (60.0, 122.0), 0.8)
            || stroke(p, (76.0, 96.0), (68.0, 122.0), 0.8);
        return if lapel { 0.3 } else { 0.14 };
    }
    0.4 - 0.12 * (y / 128.0)
}

/// A cheetah's silhouette, facing right: a long body with a deep chest, a small round head,
/// long legs and a long tail.
fn cheetah_shape(p: P) -> bool {
    ellipse(p, (56.0, 60.0), (30.0, 13.0))
        || ellipse(p, (80.0, 62.0), (12.0, 14.0))
        || stroke(p, (84.0, 58.0), (96.0, 50.0), 6.0)
        || circle(p, (100.0, 49.0), 8.5)
        || ellipse(p, (108.0, 53.0), (5.5, 4.0))
        || circle(p, (95.0, 41.0), 2.8)
        || circle(p, (103.0, 40.0), 2.8)
        || stroke(p, (32.0, 64.0), (28.0, 104.0), 2.6)
        || stroke(p, (42.0, 66.0), (48.0, 104.0), 2.6)
        || stroke(p, (78.0, 70.0), (80.0, 104.0), 2.8)
        || stroke(p, (86.0, 68.0), (94.0, 104.0), 2.8)
        || stroke(p, (28.0, 56.0), (14.0, 68.0), 2.2)
        || stroke(p, (14.0, 68.0), (10.0, 92.0), 2.2)
}

/// A cheetah on the savanna: a light coat covered in black spots inside a dark outline, dark
/// tear lines down its face, rings at the end of its tail.
fn cheetah(p: P) -> f32 {
    let (x, y) = p;
    if cheetah_shape(p) {
        let edge = [(-1.5, 0.0), (1.5, 0.0), (0.0, -1.5), (0.0, 1.5)]
            .iter()
            .any(|&(dx, dy)| !cheetah_shape((x + dx, y + dy)));
        if edge || circle(p, (102.0, 47.0), 1.6) || circle(p, (112.0, 52.0), 1.8) {
            return 0.1;
        }
        if stroke(p, (101.0, 49.0), (107.0, 59.0), 0.9) {
            return 0.1;
        }
        if x < 16.0 && y > 74.0 {
            return if y.rem_euclid(5.0) < 2.2 { 0.1 } else { 0.9 };
        }
        let row = (y / 6.0).floor();
        let shift = if row as i32 % 2 == 0 { 0.0 } else { 3.0 };
        let cell = ((x + shift) / 6.0).floor();
        let jx = hash01(0xc4e, cell as usize, row as usize) - 0.5;
        let jy = hash01(0xc4f, cell as usize, row as usize) - 0.5;
        let centre = (
            cell * 6.0 - shift + 3.0 + jx * 2.0,
            row * 6.0 + 3.0 + jy * 2.0,
        );
        if circle(p, centre, 1.6) && x < 96.0 {
            return 0.1;
        }
        return if y > 64.0 && x > 30.0 && x < 84.0 {
            0.92
        } else {
            0.74
        };
    }
    if y > 100.0 {
        let blade = (x * 1.7).sin() * (y * 0.5).cos() > 0.4;
        return if blade { 0.42 } else { 0.58 };
    }
    0.97 - 0.12 * (y / 100.0)
}
