#include "scene/mesh_loader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "core/bounds.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

// ---- Helpers -------------------------------------------------------------------------------

const SourceLocation kWhere{"scene.json", "/shapes/0"};

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\"" << text << "\" does not contain \"" << part << "\"";
}

void expect_near(Vec3 a, Vec3 b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

Vec3 geometric_normal(const TriangleMesh& mesh, size_t t) {
  const Vec3 p0 = mesh.positions[mesh.indices[3 * t]];
  const Vec3 p1 = mesh.positions[mesh.indices[3 * t + 1]];
  const Vec3 p2 = mesh.positions[mesh.indices[3 * t + 2]];
  return normalize(cross(p1 - p0, p2 - p0));
}

std::string base64(const std::string& bytes) {
  static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t chunk = 0;
    for (size_t k = 0; k < 3; ++k) chunk = chunk << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(chunk >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

template <typename T>
void append_bytes(std::string& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));  // little-endian host, as glTF requires
  out.append(raw, sizeof(T));
}

void pad_to_4(std::string& s, char fill) {
  while (s.size() % 4 != 0) s += fill;
}

// A unit right triangle in z = 0: positions (36 bytes) followed by indices of the given type.
struct TriangleBuffer {
  std::string bytes;
  size_t index_bytes = 0;
  int index_component_type = 0;
};

TriangleBuffer triangle_buffer(int component_type = 5123) {
  TriangleBuffer buffer;
  buffer.index_component_type = component_type;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append_bytes(buffer.bytes, v);
  for (uint32_t i : {0u, 1u, 2u}) {
    if (component_type == 5121) append_bytes(buffer.bytes, uint8_t(i));
    if (component_type == 5123) append_bytes(buffer.bytes, uint16_t(i));
    if (component_type == 5125) append_bytes(buffer.bytes, i);
  }
  buffer.index_bytes = buffer.bytes.size() - 36;
  return buffer;
}

struct GltfOptions {
  std::string node = R"("translation": [1, 2, 3])";
  size_t position_count = 3;
  std::string position_view_length = "36";
  std::string primitive_extra;
};

// The glTF JSON for triangle_buffer(), with `buffer_json` as its one buffer.
std::string triangle_gltf(const TriangleBuffer& buffer, const std::string& buffer_json,
                          const GltfOptions& options = {}) {
  return R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, )" +
         options.node + R"(}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1)" +
         options.primitive_extra + R"(}]}],
  "buffers": [)" +
         buffer_json + R"(],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": )" +
         options.position_view_length + R"(},
    {"buffer": 0, "byteOffset": 36, "byteLength": )" +
         std::to_string(buffer.index_bytes) + R"(}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": )" +
         std::to_string(options.position_count) + R"(, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": )" +
         std::to_string(buffer.index_component_type) + R"(, "count": 3, "type": "SCALAR"}
  ]
})";
}

std::string data_uri_buffer(const std::string& bytes) {
  return R"({"byteLength": )" + std::to_string(bytes.size()) +
         R"(, "uri": "data:application/octet-stream;base64,)" + base64(bytes) + R"("})";
}

// The binary container: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded
// with zeros (https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html#binary-gltf-layout).
std::string make_glb(std::string json, std::string bin) {
  pad_to_4(json, ' ');
  pad_to_4(bin, '\0');
  std::string glb = "glTF";
  append_bytes(glb, uint32_t(2));
  append_bytes(glb, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  append_bytes(glb, uint32_t(json.size()));
  append_bytes(glb, uint32_t(0x4E4F534A));  // "JSON"
  glb += json;
  append_bytes(glb, uint32_t(bin.size()));
  append_bytes(glb, uint32_t(0x004E4942));  // "BIN\0"
  glb += bin;
  return glb;
}

class MeshLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / ("caligo_mesh_io_" + std::to_string(getpid()) + "_" + test);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& contents) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << contents;
    return path.string();
  }

  // The message of the InputError that loading `path` throws (empty, and a failure, if none).
  static std::string load_error(const std::string& path) {
    try {
      load_mesh(path, kWhere);
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().json_path, kWhere.json_path);
      const std::string message = e.what();
      EXPECT_TRUE(contains(message, path));
      EXPECT_EQ(message.rfind("scene.json: /shapes/0: ", 0), 0u) << message;
      return message;
    }
    ADD_FAILURE() << "loading " << path << " did not throw";
    return {};
  }

  fs::path dir_;
};

// ---- OBJ -----------------------------------------------------------------------------------

constexpr const char* kObjQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

TEST_F(MeshLoaderTest, ObjQuadIsTriangulated) {
  const TriangleMesh mesh = load_mesh(write("quad.obj", kObjQuad), kWhere);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.positions.size(), 4u);
  EXPECT_TRUE(mesh.normals.empty());
  // Both halves keep the face's counter-clockwise winding.
  for (size_t t = 0; t < 2; ++t) expect_near(geometric_normal(mesh, t), {0, 0, 1});
}

TEST_F(MeshLoaderTest, ObjExtensionIsCaseInsensitive) {
  EXPECT_EQ(load_mesh(write("QUAD.OBJ", kObjQuad), kWhere).triangle_count(), 2u);
}

TEST_F(MeshLoaderTest, ObjNormalsBecomeOnePerVertex) {
  const TriangleMesh mesh = load_mesh(
      write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n"), kWhere);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.positions.size(), 4u);  // each (position, normal) pair appears once
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (Vec3 n : mesh.normals) expect_near(n, {0, 0, 1});
}

TEST_F(MeshLoaderTest, ObjPositionWithTwoNormalsIsSplit) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvn 1 0 0\n"
      "f 1/1/1 2/1/1 3/1/1\nf 1//2 3//2 4//2\n";
  const TriangleMesh mesh = load_mesh(write("split.obj", "vt 0 0\n" + obj), kWhere);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.positions.size(), 6u);
  ASSERT_EQ(mesh.normals.size(), 6u);
  for (size_t k = 0; k < 3; ++k) {
    expect_near(mesh.normals[mesh.indices[k]], {0, 0, 1});
    expect_near(mesh.normals[mesh.indices[3 + k]], {1, 0, 0});
  }
  expect_near(mesh.positions[mesh.indices[0]], mesh.positions[mesh.indices[3]]);
}

TEST_F(MeshLoaderTest, ObjNormalsAreDroppedWhenSomeFacesLackThem) {
  const TriangleMesh mesh = load_mesh(
      write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 3 4\n"),
      kWhere);
  EXPECT_EQ(mesh.triangle_count(), 2u);
  EXPECT_TRUE(mesh.normals.empty());
}

TEST_F(MeshLoaderTest, ObjShapesAreFlattenedIntoOneMesh) {
  const TriangleMesh mesh = load_mesh(
      write("two.obj",
            "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nv 0 0 5\nv 1 0 5\nv 0 1 5\nf -3 -2 -1\n"),
      kWhere);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.positions[mesh.indices[3]].z, 5.0f);
}

