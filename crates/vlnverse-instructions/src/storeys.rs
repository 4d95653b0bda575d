//! Instructions across floors (issue 30, item 3): the stair phrases of `data/stairs.toml` and
//! the joins that put them between the instructions of the walks on each floor.
//!
//! A route across floors is walks on one level joined by flights of stairs. The generator
//! describes each walk with the ordinary generator on that level's view of the scene (so every
//! room and landmark it names is on the floor the walk is on) and joins them here:
//! - fine: "<walk 1> Go up the stairs. At the top of the stairs, <walk 2>", or "... Stop at the
//!   top of the stairs." when the goal is where the flight arrives;
//! - coarse: "Go upstairs. <the goal's description>" (casual: "go upstairs, then <...>").
//!
//! Grounding is kept exact: the walks' grounded path indices are offset into the whole path by
//! the caller (see [`crate::offset_grounding`]); the stair sentences ground nothing.

use std::sync::LazyLock;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use vlnverse_score::episode::{Instruction, Style};
use vlnverse_score::{DataError, Result};

use crate::data::{expect_embedded, parse_toml, DataFileError};
use crate::lexicon::number_word;
use crate::phrases::{self as ph, capitalize, decapitalize, fill, Bank};

/// The stair phrase file, as errors name it.
const FILE: &str = "data/stairs.toml";

/// The stair phrase file's text.
const TEXT: &str = include_str!("../data/stairs.toml");

/// Which way a flight of stairs is walked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flight {
    /// Up, to the floor above.
    Up,
    /// Down, to the floor below.
    Down,
}

/// The banks of `data/stairs.toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct StairPhrases {
    up: Vec<String>,
    down: Vec<String>,
    up_opener: Vec<String>,
    down_opener: Vec<String>,
    up_stop: Vec<String>,
    down_stop: Vec<String>,
    up_goal: Vec<String>,
    down_goal: Vec<String>,
    up_casual: Vec<String>,
    down_casual: Vec<String>,
    up_steps: Vec<String>,
    down_steps: Vec<String>,
}

impl StairPhrases {
    fn banks(&self) -> [(&'static str, &[String]); 12] {
        [
            ("up", &self.up),
            ("down", &self.down),
            ("up_opener", &self.up_opener),
            ("down_opener", &self.down_opener),
            ("up_stop", &self.up_stop),
            ("down_stop", &self.down_stop),
            ("up_goal", &self.up_goal),
            ("down_goal", &self.down_goal),
            ("up_casual", &self.up_casual),
            ("down_casual", &self.down_casual),
            ("up_steps", &self.up_steps),
            ("down_steps", &self.down_steps),
        ]
    }
}

/// Parse and check the file: every bank has entries, none blank.
fn parse(text: &str) -> std::result::Result<StairPhrases, DataFileError> {
    let p: StairPhrases = parse_toml(FILE, text)?;
    for (name, bank) in p.banks() {
        if bank.is_empty() {
            return Err(DataFileError::new(
                FILE,
                format!("bank `{name}`"),
                "has no entries",
            ));
        }
        if let Some(i) = bank.iter().position(|e| e.trim().is_empty()) {
            return Err(DataFileError::new(
                FILE,
                format!("bank `{name}`, entry {i}"),
                "is blank",
            ));
        }
    }
    Ok(p)
}

static PHRASES: LazyLock<StairPhrases> = LazyLock::new(|| expect_embedded(parse(TEXT)));

fn pick<'a>(rng: &mut ChaCha8Rng, bank: &'a [String]) -> &'a str {
    &bank[rng.random_range(0..bank.len())]
}

