//! Decoration added after everything else in a home: windows on exterior walls (frame, a
//! daylight pane, sill, curtains on some), skirting boards along the foot of the walls and
//! pictures in living rooms, bedrooms and hallways, and a light panel on the ceiling over
//! every lamp of the light bake.
//!
//! Two rules keep the rest of a home as it was without them:
//! - they are added last and draw from their own random stream (the home seed with a salt), so
//!   every other object, its id and every episode stay the same;
//! - they never reach a cell of the occupancy grid that the wall they hang on does not already
//!   fill. Grid cells lie on multiples of the resolution in world coordinates (the grid's
//!   origin is snapped to one), so each decoration stays within the 5 cm cell (the default
//!   resolution, and so also within cells of 10 cm, 15 cm, ...) that its wall face reaches
//!   into. The navigable map is then the same with and without them.

use crate::config::ProcgenConfig;
use crate::floorplan::Plan;
use crate::home::{box_part, Builder};
use crate::palette::{f, Finish};
use glam::Vec3;
use rand::seq::IndexedRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{Aabb, Pose, RoomId, RoomType, Scene, SceneObject, SemanticClass as C};

/// Salt of the decoration's random stream.
const SALT: u64 = 0xdec0_7a7e_5eed_0001;
/// Occupancy cell the decorations keep within (see the module docs).
const GRID: f64 = 0.05;
/// Safety margin to a cell boundary (m): the rasteriser's own tolerance is 5e-5 m.
const GRID_MARGIN: f64 = 3e-4;
/// Window frame, bottom and top (m above the floor).
const WINDOW_Y: (f32, f32) = (0.9, 2.2);
/// Distance windows and pictures keep from doorways and corners (m).
const CLEAR: f32 = 0.3;
/// Width a window needs beside its frame for curtains (both sides together, m).
const CURTAIN_ROOM: f32 = 0.75;
/// Most windows in one room.
const MAX_WINDOWS: usize = 2;
/// Class of skirting boards. `floor`, not `wall`: instructions test sight lines against the
/// footprints of all `wall` objects (`vlnverse-instructions`, `wall_rects`), and a board's strip along
/// a wall face cuts the sight line to furniture standing flush against the wall, which changes
/// instructions. Floors are only covered area to the maps, and boards lie inside the room's
/// floor.
const SKIRTING_CLASS: C = C::Floor;
/// Skirting board height (m).
const SKIRTING_H: f32 = 0.09;
/// Skirting boards stop this far short of a doorway (m), so that no sight line through the
/// doorway grazes one.
const SKIRTING_SETBACK: f32 = 0.06;

/// Ceiling light panel: side and thickness (m).
const PANEL: (f32, f32) = (0.36, 0.025);
/// Warm white of the panels (the bake lights their underside fully: the lamp hangs just
/// below).
const PANEL_RGB: [f32; 3] = [0.97, 0.95, 0.9];

/// Material word of window panes: the light bake makes them area lights
/// (`vlnverse_env::light`), the renderers draw them as glass.
pub(crate) const PANE_MATERIAL: &str = "glass";

/// One interior face of a room's wall: a room edge seen from inside.
struct Face {
    room: usize,
    /// The wall runs along z (its line is an x coordinate).
    along_z: bool,
    /// Coordinate of the wall's centre line.
    line: f32,
    /// +1 or -1: the direction into the room along the wall's normal axis.
    sign: f32,
    /// Extent of the room edge along the wall.
    span: (f32, f32),
    /// Parts of the span that are exterior (no room on the other side).
    exterior: Vec<(f32, f32)>,
    /// Free depth in front of the face within its occupancy cell; `None` when the wall fills
    /// no cell there.
    depth: Option<f32>,
}

impl Face {
    /// Coordinate of the face along the wall's normal axis.
    fn face(&self, t: f32) -> f32 {
        self.line + self.sign * t * 0.5
    }

    /// Pose on the face at `along` metres along the wall: local x along the wall, local +z into
    /// the room, local y up.
    fn pose(&self, t: f32, along: f32) -> Pose {
        let f = self.face(t);
        if self.along_z {
            let yaw = self.sign * std::f32::consts::FRAC_PI_2;
            Pose::from_yaw(Vec3::new(f, 0.0, along), yaw)
        } else {
            let yaw = if self.sign > 0.0 {
                0.0
            } else {
                std::f32::consts::PI
            };
            Pose::from_yaw(Vec3::new(along, 0.0, f), yaw)
        }
    }

