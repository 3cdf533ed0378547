//! The artist's proxy blocks (scene objects of role `ProxyBlock`, generated boxes with chosen
//! open sides) as an MRT level: each box's open side walls, turned into the world by the
//! object's rotation about up, name the dictionary shape and its quarter turns; its world box
//! is the block's warp. What the 2D cube dictionary cannot express is an error naming the
//! object: a box tilted off the vertical or turned by other than quarter turns, an open floor or
//! ceiling, a proxy that is not a box.

use glam::{Quat, Vec3};
use thiserror::Error;

use super::level::{Block, Level};
use super::shape::{Face, Shape};
use crate::scene::{MeshSource, ObjectRole, Scene};

/// Why a scene's proxy blocks do not make a level.
#[derive(Debug, Error, PartialEq)]
pub enum ProxyError {
    /// The scene has no proxy blocks.
    #[error("the scene has no proxy blocks (add boxes of role \"proxy block\", or fit them)")]
    NoBlocks,
    /// A proxy object is not a generated box.
    #[error("proxy block {0:?} is not a box: MRT blocks are generated boxes")]
    NotABox(String),
    /// A box is tilted or turned by other than a quarter turn about up.
    #[error(
        "proxy block {0:?} is rotated other than by quarter turns about up: the dictionary's blocks stand upright on the grid's axes"
    )]
    Rotated(String),
    /// A box opens its floor or ceiling.
    #[error("proxy block {0:?} opens its floor or ceiling: the 2D cube dictionary always has both")]
    VerticalOpening(String),
}

/// The quarter turns about up (each +x -> -z) of `q`, if it is one.
fn quarter_turns(q: Quat) -> Option<u8> {
    (0..4u8).find(|&t| {
        let r = Quat::from_rotation_y(f32::from(t) * std::f32::consts::FRAC_PI_2);
        r.dot(q).abs() > 1.0 - 1e-5
    })
}

/// The dictionary shape and its quarter turns whose open sides are `open` (world side walls).
pub fn shape_for(open: &[Face]) -> Option<(Shape, u8)> {
    Shape::ALL.iter().find_map(|&shape| {
        if shape.open_faces().len() != open.len() {
            return None;
        }
        (0..4u8).find_map(|t| shape.open_faces().iter().all(|f| open.contains(&f.turned(t))).then_some((shape, t)))
    })
}

/// The faces in the order of a cuboid's `openings` (+X, -X, +Y, -Y, +Z, -Z).
pub const OPENING_ORDER: [Face; 6] = [Face::PosX, Face::NegX, Face::PosY, Face::NegY, Face::PosZ, Face::NegZ];

/// The open faces of a cuboid's `openings`, turned `turns` quarter turns about up.
pub fn open_faces(openings: &[bool; 6], turns: u8) -> Vec<Face> {
    OPENING_ORDER.iter().zip(openings).filter(|(_, o)| **o).map(|(f, _)| f.turned(turns)).collect()
}

/// The level of `scene`'s proxy blocks, and each block's object index.
pub fn level(scene: &Scene) -> Result<(Level, Vec<usize>), ProxyError> {
    level_of(scene.objects())
}

/// The level of the proxy blocks among `objects`, and each block's index in `objects`.
pub fn level_of(all: &[crate::scene::Object]) -> Result<(Level, Vec<usize>), ProxyError> {
    let mut blocks = Vec::new();
    let mut objects = Vec::new();
    for (index, object) in all.iter().enumerate().filter(|(_, o)| o.role == ObjectRole::ProxyBlock) {
        let MeshSource::Cuboid { size, openings } = &object.source else {
            return Err(ProxyError::NotABox(object.name.clone()));
        };
        let t = &object.transform;
        let turns = quarter_turns(t.rotation).ok_or_else(|| ProxyError::Rotated(object.name.clone()))?;
        let open = open_faces(openings, turns);
        if open.iter().any(|f| f.axis() == 1) {
            return Err(ProxyError::VerticalOpening(object.name.clone()));
        }
        let (shape, block_turns) = shape_for(&open).ok_or_else(|| ProxyError::VerticalOpening(object.name.clone()))?;
        // The world box: the scaled size, x and z swapped by odd quarter turns.
        let local = (*size * t.scale).abs();
        let world = if turns % 2 == 1 { Vec3::new(local.z, local.y, local.x) } else { local };
        blocks.push(Block { shape, origin: t.translation - world * 0.5, size: world, turns: block_turns });
        objects.push(index);
    }
    if blocks.is_empty() {
        return Err(ProxyError::NoBlocks);
    }
    Ok((Level::new(blocks), objects))
}

