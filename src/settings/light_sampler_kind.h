// Which strategy next-event estimation picks a light with (lights/light_sampler.h builds them;
// PathSettings::light_sampler chooses one): plain data, so that settings need not see the lights.
#pragma once

#include "core/enum_names.h"

namespace caligo {

// kTreeFixedShare is the tree as it was before lights at infinity were weighed at the receiver
// (a fixed share by power), kept to measure against.
enum class LightSamplerKind { kUniform, kPower, kTree, kTreeFixedShare };
// --light-sampler (the checkpoint key stores the enumerator).
inline constexpr std::array<EnumName<LightSamplerKind>, 4> kLightSamplerNames{
    {{LightSamplerKind::kTree, "tree"},
     {LightSamplerKind::kPower, "power"},
     {LightSamplerKind::kUniform, "uniform"},
     {LightSamplerKind::kTreeFixedShare, "tree-fixed-share"}}};

}  // namespace caligo