    /// World box (min, max) of a volume in front of the face: `a..b` along the wall, `0..reach`
    /// into the room, `y0..y1` high.
    fn volume(&self, t: f32, (a, b): (f32, f32), reach: f32, (y0, y1): (f32, f32)) -> [Vec3; 2] {
        let f = self.face(t);
        let (n0, n1) = if self.sign > 0.0 {
            (f, f + reach)
        } else {
            (f - reach, f)
        };
        if self.along_z {
            [Vec3::new(n0, y0, a), Vec3::new(n1, y1, b)]
        } else {
            [Vec3::new(a, y0, n0), Vec3::new(b, y1, n1)]
        }
    }
}

/// Depth from a wall face at `face` (looking along `sign`) to the next occupancy cell boundary,
/// less a margin; `None` when the face barely enters its cell (the wall does not fill it, so a
/// decoration there would).
fn free_depth(face: f32, sign: f32) -> Option<f32> {
    let q = f64::from(face) * f64::from(sign);
    let lo = (q / GRID).floor() * GRID;
    if q - lo < GRID_MARGIN {
        return None;
    }
    let d = lo + GRID - q - GRID_MARGIN;
    (d > 0.0).then_some(d as f32)
}

/// Quantised line coordinate (the same rule as the wall builder).
fn key(v: f32) -> i64 {
    (v * 1000.0).round() as i64
}

/// Subtract intervals from `(a, b)`.
fn subtract(a: f32, b: f32, gaps: &[(f32, f32)]) -> Vec<(f32, f32)> {
    let mut out = vec![(a, b)];
    for &(g0, g1) in gaps {
        out = out
            .into_iter()
            .flat_map(|(s, e)| {
                if g1 <= s || g0 >= e {
                    vec![(s, e)]
                } else {
                    [(s, g0), (g1, e)]
                        .into_iter()
                        .filter(|(x, y)| y - x > 1e-3)
                        .collect()
                }
            })
            .collect();
    }
    out
}

/// Every interior wall face of every room, in room order (edges x0, x1, z0, z1).
fn faces(cfg: &ProcgenConfig, plan: &Plan) -> Vec<Face> {
    let t = cfg.walls.thickness;
    let mut out = Vec::with_capacity(plan.rooms.len() * 4);
    for (i, room) in plan.rooms.iter().enumerate() {
        let r = room.rect;
        for (along_z, line, sign, span) in [
            (true, r.x0, 1.0, (r.z0, r.z1)),
            (true, r.x1, -1.0, (r.z0, r.z1)),
            (false, r.z0, 1.0, (r.x0, r.x1)),
            (false, r.z1, -1.0, (r.x0, r.x1)),
        ] {
            // Spans of other rooms on the same line are the other side of an interior wall.
            let others: Vec<(f32, f32)> = plan
                .rooms
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .filter_map(|(_, o)| {
                    let o = o.rect;
                    let (ol, os) = if along_z {
                        ([o.x0, o.x1], (o.z0, o.z1))
                    } else {
                        ([o.z0, o.z1], (o.x0, o.x1))
                    };
                    ol.iter().any(|l| key(*l) == key(line)).then_some(os)
                })
                .collect();
            let exterior = subtract(span.0, span.1, &others);
            let face = line + sign * t * 0.5;
            out.push(Face {
                room: i,
                along_z,
                line,
                sign,
                span,
                exterior,
                depth: free_depth(face, sign),
            });
        }
    }
    out
}

/// Free stretches of a face along the wall: `within` less doorways and corners (each kept
/// `clear` away).
fn free_stretches(
    cfg: &ProcgenConfig,
    plan: &Plan,
    face: &Face,
    within: (f32, f32),
    clear: f32,
) -> Vec<(f32, f32)> {
    let t = cfg.walls.thickness;
    let lo = within.0.max(face.span.0 + t * 0.5 + clear);
    let hi = within.1.min(face.span.1 - t * 0.5 - clear);
    if hi <= lo {
        return Vec::new();
    }
    subtract(lo, hi, &doorways(cfg, plan, face, clear))
}

