//! Replies to actions. A reply names one action, as a phrase (`move forward 75 cm`, `turn
//! left 45 degrees`, `stop`, `ask: which room?`) or as a JSON object (`{"action":
//! "move_forward", "distance_cm": 75}`); with chain of thought the action is read from the last
//! line that starts with `Action:`. Distances and angles become repeats of the embodiment's
//! primitives, rounded to the nearest whole step (at least one, at most the configured cap).

use vlnverse_sim::Action;

/// What a reply asks for.
#[derive(Clone, Debug, PartialEq)]
pub enum Decision {
    /// Primitive actions to take in order.
    Act(Vec<Action>),
    /// A question for the dialogue oracle.
    Ask(String),
}

/// The step sizes the parser converts distances and angles with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Steps {
    /// One forward step (m).
    pub step_m: f32,
    /// One turn (degrees).
    pub turn_deg: f32,
    /// Most primitives one reply may give.
    pub max_repeat: u32,
}

impl Steps {
    fn repeat(&self, amount: f32, unit: f32) -> usize {
        let n = (amount / unit).round();
        (n.max(1.0) as u32).min(self.max_repeat) as usize
    }

    fn forward(&self, metres: Option<f32>) -> Vec<Action> {
        let n = metres.map_or(1, |m| self.repeat(m, self.step_m));
        vec![Action::MoveForward(self.step_m); n]
    }

    fn turn(&self, left: bool, degrees: Option<f32>) -> Vec<Action> {
        let n = degrees.map_or(1, |d| self.repeat(d, self.turn_deg));
        let a = self.turn_deg.to_radians();
        let one = if left {
            Action::TurnLeft(a)
        } else {
            Action::TurnRight(a)
        };
        vec![one; n]
    }
}

/// Read a reply; `None` when it names no action.
pub fn parse_reply(reply: &str, steps: &Steps) -> Option<Decision> {
    let answer = answer_part(reply);
    match json_action(answer) {
        // A JSON answer is read as JSON only: a bad one is not guessed from its words.
        Some(v) => parse_json(&v, steps),
        None => parse_phrase(answer, steps),
    }
}

/// The JSON object of a reply, when it has an `action` key.
fn json_action(text: &str) -> Option<serde_json::Value> {
    let start = text.find('{')?;
    let end = text.rfind('}')?;
    if end <= start {
        return None;
    }
    let v: serde_json::Value = serde_json::from_str(&text[start..=end]).ok()?;
    v.get("action").is_some().then_some(v)
}

/// The part of the reply that holds the action: after the last `Action:` label when there is
/// one (chain of thought), else the whole reply.
fn answer_part(reply: &str) -> &str {
    let lower = reply.to_ascii_lowercase();
    match lower.rfind("action:") {
        Some(i) => &reply[i + "action:".len()..],
        None => reply,
    }
}

fn parse_json(v: &serde_json::Value, steps: &Steps) -> Option<Decision> {
    let name = v
        .get("action")?
        .as_str()?
        .to_ascii_lowercase()
        .replace([' ', '-'], "_");
    let num = |keys: &[&str]| keys.iter().find_map(|k| v.get(*k).and_then(|x| x.as_f64()));
    let metres = num(&["distance_m", "meters", "metres"])
        .map(|m| m as f32)
        .or_else(|| num(&["distance_cm", "cm"]).map(|c| c as f32 / 100.0))
        .or_else(|| num(&["steps"]).map(|s| s as f32 * steps.step_m));
    let degrees = num(&["degrees", "angle_deg", "angle"])
        .map(|d| d as f32)
        .or_else(|| num(&["turns", "steps"]).map(|s| s as f32 * steps.turn_deg));
    let valid = |x: Option<f32>| x.is_none_or(|x| x.is_finite() && x > 0.0);
    match name.as_str() {
        "stop" => Some(Decision::Act(vec![Action::Stop])),
        "move_forward" | "forward" if valid(metres) => Some(Decision::Act(steps.forward(metres))),
        "turn_left" | "left" if valid(degrees) => Some(Decision::Act(steps.turn(true, degrees))),
        "turn_right" | "right" if valid(degrees) => Some(Decision::Act(steps.turn(false, degrees))),
        "ask" => {
            let q = v.get("question")?.as_str()?.trim();
            (!q.is_empty()).then(|| Decision::Ask(q.to_string()))
        }
        _ => None,
    }
}

