//! Generator configuration: a plain serde struct, loaded from TOML and validated once.
//!
//! Every field has a default ([`ProcgenConfig::default`] is the `vlnverse` preset), so a TOML
//! file only needs the values it changes. Unknown fields are rejected so that typos surface.

use serde::{Deserialize, Serialize};
use std::path::Path;
use vlnverse_env::{EnvError, Result, RoomType};

/// Everything that shapes the generated homes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ProcgenConfig {
    /// Which scenes exist and how their seeds are derived.
    pub scenes: ScenesConfig,
    /// Room counts, kinds and sizes.
    pub rooms: RoomsConfig,
    /// Wall geometry.
    pub walls: WallsConfig,
    /// Doorways and open-plan openings.
    pub doors: DoorsConfig,
    /// Furniture and small objects.
    pub furniture: FurnitureConfig,
    /// Homes on two floors: how many, the slab between the floors and the stairs.
    pub floors: FloorsConfig,
}

/// Homes on two floors (docs/storeys.md). The `vlnverse` preset puts 30% of its homes on two
/// floors; `tiny` keeps every home on one. At `two_storey_share = 0` no home has a second floor
/// and no draw of any home changes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FloorsConfig {
    /// Share of homes with an upper floor and a staircase, in `[0, 1]` (drawn per home from a
    /// stream of its own; a home whose footprint has no side for the stair hall stays on one
    /// floor).
    pub two_storey_share: f32,
    /// Thickness between the ground floor's ceiling height (`walls.height`) and the upper
    /// floor (m), in `[0.05, 0.5]`: the upper floor lies at `walls.height + slab`.
    pub slab: f32,
    /// Highest riser of a stair (m), in `[0.1, 0.2]`: the flight gets as many equal risers as
    /// it needs to stay at or below it.
    pub max_riser: f32,
    /// Depth of a tread (m), in `[0.22, 0.4]`.
    pub tread: f32,
    /// Clear width of the flight (m), in `[0.8, 2]`.
    pub stair_width: f32,
}

/// Scene count, seed and naming.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ScenesConfig {
    /// Number of scenes the source provides.
    pub count: usize,
    /// Base seed; scene `i` uses a seed derived from `(seed, i)`.
    pub seed: u64,
    /// Scene ids are `<id_prefix>_<index:04>`.
    pub id_prefix: String,
}

/// How many rooms, of which kinds and sizes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RoomsConfig {
    /// Fewest rooms in a home (>= 1).
    pub count_min: usize,
    /// Most rooms in a home (<= 16).
    pub count_max: usize,
    /// Shortest side of a room between wall centre lines (m).
    pub min_side: f32,
    /// Largest ratio long side / short side of a room.
    pub max_aspect: f32,
    /// Per-home factor on every room area, drawn uniformly in `[area_scale_min, area_scale_max]`.
    pub area_scale_min: f32,
    /// See `area_scale_min`.
    pub area_scale_max: f32,
    /// Room kinds. Each home first takes every kind's `count_min` rooms (in list order, while
    /// the room count allows), then fills up with kinds drawn by `weight`.
    pub kinds: Vec<RoomKindConfig>,
}

/// One room kind in the distribution.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoomKindConfig {
    /// The room type.
    pub kind: RoomType,
    /// Rooms of this kind every home has (if the room count allows).
    #[serde(default)]
    pub count_min: usize,
    /// Most rooms of this kind in one home.
    pub count_max: usize,
    /// Relative weight when drawing extra rooms.
    #[serde(default)]
    pub weight: f32,
    /// Smallest floor area (m^2, before the home's area scale).
    pub area_min: f32,
    /// Largest floor area (m^2, before the home's area scale).
    pub area_max: f32,
}

