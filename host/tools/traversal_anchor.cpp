// Embree's closest-hit queries as an anchor for clpt's traversal rates (traversal_anchor.h).
// Without Embree in the build, only the checks exist.
#include "tools/traversal_anchor.h"

#include "util/error.h"

#ifdef CLPT_WITH_EMBREE
#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "util/clock.h"
#endif

namespace clpt {

bool traversal_anchor_available(const std::string& name) {
#ifdef CLPT_WITH_EMBREE
  return name == "embree";
#else
  (void)name;
  return false;
#endif
}

void check_traversal_anchor(const std::string& name, const std::string& option) {
  if (name != "embree")
    throw Error(ExitCode::Usage, option + ": unknown anchor '" + name + "' (expected embree)");
  if (!traversal_anchor_available(name))
    throw Error(ExitCode::Usage, option + " " + name + ": this clpt was built without Embree "
                                 "(install libembree-dev and reconfigure with CMake)");
}

#ifdef CLPT_WITH_EMBREE
namespace {

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~EmbreeScene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

// tnear: 0 for triangles alone (trace.cl intersects them for t > 0), the sample ray's t_min (the
// scene's ray epsilon, as trace.cl's sphere tests) when the scene holds spheres.
void set_ray(RTCRayHit& rh, const StatsRay& r, float tnear) {
  rh.ray.org_x = float(r.origin[0]);
  rh.ray.org_y = float(r.origin[1]);
  rh.ray.org_z = float(r.origin[2]);
  rh.ray.dir_x = float(r.direction[0]);
  rh.ray.dir_y = float(r.direction[1]);
  rh.ray.dir_z = float(r.direction[2]);
  rh.ray.tnear = tnear;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.time = 0;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// One pass of rays [begin, end) of the sample: hits.
uint64_t pass_single(RTCScene scene, const std::vector<StatsRay>& rays, bool with_t_min, size_t begin, size_t end) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  uint64_t hits = 0;
  for (size_t i = begin; i < end; ++i) {
    RTCRayHit rh;
    set_ray(rh, rays[i], with_t_min ? float(rays[i].t_min) : 0.f);
    rtcIntersect1(scene, &context, &rh);
    hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }
  return hits;
}

uint64_t pass_packets(RTCScene scene, const std::vector<StatsRay>& rays, bool with_t_min, size_t begin, size_t end) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  uint64_t hits = 0;
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[16];
  for (size_t i = begin; i < end; i += 16) {
    for (size_t k = 0; k < 16; ++k) {
      const bool live = i + k < end;
      valid[k] = live ? -1 : 0;
      RTCRayHit rh;
      const StatsRay& r = rays[live ? i + k : i];
      set_ray(rh, r, with_t_min ? float(r.t_min) : 0.f);
      packet.ray.org_x[k] = rh.ray.org_x;
      packet.ray.org_y[k] = rh.ray.org_y;
      packet.ray.org_z[k] = rh.ray.org_z;
      packet.ray.dir_x[k] = rh.ray.dir_x;
      packet.ray.dir_y[k] = rh.ray.dir_y;
      packet.ray.dir_z[k] = rh.ray.dir_z;
      packet.ray.tnear[k] = rh.ray.tnear;
      packet.ray.tfar[k] = rh.ray.tfar;
      packet.ray.time[k] = 0;
      packet.ray.mask[k] = ~0u;
      packet.ray.id[k] = 0;
      packet.ray.flags[k] = 0;
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, scene, &context, &packet);
    for (size_t k = 0; k < 16; ++k) hits += valid[k] && packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
  }
  return hits;
}

// Rays/s of `pass` over the sample on `threads` threads, each its own slice of the sample, passing
// over it again and again until min_seconds have passed (threads started once: a pass of a few
// thousand rays takes well under a millisecond, less than starting a thread).
template <typename Pass>
double rate(const Pass& pass, RTCScene scene, const std::vector<StatsRay>& rays, bool with_t_min, int threads,
            double min_seconds, uint64_t& hits, double& per_cpu_s) {
  const size_t n = rays.size();
  // Slices of whole packets, so that both queries split the sample alike.
  const size_t slice = ((n + size_t(threads) - 1) / size_t(threads) + 15) / 16 * 16;
  std::vector<uint64_t> slice_hits(size_t(threads), 0), slice_rays(size_t(threads), 0);
  const auto start = Clock::now();
  const double cpu_start = process_cpu_seconds();
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t) {
    const size_t b = std::min(n, slice * size_t(t)), e = std::min(n, b + slice);
    workers.emplace_back([&, b, e, t] {
      do {
        slice_hits[size_t(t)] = pass(scene, rays, with_t_min, b, e);
        slice_rays[size_t(t)] += e - b;
      } while (seconds_since(start) < min_seconds);
    });
  }
  for (std::thread& w : workers) w.join();
  const double elapsed = seconds_since(start);
  hits = 0;
  uint64_t traced = 0;
  for (int t = 0; t < threads; ++t) {
    hits += slice_hits[size_t(t)];
    traced += slice_rays[size_t(t)];
  }
  per_cpu_s = double(traced) / std::max(process_cpu_seconds() - cpu_start, 1e-9);
  return double(traced) / elapsed;
}

