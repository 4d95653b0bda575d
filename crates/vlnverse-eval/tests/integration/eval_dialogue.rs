//! Dialogue episodes: the agent's oracle handle is the task layer's shortest-path oracle, with
//! the episode's question budget.

use crate::eval_support;

use std::sync::{Arc, Mutex};
use vlnverse_eval::NOT_UNDERSTOOD;
use vlnverse_eval::{
    evaluate, Agent, AgentFactory, EpisodeInputs, EvalConfig, EvalRequest, StepInput,
};
use vlnverse_score::dataset;
use vlnverse_score::{Split, Task};
use vlnverse_sensors::Backend;
use vlnverse_sim::Action;

/// Asks an empty question, then "which way?" three times, then stops; records (answer, questions left).
struct Asker {
    log: Arc<Mutex<Vec<(Option<String>, u32)>>>,
}

impl Agent for Asker {
    fn reset(&mut self, _inputs: &EpisodeInputs) -> vlnverse_eval::Result<()> {
        Ok(())
    }
    fn act(&mut self, step: &mut StepInput) -> vlnverse_eval::Result<Action> {
        if step.step >= 3 {
            return Ok(Action::Stop);
        }
        let oracle = step
            .oracle
            .as_mut()
            .expect("dialogue episodes carry an oracle");
        if step.step == 0 {
            // An empty question is answered with a hint, at no cost.
            let answer = oracle.ask(" ? ");
            self.log.lock().unwrap().push((answer, oracle.remaining()));
        }
        let answer = oracle.ask("Which way should I go?");
        self.log.lock().unwrap().push((answer, oracle.remaining()));
        Ok(Action::TurnLeft(0.2))
    }
}

struct AskerFactory(Arc<Mutex<Vec<(Option<String>, u32)>>>);

impl AgentFactory for AskerFactory {
    fn name(&self) -> String {
        "asker".into()
    }
    fn make(&self) -> vlnverse_eval::Result<Box<dyn Agent>> {
        Ok(Box::new(Asker {
            log: self.0.clone(),
        }))
    }
}

/// The dialogue test split of `dir`, one thread, no rendering or plots, into `dir/run`.
fn blind_request(dir: &std::path::Path, config: EvalConfig) -> EvalRequest {
    EvalRequest::new(
        dir.to_path_buf(),
        Task::Dialogue,
        Split::Test,
        dir.join("run"),
    )
    .threads(1)
    .config(EvalConfig {
        backend: Some(Backend::Raycast),
        render: false,
        plots: 0,
        ..config
    })
}

#[test]
fn dialogue_agents_ask_the_shortest_path_oracle_within_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    let mut eps = eval_support::make_object_dataset(dir.path(), 1, 2, 11);
    assert!(!eps.is_empty());
    for e in &mut eps {
        e.task = Task::Dialogue;
        e.oracle_budget = Some(2);
    }
    dataset::write_split(dir.path(), Task::Dialogue, Split::Test, &eps).unwrap();
    let log = Arc::new(Mutex::new(Vec::new()));
    let req = blind_request(dir.path(), EvalConfig::default());
    evaluate(&req, &AskerFactory(log.clone())).unwrap();
    let log = log.lock().unwrap();
    assert_eq!(log.len(), 4 * eps.len());
    for chunk in log.chunks(4) {
        let (empty, left) = &chunk[0];
        assert_eq!(
            (empty.as_deref(), *left),
            (Some(NOT_UNDERSTOOD), 2),
            "an empty question costs nothing"
        );
        // Two answers carrying words, then the budget is spent.
        let (a0, left0) = &chunk[1];
        let (a1, left1) = &chunk[2];
        let (a2, left2) = &chunk[3];
        assert!(a0.as_ref().is_some_and(|t| !t.is_empty()), "{a0:?}");
        assert!(a1.as_ref().is_some_and(|t| !t.is_empty()), "{a1:?}");
        assert_eq!((*left0, *left1, *left2), (1, 0, 0));
        assert!(a2.is_none(), "answered beyond the budget: {a2:?}");
        // "Which way" answers speak of turning or going straight, with a distance.
        let t = a0.as_ref().unwrap().to_lowercase();
        assert!(
            ["left", "right", "straight", "ahead", "around", "arrived", "here"]
                .iter()
                .any(|w| t.contains(w)),
            "{t}"
        );
    }
}

#[cfg(feature = "llm-oracle")]
#[test]
fn the_llm_oracle_rephrases_answers_through_the_endpoint() {
    use vlnverse_eval::oracle::ORACLE_PROMPT;
    use vlnverse_instructions::llm::LlmConfig;
    use vlnverse_testkit::llm_stub::stub;

    let dir = tempfile::tempdir().unwrap();
    let mut eps = eval_support::make_object_dataset(dir.path(), 1, 1, 12);
    eps.truncate(1);
    for e in &mut eps {
        e.task = Task::Dialogue;
        e.oracle_budget = Some(2);
    }
    dataset::write_split(dir.path(), Task::Dialogue, Split::Test, &eps).unwrap();
    let said = "Head left past the table, then keep going.";
    let (url, seen) = stub(vec![(200, said.into()), (200, said.into())]);
    let log = Arc::new(Mutex::new(Vec::new()));
    let req = blind_request(
        dir.path(),
        EvalConfig {
            oracle_llm: Some(LlmConfig {
                base_url: url,
                model: "local".into(),
                api_key_env: None,
                retries: 0,
                ..Default::default()
            }),
            ..Default::default()
        },
    );
    evaluate(&req, &AskerFactory(log.clone())).unwrap();
    let log = log.lock().unwrap();
    // The empty question never reaches the endpoint; the two budgeted answers are the LLM's.
    assert_eq!(log[0].0.as_deref(), Some(NOT_UNDERSTOOD));
    assert_eq!(log[1].0.as_deref(), Some(said));
    assert_eq!(log[2].0.as_deref(), Some(said));
    assert!(log[3].0.is_none(), "budget spent");
    let seen = seen.lock().unwrap();
    assert_eq!(seen.len(), 2);
    assert_eq!(seen[0].body["messages"][0]["content"], ORACLE_PROMPT);
    // The oracle is part of the run: its endpoint is in run.json.
    let run = std::fs::read_to_string(dir.path().join("run/run.json")).unwrap();
    assert!(run.contains("oracle_llm"), "{run}");
}
