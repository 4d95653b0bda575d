//! Phrase banks of the template generator, written for this project.
//!
//! Placeholders: `{obj}` an object phrase ("the dark red sofa"), `{room}` a room ("the
//! kitchen"), `{from}` the room left behind, `{dir}` left / right, `{side}` a side phrase ("on
//! your left"), `{dist}` a distance ("about 3 metres"), `{door}` an opening ("the doorway"),
//! `{deg}` an angle in degrees, `{clock}` a clock hour. Banks that are not about sides or turns
//! never contain "left" or "right" (tests check), so a sentence's sides come from the path only.

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

// ---------------------------------------------------------------- fine-grained: turns

/// Turning in place at the start (`{dir}` = left / right).
pub(crate) const START_TURN: &[&str] = &[
    "turn {dir}",
    "face {dir}",
    "turn to your {dir}",
    "rotate to the {dir}",
    "swing round to the {dir}",
    "begin by turning {dir}",
    "first turn to face {dir}",
    "pivot to your {dir}",
    "spin to the {dir}",
    "twist round to your {dir}",
    "orient yourself to the {dir}",
    "start by facing {dir}",
    "swivel {dir}",
    "wheel round to the {dir}",
    "get yourself facing {dir}",
];

/// Turning around (start or mid-path); every entry says "around", "opposite", "u-turn" or
/// "turn back".
pub(crate) const TURN_AROUND: &[&str] = &[
    "turn around",
    "turn all the way around",
    "spin around",
    "face the opposite way",
    "do a U-turn",
    "turn back the way you are facing",
    "turn yourself around",
    "about-face and turn around",
    "swing all the way around",
    "make a U-turn",
    "turn around completely",
    "face the opposite direction",
    "pivot around",
    "wheel around",
    "turn back on yourself",
    "reverse direction and face the opposite wall",
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
    "turn to the {dir}",
    "bend {dir}",
    "cut {dir}",
    "hook {dir}",
    "veer sharply {dir}",
    "wheel {dir}",
    "pivot {dir}",
    "turn hard {dir}",
    "swing round to the {dir}",
    "change direction to the {dir}",
    "make a sharp {dir}",
    "turn off to the {dir}",
    "take a sharp {dir}",
    "go round to the {dir}",
];

/// A clear turn given as an angle (`{deg}` degrees).
pub(crate) const TURN_DEG: &[&str] = &[
    "turn {deg} degrees {dir}",
    "turn about {deg} degrees to the {dir}",
    "rotate roughly {deg} degrees to your {dir}",
    "make a {deg}-degree turn to the {dir}",
    "swing through about {deg} degrees {dir}",
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
    "bear {dir}",
    "edge {dir}",
    "ease over to the {dir}",
    "tilt your path a touch {dir}",
    "shift a little {dir}",
    "lean {dir}",
    "fork {dir}",
    "swerve gently {dir}",
    "steer a bit to the {dir}",
    "make a soft {dir}",
    "nudge over to the {dir}",
];

/// A slight turn given as a clock hour ("two o'clock").
pub(crate) const SLIGHT_CLOCK: &[&str] = &[
    "bear towards your {clock} o'clock",
    "head off at {clock} o'clock",
    "angle towards {clock} o'clock",
    "veer to about {clock} o'clock",
];

// ---------------------------------------------------------------- fine-grained: movement

/// Verbs of walking on, combined with [`ONWARD`].
pub(crate) const MOVE_VERB: &[&str] = &[
    "journey",
    "tread",
    "shuffle",
    "walk on",
    "cruise",
    "drift",
    "roam",
    "venture",
    "meander",
    "hike",
    "sidle",
    "pad along",
    "tramp",
    "keep on",
    "forge ahead",
    "progress",
    "glide",
    "toddle",
    "walk",
    "go",
    "head",
    "move",
    "continue",
    "carry on",
    "keep going",
    "keep walking",
    "press on",
    "push on",
    "stroll",
    "amble",
    "wander",
    "step",
    "stride",
    "pace",
    "travel",
    "advance",
    "proceed",
    "make your way",
    "keep moving",
    "go on",
    "move along",
    "follow the path",
    "trundle",
    "saunter",
    "plod on",
    "keep heading",
    "march",
    "roll on",
];

/// Directions of walking on.
pub(crate) const ONWARD: &[&str] = &[
    "forward",
    "ahead",
    "straight ahead",
    "straight on",
    "onward",
    "onwards",
    "on",
    "along",
    "further",
    "forwards",
    "straight",
    "in a straight line",
    "dead ahead",
];

/// How one walks (often nothing).
pub(crate) const MANNER: &[&str] = &[
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "purposefully",
    "quietly",
    "smoothly",
    "gingerly",
    "evenly",
    "attentively",
    "at a normal pace",
    "at walking speed",
    "without stopping",
    "directly",
    "casually",
    "comfortably",
    "patiently",
    "deliberately",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "",
    "slowly",
    "steadily",
    "carefully",
    "calmly",
    "at an easy pace",
    "without turning",
    "at a gentle pace",
    "unhurriedly",
    "briskly",
    "with care",
];

