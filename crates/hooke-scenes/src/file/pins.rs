//! `pins` and `moving_pins`: particles named by index or, on cloth and
//! ropes, by name, pinned in place or along a scripted path.

use hooke_core::{Path, SystemBuilder};
use toml::Spanned;

use super::bodies::{At, Built, PinNames};
use super::error::{SceneFileError, Source};
use super::schema::PinRef;
use super::values::{key, path};
use crate::grid::Pin;
use crate::{Corner, Edge, Placement};

/// The cloth pin names and what they pin.
const CLOTH_NAMES: [(&str, Pin); 8] = [
    ("top-left", Pin::Corner(Corner::TopLeft)),
    ("top-right", Pin::Corner(Corner::TopRight)),
    ("bottom-left", Pin::Corner(Corner::BottomLeft)),
    ("bottom-right", Pin::Corner(Corner::BottomRight)),
    ("top", Pin::Edge(Edge::Top)),
    ("bottom", Pin::Edge(Edge::Bottom)),
    ("left", Pin::Edge(Edge::Left)),
    ("right", Pin::Edge(Edge::Right)),
];

/// The body-local particles `pin` names.
fn resolve(
    src: &Source<'_>,
    pin: &Spanned<PinRef>,
    names: PinNames,
    particles: usize,
    key: &str,
) -> Result<Vec<usize>, SceneFileError> {
    let expected_name = match names {
        PinNames::Cloth { .. } => {
            "a particle index or one of \"top-left\", \"top-right\", \"bottom-left\", \
             \"bottom-right\", \"top\", \"bottom\", \"left\", \"right\""
        }
        PinNames::Rope { .. } => "a particle index, \"start\" or \"end\"",
        PinNames::None => "a particle index (this body has no pin names)",
    };
    match (pin.get_ref(), names) {
        (&PinRef::Index(i), _) if i < particles => Ok(vec![i]),
        (PinRef::Index(_), _) => Err(src.invalid(
            pin.span(),
            key,
            pin.get_ref(),
            format!("a particle index below {particles}, the body's particle count"),
        )),
        (PinRef::Name(name), PinNames::Cloth { columns, rows }) => CLOTH_NAMES
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.particles(columns, rows))
            .ok_or_else(|| src.invalid(pin.span(), key, pin.get_ref(), expected_name)),
        (PinRef::Name(name), PinNames::Rope { segments }) => match name.as_str() {
            "start" => Ok(vec![0]),
            "end" => Ok(vec![segments]),
            _ => Err(src.invalid(pin.span(), key, pin.get_ref(), expected_name)),
        },
        (PinRef::Name(_), PinNames::None) => {
            Err(src.invalid(pin.span(), key, pin.get_ref(), expected_name))
        }
    }
}

/// Pins the body's `pins` and `moving_pins`, placed at `placement`.
pub(crate) fn add_pins(
    src: &Source<'_>,
    built: &Built,
    placement: Placement,
    builder: &mut SystemBuilder,
    at: &At,
) -> Result<(), SceneFileError> {
    let particles = placement.count;
    for (n, pin) in built.common.pins.iter().enumerate() {
        let pin_key = format!("{}.pins[{n}]", at.key);
        for p in resolve(src, pin, built.names, particles, &pin_key)? {
            builder.pin(placement.first + p);
        }
    }
    for (n, moving) in built.common.moving_pins.iter().enumerate() {
        let pin_key = format!("{}.moving_pins[{n}]", at.key);
        let m = moving.get_ref();
        let motion = path(src, m.velocity.as_ref(), m.keyframes.as_ref(), &pin_key)?;
        if motion == Path::Fixed {
            return Err(src.invalid(
                moving.span(),
                pin_key,
                "neither `velocity` nor `keyframes`",
                "`velocity = [x, y, z]` (m/s) or `keyframes = [[t, x, y, z], …]`",
            ));
        }
        let particle_key = key(&pin_key, "particle");
        for p in resolve(src, &m.particle, built.names, particles, &particle_key)? {
            builder.pin_moving(placement.first + p, motion.clone());
        }
    }
    Ok(())
}