/// The doorways in a face's wall as intervals along it, each widened by `clear` on both sides.
fn doorways(cfg: &ProcgenConfig, plan: &Plan, face: &Face, clear: f32) -> Vec<(f32, f32)> {
    plan.openings
        .iter()
        .filter(|o| o.along_z == face.along_z && key(o.line) == key(face.line))
        .map(|o| {
            let g = o.gap(cfg) * 0.5 + clear;
            (o.center - g, o.center + g)
        })
        .collect()
}

/// Whether any placed object other than the room shell reaches into a world box.
fn blocked(objects: &[SceneObject], v: [Vec3; 2]) -> bool {
    let v = Aabb::new(v[0], v[1]);
    objects.iter().any(|o| {
        !matches!(
            o.class,
            C::Floor | C::Wall | C::Ceiling | C::DoorFrame | C::Rug
        ) && o.bbox.intersects(&v, 0.0)
    })
}

/// A spot on a face for an item `width` wide: the first of a few positions from the middle of a
/// free stretch outwards whose volume in front of the wall is clear of furniture.
fn find_spot(
    objects: &[SceneObject],
    face: &Face,
    t: f32,
    stretches: &[(f32, f32)],
    width: f32,
    reach: f32,
    ys: (f32, f32),
) -> Option<f32> {
    for &(s, e) in stretches {
        let room = e - s - width;
        if room < 0.0 {
            continue;
        }
        let mid = (s + e) * 0.5;
        for k in [0.0, -0.25, 0.25, -0.5, 0.5] {
            let c = mid + k * room;
            let v = face.volume(
                t,
                (c - width * 0.5 - 0.05, c + width * 0.5 + 0.05),
                reach,
                ys,
            );
            if !blocked(objects, v) {
                return Some(c);
            }
        }
    }
    None
}

const FRAMES: &[Finish] = &[
    f("white", "plastic", [0.9, 0.9, 0.88]),
    f("white", "plastic", [0.94, 0.93, 0.9]),
    f("brown", "wood", [0.42, 0.28, 0.16]),
    f("grey", "metal", [0.35, 0.36, 0.38]),
];

const CURTAINS: &[Finish] = &[
    f("beige", "fabric", [0.78, 0.7, 0.56]),
    f("white", "fabric", [0.9, 0.88, 0.84]),
    f("blue", "fabric", [0.3, 0.4, 0.6]),
    f("green", "fabric", [0.4, 0.52, 0.38]),
    f("red", "fabric", [0.6, 0.22, 0.2]),
    f("grey", "fabric", [0.55, 0.55, 0.57]),
    f("purple", "fabric", [0.34, 0.16, 0.42]),
];

const SKIRTING: &[Finish] = &[
    f("white", "plastic", [0.92, 0.91, 0.88]),
    f("brown", "wood", [0.38, 0.25, 0.14]),
    f("beige", "wood", [0.7, 0.58, 0.4]),
];

/// Daylight seen through a pane (bright, a little blue).
const SKY: [f32; 3] = [0.78, 0.88, 1.0];

