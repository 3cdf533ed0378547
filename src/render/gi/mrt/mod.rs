//! `mrt`: modular radiance transfer over proxy blocks (Loos 2015) at run time. The precompute
//! (dictionary, interfaces, level assembly, fitting) lives in `precompute::mrt`; this folder
//! packs a level for the GPU ([`pack`]), prepares it off the frame ([`job`]), records the
//! per-frame passes ([`passes`]), draws its inspector images ([`inspect`]) and plugs into the
//! GI seam ([`technique`]).

pub mod inspect;
pub mod job;
pub mod pack;
pub mod passes;
pub mod technique;
