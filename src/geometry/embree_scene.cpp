#include "geometry/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>

namespace caligo {
namespace {

// Embree reports errors through a callback; exceptions must not unwind through its C
// frames, so the message is kept and thrown after the API call returns.
void embree_error(void* user, RTCError, const char* message) {
  auto* last = static_cast<std::string*>(user);
  if (last->empty()) *last = message ? message : "unknown error";
}

RTCRayHit to_embree(const Ray& ray) {
  RTCRayHit rh{};
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.direction.x;
  rh.ray.dir_y = ray.direction.y;
  rh.ray.dir_z = ray.direction.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.mask = 0xffffffffu;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

Ray from_embree(const RTCRay& r) {
  return {{r.org_x, r.org_y, r.org_z}, {r.dir_x, r.dir_y, r.dir_z}, r.tnear, r.tfar};
}

// Collects every candidate hit during an all-hits query and rejects it so traversal goes on.
struct AllHitsContext {
  RTCIntersectContext context;  // must be first: Embree hands us a pointer to it
  std::vector<SurfaceHit>* out;
};

void collect_hit(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<AllHitsContext*>(args->context);
  const float t = RTCRayN_tfar(args->ray, args->N, 0);
  SurfaceHit h;
  h.t = t;
  h.geom_id = RTCHitN_geomID(args->hit, args->N, 0);
  h.prim_id = RTCHitN_primID(args->hit, args->N, 0);
  h.uv = {RTCHitN_u(args->hit, args->N, 0), RTCHitN_v(args->hit, args->N, 0)};
  h.ng = {RTCHitN_Ng_x(args->hit, args->N, 0), RTCHitN_Ng_y(args->hit, args->N, 0),
          RTCHitN_Ng_z(args->hit, args->N, 0)};
  ctx->out->push_back(h);
  args->valid[0] = 0;
}

// A shadow query that defers some geometries' hits to the caller: they are recorded and
// rejected, so traversal goes on; any other hit ends it.
struct DeferContext {
  RTCIntersectContext context;  // must be first: Embree hands us a pointer to it
  const std::vector<uint8_t>* deferred;
  std::vector<SurfaceHit>* out;
};

void defer_hit(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<DeferContext*>(args->context);
  const uint32_t geom = RTCHitN_geomID(args->hit, args->N, 0);
  if (geom >= ctx->deferred->size() || !(*ctx->deferred)[geom]) return;  // blocks
  SurfaceHit h;
  h.t = RTCRayN_tfar(args->ray, args->N, 0);
  h.geom_id = geom;
  h.prim_id = RTCHitN_primID(args->hit, args->N, 0);
  h.uv = {RTCHitN_u(args->hit, args->N, 0), RTCHitN_v(args->hit, args->N, 0)};  // opacity textures read them
  h.ng = {RTCHitN_Ng_x(args->hit, args->N, 0), RTCHitN_Ng_y(args->hit, args->N, 0),
          RTCHitN_Ng_z(args->hit, args->N, 0)};
  ctx->out->push_back(h);
  args->valid[0] = 0;
}

// Shadow rays ignore geometry that does not cast shadows.
void skip_for_shadows(const RTCFilterFunctionNArguments* args) { args->valid[0] = 0; }

}  // namespace

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<std::variant<TriangleMesh, Sphere>> shapes;
  Bounds3 bounds;
  std::string last_error;

  void throw_if_error() {
    if (last_error.empty()) return;
    const std::string message = "Embree: " + last_error;
    last_error.clear();
    throw std::runtime_error(message);
  }
  // Geometric normal of a hit, on the side of cross(p1 - p0, p2 - p0) for triangles; Embree's
  // own Ng follows a different winding convention, so it is recomputed from our copy.
  Vec3 geometric_normal(uint32_t geom_id, uint32_t prim_id, Vec3 embree_ng) const {
    if (const auto* mesh = std::get_if<TriangleMesh>(&shapes[geom_id])) {
      const uint32_t* tri = &mesh->indices[3 * size_t(prim_id)];
      const Vec3 p0 = mesh->positions[tri[0]];
      return normalize(cross(mesh->positions[tri[1]] - p0, mesh->positions[tri[2]] - p0));
    }
    return normalize(embree_ng);
  }

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  static void sphere_bounds(const RTCBoundsFunctionArguments* args);
  static void sphere_intersect(const RTCIntersectFunctionNArguments* args);
  static void sphere_occluded(const RTCOccludedFunctionNArguments* args);
};

void EmbreeScene::Impl::sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
  const Bounds3 b = sphere->world_bounds();
  *args->bounds_o = {b.lo.x, b.lo.y, b.lo.z, 0.0f, b.hi.x, b.hi.y, b.hi.z, 0.0f};
}

