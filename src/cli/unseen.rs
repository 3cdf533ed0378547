//! `bouncelab unseen-light`: the share of a view's indirect light that leaves surfaces the
//! screen does not show (off screen or hidden), from the path tracer
//! ([`crate::precompute::unseen`]): what a screen-space technique such as `sshgi` can never
//! send, per suite scene or level.
//!
//! `cargo run --release -- unseen-light cornell,rooms,window,clutter,hall,diorama`

use std::fmt::Write as _;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use crate::precompute::unseen::unseen_share;
use crate::project_file::Project;
use crate::suite;

/// `bouncelab unseen-light`'s arguments.
#[derive(clap::Args, Clone, Debug)]
pub struct UnseenArgs {
    /// Comma-separated suite scenes, or project (`.ron`) and glTF files.
    #[arg(default_value = "cornell,rooms,window,clutter,hall,diorama,glossy,bumpy")]
    pub scenes: String,
    /// The view's size, `WxH` (the screen the senders are judged against).
    #[arg(long, default_value = "160x90", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Paths per pixel.
    #[arg(long, default_value_t = 64)]
    pub spp: u32,
    #[command(flatten)]
    pub units: super::SceneArgs,
}

fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text.split_once('x').ok_or_else(|| format!("{text:?}: expected WxH, e.g. 160x90"))?;
    let parse = |v: &str| v.parse::<u32>().ok().filter(|v| (1..=4096).contains(v));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("{text:?}: width and height must be 1 to 4096")),
    }
}

/// Splits every scene's indirect light by sender and prints a markdown table.
pub fn run(args: &UnseenArgs) -> anyhow::Result<String> {
    let mut out = String::new();
    let (w, h) = args.size;
    let _ = writeln!(
        out,
        "The path tracer's indirect light by the surface it left last (its first sender), and the share whose every \
         bounce left a surface on screen, {w}x{h} at {} paths a pixel (shares of the indirect light):\n",
        args.spp
    );
    let _ = writeln!(
        out,
        "| scene | indirect / all | first sender on screen | off screen | of which its direct light | hidden | every sender on screen | ms |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|");
    let cancel = AtomicBool::new(false);
    for name in args.scenes.split(',').map(str::trim).filter(|n| !n.is_empty()) {
        let project = open(args, name)?;
        let start = Instant::now();
        let Some(s) = unseen_share(&project.scene, args.size, args.spp, &cancel) else { continue };
        let all = s.direct + s.indirect();
        let _ = writeln!(
            out,
            "| {name} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.0} |",
            if all > 0.0 { s.indirect() / all } else { 0.0 },
            s.share(s.on_screen),
            s.share(s.off_screen),
            s.share(s.off_screen_direct),
            s.share(s.hidden),
            s.share(s.screen),
            start.elapsed().as_secs_f64() * 1e3
        );
    }
    Ok(out)
}

/// A suite scene by name, or a project or glTF file.
fn open(args: &UnseenArgs, name: &str) -> anyhow::Result<Project> {
    if name.ends_with(".ron") || name.ends_with(".gltf") || name.ends_with(".glb") {
        return args.units.open(Path::new(name));
    }
    Ok(suite::scene(name)?.load(Path::new("."))?)
}
