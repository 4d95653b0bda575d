//! The prompts: data files of the crate (`prompts/`), one per history mode and one per task,
//! put together with the answer format into the system message; the user message of each
//! decision is built here from the episode's state.

use std::fmt::Write as _;

use vlnverse_score::episode::Task;

use crate::config::{ActionFormat, History, MllmConfig};

const MODE_TEXT: &str = include_str!("../prompts/mode/text.md");
const MODE_MAP: &str = include_str!("../prompts/mode/map.md");
const TASK_FINE: &str = include_str!("../prompts/task/fine.md");
const TASK_COARSE: &str = include_str!("../prompts/task/coarse.md");
const TASK_VISUAL: &str = include_str!("../prompts/task/visual_reference.md");
const TASK_LONG: &str = include_str!("../prompts/task/long_horizon.md");
const TASK_DIALOGUE: &str = include_str!("../prompts/task/dialogue.md");
const ANSWER_TEXT: &str = include_str!("../prompts/answer/text.md");
const ANSWER_JSON: &str = include_str!("../prompts/answer/json.md");
const ASK_TEXT: &str = include_str!("../prompts/answer/ask_text.md");
const ASK_JSON: &str = include_str!("../prompts/answer/ask_json.md");
const COT: &str = include_str!("../prompts/answer/cot.md");
const DIRECT: &str = include_str!("../prompts/answer/direct.md");
/// Sent after a reply with no readable move.
pub const CORRECTIVE: &str = include_str!("../prompts/corrective.md");
/// Sent after a question that cannot be asked (no oracle, no budget left).
pub const NO_QUESTIONS: &str = include_str!("../prompts/no_questions.md");

/// Every prompt file, for the agent's fingerprint (an edited prompt is another agent).
pub const ALL: [&str; 15] = [
    MODE_TEXT,
    MODE_MAP,
    TASK_FINE,
    TASK_COARSE,
    TASK_VISUAL,
    TASK_LONG,
    TASK_DIALOGUE,
    ANSWER_TEXT,
    ANSWER_JSON,
    ASK_TEXT,
    ASK_JSON,
    COT,
    DIRECT,
    CORRECTIVE,
    NO_QUESTIONS,
];

/// The system message of an episode.
pub fn system(cfg: &MllmConfig, task: Task, step_m: f32, turn_deg: f32) -> String {
    let mode = match cfg.history {
        History::Text => MODE_TEXT,
        History::Map => MODE_MAP,
    };
    let task_text = match task {
        Task::Fine => TASK_FINE,
        Task::Coarse => TASK_COARSE,
        Task::VisualReference => TASK_VISUAL,
        Task::LongHorizon => TASK_LONG,
        Task::Dialogue => TASK_DIALOGUE,
    };
    let (answer, ask) = match cfg.action_format {
        ActionFormat::Text => (ANSWER_TEXT, ASK_TEXT),
        ActionFormat::Json => (ANSWER_JSON, ASK_JSON),
    };
    let mut s = String::new();
    s.push_str(mode.trim());
    s.push_str("\n\n");
    s.push_str(task_text.trim());
    s.push_str("\n\n");
    s.push_str(answer.trim_end());
    if task == Task::Dialogue && cfg.asks_per_step > 0 {
        s.push('\n');
        s.push_str(ask.trim_end());
    }
    s.push_str("\n\n");
    s.push_str(if cfg.chain_of_thought { COT } else { DIRECT }.trim());
    s.replace("{step_cm}", &format!("{:.0}", step_m * 100.0))
        .replace("{turn_deg}", &format!("{turn_deg:.0}"))
}

/// One past decision in the text history.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// Step at which the model chose it.
    pub step: u32,
    /// The move in words (`move forward 75 cm`).
    pub action: String,
    /// A move of it was blocked.
    pub blocked: bool,
    /// What the depth camera showed once it was done.
    pub seen: Option<String>,
}

