//! The world hash grid the hemisphere renders look the cache up in for the bounces after the
//! first (`rcs_lookup.wgsl`): each record is listed in every cell its zone of influence
//! (a sphere of radius a R_k) overlaps, so the cell of a point lists every record that can
//! reach it. Built on the CPU, which knows every record's site and radius, whenever the
//! records changed.

use bytemuck::{Pod, Zeroable};
use glam::{IVec3, Vec3};

/// `GridParams` in `rcs_common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GridParams {
    /// xyz origin, w = cell size.
    pub origin: [f32; 4],
    /// x = table size - 1, y = accuracy bits, z = records listed, w unused.
    pub table: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<GridParams>() == 32);

/// Most cells one record is listed in (a zone larger than this many cells is listed in the
/// cells nearest its centre only, so far points miss it: the cell size follows the zones).
const MAX_CELLS_PER_RECORD: i32 = 8;

/// The grid as the GPU reads it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HashGrid {
    pub params: GridParams,
    /// Per hash entry: first item and count.
    pub cells: Vec<[u32; 2]>,
    /// Record slots, grouped by entry.
    pub items: Vec<u32>,
}

/// The same hash as `grid_hash` in `rcs_common.wgsl`.
pub fn hash(cell: IVec3, mask: u32) -> u32 {
    let c = cell.as_uvec3();
    (c.x.wrapping_mul(73_856_093) ^ c.y.wrapping_mul(19_349_663) ^ c.z.wrapping_mul(83_492_791)) & mask
}

impl HashGrid {
    /// Lists `records` (slot, site, zone radius a R_k) for lookups at accuracy `accuracy`. The
    /// cell size is the median zone's diameter (most zones touch at most 8 cells).
    pub fn build(records: &[(u32, Vec3, f32)], accuracy: f32) -> Self {
        let mut zones: Vec<f32> = records.iter().map(|r| r.2).filter(|z| *z > 0.0 && z.is_finite()).collect();
        if zones.is_empty() {
            return Self {
                params: GridParams { origin: [0.0, 0.0, 0.0, 1.0], table: [0, accuracy.to_bits(), 0, 0] },
                cells: vec![[0, 0]],
                items: Vec::new(),
            };
        }
        zones.sort_by(f32::total_cmp);
        let cell = (2.0 * zones[zones.len() / 2]).max(1e-4);
        let origin = records.iter().fold(Vec3::splat(f32::INFINITY), |m, r| m.min(r.1));
        let to_cell = |p: Vec3| ((p - origin) / cell).floor().as_ivec3();
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let mut listed = 0u32;
        let entries = (records.len() * 4).next_power_of_two().max(64) as u32;
        let mask = entries - 1;
        for &(slot, p, zone) in records {
            if !(zone > 0.0 && zone.is_finite()) {
                continue;
            }
            listed += 1;
            let reach = Vec3::splat(zone.min(cell * MAX_CELLS_PER_RECORD as f32 * 0.5));
            let (lo, hi) = (to_cell(p - reach), to_cell(p + reach));
            let mut seen = Vec::new();
            for z in lo.z..=hi.z {
                for y in lo.y..=hi.y {
                    for x in lo.x..=hi.x {
                        let h = hash(IVec3::new(x, y, z), mask);
                        if !seen.contains(&h) {
                            seen.push(h);
                            pairs.push((h, slot));
                        }
                    }
                }
            }
        }
        pairs.sort_unstable();
        let mut cells = vec![[0u32, 0u32]; entries as usize];
        let items: Vec<u32> = pairs.iter().map(|p| p.1).collect();
        let mut i = 0;
        while i < pairs.len() {
            let h = pairs[i].0;
            let start = i;
            while i < pairs.len() && pairs[i].0 == h {
                i += 1;
            }
            cells[h as usize] = [start as u32, (i - start) as u32];
        }
        Self {
            params: GridParams {
                origin: [origin.x, origin.y, origin.z, cell],
                table: [mask, accuracy.to_bits(), listed, 0],
            },
            cells,
            items,
        }
    }

    /// The slots listed where `p` falls (what the GPU lookup visits).
    pub fn candidates(&self, p: Vec3) -> &[u32] {
        let o = Vec3::new(self.params.origin[0], self.params.origin[1], self.params.origin[2]);
        let cell = ((p - o) / self.params.origin[3]).floor().as_ivec3();
        let [start, count] = self.cells[hash(cell, self.params.table[0]) as usize];
        &self.items[start as usize..(start + count) as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every point inside a record's zone finds the record in its cell; a point far outside
    /// every zone finds none of them in a sparse grid.
    #[test]
    fn every_point_in_a_zone_finds_its_record() {
        let records: Vec<(u32, Vec3, f32)> = (0..50)
            .map(|i| {
                let f = i as f32;
                (i, Vec3::new((f * 1.7).sin() * 5.0, (f * 0.3).cos() * 2.0, f * 0.2), 0.3 + 0.02 * f)
            })
            .collect();
        let grid = HashGrid::build(&records, 0.25);
        for &(slot, p, zone) in &records {
            for k in 0..64 {
                let d = Vec3::new((k as f32 * 2.1).sin(), (k as f32 * 1.3).cos(), (k as f32 * 0.7).sin()).normalize();
                let q = p + d * zone * 0.99 * ((k % 4) as f32 / 3.0);
                assert!(grid.candidates(q).contains(&slot), "record {slot} missing at {q}");
            }
        }
        assert!(grid.candidates(Vec3::splat(1000.0)).len() < records.len());
    }
}
