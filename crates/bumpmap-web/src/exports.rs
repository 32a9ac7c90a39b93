//! The functions the page's JavaScript calls (`web/app.js`), over the module's linear memory:
//! the page copies its input into a buffer from `bm_alloc`, calls, and reads the answer (an
//! image, a file, names, or an error message) through `bm_answer_ptr` and `bm_answer_len`.
//! Each call's status: 0 done, 1 what it was given could not be used, 2 an option or its value
//! is wrong (the command line's exit statuses). The answer lives until the next call.
//!
//! This is the crate's only `unsafe`: turning the page's pointers into slices.

use std::sync::Mutex;

use crate::{Dropped, Names, WebError};

/// The last call's answer: its bytes, and an image's size (0 × 0 for anything else).
struct Answer {
    bytes: Vec<u8>,
    width: u32,
    height: u32,
}

static ANSWER: Mutex<Answer> = Mutex::new(Answer { bytes: Vec::new(), width: 0, height: 0 });

fn answer(bytes: Vec<u8>, width: u32, height: u32) {
    let mut a = ANSWER.lock().unwrap_or_else(|p| p.into_inner());
    *a = Answer { bytes, width, height };
}

/// Keeps `result`'s bytes (or its error's message) as the answer; the call's status.
fn finish(result: Result<(Vec<u8>, u32, u32), WebError>) -> u32 {
    match result {
        Ok((bytes, w, h)) => {
            answer(bytes, w, h);
            0
        }
        Err(e) => {
            let status = if e.is_usage() { 2 } else { 1 };
            answer(e.to_string().into_bytes(), 0, 0);
            status
        }
    }
}

/// `len` bytes at `ptr` (nothing for a null pointer or no length).
///
/// # Safety
/// `ptr` is null, or `len` bytes there are readable and stay unchanged for `'a`: the page hands
/// in buffers from [`bm_alloc`] it filled and does not touch during the call.
unsafe fn bytes<'a>(ptr: *const u8, len: usize) -> &'a [u8] {
    if ptr.is_null() || len == 0 {
        return &[];
    }
    // SAFETY: the caller's contract above.
    unsafe { std::slice::from_raw_parts(ptr, len) }
}

/// A buffer of `len` zeroed bytes for the page to fill, or null where the module's memory cannot
/// hold it (a file too large; the page says so); give it back with [`bm_free`].
#[unsafe(no_mangle)]
pub extern "C" fn bm_alloc(len: usize) -> *mut u8 {
    let mut buffer = Vec::new();
    if buffer.try_reserve_exact(len).is_err() {
        return std::ptr::null_mut();
    }
    buffer.resize(len, 0u8);
    Box::into_raw(buffer.into_boxed_slice()).cast()
}

/// Gives back a buffer from [`bm_alloc`].
///
/// # Safety
/// `ptr` and `len` are one [`bm_alloc`]'s pointer and length, not given back before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bm_free(ptr: *mut u8, len: usize) {
    if !ptr.is_null() {
        // SAFETY: the caller's contract: the box `bm_alloc` made of exactly this length.
        drop(unsafe { Box::from_raw(std::ptr::slice_from_raw_parts_mut(ptr, len)) });
    }
}

/// Where the last call's answer starts.
#[unsafe(no_mangle)]
pub extern "C" fn bm_answer_ptr() -> *const u8 {
    ANSWER.lock().unwrap_or_else(|p| p.into_inner()).bytes.as_ptr()
}

/// How long the last call's answer is, in bytes.
#[unsafe(no_mangle)]
pub extern "C" fn bm_answer_len() -> usize {
    ANSWER.lock().unwrap_or_else(|p| p.into_inner()).bytes.len()
}

/// The last answer's width, if it is an image (RGBA8, row 0 at the top).
#[unsafe(no_mangle)]
pub extern "C" fn bm_answer_width() -> u32 {
    ANSWER.lock().unwrap_or_else(|p| p.into_inner()).width
}

/// The last answer's height, if it is an image.
#[unsafe(no_mangle)]
pub extern "C" fn bm_answer_height() -> u32 {
    ANSWER.lock().unwrap_or_else(|p| p.into_inner()).height
}

/// The text of `args` and the file `name`d with its bytes, or `None` where no file is given.
///
/// # Safety
/// As [`bytes`], for each pointer.
unsafe fn inputs<'a>(
    args: (*const u8, usize),
    name: (*const u8, usize),
    file: (*const u8, usize),
) -> Result<(&'a str, Option<Dropped<'a>>), WebError> {
    let text = |b: &'a [u8], what: &str| {
        std::str::from_utf8(b).map_err(|_| WebError::Usage(format!("the {what} are not UTF-8")))
    };
    // SAFETY: the caller's contract, passed on.
    let (args, name, file) = unsafe { (bytes(args.0, args.1), bytes(name.0, name.1), bytes(file.0, file.1)) };
    let args = text(args, "options")?;
    let name = text(name, "file's name characters")?;
    Ok((args, (!file.is_empty()).then_some(Dropped { name, bytes: file })))
}

