//! Diagnostic: per-set power ratios W_{k+1} / W_k of `ism` in a closed scene with one albedo
//! (every surface `BR_ALBEDO`), where energy conservation makes each ratio exactly the albedo.
use bouncelab::project_file::Project;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::render::gi::ism::technique::IsmTechnique;
use bouncelab::settings::{GiMode, IsmSettings, RenderSettings};
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let gltf = &args[1];
    let ism: IsmSettings = ron::from_str(args.get(2).map_or("()", String::as_str))?;
    let frames: u32 = args.get(3).map_or(Ok(16), |s| s.parse())?;
    let albedo: f32 = std::env::var("BR_ALBEDO").ok().and_then(|v| v.parse().ok()).unwrap_or(0.7);
    let ctx = GpuContext::new_headless()?;
    let mut project = Project::from_gltf(Path::new(gltf))?;
    for m in &mut project.scene.desc_mut().materials {
        m.base_color = [albedo, albedo, albedo, 1.0];
        m.base_color_texture = None;
        m.specular = [0.0; 3];
    }
    let settings = RenderSettings { mode: GiMode::IsmRitschel, ism: ism.clone(), ..project.render.clone() };
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    let n = ism.vpl_count as usize;
    let b = ism.bounces as usize;
    let mut sums = vec![0.0f64; b];
    for _ in 0..frames {
        r.render(&project.scene, &settings, (64, 36))?;
        let t = r.technique_as::<IsmTechnique>().ok_or_else(|| anyhow::anyhow!("ism"))?;
        let all = t.read_all_vpls(r.device(), r.queue())?;
        if std::env::var_os("BR_DUMP").is_some() {
            for v in &all[0..n] {
                println!("vpl0 {:.3} {:.3} {:.3} n {:.2} {:.2} {:.2} p {:.4e} w {:.4e}", v.position[0], v.position[1], v.position[2], v.normal[0], v.normal[1], v.normal[2], v.power[1], v.position[3]);
            }
        }
        for k in 0..b {
            sums[k] += all[k * n..(k + 1) * n].iter().map(|v| f64::from(v.power[1])).sum::<f64>();
        }
    }
    for k in 1..b {
        println!("set {k}: W = {:.4e}, W_k / W_(k-1) = {:.4} (albedo {albedo})", sums[k], sums[k] / sums[k - 1]);
    }
    Ok(())
}
