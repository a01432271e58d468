// ExrAttributes in and out of an OpenEXR header: for exr_io.cpp alone, so that users of
// exr_attributes.h need none of OpenEXR's headers.
#pragma once

#include <ImfForward.h>

#include "image/exr_attributes.h"

namespace caligo {

// Adds every attribute to `header`. A name OpenEXR itself sets (channels, dataWindow, ...) is a
// programming error: std::invalid_argument.
void add_attributes(Imf::Header& header, const ExrAttributes& attributes);

// The attributes of `header` of the four types of ExrValue, in the header's (alphabetical)
// order; OpenEXR's own structural attributes and other types are left out.
ExrAttributes attributes_of(const Imf::Header& header);

}  // namespace caligo
