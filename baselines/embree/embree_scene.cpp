// EmbreeScene: raykernel meshes in Embree 3.
#include "embree_scene.hpp"

#include <atomic>
#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace raykernel::baseline {
namespace {

float to_float(double c, FloatConversion& report) {
  const auto f = static_cast<float>(c);
  ++report.coordinates;
  if (static_cast<double>(f) != c) {
    ++report.inexact;
    if (c != 0) {
      if (std::fabs(f) < std::numeric_limits<float>::min()) ++report.underflowed;
      report.max_relative_change = std::max(report.max_relative_change, std::fabs(static_cast<double>(f) - c) / std::fabs(c));
    }
  }
  return f;
}

void throw_on_error(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(e) + ")");
}

RTCRayHit ray_hit(const Ray& r, float t_max) {
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(r.origin.x);
  rh.ray.org_y = static_cast<float>(r.origin.y);
  rh.ray.org_z = static_cast<float>(r.origin.z);
  rh.ray.dir_x = static_cast<float>(r.direction.x);
  rh.ray.dir_y = static_cast<float>(r.direction.y);
  rh.ray.dir_z = static_cast<float>(r.direction.z);
  rh.ray.tnear = 0;
  rh.ray.tfar = t_max;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// The context all_hits passes: Embree hands it to the filter, which appends each hit and rejects it.
struct CollectingContext {
  RTCIntersectContext context;  // first: Embree sees a pointer to it
  std::vector<EmbreeScene::Hit>* hits;
};

void collect_hit(const RTCFilterFunctionNArguments* args) {
  const auto* collecting = reinterpret_cast<const CollectingContext*>(args->context);
  if (collecting->hits == nullptr) return;  // intersect() and intersect8(): accept the hit
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    collecting->hits->push_back({RTCHitN_primID(args->hit, args->N, i), RTCRayN_tfar(args->ray, args->N, i)});
    args->valid[i] = 0;  // rejected: the traversal continues
  }
}

}  // namespace

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Mode mode = Mode::fast;
  bool collects = false;
  FloatConversion conversion;
  std::atomic<std::int64_t> bytes{0};  // what the device holds (its memory monitor's running sum)
  std::vector<float> vertices;  // the float mesh
  std::vector<std::array<std::uint32_t, 3>> triangles;
  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (device != nullptr) rtcReleaseDevice(device);
  }
};

// Embree's memory monitor: every allocation and release of the device, added up (returning true lets it go on).
static bool count_bytes(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<std::atomic<std::int64_t>*>(user)->fetch_add(bytes, std::memory_order_relaxed);
  return true;
}

EmbreeScene::EmbreeScene(const Mesh& mesh, Mode mode, unsigned threads, bool collect_all_hits, Quality quality)
    : impl_(std::make_unique<Impl>()) {
  if (const auto problem = validate(mesh)) throw std::invalid_argument("EmbreeScene: " + *problem);
  impl_->mode = mode;
  impl_->collects = collect_all_hits;
  const std::string config = threads == 0 ? std::string() : "threads=" + std::to_string(threads);
  impl_->device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (impl_->device == nullptr) throw std::runtime_error("Embree: rtcNewDevice failed");
  rtcSetDeviceMemoryMonitorFunction(impl_->device, count_bytes, &impl_->bytes);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, mode == Mode::robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  rtcSetSceneBuildQuality(impl_->scene, quality == Quality::high ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.vertices.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
  throw_on_error(impl_->device, "allocating the buffers");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    for (int a = 0; a < 3; ++a) {
      const double c = a == 0 ? v.x : a == 1 ? v.y : v.z;
      const float f = to_float(c, impl_->conversion);
      if (std::isinf(f)) {
        rtcReleaseGeometry(geometry);
        throw std::invalid_argument("EmbreeScene: vertex " + std::to_string(i) + " is beyond the float range");
      }
      vertices[3 * i + static_cast<std::size_t>(a)] = f;
    }
  }
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
    for (int j = 0; j < 3; ++j) indices[3 * k + static_cast<std::size_t>(j)] = mesh.triangles[k][static_cast<std::size_t>(j)];
  impl_->vertices.assign(vertices, vertices + 3 * mesh.vertices.size());
  impl_->triangles = mesh.triangles;
  if (collect_all_hits) rtcSetGeometryIntersectFilterFunction(geometry, collect_hit);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
  throw_on_error(impl_->device, "building the scene");
}

