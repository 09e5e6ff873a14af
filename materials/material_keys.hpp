// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a material model's reader may ask of its [[materials]] entry in a scene, without knowing
// TOML: io/scene implements it over the scene file. Failures name the file, line and dotted key
// (`materials.<name>.<key>`) and end the reading (InputError); `record` puts a value into the
// resolved scene that run.log shows (the values a model reads are recorded only if it says so,
// so that it can record derived or defaulted values instead).
#include <charconv>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace femdem {

class MaterialKeys {
 public:
  virtual ~MaterialKeys() = default;
  virtual bool has(std::string_view key) const = 0;
  // A number; `fallback` when the key is absent (nullopt: required).
  virtual double number(std::string_view key, std::optional<double> fallback = std::nullopt) = 0;
  // The same, and it must be > 0.
  virtual double positive(std::string_view key, std::optional<double> fallback = std::nullopt) = 0;
  virtual std::optional<std::string> text(std::string_view key) = 0;
  // An array of [a, b] number pairs: `what_array` is the message for a missing, empty or
  // non-array value, `what_pair` for an entry that is not two numbers.
  virtual std::vector<std::pair<double, double>> pairs(std::string_view key,
                                                       const std::string& what_array,
                                                       const std::string& what_pair) = 0;
  virtual void record(std::string_view key, double value) = 0;
  virtual void record(std::string_view key, const std::string& value) = 0;
  virtual void record(std::string_view key, const std::vector<std::pair<double, double>>& v) = 0;
  // The error at `key` (its value if given, else the entry) named `materials.<name>.<key>`.
  [[noreturn]] virtual void fail(std::string_view key, const std::string& message) const = 0;
  // The error at the entry itself, named `materials.<name>`.
  [[noreturn]] virtual void fail_entry(const std::string& message) const = 0;
  // " (did you mean 'x'?)" when `word` is close to one of `candidates`, else empty.
  virtual std::string did_you_mean(std::string_view word,
                                   const std::vector<std::string>& candidates) const = 0;
};

// Numbers in the reader's messages: the shortest form that reads back to the same double.
inline std::string format_shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// Numbers in printed summaries: %g (six significant digits).
inline std::string format_g(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace femdem
