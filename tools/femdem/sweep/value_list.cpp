// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/sweep/value_list.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/errors.hpp"

namespace femdem {
namespace sweep {

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return std::string(s.substr(a, b - a));
}

}  // namespace sweep

namespace {

using sweep::trim;

// ---------------------------------------------------------------------------------------------
// Value lists

// Splits at the commas outside brackets, braces, parentheses and quoted strings.
std::vector<std::string> split_top_level(const std::string& s, const std::string& key,
                                         const std::string& what) {
  std::vector<std::string> items;
  std::string cur;
  int depth = 0;
  char quote = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quote) {
      cur += c;
      if (c == '\\' && quote == '"' && i + 1 < s.size()) {
        cur += s[++i];
      } else if (c == quote) {
        quote = 0;
      }
      continue;
    }
    if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '{' || c == '(') {
      ++depth;
    } else if (c == ']' || c == '}' || c == ')') {
      if (--depth < 0)
        throw InputError("unbalanced '" + std::string(1, c) + "' in " + what, {}, 0, 0, key);
    } else if (c == ',' && depth == 0) {
      items.push_back(trim(cur));
      cur.clear();
      continue;
    }
    cur += c;
  }
  if (quote) throw InputError("unterminated quoted string in " + what, {}, 0, 0, key);
  if (depth != 0) throw InputError("unbalanced brackets in " + what, {}, 0, 0, key);
  items.push_back(trim(cur));
  return items;
}

struct Number {
  double value = 0.0;
  bool integer = false;  // written without '.', exponent, inf or nan
};

std::optional<Number> parse_number(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty()) return std::nullopt;
  for (char c : t)
    if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.' ||
          c == 'e' || c == 'E'))
      return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return Number{v, t.find_first_of(".eE") == std::string::npos};
}

// A range value as TOML text: integers as integers, floats rounded to 12 significant digits
// (so 0.1 + 2 * 0.1 is written 0.3) and always recognisable as a float.
std::string format_range_value(double v, bool integer) {
  if (integer) return std::to_string(static_cast<long long>(std::llround(v)));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  double rounded = std::strtod(buf, nullptr);
  if (rounded == 0.0) rounded = 0.0;  // no "-0"
  std::snprintf(buf, sizeof buf, "%.15g", rounded);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

constexpr std::size_t kMaxRangeValues = 10000;

// Expands "A:B:S", "linspace(A,B,N)" or "logspace(A,B,N)"; nullopt when the item is neither.
std::optional<std::vector<std::string>> expand_range(const std::string& item,
                                                     const std::string& key) {
  const std::string where = "the range '" + item + "'";
  std::vector<std::string> out;
  for (const char* fn : {"linspace", "logspace"}) {
    const std::string f = std::string(fn) + "(";
    if (item.rfind(f, 0) != 0) continue;
    if (item.back() != ')')
      throw InputError(where + " must end with ')': " + fn + "(START,STOP,COUNT)", {}, 0, 0, key);
    const auto args =
        split_top_level(item.substr(f.size(), item.size() - f.size() - 1), key, where);
    std::optional<Number> a, b, n;
    if (args.size() == 3)
      a = parse_number(args[0]), b = parse_number(args[1]), n = parse_number(args[2]);
    if (!a || !b || !n)
      throw InputError(where + ": expected " + std::string(fn) + "(START,STOP,COUNT) with numbers",
                       {}, 0, 0, key);
    if (!n->integer || n->value < 1 || n->value > static_cast<double>(kMaxRangeValues))
      throw InputError(
          where + ": COUNT must be an integer from 1 to " + std::to_string(kMaxRangeValues), {}, 0,
          0, key);
    const bool log = std::string(fn) == "logspace";
    if (log && (a->value <= 0.0 || b->value <= 0.0))
      throw InputError(where + ": logspace needs positive START and STOP", {}, 0, 0, key);
    const auto count = static_cast<std::size_t>(n->value);
    for (std::size_t i = 0; i < count; ++i) {
      const double t = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
      const double v =
          log ? std::exp(std::log(a->value) + t * (std::log(b->value) - std::log(a->value)))
              : a->value + t * (b->value - a->value);
      out.push_back(format_range_value(i + 1 == count && count > 1 ? b->value : v, false));
    }
    return out;
  }
  // START:STOP:STEP, three numbers.
  if (item.find(':') == std::string::npos) return std::nullopt;
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t c = item.find(':', start);
    parts.push_back(item.substr(start, c - start));
    if (c == std::string::npos) break;
    start = c + 1;
  }
  std::vector<Number> nums;
  for (const auto& p : parts)
    if (auto n = parse_number(p)) nums.push_back(*n);
  if (nums.size() != parts.size()) return std::nullopt;  // not a numeric range: a plain value
  if (nums.size() != 3)
    throw InputError(where + ": a range is START:STOP:STEP (three numbers)", {}, 0, 0, key);
  const double a = nums[0].value, b = nums[1].value, step = nums[2].value;
  if (step == 0.0 || (b - a) * step < 0.0)
    throw InputError(where + ": STEP must be nonzero and lead from START to STOP", {}, 0, 0, key);
  const bool integer = nums[0].integer && nums[1].integer && nums[2].integer;
  const double count_f = std::floor((b - a) / step + 1e-9) + 1.0;
  if (count_f > static_cast<double>(kMaxRangeValues))
    throw InputError(where + ": more than " + std::to_string(kMaxRangeValues) + " values", {}, 0, 0,
                     key);
  const auto count = static_cast<std::size_t>(count_f);
  for (std::size_t i = 0; i < count; ++i)
    out.push_back(format_range_value(a + static_cast<double>(i) * step, integer));
  return out;
}
}  // namespace

std::vector<std::string> split_value_list(const std::string& list, const std::string& key) {
  const auto items = split_top_level(list, key, "--vary " + key + "=" + list);
  std::vector<std::string> values;
  for (const auto& item : items) {
    if (item.empty())
      throw InputError(
          "empty value in --vary " + key + "=" + list + " (values are separated by commas)", {}, 0,
          0, key);
    if (auto range = expand_range(item, key))
      values.insert(values.end(), range->begin(), range->end());
    else
      values.push_back(item);
  }
  std::set<std::string> seen;
  for (const auto& v : values)
    if (!seen.insert(v).second)
      throw InputError("value '" + v + "' appears twice in --vary " + key + "=" + list, {}, 0, 0,
                       key);
  return values;
}

}  // namespace femdem