EmbreeScene::~EmbreeScene() = default;
EmbreeScene::EmbreeScene(EmbreeScene&&) noexcept = default;
EmbreeScene& EmbreeScene::operator=(EmbreeScene&&) noexcept = default;

EmbreeScene::Mode EmbreeScene::mode() const noexcept { return impl_->mode; }
const FloatConversion& EmbreeScene::conversion() const noexcept { return impl_->conversion; }
std::size_t EmbreeScene::device_bytes() const noexcept {
  return static_cast<std::size_t>(std::max<std::int64_t>(0, impl_->bytes.load(std::memory_order_relaxed)));
}

std::optional<EmbreeScene::Hit> EmbreeScene::intersect(const Ray& ray, float t_max) const {
  CollectingContext context{{}, nullptr};
  rtcInitIntersectContext(&context.context);
  RTCRayHit rh = ray_hit(ray, t_max);
  rtcIntersect1(impl_->scene, &context.context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return Hit{rh.hit.primID, rh.ray.tfar};
}

std::vector<EmbreeScene::Hit> EmbreeScene::all_hits(const Ray& ray, float t_max) const {
  if (!impl_->collects) throw std::logic_error("EmbreeScene::all_hits needs a scene built with collect_all_hits");
  std::vector<Hit> hits;
  CollectingContext context{{}, &hits};
  rtcInitIntersectContext(&context.context);
  RTCRayHit rh = ray_hit(ray, t_max);
  rtcIntersect1(impl_->scene, &context.context, &rh);
  return hits;
}

Mesh EmbreeScene::float_mesh() const {
  Mesh m;
  m.vertices.reserve(impl_->vertices.size() / 3);
  for (std::size_t i = 0; i + 2 < impl_->vertices.size(); i += 3)
    m.vertices.push_back({impl_->vertices[i], impl_->vertices[i + 1], impl_->vertices[i + 2]});
  m.triangles = impl_->triangles;
  return m;
}

bool EmbreeScene::occluded(const Ray& ray, float t_max) const {
  CollectingContext context{{}, nullptr};
  rtcInitIntersectContext(&context.context);
  RTCRay r = ray_hit(ray, t_max).ray;
  rtcOccluded1(impl_->scene, &context.context, &r);
  return r.tfar == -std::numeric_limits<float>::infinity();
}

void EmbreeScene::intersect8(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const {
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 packet{};
  const std::size_t n = std::min<std::size_t>(8, rays.size());
  for (std::size_t i = 0; i < 8; ++i) {
    valid[i] = i < n ? -1 : 0;
    const RTCRayHit one = ray_hit(i < n ? rays[i] : Ray{{0, 0, 0}, {1, 0, 0}}, 1e38f);
    packet.ray.org_x[i] = one.ray.org_x, packet.ray.org_y[i] = one.ray.org_y, packet.ray.org_z[i] = one.ray.org_z;
    packet.ray.dir_x[i] = one.ray.dir_x, packet.ray.dir_y[i] = one.ray.dir_y, packet.ray.dir_z[i] = one.ray.dir_z;
    packet.ray.tnear[i] = 0, packet.ray.tfar[i] = one.ray.tfar, packet.ray.mask[i] = 0xffffffffu;
    packet.ray.time[i] = 0, packet.ray.flags[i] = 0, packet.ray.id[i] = static_cast<unsigned>(i);
    packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  CollectingContext context{{}, nullptr};
  rtcInitIntersectContext(&context.context);
  rtcIntersect8(valid, impl_->scene, &context.context, &packet);
  for (std::size_t i = 0; i < n && i < hits.size(); ++i)
    hits[i] = packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID ? std::nullopt
                                                              : std::optional<Hit>(Hit{packet.hit.primID[i], packet.ray.tfar[i]});
}

Ray float_ray(const Ray& r) {
  auto f = [](double x) { return static_cast<double>(static_cast<float>(x)); };
  return {{f(r.origin.x), f(r.origin.y), f(r.origin.z)}, {f(r.direction.x), f(r.direction.y), f(r.direction.z)}};
}

void count_float_conversion(const Ray& ray, FloatConversion& into) {
  for (double c : {ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y, ray.direction.z}) (void)to_float(c, into);
}

}  // namespace raykernel::baseline
