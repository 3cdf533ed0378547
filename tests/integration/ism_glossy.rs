//! Glossy VPL lobes (Knecht 2009 Eq. 4.8 with the renderer's Blinn-Phong BRDF): a spot light
//! grazes a glossy floor, so much of the first-bounce light leaves the floor in its specular
//! lobe. `ism-ritschel` with one bounce must match a two-bounce reference in energy and be much
//! closer to it than `direct`, with the irradiance filter and with the SH filter (which also
//! shades glossy receivers).

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::render::Renderer;
use bouncelab::settings::{GiMode, ReferenceSettings};

#[test]
fn glossy_first_bounce_matches_the_reference() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = common::glossy_cornell();
    project.render.ism.bounces = 1;
    let size = (64, 36);
    let reference =
        common::reference(&project.scene, size, ReferenceSettings { spp: 512, max_bounces: 2, ..Default::default() });
    let frames = 6;
    let mean = |mode: GiMode, sh: bool| {
        let mut settings = project.render.clone();
        settings.mode = mode;
        settings.ism.sh_filter = sh;
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let mut sum = vec![[0.0f32; 4]; (size.0 * size.1) as usize];
        for _ in 0..frames {
            r.render(&project.scene, &settings, size).expect("render");
            for (s, p) in sum.iter_mut().zip(r.read_hdr().expect("hdr")) {
                for c in 0..4 {
                    s[c] += p[c] / frames as f32;
                }
            }
        }
        HdrImage { width: size.0, height: size.1, pixels: sum }
    };
    let direct = mean(GiMode::Direct, false);
    let fd = metrics::flip(&direct, &reference, 0.0).expect("flip").0;
    let ld = metrics::luminance_ratio(&direct, &reference).expect("ratio");
    eprintln!("glossy floor: direct FLIP {fd:.4} luminance {ld:.3}");
    for sh in [false, true] {
        let ism = mean(GiMode::IsmRitschel, sh);
        let fi = metrics::flip(&ism, &reference, 0.0).expect("flip").0;
        let li = metrics::luminance_ratio(&ism, &reference).expect("ratio");
        eprintln!("glossy floor, SH filter {sh}: ism-ritschel FLIP {fi:.4} luminance {li:.3}");
        assert!(fi < 0.75 * fd, "FLIP {fi} vs direct {fd}");
        assert!((li - 1.0).abs() < 0.1, "luminance off by {:.1}%", (li - 1.0) * 100.0);
    }
}
