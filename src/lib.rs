//! Bounce Lab: a lighting-authoring editor for real-time global illumination.
//!
//! Layers (architecture.md section 1): [`scene`] is pure data; [`import`] and [`project_file`]
//! fill it; [`render`] draws it with wgpu; `app` is the egui editor. Lower layers never import
//! higher ones.

pub mod import;
pub mod scene;
