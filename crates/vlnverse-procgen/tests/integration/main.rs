//! Integration tests of `vlnverse-procgen`, linked into one test binary (one link, shared fixtures).

mod baked_light_file;
mod clutter;
mod decor;
mod doors;
mod doors_kinds;
mod dressings;
mod floors_coverings;
mod homes;
mod look;
mod navigable;
mod pieces;
mod sets_homes;
mod storeys;
mod support;
mod things;
mod variants;
