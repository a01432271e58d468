// Blackbody colour and radiance (see blackbody.h). The colour-matching data are the CIE 1931
// 2-degree standard observer's tabulated values (CIE 015:2018, 360-830 nm at 5 nm).
#include "media/blackbody.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace caligo {
namespace {

// SI constants (CODATA 2018; h, c and k are exact by definition of the SI).
constexpr double kPlanck = 6.62607015e-34;           // J s
constexpr double kLightSpeed = 2.99792458e8;         // m/s
constexpr double kBoltzmann = 1.380649e-23;          // J/K
constexpr double kStefanBoltzmann = 5.670374419e-8;  // W m^-2 K^-4
// Planck's second radiation constant hc/k, in m K.
constexpr double kC2 = kPlanck * kLightSpeed / kBoltzmann;

constexpr double kFirstWavelengthNm = 360.0;
constexpr double kWavelengthStepNm = 5.0;

// x-bar, y-bar, z-bar of the CIE 1931 2-degree observer, 360 to 830 nm every 5 nm.
constexpr double kCie1931[][3] = {
    {0.0001299, 3.917e-06, 0.0006061},    // 360 nm
    {0.0002321, 6.965e-06, 0.001086},     // 365 nm
    {0.0004149, 1.239e-05, 0.001946},     // 370 nm
    {0.0007416, 2.202e-05, 0.003486},     // 375 nm
    {0.001368, 3.9e-05, 0.006450001},     // 380 nm
    {0.002236, 6.4e-05, 0.01054999},      // 385 nm
    {0.004243, 0.00012, 0.02005001},      // 390 nm
    {0.00765, 0.000217, 0.03621},         // 395 nm
    {0.01431, 0.000396, 0.06785001},      // 400 nm
    {0.02319, 0.00064, 0.1102},           // 405 nm
    {0.04351, 0.00121, 0.2074},           // 410 nm
    {0.07763, 0.00218, 0.3713},           // 415 nm
    {0.13438, 0.004, 0.6456},             // 420 nm
    {0.21477, 0.0073, 1.03905},           // 425 nm
    {0.2839, 0.0116, 1.3856},             // 430 nm
    {0.3285, 0.01684, 1.62296},           // 435 nm
    {0.34828, 0.023, 1.74706},            // 440 nm
    {0.34806, 0.0298, 1.7826},            // 445 nm
    {0.3362, 0.038, 1.77211},             // 450 nm
    {0.3187, 0.048, 1.7441},              // 455 nm
    {0.2908, 0.06, 1.6692},               // 460 nm
    {0.2511, 0.0739, 1.5281},             // 465 nm
    {0.19536, 0.09098, 1.28764},          // 470 nm
    {0.1421, 0.1126, 1.0419},             // 475 nm
    {0.09564, 0.13902, 0.8129501},        // 480 nm
    {0.05795001, 0.1693, 0.6162},         // 485 nm
    {0.03201, 0.20802, 0.46518},          // 490 nm
    {0.0147, 0.2586, 0.3533},             // 495 nm
    {0.0049, 0.323, 0.272},               // 500 nm
    {0.0024, 0.4073, 0.2123},             // 505 nm
    {0.0093, 0.503, 0.1582},              // 510 nm
    {0.0291, 0.6082, 0.1117},             // 515 nm
    {0.06327, 0.71, 0.07824999},          // 520 nm
    {0.1096, 0.7932, 0.05725001},         // 525 nm
    {0.1655, 0.862, 0.04216},             // 530 nm
    {0.2257499, 0.9148501, 0.02984},      // 535 nm
    {0.2904, 0.954, 0.0203},              // 540 nm
    {0.3597, 0.9803, 0.0134},             // 545 nm
    {0.4334499, 0.9949501, 0.008749999},  // 550 nm
    {0.5120501, 1.0, 0.005749999},        // 555 nm
    {0.5945, 0.995, 0.0039},              // 560 nm
    {0.6784, 0.9786, 0.002749999},        // 565 nm
    {0.7621, 0.952, 0.0021},              // 570 nm
    {0.8425, 0.9154, 0.0018},             // 575 nm
    {0.9163, 0.87, 0.001650001},          // 580 nm
    {0.9786, 0.8163, 0.0014},             // 585 nm
    {1.0263, 0.757, 0.0011},              // 590 nm
    {1.0567, 0.6949, 0.001},              // 595 nm
    {1.0622, 0.631, 0.0008},              // 600 nm
    {1.0456, 0.5668, 0.0006},             // 605 nm
    {1.0026, 0.503, 0.00034},             // 610 nm
    {0.9384, 0.4412, 0.00024},            // 615 nm
    {0.8544499, 0.381, 0.00019},          // 620 nm
    {0.7514, 0.321, 0.0001},              // 625 nm
    {0.6424, 0.265, 4.999999e-05},        // 630 nm
    {0.5419, 0.217, 3e-05},               // 635 nm
    {0.4479, 0.175, 2e-05},               // 640 nm
    {0.3608, 0.1382, 1e-05},              // 645 nm
    {0.2835, 0.107, 0.0},                 // 650 nm
    {0.2187, 0.0816, 0.0},                // 655 nm
    {0.1649, 0.061, 0.0},                 // 660 nm
    {0.1212, 0.04458, 0.0},               // 665 nm
    {0.0874, 0.032, 0.0},                 // 670 nm
    {0.0636, 0.0232, 0.0},                // 675 nm
    {0.04677, 0.017, 0.0},                // 680 nm
    {0.0329, 0.01192, 0.0},               // 685 nm
    {0.0227, 0.00821, 0.0},               // 690 nm
    {0.01584, 0.005723, 0.0},             // 695 nm
    {0.01135916, 0.004102, 0.0},          // 700 nm
    {0.008110916, 0.002929, 0.0},         // 705 nm
    {0.005790346, 0.002091, 0.0},         // 710 nm
    {0.004109457, 0.001484, 0.0},         // 715 nm
    {0.002899327, 0.001047, 0.0},         // 720 nm
    {0.00204919, 0.00074, 0.0},           // 725 nm
    {0.001439971, 0.00052, 0.0},          // 730 nm
    {0.0009999493, 0.0003611, 0.0},       // 735 nm
    {0.0006900786, 0.0002492, 0.0},       // 740 nm
    {0.0004760213, 0.0001719, 0.0},       // 745 nm
    {0.0003323011, 0.00012, 0.0},         // 750 nm
    {0.0002348261, 8.48e-05, 0.0},        // 755 nm
    {0.0001661505, 6e-05, 0.0},           // 760 nm
    {0.000117413, 4.24e-05, 0.0},         // 765 nm
    {8.307527e-05, 3e-05, 0.0},           // 770 nm
    {5.870652e-05, 2.12e-05, 0.0},        // 775 nm
    {4.150994e-05, 1.499e-05, 0.0},       // 780 nm
    {2.935326e-05, 1.06e-05, 0.0},        // 785 nm
    {2.067383e-05, 7.4657e-06, 0.0},      // 790 nm
    {1.455977e-05, 5.2578e-06, 0.0},      // 795 nm
    {1.025398e-05, 3.7029e-06, 0.0},      // 800 nm
    {7.221456e-06, 2.6078e-06, 0.0},      // 805 nm
    {5.085868e-06, 1.8366e-06, 0.0},      // 810 nm
    {3.581652e-06, 1.2934e-06, 0.0},      // 815 nm
    {2.522525e-06, 9.1093e-07, 0.0},      // 820 nm
    {1.776509e-06, 6.4153e-07, 0.0},      // 825 nm
    {1.251141e-06, 4.5181e-07, 0.0},      // 830 nm
};
constexpr int kCieSamples = sizeof(kCie1931) / sizeof(kCie1931[0]);
static_assert(kCieSamples == 95, "360..830 nm at 5 nm");

// Planck's law up to a factor independent of wavelength, written in inverse temperature so
// that 1/T = 0 (T = infinity) is its Rayleigh-Jeans limit rather than 0/0:
// B(lambda, T) * c2 / (2 h c^2 T) = c2 (1/T) / (lambda^5 expm1(c2 / (lambda T))).
double relative_planck(double wavelength_m, double inverse_kelvin) {
  const double l5 = std::pow(wavelength_m, 5);
  if (inverse_kelvin == 0.0) return 1.0 / (l5 / wavelength_m);
  return kC2 * inverse_kelvin / (l5 * std::expm1(kC2 * inverse_kelvin / wavelength_m));
}

Xyz xyz_from_inverse_temperature(double inverse_kelvin) {
  Xyz sum;
  for (int i = 0; i < kCieSamples; ++i) {
    const double wavelength_m = (kFirstWavelengthNm + kWavelengthStepNm * i) * 1e-9;
    const double b = relative_planck(wavelength_m, inverse_kelvin);
    sum.x += b * kCie1931[i][0];
    sum.y += b * kCie1931[i][1];
    sum.z += b * kCie1931[i][2];
  }
  // The wavelength step and Planck's prefactor cancel in the normalisation.
  return {sum.x / sum.y, 1.0, sum.z / sum.y};
}

RGB clamp_and_normalise(RGB rgb) {
  rgb = RGB(std::max(rgb.r, 0.0f), std::max(rgb.g, 0.0f), std::max(rgb.b, 0.0f));
  const float y = rgb.luminance();
  return y > 0.0f ? rgb / y : RGB(0.0f);
}

// The table: uniform in inverse temperature from 1/T = 0 to 1/kTableMinKelvin. Colour is
// a smooth function of 1/T (Planck's law depends on lambda * T only through c2 / (lambda T)),
// so uniform steps in 1/T spend nodes where the colour changes.
constexpr float kTableMinKelvin = 500.0f;
constexpr int kTableSize = 1024;

const std::array<RGB, kTableSize>& color_table() {
  static const std::array<RGB, kTableSize> table = [] {
    std::array<RGB, kTableSize> t;
    for (int i = 0; i < kTableSize; ++i) {
      const double inverse_kelvin = double(i) / (kTableSize - 1) / kTableMinKelvin;
      t[i] = clamp_and_normalise(xyz_to_linear_rec709(xyz_from_inverse_temperature(inverse_kelvin)));
    }
    return t;
  }();
  return table;
}

}  // namespace

