// Frequency weightings of radiated power: a radiation efficiency and the A
// weighting.
//
// Radiation efficiency of a baffled circular piston of radius a in a medium of
// sound speed c (Kinsler, Frey, Coppens & Sanders, "Fundamentals of
// Acoustics", 4th ed., Wiley 2000, section 7.5: the radiation resistance
// R_r = rho c S R_1(2ka), R_1(x) = 1 - 2 J_1(x) / x):
//     sigma(f) = 1 - J_1(2ka) / (ka),   k = 2 pi f / c,
// (ka)^2 / 2 for ka << 1 (the piston radiates as a monopole), -> 1 for ka >> 1
// (the plane-wave limit that ERP assumes). Applied to ERP, sigma * ERP
// estimates the radiated sound power of a surface that moves in phase over a
// piston-sized patch; it over-estimates a surface that deforms in many
// half-waves (their volume velocities cancel).
//
// A weighting (IEC 61672-1:2013, equations E.1, E.6): the gain in dB
//     A(f) = 20 log10(R_A(f)) + 2.000,
//     R_A(f) = f4^2 f^4 / ((f^2 + f1^2) sqrt((f^2 + f2^2)(f^2 + f3^2)) (f^2 + f4^2)),
// f1 = 20.598997, f2 = 107.65265, f3 = 737.86223, f4 = 12194.217 Hz; 0 dB at
// 1 kHz, -19.1 dB at 100 Hz, -39.4 dB at 31.5 Hz.
#pragma once

#include <string>

namespace evas {

/// sigma(f) of a baffled piston of radius `radius` [m] (see above); c [m/s].
double piston_radiation_efficiency(double f_hz, double radius, double c = 343.0);

/// A-weighting gain [dB] at f [Hz] (-infinity at f = 0).
double a_weighting_db(double f_hz);

/// A radiation-efficiency model from its text: "piston:RADIUS" (RADIUS in m,
/// > 0). Throws InputError naming `who` otherwise.
struct RadiationModel {
  double radius = 0.0;  ///< [m]
  double c = 343.0;     ///< [m/s]
  double sigma(double f_hz) const { return piston_radiation_efficiency(f_hz, radius, c); }
  std::string describe() const;
};
RadiationModel parse_radiation_model(const std::string& text, const std::string& who);

}  // namespace evas
