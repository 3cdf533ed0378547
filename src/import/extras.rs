//! Bounce Lab's own data in a glTF file's `extras` (under the key `bouncelab`), which an export
//! writes ([`crate::export`]) and import reads back, so that export → import gives the same
//! project: per node an object's role, sampling weight, visibility and generated mesh (proxy
//! blocks with their openings), per light whether it casts shadows, per material the specular
//! reflectance glTF's core has no field for, and at the root the light units, the render
//! settings and the environment (glTF has no sky; an image sky's path is relative to the file). Other tools keep `extras` as they are and ignore them.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::scene::ObjectRole;
use crate::settings::RenderSettings;

/// The key Bounce Lab's data sits under in every `extras` object.
pub const KEY: &str = "bouncelab";

/// A mesh Bounce Lab generates rather than reads from a file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Generated {
    /// A box of this full size; a proxy block's open faces (+X, -X, +Y, -Y, +Z, -Z).
    Cuboid { size: [f32; 3], openings: [bool; 6] },
    /// A square facing +Y.
    Plane { size: f32 },
}

/// An object's data on its node.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeExtras {
    pub role: Option<ObjectRole>,
    pub sampling_weight: Option<f32>,
    pub visible: Option<bool>,
    /// The generated mesh the node's mesh (if any) was made from; a proxy block's node has no
    /// mesh, since other tools would draw the block as a solid box over the level.
    pub generated: Option<Generated>,
}

/// A light's data beyond KHR_lights_punctual.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightExtras {
    pub cast_shadows: Option<bool>,
}

/// A material's data beyond glTF's core.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialExtras {
    /// Specular reflectance of the Blinn-Phong lobe.
    pub specular: Option<[f32; 3]>,
}

/// The document's data: the units (`light_units`, read by the importer itself) and the render
/// settings of the project the file was exported from.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RootExtras {
    pub light_units: Option<String>,
    pub render: Option<RenderSettings>,
    /// The sky, radiometric like the scene model's (the units above are for the lights).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub environment: Option<crate::scene::Environment>,
}

/// Bounce Lab's part of an `extras` value: `None` without one, an error message when it does
/// not parse.
pub fn read<T: DeserializeOwned>(extras: &gltf::json::Extras) -> Result<Option<T>, String> {
    let Some(raw) = extras else { return Ok(None) };
    let value: serde_json::Value = serde_json::from_str(raw.get()).map_err(|e| e.to_string())?;
    let Some(own) = value.get(KEY) else { return Ok(None) };
    serde_json::from_value(own.clone()).map(Some).map_err(|e| format!("extras.{KEY}: {e}"))
}

/// `{"bouncelab": value}`.
pub fn wrap<T: Serialize>(value: &T) -> serde_json::Value {
    serde_json::json!({ KEY: value })
}
