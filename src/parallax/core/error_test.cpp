#include "parallax/core/error.h"

#include <gtest/gtest.h>

namespace parallax {
namespace {

std::string dashed(const std::string& field) {
  std::string option = "--" + field;
  for (char& c : option)
    if (c == '_') c = '-';
  return option;
}
std::string dashedWithValue(const std::string& field, const std::string& value) {
  return dashed(field) + " " + value;
}

TEST(SpellFields, ReplacesEachFieldAndKeepsOtherBraces) {
  EXPECT_EQ(spellFields("needs {layers} nmf, not {depth_budget}", dashed),
            "needs --layers nmf, not --depth-budget");
  EXPECT_EQ(spellFields("{\"key\": 1} {} {Upper} {a b} {", dashed),
            "{\"key\": 1} {} {Upper} {a b} {");
  EXPECT_EQ(spellFields("{x2}", [](const std::string& f) { return f + "="; }), "x2=");
  EXPECT_EQ(spellFields("", dashed), "");
}

TEST(ErrorText, ARequestErrorNamesItsFieldAsTheFrontEndSpellsIt) {
  const RequestError bad("max_memory", "use {spp} 1");
  EXPECT_EQ(errorText(bad, dashed, dashedWithValue), "--max-memory: use --spp 1");
  const auto python = [](const std::string& f) { return f; };
  const auto pythonValue = [](const std::string& f, const std::string& v) { return f + "=" + v; };
  EXPECT_EQ(errorText(bad, python, pythonValue), "max_memory: use spp 1");
  const RequestError withValue("spp", "needs 3 days", "16");
  EXPECT_EQ(errorText(withValue, dashed, dashedWithValue), "--spp 16: needs 3 days");
  EXPECT_EQ(errorText(withValue, python, pythonValue), "spp=16: needs 3 days");
}

TEST(ErrorText, OtherInputErrorsKeepFileAndPointer) {
  const InputError bad("scene.json", "/objects/0", "see {quilt_layout}");
  EXPECT_EQ(errorText(bad, dashed, dashedWithValue), "scene.json: /objects/0: see --quilt-layout");
}

// A display the request made (calibrate apply's measured periods) refused under its file's key.
TEST(ErrorText, ADescriptionTheRequestMadeNamesItsKey) {
  const InputError bad(RequestError::kRequestSource, "/slit_period_px", "breaks {gap_mm}");
  EXPECT_EQ(errorText(bad, dashed, dashedWithValue), "/slit_period_px: breaks --gap-mm");
}

}  // namespace
}  // namespace parallax
