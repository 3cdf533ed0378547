//! The buffer inspector: any buffer the renderer exposes (G-buffer channels, depth, motion,
//! object ids, shadow maps, HDR), with channel isolation, exposure, auto range, false colour,
//! zoom and a pixel probe showing raw values; and the comparison with the reference path tracer
//! (swipe view, signed error heat map, FLIP map, metrics).

use crate::image_io::HdrImage;
use crate::metrics;
use crate::project_file::Project;
use crate::render::Renderer;
use crate::render::gi::BufferView;
use crate::render::gi::reference::job::ReferenceJob;

/// Which channels are shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    Rgb,
    R,
    G,
    B,
    A,
}

/// Inspector UI state.
/// Where the viewport's renderer stands this UI frame (reads happen only while it is idle, so
/// the inspector never waits for a frame in flight).
#[derive(Clone, Copy, Debug)]
pub struct ViewFrame {
    /// Finished viewport frames so far (the live refresh cadence).
    pub index: u64,
    /// No frame in flight: reads return at once.
    pub idle: bool,
    /// The last finished frame was rendered at full resolution.
    pub full: bool,
    /// The viewport's full size (the reference comparison's size).
    pub full_size: (u32, u32),
}

pub struct Inspector {
    /// A read was asked for (Refresh, a new buffer) while the renderer was busy.
    pending: bool,
    /// The live cadence's last frame read.
    read_frame: u64,
    /// Reads so far, and what the texture shows (reads, channel, EV bits, auto range, false
    /// colour): the image is re-visualised only when one of them changes, not every UI frame.
    reads: u64,
    visualised: Option<(u64, Channel, u32, bool, bool)>,
    buffer: String,
    channel: Channel,
    exposure_ev: f32,
    auto_range: bool,
    false_colour: bool,
    zoom: f32,
    fit: bool,
    image: Option<HdrImage>,
    texture: Option<egui::TextureHandle>,
    live: bool,
    compare: bool,
    swipe: f32,
    job: Option<ReferenceJob>,
    metrics_text: String,
    heat: Option<egui::TextureHandle>,
    flip_map: Option<egui::TextureHandle>,
    reference_tex: Option<egui::TextureHandle>,
    compared_spp: u32,
    compared_at: Option<std::time::Instant>,
    current_tex: Option<egui::TextureHandle>,
    /// The slice viewer's level and slice range (buffers shown as [`BufferView::Slices`]).
    slices: (u32, u32, u32),
}

impl Default for Inspector {
    fn default() -> Self {
        Self {
            pending: true,
            read_frame: 0,
            reads: 0,
            visualised: None,
            buffer: "albedo".into(),
            channel: Channel::Rgb,
            exposure_ev: 0.0,
            auto_range: true,
            false_colour: false,
            zoom: 1.0,
            fit: true,
            image: None,
            texture: None,
            live: true,
            compare: false,
            swipe: 0.5,
            job: None,
            metrics_text: String::new(),
            heat: None,
            flip_map: None,
            reference_tex: None,
            compared_spp: 0,
            compared_at: None,
            current_tex: None,
            slices: (2, 0, 127),
        }
    }
}

/// Maps a value in [0, 1] to a perceptually ordered colour (a compact "turbo"-like ramp).
pub fn false_colour(t: f32) -> [u8; 3] {
    let t = t.clamp(0.0, 1.0);
    let stops =
        [[48.0, 18.0, 59.0], [40.0, 150.0, 240.0], [60.0, 220.0, 120.0], [250.0, 200.0, 40.0], [180.0, 20.0, 10.0]];
    let x = t * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f32;
    let (a, b) = (stops[i], stops[i + 1]);
    [0, 1, 2].map(|c| (a[c] + (b[c] - a[c]) * f) as u8)
}

fn decode_oct(e: [f32; 2]) -> [f32; 3] {
    let mut n = [e[0], e[1], 1.0 - e[0].abs() - e[1].abs()];
    let t = (-n[2]).clamp(0.0, 1.0);
    n[0] += if n[0] >= 0.0 { -t } else { t };
    n[1] += if n[1] >= 0.0 { -t } else { t };
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-9);
    n.map(|v| v / l)
}

