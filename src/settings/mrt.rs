//! Settings of `mrt`, modular radiance transfer over proxy blocks (Loos 2015: the per-frame steps
//! of §3.6.3, the parameters of §3.6.1 and §4.1-§4.2), and their ranges. The dictionary's
//! parameters choose the precompute (cached on disk per parameter set); the rest are per-frame.

use serde::{Deserialize, Serialize};

use super::SettingsError;
use super::mrt_params::{DictionaryParams, DrtParams};

/// Settings of the `mrt` technique.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MrtSettings {
    /// The dictionary: texels per face (16), modes k_b (32), gather rays, the interface light
    /// fields. A new parameter set builds a new dictionary (27 s on two cores at the
    /// defaults, release build; then cached in `~/.cache/bouncelab`). Per frame, every block costs
    /// k_b x n multiply-adds for b (n = 6 x texels^2) and k_b more per texel for U_b b.
    pub dictionary: DictionaryParams,
    /// Propagation depth: how many blocks beyond a source's neighbours its light is carried
    /// through the interfaces (the level's T_{b->r} has one k_r x k_b matrix per source and
    /// reached interface, so its size and the per-frame r cost grow with the blocks reached).
    /// Assembly at depth 6 (`bouncelab bench`, two cores): an 11-block maze 80 ms, a 41-block
    /// one 686 ms.
    pub depth: u32,
    /// Multi-bounce feedback gain (Loos 2015 §3.6.3): each frame adds albedo x the previous
    /// frame's indirect light (clamped at zero) to the texels' direct light, one more bounce per
    /// frame. 0 = one bounce; 1 = every bounce (converges in a few frames for albedo < 1). Free:
    /// one read per texel.
    pub feedback: f32,
    /// Pad the lightmap across sides open over their whole area (Loos 2015 §4.6): within half a
    /// texel of such a side a lookup blends towards the block beyond, so neighbouring blocks
    /// meet without a seam. Off shows the unpadded lightmap (the inspector's comparison). Cost:
    /// a second block lookup for pixels near such sides (the apply pass).
    pub padding: bool,
    /// Objects whose surfaces read their light from a chosen proxy block instead of the block
    /// nearest to each point (Loos 2015 §3.6.2's artist-assigned mapping; the automatic one
    /// suits walls, floors and ceilings, not a pillar standing in an opening or a beam across
    /// two rooms). Names of scene objects and of proxy blocks; a name that matches nothing is
    /// reported in the GI panel. Free.
    pub block_overrides: Vec<BlockOverride>,
    /// Delta radiance transfer for clutter (Loos 2015 ch. 5): its indirect shadows and bounce on
    /// the blocks and the blocks' light on it.
    pub drt: DrtSettings,
}

/// Settings of delta radiance transfer inside `mrt`. Changing any rebuilds the level's DRT.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DrtSettings {
    /// On: clutter is left out of the blocks' geometry images, shadows and reflects their light,
    /// and gathers its own. Off: MRT as without DRT (the comparison). Cost measured in
    /// `docs/BENCHMARKS.md` (DRT rows).
    pub enabled: bool,
    /// Rays per block texel near clutter for the delta operators (the dissertation's 1024).
    /// Rebuild time grows linearly; only rays that meet a clutter box are traced.
    pub rays: u32,
    /// Rays per clutter texel for the gather (C_b). Rebuild time grows linearly with it times
    /// the clutter texels (6 x res^2 per object).
    pub gather_rays: u32,
    /// Texels per clutter face side (the dissertation's 16).
    pub clutter_res: u32,
    /// Static objects that are small and inside a block count as clutter (a bare glTF has no
    /// roles). Objects marked clutter always are.
    pub automatic: bool,
    /// Objects never treated as clutter automatically (names): the artist's override.
    pub not_clutter: Vec<String>,
    /// Block texels that clutter covers take their neighbours' light (Loos 2015 §5.4.2). Off
    /// shows the rim their own deltas leave at footprints (the comparison). Free.
    pub inpaint: bool,
}

impl Default for DrtSettings {
    fn default() -> Self {
        let p = DrtParams::default();
        Self {
            enabled: true,
            rays: p.rays as u32,
            gather_rays: p.gather_rays as u32,
            clutter_res: p.clutter_res as u32,
            automatic: true,
            not_clutter: Vec::new(),
            inpaint: true,
        }
    }
}

impl DrtSettings {
    /// The build parameters.
    pub fn params(&self) -> DrtParams {
        DrtParams {
            rays: self.rays as usize,
            gather_rays: self.gather_rays as usize,
            clutter_res: self.clutter_res as usize,
            inpaint: self.inpaint,
            ..Default::default()
        }
    }
}

/// One object assigned to one proxy block.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockOverride {
    /// The object's name.
    pub object: String,
    /// The proxy block's name.
    pub block: String,
}

impl Default for MrtSettings {
    fn default() -> Self {
        Self {
            dictionary: DictionaryParams::default(),
            depth: 6,
            feedback: 1.0,
            padding: true,
            block_overrides: Vec::new(),
            drt: DrtSettings::default(),
        }
    }
}

impl MrtSettings {
    /// Checks ranges (absurd values are errors, never silently clamped).
    pub fn validate(&self) -> Result<(), SettingsError> {
        if let Err(SettingsError { name, value, range }) = self.dictionary.validate() {
            return Err(SettingsError { name: "mrt.dictionary", value: format!("{name} = {value}"), range });
        }
        if self.depth > 32 {
            return Err(SettingsError { name: "mrt.depth", value: self.depth.to_string(), range: "0..=32" });
        }
        if !(0.0..=1.0).contains(&self.feedback) {
            return Err(SettingsError { name: "mrt.feedback", value: self.feedback.to_string(), range: "0..=1" });
        }
        let d = &self.drt;
        if !(16..=16384).contains(&d.rays) {
            return Err(SettingsError { name: "mrt.drt.rays", value: d.rays.to_string(), range: "16..=16384" });
        }
        if !(16..=16384).contains(&d.gather_rays) {
            return Err(SettingsError {
                name: "mrt.drt.gather_rays",
                value: d.gather_rays.to_string(),
                range: "16..=16384",
            });
        }
        if !(2..=64).contains(&d.clutter_res) {
            return Err(SettingsError {
                name: "mrt.drt.clutter_res",
                value: d.clutter_res.to_string(),
                range: "2..=64",
            });
        }
        Ok(())
    }
}
