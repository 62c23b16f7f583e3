//! `sweeplab bench stability`: the table of every case x technique
//! (src/bench/experiments/stability*.rs), the convergence of each technique
//! over the step, and a heat map of the table.

use super::args::BenchStabilityArgs;
use super::{bench_args, session};
use anyhow::{bail, Context as _};
use std::process::ExitCode;
use std::time::Instant;
use sweeplab::bench::experiments::stability::{
    convergence, convergence_scene, load_case, run_cell, Cell, Variant, Verdict, CONVERGENCE_STEPS,
};
use sweeplab::bench::experiments::stability_cases::{stability_cases, StabilityCase};
use sweeplab::bench::{plot_heat_map, BenchRow, BenchTable, HeatCell, HeatLevel, HeatMap, OutFolder, Progress};
use sweeplab::scene::suggest::nearest;
use sweeplab::techniques::Technique;

/// The cases named by `--cases` (all for none), in table order.
fn chosen_cases(all: Vec<StabilityCase>, ids: &[String]) -> anyhow::Result<Vec<StabilityCase>> {
    let known: Vec<&str> = all.iter().map(|c| c.id).collect();
    for id in ids {
        if !known.contains(&id.as_str()) {
            let near = nearest(id, known.iter().copied()).map(|n| format!(" (did you mean {n}?)")).unwrap_or_default();
            bail!("--cases: unknown case {id:?}{near}; known: {}", known.join(", "));
        }
    }
    Ok(all.into_iter().filter(|c| ids.is_empty() || ids.iter().any(|id| id == c.id)).collect())
}

/// The columns of the techniques named by `--techniques` (all for none).
fn chosen_variants(names: &[String]) -> anyhow::Result<Vec<Variant>> {
    let techniques: Vec<Technique> = names
        .iter()
        .map(|n| n.parse().map_err(|e: String| anyhow::anyhow!("--techniques: {e}")))
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

pub fn run(args: &BenchStabilityArgs) -> anyhow::Result<ExitCode> {
    let harness = session::harness(1, args.repeat)?;
    bench_args::check_sizes("--size", &[args.size])?;
    let dir = std::env::temp_dir().join(format!("sweeplab-bench-stability-{}", std::process::id()));
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    let cases = chosen_cases(stability_cases(&dir, args.size), &args.cases)?;
    let variants = chosen_variants(&args.techniques)?;
    let out_folder = OutFolder::prepare(&args.out)?;
    let ctx = session::open(&args.gpu)?;
    let mut progress = Progress::new(cases.len() * variants.len() + variants.len());
    let mut table = BenchTable::with_run(session::run_info(&ctx));
    let mut map = HeatMap {
        title: format!("Stability: case x technique, {0}x{0}, PSNR against the model's reference", args.size),
        rows: cases.iter().map(|c| c.name.to_string()).collect(),
        columns: variants.iter().map(|v| v.label()).collect(),
        cells: Vec::new(),
    };
    let mut failed = 0;
    for case in &cases {
        let loaded = load_case(case, &dir);
        let mut row_cells = Vec::new();
        for &variant in &variants {
            progress.start_step(&format!("{} / {}", case.id, variant.label()));
            let started = Instant::now();
            let cell = match &loaded {
                Ok((scene, warnings)) => run_cell(&ctx, case, scene, warnings, variant, args.size, harness),
                Err(e) => Cell {
                    case: case.name,
                    variant,
                    verdict: Verdict::Failed(format!("scene: {e}")),
                    psnr_db: None,
                    bound_db: sweeplab::bench::experiments::stability::bound_db(variant.technique),
                    gpu_ms: None,
                },
            };
            match &cell.verdict {
                Verdict::Failed(why) => {
                    failed += 1;
                    progress.fail_step(why);
                }
                _ => {
                    progress.finish_step();
                }
            }
            let mut row = BenchRow::new();
            row.set("case", case.id).set("technique", variant.label()).set("status", cell.verdict.name());
            if let Some(db) = cell.psnr_db {
                row.set("psnr_db", db);
            }
            row.set("bound_db", cell.bound_db);
            if let Some(ms) = cell.gpu_ms {
                row.set("gpu_ms", ms);
            }
            row.set("wall_s", started.elapsed().as_secs_f64()).set("message", cell.verdict.message());
            table.push(row);
            out_folder.save_rows("stability", &table)?;
            row_cells.push(heat_cell(&cell));
        }
        map.cells.push(row_cells);
    }
    let mut orders = BenchTable::with_run(session::run_info(&ctx));
    let base = convergence_scene(&stability_cases(&dir, args.size), &dir).map_err(anyhow::Error::msg)?;
    for &variant in &variants {
        progress.start_step(&format!("convergence / {}", variant.label()));
        let c = convergence(&ctx, &base, variant, args.size).map_err(anyhow::Error::msg)?;
        if c.failures.is_empty() {
            progress.finish_step();
        } else {
            failed += 1;
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
        orders.push(row);
        out_folder.save_rows("stability_convergence", &orders)?;
    }
    progress.finish();
    let _ = std::fs::remove_dir_all(&dir);
    let out = &args.out;
    table.write_csv(out.join("stability.csv"))?;
    table.write_json(out.join("stability.json"))?;
    orders.write_csv(out.join("stability_convergence.csv"))?;
    orders.write_json(out.join("stability_convergence.json"))?;
    let markdown = format!(
        "# sweeplab bench stability, {0}x{0}\n\n{3}{1}\n\n## Convergence (relative RMSE against the model at step 1/64)\n\n{2}\n",
        args.size,
        table.to_markdown(),
        orders.to_markdown(),
        session::run_info(&ctx).markdown()
    );
    std::fs::write(out.join("stability.md"), &markdown).context("writing stability.md")?;
    plot_heat_map(out.join("stability.png"), &map)?;
    print_summary(&table, &orders);
    println!(
        "wrote {}/stability.csv, stability.json, stability.md (the full table), stability_convergence.csv, \
         stability_convergence.json, stability.png and .svg",
        out.display()
    );
    out_folder.finish()?;
    let code = session::finish(&ctx);
    if failed > 0 {
        eprintln!("{failed} cell(s) or convergence row(s) FAILED");
        return Ok(ExitCode::from(1));
    }
    Ok(code)
}

/// What the terminal shows: the cells counted by status, every cell that is
/// not ok or warned by name, and the convergence orders; the full table is in
/// the files.
fn print_summary(table: &BenchTable, orders: &BenchTable) {
    let mut counts: Vec<(String, usize)> = Vec::new();
    for r in &table.rows {
        let status = r.text("status");
        match counts.iter_mut().find(|(s, _)| *s == status) {
            Some((_, n)) => *n += 1,
            None => counts.push((status, 1)),
        }
    }
    let counted: Vec<String> = counts.iter().map(|(s, n)| format!("{n} {s}")).collect();
    println!("{} cells: {}", table.rows.len(), counted.join(", "));
    for r in table.rows.iter().filter(|r| !matches!(r.text("status").as_str(), "ok" | "warned")) {
        println!("  {} / {}: {} {}", r.text("case"), r.text("technique"), r.text("status"), r.text("message"));
    }
    for r in &orders.rows {
        println!(
            "convergence {}: order {:.2} ({})",
            r.text("technique"),
            r.get_f64("overall_order").unwrap_or(f64::NAN),
            r.text("status")
        );
    }
}
