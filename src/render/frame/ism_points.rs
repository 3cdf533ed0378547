//! What the ISM passes need to know about each scene sample point's surface: its linear
//! albedo (textures by their mean colour), its specular lobe for glossy bounce VPLs, and its
//! object's sampling weight.

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

/// Albedo and sampling weight of each sample point's object (base colour factor times the mean
/// of its texture, `texture_means` indexed by image).
pub(super) fn point_materials(
    scene: &Scene,
    points: &crate::precompute::sample_points::SamplePoints,
    texture_means: &[[f32; 3]],
) -> PointMaterials {
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
    let mut out = PointMaterials::default();
    for p in &points.points {
        let (a, s, w) = per_object.get(p.object as usize).copied().unwrap_or(([0.0; 4], [0.0; 4], 1.0));
        out.albedo.push(a);
        out.specular.push(s);
        out.weights.push(w);
    }
    out
}

/// Per sample point: linear albedo (rgb), specular reflectance and Blinn-Phong exponent, and
/// the object's sampling weight.
#[derive(Default)]
pub(super) struct PointMaterials {
    pub(super) albedo: Vec<[f32; 4]>,
    pub(super) specular: Vec<[f32; 4]>,
    pub(super) weights: Vec<f32>,
}
