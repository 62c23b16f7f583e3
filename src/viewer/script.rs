//! A viewer script: what to do at which frame, so a run is reproducible
//! (tests, measurements). One step a line, `#` starts a comment:
//!
//! ```text
//! 3 set lights.0.direction=[-1, -1, 0.5]   # a scene edit, as --set takes it
//! 5 resize 96x64                            # ask the window for a new size
//! 7 key S                                   # as if the key were pressed (S, P)
//! 8 tf-point 1 0.6 0.9                      # drag transfer point 1 to scalar 0.6, opacity 0.9
//! 9 drag-light 0 12 -4                      # Ctrl-drag light 0 by 12 pixels right, 4 up
//! 10 orbit 20 -5                            # left-drag the camera 20 pixels right, 5 up
//! 11 zoom 1.5                               # turn the wheel 1.5 lines
//! 12 wait 400                               # do nothing for 400 ms (a preview settles)
//! ```

use super::error::ViewerError;

#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    Set(String),
    Resize(u32, u32),
    Key(char),
    /// The transfer-function editor's drag: point `index` to (`value`, `alpha`).
    TfPoint {
        index: usize,
        value: f32,
        alpha: f32,
    },
    /// Ctrl and the left button dragging light `index` by (`dx`, `dy`) pixels.
    DragLight {
        index: usize,
        dx: f32,
        dy: f32,
    },
    /// The left button dragging the camera by (`dx`, `dy`) pixels.
    Orbit(f32, f32),
    /// The wheel turned by this many lines.
    Zoom(f32),
    /// The user stays still this many milliseconds before the frame.
    Wait(u64),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub frame: u64,
    pub action: Action,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Script {
    pub steps: Vec<Step>,
}

const ACTIONS: [&str; 8] = ["set", "resize", "key", "tf-point", "drag-light", "orbit", "zoom", "wait"];

impl Script {
    pub fn parse(text: &str, origin: &str) -> Result<Script, ViewerError> {
        let mut steps = Vec::new();
        for (n, raw) in text.lines().enumerate() {
            let line = raw.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let at = |m: String| ViewerError::Script(format!("{origin}:{}: {m} (in `{}`)", n + 1, raw.trim()));
            let mut parts = line.splitn(3, char::is_whitespace);
            let frame = parts.next().unwrap_or("");
            let frame: u64 = frame.parse().map_err(|_| at(format!("`{frame}` is not a frame number")))?;
            let verb = parts.next().unwrap_or("");
            let rest = parts.next().unwrap_or("").trim();
            let action = match verb {
                "set" if rest.contains('=') => Action::Set(rest.to_string()),
                "set" => return Err(at("set needs KEY=VALUE".into())),
                "resize" => {
                    let (w, h) = rest.split_once('x').ok_or_else(|| at("resize needs WIDTHxHEIGHT".into()))?;
                    let size = |s: &str| s.trim().parse::<u32>().ok().filter(|&v| (1..=16384).contains(&v));
                    match (size(w), size(h)) {
                        (Some(w), Some(h)) => Action::Resize(w, h),
                        _ => return Err(at(format!("`{rest}` is not a size between 1x1 and 16384x16384"))),
                    }
                }
                "key" => match rest.to_ascii_uppercase().as_str() {
                    "S" => Action::Key('S'),
                    "P" => Action::Key('P'),
                    "H" => Action::Key('H'),
                    _ => {
                        return Err(at(format!(
                            "key `{rest}` has no action; known: S (screenshot), P (profile), H (hide or show the panel)"
                        )))
                    }
                },
                "tf-point" => match index_and_pair(rest, |v| (0.0..=1.0).contains(&v)) {
                    Some((index, value, alpha)) => Action::TfPoint { index, value, alpha },
                    None => return Err(at("tf-point needs INDEX VALUE ALPHA, value and alpha in [0, 1]".into())),
                },
                "drag-light" => match index_and_pair(rest, f32::is_finite) {
                    Some((index, dx, dy)) => Action::DragLight { index, dx, dy },
                    None => return Err(at("drag-light needs INDEX DX DY (pixels)".into())),
                },
                "orbit" => match index_and_pair(&format!("0 {rest}"), f32::is_finite) {
                    Some((_, dx, dy)) => Action::Orbit(dx, dy),
                    None => return Err(at("orbit needs DX DY (pixels)".into())),
                },
                "zoom" => match rest.parse::<f32>().ok().filter(|z| z.is_finite()) {
                    Some(lines) => Action::Zoom(lines),
                    None => return Err(at("zoom needs LINES (wheel lines)".into())),
                },
                "wait" => match rest.parse::<u64>().ok().filter(|&ms| ms <= 60_000) {
                    Some(ms) => Action::Wait(ms),
                    None => return Err(at("wait needs MILLISECONDS (0 to 60000)".into())),
                },
                other => {
                    let near = crate::scene::suggest::nearest(other, ACTIONS)
                        .map(|n| format!(" (did you mean {n}?)"))
                        .unwrap_or_default();
                    return Err(at(format!("unknown action `{other}`{near}; known: {}", ACTIONS.join(", "))));
                }
            };
            steps.push(Step { frame, action });
        }
        Ok(Script { steps })
    }

