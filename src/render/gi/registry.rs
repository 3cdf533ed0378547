//! The technique table: one row per technique is its whole description to the rest of the
//! program (its modes and their tips, support check, inspector buffers, parameter blocks,
//! shaders, whether volumetric obscurance applies, and how many frames a final image takes),
//! plus the live techniques with the one active at a time: a switch releases the previous
//! technique's GPU memory (its pipelines stay, so switching back costs no shader compilation)
//! and tells the new one [`ResetReason::ModeEntered`].
//!
//! Adding a technique adds its folders (`src/render/gi/<name>/`, `shaders/render/gi/<name>/`),
//! one row of [`TECHNIQUES`], a `GiMode` variant with its settings file, and its GI-panel file
//! (`src/app/gi_<name>.rs`, one row of the editor's panel table). The GI panel, `render`,
//! `bench --quality`, the shader tests and the obscurance pass loop over the rows; a test checks
//! that every row is complete (docs/ARCHITECTURE.md, "Adding a technique").

use super::direct::DirectTechnique;
use super::ism::technique::IsmTechnique;
use super::mrt::technique::MrtTechnique;
use super::rcs::technique::RcsTechnique;
use super::reference::ReferenceTechnique;
use super::sshgi::technique::SshgiTechnique;
use super::technique::{BufferInfo, GiTechnique, ResetReason, SupportQuery};
use crate::render::RenderError;
use crate::render::layouts::Layouts;
use crate::settings::{GiMode, VoSettings};

/// Creates a technique's pipelines on a device.
pub type Create = fn(&wgpu::Device, &Layouts) -> Result<Box<dyn GiTechnique>, RenderError>;

/// A shader parameter block: the WGSL file, the struct's name, and its Rust mirror's size
/// (checked against naga's layout by the shader tests).
pub type ParamBlock = (&'static str, &'static str, usize);

/// One mode a technique renders.
#[derive(Clone, Copy, Debug)]
pub struct ModeRow {
    /// The mode.
    pub mode: GiMode,
    /// What it is, in a sentence for the GI panel's tooltip.
    pub tip: &'static str,
    /// Whether its image builds up over frames (temporal reuse, feedback, progressive samples):
    /// a final image is then the last of several frames.
    pub temporal: bool,
}

/// Whether volumetric obscurance (Loos 2015) darkens a technique's indirect term.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Obscurance {
    /// Never (no indirect term, or one that already has its own visibility).
    Never,
    /// When `VoSettings::mrt` is on (MRT's blocks have no small-scale occlusion).
    MrtSwitch,
    /// When `VoSettings::other_modes` is on.
    OtherSwitch,
}

/// One technique: the modes it serves, its support check, its inspector buffers, its shaders
/// and parameter blocks, how obscurance and final images treat it, and how to create it.
pub struct TechniqueEntry {
    /// Its name and source, as the documentation cites it.
    pub name: &'static str,
    /// The modes this technique renders (one instance serves them all).
    pub modes: &'static [ModeRow],
    /// Whether it can run with these limits, settings and size (a sentence a user can act on).
    pub support: fn(&SupportQuery<'_>) -> Result<(), String>,
    /// The buffers it adds to the inspector.
    pub buffers: &'static [BufferInfo],
    /// Its entry shaders (paths under `shaders/`; imported files are not listed).
    pub shaders: &'static [&'static str],
    /// Its parameter blocks.
    pub param_blocks: &'static [ParamBlock],
    /// Whether obscurance applies to its indirect term.
    pub obscurance: Obscurance,
    /// Whether a final image (the CLI's `render`, `bench --quality`) must wait until the
    /// technique stops refining whatever frame count was asked: a cache that is still filling
    /// is a wrong image, not a noisy one.
    pub fill_before_final: bool,
    /// Creates it (pipelines only; memory comes with its first frame).
    pub create: Create,
}