/// Add one window (the pane and its frame with sill, two objects of class `Window`, and on
/// some a `curtain`) centred `c` along a face, `w` wide, within `depth` in front of the face.
#[allow(clippy::too_many_arguments)]
fn add_window(
    b: &mut Builder,
    face: &Face,
    t: f32,
    c: f32,
    w: f32,
    depth: f32,
    room: RoomId,
    rng: &mut ChaCha8Rng,
) {
    let (y0, y1) = WINDOW_Y;
    let h = y1 - y0;
    let pose = face.pose(t, c);
    let frame = *FRAMES.choose(rng).unwrap_or(&FRAMES[0]);
    let bar = 0.05;
    // Layers into the room: frame, pane, glazing bars, curtains; the sill spans the depth.
    let d = depth;
    let mut parts = vec![
        box_part(
            Vec3::new(0.0, y0 + h * 0.5, d * 0.2),
            Vec3::new(w, h, d * 0.4),
            frame.rgb,
        ),
        box_part(
            Vec3::new(0.0, y0 - 0.02, d * 0.5),
            Vec3::new(w + 0.12, 0.04, d),
            frame.rgb,
        ),
    ];
    let (pw, ph) = (w - 2.0 * bar, h - 2.0 * bar);
    // One glazing bar: upright on wide windows, a transom on narrow ones.
    parts.push(if w > 1.0 {
        box_part(
            Vec3::new(0.0, y0 + h * 0.5, d * 0.65),
            Vec3::new(bar * 0.8, ph, d * 0.1),
            frame.rgb,
        )
    } else {
        box_part(
            Vec3::new(0.0, y0 + bar + ph * 0.68, d * 0.65),
            Vec3::new(pw, bar * 0.8, d * 0.1),
            frame.rgb,
        )
    });
    let pane_parts = vec![box_part(
        Vec3::new(0.0, y0 + h * 0.5, d * 0.5),
        Vec3::new(pw, ph, d * 0.2),
        SKY,
    )];
    b.add(
        C::Window,
        Some(room),
        pose,
        pane_parts,
        "blue",
        PANE_MATERIAL,
        3.0 * pw * ph,
        None,
    );
    b.add_finish(C::Window, Some(room), pose, parts, frame, 8.0 * w, None);
    if rng.random_bool(0.6) {
        let cur = *CURTAINS.choose(rng).unwrap_or(&CURTAINS[0]);
        let cw = (w * 0.28).clamp(0.25, 0.45);
        let (cy0, cy1) = (y0 - 0.1, y1 + 0.2);
        let parts = [-1.0, 1.0]
            .into_iter()
            .map(|s| {
                box_part(
                    Vec3::new(s * (w * 0.5 + cw * 0.5 - 0.08), (cy0 + cy1) * 0.5, d * 0.85),
                    Vec3::new(cw, cy1 - cy0, d * 0.3),
                    cur.rgb,
                )
            })
            .collect();
        b.add_finish(C::Curtain, Some(room), pose, parts, cur, 2.0, None);
    }
}

/// Windows on the exterior walls of every room but a wine cellar: one per exterior face that
/// has room for one clear of doorways and furniture, two on long faces, at most
/// [`MAX_WINDOWS`] per room (triangles cost frame rate).
fn add_windows(
    cfg: &ProcgenConfig,
    plan: &Plan,
    faces: &[Face],
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) {
    let t = cfg.walls.thickness;
    let mut per_room = vec![0usize; plan.rooms.len()];
    for face in faces {
        let Some(depth) = face.depth.filter(|d| *d >= 0.012) else {
            continue;
        };
        let kind = plan.rooms[face.room].kind;
        // Wine is kept out of the light.
        if kind == RoomType::WineCellar {
            continue;
        }
        let (wmin, wmax): (f32, f32) = match kind {
            RoomType::Bathroom | RoomType::LaundryRoom | RoomType::Sauna => (0.5, 0.8),
            RoomType::Hallway => (0.6, 1.0),
            _ => (0.9, 1.6),
        };
        for &ext in &face.exterior {
            let stretches = free_stretches(cfg, plan, face, ext, CLEAR);
            let longest = stretches.iter().map(|(s, e)| e - s).fold(0.0, f32::max);
            let w = rng.random_range(wmin..=wmax).min(longest);
            if w < wmin.min(0.6) {
                continue;
            }
            let count = if longest > 2.0 * w + 1.5 { 2 } else { 1 };
            let mut taken: Vec<(f32, f32)> = Vec::new();
            for _ in 0..count {
                if per_room[face.room] >= MAX_WINDOWS {
                    break;
                }
                let free: Vec<(f32, f32)> = stretches
                    .iter()
                    .flat_map(|&(s, e)| subtract(s, e, &taken))
                    .collect();
                // Room for curtains drawn open at both sides.
                let Some(c) = find_spot(
                    &b.objects,
                    face,
                    t,
                    &free,
                    w + CURTAIN_ROOM,
                    0.35,
                    (WINDOW_Y.0 - 0.15, WINDOW_Y.1 + 0.25),
                ) else {
                    break;
                };
                add_window(b, face, t, c, w, depth, face.room as RoomId, rng);
                per_room[face.room] += 1;
                taken.push((c - w * 0.5 - 0.6, c + w * 0.5 + 0.6));
            }
        }
    }
}

