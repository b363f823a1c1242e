//! The viewer's server: it answers only its own host and only reads, idle connections cost no
//! thread, out-of-range query numbers are refused, `--snapshot` refuses a target that is not a
//! regular file, and a version-1 run is shown without being migrated.

use super::*;

/// Sends `request` (a request head, blank line included) to the viewer and returns the whole
/// response.
fn raw_request(viewer: &Viewer, request: &str) -> String {
    let host = viewer
        .url
        .trim_start_matches("http://")
        .trim_end_matches('/');
    let mut stream = std::net::TcpStream::connect(host).unwrap();
    stream.write_all(request.as_bytes()).unwrap();
    let mut response = Vec::new();
    stream.read_to_end(&mut response).unwrap();
    String::from_utf8_lossy(&response).into_owned()
}

#[test]
fn the_viewer_answers_only_its_own_host_and_only_reads() {
    let viewer = Viewer::start(&example("algae.lsys"));
    let port = viewer.url.rsplit(':').next().unwrap().trim_end_matches('/');
    // A page elsewhere whose domain name now points at 127.0.0.1 (DNS rebinding), or a
    // request naming no host: refused.
    for host in [
        "Host: evil.example\r\n",
        "Host: evil.example:{port}\r\n",
        "",
    ] {
        let host = host.replace("{port}", port);
        let response = raw_request(&viewer, &format!("GET /data.json HTTP/1.1\r\n{host}\r\n"));
        assert!(response.starts_with("HTTP/1.1 403 "), "{host}: {response}");
        assert!(!response.contains("\"kind\""), "{response}");
    }
    // Every name of this machine, on this port: answered, with the policy and nosniff.
    for host in ["localhost", "127.0.0.1", "[::1]"] {
        let response = raw_request(
            &viewer,
            &format!("GET / HTTP/1.1\r\nHost: {host}:{port}\r\n\r\n"),
        );
        assert!(response.starts_with("HTTP/1.1 200 "), "{host}: {response}");
        let head = response.split("\r\n\r\n").next().unwrap().to_lowercase();
        assert!(
            head.contains("\r\nx-content-type-options: nosniff"),
            "{head}"
        );
        assert!(
            head.contains("\r\ncontent-security-policy: default-src 'self';"),
            "{head}"
        );
    }
    // Only reading: anything but GET and HEAD is 405, saying what is allowed.
    for method in ["POST", "PUT", "DELETE"] {
        let response = raw_request(
            &viewer,
            &format!(
                "{method} /data.json HTTP/1.1\r\nHost: localhost:{port}\r\nContent-Length: 0\r\n\r\n"
            ),
        );
        assert!(
            response.starts_with("HTTP/1.1 405 "),
            "{method}: {response}"
        );
        assert!(response.contains("\r\nAllow: GET, HEAD\r\n"), "{response}");
    }
    let response = raw_request(
        &viewer,
        &format!("HEAD /data.json HTTP/1.1\r\nHost: localhost:{port}\r\n\r\n"),
    );
    assert!(response.starts_with("HTTP/1.1 200 "), "{response}");
    assert!(response.ends_with("\r\n\r\n"), "no body: {response}");
    assert!(
        response
            .to_lowercase()
            .contains("x-content-type-options: nosniff")
    );
}

#[cfg(target_os = "linux")]
#[test]
fn idle_connections_neither_make_threads_nor_keep_the_page_waiting() {
    let viewer = Viewer::start(&example("algae.lsys"));
    let host = viewer
        .url
        .trim_start_matches("http://")
        .trim_end_matches('/');
    let idle: Vec<std::net::TcpStream> = (0..300)
        .map(|_| std::net::TcpStream::connect(host).unwrap())
        .collect();
    let (status, _) = viewer.get("/version");
    assert_eq!(status, 200);
    let threads = std::fs::read_dir(format!("/proc/{}/task", viewer.child.id()))
        .unwrap()
        .count();
    assert!(
        threads <= 8,
        "{threads} threads for {} idle connections",
        idle.len()
    );
    drop(idle);
}

#[test]
fn a_query_number_out_of_range_is_refused_not_wrapped() {
    let dir = scratch("query-range");
    let run = dir.join("run");
    let out = ontogeny_command()
        .args([
            "evolve",
            "--encoding",
            "direct",
            "--task",
            "walker",
            "--pop",
            "4",
            "--gens",
            "1",
            "--seconds",
            "0.2",
            "--seed",
            "3",
            "--out",
        ])
        .arg(&run)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let viewer = Viewer::start(&run);
    let (status, body) = viewer.get("/individual.json?gen=0&index=4294967295");
    assert_eq!(status, 404, "{body}");
    assert!(
        body.contains("generation 0 has 4 individual(s); there is no individual 4294967295"),
        "{body}"
    );
    for query in ["gen=0&index=4294967296", "gen=-1&index=0", "gen=0&index=x"] {
        let (status, body) = viewer.get(&format!("/individual.json?{query}"));
        assert_eq!(status, 400, "{query}: {body}");
        assert!(
            body.contains("not a whole number from 0 to 4294967295"),
            "{body}"
        );
    }
    let (status, body) = viewer.get("/individual.json?gen=0&index=3");
    assert_eq!(status, 200, "{body}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn a_snapshot_refuses_a_target_that_is_not_a_regular_file() {
    use std::os::unix::fs::FileTypeExt;
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("snapshot-targets");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let socket = dir.join("socket.png");
    let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
    let directory = dir.join("directory.png");
    std::fs::create_dir(&directory).unwrap();
    std::fs::write(directory.join("kept"), "kept").unwrap();
    for target in [&socket, &directory] {
        // The browser is never started: `true` would write nothing.
        let out = ontogeny_command()
            .arg("view")
            .arg(example("algae.lsys"))
            .arg("--snapshot")
            .arg(target)
            .args(["--browser", "true"])
            .output()
            .unwrap();
        refused(
            &out,
            &format!(
                "{} exists and is not a regular file; refusing to replace it",
                target.display()
            ),
        );
    }
    assert!(
        std::fs::symlink_metadata(&socket)
            .unwrap()
            .file_type()
            .is_socket()
    );
    assert_eq!(
        std::fs::read_to_string(directory.join("kept")).unwrap(),
        "kept"
    );
}

#[test]
fn the_viewer_opens_a_version_1_run_without_migrating_it() {
    let dir = scratch("read-only-run");
    let run = dir.join("run");
    let out = ontogeny_command()
        .args([
            "evolve",
            "--encoding",
            "direct",
            "--pop",
            "6",
            "--gens",
            "2",
            "--seconds",
            "1",
            "--out",
        ])
        .arg(&run)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    crate::util::make_version_1(&run.join("run.sqlite"));
    let before = std::fs::read(run.join("run.sqlite")).unwrap();
    let viewer = Viewer::start(&run);
    let (status, body) = viewer.get("/individual.json?gen=1&index=0");
    assert_eq!(status, 200, "{body}");
    assert!(body.contains("\"parts\""), "{body}");
    drop(viewer);
    assert_eq!(std::fs::read(run.join("run.sqlite")).unwrap(), before);
    let version: i64 = rusqlite::Connection::open(run.join("run.sqlite"))
        .unwrap()
        .pragma_query_value(None, "user_version", |r| r.get(0))
        .unwrap();
    assert_eq!(version, 1);
    let _ = std::fs::remove_dir_all(dir);
}
