//! Surface materials and their procedural textures, shared by the glTF writer and the renderers
//! so that `scene.glb` in a viewer and the agent's camera show the same surfaces.
//!
//! A material is derived from what the scene already says (class, material word, room, seed;
//! see [`surface_of`]), so old scene files get materials too. Each [`Surface`] has one seeded,
//! tileable [`TEX_SIZE`]-square texture of multipliers in `[0, 1]` (grain, weave, grout,
//! stripes, brick courses) that repeats every [`Surface::repeat`] metres. Texture coordinates are a box
//! projection of the world position ([`box_uv`]), so patterns run on across neighbouring parts.
//! The texel is multiplied with the part colour and the baked light ([`crate::light`]), as
//! glTF multiplies `baseColorFactor`, `baseColorTexture` and `COLOR_0`.

use crate::scene::{Scene, SceneObject};
use crate::vocab::SemanticClass;
use glam::Vec3;
use std::sync::OnceLock;

mod patterns;
mod pictures;

/// Side of every texture in texels (a power of two: renderers wrap with a mask).
pub const TEX_SIZE: usize = 128;

/// The surfaces that are pictures on a framed canvas, as one pattern (for [`Surface::is_picture`]
/// and the texel match, which must stay exhaustive).
macro_rules! picture_surfaces {
    () => {
        Surface::PaintingSailboat
            | Surface::PaintingBeach
            | Surface::PaintingLake
            | Surface::PaintingFlowers
            | Surface::PaintingTree
            | Surface::PaintingCircles
            | Surface::PaintingSquares
            | Surface::PaintingPortrait
            | Surface::PaintingHorse
            | Surface::PaintingZebra
            | Surface::PaintingHouse
            | Surface::PaintingGiraffe
            | Surface::PaintingElephant
            | Surface::PaintingMountains
            | Surface::PaintingOcean
            | Surface::PaintingWaterfall
            | Surface::PaintingCity
            | Surface::PaintingLighthouse
            | Surface::PaintingWindmill
            | Surface::PaintingBarn
            | Surface::PaintingNightSky
            | Surface::PaintingFruit
            | Surface::PaintingLion
            | Surface::PaintingCow
            | Surface::PaintingBirds
            | Surface::PaintingFish
            | Surface::PaintingCat
            | Surface::PaintingDog
            | Surface::PaintingButterfly
            | Surface::PaintingSunflowers
            | Surface::PaintingBridge
            | Surface::PaintingShip
            | Surface::PaintingWoman
            | Surface::PaintingMan
            | Surface::PaintingCheetah
    };
}

/// What a surface is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Surface {
    /// No pattern (plastic, glass, paper, unknown).
    Plain,
    /// Painted plaster walls and ceilings.
    Plaster,
    /// Striped wallpaper.
    Wallpaper,
    /// Wooden floor boards.
    WoodFloor,
    /// Square tiles with grout.
    Tiles,
    /// Carpet.
    Carpet,
    /// Wood grain (furniture, door frames).
    Wood,
    /// Woven fabric.
    Fabric,
    /// Leather.
    Leather,
    /// Brushed metal.
    Metal,
    /// Glazed ceramic.
    Ceramic,
    /// Window glass (daylight with faint reflections).
    Glass,
    /// A rug's woven pattern (a diamond lattice between bands).
    Rug,
    /// A painted canvas (a landscape of bands, hills and brush strokes).
    Painting,
    /// Brickwork in running bond (fireplaces).
    Brick,
    /// Stone blocks of uneven tone with mortar joints (fireplaces).
    Stone,
    /// A painted sailboat on the sea (a framed canvas: see [`Surface::is_picture`]).
    PaintingSailboat,
    /// A painted beach at sunset with a palm tree.
    PaintingBeach,
    /// A painted lake under snow-capped mountains.
    PaintingLake,
    /// Painted flowers in a vase.
    PaintingFlowers,
    /// A painted tree in a field.
    PaintingTree,
    /// Abstract art: discs and a ring.
    PaintingCircles,
    /// Abstract art: blocks of tone between black lines.
    PaintingSquares,
    /// A painted portrait: head and shoulders.
    PaintingPortrait,
    /// A painted horse in a field.
    PaintingHorse,
    /// A painted zebra in a field.
    PaintingZebra,
    /// A painted house: walls, a roof, a door and windows.
    PaintingHouse,
    /// A painted giraffe: a long neck and a coat of patches.
    PaintingGiraffe,
    /// A painted elephant: a big ear, a trunk and a tusk.
    PaintingElephant,
    /// Striped fabric.
    Striped,
    /// Checkered fabric (squares of two tones).
    Checkered,
    /// Plaid fabric (crossing bands).
    Plaid,
    /// Fabric printed with flowers.
    Floral,
    /// Fabric with polka dots.
    PolkaDot,
    /// Marble: pale stone with dark veins (worktops).
    Marble,
    /// Granite: speckled stone (worktops).
    Granite,
    /// Painted snowy mountains above a pine forest.
    PaintingMountains,
    /// Painted ocean waves.
    PaintingOcean,
    /// A painted waterfall between cliffs.
    PaintingWaterfall,
    /// A painted city skyline: towers with lit windows.
    PaintingCity,
    /// A painted lighthouse on rocks by the sea.
    PaintingLighthouse,
    /// A painted windmill in a field.
    PaintingWindmill,
    /// A painted barn with a silo and a fence (a farm).
    PaintingBarn,
    /// A painted night sky: a crescent moon and stars over hills.
    PaintingNightSky,
    /// A painted bowl of fruit: apples and bananas.
    PaintingFruit,
    /// A painted lion's head with its mane.
    PaintingLion,
    /// A painted cow with black patches on a hill.
    PaintingCow,
    /// Two painted birds on a branch.
    PaintingBirds,
    /// A painted fish under water.
    PaintingFish,
    /// A painted black cat sitting.
    PaintingCat,
    /// A painted dog's head with floppy ears.
    PaintingDog,
    /// A painted butterfly.
    PaintingButterfly,
    /// Painted sunflowers.
    PaintingSunflowers,
    /// A painted suspension bridge over water.
    PaintingBridge,
    /// A painted ship: a big hull, decks and two funnels.
    PaintingShip,
    /// A painted portrait of a woman with long hair.
    PaintingWoman,
    /// A painted portrait of a man with a beard, in a suit.
    PaintingMan,
    /// A painted cheetah: a spotted coat.
    PaintingCheetah,
}

