// Which strategy next-event estimation picks a light with (lights/light_sampler.h builds them;
// PathSettings::light_sampler chooses one): plain data, so that settings need not see the lights.
#pragma once

namespace caligo {

enum class LightSamplerKind { kUniform, kPower, kTree };

}  // namespace caligo