/// Walking through a room (`{room}`).
pub(crate) const THROUGH_ROOM: &[&str] = &[
    "cross {room}",
    "walk across {room}",
    "go through {room}",
    "pass through {room}",
    "make your way across {room}",
    "cut across {room}",
    "head through {room}",
    "traverse {room}",
    "continue through {room}",
];

/// Walking along a hallway (`{room}`).
pub(crate) const ALONG_HALL: &[&str] = &[
    "walk down {room}",
    "follow {room}",
    "go along {room}",
    "head down {room}",
    "continue down {room}",
    "make your way along {room}",
    "stroll the length of {room}",
];

// ---------------------------------------------------------------- fine-grained: distances

/// A very short distance.
pub(crate) const DIST_SHORT: &[&str] = &[
    "a short way",
    "a step or two",
    "a little",
    "a few steps",
    "a couple of steps",
    "just a bit",
    "a short distance",
    "a pace or two",
    "only briefly",
    "a tiny bit",
];

/// "about" words for a distance.
pub(crate) const ABOUT: &[&str] = &[
    "about",
    "roughly",
    "around",
    "some",
    "approximately",
    "nearly",
    "close to",
    "more or less",
    "something like",
    "maybe",
    "perhaps",
    "an estimated",
];

/// Units of a distance in metres (`{n}` the number).
pub(crate) const METRES: &[&str] = &["{n} metres", "{n} meters", "{n} m", "{n} metres or so"];

// ---------------------------------------------------------------- fine-grained: landmarks

/// Passing a landmark on a side (`{obj}`, `{side}`).
pub(crate) const PASS_SIDE: &[&str] = &[
    "passing {obj} {side}",
    "with {obj} {side}",
    "keeping {obj} {side}",
    "going past {obj} {side}",
    "so that {obj} is {side}",
    "leaving {obj} {side}",
    "walking by {obj} {side}",
    "skirting {obj} {side}",
    "moving past {obj} {side}",
    "slipping past {obj} {side}",
    "edging past {obj} {side}",
    "brushing past {obj} {side}",
    "sliding by {obj} {side}",
    "having {obj} {side}",
    "past {obj} {side}",
    "alongside {obj} {side}",
    "keeping {obj} close {side}",
];

/// A full sentence about a landmark on a side (`{obj}`, `{side}`).
pub(crate) const SEE_SIDE: &[&str] = &[
    "you'll pass {obj} {side}",
    "you will see {obj} {side}",
    "{obj} should be {side}",
    "{obj} will be {side}",
    "there is {obj} {side}",
    "notice {obj} {side}",
    "look out for {obj} {side}",
    "you should spot {obj} {side}",
    "{obj} stays {side} as you go",
    "expect {obj} {side}",
    "{obj} comes up {side}",
    "keep an eye out for {obj} {side}",
    "you'll walk by {obj} {side}",
    "{obj} ought to be {side}",
    "{obj} is there {side}",
];

/// Keeping a landmark on a side, opening the sentence (`{obj}`, `{side}`).
pub(crate) const WITH_SIDE: &[&str] = &[
    "with {obj} {side}",
    "keeping {obj} {side}",
    "leaving {obj} {side}",
    "having {obj} {side}",
    "once {obj} is {side}",
];

/// Once a landmark is behind you (`{obj}`), before a turn.
pub(crate) const AFTER_OBJ: &[&str] = &[
    "once you've passed {obj}",
    "after {obj}",
    "just beyond {obj}",
    "when you get past {obj}",
    "as soon as you clear {obj}",
    "once you're level with {obj}",
    "straight after {obj}",
    "a little past {obj}",
    "after going by {obj}",
    "once {obj} is behind you",
];

/// A landmark straight ahead.
pub(crate) const TOWARDS: &[&str] = &[
    "towards {obj}",
    "in the direction of {obj}",
    "heading for {obj}",
    "aiming for {obj}",
    "making for {obj}",
    "towards {obj} in front of you",
    "toward {obj}",
    "straight at {obj}",
    "up to {obj}",
    "over to {obj}",
    "in line with {obj}",
    "with {obj} dead ahead",
    "with {obj} in front of you",
];

/// Walking until a landmark ahead (`{obj}`).
pub(crate) const UNTIL_OBJ: &[&str] = &[
    "until you reach {obj}",
    "until you get to {obj}",
    "until you come to {obj}",
    "as far as {obj}",
    "till you're at {obj}",
    "until you're close to {obj}",
    "until you arrive at {obj}",
    "up to {obj}",
    "until {obj} is just in front of you",
];

/// Side phrases (`{dir}`).
pub(crate) const SIDE: &[&str] = &[
    "on your {dir}",
    "to your {dir}",
    "on the {dir}",
    "on your {dir}-hand side",
    "to the {dir}",
    "at your {dir}",
    "off to your {dir}",
    "on your {dir} side",
    "to the {dir} of you",
    "along your {dir}",
    "on the {dir}-hand side",
    "just to your {dir}",
];

// ---------------------------------------------------------------- fine-grained: rooms

