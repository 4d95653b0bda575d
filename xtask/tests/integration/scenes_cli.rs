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

    // topdown writes a PNG.
    let png = tmp.path().join("td.png");
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
