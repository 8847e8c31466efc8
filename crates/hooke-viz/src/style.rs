//! [`Style`]: the colours, light and line width of a picture.

/// An sRGB colour, 8 bits a channel.
pub type Rgb = [u8; 3];

/// Colours, light and line width of a picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Style {
    /// Background at the top of the image, blending into `background_bottom`.
    pub background_top: Rgb,
    /// Background at the bottom of the image, and the colour a floor fades
    /// into far from the scene.
    pub background_bottom: Rgb,
    /// The front of the bodies' triangles: the side their counter-clockwise
    /// normal points to (the top of a horizontal cloth).
    pub body: Rgb,
    /// The back of the bodies' triangles.
    pub body_back: Rgb,
    /// Edges of the bodies.
    pub edge: Rgb,
    /// Spheres, boxes and capsules.
    pub obstacle: Rgb,
    /// The light and the dark tiles of planes.
    pub floor: [Rgb; 2],
    /// Share of the light that reaches every surface, clamped to [0, 1].
    pub ambient: f64,
    /// How dark shadows on planes are: the share of the key light a point
    /// in full shadow loses, clamped to [0, 1] (0 draws no shadows).
    pub shadow: f64,
    /// Width of edge lines in pixels; zero, negative or NaN draws no lines.
    pub line_width: f32,
}

impl Default for Style {
    fn default() -> Self {
        Self {
            background_top: [226, 234, 244],
            background_bottom: [246, 244, 238],
            body: [222, 96, 44],
            body_back: [238, 206, 120],
            edge: [38, 44, 66],
            obstacle: [120, 142, 176],
            floor: [[238, 236, 228], [214, 211, 202]],
            ambient: 0.25,
            shadow: 0.9,
            line_width: 1.5,
        }
    }
}
