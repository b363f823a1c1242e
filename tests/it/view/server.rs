//! The viewer's server: it answers only its own host and only reads, idle connections cost no
//! thread, an oversized request head and a client too slow to send its request are dropped
//! without an answer, walks past the limit are refused as busy (503), a file that no longer
//! reads is a server error (500), out-of-range query numbers and generations the run lacks are
//! refused, `--snapshot` refuses a target that is not a regular file, a version-1 run is shown
//! without being migrated, and a run's individual's walk is evaluated again.

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
    let run = tiny_run_of(dir.join("run"), "0.2");
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
    crate::util::tiny_run("direct", &run, &[]);
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

/// A tiny run made by `ontogeny evolve` (4 direct walkers, one generation) in scratch
/// directory `name`.
pub(super) fn tiny_run(name: &str) -> PathBuf {
    tiny_run_of(scratch(name).join("run"), "1")
}

/// [`tiny_run`] into `run`, with walks of `seconds`.
fn tiny_run_of(run: PathBuf, seconds: &str) -> PathBuf {
    tiny_run_with(run, &["--gens", "1", "--seconds", seconds])
}

/// A run of 4 direct walkers (seed 3) into `run`, with `flags` added (its generations and
/// walks' seconds among them).
fn tiny_run_with(run: PathBuf, flags: &[&str]) -> PathBuf {
    let out = ontogeny_command()
        .args([
            "evolve",
            "--encoding",
            "direct",
            "--task",
            "walker",
            "--pop",
            "4",
            "--seed",
            "3",
        ])
        .args(flags)
        .arg("--out")
        .arg(&run)
        .output()
        .unwrap();
    succeeded(&out);
    run
}

/// `GET path` from `viewer`, answered 200, as JSON.
pub(super) fn get_json(viewer: &Viewer, path: &str) -> serde_json::Value {
    let (status, body) = viewer.get(path);
    assert_eq!(status, 200, "{path}: {body}");
    serde_json::from_str(&body).unwrap()
}

#[test]
fn a_walk_is_its_individual_evaluated_again_with_the_fitness_the_run_stored() {
    let run = tiny_run("walk");
    let shown = crate::util::ontogeny_ok(&["runs", "show", run.to_str().unwrap(), "--json"]);
    let shown: serde_json::Value = serde_json::from_str(&crate::util::stdout(&shown)).unwrap();
    let best = shown["generations"][0]["best"].as_f64().unwrap();
    let viewer = Viewer::start(&run);
    let walk = get_json(&viewer, "/walk.json?gen=0&rank=1");
    assert_eq!(walk["kind"], "recording");
    assert_eq!(walk["task"], "walker");
    assert_eq!(
        (walk["generation"].clone(), walk["rank"].clone()),
        (0.into(), 1.into())
    );
    assert_eq!(walk["fitness"].as_f64(), Some(best), "{}", walk["file"]);
    assert_eq!(walk["stored_fitness"].as_f64(), Some(best));
    let parts = walk["creature"]["parts"].as_array().unwrap().len();
    let frames = walk["frames"].as_array().unwrap();
    assert!(
        parts > 0 && frames.len() > 1,
        "{parts} parts, {} frames",
        frames.len()
    );
    assert!(
        frames
            .iter()
            .all(|f| f["parts"].as_array().unwrap().len() == parts)
    );
    // Rank R is the same individual in the page's table and in the walk.
    let table = get_json(&viewer, "/generation.json?gen=0");
    for individual in table["individuals"].as_array().unwrap() {
        let rank = individual["rank"].as_u64().unwrap();
        let walk = get_json(&viewer, &format!("/walk.json?gen=0&rank={rank}"));
        assert_eq!(walk["stored_fitness"], individual["fitness"], "rank {rank}");
        assert_eq!(walk["fitness"], individual["fitness"], "rank {rank}");
        assert_eq!(walk["status"], individual["status"], "rank {rank}");
    }
}

#[test]
fn a_walk_of_a_generation_or_rank_the_run_lacks_is_refused() {
    let run = tiny_run("walk-refused");
    let viewer = Viewer::start(&run);
    for (query, status, message) in [
        (
            "gen=0&rank=5",
            404,
            "generation 0 has 4 individual(s); there is no rank 5",
        ),
        ("gen=0&rank=0", 400, "rank=0: ranks start at 1, the best"),
        (
            "gen=1&rank=1",
            404,
            "there is no generation 1: the run has generations 0 to 0",
        ),
        ("gen=0", 400, "walk.json needs ?gen=G&rank=R"),
        (
            "gen=0&rank=-1",
            400,
            "rank=-1: not a whole number from 0 to 4294967295",
        ),
        (
            "gen=4294967296&rank=1",
            400,
            "not a whole number from 0 to 4294967295",
        ),
    ] {
        let (got, body) = viewer.get(&format!("/walk.json?{query}"));
        assert_eq!(got, status, "{query}: {body}");
        let error: serde_json::Value = serde_json::from_str(&body).unwrap();
        assert!(
            error["error"]["message"]
                .as_str()
                .unwrap()
                .contains(message),
            "{query}: {body}"
        );
    }
    drop(viewer);
    let viewer = Viewer::start(&example("algae.lsys"));
    let (status, body) = viewer.get("/walk.json?gen=0&rank=1");
    assert_eq!(status, 404, "{body}");
    assert!(body.contains("not a run"), "{body}");
}

