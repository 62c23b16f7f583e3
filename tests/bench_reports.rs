//! Benchmark reports: CSV/JSON/Markdown tables, the Pareto front over a table,
//! PNG charts and the progress line.

use std::path::PathBuf;

use sweeplab::bench::{
    plot_error_vs_time, plot_lines, render_error_vs_time, render_lines, AxisScale, BenchError, BenchRow, BenchTable,
    BenchValue, Chart, Progress, Series,
};

/// A fresh directory per test under cargo's scratch space for integration tests.
fn scratch_dir(test: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench_reports").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

/// Three runs with different key sets, awkward strings and every value kind.
fn sample_table() -> BenchTable {
    let mut table = BenchTable::new();
    let mut first = BenchRow::new();
    first.set("strategy", "slices").set("line_width", 4).set("gpu_ms", 12.5).set("error", 0.0125).set("valid", true);
    table.push(first);
    table.push(
        BenchRow::new()
            .with("strategy", "cache, big")
            .with("line_width", 8)
            .with("gpu_ms", 3.25)
            .with("note", "said \"fast\"\nthen slow"),
    );
    table.push(BenchRow::new().with("gpu_ms", 0.1).with("strategy", "").with("cache_kib", 256_u32).with("error", 1e-7));
    table
}

/// RFC 4180 parsing, written here independently of the writer under test.
fn parse_csv(text: &str) -> Vec<Vec<String>> {
    let mut records = Vec::new();
    let mut record = Vec::new();
    let mut field = String::new();
    let mut chars = text.chars().peekable();
    let mut in_quotes = false;
    while let Some(c) = chars.next() {
        match (in_quotes, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            (true, '"') => in_quotes = false,
            (true, c) => field.push(c),
            (false, '"') => in_quotes = true,
            (false, ',') => record.push(std::mem::take(&mut field)),
            (false, '\n') => {
                record.push(std::mem::take(&mut field));
                records.push(std::mem::take(&mut record));
            }
            (false, c) => field.push(c),
        }
    }
    assert!(!in_quotes, "unterminated quote");
    assert!(field.is_empty() && record.is_empty(), "last line lacks a newline");
    records
}

#[test]
fn csv_has_the_union_of_keys_in_the_rows_order_and_round_trips() {
    let dir = scratch_dir("csv");
    let path = dir.join("runs.csv");
    sample_table().write_csv(&path).expect("write csv");
    let records = parse_csv(&std::fs::read_to_string(&path).expect("read csv"));

    // The first row's keys, then each new key after the one before it in its row.
    let header = ["strategy", "cache_kib", "line_width", "gpu_ms", "note", "error", "valid"];
    assert_eq!(records[0], header);
    assert_eq!(records.len(), 4);
    assert!(records.iter().all(|r| r.len() == header.len()));

    assert_eq!(records[1], ["slices", "", "4", "12.5", "", "0.0125", "true"]);
    assert_eq!(records[2], ["cache, big", "", "8", "3.25", "said \"fast\"\nthen slow", "", ""]);
    assert_eq!(records[3][0], "");
    assert_eq!(records[3][1], "256");
    assert_eq!(records[3][3].parse::<f64>(), Ok(0.1));
    assert_eq!(records[3][5].parse::<f64>(), Ok(1e-7));
}

#[test]
fn csv_quotes_only_fields_that_need_it() {
    let mut table = BenchTable::new();
    table.push(BenchRow::new().with("plain", "abc").with("comma", "a,b").with("quote", "x\"y"));
    let text = table.to_csv();
    assert_eq!(text, "plain,comma,quote\nabc,\"a,b\",\"x\"\"y\"\n");
}

#[test]
fn json_is_an_array_of_objects_that_reads_back_in_order() {
    let dir = scratch_dir("json");
    let path = dir.join("runs.json");
    let table = sample_table();
    table.write_json(&path).expect("write json");
    let text = std::fs::read_to_string(&path).expect("read json");

    // Independently of our reader: plain serde_json sees the values.
    let value: serde_json::Value = serde_json::from_str(&text).expect("valid json");
    let rows = value.as_array().expect("an array");
    assert_eq!(rows.len(), 3);
    assert_eq!(rows[0]["line_width"], 4);
    assert_eq!(rows[0]["gpu_ms"], 12.5);
    assert_eq!(rows[0]["valid"], true);
    assert_eq!(rows[1]["note"], "said \"fast\"\nthen slow");
    assert!(rows[1].get("error").is_none(), "missing values stay missing");

    // Key order in the file follows the order the keys were set.
    let positions: Vec<usize> = ["\"gpu_ms\"", "\"strategy\"", "\"cache_kib\"", "\"error\""]
        .iter()
        .map(|key| text.rfind(key).expect("key present"))
        .collect();
    assert!(positions.windows(2).all(|w| w[0] < w[1]), "{positions:?}");

    let back = BenchTable::read_json(&path).expect("read back");
    assert_eq!(back, table);
    let keys: Vec<&str> = back.rows[2].keys().collect();
    assert_eq!(keys, ["gpu_ms", "strategy", "cache_kib", "error"]);
}

#[test]
fn non_finite_floats_are_json_null_and_read_back_as_nan() {
    let dir = scratch_dir("json_nan");
    let path = dir.join("nan.json");
    let mut table = BenchTable::new();
    table.push(BenchRow::new().with("error", f64::NAN).with("n", 1));
    table.write_json(&path).expect("write json");
    let value: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).expect("read")).expect("json");
    assert!(value[0]["error"].is_null());
    let back = BenchTable::read_json(&path).expect("read back");
    assert!(back.rows[0].get_f64("error").is_some_and(f64::is_nan));
    assert_eq!(back.rows[0].get("n"), Some(&BenchValue::Int(1)));
}

