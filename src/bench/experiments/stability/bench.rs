//! `sweeplab bench stability` as an experiment: the chosen cases x
//! techniques of [`super`], each cell a row and a heat map cell,
//! then each technique's convergence over the step; the reports, the summary
//! on the terminal and how many cells or convergence rows failed.

use super::cases::{stability_cases, StabilityCase};
use super::{convergence, convergence_scene, load_case, run_cell, Cell, Variant, Verdict, CONVERGENCE_STEPS};
use crate::bench::experiments::image_sizes::check_sizes;
use crate::bench::{
    plot_heat_map, BenchError, BenchRow, BenchTable, ExperimentError, Harness, HeatCell, HeatLevel, HeatMap, OutFolder,
    Progress, RunInfo,
};
use crate::scene::suggest::nearest;
use crate::techniques::Technique;
use crate::vk::Context;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What `bench stability` measures: the chosen cases (their files in `dir`)
/// and technique columns at `size` x `size`, each cell's GPU time over
/// `harness`'s frames (cells are not compared with each other, so each is
/// timed on its own).
pub struct StabilityPlan {
    pub size: u32,
    pub cases: Vec<StabilityCase>,
    pub variants: Vec<Variant>,
    pub harness: Harness,
    /// Where the cases' files are written; removed at the end of [`run`].
    pub dir: PathBuf,
}

impl StabilityPlan {
    /// The cases named in `case_ids` and the techniques named in
    /// `techniques` (all for an empty list), in table order; an unknown name
    /// is an error with a did-you-mean, a size out of range an error naming
    /// `--size`. Writes the cases' files to `dir`.
    pub fn choose(
        size: u32,
        case_ids: &[String],
        techniques: &[String],
        harness: Harness,
        dir: PathBuf,
    ) -> Result<StabilityPlan, ExperimentError> {
        check_sizes("--size", &[size])?;
        std::fs::create_dir_all(&dir)
            .map_err(|e| ExperimentError::Invalid(format!("creating {}: {e}", dir.display())))?;
        let cases = chosen_cases(stability_cases(&dir, size), case_ids)?;
        let variants = chosen_variants(techniques)?;
        Ok(StabilityPlan { size, cases, variants, harness, dir })
    }
}

