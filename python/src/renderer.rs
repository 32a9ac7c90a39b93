//! `Renderer` and `Scene`: a backend opened once (the GPU's adapter and pipelines kept) and a
//! scene set up and prepared once, drawn frame after frame with the light or the eye moved; and
//! the arrays `render` takes where the command line takes files (a `bumpmap.Mesh` as the scene).
//!
//! Both sit on the library's `bumpmap::Renderer` and `bumpmap::Prepared`, prepared by
//! `bumpmap::frame::prepare_frame` as `bumpmap render` prepares them, so a frame is the
//! command's frame; `render()` is [`draw`], the same steps for one frame.
//!
//! What it does not do: read frames back asynchronously, or draw one scene on another
//! renderer's backend (a scene keeps the renderer it was prepared for).

use std::sync::{Arc, Mutex, PoisonError};

use bumpmap::frame::{Frame, FrameRequest, PreparedFrame};
use bumpmap::maps::Chain;
use bumpmap::options::Given;
use bumpmap_words::Error;
use bumpmap_words::frame::{frame_err, lib_err, note_fallback, say_frame_notes};
use bumpmap_words::report::ReportFn;
use glam::Vec3;
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::to_py;
use crate::{arrays, interrupt, keywords};

/// Sets up and prepares what `request` describes, with the inputs `given` in memory, a horizon
/// map's rows told to `progress`, and says what that noted as `render` says it (warnings through
/// `warnings`, notes to the logger, once the work returns); returns the notes too, in Python's
/// words.
fn prepare(
    request: &FrameRequest,
    given: &Given,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(PreparedFrame, Vec<String>), Error> {
    let prepared = bumpmap::frame::prepare_frame_told(request, given, progress)
        .map_err(|e| frame_err(e, &request.options, None))?;
    let notes = say_frame_notes(&prepared).iter().map(|n| bumpmap_words::as_keywords(n)).collect();
    Ok((prepared, notes))
}

/// Opens `backend`; with `auto`, notes why it draws on the CPU, if it does.
fn open(backend: bumpmap::BackendChoice) -> Result<bumpmap::Renderer, Error> {
    let renderer = bumpmap::Renderer::new(backend).map_err(lib_err)?;
    note_fallback(&renderer);
    Ok(renderer)
}

/// `render()`'s frame: what `request` describes prepared ([`prepare`]) and drawn on its
/// backend, a horizon map's rows and then the reference's tiles told to `progress`; a black
/// frame refused.
pub fn draw(request: &FrameRequest, given: &Given, progress: Option<ReportFn>) -> Result<Frame, Error> {
    let rows = |done: usize, total: usize| {
        if let Some(f) = &progress {
            f(done as u64, total as u64);
        }
    };
    let (prepared, _) = prepare(request, given, &rows)?;
    let progress: Option<bumpmap::renderer::Progress> =
        progress.map(|f| Arc::new(move |done: usize, total: usize| f(done as u64, total as u64)) as _);
    let mut renderer = bumpmap::frame::renderer_for(request, progress).map_err(lib_err)?;
    note_fallback(&renderer);
    bumpmap::frame::draw_frame(&mut renderer, &prepared, request.passes)
        .map_err(|e| frame_err(e, &request.options, None))
}

/// A `bumpmap.Mesh` (anything with its attributes) given for `keyword`, which must be `what`
/// otherwise: the mesh a file would give, without a material.
pub(crate) fn mesh_object(
    function: &str,
    (keyword, what): (&str, &str),
    scene: &Bound<'_, PyAny>,
) -> PyResult<bumpmap_io::LoadedMesh> {
    let get = |name: &str| {
        scene.getattr(name).map_err(|_| {
            let kind = scene.get_type().name().map(|n| n.to_string()).unwrap_or_default();
            PyTypeError::new_err(format!(
                "{function}(): {keyword} must be {what} or a bumpmap.Mesh, not {kind} (it has no {name})"
            ))
        })
    };
    let (positions, normals, uvs, tangents, indices) =
        (get("positions")?, get("normals")?, get("uvs")?, get("tangents")?, get("indices")?);
    let (mesh, had_normals, had_tangents) =
        arrays::mesh(function, &positions, &normals, &uvs, Some(&tangents), &indices)?;
    Ok(bumpmap_io::LoadedMesh { mesh, had_normals, had_tangents, ..Default::default() })
}

/// A frame as the array `render` returns: (H, W, 4) uint8, alpha 255 (the framebuffer's alpha
/// holds s_self, not coverage; the command line's PNG leaves it out).
pub fn frame_array<'py>(py: Python<'py>, mut image: bumpmap::Rgba8Image) -> PyResult<Bound<'py, PyAny>> {
    for t in &mut image.texels {
        t[3] = 255;
    }
    let level = bumpmap_math::Image::new(image.width, image.height, image.texels);
    let chain = Chain::Rgba8(bumpmap_math::MipChain { levels: vec![level], encoding: Default::default() });
    Ok(arrays::from_chain(py, chain)?.swap_remove(0))
}

/// The library's renderer, `None` once closed.
type Shared = Arc<Mutex<Option<bumpmap::Renderer>>>;

fn closed() -> PyErr {
    PyRuntimeError::new_err("this Renderer is closed: make a new one")
}

/// A backend opened once: its device, pipelines and texture caches are kept between frames.
#[pyclass(module = "bumpmap._bumpmap", frozen)]
pub struct Renderer {
    inner: Shared,
}

