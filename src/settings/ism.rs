//! Settings of the ISM techniques (`ism`, `ism-ritschel`) and their validation: pure data that
//! the project file stores and the GI panel's ISM section edits.

use serde::{Deserialize, Serialize};

use super::SettingsError;

/// Largest ISM atlas side: a u32 atlas of this side stays within 128 MiB.
pub const MAX_ATLAS_SIDE: u32 = 5792;

/// Settings of the ISM techniques (`ism`, `ism-ritschel`; Knecht 2009). Defaults are the
/// thesis's where it gives them (256 VPLs, 128^2 ISMs, c_base 0.9, alpha 0.01, beta 0.8) and
/// measured elsewhere: each VPL draws 1024 points from a 256k-point pool in proportion to the
/// projected solid angle they cover (the thesis gives every ISM an equal share of 32k evenly
/// spread points, which at level scale left a crate beside a VPL with one or two points), a
/// distance clamp scaled by each VPL's patch instead of 1 world unit, ISM lookups that test the
/// receiver's own ray against the surface of the point whose splat fills the texel (its plane
/// within its open edges) with a small normal offset in units of the VPL's angular point
/// spacing, instead of a depth compare with a bias that is a fraction of the scene diameter, points on the faces that see any geometry only, splats
/// sized as each point's surface disk with its plane's depth per texel and clipped at the
/// surface's open edges, pull-push that fills only empty texels, the next bounce's VPL picked
/// in proportion to its power instead of the brightest, and a geometric tail after the last
/// bounce (`docs/QUALITY.md` has the figures).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IsmSettings {
    /// VPLs per set (4..=1024). Cost: shading and ISM splatting grow linearly; quality: fewer
    /// blotches and less flicker (the thesis needs 256 for flicker-free results).
    pub vpl_count: u32,
    /// Side of each VPL's paraboloid ISM (64..=256). Cost: atlas memory and pull-push grow with
    /// its square; quality: sharper indirect shadows (needs enough points per ISM).
    pub ism_resolution: u32,
    /// Scene sample points in the pool every ISM draws its points from (stratified by area x
    /// sampling weight, in clusters of 64). Cost: the per-VPL point choice weighs every
    /// cluster (linear); quality: finer detail near VPLs (a VPL's points can be no denser than
    /// the pool's).
    pub total_points: u32,
    /// Points splatted into each VPL's ISM, drawn from the pool in proportion to the solid
    /// angle they subtend from that VPL (an extension of the thesis, which gives each ISM an
    /// equal share of uniformly spread points: at level scale a box next to a VPL then had one
    /// or two points, and its light leaked through). Cost: splatting and the bounce pass grow
    /// linearly; quality: fewer holes, a smaller lookup offset (it scales with the angular
    /// spacing sqrt(2 pi / P)). Measured on lavapipe (`bouncelab probe cornell --frames 8`, whole run):
    /// 10.1 s at 256, 11.9 s at 1024; the splats' texel coverage, not their count, dominates.
    /// On the suite's three rooms, where a wall far from a VPL gets about one point, the first
    /// bounce alone reads 1.059 of a one-bounce reference at 1024 and 1.030 at 2048 (FLIP over
    /// `direct`'s 0.61 and 0.42), since the selection gives the VPL's own plane no points
    /// (1.092 and 1.046 before). `ism maps` took 1369-1376 ms at 1024 and 1662-1674 ms at 2048
    /// on lavapipe before that change (stop 62, not timed since; the splat now walks 5% more
    /// texels: `docs/notes/ism-tuning.md`, "Stop 62", "The VPL's own plane").
    pub points_per_ism: u32,
    /// Interleave size n (the G-buffer splits into n x n tiles; 1..=8). Cost: none; quality:
    /// each pixel sees N/n^2 VPLs, the n x n filter hides the pattern but blurs detail.
    pub interleave: u32,
    /// Base confidence c_base of the temporal blend (0..1). Higher: smoother, more afterglow.
    pub base_confidence: f32,
    /// Time constant, in frames, of the temporal blend while the camera, lights and objects
    /// stand still (0: off, c_base throughout as in the thesis; values up to 1 / (1 - c_base)
    /// change nothing). The confidence's cap rises from c_base to 1 - 1 / this after one still
    /// frame, and any edit or camera move drops it back to c_base for the frames it moves, so
    /// the thesis's behaviour under motion is unchanged while a still view keeps refining (a
    /// still view also drops the illumination term: no light changed, and the term weighted the
    /// bright frames of VPL noise up: the Cornell box read 1.009 of the reference's energy with
    /// the thesis's blend, 1.023 with the still cap and the term, 0.988 without it). After a light or
    /// object edit the view stays at c_base until the light from before it has faded (44
    /// frames at 0.9), so the afterglow is the thesis's. Each
    /// pixel's confidence is also held at m / (m + 1), m its history's effective sample count,
    /// so a new history is the plain mean of its frames (the thesis's blend kept the first
    /// frame at weight 0.9^k). Cost: two R32 float textures and 8 bytes read and written per
    /// pixel in the temporal merge (which already reads six view-sized textures). Measured with
    /// `bouncelab bench --quality` (lavapipe; the 24 frames after the history has settled, 9-32
    /// before and 33-56 now): the suite's three rooms, lit only through doorways, went from a
    /// worst frame of 0.718 of the reference's energy and an 8.9% spread to 0.942 and 1.3%;
    /// the other scenes from 0.2-0.4% spread to 0.1% at most, temporal instability about a
    /// tenth.
    pub still_frames: u32,
    /// Weight of the screen-space/depth movement in the confidence. Higher: history dropped
    /// sooner under motion (less ghosting, more noise).
    pub w_position: f32,
    /// Weight of the normal change in the confidence.
    pub w_normal: f32,
    /// Weight of the illumination change in the confidence. Higher: reacts faster to lighting
    /// changes (less afterglow) but lets VPL resampling noise through. Off while the view
    /// stands still (`still_frames`).
    pub w_illumination: f32,
    /// Light bounces (1..=6); each extra bounce costs one VPL generation, ISM and shading pass
    /// (shading time grows linearly). The thesis's figures use 1; the default is 6, which
    /// brings the default Cornell box within 3% of the path tracer's energy (ism-ritschel at
    /// 128x72: 4 bounces 93%, 5: 96%, 6: 97% over 8 frames; each bounce adds less than the last).
    pub bounces: u32,
    /// Add the bounces beyond the last set as a geometric series: the last set's power is
    /// scaled by 1 / (1 - r), r from `tail_ratio` (an extension of the thesis; one tiny pass).
    /// Free; the Cornell box lit by a point light alone went from 0.948 to 0.956 of the
    /// reference's energy at 6 bounces (`tests/integration/ism_lights.rs`).
    pub bounce_tail: bool,
    /// Where the tail's ratio r comes from. Free within measurement (a per-workgroup sum in
    /// the shading either way).
    pub tail_ratio: TailRatio,
    /// How the lit points of a set's ISMs become the next set's VPLs. The per-VPL picks are
    /// free (one hash and a log per point); `Resampled` adds a one-workgroup scan and one
    /// workgroup per VPL per bounce.
    pub bounce_pick: BouncePick,
    /// View importance of the proportional and resampled picks: a lit point is picked as if
    /// (1 + this x I) times brighter, I its unoccluded reach into the last frame's view
    /// (`ism_view_importance.wgsl`: about 1 beside the camera, up to 100 next to what it sees,
    /// 0 facing away), and the new VPL's power is divided by the same, so every set's expected
    /// light is unchanged (0: by brightness alone). More VPLs, each carrying less, land where
    /// they light the view, which steadies a room lit only through doorways. Cost: one pass
    /// over the pool points per frame, 64 depth reads each (`ism view importance`, in
    /// `ism shade`).
    pub view_importance: f32,
    /// The first set's view weight: a lit surface or emitter the camera sees (facing it, at
    /// the depth the view has there) is drawn as if (1 + this) times brighter, and the VPLs
    /// drawn there carry less (between 1 / (1 + this) and 1 times the power they would carry
    /// by power alone), so the set's expected light is unchanged (0: by power alone, as in the
    /// thesis). A VPL off screen carries at most (1 + this) times its power without the weight.
    /// Where a light's power lands mostly out of view (the sun on a roof), the VPLs on its lit
    /// surfaces in view then no longer change in number from frame to frame. The sky's VPLs sit
    /// on the scene's bounding sphere, never in view: a sky-only scene is unchanged, and with a
    /// sky the weight moves budget from the sky to the seen surfaces other lights light.
    /// Measured with `bouncelab probe SCENE --mode ism-ritschel --trace --frames 11`
    /// (lavapipe), each frame's FLIP over `direct`'s mean / worst at 0 / 1 / 3 / 8: the
    /// sun-and-sky window room 0.26 / 0.34, 0.19 / 0.31, 0.19 / 0.29, 0.17 / 0.31 (single
    /// frames' energy 0.86-1.18 at 0, 0.95-1.15 at 1); the clutter 0.20 / 0.22, 0.21 / 0.23,
    /// 0.22 / 0.26, 0.21 / 0.28; the hall 0.12 / 0.14, 0.13 / 0.17, 0.13 / 0.14, 0.15 / 0.17;
    /// the sun-lit window room, courtyard, panels and Cornell box within 0.01 of 0 in the mean
    /// at 1 and 3, their worst frames no higher at 1; the three rooms unchanged (no first-set
    /// VPL is on screen). Cost: the importance seed reads the light normal and nine view depth
    /// texels per lit light-G-buffer texel (`ism vpls`).
    pub first_set_seen_weight: f32,
    /// Radius of each point's ISM splat as a fraction of the radius of the disk it stands for
    /// (the area it was chosen to stand for); the splat is that disk's elliptical footprint in
    /// the paraboloid map, clipped at its surface's open edges. Disks of their surface's area
    /// leave gaps between them (on a square grid a disk must have 1.57x its cell's area, radius
    /// 1.25x, to cover it), through which light leaks; larger ones close doorways seen at
    /// grazing angles. Measured with `bouncelab probe` (mean of 8 frames, `--average-from 0`,
    /// point-surface lookups, offset 0.05), energy against the reference at 1.25 / 1.35 / 1.5:
    /// the held-out four-room flat 1.20 / 1.09 / 1.03 (at 1.35: 1.22 over 16 frames, 1.56 over
    /// 32; light still leaks where its floor VPLs see a wall's foot at a few degrees), the held-out
    /// offices 1.06 / 1.02 / 0.78, the suite's three rooms 1.015 / 0.975 / 0.932, the Cornell
    /// box 0.993 at 1.25 and 1.35. Cost: the ISM maps' texel writes grow with its square
    /// (`bouncelab probe cornell --frames 8` on lavapipe, before the point-surface lookups: 7.9 s at 0.5,
    /// 11.9 s at 1.0; `bench --quick`: `ism maps` 1.75 s per frame at 1.35 against 1.31-1.34 s
    /// at 1.0, lookups included).
    pub splat_radius: f32,
    /// Geometry-aware filter threshold alpha: a neighbour farther than alpha x the scene
    /// diameter from the pixel's tangent plane is rejected (the thesis's 0.01, applied along
    /// the normal instead of the view ray so grazing walls keep their taps). Free; lower:
    /// sharper contacts, more visible interleave pattern.
    pub filter_depth: f32,
    /// Geometry-aware filter normal threshold beta (minimum cosine; the SH filter tests
    /// geometric normals only, so normal maps never break its window). Free.
    pub filter_normal: f32,
    /// Filter the incident radiance as 9 SH coefficients per colour and shade afterwards with
    /// each pixel's own normal and BRDF (Segovia & Wald): keeps glossy and normal-mapped
    /// detail. Cost: 56 bytes per pixel (f16) and 27-channel filtering: on an H100 the `ism
    /// shade` pass goes from 0.91 to 1.08 ms at 320x180 and from 1.09 to 1.68 ms at 640x360
    /// (docs/BENCHMARKS.md); on lavapipe +7% and +17% (docs/BENCHMARKS-lavapipe.md).
    pub sh_filter: bool,
    /// The resolution the VPLs are gathered at (`ism shade`, the pass whose every pixel makes
    /// `vpl_count x bounces / n^2` imperfect-shadow-map lookups). `Half` gathers at one pixel
    /// of each 2 x 2 block, a quarter of the lookups, and the geometry-aware filter then takes
    /// its n x n taps from those samples (each tested against the full-resolution pixel's
    /// plane and normal) before the temporal merge. Not with the SH filter, which gathers at
    /// full resolution. Cost and gain: [`ShadeResolution`].
    pub shade_resolution: ShadeResolution,
    /// An extra fixed minimum VPL distance in metres, on top of `clamp_disk` (0 = none, the
    /// default). The thesis clamps d^2 >= 1 in world units, which assumes large scenes: in a 2 m
    /// Cornell box that loses 9-11% of the one-bounce light, and with 0.1 m the 20 cm diorama
    /// read 0.88 of the reference's energy (0.99 with the scale-free `clamp_disk` alone).
    pub clamp_distance: f32,
    /// The scale-free distance clamp: a VPL stands for the patch it was drawn from (its light-
    /// G-buffer texel's area / (N p), or one ISM's share of the scene's area for bounce VPLs),
    /// and d^2 is clamped at this factor x that patch's area / pi (the squared radius of a disk
    /// of that area) at screen receivers only (the bounce passes spread a near point's light
    /// over the point's own disk, d^2 + A / pi, which keeps it below the VPL's power without
    /// losing light: clamping there at the VPL's disk lost 9% per bounce). 0 turns it off. Free;
    /// larger: fewer spikes near VPLs, darker corners. It replaces the thesis's 1-unit clamp,
    /// which no fixed distance can stand for from a 20 cm diorama to a 60 m hall. Measured with
    /// `bouncelab probe` (32 frames): 0.5 kept 0.76 of the three rooms' energy and 0.945
    /// of the Cornell box's, 0.25 0.76 and 0.952.
    pub clamp_disk: f32,
    /// ISM lookup normal offset, constant part, as a fraction of the world spacing of one
    /// ISM's sample points (sqrt(area / points per ISM): a splat's size on the surface): the
    /// receiver is looked up at p + n delta (`ism_offset_point` in `common/vpl.wgsl`). A lookup
    /// tests the receiver's own ray against the surface of the point whose splat fills the texel
    /// (`ism_lookup.wgsl`), so flat surfaces need no offset; this covers curved ones, whose
    /// neighbours' tangent disks lie in front of them. Free; larger: softer contact shadows and
    /// light beyond a doorway shifted (a raised receiver is seen through the doorway higher up).
    /// Measured before the point-surface lookups (`bouncelab probe`, 8 frames, splat radius 1.25,
    /// depths compared against the plane through the texel): 0 / 0.05 gave the three rooms
    /// 0.933 / 0.948 of the reference's energy, the Cornell box 0.983 / 0.989, the cluttered
    /// room 0.928 / 0.938. Unlike a depth bias it lets no light through a wall at any size.
    pub bias_constant: f32,
    /// ISM lookup normal offset, slope part: times sin(angle between the receiver's normal and
    /// the VPL) x the point spacing. Free; off by default: lookups along the receiver's own ray
    /// need no grazing margin, and it shifts the light beyond doorways (0.2 took the three
    /// rooms from 0.90 to 0.64 of the reference's energy, measured with texel-centre depths).
    pub bias_slope: f32,
}

