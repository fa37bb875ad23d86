#include "spatial/embree_scene.hpp"

#include <cstring>

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"

namespace forensim {
namespace {

std::string device_error_text(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

void check_device(RTCDevice device, const std::string& what) {
  const RTCError code = rtcGetDeviceError(device);
  if (code != RTC_ERROR_NONE) throw Error("Embree failed while " + what + ": " + device_error_text(code));
}

}  // namespace

EmbreeScene::EmbreeScene(const TriMesh& mesh, const std::string& source, bool context_filter) {
  mesh.validate(source);
  m_context_filter = context_filter;
  m_positions = mesh.positions;
  m_triangles = mesh.triangles;
  const BoundingBox box = bounding_box(m_positions);
  if (!box.empty()) {
    m_shift = box.center();
    m_extent = 0.5 * box.diagonal();
  }

  m_device = rtcNewDevice(nullptr);
  if (m_device == nullptr)
    throw Error("Embree could not create a device: " + device_error_text(rtcGetDeviceError(nullptr)));
  try {
    build();
  } catch (...) {
    if (m_scene != nullptr) rtcReleaseScene(m_scene);
    rtcReleaseDevice(m_device);
    throw;
  }
}

void EmbreeScene::build() {
  m_scene = rtcNewScene(m_device);
  check_device(m_device, "creating a scene");
  int flags = RTC_SCENE_FLAG_ROBUST;
  if (m_context_filter) flags |= RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION;
  rtcSetSceneFlags(m_scene, static_cast<RTCSceneFlags>(flags));
  rtcSetSceneBuildQuality(m_scene, RTC_BUILD_QUALITY_HIGH);

  if (!m_triangles.empty()) {
    RTCGeometry geometry = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), m_positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), m_triangles.size()));
    if (vertices == nullptr || indices == nullptr) {
      rtcReleaseGeometry(geometry);
      throw Error("Embree could not allocate buffers for " + std::to_string(m_triangles.size()) + " triangles");
    }
    for (std::size_t v = 0; v < m_positions.size(); ++v) {
      const Vec3 p = m_positions[v] - m_shift;
      for (int k = 0; k < 3; ++k) vertices[3 * v + k] = static_cast<float>(p[k]);
    }
    for (std::size_t t = 0; t < m_triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) indices[3 * t + k] = static_cast<unsigned>(m_triangles[t][k]);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(m_scene, geometry, 0);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(m_scene);
  check_device(m_device, "building the BVH");
}

EmbreeScene::~EmbreeScene() {
  if (m_scene != nullptr) rtcReleaseScene(m_scene);
  if (m_device != nullptr) rtcReleaseDevice(m_device);
}

}  // namespace forensim