/// Converts a buffer to display colours with the inspector's options.
pub fn visualize(
    img: &HdrImage,
    name: &str,
    channel: Channel,
    exposure_ev: f32,
    auto_range: bool,
    false_col: bool,
) -> egui::ColorImage {
    let values: Vec<[f32; 4]> = img
        .pixels
        .iter()
        .map(|p| match name {
            // Shading normal, decoded from its octahedral packing to [0, 1] colours.
            "normal" => {
                let n = decode_oct([p[0], p[1]]);
                [n[0] * 0.5 + 0.5, n[1] * 0.5 + 0.5, n[2] * 0.5 + 0.5, 1.0]
            }
            _ => *p,
        })
        .collect();
    let pick = |p: &[f32; 4]| -> [f32; 3] {
        match channel {
            Channel::Rgb => [p[0], p[1], p[2]],
            Channel::R => [p[0]; 3],
            Channel::G => [p[1]; 3],
            Channel::B => [p[2]; 3],
            Channel::A => [p[3]; 3],
        }
    };
    let (mut lo, mut hi) = (0.0f32, 1.0f32);
    if auto_range {
        let all = values.iter().flat_map(&pick).filter(|v| v.is_finite());
        let (mn, mx) = all.fold((f32::MAX, f32::MIN), |(a, b), v| (a.min(v), b.max(v)));
        if mn < mx {
            (lo, hi) = (mn, mx);
        }
    }
    let k = exposure_ev.exp2();
    let pixels = values
        .iter()
        .map(|p| {
            let c = pick(p).map(|v| ((v - lo) / (hi - lo) * k).clamp(0.0, 1.0));
            if false_col || name == "object_id" && channel == Channel::Rgb {
                let t = if name == "object_id" {
                    ((p[0] as u32).wrapping_mul(2_654_435_761) >> 24) as f32 / 255.0
                } else {
                    c[0]
                };
                let [r, g, b] = if name == "object_id" && p[0] == 0.0 { [0, 0, 0] } else { false_colour(t) };
                egui::Color32::from_rgb(r, g, b)
            } else {
                let e = |v: f32| {
                    (if v <= 0.003_130_8 { 12.92 * v } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 } * 255.0) as u8
                };
                egui::Color32::from_rgb(e(c[0]), e(c[1]), e(c[2]))
            }
        })
        .collect();
    egui::ColorImage {
        size: [img.width as usize, img.height as usize],
        pixels,
        source_size: egui::vec2(img.width as f32, img.height as f32),
    }
}

fn rgba8_to_color_image(w: u32, h: u32, rgba: &[u8]) -> egui::ColorImage {
    egui::ColorImage::from_rgba_unmultiplied([w as usize, h as usize], rgba)
}

impl Inspector {
    /// Shows buffer `name` (what choosing it in the combo box does).
    pub fn select(&mut self, name: &str) {
        self.buffer = name.to_owned();
        self.image = None;
    }

    /// The buffer shown and its last read-back image, if any.
    pub fn shown(&self) -> (&str, Option<&HdrImage>) {
        (&self.buffer, self.image.as_ref())
    }

