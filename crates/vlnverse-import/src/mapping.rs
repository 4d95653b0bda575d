//! Mapping files: ordered regular-expression rules from node, mesh or material names to
//! semantic classes and physical overrides.

use crate::raw::RawLabel;
use regex::Regex;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use vlnverse_env::{EnvError, Motion, Result, SemanticClass};

/// Which name a rule is matched against.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MatchOn {
    /// Node, mesh or material name (the first that matches).
    #[default]
    Any,
    /// glTF node name (OBJ: object/group name).
    Node,
    /// glTF mesh name.
    Mesh,
    /// Material name (glTF material, OBJ `usemtl`).
    Material,
}

/// One rule as written in the TOML file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RuleFile {
    pattern: String,
    class: Option<String>,
    #[serde(default, rename = "match")]
    match_on: MatchOn,
    motion: Option<Motion>,
    mass: Option<f32>,
    friction: Option<f32>,
    color: Option<String>,
    material: Option<String>,
    #[serde(default)]
    drop: bool,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MappingFile {
    #[serde(default, rename = "rule")]
    rules: Vec<RuleFile>,
}

/// A compiled rule.
#[derive(Clone, Debug)]
pub struct Rule {
    /// The regular expression (unanchored unless the pattern anchors itself).
    pub pattern: Regex,
    /// Which names it applies to.
    pub match_on: MatchOn,
    /// What a match assigns.
    pub label: RawLabel,
}

/// An ordered list of rules; the first matching rule wins.
///
/// File format (TOML):
///
/// ```toml
/// [[rule]]
/// pattern = "^Bed_"          # regular expression (Rust `regex` syntax)
/// class = "bed"              # a SemanticClass name
/// match = "node"             # any (default) | node | mesh | material
/// motion = "dynamic"         # optional: static (default) | dynamic
/// mass = 40.0                # optional override (kg), in [0, 10000]
/// friction = 0.6             # optional override, in [0, 10]
/// color = "white"            # optional colour word
/// material = "wood"          # optional material word
///
/// [[rule]]
/// pattern = "^Grass"
/// drop = true                # leave this geometry out of the scene
/// ```
#[derive(Clone, Debug, Default)]
pub struct Mapping {
    /// Rules in file order.
    pub rules: Vec<Rule>,
    /// Where the rules came from (for messages).
    pub source: Option<PathBuf>,
}

const BUILTIN: &str = include_str!("builtin_mapping.toml");

/// Largest `mass` a rule may set (kg).
pub const MAX_MASS: f32 = 10_000.0;
/// Largest `friction` a rule may set (Coulomb coefficient).
pub const MAX_FRICTION: f32 = 10.0;

impl Mapping {
    /// Parse a mapping from TOML text; `path` is only used in error messages.
    pub fn from_toml(text: &str, path: &Path) -> Result<Mapping> {
        let file: MappingFile =
            toml::from_str(text).map_err(|e| EnvError::parse(path, e.to_string()))?;
        let mut rules = Vec::with_capacity(file.rules.len());
        for (i, r) in file.rules.into_iter().enumerate() {
            let pattern = Regex::new(&r.pattern).map_err(|e| {
                EnvError::invalid(format!("rule[{i}].pattern"), &r.pattern, e.to_string())
                    .in_file(path)
            })?;
            let class = match &r.class {
                Some(c) => Some(SemanticClass::from_name(c).ok_or_else(|| {
                    EnvError::invalid(
                        format!("rule[{i}].class"),
                        c,
                        "not a semantic class name (see docs/formats.md)",
                    )
                    .in_file(path)
                })?),
                None if r.drop => None,
                None => {
                    return Err(EnvError::invalid(
                        format!("rule[{i}].class"),
                        "(missing)",
                        "a rule needs `class` unless it has `drop = true`",
                    )
                    .in_file(path))
                }
            };
            for (field, v, max) in [
                ("mass", r.mass, MAX_MASS),
                ("friction", r.friction, MAX_FRICTION),
            ] {
                if let Some(v) = v {
                    if !(v.is_finite() && (0.0..=max).contains(&v)) {
                        return Err(EnvError::invalid(
                            format!("rule[{i}].{field}"),
                            v,
                            format!("must be in [0, {max}]"),
                        )
                        .in_file(path));
                    }
                }
            }
            rules.push(Rule {
                pattern,
                match_on: r.match_on,
                label: RawLabel {
                    class,
                    motion: r.motion,
                    mass: r.mass,
                    friction: r.friction,
                    color: r.color,
                    material: r.material,
                    drop: r.drop,
                },
            });
        }
        Ok(Mapping {
            rules,
            source: Some(path.to_path_buf()),
        })
    }

