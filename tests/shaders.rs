//! Shader and pipeline validation without a GPU: every WGSL file is embedded and valid (naga),
//! and every pipeline is created, and a frame recorded, on wgpu's noop backend.

use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::shaders::{ENTRY_SHADERS, SHADERS, assemble};
use bouncelab::render::{GpuContext, Renderer};

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
    for path in ENTRY_SHADERS {
        let text = assemble(path).expect("assembles");
        let module =
            naga::front::wgsl::parse_str(&text).unwrap_or_else(|e| panic!("{path}: {}", e.emit_to_string(&text)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{path}: {}", e.emit_to_string(&text)));
    }
}

#[test]
fn every_pipeline_builds_on_the_noop_backend() {
    let ctx = GpuContext::new_noop().expect("noop device");
    let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let project = Project::load(&default_project_path()).expect("project");
    renderer.render(&project.scene, &project.render, (32, 16)).expect("frame records");
    if let Some(e) = pollster::block_on(scope.pop()) {
        panic!("validation error on the noop backend: {e}");
    }
}
