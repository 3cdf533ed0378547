//! The oracle's point listing: a tile's chosen points with their splat footprints, and
//! whether each covers a texel as the splat pass decides it.

use super::*;

/// Which points [`list_points`] lists.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointsQuery {
    /// The atlas tile (its VPL's index over all sets).
    pub tile: usize,
    /// Only points inside this box (x0, y0, z0, x1, y1, z1).
    pub bbox: Option<[f32; 6]>,
    /// Whether each point covers this map texel as the splat pass decides it.
    pub texel: Option<(f32, f32)>,
    /// With that, the point's clip lines.
    pub clips: bool,
}

/// A tile's chosen points.
#[derive(Clone, Debug, PartialEq)]
pub struct PointsReport {
    /// The atlas tile.
    pub tile: usize,
    /// The tile's VPL's position and normal (as the GPU holds them, w included).
    pub position: [f32; 4],
    pub normal: [f32; 4],
    /// Whether the tile is of the last set, the only one whose splat areas are kept
    /// (`IsmTechnique::read_chosen`): the others' points come without footprints.
    pub last_set: bool,
    /// The chosen points, by slot.
    pub points: Vec<ChosenPoint>,
}

/// One chosen point of a tile.
#[derive(Clone, Debug, PartialEq)]
pub struct ChosenPoint {
    /// Its slot in the tile's sample and its index in the pool.
    pub slot: usize,
    pub index: u32,
    /// Its position and normal (as the pool holds them).
    pub position: [f32; 4],
    pub normal: [f32; 4],
    /// Its splat (tiles of the last set only).
    pub footprint: Option<Footprint>,
}

/// A point's splat as `ism_splat.wgsl` makes it: radius, and in texels the centre and the
/// images of the two tangents.
#[derive(Clone, Debug, PartialEq)]
pub struct Footprint {
    /// The splat disk's radius in metres.
    pub radius: f32,
    /// The disk's centre in map texels.
    pub centre: Vec2,
    /// The images of the disk's two tangent radii in map texels.
    pub ta: Vec2,
    pub tb: Vec2,
    /// Whether it covers [`PointsQuery::texel`].
    pub texel: Option<TexelCover>,
}

/// Whether a splat covers a texel, as the splat pass decides it.
#[derive(Clone, Debug, PartialEq)]
pub enum TexelCover {
    /// The texel lies past the paraboloid's rim.
    PastRim,
    /// Inside the footprint's ellipse, where the texel's ray meets the point's plane, whether
    /// that hit is on the point's surface (within its clip lines), and the clip lines with the
    /// hit point ([`PointsQuery::clips`]).
    Decided { inside: bool, hit: f32, on_surface: bool, clips: Option<(Vec<[f32; 4]>, Vec3)> },
}

/// Tile `q.tile`'s chosen points (those inside the box), with their splats where the renderer
/// kept their areas (the last set's tiles).
pub fn list_points(c: &Capture, renderer: &Renderer, q: &PointsQuery) -> Result<PointsReport, OracleError> {
    list_chosen_points(c, &read_chosen(renderer)?, q)
}

/// The last set's chosen points as the renderer kept them: per slot, pool index and area.
pub(super) fn read_chosen(renderer: &Renderer) -> Result<Vec<(u32, f32)>, OracleError> {
    let t = renderer.technique_as::<IsmTechnique>().ok_or(OracleError::NotIsm)?;
    Ok(t.read_chosen(renderer.device(), renderer.queue())?)
}

