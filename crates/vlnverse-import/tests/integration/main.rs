//! Integration tests of `vlnverse-import`, linked into one test binary (one link, shared fixtures).

mod example;
mod fixtures;
mod real_scenes;
mod textures;