// Reports the near root, then (if the filter rejected it or it lies before tnear) the far
// root, so all-hits queries see both crossings of the sphere.
void EmbreeScene::Impl::sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
  RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const Ray ray = from_embree(rh->ray);
  const auto roots = intersect_sphere(*sphere, ray);
  if (!roots) return;
  for (float t : {roots->t0, roots->t1}) {
    if (t < ray.tmin || t >= rh->ray.tfar) continue;
    const Vec3 n = sphere_normal(*sphere, ray.at(t));
    RTCHit candidate{};
    candidate.Ng_x = n.x;
    candidate.Ng_y = n.y;
    candidate.Ng_z = n.z;
    candidate.u = candidate.v = 0.0f;
    candidate.primID = args->primID;
    candidate.geomID = args->geomID;
    candidate.instID[0] = args->context->instID[0];
    const float old_tfar = rh->ray.tfar;
    rh->ray.tfar = t;
    int valid = -1;
    RTCFilterFunctionNArguments fargs{&valid,
                                      args->geometryUserPtr,
                                      args->context,
                                      reinterpret_cast<RTCRayN*>(&rh->ray),
                                      reinterpret_cast<RTCHitN*>(&candidate),
                                      1};
    rtcFilterIntersection(args, &fargs);
    if (valid != 0) {
      rh->hit = candidate;
      return;
    }
    rh->ray.tfar = old_tfar;
  }
}

void EmbreeScene::Impl::sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
  RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
  const Ray ray = from_embree(*r);
  const auto roots = intersect_sphere(*sphere, ray);
  if (!roots) return;
  for (float t : {roots->t0, roots->t1}) {
    if (t < ray.tmin || t >= ray.tmax) continue;
    const Vec3 n = sphere_normal(*sphere, ray.at(t));
    RTCHit candidate{};
    candidate.Ng_x = n.x;
    candidate.Ng_y = n.y;
    candidate.Ng_z = n.z;
    candidate.primID = args->primID;
    candidate.geomID = args->geomID;
    candidate.instID[0] = args->context->instID[0];
    const float old_tfar = r->tfar;
    r->tfar = t;
    int valid = -1;
    RTCFilterFunctionNArguments fargs{
        &valid, args->geometryUserPtr, args->context, args->ray, reinterpret_cast<RTCHitN*>(&candidate), 1};
    rtcFilterOcclusion(args, &fargs);
    if (valid != 0) {
      r->tfar = -kInfinity;  // Embree's "occluded" marker
      return;
    }
    r->tfar = old_tfar;
  }
}

EmbreeScene::EmbreeScene() : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("cannot create an Embree device");
  rtcSetDeviceErrorFunction(impl_->device, embree_error, &impl_->last_error);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION | RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
}

EmbreeScene::~EmbreeScene() = default;
EmbreeScene::EmbreeScene(EmbreeScene&&) noexcept = default;
EmbreeScene& EmbreeScene::operator=(EmbreeScene&&) noexcept = default;

uint32_t EmbreeScene::add_mesh(TriangleMesh mesh) {
  if (const std::string problem = validate_mesh(mesh); !problem.empty()) throw std::invalid_argument(problem);
  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    vertices[3 * i + 0] = mesh.positions[i].x;
    vertices[3 * i + 1] = mesh.positions[i].y;
    vertices[3 * i + 2] = mesh.positions[i].z;
    impl_->bounds.extend(mesh.positions[i]);
  }
  auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangle_count()));
  std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
  rtcCommitGeometry(geom);
  const uint32_t id = uint32_t(impl_->shapes.size());
  rtcAttachGeometryByID(impl_->scene, geom, id);
  rtcReleaseGeometry(geom);
  impl_->throw_if_error();
  impl_->shapes.emplace_back(std::move(mesh));
  return id;
}

uint32_t EmbreeScene::add_sphere(const Sphere& sphere) {
  if (!is_finite(sphere.world_bounds().lo) || !is_finite(sphere.world_bounds().hi))
    throw std::invalid_argument("sphere has a non-finite placement");
  const uint32_t id = uint32_t(impl_->shapes.size());
  impl_->shapes.emplace_back(sphere);
  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geom, 1);
  rtcSetGeometryBoundsFunction(geom, Impl::sphere_bounds, nullptr);
  rtcSetGeometryIntersectFunction(geom, Impl::sphere_intersect);
  rtcSetGeometryOccludedFunction(geom, Impl::sphere_occluded);
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(impl_->scene, geom, id);
  rtcReleaseGeometry(geom);
  impl_->bounds.extend(sphere.world_bounds());
  return id;
}

