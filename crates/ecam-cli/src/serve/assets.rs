//! The designer page's files, compiled into the binary: `ecam serve` works
//! from any directory, `cargo install` and the packaged crate carry the page,
//! and nothing is fetched from the network when it is shown (uPlot is
//! vendored, see `web/README.md`).

pub use ecam_serve::net::page::{Asset, Page};

macro_rules! web_file {
    ($name:literal) => {
        include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/web/", $name))
    };
}

const HTML: &str = "text/html; charset=utf-8";
const JS: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";
const TEXT: &str = "text/plain; charset=utf-8";

/// The page's start: served at `/` and `/index.html`.
pub const INDEX: Asset = Asset {
    path: "/index.html",
    content_type: HTML,
    body: web_file!("index.html"),
};

/// Every file of the page, by the path it is served at.
pub const ASSETS: &[Asset] = &[
    INDEX,
    Asset {
        path: "/app.js",
        content_type: JS,
        body: web_file!("app.js"),
    },
    Asset {
        path: "/segments.js",
        content_type: JS,
        body: web_file!("segments.js"),
    },
    Asset {
        path: "/plots.js",
        content_type: JS,
        body: web_file!("plots.js"),
    },
    Asset {
        path: "/style.css",
        content_type: CSS,
        body: web_file!("style.css"),
    },
    Asset {
        path: "/vendor/uplot/uPlot.iife.min.js",
        content_type: JS,
        body: web_file!("vendor/uplot/uPlot.iife.min.js"),
    },
    Asset {
        path: "/vendor/uplot/uPlot.min.css",
        content_type: CSS,
        body: web_file!("vendor/uplot/uPlot.min.css"),
    },
    // The licence travels with the code it covers, also when served.
    Asset {
        path: "/vendor/uplot/LICENSE",
        content_type: TEXT,
        body: web_file!("vendor/uplot/LICENSE"),
    },
];

/// The page as the router serves it.
pub const PAGE: Page = Page {
    index: INDEX,
    files: ASSETS,
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_path_is_served_once_and_the_index_is_the_page() {
        for (i, a) in ASSETS.iter().enumerate() {
            assert!(a.path.starts_with('/'), "{}", a.path);
            assert!(!a.body.is_empty(), "{}", a.path);
            assert!(
                ASSETS[i + 1..].iter().all(|b| b.path != a.path),
                "{} twice",
                a.path
            );
        }
        assert!(INDEX.body.contains("<script src=\"app.js\""));
    }
}
