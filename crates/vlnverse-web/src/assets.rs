//! The page's files, embedded in the binary (no build step, no network).

/// Bytes and content type of an asset by name.
pub fn get(name: &str) -> Option<(&'static [u8], &'static str)> {
    match name {
        "index.html" => Some((
            include_bytes!("../assets/index.html"),
            "text/html; charset=utf-8",
        )),
        "app.js" => Some((
            include_bytes!("../assets/app.js"),
            "text/javascript; charset=utf-8",
        )),
        "app.css" => Some((
            include_bytes!("../assets/app.css"),
            "text/css; charset=utf-8",
        )),
        _ => None,
    }
}