    /// Draws the inspector; `renderer` is the viewport's (absent when the GPU is unavailable).
    pub fn ui(&mut self, ui: &mut egui::Ui, renderer: Option<&Renderer>, project: &Project, frame: ViewFrame) {
        let Some(renderer) = renderer else {
            ui.label("No renderer: the GPU is unavailable.");
            return;
        };
        // The frame's buffers, then the active technique's own.
        let buffers = Renderer::buffers_for(project.render.mode);
        let sliced = buffers.iter().any(|b| b.name == self.buffer && b.view == BufferView::Slices);
        ui.horizontal_wrapped(|ui| {
            egui::ComboBox::from_label("buffer").height(800.0).selected_text(&self.buffer).show_ui(ui, |ui| {
                for b in &buffers {
                    let r = ui
                        .selectable_value(&mut self.buffer, b.name.to_owned(), b.name)
                        .on_hover_text(format!("{} ({})", b.description, b.format));
                    self.pending |= r.changed();
                }
            });
            for (c, label) in
                [(Channel::Rgb, "RGB"), (Channel::R, "R"), (Channel::G, "G"), (Channel::B, "B"), (Channel::A, "A")]
            {
                ui.selectable_value(&mut self.channel, c, label);
            }
            if sliced {
                self.pending |= self.slices_ui(ui);
            }
        });
        ui.horizontal_wrapped(|ui| {
            ui.add(egui::Slider::new(&mut self.exposure_ev, -10.0..=10.0).text("EV"));
            ui.checkbox(&mut self.auto_range, "auto range").on_hover_text("Map the buffer's min..max to black..white.");
            ui.checkbox(&mut self.false_colour, "false colour");
            ui.checkbox(&mut self.fit, "fit");
            ui.add_enabled(!self.fit, egui::Slider::new(&mut self.zoom, 0.25..=8.0).logarithmic(true).text("zoom"));
            ui.checkbox(&mut self.live, "live")
                .on_hover_text("Read the buffer back every 10 frames (costs a GPU stall).");
            self.pending |= ui.button("Refresh").clicked() || self.image.is_none();
            if ui.button("Export...").on_hover_text("EXR: the raw values; PNG: what you see").clicked() {
                self.export();
            }
            let live = self.live && frame.index >= self.read_frame + 10;
            if frame.idle && frame.index > 0 && (self.pending || live) {
                self.pending = false;
                self.read_frame = frame.index;
                let name = if sliced {
                    let (l, a, b) = self.slices;
                    format!("{}@{l},{a},{b}", self.buffer)
                } else {
                    self.buffer.clone()
                };
                match renderer.read_buffer(&name) {
                    Ok(img) => {
                        self.image = Some(img);
                        self.reads += 1;
                    }
                    Err(e) => log::warn!("inspector: {e}"),
                }
            }
        });
        let key = (self.reads, self.channel, self.exposure_ev.to_bits(), self.auto_range, self.false_colour);
        if let Some(img) = &self.image
            && (self.visualised != Some(key) || self.texture.is_none())
        {
            self.visualised = Some(key);
            let ci = visualize(img, &self.buffer, self.channel, self.exposure_ev, self.auto_range, self.false_colour);
            match &mut self.texture {
                Some(t) => t.set(ci, egui::TextureOptions::NEAREST),
                None => self.texture = Some(ui.ctx().load_texture("inspector", ci, egui::TextureOptions::NEAREST)),
            }
        }
        ui.checkbox(&mut self.compare, "Compare with the reference path tracer");
        if self.compare {
            self.compare_ui(ui, renderer, project, frame);
            return;
        }
        if let (Some(tex), Some(img)) = (&self.texture, &self.image) {
            if self.fit {
                self.zoom = (0.97 * ui.available_width() / img.width.max(1) as f32).max(0.01);
            }
            egui::ScrollArea::both().show(ui, |ui| {
                let size = egui::vec2(img.width as f32, img.height as f32) * self.zoom;
                let resp = ui.add(egui::Image::new((tex.id(), size)).sense(egui::Sense::hover()));
                if let Some(pos) = resp.hover_pos() {
                    let rel = (pos - resp.rect.min) / self.zoom;
                    let (x, y) = (rel.x as u32, rel.y as u32);
                    if x < img.width && y < img.height {
                        let p = img.pixels[(y * img.width + x) as usize];
                        resp.on_hover_text(format!("({x}, {y}) = {:.5} {:.5} {:.5} {:.5}", p[0], p[1], p[2], p[3]));
                    }
                }
            });
        }
    }

    /// The slice viewer's pickers: voxel level, first and last slice (their OR is shown).
    /// Returns whether one changed.
    fn slices_ui(&mut self, ui: &mut egui::Ui) -> bool {
        let (l, a, b) = &mut self.slices;
        let mut changed = ui.add(egui::DragValue::new(l).range(0..=7).prefix("level ")).changed();
        changed |= ui.add(egui::DragValue::new(a).range(0..=127).prefix("slices ")).changed();
        changed |= ui.add(egui::DragValue::new(b).range(0..=127).prefix("..")).changed();
        *b = (*b).max(*a);
        changed
    }

    fn export(&self) {
        let Some(img) = &self.image else { return };
        let Some(path) = rfd::FileDialog::new()
            .add_filter("Image", &["exr", "png"])
            .set_file_name(format!("{}.exr", self.buffer))
            .save_file()
        else {
            return;
        };
        let result = match crate::image_io::output_kind(&path) {
            Ok(crate::image_io::OutputKind::Exr) => crate::image_io::write_exr(&path, img),
            Ok(crate::image_io::OutputKind::Png) => {
                let ci =
                    visualize(img, &self.buffer, self.channel, self.exposure_ev, self.auto_range, self.false_colour);
                let rgba = ci.pixels.iter().flat_map(|c| c.to_array()).collect();
                crate::image_io::write_png(&path, img.width, img.height, rgba)
            }
            Err(e) => Err(e),
        };
        match result {
            Ok(()) => log::info!("exported {} to {}", self.buffer, path.display()),
            Err(e) => log::error!("export failed: {e}"),
        }
    }

