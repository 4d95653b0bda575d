//! Assembling a home: structure (floors, walls with door gaps, door frames) from the floorplan,
//! then furniture per room and small objects on furniture.

use crate::config::ProcgenConfig;
use crate::floorplan::{self, Opening, Plan};
use crate::furnish;
use crate::models::Model;
use crate::palette::{self, f, Finish};
use crate::rect::Rect;
use crate::storeys;
use glam::Vec3;
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use vlnverse_env::scene::DoorKind;
use vlnverse_env::{
    Door, EnvError, Motion, ObjectId, Part, Physics, Pose, Result, Room, RoomId, RoomType, Scene,
    SceneObject, SemanticClass as C, Shape, SCENE_FORMAT_VERSION,
};

/// Collects objects with sequential ids.
pub(crate) struct Builder {
    pub objects: Vec<SceneObject>,
}

impl Builder {
    /// Add an object; returns its id.
    pub fn add(
        &mut self,
        class: C,
        room: Option<RoomId>,
        pose: Pose,
        parts: Vec<Part>,
        color: &str,
        material: &str,
        mass: f32,
        supported_by: Option<ObjectId>,
    ) -> ObjectId {
        let id = self.objects.len() as ObjectId + 1;
        let motion = if matches!(class, C::Chair | C::Stool | C::OfficeChair | C::TrashCan)
            || class.kind() == vlnverse_env::ClassKind::Small
        {
            Motion::Dynamic
        } else {
            Motion::Static
        };
        let mut o = SceneObject {
            id,
            name: format!("{}_{id}", class.name()),
            class,
            room,
            pose,
            bbox: vlnverse_env::Aabb::EMPTY,
            color: color.to_string(),
            material: material.to_string(),
            shade: None,
            features: Vec::new(),
            physics: Physics {
                mass,
                friction: palette::friction(material),
                motion,
            },
            supported_by,
            parts,
        };
        o.bbox = o.compute_bbox();
        self.objects.push(o);
        id
    }

    /// Add an object in a finish: its colour and material words, and its shade if it took a
    /// tone; returns its id.
    #[allow(clippy::too_many_arguments)]
    pub fn add_finish(
        &mut self,
        class: C,
        room: Option<RoomId>,
        pose: Pose,
        parts: Vec<Part>,
        fin: Finish,
        mass: f32,
        supported_by: Option<ObjectId>,
    ) -> ObjectId {
        let id = self.add(
            class,
            room,
            pose,
            parts,
            fin.color,
            fin.material,
            mass,
            supported_by,
        );
        if let Some(o) = self.objects.last_mut() {
            o.shade = fin.shade.map(String::from);
        }
        id
    }

    /// Add a placed model.
    pub fn add_model(
        &mut self,
        m: &Model,
        room: RoomId,
        pose: Pose,
        supported_by: Option<ObjectId>,
    ) -> ObjectId {
        let id = self.add_finish(
            m.class,
            Some(room),
            pose,
            m.parts.clone(),
            m.finish,
            m.mass,
            supported_by,
        );
        if let Some(o) = self.objects.last_mut() {
            o.features = m.features.iter().map(|f| f.to_string()).collect();
        }
        id
    }
}

/// An axis-aligned box part centred at `center` (object frame).
pub(crate) fn box_part(center: Vec3, size: Vec3, rgb: [f32; 3]) -> Part {
    Part {
        shape: Shape::Cuboid {
            half_extents: (size * 0.5).to_array(),
            bevel: 0.0,
        },
        transform: Pose {
            position: center.to_array(),
            rotation: [0.0, 0.0, 0.0, 1.0],
        },
        color: rgb,
    }
}

/// Salt of the floor coverings' random stream.
const FLOOR_SALT: u64 = 0xf100_c0fe_7ed0_0004;

/// Carpets: soft, plain colours (the texture adds the fleck).
const CARPET: &[Finish] = &[
    f("beige", "carpet", [0.62, 0.55, 0.44]),
    f("grey", "carpet", [0.42, 0.42, 0.44]),
    f("blue", "carpet", [0.16, 0.24, 0.42]),
    f("brown", "carpet", [0.33, 0.23, 0.15]),
    f("green", "carpet", [0.26, 0.36, 0.26]),
    f("white", "carpet", [0.8, 0.77, 0.7]),
    f("red", "carpet", [0.45, 0.1, 0.1]),
];
/// Stone tiles of halls.
const STONE: &[Finish] = &[
    f("grey", "stone", [0.52, 0.52, 0.5]),
    f("beige", "stone", [0.7, 0.64, 0.52]),
    f("white", "stone", [0.8, 0.79, 0.76]),
];

