//! The cache's GPU memory: the records, each record's check strata, the bounce lookup grid,
//! this round's jobs and results, and the one staging buffer every round reads back (the
//! coverage candidates, the computed records' radii, the light check's list, the secondary
//! sites).

use super::grid::{GridParams, HashGrid};
use super::record::{Candidate, GpuJob, GpuRecord};
use super::{storage, uniform};

/// Check strata per record (`rcs_check.wgsl`).
pub const CHECK_STRATA: u64 = 64;

/// Secondary sites one job may propose (one per plane quadrant).
pub const SECONDARIES_PER_JOB: u64 = 4;

/// Bytes of the counter header before a list (`count` and padding).
const HEADER: u64 = 16;

/// Offsets in the staging buffer.
#[derive(Clone, Copy, Debug)]
pub struct StagingLayout {
    pub candidates: u64,
    pub candidates_len: u64,
    pub results: u64,
    pub results_len: u64,
    pub changed: u64,
    pub changed_len: u64,
    pub secondaries: u64,
    pub secondaries_len: u64,
}

/// Every buffer, sized for `max_records` records, rounds of `jobs` jobs and views of `tiles`
/// coverage tiles.
pub struct Store {
    pub max_records: u32,
    pub jobs_capacity: u32,
    pub tiles: u32,
    pub records: wgpu::Buffer,
    pub check_strata: wgpu::Buffer,
    pub jobs: wgpu::Buffer,
    pub results: wgpu::Buffer,
    pub candidates: wgpu::Buffer,
    pub changed: wgpu::Buffer,
    /// Secondary record sites the reduction proposes (4 per job at most).
    pub secondaries: wgpu::Buffer,
    pub splat_list: wgpu::Buffer,
    pub grid_params: wgpu::Buffer,
    pub grid_cells: wgpu::Buffer,
    pub grid_items: wgpu::Buffer,
    pub weights: wgpu::Buffer,
    pub weights_resolution: u32,
    pub staging: wgpu::Buffer,
    pub layout: StagingLayout,
}

impl Store {
    /// Allocates everything (records cleared to free slots).
    pub fn new(device: &wgpu::Device, max_records: u32, jobs_capacity: u32, tiles: u32) -> Self {
        let records_size = u64::from(max_records) * std::mem::size_of::<GpuRecord>() as u64;
        let jobs = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rcs jobs"),
            size: u64::from(jobs_capacity.max(1)) * std::mem::size_of::<GpuJob>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let candidates_len = HEADER + u64::from(tiles.max(1)) * std::mem::size_of::<Candidate>() as u64;
        let results_len = u64::from(jobs_capacity.max(1)) * 16;
        let changed_len = HEADER + u64::from(max_records) * 4;
        let secondaries_len = HEADER + u64::from(jobs_capacity.max(1)) * SECONDARIES_PER_JOB * 32;
        let layout = StagingLayout {
            candidates: 0,
            candidates_len,
            results: candidates_len,
            results_len,
            changed: candidates_len + results_len,
            changed_len,
            secondaries: candidates_len + results_len + changed_len,
            secondaries_len,
        };
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rcs readback staging"),
            size: layout.secondaries + secondaries_len,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            max_records,
            jobs_capacity,
            tiles,
            records: storage(device, "rcs records", records_size),
            check_strata: storage(device, "rcs check strata", u64::from(max_records) * CHECK_STRATA * 16),
            jobs,
            results: storage(device, "rcs job results", results_len),
            candidates: storage(device, "rcs candidates", candidates_len),
            changed: storage(device, "rcs changed records", changed_len),
            secondaries: storage(device, "rcs secondary sites", secondaries_len),
            splat_list: storage(device, "rcs splat list", u64::from(jobs_capacity.max(1)) * 4),
            grid_params: uniform(device, "rcs grid params", std::mem::size_of::<GridParams>() as u64),
            grid_cells: storage(device, "rcs grid cells", 16),
            grid_items: storage(device, "rcs grid items", 16),
            weights: storage(device, "rcs plane weights", 16),
            weights_resolution: 0,
            staging,
            layout,
        }
    }

    /// Uploads the plane weights for `resolution` when they changed.
    pub fn ensure_weights(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, resolution: u32) {
        if self.weights_resolution == resolution {
            return;
        }
        let weights = super::hemisphere::plane_weights(resolution);
        let bytes: &[u8] = bytemuck::cast_slice(&weights);
        self.weights = storage(device, "rcs plane weights", bytes.len() as u64);
        queue.write_buffer(&self.weights, 0, bytes);
        self.weights_resolution = resolution;
    }

    /// Uploads the bounce lookup grid (buffers grow as needed).
    pub fn upload_grid(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, grid: &HashGrid) {
        let cells: &[u8] = bytemuck::cast_slice(&grid.cells);
        let items: &[u8] = bytemuck::cast_slice(&grid.items);
        if self.grid_cells.size() < cells.len() as u64 {
            self.grid_cells = storage(device, "rcs grid cells", (cells.len() as u64).next_power_of_two());
        }
        if self.grid_items.size() < items.len() as u64 {
            self.grid_items = storage(device, "rcs grid items", (items.len() as u64).next_power_of_two());
        }
        queue.write_buffer(&self.grid_params, 0, bytemuck::bytes_of(&grid.params));
        if !cells.is_empty() {
            queue.write_buffer(&self.grid_cells, 0, cells);
        }
        if !items.is_empty() {
            queue.write_buffer(&self.grid_items, 0, items);
        }
    }

    /// Bytes held.
    pub fn gpu_bytes(&self) -> u64 {
        [
            &self.records,
            &self.check_strata,
            &self.jobs,
            &self.results,
            &self.candidates,
            &self.changed,
            &self.secondaries,
            &self.splat_list,
            &self.grid_params,
            &self.grid_cells,
            &self.grid_items,
            &self.weights,
            &self.staging,
        ]
        .iter()
        .map(|b| b.size())
        .sum()
    }
}
