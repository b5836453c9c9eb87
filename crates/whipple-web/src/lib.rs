//! # whipple-web
//!
//! `whipple serve`: JBike6's window in the browser. A local web server that serves one page
//! (a bike picker, a parameter editor, the side view, eigenvalues against speed) and the JSON
//! API the page uses, described by the OpenAPI 3 document at `/api/openapi.json`.
//!
//! The page is bundled at build time (see `build.rs`) and embedded in the binary, so serving it
//! needs nothing at run time. Every answer is computed by the `whipple` library; CPU-heavy
//! requests run on the blocking pool, a bounded number at a time, under [`Limits`]: heavy work
//! (maps, studies, simulations, long sweeps) and interactive work (validating, converting,
//! critical speeds, short sweeps) each within its own budget, so that the page's small
//! requests are never queued behind maps.
//!
//! Only requests addressed to this server are answered (Host `127.0.0.1`, `localhost`,
//! `[::1]` or the bound address, else 421), state-changing ones only from its own page or
//! from clients that send no Origin (else 403), and bodies only as `application/json` (else
//! 415): a page on another site cannot drive it.
//!
//! ```no_run
//! use whipple_web::{run, ServeOptions};
//! // Serves http://127.0.0.1:8080 until Ctrl-C.
//! run(ServeOptions { port: 8080, ..ServeOptions::default() })?;
//! # Ok::<(), whipple_web::ServeError>(())
//! ```
#![warn(missing_docs)]
// Without the feature `all-routes` (the static site's first module) only the first view's
// endpoints are compiled in: the other handlers are left unused, on purpose.
#![cfg_attr(not(feature = "all-routes"), allow(dead_code, unused_imports))]

#[cfg(feature = "server")]
mod access;
mod api;
#[cfg(feature = "server")]
mod assets;
mod closed_loop;
#[cfg(feature = "server")]
mod connection;
mod design;
mod error;
mod frequency;
pub mod geometry;
mod measure;
pub mod modes;
mod ridden;
#[cfg(feature = "server")]
mod server;
pub mod simulation;
mod time;
mod turns;

use std::time::Duration;

#[cfg(feature = "server")]
pub use serve::{ServeError, ServeOptions, Server, run, serve};

pub use api::{Answer, OPENAPI, ProgressHook, answer, answer_with_progress, answers};
pub use error::{ApiError, ErrorBody};
#[cfg(feature = "server")]
pub use server::{app, app_bound_to};

/// Bounds that keep the server responsive whatever it is asked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest request body accepted, in bytes (default 1 MiB); larger bodies get 413.
    pub max_body_bytes: usize,
    /// Most speeds in one eigenvalue sweep (default 100,000); more get 422.
    pub max_speeds: usize,
    /// Longest simulated time of one simulation (default 30 s); longer gets 422.
    pub max_sim_duration: f64,
    /// Most integration steps of one simulation (default 100,000: 30 s with an RK4 step of
    /// 0.3 ms; about 20 MB of samples and 2–3 s of one core); an RK4 request needing more gets
    /// 422, an adaptive run stops there (outcome `step_limit`).
    pub max_sim_steps: usize,
    /// Longest time a whole request may take, reading the body included (default 30 s); then 408.
    pub request_timeout: Duration,
    /// Longest time one computation may run (default 10 s); then 503.
    pub compute_timeout: Duration,
    /// Longest wait for a free computing slot (default 10 s); then 503 `busy` with
    /// `Retry-After`.
    pub queue_timeout: Duration,
    /// Heavy computations (maps, studies, simulations, sensitivities, linear responses,
    /// sweeps of more than 2,000 speeds) run at once on the blocking pool (default: the number
    /// of CPUs, at least 2).
    pub max_concurrent_computations: usize,
    /// Heavy requests that may wait for a slot when all are taken (default 8); one more gets
    /// 503 `busy` with `Retry-After` at once.
    pub max_waiting_heavy: usize,
    /// Interactive computations (validate, convert, parse, critical speeds, modes, turns,
    /// sweeps of up to 2,000 speeds) run at once, in slots of their own that heavy work never
    /// takes (default: the number of CPUs, at least 2).
    pub max_interactive_computations: usize,
    /// Longest time a client may take to send a request's headers, from the moment the
    /// server waits for them (default 10 s); then the connection is closed. Guards against a
    /// client that trickles a byte at a time to hold a connection.
    pub header_timeout: Duration,
    /// Longest time a connection may go without a byte read or written (default 60 s, longer
    /// than any request may take); then it is closed. Guards against clients that stop reading.
    pub idle_timeout: Duration,
    /// Connections served at once (default 256); further ones wait in the kernel's backlog
    /// until one closes.
    pub max_connections: usize,
    /// Most designs in one `/api/map` or `/api/study` request (default 250,000: a 500 × 500
    /// map, about 0.3 s on two cores); more get 422.
    pub max_designs: usize,
}

impl Default for Limits {
    fn default() -> Self {
        let cpus = std::thread::available_parallelism()
            .map_or(2, |n| n.get())
            .max(2);
        Limits {
            max_body_bytes: 1 << 20,
            max_speeds: 100_000,
            max_sim_duration: 30.0,
            max_sim_steps: 100_000,
            request_timeout: Duration::from_secs(30),
            compute_timeout: Duration::from_secs(10),
            queue_timeout: Duration::from_secs(10),
            max_concurrent_computations: cpus,
            max_waiting_heavy: 8,
            max_interactive_computations: cpus,
            header_timeout: Duration::from_secs(10),
            idle_timeout: Duration::from_secs(60),
            max_connections: 256,
            max_designs: 250_000,
        }
    }
}

