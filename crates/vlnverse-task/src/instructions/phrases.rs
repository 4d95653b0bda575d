//! Phrase banks of the template generator, written for this project.
//!
//! Placeholders: `{obj}` an object phrase ("the red sofa"), `{room}` a room ("the kitchen"),
//! `{dir}` left / right, `{side}` a side phrase ("on your left"), `{dist}` a distance
//! ("about 3 metres"), `{desc}` a referring expression, `{sup}` a support phrase.

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

// ---------------------------------------------------------------- fine-grained

/// Turning in place at the start (`{dir}` = left / right).
pub(crate) const START_TURN: &[&str] = &[
    "turn {dir}",
    "face {dir}",
    "turn to your {dir}",
    "rotate to the {dir}",
    "swing round to the {dir}",
    "begin by turning {dir}",
];

/// Turning around (start or mid-path).
pub(crate) const TURN_AROUND: &[&str] = &[
    "turn around",
    "turn all the way around",
    "spin around",
    "face the opposite way",
    "do a U-turn",
    "turn back the way you are facing",
];

/// A clear turn at a waypoint.
pub(crate) const TURN: &[&str] = &[
    "turn {dir}",
    "take a {dir}",
    "make a {dir} turn",
    "go {dir}",
    "hang a {dir}",
    "head {dir}",
    "swing {dir}",
    "take the {dir} turn",
];

/// A slight turn at a waypoint.
pub(crate) const SLIGHT_TURN: &[&str] = &[
    "bear slightly {dir}",
    "veer {dir}",
    "turn slightly {dir}",
    "drift a little to the {dir}",
    "angle {dir}",
    "curve gently {dir}",
    "keep slightly {dir}",
];

/// Walking along a leg, with a distance.
pub(crate) const MOVE_DIST: &[&str] = &[
    "walk forward {dist}",
    "go straight for {dist}",
    "continue ahead {dist}",
    "move forward {dist}",
    "head straight {dist}",
    "keep walking for {dist}",
    "proceed {dist}",
    "carry on {dist}",
    "walk on for {dist}",
    "advance {dist}",
];

/// Walking along a leg, without a distance.
pub(crate) const MOVE: &[&str] = &[
    "walk forward",
    "go straight",
    "continue ahead",
    "keep going",
    "move ahead",
    "walk straight on",
    "carry on forward",
    "head onward",
    "keep moving",
    "go on ahead",
];

/// Passing a landmark on a side (`{obj}`, `{side}`).
pub(crate) const PASS_SIDE: &[&str] = &[
    "passing {obj} {side}",
    "with {obj} {side}",
    "keeping {obj} {side}",
    "going past {obj} {side}",
    "so that {obj} is {side}",
    "leaving {obj} {side}",
    "walking by {obj} {side}",
];

/// A landmark straight ahead.
pub(crate) const TOWARDS: &[&str] = &[
    "towards {obj}",
    "in the direction of {obj}",
    "heading for {obj}",
    "aiming for {obj}",
    "making for {obj}",
    "towards {obj} in front of you",
];

/// Side words (`{dir}`).
pub(crate) const SIDE: &[&str] = &[
    "on your {dir}",
    "to your {dir}",
    "on the {dir}",
    "on your {dir}-hand side",
    "to the {dir}",
];

/// Leaving a room.
pub(crate) const LEAVE_ROOM: &[&str] = &[
    "leave {room}",
    "exit {room}",
    "walk out of {room}",
    "step out of {room}",
    "head out of {room}",
    "make your way out of {room}",
];

/// Entering a room.
pub(crate) const ENTER_ROOM: &[&str] = &[
    "enter {room}",
    "go into {room}",
    "walk into {room}",
    "step into {room}",
    "head into {room}",
    "pass through the doorway into {room}",
    "come into {room}",
    "move into {room}",
];

/// Moving from one room into another in one clause (`{from}`, `{room}`).
pub(crate) const ROOM_TO_ROOM: &[&str] = &[
    "leave {from} and enter {room}",
    "go from {from} into {room}",
    "exit {from} into {room}",
    "cross from {from} into {room}",
    "walk out of {from} and into {room}",
    "pass out of {from} into {room}",
];

/// Where the walk starts.
pub(crate) const START_ROOM: &[&str] = &[
    "You start in {room}.",
    "You are in {room}.",
    "Starting in {room},",
    "From where you stand in {room},",
    "Beginning in {room},",
    "",
    "",
];

/// Stopping next to an object (`{obj}`).
pub(crate) const STOP_AT: &[&str] = &[
    "stop next to {obj}",
    "stop beside {obj}",
    "wait by {obj}",
    "come to a halt near {obj}",
    "stop when you reach {obj}",
    "your goal is right by {obj}",
    "stand next to {obj} and stop",
    "finish beside {obj}",
    "end your walk at {obj}",
    "halt in front of {obj}",
];

/// Stopping in a room.
pub(crate) const STOP_ROOM: &[&str] = &[
    "stop inside {room}",
    "wait there in {room}",
    "stop once you are in {room}",
    "come to a halt in {room}",
    "that spot in {room} is your goal",
    "end there in {room}",
    "you have arrived once you are in {room}",
];

/// Stopping with nothing to name.
pub(crate) const STOP: &[&str] = &[
    "stop there",
    "wait there",
    "that is your goal",
    "stop and wait",
    "you have arrived",
    "come to a stop",
    "halt there",
];

/// Joining two clauses within one sentence.
pub(crate) const AND: &[&str] = &[" and ", ", then ", " and then ", ", and ", ", after that "];

/// Starting a later sentence.
pub(crate) const NEXT: &[&str] = &[
    "",
    "",
    "",
    "then ",
    "next, ",
    "after that, ",
    "now ",
    "from there, ",
];