/// What one decision's user message says.
pub struct StepText<'a> {
    /// The instruction.
    pub instruction: &'a str,
    /// Long-horizon: the sub-instructions and the index of the current one.
    pub goals: Option<(&'a [String], u32)>,
    /// Dialogue: questions left and the answers so far.
    pub dialogue: Option<(u32, &'a [(String, String)])>,
    /// Step index and limit.
    pub step: u32,
    /// Step limit.
    pub max_steps: u32,
    /// Text history (empty in map mode).
    pub history: &'a [Entry],
    /// Entries shown (the newest).
    pub history_steps: usize,
    /// The depth camera now.
    pub seen_now: Option<&'a str>,
    /// The last move was blocked.
    pub blocked_now: bool,
    /// Descriptions of the pictures, in order.
    pub pictures: &'a [String],
}

impl StepText<'_> {
    /// The message text.
    pub fn render(&self, mode: History) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "Instruction: {}", self.instruction.trim());
        if let Some((goals, current)) = self.goals {
            s.push_str("Goals in order:\n");
            for (i, g) in goals.iter().enumerate() {
                let mark = match (i as u32).cmp(&current) {
                    std::cmp::Ordering::Less => " (done)",
                    std::cmp::Ordering::Equal => " (current)",
                    std::cmp::Ordering::Greater => "",
                };
                let _ = writeln!(s, "{}. {}{mark}", i + 1, g.trim());
            }
        }
        if let Some((left, answers)) = self.dialogue {
            let _ = writeln!(s, "Questions left: {left}.");
            for (q, a) in answers {
                let _ = writeln!(s, "You asked: {q}\nThe guide said: {a}");
            }
        }
        let _ = writeln!(s, "Step {} of at most {}.", self.step, self.max_steps);
        if mode == History::Text {
            let shown = &self.history[self.history.len().saturating_sub(self.history_steps)..];
            if shown.is_empty() {
                s.push_str("Moves so far: none.\n");
            } else {
                s.push_str("Moves so far, oldest first:\n");
                for e in shown {
                    let _ = write!(s, "- step {}: {}", e.step, e.action);
                    if e.blocked {
                        s.push_str(" (blocked)");
                    }
                    if let Some(seen) = &e.seen {
                        let _ = write!(s, "; then {seen}");
                    }
                    s.push('\n');
                }
            }
        }
        if let Some(seen) = self.seen_now {
            let _ = writeln!(s, "Depth sensor now: {seen}.");
        }
        if self.blocked_now {
            s.push_str("The last move was blocked by an obstacle.\n");
        }
        if !self.pictures.is_empty() {
            let _ = writeln!(s, "Pictures: {}.", self.pictures.join("; "));
        }
        s.push_str("What is your next move?");
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_task_and_mode_has_its_own_text_with_the_step_sizes() {
        let mut seen = std::collections::BTreeSet::new();
        for history in [History::Text, History::Map] {
            for task in Task::ALL {
                let cfg = MllmConfig {
                    history,
                    ..Default::default()
                };
                let s = system(&cfg, task, 0.25, 15.0);
                assert!(s.contains("25 cm") && s.contains("15 degrees"), "{s}");
                assert!(!s.contains('{') || s.contains("JSON"), "{s}");
                assert_eq!(s.contains("- ask:"), task == Task::Dialogue, "{task:?}");
                seen.insert(s);
            }
        }
        assert_eq!(seen.len(), 10);
    }

    #[test]
    fn the_step_message_lists_goals_answers_and_history() {
        let goals = vec!["Go to the bed.".to_string(), "Then the sofa.".to_string()];
        let answers = vec![("Where?".to_string(), "Turn left.".to_string())];
        let history = vec![
            Entry {
                step: 0,
                action: "move forward 50 cm".into(),
                blocked: true,
                seen: Some("open floor ahead 0.3 m".into()),
            },
            Entry {
                step: 2,
                action: "turn left 30 degrees".into(),
                blocked: false,
                seen: None,
            },
        ];
        let t = StepText {
            instruction: "Go to the bed, then the sofa.",
            goals: Some((&goals, 1)),
            dialogue: Some((2, &answers)),
            step: 4,
            max_steps: 100,
            history: &history,
            history_steps: 1,
            seen_now: Some("open floor ahead 2.0 m"),
            blocked_now: false,
            pictures: &["the camera view".to_string()],
        };
        let s = t.render(History::Text);
        assert!(
            s.contains("1. Go to the bed. (done)\n2. Then the sofa. (current)"),
            "{s}"
        );
        assert!(s.contains("Questions left: 2.") && s.contains("The guide said: Turn left."));
        // Only the newest entry is shown with history_steps = 1.
        assert!(
            s.contains("step 2: turn left") && !s.contains("step 0:"),
            "{s}"
        );
        assert!(!t.render(History::Map).contains("Moves so far"));
    }
}
