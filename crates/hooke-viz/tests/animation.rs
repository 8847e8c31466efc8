//! GIF animations decode with the right frames, loop, size and delay.

use std::path::Path;

use gif::{ColorOutput, DecodeOptions, Repeat};
use hooke_viz::{AnimationWriter, MAX_GIF_FRAMES, MAX_GIF_WIDTH, OutputError, Pixmap};
use tiny_skia::Color;

fn solid(width: u32, height: u32, shade: u8) -> Pixmap {
    let mut pixmap = Pixmap::new(width, height).unwrap();
    pixmap.fill(Color::from_rgba8(shade, 255 - shade, 128, 255));
    pixmap
}

struct Decoded {
    size: (u16, u16),
    repeat: Repeat,
    delays: Vec<u16>,
    first_pixel: [u8; 4],
}

fn decode(path: &Path) -> Decoded {
    let mut options = DecodeOptions::new();
    options.set_color_output(ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(path).unwrap())
        .unwrap();
    let mut delays = Vec::new();
    let mut first_pixel = None;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        delays.push(frame.delay);
        first_pixel.get_or_insert([
            frame.buffer[0],
            frame.buffer[1],
            frame.buffer[2],
            frame.buffer[3],
        ]);
    }
    Decoded {
        size: (decoder.width(), decoder.height()),
        repeat: decoder.repeat(),
        delays,
        first_pixel: first_pixel.unwrap(),
    }
}

#[test]
fn every_frame_is_written_when_under_the_cap() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("animation.gif");
    let mut writer = AnimationWriter::new(&path, 64, 48, 25.0, 12).unwrap();
    for i in 0..12 {
        writer.push(&solid(64, 48, i * 20)).unwrap();
    }
    assert_eq!(writer.finish().unwrap(), 12);

    let gif = decode(&path);
    assert_eq!(gif.size, (64, 48));
    assert_eq!(gif.repeat, Repeat::Infinite);
    assert_eq!(gif.delays, vec![4; 12], "25 fps is 4 centiseconds a frame");
    let [r, g, b, a] = gif.first_pixel;
    assert!(r < 8 && g > 247 && b.abs_diff(128) < 8 && a == 255);
}

#[test]
fn long_runs_are_subsampled_to_the_cap_and_keep_real_time() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("long.gif");
    let frames = 2 * MAX_GIF_FRAMES + 10;
    let mut writer = AnimationWriter::new(&path, 16, 16, 60.0, frames).unwrap();
    assert_eq!(writer.stride(), 3);
    let picture = solid(16, 16, 0);
    for _ in 0..frames {
        writer.push(&picture).unwrap();
    }
    let written = writer.finish().unwrap();
    assert_eq!(written, frames.div_ceil(3));
    assert!(written <= MAX_GIF_FRAMES);

    let gif = decode(&path);
    assert_eq!(gif.delays.len(), written);
    assert!(gif.delays.iter().all(|&d| d == 5), "3 frames at 60 fps");
}

#[test]
fn wide_pictures_are_scaled_down() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wide.gif");
    let mut writer = AnimationWriter::new(&path, 960, 540, 30.0, 1).unwrap();
    assert_eq!(writer.gif_size(), (MAX_GIF_WIDTH as u16, 270));
    writer.push(&solid(960, 540, 200)).unwrap();
    writer.finish().unwrap();
    let gif = decode(&path);
    assert_eq!(gif.size, (480, 270));
    assert_eq!(gif.delays, vec![3]);
    let [r, g, _, _] = gif.first_pixel;
    assert!(r.abs_diff(200) < 8 && g.abs_diff(55) < 8);
}

#[test]
fn errors_are_typed_and_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let nowhere = dir.path().join("gone").join("animation.gif");
    let err = AnimationWriter::new(&nowhere, 8, 8, 30.0, 1).unwrap_err();
    assert!(matches!(&err, OutputError::Create { path, .. } if *path == nowhere));
    assert!(err.to_string().contains("gone"));

    let path = dir.path().join("animation.gif");
    assert!(matches!(
        AnimationWriter::new(&path, 8, 8, 0.0, 1),
        Err(OutputError::FrameRate { .. })
    ));
    assert!(matches!(
        AnimationWriter::new(&path, 0, 8, 30.0, 1),
        Err(OutputError::ImageSize { .. })
    ));

    let mut writer = AnimationWriter::new(&path, 8, 8, 30.0, 1).unwrap();
    assert!(matches!(
        writer.push(&solid(8, 9, 0)),
        Err(OutputError::FrameSize {
            found_height: 9,
            ..
        })
    ));
    assert!(matches!(
        writer.finish(),
        Err(OutputError::EmptyAnimation { path: p }) if p == path
    ));
}
