//! The units a file gives light intensities in. The scene model itself is radiometric (W/sr for
//! point and spot lights, W/m^2 for directional ones; docs/ARCHITECTURE.md, "Conventions"); the
//! glTF specification's KHR_lights_punctual is photometric (candela and lux), and the tools
//! artists export from write it so: Blender's exporter (its default "Standard" lighting mode)
//! writes a lamp of P watts as P / (4 pi) x 683 cd and a sun of E W/m^2 as E x 683 lx. This
//! module converts between the two at the 683 lm/W of the photopic peak, the factor those
//! exporters, Godot and Bevy use. Files that store the radiometric numbers themselves (older
//! Bounce Lab projects and the files it writes) say so, and are read as they say.

use serde::{Deserialize, Serialize};

use super::LightKind;

/// Lumens per watt: the luminous efficacy glTF exporters and engines convert with.
pub const LUMENS_PER_WATT: f32 = 683.0;

/// How a file's light intensities are to be read (and an export writes them).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum LightUnits {
    /// The glTF specification's: candela (point, spot) and lux (directional).
    #[default]
    Photometric,
    /// W/sr (point, spot) and W/m^2 (directional): the scene model's own units.
    Radiometric,
}

impl LightUnits {
    /// Both, photometric first.
    pub const ALL: [Self; 2] = [Self::Photometric, Self::Radiometric];

    /// What project files without a unit choice meant (every project written before the choice
    /// existed stored and imported radiometric numbers).
    pub fn legacy() -> Self {
        Self::Radiometric
    }

    /// The lower-case name the command line and glTF `extras` use.
    pub fn name(self) -> &'static str {
        match self {
            Self::Photometric => "photometric",
            Self::Radiometric => "radiometric",
        }
    }

    /// Parses [`Self::name`].
    pub fn parse(text: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|u| u.name() == text)
    }

    /// A value given in these units, in the scene model's radiometric units.
    pub fn to_radiometric(self, value: f32) -> f32 {
        match self {
            Self::Photometric => value / LUMENS_PER_WATT,
            Self::Radiometric => value,
        }
    }

    /// A radiometric value of the scene model in these units.
    pub fn from_radiometric(self, value: f32) -> f32 {
        match self {
            Self::Photometric => value * LUMENS_PER_WATT,
            Self::Radiometric => value,
        }
    }

    /// The unit symbol of a light of `kind` in these units.
    pub fn symbol(self, kind: &LightKind) -> &'static str {
        match (self, kind) {
            (Self::Photometric, LightKind::Directional) => "lx",
            (Self::Photometric, _) => "cd",
            (Self::Radiometric, LightKind::Directional) => "W/m²",
            (Self::Radiometric, _) => "W/sr",
        }
    }

    /// The unit symbol of radiance (emission, the sky) in these units.
    pub fn radiance_symbol(self) -> &'static str {
        match self {
            Self::Photometric => "cd/m²",
            Self::Radiometric => "W/(sr m²)",
        }
    }

    /// The other of the two.
    pub fn other(self) -> Self {
        match self {
            Self::Photometric => Self::Radiometric,
            Self::Radiometric => Self::Photometric,
        }
    }
}

impl std::fmt::Display for LightUnits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Blender's "Standard" export of a 1000 W lamp (1000 / (4 pi) x 683 cd) reads back as
    /// Blender's own 1000 / (4 pi) W/sr, and a 5 W/m^2 sun (3415 lx) as 5 W/m^2.
    #[test]
    fn blender_standard_exports_read_back_as_blenders_radiometric_values() {
        let lamp_cd = 1000.0 / (4.0 * std::f32::consts::PI) * 683.0;
        let lamp = LightUnits::Photometric.to_radiometric(lamp_cd);
        assert!((lamp - 1000.0 / (4.0 * std::f32::consts::PI)).abs() < 1e-4, "{lamp}");
        assert!((LightUnits::Photometric.to_radiometric(5.0 * 683.0) - 5.0).abs() < 1e-5);
        assert_eq!(LightUnits::Radiometric.to_radiometric(54_351.0), 54_351.0);
        for units in LightUnits::ALL {
            assert!((units.from_radiometric(units.to_radiometric(12.5)) - 12.5).abs() < 1e-4);
            assert_eq!(LightUnits::parse(units.name()), Some(units));
        }
        assert_eq!(LightUnits::parse("lumens"), None);
    }
}
