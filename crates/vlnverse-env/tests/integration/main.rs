//! Integration tests of `vlnverse-env`, linked into one test binary (one link, shared fixtures).

mod common;
mod example;
mod io_common;
mod occupancy_fixtures;
mod scene_graph_fixture;

mod bevel;
mod doors;
mod io_leftovers;
mod io_scene_files;
mod occupancy_geodesic;
mod occupancy_maps;
mod scene_graph_properties;
mod scene_graph_queries;
mod scene_graph_relations;
mod storeys;
mod topdown_render;
