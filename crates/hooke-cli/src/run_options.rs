//! [`RunOptions`]: where a run writes and what, and the names of the files
//! it writes.

use std::path::PathBuf;

/// The file name of the run summary in the output directory.
pub const SUMMARY_FILE: &str = "summary.json";
/// The file name of the picture of the frame that shows the drape (see
/// [`run`](crate::run)).
pub const PREVIEW_FILE: &str = "preview.png";
/// The file name of the animation of the frames.
pub const ANIMATION_FILE: &str = "animation.gif";
/// The file name of the frames as one USD animation (see
/// [`hooke_viz::usd`]).
pub const USD_FILE: &str = "animation.usda";

/// Where a [`run`](crate::run) writes and what.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOptions {
    /// The output directory, created if missing.
    pub out: PathBuf,
    /// Whether to write [`ANIMATION_FILE`].
    pub gif: bool,
    /// Whether to write [`USD_FILE`].
    pub usd: bool,
    /// The simulated time, s, whose frame (the nearest written)
    /// [`PREVIEW_FILE`] shows instead of the frame of the bodies at rest;
    /// finite and not negative.
    pub preview_time: Option<f64>,
    /// Width and height of [`PREVIEW_FILE`], pixels.
    pub preview_size: (u32, u32),
    /// Width and height of the animation's frames, pixels.
    pub gif_size: (u32, u32),
}

impl RunOptions {
    /// Writes everything into `out`: a 960×720 preview, a 480×360
    /// animation and the USD animation.
    ///
    /// ```
    /// let options = hooke_cli::RunOptions::new("hooke-out");
    /// assert!(options.gif && options.usd);
    /// ```
    #[must_use]
    pub fn new(out: impl Into<PathBuf>) -> Self {
        Self {
            out: out.into(),
            gif: true,
            usd: true,
            preview_time: None,
            preview_size: (960, 720),
            gif_size: (480, 360),
        }
    }

    /// The same options with the animation written or not.
    ///
    /// ```
    /// let options = hooke_cli::RunOptions::new("hooke-out").gif(false);
    /// assert!(!options.gif);
    /// ```
    #[must_use]
    pub fn gif(self, gif: bool) -> Self {
        Self { gif, ..self }
    }

    /// The same options with the USD animation written or not.
    ///
    /// ```
    /// let options = hooke_cli::RunOptions::new("hooke-out").usd(false);
    /// assert!(!options.usd);
    /// ```
    #[must_use]
    pub fn usd(self, usd: bool) -> Self {
        Self { usd, ..self }
    }

    /// The same options with the preview showing the frame nearest the
    /// simulated time `time` in s (`None`: the frame of the bodies at
    /// rest, see [`run`](crate::run)).
    ///
    /// ```
    /// let options = hooke_cli::RunOptions::new("hooke-out").preview_time(Some(3.0));
    /// assert_eq!(options.preview_time, Some(3.0));
    /// ```
    #[must_use]
    pub fn preview_time(self, time: Option<f64>) -> Self {
        Self {
            preview_time: time,
            ..self
        }
    }
}
