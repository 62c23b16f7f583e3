//! Every chart kind: the PNG and SVG files are written and hold a real chart,
//! and a small rendering matches its committed golden image within a
//! tolerance, so a change of font or layout is seen. Re-bless after a
//! deliberate change with `SWEEPLAB_BLESS=1 cargo test --release --test suite charts::`
//! and look at the images in tests/golden/ before committing them.

use std::path::{Path, PathBuf};

use image::RgbImage;
use sweeplab::bench::{
    plot_error_map, plot_error_vs_time, plot_heat_map, plot_histogram, plot_lines, plot_point_panels,
    plot_stacked_bars, render_error_map, render_error_vs_time, render_heat_map, render_histogram, render_lines,
    render_point_panels, render_stacked_bars, AxisScale, Chart, Distribution, ErrorMap, HeatCell, HeatLevel, HeatMap,
    Panel, Point, Series, StackedBar,
};

fn scratch_dir(test: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("charts").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

/// Pixels whose largest channel difference exceeds this count as changed.
const CHANNEL_TOLERANCE: u8 = 48;
/// At most this share of pixels may change (anti-aliasing may differ a little
/// across CPUs; a different font or a moved label changes far more).
const CHANGED_SHARE: f64 = 0.002;

/// Share of pixels that differ by more than [`CHANNEL_TOLERANCE`]; 1 when the sizes differ.
fn changed_share(a: &RgbImage, b: &RgbImage) -> f64 {
    if a.dimensions() != b.dimensions() {
        return 1.0;
    }
    let changed =
        a.pixels().zip(b.pixels()).filter(|(p, q)| (0..3).any(|c| p.0[c].abs_diff(q.0[c]) > CHANNEL_TOLERANCE)).count();
    changed as f64 / (a.width() * a.height()) as f64
}

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden").join(format!("{name}.png"))
}

fn check_golden(name: &str, image: &RgbImage) {
    let path = golden_path(name);
    if std::env::var_os("SWEEPLAB_BLESS").is_some() {
        image.save(&path).expect("write golden");
        return;
    }
    let golden = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgb8();
    let share = changed_share(image, &golden);
    if share > CHANGED_SHARE {
        let seen = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.actual.png"));
        image.save(&seen).expect("write actual");
        panic!("{name}: {:.2} % of pixels differ from {} (drawn: {})", share * 100.0, path.display(), seen.display());
    }
}

/// The PNG is the requested size and not blank; the SVG beside it is a real SVG with text.
fn check_files(png: &Path, size: Option<(u32, u32)>) {
    let image = image::open(png).expect("a readable PNG").to_rgb8();
    if let Some(size) = size {
        assert_eq!(image.dimensions(), size);
    }
    let background = image.pixels().filter(|p| p.0 == [255, 255, 255]).count();
    let total = (image.width() * image.height()) as usize;
    assert!(background < total * 99 / 100, "{}: almost blank ({background} of {total} white)", png.display());
    let distinct: std::collections::HashSet<[u8; 3]> = image.pixels().map(|p| p.0).collect();
    assert!(distinct.len() > 8, "{}: only {} colours", png.display(), distinct.len());
    let svg = std::fs::read_to_string(png.with_extension("svg")).expect("an SVG beside the PNG");
    assert!(svg.starts_with("<svg") && svg.contains("<text") && svg.len() > 2000, "{}", svg.len());
}

fn small(title: &str, x: &str, y: &str) -> Chart {
    Chart::new(title, x, y).size(480, 300)
}

fn lines_data() -> Vec<Series> {
    vec![
        Series::new("lightvolume-per-light", vec![(1.0, 3.0), (2.0, 5.5), (4.0, 9.0), (8.0, 20.0)]),
        Series::new("lightvolume-per-light-grey", vec![(1.0, 2.0), (2.0, 3.0), (4.0, 6.5), (8.0, 12.0)]),
        Series::with_points(
            "l2 cost per boundary",
            vec![Point::new(1.0, 1.0).with_interval(-0.5, 2.0), Point::new(4.0, 4.0).with_interval(3.0, 5.0)],
        ),
    ]
}

fn lines_chart() -> Chart {
    small("Lines with error bars", "lights", "GPU time (ms)").x_scale(AxisScale::Log2)
}

