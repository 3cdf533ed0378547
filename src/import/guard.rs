//! Runs third-party parsing code so that a panic inside it becomes an error message, silently:
//! the default panic hook would otherwise print "thread 'main' panicked" and a backtrace to the
//! user's terminal for what is, to them, just a broken file. Only panics on the calling thread
//! while the guard is active are silenced; every other panic still reaches the previous hook.

use std::cell::Cell;
use std::panic::UnwindSafe;
use std::sync::Once;

thread_local! {
    static GUARDED: Cell<bool> = const { Cell::new(false) };
    /// Where the last silenced panic happened (named in the message, for bug reports).
    static LOCATION: Cell<Option<String>> = const { Cell::new(None) };
}

static INSTALL: Once = Once::new();

/// Calls `f`; a panic inside it is returned as its message instead of unwinding further.
pub(super) fn catch_quietly<T>(f: impl FnOnce() -> T + UnwindSafe) -> Result<T, String> {
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if GUARDED.with(Cell::get) {
                LOCATION.with(|l| l.set(info.location().map(|l| format!("{}:{}", l.file(), l.line()))));
            } else {
                previous(info);
            }
        }));
    });
    let was = GUARDED.with(|g| g.replace(true));
    let result = std::panic::catch_unwind(f);
    GUARDED.with(|g| g.set(was));
    result.map_err(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "panic".into());
        match LOCATION.with(Cell::take) {
            Some(location) => format!("{message} ({location})"),
            None => message,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::catch_quietly;

    #[test]
    fn a_panic_becomes_its_message_and_the_guard_resets() {
        let v: Vec<u32> = Vec::new();
        let index = v.len() + 7;
        let err = catch_quietly(|| v[index]).expect_err("must panic");
        assert!(err.contains("index out of bounds"), "{err}");
        assert_eq!(catch_quietly(|| 3), Ok(3));
        assert!(!super::GUARDED.with(std::cell::Cell::get));
    }
}
