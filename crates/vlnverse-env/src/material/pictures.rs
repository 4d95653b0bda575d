//! What framed canvases show: one procedural picture per subject ([`Surface::is_picture`]),
//! drawn once over the whole canvas (not tiled) in grey tones that the canvas colour tints.
//! Each is built from a few simple shapes so that the subject reads at the size a painting
//! has in a camera frame: a sailboat is a hull, a mast and two white sails over the sea.
//!
//! Coordinates are texels, `x` to the right and `y` down, over a [`TEX_SIZE`] square.

use super::{fbm, Surface, TEX_SIZE};

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
