//! What a test does when a tool it needs is not installed.

/// A missing tool: under CI (`CI` set), which installs every tool, the test fails; elsewhere it
/// says what is skipped and why.
pub fn missing(what: &str, skipped: &str) {
    if std::env::var_os("CI").is_some() {
        panic!("{what} is missing; CI must install it");
    }
    eprintln!("skipping {skipped}: {what} is missing (this fails instead when CI is set)");
}