/// Chance that a room of `kind` has a carpet, else stone tiles for halls, or what it has.
fn covering(kind: RoomType) -> (f32, &'static [Finish]) {
    match kind {
        RoomType::Bedroom => (0.55, CARPET),
        RoomType::HomeTheater => (0.7, CARPET),
        RoomType::Office | RoomType::Library => (0.35, CARPET),
        RoomType::Playroom => (0.5, CARPET),
        RoomType::Hallway | RoomType::EntranceHall => (0.3, STONE),
        _ => (0.0, CARPET),
    }
}

/// A room's floor: wood by default (saunas included), tiles in kitchens, wet rooms, spas and
/// mud rooms, concrete in garages and workshops, stone in wine cellars (one draw from `rng`,
/// as before coverings), then from `cover` (a stream of its own, so nothing else in the home
/// moves) carpet in some bedrooms, studies, home theaters, libraries and playrooms and stone
/// tiles in some halls.
fn floor_finish(kind: RoomType, rng: &mut ChaCha8Rng, cover: &mut ChaCha8Rng) -> Finish {
    use rand::seq::IndexedRandom;
    use rand::Rng;
    const WOOD: &[Finish] = &[
        f("wooden", "wood", [0.5, 0.33, 0.18]),
        f("brown", "wood", [0.32, 0.2, 0.1]),
        f("beige", "wood", [0.72, 0.6, 0.42]),
    ];
    const TILE: &[Finish] = &[
        f("white", "tile", [0.85, 0.85, 0.83]),
        f("grey", "tile", [0.5, 0.5, 0.52]),
        f("beige", "tile", [0.75, 0.7, 0.6]),
    ];
    // A garage's bare concrete.
    const CONCRETE: &[Finish] = &[
        f("grey", "concrete", [0.42, 0.42, 0.43]),
        f("grey", "concrete", [0.55, 0.55, 0.54]),
    ];
    let list = match kind {
        RoomType::Kitchen
        | RoomType::Bathroom
        | RoomType::LaundryRoom
        | RoomType::Pantry
        | RoomType::Spa
        | RoomType::MudRoom => TILE,
        RoomType::Garage | RoomType::Workshop => CONCRETE,
        RoomType::WineCellar => STONE,
        _ => WOOD,
    };
    let base = *list.choose(rng).unwrap_or(&list[0]);
    let (p, other) = covering(kind);
    // Both draws for every room, so each room's covering depends on its order alone.
    let (x, pick) = (cover.random::<f32>(), cover.random::<u32>());
    if x < p {
        other[pick as usize % other.len()]
    } else {
        base
    }
}

fn wall_finish(rng: &mut ChaCha8Rng) -> Finish {
    use rand::seq::IndexedRandom;
    const WALLS: &[Finish] = &[
        f("white", "plaster", [0.88, 0.87, 0.84]),
        f("beige", "plaster", [0.8, 0.74, 0.62]),
        f("grey", "plaster", [0.62, 0.63, 0.65]),
        f("blue", "plaster", [0.55, 0.65, 0.78]),
        f("green", "plaster", [0.6, 0.72, 0.58]),
    ];
    *WALLS.choose(rng).unwrap_or(&WALLS[0])
}

/// Quantise a coordinate to group collinear wall segments.
fn key(v: f32) -> i64 {
    (v * 1000.0).round() as i64
}

/// Subtract gaps `(lo, hi)` from the interval `(a, b)`.
fn subtract(a: f32, b: f32, gaps: &[(f32, f32)]) -> Vec<(f32, f32)> {
    let mut out = vec![(a, b)];
    for &(g0, g1) in gaps {
        let mut next = Vec::with_capacity(out.len() + 1);
        for (s, e) in out {
            if g1 <= s || g0 >= e {
                next.push((s, e));
                continue;
            }
            if g0 > s {
                next.push((s, g0));
            }
            if g1 < e {
                next.push((g1, e));
            }
        }
        out = next;
    }
    out.retain(|(s, e)| e - s > 1e-3);
    out
}

