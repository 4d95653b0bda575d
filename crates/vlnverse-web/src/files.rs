//! Paths from requests, resolved only inside the folders the server was started with.
//!
//! A request path is split on `/` after percent-decoding (the router decodes, so `..%2f` arrives
//! as `../`); any `..`, `.`, empty, absolute or drive-prefixed component is refused before the
//! file system is touched, and the resolved file must canonicalise to a path under the root (a
//! symbolic link pointing outside is refused too).

use std::path::{Component, Path, PathBuf};

use crate::error::{ApiError, ApiResult};

/// `root/rel` when `rel` names a file inside `root` (itself canonical), else a 403 or 404 error.
pub fn resolve_inside(root: &Path, rel: &str) -> ApiResult<PathBuf> {
    let refuse = || {
        ApiError::forbidden(format!(
            "path `{rel}` is outside the served folder (no `..`, absolute or empty components)"
        ))
    };
    if rel.is_empty() || rel.contains('\\') || rel.contains('\0') {
        return Err(refuse());
    }
    let mut out = root.to_path_buf();
    for part in rel.split('/') {
        let mut comps = Path::new(part).components();
        match (comps.next(), comps.next()) {
            (Some(Component::Normal(c)), None) => out.push(c),
            _ => return Err(refuse()),
        }
    }
    let canonical = out
        .canonicalize()
        .map_err(|_| ApiError::not_found(format!("no file `{rel}`")))?;
    if !canonical.starts_with(root) {
        return Err(refuse());
    }
    if !canonical.is_file() {
        return Err(ApiError::not_found(format!("`{rel}` is not a file")));
    }
    Ok(canonical)
}

/// Content type of a served file, by extension.
pub fn content_type(path: &Path) -> &'static str {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("png") => "image/png",
        Some("jpg" | "jpeg") => "image/jpeg",
        Some("json") => "application/json",
        Some("jsonl") => "application/x-ndjson",
        Some("csv") => "text/csv; charset=utf-8",
        Some("md" | "txt" | "yaml" | "pgm") => "text/plain; charset=utf-8",
        Some("html") => "text/html; charset=utf-8",
        _ => "application/octet-stream",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_traversal_and_accepts_inner_files() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path().join("root");
        std::fs::create_dir_all(root.join("a")).unwrap();
        std::fs::write(root.join("a/b.txt"), "x").unwrap();
        std::fs::write(dir.path().join("secret.txt"), "s").unwrap();
        let root = root.canonicalize().unwrap();
        assert!(resolve_inside(&root, "a/b.txt").is_ok());
        for bad in [
            "../secret.txt",
            "a/../../secret.txt",
            "/etc/passwd",
            "a//b.txt",
            "./a/b.txt",
            "",
        ] {
            let e = resolve_inside(&root, bad).unwrap_err();
            assert_eq!(e.status, axum::http::StatusCode::FORBIDDEN, "{bad}");
        }
        assert_eq!(
            resolve_inside(&root, "a/missing.txt").unwrap_err().status,
            axum::http::StatusCode::NOT_FOUND
        );
    }
}