#[test]
fn file_errors_name_the_file() {
    let dir = scratch_dir("errors");
    // A missing folder is created (a bench's folder comes with its first file);
    // a file in the way of the folder is an error naming the file.
    let in_new_folder = dir.join("new_folder").join("runs.csv");
    sample_table().write_csv(&in_new_folder).expect("the folder is created");
    let blocker = dir.join("a_file");
    std::fs::write(&blocker, "x").expect("write");
    let missing_dir = blocker.join("runs.csv");
    let err = sample_table().write_csv(&missing_dir).unwrap_err();
    assert!(matches!(err, BenchError::Write { .. }));
    assert!(err.to_string().contains("runs.csv"), "{err}");

    let bad = dir.join("bad.json");
    std::fs::write(&bad, "{\"not\": \"an array\"}").expect("write");
    let err = BenchTable::read_json(&bad).unwrap_err();
    assert!(matches!(err, BenchError::Json { .. }));
    assert!(err.to_string().contains("bad.json"), "{err}");

    let nested = dir.join("nested.json");
    std::fs::write(&nested, "[{\"a\": [1, 2]}]").expect("write");
    assert!(matches!(BenchTable::read_json(&nested), Err(BenchError::Json { .. })));

    let err = plot_lines(dir.join("no_such_dir/plot.png"), &Chart::new("t", "x", "y"), &[]).unwrap_err();
    assert!(err.to_string().contains("plot.png"), "{err}");
}

#[test]
fn markdown_is_a_rectangular_table_with_readable_numbers() {
    let mut table = sample_table();
    table.rows[0].set("gpu_ms", 12.34567);
    table.rows[1].set("strategy", "a|b");
    let markdown = table.to_markdown();
    let lines: Vec<&str> = markdown.lines().collect();
    assert_eq!(lines.len(), 2 + 3, "header, rule and one line per row");

    // Every line has the same cells (escaped pipes do not count) and width.
    let cells = |line: &str| line.replace("\\|", "").matches('|').count();
    assert!(lines.iter().all(|l| l.starts_with("| ") && l.ends_with(" |")));
    assert!(lines.iter().all(|l| cells(l) == 7 + 1), "{markdown}");
    let width = lines[0].chars().count();
    assert!(lines.iter().all(|l| l.chars().count() == width), "{markdown}");

    let rule: Vec<&str> = lines[1].trim_matches('|').split('|').map(str::trim).collect();
    assert!(rule[0].starts_with(':'), "text column left-aligned: {}", lines[1]);
    assert!(rule[2].ends_with(':'), "number column right-aligned: {}", lines[1]);
    assert!(lines[2].contains(" 12.35 |"), "{}", lines[2]);
    assert!(lines[4].contains("1e-7"), "{}", lines[4]);
    assert!(lines[3].contains("a\\|b"), "{}", lines[3]);
}

