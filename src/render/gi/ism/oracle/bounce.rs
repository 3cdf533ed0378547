//! The oracle's bounce check: the power a set's VPLs hand to the next set against the power
//! they reflect with exact visibility.

use super::lookups::{facing, sees};
use super::*;

/// The power one set's VPLs hand the next (the bounce pass) against the power they reflect with
/// exact visibility (receivers by area, the bounce pass's form factor), in luminance, by the
/// room ([`PairFilter::room`], clamped to 0..=3) the power lands in.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BounceReport {
    /// The set whose VPLs reflect (the next set receives).
    pub source: usize,
    /// The power of the next set's VPLs these VPLs made, by the room each lies in.
    pub handed: [f64; 4],
    /// The power these VPLs reflect off the receivers, by the receiver's room.
    pub reflected: [f64; 4],
}

impl BounceReport {
    /// The power handed over the power reflected (1: the bounce pass keeps the energy).
    pub fn ratio(&self) -> f64 {
        self.handed.iter().sum::<f64>() / self.reflected.iter().sum::<f64>()
    }

    /// [`BounceReport::ratio`] per room.
    pub fn room_ratios(&self) -> [f64; 4] {
        std::array::from_fn(|i| self.handed[i] / self.reflected[i])
    }

    /// Adds another frame's report of the same set.
    pub fn accumulate(&mut self, other: &BounceReport) {
        for i in 0..4 {
            self.handed[i] += other.handed[i];
            self.reflected[i] += other.reflected[i];
        }
    }
}

/// How many source sets [`bounce_power`] can compare: all but the last, and not the one before
/// it either when the bounce tail is on (the last set then carries the tail's 1 / (1 - r), the
/// later bounces' power, not the power its sources reflect).
pub fn compared_sets(ism: &IsmSettings) -> usize {
    ism.bounces.saturating_sub(1 + u32::from(ism.bounce_tail)) as usize
}

/// What VPL `k` of set `source` hands its successor and reflects (handed, reflected by room).
fn vpl_bounce(c: &Capture, recv: &Receivers, filter: &PairFilter, source: usize, k: usize) -> [[f64; 4]; 2] {
    let n = c.n();
    let mut out = [[0.0f64; 4]; 2];
    let Some(s) = c.vpl(source * n + k) else { return out };
    let n2 = f64::from(c.ism.interleave * c.ism.interleave);
    let power = luminance(s.vpl.power) / n2 / std::f64::consts::PI;
    for (&(p, pn), albedo) in recv.world.iter().zip(&recv.albedo) {
        let Some(f) = facing(s.o, s.n, p, pn) else { continue };
        if !sees(&c.bvh, p, pn, s.o, s.n) {
            continue;
        }
        // The receiving patch as a disk of its area (`incident_power` in `ism_bounce.wgsl`).
        let d2 = f64::from(f.d * f.d) + recv.area / std::f64::consts::PI;
        out[1][filter.room_index(p)] += albedo * power * f64::from(f.cos_s * f.cos_r) / d2 * recv.area;
    }
    if let Some(next) = c.vpls.get((source + 1) * n + k) {
        out[0][filter.room_index(Vec3::from_slice(&next.position[..3]))] += luminance(next.power) / n2;
    }
    out
}

/// The power set `source`'s VPLs hand set `source + 1` against what they reflect with exact
/// visibility ([`compared_sets`] says which sources compare).
pub fn bounce_power(c: &Capture, recv: &Receivers, filter: &PairFilter, source: usize) -> BounceReport {
    let per_vpl: Vec<[[f64; 4]; 2]> =
        (0..c.n()).into_par_iter().map(|k| vpl_bounce(c, recv, filter, source, k)).collect();
    let mut report = BounceReport { source, ..BounceReport::default() };
    for [handed, reflected] in per_vpl {
        report.accumulate(&BounceReport { source, handed, reflected });
    }
    report
}

/// [`bounce_power`] of every compared set ([`compared_sets`]), summed over `frames` frames: the
/// captured frame, then each further frame `renderer` renders of `scene` with `settings` (the
/// capture's VPLs are read again; its maps stay). One frame's ratios scatter by a percent or two
/// (the bounce pass estimates each next VPL's power from a few VPLs); the sum tells the bias.
pub fn bounce_over_frames(
    renderer: &mut Renderer,
    settings: &RenderSettings,
    capture: &mut Capture<'_>,
    recv: &Receivers,
    filter: &PairFilter,
    frames: usize,
) -> Result<Vec<BounceReport>, OracleError> {
    let sets = compared_sets(capture.settings());
    let mut sums: Vec<BounceReport> =
        (0..sets).map(|source| BounceReport { source, ..BounceReport::default() }).collect();
    for frame in 0..frames {
        if frame > 0 {
            render_frames(renderer, capture.scene, settings, 1)?;
            capture.reread_vpls(renderer)?;
        }
        for sum in &mut sums {
            sum.accumulate(&bounce_power(capture, recv, filter, sum.source));
        }
    }
    Ok(sums)
}

// ---------------------------------------------------------------------------------------------
// A tile's points.
