//! The preprocessing pipeline (see the module [`super`]): local histograms,
//! packing, training, and the streamed assignment of every voxel, with the
//! disk cache in front ([`preprocess_cached`]).

use glam::UVec3;

use super::histogram::LocalHistograms;
use super::packing::PackingScheme;
use super::parallel::for_each_chunk;
use super::progress::StepClock;
use super::quantize::{pack_cluster_ids, train_lbg, LbgParams};
use super::search::CodebookSearch;
use super::training_set::select_training_voxels;

use crate::scene::Volume;
use crate::vk::Context;

use super::{gpu, histogram, quantize, AoCache, AoError, AoSettings, Backend, CacheKey, CacheMiss, Metric, Progress};

/// Unpacked histograms a slab of the assignment stream holds at most (per
/// worker), bytes.
const SLAB_BYTES: usize = 8 << 20;
/// Training voxels per parallel chunk.
const TRAINING_CHUNK: usize = 256;

/// Wall-clock seconds of each step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepTimings {
    /// Global histogram and packing scheme.
    pub packing: f64,
    /// Local histograms of the training voxels, packed.
    pub training_histograms: f64,
    /// LBG.
    pub training: f64,
    /// Local histograms of every voxel, packed and assigned.
    pub assignment: f64,
}

impl StepTimings {
    pub fn total(&self) -> f64 {
        self.packing + self.training_histograms + self.training + self.assignment
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct PreprocessStats {
    /// Vectors in TS (two per training voxel).
    pub training_vectors: u64,
    /// Lloyd iterations over all codebook sizes.
    pub lloyd_iterations: u32,
    /// Mean distance of TS to the trained packed codebook, in the metric.
    pub training_distortion: f64,
    /// Mean distance of every voxel's two packed histograms to their codewords.
    pub assignment_distortion: f64,
    /// Of the run that computed the result (a cache hit keeps them).
    pub timings: StepTimings,
}

/// What rendering needs from the preprocessing, and what the cache stores.
#[derive(Clone, Debug, PartialEq)]
pub struct AoPreprocessed {
    pub dims: UVec3,
    /// 2^b histogram bins.
    pub bins: u32,
    pub packed_dim: u32,
    /// n_c.
    pub clusters: u32,
    /// `clusters x bins`: each cluster's mean unpacked (normalized) histogram,
    /// zero for a cluster no voxel uses.
    pub codebook: Vec<f32>,
    /// `clusters x packed_dim`: the trained codebook the assignment searched.
    pub packed_codebook: Vec<f32>,
    /// `bins x packed_dim` packing scheme ([`PackingScheme::matrix`]).
    pub packing_matrix: Vec<f32>,
    /// Hemisphere histograms assigned to each cluster.
    pub cluster_sizes: Vec<u64>,
    /// Per voxel (x fastest): [`quantize::pack_cluster_ids`] of the forward and
    /// backward hemisphere's clusters.
    pub cluster_ids: Vec<u32>,
    pub stats: PreprocessStats,
}

impl AoPreprocessed {
    /// Codebook histogram of cluster `c`.
    pub fn cluster_histogram(&self, c: usize) -> &[f32] {
        &self.codebook[c * self.bins as usize..(c + 1) * self.bins as usize]
    }
}

/// Runs the whole preprocessing of `volume` on the CPU; `progress` hears from
/// every long step (on the calling thread).
pub fn preprocess(
    volume: &Volume,
    settings: &AoSettings,
    progress: &mut dyn FnMut(&Progress),
) -> Result<AoPreprocessed, AoError> {
    preprocess_on(volume, settings, None, progress)
}

/// [`preprocess`] with the per-voxel work (histograms, packing, assignment) on
/// `gpu` when `ao.backend` says so (by default whenever a context is given).
pub fn preprocess_on(
    volume: &Volume,
    settings: &AoSettings,
    gpu: Option<&Context>,
    progress: &mut dyn FnMut(&Progress),
) -> Result<AoPreprocessed, AoError> {
    settings.validate()?;
    let backend = settings.backend_for(gpu.is_some())?;
    let metric = settings.metric;
    let histograms = LocalHistograms::new(volume, settings.radius, settings.bits);
    let bins = histograms.bins();
    if let (Backend::Gpu, Some(ctx)) = (backend, gpu) {
        // Refuse what the GPU cannot run before any work.
        let lmax = metric == Metric::Lmax;
        let (dim, clusters) = (settings.packed_dim as usize, settings.clusters as usize);
        gpu::sweep::supported_plan(ctx, volume, histograms.stencil(), bins, dim, clusters, lmax)?;
    }
    let mut timings = StepTimings::default();

    // Packing scheme from the normalized global histogram H.
    let clock = StepClock::start("ao packing");
    let mut global = vec![0f64; bins];
    for &k in histograms.voxel_bins() {
        global[k as usize] += 1.0;
    }
    let voxels = volume.voxel_count().max(1) as f64;
    global.iter_mut().for_each(|h| *h /= voxels);
    let packing = PackingScheme::from_histogram(&global, settings.packed_dim as usize);
    let dim = packing.packed_dim;
    progress(&clock.report(1.0));
    timings.packing = clock.elapsed().as_secs_f64();

    // Training set: packed forward and backward histograms of the chosen voxels.
    let clock = StepClock::start("ao training-set histograms");
    let chosen = select_training_voxels(volume, &settings.training)?;
    let mut vectors = vec![0f32; chosen.len() * 2 * dim];
    let chunks = chosen.len().div_ceil(TRAINING_CHUNK);
    for_each_chunk(
        chunks,
        || (histograms.scratch(), vec![0f32; bins], vec![0f32; bins]),
        |(scratch, forward, backward), c| {
            let part = &chosen[c * TRAINING_CHUNK..((c + 1) * TRAINING_CHUNK).min(chosen.len())];
            let mut packed = vec![0f32; part.len() * 2 * dim];
            for (i, &voxel) in part.iter().enumerate() {
                histograms.voxel_into_by_rows(voxel, scratch, forward, backward);
                packing.pack(forward, &mut packed[2 * i * dim..(2 * i + 1) * dim]);
                packing.pack(backward, &mut packed[(2 * i + 1) * dim..(2 * i + 2) * dim]);
            }
            packed
        },
        |c, packed, done| {
            let start = c * TRAINING_CHUNK * 2 * dim;
            vectors[start..start + packed.len()].copy_from_slice(&packed);
            progress(&clock.report(done as f64 / chunks as f64));
        },
    );
    timings.training_histograms = clock.elapsed().as_secs_f64();

    // LBG on the packed training set.
    let clock = StepClock::start("ao training");
    let params = LbgParams {
        metric,
        clusters: settings.clusters as usize,
        max_iterations: settings.lbg_iterations,
        threshold: settings.lbg_threshold,
    };
    let training = train_lbg(&vectors, dim, params, &mut |f| progress(&clock.report(f)));
    drop(vectors);
    timings.training = clock.elapsed().as_secs_f64();
    let codebook = training.codebook;
    let clusters = codebook.len();

    // Every voxel: histograms, packed, nearest codeword; the unpacked
    // histograms summed per cluster for the final codebook.
    let clock = StepClock::start(match backend {
        Backend::Cpu => "ao assignment",
        Backend::Gpu => "ao gpu sweep and assignment",
    });
    let assigned = match gpu.filter(|_| backend == Backend::Gpu) {
        Some(ctx) => {
            let report = &mut |f| progress(&clock.report(f));
            gpu::assign_volume(ctx, &histograms, &packing, &codebook, metric, report)?.0
        }
        None => assign_on_cpu(&histograms, &packing, &codebook, metric, &mut |f| progress(&clock.report(f))),
    };
    let VolumeAssignment { cluster_ids, sums, distortion_sum } = assigned;
    let (codebook_unpacked, cluster_sizes) = (sums.codebook(), sums.sizes().to_vec());
    timings.assignment = clock.elapsed().as_secs_f64();

    Ok(AoPreprocessed {
        dims: volume.dims,
        bins: bins as u32,
        packed_dim: dim as u32,
        clusters: clusters as u32,
        codebook: codebook_unpacked,
        packed_codebook: codebook.words,
        packing_matrix: packing.matrix(),
        cluster_sizes,
        cluster_ids,
        stats: PreprocessStats {
            training_vectors: training.assignment.len() as u64,
            lloyd_iterations: training.iterations,
            training_distortion: training.distortion,
            assignment_distortion: distortion_sum / (2.0 * voxels),
            timings,
        },
    })
}

/// Every voxel's cluster ids and what the final codebook is made of.
pub struct VolumeAssignment {
    /// Per voxel [`quantize::pack_cluster_ids`].
    pub cluster_ids: Vec<u32>,
    pub sums: ClusterSums,
    /// Summed distance of every hemisphere histogram to its codeword.
    pub distortion_sum: f64,
}

/// The nearest-codeword assignment of every voxel on all CPU cores (the
/// reference), streamed slab by slab.
fn assign_on_cpu(
    histograms: &LocalHistograms,
    packing: &PackingScheme,
    codebook: &quantize::Codebook,
    metric: Metric,
    progress: &mut dyn FnMut(f64),
) -> VolumeAssignment {
    let (clusters, bins, dim) = (codebook.len(), histograms.bins(), packing.packed_dim);
    let search = CodebookSearch::new(codebook, metric);
    let mut cluster_ids = vec![0u32; histograms.volume().voxel_count()];
    let mut distortion_sum = 0f64;
    let states = histograms.stream_with(
        SLAB_BYTES,
        || ClusterSums::new(clusters, bins),
        |sums, slab| assign_slab(slab, packing, &search, dim, sums),
        |_, (first, ids, distortion), done, total| {
            cluster_ids[first..first + ids.len()].copy_from_slice(&ids);
            distortion_sum += distortion;
            progress(done as f64 / total as f64);
        },
    );
    let mut sums = ClusterSums::new(clusters, bins);
    states.iter().for_each(|part| sums.absorb(part));
    VolumeAssignment { cluster_ids, sums, distortion_sum }
}

/// Sums of the unpacked histograms assigned to each cluster (per worker, then
/// merged), in f64 whatever computed the histograms.
pub struct ClusterSums {
    bins: usize,
    sums: Vec<f64>,
    sizes: Vec<u64>,
}

impl ClusterSums {
    pub fn new(clusters: usize, bins: usize) -> ClusterSums {
        ClusterSums { bins, sums: vec![0.0; clusters * bins], sizes: vec![0; clusters] }
    }

    /// Adds `histogram` (`bins` values) to cluster `id`.
    pub fn add(&mut self, id: usize, histogram: &[f32]) {
        self.add_scaled(id, histogram, 1.0);
    }

    /// Adds `histogram` scaled by `scale` (each value an f32 product, as the
    /// GPU normalizes) to cluster `id`.
    pub fn add_scaled(&mut self, id: usize, histogram: &[f32], scale: f32) {
        self.sizes[id] += 1;
        let sum = &mut self.sums[id * self.bins..(id + 1) * self.bins];
        sum.iter_mut().zip(histogram).for_each(|(s, &h)| *s += (h * scale) as f64);
    }

    /// Adds another worker's sums.
    pub fn absorb(&mut self, part: &ClusterSums) {
        self.sums.iter_mut().zip(&part.sums).for_each(|(a, b)| *a += b);
        self.sizes.iter_mut().zip(&part.sizes).for_each(|(a, b)| *a += b);
    }

    pub fn sizes(&self) -> &[u64] {
        &self.sizes
    }

    /// Each cluster's mean histogram (zero for an empty cluster).
    pub fn codebook(&self) -> Vec<f32> {
        (0..self.sums.len())
            .map(|i| match self.sizes[i / self.bins] {
                0 => 0.0,
                n => (self.sums[i] / n as f64) as f32,
            })
            .collect()
    }
}

/// Packs and assigns a slab's histograms; returns (first voxel, packed ids,
/// summed distance). Each search starts at the previous histogram's codeword
/// (neighbouring voxels have similar surroundings), and a packed histogram
/// equal to the previous one takes its codeword without a search.
fn assign_slab(
    slab: &histogram::HistogramSlab,
    packing: &PackingScheme,
    search: &CodebookSearch,
    dim: usize,
    sums: &mut ClusterSums,
) -> (usize, Vec<u32>, f64) {
    let mut packed = vec![0f32; dim];
    // Per hemisphere: the previous voxel's packed histogram, codeword and
    // distance (forward and backward histograms of one voxel differ a lot, so
    // each side follows its own neighbour).
    let mut previous = [vec![f32::NAN; dim], vec![f32::NAN; dim]];
    let mut previous_id = [0usize; 2];
    let mut previous_d = [0f32; 2];
    let mut distortion = 0f64;
    let mut ids = Vec::with_capacity(slab.voxels.len());
    for i in 0..slab.voxels.len() {
        let (forward, backward) = slab.voxel(i);
        for (side, histogram) in [forward, backward].into_iter().enumerate() {
            packing.pack(histogram, &mut packed);
            if packed != previous[side] {
                (previous_id[side], previous_d[side]) = search.nearest(&packed, previous_id[side]);
                std::mem::swap(&mut packed, &mut previous[side]);
            }
            distortion += previous_d[side] as f64;
            sums.add(previous_id[side], histogram);
        }
        ids.push(pack_cluster_ids(previous_id[0] as u32, previous_id[1] as u32));
    }
    (slab.voxels.start, ids, distortion)
}

/// How [`preprocess_cached`] got its result.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CacheOutcome {
    /// Loaded from this file.
    Hit(std::path::PathBuf),
    /// Computed and stored in this file, after this miss.
    Stored(std::path::PathBuf, CacheMiss),
    /// Computed; `ao.cache = false`.
    Disabled,
}

/// [`preprocess`] behind the disk cache of `ao.cache_dir`: a sound file for the
/// same volume content and parameters is loaded; a missing, corrupt or stale
/// one is rebuilt and replaced.
pub fn preprocess_cached(
    volume: &Volume,
    settings: &AoSettings,
    progress: &mut dyn FnMut(&Progress),
) -> Result<(AoPreprocessed, CacheOutcome), AoError> {
    preprocess_cached_on(volume, settings, None, progress)
}

/// [`preprocess_cached`] with [`preprocess_on`]'s choice of backend. The
/// backend is part of the cache key: the GPU's f32 histogram sums can differ
/// from the CPU's in the last bits, and so, at a near tie, a cluster id.
pub fn preprocess_cached_on(
    volume: &Volume,
    settings: &AoSettings,
    gpu: Option<&Context>,
    progress: &mut dyn FnMut(&Progress),
) -> Result<(AoPreprocessed, CacheOutcome), AoError> {
    settings.validate()?;
    let backend = settings.backend_for(gpu.is_some())?;
    if !settings.cache {
        return Ok((preprocess_on(volume, settings, gpu, progress)?, CacheOutcome::Disabled));
    }
    let cache = AoCache::for_settings(settings);
    let key = CacheKey::for_backend(volume, settings, backend);
    let miss = match cache.load(&key)? {
        Ok(result) => return Ok((result, CacheOutcome::Hit(cache.path(&key)))),
        Err(miss) => miss,
    };
    let result = preprocess_on(volume, settings, gpu, progress)?;
    let path = cache.store(&key, &result)?;
    Ok((result, CacheOutcome::Stored(path, miss)))
}
