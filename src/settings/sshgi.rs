//! Settings of `sshgi`, screen-space hierarchical indirect light (Soler, Hoel, Rochet and
//! Holzschuch 2010), and their ranges.
//! Defaults are the paper's (quarter start resolution, 4 levels, 64 samples per level).

use serde::{Deserialize, Serialize};

use super::SettingsError;

/// Settings of the `sshgi` technique.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SshgiSettings {
    /// Start resolution as a power-of-two reduction of the view (0 full, 1 half, 2 quarter: the
    /// paper's ¼ and ½). The gather of the start level dominates the cost: each step finer costs
    /// about 4x the start level's gather (the paper: 6.6 ms at ¼, 25.9 ms at ½ without
    /// visibility, GTX 260, 1280x720, 64 samples).
    pub start_level: u32,
    /// Texels the start level may hold at most (0: no cap): where `start_level`'s reduction of a
    /// large view leaves more, the start is halved again until it fits, so that most of the
    /// frame's cost stops growing with the view. Every pass but the voxelisation, the last
    /// up-sampling and the temporal filter works per start-level texel (the gathers, the
    /// panorama's gather and receive, the sky rays, the later bounces, the tail): on the H200 (commit e48fc51) sshgi read 50 / 82 / 289 ms at 720p /
    /// 1080p / 4K on the rooms, growing with the pixels. The default 57,600 is the paper's
    /// start level at 1280x720 (320x180, a quarter); 1920x1080 then starts at an eighth
    /// (240x135) and 3840x2160 at a sixteenth. Views up to 1280x720 (the quality matrix's
    /// 256x144 among them) start where they did. Measured cost and quality:
    /// `docs/BENCHMARKS.md`, "sshgi's start level capped".
    pub max_start_texels: u32,
    /// Levels gathered (1..=6, fewer where the view is too small): level k covers the ring
    /// r 2^(k-1)..r 2^k start-level texels around each pixel, so each level doubles the reach
    /// for about a quarter of the previous level's cost (the paper: a 5th level +1% time).
    pub levels: u32,
    /// Samples per texel and level, N (the paper's 64 and 256). Cost: every gather is linear in
    /// it; quality: less noise per frame.
    pub samples: u32,
    /// Outer ring radius r in texels of each level; 0 = automatic, the smallest r whose disc on
    /// the coarsest level spans the whole view (the paper's rule, which gives its r = 40 at
    /// 1280x720, ¼ start, 4 levels). Larger: the same samples spread over a larger area.
    pub radius: f32,
    /// Indirect bounces (1..=4). Each later bounce gathers albedo x the previous bounce's light
    /// from the same depth and normal levels, re-mipping only the illumination: one more gather
    /// and up-sampling chain each (linear cost; without visibility unless
    /// `visibility_all_bounces`). The paper shows one; the suite's Cornell box (`bouncelab probe
    /// --mode sshgi`, 256x144, mean of 8 frames) reads 0.754 / 0.846 / 0.887 / 0.905 of the path
    /// tracer's energy at 1 / 2 / 3 / 4 bounces (what is left: off-screen and hidden senders, and
    /// Eq. 4's bound, which loses 3% at 64 samples against 256: 0.933).
    pub bounces: u32,
    /// Add the bounces after the last as a geometric series of it, at the ratio of the last
    /// bounce's light on the start level to the previous bounce's (up to 0.75; past it, light
    /// still arriving on screen, the geometric mean of that and the sender list's power ratio,
    /// between 0.75 and 0.9, `sshgi_tail.wgsl`). Not in the paper (`ism`'s tail, at its screen
    /// ratio, and past the cap `ism`'s mean ratio: `bouncelab probe LEVEL --mode sshgi --frames
    /// 40 --average-from 16`, the turning corridor 0.675 -> 0.903 of the path tracer's energy,
    /// the held-out maisonette 0.522 -> 0.902, the suite's rooms 0.918 -> 0.963; free: the
    /// list's totals come with its prefix sums). The suite's cluttered room 0.795 -> 0.878 of
    /// the path tracer's energy, the hall 0.873 -> 0.927, the diorama 1.068 -> 1.110 (its later
    /// bounces leak without `visibility_all_bounces`; `bouncelab probe --mode sshgi`, 32
    /// frames). Cost: three small passes over the start level (a sum per tile, one workgroup for
    /// the ratio, an add).
    pub bounce_tail: bool,
    /// Indirect visibility by marching a solid voxelisation of the view (128 depth slices per
    /// pixel, AND-reduced per level). Off: light gathered from a surface passes through whatever
    /// lies between. Cost: the paper's frame went from 9.8 to 58 ms (1280x720, ¼ start, 64
    /// samples): each sample marches up to r columns, plus a fixed voxelisation pass.
    pub visibility: bool,
    /// March the voxels on every bounce instead of the first only (on since stop 77). The paper
    /// skips visibility after the first bounce to save cost (after Yu et al. 2009: later bounces
    /// are smooth enough that their leaks are hard to see). On levels joined by corridors the
    /// leaks are a large part of the later bounces: the development level of tall rooms joined
    /// by corridors reads 1.29 of the path tracer's indirect light of four bounces without it
    /// and 1.14 with it, its first bounce 1.08 either way (`bouncelab probe corridors_tall.gltf
    /// --mode sshgi --settings "(bounces: 4, bounce_tail: false)"` against a reference cut at
    /// five path vertices). Off, the development levels' corridors read 1.08 to 1.30 of the path
    /// tracer's energy, on, 0.95 to 1.14 (`docs/notes/sshgi.md`, stop 77; a level whose light
    /// arrives after many bounces, the turning corridor, 0.91 -> 0.82: the columns' coarseness
    /// now blocks later bounces too). Cost: each later bounce's gather marches as the first's:
    /// sshgi's passes 1.8-2.3x the time without it (lavapipe, 640x360, the rooms, the window
    /// room and the cluttered room; `docs/BENCHMARKS.md`). Off, each later bounce costs as much
    /// as without visibility.
    pub visibility_all_bounces: bool,
    /// How many levels finer than the start level the voxel columns are that the visibility
    /// march reads (0..=2, capped at the view's own): each column is the OR of the view's in its
    /// block, so coarse columns start their solid at the nearest surface in the block and
    /// falsely occlude segments leaving a surface at a grazing angle. The Cornell box's first
    /// bounce, against an exact screen-space gather with ray-cast visibility
    /// (`examples/sshgi_oracle.rs`, quarter start): 0 reads 0.980, 1 1.001, 2 1.013; its whole
    /// image's energy 0.899 / 0.905 / 0.910 of the path tracer's. Cost: each step finer doubles
    /// the march (lavapipe, 640x360, default settings, `sshgi_oracle cornell --time 640x360
    /// --settings "(visibility_detail: N)"`: sshgi 66 / 98 / 165 ms GPU).
    pub visibility_detail: u32,
    /// View-depth range [near, far] in metres that the 128 voxel slices cover; [0, 0] =
    /// automatic, the scene's bounds as seen along the view axis. Geometry beyond it casts no
    /// indirect shadow; a slice is (far - near) / 128 deep, and occluders thinner than a slice
    /// can vanish (entry and exit cancel).
    pub voxel_range: [f32; 2],
    /// Temporal blend a of the reprojected history (0: none). The paper's Eq. 6; its value is not
    /// given (the default 0.85 is a starting value for static diffuse scenes). Higher: less noise,
    /// more lag after changes (history is dropped at disocclusions and on resets). Free.
    pub temporal_weight: f32,
    /// Blend with the previous frame's raw gather (the paper's 2-tap Eq. 6) instead of the
    /// recursive history (an exponential average, the default: stronger noise reduction).
    pub temporal_two_tap: bool,
    /// Side in texels of each face of a cube G-buffer around the camera whose surfaces the view
    /// does not show send light too (0: off, the paper's screen alone; 8..=128). Not in the
    /// paper: it reaches light beside and behind the camera, not light hidden from the camera's
    /// position, and has no visibility. Cost: six more G-buffer and direct-light passes of
    /// F x F texels, and `panorama_samples` per start-level texel.
    pub panorama: u32,
    /// Panorama senders gathered per start-level texel and frame (1..=1024; the temporal filter
    /// averages them over frames). Cost: linear, as a screen level's samples, and more where the
    /// picks meet lit hidden senders, whose segments are marched. 32 since stop 71 (64 before):
    /// with half the picks by power (`sender_power_share`) 32 spread less from frame to frame
    /// than 64 uniform picks on every level measured, for about the uniform picks' cost
    /// (lavapipe, `probe SCENE --mode sshgi --frames 16 --timings`, sshgi's passes: the rooms
    /// 156 -> 169 ms, the window room 90 -> 76 ms).
    pub panorama_samples: u32,
    /// The share of the panorama's and hidden senders' picks drawn in proportion to their power
    /// (radiance x area) instead of uniformly over the list (0: uniform, the list's strata alone;
    /// 0..=0.9). Not in the paper. Where a few senders carry the light (a room lit through its
    /// doorways) uniform picks meet them in some frames and not in others; the uniform share
    /// that stays bounds a sample's weight (a dim sender near the receiver). 0 to 0.5
    /// (`bouncelab probe LEVEL --mode sshgi --frames 40 --trace`, frames 17-40): the suite's
    /// three rooms from the unlit one spread 6.4% -> 1.3% from frame to frame (worst frame 0.71
    /// -> 0.88 of the path tracer's energy, 56 frames), the held-out maisonette 21% -> 3.6%
    /// (mean 0.19 -> 0.47: uniform picks almost never met its lit senders), a 3 m corridor level
    /// 25% -> 4.6%; the suite's other scenes' energy moved at most 0.012. 0.9 spreads a little
    /// less (raw frames of the rooms: 4.3% at 0.5, 3.5% at 0.9, 18.5% at 0).
    /// Cost: per bounce, prefix sums over the list (a workgroup per 256 senders, then one over
    /// the blocks), a binary search per pick, and the marches of the lit hidden senders the
    /// picks now meet: at 64 samples sshgi's passes took 1.6x-2.4x the uniform picks' time on
    /// lavapipe, hence the default of 32 (`panorama_samples`).
    pub sender_power_share: f32,
    /// Rays per start-level texel and frame that look for the sky through the voxel columns
    /// (0: the sky lights nothing; 1..=64; the temporal filter averages them over frames). Not
    /// in the paper. A ray is open where it leaves the voxels' depth range or crosses a column
    /// in which the camera sees the sky, without meeting a solid voxel; one that leaves the
    /// screen elsewhere walks on through the world grid (`world_voxels`; without it such a ray
    /// counts as blocked: what lies there is unknown; the courtyard 0.979 -> 0.990 of the path
    /// tracer's energy). Cost: linear, one voxel march per ray, and a walk of the world grid
    /// for those that leave the view (sshgi sky 23 -> 33 ms on the courtyard on lavapipe);
    /// nothing without a sky.
    pub sky_rays: u32,
    /// Points of the scene's surfaces per frame that may send light where the camera's position
    /// does not see them (0: off; 64..=16384; needs the panorama, whose list they join): the back
    /// of a pillar, a box's far side, the floor behind it. Not in the paper. The points are drawn
    /// by area over every surface in eight stratified sets, one a frame; the hidden ones are lit
    /// by the view's lights and shadow maps and sent like the panorama's senders, their segments
    /// marched through the view's voxels and, where they leave the view, through the world grid
    /// (`world_voxels`; without it such a path counts as blocked). Cost: a pack of this
    /// many points, and the panorama's gathers and receives share their samples with them.
    pub hidden_senders: u32,
    /// Voxels along the scene's longest side of a world-space grid of the voxels its surfaces
    /// pass through (0: none; 32..=512, at least 2 cm each; at most 16 MB at 512), which answers visibility for the
    /// part of a hidden sender's segment that leaves the view (without it that segment counts
    /// as blocked), the panorama's and hidden senders' sky rays, and the screen's sky rays
    /// past the view. Not in the paper. Built on
    /// the CPU when the geometry changes (one bit a voxel: at most 2 MB at 256 for a cubic
    /// scene); each such segment walks the grid's bricks of 4^3 voxels and the voxels of those
    /// that hold a surface. The hall 0.850 -> 0.873 of the path tracer's energy, a 60 m hall's
    /// side room with the hall behind the camera 0.285 -> 0.547; lavapipe: sshgi's passes 70 ->
    /// 92 ms on the cluttered room (`probe --timings`). 512 since stop 63 (256 before): the rule
    /// of `world_grid_in_view` needs voxels finer than the view's columns in rooms of a few
    /// metres. Building it on the CPU: 27-274 ms on six suite, development and held-out levels
    /// at 512 (release build, two cores; 7-122 ms at 256), up to 3.7 MB.
    pub world_voxels: u32,
    /// A hidden sender's segment that stays in view is walked through the world grid instead of
    /// the view's voxel columns where the grid's voxel is smaller than a column's width at the
    /// segment's middle depth (a column spans 2 tan(half the horizontal field) x depth x view
    /// pixels per column / view width). Not in the paper. A corridor seen down its length
    /// spans few columns, each wide and deep at the far end, and they blocked light the
    /// world's walls let through. With the 512-voxel grid (`bouncelab probe`, 32 frames,
    /// energy over the path tracer's): corridors_3m 0.845 -> 0.903, corridors_tall 0.823 ->
    /// 0.850, corridor_turning 0.532 -> 0.636, pillars 0.791 -> 0.810, the suite's three rooms
    /// 0.845 -> 0.898; the held-out flat 0.790 -> 0.817. Cost: such segments walk the grid.
    /// A project saved before it existed reads it as off: such a project keeps its 256-voxel
    /// grid, with which the rule took the three rooms to 0.799.
    #[serde(default)]
    pub world_grid_in_view: bool,
}

