#pragma once
/// Reflection for the plain configuration structs, so that one parser (io/config_yaml), the
/// `--set key=value` overrides and the effective-config writer all see the same fields.
///
/// A config struct lists its fields once, in declaration order:
///
///   struct TimeSurfaceConfig {
///     double decay_ms = 30.0;  ///< exponential decay constant τ [ms]
///     template <class V> void VisitFields(V&& v) {
///       v("decay_ms", decay_ms, "exponential decay τ of the time surface [ms]");
///     }
///     Status Validate() const;
///   };
///
/// A member that itself has VisitFields() is a nested section ("mapping.fusion.radius"). The
/// third argument, a one-line description, is what `aavio config --list` prints beside the key.
/// Supported field types: bool, int, int64, double, std::string, enums with an EnumNames
/// specialisation, and std::array<double, N>.

#include <array>
#include <charconv>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "aavio/common/status.hpp"

namespace aavio {

/// Specialise for every enum used in a config: `static constexpr std::array kNames = {
///   std::pair{Mode::kA, "a"}, ...};`
template <typename E>
struct EnumNames;

/// The name of an enum value as configs write it ("?" for a value without one).
template <typename E>
const char* EnumName(E value) {
  for (const auto& [v, name] : EnumNames<E>::kNames) {
    if (v == value) return name;
  }
  return "?";
}

/// One value as written in a file or on the command line.
struct ConfigValue {
  std::string scalar;             ///< the text of a scalar value
  std::vector<std::string> list;  ///< the items of a sequence value
  bool is_list = false;
  std::string origin;  ///< where it came from, for messages: "configs/driving.yaml:12", "--set"
};

/// A dotted key ("mapping.static_stereo.zncc_threshold") with its value.
struct ConfigEntry {
  std::string key;
  ConfigValue value;
};

namespace config_detail {

template <typename T>
concept Section = requires(T& t) {
  t.VisitFields([](const char*, auto&, auto&&...) {});
};

template <typename T>
struct IsDoubleArray : std::false_type {};
template <std::size_t N>
struct IsDoubleArray<std::array<double, N>> : std::true_type {};

Status ParseBool(const std::string& text, bool* out);
Status ParseDouble(const std::string& text, double* out);
Status ParseInt64(const std::string& text, std::int64_t* out);
std::string FormatDouble(double value);

/// Accessors of one field, built by BuildFieldIndex.
struct FieldRef {
  std::string type;  ///< "double", "int", "bool", "string", "one of a|b", "list of 3 numbers"
  std::string doc;   ///< one-line description
  std::function<Status(const ConfigValue&)> set;
  std::function<ConfigValue()> get;
};

template <typename T>
FieldRef MakeFieldRef(T& field) {
  FieldRef ref;
  if constexpr (std::is_same_v<T, bool>) {
    ref.type = "bool (true|false)";
    ref.set = [&field](const ConfigValue& v) {
      if (v.is_list) return InvalidArgument("expected true or false, got a list");
      return ParseBool(v.scalar, &field);
    };
    ref.get = [&field] { return ConfigValue{field ? "true" : "false", {}, false, {}}; };
  } else if constexpr (std::is_enum_v<T>) {
    std::string options;
    for (const auto& [value, name] : EnumNames<T>::kNames) {
      options += (options.empty() ? "" : "|") + std::string(name);
    }
    ref.type = "one of " + options;
    ref.set = [&field, options](const ConfigValue& v) {
      if (!v.is_list) {
        for (const auto& [value, name] : EnumNames<T>::kNames) {
          if (v.scalar == name) {
            field = value;
            return Status::Ok();
          }
        }
      }
      return InvalidArgument("expected one of " + options + ", got '" + v.scalar + "'");
    };
    ref.get = [&field] {
      for (const auto& [value, name] : EnumNames<T>::kNames) {
        if (value == field) return ConfigValue{name, {}, false, {}};
      }
      return ConfigValue{"?", {}, false, {}};
    };
  } else if constexpr (std::is_integral_v<T>) {
    ref.type = "integer";
    ref.set = [&field](const ConfigValue& v) {
      if (v.is_list) return InvalidArgument("expected an integer, got a list");
      std::int64_t parsed = 0;
      AAVIO_RETURN_IF_ERROR(ParseInt64(v.scalar, &parsed));
      if (parsed < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
          parsed > static_cast<std::int64_t>(std::numeric_limits<T>::max())) {
        return InvalidArgument("integer '" + v.scalar + "' is out of range");
      }
      field = static_cast<T>(parsed);
      return Status::Ok();
    };
    ref.get = [&field] { return ConfigValue{std::to_string(field), {}, false, {}}; };
  } else if constexpr (std::is_floating_point_v<T>) {
    ref.type = "number";
    ref.set = [&field](const ConfigValue& v) {
      if (v.is_list) return InvalidArgument("expected a number, got a list");
      double parsed = 0.0;
      AAVIO_RETURN_IF_ERROR(ParseDouble(v.scalar, &parsed));
      field = static_cast<T>(parsed);
      return Status::Ok();
    };
    ref.get = [&field] { return ConfigValue{FormatDouble(field), {}, false, {}}; };
  } else if constexpr (std::is_same_v<T, std::string>) {
    ref.type = "string";
    ref.set = [&field](const ConfigValue& v) {
      if (v.is_list) return InvalidArgument("expected a string, got a list");
      field = v.scalar;
      return Status::Ok();
    };
    ref.get = [&field] { return ConfigValue{field, {}, false, {}}; };
  } else if constexpr (IsDoubleArray<T>::value) {
    constexpr std::size_t n = std::tuple_size_v<T>;
    ref.type = "list of " + std::to_string(n) + " numbers";
    ref.set = [&field](const ConfigValue& v) {
      if (!v.is_list || v.list.size() != n) {
        return InvalidArgument("expected a list of " + std::to_string(n) + " numbers like [" +
                               std::string(n > 1 ? "0, 0, ..." : "0") + "]");
      }
      T parsed{};
      for (std::size_t i = 0; i < n; ++i)
        AAVIO_RETURN_IF_ERROR(ParseDouble(v.list[i], &parsed[i]));
      field = parsed;
      return Status::Ok();
    };
    ref.get = [&field] {
      ConfigValue v;
      v.is_list = true;
      for (double x : field)
        v.list.push_back(FormatDouble(x));
      return v;
    };
  } else {
    static_assert(sizeof(T) == 0, "unsupported config field type");
  }
  return ref;
}

class IndexBuilder {
 public:
  IndexBuilder(std::map<std::string, FieldRef>* index, std::vector<std::string>* order,
               std::string prefix)
      : index_(index), order_(order), prefix_(std::move(prefix)) {}