impl Surface {
    /// Every surface, in index order.
    pub const ALL: [Surface; 58] = [
        Surface::Plain,
        Surface::Plaster,
        Surface::Wallpaper,
        Surface::WoodFloor,
        Surface::Tiles,
        Surface::Carpet,
        Surface::Wood,
        Surface::Fabric,
        Surface::Leather,
        Surface::Metal,
        Surface::Ceramic,
        Surface::Glass,
        Surface::Rug,
        Surface::Painting,
        Surface::Brick,
        Surface::Stone,
        Surface::PaintingSailboat,
        Surface::PaintingBeach,
        Surface::PaintingLake,
        Surface::PaintingFlowers,
        Surface::PaintingTree,
        Surface::PaintingCircles,
        Surface::PaintingSquares,
        Surface::PaintingPortrait,
        Surface::PaintingHorse,
        Surface::PaintingZebra,
        Surface::PaintingHouse,
        Surface::PaintingGiraffe,
        Surface::PaintingElephant,
        Surface::Striped,
        Surface::Checkered,
        Surface::Plaid,
        Surface::Floral,
        Surface::PolkaDot,
        Surface::Marble,
        Surface::Granite,
        Surface::PaintingMountains,
        Surface::PaintingOcean,
        Surface::PaintingWaterfall,
        Surface::PaintingCity,
        Surface::PaintingLighthouse,
        Surface::PaintingWindmill,
        Surface::PaintingBarn,
        Surface::PaintingNightSky,
        Surface::PaintingFruit,
        Surface::PaintingLion,
        Surface::PaintingCow,
        Surface::PaintingBirds,
        Surface::PaintingFish,
        Surface::PaintingCat,
        Surface::PaintingDog,
        Surface::PaintingButterfly,
        Surface::PaintingSunflowers,
        Surface::PaintingBridge,
        Surface::PaintingShip,
        Surface::PaintingWoman,
        Surface::PaintingMan,
        Surface::PaintingCheetah,
    ];

    /// Position in [`Surface::ALL`].
    pub fn index(self) -> usize {
        Surface::ALL.iter().position(|s| *s == self).unwrap_or(0)
    }

