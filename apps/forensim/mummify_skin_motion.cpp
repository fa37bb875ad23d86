#include "mummify_skin_motion.hpp"

#include <cmath>
#include <cstring>

#include "body/tracking.hpp"
#include "core/error.hpp"
#include "core/timer.hpp"
#include "mummify_skin.hpp"
#include "pbd/skin_checkpoint.hpp"
#include "skin/skin_moisture.hpp"

namespace forensim::cli {

MummifySkinMotion::MummifySkinMotion(const BodyModel& body, double initial_moisture, const SkinMotionJob& job)
    : m_body(body), m_initial_moisture(initial_moisture), m_job(job), m_positions(body.skin.positions) {
  require_input(job.substeps >= 1, "skin motion", "substeps", "must be at least 1");
  require_input(initial_moisture > 0.0, "skin motion", "initial moisture", "must be positive");
  m_rest_offsets = skin_rest_offsets(body);
  if (!job.pbd) return;
  SkinSettings settings = job.settings;
  settings.gravity_mm_per_s2 = Vec3::Zero();
  m_model = std::make_unique<SkinModel>(make_skin_model(body, settings));
  m_sim = std::make_unique<SkinSimulation>(*m_model);
  m_state = initial_skin_state(*m_model);
}

MummifySkinMotion::~MummifySkinMotion() = default;

const SkinModel& MummifySkinMotion::model() const {
  require_input(m_model != nullptr, "skin motion", "model", "the skin follows the volume rigidly (\"pbd\": false)");
  return *m_model;
}

SkinMotionReport MummifySkinMotion::advance(const std::vector<Vec3>& from_nodes, const DesiccationState& state) {
  const std::size_t nv = m_body.volume.vertex_count();
  require_input(from_nodes.size() == nv && state.positions.size() == nv, "skin motion", "volume nodes",
                std::to_string(from_nodes.size()) + " and " + std::to_string(state.positions.size()) +
                    " positions for " + std::to_string(nv) + " volume nodes");
  SkinMotionReport report;
  const Stopwatch watch;
  if (!m_job.pbd) {
    m_positions = skin_positions_for_frame(m_body, m_rest_offsets, state.positions);
    m_time_s = state.time_s;
    report.seconds = watch.seconds();
    return report;
  }
  const double span_s = state.time_s - m_time_s;
  if (!(span_s > 0.0)) return report;
  skin_moisture_ratio(m_body.tracking.face_nodes, m_body.tracking.weights, state.node_moisture, m_initial_moisture,
                      m_moisture);
  const double dt = span_s / m_job.substeps;
  m_nodes.resize(nv);
  for (int s = 1; s <= m_job.substeps; ++s) {
    // The volume moves linearly from the previous shape to the new one over the substeps.
    const double f = static_cast<double>(s) / m_job.substeps;
    if (s == m_job.substeps) {
      m_nodes = state.positions;
    } else {
      for (std::size_t i = 0; i < nv; ++i) m_nodes[i] = from_nodes[i] + f * (state.positions[i] - from_nodes[i]);
    }
    const SkinStepReport r = m_sim->step(m_state, m_nodes, m_moisture, dt);
    report.pulled = r.pulled;
    report.slipped = r.slipped;
    report.collisions = r.collisions;
    report.max_tracking_excess_mm = r.max_tracking_excess_mm;
    ++report.steps;
  }
  m_time_s = state.time_s;
  m_positions = m_state.positions;
  report.seconds = watch.seconds();
  return report;
}

std::string MummifySkinMotion::checkpoint_bytes() const {
  if (!m_job.pbd) return {};
  std::string out(sizeof(double), '\0');
  std::memcpy(out.data(), &m_time_s, sizeof(double));
  return out + skin_state_bytes(m_state);
}

void MummifySkinMotion::restore(const std::string& bytes, const DesiccationState& state, const std::string& source) {
  if (!m_job.pbd) {
    require_input(bytes.empty(), source, "skin", "holds a position-based skin state, but the job has \"pbd\": false");
    m_time_s = state.time_s;
    m_positions = skin_positions_for_frame(m_body, m_rest_offsets, state.positions);
    return;
  }
  require_input(bytes.size() > sizeof(double), source, "skin",
                "holds no position-based skin state (written with \"pbd\": false?)");
  double time_s = 0.0;
  std::memcpy(&time_s, bytes.data(), sizeof(double));
  require_input(std::isfinite(time_s) && time_s >= 0.0 && time_s <= state.time_s, source, "skin",
                "time of the last skin step does not fit the desiccation state");
  m_state = skin_state_from_bytes(bytes.substr(sizeof(double)), m_model->vertex_count(), source + " (skin)");
  m_time_s = time_s;
  m_positions = m_state.positions;
}

}  // namespace forensim::cli