/// Skirting boards: an object of [`SKIRTING_CLASS`] per board, one along each interior face
/// between doorways, [`SKIRTING_SETBACK`] short of each doorway.
fn add_skirting(cfg: &ProcgenConfig, plan: &Plan, faces: &[Face], b: &mut Builder) {
    let t = cfg.walls.thickness;
    // One finish per home, as a builder would fit it.
    let fin = SKIRTING[(plan.rooms.len() + plan.openings.len()) % SKIRTING.len()];
    for face in faces {
        let Some(depth) = face.depth.filter(|d| *d >= 0.006) else {
            continue;
        };
        let d = depth.min(0.015);
        let doors = doorways(cfg, plan, face, SKIRTING_SETBACK);
        let lo = face.span.0 + t * 0.5;
        let hi = face.span.1 - t * 0.5;
        for (s, e) in subtract(lo, hi, &doors) {
            let len = e - s;
            if len < 0.1 {
                continue;
            }
            let mid = (s + e) * 0.5;
            let f = face.face(t) + face.sign * d * 0.5;
            let (pos, size) = if face.along_z {
                (Vec3::new(f, 0.0, mid), Vec3::new(d, SKIRTING_H, len))
            } else {
                (Vec3::new(mid, 0.0, f), Vec3::new(len, SKIRTING_H, d))
            };
            b.add(
                SKIRTING_CLASS,
                Some(face.room as RoomId),
                Pose::from_yaw(pos, 0.0),
                vec![box_part(
                    Vec3::new(0.0, SKIRTING_H * 0.5, 0.0),
                    size,
                    fin.rgb,
                )],
                fin.color,
                fin.material,
                len,
                None,
            );
        }
    }
}

const PICTURE_FRAMES: &[[f32; 3]] = &[
    [0.12, 0.1, 0.08],
    [0.42, 0.3, 0.18],
    [0.85, 0.84, 0.8],
    [0.62, 0.52, 0.3],
];

const CANVASES: &[(&str, [f32; 3])] = &[
    ("blue", [0.35, 0.5, 0.72]),
    ("green", [0.45, 0.62, 0.42]),
    ("orange", [0.85, 0.55, 0.3]),
    ("red", [0.7, 0.3, 0.28]),
    ("yellow", [0.85, 0.75, 0.4]),
    ("beige", [0.8, 0.72, 0.6]),
];

/// Paintings on the walls of living rooms, bedrooms, hallways, dining rooms, offices, entrance
/// halls, libraries and home theaters: a frame and a painted canvas (material `canvas`: a painting texture), one or
/// two per room, at eye height, clear of windows, doorways and tall furniture (above a sofa, a
/// bed or a low cabinet, as people hang them). At 0.4 to 0.9 m across they are landmarks
/// instructions name ("the painting above the sofa").
fn add_pictures(
    cfg: &ProcgenConfig,
    plan: &Plan,
    faces: &[Face],
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) {
    let t = cfg.walls.thickness;
    for (i, room) in plan.rooms.iter().enumerate() {
        let want = match room.kind {
            RoomType::LivingRoom => 2,
            RoomType::Bedroom
            | RoomType::Hallway
            | RoomType::DiningRoom
            | RoomType::Office
            | RoomType::EntranceHall
            | RoomType::Library
            | RoomType::HomeTheater
            | RoomType::Playroom
            | RoomType::Spa => 1,
            _ => continue,
        };
        let mut placed = 0;
        // Start at a seeded face so pictures do not all hang on the same side.
        let room_faces: Vec<&Face> = faces.iter().filter(|f| f.room == i).collect();
        let start = rng.random_range(0..room_faces.len().max(1));
        for k in 0..room_faces.len() {
            if placed >= want {
                break;
            }
            let face = room_faces[(start + k) % room_faces.len()];
            let Some(depth) = face.depth.filter(|d| *d >= 0.008) else {
                continue;
            };
            let (w, h) = if rng.random_bool(0.6) {
                (rng.random_range(0.55..0.9), rng.random_range(0.4..0.6))
            } else {
                (rng.random_range(0.4..0.55), rng.random_range(0.55..0.75))
            };
            let cy = rng.random_range(1.5..1.6);
            let stretches = free_stretches(cfg, plan, face, face.span, CLEAR);
            let ys = (cy - h * 0.5 - 0.1, cy + h * 0.5 + 0.1);
            let Some(c) = find_spot(&b.objects, face, t, &stretches, w, 0.3, ys) else {
                continue;
            };
            let frame = *PICTURE_FRAMES.choose(rng).unwrap_or(&PICTURE_FRAMES[0]);
            let (name, canvas) = *CANVASES.choose(rng).unwrap_or(&CANVASES[0]);
            let d = depth.min(0.03);
            let parts = vec![
                box_part(Vec3::new(0.0, cy, d * 0.3), Vec3::new(w, h, d * 0.6), frame),
                box_part(
                    Vec3::new(0.0, cy, d * 0.6),
                    Vec3::new(w - 0.06, h - 0.06, d * 0.6),
                    canvas,
                ),
            ];
            b.add(
                C::PictureFrame,
                Some(i as RoomId),
                face.pose(t, c),
                parts,
                name,
                "canvas",
                1.5,
                None,
            );
            placed += 1;
        }
    }
}

