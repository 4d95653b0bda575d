//! Phrase banks of the template generator, written for this project.
//!
//! The banks are data: `data/phrases.toml`, one table per bank, embedded at build time and
//! parsed and checked once, at first use (the unit tests parse it too, so a malformed file never
//! ships). The code names a bank by a [`Bank`] constant (`START_TURN` is the table
//! `start_turn`); a bank dereferences to its entries, in the file's order, and [`pick`] draws
//! one uniformly.
//!
//! Placeholders: `{obj}` an object phrase ("the dark red sofa"), `{room}` a room ("the
//! kitchen"), `{from}` the room left behind, `{dir}` left / right, `{side}` a side phrase ("on
//! your left"), `{dist}` a distance ("about 3 metres"), `{door}` an opening ("the doorway"),
//! `{deg}` an angle in degrees, `{clock}` a clock hour; the rest are listed in [`PLACEHOLDERS`]
//! and described at the top of the data file. Each bank declares the placeholders its entries
//! use. No bank says "left", and "right" only as an adverb in the few banks marked so (checked
//! when the file is parsed), so a sentence's sides come from the path only.

use std::collections::BTreeMap;
use std::ops::Deref;
use std::sync::LazyLock;

use serde::Deserialize;

use crate::data::{entry_place, expect_embedded, parse_toml, DataFileError};

/// The phrase file, as errors name it.
const FILE: &str = "data/phrases.toml";

/// The phrase file's text.
const TEXT: &str = include_str!("../data/phrases.toml");

/// Every placeholder a bank may declare: the keys the code fills with [`fill`].
pub(crate) const PLACEHOLDERS: &[&str] = &[
    "obj", "room", "from", "mid", "door", "dir", "side", "dist", "deg", "clock", "n", "t", "where",
    "ord", "num", "name", "names", "desc", "sup", "rel", "a", "m", "c", "use", "f", "to",
];

/// One bank of phrases: a name for the code, its entries in the data file. Dereferences to the
/// entries (`pick(rng, &TURN)`); [`Bank::entries`] gives them with a `'static` lifetime.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Bank(usize);

impl Bank {
    /// The bank's entries, in the data file's order.
    pub(crate) fn entries(self) -> &'static [&'static str] {
        &BANKS[self.0]
    }

    /// The bank's table name in the data file.
    #[cfg(test)]
    pub(crate) fn key(self) -> &'static str {
        KEYS[self.0]
    }
}

