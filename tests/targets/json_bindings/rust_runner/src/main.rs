//! Runs the shared JSON-protocol vectors through the generated Rust bindings of
//! `remote_driving` (the runner itself is `run.rs`, which tests/targets/json_bindings also builds for the
//! protocols of every valid spec fixture).

use remote_driving_json as bindings;

include!("run.rs");
