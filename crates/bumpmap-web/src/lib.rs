//! bumpmap on a web page: what the page (`web/`) asks of the library, as the command line asks
//! it, behind a handful of functions over the module's linear memory.
//!
//! The page speaks the command line's language: each call takes `name=value` lines, the options
//! of `bumpmap render` or `bumpmap normalmap` by their command-line names, read through the
//! library's option tables (`bumpmap::option_table`), so the page has the same options, defaults
//! and checks as the command line and the Python module. A file the user drops travels as its
//! bytes, decoded here by the library's readers as the command line decodes the file.
//!
//! - [`render`]: a frame of a built-in scene on the CPU renderer (the emulated GeForce 256, one
//!   thread in a browser), as RGBA8;
//! - [`map_file`]: a height field's normal map as the PNG (level 0, 8 or 16 bits) or the KTX2
//!   (every level) `bumpmap normalmap` writes, its heights, ambient occlusion or bent normals as
//!   the PNG `--height-out`, `--ao-out` or `--bent-normals-out` writes, byte for byte;
//! - [`inspect`]: `bumpmap inspect`'s verdict on a normal map the user gave;
//! - [`names`]: the closed sets the page's menus list (techniques, scenes, presets).
//!
//! `exports` wraps them for JavaScript (pointers and lengths; the answer kept until the next
//! call). What this crate does not do: draw through WebGPU (the GPU backend waits
//! synchronously, which a browser forbids, and its bindings need wasm-bindgen's tool), read
//! meshes, or hold any logic of its own beyond reading the lines.

pub mod exports;

use std::path::Path;

use bumpmap::frame::{FrameRequest, draw_frame, prepare_frame};
use bumpmap::maps::{Chain, MapOptions};
use bumpmap::option_table::{self, FRAME, MAPS, Opt, SCENE};
use bumpmap::options::{Given, SceneChoice};
use bumpmap::{BackendChoice, Renderer, Rgba8Image};
use bumpmap_io::image_file::Png16;
use bumpmap_io::{Channel, DecodeLimits, HeightSource};
use bumpmap_math::HeightField;

/// The largest side of an image the page decodes: a 4096² RGBA image at 16 bits is 128 MiB,
/// and a wasm module has at most 4 GiB for everything it holds while working on it.
pub const MAX_SIDE: u32 = 4096;

