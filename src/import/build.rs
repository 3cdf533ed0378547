//! Turns a parsed glTF document into an [`Asset`]: buffers, images, materials, primitives and
//! the default scene's node graph.

use std::path::Path;

use super::{Asset, ImportError, ImportOptions, SUPPORTED_REQUIRED_EXTENSIONS, extras, images, nodes, primitive, uri};
use crate::scene::{LightUnits, Material, TextureRef};
use crate::settings::RenderSettings;

pub(super) fn build(bytes: &[u8], base_dir: &Path, path: &Path, options: ImportOptions) -> Result<Asset, ImportError> {
    let parse = |e: gltf::Error| ImportError::Parse { path: path.to_owned(), message: e.to_string() };
    check_glb_header(bytes, path)?;
    let unvalidated = gltf::Gltf::from_slice_without_validation(bytes).map_err(parse)?;
    check_attribute_indices(unvalidated.document.as_json(), path)?;
    let gltf = gltf::Gltf {
        document: gltf::Document::from_json(unvalidated.document.into_json()).map_err(parse)?,
        blob: unvalidated.blob,
    };
    let doc = &gltf.document;
    for ext in doc.extensions_required() {
        if !SUPPORTED_REQUIRED_EXTENSIONS.contains(&ext) {
            return Err(ImportError::UnsupportedExtension {
                path: path.to_owned(),
                extension: ext.to_owned(),
                supported: SUPPORTED_REQUIRED_EXTENSIONS.join(", "),
            });
        }
    }
    let version = &doc.as_json().asset.version;
    if version.split('.').next() != Some("2") {
        return Err(ImportError::Parse {
            path: path.to_owned(),
            message: format!("glTF version {version} is not supported (Bounce Lab reads 2.x)"),
        });
    }
    let (recorded_units, render, environment) = root_extras(doc.as_json(), path)?;
    let light_units = recorded_units.unwrap_or(options.light_units);
    if recorded_units.is_some_and(|r| r != options.light_units) {
        log::debug!("{}: lights read as {light_units}, as the file records", path.display());
    }
    let buffers = load_buffers(doc, gltf.blob.as_deref(), base_dir, path)?;
    let images = images::load_images(doc, &buffers, base_dir, path)?;
    let materials = doc.materials().map(|m| material(&m, light_units, path)).collect::<Result<Vec<_>, _>>()?;
    let emissive = materials.iter().filter(|m| m.emits()).map(|m| m.name.clone()).collect();
    let primitives = primitive::load_primitives(doc, &buffers, path)?;
    let files = referenced_files(doc, base_dir);
    let mut asset = Asset {
        primitives,
        images,
        materials,
        emissive,
        files,
        light_units,
        recorded_units,
        render,
        ..Asset::default()
    };
    nodes::build_scene(doc, &mut asset, path)?;
    if let Some(mut env) = environment {
        if let crate::scene::Sky::Image(name) = &mut env.sky {
            *name = base_dir.join(&*name).to_string_lossy().into_owned();
        }
        asset.scene.environment = env;
    }
    Ok(asset)
}

/// What a file's root `extras` record: its light units, an export's render settings and sky.
type RootRecord = (Option<LightUnits>, Option<RenderSettings>, Option<crate::scene::Environment>);

/// Bounce Lab's root `extras` (`{"bouncelab": {"light_units": "radiometric", ...}}`, which its
/// own files carry): the light units the file records (a record naming no known units is an
/// error rather than a guess), an export's render settings and its environment.
fn root_extras(root: &gltf::json::Root, path: &Path) -> Result<RootRecord, ImportError> {
    let bad = |message: String| ImportError::Parse { path: path.to_owned(), message };
    let Some(record) = extras::read::<extras::RootExtras>(&root.extras).map_err(bad)? else {
        return Ok((None, None, None));
    };
    let units = match record.light_units {
        None => None,
        Some(name) => Some(LightUnits::parse(&name).ok_or_else(|| {
            bad(format!("extras.bouncelab.light_units is {name:?}; expected \"photometric\" or \"radiometric\""))
        })?),
    };
    if let Some(render) = &record.render {
        render.validate().map_err(|e| bad(format!("extras.bouncelab.render: {e}")))?;
    }
    if let Some(env) = &record.environment {
        env.validate().map_err(|e| bad(format!("extras.bouncelab.environment: {e}")))?;
    }
    Ok((units, record.render, record.environment))
}

