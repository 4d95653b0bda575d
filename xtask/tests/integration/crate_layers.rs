//! The layers build alone and point one way (docs/architecture.md): each crate's `cargo tree`
//! holds none of what its layer must not compile, every library crate packages (its default
//! configs are inside it), and optional backends stay out without their features.

use std::path::Path;
use std::process::Command;

const LIBRARIES: [&str; 12] = [
    "vlnverse-env",
    "vlnverse-score",
    "vlnverse-sim",
    "vlnverse-sensors",
    "vlnverse-procgen",
    "vlnverse-import",
    "vlnverse-instructions",
    "vlnverse-generate",
    "vlnverse-eval",
    "vlnverse-task",
    "vlnverse-mllm",
    "vlnverse-agent-http",
];

/// The task layer's crates: the layers below must not reach them.
const TASK_LAYER: [&str; 5] = [
    "vlnverse-score",
    "vlnverse-instructions",
    "vlnverse-generate",
    "vlnverse-eval",
    "vlnverse-task",
];

fn cargo(args: &[&str]) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = Command::new(env!("CARGO"))
        .args(args)
        .current_dir(&root)
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "cargo {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn deps(args: &[&str]) -> Vec<String> {
    let mut a = vec!["tree", "--offline", "-e", "normal", "--prefix", "none"];
    a.extend_from_slice(args);
    cargo(&a)
        .lines()
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .collect()
}

/// Fail when the `cargo tree` of `args` holds any of `forbidden`.
fn assert_without(args: &[&str], forbidden: &[&str]) {
    let d = deps(args);
    assert!(d.len() > 1, "cargo tree {args:?} listed nothing: {d:?}");
    for f in forbidden {
        assert!(
            !d.iter().any(|x| x == f),
            "`cargo tree {}` pulls {f}, which docs/architecture.md keeps out of it",
            args.join(" ")
        );
    }
}

#[test]
fn the_scoring_crate_has_no_physics_graphics_or_http() {
    assert!(deps(&["-p", "vlnverse-score"]).contains(&"serde_json".to_string()));
    assert_without(
        &["-p", "vlnverse-score"],
        &[
            "rapier3d",
            "parry3d",
            "wgpu",
            "ureq",
            "vlnverse-sim",
            "vlnverse-sensors",
        ],
    );
}

#[test]
fn instructions_compile_no_physics_renderer_or_other_task_crate() {
    let heavy = [
        "rapier3d",
        "parry3d",
        "wgpu",
        "vlnverse-sim",
        "vlnverse-sensors",
        "vlnverse-generate",
        "vlnverse-eval",
    ];
    assert_without(&["-p", "vlnverse-instructions"], &heavy);
    assert_without(
        &["-p", "vlnverse-instructions", "--no-default-features"],
        &["ureq"],
    );
}

#[test]
fn generation_compiles_no_physics_gpu_or_evaluation() {
    assert_without(
        &["-p", "vlnverse-generate"],
        &["rapier3d", "wgpu", "vlnverse-sim", "vlnverse-eval"],
    );
    assert_without(
        &["-p", "vlnverse-generate", "--no-default-features"],
        &["ureq"],
    );
}

#[test]
fn evaluation_compiles_no_instruction_generator_or_http_client_by_default() {
    assert_without(
        &["-p", "vlnverse-eval"],
        &["vlnverse-instructions", "vlnverse-generate", "ureq"],
    );
    // The LLM oracle brings the chat client, and only then.
    let with = deps(&["-p", "vlnverse-eval", "--features", "llm-oracle"]);
    assert!(with.iter().any(|x| x == "ureq"), "{with:?}");
}

#[test]
fn the_mllm_agent_brings_its_http_client_but_no_gpu_backend() {
    let d = deps(&["-p", "vlnverse-mllm"]);
    assert!(d.iter().any(|x| x == "ureq"), "{d:?}");
    assert_without(&["-p", "vlnverse-mllm"], &["wgpu", "vlnverse-generate"]);
    // Evaluation does not reach the agent (the agent depends on it, not the other way).
    assert_without(&["-p", "vlnverse-eval"], &["vlnverse-mllm"]);
}

#[test]
fn the_http_agent_brings_its_http_client_but_no_gpu_backend_or_generator() {
    let d = deps(&["-p", "vlnverse-agent-http"]);
    assert!(d.iter().any(|x| x == "ureq"), "{d:?}");
    assert_without(
        &["-p", "vlnverse-agent-http"],
        &["wgpu", "vlnverse-generate", "vlnverse-instructions"],
    );
    // Evaluation does not reach the client (the client depends on it, not the other way).
    assert_without(&["-p", "vlnverse-eval"], &["vlnverse-agent-http"]);
}

#[test]
fn lower_layers_know_nothing_of_tasks() {
    for c in [
        "vlnverse-env",
        "vlnverse-sim",
        "vlnverse-sensors",
        "vlnverse-procgen",
    ] {
        assert_without(&["-p", c], &TASK_LAYER);
    }
}

#[test]
fn optional_backends_stay_out_without_their_features() {
    let sensors = deps(&["-p", "vlnverse-sensors", "--no-default-features"]);
    assert!(!sensors.iter().any(|x| x == "wgpu"), "{sensors:?}");
    assert_without(
        &["-p", "vlnverse-task", "--no-default-features"],
        &["wgpu", "ureq"],
    );
    let with = deps(&["-p", "vlnverse-task"]);
    assert!(with.iter().any(|x| x == "wgpu") && with.iter().any(|x| x == "ureq"));
}

#[test]
fn every_library_crate_packages_with_its_configs() {
    for c in LIBRARIES {
        let files = cargo(&["package", "--offline", "-p", c, "--list", "--allow-dirty"]);
        assert!(files.lines().any(|f| f == "Cargo.toml"), "{c}: {files}");
        assert!(files.lines().any(|f| f == "README.md"), "{c}: no README");
        // Files the crate embeds with include_str! are inside the package.
        let src = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../crates")
            .join(c)
            .join("src");
        for path in rs_files(&src) {
            let text = std::fs::read_to_string(&path).unwrap();
            for inc in text.split("include_str!(\"").skip(1) {
                let rel = inc.split('"').next().unwrap();
                let file = path.parent().unwrap().join(rel);
                let file = file
                    .canonicalize()
                    .unwrap_or_else(|e| panic!("{c}: {} embeds {rel}: {e}", path.display()));
                let krate = src.parent().unwrap().canonicalize().unwrap();
                let inside = file.strip_prefix(&krate).unwrap_or_else(|_| {
                    panic!("{c}: {} embeds {rel}, outside the crate", path.display())
                });
                let inside = inside.to_string_lossy().replace('\\', "/");
                assert!(
                    files.lines().any(|f| f == inside),
                    "{c}: {inside} not packaged"
                );
            }
        }
    }
}

fn rs_files(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(rs_files(&p));
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
    out
}
