// IGES parameter lines re-wrapped to the standard 64 data columns (cad/iges_layout.h).
#include "cad/iges_layout.h"

#include <cctype>
#include <cstdio>
#include <map>
#include <vector>

namespace sizemesh {
namespace {

constexpr size_t kDataColumns = 64;  // parameter data: columns 1-64
constexpr size_t kSectionColumn = 72;  // the section letter: column 73

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    out.push_back(std::move(line));
    start = end + 1;
  }
  while (!out.empty() && out.back().find_first_not_of(' ') == std::string::npos) out.pop_back();
  return out;
}

bool parse_int(const std::string& field, int& value) {
  size_t i = field.find_first_not_of(' ');
  if (i == std::string::npos) return false;
  value = 0;
  for (; i < field.size() && field[i] != ' '; ++i) {
    if (!std::isdigit(static_cast<unsigned char>(field[i]))) return false;
    value = 10 * value + (field[i] - '0');
    if (value > 99999999) return false;
  }
  return field.find_first_not_of(' ', i) == std::string::npos;
}

// The parameter and record delimiters the global section declares (default , and ;).
void delimiters(const std::vector<std::string>& global, char& param, char& record) {
  std::string g;
  for (const auto& line : global) g += line.substr(0, kSectionColumn);
  param = ',';
  record = ';';
  size_t i = 0;
  // "1Hx" then the delimiter, or an empty field (the default) then ','.
  if (g.compare(0, 2, "1H") == 0 && g.size() > 3) {
    param = g[2];
    i = 4;
  } else if (!g.empty() && g[0] == ',') {
    i = 1;
  } else {
    return;
  }
  if (g.compare(i, 2, "1H") == 0 && g.size() > i + 2) record = g[i + 2];
}

// An entity's parameters as items, each ending with its delimiter; blanks
// outside Hollerith strings dropped.
std::vector<std::string> items_of(const std::string& data, char param, char record) {
  std::vector<std::string> items;
  std::string item;
  for (size_t i = 0; i < data.size(); ++i) {
    const char c = data[i];
    if (c == ' ') continue;
    if (c == 'H' && !item.empty() && item.size() <= 6 && item.find_first_not_of("0123456789") == std::string::npos) {
      const size_t n = std::stoul(item);
      item += data.substr(i, n + 1);
      i += n;
      continue;
    }
    item += c;
    if (c == param || c == record) {
      items.push_back(item);
      item.clear();
    }
  }
  if (!item.empty()) items.push_back(item);
  return items;
}

std::string record_line(const std::string& data, int pointer, char section, int sequence) {
  char tail[32];
  std::snprintf(tail, sizeof tail, "%8d%c%7d", pointer, section, sequence);
  return data + std::string(kDataColumns - data.size(), ' ') + tail;
}

}  // namespace

std::optional<IgesRealignment> realign_iges_parameters(const std::string& file_text) {
  const std::vector<std::string> lines = split_lines(file_text);
  std::vector<std::string> start, global, directory, parameter;
  for (const auto& line : lines) {
    if (line.size() <= kSectionColumn) return std::nullopt;
    switch (line[kSectionColumn]) {
      case 'S': start.push_back(line); break;
      case 'G': global.push_back(line); break;
      case 'D': directory.push_back(line); break;
      case 'P': parameter.push_back(line); break;
      case 'T': break;
      default: return std::nullopt;
    }
  }
  if (directory.size() % 2 != 0 || parameter.empty()) return std::nullopt;
  char param, record;
  delimiters(global, param, record);

  // Each entity's data, in file order, keyed by its directory line.
  IgesRealignment out;
  std::vector<int> order;
  std::map<int, std::string> data;
  for (const auto& line : parameter) {
    const bool spilled = line[kDataColumns] == param || line[kDataColumns] == record;
    const size_t width = spilled ? kDataColumns + 1 : kDataColumns;
    int pointer = 0;
    if (!parse_int(line.substr(width, kSectionColumn - width), pointer)) return std::nullopt;
    out.lines_moved += spilled;
    if (!data.count(pointer)) order.push_back(pointer);
    data[pointer] += line.substr(0, width);
  }
  if (out.lines_moved == 0) return std::nullopt;

  std::vector<std::string> rewrapped;
  std::map<int, std::pair<int, int>> where;  // directory line -> (first parameter line, line count)
  for (int pointer : order) {
    const int first = static_cast<int>(rewrapped.size()) + 1;
    std::string current;
    for (std::string item : items_of(data[pointer], param, record)) {
      while (current.size() + item.size() > kDataColumns) {
        if (!current.empty()) {
          rewrapped.push_back(record_line(current, pointer, 'P', static_cast<int>(rewrapped.size()) + 1));
          current.clear();
        }
        if (item.size() <= kDataColumns) break;
        // A string longer than a line continues on the next one.
        rewrapped.push_back(record_line(item.substr(0, kDataColumns), pointer, 'P',
                                        static_cast<int>(rewrapped.size()) + 1));
        item.erase(0, kDataColumns);
      }
      current += item;
    }
    if (!current.empty())
      rewrapped.push_back(record_line(current, pointer, 'P', static_cast<int>(rewrapped.size()) + 1));
    where[pointer] = {first, static_cast<int>(rewrapped.size()) + 1 - first};
  }

  for (const auto& [pointer, lines] : where)
    if (pointer % 2 == 0 || pointer >= static_cast<int>(directory.size())) return std::nullopt;
  // Directory entries: field 2 of the first line points at the parameter
  // data, field 14 (the second line's fourth) counts its lines.
  for (size_t i = 0; i + 1 < directory.size(); i += 2) {
    const auto it = where.find(static_cast<int>(i) + 1);
    if (it == where.end()) continue;
    char field[16];
    std::snprintf(field, sizeof field, "%8d", it->second.first);
    directory[i].replace(8, 8, field);
    std::snprintf(field, sizeof field, "%8d", it->second.second);
    directory[i + 1].replace(24, 8, field);
  }

  char terminate[96];
  std::snprintf(terminate, sizeof terminate, "S%7zuG%7zuD%7zuP%7zu", start.size(), global.size(), directory.size(),
                rewrapped.size());
  for (const auto* section : {&start, &global, &directory, &rewrapped})
    for (const auto& line : *section) out.text += line + "\n";
  out.text += std::string(terminate) + std::string(kSectionColumn - 32, ' ') + "T      1\n";
  return out;
}

}  // namespace sizemesh