    /// Load a mapping file.
    pub fn load(path: &Path) -> Result<Mapping> {
        let text = std::fs::read_to_string(path).map_err(|e| EnvError::io(path, e))?;
        Self::from_toml(&text, path)
    }

    /// The generic English rules used when no mapping file is given (`wall`, `floor`, `bed`,
    /// `sofa`, ... anywhere in a name).
    pub fn builtin() -> Mapping {
        let mut m = Self::from_toml(BUILTIN, Path::new("<builtin mapping>"))
            .expect("the built-in mapping is valid (checked by a test)");
        m.source = None;
        m
    }

    /// First rule matching `name` as the given kind of name.
    pub fn lookup(&self, name: &str, kind: MatchOn) -> Option<&RawLabel> {
        self.rules
            .iter()
            .find(|r| {
                (r.match_on == MatchOn::Any || r.match_on == kind) && r.pattern.is_match(name)
            })
            .map(|r| &r.label)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_mapping_parses_and_matches() {
        let m = Mapping::builtin();
        assert!(m.rules.len() > 20);
        let l = m.lookup("Wall_north", MatchOn::Node).unwrap();
        assert_eq!(l.class, Some(SemanticClass::Wall));
        let l = m.lookup("my_sofa.001", MatchOn::Mesh).unwrap();
        assert_eq!(l.class, Some(SemanticClass::Sofa));
        assert!(m.lookup("Cube.003", MatchOn::Node).is_none());
    }

    #[test]
    fn bad_rules_name_the_field_and_value() {
        let p = Path::new("m.toml");
        let e = Mapping::from_toml("[[rule]]\npattern = \"(\"\nclass = \"bed\"\n", p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("m.toml") && e.contains("rule[0].pattern"), "{e}");
        let e = Mapping::from_toml("[[rule]]\npattern = \"x\"\nclass = \"spaceship\"\n", p)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("rule[0].class") && e.contains("spaceship"),
            "{e}"
        );
        let e = Mapping::from_toml("[[rule]]\npattern = \"x\"\n", p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("rule[0].class"), "{e}");
    }

    #[test]
    fn mass_and_friction_out_of_range_are_refused_by_name() {
        let p = Path::new("m.toml");
        for (field, value) in [
            ("mass", "1e12"),
            ("mass", "-1.0"),
            ("mass", "nan"),
            ("friction", "1e6"),
            ("friction", "inf"),
        ] {
            let text = format!("[[rule]]\npattern = \"x\"\nclass = \"bed\"\n{field} = {value}\n");
            let e = Mapping::from_toml(&text, p).unwrap_err().to_string();
            assert!(
                e.contains("m.toml") && e.contains(&format!("rule[0].{field}")),
                "{field} = {value}: {e}"
            );
        }
        let ok = "[[rule]]\npattern = \"x\"\nclass = \"bed\"\nmass = 10000.0\nfriction = 0.0\n";
        assert!(Mapping::from_toml(ok, p).is_ok());
    }

    #[test]
    fn match_kind_restricts_rules() {
        let m = Mapping::from_toml(
            "[[rule]]\npattern = \"wood\"\nclass = \"floor\"\nmatch = \"material\"\n",
            Path::new("m.toml"),
        )
        .unwrap();
        assert!(m.lookup("wood", MatchOn::Node).is_none());
        assert!(m.lookup("wood", MatchOn::Material).is_some());
    }
}
