//! Integration tests of `vlnverse-task`, linked into one test binary (one link, shared fixtures).

mod eval_support;
mod example;
mod instructions_fixture;

mod eval_agents;
mod eval_dialogue;
mod eval_external;
mod eval_layers;
mod eval_resume;
mod eval_runs;
mod generate_config;
mod generate_dataset;
mod generate_llm;
mod generate_output;
mod generate_skip;
#[cfg(feature = "llm")]
mod instructions_llm;
mod instructions_template;
#[cfg(feature = "llm")]
mod oracle_llm;
mod oracle_shortest_path;