/// Wall geometry.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WallsConfig {
    /// Wall thickness (m).
    pub thickness: f32,
    /// Wall height (m).
    pub height: f32,
    /// Add a ceiling slab per room (on by default: rooms seen from inside have a ceiling;
    /// top-down pictures leave ceilings out).
    pub ceiling: bool,
    /// Add windows (frame, daylight pane, sill, some with curtains) on exterior walls, skirting
    /// boards and pictures (on by default). They come after every other object and draw from
    /// their own random stream, so turning them off leaves the rest of a home as it is.
    pub decor: bool,
    /// With `decor`: also hang paintings in living rooms, bedrooms, hallways, dining rooms,
    /// offices and entrance halls (on by default; a painting is a `picture_frame`, a landmark
    /// and an object-goal target).
    pub pictures: bool,
}

/// Doorways and open-plan openings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DoorsConfig {
    /// Narrowest clear door width (m, >= 0.9).
    pub width_min: f32,
    /// Widest clear door width (m).
    pub width_max: f32,
    /// Height of the door head; the lintel sits above it (m).
    pub head_height: f32,
    /// Width of a door-frame post (m).
    pub frame_width: f32,
    /// Probability of an extra door between adjacent rooms beyond the spanning tree.
    pub extra_door_probability: f32,
    /// Probability that a connection between two public rooms (living, kitchen, dining,
    /// hallway) is an open-plan opening instead of a door.
    pub open_plan_probability: f32,
    /// Narrowest open-plan opening (m).
    pub open_plan_width_min: f32,
    /// Widest open-plan opening (m).
    pub open_plan_width_max: f32,
    /// Smallest distance between an opening and a wall corner (m).
    pub corner_margin: f32,
    /// Depth of the free box kept on both sides of every opening (m).
    pub clearance: f32,
    /// Whether doorways (not open-plan openings) get a hinged door leaf with a handle.
    pub leaves: bool,
    /// Probability that a door is closed; a door is only closed where every room stays
    /// reachable without it (closed doors block the agent and the navigable map).
    pub closed_probability: f32,
}

/// Furniture and small objects.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FurnitureConfig {
    /// Factor on the probability of every optional piece of furniture (0 = only essentials),
    /// in `[0, 4]`.
    pub density: f32,
    /// Placement attempts per piece of furniture, in `[1, 1000]`.
    pub attempts: usize,
    /// Factor on the probability of each piece of floor and wall clutter (shoes, laundry
    /// baskets, wall shelves, radiators...; 0 = none), in `[0, 4]`.
    pub clutter: f32,
    /// Factor on the chance of each feature piece (pool table, grandfather clock, kitchen
    /// island, console table, dryer...; 0 = none), in `[0, 4]`. Pieces are placed last from an
    /// rng of their own, so they never move the rest of a home.
    pub pieces: f32,
    /// Factor on the chance of each set of furniture (a matching second armchair, stools along
    /// an island, a double vanity, twin beds, bedside sconces, two desks; 0 = none), in
    /// `[0, 4]`. Sets are placed last from an rng of their own, so they never move the rest of
    /// a home.
    pub sets: f32,
    /// Most small objects on one surface, in `[0, 8]`.
    pub small_objects_max: usize,
    /// Probability that a surface gets small objects at all.
    pub small_object_probability: f32,
    /// Radius used by the in-room navigability check (m); a bit more than the agent radius so
    /// the occupancy map at 5 cm still connects every room.
    pub nav_radius: f32,
    /// Smallest gap between two pieces of furniture (m).
    pub gap: f32,
}

impl Default for ScenesConfig {
    fn default() -> Self {
        ScenesConfig {
            count: 263,
            seed: 2026,
            id_prefix: "home".into(),
        }
    }
}

fn kind(
    kind: RoomType,
    count_min: usize,
    count_max: usize,
    weight: f32,
    area_min: f32,
    area_max: f32,
) -> RoomKindConfig {
    RoomKindConfig {
        kind,
        count_min,
        count_max,
        weight,
        area_min,
        area_max,
    }
}

