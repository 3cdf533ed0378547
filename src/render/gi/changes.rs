//! Turns edits into reset reasons: compares this frame's scene, settings, camera and size with
//! the previous frame's and says what changed, so techniques drop exactly the history an edit
//! invalidates (a moved light is not a camera cut). The scene's revision counter is the fast
//! path: an unchanged revision means no scene diff is needed.

use super::technique::ResetReason;
use crate::scene::{Camera, Light, Scene};
use crate::settings::RenderSettings;

/// A camera move larger than this fraction of the scene's radius in one frame is a cut.
const CUT_DISTANCE: f32 = 0.25;
/// A view rotation larger than this (degrees) in one frame is a cut.
const CUT_DEGREES: f32 = 30.0;

/// What the previous frame looked like.
#[derive(Default)]
pub struct ChangeDetector {
    revision: u64,
    resources_revision: u64,
    lights: Vec<Light>,
    /// The area lights: every material's emission and the environment.
    emitters_key: Vec<u32>,
    objects_key: Vec<u32>,
    camera: Option<Camera>,
    settings: Option<RenderSettings>,
    size: Option<(u32, u32)>,
}

/// Bit patterns of everything about objects and materials that changes light transport.
fn objects_key(scene: &Scene) -> Vec<u32> {
    let mut key = Vec::new();
    for o in scene.objects() {
        let t = &o.transform;
        let floats = t.translation.to_array().into_iter().chain(t.rotation.to_array()).chain(t.scale.to_array());
        key.extend(floats.chain([o.sampling_weight]).map(f32::to_bits));
        key.extend([o.material as u32, o.mesh as u32, u32::from(o.is_rendered()), o.role as u32]);
        // A generated box's size and open sides (a proxy block's reach MRT's level though no
        // mesh is drawn for it); other sources are their mesh, keyed above.
        if let crate::scene::MeshSource::Cuboid { size, openings } = &o.source {
            key.extend(size.to_array().map(f32::to_bits));
            key.push(openings.iter().enumerate().map(|(i, open)| u32::from(*open) << i).sum());
        }
    }
    for m in scene.materials() {
        let values = m.base_color.iter().chain(&m.specular).chain([&m.roughness, &m.normal_scale]);
        key.extend(values.map(|v| v.to_bits()));
        key.push(m.base_color_texture.map_or(u32::MAX, |t| t.image as u32));
        key.push(m.normal_texture.map_or(u32::MAX, |t| t.image as u32));
    }
    key
}

/// Settings with the fields that never invalidate a technique's history (the mode itself is
/// handled by mode changes, the view only changes the display) normalised away.
/// What the emissive materials and the sky are (an edit of either is a light edit).
pub(crate) fn emitters_key(scene: &Scene) -> Vec<u32> {
    let mut key = Vec::new();
    for m in scene.materials() {
        key.extend(m.emissive_color.iter().chain([&m.emissive_strength]).map(|v| v.to_bits()));
        key.push(m.emissive_texture.map_or(u32::MAX, |t| t.image as u32));
    }
    let env = scene.environment();
    key.extend([env.intensity, env.rotation_degrees].map(f32::to_bits));
    match &env.sky {
        crate::scene::Sky::None => key.push(0),
        crate::scene::Sky::Constant(c) => key.extend([1].into_iter().chain(c.map(f32::to_bits))),
        crate::scene::Sky::Image(path) => key.extend([2].into_iter().chain(path.bytes().map(u32::from))),
        // The analytic sky follows the sun.
        crate::scene::Sky::Preetham { turbidity } => {
            key.extend([3, turbidity.to_bits()].into_iter().chain(scene.sun_direction().to_array().map(f32::to_bits)))
        }
    }
    key
}

/// Watches a scene's area lights ([`emitters_key`]) for a technique that bakes them (`rcs`'s
/// records, `mrt`'s texels): the key is rebuilt only when the scene's revision moved, so an
/// unedited frame costs one comparison.
#[derive(Default)]
pub struct EmittersWatch {
    revision: u64,
    key: Option<Vec<u32>>,
}

impl EmittersWatch {
    /// Whether the sky or an emission changed since the last call (false on the first).
    pub fn changed(&mut self, scene: &Scene) -> bool {
        if self.key.is_some() && self.revision == scene.revision() {
            return false;
        }
        self.revision = scene.revision();
        let key = emitters_key(scene);
        let changed = self.key.as_ref().is_some_and(|k| *k != key);
        self.key = Some(key);
        changed
    }
}

