//! Procedural test volumes: phantoms and scenes with known geometry, so renderers
//! can be checked without data files.
//!
//! Every generator takes the edge length `n` in voxels and returns an `n³` volume
//! with isotropic spacing 1 (so its world box is [-0.5, 0.5]³). `n = 0` is treated
//! as 1, so no generator panics.
//!
//! Geometry is given in *continuous voxel coordinates*: voxel `(i, j, k)` covers
//! `[i, i+1) x [j, j+1) x [k, k+1)` and its centre is `(i + 0.5, j + 0.5, k + 0.5)`.
//! [`cubic_voxel_to_world`] converts such a point to world space.
//!
//! Objects with a surface are smooth fields, so that trilinear filtering gives
//! smooth surfaces at any magnification (a binary field terraces): a voxel's
//! value is the object value times the coverage `clamp(0.5 - sd / w, 0, 1)` of
//! the signed distance `sd` (voxels, negative inside) from its centre to the
//! surface, a linear ramp [`TRANSITION_VOXELS`] `w = 1.5` voxels wide whose 0.5
//! level is the surface itself. A sphere's coverages sum to
//! `4/3 pi r³ + pi r w² / 3` (the integral of that ramp). The slab of
//! [`slab_under_sphere`] and the Shepp-Logan ellipsoids are smooth the same way.
//! The Cornell box is a labelled volume (each part its own value, the "cornell"
//! preset a narrow band per value): a ramp from one part's value to air would
//! pass through the values of the other parts and give its edges their colours,
//! so its boxes and walls keep integer bounds and it is read nearest
//! ([`Interpolation::Nearest`]), never blended: trilinear filtering would make
//! the same ramp between voxel centres, a shell of every lower label a tenth of
//! a voxel deep on each face, which a view ray's samples half a voxel apart hit
//! or miss pixel by pixel (coloured speckle, or rings without jitter).

use glam::{UVec3, Vec3};

use super::volume::{Interpolation, Volume, VoxelData};

/// A sphere in continuous voxel coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    pub centre: Vec3,
    pub radius: f32,
}

/// Width in voxels of the density ramp across a smooth surface: enough for
/// trilinear filtering to give a smooth surface, narrow enough to keep edges
/// sharp in the image.
pub const TRANSITION_VOXELS: f32 = 1.5;

/// Coverage of a voxel whose centre lies `signed_distance` voxels from a surface
/// (negative inside): 0.5 on the surface, 0 and 1 beyond half the transition.
pub fn ramp_coverage(signed_distance: f32) -> f32 {
    (0.5 - signed_distance / TRANSITION_VOXELS).clamp(0.0, 1.0)
}

impl Sphere {
    /// Coverage of the voxel whose centre is `p` ([`ramp_coverage`]).
    pub fn coverage(&self, p: Vec3) -> f32 {
        ramp_coverage(p.distance(self.centre) - self.radius)
    }
}

/// Axis-aligned box of voxels: voxel `(i, j, k)` is inside when
/// `min <= (i, j, k) < max` component-wise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VoxelBox {
    pub min: UVec3,
    pub max: UVec3,
}

impl VoxelBox {
    pub fn contains(&self, i: UVec3) -> bool {
        i.cmpge(self.min).all() && i.cmplt(self.max).all()
    }

    pub fn voxel_count(&self) -> u64 {
        let d = self.max.saturating_sub(self.min);
        d.x as u64 * d.y as u64 * d.z as u64
    }

    /// Signed distance in voxels from `p` (continuous voxel coordinates) to the
    /// box `[min, max]`, negative inside: a voxel centre is inside exactly when
    /// [`VoxelBox::contains`] holds for its voxel.
    pub fn signed_distance(&self, p: Vec3) -> f32 {
        let q = (self.min.as_vec3() - p).max(p - self.max.as_vec3());
        q.max(Vec3::ZERO).length() + q.max_element().min(0.0)
    }
}

/// World position of a point given in continuous voxel coordinates of an `n³`
/// volume with isotropic spacing (all generators here).
pub fn cubic_voxel_to_world(n: u32, p: Vec3) -> Vec3 {
    p / n.max(1) as f32 - Vec3::splat(0.5)
}

/// The synthetic volumes by name, as used in scene files (`volume.synthetic`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SyntheticKind {
    SheppLogan,
    ThreeSpheres,
    CornellBox,
    SlabUnderSphere,
    SingleVoxel,
    Noise,
}

