//! `ontogeny view` end to end without a browser: the server's answers, bad input refused with
//! exit code 2, flags that do not apply warned about. The pages drawn in headless Chromium are
//! in [`browser`], ignored unless asked for; a run with habitats in [`habitats`].

pub(crate) mod browser;
mod defines;
mod growing;
mod habitats;
mod server;

use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Stdio};

use crate::util::{
    assert_bad_input, evolve_config, ontogeny_command, refused, scratch_dir, succeeded,
};

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("view-{name}"))
}

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

/// A running `ontogeny view PATH --port 0`, stopped when dropped.
struct Viewer {
    child: Child,
    url: String,
}

impl Viewer {
    fn start(path: &Path) -> Viewer {
        Viewer::start_with(path, &[])
    }

    /// A viewer of `path` with more flags.
    fn start_with(path: &Path, flags: &[&str]) -> Viewer {
        let mut child = ontogeny_command()
            .arg("view")
            .arg(path)
            .args(["--port", "0"])
            .args(flags)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let mut line = String::new();
        BufReader::new(child.stdout.as_mut().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .split_whitespace()
            .find(|w| w.starts_with("http://127.0.0.1:"))
            .unwrap_or_else(|| panic!("no address in {line:?}"))
            .to_string();
        Viewer { child, url }
    }

    /// `GET path` over plain HTTP: (status, body).
    fn get(&self, path: &str) -> (u16, String) {
        let host = self.url.trim_start_matches("http://").trim_end_matches('/');
        let mut stream = std::net::TcpStream::connect(host).unwrap();
        write!(
            stream,
            "GET {path} HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n\r\n"
        )
        .unwrap();
        let mut response = String::new();
        stream.read_to_string(&mut response).unwrap();
        let status = response
            .split_whitespace()
            .nth(1)
            .and_then(|s| s.parse().ok())
            .unwrap();
        let body = response
            .split_once("\r\n\r\n")
            .map(|(_, b)| b.to_string())
            .unwrap_or_default();
        (status, body)
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[test]
fn a_path_that_is_no_page_is_refused_with_exit_code_2() {
    let dir = scratch("bad-path");
    let text = dir.join("notes.txt");
    std::fs::write(&text, "hello").unwrap();
    for (path, expected) in [
        (dir.join("missing.lsys"), "no such file or directory"),
        (text, "not an .lsys file"),
        (dir.clone(), "not a directory view can show"),
    ] {
        assert_bad_input(&["view", path.to_str().unwrap()], expected);
    }
    // A recording whose frames do not fit its creature.
    let rec = dir.join("rec");
    std::fs::create_dir_all(&rec).unwrap();
    std::fs::write(
        rec.join("recording.json"),
        r#"{"creature": 3, "frames": []}"#,
    )
    .unwrap();
    assert_bad_input(&["view", rec.to_str().unwrap()], "not a recording");
}

#[test]
fn a_port_in_use_is_refused_with_exit_code_2() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let out = ontogeny_command()
        .arg("view")
        .arg(example("algae.lsys"))
        .args(["--port", &port])
        .output()
        .unwrap();
    refused(&out, &format!("port {port} is already in use"));
}

#[test]
fn the_server_grows_the_file_afresh_when_it_changes() {
    let dir = scratch("watch");
    let file = dir.join("w.lsys");
    std::fs::write(&file, "axiom: forward(1)\n").unwrap();
    let viewer = Viewer::start(&file);
    let (status, page) = viewer.get("/");
    assert_eq!(status, 200);
    assert!(page.contains("/app.js"));
    let (status, script) = viewer.get("/three/three.module.min.js");
    assert_eq!(status, 200);
    assert!(script.contains("WebGLRenderer"));
    assert_eq!(viewer.get("/nothing").0, 404);

    let data = |v: &Viewer| -> serde_json::Value {
        let (status, body) = v.get("/data.json");
        assert_eq!(status, 200, "{body}");
        serde_json::from_str(&body).unwrap()
    };
    let before = data(&viewer);
    assert_eq!(before["kind"], "lsys");
    assert_eq!(before["frames"].as_array().unwrap().len(), 1);
    assert_eq!(before["frames"][0]["string"], "forward(1)");
    assert_eq!(
        before["frames"][0]["creature"]["parts"]
            .as_array()
            .unwrap()
            .len(),
        1
    );
    let version = viewer.get("/version").1;

    // Two parts in two steps; the fingerprint the page polls changes with the file.
    std::fs::write(
        &file,
        "axiom: A\nderivation length: 2\nA --> forward(1) B\nB --> forward(0.5)\n",
    )
    .unwrap();
    assert_ne!(viewer.get("/version").1, version);
    let after = data(&viewer);
    let frames = after["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 3);
    let parts: Vec<usize> = frames
        .iter()
        .map(|f| f["creature"]["parts"].as_array().unwrap().len())
        .collect();
    assert_eq!(parts, [0, 1, 2]);
    assert_eq!(frames[2]["string"], "forward(1) forward(0.5)");

    // A syntax error reaches the page with its line and column.
    std::fs::write(&file, "axiom: A\nA --> forward(1\n").unwrap();
    let broken = data(&viewer);
    let location = &broken["error"]["location"];
    assert_eq!(location["line"], 2, "{broken}");
    assert!(location["column"].as_u64().unwrap() >= 1, "{broken}");
}

/// The warnings `ontogeny view PATH FLAGS` writes on standard error before it serves.
fn view_warnings(path: &Path, flags: &[&str]) -> String {
    let mut child = ontogeny_command()
        .arg("view")
        .arg(path)
        .args(["--port", "0"])
        .args(flags)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The address is printed after the warnings.
    let mut line = String::new();
    BufReader::new(child.stdout.as_mut().unwrap())
        .read_line(&mut line)
        .unwrap();
    assert!(line.contains("http://127.0.0.1:"), "{line}");
    let _ = child.kill();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    let _ = child.wait();
    err
}

#[test]
fn flags_that_do_not_apply_are_warned_about() {
    let dir = scratch("ignored-flags");
    // A recording of two frames of a two-part creature.
    let creature = ontogeny::develop::creature_from_commands("forward(1) forward(1)").unwrap();
    let pose = serde_json::json!([[0.5, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);
    let frame = |t: f64| serde_json::json!({"t": t, "parts": [pose, pose]});
    std::fs::write(
        dir.join("recording.json"),
        serde_json::json!({"creature": creature, "frames": [frame(0.0), frame(0.1)]}).to_string(),
    )
    .unwrap();
    let err = view_warnings(
        &dir,
        &[
            "--steps",
            "3",
            "--grammar-seed",
            "1",
            "--size",
            "300x200",
            "--frame",
            "2",
        ],
    );
    for expected in [
        "warning: --steps, --grammar-seed grow a creature from a grammar",
        "warning: --size sets the size of a --snapshot picture: ignored",
        "warning: --frame 2: there are 2 frames (0 to 1, or -2 to -1): showing the last",
    ] {
        assert!(err.contains(expected), "{expected:?} not in {err}");
    }
    // Frames that exist, and no stray flags: no warning.
    assert_eq!(view_warnings(&dir, &["--frame", "-2"]), "");
    // An .lsys file is grown with the growth flags: two steps, three frames.
    let err = view_warnings(&example("algae.lsys"), &["--steps", "2", "--frame", "-99"]);
    assert!(!err.contains("--steps"), "{err}");
    assert!(
        err.contains(
            "warning: --frame -99: there are 3 frames (0 to 2, or -3 to -1): showing the first"
        ),
        "{err}"
    );
}
