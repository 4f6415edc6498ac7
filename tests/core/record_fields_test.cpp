// Declared record fields: written and read through their declaration, a key not declared or a value of the
// wrong type refused, the docs' table from the same list.
#include "campo/record_fields.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace campo {
namespace {

using ::testing::HasSubstr;

struct Point2 {
  double x = 0.0;
  double y = 0.0;
  bool operator==(const Point2&) const = default;
};

// A record as a component declares it: the list and its typed handles, once.
struct TestRecord {
  RecordFields fields;
  RecordField<int> count = fields.declare<int>("count", "", "how many");
  RecordField<double> range = fields.declare<double>("range_m", "m", "the nearest reading");
  RecordField<bool> marginal = fields.declare<bool>("marginal", "", "close to the threshold");
  RecordField<std::string> action = fields.declare<std::string>("action", "", "what was done");
  RecordField<Point2> point = fields.declare<Point2>(
      {"point_m", RecordType::array, "m", "a point [x, y]"}, [](const Point2& p) { return nlohmann::json{p.x, p.y}; },
      [](const JsonNode& n) {
        const Eigen::Vector2d v = n.as_vector2();
        return Point2{v.x(), v.y()};
      });
};

const TestRecord& test_record() {
  static const TestRecord r;
  return r;
}

TEST(RecordFields, WritesAndReadsThroughTheDeclaration) {
  const TestRecord& r = test_record();
  nlohmann::json record;  // null: becomes an object
  r.count.set(record, 3);
  r.range.set(record, 2.5);
  r.marginal.set(record, true);
  r.action.set(record, "fly");
  r.point.set(record, {1.0, -2.0});
  EXPECT_EQ(record.dump(), R"({"action":"fly","count":3,"marginal":true,"point_m":[1.0,-2.0],"range_m":2.5})");
  EXPECT_EQ(r.count.get(record), 3);
  EXPECT_EQ(r.range.get(record), 2.5);
  EXPECT_EQ(r.marginal.get(record), true);
  EXPECT_EQ(r.action.get(record), "fly");
  EXPECT_EQ(r.point.get(record), (Point2{1.0, -2.0}));
  EXPECT_NO_THROW(r.fields.check(record, "events.jsonl", "/decisions"));
  r.count.erase(record);
  EXPECT_FALSE(r.count.in(record));
  EXPECT_EQ(r.count.get(record), std::nullopt);
  EXPECT_EQ(r.count.get(nlohmann::json()), std::nullopt);
}

TEST(RecordFields, AnIntegerIsANumberButNotTheOtherWayRound) {
  const TestRecord& r = test_record();
  EXPECT_EQ(r.range.get(nlohmann::json{{"range_m", 4}}), 4.0);
  EXPECT_THAT([&] { (void)r.count.get(nlohmann::json{{"count", 2.5}}, "events.jsonl", "/decisions"); },
              testing::ThrowsMessage<InputError>(HasSubstr("/decisions/count: expected integer (how many)")));
}

TEST(RecordFields, RefusesAWrongType) {
  const TestRecord& r = test_record();
  EXPECT_THAT([&] { (void)r.action.get(nlohmann::json{{"action", 1}}, "f", "/d"); },
              testing::ThrowsMessage<InputError>(HasSubstr("/d/action: expected text (what was done)")));
  // The field's own reader refuses a value of the right JSON type but the wrong content.
  EXPECT_THAT([&] { (void)r.point.get(nlohmann::json{{"point_m", {1.0}}}, "f", "/d"); },
              testing::ThrowsMessage<InputError>(HasSubstr("/d/point_m")));
  nlohmann::json record = nlohmann::json::object();
  EXPECT_THROW(r.fields.set(record, "count", "three", "f", "/d"), InputError);
  EXPECT_TRUE(record.empty());
}

TEST(RecordFields, RefusesAKeyNotDeclared) {
  const TestRecord& r = test_record();
  nlohmann::json record = nlohmann::json::object();
  EXPECT_THAT([&] { r.fields.set(record, "counts", 3, "f", "/d"); },
              testing::ThrowsMessage<InputError>(
                  HasSubstr("/d/counts: expected a declared field (count, range_m, marginal, action, point_m), got \"counts\"")));
  r.fields.set(record, "count", 3, "f", "/d");
  EXPECT_EQ(r.count.get(record), 3);
}

TEST(RecordFields, CheckNamesEveryProblemAtOnce) {
  const TestRecord& r = test_record();
  const nlohmann::json record = {{"count", "x"}, {"range_m", 1.0}, {"wall", 1}, {"point_m", {1, 2, 3}}};
  try {
    r.fields.check(record, "events.jsonl", "/decisions");
    FAIL() << "no error";
  } catch (const InputError& e) {
    ASSERT_EQ(e.issues().size(), 3u);
    EXPECT_EQ(e.issues()[0].pointer, "/decisions/count");
    EXPECT_EQ(e.issues()[1].pointer, "/decisions/point_m");
    EXPECT_EQ(e.issues()[2].pointer, "/decisions/wall");
  }
  EXPECT_THROW(r.fields.check(nlohmann::json::array(), "f", "/d"), InputError);
  EXPECT_NO_THROW(r.fields.check(nlohmann::json(), "f", "/d"));
}

TEST(RecordFields, RefusesAWriterThatDisagreesWithItsDeclaration) {
  RecordFields fields;
  const RecordField<int> odd = fields.declare<int>({"odd", RecordType::object, "", "an object"},
                                                   [](const int& v) { return nlohmann::json(v); },
                                                   [](const JsonNode&) { return 0; });
  nlohmann::json record;
  EXPECT_THROW(odd.set(record, 1), std::logic_error);
  EXPECT_THROW((void)fields.declare<int>("odd", "", "again"), std::logic_error);
}

TEST(RecordFields, DocumentsEveryFieldInOrder) {
  EXPECT_EQ(test_record().fields.markdown(),
            "| field | type | unit | meaning |\n| --- | --- | --- | --- |\n"
            "| `count` | integer |  | how many |\n"
            "| `range_m` | number | m | the nearest reading |\n"
            "| `marginal` | flag |  | close to the threshold |\n"
            "| `action` | text |  | what was done |\n"
            "| `point_m` | array | m | a point [x, y] |\n");
  EXPECT_EQ(to_string(RecordType::object), "object");
}

}  // namespace
}  // namespace campo
