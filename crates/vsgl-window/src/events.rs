//! winit's window events as the remote-frame-buffer events the notebook view receives
//! (`jupyter_rfb`'s format, described in Python's `vsgl.camera_control`): positions in logical
//! pixels from the top left, button 1 left / 2 right / 3 middle, keys named as a browser names
//! them, wheel `dy` > 0 scrolling down in a browser's units (100 a notch).

use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::keyboard::{Key, ModifiersState, NamedKey};

/// One event in the remote-frame-buffer format; fields a kind does not have are left at their
/// defaults (`kind` says which apply, as the Python dict built from it does).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InputEvent {
    /// `pointer_down`, `pointer_move`, `pointer_up`, `wheel`, `key_down`, `key_up`, `resize`,
    /// `close`.
    pub kind: &'static str,
    pub x: f64,
    pub y: f64,
    pub button: u32,
    pub buttons: Vec<u32>,
    pub modifiers: Vec<&'static str>,
    pub dx: f64,
    pub dy: f64,
    pub key: String,
    pub width: f64,
    pub height: f64,
    pub pixel_ratio: f64,
}

/// Browser units of one wheel notch (a `LineDelta` of 1).
const WHEEL_UNITS_PER_LINE: f64 = 100.0;

/// What the converter remembers between events: where the pointer is, which buttons are held,
/// which modifiers, and the window's scale factor.
#[derive(Default)]
pub struct EventState {
    pub cursor: (f64, f64),
    pub buttons: Vec<u32>,
    pub modifiers: ModifiersState,
    pub scale: f64,
}

fn button_number(b: MouseButton) -> Option<u32> {
    match b {
        MouseButton::Left => Some(1),
        MouseButton::Right => Some(2),
        MouseButton::Middle => Some(3),
        MouseButton::Back => Some(4),
        MouseButton::Forward => Some(5),
        MouseButton::Other(_) => None,
    }
}

fn modifier_names(m: ModifiersState) -> Vec<&'static str> {
    let mut out = Vec::new();
    if m.shift_key() {
        out.push("Shift");
    }
    if m.control_key() {
        out.push("Control");
    }
    if m.alt_key() {
        out.push("Alt");
    }
    if m.super_key() {
        out.push("Meta");
    }
    out
}

/// A key's name as a browser's `KeyboardEvent.key` gives it: the character typed, or the named
/// key (`"Home"`, `"Escape"`, `"ArrowUp"`, `" "` for space).
pub fn key_name(key: &Key) -> Option<String> {
    match key {
        Key::Character(s) => Some(s.to_string()),
        Key::Named(NamedKey::Space) => Some(" ".into()),
        Key::Named(named) => Some(format!("{named:?}")),
        _ => None,
    }
}

impl EventState {
    fn pointer(&self, kind: &'static str, button: u32) -> InputEvent {
        InputEvent { kind, x: self.cursor.0, y: self.cursor.1, button, buttons: self.buttons.clone(), modifiers: modifier_names(self.modifiers), ..Default::default() }
    }

    /// The event `e` makes, if any (state changes such as the modifiers make none).
    pub fn convert(&mut self, e: &WindowEvent) -> Option<InputEvent> {
        let scale = if self.scale > 0.0 { self.scale } else { 1.0 };
        match e {
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = (position.x / scale, position.y / scale);
                Some(self.pointer("pointer_move", 0))
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let b = button_number(*button)?;
                match state {
                    ElementState::Pressed => {
                        if !self.buttons.contains(&b) {
                            self.buttons.push(b);
                        }
                        Some(self.pointer("pointer_down", b))
                    }
                    ElementState::Released => {
                        self.buttons.retain(|&x| x != b);
                        Some(self.pointer("pointer_up", b))
                    }
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                // winit's positive y scrolls up (away from the user); a browser's deltaY > 0 down.
                let (dx, dy) = match delta {
                    MouseScrollDelta::LineDelta(x, y) => (-*x as f64 * WHEEL_UNITS_PER_LINE, -*y as f64 * WHEEL_UNITS_PER_LINE),
                    MouseScrollDelta::PixelDelta(p) => (-p.x / scale, -p.y / scale),
                };
                Some(InputEvent { dx, dy, ..self.pointer("wheel", 0) })
            }
            WindowEvent::ModifiersChanged(m) => {
                self.modifiers = m.state();
                None
            }
            WindowEvent::KeyboardInput { event, .. } => {
                let key = key_name(&event.logical_key)?;
                let kind = if event.state == ElementState::Pressed { "key_down" } else { "key_up" };
                Some(InputEvent { kind, key, modifiers: modifier_names(self.modifiers), ..Default::default() })
            }
            WindowEvent::Resized(size) => Some(InputEvent {
                kind: "resize",
                width: size.width as f64 / scale,
                height: size.height as f64 / scale,
                pixel_ratio: scale,
                ..Default::default()
            }),
            WindowEvent::ScaleFactorChanged { scale_factor, .. } => {
                self.scale = *scale_factor;
                None
            }
            WindowEvent::CloseRequested | WindowEvent::Destroyed => Some(InputEvent { kind: "close", ..Default::default() }),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use winit::dpi::PhysicalPosition;

    #[test]
    fn pointer_positions_are_logical_and_buttons_are_held_until_released() {
        let mut s = EventState { scale: 2.0, ..Default::default() };
        let moved = s.convert(&WindowEvent::CursorMoved { device_id: winit::event::DeviceId::dummy(), position: PhysicalPosition::new(200.0, 100.0) }).unwrap();
        assert_eq!((moved.kind, moved.x, moved.y), ("pointer_move", 100.0, 50.0));
        let down = s.convert(&WindowEvent::MouseInput { device_id: winit::event::DeviceId::dummy(), state: ElementState::Pressed, button: MouseButton::Right }).unwrap();
        assert_eq!((down.kind, down.button, down.buttons.clone()), ("pointer_down", 2, vec![2]));
        let up = s.convert(&WindowEvent::MouseInput { device_id: winit::event::DeviceId::dummy(), state: ElementState::Released, button: MouseButton::Right }).unwrap();
        assert_eq!((up.kind, up.button, up.buttons), ("pointer_up", 2, vec![]));
    }

    #[test]
    fn a_wheel_notch_toward_the_user_is_a_browsers_positive_hundred() {
        let mut s = EventState { scale: 1.0, ..Default::default() };
        let w = s.convert(&WindowEvent::MouseWheel { device_id: winit::event::DeviceId::dummy(), delta: MouseScrollDelta::LineDelta(0.0, -1.0), phase: winit::event::TouchPhase::Moved }).unwrap();
        assert_eq!((w.kind, w.dy), ("wheel", 100.0));
    }

    #[test]
    fn keys_are_named_as_a_browser_names_them() {
        assert_eq!(key_name(&Key::Character("w".into())).as_deref(), Some("w"));
        assert_eq!(key_name(&Key::Named(NamedKey::Home)).as_deref(), Some("Home"));
        assert_eq!(key_name(&Key::Named(NamedKey::Escape)).as_deref(), Some("Escape"));
        assert_eq!(key_name(&Key::Named(NamedKey::Space)).as_deref(), Some(" "));
    }
}
