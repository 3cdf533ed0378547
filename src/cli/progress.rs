//! Progress of long headless renders on stderr, so a 10,000-frame run never looks hung: one
//! line rewritten in place on a terminal (at most every 0.25 s), a plain line every 5 s
//! otherwise (logs, CI), and always the last frame.

use std::io::{IsTerminal as _, Write as _};
use std::time::Instant;

/// Reports `done / total` frames with the rate and the time left.
pub struct Progress {
    total: u64,
    started: Instant,
    shown: Option<Instant>,
    tty: bool,
}

impl Progress {
    /// A report for `total` frames (nothing is shown for a single frame).
    pub fn new(total: u64) -> Self {
        Self { total, started: Instant::now(), shown: None, tty: std::io::stderr().is_terminal() }
    }

    /// The line for `done` frames after `seconds`.
    pub fn line(done: u64, total: u64, seconds: f64) -> String {
        let rate = done as f64 / seconds.max(1e-9);
        let left = total.saturating_sub(done) as f64 / rate.max(1e-9);
        format!("frame {done}/{total} ({rate:.1} frames/s, {left:.0} s left)")
    }

    /// Called after each frame.
    pub fn tick(&mut self, done: u64) {
        if self.total < 2 {
            return;
        }
        let every = if self.tty { 0.25 } else { 5.0 };
        let due = self.shown.is_none_or(|t| t.elapsed().as_secs_f64() >= every);
        if !(due || done == self.total) {
            return;
        }
        self.shown = Some(Instant::now());
        let line = Self::line(done, self.total, self.started.elapsed().as_secs_f64());
        let mut err = std::io::stderr().lock();
        let end = if done == self.total { "\n" } else { "" };
        let _ = if self.tty { write!(err, "\r{line}{end}") } else { writeln!(err, "{line}") };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_counts_frames_and_time_left() {
        assert_eq!(Progress::line(250, 1000, 10.0), "frame 250/1000 (25.0 frames/s, 30 s left)");
        assert_eq!(Progress::line(1000, 1000, 40.0), "frame 1000/1000 (25.0 frames/s, 0 s left)");
    }
}
