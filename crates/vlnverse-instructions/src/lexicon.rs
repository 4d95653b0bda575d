//! Words for the things a scene holds: class and room names with their everyday synonyms,
//! colour shades read from an object's rendered colour, material, size and shape words, and
//! numbers. Written for this project. Every word here is derived from data the scene model has
//! (class, room type, colour word, part colours, material word, bounding box, part shapes).

use std::collections::BTreeMap;
use std::sync::LazyLock;

use serde::Deserialize;
use vlnverse_env::{RoomType, SceneObject, SemanticClass as C, Shape};

use crate::data::{expect_embedded, parse_toml, DataFileError};

/// Names of a class, the vocabulary name first. Every name maps back to one class only
/// ([`class_of_name`]), so a grounded object can be found in the text by any of them.
pub fn class_names(class: C) -> &'static [&'static str] {
    &CLASS_WORDS[class_index(class)].0
}

/// The least seat height of a stool called a bar stool (m): counter height.
const BAR_STOOL_HEIGHT: f32 = 0.62;

/// The names of one object: its class's names, narrowed where objects of a class differ in
/// what people call them (a framed canvas on a wall is a painting, a frame on a shelf a photo
/// frame). The first is the one used by default.
pub fn object_names(o: &SceneObject) -> Vec<&'static str> {
    let names = class_names(o.class);
    // A loveseat is a sofa for two.
    if o.class == C::Sofa {
        let for_two = o.features.iter().any(|f| f == "two seats");
        return names
            .iter()
            .copied()
            .filter(|n| for_two || !matches!(*n, "loveseat" | "love seat"))
            .collect();
    }
    // A bar stool is one tall enough for a counter.
    if o.class == C::Stool {
        let tall = o.bbox.size().y >= BAR_STOOL_HEIGHT;
        return names
            .iter()
            .copied()
            .filter(|n| tall || !matches!(*n, "bar stool" | "barstool"))
            .collect();
    }
    if o.class != C::PictureFrame {
        return names.to_vec();
    }
    let painting = o.material == "canvas";
    // Art is what a painting is called; a photo in a frame is not.
    let art = |n: &str| matches!(n, "artwork" | "wall art" | "piece of art");
    let mut out: Vec<&'static str> = names
        .iter()
        .copied()
        .filter(|n| n.contains("painting") == painting && !art(n))
        .collect();
    if painting {
        out.extend(names.iter().copied().filter(|n| *n == "picture" || art(n)));
    }
    if out.is_empty() {
        names.to_vec()
    } else {
        out
    }
}

/// Phrases after the name of one object: what it is for ([`class_uses`]; for a framed canvas,
/// whose class's uses are a photo frame's, what it shows), then what it has that others of its
/// class may not (its recorded features, `data/features.toml`), less the phrases of features
/// that another object of `peers` (any objects; those of `o`'s class in its room count)
/// shares: "the one with a spindle back" must tell it from the chairs around it.
pub fn distinct_uses(o: &SceneObject, peers: &[&SceneObject]) -> Vec<&'static str> {
    let mut out = if o.class == C::PictureFrame && o.material == "canvas" {
        // A canvas shows its recorded subject (phrased with the features below); one of an
        // older scene file, with none recorded, hills under a sky (vlnverse_env::material,
        // `Surface::Painting`).
        let subject = vlnverse_env::material::feature_surface(o).is_some();
        if subject {
            Vec::new()
        } else {
            feature_phrases("landscape")
        }
    } else {
        class_uses(o.class).to_vec()
    };
    let shared = |f: &String| {
        peers.iter().any(|p| {
            p.id != o.id && p.class == o.class && p.room == o.room && p.features.contains(f)
        })
    };
    for f in o.features.iter().filter(|f| !shared(f)) {
        out.extend(feature_phrases(f));
    }
    out
}

/// The phrases of one feature (none for a feature the file does not name).
fn feature_phrases(feature: &str) -> Vec<&'static str> {
    FEATURES
        .phrases
        .get(feature)
        .map(|p| p.iter().map(String::as_str).collect())
        .unwrap_or_default()
}

/// Adjectives for the recorded features of `o`, said before its colour ("striped",
/// "abstract"; `data/features.toml` `adjectives`), less any word that another object of `peers`
/// of `o`'s class in its room has too: "the striped armchair" must tell it from the armchairs
/// around it.
pub fn feature_adjectives(o: &SceneObject, peers: &[&SceneObject]) -> Vec<&'static str> {
    distinct_feature_words(&FEATURES.adjectives, o, peers)
}

/// Nouns that name a recorded feature of `o` right before its name, after any colour ("the
/// blue zebra painting"; `data/features.toml` `modifiers`), under the rule of
/// [`feature_adjectives`]. A stone worktop's word ("marble", "granite") is said without the
/// counter's colour, which is its cabinet's: "the marble counter", not "the light maple marble
/// counter".
pub fn feature_modifiers(o: &SceneObject, peers: &[&SceneObject]) -> Vec<&'static str> {
    distinct_feature_words(&FEATURES.modifiers, o, peers)
}

/// The phrases of the features of `o` that `word` (one of its [`feature_modifiers`]) names:
/// after "the windmill painting", "of a windmill" would say the subject twice.
pub(crate) fn modifier_phrases(o: &SceneObject, word: &str) -> Vec<&'static str> {
    o.features
        .iter()
        .filter(|f| {
            FEATURES
                .modifiers
                .get(*f)
                .is_some_and(|w| w.iter().any(|x| x == word))
        })
        .flat_map(|f| feature_phrases(f))
        .collect()
}

