//! `caustics view`: an interactive window on any scene and any technique.
//!
//! The window shows the final image of the scene ([`caustics_gpu::final_image::FinalImage`], the
//! same pass `caustics render` uses) lit by the chosen technique's caustics map, from an orbit
//! camera, beside a second technique (the reference by default) when the view is split. An egui
//! panel sets the sun, the water (the scene's source or a ripple simulation that clicks drop
//! into), the technique and its parameters, and the quality; windows show the raw map and the
//! technique's intermediate buffers; an overlay gives the time of each stage and the GPU time of
//! each timed pass.
//!
//! Why the image is traced at a reduced internal resolution and scaled up: on a software adapter
//! (lavapipe) the final-image pass runs on the CPU's cores, and a full-window trace takes seconds.
//! The default scale keeps a frame well under a second there and is 1 on a hardware GPU.
//!
//! The final image comes back to the CPU and goes up again into the texture egui draws
//! (`FinalImage::render` returns an image): a copy per frame that a real GPU does not
//! notice and that keeps the viewer on the public API of the GPU crate.
//!
//! Module map: [`app`] the window, egui and the frame loop (and the scripted smoke mode);
//! [`frame`] what one frame renders; [`camera`] the orbit camera, sun and picking; [`water`] the
//! water sources; [`ui`] the panel, views and overlay; [`pictures`] the caustics maps as
//! pictures (the techniques draw their intermediate buffers: `caustics_core::techniques::buffers`).

mod app;
mod frame;
mod pictures;
mod ui;
mod water;

use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::Args;

#[derive(Args, Clone, Debug)]
pub struct ViewArgs {
    /// A scene file (.toml) or a built-in scene: pool, shore, reef, objects, glass, underwater.
    #[arg(long, default_value = "pool")]
    pub scene: String,
    /// The technique shown, with parameters as `caustics compare` spells them
    /// (`yuksel:n=15,m=14`, `yuksel-targets`); the scene's own by default.
    #[arg(long)]
    pub technique: Option<String>,
    /// Split the view: this technique beside the first (`reference` if the panel turns the split
    /// on without it).
    #[arg(long)]
    pub compare: Option<String>,
    /// The window's size WIDTHxHEIGHT in physical pixels: the picture's size (the image inside
    /// it is traced at --scale of what it covers).
    #[arg(long, value_parser = parse_size, value_name = "WxH", default_value = "1280x720")]
    pub image_size: [u32; 2],
    /// Internal resolution as a fraction of the image's size on screen (default: 1 on a hardware
    /// GPU, 0.25 on a software adapter such as lavapipe).
    #[arg(long)]
    pub scale: Option<f32>,
    /// The caustics map's size, N (N x N texels; the viewer's maps are square). Default: the
    /// scene's on a hardware GPU, 128 on a software adapter.
    #[arg(long, value_parser = crate::parse_map_size, value_name = "N")]
    pub map_size: Option<[u32; 2]>,
    /// Samples per pixel along each axis of the final image, 1 to 16 (default: 2 on a hardware
    /// GPU, 1 on a software adapter).
    #[arg(long, value_parser = clap::value_parser!(u32).range(crate::SUPERSAMPLING_RANGE))]
    pub supersampling: Option<u32>,
    /// Reference quality: triangulation cells per map texel along each axis (1 to 16).
    #[arg(long, default_value_t = crate::CELLS_PER_TEXEL,
          value_parser = clap::value_parser!(u32).range(crate::CELLS_PER_TEXEL_RANGE))]
    pub cells_per_texel: u32,
    /// Start with the interactive ripple simulation as the water (clicks drop ripples in any mode).
    #[arg(long)]
    pub ripple: bool,
    /// Wave amplitude scale (0: flat water).
    #[arg(long, default_value_t = 1.0)]
    pub amplitude: f64,
    /// Simulated seconds per real second.
    #[arg(long, default_value_t = 1.0)]
    pub time_scale: f64,
    /// Start with the water's clock stopped.
    #[arg(long)]
    pub paused: bool,
    /// Open the caustics-map window at the start.
    #[arg(long)]
    pub show_map: bool,
    /// Open the intermediate-buffers window at the start.
    #[arg(long)]
    pub show_buffers: bool,
    /// Open the intermediate-buffers window on this buffer of the first technique: `heights`, or
    /// one of the technique's own, `KEY` or `KEY:INDEX` (a name it does not have is refused with
    /// the list of those it has).
    #[arg(long, value_name = "NAME")]
    pub buffer: Option<String>,
    /// Where the final image is traced: `gpu` (the GPU frame: water, technique and final image on
    /// the GPU, shown without a CPU copy), `cpu` (the techniques' maps read back and the image traced
    /// by the CPU renderer, the GPU pass's twin), or `auto`: the faster there, the GPU frame on a
    /// GPU and the CPU image on a software adapter such as lavapipe.
    #[arg(long, value_enum, default_value_t = ImageOn::Auto)]
    pub final_image: ImageOn,
    /// Start with the water's normals filtered by each sample's footprint (as `caustics render
    /// --filter-water`; a checkbox in the panel).
    #[arg(long)]
    pub filter_water: bool,
    /// Hide the control panel (toggle with F2).
    #[arg(long)]
    pub no_panel: bool,
    /// Smoke mode: render this many frames, then exit. The water's clock then advances 1/30 s
    /// per frame, so a run is repeatable.
    #[arg(long)]
    pub frames: Option<u64>,
    /// Save the last frame of the window, panel included, as PNG (with --frames).
    #[arg(long, requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// Smoke mode: switch the technique every frame, through every technique the scene offers (or
    /// those listed, comma-separated), splitting the view every other round.
    #[arg(long, requires = "frames", num_args = 0.., value_delimiter = ',', value_name = "TECHNIQUES", hide = true)]
    pub cycle_techniques: Option<Vec<String>>,
    /// Smoke mode: resize the window every K frames.
    #[arg(long, requires = "frames", hide = true)]
    pub resize_every: Option<u64>,
    /// Smoke mode: drop a ripple as a click near the image's centre would, every K frames.
    #[arg(long, requires = "frames", hide = true)]
    pub drop_every: Option<u64>,
    /// Smoke mode: open the caustics-map window at frame N (as a click on its toggle would).
    #[arg(long, requires = "frames", value_name = "N", hide = true)]
    pub show_map_at: Option<u64>,
    /// Smoke mode: destroy the GPU device at frame N, as a driver reset would lose it, to show
    /// how the viewer reports a lost device (the window's title says so, the run exits with the
    /// error).
    #[arg(long, requires = "frames", value_name = "N", hide = true)]
    pub lose_device_at: Option<u64>,
    /// Print the resident memory (VmRSS) at frames 50 and every 100 after, and at the last, with
    /// wgpu's count of the objects alive on the device (buffers, textures, bind groups, ...).
    #[arg(long, hide = true)]
    pub report_memory: bool,
    /// After the run (with --frames), print per technique shown what the GPU crate created,
    /// uploaded and read back per frame over the steady frames (the first ones, which build the
    /// pipelines and frames, left out).
    #[arg(long, requires = "frames")]
    pub report_traffic: bool,
    /// The GPU choice; with --cpu the techniques run on their CPU twins and the final image on
    /// the CPU, and the window still draws through the adapter.
    #[command(flatten)]
    pub gpu: crate::GpuArgs,
}

