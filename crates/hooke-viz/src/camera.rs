//! The perspective [`Camera`] of the renderer and the [`View`] that places it.
//!
//! The camera looks at the centre `c` of a [`Bounds`] from the direction
//! `d = (cos e sin a, sin e, cos e cos a)` (azimuth `a` about +y from +z,
//! elevation `e` above the horizontal; +y is up), with right `r = f × y`
//! and up `u = r × f` for the viewing direction `f = -d`. A point `p` with
//! camera coordinates `(x, y, z) = ((p - eye)·r, (p - eye)·u, (p - eye)·f)`
//! lands on pixel `(W/2 + F x/z, H/2 - F y/z)`, where
//! `F = (min(W, H)/2) / tan θ` and `θ` is half the field of view across the
//! shorter image side.
//!
//! The eye sits at `c + D d`, with `D` the smallest distance at which every
//! corner `k` of the box projects within the central fraction `φ` of the
//! image width and height:
//!
//! `D = maxₖ [ max(F|xₖ| / (φ W/2), F|yₖ| / (φ H/2)) - zₖ ]`,
//!
//! with `(xₖ, yₖ, zₖ)` the corner's offset from `c` along `(r, u, f)`. The
//! scene thus fills `φ` of the image along whichever side limits it.

use hooke_core::Vec3;

use crate::bounds::Bounds;
use crate::error::OutputError;

/// Largest image side the renderer accepts.
pub const MAX_IMAGE_SIDE: u32 = 16_384;

/// Where the camera looks from and how much of the picture the scene fills.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Rotation of the eye about +y, from +z towards +x, in degrees.
    pub azimuth_degrees: f64,
    /// Angle of the eye above the horizontal plane, in degrees, within
    /// (-90, 90).
    pub elevation_degrees: f64,
    /// Field of view across the shorter image side, in degrees, within
    /// (0, 180).
    pub fov_degrees: f64,
    /// Fraction of the image width or height (whichever limits) that the
    /// scene's bounding box spans, within (0, 1].
    pub fill: f64,
}

impl Default for View {
    /// Azimuth 35°, elevation 25°, a 40° field of view, 80 % fill.
    fn default() -> Self {
        Self {
            azimuth_degrees: 35.0,
            elevation_degrees: 25.0,
            fov_degrees: 40.0,
            fill: 0.8,
        }
    }
}

/// A point as seen by the camera: pixel coordinates (x right, y down) and
/// its depth along the viewing direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projected {
    /// Horizontal pixel coordinate.
    pub x: f64,
    /// Vertical pixel coordinate, growing downwards.
    pub y: f64,
    /// Distance from the eye along the viewing direction.
    pub depth: f64,
}

/// A perspective camera for an image of a given size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    eye: Vec3,
    target: Vec3,
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    focal: f64,
    radius: f64,
    near: f64,
    width: u32,
    height: u32,
}

impl Camera {
    /// A camera framing `bounds` in a `width` x `height` image as `view` says.
    ///
    /// A box of zero size is framed as a unit cube about its centre.
    ///
    /// # Errors
    ///
    /// [`OutputError::ImageSize`] for a zero side or one above
    /// [`MAX_IMAGE_SIDE`]; [`OutputError::InvalidView`] for angles or a fill
    /// out of range or bounds that are not finite.
    pub fn new(bounds: &Bounds, width: u32, height: u32, view: &View) -> Result<Self, OutputError> {
        if width == 0 || height == 0 || width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE {
            return Err(OutputError::ImageSize {
                width,
                height,
                limit: MAX_IMAGE_SIDE,
            });
        }
        let invalid = |reason| Err(OutputError::InvalidView { reason });
        // False for NaN, like every comparison.
        let within = |x: f64, low: f64, high: f64| x > low && x < high;
        if !within(view.elevation_degrees, -90.0, 90.0) || !view.azimuth_degrees.is_finite() {
            return invalid("elevation must lie strictly between -90 and 90 degrees");
        }
        if !within(view.fov_degrees, 0.0, 180.0) {
            return invalid("field of view must lie strictly between 0 and 180 degrees");
        }
        if view.fill <= 0.0 || !(..=1.0).contains(&view.fill) {
            return invalid("fill must lie in (0, 1]");
        }
        let target = bounds.center();
        let extent = (bounds.max() - bounds.min()) * 0.5;
        if !target.iter().chain(extent.iter()).all(|c| c.is_finite()) {
            return invalid("the scene bounds are not finite");
        }
        let extent = if extent.norm() > 0.0 {
            extent
        } else {
            Vec3::repeat(0.5)
        };
        let (az, el) = (
            view.azimuth_degrees.to_radians(),
            view.elevation_degrees.to_radians(),
        );
        let towards_eye = Vec3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos());
        let forward = -towards_eye;
        let right = forward.cross(&Vec3::y()).normalize();
        let up = right.cross(&forward);
        let focal =
            f64::from(width.min(height)) * 0.5 / (view.fov_degrees.to_radians() * 0.5).tan();
        let (half_w, half_h) = (
            view.fill * f64::from(width) * 0.5,
            view.fill * f64::from(height) * 0.5,
        );
        let radius = extent.norm();
        let distance = (0..8)
            .map(|k| {
                let sign = |bit: usize| if k & bit == 0 { -1.0 } else { 1.0 };
                let offset = extent.component_mul(&Vec3::new(sign(1), sign(2), sign(4)));
                let (x, y, z) = (offset.dot(&right), offset.dot(&up), offset.dot(&forward));
                let fit = (focal * x.abs() / half_w).max(focal * y.abs() / half_h) - z;
                // Keep every corner well in front of the eye.
                fit.max(0.1 * radius - z)
            })
            .fold(0.0, f64::max);
        Ok(Self {
            eye: target + towards_eye * distance,
            target,
            right,
            up,
            forward,
            focal,
            radius,
            near: distance * 1e-3,
            width,
            height,
        })
    }

    /// Projects `p` onto the image, or `None` if it is not in front of the
    /// eye (closer than a thousandth of the framing distance).
    #[must_use]
    pub fn project(&self, p: Vec3) -> Option<Projected> {
        let rel = p - self.eye;
        let depth = rel.dot(&self.forward);
        if depth < self.near {
            return None;
        }
        Some(Projected {
            x: f64::from(self.width) * 0.5 + self.focal * rel.dot(&self.right) / depth,
            y: f64::from(self.height) * 0.5 - self.focal * rel.dot(&self.up) / depth,
            depth,
        })
    }

    /// The eye position.
    #[must_use]
    pub fn eye(&self) -> Vec3 {
        self.eye
    }

    /// The point looked at, projected to the image centre.
    #[must_use]
    pub fn target(&self) -> Vec3 {
        self.target
    }

    /// Unit viewing direction, from the eye towards the target.
    #[must_use]
    pub fn forward(&self) -> Vec3 {
        self.forward
    }

    /// Unit vector pointing up in the image.
    #[must_use]
    pub fn up(&self) -> Vec3 {
        self.up
    }

    /// Unit vector pointing right in the image.
    #[must_use]
    pub fn right(&self) -> Vec3 {
        self.right
    }

    /// Focal length in pixels: a unit length at unit depth spans this many pixels.
    #[must_use]
    pub fn focal(&self) -> f64 {
        self.focal
    }

    /// Half the diagonal of the framed box: the scale of the scene.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Image width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }
}