/// A fine instruction across floors: `walks[i]` is the instruction of the i-th walk (its
/// grounding already offset into the whole path), `None` for a walk too short to describe;
/// `flights[i]` is the flight between walk `i` and walk `i + 1` and its number of steps (0 when
/// not known), so `walks.len() == flights.len() + 1`. An error when the counts do not fit or
/// nothing at all is described.
pub fn join_walks(
    walks: &[Option<Instruction>],
    flights: &[(Flight, u32)],
    seed: u64,
) -> Result<Instruction> {
    if walks.len() != flights.len() + 1 {
        return Err(DataError::invalid(
            "walks",
            walks.len(),
            format!(
                "a route with {} flights has {} walks",
                flights.len(),
                flights.len() + 1
            ),
        ));
    }
    let p = &*PHRASES;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5354_4149_5253);
    let mut text: Vec<String> = Vec::new();
    let mut grounding = Vec::new();
    for (i, walk) in walks.iter().enumerate() {
        let arrived = i.checked_sub(1).map(|j| flights[j].0);
        let body = walk
            .as_ref()
            .map(|w| walk_body(&w.instruction_text, i + 1 == walks.len()));
        match (&body, arrived) {
            (Some(b), Some(f)) => {
                let opener = match f {
                    Flight::Up => pick(&mut rng, &p.up_opener),
                    Flight::Down => pick(&mut rng, &p.down_opener),
                };
                text.push(format!("{opener}{}", decapitalize(b)));
            }
            (Some(b), None) => text.push(b.clone()),
            (None, Some(f)) if i + 1 == walks.len() => text.push(
                match f {
                    Flight::Up => pick(&mut rng, &p.up_stop),
                    Flight::Down => pick(&mut rng, &p.down_stop),
                }
                .to_string(),
            ),
            (None, _) => {}
        }
        if let Some(w) = walk {
            grounding.extend(w.grounding.iter().cloned());
        }
        if let Some(&(f, steps)) = flights.get(i) {
            text.push(flight_sentence(f, steps, &mut rng));
        }
    }
    Ok(Instruction {
        instruction_text: text.join(" "),
        grounding,
        ..Instruction::default()
    })
}

/// The sentence for walking a flight of `steps` steps (0: not known) way `f`; now and then it
/// counts them ("Walk up the sixteen steps.").
fn flight_sentence(f: Flight, steps: u32, rng: &mut ChaCha8Rng) -> String {
    let p = &*PHRASES;
    let counted = (3..=30).contains(&steps) && rng.random_bool(0.15);
    let bank = match (f, counted) {
        (Flight::Up, false) => &p.up,
        (Flight::Down, false) => &p.down,
        (Flight::Up, true) => &p.up_steps,
        (Flight::Down, true) => &p.down_steps,
    };
    fill(pick(rng, bank), &[("n", &number_word(steps))])
}

/// A walk's instruction as a part of a route across floors: without the sentences that give
/// one walk's length as the route's ("It is not far.", "The walk takes a minute."), and, for a
/// walk the route goes on from (`last` false), without those that close it ("You are almost
/// there.", "That's it.") or a "Finally," before its stop, since the stairs come next.
fn walk_body(text: &str, last: bool) -> String {
    let whole_route: [Bank; 2] = [ph::OPEN, ph::WALK_TIME];
    // A walk past the stairs into the next room has still gone too far: the overshoot
    // sentences ("Do not go into the kitchen.") stay.
    let closing: [Bank; 2] = [ph::CLOSE, ph::ASIDE];
    let kept: Vec<String> = sentences(text.trim())
        .into_iter()
        .filter(|s| !whole_route.iter().any(|&b| said_from(s, b)))
        .filter(|s| last || !closing.iter().any(|&b| said_from(s, b)))
        .map(|s| match s.strip_prefix("Finally, ") {
            Some(rest) if !last => capitalize(rest),
            _ => s.to_string(),
        })
        .collect();
    if kept.is_empty() {
        // Nothing but remarks (not made by this crate's generator): keep the walk as written.
        return text.trim().to_string();
    }
    kept.join(" ")
}