/// [`list_points`] with the chosen points read once ([`read_chosen`]).
pub(super) fn list_chosen_points(
    c: &Capture,
    chosen: &[(u32, f32)],
    q: &PointsQuery,
) -> Result<PointsReport, OracleError> {
    let tiles = c.vpls.len();
    let vpl = *c.vpls.get(q.tile).ok_or(OracleError::NoTile { tile: q.tile, tiles })?;
    let last_set = q.tile / c.n().max(1) + 1 == c.ism.bounces.max(1) as usize;
    let frame = MapFrame::new(Vec3::from_slice(&vpl.position[..3]), Vec3::from_slice(&vpl.normal[..3]));
    let per = c.lookup.per_ism as usize;
    let points = (0..per)
        .filter_map(|slot| {
            let mut point = chosen_point(c, q, slot)?;
            let area = chosen.get(q.tile % c.n().max(1) * per + slot).map(|a| a.1).filter(|_| last_set);
            point.footprint = area.map(|area| footprint(c, &frame, q, &point, area));
            Some(point)
        })
        .collect();
    Ok(PointsReport { tile: q.tile, position: vpl.position, normal: vpl.normal, last_set, points })
}

/// The point in slot `slot` of the tile, if one is there and inside the box.
fn chosen_point(c: &Capture, q: &PointsQuery, slot: usize) -> Option<ChosenPoint> {
    let index = *c.lookup.chosen_all.get(q.tile * c.lookup.per_ism as usize + slot)?;
    let position = *c.lookup.points.get(index as usize)?;
    let normal = *c.lookup.normals.get(index as usize)?;
    let inside = q.bbox.is_none_or(|b| (0..3).all(|a| position[a] >= b[a] && position[a] <= b[3 + a]));
    inside.then_some(ChosenPoint { slot, index, position, normal, footprint: None })
}

/// The splat of point `point`, of splat area `area`, in the map of `frame`.
fn footprint(c: &Capture, frame: &MapFrame, q: &PointsQuery, point: &ChosenPoint, area: f32) -> Footprint {
    let fr = c.res() as f32;
    let radius = (c.ism.splat_radius.powi(2) / std::f32::consts::PI * area).sqrt();
    let (pp, pn) = (Vec3::from_slice(&point.position[..3]), Vec3::from_slice(&point.normal[..3]));
    let (a, b) = onb(pn);
    let centre = frame.uv(pp) * fr;
    let (ta, tb) = (frame.uv(pp + a * radius) * fr - centre, frame.uv(pp + b * radius) * fr - centre);
    let mut fp = Footprint { radius, centre, ta, tb, texel: None };
    fp.texel = q.texel.map(|texel| texel_cover(c, frame, &fp, point, texel, q.clips));
    fp
}

/// Whether the splat `fp` of `point` covers map texel `(x, y)` as the splat pass decides it:
/// inside the footprint's ellipse, the texel's ray's hit on the point's plane within its clip
/// lines.
fn texel_cover(
    c: &Capture,
    frame: &MapFrame,
    fp: &Footprint,
    point: &ChosenPoint,
    (x, y): (f32, f32),
    clips: bool,
) -> TexelCover {
    let Some(l) = MapFrame::texel_local(x, y, c.res() as f32) else { return TexelCover::PastRim };
    let (ta, tb) = (fp.ta, fp.tb);
    let m00 = ta.x * ta.x + tb.x * tb.x + 0.25;
    let m01 = ta.x * ta.y + tb.x * tb.y;
    let m11 = ta.y * ta.y + tb.y * tb.y + 0.25;
    let e = Vec2::new(x + 0.5, y + 0.5) - fp.centre;
    let inside = m11 * e.x * e.x - 2.0 * m01 * e.x * e.y + m00 * e.y * e.y <= m00 * m11 - m01 * m01;
    let (pp, pn) = (Vec3::from_slice(&point.position[..3]), Vec3::from_slice(&point.normal[..3]));
    let dir = frame.world(l);
    let den = dir.dot(pn);
    let hit = if den.abs() <= 1e-6 { 0.0 } else { (pp - frame.o).dot(pn) / den };
    let h = frame.o + dir * hit;
    let on_surface = c.lookup.on_surface(point.index, h, 0.01 * fp.radius);
    let k = point.index as usize * CLIPS_PER_POINT;
    let clips = clips.then(|| (c.lookup.clips.get(k..k + CLIPS_PER_POINT).unwrap_or_default().to_vec(), h));
    TexelCover::Decided { inside, hit, on_surface, clips }
}
