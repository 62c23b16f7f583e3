//! What a run's validation messages amount to: best-practices advice is
//! counted per message id (advice, not a failure); anything else fails the run.

use std::collections::BTreeMap;

/// The messages of a run, sorted into advice and failures.
#[derive(Debug, Default, PartialEq, Eq)]
pub struct ValidationVerdict {
    pub messages: Vec<String>,
    /// Best-practices message id -> how often it came.
    pub advice: BTreeMap<String, usize>,
    /// Messages that are not best-practices advice.
    pub failures: usize,
}

impl ValidationVerdict {
    pub fn of(messages: Vec<String>) -> ValidationVerdict {
        let mut advice = BTreeMap::new();
        let mut failures = 0;
        for m in &messages {
            if m.contains("BestPractices") {
                // The layer writes the id as `[ BestPractices-... ]`.
                let id = m.split("[ ").nth(1).and_then(|r| r.split(' ').next()).unwrap_or("?");
                *advice.entry(id.to_string()).or_default() += 1;
            } else {
                failures += 1;
            }
        }
        ValidationVerdict { messages, advice, failures }
    }

    pub fn failed(&self) -> bool {
        self.failures > 0
    }

    /// What stderr shows: every message, then the advice counted per id;
    /// `validation: clean` where there is nothing and validation was on.
    pub fn report_lines(&self, validation_enabled: bool) -> Vec<String> {
        if self.messages.is_empty() {
            return if validation_enabled { vec!["validation: clean".into()] } else { Vec::new() };
        }
        let mut lines = vec![format!("validation: {} message(s)", self.messages.len())];
        lines.extend(self.messages.iter().cloned());
        if !self.advice.is_empty() {
            lines.push(format!("best practices: {} message(s)", self.advice.values().sum::<usize>()));
            lines.extend(self.advice.iter().map(|(id, n)| format!("  {n:>5}  {id}")));
        }
        lines
    }
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
        assert_eq!(lines[0], "validation: 3 message(s)");
        assert!(lines.contains(&"best practices: 3 message(s)".to_string()), "{lines:?}");
        let hazard = ValidationVerdict::of(vec![
            advice("BestPractices-x"),
            "Validation Error: [ SYNC-HAZARD-READ-AFTER-WRITE ] ...".into(),
        ]);
        assert_eq!((hazard.failures, hazard.failed()), (1, true));
    }
}