double planck_spectral_radiance(double wavelength_m, double kelvin) {
  const double l5 = std::pow(wavelength_m, 5);
  return 2.0 * kPlanck * kLightSpeed * kLightSpeed / (l5 * std::expm1(kC2 / (wavelength_m * kelvin)));
}

Xyz blackbody_xyz(double kelvin) { return xyz_from_inverse_temperature(1.0 / kelvin); }

RGB xyz_to_linear_rec709(const Xyz& c) {
  // Rec.709 primaries and D65 white (x, y) = (0.3127, 0.3290), as in IEC 61966-2-1.
  return RGB(float(3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z),
             float(-0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z),
             float(0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z));
}

Xyz rec709_to_xyz(RGB c) {
  return {0.4124564 * c.r + 0.3575761 * c.g + 0.1804375 * c.b,
          0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b,
          0.0193339 * c.r + 0.1191920 * c.g + 0.9503041 * c.b};
}

RGB blackbody_color_direct(double kelvin) {
  return clamp_and_normalise(xyz_to_linear_rec709(blackbody_xyz(kelvin)));
}

RGB blackbody_color(float kelvin) {
  if (!(kelvin > 0.0f)) return RGB(0.0f);  // also NaN
  const auto& table = color_table();
  const float u = (kTableMinKelvin / kelvin) * (kTableSize - 1);  // 0 at T = infinity
  if (!(u < kTableSize - 1)) return table[kTableSize - 1];
  const int i = int(u);
  const float f = u - float(i);
  return table[i] * (1.0f - f) + table[i + 1] * f;
}

float blackbody_exitance_radiance(float kelvin) {
  if (!(kelvin > 0.0f)) return 0.0f;
  const double t2 = double(kelvin) * double(kelvin);
  return float(kStefanBoltzmann * t2 * t2 / std::numbers::pi);
}

}  // namespace caligo
