//! The optional LLM stage against a local stub of an OpenAI-compatible endpoint.

use crate::instructions_fixture;

use instructions_fixture::{paths, stub, worlds, Ctx, Seen};
use vlnverse_instructions::llm::{
    parse_verdict, LlmConfig, LlmGenerator, OnReject, DESCRIBER_PROMPT, SYNTHESIZER_PROMPT,
    VERIFIER_PROMPT,
};
use vlnverse_instructions::{coarse_expression, InstructionGenerator, TemplateGenerator};
use vlnverse_score::Style;

fn config(url: &str, key_env: Option<&str>) -> LlmConfig {
    LlmConfig {
        base_url: url.to_string(),
        model: "stub-model".into(),
        api_key_env: key_env.map(String::from),
        timeout_s: 10.0,
        retries: 1,
        retry_backoff_ms: 10,
        ..Default::default()
    }
}

fn messages(s: &Seen) -> Vec<(String, String)> {
    s.body["messages"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| {
            (
                m["role"].as_str().unwrap().to_string(),
                m["content"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

#[test]
fn describer_and_verifier_rewrite_a_fine_instruction() {
    let w = &worlds(1)[0];
    let s = paths(w, 3, 21)
        .into_iter()
        .find(|s| {
            !TemplateGenerator::default()
                .fine(&w.ctx(s), 1)
                .unwrap()
                .grounding
                .is_empty()
        })
        .expect("a path with landmarks");
    let base = TemplateGenerator::default().fine(&w.ctx(&s), 1).unwrap();
    // A rewrite that names only the grounded objects (the grounding check passes it).
    let named: Vec<String> = base
        .grounding
        .iter()
        .map(|g| g.class.replace('_', " "))
        .collect();
    let fluent = format!(
        "Walk on past the {}, then stop there.",
        named.join(" and the ")
    );
    let fluent = fluent.as_str();
    let (url, seen) = stub(vec![
        (200, fluent.to_string()),
        (200, "YES. Same objects and sides.".to_string()),
    ]);
    std::env::set_var("VLNVERSE_TEST_LLM_KEY_A", "sk-test-123");
    let g = LlmGenerator::new(
        TemplateGenerator::default(),
        config(&url, Some("VLNVERSE_TEST_LLM_KEY_A")),
    )
    .unwrap();
    let ins = g.fine(&w.ctx(&s), 1).unwrap();
    assert_eq!(ins.instruction_text, fluent);
    assert_eq!(ins.grounding, base.grounding, "grounding is the template's");

    let seen = seen.lock().unwrap().clone();
    assert_eq!(seen.len(), 2);
    for r in &seen {
        assert_eq!(r.request_line, "POST /v1/chat/completions HTTP/1.1");
        assert_eq!(r.authorization.as_deref(), Some("Bearer sk-test-123"));
        assert_eq!(r.body["model"], "stub-model");
        assert_eq!(r.body["temperature"], 0.0);
        assert_eq!(r.body["seed"], 1);
    }
    // Describer: its prompt, the template text and each grounded object's class.
    let m = messages(&seen[0]);
    assert_eq!(m[0], ("system".to_string(), DESCRIBER_PROMPT.to_string()));
    assert!(m[1].1.contains(&base.instruction_text));
    for gr in &base.grounding {
        assert!(m[1].1.contains(&gr.class.replace('_', " ")), "{}", m[1].1);
    }
    // Verifier: its prompt, the facts and the candidate.
    let m = messages(&seen[1]);
    assert_eq!(m[0].1, VERIFIER_PROMPT);
    assert!(m[1].1.contains(&base.instruction_text) && m[1].1.contains(fluent));
}

#[test]
fn a_rejected_candidate_falls_back_to_the_template_or_errors() {
    let w = &worlds(1)[0];
    let s = &paths(w, 1, 22)[0];
    let target = w
        .scene
        .objects
        .iter()
        .find(|o| coarse_expression(&w.ctx(s), o.id, Style::Natural).is_ok())
        .unwrap()
        .id;
    let base = TemplateGenerator::default()
        .coarse(&w.ctx(s), target, Style::Natural, 4)
        .unwrap();
    let (url, seen) = stub(vec![
        (200, "Go find the purple elephant.".into()),
        (
            200,
            "NO - the candidate names an object that is not in the facts.".into(),
        ),
    ]);
    let g = LlmGenerator::new(TemplateGenerator::default(), config(&url, None)).unwrap();
    let ins = g.coarse(&w.ctx(s), target, Style::Natural, 4).unwrap();
    assert_eq!(ins, base);
    let seen = seen.lock().unwrap().clone();
    assert_eq!(seen[0].authorization, None);
    assert!(
        messages(&seen[0])[1].1.contains("natural"),
        "the style is requested"
    );

    let (url, _) = stub(vec![
        (200, "Go find the purple elephant.".into()),
        (200, "no, it names an elephant".into()),
    ]);
    let strict = LlmConfig {
        on_reject: OnReject::Error,
        ..config(&url, None)
    };
    let g = LlmGenerator::new(TemplateGenerator::default(), strict).unwrap();
    let e = g
        .coarse(&w.ctx(s), target, Style::Natural, 4)
        .unwrap_err()
        .to_string();
    assert!(e.contains("rejected") && e.contains("elephant"), "{e}");
}

#[test]
fn synthesizer_combines_sub_instructions() {
    let w = &worlds(1)[0];
    let s = &paths(w, 1, 23)[0];
    let t = TemplateGenerator::default();
    let targets: Vec<u32> = w
        .scene
        .objects
        .iter()
        .filter(|o| coarse_expression(&w.ctx(s), o.id, Style::Casual).is_ok())
        // Only targets the path reaches: the template checks its grounding against the path.
        .filter(|o| t.coarse(&w.ctx(s), o.id, Style::Casual, 2).is_ok())
        .map(|o| o.id)
        .take(2)
        .collect();
    let parts: Vec<_> = targets
        .iter()
        .map(|&id| t.coarse(&w.ctx(s), id, Style::Casual, 2).unwrap())
        .collect();
    let combined = "First do one thing, then the other.";
    let (url, seen) = stub(vec![(200, combined.into()), (200, "YES".into())]);
    let g = LlmGenerator::new(TemplateGenerator::default(), config(&url, None)).unwrap();
    let ins = g.chain(&parts, 9).unwrap();
    assert_eq!(ins.instruction_text, combined);
    assert_eq!(ins.sub_instructions.len(), 2);
    let seen = seen.lock().unwrap().clone();
    let m = messages(&seen[0]);
    assert_eq!(m[0].1, SYNTHESIZER_PROMPT);
    for p in &parts {
        assert!(m[1].1.contains(&p.instruction_text));
    }
}

#[test]
fn server_errors_are_retried() {
    let w = &worlds(1)[0];
    let s = &paths(w, 1, 24)[0];
    let (url, seen) = stub(vec![
        (503, "busy".into()),
        (200, "Walk ahead and stop.".into()),
        (200, "YES".into()),
    ]);
    let cfg = LlmConfig {
        on_reject: OnReject::Error,
        ..config(&url, None)
    };
    let g = LlmGenerator::new(TemplateGenerator::default(), cfg).unwrap();
    assert_eq!(
        g.fine(&w.ctx(s), 3).unwrap().instruction_text,
        "Walk ahead and stop."
    );
    assert_eq!(seen.lock().unwrap().len(), 3);

    // Out of retries: the error names the endpoint; the fallback policy keeps the template.
    let (url, _) = stub(vec![(500, "down".into()), (500, "down".into())]);
    let cfg = LlmConfig {
        on_reject: OnReject::Error,
        ..config(&url, None)
    };
    let g = LlmGenerator::new(TemplateGenerator::default(), cfg).unwrap();
    let e = g.fine(&w.ctx(s), 3).unwrap_err().to_string();
    assert!(e.contains("chat/completions") && e.contains("500"), "{e}");
    let (url, _) = stub(vec![(500, "down".into()), (500, "down".into())]);
    let g = LlmGenerator::new(TemplateGenerator::default(), config(&url, None)).unwrap();
    assert_eq!(
        g.fine(&w.ctx(s), 3).unwrap(),
        TemplateGenerator::default().fine(&w.ctx(s), 3).unwrap()
    );
}

#[test]
fn config_and_verdict_errors_are_clear() {
    let e = LlmGenerator::new(TemplateGenerator::default(), config("ftp://x", None))
        .unwrap_err()
        .to_string();
    assert!(e.contains("llm.base_url") && e.contains("ftp://x"), "{e}");
    let e = LlmGenerator::new(
        TemplateGenerator::default(),
        LlmConfig {
            model: " ".into(),
            ..config("http://127.0.0.1:1", None)
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("llm.model"), "{e}");
    // A named key variable that is not set: refused when the stage is made, before any work.
    let cfg = LlmConfig {
        on_reject: OnReject::Error,
        ..config("http://127.0.0.1:1/v1", Some("VLNVERSE_TEST_LLM_KEY_UNSET"))
    };
    let e = LlmGenerator::new(TemplateGenerator::default(), cfg)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("llm.api_key_env") && e.contains("VLNVERSE_TEST_LLM_KEY_UNSET"),
        "{e}"
    );

    assert!(parse_verdict("YES").accepted);
    assert!(parse_verdict("yes, it matches").accepted);
    let v = parse_verdict("No: wrong side for the sofa");
    assert!(
        !v.accepted && v.reason == "wrong side for the sofa",
        "{v:?}"
    );
    assert!(!parse_verdict("Maybe").accepted);
    assert!(!parse_verdict("YESTERDAY it was fine").accepted);
}
