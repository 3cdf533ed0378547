//! The integration tests, one binary: one link instead of thirty, and the harness runs every
//! test of every file side by side (`--test-threads`, one per core by default), each on a
//! device lent by [`common::gpu`].
//!
//! Two tiers. `cargo test` runs the behaviour and quality checks that finish in minutes; the
//! tests marked `#[ignore = "heavy: ..."]` are the heavy tier (default-settings quality of `ism`
//! over many frames, long temporal runs), run with `cargo test -- --include-ignored`, which is
//! what CI runs. The soak test ([`editor_soak`]) measures its process's resident memory, so it runs
//! in a child process of this binary, beside the others.

mod common;

mod analytic_direct;
mod area_lights;
mod assets;
mod atomic_kill;
mod big_scene;
mod cli;
mod drt;
mod editor_drt;
mod editor_preview;
mod editor_reload;
mod editor_soak;
mod editor_ui;
mod export;
mod gi_seam;
mod gltf_import;
mod ism;
mod ism_footprint;
mod ism_glossy;
mod ism_half;
mod ism_inspector;
mod ism_lights;
mod ism_oracle;
mod ism_sh;
mod ism_temporal;
mod ism_vpl;
mod light_units;
mod mrt;
mod mrt_shapes;
mod project_file;
mod rcs;
mod reference;
mod shaders;
mod shadow_cache;
mod sshgi;
mod sshgi_glossy;
mod sshgi_hidden;
mod sshgi_panorama;
mod sshgi_threads;
mod suite;
mod textures;
mod undo;
mod vo;
