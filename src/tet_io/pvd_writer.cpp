#include "tet_io/pvd_writer.hpp"

#include <cmath>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "tet_io/number_text.hpp"
#include "tet_io/text_cursor.hpp"
#include "tet_io/xml_lite.hpp"

namespace forensim {

PvdSeries::PvdSeries(std::filesystem::path pvd_path, std::vector<PvdEntry> entries)
    : m_path(std::move(pvd_path)), m_entries(std::move(entries)) {
  write();
}

void PvdSeries::add(double time, const std::string& relative_vtu_path) {
  const std::string location = "time step " + std::to_string(m_entries.size());
  require_input(std::isfinite(time), m_path.string(), location, "time is not finite");
  require_input(!relative_vtu_path.empty(), m_path.string(), location, "data file path is empty");
  m_entries.push_back({time, relative_vtu_path});
  write();
}

void PvdSeries::write() const {
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const PvdEntry& e : m_entries) {
    out += "    <DataSet timestep=\"";
    append_double(out, e.time);
    out += "\" group=\"\" part=\"0\" file=\"" + xml_escape(e.file) + "\"/>\n";
  }
  out += "  </Collection>\n</VTKFile>\n";
  write_file_atomic(m_path, out);
}

std::vector<PvdEntry> read_pvd(const std::filesystem::path& path) {
  const std::string bytes = read_file(path, std::size_t{256} << 20);
  return parse_pvd(bytes, path.string());
}

std::vector<PvdEntry> parse_pvd(std::string_view bytes, const std::string& source) {
  const XmlDocument doc = parse_xml(bytes, source);
  const std::string* type = doc.root.attribute("type");
  if (doc.root.name != "VTKFile" || !type || *type != "Collection") {
    throw InputError(source, doc.root.location(), "not a VTK Collection (.pvd) file");
  }
  const XmlElement* collection = doc.root.child("Collection");
  if (!collection) throw InputError(source, doc.root.location(), "no <Collection> element");
  std::vector<PvdEntry> entries;
  for (const XmlElement& e : collection->children) {
    if (e.name != "DataSet") continue;
    const std::string* time = e.attribute("timestep");
    const std::string* file = e.attribute("file");
    if (!file) throw InputError(source, e.location(), "<DataSet> has no file attribute");
    PvdEntry entry;
    entry.file = *file;
    if (time && (!parse_double(*time, entry.time) || !std::isfinite(entry.time))) {
      throw InputError(source, e.location(), "timestep '" + *time + "' is not a finite number");
    }
    entries.push_back(std::move(entry));
  }
  return entries;
}

}  // namespace forensim