impl Default for RoomsConfig {
    fn default() -> Self {
        RoomsConfig {
            count_min: 3,
            count_max: 10,
            min_side: 2.2,
            max_aspect: 2.6,
            area_scale_min: 0.85,
            area_scale_max: 1.75,
            kinds: vec![
                kind(RoomType::LivingRoom, 1, 1, 0.0, 20.0, 40.0),
                kind(RoomType::Bedroom, 1, 4, 3.0, 10.0, 20.0),
                kind(RoomType::Bathroom, 1, 3, 1.2, 4.8, 8.0),
                kind(RoomType::Kitchen, 1, 1, 0.0, 8.0, 16.0),
                kind(RoomType::DiningRoom, 0, 1, 1.2, 10.0, 18.0),
                kind(RoomType::Office, 0, 1, 1.0, 7.5, 13.0),
                kind(RoomType::Hallway, 0, 1, 0.8, 6.0, 11.0),
                kind(RoomType::LaundryRoom, 0, 1, 0.6, 4.8, 7.5),
                kind(RoomType::EntranceHall, 0, 1, 0.6, 5.0, 9.0),
                kind(RoomType::Closet, 0, 1, 0.5, 4.8, 7.0),
                kind(RoomType::Balcony, 0, 1, 0.6, 4.8, 8.0),
                kind(RoomType::Pantry, 0, 1, 0.5, 4.8, 6.5),
                kind(RoomType::Gym, 0, 1, 0.5, 8.0, 14.0),
                kind(RoomType::HomeTheater, 0, 1, 0.35, 13.0, 20.0),
                kind(RoomType::Library, 0, 1, 0.4, 9.0, 15.0),
                kind(RoomType::Garage, 0, 1, 0.35, 18.0, 24.0),
                kind(RoomType::Porch, 0, 1, 0.4, 5.0, 9.0),
                kind(RoomType::Sauna, 0, 1, 0.32, 5.5, 8.0),
                kind(RoomType::Spa, 0, 1, 0.28, 8.0, 13.0),
                kind(RoomType::WineCellar, 0, 1, 0.35, 5.0, 9.0),
                kind(RoomType::Playroom, 0, 1, 0.3, 9.0, 15.0),
                kind(RoomType::MudRoom, 0, 1, 0.4, 4.8, 7.5),
                kind(RoomType::Workshop, 0, 1, 0.3, 9.0, 15.0),
            ],
        }
    }
}

impl Default for WallsConfig {
    fn default() -> Self {
        WallsConfig {
            thickness: 0.12,
            height: 2.7,
            ceiling: true,
            decor: true,
            pictures: true,
        }
    }
}

impl Default for DoorsConfig {
    fn default() -> Self {
        DoorsConfig {
            width_min: 0.9,
            width_max: 1.1,
            head_height: 2.05,
            frame_width: 0.06,
            extra_door_probability: 0.25,
            open_plan_probability: 0.5,
            open_plan_width_min: 1.6,
            open_plan_width_max: 3.0,
            corner_margin: 0.25,
            clearance: 1.0,
            leaves: true,
            closed_probability: 0.3,
        }
    }
}

impl Default for FurnitureConfig {
    fn default() -> Self {
        FurnitureConfig {
            density: 1.0,
            attempts: 24,
            clutter: 1.0,
            pieces: 1.0,
            sets: 1.0,
            small_objects_max: 7,
            small_object_probability: 0.95,
            nav_radius: 0.4,
            gap: 0.05,
        }
    }
}

impl Default for FloorsConfig {
    fn default() -> Self {
        FloorsConfig {
            two_storey_share: 0.3,
            slab: 0.1,
            max_riser: 0.18,
            tread: 0.28,
            stair_width: 1.0,
        }
    }
}