impl SyntheticKind {
    pub const ALL: [SyntheticKind; 6] = [
        SyntheticKind::SheppLogan,
        SyntheticKind::ThreeSpheres,
        SyntheticKind::CornellBox,
        SyntheticKind::SlabUnderSphere,
        SyntheticKind::SingleVoxel,
        SyntheticKind::Noise,
    ];

    pub fn name(self) -> &'static str {
        match self {
            SyntheticKind::SheppLogan => "shepp-logan",
            SyntheticKind::ThreeSpheres => "three-spheres",
            SyntheticKind::CornellBox => "cornell-box",
            SyntheticKind::SlabUnderSphere => "slab-under-sphere",
            SyntheticKind::SingleVoxel => "single-voxel",
            SyntheticKind::Noise => "noise",
        }
    }

    pub fn from_name(name: &str) -> Option<SyntheticKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Name of the transfer-function preset ([`super::presets`]) made for it.
    pub fn default_preset(self) -> &'static str {
        match self {
            SyntheticKind::SheppLogan => "phantom",
            SyntheticKind::ThreeSpheres => "spheres",
            SyntheticKind::CornellBox => "cornell",
            SyntheticKind::SlabUnderSphere => "slab-sphere",
            SyntheticKind::SingleVoxel | SyntheticKind::Noise => "grayscale-ramp",
        }
    }

    /// Builds the volume; `seed` only matters for [`SyntheticKind::Noise`].
    pub fn generate(self, n: u32, seed: u64) -> Volume {
        match self {
            SyntheticKind::SheppLogan => shepp_logan(n),
            SyntheticKind::ThreeSpheres => three_spheres(n),
            SyntheticKind::CornellBox => cornell_box(n),
            SyntheticKind::SlabUnderSphere => slab_under_sphere(n),
            SyntheticKind::SingleVoxel => single_voxel(n),
            SyntheticKind::Noise => noise(n, seed),
        }
    }
}

/// Fills an `n³` grid, x fastest, calling `f` with each voxel's index.
fn fill<T>(n: u32, mut f: impl FnMut(UVec3) -> T) -> Vec<T> {
    let mut data = Vec::with_capacity(n as usize * n as usize * n as usize);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                data.push(f(UVec3::new(x, y, z)));
            }
        }
    }
    data
}

fn voxel_centre(i: UVec3) -> Vec3 {
    i.as_vec3() + Vec3::splat(0.5)
}