/// Why a call made nothing.
#[derive(Debug, thiserror::Error)]
pub enum WebError {
    /// A line that is not `name=value` or `name`, or a name no table has.
    #[error("{0}")]
    Usage(String),
    /// A value the option does not take.
    #[error("{name}: {reason}")]
    Value {
        /// The option, as the command line spells it.
        name: String,
        /// What is wrong with the value.
        reason: String,
    },
    /// The dropped file (or a preset) could not be read.
    #[error(transparent)]
    Io(#[from] bumpmap_io::IoError),
    /// The frame could not be drawn.
    #[error(transparent)]
    Frame(#[from] bumpmap::frame::FrameError),
    /// The renderer could not start.
    #[error(transparent)]
    Renderer(#[from] bumpmap::Error),
    /// The normal map could not be made.
    #[error(transparent)]
    Map(#[from] bumpmap::maps::MapError),
}

impl WebError {
    /// Whether the call itself was wrong (an option or its value), as the command line's exit
    /// status 2 says, rather than what it was given.
    pub fn is_usage(&self) -> bool {
        matches!(self, WebError::Usage(_) | WebError::Value { .. })
    }
}

/// A file the user gave the page: its name (what messages call it) and its bytes.
#[derive(Clone, Copy, Debug)]
pub struct Dropped<'a> {
    /// The file's name.
    pub name: &'a str,
    /// Its contents.
    pub bytes: &'a [u8],
}

/// `(name, value)` for each non-empty line of `args`: `name=value`, or `name` alone for a flag
/// (`true`).
fn lines(args: &str) -> Result<Vec<(&str, &str)>, WebError> {
    args.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(|l| match l.split_once('=') {
            Some((name, value)) if !name.trim().is_empty() => Ok((name.trim(), value.trim())),
            Some(_) => Err(WebError::Usage(format!("'{l}' names no option"))),
            None => Ok((l, "true")),
        })
        .collect()
}

/// Sets each line into `options` through the first of `tables` that has its name, then checks
/// what the options need or exclude together.
fn read_into<R: Default>(options: &mut R, args: &str, tables: &[&[Opt<R>]]) -> Result<(), WebError> {
    let given = lines(args)?;
    for (name, text) in &given {
        let row = tables
            .iter()
            .find_map(|t| option_table::find(t, name))
            .ok_or_else(|| WebError::Usage(format!("unknown option '{name}'")))?;
        let value = row.parse_text(text).map_err(|reason| WebError::Value { name: row.name.into(), reason })?;
        row.set(options, value).map_err(|reason| WebError::Value { name: row.name.into(), reason })?;
    }
    let names: Vec<&str> = given.iter().map(|(n, _)| n.trim_start_matches("--")).collect();
    for table in tables {
        option_table::check_together(table, &names).map_err(|t| WebError::Usage(together(&t)))?;
    }
    Ok(())
}

/// [`option_table::Together`] in words.
fn together(t: &option_table::Together) -> String {
    match t {
        option_table::Together::Needs { option, needs } => format!("{option} is given only with {needs}"),
        option_table::Together::Excludes { option, other } => format!("{option} and {other} cannot both be given"),
    }
}

/// What the page decodes at most: [`MAX_SIDE`] a side, 1 GiB for the decoder.
fn limits() -> DecodeLimits {
    DecodeLimits { max_dimension: MAX_SIDE, max_alloc: 1 << 30 }
}

/// The heights in `file`'s image (its luminance, as `normalmap` reads a colour image), no side
/// over [`MAX_SIDE`].
fn heights_of(file: Dropped) -> Result<HeightField, WebError> {
    Ok(bumpmap_io::read_height_field(file.bytes, Path::new(file.name), Channel::Luminance, &limits())?)
}

/// A frame as `bumpmap render` draws it with the options in `args` (`render`'s names:
/// `technique=pom`, `scene=sphere`, `light=dir:1,1,2`, `width=800`, …), on the CPU renderer.
/// `file`, where given, is a mesh by its name's extension (`.glb`, `.gltf`, `.obj`: the scene,
/// drawn with its own material; a `.gltf` brings its buffers and images as `data:` URIs, as a
/// page has no folder to find files in), the normal map where the options name one
/// (`normal-map=NAME`), or else the height field.
///
/// ```
/// let frame = bumpmap_web::render("technique=single-pass\nsize=64", None).unwrap();
/// assert_eq!((frame.width, frame.height), (64, 64));
/// assert!(bumpmap_web::render("technique=nonesuch", None).unwrap_err().is_usage());
/// ```
pub fn render(args: &str, file: Option<Dropped>) -> Result<Rgba8Image, WebError> {
    View::new(args, file)?.draw(Turn::default())
}

/// How far the light and the camera are turned from where the options put them, as `bumpmap
/// view`'s mouse turns them (`bumpmap::motion`): the light round the point looked at and up
/// toward the view's up axis, the camera likewise.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Turn {
    /// Turns of the light about the up axis (1: once round).
    pub light_turns: f32,
    /// Radians the light is tilted toward the up axis.
    pub light_tilt: f32,
    /// Radians the camera is turned about the up axis.
    pub camera_yaw: f32,
    /// Radians the camera is tilted toward the up axis.
    pub camera_pitch: f32,
}

/// A scene prepared once from the options (its maps made) and drawn as often as wanted while the
/// light and the camera move: what the page keeps while the picture is dragged.
///
/// ```
/// use bumpmap_web::{Turn, View};
/// let mut view = View::new("size=48\ntechnique=single-pass", None).unwrap();
/// let still = view.draw(Turn::default()).unwrap();
/// let turned = view.draw(Turn { light_turns: 0.5, ..Turn::default() }).unwrap();
/// assert_ne!(still.texels, turned.texels);
/// assert_eq!(still.texels, bumpmap_web::render("size=48\ntechnique=single-pass", None).unwrap().texels);
/// ```
pub struct View {
    frame: bumpmap::frame::PreparedFrame,
    renderer: Renderer,
    /// The scene as prepared, whose light and camera each draw starts from.
    scene: bumpmap_core::Scene,
    orbit: bumpmap::motion::LightOrbit,
}

impl View {
    /// The scene `args` and `file` describe, as [`render`] reads them, prepared.
    pub fn new(args: &str, file: Option<Dropped>) -> Result<View, WebError> {
        let frame = prepare(args, file)?;
        let scene = frame.prepared.scene.clone();
        let orbit = bumpmap::motion::LightOrbit::of(&scene);
        Ok(View { frame, renderer: Renderer::new(BackendChoice::Cpu)?, scene, orbit })
    }

    /// The scene drawn with the light and the camera turned by `turn`.
    pub fn draw(&mut self, turn: Turn) -> Result<Rgba8Image, WebError> {
        // Only the light and the camera move; the rest of the scene stays as prepared.
        let scene = &mut self.frame.prepared.scene;
        scene.lights.clone_from(&self.scene.lights);
        scene.camera = self.scene.camera;
        // Unturned, the scene is exactly as prepared (a turn by zero still rounds).
        if turn.light_turns != 0.0 || turn.light_tilt != 0.0 {
            self.orbit.place(scene, turn.light_turns, turn.light_tilt);
        }
        if turn.camera_yaw != 0.0 || turn.camera_pitch != 0.0 {
            scene.camera = bumpmap::motion::orbit_camera(&self.scene.camera, turn.camera_yaw, turn.camera_pitch, 1.0);
        }
        Ok(draw_frame(&mut self.renderer, &self.frame, false)?.image)
    }
}

/// The frame `args` and `file` describe, prepared as `bumpmap render` prepares it.
fn prepare(args: &str, file: Option<Dropped>) -> Result<bumpmap::frame::PreparedFrame, WebError> {
    let mut request = FrameRequest { size: (512, 512), ..Default::default() };
    read_into(&mut request, args, &[SCENE, FRAME])?;
    request.backend = BackendChoice::Cpu;
    let mut given = Given::default();
    match file {
        Some(file) if let Some(format) = bumpmap_io::MeshFormat::from_path(Path::new(file.name)) => {
            request.options.scene = SceneChoice::Mesh(file.name.into());
            given.mesh = Some(bumpmap_io::read_mesh(file.bytes, Path::new(file.name), format)?);
        }
        // The options name it as the normal map: drawn as it is, with its own levels.
        Some(file) if request.options.normal_map.is_some() => {
            given.normal_map = Some(bumpmap_io::read_texture(file.bytes, Path::new(file.name), &limits())?);
        }
        Some(file) => {
            if request.options.height_field.is_none() {
                request.options.height_field = Some(HeightSource::File(file.name.into()));
            }
            given.height_field = Some(heights_of(file)?);
        }
        None => {}
    }
    Ok(prepare_frame(&request, &given)?)
}

/// A file the page saves: one of the files `bumpmap normalmap HEIGHTS` writes, byte for byte.
/// The bits are the options' (`bits=16`; 8 by default), as on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapFile {
    /// The normal map, level 0, as `-o OUT.png` writes it.
    NormalPng,
    /// The normal map with every level down to 1×1, as `-o OUT.ktx2 --mips` writes it.
    NormalKtx2,
    /// The heights as geometry, level 0, as `--height-out H.png` writes `H.png`.
    HeightsPng,
    /// The ambient occlusion of the heights' horizons, as `--ao-out AO.png` writes it.
    OcclusionPng,
    /// The bent normals of the heights' horizons, as `--bent-normals-out B.png` writes it.
    BentNormalsPng,
}

impl MapFile {
    /// Its name in the page's save menu (`WHAT-CONTAINER`; the menu adds the bits).
    pub fn name(self) -> &'static str {
        match self {
            MapFile::NormalPng => "normal-png",
            MapFile::NormalKtx2 => "normal-ktx2",
            MapFile::HeightsPng => "heights-png",
            MapFile::OcclusionPng => "occlusion-png",
            MapFile::BentNormalsPng => "bent-png",
        }
    }

