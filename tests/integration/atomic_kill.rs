//! Safe writes under SIGKILL: a child process rewrites one file through `atomic_file::write`
//! in a loop (4 MiB generations, each self-checking) and is killed at random moments. After
//! every kill the file must be one whole generation, the old or a newer one, never a mix; the
//! temp files the killed writers leave behind are removed by the next write.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use bouncelab::atomic_file;

/// Set in the child: the file it rewrites.
const CHILD: &str = "BOUNCELAB_ATOMIC_KILL_CHILD";
const SIZE: usize = 4 << 20;

/// The child's test name in this binary (`module_path!` less the crate's name).
static CHILD_TEST: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
    let module = module_path!().split_once("::").map_or("", |(_, m)| m);
    format!("{module}::child_writer")
});

/// Generation `g`: its number, then bytes that depend on it and their position, then the sum.
fn content(g: u64) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(SIZE + 16);
    bytes.extend_from_slice(&g.to_le_bytes());
    bytes.extend((0..SIZE).map(|i| (i as u64).wrapping_mul(2654435761).wrapping_add(g * 97) as u8));
    let sum = bytes.iter().fold(0u64, |s, &b| s.wrapping_mul(31).wrapping_add(u64::from(b)));
    bytes.extend_from_slice(&sum.to_le_bytes());
    bytes
}

/// The generation a file holds, if it is one whole generation.
fn generation(bytes: &[u8]) -> Option<u64> {
    let g = u64::from_le_bytes(bytes.get(..8)?.try_into().ok()?);
    (bytes == content(g).as_slice()).then_some(g)
}

fn temp_files(dir: &Path) -> usize {
    std::fs::read_dir(dir)
        .map(|entries| entries.flatten().filter(|e| e.file_name().to_string_lossy().contains(".tmp")).count())
        .unwrap_or(0)
}

/// The child's loop; a no-op in an ordinary test run.
#[test]
fn child_writer() {
    let Some(path) = std::env::var_os(CHILD) else { return };
    let path = Path::new(&path);
    let start = std::fs::read(path).ok().and_then(|b| generation(&b)).unwrap_or(0);
    // The next generations are built first (slow in a debug build), so the loop below is all
    // writing; "writing" tells the parent that the random delay may start.
    let ready: Vec<Vec<u8>> = (start + 1..start + 9).map(content).collect();
    println!("writing");
    let _ = std::io::Write::flush(&mut std::io::stdout());
    for bytes in &ready {
        atomic_file::write(path, bytes).expect("write");
    }
}

#[test]
fn a_writer_killed_at_random_points_leaves_the_old_or_a_new_whole_file() {
    let dir = std::env::temp_dir().join(format!("bouncelab-atomic-kill-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join("render.exr");
    atomic_file::write(&path, &content(0)).expect("first write");
    let exe = std::env::current_exe().expect("test binary");
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let (mut rounds, mut mid_write, mut last) = (0, 0, 0);
    while rounds < 16 || (mid_write < 6 && rounds < 64) {
        rounds += 1;
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let delay = Duration::from_micros(state % 40_000);
        let mut child = Command::new(&exe)
            .args([CHILD_TEST.as_str(), "--exact", "--test-threads=1", "--nocapture"])
            .env(CHILD, &path)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("spawn the writer");
        let mut line = String::new();
        if let Some(out) = child.stdout.take() {
            let mut reader = std::io::BufReader::new(out);
            while !line.contains("writing") {
                line.clear();
                if std::io::BufRead::read_line(&mut reader, &mut line).unwrap_or(0) == 0 {
                    break;
                }
            }
        }
        std::thread::sleep(delay);
        child.kill().expect("kill");
        child.wait().expect("reap");
        // This writer's temp file left behind means the kill landed inside a write.
        mid_write += usize::from(dir.join(format!("render.exr.tmp{}", child.id())).exists());
        let bytes = std::fs::read(&path).expect("the file still exists");
        let g = generation(&bytes)
            .unwrap_or_else(|| panic!("round {rounds}: killed after {delay:?}, the file is not one whole generation"));
        assert!(g >= last, "round {rounds}: generation {g} after {last}");
        last = g;
    }
    assert!(mid_write >= 6, "only {mid_write} of {rounds} kills landed inside a write: the test proved nothing");
    assert!(last > 0, "no write ever completed in {rounds} rounds");
    atomic_file::write(&path, &content(last + 1)).expect("a write after the kills");
    assert_eq!(temp_files(&dir), 0, "the next write removes the killed writers' temp files");
    eprintln!("{rounds} kills, {mid_write} inside a write, last whole generation {last}");
    let _ = std::fs::remove_dir_all(&dir);
}