/// The words `table` gives the features of `o`, less those another object of `peers` of `o`'s
/// class in its room is given too.
fn distinct_feature_words(
    table: &'static BTreeMap<String, Vec<String>>,
    o: &SceneObject,
    peers: &[&SceneObject],
) -> Vec<&'static str> {
    let words = |x: &SceneObject| -> Vec<&'static str> {
        x.features
            .iter()
            .filter_map(|f| table.get(f))
            .flatten()
            .map(String::as_str)
            .collect()
    };
    let mut out = words(o);
    out.dedup();
    let shared: Vec<&'static str> = peers
        .iter()
        .filter(|p| p.id != o.id && p.class == o.class && p.room == o.room)
        .flat_map(|p| words(p))
        .collect();
    out.retain(|w| !shared.contains(w));
    out
}

/// The features file, as errors name it.
const FEATURES_FILE: &str = "data/features.toml";

/// `data/features.toml`: phrases by feature name, and words before the name.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FeatureFile {
    phrases: BTreeMap<String, Vec<String>>,
    #[serde(default)]
    adjectives: BTreeMap<String, Vec<String>>,
    #[serde(default)]
    modifiers: BTreeMap<String, Vec<String>>,
}

/// The feature phrases and adjectives, parsed and checked once.
static FEATURES: LazyLock<FeatureFile> = LazyLock::new(|| {
    expect_embedded(parse_features(
        FEATURES_FILE,
        include_str!("../data/features.toml"),
    ))
});

/// Parse and check a features file: no list empty, no phrase blank or listed twice, every
/// feature with adjectives or modifiers also with phrases.
fn parse_features(file: &'static str, text: &str) -> Result<FeatureFile, DataFileError> {
    let f: FeatureFile = parse_toml(file, text)?;
    check_word_lists(file, "phrases", &f.phrases, "feature")?;
    for (table, lists) in [("adjectives", &f.adjectives), ("modifiers", &f.modifiers)] {
        check_word_lists(file, table, lists, "feature")?;
        if let Some(k) = lists.keys().find(|k| !f.phrases.contains_key(*k)) {
            return Err(DataFileError::new(
                file,
                format!("{table}.{k}"),
                "a feature without phrases",
            ));
        }
    }
    Ok(f)
}

/// Check the lists of a `table` of words by name: none empty (`what` names what to leave out
/// instead), no entry blank or listed twice in its list.
fn check_word_lists(
    file: &'static str,
    table: &str,
    lists: &BTreeMap<String, Vec<String>>,
    what: &str,
) -> Result<(), DataFileError> {
    for (key, words) in lists {
        let at = format!("{table}.{key}");
        if words.is_empty() {
            return Err(DataFileError::new(
                file,
                at,
                format!("empty (leave the {what} out instead)"),
            ));
        }
        for (i, w) in words.iter().enumerate() {
            if w.trim().is_empty() || words[..i].contains(w) {
                return Err(DataFileError::new(
                    file,
                    at,
                    format!("entry {i} ({w:?}) is blank or listed twice"),
                ));
            }
        }
    }
    Ok(())
}

/// The classes whose names include `name` (for checks: a synonym names one class, or a class
/// whose names overlap in a word, e.g. "plant" for both plants).
pub fn class_of_name(name: &str) -> Vec<C> {
    C::ALL
        .iter()
        .copied()
        .filter(|&c| class_names(c).contains(&name))
        .collect()
}

/// What a group of things of `class` and other classes of its kind is called ("exercise
/// equipment" for a treadmill; `data/groups.toml`); empty when the class is of no kind.
pub fn kind_names(class: C) -> Vec<&'static str> {
    crate::groups::kind_of(class)
        .map_or_else(Vec::new, |k| k.names.iter().map(String::as_str).collect())
}

/// Names of a room type, the vocabulary name first.
pub fn room_names(kind: RoomType) -> &'static [&'static str] {
    match kind {
        RoomType::LivingRoom => &[
            "living room",
            "lounge",
            "family room",
            "sitting room",
            "den",
        ],
        RoomType::Kitchen => &["kitchen"],
        RoomType::DiningRoom => &["dining room", "dining area"],
        RoomType::Bedroom => &["bedroom"],
        RoomType::Bathroom => &["bathroom", "restroom", "washroom"],
        RoomType::Hallway => &["hallway", "hall", "corridor", "passageway"],
        RoomType::Office => &["office", "study"],
        RoomType::LaundryRoom => &["laundry room", "laundry", "utility room"],
        RoomType::Closet => &["closet", "storage room"],
        RoomType::Gym => &[
            "gym",
            "exercise room",
            "workout room",
            "home gym",
            "fitness room",
        ],
        RoomType::Room => &["room", "spare room", "empty room"],
        RoomType::EntranceHall => &["entrance hall", "entryway", "front hall", "foyer", "entry"],
        RoomType::Balcony => &["balcony"],
        RoomType::Pantry => &["pantry"],
        RoomType::HomeTheater => &["home theater", "media room", "movie room", "theater room"],
        RoomType::Library => &["library", "reading room"],
        RoomType::Garage => &["garage"],
        RoomType::Porch => &["porch", "sun porch"],
        RoomType::Sauna => &["sauna"],
        RoomType::Spa => &["spa", "massage room", "spa room"],
        // Not a bare "cellar": the room is on the ground floor, and a wine cellar is what a
        // room kept for wine is called wherever it is.
        RoomType::WineCellar => &["wine cellar", "wine room"],
        RoomType::Playroom => &["playroom", "play room"],
        RoomType::MudRoom => &["mud room", "mudroom"],
        RoomType::Workshop => &["workshop", "workroom"],
    }
}

/// What objects of a class are for, as a phrase after the name ("the kettle for boiling
/// water"): true of every object of the class, so it never claims more than the class does.
pub fn class_uses(class: C) -> &'static [&'static str] {
    &CLASS_WORDS[class_index(class)].1
}

/// The class words file, as errors name it.
const CLASSES_FILE: &str = "data/classes.toml";