    /// What the saved file's name ends with after the heights' own (`bricks_normal.png`).
    pub fn suffix(self) -> &'static str {
        match self {
            MapFile::NormalPng => "_normal.png",
            MapFile::NormalKtx2 => "_normal.ktx2",
            MapFile::HeightsPng => "_heights.png",
            MapFile::OcclusionPng => "_ao.png",
            MapFile::BentNormalsPng => "_bent.png",
        }
    }

    /// Each file, in the order of its number in [`exports::bm_map_file`].
    pub const ALL: [MapFile; 5] =
        [MapFile::NormalPng, MapFile::NormalKtx2, MapFile::HeightsPng, MapFile::OcclusionPng, MapFile::BentNormalsPng];
}

/// The file `what` of the heights in `file`, or of the preset `preset` names (`bricks@256`),
/// made with `normalmap`'s options in `args` (`normalmap`'s names: `scale=4`, `kernel=sobel3`,
/// `y-convention=directx`, `bits=16`, …).
///
/// ```
/// use bumpmap_web::{MapFile, map_file};
/// let png = map_file("scale=4", None, "bricks@64", MapFile::NormalPng).unwrap();
/// assert_eq!(&png[1..4], b"PNG");
/// let ktx2 = map_file("bits=16", None, "bricks@64", MapFile::NormalKtx2).unwrap();
/// assert_eq!(&ktx2[1..7], b"KTX 20");
/// let heights = map_file("bits=16", None, "bricks@64", MapFile::HeightsPng).unwrap();
/// assert_eq!((heights[24], heights[25]), (16, 0), "16 bits a sample, gray");
/// ```
pub fn map_file(args: &str, file: Option<Dropped>, preset: &str, what: MapFile) -> Result<Vec<u8>, WebError> {
    use bumpmap_io::height_file::{HeightBits, gray_png_bytes};
    use bumpmap_io::texture_file::TextureFormat;
    let (options, field) = map_inputs(args, file, preset)?;
    let bits = HeightBits::of(options.bits);
    match what {
        MapFile::NormalPng => level0_png(&bumpmap::maps::normal_map(&options, false, &field)?),
        MapFile::NormalKtx2 => {
            let chain = bumpmap::maps::normal_map(&options, true, &field)?;
            let format = if options.bits == 16 { TextureFormat::Rgba16 } else { TextureFormat::Rgba8 };
            let name = Path::new(file.map_or(preset, |f| f.name));
            Ok(bumpmap_io::texture_file::ktx2_bytes(name, &bumpmap::maps::chain_layout(&chain), format)?)
        }
        MapFile::HeightsPng => {
            let stored = bumpmap::maps::height_mips(&options, &field)?;
            let level = &stored.mips.levels()[0];
            Ok(gray_png_bytes((level.width, level.height), &level.texels, bits)?)
        }
        MapFile::OcclusionPng => {
            let horizons = bumpmap::maps::horizon_map(&options, &field, &|_, _| {})?;
            // Texels per unit of height: the normal map's own geometry, as `normalmap` has it.
            let occlusion = horizons.ambient_occlusion(options.normals.scale.abs());
            Ok(gray_png_bytes((horizons.width(), horizons.height()), &occlusion, bits)?)
        }
        MapFile::BentNormalsPng => {
            let horizons = bumpmap::maps::horizon_map(&options, &field, &|_, _| {})?;
            level0_png(&bumpmap::maps::bent_normals(&options, &horizons))
        }
    }
}