/// Words of `text` in lower case, punctuation split off (`75cm` stays one word; numbers keep
/// their decimal point).
fn words(text: &str) -> Vec<String> {
    text.to_lowercase()
        .split(|c: char| !(c.is_alphanumeric() || c == '.' || c == '°'))
        .map(|w| w.trim_matches('.').to_string())
        .filter(|w| !w.is_empty())
        .collect()
}

/// A number with its unit, read from the start of some words.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Amount {
    /// Metres.
    Len(f32),
    /// Degrees.
    Deg(f32),
    /// Whole primitives.
    Steps(f32),
    /// No known unit: metres after "forward", degrees after "turn".
    Bare(f32),
    /// Zero or not a number.
    Invalid,
}

/// `75 cm`, `0.75m`, `45 degrees`, `45°`, `3 steps` at the start of `w`; `None` when `w` does
/// not start with a number.
fn amount(w: &[String]) -> Option<Amount> {
    let first = w.first()?;
    if !first.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    let split = first
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(first.len());
    let value: f32 = match first[..split].parse() {
        Ok(v) if f32::is_finite(v) && v > 0.0 => v,
        _ => return Some(Amount::Invalid),
    };
    let unit = if split < first.len() {
        first[split..].to_string()
    } else {
        w.get(1).cloned().unwrap_or_default()
    };
    Some(match unit.trim_end_matches('s') {
        "cm" | "centimeter" | "centimetre" => Amount::Len(value / 100.0),
        "m" | "meter" | "metre" => Amount::Len(value),
        "°" | "deg" | "degree" | "degre" => Amount::Deg(value),
        "step" | "time" | "turn" => Amount::Steps(value),
        _ => Amount::Bare(value),
    })
}

/// The question of `ask: ...` (the word `ask` on its own, then a colon).
fn question(text: &str) -> Option<String> {
    let lower = text.to_ascii_lowercase();
    let mut from = 0;
    while let Some(k) = lower[from..].find("ask") {
        let i = from + k;
        from = i + 3;
        let standalone = !lower[..i].ends_with(|c: char| c.is_alphanumeric());
        if let (true, Some(q)) = (standalone, text[i + 3..].trim_start().strip_prefix(':')) {
            let q = q.trim().trim_matches('"').trim();
            return (!q.is_empty()).then(|| q.to_string());
        }
    }
    None
}

