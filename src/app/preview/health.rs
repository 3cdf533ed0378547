//! What went wrong on the viewport's device, collected from wgpu's callbacks (which run on
//! whichever thread polls the device) for the interface thread to show: uncaptured GPU errors
//! (validation, out of memory) and the loss of the device (driver reset, GPU removed, or
//! [`wgpu::Device::destroy`]). The editor reports each once and, after a loss, recreates the
//! viewport's device and renderer; the project in memory is never touched.

use std::sync::{Arc, Mutex};

/// At most this many distinct error messages are kept until the interface takes them.
const MAX_ERRORS: usize = 8;

/// What the interface is told.
#[derive(Clone, Debug, PartialEq)]
pub enum GpuProblem {
    /// An uncaptured error; the device goes on (the frame that raised it may be wrong).
    Error(String),
    /// The device is gone: nothing rendered on it will ever finish.
    Lost(String),
}

/// What a device holds, from wgpu's internal counters (the `counters` feature).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GpuMemory {
    /// Bytes of buffer memory.
    pub buffer_bytes: u64,
    /// Bytes of texture memory.
    pub texture_bytes: u64,
    /// Live buffers, textures and bind groups.
    pub objects: u64,
}

impl GpuMemory {
    /// `device`'s counters now.
    pub fn of(device: &wgpu::Device) -> Self {
        let c = device.get_internal_counters();
        let get = |v: isize| u64::try_from(v).unwrap_or(0);
        Self {
            buffer_bytes: get(c.hal.buffer_memory.read()),
            texture_bytes: get(c.hal.texture_memory.read()),
            objects: get(c.hal.buffers.read()) + get(c.hal.textures.read()) + get(c.hal.bind_groups.read()),
        }
    }
}

#[derive(Default)]
struct Health {
    lost: Option<String>,
    errors: Vec<String>,
    /// Every message reported so far, so a repeating error is reported once.
    seen: Vec<String>,
}

/// Shared between the device's callbacks and the view.
#[derive(Clone, Default)]
pub struct DeviceHealth(Arc<Mutex<Health>>);

impl DeviceHealth {
    /// Routes `device`'s uncaptured errors and its loss here (and to the log); `wake` asks the
    /// interface to look.
    pub fn watch(device: &wgpu::Device, wake: Arc<dyn Fn() + Send + Sync>) -> Self {
        let health = Self::default();
        let errors = health.clone();
        let woken = Arc::clone(&wake);
        device.on_uncaptured_error(Arc::new(move |e| {
            log::error!("wgpu (viewport): {e}");
            errors.push_error(e.to_string());
            woken();
        }));
        let lost = health.clone();
        device.set_device_lost_callback(move |reason, message| {
            log::error!("viewport device lost ({reason:?}): {message}");
            if let Ok(mut h) = lost.0.lock() {
                h.lost = Some(format!(
                    "{reason:?}{}",
                    if message.is_empty() { String::new() } else { format!(": {message}") }
                ));
            }
            wake();
        });
        health
    }

    fn push_error(&self, message: String) {
        let Ok(mut h) = self.0.lock() else { return };
        // The first line names the error; later lines repeat labels and spans.
        let first = message.lines().next().unwrap_or_default().to_owned();
        if h.seen.contains(&first) || h.errors.len() >= MAX_ERRORS {
            return;
        }
        h.seen.push(first);
        h.errors.push(message);
    }

    /// The problems since the last call: the loss first if the device is gone.
    pub fn take(&self) -> Vec<GpuProblem> {
        let Ok(mut h) = self.0.lock() else { return vec![GpuProblem::Lost("device state poisoned".into())] };
        let mut out: Vec<GpuProblem> = h.lost.take().map(GpuProblem::Lost).into_iter().collect();
        out.extend(h.errors.drain(..).map(GpuProblem::Error));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_repeating_error_is_reported_once_and_a_loss_comes_first() {
        let health = DeviceHealth::default();
        health.push_error("Validation Error\nIn a set_pipeline command".into());
        health.push_error("Validation Error\nIn another command".into());
        health.push_error("Out of memory".into());
        if let Ok(mut h) = health.0.lock() {
            h.lost = Some("Unknown: reset".into());
        }
        let problems = health.take();
        assert_eq!(problems.len(), 3, "{problems:?}");
        assert_eq!(problems[0], GpuProblem::Lost("Unknown: reset".into()));
        assert!(health.take().is_empty(), "taken problems are not reported again");
        health.push_error("Out of memory".into());
        assert!(health.take().is_empty(), "a message already reported stays quiet");
    }
}