/// Merge overlapping or touching intervals.
fn merge(mut v: Vec<(f32, f32)>) -> Vec<(f32, f32)> {
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<(f32, f32)> = Vec::with_capacity(v.len());
    for (s, e) in v {
        match out.last_mut() {
            Some(last) if s <= last.1 + 1e-4 => last.1 = last.1.max(e),
            _ => out.push((s, e)),
        }
    }
    out
}

/// Floors (their coverings from a stream seeded by `seed`), walls and door frames (arched above
/// the doorways of `kinds` that are arches); returns the wall finish (ceilings share it).
fn build_structure(
    cfg: &ProcgenConfig,
    plan: &Plan,
    kinds: &[DoorKind],
    seed: u64,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) -> Finish {
    use rand::SeedableRng;
    let t = cfg.walls.thickness;
    let h = cfg.walls.height;
    let mut cover = ChaCha8Rng::seed_from_u64(seed ^ FLOOR_SALT);
    for (i, room) in plan.rooms.iter().enumerate() {
        let fin = floor_finish(room.kind, rng, &mut cover);
        let (cx, cz) = room.rect.center();
        let size = Vec3::new(room.rect.w(), 0.05, room.rect.d());
        b.add_finish(
            C::Floor,
            Some(i as RoomId),
            Pose::from_yaw(Vec3::new(cx, 0.0, cz), 0.0),
            vec![box_part(Vec3::new(0.0, -0.025, 0.0), size, fin.rgb)],
            fin,
            size.x * size.z * 50.0,
            None,
        );
    }

    // Wall lines: per orientation and coordinate, the union of room edges on that line.
    let mut lines: BTreeMap<(bool, i64), (f32, Vec<(f32, f32)>)> = BTreeMap::new();
    for room in &plan.rooms {
        let r = room.rect;
        for (along_z, line, a, c) in [
            (true, r.x0, r.z0, r.z1),
            (true, r.x1, r.z0, r.z1),
            (false, r.z0, r.x0, r.x1),
            (false, r.z1, r.x0, r.x1),
        ] {
            lines
                .entry((along_z, key(line)))
                .or_insert_with(|| (line, Vec::new()))
                .1
                .push((a, c));
        }
    }
    let wall = wall_finish(rng);
    for ((along_z, k), (line, spans)) in &lines {
        let gaps: Vec<(f32, f32)> = plan
            .openings
            .iter()
            .filter(|o| o.along_z == *along_z && key(o.line) == *k)
            .map(|o| {
                let g = o.gap(cfg) * 0.5;
                (o.center - g, o.center + g)
            })
            .collect();
        for (s, e) in merge(spans.clone()) {
            // Extend by half a thickness so that corners close.
            for (a, c) in subtract(s - t * 0.5, e + t * 0.5, &gaps) {
                let len = c - a;
                let mid = (a + c) * 0.5;
                let (pos, size) = if *along_z {
                    (Vec3::new(*line, 0.0, mid), Vec3::new(t, h, len))
                } else {
                    (Vec3::new(mid, 0.0, *line), Vec3::new(len, h, t))
                };
                b.add_finish(
                    C::Wall,
                    None,
                    Pose::from_yaw(pos, 0.0),
                    vec![box_part(Vec3::new(0.0, h * 0.5, 0.0), size, wall.rgb)],
                    wall,
                    size.x * size.y * size.z * 1500.0,
                    None,
                );
            }
        }
    }

    for (i, o) in plan
        .openings
        .iter()
        .enumerate()
        .filter(|(_, o)| !o.open_plan)
    {
        let arched = kinds.get(i) == Some(&DoorKind::Arched);
        add_door_frame(cfg, o, arched.then_some(wall.rgb), rng, b);
    }
    wall
}

/// A ceiling slab per room in the wall finish. Added after the furniture so that turning
/// ceilings on or off leaves every other object id as it is.
fn add_ceilings(cfg: &ProcgenConfig, plan: &Plan, wall: Finish, b: &mut Builder) {
    let h = cfg.walls.height;
    for (i, room) in plan.rooms.iter().enumerate() {
        let (cx, cz) = room.rect.center();
        let size = Vec3::new(room.rect.w(), 0.05, room.rect.d());
        b.add_finish(
            C::Ceiling,
            Some(i as RoomId),
            Pose::from_yaw(Vec3::new(cx, h, cz), 0.0),
            vec![box_part(Vec3::new(0.0, 0.025, 0.0), size, wall.rgb)],
            wall,
            size.x * size.z * 30.0,
            None,
        );
    }
}

