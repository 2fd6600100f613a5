#include "slam/core/json_codec.h"

#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tests/testing/error_of.h"

namespace duskmap {
namespace {

enum class Colour { kRed, kGreen };

struct Inner {
  int count = 3;
  Colour colour = Colour::kRed;
  uint64_t seed = 7;
};

struct Outer {
  double scale_m = 1.5;
  std::string name = "a";
  std::vector<int> sizes = {1, 2};
  std::map<std::string, int> per_type;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Inner inner;
  void Check() const {
    SLAM_THROW_IF_NOT(ConfigError, scale_m > 0) << "Outer.scale_m: must be > 0";
  }
};

// A list element: required keys, an optional enum and a 2-vector.
struct Item {
  std::string name;
  std::optional<Colour> colour;
  std::optional<double> weight = 1.0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
};

struct List {
  std::vector<Item> items = {Item{"default", std::nullopt, 1.0, {0.0, 0.0}}};
  std::optional<Inner> inner;
};

// A list added to a file format later: left out when empty.
struct Credits {
  std::vector<Item> items;
  std::vector<std::string> names;
};

}  // namespace

template <>
struct JsonEnumNames<Colour> {
  static constexpr std::pair<Colour, const char*> kNames[] = {{Colour::kRed, "red"},
                                                              {Colour::kGreen, "green"}};
};

template <>
struct JsonCodec<Inner> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("count", o.count);
    f("colour", o.colour);
    f("seed", o.seed);
  }
};

template <>
struct JsonCodec<Outer> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("scale_m", o.scale_m);
    f("name", o.name);
    f("sizes", o.sizes);
    f("per_type", o.per_type);
    f("axis", o.axis);
    f("inner", o.inner, {{"seed", "the outer seed"}});
  }
};

template <>
struct JsonCodec<Item> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("name", o.name, JsonRequired{});
    f("colour", o.colour);
    f("weight", o.weight);
    f("at", o.at);
  }
};

template <>
struct JsonCodec<Credits> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("items", o.items, JsonOmitEmpty{});
    f("names", o.names, JsonOmitEmpty{});
  }
};

template <>
struct JsonCodec<List> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("items", o.items);
    f("inner", o.inner);
  }
};

namespace {

Outer Read(const char* text) { return ReadJsonOptions<Outer>(nlohmann::json::parse(text), "x.json"); }

TEST(JsonCodec, ReadsDeclaredFieldsAndKeepsDefaults) {
  const Outer o = Read(R"({"scale_m": 2, "sizes": [4], "per_type": {"loop": 3},
                           "axis": [1, 0, 0], "inner": {"colour": "green"}})");
  EXPECT_DOUBLE_EQ(o.scale_m, 2.0);
  EXPECT_EQ(o.name, "a");
  EXPECT_EQ(o.sizes, std::vector<int>{4});
  EXPECT_EQ(o.per_type.at("loop"), 3);
  EXPECT_TRUE(o.axis.isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_EQ(o.inner.colour, Colour::kGreen);
  EXPECT_EQ(o.inner.count, 3);
}

TEST(JsonCodec, WritesEveryFieldButTheDerivedOnesAndReadsItBack) {
  Outer o;
  o.name = "b";
  o.inner.colour = Colour::kGreen;
  o.per_type["odometry"] = 9;
  const nlohmann::json json = ToJsonObject(o);
  EXPECT_EQ(json.dump(),
            R"({"axis":[0.0,0.0,1.0],"inner":{"colour":"green","count":3},"name":"b",)"
            R"("per_type":{"odometry":9},"scale_m":1.5,"sizes":[1,2]})");
  const Outer back = ReadJsonOptions<Outer>(json, "back");
  EXPECT_EQ(ToJsonObject(back), json);
  EXPECT_EQ(ToJsonObject(o.inner)["seed"], 7);  // on its own, the inner struct has its seed
}

TEST(JsonCodec, ErrorsNameTheFullPath) {
  using testing::ErrorOf;
  EXPECT_EQ(ErrorOf([] { Read(R"({"inner": {"cuont": 1}})"); }),
            "x.json.inner: unknown key 'cuont'");
  EXPECT_EQ(ErrorOf([] { Read(R"({"inner": {"colour": "blue"}})"); }),
            "x.json.inner.colour: expected red or green, got 'blue'");
  EXPECT_EQ(ErrorOf([] { Read(R"({"inner": {"seed": 1}})"); }),
            "x.json.inner.seed: not set here; the outer seed sets it");
  EXPECT_EQ(ErrorOf([] { Read(R"({"axis": [1, 0]})"); }), "x.json.axis: expected 3 numbers, got 2");
  EXPECT_EQ(ErrorOf([] { Read(R"({"inner": {"count": 1.5}})"); }),
            "x.json.inner.count: expected an integer, got 1.5");
  EXPECT_EQ(ErrorOf([] { Read(R"({"inner": 3})"); }),
            "x.json.inner: expected a JSON object, got number");
  EXPECT_EQ(ErrorOf([] { Read(R"({"scale_m": -1})"); }), "x.json: Outer.scale_m: must be > 0");
  EXPECT_EQ(ErrorOf([] { Read(R"({"_comment": "free text"})"); }), "");
}

List ReadList(const char* text) {
  return ReadJsonOptions<List>(nlohmann::json::parse(text), "l.json");
}

TEST(JsonCodec, OptionalsAreNullWhenEmptyAndListsOfStructsAreArrays) {
  List list;
  list.items = {Item{"a", Colour::kGreen, std::nullopt, {1.5, -2.0}},
                Item{"b", std::nullopt, 3.0, {0.0, 0.0}}};
  const nlohmann::json json = ToJsonObject(list);
  EXPECT_EQ(json.dump(),
            R"({"inner":null,"items":[{"at":[1.5,-2.0],"colour":"green","name":"a","weight":null},)"
            R"({"at":[0.0,0.0],"colour":null,"name":"b","weight":3.0}]})");
  const List back = ReadJsonOptions<List>(json, "back");
  EXPECT_EQ(ToJsonObject(back), json);
  list.inner = Inner();
  EXPECT_EQ(ToJsonObject(list)["inner"], ToJsonObject(Inner()));
}

TEST(JsonCodec, ReadsOptionalsAndListsOfStructs) {
  const List absent = ReadList("{}");  // absent keys keep the defaults
  ASSERT_EQ(absent.items.size(), 1u);
  EXPECT_EQ(absent.items[0].name, "default");
  EXPECT_FALSE(absent.inner.has_value());
  const List read = ReadList(R"({"items": [{"name": "x", "colour": "red", "at": [1, 2]},
                                           {"name": "y", "weight": null}],
                                 "inner": {"count": 5}})");
  ASSERT_EQ(read.items.size(), 2u);
  ASSERT_TRUE(read.items[0].colour.has_value());
  EXPECT_EQ(*read.items[0].colour, Colour::kRed);
  ASSERT_TRUE(read.items[0].weight.has_value());
  EXPECT_EQ(*read.items[0].weight, 1.0);
  EXPECT_TRUE(read.items[0].at.isApprox(Eigen::Vector2d(1, 2)));
  EXPECT_FALSE(read.items[1].colour.has_value());
  EXPECT_FALSE(read.items[1].weight.has_value());
  ASSERT_TRUE(read.inner.has_value());
  EXPECT_EQ(read.inner->count, 5);
  EXPECT_EQ(read.inner->seed, 7u);
  EXPECT_TRUE(ReadList(R"({"items": []})").items.empty());
}

