//! The dispatches of one `sshgi` frame, built once per plan and set of inputs: per bounce the
//! illumination levels, a gather per level and the up-sampling that sums them, the panorama's
//! gather into the first bounce, the sky's light, the bounces' sum and the output to the view.

use super::{Inputs, Pipe, Plan, Sized, SshgiPasses, Step};
use crate::render::targets::Target;

/// The parameter slot of bounce `b`'s gather of level `k`: after the two mip slots and the
/// levels' up-sampling slots.
pub(super) fn gather_slot(plan: Plan, b: usize, k: usize) -> u32 {
    2 + plan.levels + (b * plan.levels as usize + k) as u32
}

/// The parameter slot of the panorama's gather and receive of bounce `b`: after every chain's
/// gathers.
pub(super) fn panorama_slot(plan: Plan, b: usize) -> u32 {
    gather_slot(plan, plan.bounces as usize + usize::from(plan.unshadowed), 0) + b as u32
}

/// The parameter slot of the sky pass: after the panorama's.
pub(super) fn sky_slot(plan: Plan) -> u32 {
    panorama_slot(plan, plan.bounces as usize)
}

/// What the stages of [`SshgiPasses::build_steps`] share: the layouts and parameter buffer, the
/// plan's targets, the frame's inputs and the dispatches built so far.
pub(super) struct StepBuilder<'a> {
    pub(super) passes: &'a SshgiPasses,
    pub(super) device: &'a wgpu::Device,
    pub(super) key: &'a Inputs,
    pub(super) s: &'a Sized,
    pub(super) steps: Vec<Step>,
}

