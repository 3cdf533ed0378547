//! Modular Radiance Transfer's precompute (Loos et al. 2011, as Loos 2015 ch. 3-4 gives it): the
//! scene-independent dictionary of canonical block shapes ([`shape`]), each with its light prior
//! from sphere-light training sets ([`prior`]), its one-bounce gather by exact ray-box exits
//! ([`gather`]) and its reduced direct-to-indirect transfer ([`basis`]: U_b, T_{d->b}, L_imp,
//! with enrichment), built for all six shapes by [`dictionary`] and kept on disk by [`cache`];
//! the light fields at openings ([`lightfield`]) and their reduced basis with each opening's
//! R_{b->rlf} ([`interface`]), the propagation through a block ahead, left or right
//! ([`propagate`]) and a block's surface response to entering light ([`response`]: U_r,
//! T_{rlf->r}); a level of blocks from the scene's proxy boxes ([`proxy`]) with its links,
//! a frame's indirect light in the reduced spaces ([`level`]) from its T_{b->r} ([`transfer`]); the real surface
//! behind each block texel ([`geometry_image`]); the flux correction of stretched blocks
//! ([`warp`]); proxy blocks fitted to a bare level ([`fit`], joined through their doorways by
//! [`doorways`]); sides the level leaves only partly open, masked and reflecting position by
//! position ([`opening`]). The GPU runtime (`render::gi::mrt`) builds on these.

pub mod basis;
pub mod cache;
pub mod dictionary;
pub mod doorways;
pub mod fit;
pub mod gather;
pub mod geometry_image;
pub mod interface;
pub mod level;
pub mod lightfield;
pub mod opening;
pub mod operators;
pub mod prior;
pub mod propagate;
pub mod proxy;
pub mod remap;
pub mod response;
pub mod shape;
pub mod transfer;
pub mod warp;
