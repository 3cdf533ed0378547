//! Command-line entry points (docs/ARCHITECTURE.md, "Command line"): `render`, `bench` (and its quality
//! matrix), the scene suite and asset generation.
//! The binary's `main.rs` only parses arguments and calls these.

pub mod bench;
pub mod bench_drt;
pub mod bench_mrt;
pub mod bench_rcs;
pub mod bench_sshgi;
pub mod budget;
pub mod compare;
pub mod generate;
pub mod mrt;
pub mod probe;
pub mod probe_ism;
pub mod probe_mrt;
pub mod progress;
pub mod quality;
pub mod render;
pub mod report;

pub use report::error_report;