/// Level 0 of `chain` as the PNG file a normal map's `-o OUT.png` is, at its bits.
fn level0_png(chain: &Chain) -> Result<Vec<u8>, WebError> {
    Ok(match chain {
        Chain::Rgba8(chain) => {
            let level = &chain.levels[0];
            bumpmap_io::png_file_bytes(level.width, level.height, bumpmap_io::PngLayout::Rgba8, level.as_bytes())?
        }
        Chain::Rgba16(chain) => {
            let level = &chain.levels[0];
            bumpmap_io::image_file::png16_file_bytes(
                level.width,
                level.height,
                Png16::Rgba,
                level.texels.as_flattened(),
            )?
        }
    })
}

/// `normalmap`'s options read from `args`, and the heights: `file`'s, or the preset's.
fn map_inputs(args: &str, file: Option<Dropped>, preset: &str) -> Result<(MapOptions, HeightField), WebError> {
    let mut options = MapOptions::default();
    read_into(&mut options, args, &[MAPS])?;
    let field = match file {
        Some(file) => heights_of(file)?,
        None => match HeightSource::parse(preset) {
            source @ HeightSource::Preset { .. } => source.load(Channel::Luminance)?,
            HeightSource::File(_) => {
                return Err(WebError::Usage(format!(
                    "'{preset}' is not a preset ({}, optionally @SIZE)",
                    bumpmap_math::HeightPreset::NAMES
                )));
            }
        },
    };
    Ok((options, field))
}

