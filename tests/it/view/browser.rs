//! The viewer in headless Chromium: every kind of page must draw the expected number of parts
//! (the page exposes it as `data-parts` on its body and in its title), scrub to the frame the
//! URL asks for (`?frame=N`), show a grammar's error with its line and column and its
//! findings beside the creature, play a run's individual's walk, and save a screenshot with
//! `--snapshot`; and a page left open (driven through Chromium's DevTools protocol) must
//! redraw when its `.lsys` file is saved (watch mode).
//!
//! Every test here needs Chromium, so each is ignored, with that reason, in a plain `cargo test
//! --release`; `.ci/run` runs them by name (`cargo test --release --test it -- --ignored
//! browser::`), and a test asked for on a machine without a browser fails, never skips.

use super::*;

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, Command};

use ontogeny::develop::{BuildOptions, grow};
use ontogeny::lsystem::{DeriveOptions, LSystem};

use super::server::{get_json, tiny_comparison, tiny_run as tiny_walker_run};
use crate::util::tiny_run;

/// The browser the tests drive: `$ONTOGENY_BROWSER`, else the first Chromium on the `PATH`.
/// A browser test runs only when asked for by name, so a missing browser fails it.
pub(crate) fn chromium() -> PathBuf {
    let named = std::env::var_os("ONTOGENY_BROWSER")
        .filter(|p| !p.is_empty())
        .map(PathBuf::from);
    if let Some(path) = &named {
        assert!(
            path.is_file(),
            "ONTOGENY_BROWSER names {}, which is no file",
            path.display()
        );
    }
    named
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
        })
        .unwrap_or_else(|| {
            panic!(
                "no Chromium found: this browser test was asked for and needs one (install \
                 it with apt-get install chromium, or set ONTOGENY_BROWSER to its path)"
            )
        })
}

