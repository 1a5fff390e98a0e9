#pragma once

// Walks a CLI11 command line for the options that take a number, so that a test can demand a
// range check and a hostile-value row for each (option_table_test, studio_option_table_test).

#include <CLI/CLI.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace recon::testing {

/// (subcommand path, option name) of every option of `app` and its subcommands that takes a
/// number; those without any check go to `unchecked` as "path name" too.
inline void CollectNumericOptions(const CLI::App& app, const std::string& path,
                                  std::set<std::pair<std::string, std::string>>& out,
                                  std::vector<std::string>& unchecked) {
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_items_expected_max() == 0) continue;  // a flag
    const std::string type = option->get_type_name();
    const bool numeric = type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0 ||
                         type.rfind("FLOAT", 0) == 0 || type.rfind("NUMBER", 0) == 0;
    if (!numeric) continue;
    out.insert({path, option->get_name()});
    try {
      const_cast<CLI::Option*>(option)->get_validator();  // CLI11 2.1 has no const getter
    } catch (const CLI::OptionNotFound&) {
      unchecked.push_back(path + " " + option->get_name());
    }
  }
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    CollectNumericOptions(*sub, path.empty() ? sub->get_name() : path + " " + sub->get_name(), out,
                          unchecked);
  }
}

/// What a table of hostile-value rows misses in `app`: each numeric option without a range check
/// ("path name: no range check") or without a row in `table` ("path name: not in the table").
/// `found` receives how many numeric options the walk found.
inline std::vector<std::string> NumericOptionGaps(
    const CLI::App& app, const std::set<std::pair<std::string, std::string>>& table,
    size_t& found) {
  std::set<std::pair<std::string, std::string>> numeric;
  std::vector<std::string> unchecked, gaps;
  CollectNumericOptions(app, "", numeric, unchecked);
  found = numeric.size();
  for (const std::string& option : unchecked) gaps.push_back(option + ": no range check");
  for (const auto& [path, name] : numeric) {
    if (table.count({path, name}) == 0) gaps.push_back(path + " " + name + ": not in the table");
  }
  return gaps;
}

/// The values a hostile or careless user types into a numeric option; `whole` adds a fraction.
inline std::vector<std::string> HostileValues(bool whole) {
  std::vector<std::string> values = {"nan", "inf", "-1", "1e30", "abc"};
  if (whole) values.push_back("2.5");
  return values;
}

}  // namespace recon::testing
