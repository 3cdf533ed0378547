//! Modular Radiance Transfer's precompute (Loos 2015; digest `technique-mrt-drt.md`): the
//! scene-independent dictionary of canonical block shapes ([`shape`]), each with its light prior
//! from sphere-light training sets ([`prior`]), its one-bounce gather by exact ray-box exits
//! ([`gather`]) and its reduced direct-to-indirect transfer ([`basis`]: U_b, T_{d->b}, L_imp,
//! with enrichment), built for all six shapes by [`dictionary`] and kept on disk by [`cache`].
//! The interface operators, the level assembly and the runtime build on these.

pub mod basis;
pub mod cache;
pub mod dictionary;
pub mod gather;
pub mod prior;
pub mod shape;