// Embree's scene of `triangles` (one geometry, each triangle its own three vertices) and `spheres`
// (a second geometry of sphere points, each its centre and radius) built on `device` with `flags`
// and `quality`; the build's seconds in build_s.
void build_scene(EmbreeScene& e, const std::vector<GpuTriangle>& triangles, const std::vector<GpuSphere>& spheres,
                 RTCSceneFlags flags, RTCBuildQuality quality, double& build_s) {
  e.scene = rtcNewScene(e.device);
  rtcSetSceneFlags(e.scene, flags);
  rtcSetSceneBuildQuality(e.scene, quality);
  if (!triangles.empty()) {
    RTCGeometry geometry = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geometry, quality);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * triangles.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                   RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles.size()));
    for (size_t i = 0; i < triangles.size(); ++i) {
      const GpuTriangle& t = triangles[i];
      for (int k = 0; k < 3; ++k) {
        vertices[9 * i + size_t(k)] = t.v0[k];
        vertices[9 * i + 3 + size_t(k)] = t.v1[k];
        vertices[9 * i + 6 + size_t(k)] = t.v2[k];
      }
      for (unsigned k = 0; k < 3; ++k) indices[3 * i + k] = unsigned(3 * i + k);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(e.scene, geometry);
    rtcReleaseGeometry(geometry);
  }
  if (!spheres.empty()) {
    // A sphere is stored as a surface point s0, its outward normal n0 and radius r, each with a
    // remainder (kernels/types.h): its centre is s0 - r n0, summed in double, then rounded.
    RTCGeometry geometry = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    rtcSetGeometryBuildQuality(geometry, quality);
    auto* points = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.size()));
    for (size_t i = 0; i < spheres.size(); ++i) {
      const GpuSphere& s = spheres[i];
      const double r = double(s.radius) + double(s.radius_lo);
      for (int k = 0; k < 3; ++k)
        points[4 * i + size_t(k)] = float(double(s.surface_point[k]) + double(s.surface_point_lo[k]) -
                                          r * (double(s.surface_normal[k]) + double(s.surface_normal_lo[k])));
      points[4 * i + 3] = float(r);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(e.scene, geometry);
    rtcReleaseGeometry(geometry);
  }
  const auto start = Clock::now();
  rtcCommitScene(e.scene);
  build_s = seconds_since(start);
  if (rtcGetDeviceError(e.device) != RTC_ERROR_NONE)
    throw Error(ExitCode::Failure, "--traversal-anchor embree: Embree failed to build the scene");
}

}  // namespace

AnchorRates time_embree_anchor(const std::vector<GpuTriangle>& triangles, const std::vector<GpuSphere>& spheres,
                               const StatsRaySample& sample, int threads, double min_seconds, int width) {
  AnchorRates out;
  out.name = "embree " + std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
             std::to_string(RTC_VERSION_PATCH);
  out.threads = std::max(1, threads);
  out.rays = sample.rays.size();
  out.triangles = triangles.size();
  out.spheres = spheres.size();
  if ((triangles.empty() && spheres.empty()) || sample.rays.empty()) return out;
  const bool with_t_min = !spheres.empty();
  const std::string config = "threads=" + std::to_string(out.threads);
  if (width != 0 && width != 4 && width != 8)
    throw Error(ExitCode::Usage, "--traversal-anchor-width: " + std::to_string(width) + " (expected 4 or 8)");
  if (width != 0) out.tri_accel = "bvh" + std::to_string(width) + ".triangle4";
  {
    EmbreeScene e;
    const std::string fastest = out.tri_accel.empty() ? config : config + ",tri_accel=" + out.tri_accel;
    e.device = rtcNewDevice(fastest.c_str());
    if (!e.device) throw Error(ExitCode::Failure, "--traversal-anchor embree: rtcNewDevice failed");
    build_scene(e, triangles, spheres, RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_HIGH, out.build_s);
    out.single_per_s = rate(pass_single, e.scene, sample.rays, with_t_min, out.threads, min_seconds, out.hits, out.single_per_cpu_s);
    out.packet16_per_s =
        rate(pass_packets, e.scene, sample.rays, with_t_min, out.threads, min_seconds, out.packet_hits, out.packet16_per_cpu_s);
  }
  {
    EmbreeScene e;  // one scene at a time: the first is released before this one is built
    e.device = rtcNewDevice(config.c_str());
    if (!e.device) throw Error(ExitCode::Failure, "--traversal-anchor embree: rtcNewDevice failed");
    build_scene(e, triangles, spheres, RTC_SCENE_FLAG_ROBUST, RTC_BUILD_QUALITY_MEDIUM, out.robust_build_s);
    out.robust_single_per_s =
        rate(pass_single, e.scene, sample.rays, with_t_min, out.threads, min_seconds, out.robust_hits, out.robust_single_per_cpu_s);
  }
  return out;
}
#else
AnchorRates time_embree_anchor(const std::vector<GpuTriangle>&, const std::vector<GpuSphere>&, const StatsRaySample&, int,
                               double, int) {
  throw Error(ExitCode::Usage, "--traversal-anchor embree: this clpt was built without Embree");
}
#endif

}  // namespace clpt
