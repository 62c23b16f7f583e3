//! The layering rule of the library (README, "Layout"): each folder imports
//! only the layers below it. A folder that names a layer above it (in code,
//! tests included; comments do not count) fails here with the line.

use std::fs;
use std::path::Path;

/// The technique folders (`src/techniques/<name>/`): every folder there, so a
/// new technique is checked without being listed here.
fn techniques() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/techniques");
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The layers above the techniques: the catalogue (`src/techniques/*.rs`) and
/// the front ends.
const FRONT_ENDS: [&str; 4] = ["techniques", "bench", "viewer", "cli"];

/// The `crate::` modules each `src/` line of `dir` names, outside comments.
fn imports(dir: &Path) -> Vec<(String, String)> {
    let technique_names = techniques();
    let mut found = Vec::new();
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            found.extend(imports(&path));
            continue;
        }
        let text = fs::read_to_string(&path).unwrap();
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap();
            for (i, _) in code.match_indices("crate::") {
                let segment = |at: usize| -> String {
                    code[at..].chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect()
                };
                let mut module = segment(i + 7);
                // `crate::techniques::ipsvi` is the technique, `crate::techniques::registry` the catalogue.
                if module == "techniques" && code[i + 7 + module.len()..].starts_with("::") {
                    let next = segment(i + 7 + module.len() + 2);
                    if technique_names.contains(&next) {
                        module = next;
                    }
                }
                found.push((module, format!("{}:{}: {}", path.display(), n + 1, line.trim())));
            }
        }
    }
    found
}

fn assert_not_above(layer: &str, above: &[String]) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join(layer);
    let bad: Vec<String> = imports(&dir).into_iter().filter(|(m, _)| above.contains(m)).map(|(_, at)| at).collect();
    assert!(bad.is_empty(), "src/{layer} imports a layer above it:\n{}", bad.join("\n"));
}

/// `names`, then every technique and the reference, then the front ends.
fn above(names: &[&str], techniques_too: bool) -> Vec<String> {
    let mut above: Vec<String> = names.iter().map(|n| n.to_string()).collect();
    if techniques_too {
        above.extend(techniques());
        above.push("reference".into());
    }
    above.extend(FRONT_ENDS.map(String::from));
    above
}

#[test]
fn vk_knows_nothing_above_it() {
    assert_not_above("vk", &above(&["scene", "render"], true));
}

#[test]
fn scene_knows_no_technique_and_no_gpu() {
    assert_not_above("scene", &above(&["vk", "render"], true));
}

#[test]
fn render_knows_no_technique() {
    assert_not_above("render", &above(&[], true));
}

/// A technique builds on `vk`, `scene` and `render`: no other technique, not
/// the catalogue, no front end.
#[test]
fn techniques_know_no_other_technique_no_front_end_and_not_the_catalogue() {
    let all = techniques();
    assert!(all.len() >= 5, "the technique folders: {all:?}");
    for technique in &all {
        let others: Vec<&str> = all.iter().filter(|t| *t != technique).map(String::as_str).collect();
        assert_not_above(&format!("techniques/{technique}"), &above(&others, false));
    }
}

/// The ground truth stands apart from what it checks: shared march code comes
/// from `render`, so neither side needs the other.
#[test]
fn the_reference_and_the_techniques_do_not_import_each_other() {
    assert_not_above("reference", &techniques());
    for technique in techniques() {
        assert_not_above(&format!("techniques/{technique}"), &["reference".to_string()]);
    }
}

#[test]
fn the_check_sees_an_import() {
    // The scanner itself: it finds the catalogue's imports of the techniques,
    // and names them by technique.
    let main = imports(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src/techniques"));
    assert!(main.iter().any(|(m, _)| m == "ipsvi"), "the catalogue lists ipsvi");
}