impl Default for ProcgenConfig {
    /// The documented default: identical to the shipped `vlnverse` preset (263 homes, 3-10
    /// rooms, seed 2026).
    fn default() -> Self {
        ProcgenConfig {
            scenes: ScenesConfig::default(),
            rooms: RoomsConfig::default(),
            walls: WallsConfig::default(),
            doors: DoorsConfig::default(),
            furniture: FurnitureConfig::default(),
            floors: FloorsConfig::default(),
        }
    }
}

/// Most scenes one config may ask for.
const MAX_SCENES: usize = 100_000;

fn check(ok: bool, field: &str, value: impl ToString, reason: &str) -> Result<()> {
    if ok {
        Ok(())
    } else {
        Err(EnvError::invalid(field, value, reason))
    }
}

fn positive(field: &str, v: f32) -> Result<()> {
    check(
        v.is_finite() && v > 0.0,
        field,
        v,
        "must be a positive number",
    )
}

fn probability(field: &str, v: f32) -> Result<()> {
    check(
        v.is_finite() && (0.0..=1.0).contains(&v),
        field,
        v,
        "must be a probability in [0, 1]",
    )
}

impl ProcgenConfig {
    /// Parse a TOML string; `path` (if any) is named in errors.
    pub fn from_toml_str(text: &str, path: Option<&Path>) -> Result<Self> {
        let shown = path.unwrap_or_else(|| Path::new("<string>"));
        let cfg: ProcgenConfig =
            toml::from_str(text).map_err(|e| EnvError::parse(shown, e.to_string()))?;
        match cfg.validate() {
            Ok(()) => Ok(cfg),
            Err(e) => Err(match path {
                Some(p) => e.in_file(p),
                None => e,
            }),
        }
    }

