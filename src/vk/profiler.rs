//! Timestamp-query profiler: named, nestable scopes. Each scope is also a
//! debug-utils label of the same name, so RenderDoc/Nsight and our reports speak
//! the same words. Where the queue has no timestamps, labels are still written and
//! the report says timestamps are unsupported instead of printing zeros.

use super::calibration::Calibrator;
use super::commands::Recorder;
use super::context::Context;
use super::error::{VkError, VkResultExt};
use ash::vk;
use serde::Serialize;
use std::collections::BTreeMap;

/// GPU duration in nanoseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd, Serialize)]
pub struct Nanos(pub f64);

impl Nanos {
    pub fn ms(self) -> f64 {
        self.0 * 1e-6
    }
}

/// Proof that a scope was opened; `end` must get it back in LIFO order.
#[must_use = "a profiler scope must be ended"]
#[derive(Debug)]
pub struct ScopeToken {
    index: usize,
}

struct OpenScope {
    name: String,
    parent: Option<usize>,
    depth: u32,
    begin_query: Option<u32>,
    end_query: Option<u32>,
    /// Scopes marked `detail` are only recorded when per-dispatch detail is on.
    detail: bool,
    /// The recorder's dispatch and transfer counts at the begin timestamp.
    dispatches_at_begin: u32,
    transfers_at_begin: u32,
}

pub struct Profiler {
    pool: vk::QueryPool,
    capacity: u32,
    next_query: u32,
    /// Queries from 0 that a fresh pool has never had reset (all of them
    /// before the first reset, none after); the frame's own are 0..next_query.
    never_reset: u32,
    scopes: Vec<OpenScope>,
    stack: Vec<usize>,
    timestamps: bool,
    detail: bool,
    period_ns: f64,
    valid_mask: u64,
    device: ash::Device,
    device_name: String,
    /// See [`Profiler::set_flush_after_timestamps`].
    flush_after_timestamps: bool,
    calibrator: Option<std::sync::Arc<Calibrator>>,
}

/// One timed scope of the last frame.
#[derive(Clone, Debug, Serialize)]
pub struct ScopeTiming {
    pub name: String,
    /// Names from the root down to this scope, joined with '/'.
    pub path: String,
    pub depth: u32,
    pub parent: Option<usize>,
    pub start_ns: f64,
    pub duration_ns: f64,
}

/// Per-pass totals: scopes with the same path summed.
#[derive(Clone, Debug, Serialize)]
pub struct PassTiming {
    pub name: String,
    pub path: String,
    pub depth: u32,
    pub gpu_ms: f64,
    pub count: u32,
}

#[derive(Clone, Debug, Serialize)]
pub struct ProfileReport {
    pub device: String,
    pub timestamps_supported: bool,
    /// Sum of the root scopes.
    pub gpu_ms_total: f64,
    /// Peak device-local memory held by resources during the run.
    pub gpu_memory_bytes: u64,
    pub passes: Vec<PassTiming>,
    pub scopes: Vec<ScopeTiming>,
    /// The host's `CLOCK_MONOTONIC` (ns) at the frame's first timestamp, from
    /// calibrated timestamps; `None` where the device has none.
    pub host_origin_ns: Option<f64>,
}

impl Profiler {
    /// The scopes per frame the commands' profilers hold: a scope around every
    /// line dispatch of the largest frame and every view chunk at tiny steps.
    pub const FRAME_CAPACITY: u32 = 65_536;

