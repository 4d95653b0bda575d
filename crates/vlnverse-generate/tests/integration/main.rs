//! Integration tests of `vlnverse-generate`, linked into one test binary.

mod generate_config;
mod generate_dataset;
mod generate_llm;
mod generate_llm_stop;
mod generate_output;
mod generate_skip;
mod generate_storeys;
mod generate_targets;
