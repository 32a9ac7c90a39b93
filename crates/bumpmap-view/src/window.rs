//! The viewer's window: winit's event loop; frames from the front door's renderer shown on the
//! GPU's surface (wgpu: the frame never comes back to the CPU) or, from the CPU backend,
//! through softbuffer; keys and mouse turned into the model's actions, files dropped on it
//! loaded in place, and the scripted runs (`--frames`, `--keys`, `--screenshot`).
//!
//! What this module does not do: decide what a key does (`super::state`) or draw text
//! (`super::overlay`). Nothing here ends the program on a bad file or a failed frame: the
//! message is shown in the window and the old scene kept.

use std::num::NonZeroU32;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use bumpmap::{Backend, BackendChoice, Renderer, Rgba8Image, WindowSurface};
use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::{PngLayout, save_png_into};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use super::keys::Action;
use super::overlay::{self, Corner};
use super::state::{Effect, Viewer};
use crate::Run;
use bumpmap::options::SceneOptions;
use bumpmap_words::Error;
use bumpmap_words::frame::lib_err;

/// The seconds of the light's orbit each scripted frame advances: the same pictures on every
/// machine, whatever its frame rate.
const SCRIPTED_FRAME_SECONDS: f32 = 1.0 / 30.0;

/// Opens the window and runs until it is closed (or the script ends).
pub fn run(run: &Run, options: SceneOptions, backend: BackendChoice, inputs: &[&Path]) -> Result<(), Error> {
    ensure_display()?;
    let viewer = Viewer::new(options)?;
    let reference_only = viewer.technique().is_reference();
    let renderer = if reference_only && backend == bumpmap::BackendChoice::Auto {
        Renderer::new(BackendChoice::Cpu).map_err(lib_err)?
    } else {
        crate::renderer(backend)?
    };
    let event_loop = EventLoop::new().map_err(|e| no_display(&e.to_string()))?;
    let keys = run.scripted_keys();
    let frames = run
        .frames
        .map(|f| f as usize)
        .or_else(|| (run.keys.is_some() || run.screenshot.is_some()).then_some(keys.len() + 1));
    let mut app = App {
        viewer,
        renderer,
        size: run.size,
        window: None,
        presenter: None,
        last: None,
        drawn: None,
        frame: 0,
        script: Script { frames, keys, screenshot: run.screenshot.clone() },
        inputs: inputs.iter().map(|p| p.to_path_buf()).collect(),
        fps: Fps::default(),
        cursor: None,
        dragging: None,
        timing: Timing::default(),
        result: Ok(()),
    };
    event_loop.run_app(&mut app).map_err(|e| Error::Render(format!("the window's event loop failed: {e}")))?;
    app.result
}

/// Refuses to start without a display, saying what to do instead.
fn ensure_display() -> Result<(), Error> {
    let set = |v: &str| std::env::var_os(v).is_some_and(|s| !s.is_empty());
    if set("DISPLAY") || set("WAYLAND_DISPLAY") {
        return Ok(());
    }
    Err(no_display("neither DISPLAY nor WAYLAND_DISPLAY is set"))
}

fn no_display(why: &str) -> Error {
    Error::NoDevice(format!(
        "no display to open a window on ({why}). Run it in a desktop session; on a server, under \
         xvfb-run (Debian: apt-get install xvfb xauth); or write an animated PNG without a window: \
         bumpmap view --record orbit.png"
    ))
}

/// What `--frames`, `--keys` and `--screenshot` ask for.
struct Script {
    frames: Option<usize>,
    keys: Vec<Action>,
    screenshot: Option<PathBuf>,
}

/// Frames per second over the last half second or so.
#[derive(Default)]
struct Fps {
    since: Option<Instant>,
    count: u32,
    value: f32,
}

impl Fps {
    fn tick(&mut self) {
        let now = Instant::now();
        let since = *self.since.get_or_insert(now);
        self.count += 1;
        let elapsed = now.duration_since(since).as_secs_f32();
        if elapsed >= 0.5 {
            self.value = self.count as f32 / elapsed;
            self.count = 0;
            self.since = Some(now);
        }
    }
}

/// The last frame shown.
enum Shown {
    /// The frame with its overlay.
    Image(Rgba8Image),
    /// Only the overlay: the frame went from the GPU to the screen.
    Overlay(Rgba8Image),
}

/// How frames reach the window.
enum Presenter {
    /// The GPU's own surface.
    Gpu(Box<WindowSurface>),
    /// A CPU frame copied into the window (the CPU backend, or a GPU without a surface here).
    Soft(softbuffer::Surface<Arc<Window>, Arc<Window>>),
}

