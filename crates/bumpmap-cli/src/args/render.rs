//! `render`'s arguments, made from the library's option table (`bumpmap::option_table`): what
//! is drawn and how ([`SceneSetup`], which `bench render` and `view` take too) and the frame's
//! size ([`FrameSize`]); the output and `--passes` are the command line's own.

use std::path::PathBuf;

use bumpmap::frame::FrameRequest;
use bumpmap::option_table::{FRAME, SCENE};
use clap::Args;

use crate::args::parse_side;
use crate::args::table::{Table, rows};

rows!(
    /// What is drawn and how: the library's [`SCENE`] table.
    Scene: FrameRequest = SCENE
);
rows!(
    /// The frame's size: the library's [`FRAME`] table (`--size`, or `--width` with `--height`).
    Frame: FrameRequest = FRAME
);

/// Every option that says what is drawn and how, read into a [`FrameRequest`] (its scene
/// options and backend; the size is [`FrameSize`]'s).
pub type SceneSetup = Table<Scene>;

/// The frame's width and height, in a [`FrameRequest`]'s `size`.
pub type FrameSize = Table<Frame>;

/// `bumpmap render`.
#[derive(Args, Debug, Clone)]
#[command(after_help = "Examples:\n  \
bumpmap render                                         # the paper's torus, out/render.png\n  \
bumpmap render --passes -o torus.png                   # also torus.decal.png, .diffuse.png, .specular.png\n  \
bumpmap render --scene wall-floor --light -1,2,3        # the Cg Tutorial's Figure 8-4\n  \
bumpmap render --height-field dimples --bump-scale 8 --decal none\n  \
bumpmap render --light 4,0,3@1,0.6,0.4 --light dir:-1,0,1@0.3,0.3,0.6\n  \
bumpmap render --backend gpu --technique single-pass   # the same on the GPU (wgpu)\n  \
bumpmap render --technique peercy-blinn --scene patch --height-field pinwheel\n  \
bumpmap render --normal-map rock.png --scene sphere    # your own normal map (green up)\n  \
bumpmap render --normal-map rock.dds --y-convention directx   # …one made for Unreal\n  \
bumpmap render --scene mesh:model.glb                  # a glTF with its own material\n  \
bumpmap render --technique pom --scene wall --eye 0,-3,1.2   # parallax occlusion mapping, grazing\n  \
bumpmap render --technique reference-displaced --scene wall --eye 0,-3,1.2 --spp 16   # its ground truth\n  \
bumpmap render --technique relief --parallax-shadow hard --layers 64 --light 3,0,0.6\n  \
bumpmap render --normal-map n.png --height-map h.png --technique height-exact   # normalmap --height-out's files\n\n\
Lights are [dir:]X,Y,Z[@R,G,B] in world space (a mesh's own units and axes): a point light's \
position, or with dir: the direction toward a light at infinity.")]
pub struct RenderArgs {
    /// What is drawn and how.
    #[command(flatten)]
    pub setup: SceneSetup,
    /// Output PNG
    #[arg(short, long, default_value = "out/render.png")]
    pub output: PathBuf,
    /// The frame's size.
    #[command(flatten)]
    pub frame: FrameSize,
    /// Also write the framebuffer after each pass (Figure 12): OUT.decal.png, OUT.diffuse.png, …
    #[arg(long)]
    pub passes: bool,
}

/// `bumpmap bench render`.
#[derive(Args, Debug, Clone)]
#[command(after_help = "Examples:\n  \
bumpmap bench render --technique kilgard --threads 2 --json\n  \
bumpmap bench render --technique single-pass --normalize cube\n  \
bumpmap bench render --backend gpu --frames 100            # on the GPU (or lavapipe)\n\n\
The first light (the scene's own, or the first --light) orbits the point looked at about the \
view's up axis once per run — on the torus, the llvmpipe peer's orbit. Scene setup is not \
timed; every frame's vertex stage, clear, passes and (GPU) wait for the frame are. Every \
technique but the reference (see `bench reference`).")]
pub struct BenchRenderArgs {
    /// What is drawn and how.
    #[command(flatten)]
    pub setup: SceneSetup,
    /// Square framebuffer size
    #[arg(long, default_value_t = 1024, value_parser = parse_side)]
    pub size: usize,
    /// Worker threads, 1 to 256 (default: all cores)
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=256))]
    pub threads: Option<u16>,
    /// Frames per timed run
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: u32,
    /// Timed runs (after one warm-up run)
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
    pub runs: u32,
    /// Print one JSON line instead of prose
    #[arg(long)]
    pub json: bool,
}
