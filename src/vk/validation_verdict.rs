//! What a run's validation messages amount to: best-practices advice is
//! counted per message id (advice, not a failure); anything else fails the run.
//! A layer that does not know an enabled extension fails it too, and says so
//! by name: the layer is older than the driver, which no test on one machine
//! would catch (`super::layer_extensions` keeps such extensions out).

use crate::plural::count;
use std::collections::BTreeMap;

/// The messages of a run, sorted into advice and failures.
#[derive(Debug, Default, PartialEq, Eq)]
pub struct ValidationVerdict {
    pub messages: Vec<String>,
    /// Best-practices message id -> how often it came.
    pub advice: BTreeMap<String, usize>,
    /// Messages that are not best-practices advice.
    pub failures: usize,
    /// Extensions the layer said it does not know (among the failures).
    pub unknown_extensions: Vec<String>,
}

impl ValidationVerdict {
    pub fn of(messages: Vec<String>) -> ValidationVerdict {
        let mut advice = BTreeMap::new();
        let mut failures = 0;
        let mut unknown_extensions: Vec<String> = Vec::new();
        for m in &messages {
            if let Some(name) = super::layer_extensions::unknown_extension_in(m) {
                if !unknown_extensions.iter().any(|n| n == name) {
                    unknown_extensions.push(name.to_string());
                }
            }
            if is_advice(m) {
                let id = message_id(m).unwrap_or("?");
                *advice.entry(id.to_string()).or_default() += 1;
            } else {
                failures += 1;
            }
        }
        ValidationVerdict { messages, advice, failures, unknown_extensions }
    }

    pub fn failed(&self) -> bool {
        self.failures > 0
    }

    /// What stderr shows: the failures grouped by message id, each with its
    /// count and its first message as the example (a racy frame repeats one
    /// hazard hundreds of times), then the advice counted per id;
    /// `validation: clean` where there is nothing and validation was on.
    pub fn report_lines(&self, validation_enabled: bool) -> Vec<String> {
        if self.messages.is_empty() {
            return if validation_enabled { vec!["validation: clean".into()] } else { Vec::new() };
        }
        let mut lines = vec![format!("validation: {}", count(self.messages.len() as u64, "message", "messages"))];
        // In the order each id first came.
        let mut groups: Vec<(&str, usize, &str)> = Vec::new();
        for m in self.messages.iter().filter(|m| !is_advice(m)) {
            let id = message_id(m).unwrap_or(m);
            match groups.iter_mut().find(|(g, _, _)| *g == id) {
                Some(group) => group.1 += 1,
                None => groups.push((id, 1, m)),
            }
        }
        if !groups.is_empty() {
            lines.push(format!(
                "{} in {}, by message id (count, id, first message):",
                count(self.failures as u64, "failure", "failures"),
                count(groups.len() as u64, "kind", "kinds")
            ));
            for (id, n, example) in groups {
                lines.push(format!("  {n:>5}  {id}"));
                lines.push(format!("         e.g. {example}"));
            }
        }
        if !self.advice.is_empty() {
            let advice = self.advice.values().sum::<usize>() as u64;
            lines.push(format!("best practices: {}", count(advice, "message", "messages")));
            lines.extend(self.advice.iter().map(|(id, n)| format!("  {n:>5}  {id}")));
        }
        if !self.unknown_extensions.is_empty() {
            lines.push(format!(
                "validation: the layer does not know {}, which the device enabled: the layer is older than \
                 the driver, and its checks may miss what that extension does (add the extension to \
                 src/vk/layer_extensions.rs, which leaves such extensions out for older layers)",
                self.unknown_extensions.join(", ")
            ));
        }
        lines
    }
}

/// Best-practices advice, not a failure.
fn is_advice(message: &str) -> bool {
    message.contains("BestPractices")
}