/// Leaving a room.
pub(crate) const LEAVE_ROOM: &[&str] = &[
    "leave {room}",
    "exit {room}",
    "walk out of {room}",
    "step out of {room}",
    "head out of {room}",
    "make your way out of {room}",
    "get out of {room}",
    "slip out of {room}",
    "depart {room}",
    "quit {room}",
];

/// Entering a room.
pub(crate) const ENTER_ROOM: &[&str] = &[
    "enter {room}",
    "go into {room}",
    "walk into {room}",
    "step into {room}",
    "head into {room}",
    "come into {room}",
    "move into {room}",
    "pass into {room}",
    "go on into {room}",
    "continue into {room}",
    "make your way into {room}",
    "wander into {room}",
    "carry on into {room}",
    "end up in {room}",
    "arrive in {room}",
    "find yourself in {room}",
    "emerge into {room}",
];

/// Entering a room through an opening (`{door}`, `{room}`).
pub(crate) const THROUGH_DOOR: &[&str] = &[
    "go through {door} into {room}",
    "pass through {door} into {room}",
    "walk through {door} to {room}",
    "step through {door} into {room}",
    "use {door} to enter {room}",
    "cross {door} into {room}",
    "head through {door} and into {room}",
    "go out through {door} into {room}",
    "take {door} into {room}",
    "slip through {door} into {room}",
    "step over the threshold into {room}",
    "cross the threshold into {room}",
];

/// Moving from one room into another in one clause (`{from}`, `{room}`).
pub(crate) const ROOM_TO_ROOM: &[&str] = &[
    "leave {from} and enter {room}",
    "go from {from} into {room}",
    "exit {from} into {room}",
    "cross from {from} into {room}",
    "walk out of {from} and into {room}",
    "pass out of {from} into {room}",
    "move on from {from} to {room}",
    "come out of {from} into {room}",
    "get out of {from} and go into {room}",
    "swap {from} for {room}",
];

/// Leaving a room through an opening (`{from}`, `{door}`, `{room}`).
pub(crate) const LEAVE_BY_DOOR: &[&str] = &[
    "leave {from} by {door} and enter {room}",
    "exit {from} through {door} into {room}",
    "go out of {from} through {door} into {room}",
    "walk out of {from} via {door}, into {room}",
];

/// A sentence saying a room has been entered (`{room}`).
pub(crate) const NOW_IN: &[&str] = &[
    "you are now in {room}",
    "you'll be in {room}",
    "this is {room}",
    "now you're in {room}",
    "that brings you into {room}",
    "you should now be in {room}",
    "you have reached {room}",
    "welcome to {room}",
];

/// Where the walk starts (a sentence, or a prefix ending in a comma, or nothing).
pub(crate) const START_ROOM: &[&str] = &[
    "You start in {room}.",
    "You are in {room}.",
    "Starting in {room},",
    "From where you stand in {room},",
    "Beginning in {room},",
    "You're standing in {room}.",
    "At the moment you're in {room}.",
    "We begin in {room}.",
    "Your starting point is {room}.",
    "You begin in {room}.",
    "From your spot in {room},",
    "Standing in {room},",
    "",
    "",
    "",
    "",
];

// ---------------------------------------------------------------- fine-grained: the end

/// Stopping next to an object (`{obj}`).
pub(crate) const STOP_AT: &[&str] = &[
    "linger by {obj}",
    "rest beside {obj}",
    "plant yourself next to {obj}",
    "settle near {obj}",
    "hold your position by {obj}",
    "draw up beside {obj}",
    "come to a standstill by {obj}",
    "stay close to {obj}",
    "your journey ends at {obj}",
    "you'll finish near {obj}",
    "call it a day at {obj}",
    "the route ends at {obj}",
    "stop as you reach {obj}",
    "wrap up beside {obj}",
    "your target spot is by {obj}",
    "stop next to {obj}",
    "stop beside {obj}",
    "wait by {obj}",
    "come to a halt near {obj}",
    "stop when you reach {obj}",
    "your goal is just by {obj}",
    "stand next to {obj} and stop",
    "finish beside {obj}",
    "end your walk at {obj}",
    "halt in front of {obj}",
    "pause by {obj} and stay there",
    "stop close to {obj}",
    "wait near {obj}",
    "stay beside {obj}",
    "come to rest by {obj}",
    "finish up next to {obj}",
    "stop just short of {obj}",
    "wait for me by {obj}",
    "your destination is beside {obj}",
    "park yourself by {obj}",
    "that spot by {obj} is where you stop",
    "stand still by {obj}",
    "you're done once you're at {obj}",
    "stop level with {obj}",
    "remain next to {obj}",
    "end up alongside {obj}",
    "the goal is in front of {obj}",
];

/// Where an object at the end stands in the room.
pub(crate) const IN_CORNER: &[&str] = &[
    "in the corner",
    "tucked into the corner",
    "over in the corner",
    "in the nearby corner",
];

/// An object standing against a wall.
pub(crate) const AT_WALL: &[&str] = &[
    "against the wall",
    "by the wall",
    "up against the wall",
    "along the wall",
    "set against the wall",
];

