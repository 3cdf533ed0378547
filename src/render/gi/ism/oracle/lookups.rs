//! The oracle's receivers and rooms, and its lookups: per (VPL, receiver) pair, the lit share
//! the ISM lookups give against the rays'.

use super::*;

// ---------------------------------------------------------------------------------------------
// Receivers and rooms.

/// Points spread over the scene's surfaces by area (the pool's distribution), each with what the
/// oracle asks of it.
pub struct Receivers {
    /// Position and normal.
    pub(super) world: Vec<(Vec3, Vec3)>,
    /// Whether the point lies inside solid geometry (a floor's face running on under a wall).
    buried: Vec<bool>,
    /// Luminance of its material's base colour (the Lambertian albedo).
    pub(super) albedo: Vec<f64>,
    /// The area each stands for.
    pub(super) area: f64,
}

impl Receivers {
    /// About `count` receivers over `c`'s scene (seed 9, one block).
    pub fn distribute(c: &Capture, count: usize) -> Self {
        let scene = c.scene;
        let samples = sample_points::distribute(scene, count, 1, 9);
        let world = samples.world(scene);
        let buried = world.par_iter().map(|&(p, n)| facing::is_buried(&c.bvh, p, n, 1e-4 * c.bvh.scale)).collect();
        let albedo = samples
            .points
            .iter()
            .map(|pt| {
                let material = scene.objects().get(pt.object as usize).map_or(usize::MAX, |o| o.material);
                luminance(scene.materials().get(material).cloned().unwrap_or_default().base_color)
            })
            .collect();
        let area = samples.weighted_area.iter().sum::<f64>() / world.len().max(1) as f64;
        Self { world, buried, albedo, area }
    }

    /// How many there are.
    pub fn len(&self) -> usize {
        self.world.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.world.is_empty()
    }
}

/// Which (VPL, receiver) pairs count, by the rooms they are in.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairFilter {
    /// Split the plan into rooms at x and z (room = [x >] + 2 [z >]); `None`: the suite's three
    /// rooms, x / 5.2.
    pub grid: Option<(f32, f32)>,
    /// Only pairs in different rooms (light through doorways).
    pub cross: bool,
    /// Only VPLs in room a (any: -1) and receivers in room b.
    pub pair: Option<(f32, f32)>,
}

impl PairFilter {
    /// The room point `p` is in.
    pub fn room(&self, p: Vec3) -> f32 {
        match self.grid {
            Some((x, z)) => f32::from(u8::from(p.x > x)) + 2.0 * f32::from(u8::from(p.z > z)),
            None => (p.x / 5.2).floor(),
        }
    }

    /// Whether the pair of a VPL at `o` and a receiver at `p` counts.
    pub fn keeps(&self, o: Vec3, p: Vec3) -> bool {
        let (a, b) = (self.room(o), self.room(p));
        !(self.cross && a == b) && self.pair.is_none_or(|(pa, pb)| (pa < 0.0 || pa == a) && pb == b)
    }

    /// The room of `p` as an index of the four [`BounceReport`] keeps (clamped to 0..=3).
    pub(super) fn room_index(&self, p: Vec3) -> usize {
        self.room(p).clamp(0.0, 3.0) as usize
    }
}

/// Set `set`'s live VPLs by room: count and luminance power.
pub fn vpls_by_room(c: &Capture, filter: &PairFilter, set: usize) -> BTreeMap<i32, (u32, f64)> {
    let mut rooms = BTreeMap::<i32, (u32, f64)>::new();
    for v in (0..c.n()).filter_map(|k| c.vpl(set * c.n() + k)) {
        let e = rooms.entry(filter.room(v.o) as i32).or_default();
        e.0 += 1;
        e.1 += luminance(v.vpl.power);
    }
    rooms
}