impl Deref for Bank {
    type Target = [&'static str];

    fn deref(&self) -> &[&'static str] {
        self.entries()
    }
}

/// Declares the banks: `CONST = table_name`, in the data file's order. Gives a [`Bank`]
/// constant for each and [`KEYS`], the table names by bank index.
/// The indices come from an enum of the constants' names (no recursion, so no limit on the
/// number of banks).
macro_rules! banks {
    ($($konst:ident = $key:ident,)*) => {
        /// The table names of the banks, by [`Bank`] index.
        const KEYS: &[&str] = &[$(stringify!($key)),*];
        /// The index of each bank, in the data file's order.
        #[allow(non_camel_case_types, clippy::upper_case_acronyms)]
        #[derive(Clone, Copy)]
        enum BankIndex {
            $($konst,)*
        }
        $(pub(crate) const $konst: Bank = Bank(BankIndex::$konst as usize);)*
    };
}

banks! {
    START_TURN = start_turn,
    TURN_AROUND = turn_around,
    TURN = turn,
    TURN_DEG = turn_deg,
    SLIGHT_TURN = slight_turn,
    SLIGHT_CLOCK = slight_clock,
    MOVE_VERB = move_verb,
    ONWARD = onward,
    MANNER = manner,
    THROUGH_ROOM = through_room,
    ALONG_HALL = along_hall,
    DIST_SHORT = dist_short,
    ABOUT = about,
    METRES = metres,
    ONE_METRE = one_metre,
    DOOR_SLIDING = door_sliding,
    DOOR_FRENCH = door_french,
    DOOR_FRENCH_LEAF = door_french_leaf,
    DOOR_ARCHED = door_arched,
    OUT_THROUGH_DOOR = out_through_door,
    PASS_SIDE = pass_side,
    SEE_SIDE = see_side,
    SEE_SIDE_GROUP = see_side_group,
    SEE_SIDE_A = see_side_a,
    WITH_SIDE = with_side,
    AFTER_OBJ = after_obj,
    TOWARDS = towards,
    UNTIL_OBJ = until_obj,
    SIDE = side,
    LEAVE_ROOM = leave_room,
    ENTER_ROOM = enter_room,
    THROUGH_DOOR = through_door,
    ROOM_TO_ROOM = room_to_room,
    THROUGH_ROOMS = through_rooms,
    LEAVE_BY_DOOR = leave_by_door,
    NOW_IN = now_in,
    START_ROOM = start_room,
    STOP_AT = stop_at,
    STOP_FOOT = stop_foot,
    IN_CORNER = in_corner,
    AT_WALL = at_wall,
    MID_ROOM = mid_room,
    BY_DOOR = by_door,
    STOP_ROOM = stop_room,
    STOP_ROOM_WHERE = stop_room_where,
    STOP = stop,
    MOVE_WHOLE = move_whole,
    WALK_TIME = walk_time,
    OVERSHOOT = overshoot,
    ONLY_ONE = only_one,
    CANT_MISS = cant_miss,
    ROOM_SMALL = room_small,
    ROOM_BIG = room_big,
    HALL_LONG = hall_long,
    HALL_EMPTY = hall_empty,
    ROOM_NO_WINDOW = room_no_window,
    ROOM_HAS_MANY = room_has_many,
    FLOOR_CHANGE = floor_change,
    NUMBERED = numbered,
    AND = and,
    NEXT = next,
    LAST = last,
    OPEN = open,
    ASIDE = aside,
    CLOSE = close,
    FORMAL_OPEN = formal_open,
    FORMAL = formal,
    FORMAL_CLOSE = formal_close,
    FORMAL_SUP = formal_sup,
    FORMAL_NEXT = formal_next,
    FORMAL_NEAR = formal_near,
    FORMAL_ROOM = formal_room,
    NATURAL_OPEN = natural_open,
    NATURAL_ROOM = natural_room,
    NATURAL = natural,
    NATURAL_CLOSE = natural_close,
    NATURAL_SUP = natural_sup,
    NATURAL_NEXT = natural_next,
    NATURAL_NEAR = natural_near,
    CASUAL_OPEN = casual_open,
    CASUAL = casual,
    CASUAL_CLOSE = casual_close,
    CASUAL_SUP = casual_sup,
    CASUAL_NEXT = casual_next,
    CASUAL_NEAR = casual_near,
    CLOSEST = closest,
    CASUAL_ROOM = casual_room,
    FORMAL_MATERIAL = formal_material,
    FORMAL_SHADE = formal_shade,
    FORMAL_USE = formal_use,
    FORMAL_PLACE = formal_place,
    NATURAL_MATERIAL = natural_material,
    NATURAL_SHADE = natural_shade,
    NATURAL_USE = natural_use,
    NATURAL_PLACE = natural_place,
    CASUAL_MATERIAL = casual_material,
    CASUAL_SHADE = casual_shade,
    CASUAL_USE = casual_use,
    CASUAL_PLACE = casual_place,
    FORMAL_COUNT = formal_count,
    NATURAL_COUNT = natural_count,
    CASUAL_COUNT = casual_count,
    CHAIN_FIRST = chain_first,
    CHAIN_MID = chain_mid,
    CHAIN_LAST = chain_last,
    CHAIN_CASUAL = chain_casual,
    TURN_AGAIN = turn_again,
    SHARP_TURN = sharp_turn,
    AT_ONCE = at_once,
    HALL_END = hall_end,
    TO_HALL_END = to_hall_end,
    HALFWAY = halfway,
    BEFORE_HALL_END = before_hall_end,
    GO_OUTSIDE = go_outside,
    STOP_DOORWAY = stop_doorway,
    STOP_BETWEEN = stop_between,
    ROOM_MASTER = room_master,
    ROOM_GUEST = room_guest,
    ROOM_NURSERY = room_nursery,
    ROOM_EN_SUITE = room_en_suite,
    ROOM_MAIN_BATH = room_main_bath,
    ROOM_WALK_IN = room_walk_in,
    PASS_BETWEEN = pass_between,
    SEE_BETWEEN = see_between,
    SLIGHT_AGAIN = slight_again,
    ROOM_WINDOW = room_window,
    ROOM_WINDOWS = room_windows,
    ROOM_HAS = room_has,
    IMMEDIATE_TURN = immediate_turn,
    FLOOR_WOOD = floor_wood,
    FLOOR_TILE = floor_tile,
    FLOOR_CARPET = floor_carpet,
    FLOOR_STONE = floor_stone,
    FLOOR_CONCRETE = floor_concrete,
    END_COUNT = end_count,
    ROOM_DOORS = room_doors,
    ROOM_DOORS_CLOSED = room_doors_closed,
    ROOM_DOORWAYS = room_doorways,
    ROOM_OPENINGS = room_openings,
    ROOM_HALF_BATH = room_half_bath,
    STAIRWELL = stairwell,
    ROUTE_ROOMS = route_rooms,
    ROOM_OPEN_KITCHEN = room_open_kitchen,
    ROOM_OPEN_DINING = room_open_dining,
    ROOM_OPEN_LIVING = room_open_living,
    ROOM_GAME = room_game,
    ROOM_STUDIO = room_studio,
    HALL_LEADS = hall_leads,
    ROOM_LANDING = room_landing,
    DIAGONAL = diagonal,
    STOP_ON = stop_on,
    STOP_EDGE = stop_edge,
    STOP_FLOOR_CHANGE = stop_floor_change,
    ROOM_PASSAGE = room_passage,
    ROOM_KITCHENETTE = room_kitchenette,
    ROOM_DECK = room_deck,
    NOT_INTO = not_into,
    STILL_IN = still_in,
    AFTER_LEAVING = after_leaving,
    SEE_SIDE_ALSO = see_side_also,
}

/// A bank as written in the data file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BankSpec {
    /// Placeholders every entry contains.
    #[serde(default)]
    placeholders: Vec<String>,
    /// Placeholders an entry may contain.
    #[serde(default)]
    optional: Vec<String>,
    /// Whether "" (saying nothing) is an entry.
    #[serde(default)]
    may_be_empty: bool,
    /// Whether "right" appears as an adverb ("right by {obj}").
    #[serde(default)]
    adverb_right: bool,
    /// The phrases, in order.
    entries: Vec<String>,
}

