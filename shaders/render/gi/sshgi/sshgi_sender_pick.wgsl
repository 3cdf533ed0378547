// Which sender of the list a receiver's sample i takes (`gather_senders` in
// `sshgi_panorama_common.wgsl`), and the probability of that pick. Stratified over the list as
// before, but over a mixture: a share 1 - m of the picks is uniform over the list, a share m
// follows the senders' power (`sshgi_sender_cdf.wgsl`'s prefix sums, per block of 256 and over
// the blocks). m = 0, or a list without light, is the uniform pick alone. The uniform share bounds
// each sample's weight by 1 / (1 - m) times its uniform weight (defensive sampling, Hesterberg
// 1995): a dim sender very near the receiver, whose form factor the power cannot foresee, cannot
// blow up. The including shader binds `cdf`.

struct SenderPick {
    index: u32,
    // The probability of the pick among the list (1 / count when uniform).
    pdf: f32,
}

// Senders per block of the prefix sums (`BLOCK` in `sshgi_sender_cdf.wgsl`).
const PICK_BLOCK: u32 = 256u;

// The mixture's cumulative share up to and with sender k, whose prefix of power is `prefix`.
fn mixture_share(k: u32, count: u32, m: f32, prefix: f32, total: f32) -> f32 {
    return (1.0 - m) * f32(k + 1u) / f32(count) + m * prefix / total;
}

// The sender whose share of the mixture holds u in [0, 1) (the first k whose cumulative share
// exceeds u: a binary search over the blocks' ends, then within the block, about 13 reads at
// 8,192 senders), and its probability.
fn pick_sender(u: f32, count: u32, m: f32) -> SenderPick {
    let uniform = SenderPick(min(u32(u * f32(count)), count - 1u), 1.0 / f32(count));
    if m <= 0.0 {
        return uniform;
    }
    let blocks = (count + PICK_BLOCK - 1u) / PICK_BLOCK;
    let total = cdf[count + blocks - 1u];
    if !(total > 0.0) {
        return uniform;
    }
    var lo = 0u;
    var hi = blocks - 1u;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        let end = min((mid + 1u) * PICK_BLOCK, count) - 1u;
        if mixture_share(end, count, m, cdf[count + mid], total) > u {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    let start = lo * PICK_BLOCK;
    var base = 0.0;
    if lo > 0u {
        base = cdf[count + lo - 1u];
    }
    lo = start;
    hi = min(start + PICK_BLOCK, count) - 1u;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if mixture_share(mid, count, m, base + cdf[mid], total) > u {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    var before = 0.0;
    if lo > start {
        before = cdf[lo - 1u];
    }
    let share = max(cdf[lo] - before, 0.0) / total;
    return SenderPick(lo, (1.0 - m) / f32(count) + m * share);
}
