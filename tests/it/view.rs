//! `ontogeny view` end to end: the server's answers, bad input refused with exit code 2, and
//! every kind of page loaded in headless Chromium, which must draw the expected number of parts
//! (the page exposes it as `data-parts` on its body and in its title), scrub to the frame the URL
//! asks for (`?frame=N`), show a grammar's error with its line and column, and save a screenshot
//! with `--snapshot`; and a page left open (driven through Chromium's DevTools protocol) must
//! redraw when its `.lsys` file is saved (watch mode).
//!
//! The browser tests are skipped, with a message, when no Chromium is installed; in CI
//! (`CI=true`) a missing browser is a failure, as `.ci/run` installs one.

mod server;

use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use ontogeny::develop::{BuildOptions, grow};
use ontogeny::lsystem::{DeriveOptions, LSystem};

use crate::util::{assert_bad_input, ontogeny_command, refused, scratch_dir, tiny_run};

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("view-{name}"))
}

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

/// The number of parts of each frame of an example grown by the library.
fn parts_per_frame(name: &str) -> Vec<usize> {
    let lsys = LSystem::from_path(&example(name)).unwrap();
    grow(
        &lsys,
        &DeriveOptions::default(),
        None,
        &BuildOptions::default(),
    )
    .unwrap()
    .iter()
    .map(|f| f.creature.parts.len())
    .collect()
}

/// A running `ontogeny view PATH --port 0`, stopped when dropped.
struct Viewer {
    child: Child,
    url: String,
}

