#pragma once

#include <nlohmann/json.hpp>

#include "retarget/retarget.hpp"

namespace gr {

/// Every field of `options` as JSON, by its C++ name, nested as the structs are: typed
/// values already parsed and checked (enums and formats by name, infinite numbers as
/// "inf"), for a process that runs options another one parsed (a batch job).
nlohmann::json retarget_options_to_json(const RetargetOptions& options);

/// The options retarget_options_to_json wrote, field by field (no command-line parse).
/// @throw std::invalid_argument naming the field for a missing, unknown or mistyped one.
RetargetOptions retarget_options_from_typed_json(const nlohmann::json& object);

}  // namespace gr
