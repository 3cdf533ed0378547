//! WGSL sources, embedded at build time, with a small `#import path` preprocessor.
//!
//! Shaders live in `shaders/` mirroring `src/render/`; shared code sits in `shaders/common/`.
//! A line `#import common/x.wgsl` is replaced by that file's text (each file at most once per
//! shader). Tests validate every entry of [`SHADERS`] with naga and check that every file on
//! disk is listed here.

/// Every WGSL file, by path relative to `shaders/`.
pub const SHADERS: &[(&str, &str)] = &[
    ("common/brdf.wgsl", include_str!("../../shaders/common/brdf.wgsl")),
    ("common/color.wgsl", include_str!("../../shaders/common/color.wgsl")),
    ("common/frame.wgsl", include_str!("../../shaders/common/frame.wgsl")),
    ("common/interleave.wgsl", include_str!("../../shaders/common/interleave.wgsl")),
    ("common/lights.wgsl", include_str!("../../shaders/common/lights.wgsl")),
    ("common/material.wgsl", include_str!("../../shaders/common/material.wgsl")),
    ("common/object.wgsl", include_str!("../../shaders/common/object.wgsl")),
    ("common/octahedral.wgsl", include_str!("../../shaders/common/octahedral.wgsl")),
    ("common/onb.wgsl", include_str!("../../shaders/common/onb.wgsl")),
    ("common/sh9.wgsl", include_str!("../../shaders/common/sh9.wgsl")),
    ("common/shadow.wgsl", include_str!("../../shaders/common/shadow.wgsl")),
    ("common/sky.wgsl", include_str!("../../shaders/common/sky.wgsl")),
    ("common/sky_params.wgsl", include_str!("../../shaders/common/sky_params.wgsl")),
    ("common/vpl.wgsl", include_str!("../../shaders/common/vpl.wgsl")),
    ("common/workgroup_scan.wgsl", include_str!("../../shaders/common/workgroup_scan.wgsl")),
    ("common/workgroup_sum.wgsl", include_str!("../../shaders/common/workgroup_sum.wgsl")),
    ("render/composite.wgsl", include_str!("../../shaders/render/composite.wgsl")),
    ("render/gbuffer.wgsl", include_str!("../../shaders/render/gbuffer.wgsl")),
    ("render/emission.wgsl", include_str!("../../shaders/render/emission.wgsl")),
    ("render/gi/ism/importance.wgsl", include_str!("../../shaders/render/gi/ism/importance.wgsl")),
    ("render/gi/ism/ism_bounce.wgsl", include_str!("../../shaders/render/gi/ism/ism_bounce.wgsl")),
    ("render/gi/ism/ism_clips.wgsl", include_str!("../../shaders/render/gi/ism/ism_clips.wgsl")),
    ("render/gi/ism/ism_filter.wgsl", include_str!("../../shaders/render/gi/ism/ism_filter.wgsl")),
    ("render/gi/ism/ism_filter_centre.wgsl", include_str!("../../shaders/render/gi/ism/ism_filter_centre.wgsl")),
    ("render/gi/ism/ism_lookup.wgsl", include_str!("../../shaders/render/gi/ism/ism_lookup.wgsl")),
    ("render/gi/ism/ism_shade.wgsl", include_str!("../../shaders/render/gi/ism/ism_shade.wgsl")),
    ("render/gi/ism/ism_sh_filter.wgsl", include_str!("../../shaders/render/gi/ism/ism_sh_filter.wgsl")),
    ("render/gi/ism/ism_splat.wgsl", include_str!("../../shaders/render/gi/ism/ism_splat.wgsl")),
    ("render/gi/ism/ism_clear.wgsl", include_str!("../../shaders/render/gi/ism/ism_clear.wgsl")),
    ("render/gi/ism/ism_emitter_tiles.wgsl", include_str!("../../shaders/render/gi/ism/ism_emitter_tiles.wgsl")),
    ("render/gi/ism/ism_footprint.wgsl", include_str!("../../shaders/render/gi/ism/ism_footprint.wgsl")),
    ("render/gi/ism/ism_select.wgsl", include_str!("../../shaders/render/gi/ism/ism_select.wgsl")),
    ("render/gi/ism/ism_split.wgsl", include_str!("../../shaders/render/gi/ism/ism_split.wgsl")),
    ("render/gi/ism/ism_temporal.wgsl", include_str!("../../shaders/render/gi/ism/ism_temporal.wgsl")),
    ("render/gi/ism/ism_upsample.wgsl", include_str!("../../shaders/render/gi/ism/ism_upsample.wgsl")),
    ("render/gi/ism/ism_view_importance.wgsl", include_str!("../../shaders/render/gi/ism/ism_view_importance.wgsl")),
    ("render/gi/ism/ism_light_texel.wgsl", include_str!("../../shaders/render/gi/ism/ism_light_texel.wgsl")),
    ("render/gi/ism/light_gbuffer.wgsl", include_str!("../../shaders/render/gi/ism/light_gbuffer.wgsl")),
    ("render/gi/ism/pull_push.wgsl", include_str!("../../shaders/render/gi/ism/pull_push.wgsl")),
    ("render/gi/ism/vpl_generate.wgsl", include_str!("../../shaders/render/gi/ism/vpl_generate.wgsl")),
    ("render/gi/mrt/mrt_apply.wgsl", include_str!("../../shaders/render/gi/mrt/mrt_apply.wgsl")),
    ("render/gi/mrt/mrt_common.wgsl", include_str!("../../shaders/render/gi/mrt/mrt_common.wgsl")),
    ("render/gi/mrt/mrt_direct.wgsl", include_str!("../../shaders/render/gi/mrt/mrt_direct.wgsl")),
    ("render/gi/mrt/mrt_interface.wgsl", include_str!("../../shaders/render/gi/mrt/mrt_interface.wgsl")),
    ("render/gi/mrt/mrt_reconstruct.wgsl", include_str!("../../shaders/render/gi/mrt/mrt_reconstruct.wgsl")),
    ("render/gi/mrt/mrt_reduce.wgsl", include_str!("../../shaders/render/gi/mrt/mrt_reduce.wgsl")),
    ("render/gi/mrt/mrt_sides.wgsl", include_str!("../../shaders/render/gi/mrt/mrt_sides.wgsl")),
    ("render/gi/mrt/drt_patches.wgsl", include_str!("../../shaders/render/gi/mrt/drt_patches.wgsl")),
    ("render/gi/mrt/drt_rows.wgsl", include_str!("../../shaders/render/gi/mrt/drt_rows.wgsl")),
    ("render/gi/rcs/rcs_check.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_check.wgsl")),
    ("render/gi/rcs/rcs_common.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_common.wgsl")),
    ("render/gi/rcs/rcs_coverage.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_coverage.wgsl")),
    ("render/gi/rcs/rcs_hemisphere.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_hemisphere.wgsl")),
    ("render/gi/rcs/rcs_job.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_job.wgsl")),
    ("render/gi/rcs/rcs_lookup.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_lookup.wgsl")),
    ("render/gi/rcs/rcs_reduce.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_reduce.wgsl")),
    ("render/gi/rcs/rcs_resolve.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_resolve.wgsl")),
    ("render/gi/rcs/rcs_splat.wgsl", include_str!("../../shaders/render/gi/rcs/rcs_splat.wgsl")),
    ("render/gi/sshgi/sshgi_gather.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_gather.wgsl")),
    ("render/gi/sshgi/sshgi_mip.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_mip.wgsl")),
    ("render/gi/sshgi/sshgi_upsample.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_upsample.wgsl")),
    ("render/gi/sshgi/sshgi_voxel_mip.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_voxel_mip.wgsl")),
    ("render/gi/sshgi/sshgi_voxelize.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_voxelize.wgsl")),
    ("render/gi/sshgi/sshgi_visibility.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_visibility.wgsl")),
    ("render/gi/sshgi/sshgi_temporal.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_temporal.wgsl")),
    (
        "render/gi/sshgi/sshgi_panorama_pack.wgsl",
        include_str!("../../shaders/render/gi/sshgi/sshgi_panorama_pack.wgsl"),
    ),
    ("render/gi/sshgi/sshgi_hidden_pack.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_hidden_pack.wgsl")),
    (
        "render/gi/sshgi/sshgi_panorama_gather.wgsl",
        include_str!("../../shaders/render/gi/sshgi/sshgi_panorama_gather.wgsl"),
    ),
    (
        "render/gi/sshgi/sshgi_panorama_receive.wgsl",
        include_str!("../../shaders/render/gi/sshgi/sshgi_panorama_receive.wgsl"),
    ),
    ("render/gi/sshgi/sshgi_hash.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_hash.wgsl")),
    ("render/gi/sshgi/sshgi_split.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_split.wgsl")),
    ("render/gi/sshgi/sshgi_sender.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_sender.wgsl")),
    ("render/gi/sshgi/sshgi_sender_cdf.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_sender_cdf.wgsl")),
    ("render/gi/sshgi/sshgi_sender_pick.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_sender_pick.wgsl")),
    ("render/gi/sshgi/sshgi_sky.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_sky.wgsl")),
    ("render/gi/sshgi/sshgi_tail.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_tail.wgsl")),
    ("render/gi/sshgi/sshgi_world_grid.wgsl", include_str!("../../shaders/render/gi/sshgi/sshgi_world_grid.wgsl")),
    (
        "render/gi/sshgi/sshgi_panorama_common.wgsl",
        include_str!("../../shaders/render/gi/sshgi/sshgi_panorama_common.wgsl"),
    ),
    ("render/lighting.wgsl", include_str!("../../shaders/render/lighting.wgsl")),
    ("render/vo/vo.wgsl", include_str!("../../shaders/render/vo/vo.wgsl")),
    ("render/vo/vo_blur.wgsl", include_str!("../../shaders/render/vo/vo_blur.wgsl")),
    ("render/pyramid.wgsl", include_str!("../../shaders/render/pyramid.wgsl")),
    ("render/shadow_depth.wgsl", include_str!("../../shaders/render/shadow_depth.wgsl")),
    ("render/tonemap.wgsl", include_str!("../../shaders/render/tonemap.wgsl")),
];

