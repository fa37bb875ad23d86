#pragma once
/// Escaping text for XML and HTML (VTU/PVD attribute values, report pages).

#include <string>
#include <string_view>

namespace forensim {

/// Replaces &, <, >, " and ' by their entities (&amp; &lt; &gt; &quot; &apos;), valid in XML and HTML5 text
/// and attribute values.
std::string xml_escape(std::string_view text);

}  // namespace forensim