/// The sentences of `text`, each with its closing full stop (a full stop followed by a space
/// ends one; "2.5 metres" does not).
fn sentences(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, _) in text.match_indices(". ") {
        out.push(&text[start..=i]);
        start = i + 2;
    }
    if start < text.len() {
        out.push(&text[start..]);
    }
    out
}

/// Whether sentence `s` is an entry of `bank` as filled in: its text around the placeholders,
/// in order (the first letter in either case).
fn said_from(s: &str, bank: Bank) -> bool {
    bank.iter().any(|entry| {
        let pieces: Vec<&str> = entry
            .split('{')
            .map(|p| p.split_once('}').map_or(p, |(_, rest)| rest))
            .collect();
        let lowered = decapitalize(s);
        let mut rest = lowered.as_str();
        for (k, piece) in pieces.iter().enumerate() {
            let piece = decapitalize(piece);
            let found = if k == 0 {
                rest.starts_with(&piece).then_some(0)
            } else if k + 1 == pieces.len() {
                rest.ends_with(&piece).then(|| rest.len() - piece.len())
            } else {
                rest.find(&piece)
            };
            match found {
                Some(at) => rest = &rest[at + piece.len()..],
                None => return false,
            }
        }
        pieces.len() > 1 || rest.is_empty()
    })
}

