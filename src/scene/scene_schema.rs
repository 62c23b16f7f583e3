//! The scene-file schema, one serde struct per table with unknown keys denied,
//! and the checks that turn it into a [`SceneSpec`], naming the key of anything
//! wrong. The format is described in [`super::scene_file`].

use std::path::{Path, PathBuf};

use glam::Vec3;
use serde::de::DeserializeOwned;
use serde::Deserialize;
use toml::Value;

use super::camera::{Camera, Projection};
use super::light::{Falloff, Light, LightKind};
use super::loaders;
use super::presets::{preset, PRESET_NAMES};
use super::scene_file::SceneError;
use super::scene_spec::{CameraPlacement, CameraSpec, ProjectionSpec, SceneSpec, TransferSpec, VolumeSource};
use super::synthetic::SyntheticKind;
use super::transfer::{ControlPoint, TransferError, TransferFunction};
use super::{OpticalModel, PhongSettings, ReferenceSettings, RenderSettings, TechniqueSettings, VolumeFilter};

pub const MAX_IMAGE_SIZE: u32 = 16384;
pub const MAX_SYNTHETIC_SIZE: u32 = 512;
pub const MAX_TRANSFER_POINTS: usize = 256;
pub const MAX_LIGHTS: usize = 64;
/// Field of view of a perspective camera, degrees: narrower than this and the
/// framing distance no longer fits an f32 next to the target.
pub const FOV_Y_RANGE: std::ops::RangeInclusive<f32> = 0.01..=179.0;
/// Largest camera coordinate or distance, world units (the volume's longest
/// side is 1): beyond it the eye and target round together in f32 and the
/// volume is far below a pixel.
pub const MAX_CAMERA_COORDINATE: f32 = 1e6;

/// Default light: directional, from upper-left-front (as seen by the default
/// camera), travelling towards the volume centre.
pub const DEFAULT_LIGHT_DIRECTION: [f32; 3] = [1.0, -1.0, -1.0];
/// Default position of point and spot lights: upper-left-front, outside the box.
pub const DEFAULT_LIGHT_POSITION: [f32; 3] = [-1.0, 1.0, 1.0];

/// The scene tables of a document (after overrides), not yet checked.
#[derive(Default)]
pub(crate) struct SceneTables {
    pub(crate) volume: Option<Value>,
    pub(crate) transfer: Option<Value>,
    pub(crate) camera: Option<Value>,
    pub(crate) lights: Option<Value>,
    pub(crate) render: Option<Value>,
    pub(crate) reference: Option<Value>,
    pub(crate) phong: Option<Value>,
}

/// Reads and checks every table; absent ones take their defaults (the volume
/// has none).
pub(crate) fn check_scene(
    origin: &str,
    base_dir: &Path,
    tables: SceneTables,
    settings: TechniqueSettings,
    technique_tables: Vec<&'static str>,
) -> Result<SceneSpec, SceneError> {
    let c = Checker { origin };
    let volume = c.volume(c.section(tables.volume, "volume")?, base_dir)?;
    let transfer = c.transfer(c.section(tables.transfer, "transfer")?.unwrap_or_default(), &volume)?;
    let camera = c.camera(c.section(tables.camera, "camera")?.unwrap_or_default())?;
    let lights = c.lights(tables.lights)?;
    let render = c.render(c.section(tables.render, "render")?.unwrap_or_default())?;
    let reference = c.reference(c.section(tables.reference, "reference")?.unwrap_or_default())?;
    let phong = c.phong(c.section(tables.phong, "phong")?.unwrap_or_default())?;
    Ok(SceneSpec {
        origin: origin.to_string(),
        volume,
        transfer,
        camera,
        lights,
        render,
        reference,
        phong,
        settings,
        technique_tables,
    })
}