impl Default for SshgiSettings {
    fn default() -> Self {
        Self {
            start_level: 2,
            max_start_texels: Self::PAPER_START_TEXELS,
            levels: 4,
            samples: 64,
            radius: 0.0,
            bounces: 4,
            bounce_tail: true,
            visibility: true,
            visibility_all_bounces: true,
            visibility_detail: 1,
            voxel_range: [0.0, 0.0],
            temporal_weight: 0.85,
            temporal_two_tap: false,
            panorama: 32,
            panorama_samples: 32,
            sender_power_share: 0.5,
            sky_rays: 16,
            hidden_senders: 2048,
            world_voxels: 512,
            world_grid_in_view: true,
        }
    }
}

impl SshgiSettings {
    /// The paper's start level at 1280x720: a quarter of the view, 320x180 texels.
    pub const PAPER_START_TEXELS: u32 = 320 * 180;

    /// The pyramid level the gathers start at for a view of `view` pixels whose pyramid holds
    /// `pyramid_levels` levels: `start_level`, halved further while the level holds more than
    /// `max_start_texels` texels, and never past the pyramid's coarsest level.
    pub fn start_level_for(&self, view: (u32, u32), pyramid_levels: u32) -> u32 {
        let last = pyramid_levels.saturating_sub(1);
        let texels = |l: u32| u64::from((view.0 >> l.min(31)).max(1)) * u64::from((view.1 >> l.min(31)).max(1));
        let mut start = self.start_level.min(last);
        while self.max_start_texels > 0 && start < last && texels(start) > u64::from(self.max_start_texels) {
            start += 1;
        }
        start
    }