/// Whether receiver `p` (normal `pn`) sees the VPL at `o` (normal `nn`): the ray between them,
/// each end lifted off its surface by 1 mm (a first-bounce VPL comes from the light's G-buffer
/// depth and may lie a fraction of a millimetre inside its surface, which a ray to the exact
/// position would count as shadowing every receiver).
pub(super) fn sees(bvh: &SceneBvh, p: Vec3, pn: Vec3, o: Vec3, nn: Vec3) -> bool {
    let (a, b) = (p + pn * 1e-3, o + nn * 1e-3);
    let d = (b - a).length();
    d <= 0.0 || !bvh.occluded(a, (b - a) / d, d)
}

/// A VPL and a receiver that face each other: distance, the cosines at the VPL and at the
/// receiver.
#[derive(Clone, Copy)]
pub(super) struct Facing {
    pub(super) d: f32,
    pub(super) cos_s: f32,
    pub(super) cos_r: f32,
}

/// The pair's geometry, `None` unless they face each other at least 1 mm apart.
pub(super) fn facing(o: Vec3, nn: Vec3, p: Vec3, pn: Vec3) -> Option<Facing> {
    let to_p = p - o;
    let d = to_p.length();
    let dir = to_p / d;
    let (cos_s, cos_r) = (nn.dot(dir), pn.dot(-dir));
    (cos_s > 0.0 && cos_r > 0.0 && d >= 1e-3).then_some(Facing { d, cos_s, cos_r })
}

// ---------------------------------------------------------------------------------------------
// The lookups.

/// What the lookups of one set give against the rays. The weights are each pair's form factor
/// cos_s cos_r / d^2 (times the VPL's luminance power with [`LookupOptions::power_weighted`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LookupReport {
    /// The bounce set.
    pub set: usize,
    /// The weight of the pairs the rays light.
    pub rays: f64,
    /// The weight of the pairs the ISM lookups light.
    pub ism: f64,
    /// Lit by the rays, shadowed by the lookups.
    pub false_shadow: f64,
    /// The part of `false_shadow` the texel's own point's slab casts.
    pub own_slab: f64,
    /// Shadowed by the rays, lit by the lookups.
    pub false_light: f64,
    /// The weight of every pair.
    pub pairs: f64,
    /// The false light's weight times the VPL's power (r + g + b), by what the texel holds
    /// ([`FALSE_LIGHT_KINDS`]) and the VPL's elevation band (below 3, 3-10, 10-30, above 30
    /// degrees).
    pub false_light_kinds: [[f64; 4]; 6],
    /// Up to [`SHOWN_PAIRS`] wrongly lit or shadowed pairs, as [`ShowOptions`] asks.
    pub examples: Vec<PairExample>,
}

impl LookupReport {
    /// The lit share the lookups give over the rays' (1: right on average).
    pub fn lit_ratio(&self) -> f64 {
        self.ism / self.rays
    }

    /// Adds another VPL's pairs (its examples after these, up to [`SHOWN_PAIRS`]).
    fn add(&mut self, o: LookupReport) {
        self.rays += o.rays;
        self.ism += o.ism;
        self.false_shadow += o.false_shadow;
        self.own_slab += o.own_slab;
        self.false_light += o.false_light;
        self.pairs += o.pairs;
        for (row, other) in self.false_light_kinds.iter_mut().zip(o.false_light_kinds) {
            row.iter_mut().zip(other).for_each(|(a, b)| *a += b);
        }
        let room = SHOWN_PAIRS.saturating_sub(self.examples.len());
        self.examples.extend(o.examples.into_iter().take(room));
    }
}

/// Which pairs [`lookups`] counts and lists.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LookupOptions {
    /// Which pairs count, by room.
    pub filter: PairFilter,
    /// Weight the pairs by the VPL's luminance power too (what the screen sees).
    pub power_weighted: bool,
    /// Only receivers on surfaces open to the air (not a floor under a wall).
    pub unburied: bool,
    /// Which wrongly lit or shadowed pairs to list.
    pub show: ShowOptions,
}