    /// Lower-case name (glTF material and image names).
    pub fn name(self) -> &'static str {
        match self {
            Surface::Plain => "plain",
            Surface::Plaster => "plaster",
            Surface::Wallpaper => "wallpaper",
            Surface::WoodFloor => "wood_floor",
            Surface::Tiles => "tiles",
            Surface::Carpet => "carpet",
            Surface::Wood => "wood",
            Surface::Fabric => "fabric",
            Surface::Leather => "leather",
            Surface::Metal => "metal",
            Surface::Ceramic => "ceramic",
            Surface::Glass => "glass",
            Surface::Rug => "rug",
            Surface::Painting => "painting",
            Surface::Brick => "brick",
            Surface::Stone => "stone",
            Surface::PaintingSailboat => "painting_sailboat",
            Surface::PaintingBeach => "painting_beach",
            Surface::PaintingLake => "painting_lake",
            Surface::PaintingFlowers => "painting_flowers",
            Surface::PaintingTree => "painting_tree",
            Surface::PaintingCircles => "painting_circles",
            Surface::PaintingSquares => "painting_squares",
            Surface::PaintingPortrait => "painting_portrait",
            Surface::PaintingHorse => "painting_horse",
            Surface::PaintingZebra => "painting_zebra",
            Surface::PaintingHouse => "painting_house",
            Surface::PaintingGiraffe => "painting_giraffe",
            Surface::PaintingElephant => "painting_elephant",
            Surface::Striped => "striped",
            Surface::Checkered => "checkered",
            Surface::Plaid => "plaid",
            Surface::Floral => "floral",
            Surface::PolkaDot => "polka_dot",
            Surface::Marble => "marble",
            Surface::Granite => "granite",
            Surface::PaintingMountains => "painting_mountains",
            Surface::PaintingOcean => "painting_ocean",
            Surface::PaintingWaterfall => "painting_waterfall",
            Surface::PaintingCity => "painting_city",
            Surface::PaintingLighthouse => "painting_lighthouse",
            Surface::PaintingWindmill => "painting_windmill",
            Surface::PaintingBarn => "painting_barn",
            Surface::PaintingNightSky => "painting_night_sky",
            Surface::PaintingFruit => "painting_fruit",
            Surface::PaintingLion => "painting_lion",
            Surface::PaintingCow => "painting_cow",
            Surface::PaintingBirds => "painting_birds",
            Surface::PaintingFish => "painting_fish",
            Surface::PaintingCat => "painting_cat",
            Surface::PaintingDog => "painting_dog",
            Surface::PaintingButterfly => "painting_butterfly",
            Surface::PaintingSunflowers => "painting_sunflowers",
            Surface::PaintingBridge => "painting_bridge",
            Surface::PaintingShip => "painting_ship",
            Surface::PaintingWoman => "painting_woman",
            Surface::PaintingMan => "painting_man",
            Surface::PaintingCheetah => "painting_cheetah",
        }
    }

    /// Metres covered by one repeat of the texture.
    pub fn repeat(self) -> f32 {
        match self {
            Surface::WoodFloor => 2.0,
            Surface::Tiles => 1.2,
            Surface::Plaster => 2.0,
            Surface::Fabric | Surface::Leather => 0.8,
            Surface::Rug => 1.6,
            Surface::Painting => 0.5,
            Surface::Brick | Surface::Stone => 0.8,
            Surface::Striped | Surface::Checkered => 0.6,
            Surface::Plaid => 0.8,
            Surface::Floral | Surface::PolkaDot => 0.5,
            Surface::Marble => 1.2,
            Surface::Granite => 0.6,
            _ => 1.0,
        }
    }

    /// Whether it is a picture on a framed canvas, drawn once over the canvas (see
    /// [`picture_uv`]) rather than repeated every [`Surface::repeat`] metres.
    pub fn is_picture(self) -> bool {
        matches!(self, picture_surfaces!())
    }

    /// Whether glTF should call it metallic.
    pub fn metallic(self) -> bool {
        self == Surface::Metal
    }

    /// The texture: `TEX_SIZE * TEX_SIZE` RGB multipliers (255 = 1), row-major, `v` down the
    /// rows: [`Surface::luma`] times [`Surface::tint`]. Built once per process.
    pub fn texture(self) -> &'static [[u8; 3]] {
        static TEX: OnceLock<Vec<Vec<[u8; 3]>>> = OnceLock::new();
        &TEX.get_or_init(|| {
            Surface::ALL
                .iter()
                .map(|s| {
                    let tint = s.tint();
                    s.luma()
                        .iter()
                        .map(|&g| tint.map(|t| (g as f32 * t).round().min(255.0) as u8))
                        .collect()
                })
                .collect()
        })[self.index()]
    }

    /// The grey part of the texture (renderers fetch one byte per texel and fold the tint into
    /// the vertex colours).
    pub fn luma(self) -> &'static [u8] {
        static LUMA: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
        &LUMA.get_or_init(|| Surface::ALL.iter().map(|s| s.generate()).collect())[self.index()]
    }

    /// [`Surface::luma`] encoded for display (each value `v / 255` raised to `1 / 2.2`, times
    /// 255): renderers multiply encoded colours (see `vlnverse_sensors::SceneMesh`).
    pub fn luma_encoded(self) -> &'static [u8] {
        static ENC: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
        &ENC.get_or_init(|| {
            Surface::ALL
                .iter()
                .map(|s| {
                    s.luma()
                        .iter()
                        .map(|&g| ((g as f32 / 255.0).powf(1.0 / 2.2) * 255.0).round() as u8)
                        .collect()
                })
                .collect()
        })[self.index()]
    }

    /// The constant colour cast of the texture (warm wood), per channel.
    pub fn tint(self) -> [f32; 3] {
        match self {
            Surface::WoodFloor => [1.02, 1.0, 0.96],
            Surface::Wood => [1.02, 1.0, 0.95],
            _ => [1.0; 3],
        }
    }

    fn generate(self) -> Vec<u8> {
        let n = TEX_SIZE;
        let seed = 0x9e37_79b9 ^ (self.index() as u32).wrapping_mul(0x85eb_ca6b);
        let mut out = Vec::with_capacity(n * n);
        for y in 0..n {
            for x in 0..n {
                let (fx, fy) = (x as f32, y as f32);
                let v: f32 = match self {
                    Surface::Plain => 0.9,
                    Surface::Plaster => {
                        grey(0.85 + 0.1 * fbm(seed, fx, fy, 16.0) + 0.05 * hash01(seed, x, y))
                    }
                    Surface::Wallpaper => {
                        // Stripes of two widths and a faint dotted motif.
                        let s = (x % 32) as f32;
                        let stripe = if s < 14.0 {
                            0.93
                        } else if s < 16.0 {
                            0.8
                        } else {
                            0.86
                        };
                        let dot = if (x % 32 == 23) && (y % 16 == 8) {
                            -0.08
                        } else {
                            0.0
                        };
                        grey(stripe + dot + 0.02 * fbm(seed, fx, fy, 8.0))
                    }
                    Surface::WoodFloor => {
                        // Boards 16 texels wide (along v), 64 long with staggered joints.
                        let row = y / 16;
                        let off = (hash(seed, row, 7) % 64) as usize;
                        let plank = (x + off) / 64;
                        let joint = (x + off).is_multiple_of(64) || y.is_multiple_of(16);
                        let tone = 0.78 + 0.14 * hash01(seed, plank, row);
                        let grain = 0.06 * (fy * 0.9 + 6.0 * fbm(seed ^ 5, fx, fy, 24.0)).sin();
                        if joint {
                            0.5
                        } else {
                            tone + grain
                        }
                    }
                    Surface::Tiles => {
                        let grout = x % 32 < 2 || y % 32 < 2;
                        let t = hash01(seed, x / 32, y / 32);
                        grey(if grout {
                            0.62
                        } else {
                            0.9 + 0.06 * t + 0.02 * fbm(seed, fx, fy, 8.0)
                        })
                    }
                    Surface::Carpet => {
                        grey(0.78 + 0.1 * fbm(seed, fx, fy, 6.0) + 0.1 * hash01(seed, x, y))
                    }
                    Surface::Wood => {
                        let g = (fx * 0.35 + 9.0 * fbm(seed, fx, fy, 32.0)).sin();
                        0.8 + 0.08 * g + 0.04 * fbm(seed ^ 3, fx, fy, 4.0)
                    }
                    Surface::Fabric => {
                        let warp = (x / 2 + y / 2) % 2 == 0;
                        grey(if warp { 0.86 } else { 0.76 } + 0.06 * fbm(seed, fx, fy, 12.0))
                    }
                    Surface::Leather => {
                        grey(0.8 + 0.12 * fbm(seed, fx, fy, 5.0) - 0.05 * hash01(seed, x, y))
                    }
                    Surface::Metal => grey(0.82 + 0.1 * fbm(seed, fx * 0.05, fy, 3.0)),
                    Surface::Ceramic => grey(0.92 + 0.03 * fbm(seed, fx, fy, 32.0)),
                    Surface::Glass => {
                        // Two soft diagonal reflections over bright daylight.
                        let d = ((x + y) % 128) as f32;
                        let streak = (-(d - 40.0).powi(2) / 60.0).exp()
                            + 0.6 * (-(d - 58.0).powi(2) / 20.0).exp();
                        0.9 + 0.1 * streak + 0.01 * fbm(seed, fx, fy, 16.0)
                    }
                    Surface::Rug => {
                        // Diamonds of 32 texels with a dark outline, bands every 64 rows,
                        // over a fine weave.
                        let (u, v) = ((x % 32) as f32 - 16.0, (y % 32) as f32 - 16.0);
                        let r = u.abs() + v.abs();
                        let motif = if (r - 12.0).abs() < 1.5 {
                            0.45
                        } else if r < 5.0 {
                            0.62
                        } else if r < 12.0 {
                            0.95
                        } else {
                            0.78
                        };
                        let band = if y % 64 < 4 { 0.55 } else { motif };
                        let weave = if (x + y) % 2 == 0 { 0.03 } else { -0.03 };
                        band + weave + 0.05 * fbm(seed, fx, fy, 8.0)
                    }
                    Surface::Painting => {
                        // Sky brightening to a horizon, two hill lines, brush noise.
                        let hill =
                            70.0 + 10.0 * (fx * 0.05).sin() + 6.0 * fbm(seed, fx, 0.0, 16.0) * 8.0;
                        let far = 58.0 + 8.0 * (fx * 0.09 + 1.0).sin();
                        let base = if fy > hill {
                            0.45 + 0.1 * (fy - hill) / 58.0
                        } else if fy > far {
                            0.68
                        } else {
                            0.98 - 0.3 * (fy / 58.0)
                        };
                        base + 0.08 * fbm(seed ^ 11, fx, fy * 0.25, 8.0)
                    }
                    Surface::Brick => {
                        // Courses 16 texels high, bricks 32 long, every other course shifted
                        // by half a brick; mortar 2 texels wide.
                        let course = y / 16;
                        let shift = if course.is_multiple_of(2) { 0 } else { 16 };
                        let brick = (x + shift) / 32;
                        let mortar = y % 16 < 2 || (x + shift) % 32 < 2;
                        if mortar {
                            1.0
                        } else {
                            0.7 + 0.16 * hash01(seed, brick, course) + 0.05 * fbm(seed, fx, fy, 6.0)
                        }
                    }
                    Surface::Stone => {
                        // Blocks of 32 x 21 texels in staggered rows, each its own tone.
                        let row = y * 6 / TEX_SIZE;
                        let shift = if row.is_multiple_of(2) { 0 } else { 13 };
                        let block = (x + shift) / 32;
                        let joint = (y * 6) % TEX_SIZE < 6 || (x + shift) % 32 < 2;
                        if joint {
                            0.55
                        } else {
                            0.72 + 0.2 * hash01(seed, block, row) + 0.08 * fbm(seed, fx, fy, 8.0)
                        }
                    }
                    picture_surfaces!() => pictures::texel(self, seed, x, y).unwrap_or(0.9),
                    Surface::Striped
                    | Surface::Checkered
                    | Surface::Plaid
                    | Surface::Floral
                    | Surface::PolkaDot
                    | Surface::Marble
                    | Surface::Granite => patterns::texel(self, seed, x, y).unwrap_or(0.9),
                };
                out.push((v.clamp(0.0, 1.0) * 255.0).round() as u8);
            }
        }
        out
    }
}

