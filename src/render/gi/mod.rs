//! Global-illumination techniques, one folder each (architecture.md section 2). Each technique
//! is a long-lived struct that owns its pipelines and history and writes the indirect term.
//!
//! `ism/` holds Knecht 2009 (instant radiosity with imperfect shadow maps and temporal reuse).
//! Its pure math (sample sets, hierarchical warping, paraboloid maps, VPL power) is written and
//! tested first on the CPU; the WGSL passes mirror it.

pub mod ism;