    /// A profiler for up to `capacity` scopes per frame.
    pub fn new(ctx: &Context, capacity: u32) -> Result<Profiler, VkError> {
        let timestamps = ctx.timestamps_supported();
        let queries = capacity.max(1) * 2;
        let pool = if timestamps {
            let info = vk::QueryPoolCreateInfo::default().query_type(vk::QueryType::TIMESTAMP).query_count(queries);
            // SAFETY: valid device and create info.
            let pool = unsafe { ctx.device.create_query_pool(&info, None) }.call("vkCreateQueryPool")?;
            ctx.set_name(pool, "profiler timestamps");
            pool
        } else {
            vk::QueryPool::null()
        };
        let bits = ctx.info.timestamp_valid_bits;
        let valid_mask = if bits >= 64 { u64::MAX } else { (1u64 << bits) - 1 };
        let mut p = Profiler {
            pool,
            capacity: queries,
            next_query: 0,
            never_reset: queries,
            scopes: Vec::new(),
            stack: Vec::new(),
            timestamps,
            detail: false,
            period_ns: ctx.info.timestamp_period_ns as f64,
            valid_mask,
            device: ctx.device.clone(),
            device_name: ctx.info.name.clone(),
            flush_after_timestamps: false,
            calibrator: ctx.calibrator.clone(),
        };
        p.reset();
        Ok(p)
    }

    /// Per-dispatch (per-line) scopes on or off.
    pub fn set_detail(&mut self, on: bool) {
        self.detail = on;
    }

    pub fn detail(&self) -> bool {
        self.detail
    }

    /// An empty pipeline barrier after each timestamp, for command buffers
    /// that also draw (the viewer's panel). Lavapipe bins a timestamp into the
    /// rasterizer's tiles while a framebuffer is bound (and the panel's stays
    /// bound into the next frame), so it is written at the next flush, not
    /// when the commands before it are done: compute passes then read as
    /// near zero. A barrier is a flush there, and nothing elsewhere.
    pub fn set_flush_after_timestamps(&mut self, on: bool) {
        self.flush_after_timestamps = on;
    }

    pub fn timestamps_supported(&self) -> bool {
        self.timestamps
    }

    /// Clears the scopes and resets the queries on the host (hostQueryReset);
    /// call before recording a frame. Only the queries the last frame wrote
    /// (the whole pool the first time): the validation layer's host reset
    /// costs per query, and all 131,072 of [`Profiler::FRAME_CAPACITY`] made
    /// a validated `bench sync` spend two thirds of its time in it.
    pub fn reset(&mut self) {
        let written = self.next_query.max(std::mem::take(&mut self.never_reset));
        self.scopes.clear();
        self.stack.clear();
        self.next_query = 0;
        if self.timestamps && written > 0 {
            // SAFETY: the pool's queries are not in use by pending work (frames are
            // resolved after their fence); 0..written is within the pool.
            unsafe { self.device.reset_query_pool(self.pool, 0, written) };
        }
    }

    fn write(&mut self, rec: &mut Recorder, stage: vk::PipelineStageFlags2) -> Result<Option<u32>, VkError> {
        if !self.timestamps {
            return Ok(None);
        }
        if self.next_query >= self.capacity {
            return Err(VkError::Profiler(format!(
                "more than {} timestamps in one frame; raise the profiler capacity",
                self.capacity
            )));
        }
        let q = self.next_query;
        self.next_query += 1;
        // SAFETY: q is a reset query of our pool; cb is recording. `stage` is
        // COMPUTE_SHADER around compute work (written once earlier dispatches
        // finish their compute stage) and ALL_COMMANDS around anything else
        // (waits for all earlier work): see `begin_stage` and `end_stage`.
        unsafe { self.device.cmd_write_timestamp2(rec.cb, stage, self.pool, q) };
        if self.flush_after_timestamps {
            // SAFETY: cb is recording; a dependency with no barriers orders nothing.
            unsafe { self.device.cmd_pipeline_barrier2(rec.cb, &vk::DependencyInfo::default()) };
        }
        Ok(Some(q))
    }

    /// Opens a scope: a debug label and a begin timestamp of the same name.
    pub fn begin(&mut self, rec: &mut Recorder, name: &str) -> Result<ScopeToken, VkError> {
        self.begin_scope(rec, name, false)
    }

    /// Like `begin` for per-dispatch detail: records nothing unless detail is on.
    pub fn begin_detail(&mut self, rec: &mut Recorder, name: &str) -> Result<ScopeToken, VkError> {
        self.begin_scope(rec, name, true)
    }