fn grey(v: f32) -> f32 {
    v
}

pub(crate) fn hash(seed: u32, x: usize, y: usize) -> u32 {
    let mut h = seed ^ (x as u32).wrapping_mul(0x27d4_eb2d) ^ (y as u32).wrapping_mul(0x1656_67b1);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^ (h >> 15)
}

pub(crate) fn hash01(seed: u32, x: usize, y: usize) -> f32 {
    (hash(seed, x, y) >> 8) as f32 / (1u32 << 24) as f32
}

/// Tileable value noise with period [`TEX_SIZE`] at lattice spacing `cell` texels, in
/// `[-0.5, 0.5]`, two octaves.
pub(crate) fn fbm(seed: u32, x: f32, y: f32, cell: f32) -> f32 {
    let mut sum = 0.0;
    let mut amp = 0.65;
    let mut c = cell;
    for o in 0..2u32 {
        let period = ((TEX_SIZE as f32 / c).round() as usize).max(1);
        let (gx, gy) = (x / c, y / c);
        let (ix, iy) = (gx.floor(), gy.floor());
        let (tx, ty) = (gx - ix, gy - iy);
        let (sx, sy) = (tx * tx * (3.0 - 2.0 * tx), ty * ty * (3.0 - 2.0 * ty));
        let at = |i: f32, j: f32| {
            let (i, j) = (
                (i as i64).rem_euclid(period as i64) as usize,
                (j as i64).rem_euclid(period as i64) as usize,
            );
            hash01(seed.wrapping_add(o), i, j) - 0.5
        };
        let a = at(ix, iy) + (at(ix + 1.0, iy) - at(ix, iy)) * sx;
        let b = at(ix, iy + 1.0) + (at(ix + 1.0, iy + 1.0) - at(ix, iy + 1.0)) * sx;
        sum += amp * (a + (b - a) * sy);
        amp *= 0.5;
        c = (c * 0.5).max(1.0);
    }
    sum
}