TEST(JsonCodec, ListAndRequiredErrorsNameTheFullPath) {
  using testing::ErrorOf;
  EXPECT_EQ(ErrorOf([] { ReadList(R"({"items": [{"name": "a"}, {"colour": "red"}]})"); }),
            "l.json.items[1]: missing key 'name'");
  EXPECT_EQ(ErrorOf([] { ReadList(R"({"items": [{"name": "a", "wieght": 2}]})"); }),
            "l.json.items[0]: unknown key 'wieght'");
  EXPECT_EQ(ErrorOf([] { ReadList(R"({"items": [{"name": "a", "colour": "blue"}]})"); }),
            "l.json.items[0].colour: expected red or green, got 'blue'");
  EXPECT_EQ(ErrorOf([] { ReadList(R"({"items": [{"name": "a", "at": [1, 2, 3]}]})"); }),
            "l.json.items[0].at: expected 2 numbers, got 3");
  EXPECT_EQ(ErrorOf([] { ReadList(R"({"items": {"name": "a"}})"); }),
            "l.json.items: wrong type (object, expected an array)");
  EXPECT_EQ(ErrorOf([] { ReadList(R"({"items": [3]})"); }),
            "l.json.items[0]: expected a JSON object, got number");
  EXPECT_EQ(ErrorOf([] { ReadList(R"({"inner": {"cuont": 1}})"); }),
            "l.json.inner: unknown key 'cuont'");
}

TEST(JsonCodec, ListsMarkedOmitEmptyAreLeftOutWhenEmpty) {
  Credits credits;
  EXPECT_EQ(ToJsonObject(credits).dump(), "{}");
  credits.names = {"a"};
  EXPECT_EQ(ToJsonObject(credits).dump(), R"({"names":["a"]})");
  credits.items = {Item{"x", std::nullopt, 2.0, {0.0, 0.0}}};
  const nlohmann::json json = ToJsonObject(credits);
  EXPECT_EQ(json.dump(), R"({"items":[{"at":[0.0,0.0],"colour":null,"name":"x","weight":2.0}],"names":["a"]})");
  const Credits back = ReadJsonOptions<Credits>(json, "back");
  EXPECT_EQ(ToJsonObject(back), json);
  EXPECT_TRUE(ReadJsonOptions<Credits>(nlohmann::json::parse("{}"), "empty").items.empty());
  EXPECT_EQ(testing::ErrorOf([] { ReadJsonOptions<Credits>(nlohmann::json::parse(R"({"items": [{}]})"), "c"); }),
            "c.items[0]: missing key 'name'");
}

}  // namespace
}  // namespace duskmap
