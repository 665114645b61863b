//! The settings panel and the text drawn over the frame, with egui: the method, its options
//! (what Python's `vsgl.method_info` offers, passed in as [`Control`]s, so the panel never offers
//! a value `render` would refuse), exposure and the AOV; the methods' labels when two are compared;
//! the status line (GPU ms, frames per second, error once measured).
//!
//! The panel only reports what the user changed ([`PanelChange`]): the caller checks and applies
//! it as `render` checks options, and sends the next [`PanelSpec`].

use std::time::Instant;

/// A value a control holds or a change carries.
#[derive(Clone, Debug, PartialEq)]
pub enum PanelValue {
    Text(String),
    Int(i64),
    Float(f64),
    Bool(bool),
}

/// One control of the panel.
#[derive(Clone, Debug, PartialEq)]
pub enum Control {
    Choice { name: String, choices: Vec<String>, current: String },
    /// A slider; `logarithmic` for ranges over decades (`num_lights`).
    Int { name: String, min: i64, max: i64, current: i64, logarithmic: bool },
    Float { name: String, min: f64, max: f64, current: f64, logarithmic: bool },
    Toggle { name: String, current: bool },
}

impl Control {
    fn name(&self) -> &str {
        match self {
            Control::Choice { name, .. } | Control::Int { name, .. } | Control::Float { name, .. } | Control::Toggle { name, .. } => name,
        }
    }
}

/// What the panel and the overlay show this frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PanelSpec {
    pub controls: Vec<Control>,
    /// The status line at the bottom of the frame.
    pub status: String,
    /// Labels at the top of the frame: text and the left edge of its half, in logical pixels.
    pub labels: Vec<(String, f32)>,
}

/// A control the user changed this frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PanelChange {
    pub name: String,
    pub value: PanelValue,
}

/// egui's context, its renderer on the window's device, and the window's input for it.
pub struct Ui {
    pub ctx: egui::Context,
    renderer: egui_wgpu::Renderer,
    pub input: Option<egui_winit::State>,
    started: Instant,
}

/// What one UI frame draws, tessellated, to record into the target.
pub struct UiPaint {
    jobs: Vec<egui::ClippedPrimitive>,
    textures: egui::TexturesDelta,
    screen: egui_wgpu::ScreenDescriptor,
}

impl Ui {
    pub fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> Self {
        let ctx = egui::Context::default();
        let renderer = egui_wgpu::Renderer::new(device, target_format, egui_wgpu::RendererOptions::default());
        Self { ctx, renderer, input: None, started: Instant::now() }
    }

