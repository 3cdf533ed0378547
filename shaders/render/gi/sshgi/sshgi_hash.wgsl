// The per-pixel and per-frame hash `sshgi`'s gathers jitter their samples with.

// A hash of (x, y, seed) to [0, 1) (PCG, Jarzynski & Olano 2020).
fn hash01(x: u32, y: u32, seed: u32) -> f32 {
    var v = x * 747796405u + y * 2891336453u + seed * 277803737u + 1442695041u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    v = (v >> 22u) ^ v;
    return f32(v >> 8u) / 16777216.0;
}