TEST_F(MeshLoaderTest, ObjMaterialLibrariesAreIgnored) {
  const std::string path =
      write("mtl.obj", "mtllib missing.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(load_mesh(path, kWhere).triangle_count(), 1u);
}

TEST_F(MeshLoaderTest, ObjNaNVertexIsRejected) {
  const std::string path = write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string message = load_error(path);
  EXPECT_TRUE(contains(message, "non-finite"));
  EXPECT_TRUE(contains(message, "line 2"));
}

TEST_F(MeshLoaderTest, ObjInfiniteVertexIsRejected) {
  EXPECT_TRUE(
      contains(load_error(write("inf.obj", "v 0 0 0\nv 1 0 -inf\nv 0 1 0\nf 1 2 3\n")), "non-finite"));
  // Too large for a float: tinyobjloader produces infinity, which validation catches.
  EXPECT_TRUE(contains(load_error(write("huge.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n")),
                       "vertex 1 has a non-finite coordinate"));
}

TEST_F(MeshLoaderTest, ObjNaNNormalIsRejected) {
  EXPECT_TRUE(
      contains(load_error(write("nan_n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 nan 1\nf 1//1 2//1 3//1\n")),
               "normal has a non-finite coordinate"));
}

TEST_F(MeshLoaderTest, ObjUnreadableCoordinateIsRejected) {
  EXPECT_TRUE(contains(load_error(write("abc.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n")),
                       "line 2: cannot read the coordinate \"zero\""));
  EXPECT_TRUE(contains(load_error(write("short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n")),
                       "v needs three coordinates"));
}

TEST_F(MeshLoaderTest, ObjAcceptsTheNumberFormatsTinyObjReads) {
  const TriangleMesh mesh =
      load_mesh(write("numbers.obj", "v +0 -0. .0\nv 1e0 0.0E+0 -0e-3\n\tv 0 1. 0 1.0\nf 1 2 3\n"), kWhere);
  expect_near(mesh.positions[2], {0, 1, 0});
}

TEST_F(MeshLoaderTest, ObjOfOnlyDegenerateTrianglesIsRejected) {
  // Collinear vertices, and a triangle whose distinct vertices share one position.
  const std::string path = write("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 0\nf 1 2 3\nf 1 2 4\n");
  EXPECT_TRUE(contains(load_error(path), "triangle 0 is degenerate (zero area)"));
  try {
    load_mesh(path, kWhere, DegenerateTriangles::kRemove);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "all 2 triangles are degenerate (zero area)")) << e.what();
  }
}

TEST_F(MeshLoaderTest, DegenerateTrianglesAreRejectedUnlessRemovalIsAsked) {
  // Real files often contain a few (assimp's spider.obj has 56); they cover no area.
  const std::string path =
      write("some.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 4 4 1\nf 1 2 4\n");
  EXPECT_TRUE(contains(load_error(path), "triangle 0 is degenerate (zero area)"));
  const TriangleMesh mesh = load_mesh(path, kWhere, DegenerateTriangles::kRemove);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 3, 0, 1, 3}));
  EXPECT_EQ(validate_mesh(mesh), "");
}

TEST_F(MeshLoaderTest, ObjIndexOutOfRangeIsRejected) {
  EXPECT_TRUE(contains(load_error(write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")),
                       "a face refers to vertex 7, but the file has 3 vertices"));
  EXPECT_TRUE(contains(load_error(write("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9\n")),
                       "a face refers to vertex"));
  EXPECT_TRUE(
      contains(load_error(write("normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n")),
               "a face refers to normal 4, but the file has 1 normals"));
}

TEST_F(MeshLoaderTest, ObjZeroIndexIsALocatedError) {
  // tinyobjloader would fail too, without the line; the pre-scan says where.
  EXPECT_TRUE(contains(load_error(write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n")),
                       "line 4: a face refers to vertex 0 (OBJ counts from 1)"));
}

// ---- OBJ hardening (issue 12): every defect is an error with its line ---------------------

TEST_F(MeshLoaderTest, ObjFaceWithFewerThanThreeVerticesFollowsTheDegenerateRule) {
  const std::string path = write("two.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n");
  EXPECT_TRUE(contains(load_error(path), "line 5: a face has 2 vertices; a face needs at least 3"));
  EXPECT_TRUE(contains(load_error(write("one.obj", "v 0 0 0\nf 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")),
                       "line 2: a face has 1 vertices"));
  // "skip_degenerate": the short face is dropped, the triangle kept.
  EXPECT_EQ(load_mesh(path, kWhere, DegenerateTriangles::kRemove).triangle_count(), 1u);
}

TEST_F(MeshLoaderTest, ObjHugeIndexIsRejectedNotWrapped) {
  // atoi would turn 10^20 into -1, silently the last vertex.
  EXPECT_TRUE(
      contains(load_error(write("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 100000000000000000000\n")),
               "line 4: a face refers to vertex 100000000000000000000, but the file has 3 vertices"));
  EXPECT_TRUE(contains(load_error(write("huge_n.obj",
                                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"
                                        "f 1//1 2//1 3//99999999999\n")),
                       "line 5: a face refers to normal 99999999999, but the file has 1 normals"));
  EXPECT_TRUE(
      contains(load_error(write("huge_t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/4294967297\n")),
               "line 5: a face refers to texture coordinate 4294967297, but the file has 1"));
  EXPECT_TRUE(contains(load_error(write("word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x\n")),
                       "line 4: cannot read the vertex index \"3x\""));
  // A relative index reaches back only over the vertices above the face.
  EXPECT_TRUE(
      contains(load_error(write("back.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n")),
               "line 3: a face refers to vertex -3 (relative), but only 2 vertices precede the face"));
}

TEST_F(MeshLoaderTest, ObjZeroNormalIsRejectedUnlessItsFaceIsRemoved) {
  const std::string used =
      write("zero_n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 0\nf 1//1 2//2 3//1\n");
  EXPECT_TRUE(contains(load_error(used), "line 6: a face uses normal 2, which has zero length"));
  // skip_degenerate keeps a real triangle, so its zero normal is still an error (now unlocated).
  try {
    load_mesh(used, kWhere, DegenerateTriangles::kRemove);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "triangle 0 uses a zero-length normal (vertex 1)")) << e.what();
  }
  // On a zero-area face that skip_degenerate removes, it is accepted (exports write them there).
  const std::string on_degenerate = write("zero_deg.obj",
                                          "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nvn 0 0 1\nvn -0 0.0 +0e3\n"
                                          "f 1//1 2//1 3//1\nf 1//2 2//2 4//2\n");
  EXPECT_TRUE(contains(load_error(on_degenerate), "line 8: a face uses normal 2, which has zero length"));
  const TriangleMesh mesh = load_mesh(on_degenerate, kWhere, DegenerateTriangles::kRemove);
  EXPECT_EQ(mesh.triangle_count(), 1u);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  // An unused zero normal is no problem.
  EXPECT_EQ(load_mesh(write("unused.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1 2 3\n"), kWhere)
                .triangle_count(),
            1u);
}

