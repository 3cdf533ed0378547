//! The command line as scripts use it: headless renders to EXR and PNG, buffers, `compare`, and
//! clear errors (non-zero exit, the file named) for bad input.

use crate::common;

use std::process::Command;

fn bouncelab(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bouncelab")).args(args).output().expect("runs")
}

fn has_gpu() -> bool {
    common::has_gpu()
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
    assert!(!o.status.success() && err.contains("cannot create or write in the folder"), "{err}");
    // Modes are parsed by their names, and an unknown one lists them.
    let mode = |m: &str| bouncelab(&["render", "projects/default.ron", "--mode", m, "--width", "0", "--out", &out]);
    let o = mode("ISM-Ritschel");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("0x360"), "the mode parsed, the size refused: {err}");
    let o = mode("bogus");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("the modes are direct, ism, ism-ritschel"), "{err}");
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
    assert!(
        !run.status.success() && named && (err.contains("no enclosed space") || err.contains("no enclosed room")),
        "{err}"
    );
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

/// A fresh folder for one test.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("bouncelab-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    dir
}

/// The Cornell box's glTF, changed by `edit`, written to `path`.
fn cornell_variant(path: &std::path::Path, edit: impl FnOnce(&mut serde_json::Value)) {
    let text = std::fs::read_to_string("assets/cornell_box.gltf").expect("cornell");
    let mut doc: serde_json::Value = serde_json::from_str(&text).expect("json");
    edit(&mut doc);
    std::fs::write(path, serde_json::to_string(&doc).expect("json")).expect("write");
}

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn outputs_never_replace_inputs_or_take_another_format() {
    let dir = scratch("clobber");
    let level = dir.join("level.gltf");
    std::fs::copy("assets/cornell_box.gltf", &level).expect("copy");
    let level_bytes = std::fs::read(&level).expect("level");
    let (photo, notes) = (dir.join("photo.png"), dir.join("notes.txt"));
    std::fs::write(&photo, b"a photo").expect("write");
    std::fs::write(&notes, b"notes").expect("write");
    let s = |p: &std::path::Path| p.to_string_lossy().into_owned();
    // fit-blocks: the level itself, a PNG, a text file, the project it reads.
    for (out, why) in [(&level, "is also an input"), (&photo, "must end in .ron"), (&notes, "must end in .ron")] {
        let o = bouncelab(&["fit-blocks", &s(&level), "--out", &s(out)]);
        assert!(!o.status.success() && stderr(&o).contains(why), "{}: {}", out.display(), stderr(&o));
    }
    assert_eq!(std::fs::read(&level).expect("level"), level_bytes, "the level keeps its geometry");
    assert_eq!(std::fs::read(&photo).expect("photo"), b"a photo");
    assert_eq!(std::fs::read(&notes).expect("notes"), b"notes");
    let project = dir.join("p.ron");
    bouncelab::project_file::Project::load(std::path::Path::new("projects/default.ron"))
        .expect("default project")
        .save(&project)
        .expect("save");
    let project_bytes = std::fs::read(&project).expect("project");
    let o = bouncelab(&["fit-blocks", &s(&project), "--out", &s(&dir.join("./p.ron"))]);
    assert!(!o.status.success() && stderr(&o).contains("is also an input"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&project).expect("project"), project_bytes);
    // compare --heatmap: an input under its own name, or a name of another format.
    let (a, b) = (dir.join("a.png"), dir.join("b.png"));
    let img = image::RgbaImage::from_pixel(4, 4, image::Rgba([90, 90, 90, 255]));
    img.save(&a).expect("a");
    img.save(&b).expect("b");
    let b_bytes = std::fs::read(&b).expect("b");
    for (heat, why) in [(s(&b), "is also an input"), (s(&dir.join("heat.exr")), "must end in .png")] {
        let o = bouncelab(&["compare", &s(&a), &s(&b), "--heatmap", &heat]);
        assert!(!o.status.success() && stderr(&o).contains(why), "{heat}: {}", stderr(&o));
    }
    assert_eq!(std::fs::read(&b).expect("b"), b_bytes, "the reference is untouched");
    // A read-only output is not replaced; a folder is found before a long render starts.
    let mut perms = std::fs::metadata(&photo).expect("meta").permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&photo, perms).expect("chmod");
    let o = bouncelab(&["render", &s(&level), "--mode", "reference", "--spp", "100000", "--out", &s(&photo)]);
    assert!(!o.status.success() && stderr(&o).contains("read-only"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&photo).expect("photo"), b"a photo");
    let folder = dir.join("out.exr");
    std::fs::create_dir_all(&folder).expect("dir");
    let started = std::time::Instant::now();
    let o = bouncelab(&["render", &s(&level), "--mode", "reference", "--spp", "100000", "--out", &s(&folder)]);
    assert!(!o.status.success() && stderr(&o).contains("is a folder"), "{}", stderr(&o));
    assert!(started.elapsed().as_secs() < 60, "refused before the 100,000-spp render");
}