/// `inspect`'s verdict on a normal map the user gave (a PNG or other image, a DDS or a KTX2 with
/// its levels): the lines `bumpmap inspect FILE` prints.
///
/// ```
/// let png = bumpmap_web::map_file("", None, "bricks@64", bumpmap_web::MapFile::NormalPng).unwrap();
/// let file = bumpmap_web::Dropped { name: "bricks_normal.png", bytes: &png };
/// let verdict = bumpmap_web::inspect(file).unwrap();
/// assert!(verdict.contains("convention: opengl"), "{verdict}");
/// ```
pub fn inspect(file: Dropped) -> Result<String, WebError> {
    let map = bumpmap::inspect::read_bytes(file.bytes, Path::new(file.name), &limits())?;
    Ok(bumpmap::inspect::inspect_map(file.name, &map).lines().join("\n"))
}

/// A closed set the page lists, one name a line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Names {
    /// The technique catalogue, in `compare`'s order.
    Techniques,
    /// The built-in scenes.
    Scenes,
    /// The height-field presets.
    Presets,
    /// The files the page saves ([`MapFile`], in its order): `NAME SUFFIX` a line.
    MapFiles,
}

/// The names of `set`, one a line, as the command line spells them.
///
/// ```
/// use bumpmap_web::{Names, names};
/// assert!(names(Names::Techniques).lines().any(|t| t == "kilgard"));
/// assert!(names(Names::Scenes).lines().any(|s| s == "torus"));
/// assert_eq!(names(Names::MapFiles).lines().next(), Some("normal-png _normal.png"));
/// ```
pub fn names(set: Names) -> String {
    use bumpmap::TechniqueName;
    use bumpmap_core::SceneKind;
    match set {
        Names::Techniques => TechniqueName::ALL.map(TechniqueName::name).join("\n"),
        Names::Scenes => SceneKind::BUILT_IN.iter().map(SceneKind::name).collect::<Vec<_>>().join("\n"),
        // `noise:SEED` as the help says it: the page asks for the seed.
        Names::Presets => bumpmap_math::HeightPreset::NAMES.split(", ").collect::<Vec<_>>().join("\n"),
        Names::MapFiles => MapFile::ALL.map(|f| format!("{} {}", f.name(), f.suffix())).join("\n"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_names_and_values_and_a_bare_name_is_a_flag() {
        assert_eq!(lines("a=b\n\n  c = d e \nflag").unwrap(), [("a", "b"), ("c", "d e"), ("flag", "true")]);
        assert!(lines("=3").unwrap_err().is_usage());
    }

    #[test]
    fn options_are_checked_as_the_command_line_checks_them() {
        let e = render("nonesuch=1", None).unwrap_err();
        assert!(e.is_usage() && e.to_string().contains("nonesuch"), "{e}");
        let e = render("size=0", None).unwrap_err();
        assert!(e.is_usage() && e.to_string().starts_with("size:"), "{e}");
        let e = render("spot-cutoff=20", None).unwrap_err();
        assert!(e.is_usage() && e.to_string().contains("spot"), "needs --spot: {e}");
        let e = map_file("bits=12", None, "bricks", MapFile::NormalPng).unwrap_err();
        assert!(e.is_usage() && e.to_string().starts_with("bits:"), "{e}");
        let e = map_file("", None, "brick", MapFile::HeightsPng).unwrap_err();
        assert!(e.is_usage() && e.to_string().contains("brick"), "{e}");
    }

    #[test]
    fn a_dropped_file_that_is_not_an_image_is_named() {
        let file = Dropped { name: "notes.txt", bytes: b"not pixels" };
        let e = render("size=32", Some(file)).unwrap_err();
        assert!(!e.is_usage() && e.to_string().contains("notes.txt"), "{e}");
        let e = map_file("", Some(file), "bricks", MapFile::OcclusionPng).unwrap_err();
        assert!(e.to_string().contains("notes.txt"), "{e}");
    }

    #[test]
    fn a_dropped_height_field_is_the_one_drawn() {
        let field = bumpmap_math::HeightPreset::Pinwheel.render(64, 64);
        let png = bumpmap_io::png_file_bytes(64, 64, bumpmap_io::PngLayout::Gray8, &field.to_u8()).unwrap();
        let file = Dropped { name: "pinwheel.png", bytes: &png };
        let dropped = render("size=48\ntechnique=single-pass", Some(file)).unwrap();
        let bricks = render("size=48\ntechnique=single-pass", None).unwrap();
        let preset = render("size=48\ntechnique=single-pass\nheight-field=pinwheel@64", None).unwrap();
        let mean_difference = |a: &Rgba8Image, b: &Rgba8Image| {
            let d: u32 = a
                .texels
                .iter()
                .zip(&b.texels)
                .map(|(p, q)| p[..3].iter().zip(&q[..3]).map(|(x, y)| x.abs_diff(*y) as u32).sum::<u32>())
                .sum();
            d as f64 / (3 * a.texels.len()) as f64
        };
        // The same heights, but for the file's 8 bits.
        assert!(mean_difference(&dropped, &preset) < 1.0, "{}", mean_difference(&dropped, &preset));
        assert!(mean_difference(&dropped, &bricks) > 5.0, "{}", mean_difference(&dropped, &bricks));
    }

    #[test]
    fn a_dropped_mesh_is_the_scene_and_a_gltf_without_its_buffers_is_refused_by_name() {
        let dir = std::env::temp_dir().join(format!("bumpmap-web-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let glb = dir.join("cube.glb");
        let cube = bumpmap_math::mesh::rounded_cube(4, 0.3);
        bumpmap_io::save_gltf(&glb, &cube).unwrap();
        let bytes = std::fs::read(&glb).unwrap();
        let file = Dropped { name: "cube.glb", bytes: &bytes };
        let frame = render("size=48\ntechnique=single-pass", Some(file)).unwrap();
        let torus = render("size=48\ntechnique=single-pass", None).unwrap();
        assert_ne!(frame.texels, torus.texels, "the cube, not the torus");
        let gltf = br#"{"asset":{"version":"2.0"},"buffers":[{"uri":"cube.bin","byteLength":48}]}"#;
        let e = render("size=48", Some(Dropped { name: "cube.gltf", bytes: gltf })).unwrap_err();
        assert!(e.to_string().contains("cube.gltf"), "{e}");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_float_normal_map_is_inspected_as_the_command_line_inspects_its_file() {
        use bumpmap_math::{MipChain, MipMode, NormalMapOptions, YConvention};
        let field = bumpmap_math::HeightPreset::Dimples.render(64, 64);
        let options = NormalMapOptions { y_convention: YConvention::YDown, ..Default::default() };
        let chain: MipChain = MipChain::from_height(&field, &options, MipMode::LengthInAlpha).unwrap();
        // The vectors as signed floats, as a float normal map stores them.
        let signed: Vec<f32> = chain.levels[0].texels.iter().flat_map(|t| t.map(|c| c as f32 / 127.5 - 1.0)).collect();
        let image = image::Rgba32FImage::from_raw(64, 64, signed).unwrap();
        let mut exr = std::io::Cursor::new(Vec::new());
        image::DynamicImage::ImageRgba32F(image).write_to(&mut exr, image::ImageFormat::OpenExr).unwrap();
        let file = Dropped { name: "dimples_normal.exr", bytes: exr.get_ref() };
        let verdict = inspect(file).unwrap();
        assert!(verdict.contains("floating point") && verdict.contains("convention: directx"), "{verdict}");
    }

    #[test]
    fn the_exports_answer_and_give_buffers_back() {
        assert_eq!(exports::bm_names(1), 0);
        assert!(exports::bm_answer_len() > 0 && exports::bm_answer_width() == 0);
        assert_eq!(exports::bm_names(7), 2, "no such set");
        let preset = b"bricks@16";
        // SAFETY: null inputs with length 0, and the preset's bytes for the call.
        let status = unsafe {
            exports::bm_map_file(std::ptr::null(), 0, std::ptr::null(), 0, std::ptr::null(), 0, preset.as_ptr(), 9, 9)
        };
        let answer = unsafe { std::slice::from_raw_parts(exports::bm_answer_ptr(), exports::bm_answer_len()) };
        assert_eq!(status, 2, "a usage error");
        assert!(String::from_utf8_lossy(answer).contains("no map file numbered 9 (0 to 4)"));
        assert!(exports::bm_alloc(usize::MAX / 2).is_null(), "more than memory: null, not an abort");
        let p = exports::bm_alloc(16);
        // SAFETY: the pointer and length bm_alloc just gave.
        unsafe { exports::bm_free(p, 16) };
    }
}
