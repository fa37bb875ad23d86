#include "core/timer.hpp"

namespace forensim {

void Timings::add(const std::string& stage, double seconds) {
  for (auto& [name, value] : m_stages) {
    if (name == stage) {
      value += seconds;
      return;
    }
  }
  m_stages.emplace_back(stage, seconds);
}

double Timings::get(const std::string& stage) const {
  for (const auto& [name, value] : m_stages) {
    if (name == stage) return value;
  }
  return 0.0;
}

double Timings::total() const {
  double sum = 0.0;
  for (const auto& stage : m_stages) sum += stage.second;
  return sum;
}

}  // namespace forensim
