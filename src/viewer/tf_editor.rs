//! The transfer-function editor of the panel: the control points drawn as
//! the opacity curve over the volume's histogram, each point dragged in
//! scalar and opacity, its colour edited, points added and removed. An edit is
//! proposed as the `--set` edit that replaces the points (`transfer={points=
//! [...]}`), so it passes the scene's own checks; a script moves a point with
//! the same [`move_point`] (`tf-point`).

use super::ui::UiEdit;
use crate::scene::transfer::ControlPoint;

/// Bins of the histogram drawn under the curve.
pub const HISTOGRAM_BINS: usize = 128;
/// Height of the editor's plot in points.
const PLOT_HEIGHT: f32 = 110.0;
/// Half size of a point's handle in points.
const HANDLE: f32 = 5.0;

/// `points` with point `index` moved to scalar `value` and opacity `alpha`:
/// both clamped to [0, 1], the scalar also between its neighbours (the points
/// stay sorted). `None`: there is no such point.
pub fn move_point(points: &[ControlPoint], index: usize, value: f32, alpha: f32) -> Option<Vec<ControlPoint>> {
    let mut out = points.to_vec();
    let low = if index > 0 { out.get(index - 1)?.value } else { 0.0 };
    let high = out.get(index + 1).map_or(1.0, |p| p.value);
    let p = out.get_mut(index)?;
    p.value = value.clamp(low, high);
    p.rgba[3] = alpha.clamp(0.0, 1.0);
    Some(out)
}

/// `points` with a new point at scalar `value`, coloured as the curve is there
/// (the image does not change until it is moved).
pub fn add_point(points: &[ControlPoint], value: f32) -> Vec<ControlPoint> {
    let value = value.clamp(0.0, 1.0);
    let tf = crate::scene::transfer::TransferFunction { points: points.to_vec() };
    let at = points.iter().position(|p| p.value > value).unwrap_or(points.len());
    let mut out = points.to_vec();
    out.insert(at, ControlPoint { value, rgba: tf.eval(value) });
    out
}

/// `points` without point `index`; the last point stays (a transfer function
/// needs one). `None`: nothing to remove.
pub fn remove_point(points: &[ControlPoint], index: usize) -> Option<Vec<ControlPoint>> {
    if points.len() <= 1 || index >= points.len() {
        return None;
    }
    let mut out = points.to_vec();
    out.remove(index);
    Some(out)
}

/// The `--set` edit that makes `points` the transfer function.
pub fn set_edit(points: &[ControlPoint]) -> String {
    let list: Vec<String> = points
        .iter()
        .map(|p| format!("[{}, {}, {}, {}, {}]", p.value, p.rgba[0], p.rgba[1], p.rgba[2], p.rgba[3]))
        .collect();
    format!("transfer={{points=[{}]}}", list.join(", "))
}

/// What the editor keeps between frames: the points as dragged so far (the
/// edit is proposed when the drag ends: each one uploads the scene again) and
/// the point whose colour is edited.
#[derive(Default)]
pub struct TfEditor {
    draft: Option<Vec<ControlPoint>>,
    selected: usize,
}