/// `data/classes.toml`: names and uses by class vocabulary name.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ClassFile {
    class_names: BTreeMap<String, Vec<String>>,
    class_uses: BTreeMap<String, Vec<String>>,
}

/// The names and uses of each class, by position in `C::ALL`, parsed and checked once.
static CLASS_WORDS_OWNED: LazyLock<Vec<(Vec<String>, Vec<String>)>> = LazyLock::new(|| {
    expect_embedded(parse_class_words(
        CLASSES_FILE,
        include_str!("../data/classes.toml"),
    ))
});

/// [`CLASS_WORDS_OWNED`] as string slices.
static CLASS_WORDS: LazyLock<Vec<(Vec<&'static str>, Vec<&'static str>)>> = LazyLock::new(|| {
    let strs = |v: &'static Vec<String>| v.iter().map(String::as_str).collect();
    CLASS_WORDS_OWNED
        .iter()
        .map(|(names, uses)| (strs(names), strs(uses)))
        .collect()
});

/// The position of a class in `C::ALL`.
fn class_index(class: C) -> usize {
    C::ALL
        .iter()
        .position(|&c| c == class)
        .expect("C::ALL holds every class")
}

/// Parse and check a class words file: every key a class's vocabulary name, every class named
/// (a class without uses has none), no list empty, no word blank or listed twice in one list.
fn parse_class_words(
    file: &'static str,
    text: &str,
) -> Result<Vec<(Vec<String>, Vec<String>)>, DataFileError> {
    let f: ClassFile = parse_toml(file, text)?;
    for (table, map) in [
        ("class_names", &f.class_names),
        ("class_uses", &f.class_uses),
    ] {
        for (key, words) in map {
            let at = format!("{table}.{key}");
            if C::from_name(key).is_none() {
                return Err(DataFileError::new(file, at, "no such class"));
            }
            if words.is_empty() {
                return Err(DataFileError::new(
                    file,
                    at,
                    "empty (leave the class out instead)",
                ));
            }
            for (i, w) in words.iter().enumerate() {
                if w.trim().is_empty() {
                    return Err(DataFileError::new(file, at, format!("entry {i} is blank")));
                }
                if words[..i].contains(w) {
                    return Err(DataFileError::new(
                        file,
                        at,
                        format!("entry {i} ({w:?}) is listed twice"),
                    ));
                }
            }
        }
    }
    C::ALL
        .iter()
        .map(|c| {
            let names = f.class_names.get(c.name()).cloned().ok_or_else(|| {
                DataFileError::new(file, format!("class_names.{}", c.name()), "missing")
            })?;
            Ok((
                names,
                f.class_uses.get(c.name()).cloned().unwrap_or_default(),
            ))
        })
        .collect()
}

/// The main colour of an object as linear RGB: the colour of its largest part.
fn main_rgb(o: &SceneObject) -> Option<[f32; 3]> {
    o.parts
        .iter()
        .map(|p| (p.shape.nominal_volume(), p.color))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}

/// Colour phrases for an object: its colour word, alone or with a shade read from the rendered
/// colour of its largest part ("dark blue", "pale pink"); empty when it has no colour word.
/// Only shades the RGB supports are offered.
pub fn color_phrases(o: &SceneObject) -> Vec<String> {
    let c = o.color.as_str();
    if c.is_empty() {
        return Vec::new();
    }
    let mut out = vec![c.to_string()];
    if let Some(words) = o.shade.as_deref().and_then(|s| SHADES.words.get(s)) {
        out.extend(words.iter().cloned());
        return out;
    }
    let Some(rgb) = main_rgb(o) else {
        return out;
    };
    out.extend(shades_for(c, rgb).iter().cloned());
    out
}

/// The colour file, as errors name it.
const COLOURS_FILE: &str = "data/colours.toml";

/// The shade rules and words of [`color_phrases`], parsed and checked once from
/// `data/colours.toml`.
static SHADES: LazyLock<ShadeFile> = LazyLock::new(|| {
    expect_embedded(parse_shade_rules(
        COLOURS_FILE,
        include_str!("../data/colours.toml"),
    ))
});

/// `data/colours.toml`: the shade rules, in order, and the words of recorded shades.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ShadeFile {
    rule: Vec<ShadeRule>,
    /// Words for an object's recorded shade (`SceneObject::shade`), by shade name.
    #[serde(default)]
    words: BTreeMap<String, Vec<String>>,
}

/// One shade rule: when it holds (colour word and thresholds on the part's RGB), and the shades
/// it gives, or sub-rules by colour. See the head of `data/colours.toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ShadeRule {
    colour: Option<String>,
    hi_above: Option<f32>,
    hi_below: Option<f32>,
    sat_above: Option<f32>,
    green_below_red: Option<f32>,
    #[serde(default)]
    shades: Vec<String>,
    #[serde(default)]
    by_colour: Vec<ShadeRule>,
}

impl ShadeRule {
    /// Whether the rule holds for colour word `colour` and linear RGB `rgb`.
    fn holds(&self, colour: &str, rgb: [f32; 3], hi: f32, sat: f32) -> bool {
        self.colour.as_deref().is_none_or(|c| c == colour)
            && self.hi_above.is_none_or(|t| hi > t)
            && self.hi_below.is_none_or(|t| hi < t)
            && self.sat_above.is_none_or(|t| sat > t)
            && self.green_below_red.is_none_or(|k| rgb[1] < k * rgb[0])
    }
}

