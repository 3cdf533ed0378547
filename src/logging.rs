//! Logging: everything goes to stderr (env_logger formatting, `RUST_LOG` filter) and the last
//! lines are kept for the editor's log panel.

use std::collections::VecDeque;
use std::sync::{Mutex, OnceLock};

/// Lines kept for the log panel.
const KEEP: usize = 500;

static LINES: OnceLock<Mutex<VecDeque<(log::Level, String)>>> = OnceLock::new();

fn lines() -> &'static Mutex<VecDeque<(log::Level, String)>> {
    LINES.get_or_init(|| Mutex::new(VecDeque::with_capacity(KEEP)))
}

struct Tee {
    inner: env_logger::Logger,
}

impl log::Log for Tee {
    fn enabled(&self, metadata: &log::Metadata<'_>) -> bool {
        self.inner.enabled(metadata)
    }

    fn log(&self, record: &log::Record<'_>) {
        if !self.inner.matches(record) {
            return;
        }
        self.inner.log(record);
        if let Ok(mut l) = lines().lock() {
            if l.len() == KEEP {
                l.pop_front();
            }
            l.push_back((record.level(), format!("{}: {}", record.target(), record.args())));
        }
    }

    fn flush(&self) {
        self.inner.flush();
    }
}

/// Installs the logger (once; later calls do nothing).
pub fn init() {
    let inner = env_logger::Builder::from_env(
        env_logger::Env::default().default_filter_or("info,wgpu_core=warn,wgpu_hal=warn,naga=warn,egui_wgpu=warn"),
    )
    .build();
    let max = inner.filter();
    if log::set_boxed_logger(Box::new(Tee { inner })).is_ok() {
        log::set_max_level(max);
    }
}

/// A copy of the kept lines, oldest first.
pub fn recent() -> Vec<(log::Level, String)> {
    lines().lock().map(|l| l.iter().cloned().collect()).unwrap_or_default()
}
