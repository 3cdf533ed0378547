//! Glossy senders in `sshgi`: the screen's surfaces send their light as diffuse senders, and a
//! glossy floor sends its lobe's share of the light too (the lighting pass's `exitance`, the
//! senders' reflectance albedo + the lobe's share of diffuse light), not only the share its lobe
//! points at the camera. A spot grazes a dark glossy floor (albedo 0.2, specular 0.6), so most
//! of the floor's first-bounce light leaves it in the lobe: one bounce must find the one-bounce
//! reference's indirect light as it does on the diffuse Cornell box (0.7-1.1 there).

use crate::common;

use bouncelab::metrics;
use bouncelab::render::Renderer;
use bouncelab::settings::{GiMode, ReferenceSettings, RenderSettings, SshgiSettings};

const SIZE: (u32, u32) = (128, 72);

#[test]
fn sshgi_finds_the_light_a_glossy_floor_sends_in_its_lobe() {
    let Some(ctx) = common::gpu() else { return };
    let project = common::glossy_cornell();
    let one_bounce =
        common::reference(&project.scene, SIZE, ReferenceSettings { spp: 128, max_bounces: 2, ..Default::default() });
    let mean = |mode: GiMode, frames: usize| {
        let sshgi = SshgiSettings { bounces: 1, start_level: 1, bounce_tail: false, ..Default::default() };
        let settings = RenderSettings { mode, sshgi, ..project.render.clone() };
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let mut sum = 0.0;
        for _ in 0..frames {
            r.render(&project.scene, &settings, SIZE).expect("render");
            let image =
                bouncelab::image_io::HdrImage { width: SIZE.0, height: SIZE.1, pixels: r.read_hdr().expect("hdr") };
            sum += metrics::mean_luminance(&image) / frames as f64;
        }
        sum
    };
    let (d, s, r1) = (mean(GiMode::Direct, 1), mean(GiMode::Sshgi, 4), metrics::mean_luminance(&one_bounce));
    let found = (s - d) / (r1 - d);
    eprintln!("glossy floor: sshgi's first bounce finds {found:.3} of the one-bounce reference's indirect light");
    assert!((0.7..=1.1).contains(&found), "the first bounce finds {found:.3} of the reference's indirect light");
}