#[test]
fn pareto_flags_mark_rows_no_other_row_beats() {
    let mut table = BenchTable::new();
    for (time, error) in [(5.0, 0.1), (1.0, 0.4), (6.0, 0.2), (2.0, 0.4)] {
        table.push(BenchRow::new().with("gpu_ms", time).with("error", error));
    }
    table.push(BenchRow::new().with("gpu_ms", 0.5)); // no error measured
    let front = table.mark_pareto_front("gpu_ms", "error", "pareto");
    assert_eq!(front, vec![1, 0]);
    let flags: Vec<Option<&BenchValue>> = table.rows.iter().map(|r| r.get("pareto")).collect();
    let t = Some(&BenchValue::Bool(true));
    let f = Some(&BenchValue::Bool(false));
    assert_eq!(flags, vec![t, t, f, f, f]);
}

const RED: [u8; 3] = [220, 30, 30];
const GREEN: [u8; 3] = [30, 160, 60];
const BLUE: [u8; 3] = [40, 70, 220];

fn count_color(image: &image::RgbImage, color: [u8; 3]) -> usize {
    image.pixels().filter(|p| p.0 == color).count()
}

fn three_strategies() -> Vec<Series> {
    vec![
        Series::new("slices", vec![(12.0, 0.01), (6.0, 0.03), (3.0, 0.08)]).with_color(RED),
        Series::new("cache", vec![(5.0, 0.02), (2.5, 0.05), (9.0, 0.012)]).with_color(GREEN),
        Series::new("rays", vec![(20.0, 0.004), (15.0, 0.02)]).with_color(BLUE),
    ]
}

#[test]
fn error_vs_time_chart_has_the_requested_size_and_every_series() {
    let dir = scratch_dir("scatter");
    let path = dir.join("error_vs_time.png");
    let chart = Chart::new("Error against GPU time", "GPU time (ms)", "RMSE").y_scale(AxisScale::Log10).size(700, 450);
    plot_error_vs_time(&path, &chart, &three_strategies()).expect("plot");

    let image = image::open(&path).expect("a readable PNG").to_rgb8();
    assert_eq!(image.dimensions(), (700, 450));

    // The legend shows each colour too, so compare with a chart whose series
    // have no points: the difference is the data markers alone.
    let legend_only: Vec<Series> = three_strategies().into_iter().map(|s| Series { points: vec![], ..s }).collect();
    let legend_image = render_error_vs_time(&chart, &legend_only).expect("render");
    for color in [RED, GREEN, BLUE] {
        let data_pixels = count_color(&image, color) - count_color(&legend_image, color);
        // Two or three filled markers of radius 5 each.
        assert!(data_pixels > 2 * 40, "{color:?}: {data_pixels} data pixels");
    }
    let front_pixels = count_color(&image, [0, 0, 0]) - count_color(&legend_image, [0, 0, 0]);
    assert!(front_pixels > 100, "Pareto front not drawn: {front_pixels}");
}