/// A presenter for `renderer` on `window`: the GPU's surface where it has one, else
/// softbuffer, with the reason the GPU's could not be had.
fn presenter(renderer: &Renderer, window: &Arc<Window>) -> Result<(Presenter, Option<String>), Error> {
    let size = window.inner_size();
    let (w, h) = (size.width.max(1) as usize, size.height.max(1) as usize);
    let mut note = None;
    match renderer.window_surface(window.clone(), w, h) {
        Ok(Some(surface)) => return Ok((Presenter::Gpu(Box::new(surface)), None)),
        Ok(None) => {}
        Err(e) => note = Some(format!("{e}; showing the GPU's frames through the CPU instead")),
    }
    let context = softbuffer::Context::new(window.clone())
        .map_err(|e| no_display(&format!("no software buffer for the display: {e}")))?;
    let surface = softbuffer::Surface::new(&context, window.clone())
        .map_err(|e| no_display(&format!("no software buffer for the window: {e}")))?;
    Ok((Presenter::Soft(surface), note))
}

struct App {
    viewer: Viewer,
    renderer: Renderer,
    size: (usize, usize),
    window: Option<Arc<Window>>,
    presenter: Option<Presenter>,
    /// When the last frame was drawn (the orbit advances by the time since).
    last: Option<Instant>,
    /// The last frame shown: what `s` writes.
    drawn: Option<Shown>,
    frame: usize,
    script: Script,
    inputs: Vec<PathBuf>,
    fps: Fps,
    cursor: Option<(f64, f64)>,
    dragging: Option<MouseButton>,
    /// A scripted run's timings: when the first frame was shown, and the key pressed last with
    /// when, until the frame after it is shown.
    timing: Timing,
    result: Result<(), Error>,
}

/// What a scripted run measures, printed on stderr: the frame rate after the first frame
/// (the window's own making left out), and each key's time to the next frame shown (for `+`,
/// the normal map rebuilt and drawn).
#[derive(Default)]
struct Timing {
    first: Option<Instant>,
    key: Option<(Action, Instant)>,
}

impl App {
    fn fail(&mut self, event_loop: &ActiveEventLoop, e: Error) {
        self.result = Err(e);
        event_loop.exit();
    }

    fn title(&self) -> String {
        let backend = match self.renderer.backend() {
            Backend::Cpu => "cpu".to_string(),
            Backend::Gpu => format!("gpu ({})", self.renderer.describe().trim_start_matches("gpu: ")),
        };
        let mut title = format!("bumpmap view - {} on {backend}", self.viewer.technique());
        if self.viewer.view.frame_rate || self.script.frames.is_none() {
            title += &format!(" - {:.0} fps", self.fps.value);
        }
        title
    }

    fn act(&mut self, event_loop: &ActiveEventLoop, action: Action) {
        if self.script.frames.is_some() {
            self.timing.key = Some((action, Instant::now()));
        }
        match self.viewer.apply(action) {
            Effect::Redraw => {}
            Effect::Quit => event_loop.exit(),
            Effect::Screenshot => match self.screenshot(None) {
                Ok(path) => println!("wrote {}", path.display()),
                Err(e) => self.viewer.message = Some(e.to_string()),
            },
            Effect::SwitchBackend => {
                let other = match self.renderer.backend() {
                    Backend::Cpu => BackendChoice::Gpu,
                    Backend::Gpu => BackendChoice::Cpu,
                };
                match Renderer::new(other) {
                    Ok(r) => {
                        // The old surface goes before the new one is made on the same window.
                        self.presenter = None;
                        self.renderer = r;
                        if let Some(window) = self.window.clone() {
                            match presenter(&self.renderer, &window) {
                                Ok((p, note)) => {
                                    self.presenter = Some(p);
                                    self.viewer.message = note;
                                }
                                Err(e) => return self.fail(event_loop, e),
                            }
                        }
                    }
                    Err(e) => self.viewer.message = Some(lib_err(e).to_string()),
                }
            }
        }
        if let Some(m) = &self.viewer.message {
            say!("{}", m);
        }
        self.redraw();
    }

    fn redraw(&self) {
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }

    /// Writes the last frame shown to `path`, or to the first free `bumpmap-view-NNN.png` here
    /// (a frame shown on the GPU's surface is drawn again and read back for it).
    fn screenshot(&mut self, path: Option<&Path>) -> Result<PathBuf, Error> {
        let Some(shown) = self.drawn.take() else {
            return Err(Error::Render("no frame has been drawn yet".into()));
        };
        let image = match shown {
            Shown::Image(image) => image,
            Shown::Overlay(layer) => {
                let mut image = self.renderer.draw(self.viewer.frame(), layer.width, layer.height).map_err(lib_err)?;
                image.overlay(&layer);
                image
            }
        };
        let written = self.write_png(path, &image);
        self.drawn = Some(Shown::Image(image));
        written
    }

