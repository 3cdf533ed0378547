//! Regenerates the shipped assets (`assets/cornell_box.gltf`, `projects/default.ron`, the
//! suite's levels under `assets/suite/`) from code,
//! so they are reproducible and a test can check they are current.

use std::path::Path;

use anyhow::Context as _;

use crate::import::cornell;
use crate::project_file::Project;

/// The Cornell box glTF text.
pub fn cornell_gltf_text() -> String {
    cornell::cornell_box().to_string_pretty()
}

/// The default project text, given the Cornell box glTF at `gltf_path`, saved at `project_path`:
/// the box with a proxy block of its room (open towards the camera, +Z), so that `mrt` has a
/// block to transfer light in (the fitter finds no closed room in an open-fronted box), opening
/// in `rcs`, which settles in seconds on a software adapter and shows the box's colour bleeding.
pub fn default_project_text(gltf_path: &Path, project_path: &Path) -> anyhow::Result<String> {
    let mut project = Project::from_gltf(gltf_path)?;
    let open_front = [false, false, false, false, true, false];
    let block = crate::precompute::mrt::proxy::block_object("cornell room", CORNELL_MIN, CORNELL_MAX, open_front);
    project.scene.desc_mut().objects.push(block);
    let desc = project.scene.desc().clone();
    project.set_desc(desc)?;
    project.render.mode = crate::settings::GiMode::Rcs;
    Ok(project.to_ron(project_path)?)
}

/// The Cornell box's room (`import::cornell`): 2 m wide, deep and high, its floor at y = 0.
const CORNELL_MIN: glam::Vec3 = glam::Vec3::new(-1.0, 0.0, -1.0);
const CORNELL_MAX: glam::Vec3 = glam::Vec3::new(1.0, 2.0, 1.0);

/// Writes both files under `root` (the repository root).
pub fn generate(root: &Path) -> anyhow::Result<()> {
    let gltf = root.join("assets/cornell_box.gltf");
    let project = root.join("projects/default.ron");
    std::fs::create_dir_all(root.join("assets"))?;
    std::fs::create_dir_all(root.join("projects"))?;
    crate::atomic_file::write(&gltf, cornell_gltf_text().as_bytes())
        .with_context(|| format!("writing {}", gltf.display()))?;
    let text = default_project_text(&gltf, &project)?;
    crate::atomic_file::write(&project, text.as_bytes()).with_context(|| format!("writing {}", project.display()))?;
    println!("wrote {} and {}", gltf.display(), project.display());
    let levels = crate::suite::write_levels(root)?;
    println!("wrote {} suite levels under {}", levels.len(), root.join("assets/suite").display());
    Ok(())
}