/// An object standing free in the room.
pub(crate) const MID_ROOM: &[&str] = &[
    "in the middle of the room",
    "in the centre of the room",
    "out in the open",
    "near the middle of the room",
];

/// An object near a doorway.
pub(crate) const BY_DOOR: &[&str] = &[
    "by the doorway",
    "near the door",
    "close to the entrance",
    "just inside the doorway",
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
    "stop a little way into {room}",
    "pause once you're inside {room}",
    "wait just inside {room}",
    "your goal is in {room}",
    "finish in {room}",
    "stay put in {room}",
];

/// Stopping in a room near its corner or wall (`{room}`, `{where}`).
pub(crate) const STOP_ROOM_WHERE: &[&str] = &[
    "stop {where} of {room}",
    "wait {where} of {room}",
    "finish {where} of {room}",
    "come to a stop {where} of {room}",
];

/// Stopping with nothing to name.
pub(crate) const STOP: &[&str] = &[
    "rest there",
    "freeze",
    "you've reached the end",
    "stay there",
    "that's far enough",
    "settle there",
    "hold your position",
    "end the walk there",
    "wait at that point",
    "mission complete",
    "stop there",
    "wait there",
    "that is your goal",
    "stop and wait",
    "you have arrived",
    "come to a stop",
    "halt there",
    "that's the spot",
    "stop and stay put",
    "you're there",
    "stop walking",
    "stand still",
    "that is the end point",
    "pull up there",
];

// ---------------------------------------------------------------- fine-grained: discourse

/// Joining two clauses within one sentence.
pub(crate) const AND: &[&str] = &[
    " and ",
    ", then ",
    " and then ",
    ", and ",
    ", after that ",
    ", then go on and ",
    " before you ",
    "; then ",
    ", and after that ",
    ", and next ",
    " - then ",
];

/// Starting a later sentence.
pub(crate) const NEXT: &[&str] = &[
    "subsequently, ",
    "thereafter, ",
    "at this stage, ",
    "moving along, ",
    "continuing, ",
    "straight away, ",
    "immediately, ",
    "shortly after, ",
    "meanwhile, ",
    "presently, ",
    "by now, ",
    "",
    "",
    "",
    "",
    "then ",
    "next, ",
    "after that, ",
    "now ",
    "from there, ",
    "afterwards, ",
    "from here, ",
    "at that point, ",
    "when you've done that, ",
    "following that, ",
    "once there, ",
    "now then, ",
    "OK, now ",
    "so ",
    "again, ",
    "after this, ",
];

/// Starting the last sentence.
pub(crate) const LAST: &[&str] = &[
    "",
    "",
    "",
    "finally, ",
    "at last, ",
    "then ",
    "there, ",
    "lastly, ",
    "to finish, ",
    "in the end, ",
    "and then ",
    "at the end, ",
    "your final step: ",
];

/// Opening sentences some writers put first.
pub(crate) const OPEN: &[&str] = &[
    "Okey-dokey.",
    "Welcome.",
    "Good morning.",
    "Good evening.",
    "Hello!",
    "Here goes.",
    "Follow me carefully.",
    "Quick directions coming up.",
    "Let's do this.",
    "Here's what to do.",
    "Please follow along.",
    "Got a minute? Here's the way.",
    "Simple route this time.",
    "This should be straightforward.",
    "A little walk for you.",
    "Time to move.",
    "I'll keep it brief.",
    "Let's find your spot.",
    "Instructions as follows.",
    "Okay, listen carefully.",
    "Here's the plan.",
    "Directions, step by step.",
    "Okay, here we go.",
    "Here's the route.",
    "Listen up.",
    "Ready? Let's go.",
    "This one is easy.",
    "Follow these directions.",
    "It's not far.",
    "Here is how to get there.",
    "Let me talk you through it.",
    "It's a short trip.",
    "Pay attention to the turns.",
    "The way is simple.",
    "Let's get moving.",
    "Here are your directions.",
    "I'll guide you.",
    "OK, so.",
    "Hi there.",
    "Good, let's begin.",
];