/// Which parts of an object a feature's surface covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Covers {
    /// Every part (an upholstered sofa, a rug).
    Object,
    /// The canvas of a framed picture: its last part (the generator adds the canvas after the
    /// frame); the frame is wood.
    Canvas,
    /// The worktop: the highest thin slab that spans the object's footprint ([`worktop`]).
    Top,
}

/// The recorded features (`SceneObject::features`) that change how an object is drawn: what a
/// framed canvas shows, the pattern of a fabric, the stone of a worktop; with the surface each
/// draws and the parts it covers. A generator that records one of these must record at most
/// one per object; the first listed wins otherwise.
pub const FEATURE_SURFACES: &[(&str, Surface, Covers)] = &[
    ("landscape", Surface::Painting, Covers::Canvas),
    ("sailboat", Surface::PaintingSailboat, Covers::Canvas),
    ("beach", Surface::PaintingBeach, Covers::Canvas),
    ("lake", Surface::PaintingLake, Covers::Canvas),
    (
        "flowers in a vase",
        Surface::PaintingFlowers,
        Covers::Canvas,
    ),
    ("tree", Surface::PaintingTree, Covers::Canvas),
    ("abstract circles", Surface::PaintingCircles, Covers::Canvas),
    ("abstract squares", Surface::PaintingSquares, Covers::Canvas),
    ("portrait", Surface::PaintingPortrait, Covers::Canvas),
    ("horse", Surface::PaintingHorse, Covers::Canvas),
    ("zebra", Surface::PaintingZebra, Covers::Canvas),
    ("house", Surface::PaintingHouse, Covers::Canvas),
    ("giraffe", Surface::PaintingGiraffe, Covers::Canvas),
    ("elephant", Surface::PaintingElephant, Covers::Canvas),
    ("mountains", Surface::PaintingMountains, Covers::Canvas),
    ("ocean", Surface::PaintingOcean, Covers::Canvas),
    ("waterfall", Surface::PaintingWaterfall, Covers::Canvas),
    ("city", Surface::PaintingCity, Covers::Canvas),
    ("lighthouse", Surface::PaintingLighthouse, Covers::Canvas),
    ("windmill", Surface::PaintingWindmill, Covers::Canvas),
    ("barn", Surface::PaintingBarn, Covers::Canvas),
    ("night sky", Surface::PaintingNightSky, Covers::Canvas),
    ("fruit", Surface::PaintingFruit, Covers::Canvas),
    ("lion", Surface::PaintingLion, Covers::Canvas),
    ("cow", Surface::PaintingCow, Covers::Canvas),
    ("birds", Surface::PaintingBirds, Covers::Canvas),
    ("fish", Surface::PaintingFish, Covers::Canvas),
    ("cat", Surface::PaintingCat, Covers::Canvas),
    ("dog", Surface::PaintingDog, Covers::Canvas),
    ("butterfly", Surface::PaintingButterfly, Covers::Canvas),
    ("sunflowers", Surface::PaintingSunflowers, Covers::Canvas),
    ("bridge", Surface::PaintingBridge, Covers::Canvas),
    ("ship", Surface::PaintingShip, Covers::Canvas),
    ("woman", Surface::PaintingWoman, Covers::Canvas),
    ("man", Surface::PaintingMan, Covers::Canvas),
    ("cheetah", Surface::PaintingCheetah, Covers::Canvas),
    ("striped", Surface::Striped, Covers::Object),
    ("checkered", Surface::Checkered, Covers::Object),
    ("plaid", Surface::Plaid, Covers::Object),
    ("floral", Surface::Floral, Covers::Object),
    ("polka dots", Surface::PolkaDot, Covers::Object),
    ("marble top", Surface::Marble, Covers::Top),
    ("granite top", Surface::Granite, Covers::Top),
];

/// The surface a feature of `o` draws, and the parts it covers ([`FEATURE_SURFACES`]).
pub fn feature_surface(o: &SceneObject) -> Option<(Surface, Covers)> {
    FEATURE_SURFACES
        .iter()
        .find(|(f, _, _)| o.features.iter().any(|g| g == f))
        .map(|&(_, s, c)| (s, c))
}

/// The surface of each part of `o`, in part order: [`surface_of`], except where a recorded
/// feature draws a canvas's picture or a worktop's stone ([`feature_surface`]), and on a glass
/// door (class `door`, material `glass`), whose panes are glass and whose frame is not.
pub fn part_surfaces(scene: &Scene, o: &SceneObject) -> Vec<Surface> {
    let base = surface_of(scene, o);
    let mut out = vec![base; o.parts.len()];
    match feature_surface(o) {
        Some((s, Covers::Canvas)) => {
            out.fill(Surface::Wood);
            if let Some(last) = out.last_mut() {
                *last = s;
            }
        }
        Some((s, Covers::Top)) => {
            if let Some(i) = worktop(o) {
                out[i] = s;
            }
        }
        Some((_, Covers::Object)) | None => {}
    }
    if o.class == SemanticClass::Door && o.material == "glass" {
        // A glass door: its panes glass, its frame painted or (in wood tones) wood.
        let frame = if matches!(o.color.as_str(), "wooden" | "brown") {
            Surface::Wood
        } else {
            Surface::Plain
        };
        for (s, p) in out.iter_mut().zip(&o.parts) {
            let pane = match p.shape {
                crate::scene::Shape::Cuboid { half_extents, .. } => {
                    half_extents.iter().copied().fold(f32::MAX, f32::min) <= PANE_HALF
                }
                _ => false,
            };
            *s = if pane { Surface::Glass } else { frame };
        }
    }
    out
}

