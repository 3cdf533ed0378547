//! The viewport's renderer on a device of its own, with one frame in flight and a
//! non-blocking copy of each finished image back to the CPU for egui.
//!
//! Submitting a frame costs the UI thread about 1 ms; the GPU work (5.5 s for `ism` at
//! 1000x760 on lavapipe) runs on this device's queue while eframe keeps presenting on its own
//! device. [`AsyncView::poll`] never blocks: it reports the frame once the GPU has finished
//! it and its display image is mapped.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use super::health::{DeviceHealth, GpuMemory, GpuProblem};
use crate::render::{RenderError, Renderer, device_descriptor};
use crate::scene::Scene;
use crate::settings::RenderSettings;

/// Why the preview device could not be created.
#[derive(Debug, thiserror::Error)]
pub enum PreviewError {
    /// The adapter refused a second device.
    #[error("cannot create the viewport's render device: {0}")]
    Device(#[from] wgpu::RequestDeviceError),
    /// Creating the renderer failed.
    #[error(transparent)]
    Render(#[from] RenderError),
}

/// A finished frame: its display image and how long it took.
pub struct Finished {
    /// The tonemapped image (sRGB-encoded RGBA8).
    pub image: egui::ColorImage,
    /// The ladder step it was rendered at.
    pub step: usize,
    /// Submit to mapped image (ms): what the user waits for a new image.
    pub ms: f64,
}

/// Where the staging buffer's mapping stands.
type MapState = Arc<Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>;

struct InFlight {
    started: Instant,
    step: usize,
    size: (u32, u32),
    padded_row: u32,
    buffer: wgpu::Buffer,
    mapped: MapState,
}

/// The viewport's renderer, its device and the frame in flight.
pub struct AsyncView {
    device: wgpu::Device,
    renderer: Renderer,
    in_flight: Option<InFlight>,
    /// A staging buffer to reuse (its size and padded row), returned by the last frame.
    spare: Option<(wgpu::Buffer, (u32, u32))>,
    adapter: wgpu::AdapterInfo,
    /// Tells the waiter thread that a frame was submitted; it blocks on the device until the
    /// frame is done, then calls `wake` (the editor asks egui to repaint). One long-lived
    /// thread for the view's life: it ends when this sender is dropped.
    waiter: Option<std::sync::mpsc::Sender<()>>,
    /// Errors and loss reported by the device.
    health: DeviceHealth,
    /// eframe's adapter and the repaint request: what [`AsyncView::restart`] starts over from.
    source: (wgpu::Adapter, Arc<dyn Fn() + Send + Sync>),
    /// The buffer the inspector shows (applied again after a restart).
    inspected: Option<String>,
}

impl AsyncView {
    /// Creates a second device on eframe's adapter and a renderer on it; `wake` is called
    /// (from another thread) whenever a frame has finished.
    pub fn new(adapter: &wgpu::Adapter, wake: Arc<dyn Fn() + Send + Sync>) -> Result<Self, PreviewError> {
        let (device, queue) = pollster::block_on(adapter.request_device(&device_descriptor(adapter)))?;
        let health = DeviceHealth::watch(&device, Arc::clone(&wake));
        let source = (adapter.clone(), Arc::clone(&wake));
        let renderer = Renderer::new(&device, &queue)?;
        let (tx, rx) = std::sync::mpsc::channel::<()>();
        let waiting = device.clone();
        let waiter = std::thread::Builder::new().name("viewport frame waiter".into()).spawn(move || {
            while rx.recv().is_ok() {
                let _ = waiting.poll(wgpu::PollType::wait_indefinitely());
                wake();
            }
        });
        let waiter = match waiter {
            Ok(_) => Some(tx),
            Err(e) => {
                log::warn!("no waiter thread ({e}): the viewport updates on the next input");
                None
            }
        };
        let info = adapter.get_info();
        Ok(Self {
            device,
            renderer,
            in_flight: None,
            spare: None,
            adapter: info,
            waiter,
            health,
            source,
            inspected: None,
        })
    }

    /// GPU errors and the device's loss since the last call. After a loss the view is dead:
    /// [`AsyncView::restart`] it.
    pub fn problems(&mut self) -> Vec<GpuProblem> {
        // wgpu runs the loss callback from a poll; an idle view polls nowhere else.
        let _ = self.device.poll(wgpu::PollType::Poll);
        self.health.take()
    }

    /// The device's memory and live objects.
    pub fn gpu_memory(&self) -> GpuMemory {
        GpuMemory::of(&self.device)
    }

    /// Tells the renderer which buffer the inspector shows (kept across a restart).
    pub fn set_inspected(&mut self, name: Option<&str>) {
        self.inspected = name.map(str::to_owned);
        self.renderer.set_inspected(name);
    }

    /// Starts over on a new device of the same adapter (after a loss); the inspected buffer
    /// carries over, the frame in flight and the temporal history do not.
    pub fn restart(&mut self) -> Result<(), PreviewError> {
        let mut fresh = Self::new(&self.source.0, Arc::clone(&self.source.1))?;
        fresh.set_inspected(self.inspected.as_deref());
        *self = fresh;
        Ok(())
    }

    /// Destroys the device as a driver reset would (the "simulate device loss" command and
    /// its test): everything on it fails from now on and the loss is reported.
    pub fn lose_device(&self) {
        self.device.destroy();
    }

    /// The adapter's description.
    pub fn adapter(&self) -> &wgpu::AdapterInfo {
        &self.adapter
    }

    /// The renderer. Its blocking reads wait for the frame in flight: call them when
    /// [`AsyncView::busy`] is false.
    pub fn renderer(&self) -> &Renderer {
        &self.renderer
    }

    /// The renderer, mutable (settings such as the inspected buffer).
    pub fn renderer_mut(&mut self) -> &mut Renderer {
        &mut self.renderer
    }

    /// Whether a frame is in flight.
    pub fn busy(&self) -> bool {
        self.in_flight.is_some()
    }

    /// The ladder step of the frame in flight and how long it has been running (ms).
    pub fn in_flight(&self) -> Option<(usize, f64)> {
        self.in_flight.as_ref().map(|f| (f.step, f.started.elapsed().as_secs_f64() * 1e3))
    }

    /// Renders a frame at `size` and starts copying its display image back. The previous frame
    /// must have been collected ([`AsyncView::poll`]); a busy view returns without rendering.
    pub fn submit(
        &mut self,
        scene: &Scene,
        settings: &RenderSettings,
        size: (u32, u32),
        step: usize,
    ) -> Result<(), RenderError> {
        if self.busy() {
            return Ok(());
        }
        let started = Instant::now();
        let padded_row = (size.0 * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = match self.spare.take() {
            Some((b, s)) if s == size => b,
            _ => self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("viewport image staging"),
                size: u64::from(padded_row) * u64::from(size.1),
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        };
        // The copy goes into the frame's own submission (see `Renderer::render_then`).
        self.renderer.render_then(scene, settings, size, &mut |encoder, targets| {
            encoder.copy_texture_to_buffer(
                targets.ldr.texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(padded_row),
                        rows_per_image: Some(size.1),
                    },
                },
                wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            );
        })?;
        let mapped: MapState = Arc::default();
        let slot = Arc::clone(&mapped);
        buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
            if let Ok(mut s) = slot.lock() {
                *s = Some(r);
            }
        });
        self.in_flight = Some(InFlight { started, step, size, padded_row, buffer, mapped });
        // The waiter thread wakes the interface when the GPU is done: no repaints just to poll
        // (each costs a software adapter ~100 ms of CPU that the frame itself needs).
        if let Some(w) = &self.waiter {
            let _ = w.send(());
        }
        Ok(())
    }

    /// The finished frame, if the one in flight is done; never blocks.
    pub fn poll(&mut self) -> Result<Option<Finished>, RenderError> {
        if self.in_flight.is_none() {
            return Ok(None);
        }
        let _ = self.device.poll(wgpu::PollType::Poll);
        self.collect()
    }

    /// Waits for the frame in flight and returns it (tests, and before a full-size export).
    pub fn wait(&mut self) -> Result<Option<Finished>, RenderError> {
        if self.in_flight.is_none() {
            return Ok(None);
        }
        self.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| RenderError::Gpu(e.to_string()))?;
        self.collect()
    }

    fn collect(&mut self) -> Result<Option<Finished>, RenderError> {
        let state = {
            let Some(f) = &self.in_flight else { return Ok(None) };
            let mut slot = f.mapped.lock().map_err(|_| RenderError::Gpu("viewport image lock poisoned".into()))?;
            match slot.take() {
                Some(s) => s,
                None => return Ok(None),
            }
        };
        let Some(f) = self.in_flight.take() else { return Ok(None) };
        if let Err(e) = state {
            return Err(RenderError::Gpu(format!("reading the viewport image back: {e}")));
        }
        let ms = f.started.elapsed().as_secs_f64() * 1e3;
        let (w, h) = (f.size.0 as usize, f.size.1 as usize);
        let mut pixels = Vec::with_capacity(w * h);
        {
            let data = f.buffer.slice(..).get_mapped_range().map_err(|e| RenderError::Gpu(e.to_string()))?;
            // Straight from the padded rows into egui's pixels; the display image is opaque
            // (its alpha channel holds nothing to show).
            for row in data.chunks(f.padded_row as usize).take(h) {
                pixels.extend(row[..w * 4].chunks_exact(4).map(|p| egui::Color32::from_rgb(p[0], p[1], p[2])));
            }
        }
        f.buffer.unmap();
        self.spare = Some((f.buffer, f.size));
        let image = egui::ColorImage::new([w, h], pixels);
        Ok(Some(Finished { image, step: f.step, ms }))
    }
}