#[test]
fn lines_are_written_and_match_the_golden_image() {
    let dir = scratch_dir("lines");
    plot_lines(dir.join("lines.png"), &lines_chart(), &lines_data()).expect("plot");
    check_files(&dir.join("lines.png"), Some((480, 300)));
    check_golden("lines", &render_lines(&lines_chart(), &lines_data()).unwrap());
}

fn scatter_data() -> Vec<Series> {
    vec![
        Series::new("slices", vec![(12.0, 0.01), (6.0, 0.03), (3.0, 0.08)]),
        Series::new("cache", vec![(5.0, 0.02), (2.5, 0.05), (9.0, 0.012)]),
        Series::new("rays", vec![(20.0, 0.0004), (15.0, 0.002)]),
    ]
}

fn scatter_chart() -> Chart {
    small("Error against GPU time", "GPU time (ms)", "RMSE").x_scale(AxisScale::Log10).y_scale(AxisScale::Log10)
}

#[test]
fn error_vs_time_is_written_and_matches_the_golden_image() {
    let dir = scratch_dir("scatter");
    plot_error_vs_time(dir.join("scatter.png"), &scatter_chart(), &scatter_data()).expect("plot");
    check_files(&dir.join("scatter.png"), Some((480, 300)));
    check_golden("error_vs_time", &render_error_vs_time(&scatter_chart(), &scatter_data()).unwrap());
}

fn bars_data() -> Vec<StackedBar> {
    let bar = |label: &str, a: f64, b: f64, c: f64| StackedBar {
        label: label.into(),
        segments: vec![
            ("a: DVR, one dispatch".into(), a),
            ("b: + barriers".into(), b),
            ("e: + piecewise integration".into(), c),
        ],
    };
    vec![bar("256 view", 10.0, 20.0, 5.0), bar("256 rays", 10.0, 30.0, -5.0)]
}

fn bars_chart() -> Chart {
    small("One frame, step by step", "size, cache update", "GPU time (ms)")
}

#[test]
fn stacked_bars_are_written_and_match_the_golden_image() {
    let dir = scratch_dir("bars");
    plot_stacked_bars(dir.join("bars.png"), &bars_chart(), &bars_data()).expect("plot");
    check_files(&dir.join("bars.png"), Some((480, 300)));
    check_golden("stacked_bars", &render_stacked_bars(&bars_chart(), &bars_data()).unwrap());
}

fn heat_data() -> HeatMap {
    let cell = |level: HeatLevel, text: &str| HeatCell { level, text: text.into() };
    HeatMap {
        title: "Stability: case x technique".into(),
        caption: None,
        rows: vec!["thin shell".into(), "l2 dense".into()],
        columns: vec!["dvr".into(), "ipsvi".into()],
        cells: vec![
            vec![cell(HeatLevel::Good, "60 dB"), cell(HeatLevel::Bad, "FAILED")],
            vec![cell(HeatLevel::Caution, "refused"), cell(HeatLevel::Empty, "")],
        ],
    }
}

#[test]
fn heat_map_is_written_and_matches_the_golden_image() {
    let dir = scratch_dir("heat");
    plot_heat_map(dir.join("heat.png"), &heat_data()).expect("plot");
    check_files(&dir.join("heat.png"), None);
    check_golden("heat_map", &render_heat_map(&heat_data()).unwrap());
}

fn error_map_data() -> ErrorMap {
    let (width, height) = (24, 16);
    let errors = (0..width * height).map(|i| (i % width) as f32 * 0.01 + (i / width) as f32 * 0.002).collect();
    ErrorMap { title: "dvr: largest channel error".into(), width, height, errors }
}

#[test]
fn error_map_is_written_and_matches_the_golden_image() {
    let dir = scratch_dir("error_map");
    plot_error_map(dir.join("map.png"), &error_map_data()).expect("plot");
    check_files(&dir.join("map.png"), None);
    check_golden("error_map", &render_error_map(&error_map_data()).unwrap());
}

fn histogram_data() -> Vec<Distribution> {
    let spread = |base: f64, n: usize| (0..n).map(|i| base * (1.0 + (i % 7) as f64 * 0.6)).collect();
    vec![
        Distribution::new("inside the dispatch", spread(3.0, 40)),
        Distribution::new("gap to the next", spread(0.4, 40)),
    ]
}

