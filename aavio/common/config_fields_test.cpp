#include "aavio/common/config_fields.hpp"

#include <gtest/gtest.h>

namespace aavio {

enum class Flavour { kPlain, kSpicy };
template <>
struct EnumNames<Flavour> {
  static constexpr std::array kNames = {std::pair{Flavour::kPlain, "plain"},
                                        std::pair{Flavour::kSpicy, "spicy"}};
};

namespace {

struct Inner {
  double zncc_threshold = 0.2;
  int step = 3;
  template <typename V>
  void VisitFields(V&& v) {
    v("zncc_threshold", zncc_threshold);
    v("step", step);
  }
  Status Validate() const {
    FieldChecker check;
    check.InRange("zncc_threshold", zncc_threshold, 0.0, 1.0).Positive("step", step);
    return check.status();
  }
};

struct Outer {
  bool enabled = true;
  std::string name = "x";
  Flavour flavour = Flavour::kPlain;
  std::array<double, 3> bias{0.0, 0.0, 0.0};
  std::int64_t big = 5;
  Inner inner;
  template <typename V>
  void VisitFields(V&& v) {
    v("enabled", enabled);
    v("name", name);
    v("flavour", flavour);
    v("bias", bias);
    v("big", big);
    v("inner", inner);
  }
  Status Validate() const {
    FieldChecker check;
    check.Nested("inner", inner);
    return check.status();
  }
};

ConfigEntry Scalar(std::string key, std::string value) {
  return {std::move(key), {std::move(value), {}, false, "test"}};
}

TEST(ConfigFields, FlattensInDeclarationOrder) {
  Outer config;
  auto entries = FlattenConfig(config);
  ASSERT_EQ(entries.size(), 7u);
  EXPECT_EQ(entries[0].key, "enabled");
  EXPECT_EQ(entries[5].key, "inner.zncc_threshold");
  EXPECT_EQ(entries[5].value.scalar, "0.2");
  EXPECT_EQ(entries[6].value.scalar, "3");
  EXPECT_EQ(entries[2].value.scalar, "plain");
  EXPECT_TRUE(entries[3].value.is_list);
  EXPECT_EQ(entries[3].value.list.size(), 3u);
}

TEST(ConfigFields, AppliesEveryType) {
  Outer config;
  ConfigEntry bias{"bias", {"", {"0.1", "-2", "3e-3"}, true, "test"}};
  ASSERT_TRUE(
      ApplyConfigEntries({Scalar("enabled", "false"), Scalar("name", "abc"),
                          Scalar("flavour", "spicy"), bias, Scalar("big", "123456789012"),
                          Scalar("inner.zncc_threshold", "0.35"), Scalar("inner.step", "1")},
                         &config)
          .ok());
  EXPECT_FALSE(config.enabled);
  EXPECT_EQ(config.name, "abc");
  EXPECT_EQ(config.flavour, Flavour::kSpicy);
  EXPECT_DOUBLE_EQ(config.bias[1], -2.0);
  EXPECT_DOUBLE_EQ(config.bias[2], 3e-3);
  EXPECT_EQ(config.big, 123456789012LL);
  EXPECT_DOUBLE_EQ(config.inner.zncc_threshold, 0.35);
  EXPECT_EQ(config.inner.step, 1);
}

TEST(ConfigFields, FlattenThenApplyRoundTrips) {
  Outer a;
  a.inner.zncc_threshold = 0.1 + 0.2;  // not exactly representable in short decimal
  a.flavour = Flavour::kSpicy;
  Outer b;
  ASSERT_TRUE(ApplyConfigEntries(FlattenConfig(a), &b).ok());
  EXPECT_EQ(b.inner.zncc_threshold, a.inner.zncc_threshold);
  EXPECT_EQ(b.flavour, a.flavour);
}

TEST(ConfigFields, UnknownKeySuggestsClosest) {
  Outer config;
  Status s = ApplyConfigEntries({Scalar("inner.zncc_thresold", "0.3")}, &config);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("unknown configuration key 'inner.zncc_thresold'"), std::string::npos);
  EXPECT_NE(s.message().find("did you mean 'inner.zncc_threshold'"), std::string::npos);
  EXPECT_NE(s.message().find("(test)"), std::string::npos);
  // Right name, wrong section.
  s = ApplyConfigEntries({Scalar("step", "2")}, &config);
  EXPECT_NE(s.message().find("did you mean 'inner.step'"), std::string::npos);
  // Nothing close: no suggestion, but a pointer to the list.
  s = ApplyConfigEntries({Scalar("completely_different", "2")}, &config);
  EXPECT_EQ(s.message().find("did you mean"), std::string::npos);
  EXPECT_NE(s.message().find("aavio config --list"), std::string::npos);
}

TEST(ConfigFields, BadValuesNameKeyAndExpectation) {
  Outer config;
  struct Case {
    ConfigEntry entry;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {Scalar("inner.step", "2.5"), "inner.step: expected an integer"},
      {Scalar("inner.step", "99999999999"), "out of range"},
      {Scalar("inner.zncc_threshold", "abc"), "expected a number, got 'abc'"},
      {Scalar("inner.zncc_threshold", "inf"), "finite"},
      {Scalar("enabled", "maybe"), "expected true or false"},
      {Scalar("flavour", "sweet"), "expected one of plain|spicy"},
      {Scalar("bias", "1"), "expected a list of 3 numbers"},
      {ConfigEntry{"bias", {"", {"1", "2"}, true, ""}}, "expected a list of 3 numbers"},
  };
  for (const Case& c : cases) {
    Status s = ApplyConfigEntries({c.entry}, &config);
    ASSERT_FALSE(s.ok()) << c.entry.key << "=" << c.entry.value.scalar;
    EXPECT_NE(s.message().find(c.expected), std::string::npos) << s.message();
  }
}

TEST(ConfigFields, ParsesOverrides) {
  auto e = ParseKeyValueOverride("inner.step = 4");
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->key, "inner.step");
  EXPECT_EQ(e->value.scalar, "4");
  e = ParseKeyValueOverride("bias=[0.1, 0,-1]");
  ASSERT_TRUE(e.ok());
  ASSERT_TRUE(e->value.is_list);
  EXPECT_EQ(e->value.list, (std::vector<std::string>{"0.1", "0", "-1"}));
  e = ParseKeyValueOverride("name='a b'");
  EXPECT_EQ(e->value.scalar, "a b");
  EXPECT_FALSE(ParseKeyValueOverride("no_equals_sign").ok());
  EXPECT_FALSE(ParseKeyValueOverride("=3").ok());
  EXPECT_FALSE(ParseKeyValueOverride("bias=[1,2").ok());
}

TEST(ConfigFields, ValidationMessagesCarryTheDottedKey) {
  Outer config;
  config.inner.zncc_threshold = 1.5;
  Status s = config.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), "inner.zncc_threshold = 1.5 must be in [0, 1]");
  config.inner.zncc_threshold = 0.5;
  config.inner.step = 0;
  EXPECT_EQ(config.Validate().message(), "inner.step = 0 must be > 0");
}

}  // namespace
}  // namespace aavio