/// The viewer's `host:port`.
fn address(viewer: &Viewer) -> String {
    viewer
        .url
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .to_string()
}

/// Everything the server sends on `stream` until it closes it; a connection it resets (a
/// request it dropped unread) has sent what came before.
fn read_until_closed(stream: &mut std::net::TcpStream) -> Vec<u8> {
    let mut received = Vec::new();
    let mut chunk = [0u8; 4096];
    loop {
        match stream.read(&mut chunk) {
            Ok(0) | Err(_) => return received,
            Ok(n) => received.extend_from_slice(&chunk[..n]),
        }
    }
}

#[test]
fn a_request_head_over_16_kib_is_dropped_without_an_answer() {
    let viewer = Viewer::start(&example("algae.lsys"));
    let host = address(&viewer);
    let mut stream = std::net::TcpStream::connect(&host).unwrap();
    // 17 KiB of headers and no blank line: more than the server reads of any head.
    let mut head = format!("GET /data.json HTTP/1.1\r\nHost: {host}\r\n");
    while head.len() <= 17 * 1024 {
        head.push_str(
            "X-Padding: aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\r\n",
        );
    }
    // The server may close the connection before it has taken every byte.
    let _ = stream.write_all(head.as_bytes());
    let received = read_until_closed(&mut stream);
    assert_eq!(String::from_utf8_lossy(&received), "");
    // The viewer still answers the next request.
    assert_eq!(viewer.get("/version").0, 200);
}

#[test]
fn a_client_that_never_finishes_its_request_is_dropped_and_others_are_answered_meanwhile() {
    let viewer = Viewer::start(&example("algae.lsys"));
    let host = address(&viewer);
    let mut slow = std::net::TcpStream::connect(&host).unwrap();
    slow.write_all(format!("GET /data.json HTTP/1.1\r\nHost: {host}\r\n").as_bytes())
        .unwrap();
    // While it dawdles, another client is answered.
    let (status, body) = viewer.get("/data.json");
    assert_eq!(status, 200, "{body}");
    // Its head never ends: the server closes the connection (after its 5 s for a request)
    // without an answer.
    let received = read_until_closed(&mut slow);
    assert_eq!(String::from_utf8_lossy(&received), "");
}