fn parse_phrase(text: &str, steps: &Steps) -> Option<Decision> {
    if let Some(q) = question(text) {
        return Some(Decision::Ask(q));
    }
    let w = words(text);
    for (i, word) in w.iter().enumerate() {
        let rest = &w[i + 1..];
        let window = &rest[..rest.len().min(4)];
        let first_amount = || (0..window.len()).find_map(|k| amount(&window[k..]));
        match word.as_str() {
            "stop" | "stopping" => return Some(Decision::Act(vec![Action::Stop])),
            "forward" | "forwards" | "ahead" | "straight" => {
                let metres = match amount(rest) {
                    Some(Amount::Len(m) | Amount::Bare(m)) => Some(m),
                    Some(Amount::Steps(s)) => Some(s * steps.step_m),
                    Some(Amount::Deg(_) | Amount::Invalid) => return None,
                    None => None,
                };
                return Some(Decision::Act(steps.forward(metres)));
            }
            "turn" | "rotate" => {
                if window.first().is_some_and(|w| w == "around") {
                    return Some(Decision::Act(steps.turn(true, Some(180.0))));
                }
                let left = window.iter().find_map(|w| match w.as_str() {
                    "left" => Some(true),
                    "right" => Some(false),
                    _ => None,
                })?;
                let degrees = match first_amount() {
                    Some(Amount::Deg(d) | Amount::Bare(d)) => Some(d),
                    Some(Amount::Steps(s)) => Some(s * steps.turn_deg),
                    Some(Amount::Len(_) | Amount::Invalid) => return None,
                    None => None,
                };
                return Some(Decision::Act(steps.turn(left, degrees)));
            }
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    const S: Steps = Steps {
        step_m: 0.25,
        turn_deg: 15.0,
        max_repeat: 12,
    };

    fn acts(reply: &str) -> Vec<Action> {
        match parse_reply(reply, &S) {
            Some(Decision::Act(a)) => a,
            other => panic!("{reply:?} -> {other:?}"),
        }
    }

    #[test]
    fn distances_and_angles_become_repeated_primitives() {
        let fwd = Action::MoveForward(0.25);
        let left = Action::TurnLeft(15f32.to_radians());
        let right = Action::TurnRight(15f32.to_radians());
        assert_eq!(acts("move forward 75 cm"), vec![fwd; 3]);
        assert_eq!(acts("Move forward 0.5m."), vec![fwd; 2]);
        assert_eq!(acts("go forward 1 meter"), vec![fwd; 4]);
        assert_eq!(acts("move forward"), vec![fwd]);
        assert_eq!(acts("move forward 2 steps"), vec![fwd; 2]);
        assert_eq!(acts("turn left 45 degrees"), vec![left; 3]);
        assert_eq!(acts("Turn right 30°"), vec![right; 2]);
        assert_eq!(acts("turn 90 degrees right"), vec![right; 6]);
        assert_eq!(acts("turn around"), vec![left; 12]);
        assert_eq!(acts("turn left"), vec![left]);
        // Rounded to whole steps, at least one, at most the cap.
        assert_eq!(acts("move forward 10 cm"), vec![fwd]);
        assert_eq!(acts("move forward 40 cm"), vec![fwd; 2]);
        assert_eq!(acts("move forward 20 m"), vec![fwd; 12]);
        assert_eq!(acts("Stop."), vec![Action::Stop]);
        assert_eq!(acts("I am at the sofa, so I stop"), vec![Action::Stop]);
    }

    #[test]
    fn chain_of_thought_is_read_from_the_last_action_line() {
        let r = "The door is ahead, so I should not stop yet.\nAction: turn right 15 degrees";
        assert_eq!(acts(r), vec![Action::TurnRight(15f32.to_radians())]);
        let r = "Thinking...\nACTION: stop";
        assert_eq!(acts(r), vec![Action::Stop]);
    }

    #[test]
    fn json_replies_and_questions() {
        assert_eq!(
            acts(r#"{"action": "move_forward", "distance_cm": 50}"#),
            vec![Action::MoveForward(0.25); 2]
        );
        assert_eq!(
            acts(r#"Action: {"action":"turn_left","degrees":30}"#),
            vec![Action::TurnLeft(15f32.to_radians()); 2]
        );
        assert_eq!(
            parse_reply(r#"{"action":"ask","question":"Where is the bed?"}"#, &S),
            Some(Decision::Ask("Where is the bed?".into()))
        );
        assert_eq!(
            parse_reply("ask: Which way to the kitchen?", &S),
            Some(Decision::Ask("Which way to the kitchen?".into()))
        );
    }

    #[test]
    fn replies_without_an_action_give_none() {
        for r in [
            "",
            "I am not sure what to do.",
            r#"{"action": "fly"}"#,
            r#"{"action": "move_forward", "distance_cm": -5}"#,
            "move forward 45 degrees",
            "ask:",
        ] {
            assert_eq!(parse_reply(r, &S), None, "{r:?}");
        }
    }
}
