//! How an error reaches the user at the edge of the program: the whole cause chain on one line,
//! without repeating a cause that its parent's message already quotes. Our `thiserror` enums
//! put their source into their own message (`"{path}: {source}"`) so that the editor's status
//! line is complete, and anyhow's `{:#}` would print that source a second time.

/// `outer: inner: innermost`, each cause once.
pub fn error_report(error: &anyhow::Error) -> String {
    let mut report = String::new();
    let mut parent = String::new();
    for cause in error.chain() {
        let message = cause.to_string();
        if !parent.is_empty() && parent.contains(&message) {
            continue;
        }
        if !report.is_empty() {
            report.push_str(": ");
        }
        report.push_str(&message);
        parent = message;
    }
    report
}

#[cfg(test)]
mod tests {
    use super::error_report;

    #[derive(Debug, thiserror::Error)]
    #[error("scene.ron: {source}")]
    struct Quoting {
        source: std::io::Error,
    }

    fn not_found() -> std::io::Error {
        std::io::Error::new(std::io::ErrorKind::NotFound, "no such file")
    }

    #[test]
    fn a_quoted_source_is_not_repeated() {
        let e = anyhow::Error::new(Quoting { source: not_found() });
        assert_eq!(error_report(&e), "scene.ron: no such file");
    }

    #[test]
    fn context_and_unquoted_sources_are_kept() {
        let e = anyhow::Error::new(not_found()).context("opening scene.ron");
        assert_eq!(error_report(&e), "opening scene.ron: no such file");
        let e = anyhow::Error::new(Quoting { source: not_found() }).context("opening project");
        assert_eq!(error_report(&e), "opening project: scene.ron: no such file");
    }
}
