// The texels a splat covers (`ism_splat.wgsl`): the disk's footprint ellipse q^T M^-1 q <= 1
// (q: texel centre - footprint centre, M the covariance of the two tangent radii' images plus
// half a texel each way, `det` its determinant) and the centre's own texel, and each row's span
// of columns that can hold such texels. Apart from the splat pass so that a test runs the same
// code (`tests/integration/ism_footprint.rs`).

// The footprint's covariance from the images `ta`, `tb` of the disk's two tangent radii
// (texels), plus half a texel each way: (m00, m01, m11, det).
fn footprint_moments(ta: vec2<f32>, tb: vec2<f32>) -> vec4<f32> {
    let m00 = ta.x * ta.x + tb.x * tb.x + 0.25;
    let m01 = ta.x * ta.y + tb.x * tb.y;
    let m11 = ta.y * ta.y + tb.y * tb.y + 0.25;
    return vec4<f32>(m00, m01, m11, m00 * m11 - m01 * m01);
}

// Whether the texel (x, y) is in the footprint of centre `centre` and covariance
// [[m00, m01], [m01, m11]] of determinant `det`, or is the centre's own texel.
fn footprint_covers(centre: vec2<f32>, x: i32, y: i32, m00: f32, m01: f32, m11: f32, det: f32) -> bool {
    let q = vec2<f32>(f32(x), f32(y)) + 0.5 - centre;
    let inside = (m11 * q.x * q.x - 2.0 * m01 * q.x * q.y + m00 * q.y * q.y) <= det;
    let own = x == i32(centre.x) && y == i32(centre.y);
    return inside || own;
}

// Slack (texels) of `row_span`'s ends, so that rounding in its roots never drops a texel
// `footprint_covers` takes.
const SPAN_SLACK: f32 = 0.01;

// The columns of row `y` the footprint q^T M^-1 q <= 1 (q: texel centre - `centre`) can cover,
// widened by `SPAN_SLACK`, plus the centre's own texel in its row; empty (x > y) where the
// ellipse misses the row. The texel loop keeps the exact test: this only skips the bounding
// box's corners, which cost a diagonal footprint half its iterations (and on a GPU idle every
// lane of a warp while one lane walks them).
fn row_span(centre: vec2<f32>, y: i32, m00: f32, m01: f32, m11: f32, det: f32) -> vec2<i32> {
    let qy = f32(y) + 0.5 - centre.y;
    // m11 qx^2 - 2 m01 qy qx + m00 qy^2 - det <= 0; its discriminant / 4 is det (m11 - qy^2).
    let disc = det * (m11 - qy * qy);
    var span = vec2<i32>(1, 0);
    if disc >= 0.0 {
        let root = sqrt(disc);
        span = vec2<i32>(
            i32(ceil(centre.x - 0.5 + (m01 * qy - root) / m11 - SPAN_SLACK)),
            i32(floor(centre.x - 0.5 + (m01 * qy + root) / m11 + SPAN_SLACK)),
        );
    }
    if y == i32(centre.y) {
        let own = i32(centre.x);
        span = select(vec2<i32>(min(span.x, own), max(span.y, own)), vec2<i32>(own), span.x > span.y);
    }
    return span;
}