TEST_F(MeshLoaderTest, ObjWithoutFacesIsRejected) {
  EXPECT_TRUE(contains(load_error(write("empty.obj", "")), "mesh has no triangles"));
  EXPECT_TRUE(contains(load_error(write("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n")), "mesh has no triangles"));
}

TEST_F(MeshLoaderTest, GarbageFileIsRejected) {
  std::string garbage;
  for (int i = 0; i < 4096; ++i) garbage += char((i * 7919 + 13) % 256);
  load_error(write("garbage.obj", garbage));
  load_error(write("garbage.gltf", garbage));
  load_error(write("garbage.glb", "glTF" + garbage));
}

// ---- Files and formats ---------------------------------------------------------------------

TEST_F(MeshLoaderTest, MissingFileNamesThePath) {
  const std::string path = (dir_ / "missing.obj").string();
  EXPECT_TRUE(contains(load_error(path), "cannot open mesh file \"" + path + "\""));
}

TEST_F(MeshLoaderTest, DirectoryIsNotAMeshFile) {
  fs::create_directories(dir_ / "dir.obj");
  EXPECT_TRUE(contains(load_error((dir_ / "dir.obj").string()), "cannot open mesh file"));
}

TEST_F(MeshLoaderTest, UnsupportedExtensionIsRejected) {
  EXPECT_TRUE(contains(load_error(write("mesh.3ds", "solid x\nendsolid x\n")),
                       "unsupported mesh format \".3ds\" (expected .obj, .gltf, .glb, .ply, .dae, .stl or .off)"));
  EXPECT_TRUE(contains(load_error(write("mesh", kObjQuad)), "unsupported mesh format"));
}

// ---- PLY (through assimp) -----------------------------------------------------------------

// The unit cube as six quads in ASCII PLY, with one vertex per corner.
constexpr const char* kPlyCube = R"(ply
format ascii 1.0
element vertex 8
property float x
property float y
property float z
element face 6
property list uchar int vertex_indices
end_header
0 0 0
0 0 1
0 1 1
0 1 0
1 0 0
1 0 1
1 1 1
1 1 0
4 0 1 2 3
4 7 6 5 4
4 0 4 5 1
4 1 5 6 2
4 2 6 7 3
4 3 7 4 0
)";

// One triangle in binary little-endian PLY, moved by `offset`.
std::string binary_ply_triangle(Vec3 offset) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (Vec3 p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}) {
    append_bytes(ply, p.x + offset.x);
    append_bytes(ply, p.y + offset.y);
    append_bytes(ply, p.z + offset.z);
  }
  append_bytes(ply, uint8_t(3));
  for (int32_t i : {0, 1, 2}) append_bytes(ply, i);
  return ply;
}

TEST_F(MeshLoaderTest, PlyQuadsAreTriangulatedAndKeepTheirCorners) {
  const TriangleMesh mesh = load_mesh(write("cube.ply", kPlyCube), kWhere);
  EXPECT_EQ(mesh.triangle_count(), 12u);
  EXPECT_EQ(mesh.positions.size(), 8u);  // identical corners are welded, none added
  Bounds3 bounds;
  for (Vec3 p : mesh.positions) bounds.extend(p);
  expect_near(bounds.lo, {0, 0, 0});
  expect_near(bounds.hi, {1, 1, 1});
  // Triangulation keeps each quad's winding: the face 0 1 2 3 lies in x = 0, normal -x.
  expect_near(geometric_normal(mesh, 0), {-1, 0, 0});
}

TEST_F(MeshLoaderTest, PlyBinaryTriangle) {
  const TriangleMesh mesh = load_mesh(write("tri.PLY", binary_ply_triangle({5, 6, 7})), kWhere);
  ASSERT_EQ(mesh.triangle_count(), 1u);
  expect_near(mesh.positions[mesh.indices[1]], {6, 6, 7});
  expect_near(geometric_normal(mesh, 0), {0, 0, 1});
}

TEST_F(MeshLoaderTest, CorruptPlyFilesAreInputErrors) {
  EXPECT_TRUE(contains(load_error(write("garbage.ply", std::string("\x7f\x01garbage\0\xff\xfe", 12))),
                       "cannot parse PLY: no header"));
  const std::string triangle = binary_ply_triangle({0, 0, 0});
  EXPECT_TRUE(contains(load_error(write("truncated.ply", triangle.substr(0, triangle.size() - 10))),
                       "cannot parse PLY"));
  std::string cube = kPlyCube;
  cube.replace(cube.find("4 7 6 5 4"), 9, "4 7 6 x 4");
  EXPECT_FALSE(load_error(write("word.ply", cube)).empty());
  cube = kPlyCube;
  cube.replace(cube.find("4 7 6 5 4"), 9, "4 7 6 9 4");  // vertex 9 of 8
  EXPECT_FALSE(load_error(write("index.ply", cube)).empty());
  EXPECT_TRUE(contains(load_error(write("header_only.ply", "ply\nformat ascii 1.0\n")), "does not end with an \"end_header\" line"));
}

// Found by fuzz/mesh_fuzz.cpp (ply): a face with no indices (here a count byte of 0; the
// fuzzer's was a binary file shifted by one byte) passed assimp's validation and then failed an
// assertion in its triangulation that aborted the whole process (exit 134, no message).
TEST_F(MeshLoaderTest, PlyFaceWithoutIndicesIsAnInputErrorNotAnAbort) {
  std::string ply = binary_ply_triangle({0, 0, 0});
  ply.replace(ply.find("element face 1"), 14, "element face 2");
  append_bytes(ply, uint8_t(0));
  EXPECT_TRUE(contains(load_error(write("empty_face.ply", ply)), "a face has no vertex indices"));
}

// Found by fuzz/mesh_fuzz.cpp (ply): without a line that is exactly "end_header", assimp's PLY
// reader searched on through the binary data and past the end of its buffer (SIGSEGV).
TEST_F(MeshLoaderTest, PlyHeaderWithoutAnEndHeaderLineIsAnInputErrorNotACrash) {
  std::string ply = binary_ply_triangle({0, 0, 0});
  ply.replace(ply.find("end_header\n"), 11, "end_header*\n");
  EXPECT_TRUE(contains(load_error(write("star.ply", ply)), "does not end with an \"end_header\" line"));
  ply = binary_ply_triangle({0, 0, 0});
  ply.replace(ply.find("end_header\n"), 11, "end_header \r\n");  // blanks and CR LF are fine
  EXPECT_EQ(load_mesh(write("crlf.ply", ply), kWhere).triangle_count(), 1u);
}

TEST_F(MeshLoaderTest, PlyHeaderCannotClaimMoreElementsThanTheFileHolds) {
  std::string ply = binary_ply_triangle({0, 0, 0});
  ply.replace(ply.find("element vertex 3"), 16, "element vertex 4000000000");
  EXPECT_TRUE(contains(load_error(write("huge.ply", ply)), "declares 4000000000 vertex elements"));
  ply = binary_ply_triangle({0, 0, 0});
  ply.replace(ply.find("element face 1"), 14, "element face -1");
  EXPECT_TRUE(contains(load_error(write("negative.ply", ply)), "has the count \"-1\""));
}