    /// Settings from RON that names only the fields it changes (`bouncelab probe --settings`),
    /// every field left out at its current default. A project file's missing
    /// `world_grid_in_view` reads as off instead (a project saved before it existed keeps its
    /// image); here it would turn the rule off whenever other fields are named.
    pub fn from_overrides(text: &str) -> Result<Self, ron::error::SpannedError> {
        let mut settings: Self = ron::from_str(text)?;
        if !text.contains("world_grid_in_view") {
            settings.world_grid_in_view = Self::default().world_grid_in_view;
        }
        Ok(settings)
    }

    /// Checks ranges (absurd values are errors, never silently clamped).
    pub fn validate(&self) -> Result<(), SettingsError> {
        let checks: [(&'static str, bool, String, &'static str); 15] = [
            ("sshgi.start_level", self.start_level <= 2, self.start_level.to_string(), "0..=2"),
            (
                "sshgi.max_start_texels",
                self.max_start_texels == 0 || self.max_start_texels >= 1024,
                self.max_start_texels.to_string(),
                "0 (no cap) or at least 1024 texels",
            ),
            ("sshgi.levels", (1..=6).contains(&self.levels), self.levels.to_string(), "1..=6"),
            ("sshgi.samples", (1..=1024).contains(&self.samples), self.samples.to_string(), "1..=1024"),
            (
                "sshgi.radius",
                self.radius.is_finite() && (0.0..=512.0).contains(&self.radius),
                self.radius.to_string(),
                "0 (automatic) or up to 512 texels",
            ),
            ("sshgi.bounces", (1..=4).contains(&self.bounces), self.bounces.to_string(), "1..=4"),
            ("sshgi.visibility_detail", self.visibility_detail <= 2, self.visibility_detail.to_string(), "0..=2"),
            (
                "sshgi.voxel_range",
                self.voxel_range.iter().all(|v| v.is_finite() && *v >= 0.0)
                    && (self.voxel_range == [0.0, 0.0] || self.voxel_range[1] > self.voxel_range[0]),
                format!("{:?}", self.voxel_range),
                "[0, 0] (automatic) or 0 <= near < far",
            ),
            (
                "sshgi.panorama",
                self.panorama == 0 || (8..=128).contains(&self.panorama),
                self.panorama.to_string(),
                "0 (off) or 8..=128 texels",
            ),
            (
                "sshgi.panorama_samples",
                (1..=1024).contains(&self.panorama_samples),
                self.panorama_samples.to_string(),
                "1..=1024",
            ),
            (
                "sshgi.sender_power_share",
                (0.0..=0.9).contains(&self.sender_power_share),
                self.sender_power_share.to_string(),
                "0..=0.9",
            ),
            ("sshgi.sky_rays", self.sky_rays <= 64, self.sky_rays.to_string(), "0..=64"),
            (
                "sshgi.hidden_senders",
                self.hidden_senders == 0 || (64..=16384).contains(&self.hidden_senders),
                self.hidden_senders.to_string(),
                "0 (off) or 64..=16384",
            ),
            (
                "sshgi.world_voxels",
                self.world_voxels == 0 || (32..=512).contains(&self.world_voxels),
                self.world_voxels.to_string(),
                "0 (off) or 32..=512",
            ),
            (
                "sshgi.temporal_weight",
                (0.0..=0.99).contains(&self.temporal_weight),
                self.temporal_weight.to_string(),
                "0..=0.99",
            ),
        ];
        match checks.into_iter().find(|c| !c.1) {
            Some((name, _, value, range)) => Err(SettingsError { name, value, range }),
            None => Ok(()),
        }
    }

