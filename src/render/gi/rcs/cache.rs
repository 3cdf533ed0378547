//! The CPU's account of the record cache: which slots hold records, each record's site and
//! radius, how often it was computed, and the queue of records to renew in place (later
//! bounces, light and scene edits). Renewing at the same site, as Temporal Radiance Caching
//! does, keeps the record distribution stable: nothing moves, so nothing flickers.

use std::collections::VecDeque;

use glam::Vec3;

use super::record::Site;
use crate::scene::{Aabb, Scene};

/// One live record.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CachedRecord {
    pub site: Site,
    /// R_k after its computation (0 until read back).
    pub radius: f32,
    /// Times computed (1 after the first; each renewal adds one bounce).
    pub computed: u32,
    /// Times it should be computed: renewals are queued until `computed` reaches it.
    pub target: u32,
    /// Luminance of its irradiance after the last computation.
    pub luminance: f32,
    /// The frame it was made in.
    pub made: u64,
    /// 0 for a record placed on screen, d + 1 for one proposed by a depth-d record's
    /// hemisphere (a surface the camera did not see).
    pub depth: u32,
}

/// The records by slot.
#[derive(Clone, Debug, Default)]
pub struct Cache {
    slots: Vec<Option<CachedRecord>>,
    free: Vec<u32>,
    capacity: u32,
    renew: VecDeque<u32>,
    queued: Vec<bool>,
}

/// What [`Cache::invalidate_boxes`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Invalidation {
    /// Records that stood on a changed object: gone (their slots are free).
    pub dropped: Vec<u32>,
    /// Records queued for renewal in place.
    pub renewed: usize,
}

impl Cache {
    /// An empty cache of `capacity` slots.
    pub fn new(capacity: u32) -> Self {
        Self { capacity, ..Self::default() }
    }

    /// Slots in use or freed so far (the GPU passes visit `0..high_water`).
    pub fn high_water(&self) -> u32 {
        self.slots.len() as u32
    }

    /// Live records.
    pub fn live(&self) -> usize {
        self.slots.iter().filter(|s| s.is_some()).count()
    }

    /// The record in `slot`.
    pub fn get(&self, slot: u32) -> Option<&CachedRecord> {
        self.slots.get(slot as usize)?.as_ref()
    }

    /// Every live record with its slot.
    pub fn iter(&self) -> impl Iterator<Item = (u32, &CachedRecord)> {
        self.slots.iter().enumerate().filter_map(|(i, s)| Some((i as u32, s.as_ref()?)))
    }

    /// Room for `n` more records.
    pub fn room(&self) -> u32 {
        self.capacity - self.live() as u32
    }

    /// Takes a slot for a new record at `site`; `None` when full.
    pub fn allocate(&mut self, site: Site, frame: u64, depth: u32, target: u32) -> Option<u32> {
        let record = CachedRecord { site, radius: 0.0, computed: 0, target, luminance: 0.0, made: frame, depth };
        if let Some(slot) = self.free.pop() {
            self.slots[slot as usize] = Some(record);
            return Some(slot);
        }
        if self.slots.len() as u32 >= self.capacity {
            return None;
        }
        self.slots.push(Some(record));
        self.queued.push(false);
        Some(self.slots.len() as u32 - 1)
    }

    /// Frees `slot`.
    pub fn free(&mut self, slot: u32) {
        if let Some(s) = self.slots.get_mut(slot as usize)
            && s.take().is_some()
        {
            self.free.push(slot);
        }
    }

    /// Records the result of a computation; returns how much the luminance changed (0 for a
    /// new record).
    pub fn computed(&mut self, slot: u32, radius: f32, luminance: f32) -> f32 {
        let Some(Some(r)) = self.slots.get_mut(slot as usize) else { return 0.0 };
        let change = if r.computed > 0 { (luminance - r.luminance).abs() } else { 0.0 };
        r.radius = radius;
        r.computed += 1;
        r.luminance = luminance;
        change
    }

    /// Renews `slot` in place now and once more after it (its neighbours' lookups change too).
    pub fn invalidate(&mut self, slot: u32) {
        if let Some(Some(r)) = self.slots.get_mut(slot as usize) {
            r.target = r.target.max(r.computed + 2);
        }
        self.queue_renewal(slot);
    }

    /// The bounce passes have converged: no record asks for more.
    pub fn settle(&mut self) {
        for r in self.slots.iter_mut().flatten() {
            r.target = r.target.min(r.computed);
        }
    }

    /// Queues `slot` for renewal in place (once).
    pub fn queue_renewal(&mut self, slot: u32) {
        let i = slot as usize;
        if self.slots.get(i).is_some_and(Option::is_some) && !self.queued[i] {
            self.queued[i] = true;
            self.renew.push_back(slot);
        }
    }

    /// Queues every record computed fewer times than its target (one bounce pass); returns
    /// how many.
    pub fn queue_bounces(&mut self) -> usize {
        let short: Vec<u32> = self.iter().filter(|(_, r)| r.computed < r.target).map(|(s, _)| s).collect();
        let n = short.len();
        short.into_iter().for_each(|s| self.queue_renewal(s));
        n
    }

    /// Whether some record asks for more computations.
    pub fn unsettled(&self) -> bool {
        self.iter().any(|(_, r)| r.computed < r.target)
    }

    /// Records waiting for renewal.
    pub fn pending_renewals(&self) -> usize {
        self.renew.len()
    }

