#![doc = include_str!("../README.md")]

mod config;
mod decor;
mod doors;
mod floorplan;
mod furnish;
mod gear;
mod home;
mod household;
mod models;
mod more_things;
mod motifs;
mod navgrid;
mod palette;
mod pieces;
mod rect;
mod room_things;
mod sets;
mod storeys;
mod things;
mod tones;

pub use config::{
    DoorsConfig, FloorsConfig, FurnitureConfig, ProcgenConfig, RoomKindConfig, RoomsConfig,
    ScenesConfig, WallsConfig,
};
pub use motifs::motifs;
pub use rect::Rect;
pub use tones::shades;

use std::fmt;
use std::str::FromStr;
use vlnverse_env::{Aabb, Door, EnvError, Result, Scene, SceneSource};

/// The shipped configuration presets (`configs/scenes/<name>.toml`, embedded in the crate).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Preset {
    /// A handful of homes, generated in well under a second: for tests and demos.
    Tiny,
    /// The benchmark world: 263 homes of 3-10 rooms on the ground floor, 30% of them with an upper
    /// floor and stairs (the documented default config).
    Vlnverse,
}

impl Preset {
    /// Every preset.
    pub const ALL: &'static [Preset] = &[Preset::Tiny, Preset::Vlnverse];

    /// Name used on the command line and as the file stem.
    pub fn name(self) -> &'static str {
        match self {
            Preset::Tiny => "tiny",
            Preset::Vlnverse => "vlnverse",
        }
    }

    /// The TOML text of the preset.
    pub fn toml(self) -> &'static str {
        match self {
            Preset::Tiny => include_str!("../configs/scenes/tiny.toml"),
            Preset::Vlnverse => include_str!("../configs/scenes/vlnverse.toml"),
        }
    }

    /// Parse and validate the preset.
    pub fn config(self) -> Result<ProcgenConfig> {
        let path = format!("configs/scenes/{}.toml", self.name());
        ProcgenConfig::from_toml_str(self.toml(), Some(std::path::Path::new(&path)))
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Preset {
    type Err = EnvError;
    fn from_str(s: &str) -> Result<Self> {
        Preset::ALL
            .iter()
            .copied()
            .find(|p| p.name() == s)
            .ok_or_else(|| EnvError::invalid("preset", s, "expected `tiny` or `vlnverse`"))
    }
}

/// Seed of scene `index` derived from the config seed (SplitMix64 finaliser), so every scene is
/// independent of which others are generated, in which order, on which thread.
pub fn scene_seed(base: u64, index: usize) -> u64 {
    let mut z = base
        .wrapping_add(0x9E37_79B9_7F4A_7C15)
        .wrapping_add((index as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The procedural home generator: a [`SceneSource`] of `config.scenes.count` homes.
#[derive(Clone, Debug)]
pub struct HomeGenerator {
    config: ProcgenConfig,
}

impl HomeGenerator {
    /// Generator from a config (validated here).
    pub fn new(config: ProcgenConfig) -> Result<Self> {
        config.validate()?;
        Ok(HomeGenerator { config })
    }

    /// Generator from a shipped preset.
    pub fn from_preset(preset: Preset) -> Result<Self> {
        Self::new(preset.config()?)
    }

    /// The configuration.
    pub fn config(&self) -> &ProcgenConfig {
        &self.config
    }

    /// Generate a home from an explicit seed (outside the preset's numbering).
    pub fn generate(&self, seed: u64, id: &str) -> Result<Scene> {
        home::generate(&self.config, seed, id)
    }
}

impl SceneSource for HomeGenerator {
    fn len(&self) -> usize {
        self.config.scenes.count
    }

    fn scene_id(&self, index: usize) -> String {
        format!("{}_{index:04}", self.config.scenes.id_prefix)
    }

    fn scene(&self, index: usize) -> Result<Scene> {
        if index >= self.len() {
            return Err(EnvError::invalid(
                "scene index",
                index,
                format!("the source has {} scenes", self.len()),
            ));
        }
        let seed = scene_seed(self.config.scenes.seed, index);
        home::generate(&self.config, seed, &self.scene_id(index))
    }
}

/// The box that must stay free of furniture around a door: the door's clear width along the
/// wall and `depth` metres into each room, from the door's floor to `height` above it (an
/// upstairs door's box starts at the upper floor).
pub fn door_clearance(door: &Door, depth: f32, height: f32) -> Aabb {
    let [x, y, z] = door.position;
    let half = door.width * 0.5;
    let (hx, hz) = if door.normal[0].abs() > door.normal[1].abs() {
        (depth, half)
    } else {
        (half, depth)
    };
    Aabb {
        min: [x - hx, y, z - hz],
        max: [x + hx, y + height, z + hz],
    }
}
