//! The local HTTP server: the page, its scripts, and the JSON it reads.
//!
//! It serves only its own user: it listens on 127.0.0.1, answers only requests addressed to
//! `localhost`, `127.0.0.1` or `[::1]` on its own port (a page elsewhere that rebinds its domain
//! name to 127.0.0.1 gets 403), only reads (GET and HEAD; anything else gets 405), and tells
//! the browser to run nothing but the page's own scripts (`Content-Security-Policy`,
//! `X-Content-Type-Options: nosniff`). One thread gathers requests from every connection
//! without waiting on any, and a fixed pool of `WORKERS` threads answers them (one request
//! per connection), so no number of connections makes more threads, and idle ones keep no one
//! waiting; a connection that sends no request within [`REQUEST_TIMEOUT`] is dropped. A
//! run's individual's walk takes as long as its evaluation: at most [`MAX_WALKS`] are
//! evaluated at once, so the other workers stay free for the page's quick requests.

use std::collections::VecDeque;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::SyncSender;
use std::time::{Duration, Instant};

use serde_json::{Value, json};

use super::{Developer, Kind, Target, ViewError};
use crate::lsystem::DeriveOptions;
use crate::run::store::{RunStore, StoreError};

const INDEX_HTML: &str = include_str!("assets/index.html");
const APP_JS: &str = include_str!("assets/app.js");
const DEFINES_JS: &str = include_str!("assets/defines.js");
const BRAIN_JS: &str = include_str!("assets/brain.js");
const THREE_MODULE: &str = include_str!("../../vendor/three/three.module.min.js");
const THREE_CORE: &str = include_str!("../../vendor/three/three.core.min.js");
const ORBIT_CONTROLS: &str = include_str!("../../vendor/three/OrbitControls.js");
const THREE_LICENSE: &str = include_str!("../../vendor/three/LICENSE");

/// The page's one inline script, its import map, which the policy lets run by a nonce.
const IMPORT_MAP_TAG: &str = "<script type=\"importmap\">";

/// The threads that answer requests.
pub const WORKERS: usize = 4;

/// How long a connection has to send its request (and to take the answer) before it is dropped.
pub const REQUEST_TIMEOUT: Duration = Duration::from_secs(5);

/// The longest request head (request line and headers) read, in bytes.
const MAX_HEAD: usize = 16 * 1024;

/// The most connections whose requests are read at once.
pub const MAX_PENDING: usize = 256;

/// The longest wait between two looks for new connections and requests when there are none.
const MAX_PAUSE: Duration = Duration::from_millis(20);

/// The most walks (`/walk.json`) evaluated at once; more are refused as busy (503).
pub const MAX_WALKS: usize = WORKERS / 2;

/// Why the server could not start.
#[derive(Debug, thiserror::Error)]
pub enum ServerError {
    /// The port is taken.
    #[error("port {0} is already in use: choose another with --port, or --port 0 for any free one")]
    PortInUse(u16),
    /// Any other failure to listen.
    #[error("cannot listen on 127.0.0.1:{port}: {message}")]
    Listen {
        /// The port asked for.
        port: u16,
        /// What went wrong.
        message: String,
    },
}

/// The viewer's server, bound to 127.0.0.1, serving one [`Target`].
pub struct Server {
    listener: TcpListener,
    target: Target,
    options: DeriveOptions,
    steps: Option<u64>,
    /// The most parts an `.lsys` target's creature may have (`view --max-parts`).
    max_parts: usize,
    developer: Option<Developer>,
    /// How many walks are being evaluated now.
    walks: AtomicUsize,
}

/// A walk being evaluated: counted in [`Server::walks`] while it lives.
struct WalkSlot<'a>(&'a AtomicUsize);

impl Drop for WalkSlot<'_> {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// An answer: status, content type, body, and extra headers.
#[derive(Debug)]
struct Answer {
    status: u16,
    content_type: &'static str,
    body: Vec<u8>,
    headers: Vec<(&'static str, String)>,
}

impl Answer {
    fn new(status: u16, content_type: &'static str, body: impl Into<Vec<u8>>) -> Answer {
        Answer {
            status,
            content_type,
            body: body.into(),
            headers: Vec::new(),
        }
    }

