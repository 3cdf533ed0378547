//! The level-independent interface operators a level's assembly needs, built once from the
//! dictionary (Loos 2015 §3.4.1 and §4.2, enriched as in App. A): each opening's R_{b->rlf}, the
//! propagation R ahead / left / right, the surface response U_r, T_{rlf->r} and the per-position
//! operators of partly open sides ([`super::opening`]). The light-field
//! basis U~ itself (s x k_rlf, 85 MB at the dissertation's resolution) is only needed to build
//! them and is not kept.

use super::basis::{BasisError, Element};
use super::dictionary::DictionaryParams;
use super::interface::{self, Exit};
use super::lightfield::LightFieldRes;
use super::opening::PositionOps;
use super::propagate::{self, Turn};
use super::response::{self, Response};

pub use crate::settings::mrt_params::InterfaceParams;

impl InterfaceParams {
    /// The light-field resolution.
    pub fn light_field(&self) -> LightFieldRes {
        LightFieldRes { positions: self.positions, directions: self.directions, supersample: self.supersample }
    }
}

/// The interface operators.
#[derive(Clone, Debug, PartialEq)]
pub struct Interfaces {
    /// Light-field modes kept.
    pub k_rlf: usize,
    /// The light-field basis' singular values (all of them; the inspector's plot).
    pub sigma: Vec<f64>,
    /// Each dictionary opening's R_{b->rlf}.
    pub exits: Vec<Exit>,
    /// R ahead, left, right (k_rlf x k_rlf each, row-major).
    pub turns: Vec<(Turn, Vec<f64>)>,
    /// The surface response.
    pub response: Response,
    /// The per-position masks and reflections of partly open sides.
    pub positions: PositionOps,
}

impl Interfaces {
    /// The exit operator of `shape`'s open side `face`.
    pub fn exit(&self, shape: super::shape::Shape, face: super::shape::Face) -> Option<&Exit> {
        self.exits.iter().find(|e| e.shape == shape && e.face == face)
    }

    /// The propagation operator of `turn`.
    pub fn turn(&self, turn: Turn) -> Option<&[f64]> {
        self.turns.iter().find(|t| t.0 == turn).map(|t| t.1.as_slice())
    }
}

/// Builds the interface operators from the dictionary's `elements` (built with `d`: its texel
/// resolution, rays and seed).
pub fn build(elements: &[Element], d: &DictionaryParams, params: &InterfaceParams) -> Result<Interfaces, BasisError> {
    let lf = params.light_field();
    let basis = interface::build(elements, &lf, params.k_rlf, params.enrichment, params.bands)?;
    let turns = Turn::ALL.iter().map(|&t| (t, propagate::reduced(&lf, t, &basis.u, basis.k_rlf))).collect();
    let kept = &basis.sigma[..basis.k_rlf];
    let response = response::build(d.res, &lf, &basis.u, kept, basis.k_rlf, params.k_r, d.rays, d.seed)?;
    let positions = PositionOps::build(&lf, &basis.u, basis.k_rlf);
    Ok(Interfaces { k_rlf: basis.k_rlf, sigma: basis.sigma, exits: basis.exits, turns, response, positions })
}
