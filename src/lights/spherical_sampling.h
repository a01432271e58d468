// Uniform sampling of the solid angle that a triangle or a rectangle subtends at a point.
//
// Spherical triangles: Arvo 1995, "Stratified Sampling of Spherical Triangles" (the form of
// pbrt-v4's SampleSphericalTriangle). Spherical rectangles: Urena, Fajardo & King 2013, "An
// Area-Preserving Parametrization for Spherical Rectangles". Both map [0,1)^2 to points on
// the planar shape whose directions are uniform over its solid angle: the pdf is
// 1 / solid_angle in solid angle at the receiver.
//
// Everything is computed in double: the spherical angles of a small or distant
// shape differ from pi by little, and float loses the difference (see the thresholds in
// lights/area_light_sampling.h). Pure functions, thread-safe.
#pragma once

#include <optional>

#include "core/vec.h"

namespace caligo {

// Solid angle (sr) of the triangle (p0, p1, p2) seen from `receiver`, in [0, 2 pi], by Van
// Oosterom & Strackee (an independent formula, for tests).
double spherical_triangle_solid_angle(Vec3 receiver, Vec3 p0, Vec3 p1, Vec3 p2);

// The triangle (p0, p1, p2) seen from a receiver: the set-up of Arvo's sampler. Its
// solid_angle is alpha + beta + gamma - pi from the spherical angles, summed as a product of
// unit complex numbers (cos, sin from dot and cross products) and one atan2: well conditioned
// and with one transcendental call; 0 when the triangle is degenerate as seen from the receiver.
struct SphericalTriangle {
  double receiver[3], v0[3], v1[3], v2[3];
  double a[3], b[3], c[3];  // unit directions to the vertices
  double cos_alpha, sin_alpha, cos_ab;
  double solid_angle;
};
SphericalTriangle make_spherical_triangle(Vec3 receiver, Vec3 p0, Vec3 p1, Vec3 p2);

// A point on the triangle whose direction from the receiver is uniform over the triangle's
// solid angle; std::nullopt when it is degenerate (solid_angle 0).
std::optional<Vec3> sample_spherical_triangle(const SphericalTriangle& tri, Vec2 u);

// The rectangle corner + s edge1 + t edge2, s, t in [0, 1], seen from a receiver: the set-up
// of Urena et al.'s sampler. Requires edge1 perpendicular to edge2 (the component of edge2
// along edge1 is ignored).
struct SphericalRectangle {
  double origin[3];
  double x[3], y[3], z[3];  // unit frame: x along edge1, y along edge2, z with z0 <= 0
  double x0, x1, y0, y1, z0;  // the rectangle in that frame, relative to the receiver
  double b0, b1, cos_k, sin_k, solid_angle;  // the paper's constants; solid_angle in sr
};
SphericalRectangle make_spherical_rectangle(Vec3 receiver, Vec3 corner, Vec3 edge1, Vec3 edge2);

// A point on the rectangle, uniform in solid angle (u.x chooses the column, u.y the point
// along it, as in the paper).
Vec3 sample_spherical_rectangle(const SphericalRectangle& rect, Vec2 u);

}  // namespace caligo
