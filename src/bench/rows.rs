//! One row per benchmark run, and the table of all rows written as CSV, JSON and
//! Markdown. Column order is the order in which keys were first set, so reports
//! read the way the sweep code was written (parameters first, results last).

use std::fmt;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::ser::{SerializeMap, SerializeSeq};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::error::BenchError;
use super::estimate::{Estimate, Verdict};
use super::interleaved::Timings;
use super::pareto::pareto_front;
use super::run_info::RunInfo;

/// One value in a benchmark row: a parameter or a measurement.
#[derive(Debug, Clone, PartialEq)]
pub enum BenchValue {
    Int(i64),
    Float(f64),
    Bool(bool),
    Text(String),
}

impl BenchValue {
    /// The value as a number; `None` for text and bools, which are labels, not
    /// quantities.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            BenchValue::Int(i) => Some(*i as f64),
            BenchValue::Float(f) => Some(*f),
            BenchValue::Bool(_) | BenchValue::Text(_) => None,
        }
    }

    fn is_number(&self) -> bool {
        matches!(self, BenchValue::Int(_) | BenchValue::Float(_))
    }

    /// Exact text for machine-readable files: floats keep every digit needed to
    /// read back the same f64, and keep a `.0` so they stay floats.
    fn to_exact_text(&self) -> String {
        match self {
            BenchValue::Int(i) => i.to_string(),
            BenchValue::Float(f) => format!("{f:?}"),
            BenchValue::Bool(b) => b.to_string(),
            BenchValue::Text(s) => s.clone(),
        }
    }

    /// Short text for people: four significant digits is plenty to compare runs.
    fn to_readable_text(&self) -> String {
        match self {
            BenchValue::Float(f) => format_readable_number(*f),
            other => other.to_exact_text(),
        }
    }
}

impl fmt::Display for BenchValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_readable_text())
    }
}

macro_rules! bench_value_from_small_int {
    ($($t:ty),*) => {$(
        impl From<$t> for BenchValue {
            fn from(v: $t) -> Self {
                BenchValue::Int(i64::from(v))
            }
        }
    )*};
}
bench_value_from_small_int!(i8, i16, i32, i64, u8, u16, u32);

macro_rules! bench_value_from_wide_unsigned {
    ($($t:ty),*) => {$(
        impl From<$t> for BenchValue {
            // Counts beyond i64 do not occur in practice; a float keeps them sortable.
            fn from(v: $t) -> Self {
                match i64::try_from(v) {
                    Ok(i) => BenchValue::Int(i),
                    Err(_) => BenchValue::Float(v as f64),
                }
            }
        }
    )*};
}
bench_value_from_wide_unsigned!(u64, usize);

impl From<f32> for BenchValue {
    fn from(v: f32) -> Self {
        BenchValue::Float(f64::from(v))
    }
}

impl From<f64> for BenchValue {
    fn from(v: f64) -> Self {
        BenchValue::Float(v)
    }
}

impl From<bool> for BenchValue {
    fn from(v: bool) -> Self {
        BenchValue::Bool(v)
    }
}

impl From<&str> for BenchValue {
    fn from(v: &str) -> Self {
        BenchValue::Text(v.to_owned())
    }
}

impl From<String> for BenchValue {
    fn from(v: String) -> Self {
        BenchValue::Text(v)
    }
}

impl From<&String> for BenchValue {
    fn from(v: &String) -> Self {
        BenchValue::Text(v.clone())
    }
}

/// Formats a float for a table a person reads: four significant digits,
/// no trailing zeros, scientific notation only for very small or large values.
pub(crate) fn format_readable_number(v: f64) -> String {
    if v.is_nan() {
        return "NaN".to_owned();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf" } else { "-inf" }.to_owned();
    }
    if v == 0.0 {
        return "0".to_owned();
    }
    let magnitude = v.abs();
    if (1e-3..1e6).contains(&magnitude) {
        let decimals = (3 - magnitude.log10().floor() as i32).max(0) as usize;
        trim_fraction_zeros(format!("{v:.decimals$}"))
    } else {
        let text = format!("{v:.3e}");
        match text.split_once('e') {
            Some((mantissa, exponent)) => {
                format!("{}e{exponent}", trim_fraction_zeros(mantissa.to_owned()))
            }
            None => text,
        }
    }
}

fn trim_fraction_zeros(text: String) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

impl Serialize for BenchValue {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            BenchValue::Int(i) => serializer.serialize_i64(*i),
            // JSON has no NaN or infinity; serde_json writes them as null.
            BenchValue::Float(f) => serializer.serialize_f64(*f),
            BenchValue::Bool(b) => serializer.serialize_bool(*b),
            BenchValue::Text(s) => serializer.serialize_str(s),
        }
    }
}

