//! Things of different classes that people name as one group when they pass them together
//! ("the exercise equipment on your left", "the kitchen appliances"): `data/groups.toml`.

use std::sync::LazyLock;

use serde::Deserialize;
use vlnverse_env::SemanticClass as C;

use crate::data::{entry_place, expect_embedded, parse_toml, DataFileError};

/// The groups file, as errors name it.
const GROUPS_FILE: &str = "data/groups.toml";

/// A kind of thing whose members are named together: its classes and what a group is called.
#[derive(Debug)]
pub(crate) struct Kind {
    classes: Vec<C>,
    /// Names of a group, each true of any mix of the classes.
    pub names: Vec<String>,
    /// Whether the names are mass nouns ("equipment is"), not plurals.
    pub mass: bool,
}

/// `data/groups.toml` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct GroupFile {
    kind: Vec<KindEntry>,
}

/// One `[[kind]]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct KindEntry {
    classes: Vec<String>,
    names: Vec<String>,
    mass: bool,
}

/// Parse and check a groups file: known classes, each in one kind at most, at least two
/// classes and one name a kind.
fn parse_groups(file: &'static str, text: &str) -> Result<Vec<Kind>, DataFileError> {
    let parsed: GroupFile = parse_toml(file, text)?;
    let mut kinds: Vec<Kind> = Vec::new();
    for (i, k) in parsed.kind.iter().enumerate() {
        let at = |what: &str, j: usize, v: &str| entry_place(&format!("kind {i}"), what, j, v);
        if k.classes.len() < 2 {
            return Err(DataFileError::new(
                file,
                format!("kind {i}"),
                "a group needs at least two classes",
            ));
        }
        if k.names.is_empty() || k.names.iter().any(|n| n.trim().is_empty()) {
            return Err(DataFileError::new(
                file,
                format!("kind {i}"),
                "names: none, or a blank one",
            ));
        }
        let mut classes = Vec::new();
        for (j, name) in k.classes.iter().enumerate() {
            let Some(c) = C::from_name(name) else {
                return Err(DataFileError::new(
                    file,
                    at("classes", j, name),
                    "no such class",
                ));
            };
            if kinds.iter().any(|o| o.classes.contains(&c)) || classes.contains(&c) {
                return Err(DataFileError::new(
                    file,
                    at("classes", j, name),
                    "already in a kind (a class belongs to one kind at most)",
                ));
            }
            classes.push(c);
        }
        kinds.push(Kind {
            classes,
            names: k.names.clone(),
            mass: k.mass,
        });
    }
    Ok(kinds)
}

/// The kinds, parsed and checked once.
static KINDS: LazyLock<Vec<Kind>> = LazyLock::new(|| {
    expect_embedded(parse_groups(
        GROUPS_FILE,
        include_str!("../data/groups.toml"),
    ))
});

/// The kind `class` belongs to, if any.
pub(crate) fn kind_of(class: C) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.classes.contains(&class))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_groups_parse_and_a_class_has_one_kind() {
        let k = kind_of(C::Treadmill).expect("treadmills are exercise equipment");
        assert!(k.mass && k.names.iter().any(|n| n == "exercise equipment"));
        assert!(std::ptr::eq(k, kind_of(C::Elliptical).unwrap()));
        assert!(!kind_of(C::Fridge).unwrap().mass);
        assert!(kind_of(C::Bed).is_none());
    }

    #[test]
    fn a_malformed_groups_file_names_the_kind_and_entry() {
        let one = "[[kind]]\nclasses = [\"bed\"]\nnames = [\"beds\"]\nmass = false\n";
        let e = parse_groups("g.toml", one).unwrap_err().to_string();
        assert!(
            e.contains("g.toml: kind 0") && e.contains("two classes"),
            "{e}"
        );
        let unknown = "[[kind]]\nclasses = [\"bed\", \"unicorn\"]\nnames = [\"x\"]\nmass = false\n";
        let e = parse_groups("g.toml", unknown).unwrap_err().to_string();
        assert!(
            e.contains("\"unicorn\"") && e.contains("no such class"),
            "{e}"
        );
        let twice = "[[kind]]\nclasses = [\"bed\", \"crib\"]\nnames = [\"x\"]\nmass = false\n\
                     [[kind]]\nclasses = [\"crib\", \"sofa\"]\nnames = [\"y\"]\nmass = false\n";
        let e = parse_groups("g.toml", twice).unwrap_err().to_string();
        assert!(
            e.contains("kind 1") && e.contains("already in a kind"),
            "{e}"
        );
        let blank = "[[kind]]\nclasses = [\"bed\", \"crib\"]\nnames = [\" \"]\nmass = false\n";
        assert!(parse_groups("g.toml", blank).is_err());
    }
}