impl Viewer {
    fn start(path: &Path) -> Viewer {
        let mut child = ontogeny_command()
            .arg("view")
            .arg(path)
            .args(["--port", "0"])
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

/// The browser, or `None` (with a message) when there is none; in CI, none is a failure.
fn browser() -> Option<PathBuf> {
    let found = std::env::var_os("ONTOGENY_BROWSER")
        .filter(|p| !p.is_empty())
        .map(PathBuf::from)
        .or_else(|| {
            let dirs = std::env::var_os("PATH")?;
            [
                "chromium",
                "chromium-browser",
                "google-chrome",
                "google-chrome-stable",
            ]
            .iter()
            .flat_map(|n| std::env::split_paths(&dirs).map(move |d| d.join(n)))
            .find(|p| p.is_file())
        });
    if found.is_none() {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "no Chromium in CI: .ci/run should have installed it (apt-get install chromium)"
        );
        eprintln!(
            "SKIPPED: no Chromium found (install it with apt-get install chromium, or set \
             ONTOGENY_BROWSER): the browser tests of ontogeny view did not run"
        );
    }
    found
}

/// The page at `url` once loaded and drawn in headless Chromium: its body's `data-*`
/// attributes and its title.
struct Page {
    /// The body's opening tag, with its `data-` attributes.
    body: String,
    title: String,
    /// The whole document as Chromium left it.
    dom: String,
}

impl Page {
    fn load(browser: &Path, url: &str) -> Page {
        let profile = scratch(&format!("profile-{:x}", hash(url)));
        let output = Command::new(browser)
            .args([
                "--headless=new",
                "--no-sandbox",
                "--use-gl=angle",
                "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader",
                "--virtual-time-budget=8000",
                "--dump-dom",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg(url)
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let _ = std::fs::remove_dir_all(&profile);
        let dom = String::from_utf8_lossy(&output.stdout).to_string();
        let body = dom
            .find("<body")
            .map(|i| dom[i..].split('>').next().unwrap().to_string())
            .unwrap_or_else(|| panic!("no body in the page at {url}: {dom}"));
        let title = dom
            .split_once("<title>")
            .and_then(|(_, t)| t.split_once("</title>"))
            .map(|(t, _)| t.to_string())
            .unwrap_or_default();
        Page { body, title, dom }
    }

    /// A `data-NAME` attribute of the body.
    fn data(&self, name: &str) -> Option<String> {
        let key = format!("data-{name}=\"");
        let start = self.body.find(&key)? + key.len();
        let end = self.body[start..].find('"')? + start;
        Some(
            self.body[start..end]
                .replace("&quot;", "\"")
                .replace("&amp;", "&")
                .replace("&lt;", "<")
                .replace("&gt;", ">"),
        )
    }

    fn number(&self, name: &str) -> usize {
        self.data(name)
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("no number data-{name} in {}", self.body))
    }

    /// Drawn, with WebGL.
    fn assert_ready(&self) {
        assert_eq!(self.data("ready").as_deref(), Some("yes"), "{}", self.body);
        assert_eq!(self.data("webgl").as_deref(), Some("yes"), "{}", self.body);
    }
}

fn hash(s: &str) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    s.hash(&mut h);
    std::thread::current().id().hash(&mut h);
    h.finish()
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

#[test]
fn growth_pages_draw_every_frame_in_chromium() {
    let Some(browser) = browser() else { return };
    let expected = parts_per_frame("quadruped.lsys");
    assert_eq!(expected.last(), Some(&11), "the quadruped has 11 parts");
    let viewer = Viewer::start(&example("quadruped.lsys"));
    // The page opens on the last frame; scrubbing to each other frame draws its parts.
    let last = Page::load(&browser, &viewer.url);
    last.assert_ready();
    assert_eq!(last.data("kind").as_deref(), Some("lsys"));
    assert_eq!(last.number("frames"), expected.len());
    assert_eq!(last.number("frame"), expected.len() - 1);
    assert_eq!(last.number("parts"), 11);
    assert_eq!(last.title, "ontogeny view: 11 parts");
    for frame in [0, 1] {
        let page = Page::load(&browser, &format!("{}?frame={frame}&still=1", viewer.url));
        page.assert_ready();
        assert_eq!(page.number("frame"), frame);
        assert_eq!(page.number("parts"), expected[frame], "frame {frame}");
    }
    drop(viewer);

    // The same from a grow --out directory.
    let dir = scratch("grown");
    let out = ontogeny_command()
        .arg("grow")
        .arg(example("quadruped.lsys"))
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success());
    let viewer = Viewer::start(&dir);
    let page = Page::load(&browser, &format!("{}?frame=1&still=1", viewer.url));
    page.assert_ready();
    assert_eq!(page.data("kind").as_deref(), Some("growth"));
    assert_eq!(page.number("parts"), expected[1]);
    assert_eq!(page.number("frames"), expected.len());
}

#[test]
fn a_grammar_error_is_shown_in_the_page_with_its_line_and_column() {
    let Some(browser) = browser() else { return };
    let dir = scratch("error");
    let file = dir.join("broken.lsys");
    std::fs::write(&file, "axiom: A\nA --> forward(1\n").unwrap();
    let diagnostic = LSystem::from_path(&file).err().unwrap();
    let location = diagnostic.location.as_ref().unwrap();
    let viewer = Viewer::start(&file);
    let page = Page::load(&browser, &viewer.url);
    assert_eq!(page.data("ready").as_deref(), Some("yes"), "{}", page.body);
    assert_eq!(page.number("parts"), 0);
    let error = page.data("error").unwrap();
    assert!(
        error.starts_with(&format!(
            "line {}, column {}: {}",
            location.line, location.column, diagnostic.message
        )),
        "{error}"
    );
}

#[test]
fn recording_and_run_pages_draw_their_creatures_in_chromium() {
    let Some(browser) = browser() else { return };
    let dir = scratch("recorded");
    let rec = dir.join("rec");
    let out = ontogeny_command()
        .arg("eval")
        .arg(example("thrower.lsys"))
        .args(["--task", "catapult", "--seconds", "1", "--record"])
        .arg(&rec)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let recording: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(rec.join("recording.json")).unwrap())
            .unwrap();
    let parts = recording["creature"]["parts"].as_array().unwrap().len();
    let frames = recording["frames"].as_array().unwrap().len();
    assert_eq!(
        parts,
        parts_per_frame("thrower.lsys").last().copied().unwrap()
    );
    let viewer = Viewer::start(&rec);
    let page = Page::load(&browser, &format!("{}?frame=20", viewer.url));
    page.assert_ready();
    assert_eq!(page.data("kind").as_deref(), Some("recording"));
    assert_eq!(page.number("parts"), parts);
    assert_eq!(page.number("frames"), frames);
    assert_eq!(page.number("frame"), 20);
    // The page says how the evaluation went: its status and fitness, as recorded.
    assert!(recording["fitness"].is_f64());
    let status = recording["status"].as_str().unwrap();
    assert!(
        page.dom.contains(&format!("status: {status}")),
        "{}",
        page.dom
    );
    assert!(page.dom.contains("fitness: "), "{}", page.dom);
    drop(viewer);
    assert_snapshot(&browser, &rec, &dir.join("recording.png"));

