//! Motifs (`data/motifs.toml`): what a framed canvas shows, which sofas, armchairs, pillows and
//! rugs have a patterned fabric, which counters and vanity tops are marble or granite. Each is
//! a feature recorded on the object (`SceneObject::features`) that the renderer draws
//! (`vlnverse_env::material::FEATURE_SURFACES`) and language names. The choice is a hash of the
//! home's seed and the object's id, class and position, not a random draw, so no layout,
//! object or episode moves.

use serde::Deserialize;
use std::sync::LazyLock;
use vlnverse_env::material::FEATURE_SURFACES;
use vlnverse_env::{Scene, SceneObject, SemanticClass as C};

/// One rule of the motifs file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Rule {
    /// Vocabulary names of the classes it applies to.
    classes: Vec<String>,
    /// Material words it is limited to (none: any).
    #[serde(default)]
    materials: Vec<String>,
    /// The share of matching objects that take a motif, in `0..=1`.
    share: f64,
    /// The motifs, one of which is taken.
    features: Vec<String>,
    /// A feature the motif takes the place of.
    replaces: Option<String>,
}

/// `data/motifs.toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MotifFile {
    rule: Vec<Rule>,
}

/// A checked rule: its classes resolved.
#[derive(Debug)]
struct Checked {
    classes: Vec<C>,
    rule: Rule,
}

/// The motifs file, parsed and checked once. The file is embedded and checked by the unit
/// tests, so a malformed one never ships.
static MOTIFS: LazyLock<Vec<Checked>> =
    LazyLock::new(|| match parse(include_str!("../data/motifs.toml")) {
        Ok(m) => m,
        Err(e) => panic!("embedded data/motifs.toml is malformed: {e}"),
    });

/// Parse and check a motifs file: every class a vocabulary name, every share within 0..=1,
/// every feature one the renderer draws, no list empty.
fn parse(text: &str) -> Result<Vec<Checked>, String> {
    let file = toml::from_str::<MotifFile>(text).map_err(|e| e.to_string())?;
    file.rule
        .into_iter()
        .enumerate()
        .map(|(i, rule)| {
            let at = format!("rule {i}");
            if rule.classes.is_empty() || rule.features.is_empty() {
                return Err(format!("{at}: no classes or no features"));
            }
            if !(0.0..=1.0).contains(&rule.share) {
                return Err(format!("{at}: share {} is not within 0..=1", rule.share));
            }
            let classes = rule
                .classes
                .iter()
                .map(|c| C::from_name(c).ok_or_else(|| format!("{at}: no class named {c:?}")))
                .collect::<Result<Vec<C>, String>>()?;
            if let Some(f) = rule
                .features
                .iter()
                .find(|f| !FEATURE_SURFACES.iter().any(|(g, _, _)| g == f))
            {
                return Err(format!(
                    "{at}: the renderer does not draw the feature {f:?}"
                ));
            }
            Ok(Checked { classes, rule })
        })
        .collect()
}

/// Every feature a motif may record, in file order without repeats: what a language crate
/// needs words for.
pub fn motifs() -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for c in MOTIFS.iter() {
        for f in &c.rule.features {
            if !out.contains(&f.as_str()) {
                out.push(f);
            }
        }
    }
    out
}

/// Record a motif on every object of `scene` that a rule gives one.
pub(crate) fn record(scene: &mut Scene) {
    let seed = scene.seed.unwrap_or(0);
    for o in &mut scene.objects {
        if let Some(f) = motif_of(seed, o) {
            let replaced = MOTIFS
                .iter()
                .find(|c| applies(c, o))
                .and_then(|c| c.rule.replaces.as_deref());
            o.features.retain(|g| Some(g.as_str()) != replaced);
            o.features.push(f.to_string());
        }
    }
}

/// Whether rule `c` applies to `o`.
fn applies(c: &Checked, o: &SceneObject) -> bool {
    c.classes.contains(&o.class)
        && (c.rule.materials.is_empty() || c.rule.materials.contains(&o.material))
}

