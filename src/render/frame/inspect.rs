//! The renderer's buffer inspector side: every intermediate buffer by name (the frame's own
//! and the active technique's), read back as RGBA floats, and picking through the object-id
//! buffer.

use super::{RenderError, Renderer};
use crate::render::gi::{BufferInfo, BufferView, registry};
use crate::render::readback;
use crate::settings::GiMode;

/// The buffers every mode has: the G-buffer, the direct and indirect terms, the final image,
/// the shadow maps and the shared depth/normal pyramid.
pub const FRAME_BUFFERS: &[BufferInfo] = &[
    BufferInfo { name: "albedo", description: "Linear albedo.", format: "rgba16f", view: BufferView::Colour },
    BufferInfo {
        name: "normal",
        description: "Shading normal (xy) and geometric normal (zw), octahedral.",
        format: "rgba16f",
        view: BufferView::Normal,
    },
    BufferInfo {
        name: "material",
        description: "Specular colour (rgb) and roughness (a).",
        format: "rgba8",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "motion",
        description: "Screen-uv motion to the previous frame.",
        format: "rg16f",
        view: BufferView::Normal,
    },
    BufferInfo {
        name: "object_id",
        description: "Object index + 1 (0: background).",
        format: "r32u",
        view: BufferView::Id,
    },
    BufferInfo {
        name: "depth",
        description: "Reversed hardware depth (1 near, 0 far).",
        format: "d32f",
        view: BufferView::Depth,
    },
    BufferInfo {
        name: "direct",
        description: "Shadowed direct radiance (the lighting pass).",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "exitance",
        description: "The direct light as a diffuse sender sends it: emission + (albedo + the glossy lobe's directional albedo) / pi x irradiance (what sshgi's screen senders send).",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "indirect",
        description: "The GI technique's output: E / pi, outgoing radiance or the whole image (see its mode).",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo { name: "hdr", description: "Final linear radiance.", format: "rgba32f", view: BufferView::Colour },
    BufferInfo {
        name: "vo_raw",
        description: "Volumetric obscurance before the blur: r = the factor, g = V (written where it applies: mrt by default, the VO settings).",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "vo",
        description: "Volumetric obscurance after the bilateral blur: r = the factor the indirect term is multiplied by, g = before the blur.",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ldr",
        description: "Tonemapped display image (gamma-encoded).",
        format: "rgba8",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "shadow_map",
        description: "The first shadow-map layer (standard depth).",
        format: "d32f",
        view: BufferView::Depth,
    },
    BufferInfo {
        name: "pyramid_0",
        description: "Depth/normal pyramid level 0: linear distance (r), octahedral normal (gb).",
        format: "rgba32f",
        view: BufferView::Depth,
    },
    pyramid("pyramid_1", "Depth/normal pyramid level 1 (each texel one of its children, chosen by vote)."),
    pyramid("pyramid_2", "Depth/normal pyramid level 2 (sshgi's quarter start level)."),
    pyramid("pyramid_3", "Depth/normal pyramid level 3 (sshgi's start level from 1920x1080, within its texel cap)."),
    pyramid("pyramid_4", "Depth/normal pyramid level 4 (sshgi's start level at 3840x2160)."),
    pyramid("pyramid_5", "Depth/normal pyramid level 5."),
    pyramid("pyramid_6", "Depth/normal pyramid level 6 (views of 64 pixels and more a side)."),
    pyramid("pyramid_7", "Depth/normal pyramid level 7 (views of 128 pixels and more a side)."),
];

/// An inspector entry of a pyramid level.
const fn pyramid(name: &'static str, description: &'static str) -> BufferInfo {
    BufferInfo { name, description, format: "rgba32f", view: BufferView::Depth }
}

impl Renderer {
    /// The buffers the inspector can show in `mode`: the frame's, then the technique's.
    pub fn buffers_for(mode: GiMode) -> Vec<BufferInfo> {
        FRAME_BUFFERS.iter().chain(registry::buffers(mode)).copied().collect()
    }

    /// Every buffer name of every mode (the CLI's `--buffer` check before a mode is known).
    pub fn all_buffer_names() -> Vec<&'static str> {
        let mut names: Vec<&'static str> = FRAME_BUFFERS.iter().map(|b| b.name).collect();
        for t in registry::TECHNIQUES {
            names.extend(t.buffers.iter().map(|b| b.name));
        }
        names
    }

    /// Reads a named buffer of the last frame as RGBA floats with its size.
    pub fn read_buffer(&self, name: &str) -> Result<crate::image_io::HdrImage, RenderError> {
        let t = self.targets().ok_or(RenderError::Size(0, 0, 0))?;
        let pyramid_level = name.strip_prefix("pyramid_").and_then(|l| l.parse::<usize>().ok());
        let texture = match name {
            "albedo" => &t.albedo.texture,
            "normal" => &t.normal.texture,
            "material" => &t.material.texture,
            "motion" => &t.motion.texture,
            "object_id" => &t.object_id.texture,
            "depth" => &t.depth.texture,
            "direct" => &t.direct.texture,
            "exitance" => &t.exitance.texture,
            "indirect" => &t.indirect.texture,
            "hdr" => &t.hdr.texture,
            "vo_raw" => &t.vo_raw.texture,
            "vo" => &t.vo.texture,
            "ldr" => &t.ldr.texture,
            "shadow_map" => &self.shadows.texture,
            _ if pyramid_level.is_some() => {
                let levels = self.pyramid.levels().ok_or_else(|| RenderError::UnknownBuffer {
                    name: name.into(),
                    known: "render a frame while a pyramid level is inspected (Renderer::set_inspected)".into(),
                })?;
                let level = pyramid_level.and_then(|l| levels.get(l)).ok_or_else(|| RenderError::UnknownBuffer {
                    name: name.into(),
                    known: format!("the pyramid has levels 0..{}", levels.len()),
                })?;
                &level.texture
            }
            other => {
                let technique = self.techniques.active();
                if let Some(result) = technique.and_then(|t| t.read_buffer(&self.device, &self.queue, other)) {
                    return result;
                }
                let mode = self.techniques.active_mode().unwrap_or_default();
                let known: Vec<&str> = Self::buffers_for(mode).iter().map(|b| b.name).collect();
                return Err(RenderError::UnknownBuffer {
                    name: other.to_owned(),
                    known: format!("{} (mode {})", known.join(", "), mode.name()),
                });
            }
        };
        let pixels = readback::read_as_rgba_f32(&self.device, &self.queue, texture)?;
        Ok(crate::image_io::HdrImage { width: texture.width(), height: texture.height(), pixels })
    }

    /// The object under pixel (x, y) of the last frame, through the object-id buffer.
    pub fn pick(&self, x: u32, y: u32) -> Result<Option<usize>, RenderError> {
        let t = self.targets().ok_or(RenderError::Size(0, 0, 0))?;
        let id = readback::read_texel_u32(&self.device, &self.queue, &t.object_id.texture, x, y)?;
        Ok(id.checked_sub(1).map(|i| i as usize))
    }
}