    fn compare_ui(&mut self, ui: &mut egui::Ui, renderer: &Renderer, project: &Project, frame: ViewFrame) {
        let size = frame.full_size;
        let (scene, settings) = (&project.scene, &project.render.reference);
        let job = self.job.get_or_insert_with(|| ReferenceJob::start(scene, settings, size));
        if !job.matches(scene, settings, size) {
            *job = ReferenceJob::start(scene, settings, size);
            self.compared_spp = 0;
        }
        let Some((reference, progress)) = job.latest() else {
            ui.label("Reference: starting...");
            ui.ctx().request_repaint();
            return;
        };
        // Metrics and FLIP cost a readback and a full-image pass: at most every two seconds.
        let due = self.compared_at.is_none_or(|t| t.elapsed().as_secs_f32() > 2.0);
        let ready = frame.idle && frame.full && renderer.targets().is_some_and(|t| t.size == size);
        if !ready && self.metrics_text.is_empty() {
            ui.label("Waiting for a full-resolution viewport frame to compare...");
        }
        if ready && progress.spp != self.compared_spp && due {
            self.compared_spp = progress.spp;
            self.compared_at = Some(std::time::Instant::now());
            let current = match renderer.read_buffer("hdr") {
                Ok(c) => c,
                Err(e) => {
                    self.metrics_text = format!("cannot read the current image: {e}");
                    return;
                }
            };
            self.current_tex = Some(renderer_display(ui, &current, project));
            match metrics::compare(&current, &reference, project.render.view.exposure_ev) {
                Ok(c) => {
                    self.metrics_text = format!(
                        "reference {} spp ({:.1} Mrays/s) · RMSE {:.4} · relMSE {:.4} · FLIP {:.4} · luminance ratio {:.3}",
                        progress.spp,
                        progress.rays_per_second * 1e-6,
                        c.rmse,
                        c.relmse,
                        c.flip,
                        c.luminance_ratio
                    );
                    if let Ok(heat) = metrics::signed_heatmap(&current, &reference, 0.5) {
                        let ci = rgba8_to_color_image(size.0, size.1, &heat);
                        self.heat = Some(ui.ctx().load_texture("heat", ci, egui::TextureOptions::NEAREST));
                    }
                    if let Ok((_, map)) = metrics::flip(&current, &reference, project.render.view.exposure_ev) {
                        let rgba: Vec<u8> = map
                            .iter()
                            .flat_map(|v| {
                                let [r, g, b] = false_colour(*v);
                                [r, g, b, 255]
                            })
                            .collect();
                        self.flip_map =
                            Some(ui.ctx().load_texture("flip", rgba_to(size, &rgba), egui::TextureOptions::NEAREST));
                    }
                    let rgba = crate::image_io::tonemap_srgb8(&reference, &project.render.view);
                    self.reference_tex =
                        Some(ui.ctx().load_texture("reference", rgba_to(size, &rgba), egui::TextureOptions::LINEAR));
                }
                Err(e) => self.metrics_text = format!("cannot compare: {e}"),
            }
        }
        ui.label(&self.metrics_text);
        ui.add(egui::Slider::new(&mut self.swipe, 0.0..=1.0).text("swipe (left: current, right: reference)"));
        let Some(current_tex) = self.current_tex.clone() else { return };
        let avail = ui.available_width().min(size.0 as f32);
        let scale = avail / size.0 as f32;
        let draw_size = egui::vec2(size.0 as f32, size.1 as f32) * scale;
        let (rect, _) = ui.allocate_exact_size(draw_size, egui::Sense::hover());
        let split = rect.min.x + rect.width() * self.swipe;
        let left = egui::Rect::from_min_max(rect.min, egui::pos2(split, rect.max.y));
        let right = egui::Rect::from_min_max(egui::pos2(split, rect.min.y), rect.max);
        let uv = |r: egui::Rect| {
            egui::Rect::from_min_max(
                egui::pos2((r.min.x - rect.min.x) / rect.width(), 0.0),
                egui::pos2((r.max.x - rect.min.x) / rect.width(), 1.0),
            )
        };
        ui.painter().image(current_tex.id(), left, uv(left), egui::Color32::WHITE);
        if let Some(t) = &self.reference_tex {
            ui.painter().image(t.id(), right, uv(right), egui::Color32::WHITE);
        }
        ui.painter().vline(split, rect.y_range(), egui::Stroke::new(1.0, egui::Color32::YELLOW));
        ui.horizontal(|ui| {
            if let Some(t) = &self.heat {
                ui.vertical(|ui| {
                    ui.label("signed error (red: too bright, blue: too dark)");
                    ui.image((t.id(), draw_size * 0.5));
                });
            }
            if let Some(t) = &self.flip_map {
                ui.vertical(|ui| {
                    ui.label("FLIP");
                    ui.image((t.id(), draw_size * 0.5));
                });
            }
        });
        ui.ctx().request_repaint();
    }
}

fn rgba_to(size: (u32, u32), rgba: &[u8]) -> egui::ColorImage {
    rgba8_to_color_image(size.0, size.1, rgba)
}

fn renderer_display(ui: &egui::Ui, current: &HdrImage, project: &Project) -> egui::TextureHandle {
    let rgba = crate::image_io::tonemap_srgb8(current, &project.render.view);
    ui.ctx().load_texture("current", rgba_to((current.width, current.height), &rgba), egui::TextureOptions::LINEAR)
}