/// Proxy boxes fitted to `scene`'s static geometry ([`super::fit`]), as scene objects of role
/// `ProxyBlock` named "proxy 1", "proxy 2", ... (the scene's first material).
pub fn fitted_objects(scene: &Scene) -> Result<Vec<crate::scene::Object>, super::fit::FitError> {
    Ok(fit_scene(scene, &crate::precompute::bvh::SceneBvh::build(scene))?.objects)
}

/// Blocks fitted to a scene and what they leave out.
pub struct Fitted {
    /// The blocks as scene objects ("proxy 1", "proxy 2", ...).
    pub objects: Vec<crate::scene::Object>,
    /// What they leave out.
    pub gaps: Vec<GapNote>,
}

/// A gap in a level's blocks, described.
#[derive(Clone, Debug, PartialEq)]
pub struct GapNote {
    /// One sentence ([`super::fit::Gap::describe`]): where, why, what to do.
    pub text: String,
    /// Its world bounds (for the viewport's overlay).
    pub min: Vec3,
    /// Its world bounds.
    pub max: Vec3,
}

fn note(g: &super::fit::Gap, name: &dyn Fn(usize) -> String) -> GapNote {
    GapNote { text: g.describe(name), min: g.min, max: g.max }
}

/// The triangles of `scene`'s static objects (what blocks are fitted to: not clutter, not
/// proxies).
fn static_tris(scene: &Scene, bvh: &crate::precompute::bvh::SceneBvh) -> Vec<[Vec3; 3]> {
    let objects = scene.objects();
    bvh.tris
        .iter()
        .filter(|t| objects.get(t.object as usize).is_some_and(|o| o.role == ObjectRole::Static))
        .map(|t| t.p)
        .collect()
}

/// Fits proxy blocks to `scene` (its BVH already built) and names what they leave out.
pub fn fit_scene(scene: &Scene, bvh: &crate::precompute::bvh::SceneBvh) -> Result<Fitted, super::fit::FitError> {
    let report = super::fit::fit_report(&static_tris(scene, bvh))?;
    let name = |i: usize| format!("\"proxy {}\"", i + 1);
    Ok(Fitted {
        objects: report
            .blocks
            .iter()
            .enumerate()
            .map(|(i, b)| block_object(&format!("proxy {}", i + 1), b.min, b.max, b.openings))
            .collect(),
        gaps: report.gaps.iter().map(|g| note(g, &name)).collect(),
    })
}

/// What the scene's own proxy blocks (`level`, block `i` being object `objects[i]`) leave out of
/// its enclosed spaces; a level with nothing enclosed has none, and one the check cannot read
/// (not rectilinear) is one note saying so, without bounds.
pub fn gaps_of(
    scene: &Scene,
    bvh: &crate::precompute::bvh::SceneBvh,
    level: &Level,
    objects: &[usize],
) -> Vec<GapNote> {
    let boxes: Vec<(Vec3, Vec3)> = level.blocks.iter().map(|b| (b.origin, b.origin + b.size)).collect();
    let linked = super::fit::pairs_of(level);
    let name = |i: usize| {
        objects.get(i).and_then(|&o| scene.objects().get(o)).map_or(format!("block {i}"), |o| format!("{:?}", o.name))
    };
    match cached_survey(&static_tris(scene, bvh)).map(|s| s.gaps(&boxes, &linked)) {
        Ok(gaps) => gaps.iter().map(|g| note(g, &name)).collect(),
        // Nothing enclosed to cover (an open-fronted box, a diorama): nothing to say.
        Err(super::fit::FitError::NoEnclosure { .. } | super::fit::FitError::NoRoom | super::fit::FitError::Empty) => {
            Vec::new()
        }
        Err(e) => vec![GapNote {
            text: format!("the blocks' coverage of the level was not checked: {e}"),
            min: Vec3::ZERO,
            max: Vec3::ZERO,
        }],
    }
}

/// The survey of the last level checked, by a hash of its triangles: moving a block rebuilds
/// the level, not the survey of a geometry that did not change.
static SURVEY: std::sync::Mutex<Option<(u64, std::sync::Arc<super::fit::Survey>)>> = std::sync::Mutex::new(None);

/// [`super::fit::survey`] of `tris`, from [`SURVEY`] when the triangles are the last ones.
fn cached_survey(tris: &[[Vec3; 3]]) -> Result<std::sync::Arc<super::fit::Survey>, super::fit::FitError> {
    use std::hash::{Hash as _, Hasher as _};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    tris.iter().flatten().for_each(|p| p.to_array().map(f32::to_bits).hash(&mut h));
    let key = h.finish();
    if let Some((k, s)) = SURVEY.lock().ok().and_then(|g| g.clone())
        && k == key
    {
        return Ok(s);
    }
    let survey = std::sync::Arc::new(super::fit::survey(tris)?);
    if let Ok(mut g) = SURVEY.lock() {
        *g = Some((key, survey.clone()));
    }
    Ok(survey)
}