impl<'de> Deserialize<'de> for BenchValue {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(BenchValueVisitor)
    }
}

struct BenchValueVisitor;

impl Visitor<'_> for BenchValueVisitor {
    type Value = BenchValue;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number, a bool, a string or null")
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<BenchValue, E> {
        Ok(BenchValue::Bool(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<BenchValue, E> {
        Ok(BenchValue::Int(v))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<BenchValue, E> {
        Ok(BenchValue::from(v))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<BenchValue, E> {
        Ok(BenchValue::Float(v))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<BenchValue, E> {
        Ok(BenchValue::Text(v.to_owned()))
    }

    fn visit_string<E: de::Error>(self, v: String) -> Result<BenchValue, E> {
        Ok(BenchValue::Text(v))
    }

    // A null can only come from a non-finite float, which JSON cannot spell.
    fn visit_unit<E: de::Error>(self) -> Result<BenchValue, E> {
        Ok(BenchValue::Float(f64::NAN))
    }

    fn visit_none<E: de::Error>(self) -> Result<BenchValue, E> {
        Ok(BenchValue::Float(f64::NAN))
    }
}

/// The parameters and measurements of one benchmark run, in insertion order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BenchRow {
    entries: Vec<(String, BenchValue)>,
}

impl BenchRow {
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets `key`; a key set again keeps its original column position.
    pub fn set(&mut self, key: impl Into<String>, value: impl Into<BenchValue>) -> &mut Self {
        let key = key.into();
        let value = value.into();
        match self.entries.iter_mut().find(|(k, _)| *k == key) {
            Some((_, existing)) => *existing = value,
            None => self.entries.push((key, value)),
        }
        self
    }

    /// Sets `key` to the estimate and `key_lo`, `key_hi` to its 95 % interval;
    /// nothing where there is no estimate.
    pub fn set_estimate(&mut self, key: &str, estimate: Option<Estimate>) -> &mut Self {
        if let Some(e) = estimate {
            self.set(key, e.value).set(format!("{key}_lo"), e.lo).set(format!("{key}_hi"), e.hi);
        }
        self
    }

    /// A measured time: `key` the median of its counted runs, `key_lo` and
    /// `key_hi` its 95 % interval where there are enough runs for one.
    pub fn set_timing<T>(&mut self, key: &str, timings: &Timings<T>) -> &mut Self {
        self.set(key, timings.median());
        self.set_estimate(key, timings.estimate())
    }

    /// A cost against a baseline: `key_lo`, `key_hi` and `key_verdict`
    /// always, `key` itself only where the interval lies above 0, so a
    /// difference within noise is never read as a (negative) cost.
    pub fn set_cost(&mut self, key: &str, estimate: Option<Estimate>) -> &mut Self {
        if let Some(e) = estimate {
            if e.verdict() == Verdict::Cost {
                self.set(key, e.value);
            }
            self.set(format!("{key}_lo"), e.lo).set(format!("{key}_hi"), e.hi);
            self.set(format!("{key}_verdict"), e.verdict().name());
        }
        self
    }

    /// Builder form of [`BenchRow::set`].
    pub fn with(mut self, key: impl Into<String>, value: impl Into<BenchValue>) -> Self {
        self.set(key, value);
        self
    }

    pub fn get(&self, key: &str) -> Option<&BenchValue> {
        self.entries.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }

    /// The value of `key` as a number; `None` when missing or not numeric.
    pub fn get_f64(&self, key: &str) -> Option<f64> {
        self.get(key).and_then(BenchValue::as_f64)
    }

    /// The value of `key` as text (empty when missing).
    pub fn text(&self, key: &str) -> String {
        self.get(key).map(|v| v.to_string()).unwrap_or_default()
    }

    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|(k, _)| k.as_str())
    }

    pub fn iter(&self) -> impl Iterator<Item = (&str, &BenchValue)> {
        self.entries.iter().map(|(k, v)| (k.as_str(), v))
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}

impl Serialize for BenchRow {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.entries.len()))?;
        for (key, value) in &self.entries {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for BenchRow {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(BenchRowVisitor)
    }
}

struct BenchRowVisitor;

impl<'de> Visitor<'de> for BenchRowVisitor {
    type Value = BenchRow;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an object of numbers, bools and strings")
    }

    // Reading entries one by one keeps the file's key order.
    fn visit_map<A: MapAccess<'de>>(self, mut access: A) -> Result<BenchRow, A::Error> {
        let mut row = BenchRow::new();
        while let Some((key, value)) = access.next_entry::<String, BenchValue>()? {
            row.set(key, value);
        }
        Ok(row)
    }
}

