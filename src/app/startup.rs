//! What the editor starts with: the requested project, or the default (or an empty) project and
//! the reason, so a file that does not open still gives a window.

use std::path::PathBuf;

use crate::project_file::{Project, default_project_path};
use crate::scene::{Camera, Resources, Scene, SceneDesc};

/// The project to start with: `path` if it opens, else the default project (or an empty one)
/// and the reason, which the editor shows in a dialog. Someone who starts the editor from a
/// desktop never sees stderr, so a bad file must not end in no window at all.
pub fn open_or_fallback(
    path: &std::path::Path,
    options: Option<crate::import::ImportOptions>,
) -> Result<Startup, crate::scene::SceneError> {
    let is_project = |p: &std::path::Path| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("ron"));
    match Project::open_with(path, options) {
        Ok(project) => Ok(Startup {
            project,
            path: is_project(path).then(|| path.to_owned()),
            opened: Some(path.to_owned()),
            error: None,
        }),
        Err(e) => {
            let why = format!("Could not open {}:\n{e}", path.display());
            log::error!("{why}");
            let default = default_project_path();
            let (project, instead) = match (default.as_path() != path).then(|| Project::open(&default)) {
                Some(Ok(p)) => (p, "The default project is open instead."),
                _ => (empty_project()?, "An empty project is open instead."),
            };
            Ok(Startup { project, path: None, opened: None, error: Some(format!("{why}\n\n{instead}")) })
        }
    }
}

/// What the editor starts with.
pub struct Startup {
    /// The project to show.
    pub project: Project,
    /// Its file, if it is a project file (saving a glTF asks for a new name).
    pub path: Option<PathBuf>,
    /// The file it came from (a project or glTF; its crash recovery is keyed by it).
    pub opened: Option<PathBuf>,
    /// Why the requested file is not what is open.
    pub error: Option<String>,
}

/// A project with nothing in it and the default camera.
pub(super) fn empty_project() -> Result<Project, crate::scene::SceneError> {
    let desc = SceneDesc { camera: Camera::default(), ..SceneDesc::default() };
    let scene = Scene::new(desc, Resources::default())?;
    Ok(Project { assets: Vec::new(), scene, render: Default::default(), imported: Vec::new() })
}
