//! `cargo xtask test`: every test of the project, Rust and Python, in one command.
//!
//! 1. `cargo test --workspace` (the test profile: optimised dependencies, quick to build),
//!    then `cargo xtask results --check --ci` (the docs' result tables made on `tiny`);
//! 2. a virtual environment in `.venv/` with the Python test tools
//!    (`crates/vlnverse-py/requirements-dev.txt`), the `vlnverse` package built into it by
//!    maturin, and a `tiny` dataset under `target/py-test-data/`;
//! 3. for each Python suite (the package, the LeRobot export check, the baselines, the
//!    hostile-input table of `tests/hostile/`, the browser tests): its packages, ruff and mypy;
//!    then one pytest over all their tests (the hostile suite's outcome counts show in its
//!    warnings summary).

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

/// One Python test suite: a folder with its own packages, lint, types and tests.
struct Suite {
    /// Shown in the step names.
    name: &'static str,
    /// Folder, relative to the workspace root; a suite whose folder is absent is skipped.
    dir: &'static str,
    /// `pip install -r` this file (relative to `dir`) first.
    requirements: Option<&'static str>,
    /// `pip install -e dir` (a pure-Python package with a pyproject.toml).
    editable: bool,
    /// What ruff checks (relative to `dir`; the folder's pyproject.toml configures it).
    lint: &'static [&'static str],
    /// What mypy checks (relative to `dir`).
    typed: Option<&'static str>,
    /// The pytest folder (relative to `dir`).
    tests: &'static str,
}

/// Every Python suite, in the order pytest runs them. One pytest collects them all (default
/// import mode), so only `crates/vlnverse-py/tests` is a package with a `conftest.py`; the other
/// folders have neither `__init__.py` nor `conftest.py`, and their file names are unique
/// (`test_export_*`, `test_baselines_*`, `test_web_*`, helpers `_<suite>_*.py`).
const SUITES: &[Suite] = &[
    Suite {
        name: "vlnverse",
        dir: "crates/vlnverse-py",
        requirements: None,
        editable: false,
        lint: &["python", "tests", "bench", "../../examples/python"],
        typed: Some("python/vlnverse"),
        tests: "tests",
    },
    Suite {
        name: "export (LeRobot)",
        dir: "crates/vlnverse-export/python-tests",
        requirements: Some("requirements.txt"),
        editable: false,
        lint: &["."],
        typed: None,
        tests: ".",
    },
    Suite {
        name: "baselines",
        dir: "baselines",
        requirements: Some("requirements.txt"),
        editable: true,
        lint: &["."],
        typed: Some("vlnverse_baselines"),
        tests: "tests",
    },
    Suite {
        name: "hostile inputs",
        dir: "tests/hostile",
        requirements: None,
        editable: false,
        lint: &["."],
        typed: None,
        tests: ".",
    },
    Suite {
        name: "web (browser)",
        dir: "crates/vlnverse-web/browser-tests",
        requirements: Some("requirements.txt"),
        editable: false,
        lint: &["."],
        typed: None,
        tests: ".",
    },
];

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
    if !args.python_only {
        // The docs' tables on `tiny` (configs/results.toml, `ci = true`) as HEAD makes them.
        let exe = std::env::current_exe().context("locating the xtask binary")?;
        run(
            "cargo xtask results --check --ci (the docs' tiny tables)",
            Command::new(&exe)
                .current_dir(&root)
                .args(["results", "--check", "--ci"]),
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
    for suite in SUITES {
        if !root.join(suite.dir).exists() {
            continue;
        }
        if let Some(req) = suite.requirements {
            run(
                &format!("{}: python packages", suite.name),
                Command::new(&py)
                    .current_dir(root.join(suite.dir))
                    .args(["-m", "pip", "install", "-q", "-r", req]),
            )?;
        }
        if suite.editable {
            run(
                &format!("{}: editable install", suite.name),
                Command::new(&py)
                    .current_dir(&root)
                    .args([
                        "-m",
                        "pip",
                        "install",
                        "-q",
                        "--no-deps",
                        "--no-build-isolation",
                        "-e",
                    ])
                    .arg(suite.dir),
            )?;
        }
        run(
            &format!("{}: ruff (python lint)", suite.name),
            Command::new(venv.join("bin").join("ruff"))
                .current_dir(root.join(suite.dir))
                .arg("check")
                .args(suite.lint),
        )?;
        if let Some(typed) = suite.typed {
            run(
                &format!("{}: mypy (python types)", suite.name),
                Command::new(&py)
                    .current_dir(root.join(suite.dir))
                    .args(["-m", "mypy", typed]),
            )?;
        }
    }
    let mut pytest = Command::new(&py);
    pytest.current_dir(&root).args([
        "-m",
        "pytest",
        "-q",
        "-p",
        "no:cacheprovider",
        "--import-mode=importlib",
    ]);
    for suite in SUITES {
        if root.join(suite.dir).exists() {
            pytest.arg(root.join(suite.dir).join(suite.tests));
        }
    }
    run(
        "pytest",
        pytest
            .args(&args.pytest_args)
            .env("VLNVERSE_TEST_DATASET", &data)
            .env("VLNVERSE_XTASK", &exe),
    )?;
    Ok(())
}
