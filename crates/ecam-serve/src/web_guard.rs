//! Who may talk to the HTTP face. The threat model is a page in the
//! operator's browser (or a rebinding DNS name) sending requests to a
//! server on the operator's machine (`docs/modbus.md`, "Web safety"): a
//! write there moves a machine. Sans-IO: the server hands over what a
//! request's headers say ([`RequestFacts`]) and answers the [`Refusal`].

use std::fmt;
use std::net::SocketAddr;
use std::path::Path;

use ecam_core::excerpt::excerpt;

/// Shortest token `--token-file` may hold.
pub const MIN_TOKEN_LEN: usize = 16;

/// The hosts and the token the HTTP face accepts.
#[derive(Clone, Debug)]
pub struct Access {
    /// `Host` header values accepted (`name` or `name:port`).
    hosts: Vec<String>,
    /// A token writes must present as `Authorization: Bearer TOKEN`.
    token: Option<String>,
}

/// What the guard looks at in a request.
#[derive(Clone, Copy, Debug, Default)]
pub struct RequestFacts<'a> {
    /// GET or HEAD: a read, which needs no token and no JSON body.
    pub read: bool,
    /// The `Host` header ("" when missing or not text).
    pub host: &'a str,
    /// The `Origin` header, when there is one ("" when not text).
    pub origin: Option<&'a str>,
    /// The `Content-Type` header.
    pub content_type: Option<&'a str>,
    /// The `Authorization` header.
    pub authorization: Option<&'a str>,
}

/// A request the guard refuses: the HTTP status and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    /// 421, 403, 415 or 401.
    pub status: u16,
    /// What is refused, in the server's words.
    pub message: String,
}

impl Access {
    /// Accepts the bound address, `localhost` and `127.0.0.1` at its port,
    /// and `names` (as given, or with the port); writes need `token` when
    /// one is given.
    pub fn new(bound: SocketAddr, names: &[String], token: Option<String>) -> Self {
        let port = bound.port();
        let mut hosts = vec![
            bound.to_string(),
            format!("localhost:{port}"),
            format!("127.0.0.1:{port}"),
            format!("[::1]:{port}"),
        ];
        for name in names {
            hosts.push(name.clone());
            hosts.push(format!("{name}:{port}"));
        }
        Self { hosts, token }
    }

    fn host_allowed(&self, host: &str) -> bool {
        self.hosts.iter().any(|h| h.eq_ignore_ascii_case(host))
    }

    /// Refuses requests for another host (DNS rebinding, 421), from a
    /// foreign page (`Origin`, 403), writes that are not JSON (a
    /// cross-site form or `text/plain` post, 415), and writes without the
    /// token when one is set (401).
    ///
    /// # Errors
    /// The [`Refusal`] to answer.
    pub fn check(&self, request: &RequestFacts<'_>) -> Result<(), Refusal> {
        let refuse = |status, message: String| Err(Refusal { status, message });
        if !self.host_allowed(request.host) {
            return refuse(
                421,
                format!(
                    "Host `{}` is not a name this server answers to (names are added when \
                     the server starts: docs/modbus.md, Web safety)",
                    excerpt(request.host)
                ),
            );
        }
        if let Some(origin) = request.origin {
            let own = origin
                .strip_prefix("http://")
                .or_else(|| origin.strip_prefix("https://"))
                .is_some_and(|o| self.host_allowed(o));
            if !own {
                let origin = excerpt(origin);
                return refuse(
                    403,
                    format!("requests from pages of `{origin}` are refused"),
                );
            }
        }
        if request.read {
            return Ok(());
        }
        let json = request.content_type.is_some_and(|c| {
            c.trim()
                .to_ascii_lowercase()
                .starts_with("application/json")
        });
        if !json {
            return refuse(415, "writes need Content-Type: application/json".into());
        }
        if let Some(token) = &self.token {
            let given = request
                .authorization
                .and_then(|a| a.strip_prefix("Bearer "));
            if given != Some(token.as_str()) {
                return refuse(
                    401,
                    "writes need the server's token: Authorization: Bearer TOKEN".into(),
                );
            }
        }
        Ok(())
    }
}

/// A token file that cannot be used.
#[derive(Debug)]
pub enum TokenError {
    /// The file cannot be read.
    Read(std::io::Error),
    /// The token is shorter than [`MIN_TOKEN_LEN`].
    TooShort,
}

impl fmt::Display for TokenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read(e) => write!(f, "{e}"),
            Self::TooShort => write!(f, "the token must be at least {MIN_TOKEN_LEN} characters"),
        }
    }
}

impl std::error::Error for TokenError {}

/// The token in `path` (surrounding white space dropped).
///
/// # Errors
/// An unreadable file, or a token shorter than [`MIN_TOKEN_LEN`].
pub fn read_token(path: &Path) -> Result<String, TokenError> {
    let text = std::fs::read_to_string(path).map_err(TokenError::Read)?;
    let token = text.trim().to_string();
    if token.len() < MIN_TOKEN_LEN {
        return Err(TokenError::TooShort);
    }
    Ok(token)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn access(token: Option<&str>) -> Access {
        let bound = "127.0.0.1:8080".parse().unwrap();
        Access::new(bound, &["plc.local".into()], token.map(String::from))
    }

    #[test]
    fn foreign_hosts_pages_and_non_json_writes_are_refused() {
        let a = access(None);
        let read = RequestFacts {
            read: true,
            host: "localhost:8080",
            ..RequestFacts::default()
        };
        assert_eq!(a.check(&read), Ok(()));
        let rebinding = RequestFacts {
            host: "evil.example",
            ..read
        };
        assert_eq!(a.check(&rebinding).unwrap_err().status, 421);
        let foreign = RequestFacts {
            origin: Some("http://evil.example"),
            ..read
        };
        assert_eq!(a.check(&foreign).unwrap_err().status, 403);
        let own = RequestFacts {
            origin: Some("http://PLC.local:8080"),
            ..read
        };
        assert_eq!(a.check(&own), Ok(()));
        let form = RequestFacts {
            read: false,
            content_type: Some("text/plain"),
            ..read
        };
        assert_eq!(a.check(&form).unwrap_err().status, 415);
        let json = RequestFacts {
            content_type: Some(" Application/JSON; charset=utf-8"),
            ..form
        };
        assert_eq!(a.check(&json), Ok(()));
        let guarded = access(Some("0123456789abcdef"));
        assert_eq!(guarded.check(&json).unwrap_err().status, 401);
        let with = RequestFacts {
            authorization: Some("Bearer 0123456789abcdef"),
            ..json
        };
        assert_eq!(guarded.check(&with), Ok(()));
        let message = a.check(&rebinding).unwrap_err().message;
        assert!(!message.contains("--"), "{message}");
    }
}
