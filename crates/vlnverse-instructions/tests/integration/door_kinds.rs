//! A doorway is named by its kind ("the sliding glass door", "the French door", "the archway")
//! only when it is of that kind.

use crate::instructions_fixture::{paths, worlds, Ctx, World};
use vlnverse_env::DoorKind;
use vlnverse_instructions::{InstructionGenerator, TemplateGenerator};

/// Words that name a kind of doorway.
const KIND_WORDS: [&str; 5] = [
    "sliding",
    "french door",
    "double door",
    "glass door",
    "arch",
];

/// The first three tiny homes with every doorway made of one kind: those with a leaf
/// `leafed`, those without one (and not open-plan) `bare`.
fn with_kinds(leafed: DoorKind, bare: DoorKind) -> Vec<World> {
    let mut ws = worlds(3);
    for w in &mut ws {
        for d in &mut w.scene.doors {
            d.kind = match (d.leaf.is_some(), d.open_plan) {
                (true, _) => leafed,
                (false, false) => bare,
                (false, true) => DoorKind::Hinged,
            };
        }
    }
    ws
}

/// The fine instructions of 15 paths, 8 seeds each, in each of the first three tiny homes.
fn texts(worlds: &[World]) -> Vec<String> {
    let g = TemplateGenerator::default();
    let mut out = Vec::new();
    for w in worlds {
        for s in paths(w, 15, 9) {
            let ctx = w.ctx(&s);
            for seed in 0..8 {
                out.push(g.fine(&ctx, seed).unwrap().instruction_text.to_lowercase());
            }
        }
    }
    out
}

fn count(texts: &[String], words: &[&str]) -> usize {
    texts
        .iter()
        .filter(|t| words.iter().any(|w| t.contains(w)))
        .count()
}

#[test]
fn doorways_are_named_by_their_kind_only_when_they_are_of_it() {
    let plain = texts(&with_kinds(DoorKind::Hinged, DoorKind::Hinged));
    assert_eq!(
        count(&plain, &KIND_WORDS),
        0,
        "a plain door named by a kind"
    );

    let t = texts(&with_kinds(DoorKind::Sliding, DoorKind::Arched));
    assert!(
        count(&t, &["sliding", "glass door"]) > 0,
        "no sliding door named"
    );
    assert!(count(&t, &["arch"]) > 0, "no archway named");
    assert_eq!(count(&t, &["french door", "double door"]), 0);

    let t = texts(&with_kinds(DoorKind::French, DoorKind::Hinged));
    assert!(
        count(&t, &["french door", "double door"]) > 0,
        "no French door named"
    );
    assert_eq!(count(&t, &["sliding", "arch"]), 0);
}
