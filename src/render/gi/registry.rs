//! Which technique serves which mode, created on first use, and the one active at a time: a
//! switch releases the previous technique's GPU memory (its pipelines stay, so switching back
//! costs no shader compilation) and tells the new one [`ResetReason::ModeEntered`].
//!
//! Adding a technique adds one row to [`TECHNIQUES`]; nothing else here changes.

use super::direct::DirectTechnique;
use super::ism::technique::IsmTechnique;
use super::mrt::technique::MrtTechnique;
use super::rcs::technique::RcsTechnique;
use super::reference::ReferenceTechnique;
use super::sshgi::technique::SshgiTechnique;
use super::technique::{BufferInfo, GiTechnique, ResetReason, SupportQuery};
use crate::render::RenderError;
use crate::render::layouts::Layouts;
use crate::settings::GiMode;

/// Creates a technique's pipelines on a device.
pub type Create = fn(&wgpu::Device, &Layouts) -> Result<Box<dyn GiTechnique>, RenderError>;

/// One technique: the modes it serves, its support check, its inspector buffers and how to
/// create it.
pub struct TechniqueEntry {
    /// The modes this technique renders (one instance serves them all).
    pub modes: &'static [GiMode],
    /// Whether it can run with these limits, settings and size (a sentence a user can act on).
    pub support: fn(&SupportQuery<'_>) -> Result<(), String>,
    /// The buffers it adds to the inspector.
    pub buffers: &'static [BufferInfo],
    /// Creates it (pipelines only; memory comes with its first frame).
    pub create: Create,
}

/// Every technique this build has.
pub const TECHNIQUES: &[TechniqueEntry] = &[
    TechniqueEntry {
        modes: &[GiMode::Direct],
        support: DirectTechnique::support,
        buffers: &[],
        create: |_, _| Ok(Box::new(DirectTechnique::default())),
    },
    TechniqueEntry {
        modes: &[GiMode::Ism, GiMode::IsmRitschel],
        support: IsmTechnique::support,
        buffers: super::ism::technique::BUFFERS,
        create: |device, layouts| Ok(Box::new(IsmTechnique::new(device, layouts)?)),
    },
    TechniqueEntry {
        modes: &[GiMode::Mrt],
        support: MrtTechnique::support,
        buffers: super::mrt::technique::BUFFERS,
        create: |device, layouts| Ok(Box::new(MrtTechnique::new(device, layouts)?)),
    },
    TechniqueEntry {
        modes: &[GiMode::Sshgi],
        support: SshgiTechnique::support,
        buffers: super::sshgi::technique::BUFFERS,
        create: |device, layouts| Ok(Box::new(SshgiTechnique::new(device, layouts)?)),
    },
    TechniqueEntry {
        modes: &[GiMode::Rcs],
        support: RcsTechnique::support,
        buffers: super::rcs::inspect::BUFFERS,
        create: |device, layouts| Ok(Box::new(RcsTechnique::new(device, layouts)?)),
    },
    TechniqueEntry {
        modes: &[GiMode::Reference],
        support: ReferenceTechnique::support,
        buffers: &[],
        create: |_, _| Ok(Box::new(ReferenceTechnique::default())),
    },
];

/// The entry index serving `mode`.
pub fn entry_index(mode: GiMode) -> Option<usize> {
    TECHNIQUES.iter().position(|e| e.modes.contains(&mode))
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
            .filter_map(|(e, s)| Some((*e.modes.first()?, s.as_ref().map_or(0, |t| t.gpu_bytes()))))
            .collect()
    }
}