/// How every test starts Chromium: headless, drawing WebGL in software (SwiftShader).
const HEADLESS: [&str; 5] = [
    "--headless=new",
    "--no-sandbox",
    "--use-gl=angle",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
];

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
            .args(HEADLESS)
            .args(["--virtual-time-budget=8000", "--dump-dom"])
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
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn growth_pages_draw_every_frame_in_chromium() {
    let browser = chromium();
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
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_textbook_plant_of_thousands_of_parts_draws_in_chromium() {
    let browser = chromium();
    let viewer = Viewer::start_with(&example("abop-1.24a.lsys"), &["--max-parts", "5000"]);
    let page = Page::load(&browser, &format!("{}?still=1", viewer.url));
    page.assert_ready();
    assert_eq!(page.number("parts"), 3125);
    assert_eq!(page.title, "ontogeny view: 3125 parts");
}

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_grammar_error_is_shown_in_the_page_with_its_line_and_column() {
    let browser = chromium();
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
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn recording_and_run_pages_draw_their_creatures_in_chromium() {
    let browser = chromium();
    let dir = scratch("recorded");
    let rec = dir.join("rec");
    let out = ontogeny_command()
        .arg("eval")
        .arg(example("thrower.lsys"))
        .args(["--task", "catapult", "--seconds", "1", "--record"])
        .arg(&rec)
        .output()
        .unwrap();
    succeeded(&out);
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
    let store = ontogeny::run::store::RunStore::open(&run.join("run.sqlite")).unwrap();
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
    succeeded(&out);
    let picture = tiny_skia::Pixmap::load_png(png).unwrap();
    assert_eq!((picture.width(), picture.height()), (480, 300));
}

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn snapshot_writes_a_picture_of_the_page() {
    let browser = chromium();
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
    succeeded(&out);
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
            .args(HEADLESS)
            .arg("--remote-debugging-port=0")
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
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn saving_the_file_redraws_the_open_page() {
    let browser = chromium();
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

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_grammars_findings_are_shown_beside_the_creature_and_follow_its_edits() {
    let browser = chromium();
    let dir = scratch("findings-page");
    let file = dir.join("typo.lsys");
    let typo = "derivation length: 3\naxiom: forward(1) A\nA --> ] A Tial\nTail --> forward(1)\n";
    std::fs::write(&file, typo).unwrap();
    let viewer = Viewer::start(&file);

    // Drawn once: the typo with its place and caret, and the builder's problem with its count.
    let page = Page::load(&browser, &viewer.url);
    page.assert_ready();
    assert_eq!(page.number("findings"), 2, "{}", page.body);
    let shown = format!(
        "warning: 'Tial' is read as the modules T i a l (did you mean `Tail`?)\n \
         --&gt; {}:3:11\n  |\n3 | A --&gt; ] A Tial\n  |           ^^^^\n\
         warning: ']' with nothing to pop: ignored []] (at 3 frames, from t = 1)</pre>",
        file.display()
    );
    assert!(page.dom.contains(&shown), "{}", page.dom);
    // The last frame's three pops are one line of the creature's description.
    assert!(
        page.dom
            .contains("warning: ']' with nothing to pop: ignored []] (3 times)</div>"),
        "{}",
        page.dom
    );

    // Left open: every save brings the findings of the file as it is now.
    let mut page = LivePage::open(&browser, &viewer.url);
    let state = "JSON.stringify([document.body.dataset.ready, \
                 document.body.dataset.findings || '', document.getElementById('findings').textContent])";
    let first = page.wait_for(state, |s| s.starts_with(r#"["yes","2""#));
    assert!(
        first.starts_with(r#"["yes","2","warning: 'Tial'"#),
        "{first}"
    );
    std::fs::write(
        &file,
        "derivation length: 3\naxiom: forward(1) A\nA --> A Tail\nTail --> forward(1)\n",
    )
    .unwrap();
    let fixed = page.wait_for(state, |s| s.contains(r#""yes","","#));
    assert_eq!(fixed, r#"["yes","",""]"#);
    std::fs::write(&file, typo.replace("] ", "")).unwrap();
    let again = page.wait_for(state, |s| s.contains(r#""yes","1","#));
    assert!(
        again.starts_with(r#"["yes","1","warning: 'Tial' is read as the modules T i a l"#),
        "{again}"
    );
    drop(viewer);
}

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_run_page_plays_an_individuals_walk_in_chromium() {
    let browser = chromium();
    let run = tiny_walker_run("walk-page");
    let viewer = Viewer::start(&run);
    let walk = get_json(&viewer, "/walk.json?gen=0&rank=2");
    let page = Page::load(&browser, &format!("{}?gen=0&walk=2&still=1", viewer.url));
    page.assert_ready();
    assert_eq!(page.data("kind").as_deref(), Some("run"));
    assert_eq!(page.data("walk").as_deref(), Some("0/2"));
    assert_eq!(
        page.number("parts"),
        walk["creature"]["parts"].as_array().unwrap().len()
    );
    assert_eq!(
        page.number("frames"),
        walk["frames"].as_array().unwrap().len()
    );
    assert_eq!(page.number("frame"), 0);
    // The fitness plot names what the fitness measures and draws the fine reference line.
    let data = get_json(&viewer, "/data.json");
    assert_eq!(page.data("plot-y").as_deref(), data["fitness"].as_str());
    assert!(page.data("plot-y").unwrap().starts_with("fitness: "));
    assert_eq!(page.data("plot-fine").as_deref(), Some("yes"));
    // A play button on every individual's row, and the walk's outcome beside it.
    assert_eq!(
        page.dom.matches("class=\"walk\"").count(),
        4,
        "{}",
        page.dom
    );
    assert!(page.dom.contains("(rank 2)"), "{}", page.dom);
    assert!(page.dom.contains("task: walker"), "{}", page.dom);
    assert!(
        page.dom
            .contains(&format!("status: {}", walk["status"].as_str().unwrap())),
        "{}",
        page.dom
    );
    // A rank the generation lacks: said, and the page is ready.
    let page = Page::load(&browser, &format!("{}?gen=0&walk=9&still=1", viewer.url));
    assert_eq!(page.data("ready").as_deref(), Some("yes"), "{}", page.body);
    assert_eq!(
        page.data("error").as_deref(),
        Some("generation 0 has no rank 9 (it has ranks 1 to 4)")
    );
}

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_walks_play_button_plays_it_and_opening_another_individual_leaves_it() {
    let browser = chromium();
    let run = tiny_walker_run("walk-button");
    let viewer = Viewer::start(&run);
    let walk = get_json(&viewer, "/walk.json?gen=0&rank=2");
    let frames = walk["frames"].as_array().unwrap().len();
    let mut page = LivePage::open(&browser, &viewer.url);
    let state = "JSON.stringify([document.body.dataset.ready, document.body.dataset.walk || '', \
                 document.body.dataset.frames || '', document.body.dataset.error || '', \
                 document.getElementById('play').style.display])";
    let opened = page.wait_for(state, |s| s.starts_with("[\"yes\""));
    assert_eq!(opened, r#"["yes","","","","none"]"#);
    // The second row's button: rank 2.
    page.eval("document.querySelectorAll('#individuals button.walk')[1].click(); ''");
    let playing = page.wait_for(state, |s| s.contains("0/2"));
    assert_eq!(playing, format!(r#"["yes","0/2","{frames}","",""]"#));
    // A click on the first row (not its button) opens that individual, without a player.
    let best = get_json(&viewer, "/generation.json?gen=0")["individuals"][0]["index"].clone();
    page.eval("document.querySelectorAll('#individuals tr.clickable')[0].click(); ''");
    let opened = format!(r#"["","none","{best}"]"#);
    let left = page.wait_for(
        "JSON.stringify([document.body.dataset.walk || '', \
         document.getElementById('play').style.display, document.body.dataset.individual])",
        |s| s == opened,
    );
    assert_eq!(left, opened);
}

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_defines_slider_regrows_the_creature_and_the_address_carries_its_value() {
    let browser = chromium();
    let viewer = Viewer::start(&super::defines::row_file("browser-sliders"));
    // Opened at an address that sets PARTS: four parts, LENGTH following it.
    let mut page = LivePage::open(&browser, &format!("{}?define.PARTS=4", viewer.url));
    let state = "JSON.stringify([document.body.dataset.ready, document.body.dataset.parts, \
                 document.body.dataset.defines, location.search, \
                 document.querySelector('input[data-define=PARTS]').value, \
                 document.getElementById('slider').style.display])";
    let opened = page.wait_for(state, |s| s.starts_with("[\"yes\""));
    assert_eq!(
        opened,
        r#"["yes","4","{\"PARTS\":4,\"LENGTH\":1}","?define.PARTS=4","4",""]"#
    );
    // Dragged to 3: three parts, LENGTH 0.75, the address says so, the frame slider stays.
    page.eval(
        "const s = document.querySelector('input[data-define=PARTS]'); s.value = '3'; \
         s.dispatchEvent(new Event('input')); ''",
    );
    let dragged = page.wait_for(state, |s| s.contains(r#""3","{"#));
    assert_eq!(
        dragged,
        r#"["yes","3","{\"PARTS\":3,\"LENGTH\":0.75}","?define.PARTS=3","3",""]"#
    );
    // Back to the file's own values (two parts): the address sets nothing.
    page.eval("document.getElementById('defines-reset').click(); ''");
    let reset = page.wait_for(state, |s| s.contains(r#""2","{"#));
    assert_eq!(
        reset,
        r#"["yes","2","{\"PARTS\":2,\"LENGTH\":0.5}","","2",""]"#
    );
}

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_walker_recording_shows_the_distance_walked_so_far_in_chromium() {
    let browser = chromium();
    let dir = scratch("walked");
    let rec = dir.join("rec");
    let out = ontogeny_command()
        .arg("eval")
        .arg(example("quadruped.lsys"))
        .args([
            "--task",
            "walker",
            "--fitness",
            "distance",
            "--seconds",
            "1",
        ])
        .arg("--record")
        .arg(&rec)
        .output()
        .unwrap();
    succeeded(&out);
    let recording: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(rec.join("recording.json")).unwrap())
            .unwrap();
    let frames = recording["frames"].as_array().unwrap();
    let first_measuring = frames
        .iter()
        .position(|f| f["phase"] == "measuring")
        .unwrap();
    let viewer = Viewer::start(&rec);
    // At the last frame the page shows D_w, the fitness (distance) the evaluation measured.
    let last = frames.len() - 1;
    let page = Page::load(&browser, &format!("{}?frame={last}", viewer.url));
    page.assert_ready();
    let walked: f64 = page.data("walked").unwrap().parse().unwrap();
    let fitness = recording["fitness"].as_f64().unwrap();
    assert!(fitness > 0.05, "{fitness}");
    assert!((walked - fitness).abs() < 1e-4, "{walked} {fitness}");
    assert!(
        page.dom.contains(&format!("walked {fitness:.2} m")),
        "{}",
        page.dom
    );
    // Before the walk is measured, nothing is said.
    let page = Page::load(
        &browser,
        &format!("{}?frame={}", viewer.url, first_measuring - 2),
    );
    page.assert_ready();
    assert_eq!(page.data("walked").as_deref(), Some(""));
    assert!(!page.dom.contains("walked "), "{}", page.dom);
}

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_comparison_page_shows_its_report_plots_and_replicates_in_chromium() {
    let browser = chromium();
    let cmp = tiny_comparison("comparison-page");
    let viewer = Viewer::start(&cmp);
    let page = Page::load(&browser, &viewer.url);
    assert_eq!(page.data("ready").as_deref(), Some("yes"), "{}", page.body);
    assert_eq!(page.data("kind").as_deref(), Some("comparison"));
    assert_eq!(page.number("runs"), 2);
    assert_eq!(page.number("plots"), 2);
    assert!(
        page.dom.contains("<img src=\"/plot/fitness.svg\""),
        "{}",
        page.dom
    );
    assert!(
        page.dom.contains("<img src=\"/plot/parts.svg\""),
        "{}",
        page.dom
    );
    // The report's first line, and a row per replicate.
    let report = std::fs::read_to_string(cmp.join("report.md")).unwrap();
    let first = report.lines().next().unwrap().replace('&', "&amp;");
    assert!(page.dom.contains(&first), "{first}: {}", page.dom);
    assert!(
        page.dom.contains("<td>direct</td><td>1</td>"),
        "{}",
        page.dom
    );
    assert!(
        page.dom.contains("<td>lsystem</td><td>1</td>"),
        "{}",
        page.dom
    );
    drop(viewer);
    let png = cmp.parent().unwrap().join("comparison.png");
    assert_snapshot(&browser, &cmp, &png);
}

#[test]
#[ignore = "needs Chromium; run with: cargo test --release --test it -- --ignored browser::"]
fn a_recording_of_a_growing_walk_shows_its_parts_as_they_appear_in_chromium() {
    let browser = chromium();
    let rec = crate::growing_shown::growing_recording("browser");
    let recording: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(rec.join("recording.json")).unwrap())
            .unwrap();
    let frames = recording["frames"].as_array().unwrap();
    let viewer = Viewer::start(&rec);
    // The page draws the parts each frame poses: three at the start, fifteen at the end.
    for (frame, parts) in [(0, 3), (frames.len() - 1, 15)] {
        let page = Page::load(&browser, &format!("{}?frame={frame}", viewer.url));
        page.assert_ready();
        assert_eq!(page.number("parts"), parts, "frame {frame}: {}", page.body);
        assert_eq!(frames[frame]["parts"].as_array().unwrap().len(), parts);
    }
}