std::thread_local! {
    /// The scene [`bm_view`] prepared, drawn by [`bm_view_draw`].
    static VIEW: std::cell::RefCell<Option<crate::View>> = const { std::cell::RefCell::new(None) };
}

/// [`crate::View::new`]: prepares the scene the options (and the file) describe, as
/// [`crate::render`] reads them, and keeps it for [`bm_view_draw`]; the answer is empty, or the
/// message.
///
/// # Safety
/// Each pointer is null or has its length of readable bytes for the call ([`bm_alloc`]'s).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bm_view(
    args: *const u8,
    args_len: usize,
    name: *const u8,
    name_len: usize,
    file: *const u8,
    file_len: usize,
) -> u32 {
    // SAFETY: the caller's contract, passed on.
    let inputs = unsafe { inputs((args, args_len), (name, name_len), (file, file_len)) };
    finish(inputs.and_then(|(args, file)| {
        let view = crate::View::new(args, file)?;
        VIEW.with(|v| *v.borrow_mut() = Some(view));
        Ok((Vec::new(), 0, 0))
    }))
}

/// [`crate::View::draw`] of the kept scene, the light turned `light_turns` round and tilted
/// `light_tilt` radians, the camera turned `yaw` and tilted `pitch` radians: the answer is the
/// frame, RGBA8 (status 1 before any [`bm_view`]).
#[unsafe(no_mangle)]
pub extern "C" fn bm_view_draw(light_turns: f32, light_tilt: f32, yaw: f32, pitch: f32) -> u32 {
    let turn = crate::Turn { light_turns, light_tilt, camera_yaw: yaw, camera_pitch: pitch };
    let drawn = VIEW.with(|v| match v.borrow_mut().as_mut() {
        Some(view) => view.draw(turn),
        None => Err(WebError::Usage("no scene is prepared: call bm_view first".into())),
    });
    finish(drawn.map(|image| (image.as_bytes().to_vec(), image.width as u32, image.height as u32)))
}

/// [`crate::map_file`] of the file numbered `what` in [`crate::MapFile::ALL`] (0 the normal
/// map's PNG, 1 its KTX2, 2 the heights' PNG, 3 the occlusion's PNG, 4 the bent normals' PNG),
/// the heights the file's,
/// or the preset's that `preset` names: the answer is the file.
///
/// # Safety
/// Each pointer is null or has its length of readable bytes for the call ([`bm_alloc`]'s).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bm_map_file(
    args: *const u8,
    args_len: usize,
    name: *const u8,
    name_len: usize,
    file: *const u8,
    file_len: usize,
    preset: *const u8,
    preset_len: usize,
    what: u32,
) -> u32 {
    // SAFETY: the caller's contract, passed on.
    let inputs = unsafe { inputs((args, args_len), (name, name_len), (file, file_len)) };
    // SAFETY: as above.
    let preset = unsafe { bytes(preset, preset_len) };
    finish(inputs.and_then(|(args, file)| {
        let preset = std::str::from_utf8(preset).map_err(|_| WebError::Usage("the preset is not UTF-8".into()))?;
        let what = *crate::MapFile::ALL.get(what as usize).ok_or_else(|| {
            WebError::Usage(format!("no map file numbered {what} (0 to {})", crate::MapFile::ALL.len() - 1))
        })?;
        Ok((crate::map_file(args, file, preset, what)?, 0, 0))
    }))
}

/// [`crate::inspect`] of the file `name`d: the answer is the verdict's lines.
///
/// # Safety
/// Each pointer is null or has its length of readable bytes for the call ([`bm_alloc`]'s).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bm_inspect(name: *const u8, name_len: usize, file: *const u8, file_len: usize) -> u32 {
    // SAFETY: the caller's contract, passed on.
    let inputs = unsafe { inputs((std::ptr::null(), 0), (name, name_len), (file, file_len)) };
    finish(inputs.and_then(|(_, file)| {
        let file = file.ok_or_else(|| WebError::Usage("no file to inspect".into()))?;
        Ok((crate::inspect(file)?.into_bytes(), 0, 0))
    }))
}

/// [`crate::names`] of set 0 (techniques), 1 (scenes), 2 (presets) or 3 (the files saved): the
/// answer is the names, one a line.
#[unsafe(no_mangle)]
pub extern "C" fn bm_names(set: u32) -> u32 {
    let set = match set {
        0 => Names::Techniques,
        1 => Names::Scenes,
        2 => Names::Presets,
        3 => Names::MapFiles,
        other => return finish(Err(WebError::Usage(format!("no set of names {other}")))),
    };
    finish(Ok((crate::names(set).into_bytes(), 0, 0)))
}
