//! [`AnimationWriter`]: rendered frames streamed into a looping GIF file.
//!
//! Each written frame is quantised to its own 256-colour palette (NeuQuant)
//! and appended to the file at once, so no more than one picture is held in
//! memory. To keep the file small, pictures wider than [`MAX_GIF_WIDTH`] are
//! scaled down, and of a run of `n` pictures only every `s`-th is kept, with
//! `s = ⌈n / MAX_GIF_FRAMES⌉`. Each kept frame is shown for `s / fps`
//! seconds, rounded to the GIF's centiseconds (at least 2, the shortest
//! delay browsers honour), so the animation plays in about real time.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use gif::{Encoder, EncodingError, Frame, Repeat};
use tiny_skia::{FilterQuality, Pixmap, PixmapPaint, Transform};

use crate::camera::MAX_IMAGE_SIDE;
use crate::error::OutputError;

/// Widest animation written; wider pictures are scaled down to this width.
pub const MAX_GIF_WIDTH: u32 = 480;
/// Most frames an animation keeps when told the right number of pictures.
pub const MAX_GIF_FRAMES: usize = 150;
/// NeuQuant sampling factor, 1 (best) to 30 (fastest).
const QUANTIZER_SPEED: i32 = 30;

/// A picture scaled and quantised for an animation by
/// [`AnimationWriter::encode`].
#[derive(Debug)]
pub struct EncodedFrame(Frame<'static>);

/// Writes `animation.gif`-style files one picture at a time.
pub struct AnimationWriter {
    path: PathBuf,
    encoder: Encoder<BufWriter<File>>,
    width: u32,
    height: u32,
    gif_width: u16,
    gif_height: u16,
    stride: usize,
    delay: u16,
    pushed: usize,
    written: usize,
}

impl AnimationWriter {
    /// Creates `path` for an animation of `frames` pictures of `width` x
    /// `height` pixels, rendered at `fps` pictures per second of simulated
    /// time. The animation loops forever.
    ///
    /// `frames` sets the subsampling stride; pushing more pictures than
    /// announced writes more than [`MAX_GIF_FRAMES`] frames.
    ///
    /// # Errors
    ///
    /// [`OutputError::FrameRate`] for a rate that is not positive and
    /// finite, [`OutputError::ImageSize`] for an empty or oversized picture,
    /// [`OutputError::Create`] or [`OutputError::Write`] naming `path`.
    pub fn new(
        path: &Path,
        width: u32,
        height: u32,
        fps: f64,
        frames: usize,
    ) -> Result<Self, OutputError> {
        if !(fps.is_finite() && fps > 0.0) {
            return Err(OutputError::FrameRate { fps });
        }
        if width == 0 || height == 0 || width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE {
            return Err(OutputError::ImageSize {
                width,
                height,
                limit: MAX_IMAGE_SIDE,
            });
        }
        let gif_width = width.min(MAX_GIF_WIDTH);
        let gif_height = (u64::from(height) * u64::from(gif_width))
            .div_ceil(u64::from(width))
            .max(1);
        let stride = frames.div_ceil(MAX_GIF_FRAMES).max(1);
        let delay = (100.0 * stride as f64 / fps)
            .round()
            .clamp(2.0, f64::from(u16::MAX)) as u16;
        let file = File::create(path).map_err(|source| OutputError::Create {
            path: path.to_path_buf(),
            source,
        })?;
        // Both fit: the width is at most MAX_GIF_WIDTH and the height at most
        // the picture's, itself at most MAX_IMAGE_SIDE.
        let (gif_width, gif_height) = (gif_width as u16, gif_height as u16);
        let mut encoder = Encoder::new(BufWriter::new(file), gif_width, gif_height, &[])
            .map_err(|e| encoding_error(path, e))?;
        encoder
            .set_repeat(Repeat::Infinite)
            .map_err(|e| encoding_error(path, e))?;
        Ok(Self {
            path: path.to_path_buf(),
            encoder,
            width,
            height,
            gif_width,
            gif_height,
            stride,
            delay,
            pushed: 0,
            written: 0,
        })
    }

    /// Offers the next picture; every [`stride`](Self::stride)-th one,
    /// starting with the first, is scaled, quantised and appended.
    ///
    /// # Errors
    ///
    /// As [`encode`](Self::encode) and [`push_encoded`](Self::push_encoded);
    /// a picture of the wrong size is refused even when it would be left
    /// out.
    pub fn push(&mut self, pixmap: &Pixmap) -> Result<(), OutputError> {
        self.check_size(pixmap)?;
        let keep = self.pushed % self.stride == 0;
        self.pushed += 1;
        if keep {
            let frame = self.encode(pixmap)?;
            self.push_encoded(frame)?;
        }
        Ok(())
    }

    /// Scales and quantises `pixmap` into a frame of this animation, ready
    /// for [`push_encoded`](Self::push_encoded). It takes `&self`, so
    /// several pictures can be encoded at once on several threads and then
    /// appended in order.
    ///
    /// # Errors
    ///
    /// [`OutputError::FrameSize`] for a picture of another size than
    /// announced.
    pub fn encode(&self, pixmap: &Pixmap) -> Result<EncodedFrame, OutputError> {
        self.check_size(pixmap)?;
        let mut rgba = self.scaled_rgba(pixmap).ok_or(OutputError::ImageSize {
            width: self.gif_width.into(),
            height: self.gif_height.into(),
            limit: MAX_IMAGE_SIDE,
        })?;
        let mut frame =
            Frame::from_rgba_speed(self.gif_width, self.gif_height, &mut rgba, QUANTIZER_SPEED);
        frame.delay = self.delay;
        Ok(EncodedFrame(frame))
    }

    fn check_size(&self, pixmap: &Pixmap) -> Result<(), OutputError> {
        if (pixmap.width(), pixmap.height()) == (self.width, self.height) {
            Ok(())
        } else {
            Err(OutputError::FrameSize {
                width: self.width,
                height: self.height,
                found_width: pixmap.width(),
                found_height: pixmap.height(),
            })
        }
    }

    /// Appends a frame made by [`encode`](Self::encode), whatever the
    /// stride.
    ///
    /// # Errors
    ///
    /// [`OutputError::Write`] or [`OutputError::Encode`] naming the file.
    pub fn push_encoded(&mut self, frame: EncodedFrame) -> Result<(), OutputError> {
        self.encoder
            .write_frame(&frame.0)
            .map_err(|e| encoding_error(&self.path, e))?;
        self.written += 1;
        Ok(())
    }

    /// Ends the file and returns the number of frames written.
    ///
    /// # Errors
    ///
    /// [`OutputError::EmptyAnimation`] if no picture was pushed (the file is
    /// then left without frames); [`OutputError::Write`] naming the file.
    pub fn finish(self) -> Result<usize, OutputError> {
        if self.written == 0 {
            return Err(OutputError::EmptyAnimation { path: self.path });
        }
        let write_error = |source| OutputError::Write {
            path: self.path.clone(),
            source,
        };
        let mut out = self
            .encoder
            .into_inner()
            .map_err(|e| encoding_error(&self.path, e))?;
        out.flush().map_err(write_error)?;
        Ok(self.written)
    }

    /// Every how many pushed pictures one is written.
    #[must_use]
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// How long each frame shows, in centiseconds.
    #[must_use]
    pub fn delay_centiseconds(&self) -> u16 {
        self.delay
    }

    /// Width and height of the GIF, after scaling down.
    #[must_use]
    pub fn gif_size(&self) -> (u16, u16) {
        (self.gif_width, self.gif_height)
    }

    /// `pixmap` at the GIF's size as straight (not premultiplied) RGBA
    /// bytes, or `None` if no picture of that size can be allocated.
    fn scaled_rgba(&self, pixmap: &Pixmap) -> Option<Vec<u8>> {
        let scaled;
        let source = if u32::from(self.gif_width) == self.width {
            pixmap
        } else {
            let mut target = Pixmap::new(self.gif_width.into(), self.gif_height.into())?;
            let scale = |to: u16, from: u32| f32::from(to) / from as f32;
            let paint = PixmapPaint {
                quality: FilterQuality::Bicubic,
                ..PixmapPaint::default()
            };
            let transform = Transform::from_scale(
                scale(self.gif_width, self.width),
                scale(self.gif_height, self.height),
            );
            target.draw_pixmap(0, 0, pixmap.as_ref(), &paint, transform, None);
            scaled = target;
            &scaled
        };
        Some(
            source
                .pixels()
                .iter()
                .flat_map(|p| {
                    let c = p.demultiply();
                    [c.red(), c.green(), c.blue(), c.alpha()]
                })
                .collect(),
        )
    }
}

impl std::fmt::Debug for AnimationWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AnimationWriter")
            .field("path", &self.path)
            .field("size", &(self.width, self.height))
            .field("gif_size", &(self.gif_width, self.gif_height))
            .field("stride", &self.stride)
            .field("delay", &self.delay)
            .field("pushed", &self.pushed)
            .field("written", &self.written)
            .finish_non_exhaustive()
    }
}

/// An encoder error as an [`OutputError`] naming `path`.
fn encoding_error(path: &Path, error: EncodingError) -> OutputError {
    match error {
        EncodingError::Io(source) => OutputError::Write {
            path: path.to_path_buf(),
            source,
        },
        other => OutputError::Encode {
            path: path.to_path_buf(),
            format: "GIF",
            source: Box::new(other),
        },
    }
}