/// Where the final image is traced.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageOn {
    Auto,
    Gpu,
    Cpu,
}

pub fn run(args: ViewArgs) -> Result<()> {
    if let Some(0) = args.frames {
        bail!("--frames must be at least 1");
    }
    if args.resize_every == Some(0) || args.drop_every == Some(0) {
        bail!("--resize-every and --drop-every take a number of frames, at least 1");
    }
    if let Some([w, h]) = args.map_size
        && w != h
    {
        bail!(
            "--map-size {w}x{h}: the viewer's caustics map is square; give one side, e.g. --map-size {w}"
        );
    }
    if let Some(s) = args.scale
        && !(s > 0.0 && s <= 1.0)
    {
        bail!("--scale {s}: expected a fraction in (0, 1]");
    }
    if let Some(p) = &args.screenshot
        && p.extension().and_then(|e| e.to_str()) != Some("png")
    {
        bail!("--screenshot {}: expected a .png file name", p.display());
    }
    // The arguments first: a mistake in them is named even where no window can open.
    check_display()?;
    app::run(args)
}

fn parse_size(s: &str) -> Result<[u32; 2], String> {
    crate::parse_size_within(s, 64..=8192)
}

/// winit panics or fails obscurely without a display server: say what is missing first.
fn check_display() -> Result<()> {
    if cfg!(all(unix, not(target_os = "macos"), not(target_os = "ios"))) {
        let set = |v: &str| std::env::var_os(v).is_some_and(|s| !s.is_empty());
        if !set("DISPLAY") && !set("WAYLAND_DISPLAY") && !set("WAYLAND_SOCKET") {
            bail!(
                "`caustics view` opens a window, but neither DISPLAY nor WAYLAND_DISPLAY is set. \
                 On a machine without a screen run it under a virtual X server, e.g. \
                 `Xvfb :99 -screen 0 1024x768x24 -nolisten tcp & DISPLAY=:99 caustics view ...`, \
                 or use `caustics render` for images"
            );
        }
    }
    Ok(())
}

/// The resident set size of this process, KiB (Linux; `None` elsewhere).
pub fn resident_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
}

/// wgpu's own count of the objects alive on `device` (its `counters` feature), as `name value`
/// pairs: the viewer's, the techniques' and egui's together. Beside the resident memory it tells
/// growth in what the process holds from growth inside the driver, which no count of ours sees.
/// Left out: wgpu-hal 30's Vulkan `textures` count (`create_texture` never adds to it and
/// `destroy_texture` subtracts, so it falls by one per texture freed, swap-chain images
/// included) and `memory_allocations` (not counted on Vulkan); `texture_bytes` and
/// `texture_views` stand for the textures.
pub fn wgpu_objects(device: &wgpu::Device) -> String {
    let c = device.get_internal_counters().hal;
    let pairs = [
        ("buffers", &c.buffers),
        ("buffer_bytes", &c.buffer_memory),
        ("texture_bytes", &c.texture_memory),
        ("texture_views", &c.texture_views),
        ("bind_groups", &c.bind_groups),
        ("bind_group_layouts", &c.bind_group_layouts),
        ("render_pipelines", &c.render_pipelines),
        ("compute_pipelines", &c.compute_pipelines),
        ("pipeline_layouts", &c.pipeline_layouts),
        ("shader_modules", &c.shader_modules),
        ("samplers", &c.samplers),
        ("query_sets", &c.query_sets),
        ("command_encoders", &c.command_encoders),
        ("fences", &c.fences),
    ];
    pairs
        .iter()
        .map(|(name, v)| format!("{name} {}", v.read()))
        .collect::<Vec<_>>()
        .join(", ")
}
