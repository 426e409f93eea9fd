// How each kind of capture writes a duration and an unknown value.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "latsim/capture/capture.hpp"

namespace latsim::capture {

/// Whether a cell holds no value: empty or NA; in an OVR Metrics export
/// also 9999, the tool's "not available".
bool not_available(Generation g, std::string_view cell);

/// Why column `name` of a capture of generation `g` is not a duration (none:
/// it is one, or the generation does not say).
std::optional<std::string> not_a_duration(Generation g, const std::string& name);

/// A cell as milliseconds in the generation's units: OVR Metrics'
/// *_microseconds divided by 1000, a VrApi field's "1.73ms", otherwise the
/// number itself. None when the cell is not such a number.
std::optional<double> cell_ms(Generation g, const std::string& name, std::string_view cell);

/// What cell_ms expects of column `name`, for a message ("milliseconds", ...).
std::string unit_name(Generation g, const std::string& name);

/// A plain decimal number (the whole text), or none.
std::optional<double> parse_number(std::string_view text);

}  // namespace latsim::capture
