#include "app/lafit/cli_args.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace la::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
           const std::set<std::string>& flags) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() > 1 && a[0] == '-' && !(std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')) {
      std::string name = a, value;
      const auto eq = a.find('=');
      const bool inline_value = eq != std::string::npos;
      if (inline_value) {
        name = a.substr(0, eq);
        value = a.substr(eq + 1);
      }
      if (valued.count(name)) {
        if (!inline_value) {
          if (i + 1 >= argv.size()) throw UsageError("option " + name + " needs a value");
          value = argv[++i];
        }
        values_[name] = value;
      } else if (flags.count(name) && !inline_value) {
        values_[name] = "1";
      } else {
        throw UsageError("unknown option " + name);
      }
    } else {
      positional_.push_back(a);
    }
  }
}

std::optional<std::string> Args::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
  return get(name).value_or(fallback);
}

double Args::number(const std::string& name, double fallback) const {
  const auto v = get(name);
  if (!v) return fallback;
  char* end = nullptr;
  const double x = std::strtod(v->c_str(), &end);
  if (end == v->c_str() || *end != '\0' || std::isnan(x))
    throw UsageError("option " + name + " needs a number, got '" + *v + "'");
  return x;
}

int Args::integer(const std::string& name, int fallback) const {
  const double x = number(name, fallback);
  if (x != std::floor(x) || std::abs(x) > 1e9)
    throw UsageError("option " + name + " needs a whole number, got '" + get(name, "") + "'");
  return static_cast<int>(x);
}

std::vector<double> parseNumbers(const std::string& text, std::size_t count) {
  std::vector<double> values;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      throw UsageError("expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
    values.push_back(v);
  }
  if (values.size() != count || (!text.empty() && text.back() == ','))
    throw UsageError("expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
  return values;
}

Vec2 parsePoint(const std::string& text) {
  const std::vector<double> xy = parseNumbers(text, 2);
  return {xy[0], xy[1]};
}

}  // namespace la::cli
