//! An oracle for `sshgi`'s first bounce: the exact screen-space gather it approximates. It
//! renders the project in `sshgi` with one bounce and no temporal filter, reads the start
//! level's voted points and normals and its outgoing radiance, and sums on the CPU, for every
//! start-level texel, every other texel's light with the same bounded form factor (Soler et al.
//! 2010, Eq. 4 with one texel's area, Eq. 2) and exact visibility by casting rays through the
//! scene's triangles. The gap between that sum and sshgi's first bounce is what the hierarchy,
//! its sampling and the voxel visibility lose; the gap between the sum and a one-bounce path
//! tracer is what screen space itself loses (senders off screen or hidden). The example
//! `sshgi_oracle` prints it; a heavy test holds the user guide's claim to it.

use glam::Vec3;
use rayon::prelude::*;

use crate::image_io::HdrImage;
use crate::precompute::bvh::SceneBvh;
use crate::project_file::Project;
use crate::render::octahedral::oct_decode;
use crate::render::{RenderError, Renderer};
use crate::settings::{GiMode, SshgiSettings};

/// Means over the start level of E / pi (mean of the RGB channels).
#[derive(Clone, Debug, PartialEq)]
pub struct GatherReport {
    /// The start level's size (texels).
    pub start: (usize, usize),
    /// The finest level's ring radius (texels).
    pub radius: f32,
    /// sshgi's first bounce, the mean of the frames.
    pub sshgi: f64,
    /// The exact gather with ray-cast visibility.
    pub visible: f64,
    /// The exact gather without visibility.
    pub unoccluded: f64,
    /// Per screen distance bucket (level 0: the disc of `radius` texels; level k: radius
    /// 2^(k-1)..radius 2^k; the last: beyond), the gather with and without visibility.
    pub per_level: Vec<(f64, f64)>,
    /// Each level's own gather in sshgi (mean of the frames).
    pub gathers: Vec<f64>,
    /// Per level below the coarsest: the up-sampled sum of the levels above it, minus its
    /// gather.
    pub carried: Vec<f64>,
}

/// Renders `project` in `sshgi` with `settings` (one bounce, no temporal filter) at `size` for
/// `frames` frames, and compares its first bounce with the exact gather.
pub fn first_bounce(
    renderer: &mut Renderer,
    project: &Project,
    settings: &SshgiSettings,
    size: (u32, u32),
    frames: usize,
) -> Result<GatherReport, RenderError> {
    let mut render = project.render.clone();
    render.mode = GiMode::Sshgi;
    // The screen's own gather: the panorama's senders are not what it approximates.
    render.sshgi = SshgiSettings { bounces: 1, temporal_weight: 0.0, panorama: 0, ..settings.clone() };
    let levels = render.sshgi.levels as usize;
    let frames = frames.max(1);
    let (mut bounce, mut gathers, mut carried) = (None::<HdrImage>, vec![0.0f64; levels], vec![0.0f64; levels]);
    for _ in 0..frames {
        renderer.render(&project.scene, &render, size)?;
        let b = renderer.read_buffer("sshgi_bounce_1")?;
        match &mut bounce {
            Some(sum) => sum.pixels.iter_mut().zip(&b.pixels).for_each(|(s, p)| (0..4).for_each(|c| s[c] += p[c])),
            None => bounce = Some(b),
        }
        for (k, g) in gathers.iter_mut().enumerate().filter(|_| levels > 1) {
            *g += mean_rgb(&renderer.read_buffer(&format!("sshgi_gather_{k}"))?) / frames as f64;
        }
        for (k, c) in carried.iter_mut().enumerate().take(levels.saturating_sub(1)) {
            let sum = if k == 0 { "sshgi_bounce_1".to_owned() } else { format!("sshgi_sum_{k}") };
            let gather = mean_rgb(&renderer.read_buffer(&format!("sshgi_gather_{k}"))?);
            *c += (mean_rgb(&renderer.read_buffer(&sum)?) - gather) / frames as f64;
        }
    }
    let sshgi = bounce.as_ref().map_or(0.0, mean_rgb) / frames as f64;
    let start = render.sshgi.start_level_for(size, crate::render::pyramid::level_count(size)) as usize;
    let geo = renderer.read_buffer(&format!("pyramid_{start}"))?;
    let light = renderer.read_buffer("sshgi_illumination_0")?;
    let (w, h) = (geo.width as usize, geo.height as usize);
    let texels = start_texels(project, &geo, &light, size, start);
    let radius = render.sshgi.ring_radius((w as u32, h as u32), render.sshgi.levels);
    let sums = exact_gather(project, &texels, w, radius, levels);
    let n = (w * h) as f64;
    let per_level: Vec<(f64, f64)> = (0..=levels)
        .map(|k| (sums.iter().map(|s| s.0[k]).sum::<f64>() / n, sums.iter().map(|s| s.1[k]).sum::<f64>() / n))
        .collect();
    Ok(GatherReport {
        start: (w, h),
        radius,
        sshgi,
        visible: per_level.iter().map(|l| l.0).sum(),
        unoccluded: per_level.iter().map(|l| l.1).sum(),
        per_level,
        gathers,
        carried,
    })
}

