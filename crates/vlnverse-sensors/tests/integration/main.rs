//! Integration tests of `vlnverse-sensors`, linked into one test binary (one link, shared fixtures).

mod common;

mod backends;
mod imported_textures;
mod look;
mod pictures;
mod raster_backends;
mod rig;