// The schema, one struct per table. Options where "absent" means something
// (defaults that depend on other keys, or keys that only apply in some modes).

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct VolumeSection {
    file: Option<String>,
    data_file: Option<String>,
    synthetic: Option<String>,
    size: Option<u32>,
    seed: Option<u64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct TransferSection {
    preset: Option<String>,
    auto: Option<bool>,
    points: Option<Vec<[f32; 5]>>,
}

#[derive(Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "kebab-case")]
enum ProjectionName {
    Perspective,
    Orthographic,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct CameraSection {
    projection: Option<ProjectionName>,
    fov_y: Option<f32>,
    ortho_height: Option<f32>,
    azimuth: Option<f32>,
    elevation: Option<f32>,
    distance: Option<f32>,
    target: Option<[f32; 3]>,
    eye: Option<[f32; 3]>,
    up: Option<[f32; 3]>,
}

#[derive(Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "kebab-case")]
enum LightType {
    Directional,
    Point,
    Spot,
}

#[derive(Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "kebab-case")]
enum FalloffName {
    None,
    InverseSquare,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct LightSection {
    #[serde(rename = "type")]
    kind: Option<LightType>,
    direction: Option<[f32; 3]>,
    position: Option<[f32; 3]>,
    color: Option<[f32; 3]>,
    intensity: Option<f32>,
    inner_cone: Option<f32>,
    outer_cone: Option<f32>,
    falloff: Option<FalloffName>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
struct RenderSection {
    // Signed, so that a negative size gets the range check's message (1..=16384)
    // rather than serde's "a whole number (0 or more)".
    width: i64,
    height: i64,
    step: f32,
    background: [f32; 3],
    emission: f32,
    jitter: bool,
    filter: String,
}

impl Default for RenderSection {
    fn default() -> Self {
        RenderSection {
            width: 512,
            height: 512,
            step: 0.5,
            background: [0.0; 3],
            emission: 0.1,
            jitter: true,
            filter: VolumeFilter::Exact.name().to_string(),
        }
    }
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum ModelName {
    SingleScattering,
    EmissiveScattering,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
struct ReferenceSection {
    model: ModelName,
    step: f32,
    shadow_step: f32,
    min_transmittance: f32,
    chromatic: bool,
}

impl Default for ReferenceSection {
    fn default() -> Self {
        ReferenceSection {
            model: ModelName::SingleScattering,
            step: 0.25,
            shadow_step: 0.5,
            min_transmittance: 1e-4,
            chromatic: false,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
struct PhongSection {
    ambient: f32,
    diffuse: f32,
    specular: f32,
    shininess: f32,
}

impl Default for PhongSection {
    fn default() -> Self {
        PhongSection { ambient: 0.2, diffuse: 0.8, specular: 0.3, shininess: 32.0 }
    }
}

/// serde's "unknown field `x`, expected one of `a`, `b`" with the nearest known
/// field suggested: "... (did you mean `a`?)".
fn with_suggestion(message: &str) -> String {
    let message = &super::user_terms::in_user_terms(message);
    let unknown = message.strip_prefix("unknown field `").and_then(|rest| rest.split_once('`'));
    let Some((field, rest)) = unknown else { return message.to_string() };
    let known = rest.split('`').skip(1).step_by(2);
    match super::suggest::nearest(field, known) {
        Some(near) => format!("{message} (did you mean `{near}`?)"),
        None => message.to_string(),
    }
}

/// Checks values and turns the schema structs into scene types, naming the key
/// of anything wrong.
struct Checker<'a> {
    origin: &'a str,
}

impl Checker<'_> {
    fn err(&self, key: &str, problem: impl Into<String>) -> SceneError {
        SceneError::Invalid { origin: self.origin.to_string(), key: key.to_string(), problem: problem.into() }
    }

    /// Deserializes one table, with the key path of any error.
    fn section<T: DeserializeOwned>(&self, value: Option<Value>, key: &str) -> Result<Option<T>, SceneError> {
        value.map(|v| self.deserialize(v, key)).transpose()
    }

    fn deserialize<T: DeserializeOwned>(&self, value: Value, key: &str) -> Result<T, SceneError> {
        value.try_into().map_err(|e: toml::de::Error| {
            // toml names the inner key path on the error's last line ("in `a.b`").
            let display = e.to_string();
            let inner = display.lines().rev().find_map(|l| l.trim().strip_prefix("in `")?.strip_suffix('`'));
            SceneError::Schema {
                origin: self.origin.to_string(),
                key: inner.map_or_else(|| key.to_string(), |k| format!("{key}.{k}")),
                message: with_suggestion(e.message().trim_end()),
            }
        })
    }

    fn finite(&self, key: &str, v: f32) -> Result<f32, SceneError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(key, format!("must be a finite number, got {v}")))
        }
    }

    fn non_negative(&self, key: &str, v: f32) -> Result<f32, SceneError> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(key, format!("must be finite and >= 0, got {v}")))
        }
    }

    fn positive(&self, key: &str, v: f32) -> Result<f32, SceneError> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(key, format!("must be finite and > 0, got {v}")))
        }
    }

    fn point(&self, key: &str, v: [f32; 3]) -> Result<Vec3, SceneError> {
        let p = Vec3::from(v);
        if p.is_finite() {
            Ok(p)
        } else {
            Err(self.err(key, format!("must be finite, got {v:?}")))
        }
    }

    /// A camera position: finite and within [`MAX_CAMERA_COORDINATE`].
    fn camera_point(&self, key: &str, v: [f32; 3]) -> Result<Vec3, SceneError> {
        let p = self.point(key, v)?;
        if p.abs().max_element() > MAX_CAMERA_COORDINATE {
            return Err(self
                .err(key, format!("must lie within {MAX_CAMERA_COORDINATE:e} world units of the volume, got {v:?}")));
        }
        Ok(p)
    }

    fn colour(&self, key: &str, v: [f32; 3]) -> Result<Vec3, SceneError> {
        if v.iter().all(|c| c.is_finite() && *c >= 0.0) {
            Ok(Vec3::from(v))
        } else {
            Err(self.err(key, format!("must be finite and >= 0, got {v:?}")))
        }
    }

    /// A unit direction from a finite, non-zero vector.
    fn direction(&self, key: &str, v: [f32; 3]) -> Result<Vec3, SceneError> {
        Vec3::from(v)
            .try_normalize()
            .ok_or_else(|| self.err(key, format!("must be a finite, non-zero vector, got {v:?}")))
    }

    fn only_with(&self, present: bool, key: &str, condition: &str) -> Result<(), SceneError> {
        if present {
            Err(self.err(key, format!("only applies {condition}")))
        } else {
            Ok(())
        }
    }

    fn volume(&self, section: Option<VolumeSection>, base_dir: &Path) -> Result<VolumeSource, SceneError> {
        const HOW: &str = "give exactly one of volume.file, volume.data_file, volume.synthetic";
        let s = section.ok_or_else(|| self.err("volume", format!("is missing: {HOW}")))?;
        let given = [s.file.is_some(), s.data_file.is_some(), s.synthetic.is_some()];
        if given.iter().filter(|&&g| g).count() != 1 {
            return Err(self.err(
                "volume",
                format!("is ambiguous: {HOW} (from the command line, replace the whole table: --set 'volume={{synthetic=\"noise\"}}')"),
            ));
        }
        let not_synthetic = "with volume.synthetic";
        let nonempty = |key: &str, path: String| {
            if path.is_empty() {
                Err(self.err(key, "is empty"))
            } else {
                Ok(PathBuf::from(path))
            }
        };
        if let Some(file) = s.file {
            self.only_with(s.size.is_some(), "volume.size", not_synthetic)?;
            self.only_with(s.seed.is_some(), "volume.seed", not_synthetic)?;
            return Ok(VolumeSource::File(base_dir.join(nonempty("volume.file", file)?)));
        }
        if let Some(file) = s.data_file {
            self.only_with(s.size.is_some(), "volume.size", not_synthetic)?;
            self.only_with(s.seed.is_some(), "volume.seed", not_synthetic)?;
            return Ok(VolumeSource::File(loaders::data_dir().join(nonempty("volume.data_file", file)?)));
        }
        let name = s.synthetic.unwrap_or_default();
        let kind = SyntheticKind::from_name(&name).ok_or_else(|| {
            let names: Vec<&str> = SyntheticKind::ALL.iter().map(|k| k.name()).collect();
            self.err("volume.synthetic", format!("is \"{name}\", not one of: {}", names.join(", ")))
        })?;
        let size = s.size.unwrap_or(64);
        if !(1..=MAX_SYNTHETIC_SIZE).contains(&size) {
            return Err(self.err("volume.size", format!("must be in 1..={MAX_SYNTHETIC_SIZE}, got {size}")));
        }
        self.only_with(
            s.seed.is_some() && kind != SyntheticKind::Noise,
            "volume.seed",
            "with volume.synthetic = \"noise\"",
        )?;
        Ok(VolumeSource::Synthetic { kind, size, seed: s.seed.unwrap_or(1) })
    }

    fn transfer(&self, s: TransferSection, volume: &VolumeSource) -> Result<TransferSpec, SceneError> {
        let auto = s.auto == Some(true);
        if [s.preset.is_some(), auto, s.points.is_some()].iter().filter(|&&g| g).count() > 1 {
            return Err(self.err(
                "transfer",
                "takes only one of preset, auto = true, points (from the command line, replace the whole table: --set 'transfer={auto=true}')",
            ));
        }
        if let Some(name) = s.preset {
            return preset(&name).map(TransferSpec::Given).ok_or_else(|| {
                self.err("transfer.preset", format!("is \"{name}\", not one of: {}", PRESET_NAMES.join(", ")))
            });
        }
        if auto {
            return Ok(TransferSpec::FromHistogram);
        }
        if let Some(points) = s.points {
            if points.len() > MAX_TRANSFER_POINTS {
                return Err(self.err(
                    "transfer.points",
                    format!("has {} points, at most {MAX_TRANSFER_POINTS} are allowed", points.len()),
                ));
            }
            let points = points.iter().map(|p| ControlPoint { value: p[0], rgba: [p[1], p[2], p[3], p[4]] }).collect();
            return TransferFunction::new(points).map(TransferSpec::Given).map_err(|e| match e {
                TransferError::Empty => self.err("transfer.points", "is empty; give at least one point"),
                TransferError::OutOfRange { index } => self.err(
                    &format!("transfer.points.{index}"),
                    "must have value, r, g, b and alpha finite and in [0, 1]",
                ),
                TransferError::Unsorted { index, value, previous } => self.err(
                    &format!("transfer.points.{index}"),
                    format!("has value {value}, below the previous point's {previous}; points must be sorted by value"),
                ),
            });
        }
        // Nothing given: the synthetic volume's own preset, else automatic.
        Ok(match volume {
            VolumeSource::Synthetic { kind, .. } => {
                preset(kind.default_preset()).map_or(TransferSpec::FromHistogram, TransferSpec::Given)
            }
            VolumeSource::File(_) => TransferSpec::FromHistogram,
        })
    }

    fn camera(&self, s: CameraSection) -> Result<CameraSpec, SceneError> {
        let projection = match s.projection.unwrap_or(ProjectionName::Perspective) {
            ProjectionName::Perspective => {
                self.only_with(s.ortho_height.is_some(), "camera.ortho_height", "with projection = \"orthographic\"")?;
                let fov = s.fov_y.unwrap_or(30.0);
                if !FOV_Y_RANGE.contains(&fov) {
                    let (lo, hi) = (FOV_Y_RANGE.start(), FOV_Y_RANGE.end());
                    return Err(self.err("camera.fov_y", format!("must be in [{lo}, {hi}] degrees, got {fov}")));
                }
                ProjectionSpec::Perspective { fov_y_deg: fov }
            }
            ProjectionName::Orthographic => {
                self.only_with(s.fov_y.is_some(), "camera.fov_y", "with projection = \"perspective\"")?;
                let height = s.ortho_height.map(|h| self.positive("camera.ortho_height", h)).transpose()?;
                ProjectionSpec::Orthographic { height }
            }
        };
        let target = self.camera_point("camera.target", s.target.unwrap_or([0.0; 3]))?;
        let placement = if let Some(eye) = s.eye {
            let orbit_only = "to an orbit camera, not with camera.eye";
            self.only_with(s.azimuth.is_some(), "camera.azimuth", orbit_only)?;
            self.only_with(s.elevation.is_some(), "camera.elevation", orbit_only)?;
            self.only_with(s.distance.is_some(), "camera.distance", orbit_only)?;
            let eye = self.camera_point("camera.eye", eye)?;
            let up = self.direction("camera.up", s.up.unwrap_or([0.0, 1.0, 0.0]))?;
            let forward = (target - eye)
                .try_normalize()
                .ok_or_else(|| self.err("camera.eye", "must differ from camera.target"))?;
            if forward.cross(up).length() < 1e-4 {
                return Err(self.err("camera.up", "is parallel to the view direction (camera.target - camera.eye)"));
            }
            CameraPlacement::LookAt { eye, target, up }
        } else {
            self.only_with(s.up.is_some(), "camera.up", "with camera.eye (an orbit camera keeps +y up)")?;
            let azimuth_deg = self.finite("camera.azimuth", s.azimuth.unwrap_or(30.0))?;
            let elevation_deg = s.elevation.unwrap_or(20.0);
            if !(-90.0..=90.0).contains(&elevation_deg) {
                return Err(self.err("camera.elevation", format!("must be in [-90, 90] degrees, got {elevation_deg}")));
            }
            let distance = s.distance.map(|d| self.positive("camera.distance", d)).transpose()?;
            if let Some(d) = distance {
                if d > MAX_CAMERA_COORDINATE {
                    return Err(
                        self.err("camera.distance", format!("must be at most {MAX_CAMERA_COORDINATE:e}, got {d}"))
                    );
                }
                let probe = Projection::Perspective { fov_y_deg: 30.0 };
                let eye = Camera::orbit(target, d, azimuth_deg, elevation_deg, probe).eye;
                // The eye must sit where the orbit puts it, not where f32 rounds it
                // next to a large target (0.1 % of the distance).
                if ((eye - target).length() - d).abs() > 1e-3 * d {
                    return Err(self.err(
                        "camera.distance",
                        format!("{d} is lost in f32 rounding next to camera.target {target}: increase it or move the target"),
                    ));
                }
            }
            CameraPlacement::Orbit { target, azimuth_deg, elevation_deg, distance }
        };
        Ok(CameraSpec { placement, projection })
    }

    fn lights(&self, value: Option<Value>) -> Result<Vec<Light>, SceneError> {
        let items = match value {
            Some(Value::Array(items)) => items,
            // Not reached through parse_scene_table, which inserts the default light.
            None => Vec::new(),
            Some(_) => return Err(self.err("lights", "must be an array of tables ([[lights]])")),
        };
        if items.len() > MAX_LIGHTS {
            return Err(self.err("lights", format!("has {} lights, at most {MAX_LIGHTS} are allowed", items.len())));
        }
        items
            .into_iter()
            .enumerate()
            .map(|(i, item)| {
                let key = format!("lights.{i}");
                let section: LightSection = self.deserialize(item, &key)?;
                self.light(&key, section)
            })
            .collect()
    }

    fn light(&self, key: &str, s: LightSection) -> Result<Light, SceneError> {
        let k = |field: &str| format!("{key}.{field}");
        let kind = s.kind.unwrap_or(LightType::Directional);
        let not_directional = "to point and spot lights";
        let spot_only = "to spot lights";
        let kind = match kind {
            LightType::Directional => {
                self.only_with(s.position.is_some(), &k("position"), not_directional)?;
                self.only_with(s.falloff.is_some(), &k("falloff"), not_directional)?;
                self.only_with(s.inner_cone.is_some(), &k("inner_cone"), spot_only)?;
                self.only_with(s.outer_cone.is_some(), &k("outer_cone"), spot_only)?;
                LightKind::Directional {
                    direction: self.direction(&k("direction"), s.direction.unwrap_or(DEFAULT_LIGHT_DIRECTION))?,
                }
            }
            LightType::Point => {
                self.only_with(s.direction.is_some(), &k("direction"), "to directional and spot lights")?;
                self.only_with(s.inner_cone.is_some(), &k("inner_cone"), spot_only)?;
                self.only_with(s.outer_cone.is_some(), &k("outer_cone"), spot_only)?;
                LightKind::Point { position: self.point(&k("position"), s.position.unwrap_or(DEFAULT_LIGHT_POSITION))? }
            }
            LightType::Spot => {
                let position = self.point(&k("position"), s.position.unwrap_or(DEFAULT_LIGHT_POSITION))?;
                // Default: aimed at the volume centre.
                let direction = self.direction(&k("direction"), s.direction.unwrap_or((-position).to_array()))?;
                let inner = s.inner_cone.unwrap_or(20.0);
                let outer = s.outer_cone.unwrap_or(30.0);
                if !(outer > 0.0 && outer <= 180.0) {
                    return Err(self.err(&k("outer_cone"), format!("must be in (0, 180] degrees, got {outer}")));
                }
                // Strictly below: the cone edge is a smoothstep between the two.
                if !(inner >= 0.0 && inner < outer) {
                    return Err(self
                        .err(&k("inner_cone"), format!("must be in [0, outer_cone = {outer}) degrees, got {inner}")));
                }
                LightKind::Spot { position, direction, inner_cone_deg: inner, outer_cone_deg: outer }
            }
        };
        Ok(Light {
            kind,
            color: self.colour(&k("color"), s.color.unwrap_or([1.0; 3]))?,
            intensity: self.non_negative(&k("intensity"), s.intensity.unwrap_or(1.0))?,
            falloff: match s.falloff {
                Some(FalloffName::InverseSquare) => Falloff::InverseSquare,
                Some(FalloffName::None) | None => Falloff::None,
            },
        })
    }

    fn render(&self, s: RenderSection) -> Result<RenderSettings, SceneError> {
        let size = |key: &str, v: i64| match u32::try_from(v) {
            Ok(v) if (1..=MAX_IMAGE_SIZE).contains(&v) => Ok(v),
            _ => Err(self.err(key, format!("must be in 1..={MAX_IMAGE_SIZE}, got {v}"))),
        };
        Ok(RenderSettings {
            width: size("render.width", s.width)?,
            height: size("render.height", s.height)?,
            step_voxels: self.positive("render.step", s.step)?,
            background: self.colour("render.background", s.background)?,
            emission: self.non_negative("render.emission", s.emission)?,
            jitter: s.jitter,
            filter: s.filter.parse().map_err(|e: String| self.err("render.filter", e))?,
        })
    }

    fn reference(&self, s: ReferenceSection) -> Result<ReferenceSettings, SceneError> {
        if s.chromatic && !matches!(s.model, ModelName::SingleScattering) {
            return Err(self.err(
                "reference.chromatic",
                "coloured extinction is defined for model \"single-scattering\" only".to_string(),
            ));
        }
        if !(0.0..1.0).contains(&s.min_transmittance) {
            return Err(
                self.err("reference.min_transmittance", format!("must be in [0, 1), got {}", s.min_transmittance))
            );
        }
        Ok(ReferenceSettings {
            model: match s.model {
                ModelName::SingleScattering => OpticalModel::SingleScattering,
                ModelName::EmissiveScattering => OpticalModel::EmissiveScattering,
            },
            step_voxels: self.positive("reference.step", s.step)?,
            shadow_step_voxels: self.positive("reference.shadow_step", s.shadow_step)?,
            min_transmittance: s.min_transmittance,
            chromatic: s.chromatic,
        })
    }

    fn phong(&self, s: PhongSection) -> Result<PhongSettings, SceneError> {
        Ok(PhongSettings {
            ambient: self.non_negative("phong.ambient", s.ambient)?,
            diffuse: self.non_negative("phong.diffuse", s.diffuse)?,
            specular: self.non_negative("phong.specular", s.specular)?,
            shininess: self.non_negative("phong.shininess", s.shininess)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::with_suggestion;

    #[test]
    fn unknown_fields_get_the_nearest_known_one() {
        let m = "unknown field `intensityy`, expected one of `type`, `direction`, `intensity`";
        assert_eq!(with_suggestion(m), format!("{m} (did you mean `intensity`?)"));
        let far = "unknown field `zzz`, expected one of `type`, `direction`";
        assert_eq!(with_suggestion(far), far);
        let other = "invalid type: string \"abc\", expected f32";
        assert_eq!(with_suggestion(other), "invalid type: string \"abc\", expected a number");
    }
}