/// The layer's message id, which it writes as `[ ID ]`
/// (`SYNC-HAZARD-READ-AFTER-WRITE`, `VUID-vkCmdDispatch-None-02699`).
fn message_id(message: &str) -> Option<&str> {
    let (_, rest) = message.split_once("[ ")?;
    let (id, _) = rest.split_once(" ]")?;
    Some(id.trim()).filter(|id| !id.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn advice_is_counted_and_anything_else_fails() {
        let clean = ValidationVerdict::of(Vec::new());
        assert!(!clean.failed());
        assert_eq!(clean.report_lines(true), ["validation: clean"]);
        assert!(clean.report_lines(false).is_empty());
        let advice = |id: &str| format!("Validation Performance Warning: [ {id} ] | MessageID = 0x1 | ...");
        let v = ValidationVerdict::of(vec![
            advice("BestPractices-vkCreateDevice-deprecated"),
            advice("BestPractices-vkCreateDevice-deprecated"),
            advice("BestPractices-NVIDIA-CreatePipelineLayout"),
        ]);
        assert!(!v.failed(), "advice alone does not fail a run");
        assert_eq!(v.advice["BestPractices-vkCreateDevice-deprecated"], 2);
        let lines = v.report_lines(true);
        assert_eq!(lines[0], "validation: 3 messages");
        assert!(lines.contains(&"best practices: 3 messages".to_string()), "{lines:?}");
        let hazard = ValidationVerdict::of(vec![
            advice("BestPractices-x"),
            "Validation Error: [ SYNC-HAZARD-READ-AFTER-WRITE ] ...".into(),
        ]);
        assert_eq!((hazard.failures, hazard.failed()), (1, true));
        assert!(hazard.unknown_extensions.is_empty());
    }

    /// The H200 run's one message: a layer older than the driver's extension.
    /// It fails the run, and the report names it as that, not as an error of
    /// the engine's own.
    #[test]
    fn a_layer_that_does_not_know_an_extension_fails_the_run_and_says_why() {
        let message = "[WARNING VALIDATION] Validation Warning: [ VUID_Undefined ] Object 0: handle = 0x1, type = \
                       VK_OBJECT_TYPE_DEVICE; | MessageID = 0x79de34d4 | Device Extension \
                       VK_KHR_calibrated_timestamps is not supported by this layer.  Using this extension may \
                       adversely affect validation results and/or produce undefined behavior.";
        let v = ValidationVerdict::of(vec![message.into()]);
        assert!(v.failed(), "never passed over in silence");
        assert_eq!(v.unknown_extensions, ["VK_KHR_calibrated_timestamps"]);
        let lines = v.report_lines(true);
        let named = lines.iter().find(|l| l.contains("the layer does not know VK_KHR_calibrated_timestamps"));
        assert!(named.is_some_and(|l| l.contains("older than the driver")), "{lines:?}");
    }

    #[test]
    fn failures_are_grouped_by_message_id_with_a_count_and_one_example() {
        let hazard =
            |n: usize| format!("[ERROR VALIDATION] Validation Error: [ SYNC-HAZARD-READ-AFTER-WRITE ] line {n}");
        let mut messages: Vec<String> = (0..768).map(hazard).collect();
        messages.insert(3, "[ERROR VALIDATION] Validation Error: [ VUID-vkCmdDispatch-None-02699 ] unbound".into());
        let lines = ValidationVerdict::of(messages).report_lines(true);
        assert_eq!(
            lines,
            [
                "validation: 769 messages",
                "769 failures in 2 kinds, by message id (count, id, first message):",
                "    768  SYNC-HAZARD-READ-AFTER-WRITE",
                &format!("         e.g. {}", hazard(0)),
                "      1  VUID-vkCmdDispatch-None-02699",
                "         e.g. [ERROR VALIDATION] Validation Error: [ VUID-vkCmdDispatch-None-02699 ] unbound",
            ]
        );
        let one = ValidationVerdict::of(vec![hazard(7)]).report_lines(true);
        assert_eq!(
            one[..2],
            ["validation: 1 message", "1 failure in 1 kind, by message id (count, id, first message):"]
        );
    }
}
