//! The local HTTP server: the page, its scripts, and the JSON it reads.

use std::net::SocketAddr;

use serde_json::{Value, json};

use super::{Kind, Target, ViewError};
use crate::creature::Creature;
use crate::lsystem::DeriveOptions;

const INDEX_HTML: &str = include_str!("assets/index.html");
const APP_JS: &str = include_str!("assets/app.js");
const THREE_MODULE: &str = include_str!("assets/three/three.module.min.js");
const THREE_CORE: &str = include_str!("assets/three/three.core.min.js");
const ORBIT_CONTROLS: &str = include_str!("assets/three/OrbitControls.js");
const THREE_LICENSE: &str = include_str!("assets/three/LICENSE");

/// Develops a run's individual `(generation, index)` into a creature, or says why not.
pub type Developer = Box<dyn Fn(u32, u32) -> Result<Creature, String> + Send + Sync>;

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
    http: tiny_http::Server,
    target: Target,
    options: DeriveOptions,
    steps: Option<u64>,
    developer: Option<Developer>,
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
        let http = match std::net::TcpListener::bind(("127.0.0.1", port)) {
            Ok(listener) => tiny_http::Server::from_listener(listener, None).map_err(|e| {
                ServerError::Listen {
                    port,
                    message: e.to_string(),
                }
            })?,
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
            http,
            target,
            options,
            steps,
            developer,
        })
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.http
            .server_addr()
            .to_ip()
            .unwrap_or_else(|| SocketAddr::from(([127, 0, 0, 1], 0)))
    }

    /// The page's address.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr())
    }

    /// Answers requests until the process ends.
    pub fn run(&self) {
        for request in self.http.incoming_requests() {
            let (status, content_type, body) = self.answer(request.url());
            let header = tiny_http::Header::from_bytes("Content-Type", content_type)
                .expect("a valid header");
            let no_cache =
                tiny_http::Header::from_bytes("Cache-Control", "no-store").expect("a valid header");
            let response = tiny_http::Response::from_data(body)
                .with_status_code(status)
                .with_header(header)
                .with_header(no_cache);
            // A browser that went away mid-answer is not our problem.
            let _ = request.respond(response);
        }
    }

    /// The status, content type and body for a request's URL.
    fn answer(&self, url: &str) -> (u16, &'static str, Vec<u8>) {
        let (path, query) = url.split_once('?').unwrap_or((url, ""));
        let js = "text/javascript; charset=utf-8";
        match path {
            "/" | "/index.html" => (200, "text/html; charset=utf-8", INDEX_HTML.into()),
            "/app.js" => (200, js, APP_JS.into()),
            "/three/three.module.min.js" => (200, js, THREE_MODULE.into()),
            "/three/three.core.min.js" => (200, js, THREE_CORE.into()),
            "/three/OrbitControls.js" => (200, js, ORBIT_CONTROLS.into()),
            "/three/LICENSE" => (200, "text/plain; charset=utf-8", THREE_LICENSE.into()),
            "/version" => (
                200,
                "text/plain; charset=utf-8",
                self.target.version().into(),
            ),
            "/data.json" => json_answer(self.data()),
            "/generation.json" => json_answer(
                number(query, "gen")
                    .ok_or_else(|| ViewError::BadFile("generation.json needs ?gen=G".into()))
                    .and_then(|g| {
                        if self.target.kind != Kind::Run {
                            return Err(ViewError::BadFile("not a run".into()));
                        }
                        super::run_generation_data(&self.target.path, g)
                    }),
            ),
            "/individual.json" => json_answer(self.individual(query)),
            _ => (404, "text/plain; charset=utf-8", b"not found".to_vec()),
        }
    }

    /// The page's data for the target, read afresh (so an edited file shows its changes).
    fn data(&self) -> Result<Value, ViewError> {
        let path = &self.target.path;
        match self.target.kind {
            Kind::Lsys => Ok(super::lsys_data(path, &self.options, self.steps)),
            Kind::Growth => super::growth_data(path),
            Kind::Recording => super::recording_data(path),
            Kind::Run => super::run_data(path),
        }
    }

    /// One of a run's individuals, developed.
    fn individual(&self, query: &str) -> Result<Value, ViewError> {
        let (Some(generation), Some(index)) = (number(query, "gen"), number(query, "index")) else {
            return Err(ViewError::BadFile(
                "individual.json needs ?gen=G&index=I".into(),
            ));
        };
        let developer = self
            .developer
            .as_ref()
            .filter(|_| self.target.kind == Kind::Run)
            .ok_or_else(|| ViewError::BadFile("not a run".into()))?;
        let creature = developer(generation, index).map_err(ViewError::BadFile)?;
        Ok(super::creature_data(
            &format!("generation {generation}, individual {index}"),
            &creature,
        ))
    }
}

/// A JSON answer: 200 with the value, or 500 with `{"error": {"message"}}`.
fn json_answer(value: Result<Value, ViewError>) -> (u16, &'static str, Vec<u8>) {
    let json_type = "application/json";
    match value {
        Ok(v) => (200, json_type, v.to_string().into_bytes()),
        Err(e) => (
            500,
            json_type,
            json!({ "error": { "message": e.to_string() } })
                .to_string()
                .into_bytes(),
        ),
    }
}

/// The unsigned number `key` in a query string.
fn number(query: &str, key: &str) -> Option<u32> {
    query
        .split('&')
        .filter_map(|pair| pair.split_once('='))
        .find(|(k, _)| *k == key)
        .and_then(|(_, v)| v.parse().ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_numbers_are_read_by_name() {
        assert_eq!(number("gen=3&index=14", "index"), Some(14));
        assert_eq!(number("gen=3&index=14", "gen"), Some(3));
        assert_eq!(number("gen=x", "gen"), None);
        assert_eq!(number("", "gen"), None);
    }
}