impl TfEditor {
    /// Draws the editor for the scene's `points` over `histogram` (counts per
    /// bin) and pushes the edit the user made, if any.
    pub fn show(&mut self, ui: &mut egui::Ui, points: &[ControlPoint], histogram: &[u64], edits: &mut Vec<UiEdit>) {
        let mut shown = self.draft.clone().unwrap_or_else(|| points.to_vec());
        self.selected = self.selected.min(shown.len().saturating_sub(1));
        let (rect, background) =
            ui.allocate_exact_size(egui::vec2(ui.available_width(), PLOT_HEIGHT), egui::Sense::click());
        let to_screen = |value: f32, alpha: f32| {
            egui::pos2(rect.left() + value * rect.width(), rect.bottom() - alpha * rect.height())
        };
        let from_screen =
            |pos: egui::Pos2| ((pos.x - rect.left()) / rect.width(), (rect.bottom() - pos.y) / rect.height());
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 2.0, egui::Color32::from_gray(25));
        // Log counts: the air's peak would flatten everything else.
        let top = histogram.iter().map(|&c| (c as f32).ln_1p()).fold(0.0, f32::max).max(1e-6);
        let bar = rect.width() / histogram.len().max(1) as f32;
        for (i, &count) in histogram.iter().enumerate() {
            let h = (count as f32).ln_1p() / top * rect.height();
            let x = rect.left() + i as f32 * bar;
            let r = egui::Rect::from_min_max(egui::pos2(x, rect.bottom() - h), egui::pos2(x + bar, rect.bottom()));
            // Light enough to read under the white curve on the dark plot.
            painter.rect_filled(r, 0.0, egui::Color32::from_gray(115));
        }
        let curve: Vec<egui::Pos2> = shown.iter().map(|p| to_screen(p.value, p.rgba[3])).collect();
        painter.add(egui::Shape::line(curve, egui::Stroke::new(1.5, egui::Color32::WHITE)));
        let mut released = false;
        for i in 0..shown.len() {
            let p = shown[i];
            let centre = to_screen(p.value, p.rgba[3]);
            let handle = egui::Rect::from_center_size(centre, egui::vec2(2.0 * HANDLE, 2.0 * HANDLE));
            let r = ui.interact(handle, ui.id().with(("tf point", i)), egui::Sense::click_and_drag());
            if r.clicked() || r.drag_started() {
                self.selected = i;
            }
            if r.dragged() {
                if let Some(pos) = r.interact_pointer_pos() {
                    let (value, alpha) = from_screen(pos);
                    if let Some(moved) = move_point(&shown, i, value, alpha) {
                        shown = moved;
                        self.draft = Some(shown.clone());
                    }
                }
            }
            released |= r.drag_stopped();
            let [red, green, blue, _] = p.rgba.map(|c| (c.clamp(0.0, 1.0) * 255.0) as u8);
            let stroke = if i == self.selected { egui::Color32::YELLOW } else { egui::Color32::GRAY };
            painter.circle(centre, HANDLE, egui::Color32::from_rgb(red, green, blue), egui::Stroke::new(1.5, stroke));
        }
        if released {
            if let Some(draft) = self.draft.take() {
                edits.push(UiEdit::Set(set_edit(&draft)));
            }
        }
        // A double click on the plot adds a point there.
        if background.double_clicked() {
            if let Some(pos) = background.interact_pointer_pos() {
                edits.push(UiEdit::Set(set_edit(&add_point(&shown, from_screen(pos).0))));
            }
        }
        ui.horizontal(|ui| {
            let Some(p) = shown.get(self.selected) else { return };
            ui.label(format!("point {} at {:.3}, alpha {:.3}", self.selected, p.value, p.rgba[3]));
            let mut rgb = [p.rgba[0], p.rgba[1], p.rgba[2]];
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                let mut recoloured = shown.clone();
                recoloured[self.selected].rgba[..3].copy_from_slice(&rgb);
                edits.push(UiEdit::Set(set_edit(&recoloured)));
            }
        });
        ui.horizontal(|ui| {
            if ui.small_button("add point").clicked() {
                // In the middle of the widest gap.
                let mut cuts: Vec<f32> = vec![0.0];
                cuts.extend(shown.iter().map(|p| p.value));
                cuts.push(1.0);
                let gap = cuts.windows(2).max_by(|a, b| (a[1] - a[0]).total_cmp(&(b[1] - b[0])));
                let value = gap.map_or(0.5, |g| (g[0] + g[1]) / 2.0);
                edits.push(UiEdit::Set(set_edit(&add_point(&shown, value))));
            }
            if ui.small_button("remove point").clicked() {
                if let Some(fewer) = remove_point(&shown, self.selected) {
                    edits.push(UiEdit::Set(set_edit(&fewer)));
                }
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::live_scene::{LiveScene, SceneSource};

    fn point(value: f32, alpha: f32) -> ControlPoint {
        ControlPoint { value, rgba: [0.5, 0.25, 1.0, alpha] }
    }

    #[test]
    fn a_moved_point_stays_between_its_neighbours_and_in_the_unit_square() {
        let points = [point(0.0, 0.0), point(0.5, 0.5), point(0.8, 1.0)];
        let moved = move_point(&points, 1, 0.9, 1.5).unwrap();
        assert_eq!((moved[1].value, moved[1].rgba[3]), (0.8, 1.0));
        let moved = move_point(&points, 1, 0.3, -0.2).unwrap();
        assert_eq!((moved[1].value, moved[1].rgba[3]), (0.3, 0.0));
        assert_eq!(moved[1].rgba[..3], points[1].rgba[..3], "the colour stays");
        assert!(move_point(&points, 3, 0.5, 0.5).is_none());
    }

    #[test]
    fn added_points_keep_the_curve_and_the_last_point_cannot_be_removed() {
        let points = [point(0.0, 0.0), point(1.0, 1.0)];
        let more = add_point(&points, 0.25);
        assert_eq!(more.len(), 3);
        assert_eq!((more[1].value, more[1].rgba[3]), (0.25, 0.25), "on the curve");
        assert_eq!(remove_point(&more, 1).unwrap(), points.to_vec());
        assert!(remove_point(&[point(0.5, 0.5)], 0).is_none());
    }

    #[test]
    fn the_edit_is_a_set_the_scene_accepts_and_reads_back() {
        let mut live = LiveScene::load(SceneSource::Default, &["volume.size=8".to_string()]).unwrap();
        let points = move_point(&live.scene.transfer.points, 1, 0.6, 0.7).unwrap();
        live.set(&set_edit(&points)).unwrap();
        assert_eq!(live.scene.transfer.points, points);
    }
}
