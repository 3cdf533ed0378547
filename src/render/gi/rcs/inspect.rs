//! The rcs inspector buffers: what each shows and how it is read from the technique's
//! targets (the accumulation buffers normalised on the CPU, the coverage masks, the atlas).

use super::coverage::CoveragePass;
use super::hemisphere::HemispherePass;
use super::splat::SplatPass;
use crate::image_io::HdrImage;
use crate::render::gi::technique::{BufferInfo, BufferView};
use crate::render::{RenderError, readback};

/// An inspector entry.
const fn buffer(name: &'static str, description: &'static str, view: BufferView) -> BufferInfo {
    BufferInfo { name, description, format: "rgba32f", view }
}

/// The inspector's buffers.
pub const BUFFERS: &[BufferInfo] = &[
    buffer(
        "rcs_coverage",
        "coverage after the frame's last round: r = uncovered (no record reaches it: none once the cache has filled), g = the coverage pass that picked this pixel for a record this frame, b = geometry",
        BufferView::Colour,
    ),
    buffer(
        "rcs_weight",
        "summed Ward weight of the records reaching each pixel (false colour, log): peaks at record sites, smooth falloff, seams along creases where the normal term cuts zones",
        BufferView::Scalar,
    ),
    buffer(
        "rcs_record_count",
        "how many records each pixel interpolates (overlapping zones; 0 = uncovered)",
        BufferView::Scalar,
    ),
    buffer("rcs_irradiance", "interpolated irradiance E with the gradients: smooth", BufferView::Colour),
    buffer(
        "rcs_irradiance_plain",
        "interpolated irradiance without the gradients: faint disc-shaped blotches are normal",
        BufferView::Colour,
    ),
    buffer(
        "rcs_gradient_difference",
        "irradiance with gradients minus without (signed): structure near occluders and corners",
        BufferView::Colour,
    ),
    buffer(
        "rcs_records_added",
        "the pixels this frame's coverage picked for new records (the next frame makes them), coloured by the coverage pass that picked them (black: none)",
        BufferView::Scalar,
    ),
    buffer(
        "rcs_hemispheres",
        "the last round's hemisphere planes (outgoing radiance the records saw; a = distance), one tile per record",
        BufferView::Colour,
    ),
    buffer(
        "rcs_hemisphere_surfaces",
        "the surfaces the last round's planes saw: r = albedo luminance, g = 1 where the cache answered the bounce lookup, b = 1 where it had no record facing the same way, g = b = 0.5 where it extrapolated from records whose zones miss the point",
        BufferView::Colour,
    ),
];

/// The passes whose targets the buffers come from.
pub struct Inspected<'a> {
    pub splat: &'a SplatPass,
    pub coverage: &'a CoveragePass,
    pub hemisphere: &'a HemispherePass,
}

/// Reads a texture as RGBA floats.
fn read(device: &wgpu::Device, queue: &wgpu::Queue, texture: &wgpu::Texture) -> Result<HdrImage, RenderError> {
    let pixels = readback::read_as_rgba_f32(device, queue, texture)?;
    Ok(HdrImage { width: texture.width(), height: texture.height(), pixels })
}

/// `texture` read and mapped texel by texel.
fn mapped(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: Option<&wgpu::Texture>,
    name: &str,
    map: impl Fn([f32; 4]) -> [f32; 4],
) -> Result<HdrImage, RenderError> {
    let texture =
        texture.ok_or_else(|| RenderError::UnknownBuffer { name: name.into(), known: "render rcs first".into() })?;
    let mut img = read(device, queue, texture)?;
    img.pixels.iter_mut().for_each(|p| *p = map(*p));
    Ok(img)
}

impl Inspected<'_> {
    /// Buffer `name`, or `None` when it is not an rcs buffer.
    pub fn read(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        name: &str,
    ) -> Option<Result<HdrImage, RenderError>> {
        if !BUFFERS.iter().any(|b| b.name == name) {
            return None;
        }
        let mask = self.coverage.mask().map(|m| &m.texture);
        let atlas = self.hemisphere.atlas();
        Some(match name {
            "rcs_coverage" => mapped(device, queue, mask, name, |p| p),
            "rcs_records_added" => mapped(device, queue, mask, name, |p| [p[1], p[1], p[1], 1.0]),
            "rcs_hemispheres" => mapped(device, queue, atlas.map(|a| &a.radiance.texture), name, |p| p),
            "rcs_hemisphere_surfaces" => mapped(device, queue, atlas.map(|a| &a.surface.texture), name, |p| {
                let (hit, beyond, miss) = ((p[3] - 2.0).abs() < 0.1, p[3] > 2.5, (p[3] - 0.5).abs() < 0.1);
                let flag = |b: bool| f32::from(u8::from(b));
                [p[2], flag(hit) + 0.5 * flag(beyond), flag(miss) + 0.5 * flag(beyond), 1.0]
            }),
            _ => self.accumulated(device, queue, name),
        })
    }

    /// A buffer computed from the accumulation buffers.
    fn accumulated(&self, device: &wgpu::Device, queue: &wgpu::Queue, name: &str) -> Result<HdrImage, RenderError> {
        let Some(accum) = self.splat.accum() else {
            return Err(RenderError::UnknownBuffer { name: name.into(), known: "render rcs first".into() });
        };
        let texels = |buffer| -> Result<Vec<[f32; 4]>, RenderError> {
            Ok(bytemuck::pod_collect_to_vec(&readback::read_buffer(device, queue, buffer)?))
        };
        let (width, height) = accum.size;
        let mut w = HdrImage { width, height, pixels: texels(&accum.weighted)? };
        let p = texels(&accum.plain)?;
        for (a, b) in w.pixels.iter_mut().zip(&p) {
            let sum = a[3];
            let norm = |c: f32| if sum > 0.0 { c / sum } else { 0.0 };
            let with = [norm(a[0]), norm(a[1]), norm(a[2])];
            let plain = [norm(b[0]), norm(b[1]), norm(b[2])];
            *a = match name {
                "rcs_weight" => [sum, sum, sum, 1.0],
                "rcs_record_count" => [b[3], b[3], b[3], 1.0],
                "rcs_irradiance" => [with[0], with[1], with[2], 1.0],
                "rcs_irradiance_plain" => [plain[0], plain[1], plain[2], 1.0],
                _ => [with[0] - plain[0], with[1] - plain[1], with[2] - plain[2], 1.0],
            };
        }
        Ok(w)
    }
}