TEST_F(MeshLoaderTest, PlyHeaderOverTheMeshLimitsIsRefusedWithTheNumbers) {
  // The limit comes before the file-size plausibility check, so the message names it.
  std::string ply = binary_ply_triangle({0, 0, 0});
  ply.replace(ply.find("element face 1"), 14, "element face " + std::to_string(kMaxMeshTriangles + 1));
  EXPECT_TRUE(contains(load_error(write("faces.ply", ply)),
                       "declares " + std::to_string(kMaxMeshTriangles + 1) +
                           " face elements; meshes are limited to " + std::to_string(kMaxMeshTriangles) +
                           " triangles"));
  ply = binary_ply_triangle({0, 0, 0});
  ply.replace(ply.find("element vertex 3"), 16, "element vertex " + std::to_string(kMaxMeshVertices + 1));
  EXPECT_TRUE(contains(load_error(write("vertices.ply", ply)),
                       "meshes are limited to " + std::to_string(kMaxMeshVertices) + " vertices"));
}

TEST_F(MeshLoaderTest, ControlCharactersInAMeshPathAreEscaped) {
  const std::string path = write("bad\nname\x1b[31m.obj", "v 0 0 0\n");
  try {
    load_mesh(path, kWhere);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
    EXPECT_TRUE(contains(message, "bad\\nname\\x1b[31m.obj")) << message;
  }
}

TEST_F(MeshLoaderTest, PlyWithoutFacesHasNoTriangles) {
  const std::string points =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_FALSE(load_error(write("points.ply", points)).empty());
  EXPECT_TRUE(contains(load_error((dir_ / "missing.ply").string()), "cannot open mesh file"));
}

TEST_F(MeshLoaderTest, CorruptColladaIsAnInputError) {
  EXPECT_TRUE(
      contains(load_error(write("broken.dae", "<COLLADA><library_geometries>")), "cannot parse COLLADA"));
  EXPECT_TRUE(contains(load_error(write("binary.dae", std::string("\0\x01\x02garbage", 10))),
                       "cannot parse COLLADA"));
}

// A COLLADA file with one unit triangle under `depth` nested <node>s; `extra` goes into the
// <asset> element. Its deepest element, the innermost <node>, is at depth 3 + `depth` (the
// <instance_geometry> in it closes itself).
std::string nested_collada(size_t depth, const std::string& extra = "") {
  std::string nodes;
  for (size_t i = 0; i < depth; ++i) nodes += "<node id=\"n" + std::to_string(i) + "\">";
  nodes += "<instance_geometry url=\"#tri\"/>";
  for (size_t i = 0; i < depth; ++i) nodes += "</node>\n";
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1" name="meter"/><up_axis>Y_UP</up_axis>)" +
         extra + R"(</asset>
  <library_geometries>
    <geometry id="tri" name="tri"><mesh>
      <source id="tri-pos">
        <float_array id="tri-pos-array" count="9">0 0 0 1 0 0 0 1 0</float_array>
        <technique_common><accessor source="#tri-pos-array" count="3" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
      <triangles count="1"><input semantic="VERTEX" source="#tri-vtx" offset="0"/><p>0 1 2</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="scene">
)" + nodes + R"(  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
}

