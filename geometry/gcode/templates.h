// Start/end G-code templates (stdlib/gcode/<flavour>/{start,end}.gcode): `{name}` is a property
// or a print field, `{{`/`}}` are braces.
#pragma once

#include <string>
#include <string_view>

#include "runtime/base/result.h"
#include "runtime/context/context.h"

namespace tranche::gcode {

// Where stdlib/ is: $TRANCHE_STDLIB, else the checkout's stdlib (compile time), else next to the
// executable (../stdlib, ../share/tranche/stdlib, ../../stdlib).
std::string stdlib_dir();

// Reads stdlib/gcode/<flavour>/<part>.gcode (`part`: "start" or "end").
Result<std::string> load_template(const std::string& stdlib, schema::Flavor flavor, std::string_view part,
                                  std::string* file_used = nullptr);

// Replaces each {name} with the property or field value (numbers without unit, enums by name).
// Errors name `file` and the line.
Result<std::string> render_template(std::string_view text, const std::string& file, const ctx::Context& c,
                                    const ctx::PropertyValues& props);

}  // namespace tranche::gcode
