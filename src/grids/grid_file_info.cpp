// The `caligo info` table.
#include <cinttypes>
#include <cstdio>

#include "grids/grid_io.h"

namespace caligo {
namespace {

std::string format(const char* fmt, auto... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), fmt, args...);
  return buffer;
}

std::string bytes(uint64_t n) {
  if (n < 1024) return format("%" PRIu64 " B", n);
  if (n < 1024 * 1024) return format("%.1f KiB", double(n) / 1024.0);
  if (n < uint64_t(1024) * 1024 * 1024) return format("%.1f MiB", double(n) / (1024.0 * 1024.0));
  return format("%.2f GiB", double(n) / (1024.0 * 1024.0 * 1024.0));
}

std::string index_box(const GridInfo& g) {
  if (g.active_voxels == 0) return "empty";
  return format("[%d,%d,%d]..[%d,%d,%d]", g.index_min[0], g.index_min[1], g.index_min[2], g.index_max[0],
                g.index_max[1], g.index_max[2]);
}

std::string world_box(const GridInfo& g) {
  if (g.world_bounds.empty()) return "empty";
  const Bounds3& b = g.world_bounds;
  return format("[%.4g,%.4g,%.4g]..[%.4g,%.4g,%.4g]", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
}

std::string voxel(const GridInfo& g) {
  const Vec3 v = g.voxel_size;
  if (v.x == v.y && v.y == v.z) return format("%.6g", v.x);
  return format("%.4gx%.4gx%.4g", v.x, v.y, v.z);
}

std::string range(const GridInfo& g) {
  if (!g.min_value || !g.max_value) return "-";
  return format("[%.6g, %.6g]", *g.min_value, *g.max_value);
}

}  // namespace

std::string format_grid_file_info(const GridFileInfo& info) {
  std::string out =
      format("%s: %s, %zu grid%s, %s on disk\n", info.path.c_str(), info.format.c_str(), info.grids.size(),
             info.grids.size() == 1 ? "" : "s", bytes(info.file_bytes).c_str());
  out += format("%-14s %-7s %-30s %-44s %-10s %13s %9s %7s %-22s %s\n", "name", "type", "index bounds",
                "world bounds", "voxel", "active voxels", "blocks", "tiles", "value range", "memory");
  for (const GridInfo& g : info.grids)
    out += format("%-14s %-7s %-30s %-44s %-10s %13" PRIu64 " %9" PRIu64 " %7" PRIu64 " %-22s %s\n",
                  g.name.c_str(), g.type.c_str(), index_box(g).c_str(), world_box(g).c_str(),
                  voxel(g).c_str(), g.active_voxels, g.active_leaves, g.active_tiles, range(g).c_str(),
                  bytes(g.memory_bytes).c_str());
  return out;
}

}  // namespace caligo
