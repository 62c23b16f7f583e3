//! The winit window and its events. The viewer pumps the event loop once per
//! frame (`pump_app_events`) instead of handing it control, so the frame loop
//! keeps plain borrows of the context, the scene and the technique's session.

use super::error::ViewerError;
use raw_window_handle::{HasDisplayHandle, HasWindowHandle, RawDisplayHandle, RawWindowHandle};
use std::time::Duration;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::platform::pump_events::{EventLoopExtPumpEvents, PumpStatus};
use winit::window::{Window, WindowAttributes, WindowId};

/// The event loop, or a clear error where there is no display to open.
pub fn event_loop() -> Result<EventLoop<()>, ViewerError> {
    let set = |name: &str| std::env::var(name).map(|v| !v.trim().is_empty()).unwrap_or(false);
    if !set("DISPLAY") && !set("WAYLAND_DISPLAY") {
        return Err(ViewerError::NoDisplay(
            "DISPLAY is not set; run under X11, or start a virtual one: Xvfb :99 & DISPLAY=:99 sweeplab view ..."
                .into(),
        ));
    }
    use winit::platform::x11::EventLoopBuilderExtX11;
    // Any thread: tests and embedders need not own the main thread.
    EventLoop::builder().with_any_thread(true).build().map_err(|e| {
        ViewerError::NoDisplay(format!("cannot open display {:?}: {e}", std::env::var("DISPLAY").unwrap_or_default()))
    })
}

/// The window and what happened to it since the viewer last looked.
pub struct WindowEvents {
    attributes: WindowAttributes,
    pub window: Option<Window>,
    /// The control panel's input state; events it consumes do not move the camera.
    pub egui: Option<egui_winit::State>,
    create_error: Option<String>,
    pub close_requested: bool,
    pub resized: bool,
    /// The panel saw input that changes how it looks (hover, a click).
    pub panel_input: bool,
    /// Keys pressed (physical keys, so `S` and `P` work on any layout).
    pub keys: Vec<KeyCode>,
    /// Pointer movement with the left button down (orbit), the right button
    /// down (pan), the left button and Ctrl down (drag the selected light),
    /// and wheel lines (zoom), in pixels and lines.
    pub orbit: (f64, f64),
    pub light_drag: (f64, f64),
    pub pan: (f64, f64),
    pub zoom: f32,
    cursor: Option<(f64, f64)>,
    left: bool,
    right: bool,
    ctrl: bool,
}

impl WindowEvents {
    pub fn new(title: &str, width: u32, height: u32) -> WindowEvents {
        WindowEvents {
            attributes: Window::default_attributes()
                .with_title(title)
                .with_inner_size(PhysicalSize::new(width, height))
                .with_resizable(true),
            window: None,
            egui: None,
            create_error: None,
            close_requested: false,
            resized: false,
            panel_input: false,
            keys: Vec::new(),
            orbit: (0.0, 0.0),
            light_drag: (0.0, 0.0),
            pan: (0.0, 0.0),
            zoom: 0.0,
            cursor: None,
            left: false,
            right: false,
            ctrl: false,
        }
    }

    /// Handles pending events, waiting up to `timeout` for one. Returns false
    /// when the event loop has exited.
    pub fn pump(&mut self, event_loop: &mut EventLoop<()>, timeout: Duration) -> Result<bool, ViewerError> {
        let status = event_loop.pump_app_events(Some(timeout), self);
        if let Some(e) = self.create_error.take() {
            return Err(ViewerError::Window(e));
        }
        Ok(!matches!(status, PumpStatus::Exit(_)))
    }

    /// Pumps until the window exists.
    pub fn open(&mut self, event_loop: &mut EventLoop<()>) -> Result<(), ViewerError> {
        for _ in 0..1000 {
            if self.window.is_some() {
                return Ok(());
            }
            if !self.pump(event_loop, Duration::from_millis(10))? {
                break;
            }
        }
        Err(ViewerError::Window("the window was not created".into()))
    }

    pub fn window(&self) -> Result<&Window, ViewerError> {
        self.window.as_ref().ok_or_else(|| ViewerError::Window("no window".into()))
    }

    /// The window's size in pixels (0 x 0 while minimized).
    pub fn size(&self) -> Result<(u32, u32), ViewerError> {
        let s = self.window()?.inner_size();
        Ok((s.width, s.height))
    }

    /// The screen's height in pixels, where known.
    pub fn screen_height(&self) -> Option<u32> {
        self.window.as_ref()?.current_monitor().map(|m| m.size().height)
    }

    pub fn handles(&self) -> Result<(RawDisplayHandle, RawWindowHandle), ViewerError> {
        let w = self.window()?;
        let display = w.display_handle().map_err(|e| ViewerError::Window(e.to_string()))?.as_raw();
        let window = w.window_handle().map_err(|e| ViewerError::Window(e.to_string()))?.as_raw();
        Ok((display, window))
    }
}

impl ApplicationHandler for WindowEvents {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_none() && self.create_error.is_none() {
            let mut attributes = self.attributes.clone();
            // A window taller than the screen would hide the panel's end.
            if let (Some(size), Some(screen)) = (attributes.inner_size, event_loop.primary_monitor()) {
                let size = size.to_physical::<u32>(1.0);
                let (w, h) = super::window_fit::within_screen((size.width, size.height), Some(screen.size().height));
                attributes = attributes.with_inner_size(PhysicalSize::new(w, h));
            }
            match event_loop.create_window(attributes) {
                Ok(w) => self.window = Some(w),
                Err(e) => self.create_error = Some(format!("cannot create the window: {e}")),
            }
        }
    }

    fn window_event(&mut self, _event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let consumed = match (&mut self.egui, &self.window) {
            (Some(state), Some(window)) => {
                let response = state.on_window_event(window, &event);
                self.panel_input |= response.repaint;
                response.consumed
            }
            _ => false,
        };
        match event {
            WindowEvent::CloseRequested => self.close_requested = true,
            WindowEvent::Resized(_) => self.resized = true,
            WindowEvent::KeyboardInput { event, .. } if !consumed => {
                if let (ElementState::Pressed, PhysicalKey::Code(code), false) =
                    (event.state, event.physical_key, event.repeat)
                {
                    self.keys.push(code);
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let down = state == ElementState::Pressed && !consumed;
                match button {
                    MouseButton::Left => self.left = down,
                    MouseButton::Right | MouseButton::Middle => self.right = down,
                    _ => {}
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let Some((x, y)) = self.cursor {
                    let d = (position.x - x, position.y - y);
                    if self.left && self.ctrl {
                        self.light_drag = (self.light_drag.0 + d.0, self.light_drag.1 + d.1);
                    } else if self.left {
                        self.orbit = (self.orbit.0 + d.0, self.orbit.1 + d.1);
                    } else if self.right {
                        self.pan = (self.pan.0 + d.0, self.pan.1 + d.1);
                    }
                }
                self.cursor = Some((position.x, position.y));
            }
            WindowEvent::CursorLeft { .. } => self.cursor = None,
            WindowEvent::ModifiersChanged(m) => self.ctrl = m.state().control_key(),
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                self.zoom += match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                }
            }
            _ => {}
        }
    }
}
