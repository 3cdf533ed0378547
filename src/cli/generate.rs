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

/// The default project text, given the Cornell box glTF at `gltf_path`, saved at `project_path`.
pub fn default_project_text(gltf_path: &Path, project_path: &Path) -> anyhow::Result<String> {
    let project = Project::from_gltf(gltf_path)?;
    Ok(project.to_ron(project_path)?)
}

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
