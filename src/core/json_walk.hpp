// The checks of JSON text that run beside nlohmann's parser (json_key_index.cpp); internal to core.
#pragma once

#include <string>
#include <string_view>

namespace stiffpath::core {

//! Refuses text beyond max_json_bytes, or nested beyond max_json_depth (at the bracket that
//! crosses it), before it is parsed: label:line:column: LIMIT: ...
void check_json_shape(std::string_view text, const std::string& label);
//! Refuses the first key given twice in one object of valid JSON: label:line:column: DUPLICATE: ...
void check_json_duplicates(std::string_view text, const std::string& label);

}  // namespace stiffpath::core