/// Where `ism shade` gathers the VPLs ([`IsmSettings::shade_resolution`]).
///
/// Measured (lavapipe, release, `bouncelab profile --modes direct,ism --scenes cornell,rooms,window
/// --frames 2 --warm-up 2`, alone on the machine): `ism shade` (the split and the gathering) at
/// 640 x 360 went from 776 / 700 / 1601 ms to 314 / 208 / 624 ms, at 1280 x 720 from 2152 / 2518 /
/// 5428 ms to 767 / 735 / 2047 ms (Cornell box / rooms / window); `ism filter` (the filter and
/// the temporal merge) from 84-136 to 119-253 ms at 1280 x 720: its taps read the split
/// G-buffer's positions and normals as well. On the H200 at e48fc51 `ism shade` read 5.3-11.1 ms
/// at 1080p; a quarter of its lookups should bring it to about 1.5-3 ms (not yet profiled).
/// Quality (`bouncelab probe SCENES --mode ism --frames 32 --average-from 16`, the suite's
/// references at 128 x 72 rendered at 256 x 144, so half gathers 128 x 72), energy and FLIP full
/// -> half: rooms 1.059 / 0.1365 -> 1.068 / 0.1390, window 0.986 / 0.0414 -> 0.987 / 0.0400,
/// clutter 0.931 / 0.1231 -> 0.931 / 0.1228, hall 0.993 / 0.0383 -> 0.992 / 0.0382, diorama
/// 0.985 / 0.0370 -> 0.985 / 0.0362, Cornell box 0.986 / 0.0387 -> 0.989 / 0.0397: within the
/// frames' noise even at that size. `Auto` keeps full gathering below 640 x 360 (the tests'
/// and the quality matrix's sizes, and the editor's small previews).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShadeResolution {
    /// Every pixel gathers its share of the VPLs (Knecht's interleaved shading as the thesis
    /// runs it).
    Full,
    /// One pixel of each 2 x 2 block gathers; a quarter of the lookups.
    Half,
    /// `Half` from [`ShadeResolution::AUTO_HALF_FROM`] pixels on, `Full` below.
    #[default]
    Auto,
}