  template <typename T>
  void operator()(const char* name, T& member, const char* doc = "") {
    const std::string key = prefix_ + name;
    if constexpr (Section<T>) {
      member.VisitFields(IndexBuilder(index_, order_, key + "."));
    } else {
      FieldRef ref = MakeFieldRef(member);
      ref.doc = doc;
      (*index_)[key] = std::move(ref);
      order_->push_back(key);
    }
  }

 private:
  std::map<std::string, FieldRef>* index_;
  std::vector<std::string>* order_;
  std::string prefix_;
};

/// The known key closest to `key` (edit distance on the full key and on its last segment), or ""
/// when nothing is close.
std::string DidYouMean(const std::string& key, const std::vector<std::string>& known);

}  // namespace config_detail

/// Every field of `config` by dotted key, in declaration order. The references point into
/// `config`, which must outlive the index.
template <typename Config>
struct FieldIndex {
  std::map<std::string, config_detail::FieldRef> fields;
  std::vector<std::string> order;
};

template <typename Config>
FieldIndex<Config> BuildFieldIndex(Config& config) {
  FieldIndex<Config> index;
  config.VisitFields(config_detail::IndexBuilder(&index.fields, &index.order, ""));
  return index;
}

/// Sets the given keys. Unknown keys and malformed values are errors naming the key, the origin
/// and, for unknown keys, the closest known key. Values are applied in order (later wins).
template <typename Config>
Status ApplyConfigEntries(const std::vector<ConfigEntry>& entries, Config* config) {
  auto index = BuildFieldIndex(*config);
  for (const ConfigEntry& entry : entries) {
    const std::string where = entry.value.origin.empty() ? "" : " (" + entry.value.origin + ")";
    auto it = index.fields.find(entry.key);
    if (it == index.fields.end()) {
      std::string message = "unknown configuration key '" + entry.key + "'" + where;
      const std::string hint = config_detail::DidYouMean(entry.key, index.order);
      message += hint.empty() ? "; run `aavio config --list` for all keys"
                              : "; did you mean '" + hint + "'?";
      return InvalidArgument(message);
    }
    Status status = it->second.set(entry.value);
    if (!status.ok()) {
      return InvalidArgument(entry.key + ": " + status.message() + where);
    }
  }
  return Status::Ok();
}

/// All fields of `config` with their current values, in declaration order.
template <typename Config>
std::vector<ConfigEntry> FlattenConfig(const Config& config) {
  Config copy = config;  // the index needs mutable references; reading never changes them
  auto index = BuildFieldIndex(copy);
  std::vector<ConfigEntry> entries;
  entries.reserve(index.order.size());
  for (const std::string& key : index.order)
    entries.push_back({key, index.fields[key].get()});
  return entries;
}

/// Parses a command-line override "key=value"; a value in brackets is a list ("[0.1, 0, 0]").
Expected<ConfigEntry> ParseKeyValueOverride(std::string_view text);

/// Builds readable validation messages: every message starts with the dotted field key.
///   FieldChecker check;
///   check.Positive("decay_ms", decay_ms).InRange("beta", beta, 0.0, 100.0);
///   return check.status();
class FieldChecker {
 public:
  template <typename T>
  FieldChecker& Positive(const char* name, T value) {
    return Require(value > T(0), name, "= " + Num(value) + " must be > 0");
  }
  template <typename T>
  FieldChecker& NonNegative(const char* name, T value) {
    return Require(value >= T(0), name, "= " + Num(value) + " must be >= 0");
  }
  /// lo <= value <= hi.
  template <typename T>
  FieldChecker& InRange(const char* name, T value, T lo, T hi) {
    return Require(value >= lo && value <= hi, name,
                   "= " + Num(value) + " must be in [" + Num(lo) + ", " + Num(hi) + "]");
  }
  FieldChecker& Require(bool condition, const char* name, const std::string& message);
  /// Validates a nested section and prefixes its messages with "name.".
  template <typename Sub>
  FieldChecker& Nested(const char* name, const Sub& sub) {
    if (first_error_.ok()) {
      Status status = sub.Validate();
      if (!status.ok()) {
        first_error_ = Status(status.code(), std::string(name) + "." + status.message());
      }
    }
    return *this;
  }
  Status status() const { return first_error_; }

  /// Shortest text that reads back as the same number ("0.2", "30", "1e-06").
  static std::string Num(double value);
  static std::string Num(std::int64_t value) { return std::to_string(value); }
  static std::string Num(int value) { return std::to_string(value); }

 private:
  Status first_error_;
};

}  // namespace aavio
