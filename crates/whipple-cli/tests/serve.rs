//! `whipple serve`, run as a user runs it: it says where the page is, answers there on
//! loopback, and refuses a port already taken.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

type TestResult = Result<(), Box<dyn std::error::Error>>;

/// Kills the server however the test ends.
struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn get(address: &str, path: &str) -> Result<String, Box<dyn std::error::Error>> {
    let mut stream = TcpStream::connect(address)?;
    stream.set_read_timeout(Some(Duration::from_secs(20)))?;
    write!(
        stream,
        "GET {path} HTTP/1.1\r\nHost: {address}\r\nConnection: close\r\n\r\n"
    )?;
    let mut response = String::new();
    stream.read_to_string(&mut response)?;
    Ok(response)
}

#[test]
fn serve_answers_on_loopback() -> TestResult {
    let child = Command::new(env!("CARGO_BIN_EXE_whipple"))
        .args(["serve", "--port", "0"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()?;
    let mut server = Running(child);
    let stderr = server.0.stderr.take().ok_or("no stderr")?;
    let mut line = String::new();
    BufReader::new(stderr).read_line(&mut line)?;
    // "whipple serve: the page is at http://127.0.0.1:PORT/ (Ctrl-C to stop)"
    let address = line
        .split("http://")
        .nth(1)
        .and_then(|rest| rest.split('/').next())
        .ok_or_else(|| format!("no address in {line:?}"))?
        .to_string();
    assert!(address.starts_with("127.0.0.1:"), "{line}");
    let health = get(&address, "/api/health")?;
    assert!(health.starts_with("HTTP/1.1 200"), "{health}");
    assert!(health.contains("\"status\":\"ok\""), "{health}");
    let page = get(&address, "/")?;
    assert!(page.contains("<title>whipple"), "{page}");

    // A second server on the same port fails with a clear message.
    let port = address.rsplit(':').next().ok_or("no port")?;
    let second = Command::new(env!("CARGO_BIN_EXE_whipple"))
        .args(["serve", "--port", port])
        .output()?;
    assert!(!second.status.success());
    let message = String::from_utf8_lossy(&second.stderr);
    assert!(message.contains("cannot listen on 127.0.0.1:"), "{message}");
    Ok(())
}