/// The shades offered beside colour word `colour` for a largest part of linear RGB `rgb`: those
/// of the first rule that holds (or of its first sub-rule that holds); none when none holds.
fn shades_for(colour: &str, rgb: [f32; 3]) -> &'static [String] {
    let hi = rgb.iter().copied().fold(0.0f32, f32::max);
    let lo = rgb.iter().copied().fold(1.0f32, f32::min);
    let sat = if hi > 0.0 { (hi - lo) / hi } else { 0.0 };
    let Some(rule) = SHADES.rule.iter().find(|r| r.holds(colour, rgb, hi, sat)) else {
        return &[];
    };
    if rule.by_colour.is_empty() {
        return &rule.shades;
    }
    rule.by_colour
        .iter()
        .find(|r| r.holds(colour, rgb, hi, sat))
        .map_or(&[], |r| &r.shades)
}

/// Parse and check a colour file: at least one rule; each with thresholds that are finite
/// numbers (and hi / sat ones within 0..=1), a colour word that is not blank, and either
/// shades or sub-rules by colour (which have shades and no sub-rules of their own); no shade
/// blank, none listed twice in one rule.
fn parse_shade_rules(file: &'static str, text: &str) -> Result<ShadeFile, DataFileError> {
    let shades = parse_toml::<ShadeFile>(file, text)?;
    check_word_lists(file, "words", &shades.words, "shade")?;
    let rules = &shades.rule;
    if rules.is_empty() {
        return Err(DataFileError::new(file, "", "no rules"));
    }
    for (i, r) in rules.iter().enumerate() {
        let at = format!("rule {i}{}", colour_label(r));
        check_shade_rule(file, &at, r)?;
        match (r.shades.is_empty(), r.by_colour.is_empty()) {
            (true, true) => {
                return Err(DataFileError::new(file, at, "neither shades nor by_colour"))
            }
            (false, false) => {
                return Err(DataFileError::new(file, at, "both shades and by_colour"))
            }
            _ => {}
        }
        for (j, sub) in r.by_colour.iter().enumerate() {
            let at = format!("{at}, by_colour {j}{}", colour_label(sub));
            check_shade_rule(file, &at, sub)?;
            if !sub.by_colour.is_empty() {
                return Err(DataFileError::new(file, at, "by_colour within by_colour"));
            }
            if sub.shades.is_empty() {
                return Err(DataFileError::new(file, at, "no shades"));
            }
        }
    }
    Ok(shades)
}

/// " (white)" for a rule about "white", "" for a rule about any colour.
fn colour_label(r: &ShadeRule) -> String {
    r.colour
        .as_ref()
        .map(|c| format!(" ({c})"))
        .unwrap_or_default()
}

/// The checks of one rule of a colour file, sub-rules apart.
fn check_shade_rule(file: &'static str, at: &str, r: &ShadeRule) -> Result<(), DataFileError> {
    let err = |msg: String| Err(DataFileError::new(file, at, msg));
    if r.colour.as_deref().is_some_and(|c| c.trim().is_empty()) {
        return err("a blank colour".into());
    }
    for (name, t) in [
        ("hi_above", r.hi_above),
        ("hi_below", r.hi_below),
        ("sat_above", r.sat_above),
    ] {
        if t.is_some_and(|t| !(0.0..=1.0).contains(&t)) {
            return err(format!("{name} must lie in 0..=1"));
        }
    }
    if r.green_below_red
        .is_some_and(|k| !k.is_finite() || k <= 0.0)
    {
        return err("green_below_red must be a positive number".into());
    }
    for (k, shade) in r.shades.iter().enumerate() {
        if shade.trim().is_empty() {
            return err(format!("shade {k} is blank"));
        }
        if r.shades[..k].contains(shade) {
            return err(format!("shade {k} ({shade:?}) is listed twice"));
        }
    }
    Ok(())
}

/// Material adjectives for an object's material word (what it is made of); empty when none
/// reads naturally for its class. (A stone worktop is a recorded feature, not the material:
/// the colour and shade words describe the cabinet under it, so "the light maple counter made
/// of granite" would mislead; see [`feature_modifiers`].)
pub fn material_words(o: &SceneObject) -> &'static [&'static str] {
    let upholstered = matches!(o.class, C::Sofa | C::Armchair | C::OfficeChair | C::Bench);
    match o.material.as_str() {
        "wood" if o.color != "wooden" => &["wooden", "wood"],
        "fabric" if upholstered => &["fabric", "cloth", "padded", "upholstered"],
        "fabric" => &["fabric", "cloth"],
        "leather" => &["leather"],
        // Silver metal is steel on an appliance and chrome on a fitting; gold metal is brass.
        "metal" if o.color == "silver" && is_appliance(o.class) => {
            &["metal", "metallic", "steel", "stainless steel"]
        }
        "metal" if o.color == "silver" => &["metal", "metallic", "chrome"],
        "metal" if o.color == "gold" => &["metal", "metallic", "brass"],
        "metal" => &["metal", "metallic"],
        "plastic" => &["plastic"],
        "ceramic" => &["ceramic", "porcelain"],
        "glass" => &["glass"],
        "wax" => &["wax"],
        "paper" => &["paper"],
        "stone" => &["stone"],
        "brick" => &["brick"],
        "wicker" => &["wicker"],
        "cardboard" => &["cardboard"],
        _ => &[],
    }
}

/// Kitchen and laundry appliances, which people call steel when they are silver metal.
fn is_appliance(class: C) -> bool {
    matches!(
        class,
        C::Fridge
            | C::Stove
            | C::Dishwasher
            | C::WashingMachine
            | C::Toaster
            | C::Kettle
            | C::Microwave
            | C::Pot
            | C::Pan
            | C::CoffeeMachine
            | C::Blender
    )
}

/// The plain material noun behind a material adjective ("made of wood").
pub fn material_noun(word: &str) -> &str {
    match word {
        "wooden" => "wood",
        "cloth" | "padded" | "upholstered" => "fabric",
        "metallic" | "chrome" => "metal",
        "stainless steel" => "steel",
        "porcelain" => "ceramic",
        other => other,
    }
}

