//! Integration tests of `vlnverse-score`, linked into one test binary.

mod dataset_errors;
mod example;
mod metrics_fixtures;
mod metrics_formats;
mod metrics_props;
mod metrics_robustness;
mod metrics_score;
