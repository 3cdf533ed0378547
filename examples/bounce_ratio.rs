//! Energy check of the ISM bounce passes: renders `ism-ritschel` on a closed glTF level with
//! every surface one grey albedo (`--albedo`, default 0.7) and prints each bounce set's total
//! power over the last set's. All the light a set emits lands on some surface of a closed level,
//! so each ratio must be the albedo; a shortfall is light the bounce passes lose.
//!
//! `cargo run --release --example bounce_ratio -- level.gltf --settings "(bounce_tail: false, view_importance: 0.0)"
//! --frames 16` (`--help` lists the flags).
use anyhow::Context;
use bouncelab::project_file::Project;
use bouncelab::render::gi::ism::technique::IsmTechnique;
use bouncelab::render::gi::ism::vpl_pass::set_powers;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::scene::Material;
use bouncelab::settings::{GiMode, IsmSettings, RenderSettings};
use clap::Parser;

/// Each ISM bounce set's power over the previous set's on a closed level of one albedo.
#[derive(Parser)]
struct Args {
    /// A closed glTF level.
    level: std::path::PathBuf,
    /// ISM settings (RON); fields left out keep their defaults.
    #[arg(long, default_value = "()")]
    settings: String,
    /// Frames summed.
    #[arg(long, default_value_t = 16)]
    frames: u32,
    /// The grey albedo every surface gets (the ratio each set must reach).
    #[arg(long, default_value_t = 0.7)]
    albedo: f32,
}

fn main() -> anyhow::Result<()> {
    let args = Args::parse();
    let ism: IsmSettings = ron::from_str(&args.settings)?;
    let (frames, albedo) = (args.frames, args.albedo);
    let ctx = GpuContext::new_headless()?;
    let mut project = Project::from_gltf(&args.level)?;
    for m in &mut project.scene.desc_mut().materials {
        *m = Material::diffuse(&m.name, [albedo; 3]);
    }
    let settings = RenderSettings { mode: GiMode::IsmRitschel, ism: ism.clone(), ..project.render.clone() };
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    let n = ism.vpl_count as usize;
    let mut sums = vec![0.0f64; ism.bounces as usize];
    for _ in 0..frames {
        r.render(&project.scene, &settings, (64, 36))?;
        let t = r.technique_as::<IsmTechnique>().context("the ism technique is active")?;
        let all = t.read_all_vpls(r.device(), r.queue())?;
        for (sum, set) in sums.iter_mut().zip(set_powers(&all, n)) {
            *sum += set;
        }
    }
    for (k, w) in sums.windows(2).enumerate() {
        println!("set {}: power {:.4e}, over set {k}'s {:.4} (albedo {albedo})", k + 1, w[1], w[1] / w[0]);
    }
    Ok(())
}