impl ShadeResolution {
    /// The view size (pixels) from which `Auto` gathers at half resolution.
    pub const AUTO_HALF_FROM: u64 = 640 * 360;

    /// The step between gathering pixels along each axis for a view of `size` (1 or 2); the
    /// SH filter always gathers at full resolution.
    pub fn scale(self, size: (u32, u32), sh_filter: bool) -> u32 {
        let half = match self {
            Self::Full => false,
            Self::Half => true,
            Self::Auto => u64::from(size.0) * u64::from(size.1) >= Self::AUTO_HALF_FROM,
        };
        if half && !sh_filter { 2 } else { 1 }
    }
}

/// The ratio r of the bounce tail (`IsmSettings::bounce_tail`), `ism_bounce.wgsl` `tail`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TailRatio {
    /// The last set's total power over the previous set's: right where the light on screen
    /// decays as the scene's light does (one room), too small for a room light reaches late.
    Power,
    /// The light the last set gave the screen over the previous set's (last frame's shading,
    /// a running mean that starts from the power ratio): for a room that light
    /// reaches late (the default since the lookups' hole test: with the power ratio the suite's
    /// unlit third room read 0.848 at the CI test's size, under its 0.9). The held-out offices
    /// (camera two doors from the light, 24% of the light on screen after the sixth bounce)
    /// went from 0.821 to 1.011 of the reference's energy;
    /// the suite's three rooms (camera in the unlit room) from 0.913 to 1.046 (1.12 at the
    /// CI test's size, over its 1.1 limit), the rest of the suite by less than 0.002; the
    /// held-out flat from 1.102 to 1.342, its leak no longer hidden (`bouncelab probe`, 32 frames).
    /// With the lookups' hole test and buried points reflecting nothing: the offices 0.774 ->
    /// 0.921, the flat 0.925 -> 1.164. Against the path tracer's own 7-bounce image, the
    /// bounces past the sixth add 30.5% in both; the screen ratio's tail adds 32-35%, the power
    /// ratio's 11-12%.
    Screen,
    /// The geometric mean of the two, the default since the bounce passes stopped losing 9% of
    /// the light per bounce (which the screen ratio had been making up for): the screen's ratio
    /// says how fast the light on screen still grows as it spreads into the camera's room, but
    /// that growth slows as the spread settles, and the power ratio is where it ends. Against
    /// Mitsuba (`bouncelab probe --average-from 16 --ssaa 1`, frames 17-40, 128x72),
    /// power / screen / mean: the suite's three rooms 0.910 / 1.205 / 0.989, the held-out
    /// offices 0.828 / 0.980 / 0.871; the flat reads 1.084 with the screen ratio, 1.009 with
    /// the mean. Free.
    #[default]
    Mean,
}

