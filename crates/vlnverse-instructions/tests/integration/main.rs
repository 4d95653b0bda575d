//! Integration tests of `vlnverse-instructions`, linked into one test binary.

mod door_kinds;
mod instructions_fixture;

#[cfg(feature = "llm")]
mod instructions_llm;
mod instructions_template;
mod whole_home;
