// doc/parameters.md documents every entry of the schema that `ritr --print-parameters`
// prints, so the reference cannot silently fall behind the code.
#include <ritr/scene/parameters.h>

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>

#include "run_ritr.h"

TEST(ParameterDocumentation, EveryEntryIsDocumented)
{
  std::ostringstream schema;
  ritr::print_parameters(schema);
  const std::string doc = ritr::test_support::read_file(ritr::test_support::source_dir() + "/doc/parameters.md");
  ASSERT_FALSE(doc.empty());
  std::set<std::string> entries;
  const std::string     text = schema.str();
  const std::regex      entry("set ([a-z ]+?) *=");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it)
    entries.insert((*it)[1]);
  EXPECT_GT(entries.size(), 40u);
  for (const auto &name : entries)
    EXPECT_TRUE(std::regex_search(doc, std::regex("set " + name + " *="))) << "undocumented entry: " << name;
}
