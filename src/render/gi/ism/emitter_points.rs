//! The emissive surfaces and the sky of a scene as candidate VPLs for ISM: Ritschel et al.
//! (2008) made imperfect shadow maps for exactly this, many VPLs standing for area and
//! environment light. The candidates fill the emitter tiles of the light G-buffer atlas
//! ([`super::light_tiles`]), so the same importance pyramid and warp that spread the VPLs over
//! the punctual lights share the VPL budget with the emitters and the sky by power (times the
//! first set's seen weight on emitters the camera sees, [`super::first_view`]).
//!
//! **Emissive surfaces:** candidates stratified by power (area x luminance of the emission), a
//! Halton point on the chosen triangle, the emission texture read at that point. Candidate `j`
//! stands for the area `A = 1 / (M pdf_area)` around it, and as a VPL for a Lambertian emitter
//! of that patch: its power is `pi L A` (what a patch of radiance `L` sends into its
//! hemisphere), its intensity `L A cos` - the diffuse VPL of the shading passes with the
//! emitter's front normal. Only the front face emits, as in the path tracer.
//!
//! **The sky:** candidates on the scene's bounding sphere, facing inwards, each a Lambertian
//! patch of the radiance the sky has in its direction from the centre (image and analytic
//! skies importance-sampled by luminance x solid angle, a constant sky uniformly). A sphere of
//! uniform radiance `L` gives every point inside it the irradiance `pi L` of a constant sky at
//! infinity, so a constant sky is exact anywhere; an image sky is exact at the centre and seen
//! with parallax elsewhere. The bounding sphere keeps every VPL within the scene's diameter of
//! every surface, the range the imperfect shadow maps' depths are normalised to. This stands in
//! for Ritschel's directional environment VPLs, whose orthographic maps the paraboloid atlas
//! does not have.
//!
//! **Layout:** the sky's candidates take whole rows of the emitter tiles, and the candidate in
//! row `r` and column `c` of the sky's `R` rows of `row` texels is the centre of that cell of
//! the sky sampler's unit square (latitude by row, longitude by column; the sampler's inverse
//! CDFs are monotone). The warp's Halton points are spread evenly over the tiles' texels, so
//! one frame's sky VPLs are then spread evenly over the sky's directions too: about the same
//! number face a window every frame, where a Halton sequence in candidate order put them
//! anywhere and one frame of `ism-ritschel` on the suite's window room read 0.79-1.21 of the
//! reference's energy.

use glam::Vec3;

use crate::precompute::bvh::SceneBvh;
use crate::precompute::emitters::Emitters;
use crate::precompute::ism::halton::radical_inverse;
use crate::precompute::sky_sampler::{luminance, sky_distribution};
use crate::scene::{Scene, Sky, SkyImage};

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

/// Whether the sky or any drawn object of `scene` emits light.
pub fn has_area_lights(scene: &Scene) -> bool {
    scene.has_sky() || (0..scene.objects().len()).any(|i| emits(scene, i))
}

/// What the candidates depend on: every emitting object's mesh, transform and emission, the
/// sky, the scene's bounds, the resources (meshes, images), the candidate count and the
/// layout's row. Equal keys give equal candidates.
pub fn key(scene: &Scene, count: usize, row: usize) -> Vec<u32> {
    let revision = scene.resources_revision();
    let mut key = vec![count as u32, row as u32, revision as u32, (revision >> 32) as u32];
    key.extend(crate::render::gi::changes::emitters_key(scene));
    if let Some(b) = scene.bounds() {
        key.extend(b.min.to_array().into_iter().chain(b.max.to_array()).map(f32::to_bits));
    }
    for (i, o) in scene.objects().iter().enumerate().filter(|(i, _)| emits(scene, *i)) {
        key.extend([i as u32, o.mesh as u32]);
        key.extend(o.transform.matrix().to_cols_array().map(f32::to_bits));
        key.push(o.material as u32);
    }
    key
}

