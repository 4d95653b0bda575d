//! `cargo xtask test`: every test of the project, Rust and Python, in one command.
//!
//! 1. `cargo test --workspace` (the test profile: optimised dependencies, quick to build);
//! 2. a virtual environment in `.venv/` with the Python test tools
//!    (`crates/vlnverse-py/requirements-dev.txt`), the `vlnverse` package built into it by
//!    maturin, and a `tiny` dataset under `target/py-test-data/`;
//! 3. ruff and mypy over the Python package, then pytest over `crates/vlnverse-py/tests`.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context as _};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Only the Rust tests.
    #[arg(long, conflicts_with = "python_only")]
    pub rust_only: bool,
    /// Only the Python tests (and the package build they need).
    #[arg(long)]
    pub python_only: bool,
    /// Python interpreter that creates the virtual environment.
    #[arg(long, default_value = "python3")]
    pub python: String,
    /// Extra arguments for pytest (e.g. `-k vector`).
    #[arg(last = true)]
    pub pytest_args: Vec<String>,
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace")
        .to_path_buf()
}

fn run(what: &str, cmd: &mut Command) -> anyhow::Result<()> {
    eprintln!("== {what}");
    let status = cmd
        .status()
        .with_context(|| format!("{what}: cannot start {:?}", cmd.get_program()))?;
    if !status.success() {
        bail!("{what} failed ({status})");
    }
    Ok(())
}

/// Run the command.
pub fn run_tests(args: Args) -> anyhow::Result<()> {
    let root = root();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    if !args.python_only {
        run(
            "cargo test --workspace",
            Command::new(&cargo)
                .current_dir(&root)
                .args(["test", "--workspace"]),
        )?;
    }
    if args.rust_only {
        return Ok(());
    }
    let venv = root.join(".venv");
    let py = venv.join("bin").join("python");
    if !py.exists() {
        run(
            "python virtual environment (.venv)",
            Command::new(&args.python).args(["-m", "venv"]).arg(&venv),
        )?;
    }
    let pkg = root.join("crates").join("vlnverse-py");
    run(
        "python test tools",
        Command::new(&py)
            .args(["-m", "pip", "install", "-q", "-r"])
            .arg(pkg.join("requirements-dev.txt")),
    )?;
    run(
        "maturin develop --release (the vlnverse package)",
        Command::new(venv.join("bin").join("maturin"))
            .current_dir(&root)
            .args(["develop", "--release", "-q", "-m"])
            .arg(pkg.join("Cargo.toml"))
            .env("VIRTUAL_ENV", &venv),
    )?;
    let data = root.join("target").join("py-test-data").join("tiny");
    if data.exists() {
        std::fs::remove_dir_all(&data).with_context(|| format!("removing {}", data.display()))?;
    }
    let exe = std::env::current_exe().context("locating the xtask binary")?;
    run(
        "tiny dataset for the Python tests",
        Command::new(&exe)
            .current_dir(&root)
            .args(["generate", "--preset", "tiny", "--out"])
            .arg(&data),
    )?;
    run(
        "ruff (python lint)",
        Command::new(venv.join("bin").join("ruff"))
            .current_dir(&pkg)
            .args(["check", "python", "tests", "bench", "../../examples/python"]),
    )?;
    run(
        "mypy (python types)",
        Command::new(&py)
            .current_dir(&pkg)
            .args(["-m", "mypy", "python/vlnverse"]),
    )?;
    run(
        "pytest",
        Command::new(&py)
            .current_dir(&root)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(pkg.join("tests"))
            .args(&args.pytest_args)
            .env("VLNVERSE_TEST_DATASET", &data)
            .env("VLNVERSE_XTASK", &exe),
    )?;
    Ok(())
}