/// The cases' files go with the plan: a run that never starts (its output
/// folder refused, no device) or stops on an error leaves none behind.
impl Drop for StabilityPlan {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The cases named by `ids` (all for none), in table order.
fn chosen_cases(all: Vec<StabilityCase>, ids: &[String]) -> Result<Vec<StabilityCase>, ExperimentError> {
    let known: Vec<&str> = all.iter().map(|c| c.id).collect();
    if let Some(id) = ids.iter().find(|id| !known.contains(&id.as_str())) {
        let near = nearest(id, known.iter().copied()).map(|n| format!(" (did you mean {n}?)")).unwrap_or_default();
        return Err(ExperimentError::Invalid(format!(
            "--cases: unknown case {id:?}{near}; known: {}",
            known.join(", ")
        )));
    }
    Ok(all.into_iter().filter(|c| ids.is_empty() || ids.iter().any(|id| id == c.id)).collect())
}

/// The columns of the techniques named by `names` (all for none).
fn chosen_variants(names: &[String]) -> Result<Vec<Variant>, ExperimentError> {
    let techniques: Vec<Technique> = names
        .iter()
        .map(|n| n.parse().map_err(|e: String| ExperimentError::Invalid(format!("--techniques: {e}"))))
        .collect::<Result<_, _>>()?;
    Ok(Variant::all().into_iter().filter(|v| techniques.is_empty() || techniques.contains(&v.technique)).collect())
}

fn level(verdict: &Verdict) -> HeatLevel {
    match verdict {
        Verdict::Ok => HeatLevel::Good,
        Verdict::Warned(_) | Verdict::Refused(_) => HeatLevel::Caution,
        Verdict::Failed(_) => HeatLevel::Bad,
    }
}

fn heat_cell(cell: &Cell) -> HeatCell {
    let text = match (&cell.verdict, cell.psnr_db) {
        (Verdict::Ok | Verdict::Warned(_), Some(db)) if db.is_finite() => format!("{db:.0} dB"),
        (Verdict::Ok | Verdict::Warned(_), Some(_)) => "exact".into(),
        (v, _) => v.name().to_string(),
    };
    HeatCell { level: level(&cell.verdict), text }
}

/// A cell as a row of the table.
fn cell_row(case: &StabilityCase, cell: &Cell, wall_s: f64) -> BenchRow {
    let mut row = BenchRow::new();
    row.set("case", case.id).set("technique", cell.variant.label()).set("status", cell.verdict.name());
    if let Some(kernel) = &cell.line_kernel {
        row.set("line_kernel", kernel.as_str());
    }
    if let Some(db) = cell.psnr_db {
        row.set("psnr_db", db);
    }
    row.set("bound_db", cell.bound_db);
    if let Some(ms) = cell.gpu_ms {
        row.set("gpu_ms", ms).set_estimate("gpu_ms", cell.gpu_ms_interval);
    }
    row.set("wall_s", wall_s).set("message", cell.verdict.message());
    row
}

/// What a run measured.
pub struct StabilityReport {
    /// One row per case x technique.
    pub table: BenchTable,
    /// One convergence row per technique.
    pub orders: BenchTable,
    pub map: HeatMap,
    /// Cells and convergence rows that failed.
    pub failed: usize,
    pub size: u32,
}

/// Every cell of `plan`, then every technique's convergence, each table
/// saved in `out_folder` as its rows come; the files of the cases removed
/// at the end.
pub fn run(
    ctx: &Context,
    plan: &StabilityPlan,
    run: RunInfo,
    out_folder: &OutFolder,
) -> Result<StabilityReport, ExperimentError> {
    let (cases, variants) = (&plan.cases, &plan.variants);
    let mut progress = Progress::new(cases.len() * variants.len() + variants.len());
    let run = run.input("size", plan.size).input("repeat", plan.harness.repeat());
    let mut report = StabilityReport {
        table: BenchTable::with_run(run.clone()),
        orders: BenchTable::with_run(run.clone()),
        map: HeatMap {
            title: format!("Stability: case x technique, {0}x{0}, PSNR against the model's reference", plan.size),
            caption: Some(run.caption()),
            rows: cases.iter().map(|c| c.name.to_string()).collect(),
            columns: variants.iter().map(|v| v.label()).collect(),
            cells: Vec::new(),
        },
        failed: 0,
        size: plan.size,
    };
    for case in cases {
        let loaded = load_case(case, &plan.dir);
        let mut row_cells = Vec::new();
        for &variant in variants {
            progress.start_step(&format!("{} / {}", case.id, variant.label()));
            let started = Instant::now();
            let cell = match &loaded {
                Ok((scene, warnings)) => run_cell(ctx, case, scene, warnings, variant, plan.size, plan.harness),
                Err(e) => Cell::unmeasured(case, variant, Verdict::Failed(format!("scene: {e}"))),
            };
            match &cell.verdict {
                Verdict::Failed(why) => {
                    report.failed += 1;
                    progress.fail_step(why);
                }
                _ => {
                    progress.finish_step();
                }
            }
            report.table.push(cell_row(case, &cell, started.elapsed().as_secs_f64()));
            out_folder.save_rows("stability", &report.table)?;
            row_cells.push(heat_cell(&cell));
        }
        report.map.cells.push(row_cells);
    }
    let base =
        convergence_scene(&stability_cases(&plan.dir, plan.size), &plan.dir).map_err(ExperimentError::Invalid)?;
    for &variant in variants {
        progress.start_step(&format!("convergence / {}", variant.label()));
        let c = convergence(ctx, &base, variant, plan.size).map_err(ExperimentError::Invalid)?;
        if c.failures.is_empty() {
            progress.finish_step();
        } else {
            report.failed += 1;
            progress.fail_step(&c.failures.join("; "));
        }
        let mut row = BenchRow::new();
        row.set("technique", variant.label());
        for (step, e) in CONVERGENCE_STEPS.iter().zip(&c.errors) {
            row.set(format!("rel_rmse_step_{step}"), *e);
        }
        for (i, o) in c.orders.iter().enumerate() {
            row.set(format!("order_{}_{}", CONVERGENCE_STEPS[i], CONVERGENCE_STEPS[i + 1]), *o);
        }
        row.set("overall_order", c.overall_order());
        row.set("status", if c.failures.is_empty() { "ok" } else { "FAILED" }).set("message", c.failures.join("; "));
        report.orders.push(row);
        out_folder.save_rows("stability_convergence", &report.orders)?;
    }
    progress.finish();
    let _ = std::fs::remove_dir_all(&plan.dir);
    Ok(report)
}

impl StabilityReport {
    /// stability.csv, .json, .md, stability_convergence.csv, .json and the
    /// heat map (stability.png and .svg) in `out`.
    pub fn write(&self, out: &Path) -> Result<(), ExperimentError> {
        self.table.write_csv(out.join("stability.csv"))?;
        self.table.write_json(out.join("stability.json"))?;
        self.orders.write_csv(out.join("stability_convergence.csv"))?;
        self.orders.write_json(out.join("stability_convergence.json"))?;
        let markdown = format!(
            "# sweeplab bench stability, {0}x{0}\n\n{3}{1}\n\n## Convergence (relative RMSE against the model at step 1/64)\n\n{2}\n",
            self.size,
            self.table.to_markdown(),
            self.orders.to_markdown(),
            self.table.run.as_ref().map(|r| r.markdown()).unwrap_or_default()
        );
        let md = out.join("stability.md");
        std::fs::write(&md, &markdown).map_err(|source| BenchError::Write { path: md, source })?;
        plot_heat_map(out.join("stability.png"), &self.map)?;
        Ok(())
    }