fn histogram_chart() -> Chart {
    small("Per-line times", "microseconds", "lines").x_scale(AxisScale::Log10)
}

#[test]
fn histogram_is_written_and_matches_the_golden_image() {
    let dir = scratch_dir("histogram");
    plot_histogram(dir.join("histogram.png"), &histogram_chart(), &histogram_data(), 12).expect("plot");
    check_files(&dir.join("histogram.png"), Some((480, 300)));
    check_golden("histogram", &render_histogram(&histogram_chart(), &histogram_data(), 12).unwrap());
}

#[test]
fn the_golden_comparison_sees_a_shifted_layout() {
    // The comparison itself must be able to fail: the same chart moved by two
    // pixels (as a label that grew would move it) is far outside the tolerance.
    let image = render_lines(&lines_chart(), &lines_data()).unwrap();
    let mut shifted = RgbImage::from_pixel(image.width(), image.height(), image::Rgb([255, 255, 255]));
    for (x, y, p) in image.enumerate_pixels() {
        if x + 2 < image.width() {
            shifted.put_pixel(x + 2, y, *p);
        }
    }
    assert!(changed_share(&image, &shifted) > CHANGED_SHARE * 5.0, "{}", changed_share(&image, &shifted));
    assert_eq!(changed_share(&image, &image), 0.0);
}

/// Two panels of one quantity on devices a thousand times apart.
fn panels_data(color: [u8; 3]) -> Vec<Panel> {
    let panel = |title: &str, v: f64| Panel {
        chart: Chart::new(title, "strategy", "us per line").categories(["one", "two"]).y_from_zero().size(480, 260),
        series: vec![Series::with_points(
            "run",
            vec![
                Point::new(0.0, v).with_interval(0.9 * v, 1.1 * v),
                Point::new(1.0, 0.5 * v).with_interval(-0.1 * v, v),
            ],
        )
        .with_color(color)],
    };
    vec![panel("a GPU", 1.0), panel("a CPU driver", 1000.0)]
}

#[test]
fn panels_are_written_and_match_the_golden_image() {
    let dir = scratch_dir("panels");
    let panels = panels_data([0, 114, 178]);
    plot_point_panels(dir.join("panels.png"), "Panels, each on its own axis", &panels).expect("plot");
    // Under the title strip (40 px), the panels one under the other.
    check_files(&dir.join("panels.png"), Some((480, 40 + 2 * 260)));
    check_golden("panels", &render_point_panels("Panels, each on its own axis", &panels).unwrap());
    assert!(render_point_panels("none", &[]).is_err(), "a figure of no panels is refused");
}

/// Each panel on its own y axis: the series near 1 is drawn as high in its
/// panel as the one near 1000 in its own, not flattened onto the zero line of
/// a shared axis.
#[test]
fn each_panel_has_its_own_y_axis() {
    let color = [200, 30, 30];
    let image = render_point_panels("t", &panels_data(color)).unwrap();
    let top_row = |band: std::ops::Range<u32>| {
        band.clone()
            .find(|&y| (0..image.width()).any(|x| image.get_pixel(x, y).0 == color))
            .unwrap_or_else(|| panic!("no marker in rows {band:?}"))
    };
    let (gpu, cpu) = (top_row(40..300) - 40, top_row(300..560) - 300);
    assert!(gpu < 130 && cpu < 130, "both panels' highest point in their upper half: {gpu} {cpu} of 260");
    assert!(gpu.abs_diff(cpu) <= 3, "the same shape at both scales: {gpu} {cpu}");
}

fn count_color(image: &RgbImage, color: [u8; 3]) -> usize {
    image.pixels().filter(|p| p.0 == color).count()
}

