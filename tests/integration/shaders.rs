//! Shader and pipeline validation without a GPU: every WGSL file is embedded and valid (naga),
//! every parameter block's Rust mirror has the WGSL struct's size, and every pipeline of every
//! mode and option is created, and frames recorded, on wgpu's noop backend.

use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::gi::registry;
use bouncelab::render::shaders::{SHADERS, assemble, entry_shaders};
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::settings::RenderSettings;

#[test]
fn every_shader_file_is_embedded() {
    let mut on_disk = Vec::new();
    let mut stack = vec![std::path::PathBuf::from("shaders")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("shaders dir") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "wgsl") {
                on_disk.push(path.strip_prefix("shaders").expect("prefix").to_string_lossy().replace('\\', "/"));
            }
        }
    }
    on_disk.sort();
    let mut embedded: Vec<String> = SHADERS.iter().map(|(p, _)| (*p).to_owned()).collect();
    embedded.sort();
    assert_eq!(on_disk, embedded, "render::shaders::SHADERS must list every file in shaders/");
}

#[test]
fn every_entry_shader_validates_with_naga() {
    for path in entry_shaders() {
        let text = assemble(path).expect("assembles");
        let module =
            naga::front::wgsl::parse_str(&text).unwrap_or_else(|e| panic!("{path}: {}", e.emit_to_string(&text)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{path}: {}", e.emit_to_string(&text)));
    }
}

#[test]
fn every_parameter_block_matches_its_wgsl_struct() {
    let techniques = registry::TECHNIQUES.iter().flat_map(|t| t.param_blocks.iter());
    let frame = bouncelab::render::obscurance::PARAM_BLOCKS.iter().chain(bouncelab::render::sky::PARAM_BLOCKS);
    for (path, name, size) in techniques.chain(frame) {
        let text = assemble(path).expect("assembles");
        let module =
            naga::front::wgsl::parse_str(&text).unwrap_or_else(|e| panic!("{path}: {}", e.emit_to_string(&text)));
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).expect("layout");
        let (handle, _) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(*name))
            .unwrap_or_else(|| panic!("{path} has no struct {name}"));
        assert_eq!(layouter[handle].size as usize, *size, "{path}: {name} is {} bytes in WGSL", layouter[handle].size);
    }
}

#[test]
fn every_pipeline_of_every_mode_builds_on_the_noop_backend() {
    let ctx = GpuContext::new_noop().expect("noop device");
    let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let project = Project::load(&default_project_path()).expect("project");
    for mode in registry::modes().map(|m| m.mode) {
        for sh_filter in [false, true] {
            // Inspecting the splats and a pyramid level adds the capture copies and the pyramid.
            for inspected in [None, Some("ism_atlas_splats"), Some("pyramid_2"), Some("sshgi_gather_1")] {
                let mut settings = RenderSettings { mode, ..project.render.clone() };
                settings.ism.sh_filter = sh_filter;
                settings.ism.bounces = 2;
                renderer.set_inspected(inspected);
                renderer.render(&project.scene, &settings, (32, 16)).expect("frame records");
            }
        }
    }
    if let Some(e) = pollster::block_on(scope.pop()) {
        panic!("validation error on the noop backend: {e}");
    }
}