/// The frame's own entry files (G-buffer, emission, shadows, lighting, pyramid, obscurance, composite,
/// tonemap); each technique lists its own in its registry row. The others are only imported.
pub const FRAME_SHADERS: &[&str] = &[
    "render/gbuffer.wgsl",
    "render/emission.wgsl",
    "render/lighting.wgsl",
    "render/composite.wgsl",
    "render/vo/vo.wgsl",
    "render/vo/vo_blur.wgsl",
    "render/pyramid.wgsl",
    "render/shadow_depth.wgsl",
    "render/tonemap.wgsl",
];

/// Every entry file: the frame's and every technique's (`registry::TECHNIQUES`).
pub fn entry_shaders() -> Vec<&'static str> {
    let techniques = super::gi::registry::TECHNIQUES.iter().flat_map(|t| t.shaders.iter().copied());
    FRAME_SHADERS.iter().copied().chain(techniques).collect()
}

/// A shader that could not be assembled.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ShaderError {
    /// The named file is not in [`SHADERS`].
    #[error("shader {0:?} is not embedded (add it to render::shaders::SHADERS)")]
    Unknown(String),
}

fn source(path: &str) -> Result<&'static str, ShaderError> {
    SHADERS.iter().find(|(p, _)| *p == path).map(|(_, s)| *s).ok_or_else(|| ShaderError::Unknown(path.to_owned()))
}

/// The full text of `path` with its imports expanded.
pub fn assemble(path: &str) -> Result<String, ShaderError> {
    let mut seen = Vec::new();
    let mut out = String::new();
    expand(path, &mut seen, &mut out)?;
    Ok(out)
}

fn expand(path: &str, seen: &mut Vec<String>, out: &mut String) -> Result<(), ShaderError> {
    if seen.iter().any(|s| s == path) {
        return Ok(());
    }
    seen.push(path.to_owned());
    for line in source(path)?.lines() {
        match line.trim().strip_prefix("#import ") {
            Some(import) => expand(import.trim(), seen, out)?,
            None => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    Ok(())
}

/// Creates a shader module from an assembled entry file.
pub fn module(device: &wgpu::Device, path: &str) -> Result<wgpu::ShaderModule, ShaderError> {
    let text = assemble(path)?;
    Ok(device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(path),
        source: wgpu::ShaderSource::Wgsl(text.into()),
    }))
}
