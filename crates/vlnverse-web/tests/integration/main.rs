//! Integration tests of `vlnverse-web`, linked into one test binary: a real server on a free
//! port, a raw HTTP client and WebSocket drivers.

mod drive;
mod example;
mod hosts;
mod http;
mod limits;
mod replay_review;
mod support;