fn create_parent(path: &Path) -> std::io::Result<()> {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => std::fs::create_dir_all(parent),
        _ => Ok(()),
    }
}

/// All runs of a sweep, and what produced them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BenchTable {
    pub rows: Vec<BenchRow>,
    /// Device, driver, host, build, inputs and date: written ahead of the rows
    /// in every format (see [`RunInfo`]).
    pub run: Option<RunInfo>,
}

impl BenchTable {
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty table that names what produced it.
    pub fn with_run(run: RunInfo) -> Self {
        BenchTable { rows: Vec::new(), run: Some(run) }
    }

    pub fn push(&mut self, row: BenchRow) {
        self.rows.push(row);
    }

    /// (x, y) of the rows `keep` accepts that have both as numbers: a plot series.
    pub fn points(&self, keep: impl Fn(&BenchRow) -> bool, x: &str, y: &str) -> Vec<(f64, f64)> {
        self.rows.iter().filter(|r| keep(r)).filter_map(|r| Some((r.get_f64(x)?, r.get_f64(y)?))).collect()
    }

    /// Union of all rows' keys in the order the rows give them: a key first
    /// seen in a later row stands right after the key before it in that row
    /// (a verdict beside its estimate even where the first row has neither),
    /// at the end where it leads its row.
    pub fn columns(&self) -> Vec<String> {
        let mut columns: Vec<String> = Vec::new();
        for row in &self.rows {
            let mut after: Option<usize> = None;
            for key in row.keys() {
                let at = match columns.iter().position(|c| c == key) {
                    Some(i) => i,
                    None => {
                        let at = after.map_or(columns.len(), |i| i + 1);
                        columns.insert(at, key.to_owned());
                        at
                    }
                };
                after = Some(at);
            }
        }
        columns
    }

    /// One number per row; NaN where the row lacks `key` or it is not numeric,
    /// so the result lines up with `rows` and such rows never reach a Pareto front.
    pub fn column_f64(&self, key: &str) -> Vec<f64> {
        self.rows.iter().map(|row| row.get_f64(key).unwrap_or(f64::NAN)).collect()
    }

    /// Computes the Pareto front of (`time_key`, `error_key`), sets the bool
    /// column `flag_key` on every row (true on the front), and returns the
    /// front's row indices sorted by time.
    pub fn mark_pareto_front(&mut self, time_key: &str, error_key: &str, flag_key: &str) -> Vec<usize> {
        let points: Vec<(f64, f64)> = self.column_f64(time_key).into_iter().zip(self.column_f64(error_key)).collect();
        let front = pareto_front(&points);
        for (index, row) in self.rows.iter_mut().enumerate() {
            row.set(flag_key, front.contains(&index));
        }
        front
    }

    /// The table as CSV: `#` comment lines naming the run (where known), a
    /// header with every column, one line per row, empty fields where a row
    /// lacks a column, RFC 4180 quoting.
    pub fn to_csv(&self) -> String {
        let columns = self.columns();
        let mut out = self.run.as_ref().map(RunInfo::csv_comment).unwrap_or_default();
        let header: Vec<String> = columns.iter().map(|c| csv_field(c)).collect();
        out.push_str(&header.join(","));
        out.push('\n');
        for row in &self.rows {
            let fields: Vec<String> = columns
                .iter()
                .map(|column| match row.get(column) {
                    Some(value) => csv_field(&value.to_exact_text()),
                    None => String::new(),
                })
                .collect();
            out.push_str(&fields.join(","));
            out.push('\n');
        }
        out
    }

    /// Writes the table as CSV, creating the folder it goes into when needed
    /// (a bench's output folder is created by its first file).
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<(), BenchError> {
        let path = path.as_ref();
        let write_error = |source| BenchError::Write { path: path.to_owned(), source };
        create_parent(path).map_err(write_error)?;
        std::fs::write(path, self.to_csv()).map_err(write_error)
    }

    /// The table as pretty-printed JSON: `{"run": {...}, "rows": [...]}`, or a
    /// plain array of rows where the run is not known; keys in row order.
    /// Non-finite floats become `null` (JSON has no NaN) and read back as NaN.
    pub fn write_json(&self, path: impl AsRef<Path>) -> Result<(), BenchError> {
        let path = path.as_ref();
        let write_error = |source| BenchError::Write { path: path.to_owned(), source };
        create_parent(path).map_err(write_error)?;
        let file = File::create(path).map_err(write_error)?;
        let mut writer = BufWriter::new(file);
        serde_json::to_writer_pretty(&mut writer, self)
            .map_err(|e| BenchError::Write { path: path.to_owned(), source: e.into() })?;
        writer.write_all(b"\n").map_err(write_error)?;
        writer.flush().map_err(write_error)
    }

