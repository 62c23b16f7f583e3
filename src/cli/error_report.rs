//! How an error reaches the terminal: the message, then each cause the message
//! does not already say. Library errors often print their source inside their
//! own message (`{path}: {source}`) and also return it from `source()`, so
//! anyhow's `{:#}` would repeat it.

/// The error and the causes not yet in the text, joined by ": ".
pub fn error_text(error: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in error.chain() {
        let message = cause.to_string();
        if text.contains(&message) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&message);
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("{path}: {source}")]
    struct Repeats {
        path: String,
        #[source]
        source: std::io::Error,
    }

    #[test]
    fn a_cause_already_in_the_message_is_printed_once() {
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "no such file");
        let e = anyhow::Error::new(Repeats { path: "a.vti".into(), source: io }).context("--volume a.vti");
        assert_eq!(format!("{e:#}"), "--volume a.vti: a.vti: no such file: no such file");
        assert_eq!(error_text(&e), "--volume a.vti: a.vti: no such file");
    }

    #[test]
    fn causes_not_in_the_message_are_kept() {
        let e = anyhow::anyhow!("inner").context("middle").context("outer");
        assert_eq!(error_text(&e), "outer: middle: inner");
    }
}
