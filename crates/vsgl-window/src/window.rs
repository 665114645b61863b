//! The window: winit's event loop pumped on demand, the wgpu surface on the renderer's own
//! device, and the frame path (images → composition → panel → surface).
//!
//! winit allows one event loop per process. It is made on the first window and kept (per
//! thread: the thread that made it is the only one that may open windows), and pumped by
//! [`ViewWindow::poll_events`] while a window is open, so a window can be opened again after
//! one is closed, and closing it returns to the caller.

use crate::compose::{ComposeInputs, ComposePass};
use crate::events::{EventState, InputEvent};
use crate::panel::{PanelChange, PanelSpec, Ui};
use crate::surface_blit::SurfaceBlitPass;
use crate::target::{FrameTarget, TARGET_FORMAT};
use std::cell::RefCell;
use std::sync::Arc;
use std::time::{Duration, Instant};
use vsgl_core::gpu::Gpu;
use vsgl_core::renderer::SubmittedFrame;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::platform::pump_events::EventLoopExtPumpEvents;
use winit::window::{Window, WindowAttributes, WindowId};

/// Why a window could not be opened or drawn.
#[derive(Debug, thiserror::Error)]
pub enum WindowError {
    /// No display to open a window on, or one that refused (the message names the cause and
    /// what to use instead).
    #[error("{0}")]
    NoDisplay(String),
    /// The adapter cannot present to the window's surface.
    #[error("{0}")]
    CannotPresent(String),
    #[error(transparent)]
    Render(#[from] vsgl_core::Error),
}

const ALTERNATIVES: &str = "use the notebook view (vsgl.view) or run headless under Xvfb: \
`xvfb-run -a python -m vsgl view SCENE --frames 30 --screenshot out.png --no-ui`";

thread_local! {
    /// The process's one event loop, made on this thread by the first window.
    static EVENT_LOOP: RefCell<Option<EventLoop<()>>> = const { RefCell::new(None) };
}

/// Whether the event loop was made on some thread already (winit refuses a second one).
static EVENT_LOOP_MADE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

fn with_event_loop<R>(f: impl FnOnce(&mut EventLoop<()>) -> R) -> Result<R, WindowError> {
    // `try_with`: a window dropped while its thread ends (interpreter shutdown) finds the loop
    // gone and closes without pumping, instead of panicking across the Python boundary.
    let gone = || WindowError::NoDisplay("the thread's event loop is gone (the thread is ending)".into());
    EVENT_LOOP.try_with(|cell| {
        let mut slot = cell.borrow_mut();
        if slot.is_none() {
            if EVENT_LOOP_MADE.load(std::sync::atomic::Ordering::SeqCst) {
                return Err(WindowError::NoDisplay("windows can be opened from one thread per process (winit allows one event loop); this is not the thread that opened the first".into()));
            }
            check_display()?;
            let mut builder = EventLoop::builder();
            #[cfg(all(unix, not(target_os = "macos")))]
            {
                use winit::platform::x11::EventLoopBuilderExtX11;
                builder.with_any_thread(true);
            }
            let made = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| builder.build()));
            let event_loop = match made {
                Ok(Ok(l)) => l,
                Ok(Err(e)) => return Err(WindowError::NoDisplay(format!("the window system refused an event loop: {e}; {ALTERNATIVES}"))),
                Err(_) => return Err(WindowError::NoDisplay(format!("the window system could not be opened; {ALTERNATIVES}"))),
            };
            EVENT_LOOP_MADE.store(true, std::sync::atomic::Ordering::SeqCst);
            *slot = Some(event_loop);
        }
        Ok(f(slot.as_mut().expect("made above")))
    })
    .map_err(|_| gone())?
}

/// On X11 systems, a clear error when there is no display to connect to (winit would fail with
/// a less direct one).
fn check_display() -> Result<(), WindowError> {
    #[cfg(all(unix, not(target_os = "macos")))]
    {
        let set = |v: &str| std::env::var_os(v).is_some_and(|s| !s.is_empty());
        if !set("DISPLAY") {
            let wayland = if set("WAYLAND_DISPLAY") { " (WAYLAND_DISPLAY is set, but the window speaks X11: start XWayland, or set DISPLAY)" } else { "" };
            return Err(WindowError::NoDisplay(format!("no display: DISPLAY is not set{wayland}; {ALTERNATIVES}")));
        }
    }
    Ok(())
}

/// The winit side: the window once made, and the events it delivered.
struct WindowApp {
    requested: Option<WindowAttributes>,
    window: Option<Arc<Window>>,
    create_error: Option<String>,
    state: EventState,
    events: Vec<InputEvent>,
    /// egui's input state, fed every window event first (`None` without the panel).
    egui: Option<egui_winit::State>,
    /// Whether the panel asked to be drawn again (an event it took, or an animation of its own):
    /// reported as a `repaint` event, which redraws the panel over the images it has.
    ui_repaint: bool,
}