impl<'a> StepBuilder<'a> {
    /// The parameter buffer's first `size` bytes (bound at each step's slot offset).
    fn params_binding(&self, size: u64) -> wgpu::BindingResource<'a> {
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &self.passes.params,
            offset: 0,
            size: wgpu::BufferSize::new(size),
        })
    }

    /// A bind group of the mip pipelines: sources `a` and `b` into `dest`.
    fn mip_group(&self, a: &wgpu::TextureView, b: &wgpu::TextureView, dest: &wgpu::TextureView) -> wgpu::BindGroup {
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi mip bind group"),
            layout: &self.passes.mip_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.params_binding(16) },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(a) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(b) },
                wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::TextureView(dest) },
            ],
        })
    }

    /// A bind group of the up-sampling pipeline: `coarse` joint-bilateral up-sampled along the
    /// two levels' geometry, plus `add`, into `dest`.
    fn up_group(
        &self,
        coarse: &wgpu::TextureView,
        coarse_geo: &wgpu::TextureView,
        fine_geo: &wgpu::TextureView,
        add: &wgpu::TextureView,
        dest: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi upsample bind group"),
            layout: &self.passes.up_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.params_binding(32) },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(coarse) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(coarse_geo) },
                wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::TextureView(fine_geo) },
                wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(add) },
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(dest) },
                wgpu::BindGroupEntry { binding: 6, resource: self.key.frame.as_entire_binding() },
            ],
        })
    }

    /// A bind group of the gather of level `k`: its geometry and illumination into `dest`.
    fn gather_group(&self, k: usize, dest: &Target) -> wgpu::BindGroup {
        let (s, key) = (self.s, self.key);
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi gather bind group"),
            layout: &self.passes.gather_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: key.frame.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: self.params_binding(80) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(self.geo(k)) },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&s.illumination[k].view),
                },
                wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(&dest.view) },
                // Every level marches the start level's columns (`sshgi_visibility.wgsl`).
                wgpu::BindGroupEntry { binding: 5, resource: key.voxels.as_entire_binding() },
            ],
        })
    }

    /// The geometry pyramid's level under sshgi's level `k`.
    fn geo(&self, k: usize) -> &'a wgpu::TextureView {
        &self.key.pyramid[self.s.plan.start as usize + k]
    }

    /// Appends a dispatch of a pass that spreads each item's samples over threads ([`split`]):
    /// `size` items, tiled as the pass shares them.
    fn shared_step(
        &mut self,
        pass: String,
        (pipeline, shared): (Pipe, Shared),
        group: wgpu::BindGroup,
        slot: u32,
        size: (u32, u32),
    ) {
        let tile = split(self.passes.shared, shared).1;
        self.steps.push(Step { pass, pipeline, group, slot, size, tile });
    }

    /// Appends a dispatch of `pipeline` writing `dest`.
    fn step(&mut self, pass: String, pipeline: Pipe, group: wgpu::BindGroup, slot: u32, dest: &Target) {
        let size = (dest.texture.width(), dest.texture.height());
        self.steps.push(Step { pass, pipeline, group, slot, size, tile: 8 });
    }

    /// The timed pass of chain `b`'s `phase`: the first bounce's phases are timed apart, the
    /// other chains as a whole.
    fn pass(&self, b: usize, phase: &str) -> String {
        if b == self.s.plan.bounces as usize {
            "sshgi unshadowed (inspector)".to_owned()
        } else if b == 0 {
            phase.to_owned()
        } else {
            format!("sshgi bounce {}", b + 1)
        }
    }

    /// One chain into its target: illumination levels, a gather per level, then up-sampling.
    /// A bounce goes to its screen bounce when the panorama joins it after.
    pub(super) fn chain(&mut self, b: usize) {
        let s = self.s;
        let (first, out) = match (b == s.plan.bounces as usize, &s.unshadowed, s.screen_bounce.get(b)) {
            (true, Some(u), _) => (true, u),
            (false, _, Some(screen)) => (b == 0, screen),
            _ => (b == 0, &s.bounce[b.min(s.bounce.len() - 1)]),
        };
        self.illumination(b, first);
        self.gathers(b, out);
        self.up_sampling(b, out);
    }

    /// The sky's E / pi through the voxel columns (`sshgi_sky.wgsl`), at the start level and,
    /// with the panorama, added to its senders' first radiance.
    pub(super) fn sky(&mut self) {
        let (s, key) = (self.s, self.key);
        let (Some([sky, _, _]), Some((sky_view, sky_buffer))) = (&s.sky, &key.sky) else { return };
        let texture =
            |binding, view| wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(view) };
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi sky bind group"),
            layout: &self.passes.sky_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: key.frame.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: self.params_binding(96) },
                texture(2, self.geo(0)),
                texture(3, &sky.view),
                wgpu::BindGroupEntry { binding: 4, resource: key.voxels.as_entire_binding() },
                texture(5, sky_view),
                wgpu::BindGroupEntry { binding: 6, resource: sky_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 9, resource: key.world.as_entire_binding() },
            ],
        });
        let size = (sky.texture.width(), sky.texture.height());
        self.shared_step("sshgi sky".to_owned(), (Pipe::Sky, Shared::Sky), group, sky_slot(s.plan), size);
        // The panorama's senders off screen: their first radiance gains the sky's light.
        let Some(([list, first, _, _], side, count)) = &key.senders else { return };
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi sender sky bind group"),
            layout: &self.passes.sender_sky_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: key.frame.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: self.params_binding(96) },
                wgpu::BindGroupEntry { binding: 4, resource: key.voxels.as_entire_binding() },
                texture(5, sky_view),
                wgpu::BindGroupEntry { binding: 6, resource: sky_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 7, resource: list.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 8, resource: first.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 9, resource: key.world.as_entire_binding() },
            ],
        });
        let size = (*side, count.div_ceil(*side));
        self.shared_step("sshgi sky".to_owned(), (Pipe::SenderSky, Shared::Sky), group, sky_slot(s.plan), size);
    }

    /// Illumination levels: the direct term as diffuse senders send it (first bounce; plus
    /// reflectance x the sky's E / pi when the sky pass runs) or reflectance x the previous
    /// bounce's E / pi, then 2x2 box averages.
    fn illumination(&mut self, b: usize, first: bool) {
        let (s, key) = (self.s, self.key);
        let illumination = &s.illumination[0];
        let pass = self.pass(b, "sshgi illumination");
        if first {
            // The start level's reflectance, for the sky-lit senders and the later bounces.
            let g = self.mip_group(&key.albedo, &key.material, &s.albedo.view);
            self.step(pass.clone(), Pipe::ReflectanceSeed, g, 0, &s.albedo);
        }
        match (&s.sky, first) {
            (Some([sky, lit, direct]), true) => {
                let g = self.mip_group(&key.exitance, &key.albedo, &direct.view);
                self.step(pass.clone(), Pipe::BoxSeed, g, 0, direct);
                let g = self.mip_group(&s.albedo.view, &sky.view, &lit.view);
                self.step(pass.clone(), Pipe::Product, g, 1, lit);
                let g = self.mip_group(&direct.view, &lit.view, &illumination.view);
                self.step(pass.clone(), Pipe::AddLit, g, 1, illumination);
            }
            (None, true) => {
                let g = self.mip_group(&key.exitance, &key.albedo, &illumination.view);
                self.step(pass.clone(), Pipe::BoxSeed, g, 0, illumination);
            }
            (_, false) => {
                let g = self.mip_group(&s.albedo.view, &s.bounce[b - 1].view, &illumination.view);
                self.step(pass.clone(), Pipe::Product, g, 1, illumination);
            }
        }
        for k in 1..s.plan.levels as usize {
            let (fine, coarse) = (&s.illumination[k - 1], &s.illumination[k]);
            self.step(
                self.pass(b, "sshgi illumination"),
                Pipe::Reduce,
                self.mip_group(&fine.view, &fine.view, &coarse.view),
                1,
                coarse,
            );
        }
    }

    /// One gather per level; a single level writes the bounce (`out`) directly.
    fn gathers(&mut self, b: usize, out: &Target) {
        let s = self.s;
        let levels = s.plan.levels as usize;
        for k in 0..levels {
            let dest = if levels == 1 { out } else { &s.gathered[k] };
            let group = self.gather_group(k, dest);
            let (pass, size) =
                (self.pass(b, &format!("sshgi gather level {k}")), (dest.texture.width(), dest.texture.height()));
            self.shared_step(pass, (Pipe::Gather, Shared::Gather(k as u32)), group, gather_slot(s.plan, b, k), size);
        }
    }

    /// Coarse to fine: Acc_k = JBU(Acc_k+1) + Ind_k; level 0's sum is the bounce (`out`).
    fn up_sampling(&mut self, b: usize, out: &Target) {
        let s = self.s;
        let levels = s.plan.levels as usize;
        for k in (0..levels.saturating_sub(1)).rev() {
            let coarse = if k + 1 == levels - 1 { &s.gathered[k + 1] } else { &s.summed[k + 1] };
            let dest = if k == 0 { out } else { &s.summed[k] };
            let g = self.up_group(&coarse.view, self.geo(k + 1), self.geo(k), &s.gathered[k].view, &dest.view);
            self.step(self.pass(b, "sshgi up-sampling"), Pipe::Upsample, g, 2 + k as u32, dest);
        }
    }

    /// The bounces' running sum (ping-pong), then the sky's light; returns the target that
    /// holds it.
    pub(super) fn bounce_sum(&mut self) -> &'a Target {
        let s = self.s;
        let mut total = &s.bounce[0];
        let bounces = s.plan.bounces as usize;
        let sky = s.sky.as_ref().map(|[sky, _, _]| sky);
        let mut adds = 0;
        for (b, addend) in (1..bounces).map(|b| &s.bounce[b]).chain(sky).enumerate().map(|(i, t)| (i + 1, t)) {
            let dest = &s.sums[b % 2];
            let g = self.mip_group(&total.view, &addend.view, &dest.view);
            self.step("sshgi output".to_owned(), Pipe::Add, g, 1, dest);
            total = dest;
            adds = b;
        }
        if let (Some([buffer, no_world]), true) = (&s.tail, bounces >= 2) {
            let dest = &s.sums[(adds + 1) % 2];
            let powers = self.key.senders.as_ref().map_or(no_world, |([.., cdf], ..)| cdf);
            self.tail([&s.bounce[bounces - 2], &s.bounce[bounces - 1], total, dest], [buffer, powers]);
            total = dest;
        }
        total
    }

    /// The bounces after the last as a geometric tail of it (`sshgi_tail.wgsl`): `previous` and
    /// `last` bounce, the sum so far and its destination; the factor's buffer and the sender
    /// list's prefix sums (their last two floats, the list's power of the two bounces).
    fn tail(&mut self, [previous, last, total, dest]: [&'a Target; 4], [buffer, powers]: [&wgpu::Buffer; 2]) {
        let texture = |binding, t: &'a Target| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(&t.view),
        };
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi tail bind group"),
            layout: &self.passes.tail_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.params_binding(16) },
                texture(1, previous),
                texture(2, last),
                texture(3, total),
                texture(4, dest),
                wgpu::BindGroupEntry { binding: 5, resource: buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 6, resource: powers.as_entire_binding() },
            ],
        });
        let size = (last.texture.width(), last.texture.height());
        let groups = [group.clone(), group.clone(), group];
        let pipes = [(Pipe::TailSums, size), (Pipe::TailRatio, (1, 1)), (Pipe::TailAdd, size)];
        for (group, (pipeline, size)) in groups.into_iter().zip(pipes) {
            self.steps.push(Step { pass: "sshgi output".to_owned(), pipeline, group, slot: 1, size, tile: 8 });
        }
    }

    /// The bounces' sum (`total`), up-sampled to the view into the output.
    pub(super) fn output(&mut self, total: &Target) {
        let key = self.key;
        let g = self.up_group(&total.view, self.geo(0), &key.pyramid[0], &total.view, &key.out);
        let out_size = (key.out.texture().width(), key.out.texture().height());
        self.steps.push(Step {
            pass: "sshgi output".to_owned(),
            pipeline: Pipe::Upsample,
            group: g,
            slot: 2 + self.s.plan.levels - 1,
            size: out_size,
            tile: 8,
        });
    }

    /// The prefix sums of bounce `b`'s sender power (`sshgi_sender_cdf.wgsl`), which the
    /// gather and the receive after it draw from: a workgroup per block of `count` senders,
    /// then one over the blocks' totals.
    fn sender_cdf(&mut self, b: usize, [list, radiance, cdf]: [&'a wgpu::Buffer; 3], count: u32) {
        let buffer = |binding, b: &'a wgpu::Buffer| wgpu::BindGroupEntry { binding, resource: b.as_entire_binding() };
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi sender cdf bind group"),
            layout: &self.passes.sender_cdf.0,
            entries: &[
                wgpu::BindGroupEntry { binding: 1, resource: self.params_binding(16) },
                buffer(2, list),
                buffer(3, radiance),
                buffer(4, cdf),
            ],
        });
        let pass = self.pass(b, "sshgi sender cdf");
        let slot = panorama_slot(self.s.plan, b);
        let blocks = count.div_ceil(super::sender_cdf::BLOCK);
        for (pipeline, size) in [(Pipe::SenderCdfBlocks, (blocks, 1)), (Pipe::SenderCdfTotals, (1, 1))] {
            self.steps.push(Step { pass: pass.clone(), pipeline, group: group.clone(), slot, size, tile: 1 });
        }
    }

    /// The panorama's senders gathered into bounce `b` (its screen bounce plus their light),
    /// then, but after the last bounce, the senders' radiance of the next bounce
    /// ([`super::super::panorama`]); both draw their senders from the prefix sums of the
    /// bounce's sender power, written first.
    pub(super) fn panorama(&mut self, b: usize) {
        let (s, key) = (self.s, self.key);
        let (Some(screen), Some(([list, first, second, cdf], side, count))) = (s.screen_bounce.get(b), &key.senders)
        else {
            return;
        };
        let (radiance, next) = if b.is_multiple_of(2) { (first, second) } else { (second, first) };
        self.sender_cdf(b, [list, radiance, cdf], *count);
        let slot = panorama_slot(s.plan, b);
        let dest = &s.bounce[b];
        let texture =
            |binding, view| wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(view) };
        let buffer = |binding, b: &'a wgpu::Buffer| wgpu::BindGroupEntry { binding, resource: b.as_entire_binding() };
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi panorama gather bind group"),
            layout: &self.passes.panorama_layout,
            entries: &[
                buffer(0, &key.frame),
                wgpu::BindGroupEntry { binding: 1, resource: self.params_binding(128) },
                texture(2, self.geo(0)),
                texture(3, &screen.view),
                texture(4, &dest.view),
                buffer(5, list),
                buffer(6, radiance),
                buffer(7, &key.voxels),
                buffer(8, &key.world),
                buffer(9, cdf),
            ],
        });
        let pass = self.pass(b, "sshgi panorama gather");
        let size = (dest.texture.width(), dest.texture.height());
        self.shared_step(pass, (Pipe::Panorama, Shared::Panorama), group, slot, size);
        if b + 1 >= s.plan.bounces as usize {
            return;
        }
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi panorama receive bind group"),
            layout: &self.passes.receive_layout,
            entries: &[
                buffer(0, &key.frame),
                wgpu::BindGroupEntry { binding: 1, resource: self.params_binding(128) },
                texture(2, self.geo(0)),
                texture(3, &s.illumination[0].view),
                buffer(4, list),
                buffer(5, radiance),
                buffer(6, next),
                buffer(7, &key.voxels),
                buffer(8, &key.world),
                buffer(9, cdf),
            ],
        });
        let pass = self.pass(b, "sshgi panorama receive");
        let size = (*side, count.div_ceil(*side));
        self.shared_step(pass, (Pipe::Receive, Shared::Receive), group, slot, size);
    }
}