/// Which wrongly lit or shadowed pairs [`LookupReport::examples`] lists.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShowOptions {
    /// False light (lit by the lookups, shadowed by the rays).
    pub false_light: bool,
    /// False shadow, of the last set, with both cosines above 0.2.
    pub false_shadow: bool,
    /// Each with the texel's four neighbours and its coarse levels.
    pub neighbours: bool,
    /// False light of this row of [`FALSE_LIGHT_KINDS`] only.
    pub kind: Option<usize>,
    /// False light of VPLs above this cosine of elevation only.
    pub min_cos: f32,
}

/// A wrongly lit or shadowed (VPL, receiver) pair.
#[derive(Clone, Debug, PartialEq)]
pub struct PairExample {
    /// The VPL's atlas tile.
    pub tile: usize,
    /// The VPL's position and normal.
    pub vpl: (Vec3, Vec3),
    /// The receiver's position and normal.
    pub receiver: (Vec3, Vec3),
    /// The map texel looked up.
    pub texel: Vec2,
    /// The texel's stored distance in metres.
    pub stored: f32,
    /// The distance of the lookup point q (the receiver lifted by the bias) from the VPL.
    pub q_distance: f32,
    /// The rays' first hit towards q, from the VPL.
    pub first_hit: f32,
    /// False shadow or false light, with what each adds.
    pub what: ExampleKind,
    /// The texel's neighbours and coarse levels ([`ShowOptions::neighbours`]; else empty).
    pub neighbours: Vec<NeighbourWord>,
}

/// Whether a [`PairExample`] is false shadow or false light.
#[derive(Clone, Debug, PartialEq)]
pub enum ExampleKind {
    /// Lit by the rays, not by the lookup: the texel's slot.
    FalseShadow { slot: Option<u32> },
    /// Lit by the lookup, not by the rays: the VPL's point spacing, the lookup point, the
    /// texel's mark bit (depth only) and the point its word names.
    FalseLight { sigma: f32, q: Vec3, mark: u32, point: Option<([f32; 4], [f32; 4])> },
}

/// A texel near the one looked up: where, its distance in metres, the point it names.
#[derive(Clone, Debug, PartialEq)]
pub struct NeighbourWord {
    /// Which texel.
    pub at: NeighbourAt,
    /// Its stored distance in metres.
    pub depth: f32,
    /// The pool point (position, normal) its word names, if any.
    pub point: Option<([f32; 4], [f32; 4])>,
}

/// Where a [`NeighbourWord`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NeighbourAt {
    /// Offset from the texel (0, 0 is the texel itself).
    Offset(i64, i64),
    /// The texel's word at this coarse level (1: half the side).
    Level(u32),
}

/// The texel at atlas index `at` and its four neighbours, then its coarse levels: their
/// distances and points (one texel holds one surface; the lost one is often next door).
fn neighbours(c: &Capture, at: usize, tile: usize) -> Vec<NeighbourWord> {
    let side = c.side as i64;
    let word = |at: NeighbourAt, i: i64| {
        let w = *c.words.get(usize::try_from(i).ok()?)?;
        Some(NeighbourWord { at, depth: atlas_word::depth(w) * c.d_max, point: c.word_point(w, tile) })
    };
    let mut list: Vec<NeighbourWord> = [(0i64, 0i64), (-1, 0), (1, 0), (0, -1), (0, 1)]
        .into_iter()
        .filter_map(|(dx, dy)| word(NeighbourAt::Offset(dx, dy), at as i64 + dy * side + dx))
        .collect();
    let (x, y, s) = ((at % c.side) as u32, (at / c.side) as u32, c.side as u32);
    for level in 1..=atlas_word::HOLE_LEVELS {
        let i = s * s + atlas_word::level_base(s, level) + (y >> level) * (s >> level) + (x >> level);
        list.extend(word(NeighbourAt::Level(level), i64::from(i)));
    }
    list
}

