#include <ritr/common/input_error.h>
#include <ritr/scene/scene_file.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace ritr
{
  namespace
  {
    std::string trimmed(const std::string &s)
    {
      const auto first = s.find_first_not_of(" \t\r\f\v");
      return first == std::string::npos ? "" : s.substr(first, s.find_last_not_of(" \t\r\f\v") - first + 1);
    }

    // deal.II quotes input as <...> inside its sentences, or gives it a line of its own: cut
    // either kind of echo short, but keep the sentence around it.
    std::string shortened_line(const std::string &line)
    {
      if (line.find('<') == std::string::npos)
        return shortened(line, 200);
      std::string r;
      for (std::size_t i = 0; i < line.size();)
        {
          const auto open  = line.find('<', i);
          const auto close = open == std::string::npos ? open : line.find('>', open + 1);
          if (close == std::string::npos)
            {
              r += line.substr(i);
              break;
            }
          r += line.substr(i, open + 1 - i) + shortened(line.substr(open + 1, close - open - 1)) + ">";
          i = close + 1;
        }
      return shortened(r, 400);
    }

    bool starts_with_keyword(const std::string &line, const std::string &lower, const std::string &upper)
    {
      return line.compare(0, lower.size(), lower) == 0 || line.compare(0, upper.size(), upper) == 0;
    }
  } // namespace

  SceneFile read_scene_file(const std::string &file)
  {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
      throw InputError(file + ": is a directory, not a parameter file");
    std::ifstream in(file, std::ios::binary);
    if (!in)
      throw InputError(file + ": cannot open the parameter file");
    SceneFile scene;
    scene.text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());

    // The statements as deal.II reads them: '\' joins lines, '#' starts a comment, the line
    // reported is the statement's last. Malformed statements are left to deal.II's parser.
    std::vector<std::string> sections;
    std::stringstream        lines(scene.text);
    std::string              physical, statement;
    for (unsigned int n = 1; std::getline(lines, physical); ++n)
      {
        physical = trimmed(physical);
        if (!physical.empty() && physical.back() == '\\')
          {
            statement += physical.substr(0, physical.size() - 1);
            continue;
          }
        std::string line = statement + physical;
        statement.clear();
        line = trimmed(line.substr(0, line.find('#')));
        for (auto &c : line)
          c = c == '\t' ? ' ' : c;
        const auto path = [&](const std::string &name) {
          std::string p;
          for (const auto &s : sections)
            p += s + "/";
          return p + trimmed(name);
        };
        if (starts_with_keyword(line, "subsection ", "SUBSECTION "))
          {
            scene.lines[path(line.substr(11))] = n;
            sections.push_back(trimmed(line.substr(11)));
          }
        else if (starts_with_keyword(line, "end", "END") && !sections.empty() && trimmed(line.substr(3)).empty())
          sections.pop_back();
        else if (starts_with_keyword(line, "set ", "SET ") && line.find('=') != std::string::npos)
          {
            const std::string entry = path(line.substr(4, line.find('=') - 4));
            // deal.II skips the pattern check of a value with '{' (its parameter loops).
            if (line.find('{', line.find('=')) != std::string::npos)
              throw InputError(file + ":" + std::to_string(n) + ": " + shortened(entry) +
                               ": '{' is not allowed in a value");
            scene.lines[entry]  = n;
            scene.sets_an_entry = true;
          }
      }
    return scene;
  }

  namespace
  {
    // The path ("Adaptivity/epsilon r") of the one entry named `name` that `scene` sets, or "".
    std::string set_entry_named(const std::string &name, const SceneFile &scene)
    {
      std::string found;
      for (const auto &[path, line] : scene.lines)
        if (path == name || (path.size() > name.size() && path.compare(path.size() - name.size(), name.size(), name) == 0 &&
                             path[path.size() - name.size() - 1] == '/'))
          {
            if (!found.empty())
              return "";
            found = path;
          }
      return found;
    }
  } // namespace

  std::string fold_parser_message(const std::string &message, const std::string &file, const SceneFile &scene)
  {
    std::stringstream ss(message);
    std::string       line, folded;
    while (std::getline(ss, line))
      {
        line = trimmed(line);
        // The header names our file; deal.II omits the '>' after it in some messages.
        const std::string head = "Line <", of_file = "> of file <" + file;
        const auto        close = line.find('>');
        if (folded.empty() && line.compare(0, head.size(), head) == 0 && close != std::string::npos &&
            line.compare(close, of_file.size(), of_file) == 0)
          {
            folded = file + ":" + line.substr(head.size(), close - head.size()) + ":";
            line = line.substr(close + of_file.size());
            line.erase(0, std::min(line.size(), line.find_first_not_of(">:")));
            line = trimmed(line);
          }
        if (!line.empty())
          folded += (folded.empty() ? "" : " ") + shortened_line(line);
      }
    if (folded.compare(0, file.size(), file) != 0)
      {
        const std::string named = "for entry <";
        const auto        start = message.find(named);
        const auto        end   = start == std::string::npos ? start : message.find('>', start + named.size());
        const std::string entry =
          end == std::string::npos ? "" : set_entry_named(message.substr(start + named.size(), end - start - named.size()), scene);
        if (!entry.empty())
          folded = file + ":" + std::to_string(scene.lines.at(entry)) + ": " + shortened(entry) + ": " + folded;
        else
          folded = file + ": " + (folded.empty() ? "malformed parameter file" : folded);
      }
    return folded;
  }
} // namespace ritr