fn history_settings(settings: &RenderSettings) -> RenderSettings {
    RenderSettings { mode: Default::default(), view: Default::default(), ..settings.clone() }
}

fn is_cut(a: &Camera, b: &Camera, scene_radius: f32) -> bool {
    let moved = (a.position - b.position).length() > CUT_DISTANCE * scene_radius.max(1e-3);
    let turned = a.forward().dot(b.forward()).clamp(-1.0, 1.0).acos() > CUT_DEGREES.to_radians();
    moved || turned || a.yfov.to_bits() != b.yfov.to_bits()
}

impl ChangeDetector {
    /// The reasons to reset since the last call (empty on the first call, and when nothing
    /// changed); each reason appears at most once, in a fixed order.
    pub fn detect(&mut self, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) -> Vec<ResetReason> {
        let first = self.camera.is_none();
        let mut out = Vec::new();
        if self.revision != scene.revision() || first {
            let emitters = emitters_key(scene);
            let lights_changed = self.lights.as_slice() != scene.lights() || emitters != self.emitters_key;
            let key = objects_key(scene);
            let scene_changed = key != self.objects_key || self.resources_revision != scene.resources_revision();
            let radius = scene.bounds().map_or(1.0, |b| b.radius());
            let cut = self.camera.as_ref().is_some_and(|c| is_cut(c, scene.camera(), radius));
            if !first {
                if scene_changed {
                    out.push(ResetReason::SceneEdited);
                }
                if lights_changed {
                    out.push(ResetReason::LightEdited);
                }
                if cut {
                    out.push(ResetReason::CameraCut);
                }
            }
            if lights_changed {
                self.lights = scene.lights().to_vec();
                self.emitters_key = emitters;
            }
            self.objects_key = key;
            self.revision = scene.revision();
            self.resources_revision = scene.resources_revision();
            self.camera = Some(*scene.camera());
        }
        let relevant = history_settings(settings);
        if self.settings.as_ref().is_some_and(|s| *s != relevant) {
            out.push(ResetReason::SettingsChanged);
        }
        self.settings = Some(relevant);
        if self.size.is_some_and(|s| s != size) {
            out.push(ResetReason::Resized);
        }
        self.size = Some(size);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project_file::{Project, default_project_path};
    use glam::Vec3;

    #[test]
    fn each_edit_gives_exactly_its_reason() {
        let mut p = Project::load(&default_project_path()).expect("default project");
        let settings = p.render.clone();
        let mut d = ChangeDetector::default();
        assert!(d.detect(&p.scene, &settings, (8, 8)).is_empty(), "first frame");
        assert!(d.detect(&p.scene, &settings, (8, 8)).is_empty(), "nothing changed");
        p.scene.desc_mut().lights[0].position.x += 0.1;
        assert_eq!(d.detect(&p.scene, &settings, (8, 8)), [ResetReason::LightEdited]);
        p.scene.desc_mut().objects[0].transform.translation.y += 0.1;
        assert_eq!(d.detect(&p.scene, &settings, (8, 8)), [ResetReason::SceneEdited]);
        p.scene.desc_mut().materials[0].base_color[1] *= 0.5;
        assert_eq!(d.detect(&p.scene, &settings, (8, 8)), [ResetReason::SceneEdited]);
        p.scene.desc_mut().materials[0].emissive_color = [1.0, 0.5, 0.0];
        assert_eq!(d.detect(&p.scene, &settings, (8, 8)), [ResetReason::LightEdited], "emission is light");
        p.scene.desc_mut().environment.sky = crate::scene::Sky::Constant([0.1; 3]);
        assert_eq!(d.detect(&p.scene, &settings, (8, 8)), [ResetReason::LightEdited], "the sky is light");
        // A small camera step is reprojected, not a cut.
        let mut cam = *p.scene.camera();
        cam.position += Vec3::X * 0.01;
        p.scene.set_camera(cam);
        assert!(d.detect(&p.scene, &settings, (8, 8)).is_empty(), "small camera step");
        cam.position += Vec3::X * 2.0;
        p.scene.set_camera(cam);
        assert_eq!(d.detect(&p.scene, &settings, (8, 8)), [ResetReason::CameraCut]);
        let mut s = settings.clone();
        s.ism.w_normal += 1.0;
        assert_eq!(d.detect(&p.scene, &s, (8, 8)), [ResetReason::SettingsChanged]);
        s.view.exposure_ev += 1.0;
        assert!(d.detect(&p.scene, &s, (8, 8)).is_empty(), "exposure is display only");
        assert_eq!(d.detect(&p.scene, &s, (9, 8)), [ResetReason::Resized]);
    }
}
