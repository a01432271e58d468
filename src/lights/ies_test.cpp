// IES LM-63 parsing: tables, symmetry, interpolation, the sphere mean, and broken files.
#include "lights/ies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/math.h"

namespace caligo {
namespace {

// A type C file: 1 lamp, 1000 lm, multiplier 2, vertical and horizontal tables, watts.
std::string lm63(const std::string& vertical, const std::string& horizontal, int nv, int nh,
                 const std::string& candela, const std::string& header = "IESNA:LM-63-2002\n[TEST] x\n",
                 const std::string& tilt = "TILT=NONE\n") {
  return header + tilt + "1 1000 2 " + std::to_string(nv) + " " + std::to_string(nh) +
         " 1 2 0 0 0\n1.0 1.0 100\n" + vertical + "\n" + horizontal + "\n" + candela + "\n";
}

// Rotationally symmetric, 0..180 degrees in 3 steps: candela 100, 50, 0 (times 2).
const std::string kSymmetric = lm63("0 90 180", "0", 3, 1, "100 50 0");

std::string error_of(const std::string& text) {
  try {
    IesProfile::parse(text, "lamp.ies");
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "lamp.ies");
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}

TEST(IesProfile, RotationallySymmetricTableIsNormalisedAndInterpolated) {
  const IesProfile p = IesProfile::parse(kSymmetric, "lamp.ies");
  EXPECT_FLOAT_EQ(p.evaluate(0.0f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(p.evaluate(radians(90.0f), 1.0f), 0.5f);
  EXPECT_NEAR(p.evaluate(radians(45.0f), 2.0f), 0.75f, 1e-5f);  // linear in angle
  EXPECT_NEAR(p.evaluate(radians(135.0f), 4.0f), 0.25f, 1e-5f);
  EXPECT_FLOAT_EQ(p.evaluate(radians(180.0f), 0.0f), 0.0f);
}

// (1/4pi) * integral of (1 - theta/pi) dw = (1/2) * integral_0^pi (1 - theta/pi) sin theta dtheta = 1/2.
TEST(IesProfile, MeanOverTheSphereMatchesTheAnalyticIntegral) {
  const IesProfile p = IesProfile::parse(kSymmetric, "lamp.ies");
  EXPECT_NEAR(p.mean(), 0.5f, 1e-6f);  // exact in theta: float rounding only
  // A constant profile has mean 1; one lit only below the horizon (vertical 0..90) has mean 1/2.
  EXPECT_NEAR(IesProfile::parse(lm63("0 180", "0", 2, 1, "7 7"), "a.ies").mean(), 1.0f, 1e-6f);
  EXPECT_NEAR(IesProfile::parse(lm63("0 90", "0", 2, 1, "7 7"), "a.ies").mean(), 0.5f, 1e-6f);
}

// evaluate() integrated over the sphere by brute force: a midpoint rule in theta fine enough to
// resolve a one-degree beam (error ~1e-7 of the mean) and `n_phi` horizontal angles.
double brute_mean(const IesProfile& p, int n_theta, int n_phi) {
  double sum = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = kPi * (i + 0.5) / n_theta;
    for (int j = 0; j < n_phi; ++j)
      sum += p.evaluate(float(theta), float(2.0 * kPi * (j + 0.5) / n_phi)) * std::sin(theta);
  }
  return sum * (kPi / n_theta) * (2.0 * kPi / n_phi) / (4.0 * kPi);
}

// A pencil beam: full intensity to 1 degree, fading out by 2. The former rule put its first
// sample at 5.07 degrees, found a mean of 0, and the light was never chosen.
TEST(IesProfile, PencilBeamsHaveTheirPower) {
  const IesProfile p = IesProfile::parse(lm63("0 1 2 180", "0", 4, 1, "900 900 0 0"), "pencil.ies");
  const double expected = brute_mean(p, 200000, 1);
  EXPECT_GT(expected, 1e-5);
  EXPECT_NEAR(p.mean(), expected, 1e-4 * expected);
  // With horizontal structure too (quadrant symmetry, 0..90): the midpoint rule in phi is
  // exact for tables linear in phi over whole 128ths of the circle, close otherwise.
  const IesProfile q = IesProfile::parse(lm63("0 1 3 180", "0 45 90", 4, 3, "500 400 0 0 800 800 0 0 100 50 0 0"),
                                         "quad.ies");
  const double expected_q = brute_mean(q, 20000, 720);
  EXPECT_NEAR(q.mean(), expected_q, 1e-3 * expected_q);
}

TEST(IesProfile, OutsideTheMeasuredVerticalRangeIsDark) {
  const IesProfile p = IesProfile::parse(lm63("0 90", "0", 2, 1, "10 10"), "a.ies");
  EXPECT_FLOAT_EQ(p.evaluate(radians(80.0f), 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(p.evaluate(radians(100.0f), 0.0f), 0.0f);
}

// Horizontal tables 0..90 (quadrant), 0..180 (bilateral) and 0..360 (full), with candela
// growing with the horizontal angle so the folding is visible.
TEST(IesProfile, HorizontalSymmetriesFoldTheAngle) {
  const IesProfile quad = IesProfile::parse(lm63("0 180", "0 90", 2, 2, "10 10 20 20"), "q.ies");
  EXPECT_FLOAT_EQ(quad.evaluate(0.5f, radians(90.0f)), 1.0f);
  EXPECT_FLOAT_EQ(quad.evaluate(0.5f, radians(180.0f)), 0.5f);      // mirrors to 0
  EXPECT_FLOAT_EQ(quad.evaluate(0.5f, radians(270.0f)), 1.0f);      // mirrors to 90
  EXPECT_NEAR(quad.evaluate(0.5f, radians(315.0f)), 0.75f, 1e-5f);  // mirrors to 45

  const IesProfile half = IesProfile::parse(lm63("0 180", "0 90 180", 2, 3, "10 10 20 20 40 40"), "h.ies");
  EXPECT_FLOAT_EQ(half.evaluate(0.5f, radians(180.0f)), 1.0f);
  EXPECT_FLOAT_EQ(half.evaluate(0.5f, radians(270.0f)), 0.5f);      // mirrors to 90
  EXPECT_NEAR(half.evaluate(0.5f, radians(225.0f)), 0.75f, 1e-5f);  // mirrors to 135

  const IesProfile full =
      IesProfile::parse(lm63("0 180", "0 90 180 270 360", 2, 5, "10 10 20 20 30 30 40 40 10 10"), "f.ies");
  EXPECT_FLOAT_EQ(full.evaluate(0.5f, radians(270.0f)), 1.0f);
  EXPECT_NEAR(full.evaluate(0.5f, radians(315.0f)), 0.625f, 1e-5f);  // between 40 and 10
  EXPECT_NEAR(full.evaluate(0.5f, radians(-45.0f)), 0.625f, 1e-5f);  // wraps
}

TEST(IesProfile, OlderFilesWithoutKeywordsAndCommaSeparatedValuesParse) {
  const IesProfile p = IesProfile::parse(
      lm63("0, 90, 180", "0", 3, 1, "100, 50, 0", "some 1986 header\nmore text\n"), "old.ies");
  EXPECT_FLOAT_EQ(p.evaluate(radians(90.0f), 0.0f), 0.5f);
}

TEST(IesProfile, BrokenFilesGiveErrorsThatSayWhatIsWrong) {
  EXPECT_NE(error_of(lm63("0 90 180", "0", 3, 1, "100 50 0", "IESNA:LM-63-2002\n", "")).find("TILT"),
            std::string::npos);
  EXPECT_NE(
      error_of(lm63("0 90 180", "0", 3, 1, "100 50 0", "IESNA\n", "TILT=INCLUDE\n")).find("TILT=INCLUDE"),
      std::string::npos);
  EXPECT_NE(
      error_of(lm63("0 90 180", "0", 3, 1, "100 50 0", "IESNA\n", "TILT=lamp.tlt\n")).find("not supported"),
      std::string::npos);
  // Wrong counts: one candela value too many, or a table cut short.
  EXPECT_NE(error_of(lm63("0 90 180", "0", 3, 1, "100 50 0 7")).find("wrong counts"), std::string::npos);
  EXPECT_NE(error_of(lm63("0 90 180", "0", 3, 1, "100 50")).find("truncated"), std::string::npos);
  EXPECT_NE(error_of("IESNA\nTILT=NONE\n1 1000 2 3").find("truncated"), std::string::npos);
  EXPECT_NE(error_of(lm63("0 90 180", "0", 3, 1, "100 fifty 0")).find("non-numeric value 'fifty'"),
            std::string::npos);
  EXPECT_NE(error_of(lm63("0 90 180", "0", 3, 1, "100 -50 0")).find("negative candela"), std::string::npos);
  EXPECT_NE(error_of(lm63("0 90 180", "0", 3, 1, "0 0 0")).find("zero"), std::string::npos);
  EXPECT_NE(error_of(lm63("0 180 90", "0", 3, 1, "1 1 1")).find("increase"), std::string::npos);
  EXPECT_NE(error_of(lm63("0 90 180", "0 45", 3, 2, "1 1 1 1 1 1")).find("90, 180 or 360"),
            std::string::npos);
  EXPECT_NE(error_of(lm63("0 90 180", "0", 0, 1, "")).find("number of vertical angles"), std::string::npos);
  std::string type_b = lm63("0 90 180", "0", 3, 1, "1 1 1");
  type_b.replace(type_b.find(" 1 2 0 0 0"), 2, " 3");  // photometric type 3 (type A)
  EXPECT_NE(error_of(type_b).find("type C"), std::string::npos);
}

// Found by fuzz/ies_fuzz.cpp: a candela value beyond float's range (on its own, or once
// multiplied: lm63's multiplier is 2) made the peak infinite and the normalised table NaN.
TEST(IesProfile, NulBytesAreRefused) {
  std::string text = kSymmetric;
  text[text.size() / 2] = '\0';
  EXPECT_NE(error_of(text).find("NUL byte"), std::string::npos);
}

TEST(IesProfile, CandelaValuesBeyondFloatRangeAreErrorsNotNaN) {
  EXPECT_NE(error_of(lm63("0 90", "0", 2, 1, "1e39 1")).find("float range"), std::string::npos);
  EXPECT_NE(error_of(lm63("0 90", "0", 2, 1, "2e38 1")).find("float range"), std::string::npos);
  const IesProfile p = IesProfile::parse(lm63("0 90", "0", 2, 1, "1.5e38 0"), "big.ies");
  EXPECT_FLOAT_EQ(p.evaluate(0.0f, 0.0f), 1.0f);
  EXPECT_TRUE(std::isfinite(p.mean()));
}

// A header promising a 10^4 x 10^4 table is refused before the table (400 MB) is allocated.
TEST(IesProfile, TableLargerThanTheFileIsRefusedBeforeAllocating) {
  std::string vertical, horizontal;
  for (int i = 0; i < 10000; ++i) {
    vertical += std::to_string(180.0 * i / 9999) + " ";
    horizontal += std::to_string(360.0 * i / 9999) + " ";
  }
  EXPECT_NE(error_of(lm63(vertical, horizontal, 10000, 10000, "1 1")).find("needs 100000000"), std::string::npos);
}

TEST(IesProfile, MissingFileIsAnInputErrorNamingIt) {
  try {
    IesProfile::load("/nonexistent/lamp.ies");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "/nonexistent/lamp.ies");
  }
}

}  // namespace
}  // namespace caligo