/// Remarks some writers make along the way.
pub(crate) const ASIDE: &[&str] = &[
    "Shouldn't take long.",
    "You've got this.",
    "Nearly halfway.",
    "Trust me, it's simple.",
    "The house is quiet, so take it slow.",
    "No shortcuts needed.",
    "Keep your bearings.",
    "Don't overthink it.",
    "Just follow along.",
    "Simple enough.",
    "Stay focused.",
    "Breathe and keep moving.",
    "You're making good progress.",
    "Pace yourself.",
    "If you get lost, retrace your steps.",
    "Keep calm and carry on.",
    "Hang in there.",
    "Nothing complicated.",
    "It gets easier from here.",
    "Avoid bumping into things.",
    "The floor is clear, mostly.",
    "Glance around as you go.",
    "Tread lightly.",
    "Eyes forward.",
    "Good job so far.",
    "Steady now.",
    "Keep it smooth.",
    "Onwards.",
    "Keep track of where you are.",
    "Count your steps if it helps.",
    "Stay alert.",
    "This stretch is short.",
    "Bear with me.",
    "Easy does it.",
    "Follow my lead.",
    "One more bit to go.",
    "You're close.",
    "Not long now.",
    "Stay with me here.",
    "Remember the way back.",
    "Quietly does it.",
    "Keep the pace gentle.",
    "There's plenty of space.",
    "You won't need to open anything.",
    "Walk normally.",
    "Be mindful of corners.",
    "It's a cosy home, so go carefully.",
    "Keep your hands free.",
    "Slow and steady wins.",
    "Don't hurry.",
    "A few more moves.",
    "Nearly finished.",
    "It's a short walk.",
    "You can't really miss it.",
    "Take your time.",
    "There's no rush.",
    "Mind the furniture.",
    "Watch your step.",
    "Nothing tricky here.",
    "This bit is easy.",
    "Keep your eyes open.",
    "Don't worry, you're nearly there.",
    "Almost done.",
    "Stay on course.",
    "Not much further.",
    "Keep going, you're doing fine.",
    "Look around if you're unsure.",
    "Ignore the other rooms.",
    "Don't get distracted.",
    "Easy so far.",
    "Good.",
    "Still with me?",
    "It's pretty obvious from here.",
    "Keep that in mind.",
    "Stick to the open floor.",
    "Be careful not to bump into anything.",
    "Go at your own speed.",
];

/// Closing sentences some writers add.
pub(crate) const CLOSE: &[&str] = &[
    "Perfect.",
    "Great job.",
    "You made it.",
    "All finished.",
    "End of the route.",
    "That's the end.",
    "Brilliant.",
    "Lovely.",
    "Sorted.",
    "That wraps it up.",
    "Happy exploring.",
    "Take a breather.",
    "You've arrived safely.",
    "Excellent work.",
    "Thank you for following along.",
    "Bye for now.",
    "Have a rest there.",
    "Congratulations, you're there.",
    "Simple as that.",
    "Easy, wasn't it?",
    "That's it.",
    "You're done.",
    "Good luck.",
    "Done.",
    "That's your destination.",
    "Well done.",
    "Thanks.",
    "That's all.",
    "Job done.",
    "Mission accomplished.",
    "Enjoy.",
    "And that's the whole route.",
    "Nice work.",
    "See you there.",
    "Cheers.",
];

// --------------------------------------------------------------- coarse-grained

/// Formal openers (a whole sentence or nothing).
pub(crate) const FORMAL_OPEN: &[&str] = &[
    "Please pay close attention. ",
    "Instructions follow. ",
    "The assignment is as follows. ",
    "Kindly note the following. ",
    "Your navigation objective is stated below. ",
    "Please comply with the following. ",
    "This is a navigation request. ",
    "Listen carefully to this request. ",
    "The procedure is simple. ",
    "For this episode, please observe the following. ",
    "",
    "",
    "",
    "",
    "Your task is as follows. ",
    "Kindly follow this instruction. ",
    "Attention, please. ",
    "The objective is described below. ",
    "Please read carefully. ",
    "The following describes your destination. ",
    "A single goal has been assigned. ",
    "Here is the assignment. ",
];

/// Formal coarse sentences (`{desc}` = "the red mug", `{sup}`, `{rel}`, `{room}` clauses may be
/// empty; they begin with a space when present).
pub(crate) const FORMAL: &[&str] = &[
    "Proceed without delay to {desc}{sup}{rel}{room}",
    "Your assignment is to reach {desc}{sup}{rel}{room}",
    "Establish your position adjacent to {desc}{sup}{rel}{room}",
    "Relocate to {desc}{sup}{rel}{room}",
    "Navigate efficiently to {desc}{sup}{rel}{room}",
    "Conclude your route at {desc}{sup}{rel}{room}",
    "Terminate navigation upon reaching {desc}{sup}{rel}{room}",
    "Please proceed until you are adjacent to {desc}{sup}{rel}{room}",
    "It is requested that you go to {desc}{sup}{rel}{room}",
    "Carefully approach {desc}{sup}{rel}{room}",
    "Please position yourself in front of {desc}{sup}{rel}{room}",
    "Head directly towards {desc}{sup}{rel}{room}",
    "Proceed to {desc}{sup}{rel}{room}",
    "Navigate to {desc}{sup}{rel}{room}",
    "Make your way to {desc}{sup}{rel}{room}",
    "Locate {desc}{sup}{rel}{room} and stop beside it",
    "Your destination is {desc}{sup}{rel}{room}",
    "Please go to {desc}{sup}{rel}{room}",
    "Approach {desc}{sup}{rel}{room} and halt there",
    "Move to the position of {desc}{sup}{rel}{room}",
    "Travel to {desc}{sup}{rel}{room} and remain there",
    "Find {desc}{sup}{rel}{room} and stop in front of it",
    "Kindly proceed to {desc}{sup}{rel}{room}",
    "You are required to reach {desc}{sup}{rel}{room}",
    "Position yourself beside {desc}{sup}{rel}{room}",
    "The target is {desc}{sup}{rel}{room}; navigate to it",
    "Go directly to {desc}{sup}{rel}{room}",
    "Identify {desc}{sup}{rel}{room} and approach it",
    "Walk to {desc}{sup}{rel}{room} and wait there",
    "Your objective is to reach {desc}{sup}{rel}{room}",
    "Head to {desc}{sup}{rel}{room} and stand next to it",
    "Please navigate until you are beside {desc}{sup}{rel}{room}",
    "Ensure that you arrive at {desc}{sup}{rel}{room}",
    "Reach {desc}{sup}{rel}{room} and stop",
    "Please make your way over to {desc}{sup}{rel}{room}",
    "Please locate {desc}{sup}{rel}{room}",
    "Your goal is {desc}{sup}{rel}{room}",
    "The destination is {desc}{sup}{rel}{room}",
    "Advance towards {desc}{sup}{rel}{room} and stop once it is within reach",
    "Station yourself next to {desc}{sup}{rel}{room}",
];

