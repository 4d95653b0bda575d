//! The layers build alone: the scoring crate pulls no physics or graphics, every library crate
//! packages (its default configs are inside it), and the sensor and task crates build without
//! their optional backends.

use std::path::Path;
use std::process::Command;

const LIBRARIES: [&str; 7] = [
    "vlnverse-env",
    "vlnverse-score",
    "vlnverse-sim",
    "vlnverse-sensors",
    "vlnverse-procgen",
    "vlnverse-import",
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

#[test]
fn the_scoring_crate_has_no_physics_or_graphics_dependency() {
    let d = deps(&["-p", "vlnverse-score"]);
    assert!(d.contains(&"serde_json".to_string()), "{d:?}");
    for heavy in [
        "rapier3d",
        "parry3d",
        "wgpu",
        "vlnverse-sim",
        "vlnverse-sensors",
    ] {
        assert!(
            !d.iter().any(|x| x == heavy),
            "vlnverse-score depends on {heavy}"
        );
    }
}

#[test]
fn optional_backends_stay_out_without_their_features() {
    let sensors = deps(&["-p", "vlnverse-sensors", "--no-default-features"]);
    assert!(!sensors.iter().any(|x| x == "wgpu"), "{sensors:?}");
    let task = deps(&["-p", "vlnverse-task", "--no-default-features"]);
    for opt in ["wgpu", "ureq"] {
        assert!(!task.iter().any(|x| x == opt), "vlnverse-task pulls {opt}");
    }
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
