//! The README's gallery is the build's: `tools/gallery.sh` writes it with
//! docs/images/gallery.json, every named technique has a row and an image, the
//! README states the counts gallery.json holds, and those are the dispatches
//! and barriers per frame that `sweeplab render` records for the same command
//! now. Cheap: each render stops as soon as it has said its counts (a long
//! frame's first progress line, recorded at submission), so the reference at
//! 256x256 and IPSVI at 512x512 cost seconds, not minutes.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use sweeplab::techniques::Technique;

struct Row {
    technique: String,
    scene: String,
    size: String,
    dispatches: u64,
    barriers: u64,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn row(value: &serde_json::Value) -> Row {
    let text = |key: &str| value[key].as_str().unwrap_or_else(|| panic!("gallery.json: {key} in {value}")).to_string();
    let count = |key: &str| value[key].as_u64().unwrap_or_else(|| panic!("gallery.json: {key} in {value}"));
    Row {
        technique: text("technique"),
        scene: text("scene"),
        size: text("size"),
        dispatches: count("dispatches"),
        barriers: count("barriers"),
    }
}

/// The rows and the image at the top, as tools/gallery.sh recorded them.
fn gallery() -> (Vec<Row>, Row) {
    let path = root().join("docs/images/gallery.json");
    let text =
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e} (run tools/gallery.sh)", path.display()));
    let json: serde_json::Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let rows = json["rows"].as_array().expect("gallery.json: rows").iter().map(row).collect();
    (rows, row(&json["top"]))
}

/// The README's lines between the gallery table's markers.
fn readme_gallery() -> String {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let start = readme.find("<!-- gallery:table -->").expect("README.md: <!-- gallery:table --> marker");
    let end = readme.find("<!-- end gallery:table -->").expect("README.md: <!-- end gallery:table --> marker");
    readme[start..end].to_string()
}

/// What `sweeplab render` records for `row`'s command, stopped at its first
/// word of the frame's counts: the final line of a short render, or the
/// progress line a frame prints while it runs past two seconds (its counts
/// are those it was submitted with).
fn recorded_counts(row: &Row, out: &Path) -> (u64, u64) {
    let bin = env!("CARGO_BIN_EXE_sweeplab");
    let command = format!(
        "exec '{bin}' render --scene '{}' --technique {} --size {} --out '{}' 2>&1",
        root().join(&row.scene).display(),
        row.technique,
        row.size,
        out.display()
    );
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(&command)
        .env_remove("SWEEPLAB_VALIDATE")
        .stdout(Stdio::piped())
        .spawn()
        .expect("run sweeplab");
    let mut said = Vec::new();
    let mut counts = None;
    for line in BufReader::new(child.stdout.take().unwrap()).lines() {
        let line = line.unwrap();
        said.push(line.clone());
        let frame_line =
            line.starts_with(&format!("{}: ", row.technique)) || line.split(':').next().unwrap().ends_with("frame");
        if let (true, Some(open)) = (frame_line && line.ends_with(" barriers)"), line.rfind('(')) {
            let numbers: Vec<u64> =
                line[open + 1..].split(|c: char| !c.is_ascii_digit()).filter_map(|w| w.parse().ok()).collect();
            if numbers.len() == 2 {
                counts = Some((numbers[0], numbers[1]));
                break;
            }
        }
    }
    let _ = child.kill();
    let _ = child.wait();
    counts.unwrap_or_else(|| panic!("{command}: no counts said:\n{}", said.join("\n")))
}

#[test]
fn the_readme_gallery_states_what_the_build_records() {
    let (rows, top) = gallery();
    let readme = readme_gallery();
    let mut named: Vec<&str> = Technique::named().map(|t| t.name()).collect();
    let mut shown: Vec<&str> = rows.iter().map(|r| r.technique.as_str()).collect();
    named.sort();
    shown.sort();
    assert_eq!(shown, named, "the gallery shows every technique a user can name, once (tools/gallery.sh)");
    for r in &rows {
        let line = readme
            .lines()
            .find(|l| l.starts_with(&format!("| `{}`:", r.technique)))
            .unwrap_or_else(|| panic!("README.md: no gallery row for {}", r.technique));
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        assert!(
            cells[3].starts_with(&format!("{} / {}", r.dispatches, r.barriers)),
            "README.md's {} row says {:?}, gallery.json {} / {}: run tools/gallery.sh",
            r.technique,
            cells[3],
            r.dispatches,
            r.barriers
        );
        assert!(root().join(format!("docs/images/{}.png", r.technique)).is_file(), "docs/images/{}.png", r.technique);
    }
    let top_says = format!("({} dispatches, {} barriers)", top.dispatches, top.barriers);
    assert!(readme.contains(&top_says), "README.md's image at the top should say {top_says}: run tools/gallery.sh");

    let dir = crate::common::cli::temp_dir("readme-gallery");
    let mut stale = Vec::new();
    for r in rows.iter().chain([&top]) {
        let (dispatches, barriers) = recorded_counts(r, &dir.join(format!("{}.png", r.technique)));
        if (dispatches, barriers) != (r.dispatches, r.barriers) {
            stale.push(format!(
                "{} at {}: the README says {} / {}, the build records {dispatches} / {barriers}",
                r.technique, r.size, r.dispatches, r.barriers
            ));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(stale.is_empty(), "the gallery is stale; run tools/gallery.sh:\n{}", stale.join("\n"));
}
