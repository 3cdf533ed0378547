//! Where a view's indirect light comes from, as a screen-space technique sees it: the path
//! tracer's indirect light split by the surface it left last before reaching the surface a
//! pixel shows (the sender), into senders on screen, off screen (outside the view's frustum)
//! and hidden (inside the frustum but behind a nearer surface, or facing away from the camera).
//! `sshgi` (Soler et al. 2010) gathers from the screen only, so the last two are light it can
//! never send: this is the measure of its known limitation, shown in the GI panel and printed
//! by `bouncelab unseen-light`.
//!
//! A path's whole indirect part goes to its first sender's class: light that reaches an
//! on-screen sender from off screen counts as on screen there, though `sshgi` misses it too
//! (its later bounces gather from the screen again). [`UnseenShare::screen`] counts only the
//! light whose every bounce left a surface on screen: the most any screen-space gather of as
//! many bounces can find.

use std::sync::atomic::{AtomicBool, Ordering};

use glam::Vec3;
use rayon::prelude::*;

use super::bvh::SceneBvh;
use super::pathtracer::{PathTracer, Vertex};
use super::rng::Pcg32;
use crate::scene::{Camera, Scene};
use crate::settings::ReferenceSettings;

/// Means over the view of the path tracer's radiance (mean of the RGB channels), split.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UnseenShare {
    /// The view's size (pixels).
    pub size: (u32, u32),
    /// Paths per pixel.
    pub spp: u32,
    /// Light the pixels' surfaces reflect of the lights directly.
    pub direct: f64,
    /// Indirect light whose sender is on screen.
    pub on_screen: f64,
    /// Indirect light whose sender lies outside the view's frustum.
    pub off_screen: f64,
    /// Indirect light whose sender lies inside the frustum but is not what the screen shows.
    pub hidden: f64,
    /// Indirect light every bounce of which left a surface on screen (part of `on_screen`).
    pub screen: f64,
    /// Light an off-screen first sender reflects of the lights directly (part of `off_screen`):
    /// what a panorama of the direct light around the camera can add.
    pub off_screen_direct: f64,
}

impl UnseenShare {
    /// All the indirect light.
    pub fn indirect(&self) -> f64 {
        self.on_screen + self.off_screen + self.hidden
    }

    /// `part`'s share of the indirect light (0 when there is none).
    pub fn share(&self, part: f64) -> f64 {
        let all = self.indirect();
        if all > 0.0 { part / all } else { 0.0 }
    }

    /// The share of the indirect light a screen-space gather cannot send.
    pub fn missing(&self) -> f64 {
        self.share(self.off_screen + self.hidden)
    }

    /// One line for the GI panel.
    pub fn describe(&self) -> String {
        if self.indirect() <= 0.0 {
            return "this view receives no indirect light".to_owned();
        }
        format!(
            "{:.0}% of this view's indirect light leaves surfaces the screen does not show ({:.0}% off screen, {:.0}% hidden); \
             {:.0}% bounces only off surfaces on screen, the most a screen-space gather can find \
             (path-traced at {}x{}, {} paths a pixel)",
            100.0 * self.missing(),
            100.0 * self.share(self.off_screen),
            100.0 * self.share(self.hidden),
            100.0 * self.share(self.screen),
            self.size.0,
            self.size.1,
            self.spp
        )
    }
}

/// Where a sender lies for the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sender {
    OnScreen,
    OffScreen,
    Hidden,
}

/// Traces `spp` paths through every pixel of `scene`'s view at `size` and splits their
/// indirect light by sender; `None` if `cancel` was set.
pub fn unseen_share(scene: &Scene, size: (u32, u32), spp: u32, cancel: &AtomicBool) -> Option<UnseenShare> {
    let settings = ReferenceSettings { spp, ..ReferenceSettings::default() };
    let seed = settings.seed;
    let tracer = PathTracer::new(scene, size, settings);
    let frustum = Frustum::of(tracer.camera(), size);
    let rows: Vec<[f64; 6]> = (0..size.1)
        .into_par_iter()
        .map(|y| {
            let mut sum = [0.0f64; 6];
            if cancel.load(Ordering::Relaxed) {
                return sum;
            }
            for x in 0..size.0 {
                let pixel = u64::from(y) * u64::from(size.0) + u64::from(x);
                for sample in 0..spp {
                    let mut rng = Pcg32::new(seed, pixel, u64::from(sample));
                    let dir = tracer.camera_ray(x as f32, y as f32, &mut rng);
                    let mut path = Path { sums: &mut sum, first: None, all_on_screen: true };
                    tracer.walk(tracer.camera().position, dir, &mut rng, |v| {
                        path.add(&v, || frustum.classify(tracer.bvh(), v.p, v.ng));
                    });
                }
            }
            sum
        })
        .collect();
    if cancel.load(Ordering::Relaxed) {
        return None;
    }
    let n = f64::from(size.0) * f64::from(size.1) * f64::from(spp.max(1));
    let total = rows.iter().fold([0.0f64; 6], |a, r| std::array::from_fn(|i| a[i] + r[i]));
    Some(UnseenShare {
        size,
        spp,
        direct: total[0] / n,
        on_screen: total[1] / n,
        off_screen: total[2] / n,
        hidden: total[3] / n,
        screen: total[4] / n,
        off_screen_direct: total[5] / n,
    })
}

