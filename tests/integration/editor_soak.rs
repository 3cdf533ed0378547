//! Soak: the editor driven through over a thousand random actions on the software adapter (mode
//! switches, adding, duplicating, moving and deleting objects and lights, undo and redo, the
//! inspector, save and reopen). In epochs: each opens the same file and ends with undo-all,
//! which must give back that file's bytes exactly; the file saved after redo-all must reopen to
//! the same bytes. Memory must stay flat after the first two epochs (the warm-up): the
//! process's resident host memory (all but the software adapter's device-memory blocks) and the
//! viewport device's buffer and texture memory and live objects (wgpu's counters), each
//! measured in the same state (the original file, `ism`, the albedo buffer inspected).
//!
//! `SOAK_ACTIONS` sets the number of actions (default 1,250: five epochs of 250, two of them the
//! warm-up; 2,000 took 411 s of CI's two cores in a debug build, and a leak as small as Mesa
//! 22.3's 1.4 MB a frame would pass the 20% bound within one measured epoch: 250 actions of a
//! frame or more add 350 MB against a bound of about 73 MB).
//!
//! The soak runs in a child process of its own (this test binary, started again for this one
//! test): resident memory is the process's, and the other tests of the binary run beside it.

use bouncelab::app::{EditorApp, GpuMemory};
use bouncelab::project_file::{Project, default_project_path};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;

const EPOCH: usize = 250;
const MODES: [&str; 4] = ["direct", "ism", "ism-ritschel", "reference"];
const BUFFERS: [&str; 6] = ["albedo", "normal", "depth", "direct", "indirect", "object_id"];

struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n as u64) as usize
    }
}

/// Resident memory in MiB, split in two: the software adapter's device memory (lavapipe maps
/// each `VkDeviceMemory` block from a memfd named `allocation`) and everything else, the host
/// side (heap, code, the driver's own allocations).
#[derive(Clone, Copy, Debug, Default)]
struct Resident {
    host: f64,
    device: f64,
}

fn resident() -> Resident {
    let smaps = std::fs::read_to_string("/proc/self/smaps").unwrap_or_default();
    let mut out = Resident::default();
    let mut device_mapping = false;
    for line in smaps.lines() {
        let mut words = line.split_whitespace();
        let first = words.next().unwrap_or("");
        if let Some(kib) = first.strip_prefix("Rss:").and(words.next()).and_then(|v| v.parse::<f64>().ok()) {
            *if device_mapping { &mut out.device } else { &mut out.host } += kib / 1024.0;
        } else if !first.ends_with(':') && first.contains('-') {
            device_mapping = line.contains("/memfd:allocation");
        }
    }
    out
}

fn bytes(h: &Harness<'static, EditorApp>, path: &std::path::Path) -> String {
    h.state().state().project.to_ron(path).expect("project text")
}

/// Waits for the viewport, steps once (a frame of the current state), waits again.
fn settle(h: &mut Harness<'static, EditorApp>) {
    for _ in 0..2 {
        h.state_mut().wait_viewport();
        h.run_steps(1);
    }
    h.state_mut().wait_viewport();
}

/// The canonical state memory is measured in: `ism`, the albedo buffer inspected, settled.
fn measure(h: &mut Harness<'static, EditorApp>) -> (Resident, GpuMemory) {
    h.get_by_label("ism").click();
    h.state_mut().inspect("albedo");
    settle(h);
    (resident(), h.state().viewport_gpu_memory().unwrap_or_default())
}

/// Which action kinds run (`SOAK_KINDS=0,7` narrows a leak down to mode switches and the
/// inspector); all ten by default.
fn kinds() -> Vec<usize> {
    std::env::var("SOAK_KINDS")
        .ok()
        .map(|v| v.split(',').filter_map(|k| k.trim().parse().ok()).filter(|k| *k < 10).collect::<Vec<usize>>())
        .filter(|k| !k.is_empty())
        .unwrap_or_else(|| (0..10).collect())
}

fn act(h: &mut Harness<'static, EditorApp>, rng: &mut Rng, kinds: &[usize]) {
    match kinds[rng.below(kinds.len())] {
        0 => {
            h.get_by_label(MODES[rng.below(MODES.len())]).click();
        }
        1 => {
            h.get_by_label("Add").click();
            h.run_steps(2);
            let what = ["Point light", "Spot light", "Clutter box"][rng.below(3)];
            h.get_by_label(what).click();
        }
        2 => h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::D),
        3 => h.key_press(egui::Key::Delete),
        4 | 5 => h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z),
        6 => h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z),
        7 => {
            let name = BUFFERS[rng.below(BUFFERS.len())];
            h.state_mut().inspect(name);
        }
        _ => {
            // A move, recorded in the history as a gizmo drag records it.
            let app = h.state_mut();
            let state = app.state_mut();
            let lights = state.project.scene.lights().len();
            state.history.begin("move light", &state.project);
            let shift = glam::Vec3::new(0.05, -0.02, 0.03);
            if lights > 0 {
                let i = rng.below(lights);
                state.project.scene.desc_mut().lights[i].position += shift;
            }
            state.history.commit(&state.project);
        }
    }
    h.run_steps(1);
}

/// glibc's allocator settings for the soak's process, so that its resident size follows the
/// memory in use rather than what the allocator keeps: a fixed mmap threshold (glibc otherwise
/// raises it to the largest block freed, up to 32 MiB, after which the software adapter's large
/// buffers come from the heap and stay resident once freed), freed heap tops returned past
/// 128 KiB, and two arenas (one per thread otherwise, each keeping its own freed memory). Without
/// them the warm-up's size depends on thread timing: 546 to 834 MiB after the same 250 actions.
const ALLOCATOR: &str =
    "glibc.malloc.mmap_threshold=131072:glibc.malloc.trim_threshold=131072:glibc.malloc.arena_max=2";

