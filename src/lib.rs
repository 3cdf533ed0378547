//! Bounce Lab: a lighting-authoring editor for real-time global illumination.
//!
//! Layers (docs/ARCHITECTURE.md, "Layers"): [`scene`] is pure data; [`import`] and
//! [`project_file`] fill it; [`render`] draws it with wgpu; `app` is the egui editor. Lower
//! layers never import higher ones.

pub mod app;
pub mod atomic_file;
pub mod cli;
pub mod export;
pub mod image_io;
pub mod import;
pub mod input_file;
pub mod logging;
pub mod metrics;
pub mod output_path;
pub mod precompute;
pub mod project_file;
pub mod render;
pub mod scene;
pub mod settings;
pub mod suite;
