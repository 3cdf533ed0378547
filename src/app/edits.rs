//! Structural edits of a project (add, delete, duplicate lights and objects), each recorded as
//! one undo step. Property edits happen in place between `History::begin` and `commit`.
//! Pure (no egui), so the undo property test drives them directly.

use glam::Vec3;

use super::history::{History, Snapshot};
use crate::project_file::Project;
use crate::scene::{Light, LightKind, Material, MeshSource, Object, ObjectRole, Transform};

/// What is selected in the outliner and viewport.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Selection {
    /// Nothing.
    #[default]
    None,
    /// An object by index.
    Object(usize),
    /// A light by index.
    Light(usize),
}

/// Why an edit was refused.
#[derive(Debug, thiserror::Error)]
pub enum EditError {
    /// The index does not exist.
    #[error("nothing to edit at index {0}")]
    Missing(usize),
    /// The resulting scene is invalid.
    #[error(transparent)]
    Resolve(#[from] crate::import::ResolveError),
    /// A glTF to add could not be imported.
    #[error("{0}")]
    Import(String),
    /// Proxy blocks could not be fitted (the fitter's reason), or the scene has some already.
    #[error("fit proxy blocks: {0}")]
    Fit(String),
}

fn structural(
    project: &mut Project,
    history: &mut History,
    label: &str,
    f: impl FnOnce(&mut crate::scene::SceneDesc) -> Result<(), EditError>,
) -> Result<(), EditError> {
    let before = Snapshot::of(project);
    let mut desc = before.desc.clone();
    f(&mut desc)?;
    project.set_desc(desc)?;
    history.record(label, before, project);
    Ok(())
}

fn unique_name(base: &str, taken: impl Iterator<Item = String>) -> String {
    let taken: Vec<String> = taken.collect();
    (1..).map(|i| format!("{base} {i}")).find(|n| !taken.contains(n)).unwrap_or_else(|| base.to_owned())
}

/// Adds a light of `kind` at the scene's centre (under the ceiling for point and spot lights).
pub fn add_light(project: &mut Project, history: &mut History, kind: LightKind) -> Result<Selection, EditError> {
    let b = project.scene.bounds();
    let centre = b.map_or(Vec3::new(0.0, 1.0, 0.0), |b| {
        Vec3::new(b.center().x, b.max.y - 0.1 * (b.max.y - b.min.y), b.center().z)
    });
    let names = project.scene.lights().iter().map(|l| l.name.clone());
    let light = match kind {
        LightKind::Point => Light::point(&unique_name("Point light", names), centre, 1.0),
        LightKind::Spot { .. } => Light::spot(&unique_name("Spot light", names), centre, Vec3::NEG_Y, 4.0, 0.3, 0.6),
        LightKind::Directional => {
            Light::directional(&unique_name("Sun", names), Vec3::new(0.3, -1.0, -0.4).normalize(), 1.0)
        }
    };
    let index = project.scene.lights().len();
    structural(project, history, "Add light", |d| {
        d.lights.push(light);
        Ok(())
    })?;
    Ok(Selection::Light(index))
}

fn material_for(desc: &mut crate::scene::SceneDesc, name: &str, albedo: [f32; 3]) -> usize {
    if let Some(i) = desc.materials.iter().position(|m| m.name == name) {
        return i;
    }
    desc.materials.push(Material::diffuse(name, albedo));
    desc.materials.len() - 1
}

/// Adds a proxy block (an MRT box) or a clutter box at the scene's centre.
pub fn add_box(project: &mut Project, history: &mut History, role: ObjectRole) -> Result<Selection, EditError> {
    let centre = project.scene.bounds().map_or(Vec3::ZERO, |b| b.center());
    let (base, size, label) = match role {
        ObjectRole::ProxyBlock => {
            ("Proxy block", project.scene.bounds().map_or(Vec3::ONE, |b| b.max - b.min), "Add proxy block")
        }
        _ => ("Clutter", Vec3::splat(0.3), "Add clutter"),
    };
    let name = unique_name(base, project.scene.objects().iter().map(|o| o.name.clone()));
    let index = project.scene.objects().len();
    structural(project, history, label, |d| {
        let material = material_for(d, "clutter", [0.7, 0.7, 0.7]);
        d.objects.push(Object {
            name,
            source: MeshSource::Cuboid { size, openings: [false; 6] },
            mesh: 0,
            material,
            transform: Transform { translation: centre, ..Transform::default() },
            sampling_weight: 1.0,
            role,
            visible: true,
        });
        Ok(())
    })?;
    Ok(Selection::Object(index))
}

/// Fits MRT proxy blocks to the level's geometry and adds them as objects the artist can edit
/// (one undo step). Refused where the scene has proxy blocks already, so that fitting never
/// overwrites an artist's edits: delete them to fit again.
pub fn fit_proxy_blocks(project: &mut Project, history: &mut History) -> Result<Fitted, EditError> {
    let existing = project.scene.objects().iter().filter(|o| o.role == ObjectRole::ProxyBlock).count();
    if existing > 0 {
        return Err(EditError::Fit(format!(
            "the scene has {existing} proxy blocks already; delete them to fit again (fitting never replaces edited blocks)"
        )));
    }
    let bvh = crate::precompute::bvh::SceneBvh::build(&project.scene);
    let fitted =
        crate::precompute::mrt::proxy::fit_scene(&project.scene, &bvh).map_err(|e| EditError::Fit(e.to_string()))?;
    let count = fitted.objects.len();
    let first = project.scene.objects().len();
    structural(project, history, "Fit proxy blocks", |d| {
        d.objects.extend(fitted.objects.iter().cloned());
        Ok(())
    })?;
    let gaps = fitted.gaps.into_iter().map(|g| g.text).collect();
    Ok(Fitted { selection: Selection::Object(first), count, gaps })
}

/// What "Fit proxy blocks" did.
#[derive(Debug)]
pub struct Fitted {
    /// The first fitted block, selected.
    pub selection: Selection,
    /// Blocks added.
    pub count: usize,
    /// What they leave out, one sentence each (where, why, what to do).
    pub gaps: Vec<String>,
}

impl Fitted {
    /// The status line: the count, and every gap.
    pub fn status(&self) -> String {
        if self.gaps.is_empty() {
            format!("fitted {} proxy blocks, covering every enclosed space", self.count)
        } else {
            format!("fitted {} proxy blocks; the fit is partial: {}", self.count, self.gaps.join("; "))
        }
    }
}

/// Deletes the selected light or object.
pub fn delete(project: &mut Project, history: &mut History, selection: Selection) -> Result<Selection, EditError> {
    match selection {
        Selection::None => Ok(Selection::None),
        Selection::Light(i) => {
            structural(project, history, "Delete light", |d| {
                (i < d.lights.len()).then(|| d.lights.remove(i)).map(|_| ()).ok_or(EditError::Missing(i))
            })?;
            Ok(Selection::None)
        }
        Selection::Object(i) => {
            structural(project, history, "Delete object", |d| {
                (i < d.objects.len()).then(|| d.objects.remove(i)).map(|_| ()).ok_or(EditError::Missing(i))
            })?;
            Ok(Selection::None)
        }
    }
}

/// Duplicates the selected light or object (offset slightly so both are visible).
pub fn duplicate(project: &mut Project, history: &mut History, selection: Selection) -> Result<Selection, EditError> {
    match selection {
        Selection::None => Ok(Selection::None),
        Selection::Light(i) => {
            let mut light = project.scene.lights().get(i).cloned().ok_or(EditError::Missing(i))?;
            light.name = unique_name(&light.name, project.scene.lights().iter().map(|l| l.name.clone()));
            light.position += Vec3::new(0.1, 0.0, 0.1);
            let index = project.scene.lights().len();
            structural(project, history, "Duplicate light", |d| {
                d.lights.push(light);
                Ok(())
            })?;
            Ok(Selection::Light(index))
        }
        Selection::Object(i) => {
            let mut object = project.scene.objects().get(i).cloned().ok_or(EditError::Missing(i))?;
            object.name = unique_name(&object.name, project.scene.objects().iter().map(|o| o.name.clone()));
            object.transform.translation += Vec3::new(0.1, 0.0, 0.1);
            let index = project.scene.objects().len();
            structural(project, history, "Duplicate object", |d| {
                d.objects.push(object);
                Ok(())
            })?;
            Ok(Selection::Object(index))
        }
    }
}

/// Imports every mesh of a glTF file as clutter at the scene's centre (its materials and images
/// are appended; the asset joins the project's asset list).
pub fn add_clutter_asset(
    project: &mut Project,
    history: &mut History,
    path: &std::path::Path,
) -> Result<Selection, EditError> {
    let options = crate::import::ImportOptions { light_units: project.scene.desc().light_units };
    let asset = crate::import::import_gltf_with(path, options).map_err(|e| EditError::Import(e.to_string()))?;
    let asset_index = project.imported.len();
    let image_offset: usize = project.imported.iter().map(|a| a.images.len()).sum();
    let centre = project.scene.bounds().map_or(Vec3::ZERO, |b| b.center());
    let first = project.scene.objects().len();
    project.assets.push(path.to_owned());
    project.imported.push(asset.clone());
    let stem = path.file_stem().map_or("clutter".into(), |s| s.to_string_lossy().into_owned());
    let result = structural(project, history, "Add clutter from glTF", |d| {
        let material_offset = d.materials.len();
        for m in &asset.scene.materials {
            let mut m = m.clone();
            for t in [&mut m.base_color_texture, &mut m.normal_texture].into_iter().flatten() {
                t.image += image_offset;
            }
            d.materials.push(m);
        }
        for o in &asset.scene.objects {
            let mut o = o.clone();
            if let MeshSource::Asset { asset, .. } = &mut o.source {
                *asset = asset_index;
            }
            o.name = format!("{stem}/{}", o.name);
            o.material += material_offset;
            o.role = ObjectRole::Clutter;
            o.transform.translation += centre;
            d.objects.push(o);
        }
        Ok(())
    });
    if result.is_err() {
        project.assets.pop();
        project.imported.pop();
    }
    result?;
    Ok(if project.scene.objects().len() > first { Selection::Object(first) } else { Selection::None })
}
