#include "volumes/volume_context.h"

#include "grids/grid_accessor_cache.h"

namespace caligo {

VolumeContext::VolumeContext() : grids(std::make_unique<GridAccessorCache>()) {}
VolumeContext::~VolumeContext() = default;
VolumeContext::VolumeContext(VolumeContext&&) noexcept = default;
VolumeContext& VolumeContext::operator=(VolumeContext&&) noexcept = default;

}  // namespace caligo