/// Formal closing sentences (after the main one; may be empty).
pub(crate) const FORMAL_CLOSE: &[&str] = &[
    ". Maintain a safe distance from obstacles.",
    ". Proceed at a moderate pace.",
    ". Confirm arrival by stopping.",
    ". No further action is required.",
    ". Please avoid collisions.",
    ". This completes the task description.",
    ". Await further instructions there.",
    ". Your cooperation is appreciated.",
    ". The episode ends upon arrival.",
    ". Refrain from wandering elsewhere.",
    ".",
    ".",
    ".",
    ".",
    ". Stop once you have arrived.",
    ". Remain there until further notice.",
    ". Halt when you are within one metre of it.",
    ". Do not proceed any further.",
    ". Thank you.",
    ". That concludes the instruction.",
    ". Wait there upon arrival.",
    ". End the episode there.",
    ". Please remain stationary upon arrival.",
    ". Take the most direct route.",
    ". Avoid unnecessary detours.",
    ". Then stop.",
];

/// Formal support clause (`{obj}`).
pub(crate) const FORMAL_SUP: &[&str] = &[
    " located on {obj}",
    " placed on {obj}",
    " that rests on {obj}",
    " positioned on {obj}",
    " which sits on {obj}",
    " situated on top of {obj}",
    " resting upon {obj}",
    " that has been placed on {obj}",
];

/// Formal "next to" clause.
pub(crate) const FORMAL_NEXT: &[&str] = &[
    " adjacent to {obj}",
    " situated next to {obj}",
    " immediately beside {obj}",
    " directly next to {obj}",
    " located alongside {obj}",
    " positioned beside {obj}",
];

/// Formal "near" clause.
pub(crate) const FORMAL_NEAR: &[&str] = &[
    " in the vicinity of {obj}",
    " located near {obj}",
    " positioned close to {obj}",
    " in proximity to {obj}",
    " within a short distance of {obj}",
    " not far from {obj}",
];

/// Formal room clause.
pub(crate) const FORMAL_ROOM: &[&str] = &[
    " in {room}",
    " within {room}",
    " inside {room}",
    " in {room} of the home",
    " in {room} of this residence",
    " within {room} of the house",
    " located in {room}",
];

/// Natural openers (may be empty).
pub(crate) const NATURAL_OPEN: &[&str] = &[
    "Hiya. ",
    "Morning! ",
    "Quick favour: ",
    "When you're ready, ",
    "If you don't mind, ",
    "Here's a task. ",
    "Now then, ",
    "One more thing. ",
    "",
    "",
    "",
    "",
    "",
    "OK. ",
    "Alright then. ",
    "Right, ",
    "So, ",
    "Hey, ",
    "Next up: ",
    "Here's one for you. ",
    "Your turn. ",
    "Ready? ",
    "Easy one. ",
    "Okay, ",
];

/// Natural coarse sentences when a room is named (`{room}` bare room phrase).
pub(crate) const NATURAL_ROOM: &[&str] = &[
    "Nip into {room} and find {desc}{sup}{rel}",
    "Have a look in {room} for {desc}{sup}{rel}",
    "Wander into {room} and stop by {desc}{sup}{rel}",
    "Go through to {room} and wait next to {desc}{sup}{rel}",
    "Off you go to {room}; stop at {desc}{sup}{rel}",
    "Would you head to {room} and find {desc}{sup}{rel}",
    "Go to {room} and find {desc}{sup}{rel}",
    "Head into {room} and stop by {desc}{sup}{rel}",
    "Walk to {room}; {desc}{sup}{rel} is where you should stop",
    "In {room}, go over to {desc}{sup}{rel}",
    "Make your way to {room} and stand next to {desc}{sup}{rel}",
    "Go into {room} and walk up to {desc}{sup}{rel}",
    "Find {desc}{sup}{rel} in {room} and wait there",
    "Head over to {room}, then stop at {desc}{sup}{rel}",
    "There's {desc}{sup}{rel} in {room} - go and stand by it",
    "You're looking for {desc}{sup}{rel} in {room}",
    "Could you go to {room} and wait by {desc}{sup}{rel}",
    "Pop into {room} and stop next to {desc}{sup}{rel}",
    "Go through to {room}; you want {desc}{sup}{rel}",
    "I need you in {room}, next to {desc}{sup}{rel}",
    "Once you're in {room}, look for {desc}{sup}{rel}",
    "Find your way to {room} and then to {desc}{sup}{rel}",
    "Go over to {room} and find {desc}{sup}{rel}",
    "Walk into {room}; stop when you reach {desc}{sup}{rel}",
];

