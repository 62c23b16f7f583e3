//! One frame per strategy and workload with a timestamp around every line,
//! written as a Perfetto (Chrome trace-event) file `trace_<workload>_<strategy>.json`:
//! the frame's passes and its lines as slices on tracks by nesting depth, the
//! gaps between lines where nothing is drawn. Beside it in the report, the
//! frame's line and gap times (median, quartiles, every gap for the histogram).
//!
//! A trace is one frame and a picture, not an estimate: where the device
//! serializes lines around timestamps (the per-line timestamps' effect in the
//! verdict says whether it does), its lines show one after another whatever
//! the strategy, and the frame is longer than one without timestamps.

use super::{ConfigKey, Workload};
use crate::bench::estimate::{median_of, quartiles};
use crate::bench::run_info::RunInfo;
use crate::vk::ProfileReport;
use serde::{Deserialize, Serialize};

/// What one traced frame showed.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TraceSummary {
    pub workload: Workload,
    pub strategy: String,
    /// The trace file, beside sync.json.
    pub file: String,
    pub line_width: u32,
    pub chain_trips: u32,
    /// Timed lines in the frame.
    pub lines: u32,
    /// The frame's GPU time (with its timestamps), ms.
    pub frame_ms: f64,
    pub line_median_us: f64,
    pub gap_median_us: f64,
    pub gap_q1_us: f64,
    pub gap_q3_us: f64,
    /// Every gap between consecutive lines of one pass, us.
    pub gaps_us: Vec<f64>,
}

/// `trace_<workload>_<strategy>.json`.
pub fn file_name(workload: Workload, strategy: &str) -> String {
    format!("trace_{}_{strategy}.json", workload.name())
}

/// The summary of one traced frame of `key` (its lines are the scopes named
/// `line_scope`) and its trace: the profiler's trace events, a name per
/// track, and in `otherData` the run and what was traced.
pub fn trace(
    profile: &ProfileReport,
    line_scope: &str,
    run: &RunInfo,
    key: &ConfigKey,
) -> (TraceSummary, serde_json::Value) {
    let timeline = profile.timeline(line_scope);
    let mut lines = timeline.durations_us.clone();
    lines.sort_by(f64::total_cmp);
    let mut gaps = timeline.gaps_us.clone();
    gaps.sort_by(f64::total_cmp);
    let (q1, q3) = quartiles(&gaps);
    let strategy = key.arm.name();
    let summary = TraceSummary {
        workload: key.workload,
        strategy: strategy.to_string(),
        file: file_name(key.workload, strategy),
        line_width: key.line_width,
        chain_trips: key.chain_trips,
        lines: timeline.count,
        frame_ms: profile.gpu_ms_total,
        line_median_us: median_of(&lines),
        gap_median_us: median_of(&gaps),
        gap_q1_us: q1,
        gap_q3_us: q3,
        gaps_us: timeline.gaps_us,
    };
    let mut json = profile.chrome_trace();
    let depths: std::collections::BTreeSet<u32> = profile.scopes.iter().map(|s| s.depth).collect();
    let line_depth = profile.scopes.iter().find(|s| s.name == line_scope).map(|s| s.depth);
    if let Some(events) = json["traceEvents"].as_array_mut() {
        for d in depths {
            let name = if Some(d) == line_depth { "lines".to_string() } else { format!("passes, depth {d}") };
            events.push(serde_json::json!({
                "name": "thread_name", "ph": "M", "pid": 1, "tid": d, "args": {"name": name}
            }));
        }
    }
    json["otherData"]["run"] = serde_json::to_value(run).unwrap_or_default();
    json["otherData"]["workload"] = key.workload.name().into();
    json["otherData"]["strategy"] = strategy.into();
    json["otherData"]["line_width"] = key.line_width.into();
    json["otherData"]["chain_trips"] = key.chain_trips.into();
    json["otherData"]["lines"] = format!(
        "one frame with a timestamp around every line ({line_scope}); gaps between line slices are the \
         boundaries; docs/sync-study.md says how to read it"
    )
    .into();
    (summary, json)
}