/// The gltf crate subtracts the 12-byte header from a GLB's declared length unchecked (found by
/// fuzzing: a debug build panics, a release build wraps); a declared length outside 12..=the
/// file's size is an error here first.
fn check_glb_header(bytes: &[u8], path: &Path) -> Result<(), ImportError> {
    let (Some(b"glTF"), Some(length)) = (bytes.get(..4), bytes.get(8..12)) else { return Ok(()) };
    let declared = u32::from_le_bytes([length[0], length[1], length[2], length[3]]) as usize;
    if declared < 12 || declared > bytes.len() {
        return Err(ImportError::Parse {
            path: path.to_owned(),
            message: format!("the GLB header declares {declared} bytes, but the file has {}", bytes.len()),
        });
    }
    Ok(())
}

/// gltf-json's validation indexes `accessors` with a primitive's POSITION index unchecked (and
/// panics); checking every attribute first turns that into a plain error.
fn check_attribute_indices(root: &gltf::json::Root, path: &Path) -> Result<(), ImportError> {
    let count = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let indices = primitive.attributes.values().chain(primitive.indices.as_ref());
            if let Some(bad) = indices.map(|i| i.value()).find(|&i| i >= count) {
                return Err(ImportError::Parse {
                    path: path.to_owned(),
                    message: format!("mesh {m} primitive {p} refers to accessor {bad}, but there are {count}"),
                });
            }
        }
    }
    Ok(())
}

fn load_buffers(
    doc: &gltf::Document,
    blob: Option<&[u8]>,
    base_dir: &Path,
    path: &Path,
) -> Result<Vec<Vec<u8>>, ImportError> {
    doc.buffers()
        .map(|buffer| {
            let index = buffer.index();
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => {
                    blob.map(<[u8]>::to_vec).ok_or(ImportError::MissingBinaryChunk { path: path.to_owned(), index })?
                }
                gltf::buffer::Source::Uri(u) => uri::load(u, base_dir, crate::input_file::Kind::Buffer)
                    .map_err(|source| ImportError::Buffer { path: path.to_owned(), index, source })?,
            };
            if data.len() < buffer.length() {
                return Err(ImportError::BufferTooShort {
                    path: path.to_owned(),
                    index,
                    actual: data.len(),
                    declared: buffer.length(),
                });
            }
            Ok(data)
        })
        .collect()
}

/// The files the document's buffers and images name (outputs must never replace them).
fn referenced_files(doc: &gltf::Document, base_dir: &Path) -> Vec<std::path::PathBuf> {
    let buffers = doc.buffers().filter_map(|b| match b.source() {
        gltf::buffer::Source::Uri(u) => uri::file_path(u, base_dir),
        gltf::buffer::Source::Bin => None,
    });
    let images = doc.images().filter_map(|i| match i.source() {
        gltf::image::Source::Uri { uri: u, .. } => uri::file_path(u, base_dir),
        gltf::image::Source::View { .. } => None,
    });
    buffers.chain(images).collect()
}

fn material_name(m: &gltf::Material<'_>) -> String {
    m.name().map_or_else(|| format!("material {}", m.index().unwrap_or(0)), str::to_owned)
}

/// One glTF material. Emission: `emissiveFactor` is the colour, `KHR_materials_emissive_strength`
/// (1 without it) the strength, read in the file's light units (photometric: cd/m², divided by
/// 683 lm/W like the lights; radiometric: W/(sr m²)).
fn material(m: &gltf::Material<'_>, units: LightUnits, path: &Path) -> Result<Material, ImportError> {
    let pbr = m.pbr_metallic_roughness();
    let tex = |t: gltf::texture::Texture<'_>, tex_coord: u32| TextureRef { image: t.source().index(), tex_coord };
    let name = material_name(m);
    let own = extras::read::<extras::MaterialExtras>(m.extras()).map_err(|message| ImportError::Node {
        path: path.to_owned(),
        what: format!("material {name:?}"),
        message,
    })?;
    let specular = own.and_then(|o| o.specular).unwrap_or([0.0; 3]);
    Ok(Material {
        name,
        base_color: pbr.base_color_factor(),
        base_color_texture: pbr.base_color_texture().map(|i| tex(i.texture(), i.tex_coord())),
        normal_texture: m.normal_texture().map(|n| tex(n.texture(), n.tex_coord())),
        normal_scale: m.normal_texture().map_or(1.0, |n| n.scale()),
        specular,
        roughness: pbr.roughness_factor().clamp(0.02, 1.0),
        emissive_color: m.emissive_factor(),
        // A material that emits nothing keeps the model's unit strength (whatever the units), so
        // an export of it imports as the same material.
        emissive_strength: match (m.emissive_strength(), m.emissive_factor() == [0.0; 3]) {
            (None, true) => 1.0,
            (strength, _) => units.to_radiometric(strength.unwrap_or(1.0)),
        },
        emissive_texture: m.emissive_texture().map(|i| tex(i.texture(), i.tex_coord())),
    })
}