    fn text(status: u16, body: &str) -> Answer {
        Answer::new(status, "text/plain; charset=utf-8", body)
    }
}

impl Server {
    /// Listens on 127.0.0.1:`port` (0 picks a free port). `options` and `steps` say how an
    /// `.lsys` target is grown; `developer` opens a run's individuals.
    pub fn bind(
        target: Target,
        port: u16,
        options: DeriveOptions,
        steps: Option<u64>,
        developer: Option<Developer>,
    ) -> Result<Server, ServerError> {
        let listener = match TcpListener::bind(("127.0.0.1", port)) {
            Ok(listener) => listener,
            Err(e) if e.kind() == std::io::ErrorKind::AddrInUse => {
                return Err(ServerError::PortInUse(port));
            }
            Err(e) => {
                return Err(ServerError::Listen {
                    port,
                    message: e.to_string(),
                });
            }
        };
        Ok(Server {
            listener,
            target,
            options,
            steps,
            max_parts: crate::develop::BuildOptions::default().max_parts,
            developer,
            walks: AtomicUsize::new(0),
        })
    }

    /// The server with the most parts an `.lsys` target's creature may have (default
    /// [`BuildOptions::default`](crate::develop::BuildOptions::default)'s).
    pub fn with_max_parts(mut self, max_parts: usize) -> Server {
        self.max_parts = max_parts;
        self
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.listener
            .local_addr()
            .unwrap_or_else(|_| SocketAddr::from(([127, 0, 0, 1], 0)))
    }

    /// The page's address.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr())
    }

    /// Answers requests until the process ends: one thread gathers the connections' requests
    /// (without blocking on any of them), `WORKERS` threads answer them.
    pub fn run(&self) {
        let (requests, queue) = std::sync::mpsc::sync_channel::<(TcpStream, Vec<u8>)>(WORKERS);
        let queue = std::sync::Mutex::new(queue);
        std::thread::scope(|scope| {
            for _ in 0..WORKERS {
                scope.spawn(|| {
                    loop {
                        // The lock is held only while waiting for the next request.
                        let next = queue.lock().map(|queue| queue.recv());
                        match next {
                            Ok(Ok((stream, head))) => self.serve(stream, &head),
                            _ => return,
                        }
                    }
                });
            }
            gather_requests(&self.listener, &requests);
        });
    }

    /// Answers the request whose head is `head` on `stream`.
    fn serve(&self, mut stream: TcpStream, head: &[u8]) {
        if stream.set_nonblocking(false).is_err()
            || stream.set_write_timeout(Some(REQUEST_TIMEOUT)).is_err()
        {
            return;
        }
        let (answer, with_body) = match parse_head(head) {
            Err(answer) => (answer, true),
            Ok(request) => (self.answer_request(&request), request.method != "HEAD"),
        };
        // A browser that went away mid-answer is not our problem.
        let _ = stream.write_all(&response_bytes(&answer, with_body));
        let _ = stream.flush();
    }

    /// The answer to a well-formed request: refused when it is not addressed to this server
    /// (403) or does not only read (405).
    fn answer_request(&self, request: &Request) -> Answer {
        if !request
            .host
            .as_deref()
            .is_some_and(|host| is_own_host(host, self.addr().port()))
        {
            return Answer::text(
                403,
                "forbidden: this viewer answers only requests to localhost, 127.0.0.1 or [::1] \
                 on its own port",
            );
        }
        if request.method != "GET" && request.method != "HEAD" {
            let mut answer = Answer::text(405, "method not allowed: the viewer only reads");
            answer.headers.push(("Allow", "GET, HEAD".to_string()));
            return answer;
        }
        self.answer(&request.target)
    }

