//! What an export writes: the same bytes on 1 and 2 threads, after a resume, and clear refusals.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::record::RowAccessor;
use vlnverse_export::{export, ExportError, ExportRequest};
use vlnverse_task::{Split, Task};

use super::support::tiny;

fn request(out: &Path, threads: usize) -> ExportRequest {
    let mut req = ExportRequest::new(tiny(), Task::Fine, Split::ValUnseen, out);
    req.episodes = Some(3);
    req.threads = Some(threads);
    req
}

/// Every file under `dir` (relative path -> bytes), the lock and temporaries left out.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else if !p.ends_with(".lock") {
                out.insert(
                    p.strip_prefix(root).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

#[test]
fn same_bytes_on_any_thread_count_and_after_a_resume() {
    let tmp = tempfile::tempdir().unwrap();
    let (one, two) = (tmp.path().join("one"), tmp.path().join("two"));
    let a = export(&request(&one, 1), &|_| {}).unwrap();
    let b = export(&request(&two, 2), &|_| {}).unwrap();
    assert_eq!((a.episodes, a.frames), (b.episodes, b.frames));
    assert_eq!(a.episodes, 3);
    let fa = files(&one);
    assert!(fa.keys().any(|k| k.ends_with("meta/info.json")));
    assert_eq!(
        fa.keys().filter(|k| k.starts_with("data")).count(),
        3,
        "{:?}",
        fa.keys()
    );
    assert_eq!(fa, files(&two), "1 and 2 threads wrote different bytes");

    // Interrupted: one episode's data file gone (its summary kept), another never summarised,
    // the metadata not yet written.
    std::fs::remove_file(one.join("data/chunk-000/file-001.parquet")).unwrap();
    std::fs::remove_file(one.join(".parts/episode-000002.json")).unwrap();
    std::fs::remove_dir_all(one.join("meta")).unwrap();
    let r = export(&request(&one, 2), &|_| {}).unwrap();
    assert_eq!(r.resumed, 1, "only episode 0 was complete");
    assert_eq!(r.frames, a.frames);
    assert_eq!(
        r.rendered_frames as usize,
        r.frames - first_episode_len(&one),
        "episodes 1 and 2 were rendered again, episode 0 was not"
    );
    assert_eq!(
        files(&one),
        fa,
        "a resumed export differs from an uninterrupted one"
    );
}

fn first_episode_len(root: &Path) -> usize {
    let text = std::fs::read_to_string(root.join("meta/vlnverse_episodes.jsonl")).unwrap();
    let first: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    first["length"].as_u64().unwrap() as usize
}

#[test]
fn data_files_hold_the_teacher_labels() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ds");
    let s = export(&request(&out, 2), &|_| {}).unwrap();
    let mut index = 0i64;
    for e in 0..s.episodes {
        let path = out.join(format!("data/chunk-000/file-{e:03}.parquet"));
        let reader = SerializedFileReader::new(std::fs::File::open(&path).unwrap()).unwrap();
        let rows: Vec<_> = reader
            .get_row_iter(None)
            .unwrap()
            .map(|r| r.unwrap())
            .collect();
        assert!(rows.len() >= 2);
        let col = |name: &str| {
            let schema = reader.metadata().file_metadata().schema_descr();
            (0..schema.root_schema().get_fields().len())
                .find(|&i| schema.root_schema().get_fields()[i].name() == name)
                .unwrap()
        };
        let (action, frame, idx) = (col("action"), col("frame_index"), col("index"));
        for (t, row) in rows.iter().enumerate() {
            let a = row.get_long(action).unwrap();
            if t + 1 == rows.len() {
                assert_eq!(a, 0, "episode {e}: the last action is STOP");
            } else {
                assert!((1..=3).contains(&a), "episode {e} frame {t}: action {a}");
            }
            assert_eq!(row.get_long(frame).unwrap(), t as i64);
            assert_eq!(row.get_long(idx).unwrap(), index);
            index += 1;
        }
    }
    assert_eq!(index as usize, s.frames);
}

#[test]
fn refuses_bad_requests_with_clear_errors() {
    let tmp = tempfile::tempdir().unwrap();
    // A split the dataset does not have.
    let mut req = request(&tmp.path().join("a"), 1);
    req.task = Task::Coarse;
    let e = export(&req, &|_| {}).unwrap_err().to_string();
    assert!(e.contains("coarse") && e.contains("does not exist"), "{e}");
    // No dataset.
    let mut req = request(&tmp.path().join("b"), 1);
    req.dataset = tmp.path().join("nowhere");
    let e = export(&req, &|_| {}).unwrap_err().to_string();
    assert!(e.contains("nowhere"), "{e}");
    // A folder holding something else.
    let foreign = tmp.path().join("c");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    let e = export(&request(&foreign, 1), &|_| {}).unwrap_err();
    assert!(matches!(e, ExportError::Output { .. }), "{e}");
    assert!(foreign.join("notes.txt").is_file());
    // The refused folder is left as it was: no lock file, no parts folder.
    let left: Vec<_> = std::fs::read_dir(&foreign)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, vec![std::ffi::OsString::from("notes.txt")]);
    // Zero episodes.
    let mut req = request(&tmp.path().join("d"), 1);
    req.episodes = Some(0);
    assert!(export(&req, &|_| {})
        .unwrap_err()
        .to_string()
        .contains("episodes"));
}

#[test]
fn another_request_into_the_same_folder_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ds");
    let mut req = request(&out, 2);
    req.episodes = Some(1);
    export(&req, &|_| {}).unwrap();
    req.seed = 7;
    let e = export(&req, &|_| {}).unwrap_err().to_string();
    assert!(e.contains("another request"), "{e}");
}

#[test]
fn the_panorama_starts_with_the_rgb_view() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ds");
    let mut req = request(&out, 2);
    req.episodes = Some(1);
    req.panorama = true;
    export(&req, &|_| {}).unwrap();
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("meta/info.json")).unwrap()).unwrap();
    let pano = &info["features"]["observation.images.pano"];
    assert_eq!(pano["dtype"], "image");
    assert_eq!(pano["shape"], serde_json::json!([224, 224 * 12, 3]));
    let file = std::fs::File::open(out.join("data/chunk-000/file-000.parquet")).unwrap();
    let reader = SerializedFileReader::new(file).unwrap();
    let fields = reader
        .metadata()
        .file_metadata()
        .schema_descr()
        .root_schema()
        .get_fields()
        .to_vec();
    let at = |name: &str| fields.iter().position(|f| f.name() == name).unwrap();
    let (rgb, pano) = (at("observation.images.rgb"), at("observation.images.pano"));
    let decode = |bytes: &[u8]| image::load_from_memory(bytes).unwrap().to_rgb8();
    for row in reader.get_row_iter(None).unwrap().take(3) {
        let row = row.unwrap();
        let front = decode(row.get_group(rgb).unwrap().get_bytes(0).unwrap().data());
        let all = decode(row.get_group(pano).unwrap().get_bytes(0).unwrap().data());
        assert_eq!((all.width(), all.height()), (224 * 12, 224));
        let view0 = image::imageops::crop_imm(&all, 0, 0, 224, 224).to_image();
        assert_eq!(view0, front, "panorama view 0 is the RGB camera's view");
        let view3 = image::imageops::crop_imm(&all, 3 * 224, 0, 224, 224).to_image();
        assert_ne!(view3, front, "view 3 looks 90 degrees to the left");
    }
}