// assimp's COLLADA reader recursed once per <node>: 100,000 levels were a SIGSEGV.
TEST_F(MeshLoaderTest, ColladaNestedDeeperThanTheLimitIsRefusedBeforeAssimp) {
  const size_t at_limit = kMaxColladaDepth - 3;
  EXPECT_EQ(load_mesh(write("at_limit.dae", nested_collada(at_limit)), kWhere).triangle_count(), 1u);
  const std::string over = load_error(write("over.dae", nested_collada(at_limit + 1)));
  // The <node> that opens level 257 is on line 17 of the file, with all the others.
  EXPECT_TRUE(contains(over, "over.dae: line 17: elements are nested more than 256 levels deep"));
  EXPECT_TRUE(contains(load_error(write("deep.dae", nested_collada(100'000))), "nested more than 256"));
}

// COLLADA may be UTF-16 (assimp-testmodels has cube_UTF16LE.dae, which assimp 5.2 reads as
// UTF-8 up to the first NUL, and calls malformed). The scan also decodes it, for a reader that
// would: counted byte by byte, its closing tags "<\0/\0" would look like openings.
TEST_F(MeshLoaderTest, ColladaDepthIsCountedInUtf16Too) {
  const auto utf16le = [](const std::string& ascii) {
    std::string text = ascii;
    text.replace(text.find("utf-8"), 5, "utf-16");
    std::string out = "\xFF\xFE";
    for (char c : text) out += std::string{c, '\0'};
    return out;
  };
  const size_t at_limit = kMaxColladaDepth - 3;
  try {
    EXPECT_EQ(load_mesh(write("at_limit.dae", utf16le(nested_collada(at_limit))), kWhere).triangle_count(), 1u);
  } catch (const InputError& e) {
    EXPECT_FALSE(contains(e.what(), "levels deep"));
  }
  EXPECT_TRUE(contains(load_error(write("over.dae", utf16le(nested_collada(at_limit + 1)))),
                       "over.dae: line 17: elements are nested more than 256 levels deep"));
}

// Found by fuzz/mesh_fuzz.cpp (dae): a <float_array> without "count" holds no values, and
// assimp 5.2 read the accessor's 9 from it anyway (a null read, SIGSEGV). Every accessor must
// fit in its array: `count` items `stride` apart, each as long as its <param>s (assimp reads
// one value a <param>, whatever the stride).
TEST_F(MeshLoaderTest, ColladaAccessorLongerThanItsArrayIsRefusedBeforeAssimp) {
  const std::string valid = nested_collada(1);
  const auto edit = [](std::string text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const auto with = [&](const std::string& from, const std::string& to) { return edit(valid, from, to); };
  EXPECT_TRUE(contains(load_error(write("no_count.dae", with(R"( count="9">0 0 0)", ">0 0 0"))),
                       "no_count.dae: line 8: an accessor reads 9 values from \"#tri-pos-array\", which holds 0"));
  EXPECT_TRUE(contains(load_error(write("short.dae", with(R"(count="9">0 0 0 1 0 0 0 1 0)", R"(count="8">0 0 0 1 0 0 0 1)"))),
                       "an accessor reads 9 values from \"#tri-pos-array\", which holds 8"));
  // 3 items 2 apart, each of 3 <param>s, reach value 7: count * stride (6) would not see it.
  const std::string params = edit(with(R"(count="3" stride="3")", R"(count="3" stride="2")"),
                                  R"(count="9">0 0 0 1 0 0 0 1 0)", R"(count="6">0 0 0 1 0 0)");
  EXPECT_TRUE(contains(load_error(write("params.dae", params)),
                       "an accessor reads 7 values from \"#tri-pos-array\", which holds 6"));
  EXPECT_TRUE(contains(load_error(write("offset.dae", with(R"(count="3" stride="3")", R"(count="3" stride="3" offset="1")"))),
                       "an accessor reads 10 values from \"#tri-pos-array\", which holds 9"));
  EXPECT_TRUE(contains(load_error(write("hex.dae", with(R"(count="3" stride="3")", R"(count="0x3" stride="3")"))),
                       "line 8: the <accessor> count must be a whole number below 2^32"));
  EXPECT_EQ(load_mesh(write("exact.dae", valid), kWhere).triangle_count(), 1u);
  // Found by the fuzzer next: a UTF-16 byte-order mark before UTF-8 text. assimp 5.2 reads it as
  // UTF-8 anyway, so the scan must too, not only as the UTF-16 the mark announces.
  EXPECT_TRUE(contains(load_error(write("bom.dae", "\xFF\xFE" + with(R"( count="9">)", R"( count="0">)"))),
                       "an accessor reads 9 values from \"#tri-pos-array\", which holds 0"));
}

// Found by fuzz/mesh_fuzz.cpp (dae): "<p>0 1\v2</p>" sent assimp 5.2 into a loop appending
// zeros (it skips only spaces, tabs and line ends between indices) until 3 GB were gone.
TEST_F(MeshLoaderTest, ColladaIndexListWithOtherCharactersIsRefusedBeforeAssimp) {
  const std::string valid = nested_collada(1);
  const auto with_p = [&](const std::string& p) {
    std::string text = valid;
    text.replace(text.find("<p>0 1 2</p>"), 12, p);
    return text;
  };
  EXPECT_TRUE(contains(load_error(write("vtab.dae", with_p("<p>0 1\v2</p>"))),
                       "vtab.dae: line 13: a <p> holds the character \"\\x0b\"; it may hold only whole numbers"));
  EXPECT_TRUE(contains(load_error(write("ref.dae", with_p("<p>0 1&#11;2</p>"))), "holds the character \"&\""));
  EXPECT_TRUE(contains(load_error(write("cdata.dae", with_p("<p><![CDATA[0 1\v2]]></p>"))), "a <p> holds markup"));
  EXPECT_EQ(load_mesh(write("separators.dae", with_p("<p>\n 0\t1\r\n 2 </p>")), kWhere).triangle_count(), 1u);
  // Negative and huge indices, which assimp 5.2 reads as vertex 0 without a word.
  EXPECT_TRUE(contains(load_error(write("neg.dae", with_p("<p>0 -3 2</p>"))), "holds the character \"-\""));
  for (const char* huge : {"4294967295", "4294967296", "000000000004294967295", "99999999999"})
    EXPECT_TRUE(contains(load_error(write("huge.dae", with_p(std::string("<p>0 1 ") + huge + "</p>"))),
                         std::string("holds the index ") + huge))
        << huge;
  EXPECT_EQ(load_mesh(write("zeros.dae", with_p("<p>0 0001 00002</p>")), kWhere).triangle_count(), 1u);
}

TEST_F(MeshLoaderTest, ColladaDepthIgnoresCommentsCdataDeclarationsAndAttributes) {
  // Each of these holds 300 element openings that are not elements; the file stays at the limit.
  std::string opens;
  for (int i = 0; i < 300; ++i) opens += "<node>";
  const std::string extra = "<!-- " + opens + " --><title><![CDATA[" + opens + "]]></title>" +
                            "<?pi " + opens + "?><keywords a=\"" + opens + "\" b='/>'/>";
  std::string text = nested_collada(kMaxColladaDepth - 3, extra);
  text.insert(text.find("<COLLADA"), "<!DOCTYPE COLLADA [ <!ENTITY e \"" + opens + "\"> ]>\n");
  EXPECT_EQ(load_mesh(write("tricky.dae", text), kWhere).triangle_count(), 1u);
}

// ---- glTF ----------------------------------------------------------------------------------

TEST_F(MeshLoaderTest, GltfEmbeddedTriangleIsTranslatedByItsNode) {
  const TriangleBuffer buffer = triangle_buffer();
  const TriangleMesh mesh =
      load_mesh(write("tri.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes))), kWhere);
  ASSERT_EQ(mesh.triangle_count(), 1u);
  ASSERT_EQ(mesh.positions.size(), 3u);
  expect_near(mesh.positions[mesh.indices[0]], {1, 2, 3});
  expect_near(mesh.positions[mesh.indices[1]], {2, 2, 3});
  expect_near(mesh.positions[mesh.indices[2]], {1, 3, 3});
  EXPECT_TRUE(mesh.normals.empty());
}

TEST_F(MeshLoaderTest, GltfReadsEveryIndexType) {
  for (int type : {5121, 5123, 5125}) {
    const TriangleBuffer buffer = triangle_buffer(type);
    const std::string name = "tri" + std::to_string(type) + ".gltf";
    const TriangleMesh mesh =
        load_mesh(write(name, triangle_gltf(buffer, data_uri_buffer(buffer.bytes))), kWhere);
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2})) << type;
  }
}

TEST_F(MeshLoaderTest, GltfSignedIndicesAreRejected) {
  TriangleBuffer buffer = triangle_buffer(5123);
  buffer.index_component_type = 5122;  // SHORT is not a valid index type
  EXPECT_TRUE(contains(load_error(write("signed.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes)))),
                       "unsigned 8, 16 or 32-bit"));
}

TEST_F(MeshLoaderTest, GltfExternalBufferIsFoundNextToTheFile) {
  const TriangleBuffer buffer = triangle_buffer();
  write("tri.bin", buffer.bytes);
  const std::string buffer_json =
      R"({"byteLength": )" + std::to_string(buffer.bytes.size()) + R"(, "uri": "tri.bin"})";
  const std::string path = write("tri.gltf", triangle_gltf(buffer, buffer_json));
  EXPECT_EQ(load_mesh(path, kWhere).triangle_count(), 1u);
  fs::remove(dir_ / "tri.bin");
  EXPECT_TRUE(contains(load_error(path), "cannot parse glTF"));
}

TEST_F(MeshLoaderTest, GlbContainerWithTheSameTriangle) {
  const TriangleBuffer buffer = triangle_buffer();
  const std::string buffer_json = R"({"byteLength": )" + std::to_string(buffer.bytes.size()) + "}";
  const std::string glb = make_glb(triangle_gltf(buffer, buffer_json), buffer.bytes);
  const TriangleMesh mesh = load_mesh(write("tri.glb", glb), kWhere);
  ASSERT_EQ(mesh.triangle_count(), 1u);
  expect_near(mesh.positions[mesh.indices[1]], {2, 2, 3});

  // Recognised by content, whatever the extension says; a truncated container is an error.
  EXPECT_EQ(load_mesh(write("named_wrongly.gltf", glb), kWhere).triangle_count(), 1u);
  EXPECT_TRUE(
      contains(load_error(write("truncated.glb", glb.substr(0, glb.size() - 8))), "cannot parse glTF"));
}

// tinygltf recursed once per level of "extras": 20,000 "[" were a SIGSEGV. The primitive's
// object is at depth 5 (file, "meshes", mesh, "primitives", primitive), so `levels` arrays
// under it reach depth 5 + `levels`.
std::string gltf_with_nested_extras(size_t levels) {
  const TriangleBuffer buffer = triangle_buffer();
  GltfOptions options;
  options.primitive_extra = R"(, "extras": )" + std::string(levels, '[') + std::string(levels, ']');
  return triangle_gltf(buffer, data_uri_buffer(buffer.bytes), options);
}

TEST_F(MeshLoaderTest, GltfNestedDeeperThanTheLimitIsRefusedBeforeTinygltf) {
  const size_t at_limit = kMaxGltfJsonDepth - 5;
  EXPECT_EQ(load_mesh(write("at_limit.gltf", gltf_with_nested_extras(at_limit)), kWhere).triangle_count(), 1u);
  // "meshes" is on line 6 of triangle_gltf().
  EXPECT_TRUE(contains(load_error(write("over.gltf", gltf_with_nested_extras(at_limit + 1))),
                       "over.gltf: line 6: arrays and objects are nested more than 128 levels deep"));
  EXPECT_TRUE(contains(load_error(write("deep.gltf", gltf_with_nested_extras(20'000))), "nested more than 128"));

  // The same JSON as the first chunk of a GLB container.
  const TriangleBuffer buffer = triangle_buffer();
  const std::string buffer_json = R"({"byteLength": )" + std::to_string(buffer.bytes.size()) + "}";
  GltfOptions options;
  options.primitive_extra = R"(, "extras": )" + std::string(20'000, '[') + std::string(20'000, ']');
  EXPECT_TRUE(contains(load_error(write("deep.glb", make_glb(triangle_gltf(buffer, buffer_json, options), buffer.bytes))),
                       "deep.glb: GLB JSON chunk, line 6: arrays and objects are nested more than 128"));
}

TEST_F(MeshLoaderTest, GltfDepthIgnoresBracketsInStrings) {
  // 1,000 brackets in strings (one after an escaped quote) do not nest anything.
  const TriangleBuffer buffer = triangle_buffer();
  GltfOptions options;
  options.primitive_extra = R"(, "extras": {"a": ")" + std::string(500, '[') + R"(\" [{", "b\\": ")" +
                            std::string(500, '{') + R"("})";
  EXPECT_EQ(load_mesh(write("strings.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes), options)), kWhere)
                .triangle_count(),
            1u);
}

TEST_F(MeshLoaderTest, GltfAccessorPastTheEndOfItsBufferIsRejected) {
  const TriangleBuffer buffer = triangle_buffer();
  GltfOptions options;
  options.position_count = 4;  // one more vec3 than the 36-byte view holds
  EXPECT_TRUE(
      contains(load_error(write("count.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes), options))),
               "accessor 0 reads past the end of its buffer view"));

  options.position_count = size_t(1) << 62;  // large enough to overflow a naive size computation
  EXPECT_TRUE(
      contains(load_error(write("huge.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes), options))),
               "past the end"));

  options.position_count = 3;
  options.position_view_length = "4096";  // the view itself leaves the 42-byte buffer
  EXPECT_TRUE(
      contains(load_error(write("view.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes), options))),
               "buffer view 0 extends past the end of its buffer"));
}

TEST_F(MeshLoaderTest, GltfIndexBeyondTheVerticesIsRejected) {
  TriangleBuffer buffer = triangle_buffer(5123);
  buffer.bytes[36 + 4] = 9;  // third index: 2 -> 9
  EXPECT_TRUE(contains(load_error(write("index.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes)))),
                       "mesh 0, primitive 0: refers to vertex 9, but it has 3"));
}

TEST_F(MeshLoaderTest, GltfNonTriangleModesAreRejected) {
  const TriangleBuffer buffer = triangle_buffer();
  GltfOptions options;
  options.primitive_extra = R"(, "mode": 1)";
  EXPECT_TRUE(
      contains(load_error(write("lines.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes), options))),
               "mesh 0, primitive 0: has mode 1; only triangles (mode 4) are supported"));
}

TEST_F(MeshLoaderTest, GltfCyclicNodeHierarchyIsRejected) {
  const TriangleBuffer buffer = triangle_buffer();
  GltfOptions options;
  options.node = R"("children": [1]}, {"children": [0])";
  EXPECT_TRUE(
      contains(load_error(write("cycle.gltf", triangle_gltf(buffer, data_uri_buffer(buffer.bytes), options))),
               "node 0 appears more than once"));
}

// A glTF with its own buffer of interleaved positions and normals, for transform tests.
class GltfTransformTest : public MeshLoaderTest {
 protected:
  // Triangle (0,0,0), (1,0,0), (0,1,0) with normals +z, stored as p0 n0 p1 n1 p2 n2 (stride 24)
  // and no index accessor; `nodes` holds the node list, whose node 0 is the scene's root.
  std::string write_interleaved(const std::string& nodes) {
    std::string bytes;
    for (float v : {0.f, 0.f, 0.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f})
      append_bytes(bytes, v);
    const std::string json = R"({
      "asset": {"version": "2.0"},
      "scenes": [{"nodes": [0]}],
      "nodes": )" + nodes + R"(,
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
      "buffers": [)" + data_uri_buffer(bytes) +
                             R"(],
      "bufferViews": [{"buffer": 0, "byteLength": 72, "byteStride": 24}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
        {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 3, "type": "VEC3"}
      ]
    })";
    return write("interleaved.gltf", json);
  }
};

TEST_F(GltfTransformTest, InterleavedAttributesAndNoIndices) {
  const TriangleMesh mesh = load_mesh(write_interleaved(R"([{"mesh": 0}])"), kWhere);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
  ASSERT_EQ(mesh.normals.size(), 3u);
  expect_near(mesh.positions[1], {1, 0, 0});
  expect_near(mesh.positions[2], {0, 1, 0});
  for (Vec3 n : mesh.normals) expect_near(n, {0, 0, 1});
}

TEST_F(GltfTransformTest, QuaternionRotationAppliesToPositionsAndNormals) {
  // 90 degrees about +x: y -> z, z -> -y.
  const TriangleMesh mesh =
      load_mesh(write_interleaved(R"([{"mesh": 0, "rotation": [0.7071068, 0, 0, 0.7071068]}])"), kWhere);
  expect_near(mesh.positions[2], {0, 0, 1});
  for (Vec3 n : mesh.normals) expect_near(n, {0, -1, 0});
  expect_near(geometric_normal(mesh, 0), {0, -1, 0});
}

TEST_F(GltfTransformTest, HierarchyComposesParentAfterChild) {
  const TriangleMesh mesh = load_mesh(
      write_interleaved(R"([{"translation": [10, 0, 0], "children": [1]}, {"mesh": 0, "scale": [2, 2, 2]}])"),
      kWhere);
  expect_near(mesh.positions[0], {10, 0, 0});
  expect_near(mesh.positions[1], {12, 0, 0});
  expect_near(mesh.positions[2], {10, 2, 0});
}

TEST_F(GltfTransformTest, TrsOrderIsTranslateRotateScale) {
  // Scale x by 3, then rotate 90 degrees about +z (x -> y), then translate.
  const TriangleMesh mesh = load_mesh(
      write_interleaved(
          R"([{"mesh": 0, "translation": [0, 0, 5], "rotation": [0, 0, 0.7071068, 0.7071068], "scale": [3, 1, 1]}])"),
      kWhere);
  expect_near(mesh.positions[1], {0, 3, 5});
  expect_near(mesh.positions[2], {-1, 0, 5});
}

TEST_F(GltfTransformTest, ColumnMajorMatrix) {
  const TriangleMesh mesh = load_mesh(
      write_interleaved(R"([{"mesh": 0, "matrix": [2,0,0,0, 0,2,0,0, 0,0,2,0, 7,8,9,1]}])"), kWhere);
  expect_near(mesh.positions[1], {9, 8, 9});
}

TEST_F(GltfTransformTest, MirroringKeepsGeometricAndShadingNormalsTogether) {
  const TriangleMesh mesh = load_mesh(write_interleaved(R"([{"mesh": 0, "scale": [1, 1, -1]}])"), kWhere);
  for (Vec3 n : mesh.normals) expect_near(n, {0, 0, -1});
  expect_near(geometric_normal(mesh, 0), {0, 0, -1});
}

TEST_F(GltfTransformTest, ZeroScaleHidesTheMesh) {
  EXPECT_TRUE(contains(load_error(write_interleaved(R"([{"mesh": 0, "scale": [0, 0, 0]}])")),
                       "mesh has no triangles"));
}

TEST_F(GltfTransformTest, MalformedTransformsAreRejected) {
  EXPECT_TRUE(contains(load_error(write_interleaved(R"([{"mesh": 0, "translation": [1, 2]}])")),
                       "node 0 has a transform with the wrong number of values"));
  EXPECT_TRUE(contains(load_error(write_interleaved(R"([{"mesh": 0, "rotation": [0, 0, 0, 0]}])")),
                       "node 0 has an invalid rotation quaternion"));
  EXPECT_TRUE(contains(
      load_error(write_interleaved(R"([{"mesh": 0, "matrix": [1,0,0,1, 0,1,0,0, 0,0,1,0, 0,0,0,1]}])")),
      "node 0 has a non-affine or non-finite transform"));
}

// ---- Real files (Debian's assimp-testmodels, when installed) -------------------------------

fs::path test_models_dir() {
  const char* override_dir = std::getenv("CALIGO_TEST_MODELS_DIR");  // for a copy elsewhere
  return override_dir != nullptr ? fs::path(override_dir) : fs::path("/usr/share/assimp/models");
}

void expect_plausible(const TriangleMesh& mesh) {
  EXPECT_GT(mesh.triangle_count(), 0u);
  Bounds3 bounds;
  for (Vec3 p : mesh.positions) bounds.extend(p);
  EXPECT_TRUE(is_finite(bounds.lo) && is_finite(bounds.hi));
  EXPECT_FALSE(bounds.empty());
}

class RealMeshTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(test_models_dir() / "OBJ/spider.obj"))
      GTEST_SKIP() << "assimp-testmodels is not installed";
  }
  static std::string model(const std::string& relative) { return (test_models_dir() / relative).string(); }
};

TEST_F(RealMeshTest, SpiderObj) {
  // The file holds 56 zero-area triangles: rejected unless the scene asks for their removal.
  EXPECT_THROW(load_mesh(model("OBJ/spider.obj"), kWhere), InputError);
  const TriangleMesh mesh = load_mesh(model("OBJ/spider.obj"), kWhere, DegenerateTriangles::kRemove);
  expect_plausible(mesh);
}

TEST_F(RealMeshTest, GltfBoxes) {
  for (const char* file :
       {"glTF2/BoxTextured-glTF/BoxTextured.gltf", "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
        "glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    SCOPED_TRACE(file);
    const TriangleMesh mesh = load_mesh(model(file), kWhere);
    EXPECT_EQ(mesh.triangle_count(), 12u);
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    expect_plausible(mesh);
  }
}

TEST_F(RealMeshTest, PlyFiles) {
  // Wuson has 3732 triangles (with normals); the cubes are 6 quads in ASCII and binary.
  const std::pair<const char*, size_t> cases[] = {
      {"PLY/Wuson.ply", 3732}, {"PLY/cube.ply", 12}, {"PLY/cube_binary.ply", 12}};
  for (const auto& [file, triangles] : cases) {
    SCOPED_TRACE(file);
    const TriangleMesh mesh = load_mesh(model(file), kWhere);
    EXPECT_EQ(mesh.triangle_count(), triangles);
    expect_plausible(mesh);
  }
  EXPECT_EQ(load_mesh(model("PLY/Wuson.ply"), kWhere).normals.size(),
            load_mesh(model("PLY/Wuson.ply"), kWhere).positions.size());
}

TEST_F(RealMeshTest, ColladaDuck) {
  const TriangleMesh mesh = load_mesh(model("Collada/duck.dae"), kWhere);
  EXPECT_EQ(mesh.triangle_count(), 4212u);
  expect_plausible(mesh);
}

// The scans before assimp (mesh_text_scan.h) pass every COLLADA sample of assimp-testmodels
// (UTF-8, with a BOM, UTF-16, instanced nodes, skins, animations); some fail later, for reasons
// of their own (no mesh, UTF-16 that assimp 5.2 cannot read).
TEST_F(RealMeshTest, ColladaSamplesPassTheTextScans) {
  size_t files = 0, loaded = 0;
  for (const auto& entry : fs::directory_iterator(test_models_dir() / "Collada")) {
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](char c) { return char(std::tolower(c)); });
    if (extension != ".dae") continue;
    SCOPED_TRACE(entry.path().filename().string());
    ++files;
    try {
      load_mesh(entry.path().string(), kWhere, DegenerateTriangles::kRemove);
      ++loaded;
    } catch (const InputError& e) {
      EXPECT_FALSE(contains(e.what(), "levels deep"));
      EXPECT_FALSE(contains(e.what(), "an accessor reads"));
      EXPECT_FALSE(contains(e.what(), "must be a whole number"));
    }
  }
  EXPECT_GT(files, 20u);
  EXPECT_GT(loaded, files / 2);
}

TEST_F(RealMeshTest, BrokenGltfFilesAreInputErrors) {
  const std::pair<const char*, const char*> cases[] = {
      {"glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "non-finite"},
      {"glTF2/IndexOutOfRange/IndexOutOfRange.gltf", "refers to vertex"},
      {"glTF2/RecursiveNodes/RecursiveNodes.gltf", "appears more than once"},
      {"glTF2/MissingBin/BoxTextured.gltf", "cannot parse glTF"},
  };
  for (const auto& [file, expected] : cases) {
    SCOPED_TRACE(file);
    try {
      load_mesh(model(file), kWhere);
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_TRUE(contains(e.what(), expected));
    }
  }
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// Found by fuzz/mesh_fuzz.cpp (ply): an ASCII face line whose list length is 442949672954 made
// assimp allocate and fill ~9 GB before failing. A list longer than its line is refused first.
TEST(PlyAsciiLists, AListLongerThanItsLineIsRefusedBeforeAssimpAllocates) {
  const auto path = std::filesystem::temp_directory_path() / "caligo_ply_list.ply";
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  std::ofstream(path) << header << "442949672954 0 1 2\n";
  try {
    load_mesh(path.string(), {"scene.json", "/shapes/0"});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("PLY line 13: a list says it holds \"442949672954\" values"),
              std::string::npos)
        << e.what();
  }
  std::ofstream(path) << header << "3 0 1 2\n";
  EXPECT_EQ(load_mesh(path.string(), {"scene.json", "/shapes/0"}).triangle_count(), 1u);
  // UTF-8 in a comment is text; CR LF line ends are fine.
  std::string commented = header;
  commented.insert(commented.find("element"), "comment cr\xc3\xa9\xc3\xa9 par Zo\xc3\xab\r\n");
  std::ofstream(path) << commented << "3 0 1 2\r\n";
  EXPECT_EQ(load_mesh(path.string(), {"scene.json", "/shapes/0"}).triangle_count(), 1u);
  // Found by the CI fuzz run: assimp reads the body as one token stream, so a vertex line with
  // garbage or a value too few shifted a coordinate into a list length (out of memory).
  const auto expect_error = [&](const std::string& body, const std::string& says) {
    std::ofstream(path) << header.substr(0, header.find("0 0 0\n")) << body;
    try {
      load_mesh(path.string(), {"scene.json", "/shapes/0"});
      ADD_FAILURE() << "no error for " << body;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  expect_error("0 0 0\n1 0 0float\n0 1 0\n3 0 1 2\n", "PLY line 11: expected numbers only");
  expect_error("0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "PLY line 11: expected 3 values for its element, found 2");
  expect_error("0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n", "PLY line 13: expected 4 values for its element, found 5");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// Found by fuzzing: a binary PLY whose "list uint uint" length is 0x03000000 made assimp allocate
// 24 GB. The lengths are walked before assimp sees the file.
TEST(PlyBinaryLists, AListLongerThanTheFileIsRefusedBeforeAssimpAllocates) {
  std::string ply =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uint uint vertex_indices\nend_header\n";
  ply += std::string(36, '\0');                      // three vertices at the origin
  ply += std::string("\x03\x00\x00\x00", 4);         // a length of 0x03000000, big-endian
  ply += std::string(12, '\0');
  const auto path = std::filesystem::temp_directory_path() / "caligo_ply_binary_list.ply";
  std::ofstream(path, std::ios::binary) << ply;
  try {
    load_mesh(path.string(), {"scene.json", "/shapes/0"});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a list says it holds 50331648 values"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

// ---- STL and OFF ---------------------------------------------------------------------------

// A binary STL of the given triangles (normal left zero, as many exporters write it), with a
// header that starts with "solid" to show that the size decides, not the first word.
std::string binary_stl(const std::vector<std::array<Vec3, 3>>& triangles) {
  std::string stl = "solid binary header";
  stl.resize(80, ' ');
  append_bytes(stl, uint32_t(triangles.size()));
  for (const auto& t : triangles) {
    for (int i = 0; i < 3; ++i) append_bytes(stl, 0.0f);
    for (Vec3 p : t) {
      append_bytes(stl, p.x);
      append_bytes(stl, p.y);
      append_bytes(stl, p.z);
    }
    append_bytes(stl, uint16_t(0));
  }
  return stl;
}

TEST_F(MeshLoaderTest, BinaryStlKeepsItsTrianglesEvenWithASolidHeader) {
  const TriangleMesh mesh =
      load_mesh(write("two.stl", binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}}})),
                kWhere);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  EXPECT_TRUE(mesh.normals.empty());  // facet normals (here zero) are not shading normals
  expect_near(geometric_normal(mesh, 0), {0, 0, 1});
  expect_near(geometric_normal(mesh, 1), {0, 0, 1});
}

TEST_F(MeshLoaderTest, AsciiStlTriangle) {
  const TriangleMesh mesh = load_mesh(write("tri.STL",
                                            "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 2\n"
                                            "   vertex 3 0 2\n   vertex 0 4 2\n  endloop\n endfacet\nendsolid t\n"),
                                      kWhere);
  ASSERT_EQ(mesh.triangle_count(), 1u);
  expect_near(mesh.positions[mesh.indices[1]], {3, 0, 2});
  expect_near(geometric_normal(mesh, 0), {0, 0, 1});
}

TEST_F(MeshLoaderTest, TruncatedOrForeignStlIsALocatedError) {
  std::string cut = binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}});
  cut[0] = 'X';  // not "solid": it can only be binary
  cut.resize(cut.size() - 7);
  EXPECT_TRUE(contains(load_error(write("cut.stl", cut)), "a binary STL of 1 triangles has 134 bytes, this file 127"));
  EXPECT_TRUE(contains(load_error(write("short.stl", "PK\x03\x04")), "cannot parse STL: neither binary"));
  EXPECT_TRUE(contains(load_error(write("nul.stl", std::string("solid a\0 b\n", 11))),
                       "cannot parse STL: a byte that is not text (0x00) at offset 7"));
}

constexpr const char* kOffCube =
    "OFF\n# a unit cube\n8 6 12\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 0 4 7 3\n4 1 2 6 5\n";

TEST_F(MeshLoaderTest, OffQuadsAreTriangulated) {
  const TriangleMesh mesh = load_mesh(write("cube.off", kOffCube), kWhere);
  EXPECT_EQ(mesh.triangle_count(), 12u);
  EXPECT_EQ(mesh.positions.size(), 8u);
  Bounds3 bounds;
  for (Vec3 p : mesh.positions) bounds.extend(p);
  expect_near(bounds.lo, {0, 0, 0});
  expect_near(bounds.hi, {1, 1, 1});
  expect_near(geometric_normal(mesh, 0), {0, 0, -1});  // 0 3 2 1 faces down
}

TEST_F(MeshLoaderTest, OffHeaderCannotPromiseMoreThanTheFileHolds) {
  EXPECT_TRUE(contains(load_error(write("big.off", "OFF\n90000000 1 0\n0 0 0\n")), "the OFF header declares 90000000 vertex"));
  EXPECT_TRUE(contains(load_error(write("many.off", "OFF 4000 4000 0\n0 0 0\n")),
                       "more than the file's 22 bytes can hold"));
  EXPECT_TRUE(contains(load_error(write("word.off", "OFF\neight 6 12\n")), "the header's vertex count is \"eight\""));
  EXPECT_TRUE(contains(load_error(write("none.off", "PLY\n")), "expected \"OFF\" first"));
}

}  // namespace
}  // namespace caligo
