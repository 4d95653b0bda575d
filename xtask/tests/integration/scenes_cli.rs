//! End to end: `cargo xtask scenes --preset tiny` on 1 and 2 threads, resume, `scene-info` and
//! `topdown`, through the real binary.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

fn xtask(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .env("RUST_LOG", "warn")
        .output()
        .expect("run xtask");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Relative path -> bytes of every file under `dir`.
fn tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fn walk(root: &Path, d: &Path, out: &mut BTreeMap<String, Vec<u8>>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let rel = p.strip_prefix(root).unwrap().to_string_lossy().into_owned();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    let mut m = BTreeMap::new();
    walk(dir, dir, &mut m);
    m
}

#[test]
fn tiny_preset_end_to_end_same_bytes_on_1_and_2_threads_and_resumes() {
    let tmp = tempfile::tempdir().unwrap();
    let a = tmp.path().join("a");
    let b = tmp.path().join("b");
    let (ok, stdout, stderr) = xtask(&[
        "scenes",
        "--preset",
        "tiny",
        "--threads",
        "1",
        "--out",
        a.to_str().unwrap(),
    ]);
    assert!(ok, "{stdout}{stderr}");
    assert!(stdout.contains("0 complete skipped"), "{stdout}");
    let (ok, _, stderr) = xtask(&[
        "scenes",
        "--preset",
        "tiny",
        "--threads",
        "2",
        "--out",
        b.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");

    let ta = tree(&a);
    let tb = tree(&b);
    assert_eq!(ta.keys().collect::<Vec<_>>(), tb.keys().collect::<Vec<_>>());
    for (k, v) in &ta {
        assert!(v == &tb[k], "{k} differs between 1 and 2 threads");
    }
    // Every scene folder is complete, loads, and has every file; no temp folders are left.
    let scenes: Vec<_> = std::fs::read_dir(&a)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(
        scenes.len() >= 2,
        "tiny preset gave {} scenes",
        scenes.len()
    );
    for s in &scenes {
        let name = s.file_name().unwrap().to_string_lossy().into_owned();
        assert!(!name.starts_with('.'), "temp folder left: {name}");
        assert!(vlnverse_env::io::is_complete_scene_dir(s), "{name}");
        let scene = vlnverse_env::io::load_scene(s).unwrap();
        assert_eq!(scene.id, name);
        assert!(scene.items().count() > 0);
        let nav = vlnverse_env::occupancy::GridMap::load_ros(s.join("navigable.yaml")).unwrap();
        assert!(
            nav.free_area_m2() > 5.0,
            "{name}: navigable {}",
            nav.free_area_m2()
        );
    }

    // Resume: nothing to do; a damaged scene is rewritten to the same bytes.
    let victim = &scenes[0];
    std::fs::remove_file(victim.join("navigable.pgm")).unwrap();
    std::fs::write(victim.join("scene.json"), b"{ broken").unwrap();
    let (ok, stdout, stderr) = xtask(&[
        "scenes",
        "--preset",
        "tiny",
        "--threads",
        "2",
        "--out",
        a.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    assert!(
        stdout.contains(&format!("1 written, {} complete skipped", scenes.len() - 1)),
        "{stdout}"
    );
    assert_eq!(tree(&a), ta);

    // scene-info on the folder of scenes and on one scene.
    let (ok, stdout, stderr) = xtask(&["scene-info", a.to_str().unwrap()]);
    assert!(ok, "{stderr}");
    assert!(
        stdout.contains(&format!("{} scenes", scenes.len())),
        "{stdout}"
    );
    assert!(
        stdout.contains("navigable")
            && stdout.contains("object class")
            && stdout.contains("room type"),
        "{stdout}"
    );
    let (ok, stdout, _) = xtask(&["scene-info", victim.to_str().unwrap()]);
    assert!(ok && stdout.contains("1 scenes"), "{stdout}");

    // topdown writes a PNG, making its folder (as README's `--out runs/home.png` needs).
    let png = tmp.path().join("pictures/td.png");
    let (ok, _, stderr) = xtask(&[
        "topdown",
        "--scene",
        victim.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    let img = image::open(&png).unwrap();
    assert!(img.width() > 200 && img.height() > 200);
}

#[test]
fn bad_input_fails_with_a_message_naming_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let (ok, _, stderr) = xtask(&["scene-info", tmp.path().join("nope").to_str().unwrap()]);
    assert!(!ok && stderr.contains("nope"), "{stderr}");
    let scene = tmp.path().join("s");
    std::fs::create_dir_all(&scene).unwrap();
    std::fs::write(
        scene.join("scene.json"),
        b"{\"format_version\": 1, \"id\": 3}",
    )
    .unwrap();
    let (ok, _, stderr) = xtask(&[
        "topdown",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        tmp.path().join("x.png").to_str().unwrap(),
    ]);
    assert!(!ok && stderr.contains("scene.json"), "{stderr}");
    let cfg = tmp.path().join("bad.toml");
    std::fs::write(&cfg, "[rooms]\nmin_count = -1\n").unwrap();
    let (ok, _, stderr) = xtask(&[
        "scenes",
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        tmp.path().join("o").to_str().unwrap(),
    ]);
    assert!(!ok && stderr.contains("bad.toml"), "{stderr}");
}

/// The imported Godot living room (one piece of furniture) among the tiny homes: it is skipped
/// for long-horizon episodes with one warning, the run succeeds, and the report records it.
#[test]
fn generate_skips_a_scene_that_cannot_provide_a_task_and_says_why() {
    let glb = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/scenes/godot_living_room/living_room.glb"
    ));
    if !glb.is_file() {
        eprintln!("skipped: {} is absent", glb.display());
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let scenes = tmp.path().join("scenes");
    let s = scenes.to_str().unwrap();
    let (ok, _, stderr) = xtask(&["scenes", "--preset", "tiny", "--out", s]);
    assert!(ok, "{stderr}");
    let (ok, _, stderr) = xtask(&["import", "--input", glb.to_str().unwrap(), "--out", s]);
    assert!(ok, "{stderr}");
    let ds = tmp.path().join("ds");
    let (ok, stdout, stderr) = xtask(&[
        "generate",
        "--scenes-from",
        s,
        "--out",
        ds.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    let warnings: Vec<&str> = stderr.lines().filter(|l| l.contains("warning")).collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(
        warnings[0].contains("living_room: long_horizon needs 2 distinct targets, found 1"),
        "{stderr}"
    );
    assert!(stdout.contains("1 scene/task pair skipped"), "{stdout}");
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(ds.join("generation_report.json")).unwrap()).unwrap();
    assert_eq!(report["skipped"][0]["scene_id"], "living_room");
    assert_eq!(report["skipped"][0]["task"], "long_horizon");
    let (ok, stdout, stderr) = xtask(&["stats", ds.to_str().unwrap()]);
    assert!(ok && stdout.contains("| long_horizon |"), "{stderr}");
}

#[test]
fn shard_counts_from_zero_and_help_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let (ok, _, stderr) = xtask(&[
        "generate",
        "--shard",
        "2/2",
        "--out",
        tmp.path().join("o").to_str().unwrap(),
    ]);
    assert!(!ok, "{stderr}");
    assert!(
        stderr.contains("--shard 2/2: K counts from 0, so use 0/2 and 1/2"),
        "{stderr}"
    );
    assert!(!tmp.path().join("o").exists());
    let (ok, stdout, _) = xtask(&["generate", "--help"]);
    assert!(ok && stdout.contains("K counts from 0"), "{stdout}");
}

#[test]
fn merge_with_a_missing_or_repeated_shard_names_it_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let p0 = tmp.path().join("p0");
    let (ok, _, stderr) = xtask(&[
        "generate",
        "--preset",
        "tiny",
        "--tasks",
        "fine",
        "--shard",
        "0/2",
        "--out",
        p0.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    let m2 = tmp.path().join("m2");
    let (ok, _, stderr) = xtask(&["merge", "--out", m2.to_str().unwrap(), p0.to_str().unwrap()]);
    assert!(!ok, "{stderr}");
    assert!(
        stderr.contains("shard 1/2 is missing (parts for scenes tiny_0001, tiny_0003"),
        "{stderr}"
    );
    assert!(!m2.exists(), "a failed merge left {}", m2.display());
    let p = p0.to_str().unwrap();
    let (ok, _, stderr) = xtask(&["merge", "--out", m2.to_str().unwrap(), p, p]);
    assert!(
        !ok && stderr.contains("shard 0/2 is given twice"),
        "{stderr}"
    );
    assert!(!m2.exists());
    // A shard alone is not a dataset: stats says there are no episodes.
    let (ok, _, stderr) = xtask(&["stats", p]);
    assert!(!ok && stderr.contains("holds no episodes"), "{stderr}");
    assert!(stderr.contains("merge"), "{stderr}");
}

#[test]
fn generate_config_errors_name_the_config_file() {
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../configs/generate/tiny.toml"
    ))
    .unwrap();
    // 13 scenes in the splits, but the tiny scene preset makes 5.
    let cfg = tmp.path().join("my_gen.toml");
    std::fs::write(&cfg, text.replace("train = 3\n", "train = 11\n")).unwrap();
    let (ok, _, stderr) = xtask(&[
        "generate",
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        tmp.path().join("o").to_str().unwrap(),
    ]);
    assert!(!ok, "{stderr}");
    assert!(
        stderr.contains("my_gen.toml") && stderr.contains("splits") && stderr.contains("13"),
        "{stderr}"
    );
    // An empty folder has no episodes either.
    let empty = tmp.path().join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let (ok, _, stderr) = xtask(&["stats", empty.to_str().unwrap()]);
    assert!(!ok && stderr.contains("holds no episodes"), "{stderr}");
}