/// Two posts and a lintel; the clear opening stays free up to the door head. With `arch` (the
/// wall's colour) the lintel is the wall above the opening shaped as a round arch, springing
/// from the door head: a column of wall over each post and [`ARCH_PIECES`] strips across the
/// opening whose undersides step up along the arch, none below it.
fn add_door_frame(
    cfg: &ProcgenConfig,
    o: &Opening,
    arch: Option<[f32; 3]>,
    rng: &mut ChaCha8Rng,
    b: &mut Builder,
) {
    let fin = palette::pick(C::DoorFrame, rng);
    let t = cfg.walls.thickness;
    let h = cfg.walls.height;
    let fw = cfg.doors.frame_width;
    let head = cfg.doors.head_height;
    let depth = t + 0.02;
    let mut parts = Vec::with_capacity(3);
    for s in [-1.0, 1.0] {
        parts.push(box_part(
            Vec3::new(s * (o.width + fw) * 0.5, head * 0.5, 0.0),
            Vec3::new(fw, head, depth),
            fin.rgb,
        ));
    }
    if let Some(wall) = arch {
        parts.extend(arch_parts(o.width, fw, head, h, t, wall));
    } else {
        parts.push(box_part(
            Vec3::new(0.0, (head + h) * 0.5, 0.0),
            Vec3::new(o.width + 2.0 * fw, h - head, t),
            fin.rgb,
        ));
    }
    let (x, z) = o.position();
    // Local x runs along the wall.
    let yaw = if o.along_z {
        std::f32::consts::FRAC_PI_2
    } else {
        0.0
    };
    b.add_finish(
        C::DoorFrame,
        None,
        Pose::from_yaw(Vec3::new(x, 0.0, z), yaw),
        parts,
        fin,
        25.0,
        None,
    );
}

/// Strips of wall across an arched opening.
pub(crate) const ARCH_PIECES: usize = 12;
/// Wall kept above the crown of an arch (m).
const ARCH_CROWN_WALL: f32 = 0.08;

/// The wall above an opening `w` wide between posts `fw` wide, from the door head `head` to the
/// wall top `h`, `t` thick, as a round arch springing from the head (an elliptical one where
/// the wall is too low for a semicircle): a column over each post and [`ARCH_PIECES`] strips,
/// each as low as the arch allows at its edge nearer the crown, so nothing hangs below the arch.
fn arch_parts(w: f32, fw: f32, head: f32, h: f32, t: f32, rgb: [f32; 3]) -> Vec<Part> {
    let r = w * 0.5;
    let rise = r.min(h - head - ARCH_CROWN_WALL).max(0.0);
    // Height of the arch's underside at `x` across the opening.
    let under = |x: f32| head + rise * (1.0 - (x / r).powi(2)).max(0.0).sqrt();
    let mut parts = Vec::with_capacity(ARCH_PIECES + 2);
    for s in [-1.0f32, 1.0] {
        parts.push(box_part(
            Vec3::new(s * (r + fw * 0.5), (head + h) * 0.5, 0.0),
            Vec3::new(fw, h - head, t),
            rgb,
        ));
    }
    let step = w / ARCH_PIECES as f32;
    for k in 0..ARCH_PIECES {
        let (x0, x1) = (-r + k as f32 * step, -r + (k + 1) as f32 * step);
        // The edge nearer the crown, where the arch is highest over the strip.
        let near = if x0 * x1 <= 0.0 {
            0.0
        } else {
            x0.abs().min(x1.abs())
        };
        let y0 = under(near).min(h - 0.01);
        parts.push(box_part(
            Vec3::new((x0 + x1) * 0.5, (y0 + h) * 0.5, 0.0),
            Vec3::new(step, h - y0, t),
            rgb,
        ));
    }
    parts
}