    /// Takes up to `n` queued renewals (skipping freed slots).
    pub fn take_renewals(&mut self, n: usize) -> Vec<u32> {
        let mut out = Vec::new();
        while out.len() < n {
            let Some(slot) = self.renew.pop_front() else { break };
            self.queued[slot as usize] = false;
            if self.get(slot).is_some() {
                out.push(slot);
            }
        }
        out
    }

    /// Empties the cache.
    pub fn clear(&mut self) {
        *self = Self::new(self.capacity);
    }

    /// After objects changed whose old and new bounds are `boxes`: a record standing in a box
    /// (within `margin` metres) is dropped (its surface moved), a record whose hemisphere sees a
    /// box covering more than `tolerance` of its solid angle is renewed in place, every other
    /// record is kept.
    pub fn invalidate_boxes(&mut self, boxes: &[Aabb], margin: f32, tolerance: f32) -> Invalidation {
        let mut out = Invalidation::default();
        let mut renew = Vec::new();
        for (slot, r) in self.iter() {
            let p = r.site.position;
            let mut drop = false;
            let mut affected = false;
            for b in boxes {
                let (lo, hi) = (b.min - Vec3::splat(margin), b.max + Vec3::splat(margin));
                if p.cmpge(lo).all() && p.cmple(hi).all() {
                    drop = true;
                    break;
                }
                let centre = (b.min + b.max) * 0.5;
                let radius = (b.max - b.min).length() * 0.5;
                let to = centre - p;
                let d = to.length();
                // Above the record's plane, and its solid angle (about pi r^2 / d^2 of the
                // hemisphere's 2 pi) above the tolerance.
                if to.dot(r.site.normal) > -radius && (d <= radius || radius * radius / (2.0 * d * d) > tolerance) {
                    affected = true;
                }
            }
            if drop {
                out.dropped.push(slot);
            } else if affected {
                renew.push(slot);
            }
        }
        for &slot in &out.dropped {
            self.free(slot);
        }
        out.renewed = renew.len();
        renew.into_iter().for_each(|s| self.invalidate(s));
        out
    }
}

/// Every rendered object's world bounds and a fingerprint of its material, to tell which
/// objects an edit changed (moved, resized, recoloured).
pub fn object_boxes(scene: &Scene) -> Vec<(Aabb, u64)> {
    use std::hash::{Hash, Hasher};
    let materials: Vec<u64> = scene
        .materials()
        .iter()
        .map(|m| {
            let mut h = std::collections::hash_map::DefaultHasher::new();
            format!("{m:?}").hash(&mut h);
            h.finish()
        })
        .collect();
    scene
        .objects()
        .iter()
        .filter(|o| o.is_rendered())
        .filter_map(|o| {
            let mesh = scene.resources().meshes.get(o.mesh)?;
            let material = materials.get(o.material).copied().unwrap_or_default() ^ o.material as u64;
            Some((mesh.bounds()?.transformed(&o.transform.matrix()), material))
        })
        .collect()
}

/// The bounds of what differs between two snapshots of [`object_boxes`] (old and new boxes
/// of changed objects; every box of the longer list beyond the shorter's length).
pub fn changed_boxes(old: &[(Aabb, u64)], new: &[(Aabb, u64)]) -> Vec<Aabb> {
    let mut out = Vec::new();
    for i in 0..old.len().max(new.len()) {
        match (old.get(i), new.get(i)) {
            (Some(a), Some(b)) if a == b => {}
            (a, b) => out.extend(a.iter().chain(b.iter()).map(|x| x.0)),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn site(p: Vec3) -> Site {
        Site { position: p, normal: Vec3::Y, near: 0.001, radius_bounds: (0.01, 10.0) }
    }

    /// Slots are reused after a free, the capacity holds, and renewals come out once each.
    #[test]
    fn slots_are_reused_and_renewals_are_queued_once() {
        let mut c = Cache::new(3);
        let a = c.allocate(site(Vec3::ZERO), 0, 0, 1).expect("slot");
        let b = c.allocate(site(Vec3::X), 0, 0, 1).expect("slot");
        let _ = c.allocate(site(Vec3::Y), 0, 0, 1).expect("slot");
        assert!(c.allocate(site(Vec3::Z), 0, 0, 1).is_none(), "capacity 3");
        c.free(b);
        assert_eq!(c.allocate(site(Vec3::Z), 1, 0, 1), Some(b));
        c.queue_renewal(a);
        c.queue_renewal(a);
        assert_eq!(c.take_renewals(10), vec![a]);
    }

    /// A record on a moved box is dropped, one looking at it from nearby renewed, a far one
    /// and one below the box's level (facing away) kept.
    #[test]
    fn a_moved_box_drops_its_records_renews_its_neighbours_and_keeps_the_rest() {
        let mut c = Cache::new(16);
        let on = c.allocate(site(Vec3::new(0.0, 0.5, 0.0)), 0, 0, 1).expect("slot");
        let near = c.allocate(site(Vec3::new(1.0, 0.0, 0.0)), 0, 0, 1).expect("slot");
        let far = c.allocate(site(Vec3::new(40.0, 0.0, 0.0)), 0, 0, 1).expect("slot");
        let mut below = site(Vec3::new(0.0, -3.0, 0.0));
        below.normal = Vec3::NEG_Y;
        let below = c.allocate(below, 0, 0, 1).expect("slot");
        let boxes = [Aabb { min: Vec3::splat(-0.5), max: Vec3::splat(0.5) }];
        let inv = c.invalidate_boxes(&boxes, 0.01, 0.02);
        assert_eq!(inv.dropped, vec![on]);
        assert_eq!(c.take_renewals(10), vec![near]);
        assert!(c.get(far).is_some() && c.get(below).is_some());
    }
}