    /// The answer for a request's URL.
    fn answer(&self, url: &str) -> Answer {
        let (path, query) = url.split_once('?').unwrap_or((url, ""));
        let js = "text/javascript; charset=utf-8";
        match path {
            "/" | "/index.html" => {
                let nonce = format!("{:032x}", rand::random::<u128>());
                let page = INDEX_HTML.replacen(
                    IMPORT_MAP_TAG,
                    &format!("<script type=\"importmap\" nonce=\"{nonce}\">"),
                    1,
                );
                let mut answer = Answer::new(200, "text/html; charset=utf-8", page);
                answer
                    .headers
                    .push(("Content-Security-Policy", content_security_policy(&nonce)));
                answer
            }
            "/app.js" => Answer::new(200, js, APP_JS),
            "/defines.js" => Answer::new(200, js, DEFINES_JS),
            "/brain.js" => Answer::new(200, js, BRAIN_JS),
            "/three/three.module.min.js" => Answer::new(200, js, THREE_MODULE),
            "/three/three.core.min.js" => Answer::new(200, js, THREE_CORE),
            "/three/OrbitControls.js" => Answer::new(200, js, ORBIT_CONTROLS),
            "/three/LICENSE" => Answer::text(200, THREE_LICENSE),
            "/version" => Answer::text(200, &self.target.version()),
            "/data.json" => json_answer(self.data(query)),
            "/generation.json" => json_answer(self.generation(query)),
            "/individual.json" => json_answer(self.individual(query)),
            "/walk.json" => json_answer(self.walk(query)),
            _ => match path.strip_prefix("/plot/") {
                // A comparison's plots, by name: nothing else of its directory is served.
                Some(name)
                    if self.target.kind == Kind::Comparison
                        && super::COMPARISON_PLOTS.contains(&name) =>
                {
                    match std::fs::read(self.target.path.join(name)) {
                        Ok(svg) => Answer::new(200, "image/svg+xml", svg),
                        Err(_) => Answer::text(404, "not found"),
                    }
                }
                _ => Answer::text(404, "not found"),
            },
        }
    }

    /// One of a run's generations, its individuals best first; a generation the run lacks is
    /// not found (404), as for `/walk.json`.
    fn generation(&self, query: &str) -> Result<Value, ViewError> {
        let generation = number(query, "gen")?
            .ok_or_else(|| ViewError::BadRequest("generation.json needs ?gen=G".into()))?;
        if self.target.kind != Kind::Run {
            return Err(ViewError::NotFound("not a run".into()));
        }
        self.stored_generation(generation)?;
        super::run_generation_data(&self.target.path, generation)
    }

    /// Refuses (404) a generation that the run has not stored whole, saying which it has.
    fn stored_generation(&self, generation: u32) -> Result<(), ViewError> {
        let unreadable = |e: StoreError| ViewError::BadFile(e.to_string());
        let store =
            RunStore::open_read_only(&self.target.path.join("run.sqlite")).map_err(unreadable)?;
        match store.last_generation().map_err(unreadable)? {
            None => Err(ViewError::NotFound(
                "the run has no complete generation yet".to_string(),
            )),
            Some(last) if generation > last => Err(ViewError::NotFound(format!(
                "there is no generation {generation}: the run has generations 0 to {last}"
            ))),
            Some(_) => Ok(()),
        }
    }

    /// The page's data for the target, read afresh (so an edited file shows its changes); an
    /// `.lsys` file is grown with the defines the query sets (`?define.NAME=VALUE`).
    fn data(&self, query: &str) -> Result<Value, ViewError> {
        let path = &self.target.path;
        match self.target.kind {
            Kind::Lsys => {
                let defines = super::defines_of_query(query)?;
                super::lsys_data_with(path, &self.options, self.steps, self.max_parts, &defines)
            }
            Kind::Growth => super::growth_data(path),
            Kind::Recording => super::recording_data(path),
            Kind::Run => super::run_data(path),
            Kind::Comparison => super::comparison_data(path),
        }
    }

    /// A query about a run's individual: `?gen=G&KEY=K` (`page` names the page in the
    /// message when one is missing), and the run's developer; a target that is no run is
    /// refused.
    fn run_query(
        &self,
        query: &str,
        key: &str,
        page: &str,
    ) -> Result<(u32, u32, &super::Developer), ViewError> {
        let (Some(generation), Some(k)) = (number(query, "gen")?, number(query, key)?) else {
            let letter = key[..1].to_uppercase();
            return Err(ViewError::BadRequest(format!(
                "{page} needs ?gen=G&{key}={letter}"
            )));
        };
        let developer = self
            .developer
            .as_ref()
            .filter(|_| self.target.kind == Kind::Run)
            .ok_or_else(|| ViewError::NotFound("not a run".into()))?;
        Ok((generation, k, developer))
    }