    /// Read, parse and validate a TOML file. Errors name the file and the dotted field.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| EnvError::io(path, e))?;
        Self::from_toml_str(&text, Some(path))
    }

    /// Check every value; the error names the dotted field and the value.
    pub fn validate(&self) -> Result<()> {
        let s = &self.scenes;
        check(
            !s.id_prefix.is_empty()
                && s.id_prefix
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-'),
            "scenes.id_prefix",
            format!("{:?}", s.id_prefix),
            "must be non-empty ASCII letters, digits, '_' or '-' (it names folders)",
        )?;

        check(
            s.count <= MAX_SCENES,
            "scenes.count",
            s.count,
            &format!("must be at most {MAX_SCENES}"),
        )?;

        let r = &self.rooms;
        check(
            (1..=16).contains(&r.count_min),
            "rooms.count_min",
            r.count_min,
            "must be between 1 and 16",
        )?;
        check(
            (1..=16).contains(&r.count_max),
            "rooms.count_max",
            r.count_max,
            "must be between 1 and 16",
        )?;
        check(
            r.count_min <= r.count_max,
            "rooms.count_min",
            r.count_min,
            &format!("must not exceed rooms.count_max = {}", r.count_max),
        )?;
        positive("rooms.min_side", r.min_side)?;
        check(
            r.min_side >= 1.5,
            "rooms.min_side",
            r.min_side,
            "must be at least 1.5 m so an agent fits through a room",
        )?;
        check(
            r.min_side <= 20.0,
            "rooms.min_side",
            r.min_side,
            "must be at most 20 m",
        )?;
        check(
            r.max_aspect.is_finite() && (1.5..=10.0).contains(&r.max_aspect),
            "rooms.max_aspect",
            r.max_aspect,
            "must be in [1.5, 10]",
        )?;
        positive("rooms.area_scale_min", r.area_scale_min)?;
        positive("rooms.area_scale_max", r.area_scale_max)?;
        check(
            r.area_scale_max <= 10.0,
            "rooms.area_scale_max",
            r.area_scale_max,
            "must be at most 10",
        )?;
        check(
            r.kinds.len() <= 64,
            "rooms.kinds",
            format!("({} kinds)", r.kinds.len()),
            "must list at most 64 kinds",
        )?;
        check(
            r.area_scale_min <= r.area_scale_max,
            "rooms.area_scale_min",
            r.area_scale_min,
            &format!(
                "must not exceed rooms.area_scale_max = {}",
                r.area_scale_max
            ),
        )?;
        check(
            !r.kinds.is_empty(),
            "rooms.kinds",
            "[]",
            "needs at least one room kind",
        )?;
        let mut capacity = 0;
        let mut any_weight = false;
        for (i, k) in r.kinds.iter().enumerate() {
            let f = |name: &str| format!("rooms.kinds[{i}].{name}");
            check(
                k.count_min <= k.count_max,
                &f("count_min"),
                k.count_min,
                &format!("must not exceed count_max = {}", k.count_max),
            )?;
            check(
                k.count_max <= 16,
                &f("count_max"),
                k.count_max,
                "must be at most 16 (rooms.count_max's limit)",
            )?;
            check(
                k.weight.is_finite() && (0.0..=1000.0).contains(&k.weight),
                &f("weight"),
                k.weight,
                "must be in [0, 1000]",
            )?;
            positive(&f("area_min"), k.area_min)?;
            positive(&f("area_max"), k.area_max)?;
            check(
                k.area_max <= 500.0,
                &f("area_max"),
                k.area_max,
                "must be at most 500 m^2",
            )?;
            check(
                k.area_min <= k.area_max,
                &f("area_min"),
                k.area_min,
                &format!("must not exceed area_max = {}", k.area_max),
            )?;
            let side = r.min_side;
            check(
                k.area_min * r.area_scale_min >= side * side * 0.8,
                &f("area_min"),
                k.area_min,
                &format!("is too small for rooms.min_side = {side} m"),
            )?;
            capacity += k.count_max;
            any_weight |= k.weight > 0.0 && k.count_max > k.count_min;
            if let Some(j) = r.kinds[..i].iter().position(|o| o.kind == k.kind) {
                return Err(EnvError::invalid(
                    f("kind"),
                    k.kind,
                    format!("duplicates rooms.kinds[{j}]"),
                ));
            }
        }
        check(
            capacity >= r.count_max,
            "rooms.count_max",
            r.count_max,
            &format!("exceeds the sum of the kinds' count_max ({capacity})"),
        )?;
        let required: usize = r.kinds.iter().map(|k| k.count_min).sum();
        check(
            any_weight || required >= r.count_max,
            "rooms.kinds",
            "(weights)",
            "some kind needs a positive weight to draw extra rooms",
        )?;

        let w = &self.walls;
        positive("walls.thickness", w.thickness)?;
        check(
            w.thickness <= 0.5,
            "walls.thickness",
            w.thickness,
            "must be at most 0.5 m",
        )?;
        positive("walls.height", w.height)?;
        check(
            w.height <= 10.0,
            "walls.height",
            w.height,
            "must be at most 10 m",
        )?;

        let d = &self.doors;
        check(
            d.width_min.is_finite() && d.width_min >= 0.9,
            "doors.width_min",
            d.width_min,
            "must be at least 0.9 m (an agent of radius 0.3 m must pass)",
        )?;
        check(
            d.width_max.is_finite() && d.width_max >= d.width_min,
            "doors.width_max",
            d.width_max,
            &format!("must be at least doors.width_min = {}", d.width_min),
        )?;
        check(
            d.head_height.is_finite() && d.head_height >= 1.8 && d.head_height < w.height,
            "doors.head_height",
            d.head_height,
            &format!(
                "must be at least 1.8 m and below walls.height = {}",
                w.height
            ),
        )?;
        positive("doors.frame_width", d.frame_width)?;
        probability("doors.extra_door_probability", d.extra_door_probability)?;
        probability("doors.open_plan_probability", d.open_plan_probability)?;
        probability("doors.closed_probability", d.closed_probability)?;
        check(
            d.open_plan_width_min.is_finite() && d.open_plan_width_min >= d.width_min,
            "doors.open_plan_width_min",
            d.open_plan_width_min,
            &format!("must be at least doors.width_min = {}", d.width_min),
        )?;
        check(
            d.open_plan_width_max.is_finite() && d.open_plan_width_max >= d.open_plan_width_min,
            "doors.open_plan_width_max",
            d.open_plan_width_max,
            &format!(
                "must be at least doors.open_plan_width_min = {}",
                d.open_plan_width_min
            ),
        )?;
        check(
            d.corner_margin.is_finite() && d.corner_margin >= 0.0,
            "doors.corner_margin",
            d.corner_margin,
            "must be a non-negative number",
        )?;
        check(
            d.clearance.is_finite() && d.clearance >= 0.6,
            "doors.clearance",
            d.clearance,
            "must be at least 0.6 m",
        )?;
        let needed = d.width_min + 2.0 * (d.frame_width + d.corner_margin) + w.thickness;
        check(
            r.min_side >= needed,
            "rooms.min_side",
            r.min_side,
            &format!("must fit a door with its frame and corner margins ({needed:.2} m)"),
        )?;

        let f = &self.furniture;
        check(
            f.density.is_finite() && (0.0..=4.0).contains(&f.density),
            "furniture.density",
            f.density,
            "must be in [0, 4]",
        )?;
        check(
            (1..=1000).contains(&f.attempts),
            "furniture.attempts",
            f.attempts,
            "must be between 1 and 1000",
        )?;
        check(
            f.clutter.is_finite() && (0.0..=4.0).contains(&f.clutter),
            "furniture.clutter",
            f.clutter,
            "must be in [0, 4]",
        )?;
        check(
            f.pieces.is_finite() && (0.0..=4.0).contains(&f.pieces),
            "furniture.pieces",
            f.pieces,
            "must be in [0, 4]",
        )?;
        check(
            f.sets.is_finite() && (0.0..=4.0).contains(&f.sets),
            "furniture.sets",
            f.sets,
            "must be in [0, 4]",
        )?;
        check(
            f.small_objects_max <= 8,
            "furniture.small_objects_max",
            f.small_objects_max,
            "must be at most 8",
        )?;
        probability(
            "furniture.small_object_probability",
            f.small_object_probability,
        )?;
        check(
            f.nav_radius.is_finite() && (0.1..=1.0).contains(&f.nav_radius),
            "furniture.nav_radius",
            f.nav_radius,
            "must be in [0.1, 1.0] m",
        )?;
        let need = w.thickness * 0.5 + 2.0 * f.nav_radius + 0.1;
        check(
            d.clearance >= need - 1e-4,
            "doors.clearance",
            d.clearance,
            &format!(
                "must be at least {need:.2} m (half a wall plus twice furniture.nav_radius plus 0.1)"
            ),
        )?;
        check(
            f.gap.is_finite() && (0.0..=0.5).contains(&f.gap),
            "furniture.gap",
            f.gap,
            "must be in [0, 0.5] m",
        )?;

        let fl = &self.floors;
        probability("floors.two_storey_share", fl.two_storey_share)?;
        let range = |field: &str, v: f32, lo: f32, hi: f32, unit: &str| {
            check(
                v.is_finite() && (lo..=hi).contains(&v),
                field,
                v,
                &format!("must be in [{lo}, {hi}]{unit}"),
            )
        };
        range("floors.slab", fl.slab, 0.05, 0.5, " m")?;
        range("floors.max_riser", fl.max_riser, 0.1, 0.2, " m")?;
        range("floors.tread", fl.tread, 0.22, 0.4, " m")?;
        range("floors.stair_width", fl.stair_width, 0.8, 2.0, " m")?;
        let need = 2.0 * f.nav_radius + 0.1;
        check(
            fl.stair_width >= need - 1e-4,
            "floors.stair_width",
            fl.stair_width,
            &format!("must be at least {need:.2} m (twice furniture.nav_radius plus 0.1)"),
        )?;
        Ok(())
    }
}