    /// Reads a table written by [`BenchTable::write_json`], keeping key order.
    pub fn read_json(path: impl AsRef<Path>) -> Result<Self, BenchError> {
        let path = path.as_ref();
        let text =
            std::fs::read_to_string(path).map_err(|source| BenchError::Read { path: path.to_owned(), source })?;
        serde_json::from_str(&text).map_err(|source| BenchError::Json { path: path.to_owned(), source })
    }

    /// The run's header block (where known) and the table: the Markdown file
    /// a bench writes.
    pub fn to_markdown_report(&self) -> String {
        let header = self.run.as_ref().map(RunInfo::markdown).unwrap_or_default();
        format!("{header}{}", self.to_markdown())
    }

    /// A Markdown table to paste into a report: numbers right-aligned with four
    /// significant digits, columns padded so the raw text lines up too.
    pub fn to_markdown(&self) -> String {
        let columns = self.columns();
        let cells: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|row| {
                columns
                    .iter()
                    .map(|column| row.get(column).map(|v| markdown_cell(&v.to_readable_text())).unwrap_or_default())
                    .collect()
            })
            .collect();
        let numeric: Vec<bool> = columns
            .iter()
            .map(|column| {
                let mut present = self.rows.iter().filter_map(|row| row.get(column)).peekable();
                present.peek().is_some() && present.all(BenchValue::is_number)
            })
            .collect();
        let headers: Vec<String> = columns.iter().map(|c| markdown_cell(c)).collect();
        let widths: Vec<usize> = headers
            .iter()
            .enumerate()
            .map(|(i, header)| {
                cells.iter().map(|row| row[i].chars().count()).chain([header.chars().count(), 3]).max().unwrap_or(3)
            })
            .collect();

        let pad = |text: &str, width: usize, right: bool| {
            let fill = " ".repeat(width.saturating_sub(text.chars().count()));
            if right {
                format!("{fill}{text}")
            } else {
                format!("{text}{fill}")
            }
        };
        let mut out = String::new();
        let header_line: Vec<String> =
            headers.iter().zip(&widths).zip(&numeric).map(|((h, &w), &n)| pad(h, w, n)).collect();
        out.push_str(&format!("| {} |\n", header_line.join(" | ")));
        let rule: Vec<String> = widths
            .iter()
            .zip(&numeric)
            .map(|(&w, &n)| if n { format!("{}:", "-".repeat(w - 1)) } else { format!(":{}", "-".repeat(w - 1)) })
            .collect();
        out.push_str(&format!("| {} |\n", rule.join(" | ")));
        for row in &cells {
            let line: Vec<String> = row.iter().zip(&widths).zip(&numeric).map(|((c, &w), &n)| pad(c, w, n)).collect();
            out.push_str(&format!("| {} |\n", line.join(" | ")));
        }
        out
    }
}

/// The rows alone, as a JSON array.
struct RowsOf<'a>(&'a [BenchRow]);

impl Serialize for RowsOf<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut seq = serializer.serialize_seq(Some(self.0.len()))?;
        for row in self.0 {
            seq.serialize_element(row)?;
        }
        seq.end()
    }
}

impl Serialize for BenchTable {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match &self.run {
            None => RowsOf(&self.rows).serialize(serializer),
            Some(run) => {
                let mut map = serializer.serialize_map(Some(2))?;
                map.serialize_entry("run", run)?;
                map.serialize_entry("rows", &RowsOf(&self.rows))?;
                map.end()
            }
        }
    }
}

impl<'de> Deserialize<'de> for BenchTable {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(BenchTableVisitor)
    }
}

struct BenchTableVisitor;

impl<'de> Visitor<'de> for BenchTableVisitor {
    type Value = BenchTable;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an array of benchmark rows, or an object with `run` and `rows`")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut access: A) -> Result<BenchTable, A::Error> {
        let mut table = BenchTable::new();
        while let Some(row) = access.next_element::<BenchRow>()? {
            table.push(row);
        }
        Ok(table)
    }

    fn visit_map<A: MapAccess<'de>>(self, mut access: A) -> Result<BenchTable, A::Error> {
        let mut table = BenchTable::new();
        while let Some(key) = access.next_key::<String>()? {
            match key.as_str() {
                "run" => table.run = Some(access.next_value()?),
                "rows" => table.rows = access.next_value::<BenchTable>()?.rows,
                other => return Err(de::Error::unknown_field(other, &["run", "rows"])),
            }
        }
        Ok(table)
    }
}

