//! What `sweeplab bench lights` prints and writes from its [`Report`]: the
//! summary on the terminal, the tables (CSV, JSON, Markdown) and the charts.

use super::*;

impl Report {
    /// What the terminal shows: the per-added-light slopes, each entire update's
    /// sequential/coherent ratio and each error row, one line each, with
    /// their 95 % intervals where the rounds give one; every column is in the files.
    pub fn print_summary(&self) {
        let num = |r: &BenchRow, k: &str| r.get_f64(k).unwrap_or(f64::NAN);
        let ci = |r: &BenchRow, k: &str| match (r.get_f64(&format!("{k}_lo")), r.get_f64(&format!("{k}_hi"))) {
            (Some(lo), Some(hi)) => format!(" (95 % CI {}-{})", readable(lo), readable(hi)),
            _ => String::new(),
        };
        for r in &self.scaling_fit.rows {
            println!(
                "figure 10, {} {}: {:.3}{} per added light (ms; the paper {:.3})",
                r.text("resolution"),
                r.text("propagation"),
                num(r, "ms_per_added_light"),
                ci(r, "ms_per_added_light"),
                num(r, "paper_ms_per_added_light")
            );
        }
        for r in self.table1.rows.iter().filter(|r| r.text("source").starts_with("ours")) {
            println!(
                "entire update, {} {} lights: sequential/coherent {:.2}x{}",
                r.text("resolution"),
                r.text("lights"),
                num(r, "sequential_over_coherent"),
                ci(r, "sequential_over_coherent")
            );
        }
        for r in &self.error.rows {
            println!(
                "error, {} {}: rmse {:.4} in {:.0} ms{}",
                r.text("technique"),
                r.text("resolution"),
                num(r, "rmse"),
                num(r, "gpu_ms"),
                ci(r, "gpu_ms")
            );
        }
    }

    /// Per part (its rounds' label), the configuration of each timed run in
    /// the order they ran: every round runs each configuration once, in a
    /// shuffled order from the recorded seed.
    pub fn orders(&self) -> &[(String, Vec<usize>)] {
        &self.orders
    }

    fn sections(&self) -> [(&'static str, &'static str, &BenchTable); 8] {
        [
            ("table1", "Table 1 shape: median GPU ms per update, ours beside the paper's Engine rows", &self.table1),
            ("inside", "A point light inside the volume (six passes) and outside, entire update", &self.inside),
            ("update", "Every measured update", &self.updates),
            ("scaling", "Figure 10 shape: entire update over lights of one direction", &self.scaling),
            (
                "scaling_fit",
                "Figure 10 slopes: the median of each round's least-squares slope, ms per added light",
                &self.scaling_fit,
            ),
            ("memory", "Memory: one illumination volume against one RGBA32F volume per light", &self.memory),
            (
                "incremental",
                "Incremental mode: frames and GPU ms per frame until the volume is complete",
                &self.incremental,
            ),
            (
                "error",
                "Error against time: one full frame (entire update + ray cast), against model (i), grey or chromatic as the row says",
                &self.error,
            ),
        ]
    }

    /// Every part's rows in one table, each tagged with its part.
    fn combined(&self) -> BenchTable {
        let mut all = BenchTable::with_run(self.run.clone());
        for (part, _, table) in self.sections() {
            for row in &table.rows {
                let mut tagged = BenchRow::new().with("part", part);
                for (k, v) in row.iter() {
                    tagged.set(k, v.clone());
                }
                all.push(tagged);
            }
        }
        all
    }

    /// The rows measured so far, as `lights.csv` and `lights.json`.
    pub fn save(&self, out_folder: &OutFolder) -> Result<(), ExperimentError> {
        Ok(out_folder.save_rows("lights", &self.combined())?)
    }

    pub fn write(&self, plan: &LightsPlan, out: &Path) -> Result<(), ExperimentError> {
        let all = self.combined();
        let mut markdown = self.run.markdown();
        markdown.push_str(
            "Each part's configurations (each with its own renderer) run once a round, in a shuffled order \
             (rounds and seed above), after a warm-up round. Times are medians over the rounds, with exact \
             95 % intervals (`_lo`, `_hi`) from 6 rounds up; ratios are medians of per-round ratios, slopes \
             medians of per-round slopes.\n\n",
        );
        for (_, title, table) in self.sections() {
            markdown.push_str(&format!("## {title}\n\n{}\n", table.to_markdown()));
        }
        all.write_csv(out.join("lights.csv"))?;
        all.write_json(out.join("lights.json"))?;
        let md = out.join("lights.md");
        std::fs::write(&md, &markdown).map_err(|source| BenchError::Write { path: md, source })?;
        self.plots(plan, out)
    }

    fn plots(&self, plan: &LightsPlan, out: &Path) -> Result<(), ExperimentError> {
        let scaling: Vec<Series> = ["coherent", "sequential"]
            .iter()
            .map(|p| Series::new(*p, self.scaling.points(|r| r.text("propagation") == *p, "lights", "gpu_ms")))
            .collect();
        plot_lines(
            out.join("lights_scaling.png"),
            &Chart::new(
                format!("Entire update, lights of one direction, {}", resolution_label(plan.scaling_scale)),
                "lights",
                "GPU time (ms)",
            )
            .run_caption(Some(&self.run)),
            &scaling,
        )?;
        for &scale in &plan.scales {
            let label = resolution_label(scale);
            let series: Vec<Series> = Update::ALL
                .iter()
                .map(|u| {
                    let keep = |r: &BenchRow| r.text("update") == u.name() && r.get_f64("scale") == Some(scale as f64);
                    Series::new(u.name(), self.updates.points(keep, "lights", "gpu_ms"))
                })
                .collect();
            plot_lines(
                out.join(format!("lights_table1_{scale}.png")),
                &Chart::new(format!("Light volume updates, {label}"), "lights", "GPU time (ms)")
                    .y_scale(AxisScale::Log10)
                    .run_caption(Some(&self.run)),
                &series,
            )?;
        }
        let error: Vec<Series> = ["lightvolume", "lightvolume-per-light", "lightvolume-per-light-grey", "dvr"]
            .iter()
            .map(|t| Series::new(*t, self.error.points(|r| r.text("technique") == *t, "gpu_ms", "rmse")))
            .collect();
        plot_error_vs_time(
            out.join("lights_error_vs_time.png"),
            &Chart::new("Light volume frames against the ground truth of their model", "GPU time (ms)", "RMSE")
                .x_scale(AxisScale::Log10)
                .y_scale(AxisScale::Log10)
                .run_caption(Some(&self.run)),
            &error,
        )?;
        Ok(())
    }
}
