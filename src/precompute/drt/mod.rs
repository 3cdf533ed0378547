//! Delta Radiance Transfer (Loos et al. 2012; Loos 2015 ch. 5): what clutter, the small movable
//! objects inside MRT's blocks, changes of the blocks' indirect light (its shadows and its
//! bounce), and the light the blocks give the clutter. MRT's operators are scene independent and
//! ignore clutter; these are rebuilt by ray tracing whenever clutter moves, on the level job's
//! thread, and read every frame by `render::gi::mrt`'s DRT passes.

pub mod clutter;
pub mod operators;
pub mod texel_map;

use glam::Vec3;

pub use clutter::{Clutter, ClutterTexel, Why};
pub use operators::{DrtParams, Operators, SceneTexel};

use crate::precompute::bvh::SceneBvh;
use crate::precompute::mrt::dictionary::Progress;
use crate::precompute::mrt::level::Level;
use crate::scene::Scene;

/// A level's clutter and its operators.
#[derive(Clone, Debug, Default)]
pub struct Drt {
    /// Clutter objects (scene index, box, first texel).
    pub clutter: Vec<Clutter>,
    /// How each became clutter (parallel to `clutter`).
    pub why: Vec<Why>,
    /// Their texels.
    pub texels: Vec<ClutterTexel>,
    /// Per scene object, its clutter record.
    pub clutter_of: Vec<Option<usize>>,
    /// The operators.
    pub operators: Operators,
    /// Texels per clutter face side.
    pub res: usize,
    /// Build time (ms).
    pub millis: f64,
}

/// A level's clutter as [`find_clutter`] found it, with every object's bounding box.
#[derive(Clone, Debug, Default)]
pub struct Found {
    /// Clutter objects (scene index) and why each is clutter.
    pub objects: Vec<(usize, Why)>,
    /// Every scene object's world bounding box (`None`: no triangles).
    pub bounds: Vec<Option<(Vec3, Vec3)>>,
}

impl Found {
    /// No clutter.
    pub fn is_empty(&self) -> bool {
        self.objects.is_empty()
    }

    /// Whether scene object `i` is clutter.
    pub fn contains(&self, i: usize) -> bool {
        self.objects.iter().any(|(o, _)| *o == i)
    }
}

/// The objects of `scene` that are clutter of `level` (see [`clutter::classify`]).
pub fn find_clutter(scene: &Scene, bvh: &SceneBvh, level: &Level, automatic: bool, exempt: &[String]) -> Found {
    let bounds = clutter::object_bounds(bvh, scene.objects().len());
    let objects = clutter::classify(scene, &bounds, &level.blocks, automatic, exempt);
    Found { objects, bounds }
}

/// A level's block texels: their surfaces, block after block, and texels per face side.
#[derive(Clone, Copy)]
pub struct BlockTexels<'a> {
    pub texels: &'a [SceneTexel],
    pub res: usize,
}

/// Builds `level`'s DRT for the clutter `found` (from [`find_clutter`]) in `scene` (`bvh` holds
/// every object, clutter included) over its `block` texels; `None` when cancelled.
pub fn build(
    scene: &Scene,
    bvh: &SceneBvh,
    level: &Level,
    found: &Found,
    block: BlockTexels<'_>,
    params: &DrtParams,
    progress: &Progress,
) -> Option<Drt> {
    let BlockTexels { texels, res } = block;
    let started = std::time::Instant::now();
    let objects: Vec<usize> = found.objects.iter().map(|(i, _)| *i).collect();
    let records = clutter::records(&objects, &found.bounds, params.clutter_res);
    let why =
        records.iter().filter_map(|r| found.objects.iter().find(|(i, _)| *i == r.object).map(|(_, w)| *w)).collect();
    let mut clutter_of = vec![None; scene.objects().len()];
    for (k, r) in records.iter().enumerate() {
        clutter_of[r.object] = Some(k);
    }
    let clutter_texels = clutter::texels(scene, bvh, &records, params.clutter_res);
    let map = texel_map::TexelMap::new(level, res);
    let inputs = operators::Inputs {
        bvh,
        clutter_of: &clutter_of,
        clutter: &records,
        clutter_texels: &clutter_texels,
        map: &map,
        texels,
        res,
    };
    let ops = operators::build(&inputs, params, progress)?;
    Some(Drt {
        clutter: records,
        why,
        texels: clutter_texels,
        clutter_of,
        operators: ops,
        res: params.clutter_res,
        millis: started.elapsed().as_secs_f64() * 1e3,
    })
}

/// The world-space centre of a clutter record (the inspector's labels).
pub fn centre(c: &Clutter) -> Vec3 {
    0.5 * (c.lo + c.hi)
}
