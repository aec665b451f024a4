// Which point attributes a run carries to the output (pipeline.h,
// ReconstructOptions::attributes).
#include <pdd/errors.h>
#include <pdd/pipeline.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "common/quote.h"

namespace pdd {

namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    names.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) return names;
    start = comma + 1;
  }
}

}  // namespace

std::string parse_attribute_selection(const std::string& text) {
  if (text == "all" || text == "none") return text;
  for (const std::string& name : split(text)) {
    const bool word = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
    if (!word || name == "all" || name == "none")
      throw InputError("--attributes: must be colors, all, none or property names separated by "
                       "commas, got " + quote(text));
  }
  return text;
}

std::vector<Attribute> select_attributes(const PointSet& points, const std::string& selection,
                                         const std::string& source) {
  parse_attribute_selection(selection);
  std::vector<Attribute> selected;
  if (selection == "none") return selected;
  if (selection == "all") return points.attributes;
  const std::vector<std::string> names = split(selection);
  for (const std::string& name : names) {
    if (name == "colors") continue;
    const bool there = std::any_of(points.attributes.begin(), points.attributes.end(),
                                   [&](const Attribute& a) { return a.name == name; });
    if (there) continue;
    std::string have;
    for (const Attribute& a : points.attributes) have += (have.empty() ? "" : ", ") + a.name;
    throw InputError(source + ": --attributes: the points have no property " + quote(name) +
                     (have.empty() ? " (they have none)" : " (they have " + have + ")"));
  }
  // Colours: red, green and blue together (and alpha when there).
  auto has = [&](const char* name) {
    return std::any_of(points.attributes.begin(), points.attributes.end(),
                       [&](const Attribute& a) { return a.name == name; });
  };
  const bool colours = std::find(names.begin(), names.end(), "colors") != names.end() &&
                       has("red") && has("green") && has("blue");
  for (const Attribute& a : points.attributes)
    if ((colours && is_colour(a.name)) || std::find(names.begin(), names.end(), a.name) != names.end())
      selected.push_back(a);
  for (const Attribute& a : selected)
    for (double v : a.values)
      if (!std::isfinite(v))
        throw InputError(source + ": property " + quote(a.name) + " has a value that is not "
                         "finite; it cannot be interpolated");
  return selected;
}

}  // namespace pdd