    let run = dir.join("run");
    tiny_run("lsystem", &run, &["--seed", "5"]);
    let store = ontogeny::evolve::store::RunStore::open(&run.join("run.sqlite")).unwrap();
    let generation0 = store.individuals(0).unwrap();
    let viewer = Viewer::start(&run);
    // By default the best of the last generation is opened; ?gen=&index= opens any other.
    let page = Page::load(&browser, &viewer.url);
    page.assert_ready();
    assert_eq!(page.data("kind").as_deref(), Some("run"));
    assert_eq!(page.number("generations"), 2);
    assert_eq!(page.number("generation"), 1);
    for individual in generation0.iter().filter(|i| i.parts > 0).take(2) {
        let page = Page::load(
            &browser,
            &format!("{}?gen=0&index={}", viewer.url, individual.index),
        );
        page.assert_ready();
        assert_eq!(page.number("individual"), individual.index as usize);
        assert_eq!(page.number("parts"), individual.parts as usize);
    }
    // Failed individuals show a dash, not the failure floor (−999999 as −1.00e+6).
    let page = Page::load(&browser, &format!("{}?gen=0", viewer.url));
    page.assert_ready();
    let failed = generation0.iter().filter(|i| i.status != "ok").count();
    assert!(
        failed > 0,
        "the test wants a failed individual in generation 0"
    );
    assert!(!page.dom.contains("e+6"), "{}", page.dom);
    assert!(
        page.dom.matches("<td>\u{2014}</td>").count() >= failed,
        "{failed} failed: {}",
        page.dom
    );
    // A generation the run does not have: said, and the page is ready.
    let page = Page::load(&browser, &format!("{}?gen=7", viewer.url));
    assert_eq!(page.data("ready").as_deref(), Some("yes"), "{}", page.body);
    assert_eq!(
        page.data("error").as_deref(),
        Some("no generation 7 (the run has 0–1)")
    );
    drop(viewer);
    assert_snapshot(&browser, &run, &dir.join("run.png"));