#[test]
fn walks_past_the_limit_at_once_are_refused_as_busy() {
    // The server's 4 workers evaluate at most 2 walks at once. 20 s walks: each takes a while to evaluate again.
    let dir = scratch("busy");
    let run = tiny_run_of(dir.join("run"), "20");
    let viewer = Viewer::start(&run);
    let host = address(&viewer);
    // Six walks asked for at once: two are evaluated, the others find both slots taken.
    let mut streams: Vec<std::net::TcpStream> = (1..=6)
        .map(|i| {
            let mut stream = std::net::TcpStream::connect(&host).unwrap();
            let rank = 1 + i % 4;
            write!(
                stream,
                "GET /walk.json?gen=0&rank={rank} HTTP/1.1\r\nHost: {host}\r\n\r\n"
            )
            .unwrap();
            stream
        })
        .collect();
    let answers: Vec<String> = streams
        .iter_mut()
        .map(|s| String::from_utf8_lossy(&read_until_closed(s)).into_owned())
        .collect();
    let busy = answers
        .iter()
        .filter(|a| a.starts_with("HTTP/1.1 503 Service Unavailable\r\n"))
        .count();
    let walked = answers
        .iter()
        .filter(|a| a.starts_with("HTTP/1.1 200 OK\r\n"))
        .count();
    assert_eq!(busy + walked, 6, "{answers:#?}");
    assert!(busy >= 1 && walked >= 2, "{answers:#?}");
    for answer in answers.iter().filter(|a| a.contains(" 503 ")) {
        let body = answer.split_once("\r\n\r\n").unwrap().1;
        assert_eq!(
            body,
            r#"{"error":{"message":"busy: 2 walks are being evaluated; try again when one is done"}}"#
        );
    }
    // Once they are done, a walk is evaluated again.
    assert_eq!(viewer.get("/walk.json?gen=0&rank=1").0, 200);
    drop(viewer);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_file_that_no_longer_reads_is_a_server_error_naming_it() {
    let dir = scratch("unreadable");
    let creature = ontogeny::develop::creature_from_commands("forward(1)").unwrap();
    let pose = serde_json::json!([[0.5, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);
    let recording = dir.join("recording.json");
    std::fs::write(
        &recording,
        serde_json::json!({"creature": creature, "frames": [{"t": 0.0, "parts": [pose]}]})
            .to_string(),
    )
    .unwrap();
    let viewer = Viewer::start(&dir);
    assert_eq!(viewer.get("/data.json").0, 200);
    // Overwritten with something that is not JSON, then removed, while the viewer serves it.
    std::fs::write(&recording, "not json").unwrap();
    let (status, body) = viewer.get("/data.json");
    assert_eq!(status, 500, "{body}");
    let message = serde_json::from_str::<serde_json::Value>(&body).unwrap()["error"]["message"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(
        message.starts_with(&format!("{}: ", recording.display())),
        "{message}"
    );
    std::fs::remove_file(&recording).unwrap();
    let (status, body) = viewer.get("/data.json");
    assert_eq!(status, 500, "{body}");
    assert!(
        body.contains(&format!("cannot read {}: ", recording.display())),
        "{body}"
    );
    // The page itself is still served.
    assert_eq!(viewer.get("/").0, 200);
}

#[test]
fn a_generation_the_run_lacks_is_not_found_on_every_page_that_asks_for_one() {
    let run = tiny_run("generation-range");
    let viewer = Viewer::start(&run);
    let lacks = |g: &str| format!("there is no generation {g}: the run has generations 0 to 0");
    for (page, g) in [
        ("generation.json?gen=", "4294967295"),
        ("generation.json?gen=", "1"),
        ("individual.json?index=0&gen=", "4294967295"),
        ("walk.json?rank=1&gen=", "4294967295"),
    ] {
        let (status, body) = viewer.get(&format!("/{page}{g}"));
        assert_eq!(status, 404, "{page}{g}: {body}");
        let error: serde_json::Value = serde_json::from_str(&body).unwrap();
        assert_eq!(error["error"]["message"], lacks(g), "{page}{g}");
    }
    let table = get_json(&viewer, "/generation.json?gen=0");
    assert_eq!(table["individuals"].as_array().unwrap().len(), 4);
}

#[test]
fn a_grammars_findings_and_its_builders_problems_come_with_its_frames_and_follow_its_edits() {
    let dir = scratch("findings");
    let file = dir.join("typo.lsys");
    std::fs::write(
        &file,
        "derivation length: 3\naxiom: forward(1) A\nA --> ] A Tial\nTail --> forward(1)\n",
    )
    .unwrap();
    let viewer = Viewer::start(&file);
    let data = get_json(&viewer, "/data.json");
    let findings = data["findings"].as_array().unwrap();
    assert_eq!(findings.len(), 1, "{data}");
    let finding = &findings[0];
    assert_eq!(
        finding["message"],
        "'Tial' is read as the modules T i a l (did you mean `Tail`?)"
    );
    assert_eq!(
        (&finding["location"]["line"], &finding["location"]["column"]),
        (&serde_json::json!(3), &serde_json::json!(11))
    );
    assert_eq!(
        finding["text"],
        format!(
            "warning: 'Tial' is read as the modules T i a l (did you mean `Tail`?)\n \
             --> {}:3:11\n  |\n3 | A --> ] A Tial\n  |           ^^^^",
            file.display()
        )
    );
    // Frames 1 to 3 each pop with nothing to pop (frame 3 three times): once, with its count.
    let problems = data["problems"].as_array().unwrap();
    assert_eq!(problems.len(), 1, "{data}");
    assert_eq!(
        problems[0]["text"],
        "warning: ']' with nothing to pop: ignored []] (at 3 frames, from t = 1)"
    );
    assert_eq!(problems[0]["frames"], 3);

    // Fixed, the file has nothing to say.
    std::fs::write(
        &file,
        "derivation length: 3\naxiom: forward(1) A\nA --> A Tail\nTail --> forward(1)\n",
    )
    .unwrap();
    let data = get_json(&viewer, "/data.json");
    assert_eq!(data["findings"], serde_json::json!([]), "{data}");
    assert_eq!(data["problems"], serde_json::json!([]), "{data}");
}

#[test]
fn max_parts_lets_the_page_hold_a_plant_of_thousands_of_parts() {
    let frames = |viewer: &Viewer| -> Vec<(usize, bool)> {
        get_json(viewer, "/data.json")["frames"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| {
                let c = &f["creature"];
                let errors = c["problems"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .any(|p| p["severity"] == "error");
                (c["parts"].as_array().unwrap().len(), errors)
            })
            .collect()
    };
    let viewer = Viewer::start_with(&example("abop-1.24a.lsys"), &["--max-parts", "5000"]);
    // 5^k parts at step k; overlaps are warnings in a picture, so no frame has an error.
    let shown = frames(&viewer);
    assert_eq!(
        shown,
        [
            (1, false),
            (5, false),
            (25, false),
            (125, false),
            (625, false),
            (3125, false)
        ]
    );
    drop(viewer);
    // Without it the page stops at the default limit, with an error.
    let viewer = Viewer::start(&example("abop-1.24a.lsys"));
    let last = *frames(&viewer).last().unwrap();
    assert_eq!(last, (201, true));
}

#[test]
fn a_run_page_says_what_the_fitness_measures_and_the_fine_reference_of_each_best() {
    let run = tiny_run("plot-data");
    let store = ontogeny::run::store::RunStore::open(&run.join("run.sqlite")).unwrap();
    let generations = store.generations().unwrap();
    let spec = store.run().unwrap().task_spec().unwrap();
    let viewer = Viewer::start(&run);
    let data = get_json(&viewer, "/data.json");
    // The y axis of fitness.svg.
    assert_eq!(
        data["fitness"],
        format!("fitness: {}", spec.fitness_measure())
    );
    // A generational run names no algorithm.
    assert!(data["algorithm"].is_null(), "{}", data["algorithm"]);
    let pages = data["generations"].as_array().unwrap();
    assert_eq!(pages.len(), generations.len());
    assert!(generations.iter().any(|g| g.best_fine.is_some()));
    for (page, g) in pages.iter().zip(&generations) {
        match &g.best_fine {
            Some(fine) => assert_eq!(page["best_fine"].as_f64(), Some(fine.fitness)),
            None => assert!(page["best_fine"].is_null(), "{page}"),
        }
    }
}

#[test]
fn a_steady_state_run_page_names_its_algorithm_and_births_in_flight() {
    let run = tiny_run_with(
        scratch("steady-page").join("run"),
        &[
            "--algorithm",
            "steady-state",
            "--in-flight",
            "3",
            "--gens",
            "2",
            "--seconds",
            "0.5",
        ],
    );
    let viewer = Viewer::start(&run);
    let data = get_json(&viewer, "/data.json");
    assert_eq!(
        data["algorithm"],
        serde_json::json!({ "name": "steady-state", "in_flight": 3 })
    );
    // Each stored block of births is a generation of the page.
    assert_eq!(data["generations"].as_array().unwrap().len(), 2);
}

/// A tiny comparison made by `ontogeny compare` (direct against lsystem, one replicate each, 9
/// evaluations of half-second walks) in scratch directory `name`.
pub(super) fn tiny_comparison(name: &str) -> PathBuf {
    let out = scratch(name).join("cmp");
    let o = ontogeny_command()
        .args([
            "compare",
            "--encodings",
            "direct,lsystem",
            "--task",
            "walker",
            "--replicates",
            "1",
            "--evaluations",
            "9",
            "--pop",
            "4",
            "--seconds",
            "0.5",
            "--seed",
            "2",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out
}

#[test]
fn a_comparison_is_shown_with_its_report_its_plots_and_its_replicates() {
    let cmp = tiny_comparison("comparison");
    let viewer = Viewer::start(&cmp);
    let data = get_json(&viewer, "/data.json");
    assert_eq!(data["kind"], "comparison");
    assert_eq!(data["encodings"], serde_json::json!(["direct", "lsystem"]));
    assert_eq!(data["fitness"], "walker, normalised (Chaumont eq. 1)");
    let report = std::fs::read_to_string(cmp.join("report.md")).unwrap();
    assert_eq!(data["report"], report);
    assert_eq!(
        data["plots"],
        serde_json::json!(["fitness.svg", "parts.svg"])
    );
    let runs = data["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    for (run, encoding) in runs.iter().zip(["direct", "lsystem"]) {
        assert_eq!(run["encoding"], encoding);
        assert_eq!(run["k"], 1);
        let dir = cmp.join(encoding).join("rep-1");
        assert_eq!(run["dir"], dir.display().to_string());
        let store = ontogeny::run::store::RunStore::open(&dir.join("run.sqlite")).unwrap();
        let generations = store.generations().unwrap();
        assert_eq!(run["generations"], generations.len());
        assert_eq!(run["best"].as_f64(), Some(generations.last().unwrap().best));
    }
    // Its plots are served, and nothing else of the folder.
    let (status, svg) = viewer.get("/plot/fitness.svg");
    assert_eq!(status, 200);
    assert_eq!(
        svg,
        std::fs::read_to_string(cmp.join("fitness.svg")).unwrap()
    );
    assert_eq!(viewer.get("/plot/parts.svg").0, 200);
    assert_eq!(viewer.get("/plot/report.md").0, 404);
    assert_eq!(viewer.get("/plot/../compare.toml").0, 404);
}
