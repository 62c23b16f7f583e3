//! The window's size and the image's place in it. The first window holds the
//! panel and the image at the size asked for (`--size`, the scene's): as wide
//! as both, and as tall as the taller of the image and the panel's content
//! (within the screen), so no setting is cut off; where the window is taller
//! than the image, the image keeps its size at the top and the rest is
//! background. Once the window is resized by anyone but the viewer (the user,
//! a script's `resize`), the image follows the window.

/// Window pixels kept free below the window on the screen (title bar, task bar).
const SCREEN_MARGIN: u32 = 80;
/// The panel's content is laid out with this much room around it.
const PANEL_MARGIN: u32 = 16;

#[derive(Debug)]
pub struct ImageArea {
    /// The image's size as asked for.
    requested: (u32, u32),
    /// The window size the viewer asked for last.
    asked: (u32, u32),
    /// The window was resized by someone else: the image takes all of it.
    follow: bool,
}

impl ImageArea {
    /// The image at `requested` beside a panel `panel_px` wide whose content
    /// is `panel_content_px` tall (0 without a panel); returns the area and
    /// the window size to ask for.
    pub fn new(requested: (u32, u32), panel_px: u32, panel_content_px: u32) -> (ImageArea, (u32, u32)) {
        let height = if panel_px > 0 { requested.1.max(panel_content_px + PANEL_MARGIN) } else { requested.1 };
        let window = (requested.0 + panel_px, height);
        (ImageArea { requested, asked: window, follow: false }, window)
    }

    /// The window has `size` now: unless the viewer asked for it, the image
    /// follows the window from now on.
    pub fn window_is(&mut self, size: (u32, u32)) {
        if size != self.asked {
            self.follow = true;
        }
    }

    /// The size the viewer asks the window for (the screen held it to less, or
    /// the panel grew).
    pub fn ask(&mut self, size: (u32, u32)) {
        self.asked = size;
    }

    /// The image's size in a window of `window` pixels with a panel `panel_px` wide.
    pub fn image(&self, window: (u32, u32), panel_px: u32) -> (u32, u32) {
        let area = (window.0.saturating_sub(panel_px).max(1), window.1.max(1));
        if self.follow {
            area
        } else {
            (self.requested.0.min(area.0), self.requested.1.min(area.1))
        }
    }

    /// A taller window where the panel's content (`panel_content_px`) no
    /// longer fits in `window` and the viewer still sizes the window; at most
    /// `screen_height` less a margin.
    pub fn grow_for_panel(
        &self,
        window: (u32, u32),
        panel_content_px: u32,
        screen_height: Option<u32>,
    ) -> Option<(u32, u32)> {
        let wanted = panel_content_px + PANEL_MARGIN;
        let most = screen_height.map_or(u32::MAX, |h| h.saturating_sub(SCREEN_MARGIN));
        let height = wanted.min(most);
        (!self.follow && height > window.1).then_some((window.0, height))
    }
}

/// `size` held within a screen `screen_height` tall (less a margin), if known.
pub fn within_screen(size: (u32, u32), screen_height: Option<u32>) -> (u32, u32) {
    match screen_height {
        Some(h) => (size.0, size.1.min(h.saturating_sub(SCREEN_MARGIN).max(1))),
        None => size,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_window_holds_the_panel_and_the_image_at_its_size() {
        // A short image beside a tall panel: the window is the panel's height,
        // the image keeps its size.
        let (area, window) = ImageArea::new((256, 256), 260, 900);
        assert_eq!(window, (516, 916));
        assert_eq!(area.image(window, 260), (256, 256));
        // A tall image: the image's height.
        let (area, window) = ImageArea::new((512, 1000), 260, 900);
        assert_eq!((window, area.image(window, 260)), ((772, 1000), (512, 1000)));
        // No panel: the image alone.
        let (area, window) = ImageArea::new((64, 48), 0, 0);
        assert_eq!((window, area.image(window, 0)), ((64, 48), (64, 48)));
    }

    #[test]
    fn once_resized_by_the_user_the_image_follows_the_window() {
        let (mut area, window) = ImageArea::new((256, 256), 260, 900);
        area.window_is(window);
        assert_eq!(area.image(window, 260), (256, 256), "the viewer's own size changes nothing");
        area.window_is((800, 600));
        assert_eq!(area.image((800, 600), 260), (540, 600));
        assert_eq!(area.grow_for_panel((800, 600), 900, None), None, "the user's size stays");
    }

    #[test]
    fn the_panel_grows_the_window_within_the_screen() {
        let (area, window) = ImageArea::new((256, 256), 260, 300);
        assert_eq!(window, (516, 316));
        assert_eq!(area.grow_for_panel(window, 250, None), None);
        assert_eq!(area.grow_for_panel(window, 600, None), Some((516, 616)));
        assert_eq!(area.grow_for_panel(window, 2000, Some(768)), Some((516, 688)));
        assert_eq!(within_screen((516, 2000), Some(768)), (516, 688));
    }
}