/// Every technique this build has.
pub const TECHNIQUES: &[TechniqueEntry] = &[
    TechniqueEntry {
        name: "direct light",
        modes: &[ModeRow {
            mode: GiMode::Direct,
            tip: "Shadowed punctual lights only: the baseline every technique adds to.",
            temporal: false,
        }],
        support: DirectTechnique::support,
        buffers: &[],
        shaders: &[],
        param_blocks: &[],
        obscurance: Obscurance::Never,
        fill_before_final: false,
        create: |_, _| Ok(Box::new(DirectTechnique::default())),
    },
    TechniqueEntry {
        name: "imperfect shadow maps (Ritschel 2008, Knecht 2009)",
        modes: &[
            ModeRow {
                mode: GiMode::Ism,
                tip: "Instant radiosity with imperfect shadow maps and temporal reuse (Knecht 2009).",
                temporal: true,
            },
            ModeRow {
                mode: GiMode::IsmRitschel,
                tip: "The same ISM pipeline without temporal reuse (Ritschel 2008): the baseline for flicker.",
                temporal: false,
            },
        ],
        support: IsmTechnique::support,
        buffers: super::ism::technique::BUFFERS,
        shaders: super::ism::SHADERS,
        param_blocks: super::ism::params::PARAM_BLOCKS,
        obscurance: Obscurance::OtherSwitch,
        fill_before_final: false,
        create: |device, layouts| Ok(Box::new(IsmTechnique::new(device, layouts)?)),
    },
    TechniqueEntry {
        name: "modular and delta radiance transfer (Loos 2011, 2012, 2015)",
        modes: &[ModeRow {
            mode: GiMode::Mrt,
            tip: "Modular and delta radiance transfer on proxy blocks (Loos 2015).",
            temporal: true,
        }],
        support: MrtTechnique::support,
        buffers: super::mrt::technique::BUFFERS,
        shaders: super::mrt::SHADERS,
        param_blocks: super::mrt::PARAM_BLOCKS,
        obscurance: Obscurance::MrtSwitch,
        fill_before_final: false,
        create: |device, layouts| Ok(Box::new(MrtTechnique::new(device, layouts)?)),
    },
    TechniqueEntry {
        name: "screen-space hierarchical GI (Soler et al. 2010)",
        modes: &[ModeRow {
            mode: GiMode::Sshgi,
            tip: "Screen-space hierarchical indirect light (Soler et al. 2010).",
            temporal: true,
        }],
        support: SshgiTechnique::support,
        buffers: super::sshgi::technique::BUFFERS,
        shaders: super::sshgi::SHADERS,
        param_blocks: super::sshgi::PARAM_BLOCKS,
        obscurance: Obscurance::OtherSwitch,
        fill_before_final: false,
        create: |device, layouts| Ok(Box::new(SshgiTechnique::new(device, layouts)?)),
    },
    TechniqueEntry {
        name: "radiance cache splatting (Gautron et al. 2005)",
        modes: &[ModeRow {
            mode: GiMode::Rcs,
            tip: "GPU irradiance caching by radiance cache splatting (Gautron et al.).",
            temporal: true,
        }],
        support: RcsTechnique::support,
        buffers: super::rcs::inspect::BUFFERS,
        shaders: super::rcs::SHADERS,
        param_blocks: super::rcs::PARAM_BLOCKS,
        obscurance: Obscurance::OtherSwitch,
        fill_before_final: true,
        create: |device, layouts| Ok(Box::new(RcsTechnique::new(device, layouts)?)),
    },
    TechniqueEntry {
        name: "reference path tracer (CPU)",
        modes: &[ModeRow {
            mode: GiMode::Reference,
            tip: "Progressive CPU path tracer: the ground truth (shown in the inspector's comparison).",
            temporal: true,
        }],
        support: ReferenceTechnique::support,
        buffers: &[],
        shaders: &[],
        param_blocks: &[],
        obscurance: Obscurance::Never,
        fill_before_final: false,
        create: |_, _| Ok(Box::new(ReferenceTechnique::default())),
    },
];

/// Every mode of every row, in table order (the GI panel's order).
pub fn modes() -> impl Iterator<Item = &'static ModeRow> {
    TECHNIQUES.iter().flat_map(|t| t.modes.iter())
}

/// The row serving `mode`.
pub fn entry(mode: GiMode) -> Option<&'static TechniqueEntry> {
    TECHNIQUES.iter().find(|e| e.modes.iter().any(|m| m.mode == mode))
}

/// The mode row of `mode`.
pub fn mode_row(mode: GiMode) -> Option<&'static ModeRow> {
    modes().find(|m| m.mode == mode)
}

/// Whether `settings` apply obscurance to `mode`'s indirect term.
pub fn obscurance_applies(mode: GiMode, settings: &VoSettings) -> bool {
    match entry(mode).map_or(Obscurance::Never, |e| e.obscurance) {
        Obscurance::Never => false,
        Obscurance::MrtSwitch => settings.mrt,
        Obscurance::OtherSwitch => settings.other_modes,
    }
}

/// The entry index serving `mode`.
pub fn entry_index(mode: GiMode) -> Option<usize> {
    TECHNIQUES.iter().position(|e| e.modes.iter().any(|m| m.mode == mode))
}

/// Whether `mode` can run: built into this build and supported here.
pub fn support(mode: GiMode, query: &SupportQuery<'_>) -> Result<(), String> {
    let entry = entry_index(mode).and_then(|i| TECHNIQUES.get(i));
    match entry {
        Some(e) => (e.support)(query),
        None => Err(format!("{} is not implemented yet in this build", mode.name())),
    }
}

/// The inspector buffers `mode` adds.
pub fn buffers(mode: GiMode) -> &'static [BufferInfo] {
    entry_index(mode).and_then(|i| TECHNIQUES.get(i)).map_or(&[], |e| e.buffers)
}

/// The live techniques and which one is active.
pub struct Registry {
    slots: Vec<Option<Box<dyn GiTechnique>>>,
    active: Option<GiMode>,
}