/// Which row of [`FALSE_LIGHT_KINDS`] a false-light lookup's texel word is: receiver `p`
/// (normal `pn`) whose ray from VPL `o` along `dir` first meets geometry at `wall`.
fn false_light_kind(
    c: &Capture,
    word: u32,
    tile: usize,
    (p, pn): (Vec3, Vec3),
    wall: f32,
    dir: Vec3,
    o: Vec3,
) -> usize {
    if word == u32::MAX {
        return 0;
    }
    let Some((sp, sn)) = c.word_point(word, tile).filter(|_| word & 1 == 0) else { return 1 };
    let (sp, sn) = (Vec3::from_slice(&sp[..3]), Vec3::from_slice(&sn[..3]));
    if sn.dot(pn) > 0.99 && (sp - p).dot(pn).abs() < 0.02 {
        return 2;
    }
    if (sp - o).length() > wall * 1.05 {
        return 3;
    }
    let den = dir.dot(sn);
    let t = if den.abs() > 1e-6 { (sp - o).dot(sn) / den } else { -1.0 };
    if t <= 0.0 || t >= (p - o).length() * 0.999 { 4 } else { 5 }
}

/// One ISM lookup as `ism_lit` makes it: the lookup point q (the receiver lifted along its
/// normal by the bias), its offset from the VPL and distance, the texel, its atlas index, and
/// whether the lookup lights it.
struct Lookup {
    q: Vec3,
    dir: Vec3,
    qd: f32,
    texel: Vec2,
    at: usize,
    lit: bool,
}

/// The lookup for receiver `p` (normal `pn`) of VPL `s` (map frame `frame`).
fn look_up(c: &Capture, s: &Sampled, frame: &MapFrame, (p, pn): (Vec3, Vec3), f: &Facing) -> Lookup {
    let (res, sigma) = (c.res() as f32, s.vpl.normal[3]);
    let sin_r = (1.0 - f.cos_r * f.cos_r).max(0.0).sqrt();
    let delta = f.d * sigma * (c.ism.bias_constant + c.ism.bias_slope * sin_r);
    let q = p + pn * delta;
    let qq = q - s.o;
    let qd = qq.length();
    let texel = ((frame.uv(q) * res).floor().max(Vec2::ZERO)).min(Vec2::splat(res - 1.0));
    let at = c.texel_index(s.tile, texel.x as usize, texel.y as usize);
    let atlas = AtlasTexel {
        words: &c.words,
        r: c.res() as u32,
        c: c.columns() as u32,
        texel: (texel.x as u32, texel.y as u32),
    };
    let lit = c.lookup.lit(atlas, s.o, sigma, s.tile as u32, qq / qd, qd, qd / c.d_max, 8.0 / res);
    Lookup { q, dir: qq / qd, qd, texel, at, lit }
}

/// One sampled VPL's pairs as [`lookups`] counts them.
struct VplPairs<'c, 'a> {
    c: &'c Capture<'a>,
    s: Sampled,
    frame: MapFrame,
    opts: &'c LookupOptions,
    /// Whether this is the last set (the only one whose false shadow is listed).
    last_set: bool,
    rep: LookupReport,
}

impl VplPairs<'_, '_> {
    /// Counts the pair of this VPL and receiver `recv` (`buried`: inside solid geometry).
    fn pair(&mut self, recv: (Vec3, Vec3), buried: bool) {
        let (c, s, opts) = (self.c, self.s, self.opts);
        let Some(f) = facing(s.o, s.n, recv.0, recv.1) else { return };
        if !opts.filter.keeps(s.o, recv.0) || (opts.unburied && buried) {
            return;
        }
        let mut w = f64::from(f.cos_s * f.cos_r / (f.d * f.d).max(0.01));
        if opts.power_weighted {
            w *= luminance(s.vpl.power);
        }
        let by_rays = sees(&c.bvh, recv.0, recv.1, s.o, s.n);
        let l = look_up(c, &s, &self.frame, recv, &f);
        self.rep.pairs += w;
        if by_rays {
            self.rep.rays += w;
        }
        if l.lit {
            self.rep.ism += w;
        }
        if by_rays && !l.lit {
            self.false_shadow(recv, &l, &f, w);
        }
        if !by_rays && l.lit {
            self.false_light(recv, &l, &f, w);
        }
    }