/// The motif the first rule that applies to `o` gives it, if any.
fn motif_of(seed: u64, o: &SceneObject) -> Option<&'static str> {
    let c = MOTIFS.iter().find(|c| applies(c, o))?;
    let h = object_hash(seed, o);
    // The top 24 bits decide whether, the low bits which.
    let u = (h >> 40) as f64 / (1u64 << 24) as f64;
    if u >= c.rule.share {
        return None;
    }
    let i = (h % c.rule.features.len() as u64) as usize;
    Some(c.rule.features[i].as_str())
}

/// A hash of the home's seed and the object's id, class and position.
fn object_hash(seed: u64, o: &SceneObject) -> u64 {
    let p = o.pose.position;
    let words = [
        o.id as u64,
        o.class.id() as u64,
        p[0].to_bits() as u64 | (p[2].to_bits() as u64) << 32,
        p[1].to_bits() as u64,
    ];
    let mut z = seed ^ 0x6d6f_7469_6673_2121;
    for w in words {
        z = (z ^ w).wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_env::Pose;

    #[test]
    fn the_embedded_motifs_parse_and_every_canvas_shows_a_subject() {
        assert!(MOTIFS.len() >= 5);
        assert!(motifs().len() >= 15, "{:?}", motifs());
        let mut canvas = SceneObject::from_parts(3, C::PictureFrame, Pose::IDENTITY, Vec::new());
        canvas.material = "canvas".into();
        let subjects: std::collections::BTreeSet<_> =
            (0..400).filter_map(|s| motif_of(s, &canvas)).collect();
        assert_eq!(
            subjects.len(),
            MOTIFS[0].rule.features.len(),
            "{subjects:?}"
        );
        // A photo frame (not canvas) shows none.
        canvas.material = "wood".into();
        assert!((0..100).all(|s| motif_of(s, &canvas).is_none()));
    }

    #[test]
    fn a_share_of_fabric_sofas_is_patterned_and_a_rug_pattern_replaces_the_diamonds() {
        let mut sofa = SceneObject::from_parts(5, C::Sofa, Pose::IDENTITY, Vec::new());
        sofa.material = "fabric".into();
        let n = (0..1000).filter(|&s| motif_of(s, &sofa).is_some()).count();
        assert!((220..380).contains(&n), "{n}");
        sofa.material = "leather".into();
        assert!((0..200).all(|s| motif_of(s, &sofa).is_none()));
        let mut rug = SceneObject::from_parts(6, C::Rug, Pose::IDENTITY, Vec::new());
        rug.features = vec!["diamond pattern".into()];
        let seed = (0..100)
            .find(|&s| motif_of(s, &rug).is_some())
            .expect("some rug is patterned");
        let mut scene = Scene {
            format_version: vlnverse_env::SCENE_FORMAT_VERSION,
            id: "t".into(),
            source: "test".into(),
            seed: Some(seed),
            floor_height: 0.0,
            rooms: vec![],
            doors: vec![],
            objects: vec![rug],
            storeys: Default::default(),
        };
        record(&mut scene);
        let f = &scene.objects[0].features;
        assert_eq!(f.len(), 1, "{f:?}");
        assert_ne!(f[0], "diamond pattern");
    }

    #[test]
    fn bad_motif_files_are_refused_with_the_rule_named() {
        let e = parse("[[rule]]\nclasses = [\"sofaa\"]\nshare = 0.5\nfeatures = [\"striped\"]\n")
            .unwrap_err();
        assert!(e.contains("rule 0") && e.contains("sofaa"), "{e}");
        let e = parse("[[rule]]\nclasses = [\"sofa\"]\nshare = 0.5\nfeatures = [\"tartan\"]\n")
            .unwrap_err();
        assert!(e.contains("tartan") && e.contains("does not draw"), "{e}");
        let e = parse("[[rule]]\nclasses = [\"sofa\"]\nshare = 1.5\nfeatures = [\"striped\"]\n")
            .unwrap_err();
        assert!(e.contains("share"), "{e}");
    }
}