    fn begin_scope(&mut self, rec: &mut Recorder, name: &str, detail: bool) -> Result<ScopeToken, VkError> {
        let active = !detail || self.detail;
        let parent = self.stack.last().copied();
        let depth = self.stack.len() as u32;
        let begin_query = if active {
            rec.begin_label(name);
            self.write(rec, begin_stage(rec))?
        } else {
            None
        };
        let index = self.scopes.len();
        self.scopes.push(OpenScope {
            name: name.to_string(),
            parent,
            depth,
            begin_query,
            end_query: None,
            detail: !active,
            dispatches_at_begin: rec.dispatch_count,
            transfers_at_begin: rec.transfers(),
        });
        self.stack.push(index);
        Ok(ScopeToken { index })
    }

    pub fn end(&mut self, rec: &mut Recorder, token: ScopeToken) -> Result<(), VkError> {
        match self.stack.last() {
            Some(&top) if top == token.index => {}
            _ => {
                return Err(VkError::Profiler(format!(
                    "scope '{}' ended out of order (innermost open scope: {:?})",
                    self.scopes.get(token.index).map(|s| s.name.as_str()).unwrap_or("?"),
                    self.stack.last().map(|&i| self.scopes[i].name.clone())
                )))
            }
        }
        self.stack.pop();
        if !self.scopes[token.index].detail {
            let s = &self.scopes[token.index];
            let stage = end_stage(rec, s.dispatches_at_begin, s.transfers_at_begin);
            let q = self.write(rec, stage)?;
            self.scopes[token.index].end_query = q;
            rec.end_label();
        }
        Ok(())
    }

    /// Reads the timestamps of the frame just executed (its fence waited) and
    /// builds the report.
    pub fn resolve(&mut self, gpu_memory_bytes: u64) -> Result<ProfileReport, VkError> {
        if let Some(&open) = self.stack.last() {
            return Err(VkError::Profiler(format!("scope '{}' was never ended", self.scopes[open].name)));
        }
        let mut values = vec![0u64; self.next_query as usize];
        if self.timestamps && self.next_query > 0 {
            // SAFETY: the queries 0..next_query were written by a completed submission.
            unsafe {
                self.device.get_query_pool_results(
                    self.pool,
                    0,
                    &mut values,
                    vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
                )
            }
            .call("vkGetQueryPoolResults")?;
        }
        let origin = values.first().copied().unwrap_or(0) & self.valid_mask;
        let host_origin_ns = match &self.calibrator {
            Some(c) if self.timestamps && self.next_query > 0 => {
                let cal = c.calibrate()?;
                // Device ticks from the frame's first timestamp to the calibration
                // (within the valid bits; the calibration comes after the frame).
                let ticks = (cal.device_ticks & self.valid_mask).wrapping_sub(origin) & self.valid_mask;
                Some(cal.host_ns as f64 - ticks as f64 * self.period_ns)
            }
            _ => None,
        };
        let to_ns = |ticks: u64| ticks as f64 * self.period_ns;
        let mut scopes = Vec::new();
        let mut index_map = vec![None; self.scopes.len()];
        for (i, s) in self.scopes.iter().enumerate() {
            if s.detail {
                continue;
            }
            let (start, dur) = match (s.begin_query, s.end_query) {
                (Some(b), Some(e)) => {
                    let b = values[b as usize] & self.valid_mask;
                    let e = values[e as usize] & self.valid_mask;
                    // Wrapping subtraction in the valid bits handles one counter wrap.
                    (to_ns(b.wrapping_sub(origin) & self.valid_mask), to_ns(e.wrapping_sub(b) & self.valid_mask))
                }
                _ => (0.0, 0.0),
            };
            let parent = s.parent.and_then(|p| index_map[p]);
            let path = match parent {
                Some(p) => format!("{}/{}", scopes.get(p).map(|x: &ScopeTiming| x.path.as_str()).unwrap_or(""), s.name),
                None => s.name.clone(),
            };
            index_map[i] = Some(scopes.len());
            scopes.push(ScopeTiming {
                name: s.name.clone(),
                path,
                depth: s.depth,
                parent,
                start_ns: start,
                duration_ns: dur,
            });
        }
        let mut order: Vec<String> = Vec::new();
        let mut sums: BTreeMap<String, PassTiming> = BTreeMap::new();
        for s in &scopes {
            let e = sums.entry(s.path.clone()).or_insert_with(|| {
                order.push(s.path.clone());
                PassTiming { name: s.name.clone(), path: s.path.clone(), depth: s.depth, gpu_ms: 0.0, count: 0 }
            });
            e.gpu_ms += s.duration_ns * 1e-6;
            e.count += 1;
        }
        let passes: Vec<PassTiming> = order.iter().filter_map(|p| sums.remove(p)).collect();
        let gpu_ms_total = scopes.iter().filter(|s| s.parent.is_none()).map(|s| s.duration_ns * 1e-6).sum();
        Ok(ProfileReport {
            device: self.device_name.clone(),
            timestamps_supported: self.timestamps,
            gpu_ms_total,
            gpu_memory_bytes,
            passes,
            scopes,
            host_origin_ns,
        })
    }
}

