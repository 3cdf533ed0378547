//! The renderer's buffer inspector side: every intermediate buffer by name, read back as
//! RGBA floats, and picking through the object-id buffer.

use super::{RenderError, Renderer};
use crate::render::readback;

impl Renderer {
    /// Names of the buffers [`Renderer::read_buffer`] can read (G-buffer channels, lighting
    /// inputs and outputs).
    pub fn buffer_names() -> &'static [&'static str] {
        &[
            "albedo",
            "normal",
            "material",
            "motion",
            "object_id",
            "depth",
            "indirect",
            "hdr",
            "ldr",
            "shadow_map",
            "ism_light_albedo",
            "ism_light_normal",
            "ism_light_power",
            "ism_importance",
            "ism_atlas",
            "ism_atlas_splats",
            "ism_split_position",
            "ism_split_normal",
            "ism_raw",
            "ism_confidence",
            "ism_history",
            "ism_sh_shaded",
            "ism_sh_dc",
            "ism_sh_direction",
        ]
    }

    /// Reads a named buffer of the last frame as RGBA floats with its size.
    pub fn read_buffer(&self, name: &str) -> Result<crate::image_io::HdrImage, RenderError> {
        let t = self.targets().ok_or(RenderError::Size(0, 0, 0))?;
        let texture = match name {
            "albedo" => &t.albedo.texture,
            "normal" => &t.normal.texture,
            "material" => &t.material.texture,
            "motion" => &t.motion.texture,
            "object_id" => &t.object_id.texture,
            "depth" => &t.depth.texture,
            "indirect" => &t.indirect.texture,
            "hdr" => &t.hdr.texture,
            "ldr" => &t.ldr.texture,
            "shadow_map" => &self.shadows.texture,
            "ism_atlas" | "ism_atlas_splats" => {
                let missing =
                    || RenderError::UnknownBuffer { name: name.into(), known: "render an ism mode first".into() };
                let (levels, side) = self.gather.as_ref().and_then(|g| g.atlas()).ok_or_else(missing)?;
                let level = levels.first().ok_or_else(missing)?;
                let bytes = readback::read_buffer(&self.device, &self.queue, level)?;
                // Texels filled by pull-push carry the lowest mantissa bit (pull_push.wgsl).
                let splats_only = name == "ism_atlas_splats";
                let pixels = bytemuck::pod_collect_to_vec::<u8, u32>(&bytes)
                    .into_iter()
                    .map(|bits| {
                        let v = if splats_only && bits & 1 == 1 { 1.0 } else { f32::from_bits(bits) };
                        [v, v, v, 1.0]
                    })
                    .collect();
                return Ok(crate::image_io::HdrImage { width: side, height: side, pixels });
            }
            ism if ism.starts_with("ism_") => {
                let missing =
                    || RenderError::UnknownBuffer { name: name.into(), known: "render an ism mode first".into() };
                let light = self.vpl_pass.as_ref();
                let screen = self.gather.as_ref().map(|g| &g.screen);
                let sh_missing = || RenderError::UnknownBuffer {
                    name: name.into(),
                    known: "render an ism mode with the SH filter on first".into(),
                };
                match ism {
                    "ism_light_albedo" => &light.ok_or_else(missing)?.albedo.texture,
                    "ism_light_normal" => &light.ok_or_else(missing)?.normal.texture,
                    "ism_light_power" => &light.ok_or_else(missing)?.power.texture,
                    "ism_importance" => &light.ok_or_else(missing)?.importance,
                    "ism_split_position" => &screen.and_then(|g| g.split_gbuffer()).ok_or_else(missing)?.0.texture,
                    "ism_split_normal" => &screen.and_then(|g| g.split_gbuffer()).ok_or_else(missing)?.1.texture,
                    "ism_raw" => {
                        let raw = screen.and_then(|g| g.raw()).ok_or_else(|| RenderError::UnknownBuffer {
                            name: name.into(),
                            known: "render an ism mode with the irradiance filter first (the SH filter \
                                    accumulates coefficients: see ism_sh_shaded, ism_sh_dc, ism_sh_direction)"
                                .into(),
                        })?;
                        &raw.texture
                    }
                    "ism_confidence" => &screen.and_then(|g| g.confidence()).ok_or_else(missing)?.texture,
                    "ism_history" => &screen.and_then(|g| g.history()).ok_or_else(missing)?.texture,
                    "ism_sh_shaded" => &screen.and_then(|g| g.sh_views()).ok_or_else(sh_missing)?.0.texture,
                    "ism_sh_dc" => &screen.and_then(|g| g.sh_views()).ok_or_else(sh_missing)?.1.texture,
                    "ism_sh_direction" => &screen.and_then(|g| g.sh_views()).ok_or_else(sh_missing)?.2.texture,
                    _ => return Err(missing()),
                }
            }
            other => {
                return Err(RenderError::UnknownBuffer {
                    name: other.to_owned(),
                    known: Self::buffer_names().join(", "),
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