/// Natural coarse sentences without a room.
pub(crate) const NATURAL: &[&str] = &[
    "Wander over to {desc}{sup}{rel}",
    "Go find {desc}{sup}{rel} for me",
    "See if you can find {desc}{sup}{rel}",
    "Could you head over to {desc}{sup}{rel}",
    "Stroll over to {desc}{sup}{rel}",
    "Would you go and stand by {desc}{sup}{rel}",
    "Let's get you to {desc}{sup}{rel}",
    "Off you go to {desc}{sup}{rel}",
    "Take yourself over to {desc}{sup}{rel}",
    "Go and wait beside {desc}{sup}{rel}",
    "Go and find {desc}{sup}{rel}",
    "Walk over to {desc}{sup}{rel} and stop there",
    "Find {desc}{sup}{rel} and wait next to it",
    "Head to {desc}{sup}{rel}",
    "Go stand by {desc}{sup}{rel}",
    "Look for {desc}{sup}{rel} and stop when you get there",
    "Make your way over to {desc}{sup}{rel}",
    "Walk up to {desc}{sup}{rel}",
    "Can you go to {desc}{sup}{rel}",
    "I'd like you to go to {desc}{sup}{rel}",
    "You're looking for {desc}{sup}{rel}",
    "Try to find {desc}{sup}{rel} and stop beside it",
    "Go over and stand next to {desc}{sup}{rel}",
    "Please find {desc}{sup}{rel}",
    "Your goal is {desc}{sup}{rel}",
    "Get to {desc}{sup}{rel} and wait",
];

/// Natural closing remarks (may be empty).
pub(crate) const NATURAL_CLOSE: &[&str] = &[
    ". Cheers.",
    ". Appreciate it.",
    ". Shouldn't take you long.",
    ". Just wait there.",
    ". No need to hurry.",
    ". Give me a shout when you're there.",
    ". Stay there once you arrive.",
    ". That's the one.",
    ".",
    ".",
    ".",
    ".",
    ". Thanks.",
    ". Stop when you're next to it.",
    ". That's where I want you.",
    ". Wait there for me.",
    ". It shouldn't be hard to find.",
    ". That's all there is to it.",
    ", please.",
    ". Then you're done.",
    ". You'll know it when you see it.",
    ". Take whatever route you like.",
];

/// Natural support clause.
pub(crate) const NATURAL_SUP: &[&str] = &[
    " on {obj}",
    " sitting on {obj}",
    " on top of {obj}",
    " that's on {obj}",
    " standing on {obj}",
    " lying on {obj}",
];

/// Natural "next to" clause.
pub(crate) const NATURAL_NEXT: &[&str] = &[
    " next to {obj}",
    " right beside {obj}",
    " beside {obj}",
    " right next to {obj}",
    " just by {obj}",
];

/// Natural "near" clause.
pub(crate) const NATURAL_NEAR: &[&str] = &[
    " near {obj}",
    " close to {obj}",
    " not far from {obj}",
    " a little way from {obj}",
    " close by {obj}",
];

/// Casual openers (may be empty).
pub(crate) const CASUAL_OPEN: &[&str] = &[
    "dude, ",
    "mate, ",
    "psst, ",
    "okie, ",
    "listen, ",
    "heads up, ",
    "aight, ",
    "kk so ",
    "hmm, ",
    "ooh, ",
    "",
    "",
    "",
    "",
    "",
    "ok so ",
    "yo, ",
    "hey ",
    "alright, ",
    "so yeah, ",
    "right, ",
    "um, ",
    "quick one: ",
    "ok ",
    "oi, ",
    "so basically ",
    "erm, ",
];

/// Casual coarse sentences (lower case, clipped).
pub(crate) const CASUAL: &[&str] = &[
    "go plonk yourself by {desc}{sup}{rel}{room}",
    "get over to {desc}{sup}{rel}{room} asap",
    "c'mon, over to {desc}{sup}{rel}{room}",
    "head to {desc}{sup}{rel}{room} yeah",
    "wanna stroll to {desc}{sup}{rel}{room}",
    "go loiter by {desc}{sup}{rel}{room}",
    "roll over to {desc}{sup}{rel}{room}",
    "nip over to {desc}{sup}{rel}{room}",
    "dash over to {desc}{sup}{rel}{room}",
    "skedaddle to {desc}{sup}{rel}{room}",
    "go say hi to {desc}{sup}{rel}{room}",
    "bounce over to {desc}{sup}{rel}{room}",
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
    "wander over to {desc}{sup}{rel}{room}",
    "go hang out by {desc}{sup}{rel}{room}",
    "mosey on over to {desc}{sup}{rel}{room}",
    "scoot over to {desc}{sup}{rel}{room}",
    "you wanna go to {desc}{sup}{rel}{room}",
    "gotta get to {desc}{sup}{rel}{room}",
    "need you at {desc}{sup}{rel}{room}",
    "go find {desc}{sup}{rel}{room} real quick",
    "make tracks to {desc}{sup}{rel}{room}",
    "zip over to {desc}{sup}{rel}{room}",
    "take a walk to {desc}{sup}{rel}{room}",
    "shuffle on over to {desc}{sup}{rel}{room}",
    "go chill by {desc}{sup}{rel}{room}",
    "park it next to {desc}{sup}{rel}{room}",
];

