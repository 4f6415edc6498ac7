#include "campo/config_fields.hpp"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace campo {
namespace {

using ::testing::HasSubstr;

enum class Shape { square, disc };

struct InnerConfig {
  double gain = 2.0;
  int count = 3;
};

struct ExampleConfig {
  std::string sensor;
  double speed_mps = 1.5;
  int levels = 4;
  int ground_level = 1;
  bool horizontal = false;
  std::uint64_t seed = 7;
  Eigen::Vector3d size_m{1.0, 2.0, 3.0};
  Eigen::Vector2d origin_m{0.0, -1.0};
  Shape shape = Shape::square;
  double margin_m = 0.25;
  InnerConfig inner{5.0, 6};
  InnerConfig disc_only;
};

const ConfigFields<InnerConfig>& inner_fields() {
  static const ConfigFields<InnerConfig> fields =
      ConfigFields<InnerConfig>()
          .number("gain", &InnerConfig::gain, Range::non_negative(), "1/s", "a gain")
          .integer("count", &InnerConfig::count, {0, 9}, "", "a count");
  return fields;
}

const ConfigFields<ExampleConfig>& example_fields() {
  using C = ExampleConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .text("sensor", &C::sensor, "alias; none: the first")
          .omitted_when_default()
          .number("speed_mps", &C::speed_mps, Range::closed(0.01, 20.0), "m/s", "cruise speed")
          .integer("levels", &C::levels, {1, 10}, "", "levels")
          .integer("ground_level", &C::ground_level,
                   DependentBound<C, IntRange>{[](const C& c) { return IntRange{0, c.levels - 1}; }, "[0, levels - 1]"},
                   "", "ground | level")
          .flag("horizontal", &C::horizontal, "x, y only")
          .seed("seed", &C::seed, "sampler seed")
          .vector("size_m", &C::size_m, Range::positive(), "m", "box")
          .vector("origin_m", &C::origin_m, Range{}, "m", "corner")
          .choice("shape", &C::shape, {{"square", Shape::square}, {"disc", Shape::disc}}, "element")
          .number("margin_m", &C::margin_m, Range{0.0, 1.0, true, false}, "m", "kept when default")
          .omitted_when_default()
          .nested("inner", &C::inner, inner_fields(), "inner loop")
          .nested("disc_only", &C::disc_only, inner_fields(), "disc settings")
          .only_when([](const C& c) { return c.shape == Shape::disc; }, "disc_only needs \"shape\": \"disc\"");
  return fields;
}

ParamsBlock params(const std::string& text) {
  return {nlohmann::json::parse(text), "scene.json", "/vehicles/0/planner/params"};
}

std::string error_of(const std::string& text) {
  try {
    example_fields().read(params(text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ConfigFields, ReadsTheGivenKeysAndKeepsTheOtherDefaults) {
  const ExampleConfig c = example_fields().read(params(
      R"({"speed_mps": 2.5, "shape": "disc", "size_m": [4, 5, 6], "inner": {"count": 8}, "seed": 18446744073709551615})"));
  EXPECT_EQ(c.speed_mps, 2.5);
  EXPECT_EQ(c.shape, Shape::disc);
  EXPECT_EQ(c.size_m, Eigen::Vector3d(4.0, 5.0, 6.0));
  EXPECT_EQ(c.inner.count, 8);
  EXPECT_EQ(c.inner.gain, 5.0);  // the outer struct's default for its member, not InnerConfig's
  EXPECT_EQ(c.seed, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(c.levels, 4);
  EXPECT_EQ(c.sensor, "");
  EXPECT_EQ(c.margin_m, 0.25);
  EXPECT_EQ(c.origin_m, Eigen::Vector2d(0.0, -1.0));
}

TEST(ConfigFields, ReadingOverridesTheConfigGiven) {
  ExampleConfig c;
  c.speed_mps = 0.5;
  c.horizontal = true;
  example_fields().read(params(R"({"levels": 2})"), c);
  EXPECT_EQ(c.speed_mps, 0.5);
  EXPECT_TRUE(c.horizontal);
  EXPECT_EQ(c.levels, 2);
}

TEST(ConfigFields, UnknownKeysNameTheFilePointerAndTheDeclaredKeys) {
  EXPECT_EQ(error_of(R"({"sped_mps": 1})"),
            "scene.json: /vehicles/0/planner/params/sped_mps: unknown key \"sped_mps\"; expected one of: disc_only, "
            "ground_level, horizontal, inner, levels, margin_m, origin_m, seed, sensor, shape, size_m, speed_mps");
  EXPECT_EQ(error_of(R"({"inner": {"gain": 1, "bogus": 2}})"),
            "scene.json: /vehicles/0/planner/params/inner/bogus: unknown key \"bogus\"; expected one of: count, gain");
}

TEST(ConfigFields, OutOfRangeValuesStateTheRange) {
  EXPECT_EQ(error_of(R"({"speed_mps": 50})"),
            "scene.json: /vehicles/0/planner/params/speed_mps: expected a number in [0.01, 20], got 50");
  EXPECT_EQ(error_of(R"({"levels": 0})"),
            "scene.json: /vehicles/0/planner/params/levels: expected an integer in [1, 10], got 0");
  EXPECT_EQ(error_of(R"({"margin_m": 0})"),
            "scene.json: /vehicles/0/planner/params/margin_m: expected a number in (0, 1], got 0");
  EXPECT_EQ(error_of(R"({"size_m": [1, 0, 1]})"),
            "scene.json: /vehicles/0/planner/params/size_m/1: expected a number > 0, got 0");
  EXPECT_EQ(error_of(R"({"inner": {"count": 10}})"),
            "scene.json: /vehicles/0/planner/params/inner/count: expected an integer in [0, 9], got 10");
}

TEST(ConfigFields, ABoundMayDependOnTheFieldsReadBefore) {
  // levels 4 by default: ground_level in [0, 3]; levels 8: [0, 7].
  EXPECT_EQ(error_of(R"({"ground_level": 5})"),
            "scene.json: /vehicles/0/planner/params/ground_level: expected an integer in [0, 3], got 5");
  EXPECT_EQ(example_fields().read(params(R"({"levels": 8, "ground_level": 5})")).ground_level, 5);
}

TEST(ConfigFields, WrongTypesSayWhatWasExpected) {
  EXPECT_THAT(error_of(R"({"speed_mps": "fast"})"), HasSubstr("/speed_mps: expected a number in [0.01, 20], got \"fast\""));
  EXPECT_THAT(error_of(R"({"levels": 2.5})"), HasSubstr("/levels: expected an integer in [1, 10], got 2.5"));
  EXPECT_THAT(error_of(R"({"horizontal": 1})"), HasSubstr("/horizontal: expected true or false, got 1"));
  EXPECT_THAT(error_of(R"({"shape": "hex"})"), HasSubstr("/shape: expected one of \"square\", \"disc\", got \"hex\""));
  EXPECT_THAT(error_of(R"({"sensor": ""})"), HasSubstr("/sensor: expected a non-empty string, got \"\""));
  EXPECT_THAT(error_of(R"({"origin_m": [1, 2, 3]})"), HasSubstr("/origin_m: expected an array of 2 elements"));
  EXPECT_THAT(error_of(R"({"seed": -1})"), HasSubstr("/seed: expected an integer seed in [0, 18446744073709551615]"));
  EXPECT_THAT(error_of(R"({"inner": 3})"), HasSubstr("/inner: expected an object, got 3"));
  EXPECT_THAT(error_of("[1]"), HasSubstr("scene.json: /vehicles/0/planner/params: expected an object, got [1]"));
}

TEST(ConfigFields, AFieldOnlyWhenAnotherHoldsIsRefusedOtherwise) {
  EXPECT_EQ(error_of(R"({"disc_only": {"gain": 1}})"),
            "scene.json: /vehicles/0/planner/params/disc_only: disc_only needs \"shape\": \"disc\"");
  EXPECT_EQ(example_fields().read(params(R"({"shape": "disc", "disc_only": {"gain": 1}})")).disc_only.gain, 1.0);
}

TEST(ConfigFields, WritesEveryValueInTheFormItReads) {
  // Defaults: no sensor, no margin_m (at its default), no disc_only (shape square).
  const nlohmann::json expected = nlohmann::json::parse(R"({
    "speed_mps": 1.5, "levels": 4, "ground_level": 1, "horizontal": false, "seed": 7,
    "size_m": [1.0, 2.0, 3.0], "origin_m": [0.0, -1.0], "shape": "square", "inner": {"gain": 5.0, "count": 6}})");
  EXPECT_EQ(example_fields().write(ExampleConfig{}), expected);

  ExampleConfig c;
  c.sensor = "front";
  c.margin_m = 0.5;
  c.shape = Shape::disc;
  const nlohmann::json j = example_fields().write(c);
  EXPECT_EQ(j["sensor"], "front");
  EXPECT_EQ(j["margin_m"], 0.5);
  EXPECT_EQ(j["shape"], "disc");
  EXPECT_EQ(j["disc_only"], nlohmann::json::parse(R"({"gain": 2.0, "count": 3})"));
  EXPECT_TRUE(j["seed"].is_number_unsigned());
  EXPECT_TRUE(j["levels"].is_number_integer());
}

TEST(ConfigFields, ReadingWhatIsWrittenGivesTheConfigBack) {
  ExampleConfig c;
  c.sensor = "lidar";
  c.speed_mps = 3.25;
  c.levels = 9;
  c.ground_level = 8;
  c.horizontal = true;
  c.seed = 12345678901234567890u;
  c.size_m = {0.5, 0.25, 8.0};
  c.origin_m = {-3.0, 4.5};
  c.shape = Shape::disc;
  c.margin_m = 1.0;
  c.inner = {0.0, 0};
  c.disc_only = {7.5, 9};
  const ExampleConfig back = example_fields().read(ParamsBlock{example_fields().write(c), "p.json", ""});
  EXPECT_EQ(back.sensor, c.sensor);
  EXPECT_EQ(back.speed_mps, c.speed_mps);
  EXPECT_EQ(back.levels, c.levels);
  EXPECT_EQ(back.ground_level, c.ground_level);
  EXPECT_EQ(back.horizontal, c.horizontal);
  EXPECT_EQ(back.seed, c.seed);
  EXPECT_EQ(back.size_m, c.size_m);
  EXPECT_EQ(back.origin_m, c.origin_m);
  EXPECT_EQ(back.shape, c.shape);
  EXPECT_EQ(back.margin_m, c.margin_m);
  EXPECT_EQ(back.inner.gain, 0.0);
  EXPECT_EQ(back.inner.count, 0);
  EXPECT_EQ(back.disc_only.gain, 7.5);
  EXPECT_EQ(back.disc_only.count, 9);
}

TEST(ConfigFields, RendersTheDocsTable) {
  EXPECT_EQ(example_fields().markdown(),
            "| key | default | unit | accepted | meaning |\n"
            "| --- | --- | --- | --- | --- |\n"
            "| `sensor` | none |  | a non-empty string | alias; none: the first |\n"
            "| `speed_mps` | 1.5 | m/s | [0.01, 20] | cruise speed |\n"
            "| `levels` | 4 |  | [1, 10] | levels |\n"
            "| `ground_level` | 1 |  | [0, levels - 1] | ground \\| level |\n"
            "| `horizontal` | false |  | true or false | x, y only |\n"
            "| `seed` | 7 |  | an integer in [0, 2^64 - 1] | sampler seed |\n"
            "| `size_m` | [1.0, 2.0, 3.0] | m | 3 numbers, each > 0 | box |\n"
            "| `origin_m` | [0.0, -1.0] | m | 2 numbers | corner |\n"
            "| `shape` | `square` |  | `square` or `disc` | element |\n"
            "| `margin_m` | 0.25 | m | (0, 1] | kept when default |\n"
            "| `inner` |  |  | an object | inner loop |\n"
            "| `inner.gain` | 5.0 | 1/s | >= 0 | a gain |\n"
            "| `inner.count` | 6 |  | [0, 9] | a count |\n"
            "| `disc_only` |  |  | an object | disc settings |\n"
            "| `disc_only.gain` | 2.0 | 1/s | >= 0 | a gain |\n"
            "| `disc_only.count` | 3 |  | [0, 9] | a count |\n");
  // The defaults come from the config given.
  ExampleConfig rover;
  rover.speed_mps = 0.5;
  EXPECT_EQ(example_fields().docs(rover)[1].default_value, "0.5");
  EXPECT_EQ(example_fields().keys().front(), "sensor");
}

TEST(ConfigFields, RangeTexts) {
  EXPECT_EQ(range_text(Range::positive()), "> 0");
  EXPECT_EQ(range_text(Range::non_negative()), ">= 0");
  EXPECT_EQ(range_text(Range::closed(0.01, 20.0)), "[0.01, 20]");
  EXPECT_EQ(range_text(Range{0.5, 1.0, true, true}), "(0.5, 1)");
  EXPECT_EQ(range_text(Range{1.0}), ">= 1");
  EXPECT_EQ(range_text(Range{-std::numeric_limits<double>::infinity(), 5.0, false, true}), "< 5");
  EXPECT_EQ(range_text(Range{}), "any");
}

TEST(ConfigFields, AKeyDeclaredTwiceIsABug) {
  ConfigFields<InnerConfig> fields;
  fields.number("gain", &InnerConfig::gain, Range{}, "", "");
  EXPECT_THROW(fields.integer("gain", &InnerConfig::count, {0, 1}, "", ""), std::logic_error);
  EXPECT_THROW(ConfigFields<InnerConfig>().omitted_when_default(), std::logic_error);
}

}  // namespace
}  // namespace campo