/// The entries of every bank, by [`Bank`] index, parsed once.
static OWNED: LazyLock<Vec<Vec<String>>> =
    LazyLock::new(|| expect_embedded(parse_banks(FILE, TEXT)));

/// [`OWNED`] as string slices, which [`pick`] hands out.
static BANKS: LazyLock<Vec<Vec<&'static str>>> = LazyLock::new(|| {
    OWNED
        .iter()
        .map(|b| b.iter().map(String::as_str).collect())
        .collect()
});

/// Parse and check a phrase file: every bank of [`KEYS`] present and no other, each valid
/// ([`check_bank`]). Gives the entries by bank index.
fn parse_banks(file: &'static str, text: &str) -> Result<Vec<Vec<String>>, DataFileError> {
    let mut specs: BTreeMap<String, BankSpec> = parse_toml(file, text)?;
    if let Some(k) = specs.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(DataFileError::new(
            file,
            format!("bank `{k}`"),
            "no such bank in the code",
        ));
    }
    KEYS.iter()
        .map(|&k| {
            let spec = specs
                .remove(k)
                .ok_or_else(|| DataFileError::new(file, format!("bank `{k}`"), "missing"))?;
            check_bank(file, k, &spec)?;
            Ok(spec.entries)
        })
        .collect()
}

