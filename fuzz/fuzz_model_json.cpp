// libFuzzer harness: the compliance-model file loader (JSON document to a model that predicts).
#include "fuzz_input.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = stiffpath::fuzz::text(data, size);
  STIFFPATH_FUZZ_EXPECT_REFUSAL({
    const auto document = stiffpath::core::parse_json_document(text, "fuzz.json");
    (void)stiffpath::compliance::model_from_json(document);
  })
  return 0;
}