    /// Runs the panel for one frame of `size` physical pixels at `pixels_per_point`; `window`
    /// gives egui its input (offscreen, it gets none). Returns the changes, what to draw, and
    /// whether the panel asks to be drawn again at once (an animation, a menu opening).
    pub fn run(&mut self, spec: &PanelSpec, size: (u32, u32), pixels_per_point: f32, window: Option<&winit::window::Window>) -> (Vec<PanelChange>, UiPaint, bool) {
        let mut raw = match (&mut self.input, window) {
            (Some(state), Some(w)) => state.take_egui_input(w),
            _ => egui::RawInput::default(),
        };
        let logical = egui::vec2(size.0 as f32, size.1 as f32) / pixels_per_point;
        raw.screen_rect = Some(egui::Rect::from_min_size(egui::Pos2::ZERO, logical));
        raw.time = Some(self.started.elapsed().as_secs_f64());
        let mut changes = Vec::new();
        let output = self.ctx.run_ui(raw, |ui| draw(ui.ctx(), spec, &mut changes));
        if let (Some(state), Some(w)) = (&mut self.input, window) {
            state.handle_platform_output(w, output.platform_output.clone());
        }
        let again = output.viewport_output.get(&egui::ViewportId::ROOT).is_some_and(|v| v.repaint_delay < std::time::Duration::from_millis(100));
        let jobs = self.ctx.tessellate(output.shapes, output.pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor { size_in_pixels: [size.0, size.1], pixels_per_point: output.pixels_per_point };
        (changes, UiPaint { jobs, textures: output.textures_delta, screen }, again)
    }

    /// Records `paint` over `target` (its pixels kept where the panel draws nothing).
    pub fn record(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, encoder: &mut wgpu::CommandEncoder, paint: UiPaint, target: &wgpu::TextureView) -> Vec<wgpu::CommandBuffer> {
        for (id, deltas) in &paint.textures.set {
            for delta in deltas {
                self.renderer.update_texture(device, queue, *id, delta);
            }
        }
        let extra = self.renderer.update_buffers(device, queue, encoder, &paint.jobs, &paint.screen);
        {
            let pass = crate::target_pass(encoder, "window_panel", target, wgpu::LoadOp::Load);
            self.renderer.render(&mut pass.forget_lifetime(), &paint.jobs, &paint.screen);
        }
        for id in &paint.textures.free {
            self.renderer.free_texture(id);
        }
        extra
    }
}

/// Logical size from which the panel starts open (it is about 300 × 230 points open).
const PANEL_OPEN_MIN_SIZE: (f32, f32) = (800.0, 480.0);

/// The panel's widgets; appends what the user changed to `changes`.
fn draw(ctx: &egui::Context, spec: &PanelSpec, changes: &mut Vec<PanelChange>) {
    // Below the row of method labels; open from the start only where it leaves most of the
    // frame in view (at 480×270 it covered the image: it then starts collapsed, a click opens it).
    let roomy = ctx.content_rect().width() >= PANEL_OPEN_MIN_SIZE.0 && ctx.content_rect().height() >= PANEL_OPEN_MIN_SIZE.1;
    egui::Window::new("settings").anchor(egui::Align2::RIGHT_TOP, egui::vec2(-8.0, 28.0)).resizable(false).default_open(roomy).show(ctx, |ui| {
        egui::Grid::new("controls").num_columns(2).show(ui, |ui| {
            for control in &spec.controls {
                ui.label(control.name());
                if let Some(value) = control_widget(ui, control) {
                    changes.push(PanelChange { name: control.name().to_string(), value });
                }
                ui.end_row();
            }
        });
    });
    let painter = ctx.layer_painter(egui::LayerId::new(egui::Order::Foreground, egui::Id::unique("overlay")));
    let font = egui::FontId::monospace(13.0);
    let screen = ctx.content_rect();
    for (text, x) in &spec.labels {
        let at = egui::pos2(x + 6.0, 6.0);
        let galley = painter.layout_no_wrap(text.clone(), font.clone(), egui::Color32::WHITE);
        painter.rect_filled(egui::Rect::from_min_size(at, galley.size()).expand(3.0), 2.0, egui::Color32::from_black_alpha(160));
        painter.galley(at, galley, egui::Color32::WHITE);
    }
    if !spec.status.is_empty() {
        let galley = painter.layout_no_wrap(spec.status.clone(), font, egui::Color32::WHITE);
        let at = egui::pos2(6.0, screen.bottom() - galley.size().y - 6.0);
        painter.rect_filled(egui::Rect::from_min_size(at, galley.size()).expand(3.0), 2.0, egui::Color32::from_black_alpha(160));
        painter.galley(at, galley, egui::Color32::WHITE);
    }
}

/// One control's widget; the new value when the user changed it.
fn control_widget(ui: &mut egui::Ui, control: &Control) -> Option<PanelValue> {
    match control {
        Control::Choice { name, choices, current } => {
            let mut chosen = current.clone();
            egui::ComboBox::from_id_salt(name).selected_text(chosen.clone()).show_ui(ui, |ui| {
                for c in choices {
                    ui.selectable_value(&mut chosen, c.clone(), c);
                }
            });
            (chosen != *current).then_some(PanelValue::Text(chosen))
        }
        Control::Int { min, max, current, logarithmic, .. } => {
            let mut v = *current;
            let changed = ui.add(egui::Slider::new(&mut v, *min..=*max).logarithmic(*logarithmic)).changed();
            (changed && v != *current).then_some(PanelValue::Int(v))
        }
        Control::Float { min, max, current, logarithmic, .. } => {
            let mut v = *current;
            let changed = ui.add(egui::Slider::new(&mut v, *min..=*max).logarithmic(*logarithmic)).changed();
            (changed && v != *current).then_some(PanelValue::Float(v))
        }
        Control::Toggle { current, .. } => {
            let mut v = *current;
            ui.checkbox(&mut v, "").changed().then_some(PanelValue::Bool(v))
        }
    }
}