/// `whipple serve`'s options, server and entry points.
#[cfg(feature = "server")]
mod serve {
    use std::future::Future;
    use std::net::{IpAddr, Ipv4Addr, SocketAddr};

    use crate::{Limits, connection};

    /// Where and how to serve.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct ServeOptions {
        /// Address to listen on (default 127.0.0.1, reachable from this machine only).
        pub address: IpAddr,
        /// Port to listen on (default 8080; 0 picks a free one).
        pub port: u16,
        /// Open the page in the system's browser once listening (default false).
        pub open: bool,
        /// Bounds on requests (see [`Limits`]).
        pub limits: Limits,
    }

    impl Default for ServeOptions {
        fn default() -> Self {
            ServeOptions {
                address: IpAddr::V4(Ipv4Addr::LOCALHOST),
                port: 8080,
                open: false,
                limits: Limits::default(),
            }
        }
    }

    /// What can stop the server.
    #[derive(Debug, thiserror::Error)]
    #[non_exhaustive]
    pub enum ServeError {
        /// The address could not be bound (in use, not local, not permitted).
        #[error("cannot listen on {address}")]
        Bind {
            /// The address asked for.
            address: SocketAddr,
            /// Why.
            source: std::io::Error,
        },
        /// The async runtime could not be started.
        #[error("cannot start the async runtime")]
        Runtime(#[source] std::io::Error),
        /// Serving failed after start.
        #[error("the server failed")]
        Serve(#[source] std::io::Error),
    }

    /// A bound, not yet serving, server: bind first to learn the port (for `port: 0`).
    #[derive(Debug)]
    pub struct Server {
        listener: tokio::net::TcpListener,
        limits: Limits,
        address: SocketAddr,
    }

    impl Server {
        /// Binds the listening socket.
        pub async fn bind(options: &ServeOptions) -> Result<Server, ServeError> {
            let wanted = SocketAddr::new(options.address, options.port);
            let listener = tokio::net::TcpListener::bind(wanted)
                .await
                .map_err(|source| ServeError::Bind {
                    address: wanted,
                    source,
                })?;
            let address = listener.local_addr().map_err(|source| ServeError::Bind {
                address: wanted,
                source,
            })?;
            Ok(Server {
                listener,
                limits: options.limits,
                address,
            })
        }

        /// The address actually bound.
        pub fn local_addr(&self) -> SocketAddr {
            self.address
        }

        /// The page's address, `http://IP:PORT/`.
        pub fn url(&self) -> String {
            format!("http://{}/", self.address)
        }

        /// Serves until `shutdown` completes, then finishes the requests under way (for at most
        /// the request timeout). Each connection is bounded by [`Limits::header_timeout`] and
        /// [`Limits::idle_timeout`], and at most [`Limits::max_connections`] are served at once.
        pub async fn serve_until(
            self,
            shutdown: impl Future<Output = ()> + Send + 'static,
        ) -> Result<(), ServeError> {
            connection::serve(self.listener, self.limits, self.address.ip(), shutdown).await;
            Ok(())
        }
    }

    /// Binds, says where on standard error, opens the browser when asked, and serves until Ctrl-C.
    pub async fn serve(options: ServeOptions) -> Result<(), ServeError> {
        let server = Server::bind(&options).await?;
        let url = server.url();
        eprintln!("whipple serve: the page is at {url} (Ctrl-C to stop)");
        if !options.address.is_loopback() {
            eprintln!(
                "whipple serve: warning: listening on {}, which other machines may reach",
                options.address
            );
        }
        if options.address.is_unspecified() {
            eprintln!(
                "whipple serve: note: requests are answered only when addressed to 127.0.0.1, \
             localhost, [::1] or {} itself (Host header); to serve other machines, give this \
             machine's own address with --address",
                options.address
            );
        }
        if options.open {
            open_browser(&url);
        }
        server
            .serve_until(async {
                // If Ctrl-C cannot be listened for, serve until killed.
                if tokio::signal::ctrl_c().await.is_err() {
                    std::future::pending::<()>().await;
                }
            })
            .await
    }

    /// [`serve`] on a new multi-threaded runtime, blocking until Ctrl-C.
    pub fn run(options: ServeOptions) -> Result<(), ServeError> {
        tokio::runtime::Builder::new_multi_thread()
            .enable_all()
            .build()
            .map_err(ServeError::Runtime)?
            .block_on(serve(options))
    }

    /// Asks the desktop to open `url`; reports on standard error when it cannot.
    fn open_browser(url: &str) {
        let mut command = if cfg!(target_os = "macos") {
            std::process::Command::new("open")
        } else if cfg!(windows) {
            let mut c = std::process::Command::new("cmd");
            c.args(["/C", "start", ""]);
            c
        } else {
            std::process::Command::new("xdg-open")
        };
        command
            .arg(url)
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null());
        match command.spawn() {
            // Reap the opener when it exits, so that it leaves no zombie behind.
            Ok(mut child) => {
                std::thread::spawn(move || child.wait());
            }
            Err(e) => {
                eprintln!("whipple serve: could not open a browser ({e}); open {url} yourself")
            }
        }
    }
}