/// One path's walk into the sums (direct, on screen, off screen, hidden, all on screen, off
/// screen's direct light).
struct Path<'a> {
    sums: &'a mut [f64; 6],
    /// The first sender's slot in the sums.
    first: Option<usize>,
    /// Every sender so far was on screen.
    all_on_screen: bool,
}

impl Path<'_> {
    /// Adds the light vertex `v` sends; `class` tells where it lies (asked once per sender).
    fn add(&mut self, v: &Vertex, class: impl FnOnce() -> Sender) {
        let light = f64::from(v.light.x + v.light.y + v.light.z) / 3.0;
        if v.depth == 0 {
            self.sums[0] += light;
            return;
        }
        let sender = class();
        self.all_on_screen &= sender == Sender::OnScreen;
        let first = *self.first.get_or_insert(match sender {
            Sender::OnScreen => 1,
            Sender::OffScreen => 2,
            Sender::Hidden => 3,
        });
        self.sums[first] += light;
        if self.all_on_screen {
            self.sums[4] += light;
        }
        if v.depth == 1 && first == 2 {
            self.sums[5] += light;
        }
    }
}

/// The view's frustum, with what [`Frustum::classify`] needs computed once per measure.
struct Frustum {
    position: Vec3,
    view_from_world: glam::Mat4,
    /// tan of half the vertical field of view, and that times the aspect.
    tan_y: f32,
    tan_x: f32,
    znear: f32,
}

impl Frustum {
    fn of(camera: &Camera, size: (u32, u32)) -> Self {
        let tan_y = (0.5 * camera.yfov).tan();
        let aspect = size.0 as f32 / size.1.max(1) as f32;
        let view_from_world = camera.view_from_world();
        Self { position: camera.position, view_from_world, tan_y, tan_x: tan_y * aspect, znear: camera.znear }
    }

    /// Whether the view shows the point `p` (geometric normal `ng`).
    fn classify(&self, bvh: &SceneBvh, p: Vec3, ng: Vec3) -> Sender {
        let local = self.view_from_world.transform_point3(p);
        let depth = -local.z;
        if depth <= self.znear || local.x.abs() > depth * self.tan_x || local.y.abs() > depth * self.tan_y {
            return Sender::OffScreen;
        }
        let to = p - self.position;
        let dist = to.length();
        if ng.dot(-to) <= 0.0 {
            return Sender::Hidden; // The camera sees its back: the screen shows another side.
        }
        let eps = 1e-3 * bvh.scale;
        if bvh.occluded(self.position, to / dist, dist - eps) { Sender::Hidden } else { Sender::OnScreen }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default project's Cornell box, seen through its open side or (close up) its floor.
    fn cornell(close_up_of_the_floor: bool) -> Scene {
        let path = crate::project_file::default_project_path();
        let mut scene = crate::project_file::Project::load(&path).expect("the default project").scene;
        if close_up_of_the_floor {
            scene.set_camera(Camera::look_at(Vec3::new(0.0, 1.2, 0.5), Vec3::new(0.0, 0.0, 0.3), 0.5));
        }
        scene
    }

    #[test]
    fn a_close_up_of_the_floor_moves_the_senders_off_screen() {
        let cancel = AtomicBool::new(false);
        let whole = unseen_share(&cornell(false), (16, 12), 4, &cancel).expect("not cancelled");
        let floor = unseen_share(&cornell(true), (16, 12), 4, &cancel).expect("not cancelled");
        assert!(whole.indirect() > 0.0 && floor.indirect() > 0.0, "{whole:?} {floor:?}");
        assert!(whole.missing() < 0.4, "the whole box in view: most senders on screen: {whole:?}");
        assert!(floor.share(floor.off_screen) > 0.6, "the floor alone: most senders off screen: {floor:?}");
        assert!(floor.direct > 0.0 && floor.screen <= floor.on_screen, "{floor:?}");
        assert!(whole.screen > 0.5 * whole.on_screen, "{whole:?}");
    }
}