void EmbreeScene::set_casts_shadows(uint32_t geom_id, bool casts) {
  RTCGeometry geom = rtcGetGeometry(impl_->scene, geom_id);
  rtcSetGeometryOccludedFilterFunction(geom, casts ? nullptr : skip_for_shadows);
  rtcCommitGeometry(geom);
}

void EmbreeScene::commit() {
  // User geometry keeps a pointer to its Sphere; the vector no longer grows after commit.
  for (size_t i = 0; i < impl_->shapes.size(); ++i)
    if (auto* s = std::get_if<Sphere>(&impl_->shapes[i])) {
      RTCGeometry geom = rtcGetGeometry(impl_->scene, uint32_t(i));
      rtcSetGeometryUserData(geom, s);
      rtcCommitGeometry(geom);
    }
  rtcCommitScene(impl_->scene);
  impl_->throw_if_error();
}

// Embree asserts (or misbehaves) on rays with non-finite components; such a ray comes only
// from a degenerate computation upstream and is treated as hitting nothing.
static bool valid_ray(const Ray& ray) {
  return is_finite(ray.origin) && is_finite(ray.direction) && !std::isnan(ray.tmin);
}

std::optional<SurfaceHit> EmbreeScene::intersect(const Ray& ray) const {
  if (!valid_ray(ray)) return std::nullopt;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = to_embree(ray);
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  SurfaceHit h;
  h.t = rh.ray.tfar;
  h.geom_id = rh.hit.geomID;
  h.prim_id = rh.hit.primID;
  h.uv = {rh.hit.u, rh.hit.v};
  h.ng = impl_->geometric_normal(h.geom_id, h.prim_id, {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
  return h;
}

bool EmbreeScene::occluded(const Ray& ray) const {
  if (!valid_ray(ray)) return true;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = to_embree(ray).ray;
  rtcOccluded1(impl_->scene, &context, &r);
  return r.tfar < 0.0f;
}

bool EmbreeScene::occluded(const Ray& ray, const std::vector<uint8_t>& deferred,
                           std::vector<SurfaceHit>& deferred_hits) const {
  if (!valid_ray(ray)) return true;
  DeferContext ctx;
  rtcInitIntersectContext(&ctx.context);
  ctx.context.filter = defer_hit;
  ctx.deferred = &deferred;
  ctx.out = &deferred_hits;
  const size_t first = deferred_hits.size();
  RTCRay r = to_embree(ray).ray;
  rtcOccluded1(impl_->scene, &ctx.context, &r);
  for (size_t i = first; i < deferred_hits.size(); ++i) {
    SurfaceHit& h = deferred_hits[i];
    h.ng = impl_->geometric_normal(h.geom_id, h.prim_id, h.ng);
  }
  return r.tfar < 0.0f;
}

void EmbreeScene::all_hits(const Ray& ray, std::vector<SurfaceHit>& out) const {
  out.clear();
  if (!valid_ray(ray)) return;
  AllHitsContext ctx;
  rtcInitIntersectContext(&ctx.context);
  ctx.context.filter = collect_hit;
  ctx.out = &out;
  RTCRayHit rh = to_embree(ray);
  rtcIntersect1(impl_->scene, &ctx.context, &rh);
  for (SurfaceHit& h : out) h.ng = impl_->geometric_normal(h.geom_id, h.prim_id, h.ng);
  std::sort(out.begin(), out.end(), [](const SurfaceHit& a, const SurfaceHit& b) {
    return a.t != b.t ? a.t < b.t : (a.geom_id != b.geom_id ? a.geom_id < b.geom_id : a.prim_id < b.prim_id);
  });
  // Embree may report one primitive's crossing more than once; keep the first.
  out.erase(std::unique(out.begin(), out.end(),
                        [](const SurfaceHit& a, const SurfaceHit& b) {
                          return a.geom_id == b.geom_id && a.prim_id == b.prim_id && a.t == b.t;
                        }),
            out.end());
}

size_t EmbreeScene::geometry_count() const { return impl_->shapes.size(); }
bool EmbreeScene::is_sphere(uint32_t id) const { return std::holds_alternative<Sphere>(impl_->shapes[id]); }
const TriangleMesh& EmbreeScene::mesh(uint32_t id) const { return std::get<TriangleMesh>(impl_->shapes[id]); }
const Sphere& EmbreeScene::sphere(uint32_t id) const { return std::get<Sphere>(impl_->shapes[id]); }
Bounds3 EmbreeScene::bounds() const { return impl_->bounds; }

}  // namespace caligo