/// A coarse instruction whose goal is on another floor than the start: `ins` (the goal's
/// description, grounding already offset) led by a sentence that says to take the stairs
/// (`flight`: the last flight of the route) and that the goal is upstairs / downstairs. The
/// style's casing is kept (a casual instruction stays lowercase).
pub fn goal_across(ins: &Instruction, flight: Flight, seed: u64) -> Instruction {
    let p = &*PHRASES;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x0055_5053_5441_4952);
    let body = ins.instruction_text.trim();
    let text = if ins.style == Some(Style::Casual) {
        let lead = match flight {
            Flight::Up => pick(&mut rng, &p.up_casual),
            Flight::Down => pick(&mut rng, &p.down_casual),
        };
        format!("{lead}{body}")
    } else {
        let lead = match flight {
            Flight::Up => pick(&mut rng, &p.up_goal),
            Flight::Down => pick(&mut rng, &p.down_goal),
        };
        format!("{lead} {body}")
    };
    Instruction {
        instruction_text: text,
        ..ins.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_score::episode::{GroundedObject, Role};

    fn ins(text: &str, index: u32) -> Instruction {
        Instruction {
            instruction_text: text.into(),
            grounding: vec![GroundedObject {
                object_id: 3,
                class: "bed".into(),
                role: Role::Target,
                side: None,
                path_index: Some(index),
            }],
            ..Instruction::default()
        }
    }

    #[test]
    fn the_data_file_parses_and_every_bank_has_words() {
        let p = parse(TEXT).unwrap();
        for (name, bank) in p.banks() {
            assert!(!bank.is_empty(), "{name}");
        }
        let up =
            p.up.iter()
                .chain(&p.up_goal)
                .any(|e| e.contains("up the stairs"));
        assert!(up);
        assert!(p.up_goal.iter().any(|e| e.contains("upstairs")));
        assert!(p.up_goal.iter().any(|e| e.contains("upper floor")));
        assert!(p.up_opener.iter().any(|e| e.contains("landing")));
    }

    #[test]
    fn an_empty_bank_is_refused_naming_it() {
        let bad = TEXT.replacen("up_stop = [", "up_stop = [] \nunused = [", 1);
        let e = parse(&bad).unwrap_err().to_string();
        assert!(e.contains("data/stairs.toml"), "{e}");
    }

    #[test]
    fn a_fine_walk_up_says_the_stairs_and_keeps_both_walks_grounding() {
        let a = ins("Walk past the sofa and stop at the stairs.", 1);
        let b = ins("Turn left and stop by the bed.", 7);
        let j = join_walks(&[Some(a), Some(b)], &[(Flight::Up, 0)], 3).unwrap();
        let t = &j.instruction_text;
        assert!(t.starts_with("Walk past the sofa"), "{t}");
        assert!(t.contains("stairs."), "{t}");
        assert!(t.contains("turn left and stop by the bed."), "{t}");
        assert!(!t.contains("Turn left"), "{t}");
        let idx: Vec<_> = j.grounding.iter().map(|g| g.path_index).collect();
        assert_eq!(idx, vec![Some(1), Some(7)]);
        assert_eq!(
            j,
            join_walks(
                &[
                    Some(ins("Walk past the sofa and stop at the stairs.", 1)),
                    Some(ins("Turn left and stop by the bed.", 7))
                ],
                &[(Flight::Up, 0)],
                3
            )
            .unwrap()
        );
    }

    #[test]
    fn only_the_last_walk_closes_the_route() {
        let a = ins(
            "It is not far. Walk 2.5 metres to the stairs. You are almost there. Finally, stop \
             by the stairs. If you reach the kitchen, you have gone too far. That's it.",
            1,
        );
        let b = ins("Turn left. Finally, stop by the bed. That's it.", 7);
        let j = join_walks(&[Some(a), Some(b)], &[(Flight::Up, 0)], 3).unwrap();
        let t = &j.instruction_text;
        assert!(
            t.starts_with("Walk 2.5 metres to the stairs. Stop by the stairs. "),
            "{t}"
        );
        assert!(
            t.contains("If you reach the kitchen, you have gone too far."),
            "{t}"
        );
        for gone in ["not far", "almost there"] {
            assert!(!t.contains(gone), "{t}");
        }
        assert_eq!(t.matches("That's it.").count(), 1, "{t}");
        assert!(t.ends_with("Finally, stop by the bed. That's it."), "{t}");
        assert_eq!(j.grounding.len(), 2);
    }

    #[test]
    fn a_flight_is_now_and_then_counted_in_its_true_steps() {
        let (mut counted, mut any) = (0, 0);
        for seed in 0..80 {
            let walks = [Some(ins("Walk to the stairs.", 1)), Some(ins("Stop.", 4))];
            let t = join_walks(&walks, &[(Flight::Down, 16)], seed)
                .unwrap()
                .instruction_text;
            counted += usize::from(t.contains("sixteen steps"));
            let unknown = join_walks(&walks, &[(Flight::Down, 0)], seed)
                .unwrap()
                .instruction_text;
            any += usize::from(unknown.contains("{n}") || unknown.contains("zero"));
        }
        assert!(counted > 0 && counted < 40, "{counted} of 80 counted");
        assert_eq!(any, 0);
    }

    #[test]
    fn a_walk_ending_where_the_flight_arrives_stops_there() {
        let a = ins("Walk to the hall.", 1);
        let j = join_walks(&[Some(a), None], &[(Flight::Down, 0)], 1).unwrap();
        let t = &j.instruction_text;
        assert!(t.contains("down"), "{t}");
        assert!(t.ends_with("stairs."), "{t}");
        assert!(join_walks(&[None], &[(Flight::Up, 0)], 1).is_err());
    }

    #[test]
    fn a_coarse_goal_upstairs_says_so_in_its_style() {
        let mut c = ins("go straight to the beige sink in the bathroom", 9);
        c.style = Some(Style::Casual);
        let j = goal_across(&c, Flight::Up, 5);
        assert!(j
            .instruction_text
            .ends_with("go straight to the beige sink in the bathroom"));
        assert!(j.instruction_text.chars().next().unwrap().is_lowercase());
        assert!(j.instruction_text.contains("up"));
        assert_eq!(j.grounding, c.grounding);
        let mut f = ins("Make your way to the beige sink.", 9);
        f.style = Some(Style::Formal);
        let j = goal_across(&f, Flight::Down, 5);
        assert!(
            j.instruction_text.contains("down"),
            "{}",
            j.instruction_text
        );
        assert!(j
            .instruction_text
            .ends_with("Make your way to the beige sink."));
    }
}
