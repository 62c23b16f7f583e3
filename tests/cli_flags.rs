//! Flags that mean one thing everywhere: no preset silently replaces a flag
//! given on the command line, the same flag names the same thing in every
//! subcommand (`--out` a file, `--out-dir` a folder, `--repeat` the timed
//! rounds, one default technique), a missing argument is named on the error's
//! first line, and the small messages say things once, in the right number.
//! All but the last test end before any GPU work.

use crate::common;

use common::cli::*;

/// The short help (`-h`: one line per flag).
fn help(args: &[&str]) -> String {
    let o = sweeplab(&[args, &["-h"]].concat());
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn quick_presets_never_replace_a_flag_given_on_the_command_line() {
    let out = temp_dir("quick-clash").join("out");
    // Refused without --quick, so refused with it: the given widths are used.
    let o = sweeplab(&["bench", "sync", "--quick", "--line-widths", "1,64", "--out-dir", out.to_str().unwrap()]);
    assert_user_error(&o, "line_width = 64");
    let err = stderr(&o);
    assert!(err.contains("--quick: 64x64") && err.contains("--line-widths given: used instead"), "{err}");
    assert!(!err.contains("device:") && !out.exists(), "{err}");
    // The size given two ways is an error, not a silent choice.
    let o = sweeplab(&["render", "--size", "8x8", "--set", "render.width=4"]);
    assert_user_error(&o, "--size 8x8 and --set render.width=4 both give the image size");
    // The breakdown does not run the grid: the grid's flags are refused with it.
    let o = sweeplab(&["bench", "ipsvi", "--breakdown", "--cache-sizes", "64"]);
    assert_user_error(&o, "'--breakdown' cannot be used with '--cache-sizes");
}

#[test]
fn render_compare_and_view_run_one_default_technique() {
    for command in ["render", "compare", "view"] {
        let text = help(&[command]);
        let line = text.lines().find(|l| l.trim_start().starts_with("--technique")).unwrap();
        assert!(line.ends_with("[default: ipsvi]"), "{command}: {line}");
    }
    assert_eq!(sweeplab::techniques::Technique::DEFAULT.name(), "ipsvi");
}

#[test]
fn out_is_a_file_out_dir_a_folder_and_every_bench_takes_repeat() {
    for command in ["render", "compare"] {
        let text = help(&[command]);
        assert!(text.contains("--out <FILE>") && !text.contains("--out-dir"), "{command}: {text}");
    }
    for bench in ["ipsvi", "sync", "table1", "lights", "stability", "ao"] {
        let text = help(&["bench", bench]);
        for flag in ["--out-dir <DIR>", "--force", "--repeat <REPEAT>"] {
            assert!(text.contains(flag), "bench {bench} lacks {flag}: {text}");
        }
        assert!(!text.contains("--out <"), "bench {bench}: {text}");
    }
    assert!(help(&["report"]).contains("--out-dir <DIR>"));
    // The old folder flag of the benches points to the new one.
    let o = sweeplab(&["bench", "sync", "--out", "x"]);
    assert_user_error(&o, "a similar argument exists: '--out-dir'");
    // --force only with a folder named.
    assert_user_error(&sweeplab(&["bench", "sync", "--force"]), "missing --out-dir");
}

#[test]
fn a_missing_argument_is_named_on_the_first_line() {
    let o = sweeplab(&["report"]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert_eq!(err.lines().next(), Some("error: missing <INPUTS>..."), "{err}");
    assert!(err.contains("Usage: sweeplab report"), "{err}");
}

#[test]
fn a_volume_that_does_not_load_is_named_once() {
    let dir = temp_dir("volume-once");
    let truncated = dir.join("trunc.vti");
    std::fs::write(&truncated, b"<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1").unwrap();
    let o = sweeplab(&["render", "--volume", truncated.to_str().unwrap()]);
    assert_user_error(&o, "cannot load");
    let err = stderr(&o);
    assert_eq!(err.matches("trunc.vti").count(), 1, "{err}");
}

#[test]
fn counts_read_in_the_right_number_and_every_output_is_named() {
    let dir = temp_dir("plurals");
    let (png, json) = (dir.join("dvr.png"), dir.join("p.json"));
    let (png, json) = (png.to_str().unwrap(), json.to_str().unwrap());
    let o = sweeplab(&["render", "--technique", "dvr", "--size", "8x8", "--out", png, "--profile-json", json]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains(&format!("dvr: 8x8 -> {png} (1 dispatch, ")), "{out}");
    assert!(out.contains(&format!("wrote {json}")), "{out}");
    let heat = dir.join("h.png");
    let o = sweeplab(&["compare", "--technique", "dvr", "--size", "8x8", "--heatmap", heat.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains(&format!("wrote {}", heat.display())));
}

#[test]
fn keys_prints_the_declared_reference_of_one_table_or_all() {
    let o = sweeplab(&["keys"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let all = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(all, sweeplab::techniques::CATALOGUE.documented_tables());
    for table in ["[ipsvi]", "[half_angle]", "[lightvolume]", "[ao]"] {
        assert!(all.contains(table), "{table} missing: {all}");
    }
    let o = sweeplab(&["keys", "ipsvi"]);
    let one = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(one.starts_with("[ipsvi]\nline_width = 1 ") && !one.contains("[ao]"), "{one}");
    assert!(one.contains("# lines per dispatch (and per barrier); 1..=32\n"), "{one}");
    let o = sweeplab(&["keys", "ipsv"]);
    assert_user_error(&o, "no technique table [ipsv] (did you mean ipsvi?)");
}