    pub fn load(path: &std::path::Path) -> Result<Script, ViewerError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| ViewerError::Script(format!("cannot read script {}: {e}", path.display())))?;
        Script::parse(&text, &path.display().to_string())
    }

    /// The steps of frame `frame`, in file order.
    pub fn at(&self, frame: u64) -> impl Iterator<Item = &Action> {
        self.steps.iter().filter(move |s| s.frame == frame).map(|s| &s.action)
    }
}

/// `INDEX X Y`, both numbers passing `ok`.
fn index_and_pair(rest: &str, ok: impl Fn(f32) -> bool) -> Option<(usize, f32, f32)> {
    let words: Vec<&str> = rest.split_whitespace().collect();
    let number = |s: &str| s.parse::<f32>().ok().filter(|&v| ok(v));
    match words[..] {
        [i, x, y] => Some((i.parse().ok()?, number(x)?, number(y)?)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_parse_and_mistakes_name_the_line_and_a_suggestion() {
        let s = Script::parse("# light moves\n2 set lights.0.intensity=3\n4 resize 96x64\n5 key s\n", "t").unwrap();
        assert_eq!(s.steps.len(), 3);
        assert_eq!(s.at(2).collect::<Vec<_>>(), vec![&Action::Set("lights.0.intensity=3".into())]);
        assert_eq!(s.at(4).next(), Some(&Action::Resize(96, 64)));
        assert_eq!(s.at(5).next(), Some(&Action::Key('S')));
        let e = Script::parse("1 resise 9x9", "t").unwrap_err().to_string();
        assert!(e.contains("t:1") && e.contains("did you mean resize?"), "{e}");
        let e = Script::parse("x set a=1", "t").unwrap_err().to_string();
        assert!(e.contains("not a frame number"), "{e}");
        assert!(Script::parse("1 resize 0x9", "t").is_err());
        assert!(Script::parse("1 set nothing", "t").is_err());
        assert!(Script::parse("1 key Q", "t").is_err());
        let s = Script::parse("3 tf-point 1 0.6 0.9", "t").unwrap();
        assert_eq!(s.at(3).next(), Some(&Action::TfPoint { index: 1, value: 0.6, alpha: 0.9 }));
        assert!(Script::parse("3 tf-point 1 1.6 0.9", "t").is_err());
        let e = Script::parse("3 tf-piont 1 0.5 0.5", "t").unwrap_err().to_string();
        assert!(e.contains("did you mean tf-point?"), "{e}");
        let s = Script::parse("4 drag-light 0 12 -4", "t").unwrap();
        assert_eq!(s.at(4).next(), Some(&Action::DragLight { index: 0, dx: 12.0, dy: -4.0 }));
        assert!(Script::parse("4 drag-light 0 12", "t").is_err());
        let s = Script::parse("5 orbit 20 -5\n6 zoom 1.5", "t").unwrap();
        assert_eq!(s.at(5).next(), Some(&Action::Orbit(20.0, -5.0)));
        assert_eq!(s.at(6).next(), Some(&Action::Zoom(1.5)));
        assert!(Script::parse("5 orbit 20", "t").is_err());
        assert!(Script::parse("6 zoom far", "t").is_err());
        assert_eq!(Script::parse("7 wait 400", "t").unwrap().at(7).next(), Some(&Action::Wait(400)));
        assert!(Script::parse("7 wait soon", "t").is_err());
    }
}