/// Starting the last sentence.
pub(crate) const LAST: &[&str] = &["", "", "finally, ", "at last, ", "then ", "there, "];

// --------------------------------------------------------------- coarse-grained

/// Formal coarse sentences (`{desc}` = "the red mug", `{sup}`, `{rel}`, `{room}` clauses may be
/// empty; they begin with a space when present).
pub(crate) const FORMAL: &[&str] = &[
    "Proceed to {desc}{sup}{rel}{room}.",
    "Navigate to {desc}{sup}{rel}{room}.",
    "Make your way to {desc}{sup}{rel}{room}.",
    "Locate {desc}{sup}{rel}{room} and stop beside it.",
    "Your destination is {desc}{sup}{rel}{room}.",
    "Please go to {desc}{sup}{rel}{room}.",
    "Approach {desc}{sup}{rel}{room} and halt there.",
    "Move to the position of {desc}{sup}{rel}{room}.",
    "Travel to {desc}{sup}{rel}{room} and remain there.",
    "Find {desc}{sup}{rel}{room} and stop in front of it.",
];

/// Formal support clause (`{obj}`).
pub(crate) const FORMAL_SUP: &[&str] = &[
    " located on {obj}",
    " placed on {obj}",
    " that rests on {obj}",
    " positioned on {obj}",
    " which sits on {obj}",
];

/// Formal "next to" clause.
pub(crate) const FORMAL_NEXT: &[&str] = &[
    " adjacent to {obj}",
    " situated next to {obj}",
    " immediately beside {obj}",
    " directly next to {obj}",
];

/// Formal "near" clause.
pub(crate) const FORMAL_NEAR: &[&str] = &[
    " in the vicinity of {obj}",
    " located near {obj}",
    " positioned close to {obj}",
    " in proximity to {obj}",
];

/// Formal room clause.
pub(crate) const FORMAL_ROOM: &[&str] = &[
    " in {room}",
    " within {room}",
    " inside {room}",
    " in {room} of the home",
];

/// Natural coarse sentences when a room is named (`{room}` bare room phrase).
pub(crate) const NATURAL_ROOM: &[&str] = &[
    "Go to {room} and find {desc}{sup}{rel}.",
    "Head into {room} and stop by {desc}{sup}{rel}.",
    "Walk to {room}; {desc}{sup}{rel} is where you should stop.",
    "In {room}, go over to {desc}{sup}{rel}.",
    "Make your way to {room} and stand next to {desc}{sup}{rel}.",
    "Go into {room} and walk up to {desc}{sup}{rel}.",
    "Find {desc}{sup}{rel} in {room} and wait there.",
    "Head over to {room}, then stop at {desc}{sup}{rel}.",
];

/// Natural coarse sentences without a room.
pub(crate) const NATURAL: &[&str] = &[
    "Go and find {desc}{sup}{rel}.",
    "Walk over to {desc}{sup}{rel} and stop there.",
    "Find {desc}{sup}{rel} and wait next to it.",
    "Head to {desc}{sup}{rel}.",
    "Go stand by {desc}{sup}{rel}.",
    "Look for {desc}{sup}{rel} and stop when you get there.",
    "Make your way over to {desc}{sup}{rel}.",
    "Walk up to {desc}{sup}{rel}.",
];

/// Natural support clause.
pub(crate) const NATURAL_SUP: &[&str] = &[" on {obj}", " sitting on {obj}", " on top of {obj}"];

/// Natural "next to" clause.
pub(crate) const NATURAL_NEXT: &[&str] =
    &[" next to {obj}", " right beside {obj}", " beside {obj}"];

/// Natural "near" clause.
pub(crate) const NATURAL_NEAR: &[&str] = &[" near {obj}", " close to {obj}", " not far from {obj}"];

/// Casual coarse sentences (lower case, clipped).
pub(crate) const CASUAL: &[&str] = &[
    "head over to {desc}{sup}{rel}{room}",
    "go grab a spot by {desc}{sup}{rel}{room}",
    "swing by {desc}{sup}{rel}{room}",
    "find {desc}{sup}{rel}{room}, that's it",
    "just go to {desc}{sup}{rel}{room}",
    "pop over to {desc}{sup}{rel}{room}",
    "over to {desc}{sup}{rel}{room}, please",
    "get yourself to {desc}{sup}{rel}{room}",
    "go check out {desc}{sup}{rel}{room}",
    "hop over to {desc}{sup}{rel}{room} and stop",
];

/// Casual support clause.
pub(crate) const CASUAL_SUP: &[&str] = &[" on {obj}", " sitting on {obj}", " up on {obj}"];

/// Casual "next to" clause.
pub(crate) const CASUAL_NEXT: &[&str] = &[" by {obj}", " right by {obj}", " next to {obj}"];

/// Casual "near" clause.
pub(crate) const CASUAL_NEAR: &[&str] = &[" near {obj}", " around {obj}", " close to {obj}"];

/// Casual room clause.
pub(crate) const CASUAL_ROOM: &[&str] = &[" in {room}", " over in {room}", " in {room} there"];

// ------------------------------------------------------------------ long-horizon

/// Openers of the first sub-instruction.
pub(crate) const CHAIN_FIRST: &[&str] = &["First, ", "To begin, ", "Start off: ", "First of all, "];

/// Openers of middle sub-instructions.
pub(crate) const CHAIN_MID: &[&str] = &["then ", "after that, ", "next, ", "once there, "];

/// Openers of the last sub-instruction.
pub(crate) const CHAIN_LAST: &[&str] = &[
    "finally, ",
    "and lastly, ",
    "to finish, ",
    "and at the end, ",
];