/// Half the thickness of the thickest part of a glass door drawn as glass (m): its panes are
/// 1 cm thick, its frame 4 cm.
const PANE_HALF: f32 = 0.006;

/// The index of `o`'s worktop: of its box parts no thicker than 8 cm that cover at least 60%
/// of the largest box part's footprint, the one whose top is highest (in the object's frame);
/// `None` when there is none.
pub fn worktop(o: &SceneObject) -> Option<usize> {
    let boxes: Vec<(usize, [f32; 3], f32)> = o
        .parts
        .iter()
        .enumerate()
        .filter_map(|(i, p)| match p.shape {
            crate::scene::Shape::Cuboid { half_extents, .. } => {
                Some((i, half_extents, p.transform.position[1] + half_extents[1]))
            }
            _ => None,
        })
        .collect();
    let widest = boxes
        .iter()
        .map(|(_, h, _)| h[0] * h[2])
        .fold(0.0f32, f32::max);
    boxes
        .iter()
        .filter(|(_, h, _)| h[1] <= 0.04 && h[0] * h[2] >= 0.6 * widest)
        .max_by(|a, b| a.2.total_cmp(&b.2))
        .map(|&(i, _, _)| i)
}

/// Texture coordinates in `[0, 1]` of a world point `p` on a picture whose canvas spans the
/// world box `lo..hi`, seen from the side its normal `n` faces: `u` to the viewer's right, `v`
/// down, so the picture reads the same way round on every wall.
pub fn picture_uv(p: Vec3, n: Vec3, lo: Vec3, hi: Vec3) -> [f32; 2] {
    let size = (hi - lo).max(Vec3::splat(1e-6));
    let f = (p - lo) / size;
    let v = 1.0 - f.y;
    let u = if n.x.abs() > n.z.abs() {
        // Facing +x the viewer looks along -x, with -z to the right.
        if n.x > 0.0 {
            1.0 - f.z
        } else {
            f.z
        }
    } else if n.z >= 0.0 {
        f.x
    } else {
        1.0 - f.x
    };
    [u.clamp(0.0, 1.0), v.clamp(0.0, 1.0)]
}

/// The material of an object's surfaces: from its class (walls, floors, ceilings), its
/// material word, and for walls a choice seeded by the scene seed, so homes
/// differ in look as they differ in layout; a recorded feature's surface where it draws one
/// ([`feature_surface`]: for a worktop's stone see [`part_surfaces`]).
pub fn surface_of(scene: &Scene, o: &SceneObject) -> Surface {
    match feature_surface(o) {
        Some((s, Covers::Object | Covers::Canvas)) => return s,
        Some((_, Covers::Top)) | None => {}
    }
    let seed = scene.seed.unwrap_or(0);
    let pick = |salt: u64| {
        let h = hash((seed ^ (seed >> 32)) as u32, salt as usize, 0x5eed);
        h % 3
    };
    match o.class {
        // Skirting boards (low walls or raised floors) of wood or painted plastic.
        SemanticClass::Wall | SemanticClass::Floor
            if matches!(o.material.as_str(), "wood" | "plastic")
                && o.bbox.max[1] - o.bbox.min[1] > 0.06
                && o.bbox.max[1] - o.bbox.min[1] < 0.5 =>
        {
            if o.material == "wood" {
                Surface::Wood
            } else {
                Surface::Plain
            }
        }
        SemanticClass::Wall => {
            if pick(1) == 0 {
                Surface::Wallpaper
            } else {
                Surface::Plaster
            }
        }
        SemanticClass::Ceiling => Surface::Plaster,
        // A floor looks like what its material word says (carpet is a material of its own).
        SemanticClass::Floor => match o.material.as_str() {
            "tile" | "stone" | "marble" => Surface::Tiles,
            "carpet" => Surface::Carpet,
            "concrete" => Surface::Plaster,
            "wood" | "wooden" => Surface::WoodFloor,
            _ => Surface::Plain,
        },
        SemanticClass::DoorFrame => Surface::Wood,
        SemanticClass::Rug => Surface::Rug,
        _ if o.material == "canvas" => Surface::Painting,
        _ => match o.material.as_str() {
            "wood" | "wooden" => Surface::Wood,
            "fabric" | "cotton" | "wool" => Surface::Fabric,
            "leather" => Surface::Leather,
            "metal" | "steel" | "aluminium" => Surface::Metal,
            "ceramic" | "porcelain" | "tile" => Surface::Ceramic,
            "glass" => Surface::Glass,
            "brick" => Surface::Brick,
            "stone" => Surface::Stone,
            "wicker" => Surface::Fabric,
            _ => Surface::Plain,
        },
    }
}

