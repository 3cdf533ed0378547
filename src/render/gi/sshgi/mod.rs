//! `sshgi`: screen-space hierarchical indirect light (Soler, Hoel, Rochet and Holzschuch 2010;
//! digest part C of `technique-rcs-shfilter-sshgi.md`). A purely deferred technique: its cost does
//! not depend on the scene's geometry or lights, every light type feeds it through the direct
//! term, and it adds several bounces, but only surfaces on screen send light.

pub mod passes;
pub mod technique;