#[test]
fn fit_blocks_on_a_project_with_blocks_replaces_them() {
    let dir = scratch("refit");
    let s = |p: &std::path::Path| p.to_string_lossy().into_owned();
    let (first, second) = (dir.join("first.ron"), dir.join("second.ron"));
    let o = bouncelab(&["fit-blocks", "assets/suite/rooms.gltf", "--out", &s(&first)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = bouncelab(&["fit-blocks", &s(&first), "--out", &s(&second)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("replaced the 3 proxy blocks"), "{o:?}");
    let blocks = |p: &std::path::Path| {
        let project = bouncelab::project_file::Project::load(p).expect("project");
        project.scene.objects().iter().filter(|o| o.role == bouncelab::scene::ObjectRole::ProxyBlock).count()
    };
    assert_eq!(blocks(&first), 3, "one block per room");
    assert_eq!(blocks(&second), 3, "never stacked");
}

#[test]
fn a_render_that_is_not_what_was_asked_for_is_refused_unless_allowed() {
    if !has_gpu() {
        return;
    }
    let dir = scratch("partial");
    let s = |p: &std::path::Path| p.to_string_lossy().into_owned();
    let dark = dir.join("dark.gltf");
    cornell_variant(&dark, |doc| {
        doc.as_object_mut().expect("object").remove("extensions");
        for node in doc["nodes"].as_array_mut().expect("nodes") {
            node.as_object_mut().expect("node").remove("extensions");
        }
    });
    let glowing = dir.join("glowing.gltf");
    cornell_variant(&glowing, |doc| doc["materials"][0]["emissiveFactor"] = serde_json::json!([1.0, 0.9, 0.8]));
    let size = ["--width", "16", "--height", "9", "--ssaa", "1", "--mode", "direct"];
    for (scene, why) in [(&dark, "no light"), (&glowing, "emissive material")] {
        let out = dir.join("out.png");
        let o = bouncelab(&[&["render", &s(scene), "--out", &s(&out)][..], &size[..]].concat());
        assert!(!o.status.success(), "{}: exit 0", scene.display());
        assert!(stderr(&o).contains(why) && stderr(&o).contains("--allow-partial"), "{}", stderr(&o));
        assert!(!out.exists(), "nothing written");
        let o = bouncelab(&[&["render", &s(scene), "--out", &s(&out), "--allow-partial"][..], &size[..]].concat());
        assert!(o.status.success() && stderr(&o).contains(why), "{}", stderr(&o));
        assert!(out.exists(), "written when accepted");
        std::fs::remove_file(&out).expect("rm");
    }
    // A size this machine cannot render is refused before anything renders (on a software
    // adapter, whose GPU memory is this machine's; a real GPU's is not known before it fails).
    let cpu = common::gpu().is_some_and(|c| c.info.device_type == wgpu::DeviceType::Cpu);
    if !cpu {
        return;
    }
    let out = s(&dir.join("huge.png"));
    let o = bouncelab(&[
        "render",
        "projects/default.ron",
        "--mode",
        "direct",
        "--width",
        "16384",
        "--height",
        "16384",
        "--ssaa",
        "1",
        "--out",
        &out,
    ]);
    assert!(!o.status.success() && stderr(&o).contains("16384"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
}

#[test]
fn temporal_modes_converge_before_writing_unless_frames_cap_them() {
    if !has_gpu() {
        return;
    }
    let dir = scratch("converge");
    let s = |p: &std::path::Path| p.to_string_lossy().into_owned();
    // A still ISM view settles in its still frames (`IsmSettings::still_frames`): 8 here, above
    // the 2 of base confidence 0.5.
    let project = dir.join("quick.ron");
    let mut loaded =
        bouncelab::project_file::Project::load(std::path::Path::new("projects/default.ron")).expect("default");
    loaded.render.ism.base_confidence = 0.5;
    loaded.render.ism.still_frames = 8;
    loaded.save(&project).expect("save");
    let out = dir.join("ism.png");
    let args =
        ["render", &s(&project), "--mode", "ism", "--width", "16", "--height", "9", "--ssaa", "1", "--out", &s(&out)];
    let o = bouncelab(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("frame 8/8"), "converged over its 8 frames: {}", stderr(&o));
    assert!(!stderr(&o).contains("had not converged"), "{}", stderr(&o));
    let o = bouncelab(&[&args[..], &["--frames", "2"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("had not converged after the 2 frames asked for"), "{}", stderr(&o));
}

#[cfg(unix)]
#[test]
fn inputs_that_are_not_regular_files_or_too_large_are_refused() {
    let dir = scratch("inputs");
    let s = |p: &std::path::Path| p.to_string_lossy().into_owned();
    let out = s(&dir.join("x.png"));
    let o = bouncelab(&["render", "/dev/zero", "--out", &out]);
    assert!(!o.status.success() && stderr(&o).contains("a device"), "{}", stderr(&o));
    let o = bouncelab(&["compare", "/dev/zero", "x.png"]);
    assert!(!o.status.success() && stderr(&o).contains("a device"), "{}", stderr(&o));
    let fifo = dir.join("scene.gltf");
    if Command::new("mkfifo").arg(&fifo).status().is_ok_and(|st| st.success()) {
        let o = bouncelab(&["render", &s(&fifo), "--out", &out]);
        assert!(!o.status.success() && stderr(&o).contains("FIFO"), "{}", stderr(&o));
    }
    // A glTF whose six images are one 8192² PNG: over the texture budget, said before decoding.
    let big = dir.join("big.png");
    image::RgbaImage::new(8192, 8192).save(&big).expect("png");
    let textured = dir.join("textured.gltf");
    cornell_variant(&textured, |doc| {
        doc["images"] = serde_json::json!(vec![serde_json::json!({"uri": "big.png"}); 6]);
    });
    let o = bouncelab(&["render", &s(&textured), "--mode", "direct", "--out", &out]);
    assert!(!o.status.success() && stderr(&o).contains("texture budget"), "{}", stderr(&o));
}

#[test]
fn the_render_memory_estimate_covers_what_each_mode_allocates_per_pixel() {
    if !has_gpu() {
        return;
    }
    use bouncelab::settings::GiMode;
    let project =
        bouncelab::project_file::Project::load(std::path::Path::new("projects/default.ron")).expect("project");
    let ctx = common::gpu().expect("adapter");
    let bytes_at = |mode: GiMode, size: (u32, u32)| {
        let mut r = bouncelab::render::Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let settings = bouncelab::settings::RenderSettings { mode, ..project.render.clone() };
        r.render(&project.scene, &settings, size).expect("render");
        ctx.device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
        let m = bouncelab::app::GpuMemory::of(&ctx.device);
        m.buffer_bytes + m.texture_bytes
    };
    for mode in [GiMode::Direct, GiMode::Ism, GiMode::Sshgi, GiMode::Rcs] {
        let small = bytes_at(mode, (64, 64));
        let large = bytes_at(mode, (256, 256));
        assert!(small > 0, "the device counts its memory");
        let per_pixel = large.saturating_sub(small) as f64 / f64::from(256 * 256 - 64 * 64);
        eprintln!("{}: {per_pixel:.0} GPU bytes per render pixel", mode.name());
        assert!(
            per_pixel <= bouncelab::cli::budget::RASTER_GPU_BYTES_PER_PIXEL as f64,
            "{}: {per_pixel:.0} bytes per pixel, over the estimate",
            mode.name()
        );
    }
}

/// `probe-mrt` on the one-room `window` scene, with the MRT tests' small dictionary (it builds in
/// seconds in a debug build; the default one takes minutes) and 16 brute-force rays per texel:
/// the room's line, MRT's bounce within a factor of two of the brute force's, and the per-block
/// table.
#[test]
fn probe_mrt_compares_each_block_with_the_brute_force() {
    let dictionary = "(res: 4, k_d: 32, k_b: 16, rays: 256, enrichment: 1, seed: 3, interfaces: (positions: 4, \
                      directions: 8, supersample: 1, k_rlf: 48, k_r: 16, enrichment: 1, bands: 2))";
    let o = bouncelab(&["probe-mrt", "window", "--rays", "16", "--dictionary", dictionary]);
    assert!(o.status.success(), "probe-mrt window: {}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let room = text.lines().find(|l| l.starts_with("room 0:")).unwrap_or_else(|| panic!("room 0 in {text}"));
    let ratio: f64 = room
        .rsplit_once("MRT / brute force")
        .and_then(|(_, r)| r.trim().parse().ok())
        .unwrap_or_else(|| panic!("a ratio in {room:?}"));
    assert!(ratio.is_finite() && (0.5..=2.0).contains(&ratio), "MRT / brute force {ratio}:\n{text}");
    assert!(text.contains("| block | shape |"), "{text}");
}

#[test]
fn probe_judges_a_technique_and_direct_against_the_reference_and_refuses_bad_flags() {
    if !has_gpu() {
        return;
    }
    let o = bouncelab(&[
        "probe",
        "cornell",
        "--mode",
        "ism",
        "--settings",
        "(vpl_count: 16, bounces: 2, interleave: 2)",
        "--frames",
        "3",
        "--average-from",
        "1",
        "--ssaa",
        "1",
        "--trace",
        "--objects",
    ]);
    assert!(o.status.success(), "probe cornell: {}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let line = text.lines().find(|l| l.starts_with("cornell")).unwrap_or_else(|| panic!("a cornell line in {text}"));
    let number = |key: &str| -> f64 {
        line.split_once(key)
            .and_then(|(_, rest)| rest.split_whitespace().next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("{key} in {line:?}"))
    };
    // Two bounces of a handful of VPLs: more light than `direct`, not more than the reference
    // and a half, and a smaller FLIP than `direct`'s.
    let (energy, flip, direct_flip) = (number("energy"), number("FLIP"), number("/ direct"));
    assert!((0.6..1.5).contains(&energy), "energy {energy}: {text}");
    assert!(flip < direct_flip, "FLIP {flip} against direct's {direct_flip}: {text}");
    assert!(text.contains("frames:") && text.contains(" px  energy "), "--trace and --objects lines: {text}");
    for bad in [vec!["probe", "cornell", "--mode", "reference"], vec!["probe", "cornell", "--settings", "(nope: 1)"]] {
        let o = bouncelab(&bad);
        assert!(!o.status.success(), "{bad:?} must fail");
        assert!(!String::from_utf8_lossy(&o.stderr).trim().is_empty(), "{bad:?} says why");
    }
}

/// `probe-ism` on the Cornell box with a handful of VPLs and receivers: a map line and a lookup
/// line per set and a bounce line for the one set compared (no tail), each ratio a number; bad
/// flag values are refused with a message naming what is wrong, before anything renders.
#[test]
fn probe_ism_reports_each_set_and_refuses_bad_flags() {
    for (bad, says) in [
        (vec!["probe-ism", "cornell", "--grid", "1"], "two comma-separated numbers"),
        (vec!["probe-ism", "cornell", "--settings", "(vpl_count: 0)"], "vpl_count"),
        (vec!["probe-ism", "cornell", "--show", "--show-kind", "9"], "kind of false light"),
        (vec!["probe-ism", "cornell", "--points", "3,0,0"], "six numbers"),
        (vec!["probe-ism", "cornell", "--texel", "3,4"], "--points"),
    ] {
        let o = bouncelab(&bad);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(!o.status.success(), "{bad:?} must fail");
        assert!(err.contains(says), "{bad:?} says why ({says}): {err}");
    }
    if !has_gpu() {
        return;
    }
    let settings = "(vpl_count: 16, bounces: 2, bounce_tail: false)";
    let o =
        bouncelab(&["probe-ism", "cornell", "--settings", settings, "--receivers", "2000", "--power", "--unburied"]);
    assert!(o.status.success(), "probe-ism cornell: {}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let ratio = |start: &str, key: &str| -> f64 {
        let line = text.lines().find(|l| l.starts_with(start)).unwrap_or_else(|| panic!("{start:?} in {text}"));
        line.split_once(key)
            .and_then(|(_, rest)| rest.split_whitespace().next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("{key} in {line:?}"))
    };
    for set in 0..2 {
        let hole = ratio(&format!("cornell set {set}: false occluder"), "hole");
        let lit = ratio(&format!("cornell set {set} lookups:"), "ism/true");
        assert!((0.0..=1.0).contains(&hole) && lit.is_finite() && lit > 0.0, "set {set}: {text}");
    }
    let handed = ratio("cornell bounce power set1/true", "set1/true");
    assert!(handed.is_finite() && handed > 0.0, "{text}");
}

/// `bouncelab profile` writes the profile in the shape the GPU budget is checked against (card,
/// driver, commit; per row mode, scene, resolution, technique_ms, direct_ms, cpu_ms, cpu_waits),
/// a Chrome trace per mode, and a table; `direct` has no technique passes of its own and
/// `sshgi` has some; still frames keep their shadow maps, which a redrawing frame is timed for;
/// a warm `rcs` frame does not wait for the GPU, and the frame after a camera move does.
#[test]
fn profile_writes_the_json_the_budget_is_checked_against_and_a_trace_per_mode() {
    if !has_gpu() {
        return;
    }
    let dir = scratch("profile");
    let out = dir.join("gpu-profile.json");
    let traces = dir.join("trace");
    let o = bouncelab(&[
        "profile",
        "--resolutions",
        "96x54",
        "--scenes",
        "cornell",
        "--modes",
        "direct,sshgi,rcs",
        "--frames",
        "2",
        "--warm-up",
        "1",
        "--commit",
        "abc123",
        "--out",
        out.to_str().expect("utf8"),
        "--traces",
        traces.to_str().expect("utf8"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(table.contains("| sshgi | cornell | 96x54 |"), "{table}");
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).expect("json")).expect("parses");
    assert_eq!(doc["commit"], "abc123");
    assert!(doc["card"].as_str().is_some_and(|c| !c.is_empty()) && doc["driver"].is_string());
    let rows = doc["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 3);
    for row in rows {
        for key in ["mode", "scene", "resolution", "technique_ms", "direct_ms", "cpu_ms", "cpu_waits"] {
            assert!(row.get(key).is_some(), "{key} missing in {row}");
        }
        assert!(row["direct_ms"].as_f64().is_some_and(|v| v > 0.0), "{row}");
        assert!(row["shadows_redraw_ms"].as_f64().is_some_and(|v| v > 0.0), "the point light's maps redrawn: {row}");
    }
    let has = |row: &serde_json::Value, pass: &str| {
        row["passes"].as_array().is_some_and(|p| p.iter().any(|p| p["name"] == pass))
    };
    assert!(!has(&rows[0], "shadows"), "a still frame draws no shadow map: {}", rows[0]);
    assert_eq!(rows[2]["cpu_waits"].as_u64(), Some(0), "a warm rcs frame waits for no readback: {}", rows[2]);
    // After a 10 cm move rcs places records in the second frame, and neither frame waits.
    assert_eq!(rows[2]["moved_cpu_waits"].as_u64(), Some(0), "a frame after the move waited: {}", rows[2]);
    let made = rows[2]["moved_counters"]["records made last frame"].as_u64();
    assert!(made.is_some_and(|m| m > 0), "the frames after the move placed no record: {}", rows[2]);
    assert_eq!(rows[0]["technique_ms"].as_f64(), Some(0.0), "direct has no passes of its own");
    assert_eq!(rows[0]["cpu_waits"].as_u64(), Some(0), "direct never waits for the GPU inside a frame");
    let kind = |row: &serde_json::Value, pass: &str| {
        row["passes"].as_array().and_then(|p| p.iter().find(|p| p["name"] == pass)).map(|p| p["kind"].clone())
    };
    assert_eq!(kind(&rows[0], "gbuffer"), Some(serde_json::json!("raster")), "the G-buffer is rasterised");
    assert_eq!(kind(&rows[0], "lighting"), Some(serde_json::json!("compute")), "direct light is a compute pass");
    let (raster, compute) =
        (rows[1]["raster_ms"].as_f64().expect("raster"), rows[1]["compute_ms"].as_f64().expect("compute"));
    assert!(raster > 0.0 && compute > 0.0, "sshgi's frame has both: {raster} {compute}");
    assert!(rows[1]["technique_ms"].as_f64().is_some_and(|v| v > 0.0), "sshgi's passes are timed");
    for mode in ["direct", "sshgi"] {
        let trace: serde_json::Value =
            serde_json::from_slice(&std::fs::read(traces.join(format!("{mode}.json"))).expect("trace"))
                .expect("parses");
        assert!(trace["traceEvents"].as_array().is_some_and(|e| e.iter().any(|e| e["name"] == "gbuffer")), "{mode}");
    }
}

#[test]
fn dev_levels_writes_every_shape_and_probe_mrt_names_the_shapes_it_knows() {
    let dir = scratch("dev-levels");
    let run = bouncelab(&["dev-levels", dir.to_str().expect("utf-8")]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let written: Vec<_> = std::fs::read_dir(&dir).expect("dir").flatten().collect();
    assert_eq!(written.len(), 13, "{written:?}");
    // Each is a level a user could bring: it opens, and the fitter fits it.
    let corridors = dir.join("corridors_3m.gltf");
    let out = dir.join("corridors.ron");
    let run = bouncelab(&["fit-blocks", corridors.to_str().expect("utf-8"), "--out", out.to_str().expect("utf-8")]);
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success() && text.contains("cover every enclosed space"), "{text}");
    let stacked = dir.join("stacked_stairwell.gltf");
    let run = bouncelab(&["fit-blocks", stacked.to_str().expect("utf-8"), "--out", out.to_str().expect("utf-8")]);
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(text.contains("warning: the fit is partial (1 gap):") && text.contains("between storeys"), "{text}");
    let run = bouncelab(&["probe-mrt", "shape:nowhere"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        !run.status.success() && err.contains("no shape level \"nowhere\"") && err.contains("corridors_3m"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