/// The placeholders of an entry (`{key}`), or what is wrong with its braces.
fn placeholders_of(entry: &str) -> Result<Vec<&str>, String> {
    let mut out = Vec::new();
    let mut rest = entry;
    while let Some(open) = rest.find(['{', '}']) {
        if rest[open..].starts_with('}') {
            return Err("a `}` without its `{`".into());
        }
        let after = &rest[open + 1..];
        let close = after.find('}').ok_or("a `{` without its `}`")?;
        let key = &after[..close];
        if key.is_empty() || !key.chars().all(|c| c.is_ascii_lowercase()) {
            return Err(format!("`{{{key}}}` is not a placeholder"));
        }
        out.push(key);
        rest = &after[close + 1..];
    }
    Ok(out)
}

/// Check one bank: it has a non-empty entry; no entry is only spaces, and none is empty unless
/// the bank says `may_be_empty`; the placeholders it declares are known ones, each used, and
/// its entries use only those and all of `placeholders`; no entry says "left", nor "right"
/// unless the bank says `adverb_right`; no phrase is listed twice (repeated "" or "." are
/// weights).
fn check_bank(file: &'static str, key: &str, spec: &BankSpec) -> Result<(), DataFileError> {
    let bank_err = |msg: String| DataFileError::new(file, format!("bank `{key}`"), msg);
    if spec.entries.iter().all(|e| e.is_empty()) {
        return Err(bank_err("no entries".into()));
    }
    for p in spec.placeholders.iter().chain(&spec.optional) {
        if !PLACEHOLDERS.contains(&p.as_str()) {
            return Err(bank_err(format!("`{{{p}}}` is not a known placeholder")));
        }
        if spec
            .entries
            .iter()
            .all(|e| !e.contains(&format!("{{{p}}}")))
        {
            return Err(bank_err(format!("declares `{{{p}}}` but no entry uses it")));
        }
    }
    if let Some(p) = spec.placeholders.iter().find(|p| spec.optional.contains(p)) {
        return Err(bank_err(format!("`{{{p}}}` is both required and optional")));
    }
    for (i, e) in spec.entries.iter().enumerate() {
        let err = |msg: String| DataFileError::new(file, entry_place("bank", key, i, e), msg);
        if e.is_empty() && !spec.may_be_empty {
            return Err(err(
                "empty (say `may_be_empty = true` if saying nothing is meant)".into(),
            ));
        }
        if !e.is_empty() && e.trim().is_empty() {
            return Err(err("only spaces".into()));
        }
        let used = placeholders_of(e).map_err(&err)?;
        if let Some(p) = used.iter().find(|p| {
            !spec
                .placeholders
                .iter()
                .chain(&spec.optional)
                .any(|d| d == *p)
        }) {
            return Err(err(format!(
                "uses `{{{p}}}`, which the bank does not declare (placeholders / optional)"
            )));
        }
        if let Some(p) = spec
            .placeholders
            .iter()
            .find(|p| !used.contains(&p.as_str()))
        {
            return Err(err(format!(
                "lacks `{{{p}}}`, which every entry of the bank must use"
            )));
        }
        let lower = e.to_lowercase();
        if lower.contains("left") || (!spec.adverb_right && lower.contains("right")) {
            return Err(err(
                "names a side: sides come from the path, through `{dir}` or `{side}`".into(),
            ));
        }
        if e.chars().any(char::is_alphabetic) && spec.entries[..i].contains(e) {
            return Err(err("listed twice".into()));
        }
    }
    Ok(())
}

/// Pick one entry of a bank.
pub(crate) fn pick<'a, R: rand::Rng>(rng: &mut R, bank: &[&'a str]) -> &'a str {
    bank[rng.random_range(0..bank.len())]
}

/// Replace `{key}` placeholders.
pub(crate) fn fill(template: &str, pairs: &[(&str, &str)]) -> String {
    let mut s = template.to_string();
    for (k, v) in pairs {
        s = s.replace(&format!("{{{k}}}"), v);
    }
    s
}

/// Capitalise the first letter.
pub(crate) fn capitalize(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().collect::<String>() + c.as_str(),
        None => String::new(),
    }
}

