//! The quality matrix's contact sheet (`docs/quality_sheet.png`): per suite scene a row of
//! tiles, the reference and then each mode, and beneath it each mode's signed error map (red:
//! too bright, blue: too dark). Tiles are scaled up (nearest texel) to at least 256 pixels wide
//! so a reader can judge them, each column is named above the first row, and each row is named
//! at its left. The labels are drawn with egui's own fonts, rasterised on the CPU, so the sheet
//! needs no font of the system's.

use std::path::Path;

use egui::epaint::text::{FontDefinitions, Fonts, TextOptions};
use egui::{Color32, FontId};

use crate::image_io;

/// Tile magnification: the suite's 128 x 72 references become 256 x 144.
pub const SCALE: usize = 2;
/// Height of the column titles' band (pixels).
const HEADER: usize = 24;
/// Width of the row names' band (pixels).
const GUTTER: usize = 112;
/// Label text size (pixels).
const TEXT: f32 = 14.0;

/// One scene of the sheet: its name, its reference and per mode the tonemapped tile and the
/// error map (RGBA8, the reference's size).
pub struct SheetRow {
    pub scene: String,
    pub reference: Vec<u8>,
    pub cells: Vec<(Vec<u8>, Option<Vec<u8>>)>,
}

/// An RGBA8 canvas with labels.
struct Canvas {
    width: usize,
    height: usize,
    rgba: Vec<u8>,
    fonts: Fonts,
}

impl Canvas {
    fn new(width: usize, height: usize) -> Self {
        let rgba = std::iter::repeat_n([24u8, 24, 24, 255], width * height).flatten().collect();
        Self { width, height, rgba, fonts: Fonts::new(TextOptions::default(), FontDefinitions::default()) }
    }

    /// Copies a `w` x `h` RGBA8 tile scaled by [`SCALE`] with its top-left at (x, y).
    fn tile(&mut self, tile: &[u8], (w, h): (usize, usize), (x, y): (usize, usize)) {
        for ty in 0..h * SCALE {
            let dst = ((y + ty) * self.width + x) * 4;
            for tx in 0..w * SCALE {
                let src = ((ty / SCALE) * w + tx / SCALE) * 4;
                if let (Some(d), Some(s)) = (self.rgba.get_mut(dst + tx * 4..dst + tx * 4 + 4), tile.get(src..src + 4))
                {
                    d.copy_from_slice(s);
                }
            }
        }
    }

    /// Draws `text` in light grey with its top-left at (x, y), clipped to the canvas.
    fn label(&mut self, text: &str, (x, y): (usize, usize)) {
        let galley = self.fonts.with_pixels_per_point(1.0).layout_no_wrap(
            text.to_owned(),
            FontId::proportional(TEXT),
            Color32::WHITE,
        );
        // The glyph atlas as laid out so far, borrowed (the view's `image()` copies it whole).
        let atlas = self.fonts.texture_atlas().image();
        let (width, height) = (self.width, self.height);
        for row in &galley.rows {
            for glyph in &row.row.glyphs {
                let uv = glyph.uv_rect;
                let left = x as f32 + row.pos.x + glyph.pos.x + uv.offset.x;
                let top = y as f32 + row.pos.y + glyph.pos.y + uv.offset.y;
                for v in uv.min[1]..uv.max[1] {
                    for u in uv.min[0]..uv.max[0] {
                        let coverage = atlas[(usize::from(u), usize::from(v))].a();
                        let px = left.round() as i64 + i64::from(u - uv.min[0]);
                        let py = top.round() as i64 + i64::from(v - uv.min[1]);
                        blend(&mut self.rgba, (width, height), px, py, coverage);
                    }
                }
            }
        }
    }
}