impl TailRatio {
    /// The code `tail` in `ism_bounce.wgsl` reads (`BounceParams::area[1]`).
    pub fn shader_code(self) -> f32 {
        match self {
            Self::Power => 0.0,
            Self::Screen => 1.0,
            Self::Mean => 2.0,
        }
    }
}

/// How the multi-bounce pass picks the point that becomes a VPL of the next bounce (the new VPL
/// carries the source VPL's whole reflected power either way).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BouncePick {
    /// The thesis's: the brightest lit point. Its power is unbiased but its place is not: the
    /// brightest point is nearly always the one nearest the source, so bounced light stays
    /// near where it landed (the suite's unlit room, two doorways from the spot, got none).
    Brightest,
    /// A lit point picked with probability proportional to its reflected luminance: the power
    /// and where it lands are both unbiased; the places change every frame (the temporal
    /// filter averages them).
    Proportional,
    /// The whole next set drawn at once from every lit point of every source VPL, N draws
    /// evenly spaced on their cumulative luminance (systematic resampling): as unbiased as the
    /// proportional pick, every VPL of a set carries the same luminance, and how many land in a
    /// region (a room lit only through a doorway) varies by at most one instead of one coin flip
    /// per chain. Cost: two passes per bounce (a one-workgroup scan, one workgroup per VPL).
    /// With `view_importance` 8, the default: the suite's three rooms seen from the unlit room,
    /// each frame's energy without the temporal filter (lavapipe, 128x72, 20 frames) has a
    /// relative spread of 16% around 1.006 of the reference, against 38% around 0.986 for
    /// `Proportional` without importance.
    #[default]
    Resampled,
}

