// ConfigFields read past errors into an InputErrors (issue 31, point 3): each
// field on its own, and a field checked against an earlier one that had an
// error is not checked (it would blame itself for the other's mistake).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/config_fields.hpp"

namespace campo {
namespace {

struct LevelsConfig {
  int levels = 4;
  int level = 0;
  double gain = 1.0;
  bool smooth = false;
  double smoothing_s = 0.5;
};

const ConfigFields<LevelsConfig>& levels_fields() {
  using C = LevelsConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .integer("levels", &C::levels, {1, 16}, "", "how many levels")
          .integer("level", &C::level,
                   DependentBound<C, IntRange>{[](const C& c) { return IntRange{0, c.levels - 1}; }, "[0, levels - 1]"},
                   "", "which level")
          .number("gain", &C::gain, Range::non_negative(), "", "a gain")
          .flag("smooth", &C::smooth, "smooth or not")
          .number("smoothing_s", &C::smoothing_s, Range::positive(), "s", "how long")
          .only_when([](const C& c) { return c.smooth; }, "expected \"smooth\": true with \"smoothing_s\"");
  return fields;
}

InputErrors read_collecting(const nlohmann::json& document) {
  InputErrors errors;
  ObjectReader r(JsonNode(document, "p.json", ""), &errors);
  LevelsConfig c;
  levels_fields().read_fields(r, c);
  r.finish();
  return errors;
}

TEST(ConfigFieldsErrors, EveryIndependentFieldIsChecked) {
  const InputErrors errors = read_collecting({{"levels", 0}, {"gain", -1}, {"colour", 1}});
  ASSERT_EQ(errors.count(), 3u);
  try {
    errors.throw_if_any();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.issues()[0].pointer, "/levels");
    EXPECT_EQ(e.issues()[1].pointer, "/gain");
    EXPECT_EQ(e.issues()[2].pointer, "/colour");
  }
}

TEST(ConfigFieldsErrors, AFieldThatDependsOnOneWithAnErrorIsNotBlamed) {
  // levels 99 is refused; level 20 fits the 99 given, so it is not checked against the default 4.
  // smooth "yes" is refused; smoothing_s may be meant with it, so it is not refused for want of smooth.
  const InputErrors errors = read_collecting({{"levels", 99}, {"level", 20}, {"smooth", "yes"}, {"smoothing_s", 2}});
  EXPECT_EQ(errors.count(), 2u);
  try {
    errors.throw_if_any();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.issues()[0].pointer, "/levels");
    EXPECT_EQ(e.issues()[1].pointer, "/smooth");
  }
  // Without an error before them, both are checked.
  EXPECT_EQ(read_collecting({{"levels", 8}, {"level", 20}}).count(), 1u);
  EXPECT_EQ(read_collecting({{"smoothing_s", 2}}).count(), 1u);
}

struct OuterConfig {
  double speed_mps = 1.0;
  LevelsConfig inner;
};

// read() of a whole block (a planner's or vehicle's params) throws every error of it at once,
// those of a nested object included, in declaration order and then the unknown keys.
TEST(ConfigFieldsErrors, ReadThrowsEveryErrorOfTheBlock) {
  using C = OuterConfig;
  const ConfigFields<C> fields = ConfigFields<C>()
                                     .number("speed_mps", &C::speed_mps, Range::positive(), "m/s", "speed")
                                     .nested("inner", &C::inner, levels_fields(), "inner");
  const nlohmann::json document = {{"speed_mps", -1}, {"inner", {{"gain", -2}, {"hue", 0}}}, {"colour", 1}};
  C config;
  try {
    fields.read(JsonNode(document, "p.json", "/params"), config);
    FAIL();
  } catch (const InputError& e) {
    ASSERT_EQ(e.count(), 4u) << e.what();
    EXPECT_EQ(e.issues()[0].pointer, "/params/speed_mps");
    EXPECT_EQ(e.issues()[1].pointer, "/params/inner/gain");
    EXPECT_EQ(e.issues()[2].pointer, "/params/inner/hue");
    EXPECT_EQ(e.issues()[3].pointer, "/params/colour");
  }
  // A valid block is read as before.
  fields.read(JsonNode(nlohmann::json{{"speed_mps", 2}, {"inner", {{"gain", 3}}}}, "p.json", "/params"), config);
  EXPECT_EQ(config.speed_mps, 2.0);
  EXPECT_EQ(config.inner.gain, 3.0);
}

}  // namespace
}  // namespace campo
