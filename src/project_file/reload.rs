//! Reloading one of a project's glTF assets after it changed on disk (the artist exported the
//! level again): the file's geometry and materials come in, everything authored in Bounce Lab
//! stays. Objects from the file are matched by name (the node's name, `name#k` for a mesh of
//! several primitives); a matched object takes the file's mesh, transform and material and
//! keeps its role, sampling weight and visibility; an object the file no longer has is removed
//! and named; a new node comes in as static geometry. Lights, proxy blocks, clutter boxes and
//! objects of the other assets are untouched. Materials are matched by name: the file's values
//! replace a matched material's, new ones are appended. A file that does not import (caught
//! half-written) changes nothing: the error says why, and the caller tries again.

use std::collections::HashMap;

use crate::import::{self, Asset, ImportOptions};
use crate::scene::{Material, MeshSource, Object, SceneDesc};

use super::{Project, ProjectError};

/// What a reload kept, changed and could not match.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ReloadReport {
    /// The file's name.
    pub file: String,
    /// Objects matched by name (authored fields kept, geometry from the file).
    pub matched: usize,
    /// Nodes new in the file, added as static geometry.
    pub added: Vec<String>,
    /// Objects whose node the file no longer has, removed.
    pub missing: Vec<String>,
    /// Lights and objects not from this file (proxy blocks, clutter, other assets), kept as
    /// they were.
    pub kept: usize,
}

impl std::fmt::Display for ReloadReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "reloaded {}: {} objects matched, {} lights and objects kept", self.file, self.matched, self.kept)?;
        if !self.added.is_empty() {
            write!(f, "; new: {}", list(&self.added))?;
        }
        if !self.missing.is_empty() {
            write!(f, "; no longer in the file, removed: {}", list(&self.missing))?;
        }
        Ok(())
    }
}

fn list(names: &[String]) -> String {
    let mut out = names.iter().take(6).cloned().collect::<Vec<_>>().join(", ");
    if names.len() > 6 {
        out.push_str(&format!(" and {} more", names.len() - 6));
    }
    out
}

impl Project {
    /// The index of the asset `path` is, or a buffer or image of (compared canonically).
    pub fn asset_of_file(&self, path: &std::path::Path) -> Option<usize> {
        let canon = |p: &std::path::Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_owned());
        let target = canon(path);
        self.assets
            .iter()
            .zip(&self.imported)
            .position(|(a, imported)| canon(a) == target || imported.files.iter().any(|f| canon(f) == target))
    }

    /// Imports asset `index` again and merges it (module docs); on an error the project is
    /// unchanged.
    pub fn reload_asset(&mut self, index: usize) -> Result<ReloadReport, ProjectError> {
        let path = self.assets.get(index).cloned().ok_or_else(|| ProjectError::Io {
            path: std::path::PathBuf::from(format!("asset {index}")),
            source: std::io::Error::new(std::io::ErrorKind::NotFound, "the project has no such asset"),
        })?;
        let options = ImportOptions { light_units: self.scene.desc().light_units };
        let fresh = import::import_gltf_with(&path, options).map_err(|e| ProjectError::Import(Box::new(e)))?;
        let (desc, mut report) = merged(self, index, &fresh);
        report.file = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
        let mut imported = self.imported.clone();
        imported[index] = fresh;
        let scene = import::resolve(desc, &imported).map_err(|source| ProjectError::Resolve { path, source })?;
        self.imported = imported;
        self.scene = scene;
        Ok(report)
    }
}

/// The project's description with asset `index` replaced by `fresh`.
fn merged(project: &Project, index: usize, fresh: &Asset) -> (SceneDesc, ReloadReport) {
    let mut desc = project.scene.desc().clone();
    let images = image_shift(project, index, fresh);
    for m in &mut desc.materials {
        images.shift_later(m);
    }
    let materials = merge_materials(&mut desc.materials, fresh, images.offset);
    let mut report = ReloadReport::default();
    let mut from_file: HashMap<&str, &Object> = fresh.scene.objects.iter().map(|o| (o.name.as_str(), o)).collect();
    let mut objects = Vec::with_capacity(desc.objects.len());
    for mut o in std::mem::take(&mut desc.objects) {
        if !matches!(o.source, MeshSource::Asset { asset, .. } if asset == index) {
            report.kept += 1;
            objects.push(o);
            continue;
        }
        match from_file.remove(o.name.as_str()) {
            Some(f) => {
                o.source = with_asset(&f.source, index);
                o.transform = f.transform;
                o.material = materials.get(f.material).copied().unwrap_or(o.material);
                report.matched += 1;
                objects.push(o);
            }
            None => report.missing.push(o.name.clone()),
        }
    }
    for f in &fresh.scene.objects {
        if from_file.contains_key(f.name.as_str()) {
            let mut o = f.clone();
            o.source = with_asset(&f.source, index);
            o.material = materials.get(f.material).copied().unwrap_or(0);
            report.added.push(o.name.clone());
            objects.push(o);
        }
    }
    desc.objects = objects;
    report.kept += desc.lights.len();
    (desc, report)
}

/// A fresh object's mesh source, pointing at asset `index`.
fn with_asset(source: &MeshSource, index: usize) -> MeshSource {
    match source {
        MeshSource::Asset { mesh, primitive, baked, .. } => {
            MeshSource::Asset { asset: index, mesh: *mesh, primitive: *primitive, baked: *baked }
        }
        other => other.clone(),
    }
}

/// Where asset `index`'s images start in the project's concatenation, and how far the later
/// assets' images move when its image count changes.
struct ImageShift {
    offset: usize,
    old_end: usize,
    delta: isize,
}

impl ImageShift {
    fn shift_later(&self, m: &mut Material) {
        for t in [&mut m.base_color_texture, &mut m.normal_texture].into_iter().flatten() {
            if t.image >= self.old_end {
                t.image = t.image.saturating_add_signed(self.delta);
            }
        }
    }
}

fn image_shift(project: &Project, index: usize, fresh: &Asset) -> ImageShift {
    let offset: usize = project.imported[..index].iter().map(|a| a.images.len()).sum();
    let old = project.imported[index].images.len();
    ImageShift { offset, old_end: offset + old, delta: fresh.images.len() as isize - old as isize }
}

/// Merges the file's materials into the project's by name; returns, per file material, its
/// index in the project's list.
fn merge_materials(materials: &mut Vec<Material>, fresh: &Asset, image_offset: usize) -> Vec<usize> {
    fresh
        .scene
        .materials
        .iter()
        .map(|m| {
            let mut m = m.clone();
            for t in [&mut m.base_color_texture, &mut m.normal_texture].into_iter().flatten() {
                t.image += image_offset;
            }
            match materials.iter().position(|existing| existing.name == m.name) {
                Some(i) => {
                    materials[i] = m;
                    i
                }
                None => {
                    materials.push(m);
                    materials.len() - 1
                }
            }
        })
        .collect()
}