#[test]
fn line_chart_on_a_log2_axis_draws_every_series() {
    let dir = scratch_dir("lines");
    let path = dir.join("time_vs_size.png");
    let chart = Chart::new("GPU time against image size", "image side (px)", "GPU time (ms)").x_scale(AxisScale::Log2);
    let series = vec![
        Series::new("slices", vec![(256.0, 1.0), (512.0, 3.8), (1024.0, 15.0)]).with_color(RED),
        Series::new("cache", vec![(1024.0, 9.0), (256.0, 0.8), (512.0, 2.5)]).with_color(BLUE),
    ];
    plot_lines(&path, &chart, &series).expect("plot");
    let image = image::open(&path).expect("a readable PNG").to_rgb8();
    assert_eq!(image.dimensions(), (900, 600));
    let legend_only: Vec<Series> = series.iter().map(|s| Series { points: vec![], ..s.clone() }).collect();
    let legend_image = render_lines(&chart, &legend_only).expect("render");
    for color in [RED, BLUE] {
        let data_pixels = count_color(&image, color) - count_color(&legend_image, color);
        // Two segments spanning a good part of the plot, two pixels thick.
        assert!(data_pixels > 400, "{color:?}: {data_pixels} data pixels");
    }
}

#[test]
fn empty_and_unplottable_data_do_not_panic() {
    let dir = scratch_dir("degenerate");
    let chart = Chart::new("nothing", "x", "y").y_scale(AxisScale::Log10);
    let cases: Vec<Vec<Series>> = vec![
        vec![],
        vec![Series::new("empty", vec![])],
        vec![Series::new("bad", vec![(f64::NAN, 1.0), (1.0, f64::INFINITY), (2.0, 0.0), (3.0, -1.0)])],
        vec![Series::new("one point", vec![(4.0, 0.5)])],
        vec![Series::new("same x", vec![(4.0, 0.5), (4.0, 0.25), (4.0, 0.5)])],
    ];
    for (i, series) in cases.iter().enumerate() {
        let scatter = dir.join(format!("scatter_{i}.png"));
        plot_error_vs_time(&scatter, &chart, series).expect("scatter");
        let lines = dir.join(format!("lines_{i}.png"));
        plot_lines(&lines, &chart, series).expect("lines");
        let image = image::open(&scatter).expect("PNG").to_rgb8();
        assert_eq!(image.dimensions(), (900, 600));
    }
}

#[test]
fn progress_without_a_terminal_prints_one_line_per_step() {
    let mut out: Vec<u8> = Vec::new();
    {
        let mut progress = Progress::with_writer(12, &mut out, false);
        progress.start_step("line_width=4 cache=256");
        progress.finish_step();
        progress.start_step("line_width=8 cache=256");
        progress.message("note: validation is on");
        progress.fail_step("device lost");
        progress.start_step("line_width=16 cache=256");
        progress.finish();
    }
    let text = String::from_utf8(out).expect("utf-8");
    let lines: Vec<&str> = text.lines().collect();
    assert!(!text.contains('\r') && !text.contains('\x1b'), "{text:?}");
    assert!(lines[0].starts_with("[ 1/12] line_width=4 cache=256 ... "), "{text}");
    assert!(lines[0].contains("(eta "), "{text}");
    assert!(lines.contains(&"note: validation is on"), "{text}");
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("[ 2/12] line_width=8 cache=256 ... failed after") && l.contains("device lost")),
        "{text}"
    );
    assert!(lines.iter().any(|l| l.starts_with("[ 3/12] line_width=16")), "{text}");
    assert!(lines.last().is_some_and(|l| l.starts_with("3/12 steps in ")), "{text}");
}

#[test]
fn progress_on_a_terminal_redraws_one_line() {
    let mut out: Vec<u8> = Vec::new();
    {
        let mut progress = Progress::with_writer(2, &mut out, true);
        progress.start_step("a=1");
        progress.finish_step();
        progress.start_step("a=2");
        progress.finish_step();
    }
    let text = String::from_utf8(out).expect("utf-8");
    // No line ends until the progress reporter goes away.
    assert_eq!(text.matches('\n').count(), 1, "{text:?}");
    assert!(text.ends_with('\n'));
    assert!(text.matches("\r\x1b[2K").count() >= 4, "{text:?}");
    assert!(text.contains("[2/2] a=2 ... "), "{text:?}");
}