    fn write_png(&self, path: Option<&Path>, image: &Rgba8Image) -> Result<PathBuf, Error> {
        let path = match path {
            Some(p) => p.to_path_buf(),
            None => (1..10_000)
                .map(|n| PathBuf::from(format!("bumpmap-view-{n:03}.png")))
                .find(|p| !p.exists())
                .ok_or_else(|| Error::Render("bumpmap-view-001..9999.png all exist here".into()))?,
        };
        let inputs: Vec<&Path> = self.inputs.iter().chain(self.viewer.inputs()).map(PathBuf::as_path).collect();
        let mut set = FileSet::new(&inputs);
        let rgb = crate::rgb(image);
        save_png_into(&mut set, &path, image.width, image.height, PngLayout::Rgb8, &rgb)?;
        set.commit()?;
        Ok(path)
    }

    /// Draws a frame, puts the overlay on it and presents it.
    fn draw(&mut self, event_loop: &ActiveEventLoop) {
        let Some(window) = self.window.clone() else { return };
        let now = Instant::now();
        let seconds = match (self.script.frames, self.last) {
            (Some(_), _) if self.frame > 0 => SCRIPTED_FRAME_SECONDS,
            (None, Some(last)) => now.duration_since(last).as_secs_f32().min(0.25),
            _ => 0.0,
        };
        self.last = Some(now);
        self.viewer.advance(seconds);
        let size = window.inner_size();
        let (Some(w), Some(h)) = (NonZeroU32::new(size.width), NonZeroU32::new(size.height)) else { return };
        let (width, height) = (w.get() as usize, h.get() as usize);
        // Once per frame: each call moves the reference a step on in its refinement.
        let prepared = self.viewer.frame().clone();
        let mut layer = overlay::layer(width, height);
        if self.viewer.view.wireframe {
            overlay::wireframe(&mut layer, &prepared.scene);
        }
        self.fps.tick();
        self.overlay_text(&mut layer);
        if let Some(Presenter::Gpu(surface)) = &mut self.presenter {
            self.renderer.resize_surface(surface, width, height);
            match self.renderer.present(surface, &prepared, &layer) {
                Ok(()) => self.drawn = Some(Shown::Overlay(layer)),
                // The device or the window failed: nothing more can be shown.
                Err(e @ bumpmap::Error::Gpu(_)) => {
                    return self.fail(event_loop, Error::Render(format!("showing a frame in the window: {e}")));
                }
                // The scene: say so and keep the window.
                Err(e) => self.viewer.message = Some(lib_err(e).to_string()),
            }
        } else {
            let reference = self.viewer.technique().is_reference();
            // The reference samples the exact surface on the CPU whichever backend is open.
            let drawn = if reference && self.renderer.backend() == Backend::Gpu {
                Renderer::new(BackendChoice::Cpu).and_then(|mut r| r.draw(&prepared, width, height))
            } else {
                self.renderer.draw(&prepared, width, height)
            };
            let mut image = match drawn {
                Ok(image) => image,
                Err(e) => {
                    self.viewer.message = Some(lib_err(e).to_string());
                    Rgba8Image::new(width, height, vec![[0, 0, 0, 255]; width * height])
                }
            };
            image.overlay(&layer);
            if let Err(e) = self.present_soft(w, h, &image) {
                return self.fail(event_loop, Error::Render(format!("showing a frame in the window: {e}")));
            }
            self.drawn = Some(Shown::Image(image));
        }
        window.set_title(&self.title());
        self.frame += 1;
        self.script_step(event_loop);
    }

    /// The help, the status line and the last message, drawn into `layer`.
    fn overlay_text(&self, layer: &mut Rgba8Image) {
        if self.viewer.view.help {
            let mut lines = vec!["bumpmap view: keys".to_string(), String::new()];
            lines.extend(Action::ALL.iter().map(|a| {
                let key = match a.key() {
                    ' ' => "space".to_string(),
                    c => c.to_string(),
                };
                format!("{key:<6} {}", a.description())
            }));
            lines.push(String::new());
            lines.push("drag: camera; right-drag: light; wheel: zoom".into());
            lines.push("drop a height field, normal map or mesh on it".into());
            overlay::text(layer, &lines, Corner::TopLeft, 2);
        }
        let mut status = vec![self.viewer.status()];
        if self.viewer.view.frame_rate {
            status[0] = format!("{:.1} fps | {}", self.fps.value, status[0]);
        }
        if let Some(m) = &self.viewer.message {
            status.insert(0, m.clone());
        }
        overlay::text(layer, &status, Corner::BottomLeft, 1);
    }

