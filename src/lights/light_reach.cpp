#include "lights/light_reach.h"

namespace caligo {

OrientedBox light_box(const BoxLight& light) {
  return {light.position,
          {cross(light.direction, light.up), light.up, light.direction},
          {-light.half_width, -light.half_height, 0.0f},
          {light.half_width, light.half_height, light.range}};
}

}  // namespace caligo
