//! Integration tests of `vlnverse-task`, linked into one test binary (one link, shared fixtures).

mod eval_support;
mod instructions_fixture;

mod eval_agents;
mod eval_dialogue;
mod eval_external;
mod eval_resume;
mod generate_config;
mod generate_dataset;
mod generate_skip;
mod instructions_llm;
mod instructions_template;
mod metrics_fixtures;
mod metrics_formats;
mod metrics_props;
mod metrics_robustness;
mod metrics_score;
mod oracle_llm;
mod oracle_shortest_path;