#[pymethods]
impl Renderer {
    /// Opens `backend` ("cpu", "gpu" or "auto"): on the GPU, the adapter and device.
    #[new]
    #[pyo3(signature = (backend = "cpu".to_string()))]
    fn new(py: Python<'_>, backend: String) -> PyResult<Self> {
        let choice: bumpmap::BackendChoice = bumpmap::Named::parse(&backend).ok_or_else(|| {
            PyValueError::new_err(format!(
                "Renderer(): invalid value '{backend}' for backend; possible values: {}",
                <bumpmap::BackendChoice as bumpmap::Named>::names().join(", ")
            ))
        })?;
        let renderer = interrupt::run(py, move |_| open(choice))?.map_err(|e| to_py("Renderer", e))?;
        Ok(Self { inner: Arc::new(Mutex::new(Some(renderer))) })
    }

    /// What it draws on, in words (the CPU, or the GPU adapter's name and driver).
    fn describe(&self) -> PyResult<String> {
        let inner = self.inner.lock().unwrap_or_else(PoisonError::into_inner);
        inner.as_ref().map(|r| r.describe()).ok_or_else(closed)
    }

    /// Frees the device and caches; the renderer and its scenes refuse to draw afterwards.
    fn close(&self) {
        self.inner.lock().unwrap_or_else(PoisonError::into_inner).take();
    }

    /// Whether [`Renderer::close`] was called.
    #[getter]
    fn closed(&self) -> bool {
        self.inner.lock().unwrap_or_else(PoisonError::into_inner).is_none()
    }

    /// Sets up and prepares a scene from `render`'s options (arrays or files; the backend is
    /// this renderer's): the maps are made once, for every frame drawn of it.
    #[pyo3(signature = (options = None))]
    fn prepare(&self, py: Python<'_>, options: Option<&Bound<'_, PyDict>>) -> PyResult<Scene> {
        if self.closed() {
            return Err(closed());
        }
        if let Some(options) = options
            && options.contains("backend")?
        {
            return Err(PyTypeError::new_err(
                "prepare(): the backend is the Renderer's (Renderer(backend=...)), not a scene's option",
            ));
        }
        let (request, given) = keywords::render_request(py, "prepare", options, false)?;
        let technique = request.options.technique.technique.name().to_string();
        // Its notes said once, when the scene is prepared; `Scene.notes` keeps them too. The
        // horizon map's rows are told to nobody, but Ctrl-C stops the work at the next one.
        let (prepared, notes) = interrupt::run_reporting(
            py,
            move |_, shown| {
                prepare(&request, &given, &|done, total| {
                    if let Some(f) = &shown {
                        f(done as u64, total as u64);
                    }
                })
            },
            None,
        )?
        .map_err(|e| to_py("prepare", e))?;
        Ok(Scene {
            renderer: self.inner.clone(),
            prepared: Arc::new(Mutex::new(prepared.prepared)),
            size: prepared.size,
            technique,
            notes,
        })
    }
}

/// A scene set up and prepared once, drawn by its renderer frame after frame.
#[pyclass(module = "bumpmap._bumpmap", frozen)]
pub struct Scene {
    renderer: Shared,
    prepared: Arc<Mutex<bumpmap::Prepared>>,
    size: (usize, usize),
    technique: String,
    notes: Vec<String>,
}

/// A vector from a 3-sequence of numbers, finite.
fn vec3(what: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec3> {
    let v: [f32; 3] = value.extract().map_err(|_| {
        PyTypeError::new_err(format!("Scene.render(): {what} must be three numbers (x, y, z), got {value}"))
    })?;
    let v = Vec3::from(v);
    if !v.is_finite() {
        return Err(PyValueError::new_err(format!("Scene.render(): {what} must be finite, got {v}")));
    }
    Ok(v)
}

#[pymethods]
impl Scene {
    /// Draws a frame: with `light`, the first light moved to that point (world space; a
    /// directional light turned to come from it), with `eye`, the camera moved there (still
    /// looking at its target). Both stay where they are put for later frames.
    #[pyo3(signature = (light = None, eye = None))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        light: Option<&Bound<'py, PyAny>>,
        eye: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let light = light.map(|l| vec3("light", l)).transpose()?;
        let eye = eye.map(|e| vec3("eye", e)).transpose()?;
        let (renderer, prepared, (w, h)) = (self.renderer.clone(), self.prepared.clone(), self.size);
        // The locks are taken on the worker thread, outside the pool (see `run_beside_pool`).
        let image = interrupt::run_beside_pool(py, move |_, pool| {
            let mut prepared = prepared.lock().unwrap_or_else(PoisonError::into_inner);
            if let Some(at) = light {
                bumpmap::motion::move_first_light(&mut prepared.scene, at);
            }
            if let Some(eye) = eye {
                bumpmap::motion::move_eye(&mut prepared.scene, eye).map_err(bumpmap::Error::Core)?;
            }
            let mut renderer = renderer.lock().unwrap_or_else(PoisonError::into_inner);
            // None: the renderer was closed.
            let Some(renderer) = renderer.as_mut() else { return Ok(None) };
            pool.install(|| renderer.draw_scene(&prepared.scene, &prepared.technique, w, h, None)).map(Some)
        })?
        .map_err(|e| to_py("Scene.render", lib_err(e)))?
        .ok_or_else(closed)?;
        frame_array(py, image)
    }

    /// The frame's (width, height).
    #[getter]
    fn size(&self) -> (usize, usize) {
        self.size
    }

    /// The technique it is drawn with.
    #[getter]
    fn technique(&self) -> &str {
        &self.technique
    }

    /// What setting it up noted (what a glTF's material gave, what was left out), a line each.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }
}
