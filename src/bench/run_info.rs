//! What produced a bench result: the device and driver, the host, the build,
//! the inputs and the date. Every bench output carries it (JSON `run`
//! object, `#` comment lines before a CSV header, a Markdown header block, a
//! chart caption), so a lavapipe run from CI and a run on a desk GPU can be
//! put side by side and told apart.

use crate::vk::Context;
use serde::{Deserialize, Serialize};

/// The git commit this binary was built from (`build.rs`), `-dirty` where the
/// tracked files differed from it; `unknown` outside a git checkout.
pub const GIT_COMMIT: &str = env!("SWEEPLAB_GIT_COMMIT");

/// Everything a reader needs to know where a figure came from.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RunInfo {
    pub device: String,
    pub device_type: String,
    pub vendor_id: String,
    pub device_id: String,
    pub driver_name: String,
    pub driver_info: String,
    pub driver_version: String,
    pub api_version: String,
    pub timestamp_period_ns: f64,
    pub timestamp_valid_bits: u32,
    /// The validation layer's version where validation was on (empty where off).
    #[serde(default)]
    pub validation_layer: String,
    pub host_cpu: String,
    pub host_cores: usize,
    /// The host's load averages over 1, 5 and 15 minutes as the run began
    /// (empty where /proc/loadavg is not there).
    #[serde(default)]
    pub host_load: Vec<f64>,
    pub sweeplab_version: String,
    pub git_commit: String,
    /// UTC, ISO 8601.
    pub date: String,
    /// The command line, as given.
    pub command: String,
    /// The inputs that shaped the result (scene or volume, sizes, rounds, ...),
    /// in the order the bench set them.
    pub inputs: Vec<(String, String)>,
    /// Set on the rows a run saves while it measures (`OutFolder::save_rows`):
    /// what is partial about them. The final report has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub partial: Option<String>,
}

impl RunInfo {
    /// The device of `ctx`, this host and build, now, and the command line.
    pub fn collect(ctx: &Context) -> RunInfo {
        let i = &ctx.info;
        RunInfo {
            device: i.name.clone(),
            device_type: i.device_type.clone(),
            vendor_id: format!("0x{:04x}", i.vendor_id),
            device_id: format!("0x{:04x}", i.device_id),
            driver_name: i.driver_name.clone(),
            driver_info: i.driver_info.clone(),
            driver_version: i.driver_version.clone(),
            api_version: i.api_version.clone(),
            timestamp_period_ns: f64::from(i.timestamp_period_ns),
            timestamp_valid_bits: i.timestamp_valid_bits,
            validation_layer: ctx.validation_layer.clone().filter(|_| ctx.validation_enabled()).unwrap_or_default(),
            ..RunInfo::host()
        }
    }

    /// This host and build, now, and the command line; no device.
    pub fn host() -> RunInfo {
        RunInfo {
            host_cpu: host_cpu_model(),
            host_cores: std::thread::available_parallelism().map(|n| n.get()).unwrap_or(0),
            host_load: std::fs::read_to_string("/proc/loadavg").map(|t| load_averages(&t)).unwrap_or_default(),
            sweeplab_version: env!("CARGO_PKG_VERSION").to_string(),
            git_commit: GIT_COMMIT.to_string(),
            date: utc_now_iso8601(),
            command: std::env::args().collect::<Vec<_>>().join(" "),
            ..RunInfo::default()
        }
    }

    /// Adds an input (`volume`, `sizes`, `rounds`, ...).
    pub fn input(mut self, key: &str, value: impl ToString) -> RunInfo {
        self.inputs.push((key.to_string(), value.to_string()));
        self
    }