/// Set in the child process: run the soak here.
const CHILD: &str = "BOUNCELAB_SOAK_CHILD";

#[test]
#[ignore = "heavy: 1,250 editor actions in a process of their own (about 3 minutes in a debug build)"]
fn over_a_thousand_random_actions_keep_memory_flat_and_undo_all_restores_the_file() {
    if std::env::var_os(CHILD).is_some() {
        soak();
        return;
    }
    if !crate::common::has_gpu() {
        return;
    }
    let module = module_path!().split_once("::").map_or("", |(_, m)| m);
    let name = format!("{module}::over_a_thousand_random_actions_keep_memory_flat_and_undo_all_restores_the_file");
    let exe = std::env::current_exe().expect("test binary");
    let out = std::process::Command::new(exe)
        .args([name.as_str(), "--exact", "--include-ignored", "--nocapture", "--test-threads=1"])
        .env(CHILD, "1")
        .env("GLIBC_TUNABLES", ALLOCATOR)
        .output()
        .expect("start the soak's own process");
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    eprintln!("{stdout}{stderr}");
    assert!(out.status.success(), "the soak failed in its own process (its output is above)");
    assert!(stdout.contains("1 passed"), "the child ran no soak: {stdout}");
}

/// The soak itself (in the child process).
fn soak() {
    let actions: usize = std::env::var("SOAK_ACTIONS").ok().and_then(|v| v.parse().ok()).unwrap_or(1250);
    let dir = std::env::temp_dir().join(format!("bouncelab-soak-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let file = dir.join("soak.ron");
    let mut project = Project::load(&default_project_path()).expect("default project");
    project.render.mode = bouncelab::settings::GiMode::Direct;
    project.save(&file).expect("save the soak project");
    let open = file.clone();
    let mut h = Harness::builder()
        .with_size(egui::vec2(640.0, 420.0))
        .wgpu()
        .build_eframe(move |cc| EditorApp::new(cc, Project::load(&open).expect("project"), Some(open)));
    h.run_steps(2);
    settle(&mut h);

    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let edited_file = dir.join("soak-edited.ron");
    let kinds = kinds();
    let mut warm: Option<(f64, GpuMemory)> = None;
    let mut done = 0;
    let mut epochs = 0;
    let started = std::time::Instant::now();
    while done < actions {
        // Every epoch starts from the same file, so memory is compared on the same project.
        h.state_mut().open(&file);
        h.run_steps(1);
        let original = bytes(&h, &file);
        let n = EPOCH.min(actions - done);
        for _ in 0..n {
            act(&mut h, &mut rng, &kinds);
        }
        done += n;
        epochs += 1;
        settle(&mut h);
        // Undo everything: the epoch's file comes back byte for byte.
        let mut undone = 0;
        while h.state().state().history.undo_label().is_some() && undone < 10 * EPOCH {
            h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
            h.run_steps(1);
            undone += 1;
        }
        assert_eq!(bytes(&h, &file), original, "epoch {epochs}: undo-all after {n} actions ({undone} undos)");
        // Redo everything, save, reopen: the same bytes again.
        while h.state().state().history.redo_label().is_some() {
            h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z);
            h.run_steps(1);
        }
        let edited = bytes(&h, &edited_file);
        h.state_mut().save_to(&edited_file);
        h.state_mut().open(&edited_file);
        h.run_steps(1);
        assert_eq!(bytes(&h, &edited_file), edited, "epoch {epochs}: save and reopen");
        assert!(h.state().state().history.undo_label().is_none(), "a reopened file starts a new history");
        // Memory on the original project in the canonical state.
        h.state_mut().open(&file);
        h.run_steps(1);
        let now = measure(&mut h);
        eprintln!(
            "after {done} actions: resident host {:.0} MiB, adapter memory {:.0} MiB; GPU buffers {:.1} MiB, \
             textures {:.1} MiB, {} objects ({:.0} s)",
            now.0.host,
            now.0.device,
            now.1.buffer_bytes as f64 / 1048576.0,
            now.1.texture_bytes as f64 / 1048576.0,
            now.1.objects,
            started.elapsed().as_secs_f64()
        );
        // Two warm-up epochs, the larger host size the baseline. The host side is what a leak in
        // this program or the driver grows (Mesa 22.3's lavapipe leaked 1.4 MB a frame there);
        // it reads 206-208 MiB in every epoch of a run. The adapter's device memory is not
        // compared: lavapipe maps wgpu's allocator blocks whole, and which blocks are touched
        // depends on the peak of the epoch (one run: 442 MiB for three epochs, then 578 with one
        // block more, while wgpu's counters below stayed at the same bytes and objects); what is
        // live in those blocks is what the counters measure.
        if epochs <= 2 {
            let host = warm.as_ref().map_or(now.0.host, |w| w.0.max(now.0.host));
            warm = Some((host, now.1));
            continue;
        }
        let Some((host, gpu)) = warm else { continue };
        assert!(now.0.host <= host * 1.2 + 32.0, "resident host memory grew from {host:.0} to {:.0} MiB", now.0.host);
        let gpu_bytes = |m: &GpuMemory| (m.buffer_bytes + m.texture_bytes) as f64;
        assert!(
            gpu_bytes(&now.1) <= gpu_bytes(&gpu) * 1.05 + 4.0 * 1048576.0,
            "GPU memory grew from {gpu:?} to {:?}",
            now.1
        );
        assert!(now.1.objects <= gpu.objects + 8, "live GPU objects grew from {} to {}", gpu.objects, now.1.objects);
    }
    assert!(epochs >= 3, "two warm-up epochs and at least one measured one");
    let _ = std::fs::remove_dir_all(&dir);
}
