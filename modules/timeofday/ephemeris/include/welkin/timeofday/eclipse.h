// How much of the sun's disc the moon leaves visible.
#pragma once

namespace welkin::timeofday {

// Fraction of the solar disc's AREA left uncovered by the lunar disc, in [0, 1], from the exact
// area of overlap of two circles: 1 apart, 1 - (rm/rs)^2 when annular, 0 when total. Radii and
// centre separation share one angular unit and should be topocentric (the moon's ~1 degree
// parallax moves eclipses by thousands of km). Throws std::invalid_argument for a non-finite or
// negative input or a zero sun radius.
double sun_visible_fraction(double sun_angular_radius, double moon_angular_radius,
                            double separation);

// Fraction of the solar FLUX left uncovered, with the linear limb-darkening law
// I(mu) / I(1) = 1 - u (1 - mu), mu the cosine of the emission angle. u = 0 gives the area
// fraction; u ~ 0.6 matches the visible sun. Integrated over rings of the solar disc to ~1e-9.
// Throws std::invalid_argument as above or for u outside [0, 1].
double sun_visible_flux_fraction(double sun_angular_radius, double moon_angular_radius,
                                 double separation, double limb_darkening_u);

}  // namespace welkin::timeofday
