//! The emissive surfaces of a scene as candidate VPLs for ISM: Ritschel et al. (2008) made
//! imperfect shadow maps for exactly this, many VPLs standing for area and environment light.
//! Here the candidates fill the emitter tiles of the light G-buffer atlas ([`super::light_tiles`]),
//! so the same importance pyramid and warp that spread the VPLs over the punctual lights share
//! the VPL budget with the emitters by power.
//!
//! Candidates are stratified by power (area x luminance of the emission), a Halton point on the
//! chosen triangle, the emission texture read at that point. Candidate `j` stands for the area
//! `1 / (M pdf_area)` around it, and as a VPL for a Lambertian emitter of that patch: its power
//! is `pi L A` (what a patch of radiance `L` sends into its hemisphere), its intensity
//! `L A cos` - the diffuse VPL of the shading passes with the emitter's front normal. Only the
//! front face emits, as in the path tracer.

use glam::{Vec2, Vec3};

use crate::precompute::bvh::SceneBvh;
use crate::precompute::emitters::Emitters;
use crate::precompute::ism::halton::radical_inverse;
use crate::scene::Scene;

/// `EmitterPoint` in `ism_emitter_tiles.wgsl` and `vpl_generate.wgsl`: one candidate VPL on an
/// emissive surface.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuEmitterPoint {
    /// xyz world position, w = the area it stands for (m^2).
    pub position: [f32; 4],
    /// xyz unit front normal, w unused.
    pub normal: [f32; 4],
    /// rgb power pi L A (W), a = importance (the light G-buffer's: luminance x 0.5, no lobe).
    pub power: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<GpuEmitterPoint>() == 48);

/// Whether `object` of `scene` is drawn with an emitting material.
fn emits(scene: &Scene, object: usize) -> bool {
    scene.objects().get(object).is_some_and(|o| {
        o.is_rendered()
            && scene.resources().meshes.get(o.mesh).is_some()
            && scene.materials().get(o.material).is_some_and(|m| m.emits())
    })
}

/// Whether any drawn object of `scene` emits light.
pub fn has_emitters(scene: &Scene) -> bool {
    (0..scene.objects().len()).any(|i| emits(scene, i))
}

/// What the candidates depend on: every emitting object's mesh, transform and emission, the
/// resources (meshes, images) and the candidate count. Equal keys give equal candidates.
pub fn key(scene: &Scene, count: usize) -> Vec<u32> {
    let mut key = vec![count as u32, scene.resources_revision() as u32, (scene.resources_revision() >> 32) as u32];
    for (i, o) in scene.objects().iter().enumerate().filter(|(i, _)| emits(scene, *i)) {
        key.extend([i as u32, o.mesh as u32]);
        key.extend(o.transform.matrix().to_cols_array().map(f32::to_bits));
        if let Some(m) = scene.materials().get(o.material) {
            key.extend(m.emission().to_array().map(f32::to_bits));
            key.push(m.emissive_texture.map_or(u32::MAX, |t| t.image as u32));
        }
    }
    key
}

/// `count` candidates on the emissive surfaces of `scene` (empty without emitters).
pub fn emitter_points(scene: &Scene, count: usize) -> Vec<GpuEmitterPoint> {
    let bvh = SceneBvh::build_where(scene, |i| emits(scene, i));
    let emitters = Emitters::new(&bvh, scene.materials());
    if emitters.is_empty() || count == 0 {
        return Vec::new();
    }
    let images = &scene.resources().images;
    (0..count)
        .filter_map(|j| {
            let u = [
                ((j as f64 + 0.5) / count as f64) as f32,
                radical_inverse(j as u64 + 1, 2) as f32,
                radical_inverse(j as u64 + 1, 3) as f32,
            ];
            let s = emitters.sample(&bvh, u)?;
            let tri = &bvh.tris[s.tri as usize];
            let material = scene.materials().get(tri.material as usize)?;
            let mut radiance = material.emission();
            if let Some(img) = material.emissive_texture.and_then(|t| images.get(t.image)) {
                let uv: Vec2 = tri.uv[0] * (1.0 - s.u - s.v) + tri.uv[1] * s.u + tri.uv[2] * s.v;
                radiance *= crate::precompute::pathtracer::sample_image(img, uv, true);
            }
            let area = 1.0 / (count as f32 * s.pdf_area);
            let power = std::f32::consts::PI * radiance * area;
            let importance = 0.5 * crate::precompute::sky_sampler::luminance(power);
            Some(GpuEmitterPoint {
                position: s.p.extend(area).to_array(),
                normal: tri.ng.extend(0.0).to_array(),
                power: power.extend(importance).to_array(),
            })
        })
        .collect()
}