/// A scope's begin timestamp: at the compute stage (written once earlier
/// dispatches finish computing) unless a transfer came last, which only
/// ALL_COMMANDS waits for.
fn begin_stage(rec: &Recorder) -> vk::PipelineStageFlags2 {
    if rec.last_was_transfer() {
        vk::PipelineStageFlags2::ALL_COMMANDS
    } else {
        vk::PipelineStageFlags2::COMPUTE_SHADER
    }
}

/// A scope's end timestamp: at the compute stage where the scope recorded
/// dispatches and nothing else the recorder knows of; ALL_COMMANDS otherwise
/// (copies, clears, secondaries, or commands recorded on `cb` directly).
fn end_stage(rec: &Recorder, dispatches_at_begin: u32, transfers_at_begin: u32) -> vk::PipelineStageFlags2 {
    if rec.dispatch_count > dispatches_at_begin && rec.transfers() == transfers_at_begin {
        vk::PipelineStageFlags2::COMPUTE_SHADER
    } else {
        vk::PipelineStageFlags2::ALL_COMMANDS
    }
}

impl Drop for Profiler {
    fn drop(&mut self) {
        if self.pool != vk::QueryPool::null() {
            // SAFETY: no pending work uses the pool once the profiler is dropped.
            unsafe { self.device.destroy_query_pool(self.pool, None) };
        }
    }
}

/// Repeated scopes of one name (per-line dispatches) on the GPU timeline: time
/// inside them and in the gaps between consecutive ones under the same parent
/// (the synchronization bubble: barrier, hand-off, timestamps).
#[derive(Clone, Debug, Default, Serialize)]
pub struct ScopeTimeline {
    pub count: u32,
    pub inside_ms: f64,
    pub gap_ms: f64,
    pub durations_us: Vec<f64>,
    pub gaps_us: Vec<f64>,
}

impl ProfileReport {
    /// The timeline of every scope called `name`, in start order.
    pub fn timeline(&self, name: &str) -> ScopeTimeline {
        let mut scopes: Vec<&ScopeTiming> = self.scopes.iter().filter(|s| s.name == name).collect();
        scopes.sort_by(|a, b| a.start_ns.total_cmp(&b.start_ns));
        let mut t = ScopeTimeline { count: scopes.len() as u32, ..Default::default() };
        for (i, s) in scopes.iter().enumerate() {
            t.durations_us.push(s.duration_ns * 1e-3);
            t.inside_ms += s.duration_ns * 1e-6;
            if let Some(next) = scopes.get(i + 1) {
                if next.parent == s.parent {
                    let gap = (next.start_ns - (s.start_ns + s.duration_ns)).max(0.0);
                    t.gaps_us.push(gap * 1e-3);
                    t.gap_ms += gap * 1e-6;
                }
            }
        }
        t
    }

    /// GPU time of all passes with this name (any depth), in ms.
    pub fn pass_ms(&self, name: &str) -> f64 {
        self.passes.iter().filter(|p| p.name == name).map(|p| p.gpu_ms).sum()
    }

