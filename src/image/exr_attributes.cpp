#include "image/exr_header_attributes.h"

#include <ImfHeader.h>
#include <ImfMatrixAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfIntAttribute.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "core/overloaded.h"

namespace caligo {
namespace {

// Set by OpenEXR from the image and its own options; never an extra attribute.
constexpr std::array<const char*, 9> kStructural = {"channels",        "compression",        "dataWindow",
                                                    "displayWindow",   "lineOrder",          "pixelAspectRatio",
                                                    "screenWindowCenter", "screenWindowWidth", "type"};

bool structural(const std::string& name) {
  return std::find(kStructural.begin(), kStructural.end(), name) != kStructural.end();
}

Imath::M44f to_imath(const Mat4& m) {
  Imath::M44f out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[c][r] = m.m[size_t(r)][size_t(c)];
  return out;
}

Mat4 from_imath(const Imath::M44f& m) {
  Mat4 out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.m[size_t(r)][size_t(c)] = m[c][r];
  return out;
}

}  // namespace

const ExrValue* find_attribute(const ExrAttributes& attributes, const std::string& name) {
  for (const ExrAttribute& a : attributes)
    if (a.name == name) return &a.value;
  return nullptr;
}

void add_attributes(Imf::Header& header, const ExrAttributes& attributes) {
  for (const ExrAttribute& a : attributes) {
    if (a.name.empty() || structural(a.name))
      throw std::invalid_argument("EXR attribute \"" + a.name + "\" is OpenEXR's own");
    std::visit(Overloaded{[&](const std::string& s) { header.insert(a.name, Imf::StringAttribute(s)); },
                          [&](int i) { header.insert(a.name, Imf::IntAttribute(i)); },
                          [&](float f) { header.insert(a.name, Imf::FloatAttribute(f)); },
                          [&](const Mat4& m) { header.insert(a.name, Imf::M44fAttribute(to_imath(m))); }},
               a.value);
  }
}

ExrAttributes attributes_of(const Imf::Header& header) {
  ExrAttributes out;
  for (auto it = header.begin(); it != header.end(); ++it) {
    const std::string name = it.name();
    if (structural(name)) continue;
    const Imf::Attribute& a = it.attribute();
    if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a)) {
      out.push_back({name, s->value()});
    } else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&a)) {
      out.push_back({name, i->value()});
    } else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a)) {
      out.push_back({name, f->value()});
    } else if (const auto* m = dynamic_cast<const Imf::M44fAttribute*>(&a)) {
      out.push_back({name, from_imath(m->value())});
    }
  }
  return out;
}

}  // namespace caligo