    /// Counts a pair the rays light and the lookup does not, and lists it if asked.
    fn false_shadow(&mut self, recv: (Vec3, Vec3), l: &Lookup, f: &Facing, w: f64) {
        let (c, s) = (self.c, self.s);
        self.rep.false_shadow += w;
        let word = c.words[l.at];
        let per = c.lookup.per_ism as usize;
        let own = atlas_word::slot(word).and_then(|slot| c.lookup.chosen_all.get(s.tile * per + slot as usize));
        let reach = atlas_word::NEIGHBOUR_REACH * s.vpl.normal[3];
        if own.is_some_and(|&j| c.lookup.slab_blocks(j, s.o, l.dir, l.qd, reach)) {
            self.rep.own_slab += w;
        }
        let show = self.opts.show.false_shadow && self.last_set && f.cos_s > 0.2 && f.cos_r > 0.2;
        if show && self.rep.examples.len() < SHOWN_PAIRS {
            let wall = c.first_hit(s.o, s.n, l.dir);
            let example = self.example(recv, l, wall, ExampleKind::FalseShadow { slot: atlas_word::slot(word) });
            self.rep.examples.push(example);
        }
    }

    /// Counts a pair the lookup lights and the rays do not, by what its texel holds and the
    /// VPL's elevation, and lists it if asked.
    fn false_light(&mut self, recv: (Vec3, Vec3), l: &Lookup, f: &Facing, w: f64) {
        let (c, s, show) = (self.c, self.s, self.opts.show);
        self.rep.false_light += w;
        let wall = c.first_hit(s.o, s.n, l.dir);
        let word = c.words[l.at];
        let kind = false_light_kind(c, word, s.tile, recv, wall, l.dir, s.o);
        let band = ELEVATION_BANDS.iter().position(|&b| f.cos_s < b).unwrap_or(ELEVATION_BANDS.len());
        let power = s.vpl.power[0] + s.vpl.power[1] + s.vpl.power[2];
        self.rep.false_light_kinds[kind][band] += w * f64::from(power);
        let listed = show.false_light && f.cos_s >= show.min_cos && show.kind.is_none_or(|k| k == kind);
        if listed && self.rep.examples.len() < SHOWN_PAIRS {
            let point = c.word_point(word, s.tile);
            let what = ExampleKind::FalseLight { sigma: s.vpl.normal[3], q: l.q, mark: word & 1, point };
            let example = self.example(recv, l, wall, what);
            self.rep.examples.push(example);
        }
    }

    /// The example a wrongly decided pair makes.
    fn example(&self, receiver: (Vec3, Vec3), l: &Lookup, wall: f32, what: ExampleKind) -> PairExample {
        let c = self.c;
        PairExample {
            tile: self.s.tile,
            vpl: (self.s.o, self.s.n),
            receiver,
            texel: l.texel,
            stored: atlas_word::depth(c.words[l.at]) * c.d_max,
            q_distance: l.qd,
            first_hit: wall,
            what,
            neighbours: if self.opts.show.neighbours { neighbours(c, l.at, self.s.tile) } else { Vec::new() },
        }
    }
}

/// Set `set`'s lookups against the rays: every fourth live VPL with every receiver that faces
/// it and that `opts` keeps.
pub fn lookups(c: &Capture, recv: &Receivers, opts: &LookupOptions, set: usize) -> LookupReport {
    let last_set = set + 1 >= c.ism.bounces as usize;
    let per_vpl: Vec<LookupReport> = c
        .sampled(set)
        .into_par_iter()
        .map(|s| {
            let rep = LookupReport { set, ..LookupReport::default() };
            let mut pairs = VplPairs { c, s, frame: MapFrame::new(s.o, s.n), opts, last_set, rep };
            for (&p, &buried) in recv.world.iter().zip(&recv.buried) {
                pairs.pair(p, buried);
            }
            pairs.rep
        })
        .collect();
    per_vpl.into_iter().fold(LookupReport { set, ..LookupReport::default() }, |mut all, r| {
        all.add(r);
        all
    })
}

// ---------------------------------------------------------------------------------------------
// The bounce.
