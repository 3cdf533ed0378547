//! Read-only views of [`IsmGather`]'s GPU state, for the buffer inspectors, the CPU oracles,
//! the tests and the memory report; kept apart from the passes that fill it.

use super::IsmGather;

impl IsmGather {
    /// VPL sets (bounces) of the current buffers (0 before the first frame).
    pub fn sets(&self) -> u32 {
        self.sized.as_ref().map_or(0, |s| s.key.bounces)
    }

    /// The VPLs of every bounce of the last frame (set b at `b * vpl_count`).
    pub fn all_vpls(&self) -> Option<&wgpu::Buffer> {
        self.sized.as_ref().map(|s| &s.all_vpls)
    }

    /// What the lookups read besides the atlas (`ism_lookup.wgsl`): per VPL of every set and
    /// slot the pool point, the pool's positions, normals and clip lines, and points per ISM.
    pub fn lookup_buffers(&self) -> Option<([&wgpu::Buffer; 4], u32)> {
        self.sized.as_ref().map(|s| ([&s.chosen_all, &s.points, &s.normals, &s.clips], s.key.per_ism))
    }

    /// The last set's chosen points with the areas they stand for (`ism_select.wgsl`).
    pub fn chosen(&self) -> Option<&wgpu::Buffer> {
        self.sized.as_ref().map(|s| &s.chosen)
    }

    /// The ISM atlas of the last frame, its coarse levels (`level_base`) and the finest
    /// level's side.
    pub fn atlas(&self) -> Option<(&wgpu::Buffer, &wgpu::Buffer, u32)> {
        self.sized.as_ref().map(|s| (&s.atlas, &s.coarse, s.key.r * Self::tiles_per_row(s.key.vpls * s.key.bounces)))
    }

    /// Bytes of GPU memory held.
    pub fn gpu_bytes(&self) -> u64 {
        let own = self.sized.as_ref().map_or(0, |s| {
            let buffers = [
                &s.points,
                &s.all_vpls,
                &s.normals,
                &s.albedo,
                &s.specular,
                &s.selection,
                &s.lit,
                &s.clusters,
                &s.clips,
                &s.chosen,
                &s.chosen_all,
            ];
            [&s.atlas, &s.coarse].into_iter().chain(buffers).chain(&s.splats).map(wgpu::Buffer::size).sum::<u64>()
        });
        own + self.screen.gpu_bytes()
    }

    /// The atlas as splatted, before hole filling, when [`Self::capture_splats`] was on for
    /// the last frame.
    pub fn splats(&self) -> Option<&wgpu::Buffer> {
        self.sized.as_ref().and_then(|s| s.splats.as_ref())
    }
}