    /// The table printed on stdout.
    pub fn table(&self) -> String {
        let mut out = String::new();
        if !self.timestamps_supported {
            out.push_str(&format!(
                "GPU profile ({}): timestamps are not supported on this queue; no GPU times measured\n",
                self.device
            ));
            return out;
        }
        out.push_str(&format!("GPU profile ({})\n", self.device));
        out.push_str(&format!("{:<44} {:>7} {:>11} {:>11} {:>7}\n", "pass", "count", "total ms", "mean ms", "%"));
        for p in &self.passes {
            let name = format!("{}{}", "  ".repeat(p.depth as usize), p.name);
            let pct = if self.gpu_ms_total > 0.0 { 100.0 * p.gpu_ms / self.gpu_ms_total } else { 0.0 };
            out.push_str(&format!(
                "{:<44} {:>7} {:>11.3} {:>11.4} {:>6.1}%\n",
                name,
                p.count,
                p.gpu_ms,
                p.gpu_ms / p.count.max(1) as f64,
                pct
            ));
        }
        out.push_str(&format!("{:<44} {:>7} {:>11.3}\n", "total", "", self.gpu_ms_total));
        out.push_str(&format!(
            "GPU memory held by resources: {:.2} MiB\n",
            self.gpu_memory_bytes as f64 / (1024.0 * 1024.0)
        ));
        out
    }

    /// JSON with `device`, `gpu_ms_total`, `gpu_memory_bytes`, `passes` and `scopes`.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
    }

    /// Chrome trace-event JSON (opens in Perfetto / chrome://tracing); one track
    /// per nesting depth.
    pub fn chrome_trace(&self) -> serde_json::Value {
        let events: Vec<serde_json::Value> = self
            .scopes
            .iter()
            .map(|s| {
                serde_json::json!({
                    "name": s.name, "cat": "gpu", "ph": "X", "pid": 1, "tid": s.depth,
                    "ts": (self.host_origin_ns.unwrap_or(0.0) + s.start_ns) / 1000.0, "dur": s.duration_ns / 1000.0,
                    "args": {"path": s.path}
                })
            })
            .collect();
        serde_json::json!({
            "displayTimeUnit": "ms",
            "otherData": {
                "device": self.device,
                "timestamps_supported": self.timestamps_supported,
                // ts is CLOCK_MONOTONIC in us where the device calibrates its
                // timestamps against it, else from the frame's first timestamp.
                "clock": if self.host_origin_ns.is_some() { "CLOCK_MONOTONIC" } else { "frame" }
            },
            "traceEvents": events
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scope(name: &str, parent: Option<usize>, start_ns: f64, duration_ns: f64) -> ScopeTiming {
        ScopeTiming {
            name: name.into(),
            path: name.into(),
            depth: parent.map_or(0, |_| 1),
            parent,
            start_ns,
            duration_ns,
        }
    }

    #[test]
    fn timeline_separates_time_inside_scopes_from_the_gaps_between_them() {
        let report = ProfileReport {
            device: "test".into(),
            timestamps_supported: true,
            gpu_ms_total: 0.0,
            gpu_memory_bytes: 0,
            passes: vec![],
            host_origin_ns: None,
            scopes: vec![
                scope("sweep", None, 0.0, 10_000.0),
                scope("line", Some(0), 1_000.0, 2_000.0),
                scope("line", Some(0), 4_000.0, 1_000.0),
                scope("line", Some(0), 8_000.0, 1_500.0),
                scope("sweep", None, 20_000.0, 5_000.0),
                // First line of another sweep: no gap counted across sweeps.
                scope("line", Some(4), 21_000.0, 1_000.0),
            ],
        };
        let t = report.timeline("line");
        assert_eq!(t.count, 4);
        assert_eq!(t.durations_us, vec![2.0, 1.0, 1.5, 1.0]);
        assert_eq!(t.gaps_us, vec![1.0, 3.0]);
        assert!((t.inside_ms - 0.0055).abs() < 1e-12 && (t.gap_ms - 0.004).abs() < 1e-12);
    }
}
