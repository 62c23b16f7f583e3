//! Where each light's illumination cache lies (the plane fitted to the volume
//! box, or with `fit_to_visible` to the box of the visible cells), and how wide
//! its texels are against the image's pixels. View samples write a texel only
//! as densely as view rays sample the volume, so their error is smallest near
//! a texel of about one pixel (docs/ipsvi.md, "The illumination cache"); the
//! width is printed with the settings so a user can size `cache_size` to it.

use super::lit_box::lit_box;
use super::settings::IpsviSettings;
use crate::render::light_space::{LightProjection, LightSpacePlane};
use crate::scene::framing::WorldBox;
use crate::scene::transfer::TransferLut;
use crate::scene::Scene;

pub struct CachePlanes {
    /// The box the planes are fitted to and the light rays are clipped to.
    pub lit: WorldBox,
    /// One per rendered light, in the scene's order.
    pub planes: Vec<LightSpacePlane>,
}

/// `settings.cache_size` must be resolved ([`IpsviSettings::sized_for`]).
pub fn cache_planes(scene: &Scene, settings: &IpsviSettings) -> CachePlanes {
    assert!(settings.cache_size != 0, "ipsvi.cache_size = 0 is resolved per image before the cache is fitted");
    let bx = scene.volume_box();
    let lit = if settings.fit_to_visible {
        lit_box(&scene.volume, &scene.transfer.bake(TransferLut::DEFAULT_SIZE), &bx)
    } else {
        WorldBox::of_volume(&bx)
    };
    let (corners, radius) = (lit.corners(), bx.half_extent.length());
    let planes = scene
        .rendered_lights()
        .iter()
        .map(|l| LightSpacePlane::fit_to(&l.kind, &corners, radius, settings.cache_size))
        .collect();
    CachePlanes { lit, planes }
}

/// The narrowest light's cache texel at the lit box's centre, in pixels of a
/// `width` x `height` image of the scene there (None without lights).
pub fn texel_pixels(scene: &Scene, settings: &IpsviSettings, width: u32, height: u32) -> Option<f32> {
    if settings.cache_size == 0 {
        return texel_pixels(scene, &settings.sized_for(scene, width, height), width, height);
    }
    let CachePlanes { lit, planes } = cache_planes(scene, settings);
    let centre = (lit.min + lit.max) * 0.5;
    let pixel = scene.camera.basis(width, height).pixel_size_at(centre, height);
    planes
        .iter()
        .map(|g| {
            let from_light = centre - g.origin;
            let world = match g.projection {
                LightProjection::Orthographic => g.texel,
                // Tangent units at the frustum's distance along its axis.
                LightProjection::Perspective => g.texel * from_light.dot(g.axis).max(0.0),
                // An angle: its arc at the centre's distance.
                LightProjection::Octahedral => g.texel * from_light.length(),
            };
            world / pixel
        })
        .reduce(f32::min)
}

/// `cache_size = 0` starts from this many texels per side (the paper's
/// Table 1 runs, and the size that serves images up to about 256 pixels).
pub const AUTO_CACHE_MIN: u32 = 256;
/// `cache_size = 0` grows the cache until a texel is at most this wide
/// (pixels at the lit box's centre): on the engine at 512x512, 2.15 px texels
/// (256) give 33.5 dB, 1.43 px (384) 37.5 dB (docs/ipsvi.md, "Default images").
pub const AUTO_TEXEL_PX: f32 = 1.5;

/// What `cache_size = 0` means for a `width` x `height` image of `scene`:
/// [`AUTO_CACHE_MIN`], or more (a multiple of 16) where its texel would be
/// wider than [`AUTO_TEXEL_PX`], never more than the image's longer side
/// (a camera close to the volume sees only part of the cache).
pub fn auto_cache_size(scene: &Scene, settings: &IpsviSettings, width: u32, height: u32) -> u32 {
    let at = |size: u32| IpsviSettings { cache_size: size, ..settings.clone() };
    let most = width.max(height).next_multiple_of(16).clamp(AUTO_CACHE_MIN, MAX_CACHE_SIZE);
    let Some(px) = texel_pixels(scene, &at(AUTO_CACHE_MIN), width, height) else { return AUTO_CACHE_MIN };
    if px <= AUTO_TEXEL_PX {
        return AUTO_CACHE_MIN;
    }
    // An orthographic or perspective texel is its side over (size - 2), an
    // octahedral one pi / size: start from the first, step while too wide.
    let needed = 2.0 + (AUTO_CACHE_MIN - 2) as f32 * px / AUTO_TEXEL_PX;
    let mut size = (needed.ceil() as u32).next_multiple_of(16).min(most);
    while size < most && texel_pixels(scene, &at(size), width, height).is_some_and(|p| p > AUTO_TEXEL_PX) {
        size += 16;
    }
    size
}

/// The largest `cache_size` a table accepts (every Vulkan device's
/// guaranteed 2D image side).
pub const MAX_CACHE_SIZE: u32 = 4096;