impl Default for Registry {
    fn default() -> Self {
        Self { slots: TECHNIQUES.iter().map(|_| None).collect(), active: None }
    }
}

impl Registry {
    /// Makes `mode` the active mode: creates its technique if needed, releases the previously
    /// active technique's memory when it is another one, and resets the new one with
    /// [`ResetReason::ModeEntered`] when the mode changed.
    pub fn activate(
        &mut self,
        mode: GiMode,
        device: &wgpu::Device,
        layouts: &Layouts,
    ) -> Result<&mut (dyn GiTechnique + 'static), RenderError> {
        let index = entry_index(mode).ok_or_else(|| RenderError::Unsupported {
            mode: mode.name(),
            reason: format!("{} is not implemented yet in this build", mode.name()),
        })?;
        let previous = self.active.and_then(entry_index);
        if let Some(p) = previous.filter(|p| *p != index)
            && let Some(Some(t)) = self.slots.get_mut(p)
        {
            t.release();
        }
        let entered = self.active != Some(mode);
        self.active = Some(mode);
        let slot = self.slots.get_mut(index).ok_or_else(|| RenderError::Unsupported {
            mode: mode.name(),
            reason: "technique table out of step".into(),
        })?;
        if slot.is_none() {
            *slot = Some((TECHNIQUES[index].create)(device, layouts)?);
        }
        let technique = slot.as_deref_mut().ok_or_else(|| RenderError::Unsupported {
            mode: mode.name(),
            reason: "technique could not be created".into(),
        })?;
        if entered {
            technique.reset(ResetReason::ModeEntered);
        }
        Ok(technique)
    }

    /// The active mode.
    pub fn active_mode(&self) -> Option<GiMode> {
        self.active
    }

    /// The active technique.
    pub fn active(&self) -> Option<&dyn GiTechnique> {
        self.get(self.active?)
    }

    /// The active technique, mutable.
    pub fn active_mut(&mut self) -> Option<&mut (dyn GiTechnique + 'static)> {
        let index = entry_index(self.active?)?;
        self.slots.get_mut(index)?.as_deref_mut()
    }

    /// The technique serving `mode`, if it was created.
    pub fn get(&self, mode: GiMode) -> Option<&dyn GiTechnique> {
        self.slots.get(entry_index(mode)?)?.as_deref()
    }

    /// GPU bytes held by every live technique, per mode group (the first mode of each entry).
    pub fn gpu_bytes(&self) -> Vec<(GiMode, u64)> {
        TECHNIQUES
            .iter()
            .zip(&self.slots)
            .filter_map(|(e, s)| Some((e.modes.first()?.mode, s.as_ref().map_or(0, |t| t.gpu_bytes()))))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::shaders::SHADERS;

    #[test]
    fn every_mode_has_exactly_one_row_and_every_row_is_complete() {
        for mode in GiMode::ALL {
            let rows = TECHNIQUES.iter().filter(|e| e.modes.iter().any(|m| m.mode == mode)).count();
            assert_eq!(rows, 1, "{} is served by {rows} rows", mode.name());
        }
        assert_eq!(modes().count(), GiMode::ALL.len(), "a mode listed twice");
        for e in TECHNIQUES {
            assert!(!e.name.is_empty() && !e.modes.is_empty(), "a row without a name or modes");
            for m in e.modes {
                assert!(
                    m.tip.ends_with('.') && m.tip.len() > 20,
                    "{}: a tip is a sentence: {:?}",
                    m.mode.name(),
                    m.tip
                );
            }
            // A GPU technique has shaders, and each of them and each parameter block's file is
            // embedded.
            let gpu = !matches!(e.modes[0].mode, GiMode::Direct | GiMode::Reference);
            assert_eq!(!e.shaders.is_empty(), gpu, "{}: shaders {:?}", e.name, e.shaders);
            for path in e.shaders.iter().chain(e.param_blocks.iter().map(|(p, _, _)| p)) {
                assert!(SHADERS.iter().any(|(p, _)| p == path), "{}: {path} is not embedded", e.name);
            }
            assert_eq!(e.param_blocks.is_empty(), !gpu, "{}: parameter blocks", e.name);
            for b in e.buffers {
                assert!(!b.name.is_empty() && !b.description.is_empty(), "{}: buffer {b:?}", e.name);
            }
        }
    }

    #[test]
    fn obscurance_follows_each_rows_switch() {
        let on = VoSettings { mrt: true, other_modes: false, ..VoSettings::default() };
        assert!(obscurance_applies(GiMode::Mrt, &on));
        assert!(!obscurance_applies(GiMode::Ism, &on));
        let other = VoSettings { mrt: false, other_modes: true, ..VoSettings::default() };
        assert!(!obscurance_applies(GiMode::Mrt, &other) && obscurance_applies(GiMode::Sshgi, &other));
        assert!(!obscurance_applies(GiMode::Direct, &other) && !obscurance_applies(GiMode::Reference, &other));
    }
}