    /// One of a run's individuals, developed (in the habitat `view --habitat` names, which the
    /// answer's `habitat` says).
    fn individual(&self, query: &str) -> Result<Value, ViewError> {
        let (generation, index, developer) = self.run_query(query, "index", "individual.json")?;
        self.stored_generation(generation)?;
        let count = super::run_population_size(&self.target.path, generation)?;
        if index as usize >= count {
            return Err(ViewError::NotFound(format!(
                "generation {generation} has {count} individual(s); there is no individual {index}"
            )));
        }
        let creature = (developer.develop)(generation, index).map_err(ViewError::BadFile)?;
        let mut value = super::creature_data(
            &format!("generation {generation}, individual {index}"),
            &creature,
        );
        if let Some(name) = &developer.habitat {
            value["habitat"] = json!(name);
        }
        Ok(value)
    }

    /// The walk of a run's individual picked by generation and rank (1 the best): evaluated
    /// again with a recording, as `ontogeny replay --gen G --rank R` does.
    fn walk(&self, query: &str) -> Result<Value, ViewError> {
        let (generation, rank, developer) = self.run_query(query, "rank", "walk.json")?;
        let _slot = self
            .walks
            .fetch_update(Ordering::SeqCst, Ordering::SeqCst, |n| {
                (n < MAX_WALKS).then_some(n + 1)
            })
            .map(|_| WalkSlot(&self.walks))
            .map_err(|_| {
                ViewError::Busy(format!(
                    "busy: {MAX_WALKS} walks are being evaluated; try again when one is done"
                ))
            })?;
        (developer.walk)(generation, rank)
    }
}

/// A JSON answer: 200 with the value, or `{"error": {"message"}}` with 400 (a bad query), 404
/// (nothing there), 503 (busy) or 500 (a file that cannot be read).
fn json_answer(value: Result<Value, ViewError>) -> Answer {
    let json_type = "application/json";
    match value {
        Ok(v) => Answer::new(200, json_type, v.to_string()),
        Err(e) => {
            let status = match e {
                ViewError::BadRequest(_) => 400,
                ViewError::NotFound(_) => 404,
                ViewError::Busy(_) => 503,
                ViewError::NotViewable(_) | ViewError::BadFile(_) => 500,
            };
            let body = json!({ "error": { "message": e.to_string() } }).to_string();
            Answer::new(status, json_type, body)
        }
    }
}

/// The unsigned number `key` in a query string: `None` when the key is missing, an error when
/// its value is not a whole number from 0 to 4294967295.
fn number(query: &str, key: &str) -> Result<Option<u32>, ViewError> {
    let Some((_, value)) = query
        .split('&')
        .filter_map(|pair| pair.split_once('='))
        .find(|(k, _)| *k == key)
    else {
        return Ok(None);
    };
    value.parse().map(Some).map_err(|_| {
        ViewError::BadRequest(format!(
            "{key}={value}: not a whole number from 0 to {}",
            u32::MAX
        ))
    })
}

/// The policy the page runs under: its own scripts (and its import map, by `nonce`), its own
/// data, inline styles, and nothing from elsewhere.
fn content_security_policy(nonce: &str) -> String {
    format!(
        "default-src 'self'; script-src 'self' 'nonce-{nonce}'; style-src 'self' \
         'unsafe-inline'; img-src 'self' data:; connect-src 'self'; object-src 'none'; \
         base-uri 'none'; form-action 'none'; frame-ancestors 'none'"
    )
}

/// A request's method, target and `Host` header.
#[derive(Debug, PartialEq)]
struct Request {
    method: String,
    target: String,
    host: Option<String>,
}

/// A connection whose request head is being read.
struct Pending {
    stream: TcpStream,
    head: Vec<u8>,
    since: Instant,
}

/// What became of a read from a [`Pending`] connection.
enum Progress {
    /// Its whole head has come.
    Complete,
    /// More has come, not all.
    Some,
    /// Nothing new.
    Nothing,
    /// It closed, failed, sent too much, or took too long: dropped.
    Dropped,
}

