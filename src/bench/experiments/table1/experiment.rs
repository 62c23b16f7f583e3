//! `bench table1` in the one shape the CLI runs ([`Experiment`]): the rows
//! saved as each data set ends, the tables and the Markdown report at the end.

use super::{print_summary, Table1Plan};
use crate::bench::experiments::image_sizes::check_sizes;
use crate::bench::{BenchError, BenchTable, Experiment, ExperimentError, OutFolder, RunInfo};
use crate::vk::{Context, Profiler};

/// The paper's Table 1 on our data sets ([`super::run`]).
pub struct Table1Experiment {
    pub plan: Table1Plan,
}

impl Experiment for Table1Experiment {
    type Report = BenchTable;
    const FOLDER: &'static str = "bench-table1";

    fn check(&self) -> Result<(), ExperimentError> {
        check_sizes("--sizes", &self.plan.sizes)
    }

    fn run(&self, ctx: &Context, run: RunInfo, out: &OutFolder) -> Result<BenchTable, ExperimentError> {
        let table = super::run(ctx, &self.plan, run, out, Profiler::FRAME_CAPACITY)?;
        // The rows again, without the mark of rows saved while measuring.
        table.write_csv(out.path().join("table1.csv"))?;
        table.write_json(out.path().join("table1.json"))?;
        let md = out.path().join("table1.md");
        std::fs::write(&md, table.to_markdown_report()).map_err(|source| BenchError::Write { path: md, source })?;
        Ok(table)
    }

    fn print_summary(&self, table: &BenchTable) {
        print_summary(table);
    }
}
