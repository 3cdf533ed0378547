//! Segovia & Wald's SH filter in the ISM technique: on diffuse scenes it matches the irradiance
//! filter and the reference; on a normal-mapped floor it stays closer to brute-force shading
//! (every VPL at every pixel, no interleaving, no filter) than the irradiance filter does; its
//! inspector buffers are readable.

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::Renderer;
use bouncelab::settings::{GiMode, ReferenceSettings, RenderSettings};

/// The suite's normal-mapped Cornell box: a 2 m floor overlay whose normal map has grooves two
/// texels wide (normals tilted +-35 degrees about the z axis), 64 texels across: 2-4 px at 128^2.
fn bumpy_cornell() -> Project {
    bouncelab::suite::scene("bumpy").expect("suite scene").load(std::path::Path::new(".")).expect("loads")
}

fn render(r: &mut Renderer, project: &Project, settings: &RenderSettings, size: (u32, u32)) -> Vec<[f32; 4]> {
    r.render(&project.scene, settings, size).expect("render");
    r.read_hdr().expect("hdr")
}

#[test]
fn sh_filter_keeps_normal_map_detail_the_irradiance_filter_loses() {
    let Some(ctx) = common::gpu() else { return };
    let project = bumpy_cornell();
    let size = (128, 128);
    let mut settings = project.render.clone();
    settings.mode = GiMode::IsmRitschel;
    settings.ism.bounces = 1;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    // The same VPL set (frame 0 of a fresh renderer) for all three.
    let run = |interleave: u32, sh: bool| {
        let mut s = settings.clone();
        s.ism.interleave = interleave;
        s.ism.sh_filter = sh;
        let mut fresh = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        render(&mut fresh, &project, &s, size)
    };
    let brute = run(1, false);
    let irradiance = run(4, false);
    let sh = run(4, true);
    r.render(&project.scene, &settings, size).expect("render");
    let ids = r.read_buffer("object_id").expect("ids");
    let bumpy = project.scene.objects().len() as f32; // id = index + 1 of the last object
    let mask: Vec<bool> = ids.pixels.iter().map(|p| p[0] == bumpy).collect();
    let count = mask.iter().filter(|m| **m).count();
    assert!(count > 1000, "the bumpy floor covers {count} pixels");
    let rmse = |img: &[[f32; 4]]| {
        let se: f64 = img
            .iter()
            .zip(&brute)
            .zip(&mask)
            .filter(|(_, m)| **m)
            .map(|((a, b), _)| (0..3).map(|c| f64::from(a[c] - b[c]).powi(2)).sum::<f64>() / 3.0)
            .sum();
        (se / count as f64).sqrt()
    };
    let mean: f64 =
        brute.iter().zip(&mask).filter(|(_, m)| **m).map(|(p, _)| f64::from(p[1])).sum::<f64>() / count as f64;
    let (e_irr, e_sh) = (rmse(&irradiance), rmse(&sh));
    for (name, img) in [("brute", &brute), ("irradiance", &irradiance), ("sh", &sh)] {
        let img = HdrImage { width: size.0, height: size.1, pixels: img.clone() };
        let ldr = bouncelab::image_io::tonemap_srgb8(&img, &settings.view);
        let path = std::env::temp_dir().join(format!("bouncelab-ism-sh-bumpy-{name}.png"));
        bouncelab::image_io::write_png(&path, size.0, size.1, ldr).expect("png");
    }
    eprintln!(
        "bumpy floor ({count} px, mean {mean:.4}): RMSE against brute force, irradiance filter {e_irr:.5}, SH filter {e_sh:.5}"
    );
    // Measured 0.70 of the irradiance filter's error with the footprint splats.
    assert!(e_sh < 0.75 * e_irr, "SH filter {e_sh} vs irradiance filter {e_irr}");
}