impl Default for IsmSettings {
    fn default() -> Self {
        Self {
            vpl_count: 256,
            ism_resolution: 128,
            total_points: 256 * 1024,
            points_per_ism: 1024,
            interleave: 4,
            base_confidence: 0.9,
            still_frames: 32,
            w_position: 20.0,
            w_normal: 10.0,
            w_illumination: 0.5,
            bounces: 6,
            filter_depth: 0.01,
            filter_normal: 0.8,
            sh_filter: false,
            shade_resolution: ShadeResolution::Auto,
            bounce_tail: true,
            bounce_pick: BouncePick::Resampled,
            view_importance: 8.0,
            first_set_seen_weight: 1.0,
            tail_ratio: TailRatio::Mean,
            splat_radius: 1.35,
            clamp_distance: 0.0,
            clamp_disk: 0.25,
            bias_constant: 0.05,
            bias_slope: 0.0,
        }
    }
}

impl IsmSettings {
    /// The temporal blend's confidence cap: `base_confidence`, or 1 - 1 / `still_frames` when
    /// the view has stood still and that is higher.
    pub fn confidence_cap(&self, still: bool) -> f32 {
        let c = self.base_confidence;
        if still && self.still_frames > 0 { c.max(1.0 - 1.0 / self.still_frames as f32) } else { c }
    }

