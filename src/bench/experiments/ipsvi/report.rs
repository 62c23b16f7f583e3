//! What `bench ipsvi` leaves: its table (the Pareto front marked per size),
//! the files, the error-against-time chart per size and the terminal summary.

use super::{mode_name, modes, IpsviPlan};
use crate::bench::{
    pareto_front, plot_error_vs_time, AxisScale, BenchError, BenchRow, BenchTable, Chart, ExperimentError, Series,
};
use crate::techniques::ipsvi::IpsviSettings;
use std::path::Path;

/// What a run measured: per size the ground truth, DVR, IPSVI and half-angle rows.
pub struct IpsviReport {
    pub table: BenchTable,
    /// Why the half-angle rows asked for were left out (the scene's lights).
    pub half_angle_left_out: Option<String>,
}

/// Marks each size's Pareto front of IPSVI rows over (GPU time, RMSE).
pub(super) fn mark_pareto(table: &mut BenchTable, sizes: &[u32]) {
    for &size in sizes {
        let idx = ipsvi_rows(table, size);
        let points: Vec<(f64, f64)> = idx
            .iter()
            .map(|&i| {
                (table.rows[i].get_f64("gpu_ms").unwrap_or(f64::NAN), table.rows[i].get_f64("rmse").unwrap_or(f64::NAN))
            })
            .collect();
        let front = pareto_front(&points);
        for (k, &i) in idx.iter().enumerate() {
            table.rows[i].set("pareto", front.contains(&k));
        }
    }
}

fn ipsvi_rows(table: &BenchTable, size: u32) -> Vec<usize> {
    (0..table.rows.len())
        .filter(|&i| table.rows[i].text("technique") == "ipsvi" && table.rows[i].get_f64("width") == Some(size as f64))
        .collect()
}

/// The plot's series at one image size: one per line width and mode (which
/// IPSVI to pick at each budget) and the half-angle runs; a series without
/// points (no half-angle runs, a line width measured in no mode) is left out
/// of the legend, where it would say nothing.
fn error_vs_time_series(table: &BenchTable, size: u32, line_widths: &[u32], base: &IpsviSettings) -> Vec<Series> {
    let idx = ipsvi_rows(table, size);
    // The scene's modes first, then any other the rows hold (the other box).
    let mut modes: Vec<String> = modes(base).iter().map(mode_name).collect();
    for &i in &idx {
        let mode = table.rows[i].text("mode");
        if !mode.is_empty() && !modes.contains(&mode) {
            modes.push(mode);
        }
    }
    line_widths
        .iter()
        .flat_map(|&lw| modes.iter().map(move |mode| (lw, mode)))
        .map(|(lw, mode)| {
            let pts = idx
                .iter()
                .map(|&i| &table.rows[i])
                .filter(|r| r.get_f64("line_width") == Some(lw as f64) && r.text("mode") == *mode)
                .map(|r| (r.get_f64("gpu_ms").unwrap_or(f64::NAN), r.get_f64("rmse").unwrap_or(f64::NAN)))
                .collect();
            Series::new(format!("line width {lw}, {mode}"), pts)
        })
        .chain(std::iter::once(Series::new(
            "half-angle (model i)",
            table.points(
                |r| r.text("technique") == "half-angle" && r.get_f64("width") == Some(size as f64),
                "gpu_ms",
                "rmse",
            ),
        )))
        .filter(|s| !s.points.is_empty())
        .collect()
}

impl IpsviReport {
    /// ipsvi.csv, ipsvi.json, ipsvi.md and per size ipsvi_<size>_error_vs_time.png (and .svg) in `out`.
    pub fn write(&self, out: &Path, plan: &IpsviPlan, base: &IpsviSettings) -> Result<(), ExperimentError> {
        let table = &self.table;
        for &size in &plan.sizes {
            let series = error_vs_time_series(table, size, &plan.line_widths, base);
            let chart = Chart::new(
                format!("IPSVI {size}x{size}: error against GPU time"),
                "GPU time (ms)",
                "RMSE vs ground truth",
            )
            .x_scale(AxisScale::Log10)
            .y_scale(AxisScale::Log10)
            .run_caption(table.run.as_ref());
            plot_error_vs_time(out.join(format!("ipsvi_{size}_error_vs_time.png")), &chart, &series)?;
        }
        table.write_csv(out.join("ipsvi.csv"))?;
        table.write_json(out.join("ipsvi.json"))?;
        let md = out.join("ipsvi.md");
        std::fs::write(&md, table.to_markdown_report()).map_err(|source| BenchError::Write { path: md, source })?;
        Ok(())
    }

    /// What the terminal shows: per size the fastest and the most accurate
    /// IPSVI run and the unshaded baseline; the full table is in the files.
    pub fn print_summary(&self) {
        if let Some(why) = &self.half_angle_left_out {
            println!("half-angle rows left out: {why} (--half-angle-slices with no value asks for none)");
        }
        let table = &self.table;
        let mut sizes: Vec<u64> = table.rows.iter().filter_map(|r| r.get_f64("width")).map(|w| w as u64).collect();
        sizes.dedup();
        for size in sizes {
            let of = |technique: &str| -> Vec<&BenchRow> {
                table
                    .rows
                    .iter()
                    .filter(|r| r.text("technique") == technique && r.get_f64("width") == Some(size as f64))
                    .collect()
            };
            let ipsvi = of("ipsvi");
            let by = |key: &str| {
                ipsvi.iter().copied().min_by(|a, b| {
                    a.get_f64(key).unwrap_or(f64::INFINITY).total_cmp(&b.get_f64(key).unwrap_or(f64::INFINITY))
                })
            };
            let describe = |r: &BenchRow| {
                format!(
                    "lw={} cache={} {} {:.0} ms ({:.1}x DVR), rmse {:.3e}",
                    r.text("line_width"),
                    r.text("cache_size"),
                    r.text("mode"),
                    r.get_f64("gpu_ms").unwrap_or(f64::NAN),
                    r.get_f64("time_over_dvr").unwrap_or(f64::NAN),
                    r.get_f64("rmse").unwrap_or(f64::NAN)
                )
            };
            let dvr = of("dvr").first().and_then(|r| r.get_f64("gpu_ms")).unwrap_or(f64::NAN);
            println!("{size}x{size}: {} IPSVI runs; unshaded DVR {dvr:.0} ms", ipsvi.len());
            if let (Some(fast), Some(exact)) = (by("gpu_ms"), by("rmse")) {
                println!("  fastest:       {}", describe(fast));
                println!("  most accurate: {}", describe(exact));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::experiments::ipsvi::size_row;

    #[test]
    fn the_plot_has_a_series_per_mode_measured_and_none_without_points() {
        let base = IpsviSettings::default();
        let mut table = BenchTable::default();
        for mode in modes(&base) {
            let mut row = size_row("ipsvi", 16);
            row.set("line_width", 1).set("mode", mode_name(&mode)).set("gpu_ms", 2.0).set("rmse", 0.1);
            table.push(row);
        }
        let names: Vec<String> = error_vs_time_series(&table, 16, &[1, 4], &base).into_iter().map(|s| s.name).collect();
        assert_eq!(
            names,
            [
                "line width 1, view samples, every-sample",
                "line width 1, view samples, non-empty",
                "line width 1, light rays"
            ]
        );
        let mut ha = size_row("half-angle", 16);
        ha.set("gpu_ms", 1.0).set("rmse", 0.2);
        table.push(ha);
        assert_eq!(error_vs_time_series(&table, 16, &[1], &base).last().unwrap().name, "half-angle (model i)");
    }
}