    /// Copies `image` into the window's buffer (0RGB words) and shows it.
    fn present_soft(
        &mut self,
        w: NonZeroU32,
        h: NonZeroU32,
        image: &Rgba8Image,
    ) -> Result<(), softbuffer::SoftBufferError> {
        let Some(Presenter::Soft(surface)) = &mut self.presenter else { return Ok(()) };
        surface.resize(w, h)?;
        let mut buffer = surface.buffer_mut()?;
        for (out, &[r, g, b, _]) in buffer.iter_mut().zip(&image.texels) {
            *out = (r as u32) << 16 | (g as u32) << 8 | b as u32;
        }
        buffer.present()
    }

    /// After each frame of a scripted run: the next key, or the screenshot and the end.
    fn script_step(&mut self, event_loop: &ActiveEventLoop) {
        let Some(frames) = self.script.frames else { return };
        let now = Instant::now();
        if let Some((key, at)) = self.timing.key.take() {
            say!("{}: the next frame after {:.1} ms", key.name(), now.duration_since(at).as_secs_f64() * 1e3);
        }
        let first = *self.timing.first.get_or_insert(now);
        if self.frame >= frames {
            if frames > 1 {
                let seconds = now.duration_since(first).as_secs_f64();
                let (w, h) = match &self.drawn {
                    Some(Shown::Image(i) | Shown::Overlay(i)) => (i.width, i.height),
                    None => (0, 0),
                };
                say!(
                    "{} frames of {w}x{h} in {seconds:.2} s after the first: {:.1} frames/s ({} on {})",
                    frames - 1,
                    (frames - 1) as f64 / seconds,
                    self.viewer.technique(),
                    self.renderer.describe()
                );
            }
            if let Some(path) = self.script.screenshot.clone() {
                match self.screenshot(Some(&path)) {
                    Ok(p) => say!("wrote {}", p.display()),
                    Err(e) => return self.fail(event_loop, e),
                }
            }
            event_loop.exit();
            return;
        }
        if let Some(&action) = self.script.keys.get(self.frame - 1) {
            self.act(event_loop, action);
        }
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let (w, h) = self.size;
        let attributes = Window::default_attributes()
            .with_title(self.title())
            .with_inner_size(PhysicalSize::new(w as u32, h as u32));
        let window = match event_loop.create_window(attributes) {
            Ok(w) => Arc::new(w),
            Err(e) => return self.fail(event_loop, no_display(&format!("the window could not be made: {e}"))),
        };
        match presenter(&self.renderer, &window) {
            Ok((p, note)) => {
                if let Some(note) = note {
                    say!("{note}");
                    self.viewer.message = Some(note);
                }
                self.presenter = Some(p);
                window.request_redraw();
                self.window = Some(window);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(_) => self.redraw(),
            WindowEvent::RedrawRequested => self.draw(event_loop),
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                let action = match &event.logical_key {
                    Key::Named(NamedKey::Space) => Some(Action::Pause),
                    Key::Named(NamedKey::Escape) => Some(Action::Quit),
                    Key::Named(NamedKey::F1) => Some(Action::Help),
                    Key::Character(s) => s.chars().next().and_then(Action::for_key),
                    _ => None,
                };
                if let Some(action) = action {
                    self.act(event_loop, action);
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                self.dragging = (state == ElementState::Pressed).then_some(button);
            }
            WindowEvent::CursorMoved { position, .. } => {
                let (x, y) = (position.x, position.y);
                if let (Some((px, py)), Some(button)) = (self.cursor, self.dragging) {
                    let (dx, dy) = ((x - px) as f32, (y - py) as f32);
                    match button {
                        MouseButton::Left => self.viewer.orbit_camera(dx * 0.01, dy * 0.01),
                        MouseButton::Right => self.viewer.move_light(dx / self.size.0 as f32, -dy * 0.01),
                        _ => {}
                    }
                    self.redraw();
                }
                self.cursor = Some((x, y));
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                self.viewer.zoom(steps);
                self.redraw();
            }
            WindowEvent::DroppedFile(path) => {
                match self.viewer.load(&path) {
                    Ok(note) => say!("{note}"),
                    Err(e) => {
                        say!("{e}");
                        self.viewer.message = Some(e);
                    }
                }
                self.redraw();
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if self.viewer.animating() || self.script.frames.is_some() {
            event_loop.set_control_flow(ControlFlow::Poll);
            self.redraw();
        } else {
            event_loop.set_control_flow(ControlFlow::Wait);
        }
    }
}
