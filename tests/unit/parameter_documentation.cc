// doc/parameters.md documents every entry of the schema that `ritr --print-parameters`
// prints, and its listing shows the schema's defaults, so the reference cannot silently fall
// behind the code.
#include <ritr/scene/parameters.h>

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "run_ritr.h"

namespace
{
  std::string
  documentation()
  {
    return ritr::test_support::read_file(ritr::test_support::source_dir() + "/doc/parameters.md");
  }

  std::string
  schema()
  {
    std::ostringstream out;
    ritr::print_parameters(out);
    return out.str();
  }

  // "Subsection/.../name" -> value of every `set name = value` of a parameter listing.
  std::map<std::string, std::string>
  entries_by_path(const std::string &listing)
  {
    std::map<std::string, std::string> entries;
    for (const auto &[path, value] : ritr::listing_entries(listing))
      entries[path] = value;
    return entries;
  }
} // namespace

TEST(ParameterDocumentation, EveryEntryIsDocumented)
{
  const std::string doc = documentation();
  ASSERT_FALSE(doc.empty());
  std::set<std::string> entries;
  const std::string     text = schema();
  const std::regex      entry("set ([a-z ]+?) *=");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it)
    entries.insert((*it)[1]);
  EXPECT_GT(entries.size(), 40u);
  for (const auto &name : entries)
    EXPECT_TRUE(std::regex_search(doc, std::regex("set " + name + " *="))) << "undocumented entry: " << name;
}

TEST(ParameterDocumentation, ListingShowsTheSchemaDefaults)
{
  const std::string doc   = documentation();
  const auto        begin = doc.find("```", doc.find("## Listing"));
  ASSERT_NE(begin, std::string::npos);
  const auto end = doc.find("```", begin + 3);
  ASSERT_NE(end, std::string::npos);
  const auto listed   = entries_by_path(doc.substr(begin + 3, end - begin - 3));
  const auto defaults = entries_by_path(schema());
  EXPECT_GT(listed.size(), 40u);
  for (const auto &[path, value] : listed)
    {
      const auto it = defaults.find(path);
      if (it == defaults.end())
        ADD_FAILURE() << "listed but not in the schema: " << path;
      else
        EXPECT_EQ(value, it->second) << "default of " << path;
    }
}