/// A candidate of power `pi radiance area` (W; the scene's radiance is radiometric) at `p`
/// facing `normal`, a Lambertian patch.
fn candidate(p: Vec3, normal: Vec3, radiance: Vec3, area: f32) -> GpuEmitterPoint {
    let power = std::f32::consts::PI * radiance * area;
    GpuEmitterPoint {
        position: p.extend(area).to_array(),
        normal: normal.extend(0.0).to_array(),
        power: power.extend(0.5 * luminance(power)).to_array(),
    }
}

/// The `j`th of `count` stratified points of the unit square (a Halton pair).
fn halton2(j: usize) -> [f32; 2] {
    [radical_inverse(j as u64 + 1, 2) as f32, radical_inverse(j as u64 + 1, 3) as f32]
}

/// `count` candidates on the emissive surfaces and the sky of `scene` (empty without either),
/// shared between the two by power, for tiles of `row` texels a row (`count` a multiple of
/// `row`): the sky takes whole rows after the surfaces' (module docs, "Layout").
pub fn emitter_points(scene: &Scene, count: usize, row: usize) -> Vec<GpuEmitterPoint> {
    let bvh = SceneBvh::build_where(scene, |i| emits(scene, i));
    let emitters = Emitters::new(&bvh, scene.materials());
    let sky = scene.has_sky().then(|| SkySphere::new(scene)).flatten();
    let surface_power = std::f32::consts::PI * emitters.total();
    let sky_power = sky.as_ref().map_or(0.0, SkySphere::power);
    let total = surface_power + sky_power;
    if count == 0 || total <= 0.0 || !total.is_finite() {
        return Vec::new();
    }
    let row = row.clamp(1, count);
    let rows = count / row;
    let mut sky_rows = (rows as f64 * f64::from(sky_power / total)).round() as usize;
    if sky.is_some() && !emitters.is_empty() && rows >= 2 {
        sky_rows = sky_rows.clamp(1, rows - 1);
    }
    let mut out = surface_points(scene, &bvh, &emitters, count - sky_rows * row);
    if let Some(sky) = sky {
        let cell = 1.0 / (sky_rows * row) as f32;
        out.extend((0..sky_rows * row).map(|j| sky.candidate(grid_centre(j, row, sky_rows), cell)));
    }
    out
}

/// The centre of cell `j` of the unit square cut into `rows` rows (first coordinate) of `row`
/// columns (second coordinate), row after row.
fn grid_centre(j: usize, row: usize, rows: usize) -> [f32; 2] {
    let (r, c) = (j / row, j % row);
    [((r as f64 + 0.5) / rows as f64) as f32, ((c as f64 + 0.5) / row as f64) as f32]
}

/// `count` candidates on the emissive triangles of `bvh`.
fn surface_points(scene: &Scene, bvh: &SceneBvh, emitters: &Emitters, count: usize) -> Vec<GpuEmitterPoint> {
    if emitters.is_empty() || count == 0 {
        return Vec::new();
    }
    let images = &scene.resources().images;
    (0..count)
        .filter_map(|j| {
            let [u1, u2] = halton2(j);
            let s = emitters.sample(bvh, [((j as f64 + 0.5) / count as f64) as f32, u1, u2])?;
            let tri = &bvh.tris[s.tri as usize];
            let material = scene.materials().get(tri.material as usize)?;
            let radiance = crate::precompute::emitters::emission_at(material, images, tri, s.u, s.v);
            Some(candidate(s.p, tri.ng, radiance, 1.0 / (count as f32 * s.pdf_area)))
        })
        .collect()
}

/// The sky as a sphere of Lambertian patches around the scene.
struct SkySphere<'a> {
    scene: &'a Scene,
    image: Option<std::sync::Arc<SkyImage>>,
    distribution: Option<crate::precompute::sky_sampler::SkyDistribution>,
    centre: Vec3,
    radius: f32,
}

impl<'a> SkySphere<'a> {
    /// The bounding sphere of `scene` and its sky (`None` without bounds).
    fn new(scene: &'a Scene) -> Option<Self> {
        let bounds = scene.bounds()?;
        let image = scene.sky_texels();
        let distribution = sky_distribution(scene.environment(), image.as_deref());
        Some(Self { scene, distribution, image, centre: bounds.center(), radius: bounds.radius().max(1e-3) })
    }

