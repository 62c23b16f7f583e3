//! `sweeplab keys [TABLE]`: the technique tables' key reference, written from
//! each settings type's declared keys (`sweeplab::scene::settings_docs`).

use super::args::KeysArgs;
use std::process::ExitCode;
use sweeplab::scene::suggest::nearest;
use sweeplab::scene::technique_settings::TableCatalogue;
use sweeplab::techniques::CATALOGUE;

pub fn run(args: &KeysArgs) -> anyhow::Result<ExitCode> {
    let Some(table) = args.table.as_deref() else {
        print!("{}", CATALOGUE.documented_tables());
        return Ok(ExitCode::SUCCESS);
    };
    let tables = CATALOGUE.tables();
    match CATALOGUE.documented_table(table) {
        Some(text) => print!("{text}"),
        None => {
            let near =
                nearest(table, tables.iter().copied()).map(|n| format!(" (did you mean {n}?)")).unwrap_or_default();
            anyhow::bail!("no technique table [{table}]{near}; known: {}", tables.join(", "));
        }
    }
    Ok(ExitCode::SUCCESS)
}
