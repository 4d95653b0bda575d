//! The optional LLM oracle against a local stub endpoint.

use std::sync::Arc;
use vlnverse_eval::oracle::{
    LlmOracle, Oracle, OracleConfig, OracleQuery, ShortestPathOracle, ORACLE_PROMPT,
};
use vlnverse_instructions::llm::{LlmConfig, OnReject};
use vlnverse_testkit::homes::{paths, worlds};
use vlnverse_testkit::llm_stub::stub;

#[test]
fn llm_oracle_rephrases_answers_and_keeps_the_budget() {
    let w = &worlds(1)[0];
    let s = &paths(w, 1, 31)[0];
    let a = s.path[0];
    let b = s.path[s.path.len() - 1];
    let make = || {
        ShortestPathOracle::new(
            Arc::new(w.scene.clone()),
            Arc::new(w.graph.clone()),
            Arc::new(w.maps.navigable.clone()),
            b,
            None,
            OracleConfig {
                budget: 1,
                ..Default::default()
            },
        )
        .unwrap()
    };
    let plain = make().ask(&OracleQuery::WhichWay, a, 0.2).unwrap();
    let (url, seen) = stub(vec![(200, "Head that way, friend.".into())]);
    let cfg = LlmConfig {
        base_url: url,
        model: "stub-oracle".into(),
        api_key_env: None,
        on_reject: OnReject::Error,
        retries: 0,
        ..Default::default()
    };
    let mut o = LlmOracle::new(make(), cfg, 5).unwrap();
    let ans = o.ask(&OracleQuery::WhichWay, a, 0.2).unwrap();
    assert_eq!(ans.text, "Head that way, friend.");
    assert_eq!(ans.turn, plain.turn);
    assert_eq!(ans.distance_m, plain.distance_m);
    {
        let seen = seen.lock().unwrap();
        assert_eq!(seen.len(), 1);
        let msgs = seen[0].body["messages"].as_array().unwrap();
        assert_eq!(seen[0].body["model"], "stub-oracle");
        assert_eq!(msgs[0]["content"], ORACLE_PROMPT);
        let user = msgs[1]["content"].as_str().unwrap();
        assert!(
            user.contains("Which way") && user.contains(&plain.text),
            "{user}"
        );
    }
    // Budget spent: answered locally, no request (the stub would refuse a second connection).
    let spent = o.ask(&OracleQuery::AmIClose, a, 0.0).unwrap();
    assert!(!spent.answered && spent.distance_m.is_none());
    assert_eq!(o.remaining(), 0);
    assert_eq!(seen.lock().unwrap().len(), 1);
}