/// A pass that spreads each item's (texel's or sender's) samples over threads.
#[derive(Clone, Copy, Debug)]
pub(super) enum Shared {
    /// The screen's gather of level k.
    Gather(u32),
    /// The panorama's senders gathered on the start level.
    Panorama,
    /// The panorama's and hidden senders' receive.
    Receive,
    /// The sky's rays, on the start level and at the senders.
    Sky,
}

/// How a pass spreads an item's samples over threads: (threads per item S, items per workgroup
/// side, 8 / sqrt(S)). Each thread takes every S-th sample and the workgroup of 64 adds them up
/// (`sshgi_gather.wgsl`, `sshgi_panorama_*.wgsl`, `sshgi_sky.wgsl`). A thread per item made each
/// thread a serial chain of N samples, each marching up to 2^k r voxel columns, and the coarse
/// levels have few texels: on the H200 at 1080p the 2,040 texels of level 3 took 21 ms, level
/// 0's 130,000 5.5 ms, the 8,192 senders' receive 5 ms and the sky 12.6 ms (`bouncelab
/// profile`, commit e48fc51). S grows with the level so that every level launches about four
/// threads per start-level texel. A software adapter has no latency to hide and pays for the
/// barrier: it keeps a thread per item (lavapipe: sshgi's probe 9.4-10.2 s with, 11.2 s
/// without).
pub(super) fn split(shared: bool, pass: Shared) -> (u32, u32) {
    if !shared {
        return (1, 8);
    }
    match pass {
        Shared::Gather(0) | Shared::Panorama | Shared::Sky => (4, 4),
        Shared::Gather(1) | Shared::Receive => (16, 2),
        Shared::Gather(_) => (64, 1),
    }
}

/// Whether passes made on `device` share items' samples over threads ([`split`]): on a GPU, and
/// on a software adapter after [`share_samples_as_on_a_gpu`].
pub(super) fn shares_samples(device: &wgpu::Device) -> bool {
    device.adapter_info().device_type != wgpu::DeviceType::Cpu || AS_ON_A_GPU.load(std::sync::atomic::Ordering::Relaxed)
}

/// Set by [`share_samples_as_on_a_gpu`].
static AS_ON_A_GPU: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Makes sshgi passes created after the call share each item's samples over threads as on a GPU even
/// on a software adapter ([`split`]), so that the tests, which run on one, check the kernels a
/// GPU runs. Process-wide.
pub fn share_samples_as_on_a_gpu(on: bool) {
    AS_ON_A_GPU.store(on, std::sync::atomic::Ordering::Relaxed);
}
