#pragma once
// A small command-line parser for lafit: `--name value`, `--flag`, `-o value`, and
// positionals. Unknown options and missing values are usage errors (exit code 2).

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace la::cli {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Args {
 public:
  /// `valued` are options that take a value, `flags` those that do not.
  Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
       const std::set<std::string>& flags);
  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::optional<std::string> get(const std::string& name) const;
  std::string get(const std::string& name, const std::string& fallback) const;
  double number(const std::string& name, double fallback) const;
  int integer(const std::string& name, int fallback) const;

 private:
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_;
};

/// A point written X,Y (a command-line positional); UsageError otherwise.
Vec2 parsePoint(const std::string& text);

/// Comma-separated numbers, exactly `count` of them (e.g. X,Y,THETA,KAPPA); UsageError otherwise.
std::vector<double> parseNumbers(const std::string& text, std::size_t count);

}  // namespace la::cli