    /// The ring radius in texels for a start level of `start` texels (width, height) and
    /// `levels` levels: the setting, or the automatic one.
    pub fn ring_radius(&self, start: (u32, u32), levels: u32) -> f32 {
        if self.radius > 0.0 {
            return self.radius;
        }
        let coarsest = start.0.max(start.1) >> levels.saturating_sub(1).min(31);
        (coarsest.max(1)) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn automatic_radius_is_the_papers_forty_at_1280x720_quarter_four_levels() {
        let s = SshgiSettings::default();
        assert_eq!(s.ring_radius((320, 180), 4), 40.0);
        assert_eq!(SshgiSettings { radius: 12.0, ..s.clone() }.ring_radius((320, 180), 4), 12.0);
    }

    #[test]
    fn the_start_level_is_halved_until_it_holds_at_most_the_cap() {
        let s = SshgiSettings::default();
        // Enough pyramid levels for every view below (a 3840x2160 view has 12).
        assert_eq!(s.start_level_for((1280, 720), 12), 2, "the paper's 320x180 at 720p is within the cap");
        assert_eq!(s.start_level_for((1024, 640), 12), 2);
        assert_eq!(s.start_level_for((256, 144), 12), 2, "the quality matrix's view is unchanged");
        assert_eq!(s.start_level_for((1920, 1080), 12), 3, "1080p starts at 240x135");
        assert_eq!(s.start_level_for((2560, 1440), 12), 3, "1440p starts at 320x180");
        assert_eq!(s.start_level_for((3840, 2160), 12), 4, "4K starts at 240x135");
        let uncapped = SshgiSettings { max_start_texels: 0, ..s.clone() };
        assert_eq!(uncapped.start_level_for((3840, 2160), 12), 2, "0 is no cap");
        let full = SshgiSettings { start_level: 0, ..s.clone() };
        assert_eq!(full.start_level_for((320, 180), 12), 0, "a view within the cap starts where it is set");
        assert_eq!(full.start_level_for((1920, 1080), 12), 3);
        assert_eq!(s.start_level_for((3840, 2160), 3), 2, "never past the pyramid's coarsest level");
        assert_eq!(s.start_level_for((3840, 2160), 0), 0);
    }

    #[test]
    fn a_project_saved_before_the_grid_in_view_keeps_it_off_and_new_settings_have_it_on() {
        let old: SshgiSettings = ron::from_str("(world_voxels: 256, hidden_senders: 2048)").expect("old settings");
        assert!(!old.world_grid_in_view, "an old project's 256-voxel grid got the rule it reads worse with");
        assert_eq!(old.world_voxels, 256);
        let new = SshgiSettings::default();
        assert!(new.world_grid_in_view && new.world_voxels == 512, "the defaults: {new:?}");
        let saved: SshgiSettings = ron::from_str(&ron::to_string(&new).expect("save")).expect("load");
        assert_eq!(saved, new, "a saved project reads back its settings");
    }

    #[test]
    fn fields_left_out_of_overrides_keep_their_defaults() {
        let defaults = SshgiSettings::default();
        let probed = SshgiSettings::from_overrides("(bounces: 3)").expect("settings");
        assert_eq!(probed, SshgiSettings { bounces: 3, ..defaults.clone() });
        let off = SshgiSettings::from_overrides("(world_grid_in_view: false)").expect("settings");
        assert_eq!(off, SshgiSettings { world_grid_in_view: false, ..defaults });
    }

    #[test]
    fn out_of_range_values_are_named() {
        let bad = SshgiSettings { bounces: 0, ..Default::default() };
        assert_eq!(bad.validate().map_err(|e| e.name), Err("sshgi.bounces"));
        let bad = SshgiSettings { radius: f32::NAN, ..Default::default() };
        assert_eq!(bad.validate().map_err(|e| e.name), Err("sshgi.radius"));
        let bad = SshgiSettings { max_start_texels: 100, ..Default::default() };
        assert_eq!(bad.validate().map_err(|e| e.name), Err("sshgi.max_start_texels"));
        assert!(SshgiSettings { max_start_texels: 0, ..Default::default() }.validate().is_ok());
        assert!(SshgiSettings::default().validate().is_ok());
    }
}