#[test]
fn stacked_bars_draw_each_segment_in_its_colour_and_skip_negative_ones() {
    use sweeplab::bench::palette_color;
    let bar = |label: &str, a: f64, b: f64, c: f64| StackedBar {
        label: label.into(),
        segments: vec![("a".into(), a), ("b".into(), b), ("c".into(), c)],
    };
    let chart = Chart::new("t", "x", "y").size(640, 400);
    let image = render_stacked_bars(&chart, &[bar("one", 10.0, 20.0, 5.0), bar("two", 10.0, 30.0, -5.0)]).unwrap();
    let (a, b, c) = (
        count_color(&image, palette_color(0)),
        count_color(&image, palette_color(1)),
        count_color(&image, palette_color(2)),
    );
    // Both bars share a (10 each), b is 20 and 30, c only 5 (the -5 draws nothing);
    // the legend adds a few pixels of each colour.
    assert!(a > 0 && b > 0 && c > 0, "{a} {b} {c}");
    assert!(b > 2 * a && b < 3 * a, "b (50 units) against a (20): {b} vs {a}");
    assert!(c < a, "c is 5 units against a's 20: {c} vs {a}");
}

#[test]
fn each_heat_map_cell_is_drawn_in_its_level_colour_in_its_row_and_column() {
    let cell = |level: HeatLevel, text: &str| HeatCell { level, text: text.into() };
    let map = HeatMap {
        title: "t".into(),
        caption: None,
        rows: vec!["first case".into(), "second".into()],
        columns: vec!["dvr".into(), "ipsvi".into()],
        cells: vec![
            vec![cell(HeatLevel::Good, "60 dB"), cell(HeatLevel::Bad, "FAILED")],
            vec![cell(HeatLevel::Caution, "refused"), cell(HeatLevel::Good, "50 dB")],
        ],
    };
    let image = render_heat_map(&map).unwrap();
    let count = |level: HeatLevel| count_color(&image, level.color());
    // Two good cells against one bad and one caution (each legend swatch adds the same few pixels).
    let (good, bad, caution) = (count(HeatLevel::Good), count(HeatLevel::Bad), count(HeatLevel::Caution));
    assert!(bad > 0 && caution > 0, "{bad} {caution}");
    assert!(good > bad * 3 / 2 && good < bad * 5 / 2, "good {good} bad {bad}");
    // The bad cell is right of the good one on the first row.
    let first_bad = image.enumerate_pixels().find(|(_, _, p)| p.0 == HeatLevel::Bad.color()).unwrap();
    let row_good = image
        .enumerate_pixels()
        .filter(|(x, y, p)| *y == first_bad.1 && p.0 == HeatLevel::Good.color() && *x < first_bad.0)
        .count();
    assert!(row_good > 0, "the good cell sits left of the bad one on its row");
}

#[test]
fn bad_shapes_and_sizes_are_refused() {
    use sweeplab::bench::BenchError;
    let map = HeatMap {
        title: "t".into(),
        caption: None,
        rows: vec!["a".into(), "b".into()],
        columns: vec!["x".into()],
        cells: vec![vec![HeatCell { level: HeatLevel::Good, text: String::new() }]],
    };
    assert!(matches!(render_heat_map(&map), Err(BenchError::HeatMapShape { rows: 2, columns: 1 })));
    let tiny = Chart::new("t", "x", "y").size(10, 10);
    assert!(matches!(render_lines(&tiny, &[]), Err(BenchError::ChartSize { .. })));
    assert!(matches!(render_stacked_bars(&tiny, &[]), Err(BenchError::ChartSize { .. })));
    let short = ErrorMap { title: "t".into(), width: 4, height: 4, errors: vec![0.0; 3] };
    assert!(matches!(render_error_map(&short), Err(BenchError::Chart(_))));
}

#[test]
fn a_hollow_marker_shows_an_interval_that_holds_zero() {
    let chart = Chart::new("t", "x", "y").size(640, 400);
    let color = [200, 30, 30];
    let at = |interval: (f64, f64)| {
        let series = Series::with_points(
            "s",
            vec![Point::new(1.0, 1.0).with_interval(interval.0, interval.1), Point::new(2.0, 2.0)],
        );
        count_color(&render_error_vs_time(&chart, &[series.with_color(color)]).unwrap(), color)
    };
    // The same two points; the first one's marker loses its fill when its interval holds 0.
    let (filled, hollow) = (at((0.5, 1.5)), at((-0.5, 1.5)));
    assert!(hollow + 30 < filled, "filled {filled} hollow {hollow}");
}
