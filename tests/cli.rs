//! The command line as scripts use it: headless renders to EXR and PNG, buffers, `compare`, and
//! clear errors (non-zero exit, the file named) for bad input.

use std::process::Command;

fn bouncelab(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bouncelab")).args(args).output().expect("runs")
}

fn has_gpu() -> bool {
    std::env::var_os("CI").is_some() || bouncelab::render::GpuContext::new_headless().is_ok()
}

#[test]
fn renders_and_compares() {
    if !has_gpu() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("bouncelab-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let p = |n: &str| dir.join(n).to_string_lossy().into_owned();
    let size = ["--width", "32", "--height", "18"];
    for (mode, out) in [("direct", p("d.exr")), ("direct", p("d.png")), ("reference", p("r.exr"))] {
        let mut args = vec!["render", "projects/default.ron", "--mode", mode, "--out", &out, "--spp", "8"];
        args.extend(size);
        let o = bouncelab(&args);
        assert!(o.status.success(), "{mode} {out}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(std::path::Path::new(&out).exists());
    }
    let normal = p("n.exr");
    let mut args = vec!["render", "assets/cornell_box.gltf", "--buffer", "normal", "--out", &normal];
    args.extend(size);
    assert!(bouncelab(&args).status.success());
    let heat = p("heat.png");
    // A negative exposure is a value, not an unknown flag (`-0.5` was refused as an argument).
    let dark = p("dark.png");
    let mut args = vec!["render", "projects/default.ron", "--mode", "direct", "--out", &dark, "--exposure", "-1.5"];
    args.extend(size);
    let o = bouncelab(&args);
    assert!(o.status.success(), "render --exposure -1.5: {}", String::from_utf8_lossy(&o.stderr));
    let o = bouncelab(&["compare", &p("d.exr"), &p("r.exr"), "--exposure", "-0.5"]);
    assert!(o.status.success(), "compare --exposure -0.5: {}", String::from_utf8_lossy(&o.stderr));
    // --exposure-auto judges at the exposure that puts the reference's mean at 0.18 (the
    // quality matrix's), prints it, and gives the FLIP that exposure gives when named.
    let o = bouncelab(&["compare", &p("d.exr"), &p("r.exr"), "--exposure-auto"]);
    assert!(o.status.success(), "compare --exposure-auto: {}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let field = |text: &str, key: &str| -> f64 {
        let line = text.lines().find(|l| l.starts_with(key)).unwrap_or_else(|| panic!("{key} in {text}"));
        line[key.len()..].trim().parse().expect("a number")
    };
    let ev = field(&text, "exposure:");
    assert!(ev.is_finite() && ev.abs() > 0.01, "{text}");
    let named = bouncelab(&["compare", &p("d.exr"), &p("r.exr"), "--exposure", &format!("{ev}")]);
    let named = String::from_utf8_lossy(&named.stdout).into_owned();
    assert!((field(&text, "flip:") - field(&named, "flip:")).abs() < 1e-4, "{text}\n{named}");
    let o = bouncelab(&["compare", &p("d.exr"), &p("r.exr"), "--exposure", "1", "--exposure-auto"]);
    assert!(!o.status.success(), "--exposure and --exposure-auto together are refused");
    let o = bouncelab(&["compare", &p("d.exr"), &p("r.exr"), "--heatmap", &heat]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("rmse: ") && lines[1].starts_with("relmse: ") && lines[2].starts_with("flip: "));
    assert!(lines[3].starts_with("luminance_ratio: "));
    let json: serde_json::Value = serde_json::from_str(lines[4]).expect("last line is JSON");
    assert!(json["flip"].as_f64().is_some_and(|f| (0.0..=1.0).contains(&f)));
    assert!(std::path::Path::new(&heat).exists());
}

#[test]
fn bad_input_fails_with_the_file_named() {
    let cases: [(&[&str], &str); 5] = [
        (&["render", "nowhere.gltf", "--out", "/tmp/x.png"], "nowhere.gltf"),
        (&["render", "assets/cornell_box.gltf", "--out", "/tmp/x.bmp"], "x.bmp"),
        (&["render", "projects/default.ron", "--out", "/tmp/x.png", "--width", "0"], "0x360"),
        (&["render", "projects/default.ron", "--out", "/tmp/x.png", "--buffer", "bogus"], "bogus"),
        (&["compare", "/tmp/does-not-exist-a.exr", "/tmp/does-not-exist-b.exr"], "does-not-exist-a.exr"),
    ];
    for (args, needle) in cases {
        let o = bouncelab(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} should fail");
        assert!(err.contains(needle), "{args:?}: stderr does not name {needle:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
        // Each cause once: "x: no such file", not "x: no such file: no such file".
        let line = err.lines().find(|l| l.starts_with("error: ")).unwrap_or_default();
        let parts: Vec<&str> = line.split(": ").collect();
        assert!(parts.windows(2).all(|w| w[0] != w[1]), "{args:?}: repeated cause in {line:?}");
    }
}

#[test]
fn a_gltf_that_crashes_the_parser_is_a_quiet_error() {
    // gltf-json's validation indexes `accessors` with the attribute's index unchecked.
    let dir = std::env::temp_dir().join(format!("bouncelab-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("crash.gltf");
    let doc = r#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":7}}]}]}"#;
    std::fs::write(&path, doc).expect("write");
    let path = path.to_str().expect("utf-8 temp path");
    let o = bouncelab(&["render", path, "--out", "/tmp/x.png"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("crash.gltf"), "{err}");
    assert!(!err.contains("panicked") && !err.contains("backtrace"), "{err}");
}

#[test]
fn a_thousand_frames_run_to_the_end_and_report_progress() {
    if !has_gpu() {
        return;
    }
    let out = std::env::temp_dir().join(format!("bouncelab-long-{}.png", std::process::id()));
    let out = out.to_string_lossy().into_owned();
    // Unbounded submission ended in a segfault after about 600 frames (issue: long runs).
    let args = ["render", "projects/default.ron", "--mode", "direct", "--frames", "1000"];
    let o = bouncelab(&[&args[..], &["--width", "16", "--height", "9", "--ssaa", "1", "--out", &out]].concat());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("frame 1000/1000"), "the last frame is reported: {err}");
    assert!(std::path::Path::new(&out).exists());
}

#[test]
fn bad_arguments_fail_before_anything_renders() {
    let out = std::env::temp_dir().join(format!("bouncelab-args-{}.png", std::process::id()));
    let out = out.to_string_lossy().into_owned();
    let render = |extra: &[&str], out: &str| {
        let args =
            ["render", "projects/default.ron", "--mode", "direct", "--width", "8", "--height", "8", "--out", out];
        bouncelab(&[&args[..], extra].concat())
    };
    for (extra, want) in [(&["--frames", "0"][..], "--frames 0"), (&["--ssaa", "9"][..], "--ssaa 9")] {
        let o = render(extra, &out);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(want), "{extra:?}: {err}");
    }
    // A folder that cannot be created (its parent is a file) fails before the render.
    let file = std::env::temp_dir().join(format!("bouncelab-a-file-{}", std::process::id()));
    std::fs::write(&file, "x").expect("write");
    let o = render(&[], &file.join("x.png").to_string_lossy());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("cannot create the folder"), "{err}");
    // NaN exposure used to report FLIP 0 (identical) for any two images.
    let o = bouncelab(&["compare", "a.exr", "b.exr", "--exposure", "NaN"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("--exposure"), "{err}");
}

#[cfg(unix)]
#[test]
fn a_write_cut_short_by_a_full_disk_keeps_the_old_image() {
    if !has_gpu() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("bouncelab-full-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    let out = dir.join("image.png");
    std::fs::write(&out, b"the old image").expect("write");
    let args =
        format!("render projects/default.ron --mode direct --width 128 --height 72 --ssaa 1 --out {}", out.display());
    // A file-size limit of 1 KB stands in for a full disk: the PNG (tens of KB) cannot be written.
    let limited = format!("ulimit -f 2; exec {} {args}", env!("CARGO_BIN_EXE_bouncelab"));
    let o = Command::new("sh").arg("-c").arg(&limited).output().expect("runs");
    assert!(!o.status.success(), "the write must fail under the limit");
    assert_eq!(std::fs::read(&out).expect("read"), b"the old image", "never a partial image");
    // The next write succeeds and clears what the killed one left behind.
    let o = bouncelab(&args.split(' ').collect::<Vec<_>>());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let names: Vec<String> =
        std::fs::read_dir(&dir).expect("dir").flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect();
    assert_eq!(names, ["image.png"], "no temp files remain");
    assert!(std::fs::read(&out).expect("read").starts_with(b"\x89PNG"));
}

#[test]
fn mrt_dictionary_builds_then_loads_from_its_cache_and_rejects_bad_parameters() {
    let dir = std::env::temp_dir().join(format!("bouncelab-cli-mrt-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let cache = dir.to_str().expect("utf-8");
    let args = [
        "mrt-dictionary",
        "--res",
        "3",
        "--rays",
        "16",
        "--modes",
        "8",
        "--lf-positions",
        "2",
        "--lf-directions",
        "4",
        "--lf-supersample",
        "1",
        "--lf-enrichment",
        "1",
        "--cache",
        cache,
    ];
    let built = bouncelab(&args);
    let text = String::from_utf8_lossy(&built.stdout);
    assert!(built.status.success(), "{}", String::from_utf8_lossy(&built.stderr));
    assert!(text.contains("built in") && text.contains("| closed | 54 |") && text.contains("interfaces:"), "{text}");
    let loaded = bouncelab(&args);
    assert!(String::from_utf8_lossy(&loaded.stdout).contains("loaded"), "the second run reads the cache");
    let bad = bouncelab(&["mrt-dictionary", "--res", "1", "--cache", cache]);
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(!bad.status.success() && err.contains("res = 1"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fit_blocks_finds_the_suite_levels_rooms_and_doorways_and_names_what_it_cannot_fit() {
    let dir = std::env::temp_dir().join(format!("bouncelab-cli-fit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    // Into a folder that does not exist yet (made for it).
    let out = dir.join("fitted").join("rooms.ron");
    let run = bouncelab(&["fit-blocks", "assets/suite/rooms.gltf", "--out", out.to_str().expect("utf-8")]);
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    // Three rooms, one doorway per side: one block each.
    assert!(text.contains("3 proxy blocks"), "{text}");
    // The written project reopens with its blocks, and they make one connected level: two
    // doorway sides, linked both ways.
    let project = bouncelab::project_file::Project::load(&out).expect("the written project");
    let (level, objects) = bouncelab::precompute::mrt::proxy::level(&project.scene).expect("a level");
    assert_eq!((objects.len(), level.link_count()), (3, 4));
    assert!(level.unlinked().is_empty());
    // An open box (the Cornell box has no front) holds no room: a clear error, no file.
    let open = dir.join("cornell.ron");
    let run = bouncelab(&["fit-blocks", "assets/cornell_box.gltf", "--out", open.to_str().expect("utf-8")]);
    let err = String::from_utf8_lossy(&run.stderr);
    let named = err.contains("cannot fit proxy blocks") && err.contains("cornell_box.gltf");
    assert!(!run.status.success() && named && (err.contains("no enclosed space") || err.contains("no room")), "{err}");
    // A room with a 2 x 1.2 m window is still a room: the flood does not pass a window. Being
    // 6 m long, 5 m wide and 3 m high, it is cut into two near-cubic parts along its length.
    let window = dir.join("window.ron");
    let run = bouncelab(&["fit-blocks", "assets/suite/window.gltf", "--out", window.to_str().expect("utf-8")]);
    assert!(
        String::from_utf8_lossy(&run.stdout).contains("2 proxy blocks"),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(!open.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