/// A start-level texel: point, normal, outgoing radiance and the area it stands for.
type Texel = (Vec3, Vec3, Vec3, f32);

/// Each start-level texel's point, normal, radiance and area (`None`: background), from the
/// depth pyramid (x: distance, yz: octahedral normal, w: the voted pixel's index + 0.5).
fn start_texels(
    project: &Project,
    geo: &HdrImage,
    light: &HdrImage,
    size: (u32, u32),
    start: usize,
) -> Vec<Option<Texel>> {
    let camera = *project.scene.camera();
    let forward = camera.forward();
    let tan_y = (camera.yfov * 0.5).tan();
    let tan_x = tan_y * size.0 as f32 / size.1 as f32;
    let texel_sr = 4.0 * tan_x * tan_y / (size.0 * size.1) as f32 * (1u32 << (2 * start)) as f32;
    geo.pixels
        .iter()
        .zip(&light.pixels)
        .map(|(g, l)| {
            (g[3] >= 0.5).then(|| {
                let index = (g[3] - 0.5) as u32;
                let (px, py) = ((index % size.0) as f32 + 0.5, (index / size.0) as f32 + 0.5);
                let dir = camera.ray_direction(px, py, size.0, size.1);
                let cos_a = dir.dot(forward).max(0.0);
                let n = oct_decode([g[1], g[2]]);
                let cos_b = n.dot(-dir).max(0.05);
                let ds = texel_sr * cos_a.powi(3) * g[0] * g[0] / cos_b;
                (camera.position + dir * g[0], n, Vec3::new(l[0], l[1], l[2]), ds)
            })
        })
        .collect()
}

/// Per texel, E / pi by screen distance bucket, with and without ray-cast visibility.
fn exact_gather(
    project: &Project,
    texels: &[Option<Texel>],
    w: usize,
    radius: f32,
    levels: usize,
) -> Vec<(Vec<f64>, Vec<f64>)> {
    let bucket =
        |d: f32| -> usize { if d < radius { 0 } else { ((d / radius).log2().floor() as usize + 1).min(levels) } };
    let bvh = SceneBvh::build(&project.scene);
    let eps = 1e-3 * bvh.scale;
    (0..texels.len())
        .into_par_iter()
        .map(|i| {
            let (mut vis, mut open) = (vec![0.0f64; levels + 1], vec![0.0f64; levels + 1]);
            let Some((x, nx, _, _)) = texels[i] else { return (vis, open) };
            for (j, t) in texels.iter().enumerate() {
                let Some((y, ny, l, ds)) = *t else { continue };
                let v = y - x;
                let d2 = v.length_squared();
                if i == j || d2 < 1e-10 {
                    continue;
                }
                let vh = v / d2.sqrt();
                let (cos_r, cos_s) = (nx.dot(vh), ny.dot(-vh));
                if cos_r <= 0.0 || cos_s <= 0.0 {
                    continue;
                }
                let r2 = cos_s * ds / std::f32::consts::PI;
                let e = f64::from((l.x + l.y + l.z) / 3.0 * r2 * cos_r / (d2 + r2));
                let (dx, dy) = ((i % w) as f32 - (j % w) as f32, (i / w) as f32 - (j / w) as f32);
                let k = bucket((dx * dx + dy * dy).sqrt());
                open[k] += e;
                let o = x + nx * eps;
                let to = y + ny * eps - o;
                if !bvh.occluded(o, to.normalize(), to.length() * 0.999) {
                    vis[k] += e;
                }
            }
            (vis, open)
        })
        .collect()
}

fn mean_rgb(img: &HdrImage) -> f64 {
    img.pixels.iter().map(|p| f64::from(p[0] + p[1] + p[2]) / 3.0).sum::<f64>() / img.pixels.len().max(1) as f64
}
