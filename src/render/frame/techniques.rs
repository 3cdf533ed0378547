//! The renderer's side of the technique seam that the editor, the CLI and tests use: the
//! active technique, its status, limitations, overlays and GPU memory, and the inspected buffer.

use super::Renderer;
use crate::render::gi::{GiTechnique, Overlay, TechniqueStatus};
use crate::scene::Scene;
use crate::settings::{GiMode, RenderSettings};

impl Renderer {
    /// The active technique (after the first frame).
    pub fn technique(&self) -> Option<&dyn GiTechnique> {
        self.techniques.active()
    }

    /// The active technique, downcast to its concrete type (tests and tools).
    pub fn technique_as<T: 'static>(&self) -> Option<&T> {
        self.techniques.active()?.as_any().downcast_ref::<T>()
    }

    /// The active mode's status (history length, resets, progress).
    pub fn technique_status(&self) -> Option<TechniqueStatus> {
        self.techniques.active().map(GiTechnique::status)
    }

    /// What the technique for `settings.mode` ignores in `scene` (sentences for the GI panel
    /// and the CLI); empty before it was first used.
    pub fn limitations(&self, scene: &Scene, settings: &RenderSettings) -> Vec<String> {
        self.techniques.get(settings.mode).map_or_else(Vec::new, |t| t.limitations(scene, settings))
    }

    /// Why the technique for `settings.mode` could not do its work (see
    /// [`GiTechnique::shortfalls`]); empty before it was first used.
    /// A scene with a sky or emissive surfaces adds one for the modes that do not light with
    /// them yet ([`area_light_shortfall`]).
    pub fn shortfalls(&self, scene: &Scene, settings: &RenderSettings) -> Vec<String> {
        let mut out = self.techniques.get(settings.mode).map_or_else(Vec::new, |t| t.shortfalls(scene, settings));
        out.extend(area_light_shortfall(scene, settings));
        out
    }

    /// The active technique's viewport overlays (reads back from the GPU: call sparingly).
    pub fn overlays(&self) -> Vec<Overlay> {
        self.techniques.active().map_or_else(Vec::new, |t| t.overlays(&self.device, &self.queue))
    }

    /// GPU bytes held by each technique created so far (released ones hold none).
    pub fn technique_gpu_bytes(&self) -> Vec<(GiMode, u64)> {
        self.techniques.gpu_bytes()
    }

    /// Tells the renderer which buffer the inspector shows (techniques keep debug copies, and
    /// the depth/normal pyramid is built, only while shown).
    pub fn set_inspected(&mut self, name: Option<&str>) {
        self.inspected = name.map(str::to_owned);
    }

    /// The device this renderer draws with.
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The queue this renderer submits to.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }
}

/// The sentence saying that `mode` shows the sky and emissive surfaces to the camera but lights
/// nothing with them, or `None` where it does: `reference` (next-event estimation and MIS) and
/// `rcs` (the records' hemisphere renders see emissive surfaces and the sky, as they see every
/// other surface) and `mrt` (emission and the sky through holes in the blocks' faces enter the
/// texels' l_d) light with both; `sshgi` sends emission from the emitters on screen (its
/// senders take the direct term, which holds it) and the sky through the voxel columns, unless
/// its sky rays or its visibility are off; `ism` and `ism-ritschel` light with VPLs on the
/// emitters and the sky (`render::gi::ism::emitter_points`).
pub fn area_light_shortfall(scene: &Scene, settings: &RenderSettings) -> Option<String> {
    let mode = settings.mode;
    let emissive = match mode {
        GiMode::Reference | GiMode::Rcs | GiMode::Mrt | GiMode::Ism | GiMode::IsmRitschel => return None,
        GiMode::Sshgi if settings.sshgi.sky_rays > 0 && settings.sshgi.visibility => return None,
        GiMode::Sshgi => 0,
        _ => scene.materials().iter().filter(|m| m.emits()).count(),
    };
    let what = match (scene.has_sky(), emissive) {
        (false, 0) => return None,
        (true, 0) => "the sky".to_owned(),
        (false, n) => format!("{n} emissive material{}", if n == 1 { "" } else { "s" }),
        (true, n) => format!("the sky and {n} emissive material{}", if n == 1 { "" } else { "s" }),
    };
    Some(format!(
        "{}: the camera sees {what}, but this mode lights no surface with {} (`reference`, `rcs`, `mrt` and `ism` do)",
        mode.name(),
        if what.contains(" and ") || emissive > 1 { "them" } else { "it" }
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every mode that does not light with the sky or emission says so, naming what it leaves
    /// out: only `direct` does by default, and `sshgi` of the sky when its sky rays are off.
    #[test]
    fn each_mode_names_the_area_lights_it_leaves_out() {
        let mut scene = crate::precompute::test_scenes::scene_of_slabs(&[], Vec::new());
        let with = |mode| RenderSettings { mode, ..RenderSettings::default() };
        assert!(GiMode::ALL.iter().all(|m| area_light_shortfall(&scene, &with(*m)).is_none()), "no area lights");
        scene.desc_mut().materials[0].emissive_color = [1.0; 3];
        scene.desc_mut().environment.sky = crate::scene::Sky::Constant([0.5; 3]);
        for mode in GiMode::ALL {
            let said = area_light_shortfall(&scene, &with(mode));
            match mode {
                GiMode::Reference | GiMode::Rcs | GiMode::Mrt | GiMode::Ism | GiMode::IsmRitschel | GiMode::Sshgi => {
                    assert_eq!(said, None)
                }
                _ => {
                    assert!(said.as_deref().is_some_and(|s| s.contains("the sky and 1 emissive material")), "{said:?}")
                }
            }
        }
        // `sshgi` without its sky rays (or its voxels) leaves the sky out, and says so.
        let mut off = with(GiMode::Sshgi);
        off.sshgi.sky_rays = 0;
        let said = area_light_shortfall(&scene, &off);
        assert!(said.as_deref().is_some_and(|s| s.contains("sees the sky,")), "{said:?}");
    }
}
