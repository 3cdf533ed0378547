//! The level-independent interface operators a level's assembly needs, built once from the
//! dictionary (Loos 2015 §3.4.1 and §4.2, enriched as in App. A): each opening's R_{b->rlf}, the
//! propagation R ahead / left / right, the surface response U_r, T_{rlf->r} and the per-position
//! operators of partly open sides ([`super::opening`]). The light-field
//! basis U~ itself (s x k_rlf, 85 MB at the dissertation's resolution) is only needed to build
//! them and is not kept.

use serde::{Deserialize, Serialize};

use super::basis::{BasisError, Element};
use super::dictionary::DictionaryParams;
use super::interface::{self, Exit};
use super::lightfield::LightFieldRes;
use super::opening::PositionOps;
use super::propagate::{self, Turn};
use super::response::{self, Response};

/// The interface operators' parameters (in parentheses: Loos 2015's values, §3.6.1 and §4.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InterfaceParams {
    /// Light-field positions per side of an opening (12).
    pub positions: usize,
    /// Light-field direction cells per side of the concentric square (24).
    pub directions: usize,
    /// Supersamples per side of a direction cell (5).
    pub supersample: usize,
    /// Light-field modes k_rlf (128).
    pub k_rlf: usize,
    /// Surface-response modes k_r (32).
    pub k_r: usize,
    /// Enrichment passes of the light-field basis (the dissertation's 3).
    pub enrichment: usize,
    /// Bands across an opening (along u) whose masked copies of the basis join each enrichment
    /// pass, so that light crossing only part of a side (a doorway in a room's wall) keeps its
    /// place (0: the dissertation's basis, whose fields are smooth across a side). Cost: only
    /// the dictionary build (the enrichment SVDs grow with (4 + bands)^2; 27.1 s at 6, 18.1 s
    /// before bands and the per-position operators, two cores); on the suite's rooms
    /// (`MRT_MIMIC=1 MRT_MULTI=4 mrt_probe rooms`:
    /// the third room 1.12 / 1.06 / 1.04 of a brute force at 4 / 6 / 12 bands).
    pub bands: usize,
}

impl Default for InterfaceParams {
    fn default() -> Self {
        Self { positions: 12, directions: 24, supersample: 5, k_rlf: 128, k_r: 32, enrichment: 3, bands: 6 }
    }
}

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