    /// The luminance of the sky integrated over the sphere of directions (∫ L dω).
    fn flux(&self) -> f32 {
        let env = self.scene.environment();
        match (&env.sky, self.image.as_deref()) {
            (Sky::Constant(c), _) => 4.0 * std::f32::consts::PI * luminance(Vec3::from_array(*c)) * env.intensity,
            (Sky::Image(_) | Sky::Preetham { .. }, Some(img)) => {
                let rows = (0..img.height).map(|y| {
                    let row: f32 = (0..img.width).map(|x| luminance(img.texel(x, y))).sum();
                    row * img.texel_solid_angle(y)
                });
                rows.sum::<f32>() * env.intensity
            }
            _ => 0.0,
        }
    }

    /// The power the sphere's inner face sends into it: pi r^2 ∫ L dω.
    fn power(&self) -> f32 {
        std::f32::consts::PI * self.radius * self.radius * self.flux()
    }

    /// The candidate at `u` of the sampler's unit square, standing for a cell of area `cell`
    /// there: a direction by the sky's distribution (uniform for a constant sky), the sphere's
    /// patch there of area r^2 cell / pdf.
    fn candidate(&self, u: [f32; 2], cell: f32) -> GpuEmitterPoint {
        let env = self.scene.environment();
        let (d, pdf) = match &self.distribution {
            Some(dist) => {
                let (d, pdf) = dist.sample((u[0], u[1]));
                (env.to_world(d), pdf)
            }
            None => {
                let z = 1.0 - 2.0 * u[0];
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = std::f32::consts::TAU * u[1];
                (Vec3::new(r * phi.cos(), z, r * phi.sin()), 0.25 / std::f32::consts::PI)
            }
        };
        let radiance = env.radiance(d, self.image.as_deref());
        let area = self.radius * self.radius * cell / pdf.max(1e-12);
        candidate(self.centre + d * self.radius, -d, radiance, area)
    }
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
            &[
                ("floor", Vec3::ZERO, Vec3::new(4.0, 0.1, 4.0)),
                ("panel", Vec3::new(0.0, 2.0, 0.0), Vec3::new(1.0, 0.001, 0.5)),
            ],
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
        assert!(has_area_lights(&scene));
        let points = emitter_points(&scene, 4096, 64);
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
        let before = key(&scene, 4096, 64);
        assert_eq!(before, key(&scene, 4096, 64));
        scene.desc_mut().objects[1].transform.translation.x += 0.5;
        assert_ne!(before, key(&scene, 4096, 64), "a moved emitter makes new candidates");
        scene.desc_mut().objects[1].visible = false;
        assert!(
            !has_area_lights(&scene) && emitter_points(&scene, 64, 64).is_empty(),
            "a hidden emitter sends nothing"
        );
    }

    /// The sky's candidates form a grid of its directions in the tiles' layout: row r of R is
    /// latitude band r, column c longitude c, so any even pick of texels (here one texel in
    /// every block of 8 x 8, as the warp's Halton points fall on a uniform pyramid) is an even
    /// pick of directions: the same count in every octant, as many up as down.
    #[test]
    fn an_even_pick_of_the_sky_tiles_texels_is_an_even_pick_of_the_skys_directions() {
        let mut scene = crate::precompute::test_scenes::scene_of_slabs(
            &[("floor", Vec3::ZERO, Vec3::new(4.0, 0.1, 4.0))],
            Vec::new(),
        );
        scene.desc_mut().environment.sky = Sky::Constant([0.2, 0.4, 0.8]);
        let (row, rows) = (64usize, 64usize);
        let points = emitter_points(&scene, row * rows, row);
        let centre = scene.bounds().expect("bounds").center();
        let direction = |j: usize| (Vec3::from_slice(&points[j].position[..3]) - centre).normalize();
        for r in 0..rows {
            let band = (1.0 - 2.0 * r as f32 / rows as f32, 1.0 - 2.0 * (r + 1) as f32 / rows as f32);
            for c in [0, row / 2, row - 1] {
                let y = direction(r * row + c).y;
                assert!(y <= band.0 + 1e-4 && y >= band.1 - 1e-4, "row {r} column {c}: y = {y} outside {band:?}");
            }
        }
        let mut octants = [0usize; 8];
        for (by, bx) in (0..rows / 8).flat_map(|by| (0..row / 8).map(move |bx| (by, bx))) {
            // One texel per block, at an offset that moves from block to block.
            let (y, x) = (by * 8 + (bx * 3) % 8, bx * 8 + (by * 5) % 8);
            let d = direction(y * row + x);
            octants[usize::from(d.x > 0.0) + 2 * usize::from(d.y > 0.0) + 4 * usize::from(d.z > 0.0)] += 1;
        }
        assert!(octants.iter().all(|&n| n == 8), "64 picks over the octants: {octants:?}");
    }

    /// A constant sky alone: every candidate lies on the bounding sphere facing its centre, and
    /// the irradiance they give an upward patch at the centre is pi L (within sampling noise);
    /// with a panel as well, the candidates split between the two by power.
    #[test]
    fn the_sky_candidates_give_the_centre_the_irradiance_of_the_sky() {
        let mut scene = crate::precompute::test_scenes::scene_of_slabs(
            &[
                ("floor", Vec3::ZERO, Vec3::new(4.0, 0.1, 4.0)),
                ("post", Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.1, 2.0, 0.1)),
            ],
            Vec::new(),
        );
        scene.desc_mut().environment.sky = Sky::Constant([0.2, 0.4, 0.8]);
        assert!(has_area_lights(&scene));
        let bounds = scene.bounds().expect("bounds");
        let (c, r) = (bounds.center(), bounds.radius());
        let points = emitter_points(&scene, 8192, 64);
        assert_eq!(points.len(), 8192);
        let mut e = 0.0f32;
        for p in &points {
            let at = Vec3::new(p.position[0], p.position[1], p.position[2]);
            assert!(((at - c).length() - r).abs() < 1e-3 * r, "on the sphere");
            let n = Vec3::new(p.normal[0], p.normal[1], p.normal[2]);
            assert!(n.dot((c - at).normalize()) > 0.999, "facing the centre");
            let to = (at - c) / r;
            // Diffuse VPL intensity Phi / pi cos_s (cos_s = 1 towards the centre), cos_r / d^2.
            e += luminance(Vec3::new(p.power[0], p.power[1], p.power[2])) / std::f32::consts::PI * to.y.max(0.0)
                / (r * r);
        }
        let expected = std::f32::consts::PI * luminance(Vec3::new(0.2, 0.4, 0.8));
        assert!((e / expected - 1.0).abs() < 0.02, "irradiance {e} against pi L = {expected}");
        // A sky edit makes new candidates, of twice the power for twice the sky.
        let before = key(&scene, 8192, 64);
        scene.desc_mut().environment.intensity = 2.0;
        assert_ne!(before, key(&scene, 8192, 64), "a sky edit changes the key");
        let brighter = total_power(&emitter_points(&scene, 8192, 64));
        let ratio = brighter.y / total_power(&points).y;
        assert!((ratio - 2.0).abs() < 1e-3, "twice the sky: x{ratio}");
        scene.desc_mut().environment.intensity = 1.0;
        // A panel: its power over the sky's decides the split.
        scene.desc_mut().materials.push(crate::scene::Material {
            emissive_color: [1.0; 3],
            emissive_strength: 50.0,
            ..crate::scene::Material::diffuse("panel", [0.0; 3])
        });
        scene.desc_mut().objects[1].material = 1;
        let both = emitter_points(&scene, 8192, 64);
        let on_sky =
            both.iter().filter(|p| ((Vec3::from_slice(&p.position[..3]) - c).length() - r).abs() < 1e-3 * r).count();
        let post_area = 4.0 * 0.1 * 2.0 + 2.0 * 0.01;
        let (surface, sky) = (std::f32::consts::PI * post_area * 50.0, std::f32::consts::PI * r * r * 4.0 * expected);
        let share = sky / (surface + sky);
        assert!((on_sky as f32 / 8192.0 - share).abs() < 0.01, "{on_sky} on the sky, expected share {share}");
    }
}
