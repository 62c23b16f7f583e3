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

pub fn cache_planes(scene: &Scene, settings: &IpsviSettings) -> CachePlanes {
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