impl WindowApp {
    fn create(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(attrs) = self.requested.take() {
            match event_loop.create_window(attrs) {
                Ok(w) => {
                    self.state.scale = w.scale_factor();
                    self.window = Some(Arc::new(w));
                }
                Err(e) => self.create_error = Some(e.to_string()),
            }
        }
    }
}

impl ApplicationHandler for WindowApp {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        self.create(event_loop);
    }

    fn new_events(&mut self, event_loop: &ActiveEventLoop, _cause: winit::event::StartCause) {
        self.create(event_loop);
    }

    fn window_event(&mut self, _event_loop: &ActiveEventLoop, id: WindowId, event: WindowEvent) {
        let Some(window) = self.window.clone().filter(|w| w.id() == id) else { return };
        if matches!(event, WindowEvent::RedrawRequested) {
            // Exposed again (uncovered, restored): the frame is drawn again from its images.
            self.ui_repaint = true;
            return;
        }
        let consumed = match &mut self.egui {
            Some(state) => {
                let response = state.on_window_event(&window, &event);
                self.ui_repaint |= response.repaint;
                response.consumed
            }
            None => false,
        };
        // A release is always passed on, so a drag that ends over the panel ends.
        let release = matches!(event, WindowEvent::MouseInput { state: winit::event::ElementState::Released, .. });
        if let Some(e) = self.state.convert(&event) {
            if !consumed || release || matches!(e.kind, "resize" | "close") {
                self.events.push(e);
            }
        }
    }
}

/// The surface and how its textures are viewed.
struct SurfaceState {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    view_format: wgpu::TextureFormat,
    blit: SurfaceBlitPass,
}

/// A live view's window (or its offscreen stand-in).
pub struct ViewWindow {
    gpu: Arc<Gpu>,
    app: WindowApp,
    surface: Option<SurfaceState>,
    /// Offscreen, a texture of a surface's usual format (BGRA8) the target is blitted to, so the
    /// frame path does the work a window's does (timing where no display exists).
    stand_in: Option<(wgpu::TextureView, SurfaceBlitPass)>,
    compose: ComposePass,
    target: FrameTarget,
    /// The images shown: copies of the frames' `ldr` words (or uploaded pixels), one per method.
    images: [Option<wgpu::Buffer>; 2],
    ui: Option<Ui>,
    closed: bool,
    /// Seconds spent in the last [`Self::present`] (recording, submitting, presenting).
    pub last_present: Duration,
}