/// The total power of `points` (W per channel).
pub fn total_power(points: &[GpuEmitterPoint]) -> Vec3 {
    points.iter().map(|p| Vec3::new(p.power[0], p.power[1], p.power[2])).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Material;

    /// A floor and a 1 m x 0.5 m x 1 mm panel of radiance (2, 1, 0.5) 2 m above it.
    fn panel_scene() -> Scene {
        let mut scene = crate::precompute::test_scenes::scene_of_slabs(
            &[("floor", Vec3::ZERO, Vec3::new(4.0, 0.1, 4.0)), ("panel", Vec3::new(0.0, 2.0, 0.0), Vec3::new(1.0, 0.001, 0.5))],
            Vec::new(),
        );
        let desc = scene.desc_mut();
        desc.materials.push(Material {
            emissive_color: [1.0, 0.5, 0.25],
            emissive_strength: 2.0,
            ..Material::diffuse("panel", [0.0; 3])
        });
        desc.objects[1].material = 1;
        scene
    }

    #[test]
    fn the_candidates_carry_pi_l_a_of_every_emitting_face_and_follow_the_panel() {
        let mut scene = panel_scene();
        assert!(has_emitters(&scene));
        let points = emitter_points(&scene, 4096);
        assert_eq!(points.len(), 4096);
        // A closed cuboid of 1 x 0.5 x 0.001 m: 2 x 0.5 m^2 of large faces plus 0.003 m^2 of sides.
        let area = 2.0 * 0.5 + 2.0 * 0.001 * 1.5;
        let expected = std::f32::consts::PI * area * Vec3::new(2.0, 1.0, 0.5);
        let total = total_power(&points);
        assert!((total - expected).abs().max_element() < 1e-3 * expected.max_element(), "{total} vs {expected}");
        let areas: f32 = points.iter().map(|p| p.position[3]).sum();
        assert!((areas - area).abs() < 1e-3, "the candidates' areas sum to the emitters' area: {areas}");
        // Stratified: the bottom face's candidates spread over its whole area.
        let bottom: Vec<&GpuEmitterPoint> = points.iter().filter(|p| p.normal[1] < -0.9).collect();
        assert!((bottom.len() as f32 - 4096.0 * 0.5 / area).abs() < 4.0, "{} on the bottom face", bottom.len());
        let quadrants = |sx: f32, sz: f32| {
            bottom.iter().filter(|p| p.position[0] * sx > 0.0 && p.position[2] * sz > 0.0).count() as f32
        };
        for (sx, sz) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let share = quadrants(sx, sz) / bottom.len() as f32;
            assert!((share - 0.25).abs() < 0.02, "quadrant ({sx}, {sz}) holds {share}");
        }
        let before = key(&scene, 4096);
        assert_eq!(before, key(&scene, 4096));
        scene.desc_mut().objects[1].transform.translation.x += 0.5;
        assert_ne!(before, key(&scene, 4096), "a moved emitter makes new candidates");
        scene.desc_mut().objects[1].visible = false;
        assert!(!has_emitters(&scene) && emitter_points(&scene, 64).is_empty(), "a hidden emitter sends nothing");
    }
}
