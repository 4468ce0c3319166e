//! The designer page's files as the router serves them; the binary compiles
//! them in (`crates/ecam-cli/web/`) and hands them over, so this crate reads
//! no files of another.

/// One file of the page.
#[derive(Clone, Copy, Debug)]
pub struct Asset {
    /// Path the page asks for (`/app.js`).
    pub path: &'static str,
    /// `Content-Type` it is served with.
    pub content_type: &'static str,
    /// The file itself.
    pub body: &'static str,
}

/// The whole page: its start and every file, by the path it is served at.
#[derive(Clone, Copy, Debug)]
pub struct Page {
    /// Served at `/` (and at its own path, as one of `files`).
    pub index: Asset,
    /// Every file of the page.
    pub files: &'static [Asset],
}