/// Free box on both sides of an opening: along the wall it covers the gap plus `margin`, across
/// it `depth` into each room.
pub(crate) fn clearance_rect(o: &Opening, cfg: &ProcgenConfig, depth: f32, margin: f32) -> Rect {
    let (x, z) = o.position();
    let half = o.gap(cfg) * 0.5 + margin;
    if o.along_z {
        Rect {
            x0: x - depth,
            x1: x + depth,
            z0: z - half,
            z1: z + half,
        }
    } else {
        Rect {
            x0: x - half,
            x1: x + half,
            z0: z - depth,
            z1: z + depth,
        }
    }
}

/// Generate one home from its seed.
pub(crate) fn generate(cfg: &ProcgenConfig, seed: u64, id: &str) -> Result<Scene> {
    use rand::SeedableRng;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut plan = floorplan::generate(cfg, &mut rng).ok_or_else(|| EnvError::InvalidScene {
        scene: id.to_string(),
        message: format!(
            "no floorplan satisfies rooms.min_side = {} and rooms.max_aspect = {} (seed {seed})",
            cfg.rooms.min_side, cfg.rooms.max_aspect
        ),
    })?;
    // A second floor comes from streams of its own: without one nothing below changes.
    let upper = storeys::plan_upper(cfg, seed, &plan);
    if let Some(up) = &upper {
        plan.rooms.push(up.ground_hall.clone());
        plan.openings.push(up.ground_opening.clone());
    }
    let mut b = Builder {
        objects: Vec::with_capacity(256),
    };
    // From streams of their own: which doorways are arches, sliding or french doors.
    let kinds = crate::doors::kinds(&plan, seed);
    let wall = build_structure(cfg, &plan, &kinds, seed, &mut rng, &mut b);
    furnish::furnish(cfg, &plan, &mut rng, &mut b);
    let mut flight = None;
    if let Some(up) = &upper {
        let mut srng = ChaCha8Rng::seed_from_u64(seed ^ storeys::UPPER_SALT);
        let hall = (plan.rooms.len() - 1) as RoomId;
        flight = Some(storeys::add_flight(&up.stairs, hall, &mut srng, &mut b));
    }
    if cfg.walls.ceiling {
        add_ceilings(cfg, &plan, wall, &mut b);
    }
    // From their own stream, clear of the furniture; the decoration then keeps clear of them.
    let leaves = crate::doors::add_leaves(cfg, &plan, &kinds, seed, &mut b);
    crate::household::add_fixtures(cfg, &plan, seed, &mut b);
    if cfg.walls.decor {
        crate::decor::add_decor(cfg, &plan, seed, &mut b);
    }

    let t = cfg.walls.thickness;
    let mut counts: BTreeMap<RoomType, usize> = BTreeMap::new();
    let mut rooms = rooms_of(&plan, t, 0, &mut counts);
    let mut doors = doors_of(&plan, leaves, 0.0, 0, 0, 0);
    let mut storeys = vlnverse_env::Storeys::default();
    if let Some(up) = upper {
        let hall = (plan.rooms.len() - 1) as RoomId;
        let s = &up.stairs;
        // The stairwell: no ceiling over the flight (the upper floor's slab is cut likewise).
        storeys::cut_hole(&mut b.objects, C::Ceiling, hall, &s.flight);
        let ground_rooms = plan.rooms.len() as RoomId;
        let (upper_objects, upper_leaves) = build_upper(cfg, seed, &up);
        let off = storeys::append_lifted(&mut b, upper_objects, s.upper_height, ground_rooms);
        rooms.extend(rooms_of(&up.plan, t, ground_rooms, &mut counts));
        let first_door = doors.len() as u32;
        doors.extend(doors_of(
            &up.plan,
            upper_leaves,
            s.upper_height,
            ground_rooms,
            off,
            first_door,
        ));
        let level = |id: u32, name: &str, h: f32, r: std::ops::Range<RoomId>| vlnverse_env::Level {
            id,
            name: name.into(),
            floor_height: h,
            rooms: r.collect(),
        };
        let f = s.flight;
        storeys.levels = vec![
            level(0, "ground floor", 0.0, 0..ground_rooms),
            level(
                1,
                "upper floor",
                s.upper_height,
                ground_rooms..rooms.len() as RoomId,
            ),
        ];
        storeys.stairs = vec![vlnverse_env::Stairs {
            id: 0,
            levels: [0, 1],
            object: flight,
            footprint: vec![[f.x0, f.z0], [f.x0, f.z1], [f.x1, f.z1], [f.x1, f.z0]],
            foot: [s.foot.0, 0.0, s.foot.1],
            head: [s.head.0, s.upper_height, s.head.1],
            steps: s.steps,
            rise: s.rise,
            run: s.run,
            width: s.width,
        }];
    }
    let mut scene = Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: id.to_string(),
        source: "procgen".into(),
        seed: Some(seed),
        floor_height: 0.0,
        rooms,
        doors,
        objects: b.objects,
        storeys,
    };
    if cfg.walls.ceiling && cfg.walls.decor {
        crate::decor::add_light_panels(&mut scene);
    }
    crate::motifs::record(&mut scene);
    Ok(scene)
}