    /// `(key, value)` lines in a fixed order: the device first, then host,
    /// build, date, command and inputs.
    pub fn lines(&self) -> Vec<(String, String)> {
        let mut out: Vec<(String, String)> = [
            ("device", self.device.clone()),
            ("device_type", self.device_type.clone()),
            ("vendor_id", self.vendor_id.clone()),
            ("device_id", self.device_id.clone()),
            ("driver", format!("{} ({})", self.driver_name, self.driver_info)),
            ("driver_version", self.driver_version.clone()),
            ("api_version", self.api_version.clone()),
            ("timestamp_period_ns", self.timestamp_period_ns.to_string()),
            ("timestamp_valid_bits", self.timestamp_valid_bits.to_string()),
            (
                "validation_layer",
                if self.validation_layer.is_empty() { "off".into() } else { self.validation_layer.clone() },
            ),
            ("host_cpu", format!("{} ({} cores)", self.host_cpu, self.host_cores)),
            ("host_load", self.host_load_text()),
            ("sweeplab", format!("{} at {}", self.sweeplab_version, self.git_commit)),
            ("date", self.date.clone()),
            ("command", self.command.clone()),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        if let Some(partial) = &self.partial {
            out.insert(0, ("partial".to_string(), partial.clone()));
        }
        out.extend(self.inputs.iter().cloned());
        out
    }

    /// The load averages as `1 min, 5 min, 15 min`, or `unknown`.
    pub fn host_load_text(&self) -> String {
        match self.host_load.as_slice() {
            [one, five, fifteen] => format!("{one:.2}, {five:.2}, {fifteen:.2} (1, 5, 15 min, at the start)"),
            _ => "unknown".to_string(),
        }
    }

    /// A note where a CPU device (lavapipe) ran on a host whose last minute's
    /// load exceeds its cores: there a frame's time includes waiting for a
    /// core, and frames of different lengths wait differently (a burst shorter
    /// than the scheduler's slice runs at full speed, a longer one shares the
    /// cores), so ratios between them move too (docs/sync-study.md, the calibration).
    pub fn load_note(&self) -> Option<String> {
        let one = *self.host_load.first()?;
        (self.device_type == "CPU" && self.host_cores > 0 && one > self.host_cores as f64).then(|| {
            format!(
                "note: the host's load average over the last minute is {one:.2} on {} cores: on a CPU device \
                 these times include waiting for a core, and frames of different lengths wait differently",
                self.host_cores
            )
        })
    }

    /// One line for a chart caption: device, driver, commit, date.
    pub fn caption(&self) -> String {
        let driver = if self.driver_info.is_empty() { &self.driver_version } else { &self.driver_info };
        format!(
            "{}, {} {}, sweeplab {} at {}, {}",
            self.device, self.driver_name, driver, self.sweeplab_version, self.git_commit, self.date
        )
    }

    /// `# key: value` lines to stand before a CSV header.
    pub fn csv_comment(&self) -> String {
        self.lines().iter().map(|(k, v)| format!("# {k}: {}\n", v.replace('\n', " "))).collect()
    }

    /// A Markdown block: one bullet per line, to stand above a table.
    pub fn markdown(&self) -> String {
        let mut out = String::from("Run:\n\n");
        for (k, v) in self.lines() {
            out.push_str(&format!("- {k}: `{}`\n", v.replace('`', "'")));
        }
        out.push('\n');
        out
    }
}

/// The three load averages of /proc/loadavg's text (empty if it does not parse).
fn load_averages(text: &str) -> Vec<f64> {
    let loads: Option<Vec<f64>> = text.split_whitespace().take(3).map(|w| w.parse().ok()).collect();
    loads.filter(|l| l.len() == 3).unwrap_or_default()
}

/// The first `model name` of /proc/cpuinfo; `unknown` elsewhere.
fn host_cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|text| {
            text.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".to_string())
}

/// Now, as `YYYY-MM-DDThh:mm:ssZ`.
pub fn utc_now_iso8601() -> String {
    let secs = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_secs()).unwrap_or(0);
    iso8601_from_unix(secs)
}

/// Seconds since 1970 as a UTC date and time (days to civil date by Howard
/// Hinnant's algorithm, valid for every date after 1970).
pub fn iso8601_from_unix(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z", rem / 3600, rem % 3600 / 60, rem % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_are_utc_iso8601() {
        assert_eq!(iso8601_from_unix(0), "1970-01-01T00:00:00Z");
        assert_eq!(iso8601_from_unix(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(iso8601_from_unix(1_796_083_199), "2026-11-30T23:59:59Z");
        assert!(utc_now_iso8601().starts_with("20"));
    }

    #[test]
    fn every_line_is_in_the_csv_comment_and_the_markdown() {
        let info = RunInfo { device: "fake GPU".into(), ..RunInfo::host() }.input("volume", "engine.vti");
        let csv = info.csv_comment();
        let md = info.markdown();
        for (key, _) in info.lines() {
            assert!(csv.contains(&format!("# {key}: ")), "{key} in {csv}");
            assert!(md.contains(&format!("- {key}: ")), "{key} in {md}");
        }
        assert!(csv.contains("# volume: engine.vti") && csv.contains("# device: fake GPU"));
        assert!(!info.git_commit.is_empty() && info.host_cores > 0);
    }

    #[test]
    fn the_load_is_read_and_a_loaded_host_noted_for_a_cpu_device_only() {
        assert_eq!(load_averages("3.10 2.05 1.00 4/321 12345\n"), vec![3.10, 2.05, 1.00]);
        assert!(load_averages("").is_empty() && load_averages("1.0 x 2.0").is_empty());
        let info = |device_type: &str, load: f64| RunInfo {
            device_type: device_type.into(),
            host_cores: 2,
            host_load: vec![load, 1.0, 1.0],
            ..RunInfo::default()
        };
        let note = info("CPU", 3.1).load_note().expect("a loaded host is noted");
        assert!(note.contains("3.10 on 2 cores"), "{note}");
        assert!(info("CPU", 1.9).load_note().is_none() && info("discrete GPU", 9.0).load_note().is_none());
        assert!(RunInfo::default().load_note().is_none());
        assert!(info("CPU", 3.1).lines().iter().any(|(k, v)| k == "host_load" && v.starts_with("3.10, 1.00, 1.00")));
        assert_eq!(RunInfo::default().host_load_text(), "unknown");
    }
}
