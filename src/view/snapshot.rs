//! `view --snapshot`: the page rendered to a PNG by headless Chromium, and the browser found
//! to do it.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Why a snapshot could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum SnapshotError {
    /// No browser was named and none is on the PATH.
    #[error(
        "--snapshot needs Chromium: install it (e.g. apt-get install chromium), or name a browser with --browser or $ONTOGENY_BROWSER"
    )]
    NoBrowser,
    /// A file or directory could not be made or read, or the browser could not be run.
    #[error("{what}")]
    Io {
        /// What could not be done (`cannot create DIR`).
        what: String,
        /// Why.
        source: std::io::Error,
    },
    /// The picture's file was refused or could not be written (see [`crate::output`]).
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// The browser ran but wrote no picture: what it said.
    #[error("{0}")]
    NoPicture(String),
}

/// The size of a snapshot when none is given.
pub const DEFAULT_SIZE: (u32, u32) = (1280, 800);

/// Parses a snapshot's size, `WIDTHxHEIGHT`, each 64 to 8192 pixels.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{text}' is not WIDTHxHEIGHT (e.g. 1280x800)");
    let (w, h) = text.split_once('x').ok_or_else(bad)?;
    let (w, h): (u32, u32) = (w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?);
    if !(64..=8192).contains(&w) || !(64..=8192).contains(&h) {
        return Err(format!(
            "{text}: width and height must be 64 to 8192 pixels"
        ));
    }
    Ok((w, h))
}

/// The browser to run: `given` (`--browser`), `$ONTOGENY_BROWSER`, or a Chromium on the PATH.
pub fn find_browser(given: Option<&Path>) -> Option<PathBuf> {
    if let Some(path) = given {
        return Some(path.to_path_buf());
    }
    if let Some(path) = std::env::var_os("ONTOGENY_BROWSER").filter(|p| !p.is_empty()) {
        return Some(PathBuf::from(path));
    }
    let dirs = std::env::var_os("PATH")?;
    [
        "chromium",
        "chromium-browser",
        "google-chrome",
        "google-chrome-stable",
    ]
    .iter()
    .flat_map(|name| std::env::split_paths(&dirs).map(move |d| d.join(name)))
    .find(|p| p.is_file())
}

fn io(what: String) -> impl FnOnce(std::io::Error) -> SnapshotError {
    move |source| SnapshotError::Io { what, source }
}

/// Renders `url` with headless Chromium (`browser`, else [`find_browser`]'s) at `size` into
/// `out`. Chromium runs with a fresh private profile and writes its screenshot there; the
/// picture is then put in place whole ([`crate::output`]), and a target that is not a regular
/// file is refused before Chromium starts.
pub fn snapshot(
    browser: Option<&Path>,
    size: (u32, u32),
    url: &str,
    out: &Path,
) -> Result<(), SnapshotError> {
    let browser = find_browser(browser).ok_or(SnapshotError::NoBrowser)?;
    let out = std::path::absolute(out).map_err(io(format!("bad path {}", out.display())))?;
    if let Some(parent) = out.parent() {
        std::fs::create_dir_all(parent)
            .map_err(io(format!("cannot create {}", parent.display())))?;
    }
    crate::output::check_target(&out)?;
    // Removed, with everything Chromium put in it, when dropped.
    let scratch = tempfile::Builder::new()
        .prefix("ontogeny-view-")
        .tempdir()
        .map_err(io(
            "cannot make a temporary directory for the browser".to_string()
        ))?;
    let profile = scratch.path().join("profile");
    let screenshot = scratch.path().join("snapshot.png");
    let (w, h) = size;
    let output = Command::new(&browser)
        .args(chromium_flags())
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={w},{h}"))
        .arg(format!("--screenshot={}", screenshot.display()))
        .arg(url)
        .stdin(std::process::Stdio::null())
        .output()
        .map_err(io(format!("cannot run {}", browser.display())))?;
    if !screenshot.is_file() {
        return Err(SnapshotError::NoPicture(format!(
            "{} did not write {} (exit status {}):\n{}",
            browser.display(),
            out.display(),
            output.status,
            String::from_utf8_lossy(&output.stderr)
        )));
    }
    crate::output::copy_into_place(&screenshot, &out)?;
    Ok(())
}

/// The flags a snapshot gives Chromium: headless, WebGL through SwiftShader (a CPU renderer,
/// so no GPU is needed), and virtual time so the page finishes loading and drawing before
/// the picture is taken.
pub fn chromium_flags() -> Vec<String> {
    [
        "--headless=new",
        "--no-sandbox",
        "--use-gl=angle",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--hide-scrollbars",
        "--no-first-run",
        "--no-default-browser-check",
        "--disable-extensions",
        "--virtual-time-budget=8000",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}