/// Add windows, skirting boards and pictures to a home whose other objects are all placed.
pub(crate) fn add_decor(cfg: &ProcgenConfig, plan: &Plan, seed: u64, b: &mut Builder) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ SALT);
    let faces = faces(cfg, plan);
    add_windows(cfg, plan, &faces, &mut rng, b);
    add_skirting(cfg, plan, &faces, b);
    if cfg.walls.pictures {
        add_pictures(cfg, plan, &faces, &mut rng, b);
    }
}

/// A square light panel on the ceiling over every lamp of the light bake
/// ([`vlnverse_env::light::lamps`]), so that the light in a room has a visible source. The
/// panel is a part of the room's ceiling object, not an object of its own: ceilings are
/// structure, so targets, the scene graph and episodes stay as they are, and the panel is
/// above the agent's height band, so the maps do too. Its class in semantic images is
/// `ceiling`.
pub(crate) fn add_light_panels(scene: &mut Scene) {
    let lamps = vlnverse_env::light::lamps(scene);
    for lamp in lamps {
        let inside = |o: &SceneObject| {
            o.class == C::Ceiling
                && (o.bbox.min[0]..=o.bbox.max[0]).contains(&lamp.x)
                && (o.bbox.min[2]..=o.bbox.max[2]).contains(&lamp.z)
        };
        // In a home on several floors ceilings overlap in plan: the lowest one above the lamp
        // (the first in object order among equals, so a single-storey home is as before).
        let above = |o: &SceneObject| o.bbox.min[1] >= lamp.y - 0.01;
        let mut pick: Option<usize> = None;
        for (i, o) in scene.objects.iter().enumerate() {
            if !inside(o) {
                continue;
            }
            let better = match pick {
                None => true,
                Some(j) => {
                    let b = &scene.objects[j];
                    above(o) && (!above(b) || o.bbox.min[1] < b.bbox.min[1])
                }
            };
            if better {
                pick = Some(i);
            }
        }
        let Some(ceiling) = pick.map(|i| &mut scene.objects[i]) else {
            continue;
        };
        // Ceilings are placed without rotation; the panel hangs from the slab's underside.
        let local = lamp - Vec3::from_array(ceiling.pose.position);
        // The slab is the first part (a second lamp's panel must not hang from the first's).
        let Some(slab) = ceiling.parts.first() else {
            continue;
        };
        let vlnverse_env::Shape::Cuboid { half_extents, .. } = slab.shape else {
            continue;
        };
        let bottom = slab.transform.position[1] - half_extents[1];
        // Sharp: bevels chamfer top edges, which here touch the slab.
        ceiling.parts.push(box_part(
            Vec3::new(local.x, bottom - PANEL.1 * 0.5, local.z),
            Vec3::new(PANEL.0, PANEL.1, PANEL.0),
            PANEL_RGB,
        ));
        ceiling.bbox = ceiling.compute_bbox();
    }
}