/// Texture coordinates in metres of a world point on a surface with normal `n`: a box
/// projection onto the plane of the dominant normal axis (u along x or z, v down).
pub fn box_uv(p: Vec3, n: Vec3) -> [f32; 2] {
    let a = n.abs();
    if a.y >= a.x && a.y >= a.z {
        [p.x, p.z]
    } else if a.x >= a.z {
        [p.z, -p.y]
    } else {
        [p.x, -p.y]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn textures_are_deterministic_and_not_flat() {
        for s in Surface::ALL {
            let t = s.texture();
            assert_eq!(t.len(), TEX_SIZE * TEX_SIZE);
            assert_eq!(s.luma(), s.generate().as_slice(), "{s:?}");
            let distinct: std::collections::BTreeSet<_> = t.iter().collect();
            assert_eq!(distinct.len() == 1, s == Surface::Plain, "{s:?}");
        }
    }

    /// Mean and standard deviation of a grey texture (0..=255).
    fn stats(t: &[u8]) -> (f32, f32) {
        let n = t.len() as f32;
        let mean = t.iter().map(|&g| g as f32).sum::<f32>() / n;
        let var = t.iter().map(|&g| (g as f32 - mean).powi(2)).sum::<f32>() / n;
        (mean, var.sqrt())
    }

    /// The grey value at texel `(x, y)` of `s`.
    fn at(s: Surface, x: usize, y: usize) -> u8 {
        s.luma()[y * TEX_SIZE + x]
    }

    #[test]
    fn every_picture_and_pattern_has_contrast_and_differs_from_the_others() {
        let drawn: Vec<Surface> = FEATURE_SURFACES.iter().map(|f| f.1).collect();
        for (i, &a) in drawn.iter().enumerate() {
            let (mean, sd) = stats(a.luma());
            assert!(sd > 18.0, "{a:?}: flat (sd {sd:.1})");
            assert!((40.0..235.0).contains(&mean), "{a:?}: mean {mean:.1}");
            for &b in &drawn[..i] {
                let diff = a
                    .luma()
                    .iter()
                    .zip(b.luma())
                    .map(|(&x, &y)| (x as f32 - y as f32).abs())
                    .sum::<f32>()
                    / (TEX_SIZE * TEX_SIZE) as f32;
                assert!(diff > 15.0, "{a:?} and {b:?} differ by {diff:.1} a texel");
            }
        }
        let pictures = Surface::ALL.iter().filter(|s| s.is_picture()).count();
        assert_eq!(pictures, 35);
        assert!(!Surface::Painting.is_picture() && !Surface::Marble.is_picture());
    }

    #[test]
    fn pictures_show_their_subjects() {
        // The sailboat: a white sail over a dark hull, the sea darker than the sky.
        assert!(at(Surface::PaintingSailboat, 80, 60) > 240);
        assert!(at(Surface::PaintingSailboat, 64, 76) < 60);
        assert!(
            at(Surface::PaintingSailboat, 10, 110) + 60 < at(Surface::PaintingSailboat, 10, 30)
        );
        // The beach: the sun bright on the horizon, the palm dark.
        assert!(at(Surface::PaintingBeach, 64, 55) > 240);
        assert!(at(Surface::PaintingBeach, 21, 110) < 50);
        // The portrait: dark eyes in a light face.
        assert!(at(Surface::PaintingPortrait, 56, 54) < 50);
        assert!(at(Surface::PaintingPortrait, 64, 60) > 200);
        // The zebra: black and white across its body, the horse dark all over.
        let row: Vec<u8> = (40..76)
            .map(|x| at(Surface::PaintingZebra, x, 66))
            .collect();
        let flips = row.windows(2).filter(|w| w[0].abs_diff(w[1]) > 150).count();
        assert!(flips >= 6, "{row:?}");
        assert!((40..76).all(|x| at(Surface::PaintingHorse, x, 66) < 60));
        // Flowers: a white head with a dark centre above a dark vase.
        assert!(at(Surface::PaintingFlowers, 64, 20) > 230);
        assert!(at(Surface::PaintingFlowers, 64, 26) < 70);
        assert!(at(Surface::PaintingFlowers, 70, 96) < 70);
        // The house: a dark roof over light walls; the elephant grey with a white tusk; the
        // giraffe patched.
        assert!(at(Surface::PaintingHouse, 64, 50) < 80);
        assert!(at(Surface::PaintingHouse, 45, 95) > 200);
        assert!((90..150).contains(&at(Surface::PaintingElephant, 60, 66)));
        assert!(at(Surface::PaintingElephant, 103, 74) > 220);
        let coat: Vec<u8> = (40..72)
            .map(|x| at(Surface::PaintingGiraffe, x, 68))
            .collect();
        let flips = coat
            .windows(2)
            .filter(|w| w[0].abs_diff(w[1]) > 100)
            .count();
        assert!(flips >= 4, "{coat:?}");
        // The night sky: a bright moon in a dark sky; the lighthouse: a bright lantern over a
        // tower of light and dark bands; the ship: dark funnel tops over white decks and a
        // dark hull.
        assert!(at(Surface::PaintingNightSky, 80, 32) > 240);
        assert!(at(Surface::PaintingNightSky, 30, 60) < 80);
        assert!(at(Surface::PaintingLighthouse, 60, 25) > 240);
        assert!(at(Surface::PaintingLighthouse, 64, 40) > 200);
        assert!(at(Surface::PaintingLighthouse, 64, 50) < 80);
        assert!(at(Surface::PaintingShip, 55, 26) < 50);
        assert!(at(Surface::PaintingShip, 40, 60) > 220);
        assert!(at(Surface::PaintingShip, 60, 84) < 60);
        // The lion: a dark nose in a light face ringed by a darker mane; the cat: light eyes
        // in a black head.
        assert!(at(Surface::PaintingLion, 64, 73) < 50);
        assert!(at(Surface::PaintingLion, 64, 64) > 160);
        assert!(at(Surface::PaintingLion, 64, 20) < 110);
        assert!(at(Surface::PaintingCat, 54, 46) > 200);
        assert!(at(Surface::PaintingCat, 64, 36) < 60);
        // The woman's long hair beside her neck; the man's beard under a light cheek.
        assert!(at(Surface::PaintingWoman, 42, 80) < 70);
        assert!(at(Surface::PaintingWoman, 70, 62) > 200);
        assert!(at(Surface::PaintingMan, 64, 76) < 70);
        assert!(at(Surface::PaintingMan, 56, 58) > 190);
        // Sunflowers: a dark seed head ringed by light petals; the cow white with black
        // patches; the cheetah spotted.
        assert!(at(Surface::PaintingSunflowers, 36, 44) < 90);
        assert!(at(Surface::PaintingSunflowers, 51, 44) > 220);
        assert!(at(Surface::PaintingCow, 50, 60) < 40);
        assert!(at(Surface::PaintingCow, 60, 70) > 220);
        let coat: Vec<u8> = (40..76)
            .map(|x| at(Surface::PaintingCheetah, x, 58))
            .collect();
        let spots = coat.windows(2).filter(|w| w[0].abs_diff(w[1]) > 80).count();
        assert!(spots >= 4, "{coat:?}");
    }

    #[test]
    fn patterns_repeat_every_cell() {
        // Stripes, checks and dots repeat every 32 texels across (their weave and noise
        // apart), so they tile across the texture's edge like anywhere else.
        for s in [Surface::Striped, Surface::Checkered, Surface::PolkaDot] {
            let t = s.luma();
            let off = (0..TEX_SIZE * TEX_SIZE)
                .filter(|i| {
                    t[*i].abs_diff(t[(i / TEX_SIZE) * TEX_SIZE + (i % TEX_SIZE + 64) % TEX_SIZE])
                        > 30
                })
                .count();
            assert!(
                off < TEX_SIZE,
                "{s:?}: {off} texels differ from the cell beside"
            );
        }
    }

    #[test]
    fn features_pick_the_surface_of_a_canvas_a_fabric_and_a_worktop() {
        use crate::scene::{Part, Pose, Shape};
        let slab = |y: f32, h: f32, w: f32| Part {
            shape: Shape::Cuboid {
                half_extents: [w * 0.5, h * 0.5, 0.3],
                bevel: 0.0,
            },
            transform: Pose {
                position: [0.0, y, 0.0],
                rotation: [0.0, 0.0, 0.0, 1.0],
            },
            color: [0.7; 3],
        };
        let scene = Scene {
            format_version: crate::SCENE_FORMAT_VERSION,
            id: "t".into(),
            source: "test".into(),
            seed: None,
            floor_height: 0.0,
            rooms: vec![],
            doors: vec![],
            objects: vec![],
            storeys: Default::default(),
        };
        let mut counter = SceneObject::from_parts(
            1,
            SemanticClass::Counter,
            Pose::IDENTITY,
            vec![
                slab(0.05, 0.1, 1.1),
                slab(0.5, 0.76, 1.2),
                slab(0.88, 0.04, 1.2),
            ],
        );
        counter.material = "wood".into();
        assert_eq!(part_surfaces(&scene, &counter), vec![Surface::Wood; 3]);
        counter.features = vec!["granite top".into()];
        assert_eq!(worktop(&counter), Some(2));
        assert_eq!(
            part_surfaces(&scene, &counter),
            [Surface::Wood, Surface::Wood, Surface::Granite]
        );
        let mut painting = SceneObject::from_parts(
            2,
            SemanticClass::PictureFrame,
            Pose::IDENTITY,
            vec![slab(1.5, 0.5, 0.8), slab(1.5, 0.44, 0.74)],
        );
        painting.material = "canvas".into();
        assert_eq!(part_surfaces(&scene, &painting), [Surface::Painting; 2]);
        painting.features = vec!["zebra".into()];
        assert_eq!(
            part_surfaces(&scene, &painting),
            [Surface::Wood, Surface::PaintingZebra]
        );
        let mut sofa = SceneObject::from_parts(3, SemanticClass::Sofa, Pose::IDENTITY, vec![]);
        sofa.material = "fabric".into();
        assert_eq!(surface_of(&scene, &sofa), Surface::Fabric);
        sofa.features = vec!["two seats".into(), "floral".into()];
        assert_eq!(surface_of(&scene, &sofa), Surface::Floral);
    }

    #[test]
    fn a_picture_reads_left_to_right_from_the_side_it_faces() {
        let (lo, hi) = (Vec3::new(-1.0, 1.0, -1.0), Vec3::new(1.0, 2.0, 1.0));
        // Facing +z the viewer's right is +x; facing -z it is -x.
        let right = Vec3::new(0.9, 1.9, 0.0);
        assert_eq!(picture_uv(right, Vec3::Z, lo, hi)[0].round(), 1.0);
        assert_eq!(picture_uv(right, Vec3::NEG_Z, lo, hi)[0].round(), 0.0);
        // The top row is v = 0.
        assert!(picture_uv(right, Vec3::Z, lo, hi)[1] < 0.15);
        // Facing +x the viewer's right is -z.
        let p = Vec3::new(0.0, 1.5, -0.9);
        assert!(picture_uv(p, Vec3::X, lo, hi)[0] > 0.9);
        assert!(picture_uv(p, Vec3::NEG_X, lo, hi)[0] < 0.1);
    }

    #[test]
    fn box_uv_follows_the_dominant_axis() {
        assert_eq!(box_uv(Vec3::new(1.0, 2.0, 3.0), Vec3::Y), [1.0, 3.0]);
        assert_eq!(box_uv(Vec3::new(1.0, 2.0, 3.0), Vec3::X), [3.0, -2.0]);
        assert_eq!(box_uv(Vec3::new(1.0, 2.0, 3.0), Vec3::NEG_Z), [1.0, -2.0]);
    }
}
