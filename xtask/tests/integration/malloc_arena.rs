//! `xtask evaluate` runs with one glibc malloc arena (`xtask/src/malloc_arena.rs`): it executes
//! itself again with `MALLOC_ARENA_MAX=1`, keeping its arguments and a value the user set
//! (Linux with glibc only, where the module is compiled).

use std::process::Command;

/// `xtask evaluate` on a dataset that does not exist, with `RUST_LOG=debug` and `env` set:
/// whether it succeeded, and its stderr.
fn evaluate_missing(env: &[(&str, &str)]) -> (bool, String) {
    let missing = std::env::temp_dir().join(format!("vlnverse-no-dataset-{}", std::process::id()));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_xtask"));
    cmd.args(["evaluate", "--dataset"])
        .arg(&missing)
        .args(["--task", "coarse", "--split", "test", "--agent", "oracle"])
        .args(["--out"])
        .arg(missing.join("out"))
        .env_remove("MALLOC_ARENA_MAX")
        .env_remove("GLIBC_TUNABLES")
        .env("RUST_LOG", "debug");
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().expect("run xtask");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn evaluate_runs_with_one_malloc_arena_and_keeps_its_arguments_and_the_users_setting() {
    let (ok, err) = evaluate_missing(&[]);
    assert!(!ok, "{err}");
    assert!(err.contains("MALLOC_ARENA_MAX=1"), "{err}");
    // The arguments came through the second execution: the error names the dataset.
    assert!(err.contains("vlnverse-no-dataset-"), "{err}");
    let (ok, err) = evaluate_missing(&[("MALLOC_ARENA_MAX", "4")]);
    assert!(!ok, "{err}");
    assert!(err.contains("MALLOC_ARENA_MAX=4"), "{err}");
    assert!(!err.contains("MALLOC_ARENA_MAX=1"), "{err}");
}