/// Size and shape words an object's geometry supports: height, footprint, bulk relative to
/// others of its class in the scene, and the shape of its largest part; then the words its
/// recorded features put before its name ([`feature_adjectives`]: "striped", "marble").
pub fn shape_words(o: &SceneObject, peers: &[&SceneObject]) -> Vec<&'static str> {
    let s = o.bbox.size();
    let (w, h, d) = (s.x.max(s.z), s.y, s.x.min(s.z));
    let mut out = Vec::new();
    // Every door is tall and thin; saying so tells one door from another no better.
    if o.class == C::Door {
        return out;
    }
    let furniture = o.class.kind() == vlnverse_env::ClassKind::Furniture;
    if furniture && h > 1.5 {
        out.push("tall");
    } else if furniture && h < 0.55 && w > 0.5 {
        out.push("low");
    }
    if furniture && w > 1.8 {
        out.extend(["long", "wide"]);
    } else if furniture && d > 0.0 && w / d > 2.5 && w > 0.8 {
        out.extend(["long", "narrow"]);
    } else if furniture && (w - d).abs() < 0.1 * w && w > 0.5 {
        out.push("square");
    } else if furniture && d > 0.0 && w / d > 1.3 && w > 0.5 {
        out.push("rectangular");
    }
    // Sizes people name for beds, from the width across.
    match o.class {
        C::Bed if d > 1.7 => out.push("king-size"),
        C::Bed if d > 1.3 => out.push("double"),
        C::Bed if d > 0.5 && d < 1.1 => out.extend(["single", "twin"]),
        _ => {}
    }
    let largest = o.parts.iter().max_by(|a, b| {
        a.shape
            .nominal_volume()
            .total_cmp(&b.shape.nominal_volume())
    });
    if let Some(Shape::Cylinder { .. } | Shape::Sphere { .. }) = largest.map(|p| &p.shape) {
        out.push("round");
        // "the circular table", not "the circular candle".
        if furniture {
            out.push("circular");
        }
    }
    // Bulk against the other objects of its class, when there are any.
    let vol = |x: &SceneObject| {
        let s = x.bbox.size();
        s.x * s.y * s.z
    };
    let others: Vec<f32> = peers
        .iter()
        .filter(|x| x.class == o.class && x.id != o.id)
        .map(|x| vol(x))
        .collect();
    // Against one other: "the bigger table"; against several: "the biggest table".
    let one = others.len() == 1;
    if !others.is_empty() {
        let v = vol(o);
        if others.iter().all(|&x| v > 1.3 * x) {
            out.extend(["large", "big"]);
            out.extend(if one {
                ["bigger", "larger"]
            } else {
                ["biggest", "largest"]
            });
        } else if others.iter().all(|&x| v * 1.3 < x) {
            out.extend(["small", "little"]);
            out.push(if one { "smaller" } else { "smallest" });
        }
    }
    // Height against the others of its class (furniture: people compare what they see).
    let heights: Vec<f32> = peers
        .iter()
        .filter(|x| x.class == o.class && x.id != o.id)
        .map(|x| x.bbox.size().y)
        .collect();
    if furniture && !heights.is_empty() {
        if heights.iter().all(|&x| h > 1.25 * x) {
            out.push(if one { "taller" } else { "tallest" });
        } else if heights.iter().all(|&x| h * 1.25 < x) {
            out.push(if one { "shorter" } else { "shortest" });
        }
    }
    out.extend(feature_adjectives(o, peers));
    out
}

/// The plural of a class name: "chairs", "benches", "bookshelves", "potted plants".
pub fn plural(name: &str) -> String {
    // "piece of art" -> "pieces of art"; art on a wall is counted in pieces.
    if let Some((one, rest)) = name.split_once(" of ") {
        return format!("{} of {rest}", plural(one));
    }
    if name == "wall art" {
        return "pieces of wall art".into();
    }
    let (head, last) = name.rsplit_once(' ').map_or(("", name), |(h, l)| (h, l));
    let p = if let Some(stem) = last.strip_suffix("shelf") {
        format!("{stem}shelves")
    } else if ["s", "x", "z", "ch", "sh"]
        .iter()
        .any(|e| last.ends_with(e))
    {
        format!("{last}es")
    } else if last.ends_with('y')
        && !last.ends_with("ay")
        && !last.ends_with("ey")
        && !last.ends_with("oy")
    {
        format!("{}ies", &last[..last.len() - 1])
    } else {
        format!("{last}s")
    };
    if head.is_empty() {
        p
    } else {
        format!("{head} {p}")
    }
}

/// A whole number written out ("three", "twenty-four"); digits above ninety-nine.
pub fn number_word(n: u32) -> String {
    const ONES: [&str; 20] = [
        "zero",
        "one",
        "two",
        "three",
        "four",
        "five",
        "six",
        "seven",
        "eight",
        "nine",
        "ten",
        "eleven",
        "twelve",
        "thirteen",
        "fourteen",
        "fifteen",
        "sixteen",
        "seventeen",
        "eighteen",
        "nineteen",
    ];
    const TENS: [&str; 10] = [
        "", "", "twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety",
    ];
    match n {
        0..=19 => ONES[n as usize].to_string(),
        20..=99 if n.is_multiple_of(10) => TENS[(n / 10) as usize].to_string(),
        20..=99 => format!("{}-{}", TENS[(n / 10) as usize], ONES[(n % 10) as usize]),
        _ => n.to_string(),
    }
}