impl Pending {
    fn read(&mut self) -> Progress {
        let mut chunk = [0u8; 4096];
        match self.stream.read(&mut chunk) {
            Ok(0) => Progress::Dropped,
            Ok(n) => {
                self.head.extend_from_slice(&chunk[..n]);
                if self.head.windows(4).any(|w| w == b"\r\n\r\n") {
                    Progress::Complete
                } else if self.head.len() > MAX_HEAD {
                    Progress::Dropped
                } else {
                    Progress::Some
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                if self.since.elapsed() > REQUEST_TIMEOUT {
                    Progress::Dropped
                } else {
                    Progress::Nothing
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => Progress::Nothing,
            Err(_) => Progress::Dropped,
        }
    }
}

/// Accepts connections and reads their request heads without blocking on any, sending each
/// complete head with its connection to `requests`; so idle connections hold no thread and
/// cannot keep others waiting. At most [`MAX_PENDING`] are read at once (the oldest is dropped
/// for a newer one), each for at most [`REQUEST_TIMEOUT`]. Returns when the listener fails or
/// the workers are gone.
fn gather_requests(listener: &TcpListener, requests: &SyncSender<(TcpStream, Vec<u8>)>) {
    if listener.set_nonblocking(true).is_err() {
        return;
    }
    let mut pending: VecDeque<Pending> = VecDeque::new();
    let mut pause = Duration::from_millis(1);
    loop {
        let mut busy = false;
        loop {
            match listener.accept() {
                Ok((stream, _)) => {
                    busy = true;
                    if stream.set_nonblocking(true).is_err() {
                        continue;
                    }
                    if pending.len() >= MAX_PENDING {
                        pending.pop_front();
                    }
                    pending.push_back(Pending {
                        stream,
                        head: Vec::new(),
                        since: Instant::now(),
                    });
                }
                Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => break,
                // A connection reset before it was accepted, or no descriptors left for a
                // moment: try again on the next round.
                Err(_) => break,
            }
        }
        let mut still = VecDeque::with_capacity(pending.len());
        for mut connection in pending.drain(..) {
            match connection.read() {
                Progress::Complete => {
                    busy = true;
                    if requests.send((connection.stream, connection.head)).is_err() {
                        return;
                    }
                }
                Progress::Some => {
                    busy = true;
                    still.push_back(connection);
                }
                Progress::Nothing => still.push_back(connection),
                Progress::Dropped => {}
            }
        }
        pending = still;
        // Quick to answer a browser's burst of requests, idle when there is none.
        pause = if busy {
            Duration::from_millis(1)
        } else {
            (pause * 2).min(MAX_PAUSE)
        };
        std::thread::sleep(pause);
    }
}

/// Parses a request head (with `httparse`), or says why it is malformed (400): not HTTP/1,
/// a target that is not a path (an absolute URL), or two `Host` headers.
fn parse_head(head: &[u8]) -> Result<Request, Answer> {
    let bad = || Answer::text(400, "bad request");
    let mut headers = [httparse::EMPTY_HEADER; 64];
    let mut request = httparse::Request::new(&mut headers);
    match request.parse(head) {
        Ok(httparse::Status::Complete(_)) => {}
        _ => return Err(bad()),
    }
    let (Some(method), Some(target)) = (request.method, request.path) else {
        return Err(bad());
    };
    if !target.starts_with('/') {
        return Err(bad());
    }
    let mut hosts = request
        .headers
        .iter()
        .filter(|h| h.name.eq_ignore_ascii_case("host"));
    let host = match (hosts.next(), hosts.next()) {
        // Two Host headers: which one is meant is anyone's guess.
        (Some(_), Some(_)) => return Err(bad()),
        (Some(h), None) => Some(
            std::str::from_utf8(h.value)
                .map_err(|_| bad())?
                .trim()
                .to_string(),
        ),
        (None, _) => None,
    };
    Ok(Request {
        method: method.to_string(),
        target: target.to_string(),
        host,
    })
}

/// Whether a `Host` header names this server: `localhost`, `127.0.0.1` or `[::1]`, alone or
/// with `port`, its own port.
fn is_own_host(host: &str, port: u16) -> bool {
    let (name, given_port) = match host.rsplit_once(':') {
        // `[::1]` alone has colons inside its brackets, not a port.
        Some((name, p)) if !p.ends_with(']') => (name, Some(p)),
        _ => (host, None),
    };
    let known = name.eq_ignore_ascii_case("localhost") || name == "127.0.0.1" || name == "[::1]";
    known && given_port.is_none_or(|p| p == port.to_string())
}

/// The bytes of a response (the body left out for HEAD), with the headers every answer
/// carries.
fn response_bytes(answer: &Answer, with_body: bool) -> Vec<u8> {
    let reason = match answer.status {
        200 => "OK",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        503 => "Service Unavailable",
        _ => "Internal Server Error",
    };
    let mut head = format!(
        "HTTP/1.1 {} {reason}\r\nContent-Type: {}\r\nContent-Length: {}\r\n\
         Cache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\n\
         Connection: close\r\n",
        answer.status,
        answer.content_type,
        answer.body.len()
    );
    if !answer
        .headers
        .iter()
        .any(|(name, _)| *name == "Content-Security-Policy")
    {
        head.push_str("Content-Security-Policy: default-src 'none'; frame-ancestors 'none'\r\n");
    }
    for (name, value) in &answer.headers {
        head.push_str(&format!("{name}: {value}\r\n"));
    }
    head.push_str("\r\n");
    let mut bytes = head.into_bytes();
    if with_body {
        bytes.extend_from_slice(&answer.body);
    }
    bytes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_numbers_are_read_by_name() {
        assert_eq!(number("gen=3&index=14", "index").unwrap(), Some(14));
        assert_eq!(number("gen=3&index=14", "gen").unwrap(), Some(3));
        assert_eq!(number("", "gen").unwrap(), None);
    }

    #[test]
    fn query_numbers_out_of_range_are_bad_requests() {
        for value in ["x", "-1", "4294967296", "99999999999999999999"] {
            assert!(
                matches!(
                    number(&format!("gen={value}"), "gen"),
                    Err(ViewError::BadRequest(_))
                ),
                "{value}"
            );
        }
        assert_eq!(number("index=4294967295", "index").unwrap(), Some(u32::MAX));
    }

    #[test]
    fn only_this_machines_names_on_this_port_are_its_own_host() {
        for host in [
            "localhost",
            "localhost:8750",
            "LocalHost:8750",
            "127.0.0.1",
            "127.0.0.1:8750",
            "[::1]",
            "[::1]:8750",
        ] {
            assert!(is_own_host(host, 8750), "{host}");
        }
        for host in [
            "evil.example",
            "evil.example:8750",
            "localhost:8751",
            "127.0.0.2:8750",
            "localhost.evil.example",
            "[::1]:80",
            "::1",
            "",
        ] {
            assert!(!is_own_host(host, 8750), "{host}");
        }
    }

    #[test]
    fn a_request_head_is_parsed_and_a_malformed_one_refused() {
        let request =
            parse_head(b"GET /data.json?x=1 HTTP/1.1\r\nhOsT: localhost:9\r\nAccept: */*\r\n\r\n")
                .unwrap();
        assert_eq!(
            request,
            Request {
                method: "GET".into(),
                target: "/data.json?x=1".into(),
                host: Some("localhost:9".into()),
            }
        );
        assert_eq!(parse_head(b"GET / HTTP/1.0\r\n\r\n").unwrap().host, None);
        for bad in [
            &b"GET /\r\n\r\n"[..],
            b"GET http://evil.example/ HTTP/1.1\r\nHost: localhost\r\n\r\n",
            b"GET / HTTP/1.1\r\nHost: localhost\r\nHost: evil.example\r\n\r\n",
            b"GET / HTTP/1.1\r\nno colon\r\n\r\n",
        ] {
            assert!(parse_head(bad).is_err(), "{}", String::from_utf8_lossy(bad));
        }
    }

    #[test]
    fn every_response_forbids_sniffing_and_outside_resources() {
        let page =
            String::from_utf8(response_bytes(&Answer::text(404, "not found"), true)).unwrap();
        assert!(page.starts_with("HTTP/1.1 404 Not Found\r\n"), "{page}");
        assert!(page.contains("\r\nX-Content-Type-Options: nosniff\r\n"));
        assert!(page.contains("\r\nContent-Security-Policy: default-src 'none'"));
        assert!(page.ends_with("\r\n\r\nnot found"));
        let head = String::from_utf8(response_bytes(&Answer::text(200, "body"), false)).unwrap();
        assert!(head.contains("Content-Length: 4\r\n") && head.ends_with("\r\n\r\n"));
    }

    #[test]
    fn the_page_carries_the_import_maps_nonce() {
        assert_eq!(INDEX_HTML.matches(IMPORT_MAP_TAG).count(), 1);
        assert_eq!(
            INDEX_HTML.matches("<script").count(),
            2,
            "one inline script only"
        );
    }
}