/// Quotes a CSV field when it would otherwise be misread: separators, quotes,
/// line breaks, edge spaces (trimmed by some readers) and empty text (which
/// would read as a missing value).
fn csv_field(text: &str) -> String {
    let needs_quotes = text.is_empty()
        || text.contains([',', '"', '\n', '\r'])
        || text.starts_with(char::is_whitespace)
        || text.ends_with(char::is_whitespace);
    if needs_quotes {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

/// Keeps a cell inside its Markdown table column.
fn markdown_cell(text: &str) -> String {
    text.replace('|', "\\|").replace(['\n', '\r'], " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_column_first_seen_in_a_later_row_stands_where_that_row_puts_it() {
        let mut table = BenchTable::new();
        table.push(BenchRow::new().with("strategy", "base").with("fixed", 1.0).with("chain", 2.0));
        let full = BenchRow::new().with("strategy", "b").with("fixed", 1.0).with("fixed_verdict", "cost");
        table.push(full.with("chain", 2.0).with("note", "x"));
        table.push(BenchRow::new().with("lead", 0.0).with("strategy", "c"));
        assert_eq!(table.columns(), ["strategy", "fixed", "fixed_verdict", "chain", "note", "lead"]);
    }

    #[test]
    fn a_timing_has_its_interval_only_from_six_runs_and_a_cost_within_noise_has_no_value() {
        let six = Timings { rounds: [3.0, 1.0, 2.0, 6.0, 5.0, 4.0].map(Some).to_vec(), last: () };
        let mut row = BenchRow::new();
        row.set_timing("ms", &six);
        assert_eq!((row.get_f64("ms"), row.get_f64("ms_lo"), row.get_f64("ms_hi")), (Some(3.5), Some(1.0), Some(6.0)));
        let two = Timings { rounds: vec![Some(1.0), Some(3.0)], last: () };
        let mut row = BenchRow::new();
        row.set_timing("ms", &two);
        assert_eq!((row.get_f64("ms"), row.get("ms_lo")), (Some(2.0), None));
        let mut row = BenchRow::new();
        row.set_cost("step", Some(Estimate { value: -0.5, lo: -2.0, hi: 1.0, n: 6 }));
        assert_eq!(row.get("step"), None, "no value for a difference within noise");
        assert_eq!((row.get_f64("step_lo"), row.text("step_verdict")), (Some(-2.0), "within noise".to_string()));
        row.set_cost("cost", Some(Estimate { value: 2.0, lo: 1.0, hi: 3.0, n: 6 }));
        assert_eq!((row.get_f64("cost"), row.text("cost_verdict")), (Some(2.0), "cost".to_string()));
    }

    #[test]
    fn readable_numbers_keep_four_significant_digits() {
        assert_eq!(format_readable_number(12.5), "12.5");
        assert_eq!(format_readable_number(12.0), "12");
        assert_eq!(format_readable_number(12.34567), "12.35");
        assert_eq!(format_readable_number(0.00123456), "0.001235");
        assert_eq!(format_readable_number(123456.7), "123457");
        assert_eq!(format_readable_number(-0.5), "-0.5");
        assert_eq!(format_readable_number(1.5e-7), "1.5e-7");
        assert_eq!(format_readable_number(2.0e9), "2e9");
        assert_eq!(format_readable_number(0.0), "0");
        assert_eq!(format_readable_number(f64::NAN), "NaN");
        assert_eq!(format_readable_number(f64::NEG_INFINITY), "-inf");
    }

    #[test]
    fn setting_a_key_again_keeps_its_position() {
        let mut row = BenchRow::new();
        row.set("a", 1).set("b", 2.5).set("a", "x");
        let keys: Vec<&str> = row.keys().collect();
        assert_eq!(keys, ["a", "b"]);
        assert_eq!(row.get("a"), Some(&BenchValue::Text("x".into())));
    }

    #[test]
    fn csv_fields_are_quoted_only_when_needed() {
        assert_eq!(csv_field("plain"), "plain");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(csv_field("two\nlines"), "\"two\nlines\"");
        assert_eq!(csv_field(" padded"), "\" padded\"");
        assert_eq!(csv_field(""), "\"\"");
    }

    #[test]
    fn huge_unsigned_counts_become_floats() {
        assert_eq!(BenchValue::from(7_u64), BenchValue::Int(7));
        assert_eq!(BenchValue::from(u64::MAX), BenchValue::Float(u64::MAX as f64));
    }
}
