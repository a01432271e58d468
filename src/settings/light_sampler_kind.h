// Which strategy next-event estimation picks a light with (lights/light_sampler.h builds them;
// PathSettings::light_sampler chooses one): plain data, so that settings need not see the lights.
#pragma once

#include "core/enum_names.h"

namespace caligo {

enum class LightSamplerKind { kUniform, kPower, kTree };
// --light-sampler (the checkpoint key stores the enumerator).
inline constexpr std::array<EnumName<LightSamplerKind>, 3> kLightSamplerNames{
    {{LightSamplerKind::kTree, "tree"}, {LightSamplerKind::kPower, "power"}, {LightSamplerKind::kUniform, "uniform"}}};

}  // namespace caligo