#[test]
#[ignore = "heavy: default-settings ism frames with and without the SH filter against a reference"]
fn sh_filter_on_the_diffuse_cornell_box_matches_the_reference() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let size = (64, 36);
    let reference = common::reference(&project.scene, size, ReferenceSettings { spp: 512, ..Default::default() });
    let direct = {
        let settings = RenderSettings { mode: GiMode::Direct, ..project.render.clone() };
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        HdrImage { width: size.0, height: size.1, pixels: render(&mut r, &project, &settings, size) }
    };
    let direct_flip = metrics::flip(&direct, &reference, 0.0).expect("flip").0;
    let mut results = Vec::new();
    for sh in [false, true] {
        let mut settings = project.render.clone();
        settings.mode = GiMode::Ism;
        settings.ism.sh_filter = sh;
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let mut img = Vec::new();
        for _ in 0..32 {
            img = render(&mut r, &project, &settings, size);
        }
        let img = HdrImage { width: size.0, height: size.1, pixels: img };
        if sh {
            for name in ["ism_sh_shaded", "ism_sh_dc", "ism_sh_direction", "ism_split_normal"] {
                let b = r.read_buffer(name).expect(name);
                assert!(b.pixels.iter().all(|p| p.iter().all(|v| v.is_finite())), "{name} has non-finite texels");
            }
            let dc = r.read_buffer("ism_sh_dc").expect("dc");
            let accepted = dc.pixels.iter().filter(|p| p[3] > 0.0).map(|p| p[3]).sum::<f32>()
                / dc.pixels.iter().filter(|p| p[3] > 0.0).count().max(1) as f32;
            eprintln!("mean accepted-tap fraction of the SH filter: {accepted:.3}");
            assert!(accepted > 0.3, "the SH filter rejects too many taps: {accepted}");
        }
        let flip = metrics::flip(&img, &reference, 0.0).expect("flip").0;
        let lum = metrics::luminance_ratio(&img, &reference).expect("ratio");
        results.push((flip, lum));
    }
    let [(f_irr, l_irr), (f_sh, l_sh)] = [results[0], results[1]];
    eprintln!(
        "full GI, 32 frames: direct FLIP {direct_flip:.4}; irradiance filter FLIP {f_irr:.4} lum {l_irr:.3}; \
         SH filter FLIP {f_sh:.4} lum {l_sh:.3}"
    );
    // Against the reference: both filters at most half of direct's error, energy within the
    // scene-suite issue's 10% (0.91 with the SH filter, 0.92 without; tests/integration/ism.rs says why).
    assert!(f_sh < 0.5 * direct_flip, "SH filter FLIP {f_sh} vs direct {direct_flip}");
    assert!((l_sh - 1.0).abs() < 0.1, "SH filter luminance ratio {l_sh}");
    assert!(f_irr < 0.5 * direct_flip, "irradiance filter FLIP {f_irr} vs direct {direct_flip}");
    // Measured 0.132 against 0.113 with the default (footprint-splat) maps.
    assert!(f_sh < 1.2 * f_irr, "SH filter FLIP {f_sh} vs irradiance filter {f_irr}");
    assert!((l_sh / l_irr - 1.0).abs() < 0.03, "SH and irradiance luminance differ: {l_sh} vs {l_irr}");
}

#[test]
fn sh_filter_beyond_the_adapters_binding_limit_is_a_clear_error() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let mut settings = project.render.clone();
    settings.mode = GiMode::Ism;
    settings.ism.sh_filter = true;
    let limits = ctx.device.limits();
    let side = limits.max_texture_dimension_2d;
    let needed = u64::from(side.div_ceil(4) * 4).pow(2) * 56;
    let limit = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
    eprintln!("SH coefficients at {side}^2: {} MiB, binding limit {} MiB", needed >> 20, limit >> 20);
    if needed <= limit {
        return; // This adapter binds enough for its largest view.
    }
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let err = r.render(&project.scene, &settings, (side, side)).expect_err("must refuse");
    let text = err.to_string();
    assert!(text.contains("SH filter") && text.contains("MiB"), "{text}");
}

#[test]
fn the_filtered_sh_field_carries_no_trace_of_the_normal_map() {
    let Some(ctx) = common::gpu() else { return };
    let bumpy = bumpy_cornell();
    let mut flat = bumpy.clone();
    let last = flat.scene.desc().materials.len() - 1;
    flat.scene.desc_mut().materials[last].normal_texture = None;
    let size = (96, 96);
    let mut settings = bumpy.render.clone();
    settings.mode = GiMode::IsmRitschel;
    settings.ism.bounces = 1;
    settings.ism.sh_filter = true;
    let read = |project: &Project| {
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        r.render(&project.scene, &settings, size).expect("render");
        let ids = r.read_buffer("object_id").expect("ids");
        let dc = r.read_buffer("ism_sh_dc").expect("dc");
        let dir = r.read_buffer("ism_sh_direction").expect("direction");
        let shaded = r.read_buffer("ism_sh_shaded").expect("shaded");
        (ids, dc, dir, shaded)
    };
    let (ids, dc_b, dir_b, shaded_b) = read(&bumpy);
    let (_, dc_f, dir_f, shaded_f) = read(&flat);
    let floor = bumpy.scene.objects().len() as f32;
    let mask: Vec<usize> = (0..ids.pixels.len()).filter(|&i| ids.pixels[i][0] == floor).collect();
    assert!(mask.len() > 500, "floor pixels: {}", mask.len());
    let max_diff = |a: &bouncelab::image_io::HdrImage, b: &bouncelab::image_io::HdrImage| {
        mask.iter()
            .map(|&i| (0..3).map(|c| (a.pixels[i][c] - b.pixels[i][c]).abs()).fold(0.0, f32::max))
            .fold(0.0, f32::max)
    };
    let mean = mask.iter().map(|&i| shaded_f.pixels[i][1]).sum::<f32>() / mask.len() as f32;
    let (d_dc, d_dir, d_shaded) = (max_diff(&dc_b, &dc_f), max_diff(&dir_b, &dir_f), max_diff(&shaded_b, &shaded_f));
    eprintln!(
        "normal map on/off over {} floor px: max change of the SH field DC {d_dc:.2e}, direction {d_dir:.2e}; \
         of the shaded result {d_shaded:.3} (mean {mean:.3})",
        mask.len()
    );
    assert!(d_dc < 1e-3 * mean.max(1e-3) && d_dir < 1e-3, "the normal map leaked into the filtered field");
    assert!(d_shaded > 0.1 * mean, "the shading must carry the normal map's detail");
}
