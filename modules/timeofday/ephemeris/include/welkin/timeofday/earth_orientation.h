// Earth's orientation at an instant: nutation, obliquity and sidereal time, shared by the sun and
// the moon so both are seen through the same equator and the same rotation.
#pragma once

namespace welkin::timeofday {

// The five Delaunay-type arguments of the nutation series, in degrees, not reduced to [0, 360)
// (NREL SPA eqs. 15-19, the X0..X4 of the paper; Meeus ch. 22).
struct LunisolarArguments {
  double moon_mean_elongation_deg = 0.0;       // D, X0
  double sun_mean_anomaly_deg = 0.0;           // M, X1
  double moon_mean_anomaly_deg = 0.0;          // M', X2
  double moon_argument_of_latitude_deg = 0.0;  // F, X3
  double moon_ascending_node_deg = 0.0;        // Omega, X4
};

// Nutation in longitude (Delta-psi) and in obliquity (Delta-epsilon), degrees.
struct Nutation {
  double longitude_deg = 0.0;
  double obliquity_deg = 0.0;
};

// The arguments at `jce` Julian ephemeris centuries since J2000.0.
LunisolarArguments lunisolar_arguments(double jce);

// IAU 1980 nutation from the 63-term series of the SPA paper (Table A4.3; Meeus Table 22.A).
Nutation nutation(double jce);

// Mean obliquity of the ecliptic in arc-seconds (Laskar 1986, SPA eq. 24; Meeus eq. 22.3): 0.01"
// from AD 1000 to 3000, a few arc-seconds at +/-10 000 years (|jme| < 10).
double mean_obliquity_arcsec(double jme);

// Greenwich mean sidereal time in degrees [0, 360) for a Julian Day in UT (Meeus eq. 12.4).
double mean_sidereal_time_deg(double jd_ut);

// Everything about Earth's orientation that both bodies need, computed once per instant.
struct EarthOrientation {
  double jd_ut = 0.0;      // Julian Day, UT
  double delta_t_s = 0.0;  // TT - UT
  double jde = 0.0;        // Julian Ephemeris Day, TT
  double jc = 0.0;         // Julian centuries (UT) since J2000.0
  double jce = 0.0;        // Julian ephemeris centuries (TT) since J2000.0
  double jme = 0.0;        // Julian ephemeris millennia (TT) since J2000.0
  LunisolarArguments arguments;
  Nutation nutation;
  double mean_obliquity_deg = 0.0;
  double true_obliquity_deg = 0.0;          // mean + nutation in obliquity
  double mean_sidereal_time_deg = 0.0;      // nu0, Greenwich
  double apparent_sidereal_time_deg = 0.0;  // nu, Greenwich, includes the equation of equinoxes
};

// Earth's orientation at `jd_ut` (UT) with the given Delta-T. Inputs are not range-checked here:
// compute_sky and solar_position do that.
EarthOrientation earth_orientation(double jd_ut, double delta_t_s);

}  // namespace welkin::timeofday
