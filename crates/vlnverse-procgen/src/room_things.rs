//! The room lists of the things placed after a room's furniture and sets, in two lots
//! (`more_things.rs`, then `household.rs`), read from `data/room_things.toml`: for each room
//! type, the classes it may get, how likely each is, where it goes and the least floor area it
//! needs.

use serde::Deserialize;
use std::collections::BTreeMap;
use std::sync::LazyLock;
use vlnverse_env::{RoomType, SemanticClass as C};

/// Where a thing goes in its room.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Spot {
    /// Back to a wall.
    Wall,
    /// In a corner.
    Corner,
    /// Free in the room, away from the walls.
    Centre,
    /// Hung from the ceiling, above the agent's height.
    Ceiling,
    /// On the top of a piece of furniture of the room (which ones, each lot says).
    OnTop,
}

/// One line of a room's list: the class, its chance (times `furniture.pieces`), where it goes
/// and the least room floor area (m²) it needs.
#[derive(Debug)]
pub(crate) struct Thing {
    pub class: C,
    pub chance: f32,
    pub spot: Spot,
    pub min_area: f32,
}

/// The two lots, placed one after the other.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lot {
    /// `more_things.rs`: a ceiling fan, a sectional, a bust, a water heater and the like.
    Second,
    /// `household.rs`: a futon, a record player, a broom and the like; never free in the room
    /// nor on the ceiling.
    Third,
}

/// The things a room of kind `kind` may get in lot `lot`, in the order they are tried.
pub(crate) fn things(lot: Lot, kind: RoomType) -> &'static [Thing] {
    let lists = match lot {
        Lot::Second => &TABLES.0,
        Lot::Third => &TABLES.1,
    };
    lists.get(&kind).map_or(&[], Vec::as_slice)
}

type Lists = BTreeMap<RoomType, Vec<Thing>>;

/// The file, parsed and checked once. It is embedded and checked by the unit tests, so a
/// malformed one never ships.
static TABLES: LazyLock<(Lists, Lists)> =
    LazyLock::new(|| match parse(include_str!("../data/room_things.toml")) {
        Ok(t) => t,
        Err(e) => panic!("embedded data/room_things.toml is malformed: {e}"),
    });

/// One line as written: class, chance, where, least area.
type Line = (String, f32, String, f32);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    second: BTreeMap<String, Vec<Line>>,
    third: BTreeMap<String, Vec<Line>>,
}

/// Parse and check the file: every room type and class a vocabulary name, every chance within
/// 0..=1, every area at least 0, every place a known one (the third lot's only on a wall, in a
/// corner or on top).
fn parse(text: &str) -> Result<(Lists, Lists), String> {
    let file = toml::from_str::<File>(text).map_err(|e| e.to_string())?;
    Ok((
        lists(file.second, Lot::Second)?,
        lists(file.third, Lot::Third)?,
    ))
}

fn lists(raw: BTreeMap<String, Vec<Line>>, lot: Lot) -> Result<Lists, String> {
    let section = match lot {
        Lot::Second => "second",
        Lot::Third => "third",
    };
    raw.into_iter()
        .map(|(room, lines)| {
            let at = |i: usize| format!("[{section}] {room}, line {}", i + 1);
            let kind = RoomType::from_name(&room)
                .ok_or_else(|| format!("[{section}]: `{room}` is not a room type"))?;
            let things = lines
                .into_iter()
                .enumerate()
                .map(|(i, (class, chance, spot, min_area))| {
                    let class = C::from_name(&class)
                        .ok_or_else(|| format!("{}: `{class}` is not a class", at(i)))?;
                    if !(0.0..=1.0).contains(&chance) {
                        return Err(format!("{}: chance {chance} is not within 0..=1", at(i)));
                    }
                    if min_area.is_nan() || min_area < 0.0 {
                        return Err(format!("{}: least area {min_area} is below 0", at(i)));
                    }
                    let spot = match (spot.as_str(), lot) {
                        ("wall", _) => Spot::Wall,
                        ("corner", _) => Spot::Corner,
                        ("on_top", _) => Spot::OnTop,
                        ("centre", Lot::Second) => Spot::Centre,
                        ("ceiling", Lot::Second) => Spot::Ceiling,
                        _ => return Err(format!("{}: `{spot}` is not a place here", at(i))),
                    };
                    Ok(Thing {
                        class,
                        chance,
                        spot,
                        min_area,
                    })
                })
                .collect::<Result<Vec<_>, String>>()?;
            Ok((kind, things))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_file_parses() {
        let (second, third) = &*TABLES;
        assert!(second.values().map(Vec::len).sum::<usize>() > 50);
        assert!(third.values().map(Vec::len).sum::<usize>() > 50);
        assert!(things(Lot::Third, RoomType::Sauna).is_empty());
        assert_eq!(
            things(Lot::Third, RoomType::Kitchen)[0].class,
            C::KnifeBlock
        );
    }

    #[test]
    fn a_bad_file_is_refused_naming_the_line() {
        let ok = "[second]\n[third]\n";
        assert!(parse(ok).is_ok());
        let bad = [
            (
                "[second]\nkitchen = [[\"sofa\", 1.5, \"wall\", 0.0]]\n[third]\n",
                "chance 1.5",
            ),
            (
                "[second]\nkitchen = [[\"sofaa\", 0.5, \"wall\", 0.0]]\n[third]\n",
                "`sofaa`",
            ),
            ("[second]\nkitchn = []\n[third]\n", "`kitchn`"),
            (
                "[second]\n[third]\nkitchen = [[\"broom\", 0.5, \"ceiling\", 0.0]]\n",
                "line 1",
            ),
            (
                "[second]\nkitchen = [[\"sofa\", 0.5, \"wall\", -1.0]]\n[third]\n",
                "below 0",
            ),
        ];
        for (text, want) in bad {
            let e = parse(text).unwrap_err();
            assert!(e.contains(want), "{e}");
        }
    }
}