    // An evaluation refused before simulating: the page shows the creature as built and why.
    let crossing = dir.join("crossing.lsys");
    std::fs::write(
        &crossing,
        "axiom: forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)\n",
    )
    .unwrap();
    let refused = dir.join("refused");
    let out = ontogeny_command()
        .arg("eval")
        .arg(&crossing)
        .args(["--task", "walker", "--record"])
        .arg(&refused)
        .output()
        .unwrap();
    assert!(out.status.success());
    let viewer = Viewer::start(&refused);
    let page = Page::load(&browser, &viewer.url);
    page.assert_ready();
    assert_eq!(page.data("kind").as_deref(), Some("recording"));
    assert_eq!(page.number("frames"), 0);
    assert_eq!(page.number("parts"), 4);
    assert_eq!(
        page.data("error").as_deref(),
        Some("no frames recorded: self-intersecting: parts 0 and 3 interpenetrate")
    );
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
            "--steps", "3", "--seed", "1", "--size", "300x200", "--frame", "2",
        ],
    );
    for expected in [
        "warning: --steps, --seed grow a creature from a grammar",
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

/// `ontogeny view PATH --snapshot OUT --size 480x300` writes a 480 × 300 picture.
fn assert_snapshot(browser: &Path, path: &Path, png: &Path) {
    let out = ontogeny_command()
        .arg("view")
        .arg(path)
        .arg("--snapshot")
        .arg(png)
        .args(["--size", "480x300", "--browser"])
        .arg(browser)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let picture = tiny_skia::Pixmap::load_png(png).unwrap();
    assert_eq!((picture.width(), picture.height()), (480, 300));
}

#[test]
fn snapshot_writes_a_picture_of_the_page() {
    let Some(browser) = browser() else { return };
    let dir = scratch("snapshot");
    let png = dir.join("quadruped.png");
    let out = ontogeny_command()
        .arg("view")
        .arg(example("quadruped.lsys"))
        .arg("--snapshot")
        .arg(&png)
        .args(["--size", "640x400", "--browser"])
        .arg(&browser)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let picture = tiny_skia::Pixmap::load_png(&png).unwrap();
    assert_eq!((picture.width(), picture.height()), (640, 400));
    // The creature is drawn: many pixels of the parts' blue in the 3D view (the left 340 × 260
    // pixels under the header; the brain's panel is at most 300 pixels wide), none in an
    // empty view.
    let blue = picture
        .pixels()
        .iter()
        .enumerate()
        .filter(|(i, _)| (i % 640) < 340 && (40..300).contains(&(i / 640)))
        .filter(|(_, p)| {
            let (r, g, b) = (p.red() as i32, p.green() as i32, p.blue() as i32);
            b > 120 && b - r > 60 && b - g > 20
        })
        .count();
    assert!(blue > 2000, "only {blue} blue pixels in {}", png.display());

    // A grammar with an error: the picture shows it, and the exit code is 2.
    let broken = dir.join("broken.lsys");
    std::fs::write(&broken, "axiom: A\nA --> forward(1\n").unwrap();
    let png = dir.join("broken.png");
    let out = ontogeny_command()
        .arg("view")
        .arg(&broken)
        .arg("--snapshot")
        .arg(&png)
        .args(["--size", "640x400", "--browser"])
        .arg(&browser)
        .output()
        .unwrap();
    refused(&out, "broken.lsys:2:");
    assert!(png.is_file());
}

/// A page open in headless Chromium, driven through the DevTools protocol (a WebSocket), so a
/// test can watch it change over real time.
struct LivePage {
    browser: Child,
    socket: std::net::TcpStream,
    profile: PathBuf,
    next_id: u64,
}

impl LivePage {
    fn open(browser: &Path, url: &str) -> LivePage {
        let profile = scratch(&format!("live-{:x}", hash(url)));
        let mut child = Command::new(browser)
            .args([
                "--headless=new",
                "--no-sandbox",
                "--use-gl=angle",
                "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader",
                "--remote-debugging-port=0",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg(url)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // "DevTools listening on ws://127.0.0.1:PORT/devtools/browser/ID"
        let mut stderr = BufReader::new(child.stderr.take().unwrap());
        let mut port = None;
        let mut line = String::new();
        while port.is_none() && stderr.read_line(&mut line).unwrap() > 0 {
            port = line
                .split("ws://127.0.0.1:")
                .nth(1)
                .and_then(|rest| rest.split('/').next())
                .map(str::to_string);
            line.clear();
        }
        let port = port.expect("Chromium printed no DevTools address");
        // Keep reading its standard error so that it never blocks on a full pipe.
        std::thread::spawn(move || std::io::copy(&mut stderr, &mut std::io::sink()));
        let list = http_get(&format!("127.0.0.1:{port}"), "/json/list");
        let targets: serde_json::Value = serde_json::from_str(&list).unwrap();
        let page = targets
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["type"] == "page")
            .expect("a page target");
        let ws = page["webSocketDebuggerUrl"].as_str().unwrap();
        let path = &ws[ws.find("/devtools").unwrap()..];
        let mut socket = std::net::TcpStream::connect(format!("127.0.0.1:{port}")).unwrap();
        write!(
            socket,
            "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n\
             Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\
             Sec-WebSocket-Version: 13\r\n\r\n"
        )
        .unwrap();
        // The handshake's answer ends with an empty line.
        let mut head = Vec::new();
        let mut byte = [0u8; 1];
        while !head.ends_with(b"\r\n\r\n") {
            socket.read_exact(&mut byte).unwrap();
            head.push(byte[0]);
        }
        assert!(
            head.starts_with(b"HTTP/1.1 101"),
            "{}",
            String::from_utf8_lossy(&head)
        );
        LivePage {
            browser: child,
            socket,
            profile,
            next_id: 0,
        }
    }

    /// Evaluates `expression` in the page and returns its value (a string).
    fn eval(&mut self, expression: &str) -> String {
        self.next_id += 1;
        let id = self.next_id;
        let message = serde_json::json!({
            "id": id,
            "method": "Runtime.evaluate",
            "params": { "expression": expression, "returnByValue": true },
        })
        .to_string();
        // A client's frame: final text frame, masked (with a zero mask, which leaves it as is).
        let mut frame = vec![0x81u8];
        let n = message.len();
        if n < 126 {
            frame.push(0x80 | n as u8);
        } else {
            frame.push(0x80 | 126);
            frame.extend_from_slice(&(n as u16).to_be_bytes());
        }
        frame.extend_from_slice(&[0, 0, 0, 0]);
        frame.extend_from_slice(message.as_bytes());
        self.socket.write_all(&frame).unwrap();
        loop {
            let text = self.read_message();
            let reply: serde_json::Value = serde_json::from_str(&text).unwrap();
            if reply["id"] == id {
                let value = &reply["result"]["result"]["value"];
                return value.as_str().map(str::to_string).unwrap_or_default();
            }
        }
    }

    /// One message from the browser (unmasked frames; continuation frames joined).
    fn read_message(&mut self) -> String {
        let mut payload = Vec::new();
        loop {
            let mut head = [0u8; 2];
            self.socket.read_exact(&mut head).unwrap();
            let mut n = u64::from(head[1] & 0x7f);
            if n == 126 {
                let mut b = [0u8; 2];
                self.socket.read_exact(&mut b).unwrap();
                n = u64::from(u16::from_be_bytes(b));
            } else if n == 127 {
                let mut b = [0u8; 8];
                self.socket.read_exact(&mut b).unwrap();
                n = u64::from_be_bytes(b);
            }
            let mut part = vec![0u8; n as usize];
            self.socket.read_exact(&mut part).unwrap();
            payload.extend_from_slice(&part);
            if head[0] & 0x80 != 0 {
                return String::from_utf8(payload).unwrap();
            }
        }
    }

    /// Asks the page for `expression` until `accept` likes the answer, for at most 30 s of
    /// real time (a deadline, not a measurement); returns the last answer.
    fn wait_for(&mut self, expression: &str, accept: impl Fn(&str) -> bool) -> String {
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
        loop {
            let value = self.eval(expression);
            if accept(&value) || std::time::Instant::now() > deadline {
                return value;
            }
            std::thread::sleep(std::time::Duration::from_millis(200));
        }
    }
}

impl Drop for LivePage {
    fn drop(&mut self) {
        let _ = self.browser.kill();
        let _ = self.browser.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

/// `GET path` from `host` over plain HTTP: the body, `Content-Length` bytes of it (Chromium's
/// DevTools server keeps the connection open).
fn http_get(host: &str, path: &str) -> String {
    let mut stream = std::net::TcpStream::connect(host).unwrap();
    write!(stream, "GET {path} HTTP/1.1\r\nHost: {host}\r\n\r\n").unwrap();
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        stream.read_exact(&mut byte).unwrap();
        head.push(byte[0]);
    }
    let head = String::from_utf8_lossy(&head).to_lowercase();
    let length: usize = head
        .lines()
        .find_map(|l| l.strip_prefix("content-length:"))
        .and_then(|v| v.trim().parse().ok())
        .expect("a Content-Length");
    let mut body = vec![0u8; length];
    stream.read_exact(&mut body).unwrap();
    String::from_utf8(body).unwrap()
}

#[test]
fn saving_the_file_redraws_the_open_page() {
    let Some(browser) = browser() else { return };
    let dir = scratch("live");
    let file = dir.join("live.lsys");
    std::fs::write(&file, "axiom: forward(1)\n").unwrap();
    let viewer = Viewer::start(&file);
    let mut page = LivePage::open(&browser, &viewer.url);
    let state = "JSON.stringify([document.body.dataset.ready, document.body.dataset.frames, \
                 document.body.dataset.parts, document.body.dataset.error || ''])";
    let first = page.wait_for(state, |s| s.starts_with("[\"yes\""));
    assert_eq!(first, r#"["yes","1","1",""]"#);

    // Saved with two steps and two parts: the page shows them, on the last frame.
    std::fs::write(
        &file,
        "axiom: A\nderivation length: 2\nA --> forward(1) B\nB --> forward(0.5)\n",
    )
    .unwrap();
    let grown = page.wait_for(state, |s| s.contains(r#""3","2""#));
    assert_eq!(grown, r#"["yes","3","2",""]"#);

    // Saved with an error: the page says where, and keeps the last good creature drawn.
    std::fs::write(&file, "axiom: A\nA --> forward(1\n").unwrap();
    let broken = page.wait_for(state, |s| s.contains("line 2"));
    assert!(
        broken.starts_with(r#"["yes","3","2","line 2, column 16: "#),
        "{broken}"
    );

    // Fixed again: the error goes.
    std::fs::write(&file, "axiom: forward(1) forward(1) forward(1)\n").unwrap();
    let fixed = page.wait_for(state, |s| !s.contains("line 2"));
    assert_eq!(fixed, r#"["yes","1","3",""]"#);
    drop(viewer);
}