/// Lower-case the first letter (for chaining sentences).
pub(crate) fn decapitalize(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_lowercase().collect::<String>() + c.as_str(),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_phrase_file_is_valid() {
        if let Err(e) = parse_banks(FILE, TEXT) {
            panic!("{e}");
        }
        assert_eq!(BANKS.len(), KEYS.len());
        assert_eq!(TURN.key(), "turn");
        assert_eq!(CHAIN_LAST.entries()[0], "finally, ");
    }

    #[test]
    fn turn_around_always_says_so() {
        for e in TURN_AROUND.iter() {
            let l = e.to_lowercase();
            assert!(
                [
                    "around",
                    "opposite",
                    "u-turn",
                    "turn back",
                    "180 degrees",
                    "eighty degrees"
                ]
                .iter()
                .any(|k| l.contains(k)),
                "`{e}`"
            );
        }
    }

    #[test]
    fn side_and_turn_banks_name_the_direction() {
        for bank in [START_TURN, TURN, TURN_DEG, SLIGHT_TURN, SIDE] {
            for e in bank.iter() {
                assert!(e.contains("{dir}"), "{}: `{e}`", bank.key());
            }
        }
    }

    /// The embedded file with `from` replaced by `to` (once, where it must occur).
    fn edited(from: &str, to: &str) -> String {
        assert!(TEXT.contains(from), "{from}");
        TEXT.replacen(from, to, 1)
    }

    fn error_of(text: &str) -> String {
        parse_banks("test.toml", text).unwrap_err().to_string()
    }

    #[test]
    fn bad_files_name_the_file_bank_and_entry() {
        let e = error_of(&edited(
            "    \"turn to your {dir}\",\n",
            "    \"turn to your {dri}\",\n",
        ));
        assert!(
            e.starts_with("test.toml: bank `start_turn`, entry 2 (\"turn to your {dri}\"):"),
            "{e}"
        );
        let e = error_of(&edited(
            "    \"turn {dir} first\",\n",
            "    \"turn {dir} first to the left\",\n",
        ));
        assert!(
            e.contains("bank `start_turn`, entry 5") && e.contains("side"),
            "{e}"
        );
        let e = error_of(&edited(
            "    \"turn around and face the other way\",\n",
            "    \"turn around and face the other way\",\n    \"  \",\n",
        ));
        assert!(
            e.contains("bank `turn_around`, entry 3") && e.contains("spaces"),
            "{e}"
        );
        let e = error_of(&edited(
            "    \"turn around and face the other way\",\n",
            "    \"turn around and face the other way\",\n    \"\",\n",
        ));
        assert!(
            e.contains("bank `turn_around`, entry 3") && e.contains("empty"),
            "{e}"
        );
        let e = error_of(&edited("    \"face {dir}\",\n", "    \"face {dir\",\n"));
        assert!(e.contains("entry 1") && e.contains("without its"), "{e}");
        let e = error_of(&edited("    \"face {dir}\",\n", "    \"face {obj}\",\n"));
        assert!(e.contains("does not declare"), "{e}");
        let e = error_of(&edited("[start_turn]", "[start_turns]"));
        assert!(
            e.starts_with("test.toml: bank `start_turns`: no such bank"),
            "{e}"
        );
        let e = error_of(&edited(
            "placeholders = [\"dir\"]\nentries",
            "placeholders = [\"dri\"]\nentries",
        ));
        assert!(e.contains("`{dri}` is not a known placeholder"), "{e}");
        let e = error_of(&edited(
            "[turn_around]\nentries = [",
            "[turn_around]\nentries = [\"u-turn\"]\n[x]\nentries = [",
        ));
        assert!(e.starts_with("test.toml: bank `x`: no such bank"), "{e}");
        let e = error_of("[start_turn]\nentries = []\n");
        assert!(
            e.starts_with("test.toml: bank `start_turn`: no entries"),
            "{e}"
        );
        let e = error_of("[start_turn\n");
        assert!(e.starts_with("test.toml: not a valid table"), "{e}");
    }
}
