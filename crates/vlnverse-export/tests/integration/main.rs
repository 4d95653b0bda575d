//! Integration tests of `vlnverse-export` (one test binary).

mod example;
mod export_files;
mod support;
