//! Tables of words kept as data (`data/*.toml`, embedded at build time), and the error a
//! malformed table gives: it names the file, the table and the entry.

use std::fmt;

use serde::de::DeserializeOwned;

/// What is wrong with a data file, and where.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct DataFileError {
    /// The file, as the crate names it (`data/phrases.toml`).
    pub file: &'static str,
    /// The table and entry ("bank `turn`, entry 3 (\"turn {dir\")"); empty for the whole file.
    pub place: String,
    /// What is wrong.
    pub message: String,
}

impl DataFileError {
    /// An error at `place` in `file`.
    pub(crate) fn new(
        file: &'static str,
        place: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Self {
            file,
            place: place.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for DataFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.place.is_empty() {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}: {}: {}", self.file, self.place, self.message)
        }
    }
}

impl std::error::Error for DataFileError {}

/// Parse a TOML data file.
pub(crate) fn parse_toml<T: DeserializeOwned>(
    file: &'static str,
    text: &str,
) -> Result<T, DataFileError> {
    toml::from_str(text)
        .map_err(|e| DataFileError::new(file, "", format!("not a valid table: {e}")))
}

/// Where an entry is, for an error: "bank `x`, entry 3 (\"...\")" (entries count from 0, as
/// the code indexes them).
pub(crate) fn entry_place(kind: &str, table: &str, index: usize, entry: &str) -> String {
    format!("{kind} `{table}`, entry {index} ({entry:?})")
}

/// The embedded data of this crate is a build-time constant: a malformed file is a bug of the
/// build, caught by the unit tests, so loading it panics with the error instead of returning
/// it.
pub(crate) fn expect_embedded<T>(r: Result<T, DataFileError>) -> T {
    r.unwrap_or_else(|e| panic!("embedded data is malformed: {e}"))
}