/// Casual closers (no final full stop).
pub(crate) const CASUAL_CLOSE: &[&str] = &[
    " ta muchly",
    " sweet",
    " ez",
    " cya",
    " later",
    " yay",
    " thx mate",
    " np",
    " brb",
    " done deal",
    " savvy?",
    " ok cool",
    " gg",
    " whenever",
    "",
    "",
    "",
    "",
    " thx",
    " ty",
    " cheers",
    " lol",
    " k?",
    " ta",
    " cool?",
    " and that's it",
    " then chill",
    " easy",
    " pls",
    " no rush",
    " and stop there",
    " ok",
    " nice one",
    " go go go",
];

/// Casual support clause.
pub(crate) const CASUAL_SUP: &[&str] = &[
    " on {obj}",
    " sitting on {obj}",
    " up on {obj}",
    " on top of {obj}",
    " chilling on {obj}",
    " that's on {obj}",
];

/// Casual "next to" clause.
pub(crate) const CASUAL_NEXT: &[&str] = &[
    " by {obj}",
    " right by {obj}",
    " next to {obj}",
    " smack next to {obj}",
    " right up by {obj}",
];

/// Casual "near" clause.
pub(crate) const CASUAL_NEAR: &[&str] = &[
    " near {obj}",
    " around {obj}",
    " close to {obj}",
    " kinda near {obj}",
    " somewhere near {obj}",
];

/// Casual room clause.
pub(crate) const CASUAL_ROOM: &[&str] = &[
    " in {room}",
    " over in {room}",
    " in {room} there",
    " in {room} btw",
    " down in {room}",
    " out in {room}",
];

// ------------------------------------------------------------------ long-horizon

/// Openers of the first sub-instruction.
pub(crate) const CHAIN_FIRST: &[&str] = &[
    "First, ",
    "To begin, ",
    "Start off: ",
    "First of all, ",
    "To start with, ",
    "Step one: ",
    "Initially, ",
    "Before anything else, ",
    "Let's start here: ",
    "For a start, ",
];

/// Openers of middle sub-instructions.
pub(crate) const CHAIN_MID: &[&str] = &[
    "then ",
    "after that, ",
    "next, ",
    "once there, ",
    "after this, ",
    "from that point, ",
    "when you've done that, ",
    "second, ",
    "following that, ",
    "moving on, ",
];

/// Openers of the last sub-instruction.
pub(crate) const CHAIN_LAST: &[&str] = &[
    "finally, ",
    "and lastly, ",
    "to finish, ",
    "and at the end, ",
    "last of all, ",
    "to wrap up, ",
    "as the final step, ",
    "and to conclude, ",
    "at the very end, ",
    "and finally, ",
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Banks that say nothing about sides or turns.
    const SIDELESS: &[&[&str]] = &[
        MOVE_VERB,
        ONWARD,
        MANNER,
        THROUGH_ROOM,
        ALONG_HALL,
        DIST_SHORT,
        ABOUT,
        METRES,
        TOWARDS,
        UNTIL_OBJ,
        AFTER_OBJ,
        LEAVE_ROOM,
        ENTER_ROOM,
        THROUGH_DOOR,
        ROOM_TO_ROOM,
        LEAVE_BY_DOOR,
        NOW_IN,
        START_ROOM,
        STOP_AT,
        IN_CORNER,
        AT_WALL,
        MID_ROOM,
        BY_DOOR,
        STOP_ROOM,
        STOP_ROOM_WHERE,
        STOP,
        AND,
        NEXT,
        LAST,
        OPEN,
        ASIDE,
        CLOSE,
        TURN_AROUND,
    ];

    #[test]
    fn sideless_banks_never_say_left_or_right() {
        for bank in SIDELESS {
            for e in *bank {
                let l = e.to_lowercase();
                assert!(!l.contains("left") && !l.contains("right"), "`{e}`");
            }
        }
    }

    #[test]
    fn turn_around_always_says_so() {
        for e in TURN_AROUND {
            let l = e.to_lowercase();
            assert!(
                ["around", "opposite", "u-turn", "turn back"]
                    .iter()
                    .any(|k| l.contains(k)),
                "`{e}`"
            );
        }
    }

    #[test]
    fn side_and_turn_banks_name_the_direction() {
        for bank in [START_TURN, TURN, TURN_DEG, SLIGHT_TURN, SIDE] {
            for e in bank {
                assert!(e.contains("{dir}"), "`{e}`");
            }
        }
    }
}