    /// What the terminal shows: the cells counted by status, every cell that
    /// is not ok or warned by name, and the convergence orders; the full
    /// table is in the files.
    pub fn print_summary(&self) {
        for line in self.summary_lines() {
            println!("{line}");
        }
    }

    fn summary_lines(&self) -> Vec<String> {
        let mut counts: Vec<(String, usize)> = Vec::new();
        for r in &self.table.rows {
            let status = r.text("status");
            match counts.iter_mut().find(|(s, _)| *s == status) {
                Some((_, n)) => *n += 1,
                None => counts.push((status, 1)),
            }
        }
        let counted: Vec<String> = counts.iter().map(|(s, n)| format!("{n} {s}")).collect();
        let mut lines = vec![format!("{} cells: {}", self.table.rows.len(), counted.join(", "))];
        for r in self.table.rows.iter().filter(|r| !matches!(r.text("status").as_str(), "ok" | "warned")) {
            lines.push(format!(
                "  {} / {}: {} {}",
                r.text("case"),
                r.text("technique"),
                r.text("status"),
                r.text("message")
            ));
        }
        for r in &self.orders.rows {
            lines.push(format!(
                "convergence {}: order {:.2} ({})",
                r.text("technique"),
                r.get_f64("overall_order").unwrap_or(f64::NAN),
                r.text("status")
            ));
        }
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("sweeplab-stability-bench-{name}-{}", std::process::id()))
    }

    #[test]
    fn unknown_cases_and_techniques_are_refused_with_a_suggestion() {
        let names = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let harness = Harness::once_after(0);
        let e = StabilityPlan::choose(8, &names(&["baseline", "stif"]), &[], harness, dir("a")).err().unwrap();
        assert!(e.to_string().contains("did you mean stiff?"), "{e}");
        let e = StabilityPlan::choose(8, &[], &names(&["half_angle"]), harness, dir("b")).err().unwrap();
        assert!(e.to_string().starts_with("--techniques") && e.to_string().contains("half-angle"), "{e}");
        let plan = StabilityPlan::choose(8, &names(&["opaque", "baseline"]), &names(&["dvr"]), harness, dir("c"));
        let plan = plan.unwrap();
        let ids: Vec<&str> = plan.cases.iter().map(|c| c.id).collect();
        assert_eq!(ids, ["baseline", "opaque"], "table order, not the order given");
        assert!(plan.variants.iter().all(|v| v.technique == Technique::Dvr) && !plan.variants.is_empty());
        let all = StabilityPlan::choose(8, &[], &[], harness, dir("d")).unwrap();
        assert_eq!(all.variants.len(), Variant::all().len());
        for d in ["a", "b", "c", "d"] {
            let _ = std::fs::remove_dir_all(dir(d));
        }
    }

    #[test]
    fn the_summary_counts_statuses_and_names_what_is_not_ok() {
        let mut table = BenchTable::new();
        for (case, status, message) in [("a", "ok", ""), ("b", "warned", "w"), ("c", "FAILED", "12 dB < 30 dB")] {
            table.push(
                BenchRow::new()
                    .with("case", case)
                    .with("technique", "dvr")
                    .with("status", status)
                    .with("message", message),
            );
        }
        let mut orders = BenchTable::new();
        orders.push(BenchRow::new().with("technique", "dvr").with("overall_order", 2.0).with("status", "ok"));
        let map =
            HeatMap { title: String::new(), caption: None, rows: Vec::new(), columns: Vec::new(), cells: Vec::new() };
        let report = StabilityReport { table, orders, map, failed: 1, size: 8 };
        assert_eq!(
            report.summary_lines(),
            [
                "3 cells: 1 ok, 1 warned, 1 FAILED",
                "  c / dvr: FAILED 12 dB < 30 dB",
                "convergence dvr: order 2.00 (ok)"
            ]
        );
    }

    #[test]
    fn a_cell_reads_as_its_psnr_or_its_verdict() {
        std::fs::create_dir_all(dir("e")).unwrap();
        let case = &stability_cases(&dir("e"), 8)[0];
        let variant = Variant::all()[0];
        let mut cell = Cell::unmeasured(case, variant, Verdict::Ok);
        cell.psnr_db = Some(41.6);
        assert_eq!(heat_cell(&cell), HeatCell { level: HeatLevel::Good, text: "42 dB".into() });
        cell.psnr_db = Some(f64::INFINITY);
        assert_eq!(heat_cell(&cell).text, "exact");
        let refused = Cell::unmeasured(case, variant, Verdict::Refused("no".into()));
        assert_eq!(heat_cell(&refused), HeatCell { level: HeatLevel::Caution, text: "refused".into() });
        let row = cell_row(case, &cell, 0.5);
        assert_eq!(row.text("status"), "ok");
        assert_eq!(row.get("gpu_ms"), None, "no frame, no time");
        let _ = std::fs::remove_dir_all(dir("e"));
    }
}