    /// Checks ranges (absurd values are errors, never silently clamped).
    pub fn validate(&self) -> Result<(), SettingsError> {
        let m = self;
        let weights = [
            m.w_position,
            m.w_normal,
            m.w_illumination,
            m.filter_depth,
            m.bias_constant,
            m.bias_slope,
            m.clamp_disk,
            m.splat_radius,
        ];
        let checks: [(&'static str, bool, String, &'static str); 14] = [
            ("ism.vpl_count", (4..=1024).contains(&m.vpl_count), m.vpl_count.to_string(), "4..=1024"),
            (
                "ism.ism_resolution",
                (64..=256).contains(&m.ism_resolution) && m.ism_resolution.is_power_of_two(),
                m.ism_resolution.to_string(),
                "64, 128 or 256",
            ),
            (
                "ism.total_points",
                (1024..=1 << 22).contains(&m.total_points),
                m.total_points.to_string(),
                "1024..=4194304",
            ),
            ("ism.points_per_ism", (64..=8192).contains(&m.points_per_ism), m.points_per_ism.to_string(), "64..=8192"),
            (
                "ism VPLs x points per ISM (one thread each, 64 per workgroup)",
                u64::from(m.vpl_count) * u64::from(m.points_per_ism) <= 65_535 * 64,
                format!("{} x {}", m.vpl_count, m.points_per_ism),
                "<= 4194240",
            ),
            ("ism.interleave", (1..=8).contains(&m.interleave), m.interleave.to_string(), "1..=8"),
            ("ism.base_confidence", (0.0..=1.0).contains(&m.base_confidence), m.base_confidence.to_string(), "0..=1"),
            ("ism.still_frames", m.still_frames <= 1024, m.still_frames.to_string(), "0..=1024"),
            ("ism.bounces", (1..=6).contains(&m.bounces), m.bounces.to_string(), "1..=6"),
            ("ism.filter_normal", (-1.0..=1.0).contains(&m.filter_normal), m.filter_normal.to_string(), "-1..=1"),
            ("ism.view_importance", (0.0..=64.0).contains(&m.view_importance), m.view_importance.to_string(), "0..=64"),
            (
                "ism.first_set_seen_weight",
                (0.0..=64.0).contains(&m.first_set_seen_weight),
                m.first_set_seen_weight.to_string(),
                "0..=64",
            ),
            (
                "ism.clamp_distance",
                m.clamp_distance.is_finite() && m.clamp_distance >= 0.0,
                m.clamp_distance.to_string(),
                ">= 0",
            ),
            (
                "ism weights and biases",
                weights.iter().all(|w| w.is_finite() && *w >= 0.0),
                weights.map(|w| w.to_string()).join(" "),
                ">= 0",
            ),
        ];
        if let Some((name, _, value, range)) = checks.into_iter().find(|c| !c.1) {
            return Err(SettingsError { name, value, range });
        }
        // The ISM atlas holds one tile per VPL of every bounce; keep its side within 5792 texels
        // (a 5792^2 u32 atlas is just under 128 MiB, WebGPU's default storage-binding limit),
        // which fits 256 VPLs x 6 bounces at 128^2.
        let tiles = f64::from(m.vpl_count * m.bounces).sqrt().ceil() as u32;
        if m.ism_resolution * tiles > MAX_ATLAS_SIDE {
            return Err(SettingsError {
                name: "ism atlas (ism_resolution x sqrt(vpl_count x bounces))",
                value: format!("{} x {tiles} = {}", m.ism_resolution, m.ism_resolution * tiles),
                range: "<= 5792 texels",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::ShadeResolution;

    #[test]
    fn auto_gathers_at_half_resolution_from_640_by_360_and_the_sh_filter_always_at_full() {
        let auto = ShadeResolution::Auto;
        assert_eq!(auto.scale((639, 360), false), 1);
        assert_eq!(auto.scale((640, 360), false), 2);
        assert_eq!(auto.scale((3840, 2160), false), 2);
        assert_eq!(auto.scale((3840, 2160), true), 1);
        assert_eq!(ShadeResolution::Half.scale((64, 36), false), 2);
        assert_eq!(ShadeResolution::Half.scale((64, 36), true), 1);
        assert_eq!(ShadeResolution::Full.scale((3840, 2160), false), 1);
    }
}
