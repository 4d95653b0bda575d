//! Integration tests of `vlnverse-sim`, linked into one test binary (one link, shared fixtures).

mod common;

mod behaviour;
mod doors;
mod generated_home;
mod shared_worlds;
mod storeys;