/// Blends light grey over the pixel (x, y) of an RGBA8 canvas of `size` by `coverage`; pixels
/// off the canvas are skipped.
fn blend(rgba: &mut [u8], (width, height): (usize, usize), x: i64, y: i64, coverage: u8) {
    let (Ok(x), Ok(y)) = (usize::try_from(x), usize::try_from(y)) else { return };
    if x >= width || y >= height {
        return;
    }
    let i = (y * width + x) * 4;
    let a = f32::from(coverage) / 255.0;
    for c in &mut rgba[i..i + 3] {
        *c = (f32::from(*c) * (1.0 - a) + 230.0 * a).round() as u8;
    }
}

/// Lays out and writes the sheet (atomically) for tiles of `size`, under the column titles
/// `columns` (the reference's first).
pub fn write(path: &Path, size: (u32, u32), columns: &[String], rows: &[SheetRow]) -> anyhow::Result<()> {
    let (w, h) = (size.0 as usize, size.1 as usize);
    let (tw, th) = (w * SCALE, h * SCALE);
    let mut canvas = Canvas::new(GUTTER + columns.len() * tw, HEADER + rows.len() * 2 * th);
    for (c, title) in columns.iter().enumerate() {
        canvas.label(title, (GUTTER + c * tw + 6, 4));
    }
    for (r, row) in rows.iter().enumerate() {
        let top = HEADER + 2 * r * th;
        canvas.label(&row.scene, (6, top + 6));
        canvas.label("error", (6, top + th + 6));
        canvas.label("red: too bright", (6, top + th + 26));
        canvas.label("blue: too dark", (6, top + th + 44));
        canvas.tile(&row.reference, (w, h), (GUTTER, top));
        for (c, (image, error)) in row.cells.iter().enumerate() {
            canvas.tile(image, (w, h), (GUTTER + (c + 1) * tw, top));
            if let Some(error) = error {
                canvas.tile(error, (w, h), (GUTTER + (c + 1) * tw, top + th));
            }
        }
    }
    let tmp = path.with_extension("tmp.png");
    image_io::write_png(&tmp, canvas.width as u32, canvas.height as u32, canvas.rgba)?;
    std::fs::rename(&tmp, path)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Labels leave light pixels in the header band and the gutter, and tiles land scaled at
    /// their cells: a uniform tile fills its whole scaled cell.
    #[test]
    fn the_sheet_names_its_columns_and_rows_and_scales_its_tiles() {
        let dir = std::env::temp_dir().join(format!("bouncelab-sheet-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join("sheet.png");
        let (w, h) = (16usize, 40usize);
        let solid = |v: u8| std::iter::repeat_n([v, v, v, 255], w * h).flatten().collect::<Vec<u8>>();
        let rows =
            vec![SheetRow { scene: "rooms".into(), reference: solid(100), cells: vec![(solid(200), Some(solid(50)))] }];
        write(&path, (w as u32, h as u32), &["reference".into(), "ism".into()], &rows).expect("write");
        let img = image::open(&path).expect("png").to_rgba8();
        let (sw, sh) = (GUTTER + 2 * w * SCALE, HEADER + 2 * h * SCALE);
        assert_eq!((img.width() as usize, img.height() as usize), (sw, sh));
        let light = |x0: usize, x1: usize, y0: usize, y1: usize| {
            (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| img.get_pixel(x as u32, y as u32)[0] > 150)
                .count()
        };
        assert!(light(GUTTER, sw, 0, HEADER) > 20, "column titles drawn");
        assert!(light(0, GUTTER, HEADER, sh) > 20, "row names drawn");
        let cell = |x: usize, y: usize| img.get_pixel(x as u32, y as u32)[0];
        assert_eq!(cell(GUTTER, HEADER), 100);
        assert_eq!(cell(GUTTER + w * SCALE - 1, HEADER + h * SCALE - 1), 100);
        assert_eq!(cell(GUTTER + w * SCALE, HEADER), 200);
        assert_eq!(cell(GUTTER + w * SCALE, HEADER + h * SCALE), 50);
    }
}
