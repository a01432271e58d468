// A photometric intensity profile read from an IES LM-63 file (1986, 1991, 1995, 2002
// variants). Only type C photometry with TILT=NONE is supported; other files are rejected
// with an InputError that names the file and the problem.
//
// Angles follow LM-63 type C: the vertical angle is measured from the photometric nadir
// (the light's axis, 0..180 degrees), the horizontal angle around it (0..360 degrees).
// Horizontal symmetry follows the last horizontal angle: a single angle (0) means
// rotational symmetry, 0..90 quadrant symmetry, 0..180 bilateral symmetry, 0..360 none.
// Values are normalised so the largest is 1; the light's own intensity sets the scale.
// Immutable after construction: safe to share between threads.
#pragma once

#include <string>
#include <vector>

namespace caligo {

class IesProfile {
 public:
  // Parses LM-63 text; `file` names the source in error messages.
  static IesProfile parse(const std::string& text, const std::string& file);
  // Reads and parses a file (InputError if it cannot be read).
  static IesProfile load(const std::string& path);
  // A profile from its table, for profiles the program makes itself (the real-time stand-in
  // of an area light: realtime/light_stand_ins.h). Angles in degrees as in a file (vertical
  // increasing from 0 or 90 to 90 or 180, horizontal from 0); values [h * vertical.size() + v],
  // non-negative, normalised here. Throws std::invalid_argument for a table a file could not hold.
  static IesProfile tabulated(std::vector<float> vertical_degrees, std::vector<float> horizontal_degrees,
                              std::vector<float> values);

  // Relative intensity in [0, 1], bilinear in the tables. Angles in radians.
  // Directions outside the measured vertical range receive 0.
  float evaluate(float vertical, float horizontal) const;
  // Mean of evaluate() over the sphere of directions: (1 / 4 pi) * integral of I dw.
  // A light of peak intensity I then emits 4 pi I mean() watts.
  float mean() const { return mean_; }

  const std::vector<float>& vertical_degrees() const { return vertical_; }
  const std::vector<float>& horizontal_degrees() const { return horizontal_; }
  // The normalised table, [h * vertical_degrees().size() + v], for lane-parallel lookups.
  const std::vector<float>& values() const { return values_; }

 private:
  IesProfile() = default;
  float fold_horizontal(float degrees) const;
  float evaluate_degrees(float vertical, float horizontal) const;
  float mean_over_sphere() const;

  std::vector<float> vertical_, horizontal_;
  std::vector<float> values_;  // [h * vertical_.size() + v], normalised to max 1
  float mean_ = 0.0f;
};

}  // namespace caligo
