//! A pair's contact margin and slop, held to shares of its thinner body's thickness (its least
//! width, [`Body`]'s `thickness`).
//!
//! The settings' margin (5 mm: bodies closer get a contact) and slop (2 mm: how deep a resting
//! contact may stay) are lengths that suit bodies of a few centimetres and up. Wider than a
//! body, the margin reached through it: in a tower of 2 mm coins each coin got contacts with
//! the coins past its neighbours, and the tower fell; 3–10 mm bodies dropped in a bin jostled
//! at 0.13 m/s for seconds with contacts 8 mm deep. Deeper than a body, the slop let it sink
//! through what it rested on: a 0.5 mm sheet lay 1.7 mm in the floor. So each pair's margin is
//! at most a quarter of its thinner body's thickness, and its slop a tenth. A body thicker than
//! 2 cm (where both shares reach the settings' values) keeps the settings' tolerances, to the
//! bit.

use tatami_contact::{Contact, ContactSettings};

use crate::Body;

/// Most of the thinner body's thickness a pair's contact margin takes.
pub(crate) const MARGIN_SHARE_OF_THICKNESS: f64 = 0.25;

/// Most of the thinner body's thickness a pair's slop takes: a resting contact stays within a
/// tenth of what it rests on or carries.
pub(crate) const SLOP_SHARE_OF_THICKNESS: f64 = 0.1;

/// The contact margin (m) of a pair whose bodies are `thickness` thick: `margin`, at most
/// [`MARGIN_SHARE_OF_THICKNESS`] of the thinner.
pub(crate) fn pair_margin(margin: f64, thickness: [f64; 2]) -> f64 {
    margin.min(MARGIN_SHARE_OF_THICKNESS * thickness[0].min(thickness[1]))
}

/// The slop (m) of a pair whose bodies are `thickness` thick: `slop`, at most
/// [`SLOP_SHARE_OF_THICKNESS`] of the thinner.
pub(crate) fn pair_slop(slop: f64, thickness: [f64; 2]) -> f64 {
    slop.min(SLOP_SHARE_OF_THICKNESS * thickness[0].min(thickness[1]))
}

/// The contact settings of `contact`'s pair among `bodies`: `settings` with the pair's slop
/// ([`pair_slop`]).
pub(crate) fn pair_settings(
    settings: &ContactSettings,
    bodies: &[Body],
    contact: &Contact,
) -> ContactSettings {
    let thickness = [contact.body_a, contact.body_b].map(|id| bodies[id.0].thickness);
    ContactSettings {
        slop: pair_slop(settings.slop, thickness),
        ..*settings
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bodies thicker than 2 cm keep the settings' tolerances exactly; thinner ones get a
    /// quarter (margin) and a tenth (slop) of the thinner body's thickness.
    #[test]
    fn tolerances_follow_the_thinner_body_below_two_centimetres() {
        let (margin, slop) = (0.005, 0.002);
        for thick in [[0.02, 1.0], [3.0, f64::INFINITY], [0.5, 0.021]] {
            assert_eq!(pair_margin(margin, thick).to_bits(), margin.to_bits());
            assert_eq!(pair_slop(slop, thick).to_bits(), slop.to_bits());
        }
        assert!((pair_margin(margin, [0.004, 0.01]) - 0.001).abs() < 1e-18);
        assert!((pair_slop(slop, [1.0, 0.0005]) - 0.00005).abs() < 1e-18);
    }
}