impl ViewWindow {
    /// Opens a window of `size` logical pixels presenting from `gpu`'s device; `ui`: with the
    /// settings panel and overlay; `vsync`: presentation waits for the display's refresh.
    pub fn open(gpu: Arc<Gpu>, title: &str, size: (u32, u32), ui: bool, vsync: bool) -> Result<Self, WindowError> {
        let attrs = Window::default_attributes().with_title(title).with_inner_size(winit::dpi::LogicalSize::new(size.0, size.1));
        let mut app = WindowApp { requested: Some(attrs), window: None, create_error: None, state: EventState::default(), events: Vec::new(), egui: None, ui_repaint: false };
        // The window is made inside the loop (winit 0.30 makes windows from an active loop).
        let started = Instant::now();
        while app.window.is_none() && app.create_error.is_none() && started.elapsed() < Duration::from_secs(10) {
            with_event_loop(|l| l.pump_app_events(Some(Duration::from_millis(5)), &mut app))?;
        }
        if let Some(e) = app.create_error.take() {
            return Err(WindowError::NoDisplay(format!("the window system refused a window: {e}; {ALTERNATIVES}")));
        }
        let window = app.window.clone().ok_or_else(|| WindowError::NoDisplay(format!("no window appeared within 10 s; {ALTERNATIVES}")))?;
        let surface = gpu.instance.create_surface(window.clone()).map_err(|e| WindowError::CannotPresent(format!("could not make a surface for the window: {e}; {ALTERNATIVES}")))?;
        if !gpu.wgpu_adapter.is_surface_supported(&surface) {
            return Err(WindowError::CannotPresent(format!("adapter {:?} cannot present to this window's surface; {ALTERNATIVES}", gpu.adapter.name)));
        }
        let caps = surface.get_capabilities(&gpu.wgpu_adapter);
        let format = caps.formats.iter().copied().find(|f| matches!(f.remove_srgb_suffix(), wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm));
        let format = format.ok_or_else(|| WindowError::CannotPresent(format!("the surface offers no 8-bit RGBA or BGRA format (offers {:?}); {ALTERNATIVES}", caps.formats)))?;
        let view_format = format.remove_srgb_suffix();
        let physical = window.inner_size();
        let present_mode = if vsync { wgpu::PresentMode::AutoVsync } else { wgpu::PresentMode::AutoNoVsync };
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: physical.width.max(1),
            height: physical.height.max(1),
            present_mode,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps.alpha_modes.first().copied().unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: if view_format == format { vec![] } else { vec![view_format] },
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&gpu.device, &config);
        let blit = SurfaceBlitPass::new(&gpu.device, view_format);
        let size = (config.width, config.height);
        let mut ui_state = ui.then(|| Ui::new(&gpu.device, TARGET_FORMAT));
        if let Some(u) = &mut ui_state {
            let input = egui_winit::State::new(u.ctx.clone(), egui::ViewportId::ROOT, &*window, Some(window.scale_factor() as f32), None, Some(gpu.limits.max_texture_dimension_2d as usize));
            app.egui = Some(input);
        }
        let mut me = Self::with_parts(gpu, app, size, ui_state);
        me.surface = Some(SurfaceState { surface, config, view_format, blit });
        Ok(me)
    }

    /// The frame path without a window: composition and panel into a target of `size` pixels,
    /// nothing presented (timing on a machine with no display; tests).
    pub fn offscreen(gpu: Arc<Gpu>, size: (u32, u32), ui: bool) -> Self {
        let app = WindowApp { requested: None, window: None, create_error: None, state: EventState { scale: 1.0, ..Default::default() }, events: Vec::new(), egui: None, ui_repaint: false };
        let ui = ui.then(|| Ui::new(&gpu.device, TARGET_FORMAT));
        let format = wgpu::TextureFormat::Bgra8Unorm;
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("window_surface_stand_in_texture"),
            size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        let blit = SurfaceBlitPass::new(&gpu.device, format);
        let mut me = Self::with_parts(gpu, app, size, ui);
        me.stand_in = Some((texture.create_view(&Default::default()), blit));
        me
    }

    fn with_parts(gpu: Arc<Gpu>, app: WindowApp, size: (u32, u32), ui: Option<Ui>) -> Self {
        let compose = ComposePass::new(&gpu.device, TARGET_FORMAT);
        let target = FrameTarget::new(&gpu.device, size);
        Self { gpu, app, surface: None, stand_in: None, compose, target, images: [None, None], ui, closed: false, last_present: Duration::ZERO }
    }

    /// (width, height) in physical pixels of what the window shows (its frames' size).
    pub fn size(&self) -> (u32, u32) {
        self.target.size
    }

    /// The window's scale factor (physical pixels per logical one).
    pub fn pixel_ratio(&self) -> f64 {
        self.app.window.as_ref().map_or(1.0, |w| w.scale_factor())
    }

    pub fn is_closed(&self) -> bool {
        self.closed
    }

    pub fn has_window(&self) -> bool {
        self.surface.is_some()
    }

    /// The events since the last call, waiting up to `wait` for the first (offscreen: none).
    /// A resize reconfigures the surface and the target before it is returned.
    pub fn poll_events(&mut self, wait: Duration) -> Result<Vec<InputEvent>, WindowError> {
        if self.surface.is_none() || self.closed {
            return Ok(Vec::new());
        }
        let wait = if self.app.ui_repaint { Duration::ZERO } else { wait };
        with_event_loop(|l| l.pump_app_events(Some(wait), &mut self.app))?;
        let mut events = std::mem::take(&mut self.app.events);
        if std::mem::take(&mut self.app.ui_repaint) {
            events.push(InputEvent { kind: "repaint", ..Default::default() });
        }
        for e in &events {
            match e.kind {
                "close" => self.closed = true,
                "resize" => {
                    let physical = self.app.window.as_ref().map(|w| w.inner_size());
                    if let (Some(p), Some(s)) = (physical, &mut self.surface) {
                        if p.width > 0 && p.height > 0 && (p.width, p.height) != (s.config.width, s.config.height) {
                            s.config.width = p.width;
                            s.config.height = p.height;
                            s.surface.configure(&self.gpu.device, &s.config);
                            self.target = FrameTarget::new(&self.gpu.device, (p.width, p.height));
                        }
                    }
                }
                _ => {}
            }
        }
        Ok(events)
    }

    fn image_buffer(&mut self, slot: usize, bytes: u64) -> wgpu::Buffer {
        let slot = slot.min(1);
        match &self.images[slot] {
            Some(b) if b.size() == bytes => b.clone(),
            _ => {
                let b = self.gpu.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("window_image_buffer"),
                    size: bytes.max(4),
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                self.images[slot] = Some(b.clone());
                b
            }
        }
    }

    /// Shows `frame`'s `ldr` image as image `slot` (0 left or alone, 1 right): a GPU copy,
    /// submitted now, so the next frame may pack into the renderer's buffer.
    pub fn take_frame(&mut self, slot: usize, frame: &SubmittedFrame) -> Result<(), WindowError> {
        let (w, h) = frame.size();
        let Some((buffer, offset)) = frame.packed_aov("ldr") else {
            return Err(WindowError::Render(vsgl_core::Error::invalid("frame", "was not rendered with aovs=[\"ldr\"] kept on the GPU")));
        };
        let bytes = w as u64 * h as u64 * 4;
        let image = self.image_buffer(slot, bytes);
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(buffer, offset, &image, 0, bytes);
        self.gpu.queue.submit([encoder.finish()]);
        Ok(())
    }

    /// Shows `rgba` (RGBA8 rows top to bottom, `size` pixels) as image `slot`: the path for
    /// what the GPU does not make ready to show (other AOVs, exposure, a slow method's last
    /// image).
    pub fn upload_image(&mut self, slot: usize, size: (u32, u32), rgba: &[u8]) -> Result<(), WindowError> {
        let bytes = size.0 as u64 * size.1 as u64 * 4;
        if rgba.len() as u64 != bytes {
            return Err(WindowError::Render(vsgl_core::Error::invalid("image", format!("expected {bytes} bytes ({} × {} RGBA8), got {}", size.0, size.1, rgba.len()))));
        }
        let image = self.image_buffer(slot, bytes);
        self.gpu.queue.write_buffer(&image, 0, rgba);
        Ok(())
    }

    /// Draws the images (`split`: the right image's first column when two are shown), the panel
    /// (unless the window has none) and presents. Returns what the user changed in the panel.
    pub fn present(&mut self, split: Option<u32>, spec: &PanelSpec) -> Result<Vec<PanelChange>, WindowError> {
        let started = Instant::now();
        let size = self.target.size;
        let bytes = size.0 as u64 * size.1 as u64 * 4;
        let left = self.image_buffer(0, bytes);
        let right = split.map(|s| (self.image_buffer(1, bytes), s));
        let device = &self.gpu.device;
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("window_frame") });
        self.compose.record(device, &mut encoder, &ComposeInputs { size, left: &left, right: right.as_ref().map(|(b, s)| (b, *s)) }, &self.target.view);
        let mut changes = Vec::new();
        let mut extra = Vec::new();
        if let Some(ui) = &mut self.ui {
            ui.input = self.app.egui.take();
            let (c, paint, again) = ui.run(spec, size, self.app.window.as_ref().map_or(1.0, |w| w.scale_factor() as f32), self.app.window.as_deref());
            self.app.egui = ui.input.take();
            changes = c;
            self.app.ui_repaint |= again && self.surface.is_some();
            extra = ui.record(device, &self.gpu.queue, &mut encoder, paint, &self.target.view);
        }
        let mut frame = None;
        if let Some(s) = &self.surface {
            match s.surface.get_current_texture() {
                wgpu::CurrentSurfaceTexture::Success(t) | wgpu::CurrentSurfaceTexture::Suboptimal(t) => {
                    let view = t.texture.create_view(&wgpu::TextureViewDescriptor { format: Some(s.view_format), ..Default::default() });
                    s.blit.record(device, &mut encoder, &self.target.view, &view);
                    frame = Some(t);
                }
                // Minimised, occluded or outdated: this frame is not shown; a resize follows.
                _ => s.surface.configure(device, &s.config),
            }
        } else if let Some((view, blit)) = &self.stand_in {
            blit.record(device, &mut encoder, &self.target.view, view);
        }
        extra.push(encoder.finish());
        self.gpu.queue.submit(extra);
        if let Some(f) = frame {
            if let Some(w) = &self.app.window {
                w.pre_present_notify();
            }
            self.gpu.queue.present(f);
        }
        self.last_present = started.elapsed();
        Ok(changes)
    }

    /// The last frame presented, RGBA8 rows top to bottom (the target the surface was blitted
    /// from, panel included when shown).
    pub fn screenshot(&self) -> Result<((u32, u32), Vec<u8>), WindowError> {
        Ok((self.target.size, self.target.read(&self.gpu)?))
    }

    /// Closes the window (the event loop is kept for the next).
    pub fn close(&mut self) {
        self.surface = None;
        self.app.egui = None;
        self.app.window = None;
        self.closed = true;
        // Let the window system see the window go.
        let _ = with_event_loop(|l| l.pump_app_events(Some(Duration::ZERO), &mut self.app));
    }
}

impl Drop for ViewWindow {
    fn drop(&mut self) {
        if self.app.window.is_some() {
            self.close();
        }
    }
}