/// An ordinal written out ("first", "seventh"), up to twelfth; `None` beyond.
pub fn ordinal_word(n: u32) -> Option<&'static str> {
    const ORD: [&str; 12] = [
        "first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth",
        "tenth", "eleventh", "twelfth",
    ];
    n.checked_sub(1).and_then(|i| ORD.get(i as usize)).copied()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_names_its_class() {
        for &c in C::ALL {
            let names = class_names(c);
            assert_eq!(
                names[0],
                c.words(),
                "{c:?}: the vocabulary name comes first"
            );
            for n in names {
                assert_eq!(class_of_name(n), vec![c], "`{n}` names more than one class");
            }
        }
        for &k in RoomType::ALL {
            assert_eq!(room_names(k)[0], k.words());
        }
    }

    #[test]
    fn the_embedded_colour_file_is_valid() {
        if let Err(e) = parse_shade_rules(COLOURS_FILE, include_str!("../data/colours.toml")) {
            panic!("{e}");
        }
    }

    #[test]
    fn a_recorded_shade_gives_its_words_and_every_generated_tone_has_words() {
        use vlnverse_env::Pose;
        let mut sofa = SceneObject::from_parts(1, C::Sofa, Pose::IDENTITY, Vec::new());
        sofa.color = "blue".into();
        sofa.shade = Some("navy".into());
        assert_eq!(color_phrases(&sofa), ["blue", "navy", "navy blue"]);
        // A shade without words falls back to the rules on the RGB (none here: no parts).
        sofa.shade = Some("no such shade".into());
        assert_eq!(color_phrases(&sofa), ["blue"]);
        // The generator's tones all have words here.
        let shades = vlnverse_procgen::shades();
        assert!(shades.len() > 30);
        for shade in shades {
            assert!(
                SHADES.words.contains_key(shade),
                "no words for the tone {shade:?}"
            );
        }
    }

    #[test]
    fn every_feature_the_generator_records_has_phrases() {
        use vlnverse_env::SceneSource;
        let homes =
            vlnverse_procgen::HomeGenerator::from_preset(vlnverse_procgen::Preset::Tiny).unwrap();
        let mut seen = std::collections::BTreeSet::new();
        for i in 0..homes.len() {
            for o in &homes.scene(i).unwrap().objects {
                for f in &o.features {
                    assert!(
                        FEATURES.phrases.contains_key(f),
                        "no phrases for the feature {f:?}"
                    );
                    seen.insert(f.clone());
                }
            }
        }
        assert!(seen.len() > 20, "{seen:?}");
    }

    #[test]
    fn every_motif_the_generator_may_record_has_phrases_and_draws_a_surface() {
        for f in vlnverse_procgen::motifs() {
            assert!(
                !feature_phrases(f).is_empty(),
                "no phrases for the motif {f:?}"
            );
            let mut o = SceneObject::from_parts(1, C::Sofa, vlnverse_env::Pose::IDENTITY, vec![]);
            o.features = vec![f.to_string()];
            assert!(
                vlnverse_env::material::feature_surface(&o).is_some(),
                "{f:?}"
            );
        }
    }

    #[test]
    fn a_canvas_is_phrased_by_its_subject_and_patterns_go_before_the_name() {
        use vlnverse_env::Pose;
        let mut canvas = SceneObject::from_parts(1, C::PictureFrame, Pose::IDENTITY, vec![]);
        canvas.material = "canvas".into();
        // An older scene's canvas, with no subject, shows the landscape.
        assert_eq!(distinct_uses(&canvas, &[]), feature_phrases("landscape"));
        canvas.features = vec!["sailboat".into()];
        let uses = distinct_uses(&canvas, &[]);
        assert!(uses.contains(&"of a sailboat"), "{uses:?}");
        assert!(!uses.iter().any(|u| u.contains("landscape")), "{uses:?}");
        assert!(feature_adjectives(&canvas, &[]).is_empty());
        assert_eq!(feature_modifiers(&canvas, &[]), ["sailboat"]);
        let twice = modifier_phrases(&canvas, "sailboat");
        assert!(twice.contains(&"of a boat on the water"), "{twice:?}");
        assert!(modifier_phrases(&canvas, "zebra").is_empty());
        // Grounding: no picture word for a canvas without that subject.
        let mut other = SceneObject::from_parts(2, C::PictureFrame, Pose::IDENTITY, vec![]);
        other.material = "canvas".into();
        other.features = vec!["zebra".into()];
        let told = distinct_uses(&other, &[&canvas, &other]);
        assert!(told.iter().all(|u| !u.contains("sailboat")), "{told:?}");
        assert_eq!(feature_modifiers(&other, &[&canvas, &other]), ["zebra"]);
        // The subject is a noun before the name, never an adjective before the colour.
        assert!(!shape_words(&other, &[&canvas, &other]).contains(&"zebra"));
        // Two abstract paintings in a room: "abstract" tells neither apart, their phrases do.
        canvas.features = vec!["abstract circles".into()];
        other.features = vec!["abstract squares".into()];
        assert!(feature_adjectives(&canvas, &[&canvas, &other]).is_empty());
        assert_eq!(feature_adjectives(&canvas, &[&canvas]), ["abstract"]);
        assert!(distinct_uses(&canvas, &[&canvas, &other]).contains(&"with circles on it"));
        // A striped armchair is the striped one; among striped armchairs it is not.
        let mut chair = SceneObject::from_parts(3, C::Armchair, Pose::IDENTITY, vec![]);
        chair.features = vec!["striped".into()];
        let plain = SceneObject::from_parts(4, C::Armchair, Pose::IDENTITY, vec![]);
        assert!(shape_words(&chair, &[&chair, &plain]).contains(&"striped"));
        assert!(!shape_words(&plain, &[&chair, &plain]).contains(&"striped"));
        let mut twin = plain.clone();
        twin.features = vec!["striped".into()];
        assert!(!shape_words(&chair, &[&chair, &twin]).contains(&"striped"));
        // A marble counter.
        let mut counter = SceneObject::from_parts(5, C::Counter, Pose::IDENTITY, vec![]);
        counter.features = vec!["marble top".into()];
        counter.material = "wood".into();
        assert_eq!(feature_modifiers(&counter, &[]), ["marble"]);
        assert_eq!(material_words(&counter), ["wooden", "wood"]);
        assert!(distinct_uses(&counter, &[]).contains(&"with a marble top"));
        // A sink with a marble top is a ceramic sink.
        let mut sink = SceneObject::from_parts(6, C::Sink, Pose::IDENTITY, vec![]);
        sink.material = "ceramic".into();
        sink.features = vec!["marble top".into()];
        assert_eq!(material_words(&sink), ["ceramic", "porcelain"]);
        let e = parse_features("f.toml", "[phrases]\n[adjectives]\nzebra = [\"zebra\"]\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("adjectives.zebra"), "{e}");
    }

    #[test]
    fn a_painting_is_art_a_framed_photo_is_not() {
        use vlnverse_env::Pose;
        let mut frame = SceneObject::from_parts(1, C::PictureFrame, Pose::IDENTITY, Vec::new());
        frame.material = "wood".into();
        let photo = object_names(&frame);
        assert!(photo.contains(&"photo frame"));
        assert!(!photo
            .iter()
            .any(|n| n.contains("art") || n.contains("painting")));
        frame.material = "canvas".into();
        let painting = object_names(&frame);
        for n in ["painting", "picture", "artwork", "wall art", "piece of art"] {
            assert!(painting.contains(&n), "{n} not among {painting:?}");
        }
        assert!(!painting.contains(&"photo frame"));
    }

    #[test]
    fn features_add_phrases_a_sofa_for_two_is_a_loveseat_a_tall_stool_a_bar_stool() {
        use vlnverse_env::Pose;
        let mut sofa = SceneObject::from_parts(1, C::Sofa, Pose::IDENTITY, Vec::new());
        assert!(!object_names(&sofa).contains(&"loveseat"));
        assert!(!object_names(&sofa).contains(&"love seat"));
        let uses = class_uses(C::Sofa);
        assert_eq!(distinct_uses(&sofa, &[]), uses);
        sofa.features = vec![
            "two seats".into(),
            "low arms".into(),
            "no such feature".into(),
        ];
        assert!(object_names(&sofa).contains(&"loveseat"));
        assert!(object_names(&sofa).contains(&"love seat"));
        assert_eq!(
            distinct_uses(&sofa, &[])[uses.len()..],
            [
                "with two seats",
                "for two people",
                "with low arms",
                "with low armrests"
            ]
        );
        let stool = |h: f32| {
            let mut o = SceneObject::from_parts(3, C::Stool, Pose::IDENTITY, Vec::new());
            o.bbox = vlnverse_env::Aabb::new(glam::Vec3::ZERO, glam::Vec3::new(0.3, h, 0.3));
            object_names(&o)
        };
        assert!(stool(0.7).contains(&"bar stool") && stool(0.7).contains(&"barstool"));
        assert_eq!(stool(0.45), ["stool"]);
        // A feature another sofa in the room shares does not tell this one apart.
        let mut other = SceneObject::from_parts(9, C::Sofa, Pose::IDENTITY, Vec::new());
        other.features = vec!["low arms".into()];
        let told = distinct_uses(&sofa, &[&sofa, &other]);
        assert!(told.contains(&"with two seats") && !told.contains(&"with low arms"));
        other.room = Some(7);
        assert!(distinct_uses(&sofa, &[&other]).contains(&"with low arms"));
        let mut kettle = SceneObject::from_parts(2, C::Kettle, Pose::IDENTITY, Vec::new());
        kettle.features = vec!["four legs".into()];
        assert_eq!(distinct_uses(&kettle, &[])[0], class_uses(C::Kettle)[0]);
        assert_eq!(distinct_uses(&kettle, &[]).last(), Some(&"on four legs"));
        let err = parse_features("f.toml", "[phrases]\nfootboard = [\"a\", \"a\"]\n")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("f.toml") && err.contains("phrases.footboard"),
            "{err}"
        );
    }

    #[test]
    fn silver_metal_is_steel_on_appliances_and_chrome_elsewhere() {
        use vlnverse_env::Pose;
        let metal = |class: C, color: &str| {
            let mut o = SceneObject::from_parts(1, class, Pose::IDENTITY, Vec::new());
            o.color = color.into();
            o.material = "metal".into();
            material_words(&o)
        };
        assert!(metal(C::Fridge, "silver").contains(&"stainless steel"));
        assert!(!metal(C::Fridge, "silver").contains(&"chrome"));
        assert!(metal(C::FloorLamp, "silver").contains(&"chrome"));
        assert!(metal(C::Mirror, "gold").contains(&"brass"));
        assert!(!metal(C::Fridge, "white").contains(&"steel"));
        assert_eq!(material_noun("stainless steel"), "steel");
    }

    #[test]
    fn the_embedded_feature_file_is_valid() {
        if let Err(e) = parse_features(FEATURES_FILE, include_str!("../data/features.toml")) {
            panic!("{e}");
        }
    }

    #[test]
    fn a_single_bed_is_also_twin_and_round_furniture_also_circular() {
        use vlnverse_env::{Part, Pose, Shape};
        let part = |shape: Shape| Part {
            shape,
            transform: Pose::IDENTITY,
            color: [0.5, 0.5, 0.5],
        };
        let boxed = |class: C, half: [f32; 3]| {
            SceneObject::from_parts(
                0,
                class,
                Pose::IDENTITY,
                vec![part(Shape::Cuboid {
                    half_extents: half,
                    bevel: 0.0,
                })],
            )
        };
        let single = shape_words(&boxed(C::Bed, [0.45, 0.25, 1.0]), &[]);
        assert!(
            single.contains(&"single") && single.contains(&"twin"),
            "{single:?}"
        );
        let double = shape_words(&boxed(C::Bed, [0.75, 0.25, 1.0]), &[]);
        assert!(
            double.contains(&"double") && !double.contains(&"twin"),
            "{double:?}"
        );
        let table = SceneObject::from_parts(
            0,
            C::SideTable,
            Pose::IDENTITY,
            vec![part(Shape::Cylinder {
                radius: 0.3,
                half_height: 0.3,
            })],
        );
        let round = shape_words(&table, &[]);
        assert!(
            round.contains(&"round") && round.contains(&"circular"),
            "{round:?}"
        );
        let square = shape_words(&boxed(C::SideTable, [0.3, 0.3, 0.3]), &[]);
        assert!(!square.contains(&"circular"), "{square:?}");
        let candle = SceneObject::from_parts(
            0,
            C::Candle,
            Pose::IDENTITY,
            vec![part(Shape::Cylinder {
                radius: 0.04,
                half_height: 0.1,
            })],
        );
        let small = shape_words(&candle, &[]);
        assert!(
            small.contains(&"round") && !small.contains(&"circular"),
            "{small:?}"
        );
    }

    #[test]
    fn plurals_of_class_names() {
        for (one, many) in [
            ("chair", "chairs"),
            ("bench", "benches"),
            ("bookshelf", "bookshelves"),
            ("glass", "glasses"),
            ("potted plant", "potted plants"),
            ("wall shelf", "wall shelves"),
            ("tv", "tvs"),
            ("laundry", "laundries"),
            ("piece of art", "pieces of art"),
            ("wall art", "pieces of wall art"),
            ("pair of shoes", "pairs of shoes"),
            ("tray", "trays"),
            ("box", "boxes"),
        ] {
            assert_eq!(plural(one), many);
        }
    }

    #[test]
    fn shades_follow_the_rules_in_order() {
        assert_eq!(shades_for("white", [0.95, 0.95, 0.95])[0], "bright white");
        assert_eq!(shades_for("white", [0.8, 0.7, 0.6])[0], "off-white");
        assert_eq!(shades_for("white", [0.8, 0.8, 0.8])[0], "plain white");
        assert_eq!(shades_for("red", [0.2, 0.0, 0.0])[0], "dark red");
        assert_eq!(shades_for("red", [0.5, 0.1, 0.1])[0], "dark red");
        assert_eq!(shades_for("brown", [0.5, 0.3, 0.1])[0], "reddish brown");
        assert_eq!(shades_for("red", [0.9, 0.1, 0.1])[0], "bright red");
        assert_eq!(shades_for("yellow", [0.9, 0.5, 0.1])[0], "dark yellow");
        assert_eq!(shades_for("yellow", [0.9, 0.8, 0.1])[0], "bright yellow");
        // A dark band that has no shades for a colour ends the search: no shade, not a
        // brighter band's.
        assert!(shades_for("yellow", [0.3, 0.25, 0.0]).is_empty());
        assert!(shades_for("purple", [0.5, 0.1, 0.5]).is_empty());
    }

    #[test]
    fn bad_colour_files_name_the_file_and_rule() {
        let err = |t: &str| parse_shade_rules("c.toml", t).unwrap_err().to_string();
        let e = err("[[rule]]\ncolour = \"red\"\nhi_above = 2.0\nshades = [\"x\"]\n");
        assert_eq!(e, "c.toml: rule 0 (red): hi_above must lie in 0..=1");
        let e = err(
            "[[rule]]\nshades = [\"x\"]\n[[rule]]\ncolour = \"red\"\nshades = [\"a\", \" \"]\n",
        );
        assert_eq!(e, "c.toml: rule 1 (red): shade 1 is blank");
        let e =
            err("[[rule]]\nhi_below = 0.3\n[[rule.by_colour]]\ncolour = \"red\"\nshades = []\n");
        assert_eq!(e, "c.toml: rule 0, by_colour 0 (red): no shades");
        let e = err("[[rule]]\ncolour = \"red\"\n");
        assert_eq!(e, "c.toml: rule 0 (red): neither shades nor by_colour");
        assert!(err("[[rule]]\nshade = [\"x\"]\n").starts_with("c.toml: not a valid table"));
    }

    #[test]
    fn the_embedded_class_file_is_valid() {
        if let Err(e) = parse_class_words(CLASSES_FILE, include_str!("../data/classes.toml")) {
            panic!("{e}");
        }
        assert_eq!(class_uses(C::Cup), class_uses(C::Mug));
        assert!(class_uses(C::Wall).is_empty());
    }

    #[test]
    fn bad_class_files_name_the_file_and_class() {
        let err = |t: &str| parse_class_words("w.toml", t).unwrap_err().to_string();
        let e = err("[class_names]\nsofaa = [\"sofa\"]\n[class_uses]\n");
        assert_eq!(e, "w.toml: class_names.sofaa: no such class");
        let e = err("[class_names]\nsofa = [\"sofa\", \"sofa\"]\n[class_uses]\n");
        assert_eq!(
            e,
            "w.toml: class_names.sofa: entry 1 (\"sofa\") is listed twice"
        );
        let e = err("[class_names]\n[class_uses]\nsofa = [\" \"]\n");
        assert_eq!(e, "w.toml: class_uses.sofa: entry 0 is blank");
        let e = err("[class_names]\n[class_uses]\n");
        assert!(
            e.starts_with("w.toml: class_names.") && e.ends_with(": missing"),
            "{e}"
        );
    }

    #[test]
    fn numbers_are_written_out() {
        assert_eq!(number_word(3), "three");
        assert_eq!(number_word(14), "fourteen");
        assert_eq!(number_word(40), "forty");
        assert_eq!(number_word(23), "twenty-three");
        assert_eq!(number_word(120), "120");
    }
}
