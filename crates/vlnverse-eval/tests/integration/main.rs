//! Integration tests of `vlnverse-eval`, linked into one test binary (one link, shared fixtures).

mod eval_support;
mod example;

mod eval_agents;
mod eval_dialogue;
mod eval_external;
mod eval_identity;
mod eval_layers;
mod eval_resume;
mod eval_runs;
mod eval_split_checks;
#[cfg(feature = "llm-oracle")]
mod oracle_llm;
mod oracle_shortest_path;
mod oracle_storeys;
mod vec_env_train;
