//! Tones of the palette's colour words (`data/tones.toml`): a drawn finish may take a tone of
//! its colour word ("navy" for blue, "oak" for wooden), which changes the RGB the renderer
//! shows and gives language a finer word, recorded as the object's shade.

use crate::palette::Finish;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use std::sync::LazyLock;

/// One tone of a colour word.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Tone {
    /// The colour word of the finishes that may take it.
    of: String,
    /// Its name, recorded as `SceneObject::shade`.
    shade: String,
    /// Linear RGB.
    rgb: [f32; 3],
    /// A colour word replacing `of`, if the tone reads as another colour.
    colour: Option<String>,
    /// Material words it is limited to (none: any).
    #[serde(default)]
    materials: Vec<String>,
}

/// `data/tones.toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ToneFile {
    tone: Vec<Tone>,
}

/// The tones file, parsed and checked once. The file is embedded and checked by the unit
/// tests, so a malformed one never ships.
static TONES: LazyLock<Vec<Tone>> =
    LazyLock::new(|| match parse(include_str!("../data/tones.toml")) {
        Ok(t) => t,
        Err(e) => panic!("embedded data/tones.toml is malformed: {e}"),
    });

/// Parse and check a tones file: linear RGB within 0..=1, no blank word, no shade of one
/// colour word listed twice.
fn parse(text: &str) -> Result<Vec<Tone>, String> {
    let tones = toml::from_str::<ToneFile>(text)
        .map_err(|e| e.to_string())?
        .tone;
    for (i, t) in tones.iter().enumerate() {
        let at = format!("tone {i} ({} {})", t.of, t.shade);
        if t.of.trim().is_empty() || t.shade.trim().is_empty() {
            return Err(format!("{at}: a blank word"));
        }
        if t.colour.as_deref().is_some_and(|c| c.trim().is_empty()) {
            return Err(format!("{at}: a blank colour"));
        }
        if !t.rgb.iter().all(|c| (0.0..=1.0).contains(c)) {
            return Err(format!("{at}: rgb {:?} is not within 0..=1", t.rgb));
        }
        if tones[..i]
            .iter()
            .any(|u| u.of == t.of && u.shade == t.shade)
        {
            return Err(format!("{at}: listed twice"));
        }
    }
    Ok(tones)
}

/// Every shade a generated object may record (`SceneObject::shade`), in file order: what a
/// language crate needs words for.
pub fn shades() -> Vec<&'static str> {
    TONES.iter().map(|t| t.shade.as_str()).collect()
}

/// `fin`, or one of its colour word's tones, chosen by a hash of the generator's seed and
/// stream position (so choosing draws nothing and moves no later draw).
pub(crate) fn toned(fin: Finish, rng: &ChaCha8Rng) -> Finish {
    let tones: Vec<&'static Tone> = TONES
        .iter()
        .filter(|t| t.of == fin.color)
        .filter(|t| t.materials.is_empty() || t.materials.iter().any(|m| m == fin.material))
        .collect();
    if tones.is_empty() {
        return fin;
    }
    let i = (stream_hash(rng) % (tones.len() as u64 + 1)) as usize;
    let Some(t) = i.checked_sub(1).map(|i| tones[i]) else {
        return fin;
    };
    Finish {
        color: t.colour.as_deref().unwrap_or(fin.color),
        rgb: t.rgb,
        shade: Some(&t.shade),
        ..fin
    }
}

/// A hash of the generator's seed and stream position.
pub(crate) fn stream_hash(rng: &ChaCha8Rng) -> u64 {
    let mut z: u64 = 0x94D0_49BB_1331_11EB;
    for chunk in rng.get_seed().chunks(8) {
        let mut b = [0u8; 8];
        b[..chunk.len()].copy_from_slice(chunk);
        z = (z ^ u64::from_le_bytes(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        z ^= z >> 31;
    }
    let pos = rng.get_word_pos();
    for w in [pos as u64, (pos >> 64) as u64, rng.get_stream()] {
        z = (z ^ w).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z ^= z >> 29;
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::palette::f;
    use rand::SeedableRng;

    #[test]
    fn the_embedded_tones_parse() {
        assert!(TONES.len() > 30);
    }

    #[test]
    fn bad_tone_files_are_refused_with_the_entry_named() {
        let e = parse("[[tone]]\nof = \"blue\"\nshade = \"navy\"\nrgb = [0.1, 2.0, 0.1]\n")
            .unwrap_err();
        assert!(e.contains("tone 0 (blue navy)") && e.contains("rgb"), "{e}");
        let twice = "[[tone]]\nof = \"red\"\nshade = \"maroon\"\nrgb = [0.1, 0.0, 0.0]\n";
        let e = parse(&format!("{twice}{twice}")).unwrap_err();
        assert!(e.contains("tone 1") && e.contains("twice"), "{e}");
    }

    #[test]
    fn toning_keeps_the_word_and_material_and_draws_nothing() {
        let blue = f("blue", "fabric", [0.08, 0.16, 0.5]);
        let mut shades = std::collections::BTreeSet::new();
        for seed in 0..400 {
            let rng = ChaCha8Rng::seed_from_u64(seed);
            let before = rng.get_word_pos();
            let t = toned(blue, &rng);
            assert_eq!(rng.get_word_pos(), before);
            assert_eq!((t.color, t.material), ("blue", "fabric"));
            assert_eq!(t.shade.is_none(), t.rgb == blue.rgb);
            shades.insert(t.shade);
        }
        // Every tone of blue and the finish itself occur.
        let blues = TONES.iter().filter(|t| t.of == "blue").count();
        assert_eq!(shades.len(), blues + 1, "{shades:?}");
        // A material-limited tone: terracotta is for ceramic only.
        let paper = f("orange", "paper", [0.8, 0.35, 0.08]);
        assert!((0..200)
            .all(|s| toned(paper, &ChaCha8Rng::seed_from_u64(s)).shade != Some("terracotta")));
        // A tone may change the colour word: a pink finish toned lavender is purple.
        let pink = f("pink", "fabric", [0.85, 0.45, 0.55]);
        let words: std::collections::BTreeSet<_> = (0..200)
            .map(|s| toned(pink, &ChaCha8Rng::seed_from_u64(s)))
            .map(|t| (t.color, t.shade))
            .collect();
        assert!(words.contains(&("purple", Some("lavender"))), "{words:?}");
        assert!(words.contains(&("pink", None)), "{words:?}");
    }
}