/// The upper floor built at height 0 in a builder of its own (structure, furniture, railings,
/// ceilings, door leaves, decoration, the stairwell cut out of the landing's floor): its objects
/// and each opening's leaf.
fn build_upper(
    cfg: &ProcgenConfig,
    seed: u64,
    up: &storeys::UpperFloor,
) -> (Vec<SceneObject>, Vec<crate::doors::DoorLeaf>) {
    use rand::SeedableRng;
    let upper_seed = seed ^ storeys::UPPER_SALT;
    let mut rng = ChaCha8Rng::seed_from_u64(upper_seed.rotate_left(17));
    let mut b = Builder {
        objects: Vec::with_capacity(192),
    };
    let landing = (up.plan.rooms.len() - 1) as RoomId;
    let kinds = crate::doors::kinds(&up.plan, upper_seed);
    let wall = build_structure(cfg, &up.plan, &kinds, upper_seed, &mut rng, &mut b);
    storeys::cut_hole(&mut b.objects, C::Floor, landing, &up.stairs.flight);
    furnish::furnish(cfg, &up.plan, &mut rng, &mut b);
    storeys::add_railings(&up.stairs, landing, &mut rng, &mut b);
    if cfg.walls.ceiling {
        add_ceilings(cfg, &up.plan, wall, &mut b);
    }
    let leaves = crate::doors::add_leaves(cfg, &up.plan, &kinds, upper_seed, &mut b);
    crate::household::add_fixtures(cfg, &up.plan, upper_seed, &mut b);
    if cfg.walls.decor {
        crate::decor::add_decor(cfg, &up.plan, upper_seed, &mut b);
    }
    (b.objects, leaves)
}

/// The scene rooms of a plan, ids from `first`, names numbered on from `counts`.
fn rooms_of(
    plan: &Plan,
    t: f32,
    first: RoomId,
    counts: &mut BTreeMap<RoomType, usize>,
) -> Vec<Room> {
    plan.rooms
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let n = counts.entry(r.kind).or_insert(0);
            *n += 1;
            let inner = r.rect.inset(t * 0.5);
            Room {
                id: first + i as RoomId,
                kind: r.kind,
                name: format!("{}_{}", r.kind.name(), *n),
                // Counter-clockwise seen from above (+Y): with x right and z towards the
                // viewer's bottom, that is the order (x0,z0) (x0,z1) (x1,z1) (x1,z0).
                polygon: vec![
                    [inner.x0, inner.z0],
                    [inner.x0, inner.z1],
                    [inner.x1, inner.z1],
                    [inner.x1, inner.z0],
                ],
            }
        })
        .collect()
}

/// The scene doors of a plan's openings on the floor at `y`: room ids after `room_offset`, leaf
/// ids after `leaf_offset`, door ids from `first`.
pub(crate) fn doors_of(
    plan: &Plan,
    leaves: Vec<crate::doors::DoorLeaf>,
    y: f32,
    room_offset: RoomId,
    leaf_offset: ObjectId,
    first: u32,
) -> Vec<Door> {
    plan.openings
        .iter()
        .zip(leaves)
        .enumerate()
        .map(|(i, (o, l))| {
            let (x, z) = o.position();
            Door {
                id: first + i as u32,
                position: [x, y, z],
                width: o.width,
                normal: o.normal(plan),
                rooms: [
                    room_offset + o.rooms[0] as RoomId,
                    room_offset + o.rooms[1] as RoomId,
                ],
                open_plan: o.open_plan,
                state: l.state,
                leaf: l.leaf.map(|l| l + leaf_offset),
                second_leaf: l.second.map(|l| l + leaf_offset),
                kind: l.kind,
            }
        })
        .collect()
}
