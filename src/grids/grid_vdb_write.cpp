// OpenVDB files out, and the sparse-block form's way into NanoVDB (through an OpenVDB grid,
// so one converter makes every NanoVDB grid). Blocks become leaves directly: no per-voxel
// tree descent.
#include <openvdb/io/File.h>

#include "grids/grid_io_internal.h"
#include "grids/openvdb_bridge.h"

namespace caligo {
namespace {

openvdb::FloatGrid::Ptr to_openvdb(const SparseFloatGrid& sparse) {
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(sparse.voxel_size);
  xform->postTranslate(openvdb::Vec3d(sparse.origin.x, sparse.origin.y, sparse.origin.z));
  grid->setTransform(xform);
  grid->setName(sparse.name);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  openvdb::FloatTree& tree = grid->tree();
  for (const SparseBlock& block : sparse.blocks) {
    openvdb::FloatTree::LeafNodeType* leaf =
        tree.touchLeaf(openvdb::Coord(block.origin[0], block.origin[1], block.origin[2]));
    for (int n = 0; n < kBlockVoxels; ++n) {
      // Our block order is the leaf's own (block_offset == LeafNode::coordToOffset).
      leaf->setValueOnly(openvdb::Index(n), block.values[size_t(n)]);
      leaf->setActiveState(openvdb::Index(n), block.values[size_t(n)] != 0.0f);
    }
  }
  return grid;
}

}  // namespace

void write_vdb_file(const std::string& path, const std::vector<SparseFloatGrid>& grids) {
  initialize_openvdb();
  openvdb::GridPtrVec vdb_grids;
  for (const SparseFloatGrid& g : grids) vdb_grids.push_back(to_openvdb(g));
  try {
    openvdb::io::File file(path);
    file.write(vdb_grids);
    file.close();
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error(std::string("cannot write the OpenVDB file: ") + e.what());
  }
}

NanoGridHandle sparse_to_nanovdb(const SparseFloatGrid& grid, bool full_checksum) {
  initialize_openvdb();
  return to_nanovdb(*to_openvdb(grid), full_checksum);
}

}  // namespace caligo
