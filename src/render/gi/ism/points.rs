//! What the ISM passes need to know about each scene sample point of the pool: its world
//! position and normal, its linear albedo (textures by their mean colour), its specular lobe for
//! glossy bounce VPLs and its object's sampling weight, in cluster order with the clusters,
//! rebuilt only when something it reads changed.

use crate::precompute::sample_points::SamplePoints;
use crate::render::gi::ism::gather::PointData;
use crate::scene::Scene;

/// The mean linear colour of an sRGB image.
pub(super) fn mean_linear_colour(img: &crate::scene::Image) -> [f32; 3] {
    let n = (img.rgba8.len() / 4).max(1) as f32;
    let mut sum = [0.0f32; 3];
    for px in img.rgba8.chunks_exact(4) {
        for c in 0..3 {
            sum[c] += crate::image_io::srgb_to_linear(f32::from(px[c]) / 255.0);
        }
    }
    sum.map(|v| v / n)
}

/// What the ISM passes read per sample point (see [`PointData`]): world position (w: the depth
/// of the solid behind it) and normal under the objects' current transforms, the object's sampling weight, albedo (base colour
/// factor times the mean of its texture, `texture_means` indexed by image) and specular lobe.
pub(super) fn point_data(
    scene: &Scene,
    points: &SamplePoints,
    texture_means: &[[f32; 3]],
    clips: &crate::precompute::open_edges::PointClips,
    solids: &crate::precompute::facing::PointSolids,
) -> PointData {
    let mean_texture = |image: usize| texture_means.get(image).copied().unwrap_or([1.0; 3]);
    let per_object: Vec<([f32; 4], [f32; 4], f32)> = scene
        .objects()
        .iter()
        .map(|o| {
            let m = scene.materials().get(o.material).cloned().unwrap_or_default();
            let t = m.base_color_texture.map_or([1.0; 3], |t| mean_texture(t.image));
            let albedo = [m.base_color[0] * t[0], m.base_color[1] * t[1], m.base_color[2] * t[2], 1.0];
            let glossy = m.specular.iter().any(|s| *s > 0.0);
            let exponent = if glossy { crate::precompute::brdf::phong_exponent(m.roughness).min(4096.0) } else { 0.0 };
            (albedo, [m.specular[0], m.specular[1], m.specular[2], exponent], o.sampling_weight)
        })
        .collect();
    let mut out = PointData::default();
    let world = points.world(scene);
    let normals: Vec<glam::Vec3> = world.iter().map(|(_, n)| *n).collect();
    out.clips = clips.world_lines(scene, &normals);
    for (i, (p, (position, normal))) in points.points.iter().zip(world).enumerate() {
        let (mut a, mut s, w) = per_object.get(p.object as usize).copied().unwrap_or(([0.0; 4], [0.0; 4], 1.0));
        // A point inside solid geometry receives no light, so it reflects none either.
        if solids.buried.get(i).copied().unwrap_or(false) {
            (a, s) = ([0.0, 0.0, 0.0, 1.0], [0.0; 4]);
        }
        // w: how deep the solid behind the point runs (the lookups' slab test).
        out.positions.push(position.extend(solids.depth.get(i).copied().unwrap_or(0.0)).to_array());
        out.normals.push(normal.extend(w).to_array());
        out.albedo.push(a);
        out.specular.push(s);
    }
    // A pool point of weight w stands for sum(area x weight) / (N w) of the scene's area.
    let total: f64 = points.weighted_area.iter().sum();
    out.area_unit = (total / points.points.len().max(1) as f64) as f32;
    let unit = out.area_unit;
    out.clusters = super::clusters::build(&mut out, |w| unit / w.max(1e-6));
    out
}

/// Bit patterns of everything [`point_data`] reads from the scene besides the point set: the
/// objects' transforms, materials and weights and the materials' parameters. Equal keys mean
/// the uploaded point data is still current, so it is not rebuilt every frame.
pub(super) fn point_data_key(scene: &Scene) -> Vec<u32> {
    let mut key = Vec::new();
    for o in scene.objects() {
        let t = &o.transform;
        let floats = t.translation.to_array().into_iter().chain(t.rotation.to_array()).chain(t.scale.to_array());
        key.extend(floats.chain([o.sampling_weight]).map(f32::to_bits));
        key.extend([o.material as u32, o.mesh as u32]);
    }
    for m in scene.materials() {
        key.extend(m.base_color.iter().chain(&m.specular).chain([&m.roughness]).map(|v| v.to_bits()));
        key.push(m.base_color_texture.map_or(u32::MAX, |t| t.image as u32));
    }
    key
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project_file::{Project, default_project_path};

    #[test]
    fn the_key_changes_exactly_when_point_data_would() {
        let mut project = Project::load(&default_project_path()).expect("default project");
        let key = point_data_key(&project.scene);
        project.scene.desc_mut().lights[0].intensity *= 2.0;
        assert_eq!(point_data_key(&project.scene), key, "lights do not touch the point data");
        project.scene.desc_mut().objects[5].transform.translation.x += 0.01;
        let moved = point_data_key(&project.scene);
        assert_ne!(moved, key, "a moved object moves its points");
        project.scene.desc_mut().materials[0].base_color[0] *= 0.5;
        assert_ne!(point_data_key(&project.scene), moved, "an albedo edit changes the point albedo");
    }
}