fn u8_volume(name: &str, n: u32, data: Vec<u8>) -> Volume {
    let (lo, hi) = data.iter().fold((u8::MAX, u8::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    Volume {
        name: name.to_string(),
        dims: UVec3::splat(n),
        spacing: Vec3::ONE,
        data: VoxelData::U8(data),
        value_range: (lo as f64, hi as f64),
        non_finite_voxels: 0,
        interpolation: Interpolation::Trilinear,
    }
}

/// Rescales raw values from their own [min, max] into [0, 1] (constant data maps
/// to 0, the convention of the loaders), keeping the raw range in `value_range`.
fn rescaled_f32_volume(name: &str, n: u32, raw: Vec<f32>) -> Volume {
    let (lo, hi) = raw.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    let span = hi - lo;
    let data = raw.iter().map(|&v| if span > 0.0 { (v - lo) / span } else { 0.0 }).collect();
    Volume {
        name: name.to_string(),
        dims: UVec3::splat(n),
        spacing: Vec3::ONE,
        data: VoxelData::F32(data),
        value_range: (lo as f64, hi as f64),
        non_finite_voxels: 0,
        interpolation: Interpolation::Trilinear,
    }
}

fn coverage_to_u8(value: u8, coverage: f32) -> u8 {
    (value as f32 * coverage).round() as u8
}

/// One ellipsoid of the Shepp-Logan phantom, in the phantom's [-1, 1]³ frame.
struct Ellipsoid {
    /// Density in tenths, so sums are exact (1 - 0.8 - 0.2 is 0, not -1.5e-8).
    density_tenths: i32,
    semi_axes: [f32; 3],
    centre: [f32; 3],
    /// Rotation about z in degrees (the table's phi + psi; its theta is 0 throughout,
    /// so the z-x-z Euler rotation reduces to one turn about z).
    angle_deg: f32,
}

/// The modified (higher-contrast) 3D Shepp-Logan head phantom of Kak & Slaney, with
/// Toft's densities: skull 1, brain 0.2, ventricles 0, small features 0.3.
const SHEPP_LOGAN_ELLIPSOIDS: [Ellipsoid; 10] = [
    Ellipsoid { density_tenths: 10, semi_axes: [0.69, 0.92, 0.81], centre: [0.0, 0.0, 0.0], angle_deg: 0.0 },
    Ellipsoid { density_tenths: -8, semi_axes: [0.6624, 0.874, 0.78], centre: [0.0, -0.0184, 0.0], angle_deg: 0.0 },
    Ellipsoid { density_tenths: -2, semi_axes: [0.11, 0.31, 0.22], centre: [0.22, 0.0, 0.0], angle_deg: -18.0 + 10.0 },
    Ellipsoid { density_tenths: -2, semi_axes: [0.16, 0.41, 0.28], centre: [-0.22, 0.0, 0.0], angle_deg: 18.0 + 10.0 },
    Ellipsoid { density_tenths: 1, semi_axes: [0.21, 0.25, 0.41], centre: [0.0, 0.35, -0.15], angle_deg: 0.0 },
    Ellipsoid { density_tenths: 1, semi_axes: [0.046, 0.046, 0.05], centre: [0.0, 0.1, 0.25], angle_deg: 0.0 },
    Ellipsoid { density_tenths: 1, semi_axes: [0.046, 0.046, 0.05], centre: [0.0, -0.1, 0.25], angle_deg: 0.0 },
    Ellipsoid { density_tenths: 1, semi_axes: [0.046, 0.023, 0.05], centre: [-0.08, -0.605, 0.0], angle_deg: 0.0 },
    Ellipsoid { density_tenths: 1, semi_axes: [0.023, 0.023, 0.02], centre: [0.0, -0.606, 0.0], angle_deg: 0.0 },
    Ellipsoid { density_tenths: 1, semi_axes: [0.023, 0.046, 0.02], centre: [0.06, -0.605, 0.0], angle_deg: 0.0 },
];

impl Ellipsoid {
    /// `p` in the ellipsoid's own frame, divided by the semi-axes: inside when
    /// its length is at most 1.
    fn scaled_local(&self, p: [f32; 3]) -> Vec3 {
        let d = Vec3::from(p) - Vec3::from(self.centre);
        // Into the ellipsoid's own frame: rotate by -angle about z.
        let (s, c) = self.angle_deg.to_radians().sin_cos();
        Vec3::new(c * d.x + s * d.y, -s * d.x + c * d.y, d.z) / Vec3::from(self.semi_axes)
    }

    fn contains(&self, p: [f32; 3]) -> bool {
        self.scaled_local(p).length_squared() <= 1.0
    }

    /// Signed distance from `p` to the surface in phantom units, to first order
    /// (exact on the axes, good near the surface, which is all a ramp needs):
    /// `(|q| - 1) |q| / |q / semi_axes|` for the scaled point `q`.
    fn signed_distance(&self, p: [f32; 3]) -> f32 {
        let q = self.scaled_local(p);
        let k0 = q.length();
        let k1 = (q / Vec3::from(self.semi_axes)).length();
        if k1 > 0.0 {
            (k0 - 1.0) * k0 / k1
        } else {
            -Vec3::from(self.semi_axes).min_element()
        }
    }
}

/// Density of the Shepp-Logan phantom at `p` in its [-1, 1]³ frame (+y is the top
/// of the head, as in the 2D phantom), hard-edged.
pub fn shepp_logan_density(p: [f32; 3]) -> f32 {
    let tenths: i32 = SHEPP_LOGAN_ELLIPSOIDS.iter().filter(|e| e.contains(p)).map(|e| e.density_tenths).sum();
    tenths as f32 / 10.0
}

/// The density at `p` of an `n³` phantom with smooth surfaces: each ellipsoid's
/// density weighted by its [`ramp_coverage`] (distances in voxels, `n / 2` per
/// phantom unit). Equals [`shepp_logan_density`] farther than half a transition
/// from every surface.
fn smooth_shepp_logan_density(p: [f32; 3], n: u32) -> f32 {
    let voxels_per_unit = n as f32 / 2.0;
    let tenths: f32 = SHEPP_LOGAN_ELLIPSOIDS
        .iter()
        .map(|e| e.density_tenths as f32 * ramp_coverage(e.signed_distance(p) * voxels_per_unit))
        .sum();
    tenths / 10.0
}

/// 3D Shepp-Logan phantom (Kak-Slaney geometry, Toft densities), F32 data. The
/// phantom's [-1, 1]³ fills the volume; each voxel takes the smooth density at
/// its centre ([`smooth_shepp_logan_density`]); densities are rescaled from
/// their [min, max] (0 and 1) into [0, 1], so the normalized values are the
/// densities themselves.
pub fn shepp_logan(n: u32) -> Volume {
    let n = n.max(1);
    let raw = fill(n, |i| {
        let p = voxel_centre(i) / n as f32 * 2.0 - Vec3::ONE;
        smooth_shepp_logan_density(p.to_array(), n)
    });
    rescaled_f32_volume("shepp-logan", n, raw)
}

/// The spheres of [`three_spheres`], in continuous voxel coordinates: radii 0.08 n,
/// 0.12 n and 0.16 n, centres along x at 0.18 n, 0.43 n and 0.76 n, slightly
/// staggered in y (0.45 n, 0.55 n, 0.50 n), all at z = 0.5 n. Gaps between them are
/// at least 0.05 n.
pub fn three_spheres_geometry(n: u32) -> [Sphere; 3] {
    let n = n.max(1) as f32;
    let sphere = |x: f32, y: f32, r: f32| Sphere { centre: Vec3::new(x, y, 0.5) * n, radius: r * n };
    [sphere(0.18, 0.45, 0.08), sphere(0.43, 0.55, 0.12), sphere(0.76, 0.50, 0.16)]
}

/// Three solid spheres of growing size side by side along x (the test scene of the
/// selective-light-updates paper, Fig. 7), U8 data: 255 inside, 0 outside,
/// smooth surfaces ([`ramp_coverage`]). Geometry: [`three_spheres_geometry`].
pub fn three_spheres(n: u32) -> Volume {
    let n = n.max(1);
    let spheres = three_spheres_geometry(n);
    let data = fill(n, |i| {
        let p = voxel_centre(i);
        let c = spheres.iter().map(|s| s.coverage(p)).fold(0.0, f32::max);
        coverage_to_u8(255, c)
    });
    u8_volume("three-spheres", n, data)
}

/// Raw U8 values of the parts of [`cornell_box`]; distinct, at least 30 apart, so a
/// transfer function can colour each part (preset "cornell").
pub const CORNELL_FLOOR: u8 = 40;
pub const CORNELL_CEILING: u8 = 70;
pub const CORNELL_BACK_WALL: u8 = 100;
/// The -x wall (red in the "cornell" preset).
pub const CORNELL_LEFT_WALL: u8 = 130;
/// The +x wall (green in the "cornell" preset).
pub const CORNELL_RIGHT_WALL: u8 = 160;
pub const CORNELL_SHORT_BOX: u8 = 200;
pub const CORNELL_TALL_BOX: u8 = 235;

/// The parts of [`cornell_box`] with their values, in painting order (later parts
/// overwrite earlier ones where they overlap, i.e. along the room's edges).
///
/// Walls are `t = max(1, n / 16)` voxels thick (integer division): floor
/// `y < t`, ceiling `y >= n - t`, back wall `z < t`, left wall `x < t`, right wall
/// `x >= n - t`; the front (+z) is open. Boxes stand on the floor, bounds
/// `floor(f * n)`: short box x in [0.55 n, 0.80 n), y in [t, t + 0.30 n), z in
/// [0.50 n, 0.75 n); tall box x in [0.20 n, 0.45 n), y in [t, t + 0.60 n), z in
/// [0.20 n, 0.45 n).
pub fn cornell_box_parts(n: u32) -> Vec<(VoxelBox, u8)> {
    let n = n.max(1);
    let t = (n / 16).max(1);
    let f = |fraction: f32| (fraction * n as f32) as u32;
    let b =
        |min: [u32; 3], max: [u32; 3]| VoxelBox { min: UVec3::from(min), max: UVec3::from(max).min(UVec3::splat(n)) };
    vec![
        (b([0, 0, 0], [n, t, n]), CORNELL_FLOOR),
        (b([0, n - t, 0], [n, n, n]), CORNELL_CEILING),
        (b([0, 0, 0], [n, n, t]), CORNELL_BACK_WALL),
        (b([0, 0, 0], [t, n, n]), CORNELL_LEFT_WALL),
        (b([n - t, 0, 0], [n, n, n]), CORNELL_RIGHT_WALL),
        (b([f(0.55), t, f(0.50)], [f(0.80), t + f(0.30), f(0.75)]), CORNELL_SHORT_BOX),
        (b([f(0.20), t, f(0.20)], [f(0.45), t + f(0.60), f(0.45)]), CORNELL_TALL_BOX),
    ]
}

/// A volumetric Cornell box (as in the ambient-occlusion and colour-bleeding
/// paper, Fig. 5): floor, ceiling, back, left and right walls and two boxes, each
/// with its own U8 value, air 0, open towards +z. Geometry: [`cornell_box_parts`].
/// A labelled volume, read nearest ([`Interpolation::Nearest`]): its parts'
/// faces lie on voxel faces, so it shows the boxes exactly, and no position
/// reads a value between two parts' labels.
pub fn cornell_box(n: u32) -> Volume {
    let n = n.max(1);
    let parts = cornell_box_parts(n);
    let data = fill(n, |i| parts.iter().rev().find(|(b, _)| b.contains(i)).map_or(0, |&(_, v)| v));
    Volume { interpolation: Interpolation::Nearest, ..u8_volume("cornell-box", n, data) }
}

/// Raw U8 values of [`slab_under_sphere`].
pub const SLAB_VALUE: u8 = 128;
pub const SPHERE_VALUE: u8 = 255;

/// Geometry of [`slab_under_sphere`] in continuous voxel coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlabUnderSphere {
    /// Slab: y in [n / 10, n / 5), x and z in [n / 10, n - n / 10) (integer
    /// division), smooth faces ([`ramp_coverage`] of its signed distance). Its
    /// top face (the 0.5 level of the ramp) is the plane y = `slab.max.y`.
    pub slab: VoxelBox,
    /// Sphere: centre (0.5 n, 0.6 n, 0.5 n), radius 0.2 n, smooth surface. Its
    /// lowest point (y = 0.4 n) is at least 0.2 n above the slab, far more than
    /// the two ramps' half widths, so they never overlap.
    pub sphere: Sphere,
}

impl SlabUnderSphere {
    pub fn for_size(n: u32) -> SlabUnderSphere {
        let n = n.max(1);
        let margin = n / 10;
        let nf = n as f32;
        SlabUnderSphere {
            slab: VoxelBox { min: UVec3::new(margin, n / 10, margin), max: UVec3::new(n - margin, n / 5, n - margin) },
            sphere: Sphere { centre: Vec3::new(nf / 2.0, 3.0 * nf / 5.0, nf / 2.0), radius: nf / 5.0 },
        }
    }

    /// True where a light travelling straight down (-y) is blocked by the sphere
    /// before reaching the slab's top face at horizontal position (x, z): inside the
    /// sphere's disc of radius 0.2 n around (0.5 n, 0.5 n).
    pub fn in_shadow_from_above(&self, x: f32, z: f32) -> bool {
        let dx = x - self.sphere.centre.x;
        let dz = z - self.sphere.centre.z;
        dx * dx + dz * dz < self.sphere.radius * self.sphere.radius
    }
}

/// The known-shadow scene: a horizontal slab near the bottom (-y) and a sphere
/// above it, U8 data (slab [`SLAB_VALUE`], sphere [`SPHERE_VALUE`], air 0). A
/// directional light travelling along -y casts the sphere's shadow on the slab's
/// top face as a disc (see [`SlabUnderSphere`] for the exact geometry).
pub fn slab_under_sphere(n: u32) -> Volume {
    let n = n.max(1);
    let g = SlabUnderSphere::for_size(n);
    let data = fill(n, |i| {
        let p = voxel_centre(i);
        let slab = coverage_to_u8(SLAB_VALUE, ramp_coverage(g.slab.signed_distance(p)));
        slab.max(coverage_to_u8(SPHERE_VALUE, g.sphere.coverage(p)))
    });
    u8_volume("slab-under-sphere", n, data)
}

/// Index of the one non-zero voxel of [`single_voxel`]: `(n / 2, n / 2, n / 2)`,
/// i.e. the voxel whose lower corner is the box centre (for even n its centre lies
/// half a voxel off the box centre along each axis).
pub fn single_voxel_index(n: u32) -> UVec3 {
    UVec3::splat(n.max(1) / 2)
}

/// Zero everywhere except one voxel of value 255 (normalized 1) at
/// [`single_voxel_index`]; U8 data. An impulse for filter and sampling tests.
pub fn single_voxel(n: u32) -> Volume {
    let n = n.max(1);
    let centre = single_voxel_index(n);
    let data = fill(n, |i| if i == centre { 255 } else { 0 });
    u8_volume("single-voxel", n, data)
}

/// SplitMix64 finalizer: a well-mixed 64-bit hash, enough for lattice noise.
fn splitmix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

/// Pseudo-random value in [0, 1) at an integer lattice point of one octave.
fn lattice_value(seed: u64, octave: u32, p: [i64; 3]) -> f32 {
    let mut h = splitmix64(seed ^ ((octave as u64) << 56));
    for c in p {
        h = splitmix64(h ^ c as u64);
    }
    (h >> 40) as f32 / (1u64 << 24) as f32
}

/// One octave of value noise: lattice values every `cell` voxels, blended with a
/// smoothstep so the field has no visible grid creases.
fn value_noise(seed: u64, octave: u32, cell: f32, p: Vec3) -> f32 {
    let q = p / cell;
    let base = q.floor();
    let f = q - base;
    let w = f * f * (Vec3::splat(3.0) - 2.0 * f);
    let b = base.as_i64vec3();
    let mut sum = 0.0;
    for corner in 0..8u32 {
        let o = [(corner & 1) as i64, ((corner >> 1) & 1) as i64, ((corner >> 2) & 1) as i64];
        let weight = (if o[0] == 1 { w.x } else { 1.0 - w.x })
            * (if o[1] == 1 { w.y } else { 1.0 - w.y })
            * (if o[2] == 1 { w.z } else { 1.0 - w.z });
        sum += weight * lattice_value(seed, octave, [b.x + o[0], b.y + o[1], b.z + o[2]]);
    }
    sum
}

/// Deterministic fractal value noise (three octaves, base cell `max(2, n / 8)`
/// voxels, amplitudes 1, 1/2, 1/4), F32 data rescaled to [0, 1]. Same `seed`, same
/// volume; different seeds give unrelated volumes.
pub fn noise(n: u32, seed: u64) -> Volume {
    let n = n.max(1);
    let cell = (n / 8).max(2) as f32;
    let raw = fill(n, |i| {
        let p = voxel_centre(i);
        (0..3u32).map(|o| value_noise(seed, o, cell / (1 << o) as f32, p) / (1 << o) as f32).sum()
    });
    rescaled_f32_volume(&format!("noise-{seed}"), n, raw)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    fn value_at(v: &Volume, i: UVec3) -> f32 {
        v.voxel(i.x, i.y, i.z)
    }

    /// Sum of normalized values over a box of voxels.
    fn sum_over(v: &Volume, min: UVec3, max: UVec3) -> f64 {
        let mut s = 0.0;
        for z in min.z..max.z {
            for y in min.y..max.y {
                for x in min.x..max.x {
                    s += v.voxel(x, y, z) as f64;
                }
            }
        }
        s
    }

    fn sphere_bounds(s: &Sphere, n: u32) -> (UVec3, UVec3) {
        let lo = (s.centre - Vec3::splat(s.radius + 1.0)).max(Vec3::ZERO).as_uvec3();
        let hi = (s.centre + Vec3::splat(s.radius + 2.0)).as_uvec3().min(UVec3::splat(n));
        (lo, hi)
    }

    #[test]
    fn every_kind_has_the_requested_dims_and_unit_spacing() {
        for kind in SyntheticKind::ALL {
            let v = kind.generate(20, 3);
            assert_eq!(v.dims, UVec3::splat(20), "{}", kind.name());
            assert_eq!(v.spacing, Vec3::ONE, "{}", kind.name());
            assert_eq!(v.data.len(), 20 * 20 * 20, "{}", kind.name());
            let (lo, hi) = v.normalized_range();
            assert!(lo >= 0.0 && hi <= 1.0 && hi > lo, "{}: range {lo}..{hi}", kind.name());
            assert_eq!(SyntheticKind::from_name(kind.name()), Some(kind));
        }
    }

    #[test]
    fn size_zero_does_not_panic() {
        for kind in SyntheticKind::ALL {
            assert_eq!(kind.generate(0, 1).dims, UVec3::ONE);
        }
    }

    #[test]
    fn shepp_logan_has_toft_densities_at_known_points() {
        let n = 64;
        let v = shepp_logan(n);
        // Voxel index whose centre is nearest to phantom coordinate c in [-1, 1].
        let at = |c: [f32; 3]| {
            let i = Vec3::from(c).map(|x| ((x + 1.0) * 0.5 * n as f32 - 0.5).round()).as_uvec3();
            value_at(&v, i)
        };
        assert_eq!(at([0.0, 0.0, 0.0]), 0.2, "brain: 1 - 0.8");
        assert_eq!(at([0.0, 0.89, 0.0]), 1.0, "skull between the two outer ellipsoids");
        assert_eq!(at([0.22, 0.0, 0.0]), 0.0, "right ventricle: 1 - 0.8 - 0.2");
        assert_eq!(at([0.0, 0.35, -0.15]), 0.3, "feature: 1 - 0.8 + 0.1");
        assert_eq!(at([0.95, 0.95, 0.95]), 0.0, "outside the head");
        assert_eq!(v.value_range, (0.0, 1.0));
    }

    #[test]
    fn three_spheres_hold_their_volumes() {
        let n = 64;
        let v = three_spheres(n);
        let spheres = three_spheres_geometry(n);
        for s in &spheres {
            let (lo, hi) = sphere_bounds(s, n);
            let sum = sum_over(&v, lo, hi);
            let r = s.radius as f64;
            let w = TRANSITION_VOXELS as f64;
            let ball = 4.0 / 3.0 * PI as f64 * r.powi(3);
            // The ramp adds pi r w² / 3 (see the module doc); sampling it on the
            // voxel lattice is good to far better than 0.2 % at these radii.
            let ramp = ball + PI as f64 * r * w * w / 3.0;
            assert!((sum / ramp - 1.0).abs() < 0.002, "radius {r}: {sum} vs {ramp}");
            // So the ball's own volume is off by the ramp's share, w² / (4 r²)
            // (2.1 % at the smallest radius, 5.1 voxels), plus that 0.2 %.
            let ramp_share = w * w / (4.0 * r * r);
            assert!((sum / ball - 1.0).abs() < ramp_share + 0.002, "radius {r}: {sum} vs {ball}");
            assert_eq!(value_at(&v, s.centre.as_uvec3()), 1.0);
        }
        // Different sizes, disjoint.
        assert!(spheres[0].radius < spheres[1].radius && spheres[1].radius < spheres[2].radius);
        for w in spheres.windows(2) {
            assert!(w[0].centre.distance(w[1].centre) > w[0].radius + w[1].radius + 2.0);
        }
        assert_eq!(value_at(&v, UVec3::ZERO), 0.0);
    }

    #[test]
    fn cornell_box_parts_have_their_values() {
        let n = 48;
        let v = cornell_box(n);
        let raw = |i: UVec3| (value_at(&v, i) * 255.0).round() as u8;
        let (m, t) = (n / 2, n / 16);
        assert_eq!(raw(UVec3::new(m, 0, m)), CORNELL_FLOOR);
        assert_eq!(raw(UVec3::new(m, n - 1, m)), CORNELL_CEILING);
        assert_eq!(raw(UVec3::new(m, m, 0)), CORNELL_BACK_WALL);
        assert_eq!(raw(UVec3::new(0, m, m)), CORNELL_LEFT_WALL);
        assert_eq!(raw(UVec3::new(n - 1, m, m)), CORNELL_RIGHT_WALL);
        // Just above the floor in each box's footprint, and the open room between.
        assert_eq!(raw(UVec3::new((0.67 * n as f32) as u32, t, (0.62 * n as f32) as u32)), CORNELL_SHORT_BOX);
        assert_eq!(raw(UVec3::new((0.32 * n as f32) as u32, t, (0.32 * n as f32) as u32)), CORNELL_TALL_BOX);
        assert_eq!(raw(UVec3::new(m, (0.8 * n as f32) as u32, (0.9 * n as f32) as u32)), 0);
        // The front is open: the last z slice holds no back wall in the middle.
        assert_eq!(raw(UVec3::new(m, m, n - 1)), 0);
        // Each part's voxel count (before overlaps) is its box size.
        let tall = cornell_box_parts(n)[6].0;
        let count = (0..n)
            .flat_map(|z| (0..n).flat_map(move |y| (0..n).map(move |x| UVec3::new(x, y, z))))
            .filter(|&i| raw(i) == CORNELL_TALL_BOX)
            .count() as u64;
        assert_eq!(count, tall.voxel_count());
    }

    #[test]
    fn slab_under_sphere_matches_its_documented_geometry() {
        let n = 50;
        let v = slab_under_sphere(n);
        let g = SlabUnderSphere::for_size(n);
        assert_eq!(g.slab.min, UVec3::new(5, 5, 5));
        assert_eq!(g.slab.max, UVec3::new(45, 10, 45));
        assert_eq!(g.sphere.centre, Vec3::new(25.0, 30.0, 25.0));
        assert_eq!(g.sphere.radius, 10.0);
        let slab_value = SLAB_VALUE as f32 / 255.0;
        // Voxel centres more than half a transition (0.75 voxel) inside hold the
        // full value; the outermost layer, 0.5 voxel inside, 0.5 + 0.5 / 1.5 of
        // it; the first layer of air, 0.5 voxel out, 0.5 - 0.5 / 1.5; the next
        // (1.5 voxels out) nothing.
        let raw = |i: UVec3| (value_at(&v, i) * 255.0).round() as u8;
        let part = |c: f32| (SLAB_VALUE as f32 * c).round() as u8;
        assert_eq!(value_at(&v, UVec3::new(25, 7, 25)), slab_value);
        assert_eq!(value_at(&v, UVec3::new(6, 8, 43)), slab_value);
        assert_eq!(raw(UVec3::new(25, 9, 25)), part(0.5 + 1.0 / 3.0), "top layer of the slab");
        assert_eq!(raw(UVec3::new(25, 10, 25)), part(0.5 - 1.0 / 3.0), "air right above the slab");
        assert_eq!(raw(UVec3::new(25, 4, 25)), part(0.5 - 1.0 / 3.0), "air right below the slab");
        assert_eq!(raw(UVec3::new(25, 11, 25)), 0, "air 1.5 voxels above the slab");
        // The top face is the ramp's 0.5 level: the two layers around y = 10 average to it.
        let face = (value_at(&v, UVec3::new(25, 9, 25)) + value_at(&v, UVec3::new(25, 10, 25))) / 2.0;
        assert!((face / slab_value - 0.5).abs() < 0.01, "{face}");
        assert_eq!(value_at(&v, UVec3::new(25, 30, 25)), 1.0);
        let (lo, hi) = sphere_bounds(&g.sphere, n);
        let sum = sum_over(&v, lo.max(UVec3::new(0, 11, 0)), hi);
        let w = TRANSITION_VOXELS as f64;
        let ramp = 4.0 / 3.0 * PI as f64 * 1000.0 + PI as f64 * 10.0 * w * w / 3.0;
        assert!((sum / ramp - 1.0).abs() < 0.002, "{sum} vs {ramp}");
        assert!(g.in_shadow_from_above(25.0, 25.0) && g.in_shadow_from_above(34.9, 25.0));
        assert!(!g.in_shadow_from_above(35.1, 25.0) && !g.in_shadow_from_above(10.0, 10.0));
        assert!(cubic_voxel_to_world(n, g.sphere.centre).abs_diff_eq(Vec3::new(0.0, 0.1, 0.0), 1e-6));
    }

    #[test]
    fn box_signed_distance_is_negative_exactly_inside() {
        let b = VoxelBox { min: UVec3::new(2, 2, 2), max: UVec3::new(6, 5, 7) };
        for z in 0..9 {
            for y in 0..9 {
                for x in 0..9 {
                    let i = UVec3::new(x, y, z);
                    assert_eq!(b.signed_distance(voxel_centre(i)) < 0.0, b.contains(i), "{i}");
                }
            }
        }
        assert_eq!(b.signed_distance(Vec3::new(4.0, 3.5, 4.0)), -1.5);
        assert_eq!(b.signed_distance(Vec3::new(9.0, 3.0, 4.0)), 3.0);
        assert!((b.signed_distance(Vec3::new(9.0, 8.0, 4.0)) - 18f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn smooth_surfaces_ramp_over_the_transition() {
        assert_eq!(ramp_coverage(0.0), 0.5);
        assert_eq!(ramp_coverage(-0.75), 1.0);
        assert_eq!(ramp_coverage(0.75), 0.0);
        assert_eq!(ramp_coverage(-0.375), 0.75);
        // The phantom's smooth density equals the hard one away from surfaces,
        // and takes values between them on the skull's outer surface.
        let n = 64;
        for p in [[0.0, 0.0, 0.0], [0.0, 0.35, -0.15], [0.95, 0.95, 0.95]] {
            assert_eq!(smooth_shepp_logan_density(p, n), shepp_logan_density(p), "{p:?}");
        }
        let on_surface = smooth_shepp_logan_density([0.0, 0.92, 0.0], n);
        assert!((on_surface - 0.5).abs() < 0.01, "{on_surface}");
    }

    #[test]
    fn single_voxel_has_exactly_one_non_zero_voxel_at_the_centre() {
        for n in [1, 7, 16] {
            let v = single_voxel(n);
            let non_zero: Vec<usize> = (0..v.voxel_count()).filter(|&i| v.data.normalized(i) != 0.0).collect();
            assert_eq!(non_zero.len(), 1, "n = {n}");
            assert_eq!(value_at(&v, UVec3::splat(n / 2)), 1.0);
        }
    }

    #[test]
    fn noise_is_deterministic_by_seed_and_differs_between_seeds() {
        let a = noise(24, 7);
        let b = noise(24, 7);
        let c = noise(24, 8);
        assert_eq!(a.data, b.data);
        let differing =
            (0..a.voxel_count()).filter(|&i| (a.data.normalized(i) - c.data.normalized(i)).abs() > 0.05).count();
        assert!(differing > a.voxel_count() / 2, "only {differing} voxels differ");
        assert_eq!(a.normalized_range(), (0.0, 1.0));
        // Spread over the range, not two clusters: every quarter of [0, 1] is used.
        let h = a.histogram(4);
        assert!(h.iter().all(|&c| c > 0), "{h:?}");
    }
}
