//! The layering rule of the library (README, "Layout"): each folder imports
//! only the layers below it. A folder that names a layer above it (in code,
//! tests included; comments do not count) fails here with the line.

use std::fs;
use std::path::Path;

/// The modules a technique folder builds on; what is not listed is above it.
const TECHNIQUES: [&str; 6] = ["dvr", "ipsvi", "lightvolume", "half_angle", "ao", "reference"];
const FRONT_ENDS: [&str; 4] = ["techniques", "bench", "viewer", "cli"];

/// The `crate::` modules each `src/` line of `dir` names, outside comments.
fn imports(dir: &Path) -> Vec<(String, String)> {
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
                let module: String =
                    code[i + 7..].chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
                found.push((module, format!("{}:{}: {}", path.display(), n + 1, line.trim())));
            }
        }
    }
    found
}

fn assert_not_above(layer: &str, above: &[&str]) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join(layer);
    let bad: Vec<String> =
        imports(&dir).into_iter().filter(|(m, _)| above.contains(&m.as_str())).map(|(_, at)| at).collect();
    assert!(bad.is_empty(), "src/{layer} imports a layer above it:\n{}", bad.join("\n"));
}

#[test]
fn vk_knows_nothing_above_it() {
    let above: Vec<&str> = ["scene", "render"].into_iter().chain(TECHNIQUES).chain(FRONT_ENDS).collect();
    assert_not_above("vk", &above);
}

#[test]
fn scene_knows_no_technique_and_no_gpu() {
    let above: Vec<&str> = ["vk", "render"].into_iter().chain(TECHNIQUES).chain(FRONT_ENDS).collect();
    assert_not_above("scene", &above);
}

#[test]
fn render_knows_no_technique() {
    let above: Vec<&str> = TECHNIQUES.into_iter().chain(FRONT_ENDS).collect();
    assert_not_above("render", &above);
}

#[test]
fn techniques_know_no_front_end_and_not_the_catalogue() {
    for technique in TECHNIQUES {
        assert_not_above(technique, &FRONT_ENDS);
    }
}

#[test]
fn the_check_sees_an_import() {
    // The scanner itself: it finds the catalogue's imports of the techniques.
    let main = imports(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join("techniques"));
    assert!(main.iter().any(|(m, _)| m == "ipsvi"), "the catalogue lists ipsvi");
}