/// An unrotated proxy block object spanning `min .. max` with `openings` (in
/// [`OPENING_ORDER`]), using the scene's first material.
pub fn block_object(name: &str, min: Vec3, max: Vec3, openings: [bool; 6]) -> crate::scene::Object {
    crate::scene::Object {
        name: name.to_owned(),
        source: MeshSource::Cuboid { size: max - min, openings },
        mesh: 0,
        material: 0,
        transform: crate::scene::Transform { translation: 0.5 * (min + max), ..Default::default() },
        sampling_weight: 1.0,
        role: ObjectRole::ProxyBlock,
        visible: true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Camera, Material, Object, SceneDesc, Transform};

    fn proxy(name: &str, at: Vec3, size: Vec3, openings: [bool; 6], turns: u8) -> Object {
        Object {
            name: name.into(),
            source: MeshSource::Cuboid { size, openings },
            mesh: 0,
            material: 0,
            transform: Transform {
                translation: at,
                rotation: Quat::from_rotation_y(f32::from(turns) * std::f32::consts::FRAC_PI_2),
                scale: Vec3::ONE,
            },
            sampling_weight: 1.0,
            role: ObjectRole::ProxyBlock,
            visible: true,
        }
    }

    fn scene(objects: Vec<Object>) -> Scene {
        let desc = SceneDesc {
            objects,
            materials: vec![Material::diffuse("grey", [0.8; 3])],
            lights: Vec::new(),
            camera: Camera::default(),
            ..SceneDesc::default()
        };
        crate::import::resolve(desc, &[]).expect("scene")
    }

    #[test]
    fn three_rooms_in_a_row_become_a_linked_level() {
        // 5 x 3 x 4 m rooms along +z: the middle one open at both ends, the last one's box
        // turned half round so its one opening (+z in its own frame) faces back.
        let (w, h, d) = (5.0, 3.0, 4.0);
        let s = scene(vec![
            proxy("room a", Vec3::new(0.0, 1.5, 0.0), Vec3::new(w, h, d), [false, false, false, false, true, false], 0),
            proxy("room b", Vec3::new(0.0, 1.5, 4.0), Vec3::new(w, h, d), [false, false, false, false, true, true], 0),
            proxy("room c", Vec3::new(0.0, 1.5, 8.0), Vec3::new(w, h, d), [false, false, false, false, true, false], 2),
        ]);
        let (level, objects) = level(&s).expect("level");
        assert_eq!(objects, vec![0, 1, 2]);
        let shapes: Vec<(Shape, u8)> = level.blocks.iter().map(|b| (b.shape, b.turns)).collect();
        assert_eq!(shapes, vec![(Shape::DeadEnd, 0), (Shape::Corridor, 0), (Shape::DeadEnd, 2)]);
        assert_eq!(level.blocks[1].size, Vec3::new(w, h, d));
        assert_eq!(level.link_count(), 4);
        assert_eq!(level.link(0, Face::PosZ), Some(1));
        assert!(level.unlinked().is_empty());
    }

    #[test]
    fn what_the_dictionary_cannot_express_is_named() {
        let open_z = [false, false, false, false, true, false];
        let mut tilted = proxy("tilted", Vec3::ZERO, Vec3::ONE, open_z, 0);
        tilted.transform.rotation = Quat::from_rotation_x(0.3);
        assert_eq!(level(&scene(vec![tilted])).err(), Some(ProxyError::Rotated("tilted".into())));
        let skewed = {
            let mut o = proxy("skewed", Vec3::ZERO, Vec3::ONE, open_z, 0);
            o.transform.rotation = Quat::from_rotation_y(0.4);
            o
        };
        assert_eq!(level(&scene(vec![skewed])).err(), Some(ProxyError::Rotated("skewed".into())));
        let floor = proxy("stairwell", Vec3::ZERO, Vec3::ONE, [false, false, false, true, false, false], 0);
        assert_eq!(level(&scene(vec![floor])).err(), Some(ProxyError::VerticalOpening("stairwell".into())));
        assert_eq!(level(&scene(Vec::new())).err(), Some(ProxyError::NoBlocks));
        // A corner block turned a quarter: its +x and +z openings face -z and +x in the world.
        let corner = proxy("corner", Vec3::ZERO, Vec3::ONE, [true, false, false, false, true, false], 1);
        let (l, _) = level(&scene(vec![corner])).expect("level");
        assert_eq!((l.blocks[0].shape, l.blocks[0].turns), (Shape::Corner, 1));
        let mut open = l.unlinked().iter().map(|u| u.1).collect::<Vec<_>>();
        open.sort();
        assert_eq!(open, vec![Face::PosX, Face::NegZ]);
    }
}
