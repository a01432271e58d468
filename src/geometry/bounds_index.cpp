#include "geometry/bounds_index.h"

#include <embree3/rtcore.h>

#include <stdexcept>
#include <string>

#include "core/ray_solids.h"

namespace caligo {
namespace {

// Extends Embree's context with the output list; Embree passes the context to the callback.
struct CandidateContext {
  RTCIntersectContext context;  // must be first
  std::vector<uint32_t>* out;
};

}  // namespace

struct BoundsIndex::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<Bounds3> boxes;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  static void bounds(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const Impl*>(args->geometryUserPtr);
    const Bounds3& b = self->boxes[args->primID];
    *args->bounds_o = {b.lo.x, b.lo.y, b.lo.z, 0.0f, b.hi.x, b.hi.y, b.hi.z, 0.0f};
  }

  // Records the box when the ray overlaps it and never reports a hit, so traversal visits
  // every overlapping leaf.
  static void intersect(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    const auto* self = static_cast<const Impl*>(args->geometryUserPtr);
    const RTCRay& r = reinterpret_cast<RTCRayHit*>(args->rayhit)->ray;
    const Bounds3& box = self->boxes[args->primID];
    if (ray_box({r.org_x, r.org_y, r.org_z}, {r.dir_x, r.dir_y, r.dir_z}, box.lo, box.hi, r.tnear, r.tfar))
      reinterpret_cast<CandidateContext*>(args->context)->out->push_back(args->primID);
  }
};

BoundsIndex::BoundsIndex() : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("cannot create an Embree device");
  impl_->scene = rtcNewScene(impl_->device);
}

BoundsIndex::~BoundsIndex() = default;
BoundsIndex::BoundsIndex(BoundsIndex&&) noexcept = default;
BoundsIndex& BoundsIndex::operator=(BoundsIndex&&) noexcept = default;

uint32_t BoundsIndex::add(const Bounds3& box) {
  if (!is_finite(box.lo) || !is_finite(box.hi) || box.empty())
    throw std::invalid_argument("volume bounds must be finite and non-empty");
  impl_->boxes.push_back(box);
  return uint32_t(impl_->boxes.size() - 1);
}

void BoundsIndex::commit() {
  if (!impl_->boxes.empty()) {
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(impl_->boxes.size()));
    rtcSetGeometryUserData(geom, impl_.get());
    rtcSetGeometryBoundsFunction(geom, Impl::bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, Impl::intersect);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  if (rtcGetDeviceError(impl_->device) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree: cannot build the volume BVH");
}

size_t BoundsIndex::size() const { return impl_->boxes.size(); }

void BoundsIndex::candidates(const Ray& ray, std::vector<uint32_t>& out) const {
  out.clear();
  if (impl_->boxes.empty() || !is_finite(ray.origin) || !is_finite(ray.direction)) return;
  CandidateContext ctx;
  rtcInitIntersectContext(&ctx.context);
  ctx.out = &out;
  RTCRayHit rh{};
  rh.ray = {ray.origin.x,
            ray.origin.y,
            ray.origin.z,
            ray.tmin,
            ray.direction.x,
            ray.direction.y,
            ray.direction.z,
            0.0f,
            ray.tmax,
            0xffffffffu,
            0,
            0};
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx.context, &rh);
}

}  // namespace caligo
